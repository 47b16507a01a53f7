#pragma once
// GOG, the procedural obstacle field of seed 002 (Algorithm 1), on the integer lattice
// [0, extent)^d. Each axis maps its coordinate to a two-bit "level"; a state is blocked when
// the levels summed over all axes reach the threshold c_v. Because the field is a sum of
// per-axis terms, both the exact blocked fraction and incremental neighbour checks are cheap.
//
// Threads: immutable once built; safe for any number of concurrent readers.
#include <cstdint>
#include <span>
#include <vector>

namespace hpcplan {

struct GogParams {
  std::uint64_t seed = 1;  // one seed; per-axis seeds h_i are drawn from SplitMix64(seed)
  int shift_p = 4;         // b_p: the coordinate >> b_p is added before the final shift
  int shift_v = 3;         // b_v: obstacles are runs of about 2^b_v voxels per axis
  double density = 0.40;   // blocked fraction aimed at when threshold is automatic
  int threshold = 0;       // c_v; 0 = smallest value whose blocked fraction <= density
};

class GogField {
 public:
  GogField(int dims, int extent, const GogParams& params);

  int dims() const { return dims_; }
  int extent() const { return extent_; }
  int threshold() const { return threshold_; }
  const GogParams& params() const { return params_; }
  std::uint64_t axis_seed(int axis) const { return axis_seeds_[axis]; }

  // Algorithm 1 for one coordinate, computed from the formula (never from a table).
  int level(int axis, int coord) const;
  // Full O(d) evaluation from the formula. Coordinates outside the box are not free.
  bool is_free(std::span<const int> coords) const;
  // Precomputed levels of one axis, indexed by coordinate (size = extent).
  const std::uint8_t* level_table(int axis) const { return tables_[axis].data(); }

  // Exact fraction of the extent^d lattice that is blocked (from per-axis level histograms).
  double blocked_fraction() const { return blocked_fraction_for(threshold_); }
  double blocked_fraction_for(int threshold) const;

 private:
  std::vector<double> level_sum_distribution() const;

  int dims_;
  int extent_;
  GogParams params_;
  int threshold_ = 0;
  std::vector<std::uint64_t> axis_seeds_;
  std::vector<std::vector<std::uint8_t>> tables_;
};

}  // namespace hpcplan
