#include "hpcplan/env/hypercube.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "hpcplan/core/error.hpp"

#if defined(_OPENMP)
#define HPCPLAN_LANES_LOOP _Pragma("omp simd")
#else
#define HPCPLAN_LANES_LOOP
#endif

namespace hpcplan {

namespace {

constexpr std::size_t kLanes = 64;  // states per block of valid_batch

std::vector<AxisBounds> unit_axes(int dims) {
  if (dims < Hypercube::kMinDims || dims > Hypercube::kMaxDims)
    throw InputError("hypercube: dims must be in [" + std::to_string(Hypercube::kMinDims) + ", " +
                     std::to_string(Hypercube::kMaxDims) + "], got " + std::to_string(dims));
  return std::vector<AxisBounds>(dims, AxisBounds{0.0, 1.0, false});
}

double checked_edge_width(double edge_width) {
  if (!(edge_width > 0.0 && edge_width < 0.5))
    throw InputError("hypercube: the edge width must be in (0, 0.5), got " +
                     std::to_string(edge_width));
  return edge_width;
}

double cube_resolution(int dims, double fraction) {
  if (!(fraction > 0.0) || !std::isfinite(fraction))
    throw InputError("hypercube: the resolution fraction must be positive, got " +
                     std::to_string(fraction));
  return fraction * std::sqrt(static_cast<double>(dims));
}

}  // namespace

Hypercube::Hypercube(int dims, double edge_width, double resolution_fraction)
    : ConfigSpace("hypercube_" + std::to_string(dims), unit_axes(dims),
                  cube_resolution(dims, resolution_fraction)),
      edge_width_(checked_edge_width(edge_width)),
      upper_edge_(1.0 - edge_width) {}

std::vector<double> Hypercube::start() const {
  return std::vector<double>(dims(), 0.0);
}
std::vector<double> Hypercube::goal() const {
  return std::vector<double>(dims(), 1.0);
}

// "Every axis before k is low" holds for k up to the first axis that is not low (first_high),
// "every axis after k is high" for k from the last axis that is not high (last_low) on; so the
// candidates for k are max(last_low, 0) .. min(first_high, d - 1), at most two of them when
// edge_width < 0.5. A NaN is neither low nor high nor in [0, 1]: no k admits it.
bool Hypercube::valid(const double* s) const {
  const int d = dims();
  int first_high = 0;
  while (first_high < d && s[first_high] <= edge_width_) ++first_high;
  int last_low = d - 1;
  while (last_low >= 0 && s[last_low] >= upper_edge_) --last_low;
  for (int k = std::max(last_low, 0); k <= std::min(first_high, d - 1); ++k)
    if (s[k] >= 0.0 && s[k] <= 1.0) return true;
  return false;
}

// The same rule without branches, for a block of states at once: first_high and last_low per
// lane from one pass over the axes each, then the candidates' test over all axes.
void Hypercube::valid_batch(const double* states, std::size_t k, std::uint8_t* out) const {
  const int d = dims();
  const double low = edge_width_, high = upper_edge_;
  alignas(64) double v[kMaxDims][kLanes];
  alignas(64) double first_high[kLanes], last_low[kLanes];
  alignas(64) std::int64_t ok[kLanes];
  for (std::size_t first = 0; first < k; first += kLanes) {
    const std::size_t lanes = std::min(kLanes, k - first);
    const double* block = states + first * d;
    for (std::size_t l = 0; l < lanes; ++l)
      for (int i = 0; i < d; ++i) v[i][l] = block[l * d + i];
    HPCPLAN_LANES_LOOP
    for (std::size_t l = 0; l < lanes; ++l) {
      first_high[l] = d;
      last_low[l] = -1.0;
      ok[l] = 0;
    }
    for (int i = d - 1; i >= 0; --i) {
      const double axis = i;
      HPCPLAN_LANES_LOOP
      for (std::size_t l = 0; l < lanes; ++l) first_high[l] = v[i][l] <= low ? first_high[l] : axis;
    }
    for (int i = 0; i < d; ++i) {
      const double axis = i;
      HPCPLAN_LANES_LOOP
      for (std::size_t l = 0; l < lanes; ++l) last_low[l] = v[i][l] >= high ? last_low[l] : axis;
    }
    for (int i = 0; i < d; ++i) {
      const double axis = i;
      HPCPLAN_LANES_LOOP
      for (std::size_t l = 0; l < lanes; ++l) {
        const bool candidate = (axis >= last_low[l]) & (axis <= first_high[l]);
        const bool inside = (v[i][l] >= 0.0) & (v[i][l] <= 1.0);
        ok[l] |= (candidate & inside) ? 1 : 0;
      }
    }
    for (std::size_t l = 0; l < lanes; ++l) out[first + l] = ok[l] ? 1 : 0;
  }
}

}  // namespace hpcplan
