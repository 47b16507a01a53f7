// Runs the fuzz target without libFuzzer (any compiler): every file named on the command line,
// then deterministic mutations of them (byte flips, insertions, truncations, line splices),
// so the suite exercises the parsers on malformed input even where clang is absent.
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

int main(int argc, char** argv) {
  std::vector<std::string> corpus;
  for (int i = 1; i < argc; ++i) {
    std::ifstream in(argv[i], std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    if (!in || s.str().empty()) {
      std::fprintf(stderr, "fuzz replay: cannot read corpus file '%s' (or it is empty)\n", argv[i]);
      return 1;
    }
    corpus.push_back(s.str());
  }
  // A glob that matched nothing would otherwise replay nothing and pass.
  if (corpus.size() < 5) {
    std::fprintf(stderr, "fuzz replay: %zu corpus files given, expected the shipped maps\n",
                 corpus.size());
    return 1;
  }
  const char* tokens[] = {"boundary", "block", "start", "goal", "sphere", "nan",   "inf", "-",
                          "1e308",    "\r\n",  "#",     " ",    "\t",     "0x1p3", "+",   "."};
  hpcplan::SplitMix64 rng(2026);
  std::size_t runs = 0;
  for (const std::string& seed : corpus) {
    LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(seed.data()), seed.size());
    for (int i = 0; i < 3000; ++i) {
      std::string s = seed;
      for (int m = 0, n = 1 + static_cast<int>(rng.next_below(4)); m < n && !s.empty(); ++m) {
        const std::size_t at = rng.next_below(s.size());
        switch (rng.next_below(4)) {
          case 0:
            s[at] = static_cast<char>(rng.next_below(256));
            break;
          case 1:
            s.insert(at, tokens[rng.next_below(std::size(tokens))]);
            break;
          case 2:
            s.resize(at);
            break;
          default:
            s.erase(at, rng.next_below(16));
            break;
        }
      }
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
      ++runs;
    }
  }
  std::printf("replayed %zu corpus files and %zu mutations\n", corpus.size(), runs);
  return 0;
}
