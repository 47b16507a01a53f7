// This machine's memory bandwidth, the dense engine's physical limit (bench/dense_floor.py):
// streaming reads (a sum over an array far larger than the caches) and read-modify-writes
// (each word or-ed with a value and stored back, what a BFS does to its store), on 1 and on
// `--threads` OpenMP threads, each the best of `--repeats` passes over `--mib` MiB. Prints one
// JSON object: {"mib": ..., "read_gbs": {"1": ..., "2": ...}, "rmw_gbs": {...}} (bytes moved
// per second: a read-modify-write moves each byte twice).
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t mib = 1024;
  int threads = 2, repeats = 5;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    const long v = std::strtol(argv[i + 1], nullptr, 10);
    if (a == "--mib" && v > 0) {
      mib = static_cast<std::size_t>(v);
    } else if (a == "--threads" && v > 0) {
      threads = static_cast<int>(v);
    } else if (a == "--repeats" && v > 0) {
      repeats = static_cast<int>(v);
    } else {
      std::fprintf(stderr, "memory_bandwidth: unknown option or bad value: %s %s\n", argv[i],
                   argv[i + 1]);
      return 2;
    }
  }
  const std::size_t n = mib * (std::size_t{1} << 20) / sizeof(std::uint64_t);
  std::vector<std::uint64_t> a(n);
  // First touch by the threads that will read it, so a NUMA machine places it near them.
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::size_t i = 0; i < n; ++i) a[i] = i;
  std::string read_json, rmw_json;
  std::uint64_t sink = 0;
  for (int t = 1; t <= threads; ++t) {
    double best_read = 1e30, best_rmw = 1e30;
    for (int r = 0; r < repeats; ++r) {
      auto start = std::chrono::steady_clock::now();
      std::uint64_t sum = 0;
#pragma omp parallel for num_threads(t) schedule(static) reduction(+ : sum)
      for (std::size_t i = 0; i < n; ++i) sum += a[i];
      best_read = std::min(best_read, seconds_since(start));
      sink += sum;
      start = std::chrono::steady_clock::now();
      const std::uint64_t mask = std::uint64_t{1} << (r % 64);
#pragma omp parallel for num_threads(t) schedule(static)
      for (std::size_t i = 0; i < n; ++i) a[i] |= mask;
      best_rmw = std::min(best_rmw, seconds_since(start));
    }
    const double bytes = static_cast<double>(n * sizeof(std::uint64_t));
    char item[96];
    std::snprintf(item, sizeof item, "%s\"%d\": %.2f", t > 1 ? ", " : "", t,
                  bytes / best_read / 1e9);
    read_json += item;
    std::snprintf(item, sizeof item, "%s\"%d\": %.2f", t > 1 ? ", " : "", t,
                  2 * bytes / best_rmw / 1e9);
    rmw_json += item;
  }
  std::printf("{\"mib\": %zu, \"read_gbs\": {%s}, \"rmw_gbs\": {%s}, \"check\": %llu}\n", mib,
              read_json.c_str(), rmw_json.c_str(), static_cast<unsigned long long>(sink % 7));
  return 0;
}
