// core's atomic writes (core/atomic_file.hpp) when the write fails at each of its steps: the
// destination keeps its old content (or stays absent), no temporary file is left beside it, and
// the error names the step and the file.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "hpcplan/core/atomic_file.hpp"
#include "hpcplan/core/error.hpp"

namespace hpcplan {
namespace {

namespace fs = std::filesystem;

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("hpcplan_atomic_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  static std::string read(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }
  // The directory's entries other than `keep`: a temporary left behind shows here.
  std::size_t strays(const fs::path& keep) const {
    std::size_t n = 0;
    for (const auto& e : fs::directory_iterator(dir_)) n += e.path() != keep;
    return n;
  }
  // What write_file_atomically throws, as text ("" if it did not).
  static std::string failure(const fs::path& p, const std::string& content) {
    try {
      write_file_atomically(p.string(), content);
    } catch (const RunError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

TEST_F(AtomicFile, ReplacesTheContentAndLeavesNothingElse) {
  const fs::path file = dir_ / "out.json";
  write_file_atomically(file.string(), "first");
  write_file_atomically(file.string(), "second, longer");
  EXPECT_EQ(read(file), "second, longer");
  EXPECT_EQ(strays(file), 0u);
}

// The rename fails (the destination is a directory with something in it): it is untouched.
TEST_F(AtomicFile, AFailedRenameKeepsTheOldDestination) {
  const fs::path target = dir_ / "taken";
  fs::create_directories(target / "inside");
  const std::string why = failure(target, "new");
  EXPECT_NE(why.find("cannot rename the temporary file onto '" + target.string() + "'"),
            std::string::npos)
      << why;
  EXPECT_TRUE(fs::is_directory(target / "inside"));
  EXPECT_EQ(strays(target), 0u);
}

// No temporary can be created (the "directory" is a regular file).
TEST_F(AtomicFile, AFailedCreateNamesTheFile) {
  const fs::path blocker = dir_ / "plain";
  write_file_atomically(blocker.string(), "I am a file");
  const std::string why = failure(blocker / "out.json", "new");
  EXPECT_NE(why.find("cannot create a temporary file for '" + (blocker / "out.json").string()),
            std::string::npos)
      << why;
  EXPECT_EQ(read(blocker), "I am a file");
  EXPECT_EQ(strays(blocker), 0u);
}

// The write itself fails part way (a file-size limit stands in for a full disk: the same
// short write): the old content stays and the partial temporary is removed.
TEST_F(AtomicFile, AFailedWriteKeepsTheOldContentAndRemovesTheTemporary) {
  const fs::path file = dir_ / "result.csv";
  write_file_atomically(file.string(), "old result\n");
  rlimit before{};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &before), 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of a signal
  rlimit small = before;
  small.rlim_cur = 4096;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string why = failure(file, std::string(1 << 20, 'x'));
  ::setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, old_handler);
  EXPECT_NE(why.find("cannot write '" + file.string() + "'"), std::string::npos) << why;
  EXPECT_EQ(read(file), "old result\n");
  EXPECT_EQ(strays(file), 0u);
}

// Threads of one process writing the same destination (the Python module's calls, each with
// the GIL released): every write succeeds and the file is always one writer's whole content.
// With one temporary name per process, the writers truncated each other's temporary and the
// later renames failed ("No such file or directory").
TEST_F(AtomicFile, ThreadsWritingOneFileEachLeaveAWholeFile) {
  const fs::path file = dir_ / "same.json";
  constexpr int kThreads = 4, kWrites = 40;
  std::atomic<int> failed{0}, torn{0};
  std::vector<std::thread> writers;
  for (int t = 0; t < kThreads; ++t)
    writers.emplace_back([&, t] {
      const std::string mine(10000 + t, static_cast<char>('a' + t));
      for (int i = 0; i < kWrites; ++i) {
        if (!failure(file, mine).empty()) ++failed;
        const std::string now = read(file);
        if (now.size() < 10000 || now.find_first_not_of(now[0]) != std::string::npos ||
            now.size() != 10000u + static_cast<unsigned>(now[0] - 'a'))
          ++torn;
      }
    });
  for (auto& w : writers) w.join();
  EXPECT_EQ(failed.load(), 0);
  EXPECT_EQ(torn.load(), 0);
  EXPECT_EQ(strays(file), 0u);
}

}  // namespace
}  // namespace hpcplan
