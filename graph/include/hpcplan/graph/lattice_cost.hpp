#pragma once
// Exact path costs on lattices. Every lattice move costs sqrt k for k changed axes, so every
// path cost is ones + root2*sqrt2 + root3*sqrt3 with integer counts (sqrt4 = 2 folds into
// ones). Carrying the counts instead of a running double sum means equal costs are bitwise
// equal however they were summed, which A*'s tie-breaking depends on: on the lattice's huge
// optimal plateaus, rounding noise in f would otherwise order states at random and flood them.
// Since 1, sqrt2, sqrt3 are linearly independent over the rationals, different counts give
// different values, and for realistic path lengths their doubles differ far above rounding.
#include <cmath>
#include <cstdint>

namespace hpcplan {

struct LatticeCost {
  std::int32_t ones = 0;
  std::int32_t root2 = 0;
  std::int32_t root3 = 0;

  static constexpr LatticeCost for_axes(int k) {
    switch (k) {
      case 1:
        return {1, 0, 0};
      case 2:
        return {0, 1, 0};
      case 3:
        return {0, 0, 1};
      case 4:
        return {2, 0, 0};
      default:
        return {};
    }
  }
  double value() const {
    return ones + root2 * 1.41421356237309504880 + root3 * 1.73205080756887729353;
  }
  friend constexpr LatticeCost operator+(LatticeCost a, LatticeCost b) {
    return {a.ones + b.ones, a.root2 + b.root2, a.root3 + b.root3};
  }
  friend constexpr bool operator==(LatticeCost, LatticeCost) = default;
};

}  // namespace hpcplan
