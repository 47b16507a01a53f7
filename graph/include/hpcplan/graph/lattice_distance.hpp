#pragma once
// Obstacle-free shortest-path lengths on the lattice, used as A* heuristics.
//
// Seed rule (moves of +-1 on one axis, cost 1, or on two distinct axes, cost sqrt2), with
// per-axis distances delta_i, S = sum delta_i and M = max delta_i. Any path with a single-axis
// and b two-axis moves satisfies  a + 2b >= S  (each move shrinks S by at most 2) and
// a + b >= M  (each move changes the largest axis by at most 1). Minimising a + sqrt2*b over
// those constraints (sqrt2 < 2, so two-axis moves are preferred while the largest axis allows):
//   2M <= S:  b = floor(S/2), a = S mod 2        -> floor(S/2)*sqrt2 + (S mod 2)
//   2M >  S:  b = S - M,      a = 2M - S         -> (S-M)*sqrt2 + (2M - S)
// and both are attained in free space (pair the two largest remaining axes each step), so
// this is the exact free-space distance. Admissible: obstacles only remove edges. Consistent:
// it is a shortest-path metric of a supergraph, so h(x) <= d_free(x,y) + h(y) <= c(x,y) + h(y).
//
// Full connectivity (moves on any k axes at once, cost sqrt k): with deltas sorted descending,
// the exact free distance is sum_k (delta_(k) - delta_(k+1)) * sqrt k (move all axes still
// unfinished together); the same argument gives admissibility and consistency.
#include <algorithm>
#include <cmath>
#include <span>

#include "hpcplan/graph/lattice_cost.hpp"

namespace hpcplan {

// (Forced inline: a heuristic evaluated on every push.)
[[gnu::always_inline]] inline LatticeCost seed_rule_free_distance(std::span<const int> deltas) {
  std::int32_t sum = 0, max = 0;
  for (int d : deltas) {
    sum += d;
    max = std::max<std::int32_t>(max, d);
  }
  if (2 * max <= sum) return {sum % 2, sum / 2, 0};
  return {2 * max - sum, sum - max, 0};
}

inline LatticeCost full_connectivity_free_distance(std::span<const int> deltas) {
  int sorted[16];
  const int n = std::min<int>(static_cast<int>(deltas.size()), 16);
  for (int i = 0; i < n; ++i) sorted[i] = deltas[i];
  std::sort(sorted, sorted + n, [](int a, int b) { return a > b; });
  LatticeCost total;
  for (int k = 1; k <= n && k <= 4; ++k) {
    const int next = k < n ? sorted[k] : 0;
    const LatticeCost unit = LatticeCost::for_axes(k);
    const int times = sorted[k - 1] - next;
    total = total + LatticeCost{unit.ones * times, unit.root2 * times, unit.root3 * times};
  }
  return total;
}

inline double euclidean_distance(std::span<const int> deltas) {
  double s = 0.0;
  for (int d : deltas) s += static_cast<double>(d) * d;
  return std::sqrt(s);
}

}  // namespace hpcplan
