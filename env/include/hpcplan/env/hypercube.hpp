#pragma once
// The unit hypercube with a narrow corridor along its edges: OMPL's dimension-scalable
// HypercubeBenchmark, as a ConfigSpace.
//
// Every axis is [0, 1], not periodic. A state s is valid when some axis k has 0 <= s_k <= 1,
// every axis i < k has s_i <= edge_width and every axis i > k has s_i >= 1 - edge_width: the
// free space is the chain of edges from the origin (start) to the all-ones corner (goal) that
// moves along axis 0, then axis 1, and so on, thickened by edge_width. The comparisons are the
// plain double ones above, with 1 - edge_width computed once, so valid() and valid_batch()
// agree on every state, boundary values included (s_i == edge_width is inside).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "hpcplan/env/config_space.hpp"

namespace hpcplan {

class Hypercube final : public ConfigSpace {
 public:
  static constexpr int kMinDims = 2;
  static constexpr int kMaxDims = 64;

  // dims in [kMinDims, kMaxDims]; edge_width in (0, 0.5) (from 0.5 on the corridors cover
  // the whole cube); the motion-check resolution is resolution_fraction times maximum_extent()
  // (OMPL's benchmark sets 0.001). Throws InputError otherwise.
  explicit Hypercube(int dims, double edge_width = 0.1, double resolution_fraction = 0.001);

  double edge_width() const { return edge_width_; }
  std::vector<double> start() const;  // all zeros
  std::vector<double> goal() const;   // all ones

  // Public here (protected in ConfigSpace) so that benchmarks can time them without the check
  // counter; planners go through is_valid() / are_valid().
  bool valid(const double* s) const override;
  void valid_batch(const double* states, std::size_t k, std::uint8_t* out) const override;

 private:
  double edge_width_;
  double upper_edge_;  // 1 - edge_width, computed once so both paths compare against one value
};

}  // namespace hpcplan
