#include "hpcplan/core/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "hpcplan/core/error.hpp"

namespace hpcplan {

void write_file_atomically(const std::string& path, std::string_view content) {
  // One temporary name per call, not per process: the Python module writes from several
  // threads of one process, and two calls writing the same destination shared one temporary
  // (each truncated the other's, and the second rename found nothing to move).
  static std::atomic<std::uint64_t> calls{0};
  const std::string tmp =
      path + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(++calls);
  auto fail = [&](const char* step) {
    const std::string why = std::strerror(errno);
    std::remove(tmp.c_str());
    throw RunError("cannot " + std::string(step) + " '" + path + "': " + why);
  };
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) fail("create a temporary file for");
  const bool written = std::fwrite(content.data(), 1, content.size(), f) == content.size();
  const bool flushed = std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  if (std::fclose(f) != 0 || !written || !flushed) fail("write");
  if (std::rename(tmp.c_str(), path.c_str()) != 0) fail("rename the temporary file onto");
}

void require_writable_destination(const std::string& path, std::string_view option) {
  const std::string what = std::string(option) + " '" + path + "'";
  if (path.empty()) throw InputError(what + ": empty file name");
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
    throw InputError(what + " is a directory");
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "." : path.substr(0, slash == 0 ? 1 : slash);
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw InputError(what + ": directory '" + dir + "' does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError(what + ": directory '" + dir + "' is not writable");
}

}  // namespace hpcplan
