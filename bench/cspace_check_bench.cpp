// States per second of a configuration space's one-at-a-time validity test (valid(), as a
// planner asking about one state pays) against its batch test (valid_batch(), in blocks of 64
// and 1024 states, as the lattice engines hand whole expansions), on the kinematic chain and
// the hypercube (env/kinematic_chain.hpp, env/hypercube.hpp).
//
// Two state sets per space, fixed seed: "uniform" (every axis uniform in its bounds: mostly
// invalid chains, which a one-at-a-time test leaves at the first collision) and "near start"
// (start plus a small uniform perturbation: mostly valid, every pair tested). The two tests
// alternate over several rounds on the same states and each reports its median round, so that
// a frequency change or a neighbour's load hits both alike. Both tests' answers are compared
// on every state (a mismatch is an error: exit 1).
//
//   hpcplan_cspace_check_bench [--rounds R] [--states N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/hypercube.hpp"
#include "hpcplan/env/kinematic_chain.hpp"

namespace {

using hpcplan::ConfigSpace;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t h = v.size() / 2;
  return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
}

// `count` states, row-major: uniform in the bounds, or start + uniform in [-spread, spread]
// per axis (clamped into the bounds on a bounded axis, wrapped on a periodic one).
std::vector<double> make_states(const ConfigSpace& space, const std::vector<double>* start,
                                double spread, std::size_t count, std::uint64_t seed) {
  hpcplan::SplitMix64 rng(seed);
  const auto& axes = space.axes();
  const std::size_t d = axes.size();
  std::vector<double> states(count * d);
  for (std::size_t i = 0; i < count; ++i) {
    for (std::size_t a = 0; a < d; ++a) {
      const auto& ax = axes[a];
      double v;
      if (!start) {
        v = ax.lower + rng.next_unit() * (ax.upper - ax.lower);
      } else {
        v = (*start)[a] + (2.0 * rng.next_unit() - 1.0) * spread;
        if (ax.periodic) {
          const double period = ax.upper - ax.lower;
          if (v >= ax.upper) v -= period;
          if (v < ax.lower) v += period;
        } else {
          v = std::clamp(v, ax.lower, ax.upper);
        }
      }
      states[i * d + a] = v;
    }
  }
  return states;
}

struct Row {
  std::string space, set;
  double valid_fraction;
  double scalar_rate, batch64_rate, batch1024_rate;
  double paired64, paired1024;  // median over rounds of that round's scalar time / batch time
};

template <class Space>
Row measure(const Space& space, const std::string& set, const std::vector<double>& states,
            int rounds) {
  const std::size_t d = space.dims();
  const std::size_t count = states.size() / d;
  std::vector<std::uint8_t> scalar(count), batch64(count), batch1024(count);
  std::vector<double> t_scalar, t_64, t_1024;
  for (int r = 0; r < rounds; ++r) {
    auto t0 = Clock::now();
    for (std::size_t i = 0; i < count; ++i) scalar[i] = space.valid(states.data() + i * d) ? 1 : 0;
    t_scalar.push_back(seconds_since(t0));
    for (const std::size_t block : {std::size_t{64}, std::size_t{1024}}) {
      auto& out = block == 64 ? batch64 : batch1024;
      t0 = Clock::now();
      for (std::size_t i = 0; i < count; i += block)
        space.valid_batch(states.data() + i * d, std::min(block, count - i), out.data() + i);
      (block == 64 ? t_64 : t_1024).push_back(seconds_since(t0));
    }
  }
  if (scalar != batch64 || scalar != batch1024) {
    std::fprintf(stderr, "%s %s: valid and valid_batch disagree\n", space.name().c_str(),
                 set.c_str());
    std::exit(1);
  }
  std::size_t valid = 0;
  for (auto v : scalar) valid += v;
  std::vector<double> r64, r1024;
  for (int r = 0; r < rounds; ++r) {
    r64.push_back(t_scalar[r] / t_64[r]);
    r1024.push_back(t_scalar[r] / t_1024[r]);
  }
  const double n = static_cast<double>(count);
  return {space.name(),       set,         valid / n,    n / median(t_scalar), n / median(t_64),
          n / median(t_1024), median(r64), median(r1024)};
}

template <class Space>
void run_space(const Space& space, double spread, std::size_t count, int rounds,
               std::vector<Row>& rows) {
  const std::vector<double> start = space.start();
  const auto uniform = make_states(space, nullptr, 0.0, count, 0x756e69666f726dULL + space.dims());
  const auto near = make_states(space, &start, spread, count, 0x6e656172ULL + space.dims());
  rows.push_back(measure(space, "uniform", uniform, rounds));
  rows.push_back(measure(space, "near start", near, rounds));
  const Row& a = rows[rows.size() - 2];
  const Row& b = rows.back();
  std::fprintf(stderr, "%s done (valid: uniform %.3f, near start %.3f)\n", space.name().c_str(),
               a.valid_fraction, b.valid_fraction);
}

}  // namespace

int main(int argc, char** argv) {
  int rounds = 15;
  std::size_t count = 1 << 16;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--rounds") && i + 1 < argc)
      rounds = std::max(1, std::atoi(argv[++i]));
    else if (!std::strcmp(argv[i], "--states") && i + 1 < argc)
      count = std::max(1L, std::atol(argv[++i]));
    else {
      std::fprintf(stderr, "usage: %s [--rounds R] [--states N]\n", argv[0]);
      return 2;
    }
  }
  std::vector<Row> rows;
  // Near start: joint angles within 0.05 rad of the curled start (the chain stays in the
  // horn), cube coordinates within 0.05 of the origin corner.
  for (int links : {4, 8, 12, 16})
    run_space(hpcplan::KinematicChain(links), 0.05, count, rounds, rows);
  for (int dims : {8, 16}) run_space(hpcplan::Hypercube(dims), 0.05, count, rounds, rows);

  std::printf("states per set: %zu, rounds: %d (median), chain batch build: %s\n", count, rounds,
              hpcplan::KinematicChain::batch_uses_avx2() ? "AVX2" : "baseline");
  // x64, x1024: the ratio of the median rates; paired: the median of each round's own ratio
  // (the two tests of one round ran back to back, so a burst of load hits both).
  std::printf("%-20s %-11s %6s %12s %12s %12s %7s %7s %8s %8s\n", "space", "states", "valid",
              "valid/s", "batch64/s", "batch1024/s", "x64", "x1024", "paired64", "paired1k");
  for (const Row& r : rows)
    std::printf("%-20s %-11s %6.3f %12.3e %12.3e %12.3e %7.2f %7.2f %8.2f %8.2f\n", r.space.c_str(),
                r.set.c_str(), r.valid_fraction, r.scalar_rate, r.batch64_rate, r.batch1024_rate,
                r.batch64_rate / r.scalar_rate, r.batch1024_rate / r.scalar_rate, r.paired64,
                r.paired1024);
  return 0;
}
