#include "hpcplan/env/gog.hpp"

#include <string>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"

namespace hpcplan {

GogField::GogField(int dims, int extent, const GogParams& params)
    : dims_(dims), extent_(extent), params_(params) {
  if (dims < 1) throw InputError("GOG needs at least one dimension");
  if (extent < 1) throw InputError("GOG needs a positive extent");
  if (params.shift_p < 0 || params.shift_p > 63)
    throw InputError("--gog-shift-p must be in [0, 63], got " + std::to_string(params.shift_p));
  if (params.shift_v < 0 || params.shift_v > 61)
    throw InputError("--gog-shift-v must be in [0, 61], got " + std::to_string(params.shift_v));
  if (!(params.density >= 0.0 && params.density <= 1.0))
    throw InputError("--density must be in [0, 1]");
  if (params.threshold < 0 || params.threshold > 3 * dims + 1)
    throw InputError("--threshold must be in [1, " + std::to_string(3 * dims + 1) +
                     "] (or 0 for automatic), got " + std::to_string(params.threshold));

  SplitMix64 rng(params.seed);
  axis_seeds_.resize(dims);
  for (auto& h : axis_seeds_) h = rng.next();

  tables_.assign(dims, std::vector<std::uint8_t>(extent));
  for (int axis = 0; axis < dims; ++axis)
    for (int c = 0; c < extent; ++c) tables_[axis][c] = static_cast<std::uint8_t>(level(axis, c));

  if (params.threshold > 0) {
    threshold_ = params.threshold;
  } else {
    // The smallest threshold whose blocked fraction does not exceed the requested density:
    // as dense as asked, never denser. 3d+1 (nothing blocked) always qualifies.
    const auto dist = level_sum_distribution();
    double tail = 0.0;
    threshold_ = 3 * dims + 1;
    for (int c = 3 * dims; c >= 1; --c) {
      tail += dist[c];
      if (tail > params.density + 1e-12) break;
      threshold_ = c;
    }
  }
}

int GogField::level(int axis, int coord) const {
  const auto x = static_cast<std::uint64_t>(coord);
  std::uint64_t v = x ^ axis_seeds_[axis];
  const std::uint64_t p = x >> params_.shift_p;
  v = (p + v) >> params_.shift_v;
  return static_cast<int>(v & 0x3);
}

bool GogField::is_free(std::span<const int> coords) const {
  int sum = 0;
  for (int axis = 0; axis < dims_; ++axis) {
    const int c = coords[axis];
    if (c < 0 || c >= extent_) return false;
    sum += level(axis, c);
  }
  return sum < threshold_;
}

std::vector<double> GogField::level_sum_distribution() const {
  // Distribution of the level sum over a uniformly drawn lattice state: the convolution of the
  // per-axis level histograms, exact because axes are independent by construction.
  std::vector<double> dist(3 * dims_ + 1, 0.0);
  dist[0] = 1.0;
  for (int axis = 0; axis < dims_; ++axis) {
    double hist[4] = {0, 0, 0, 0};
    for (auto level : tables_[axis]) hist[level] += 1.0 / extent_;
    std::vector<double> next(dist.size(), 0.0);
    for (std::size_t s = 0; s < dist.size(); ++s) {
      if (dist[s] == 0.0) continue;
      for (int l = 0; l < 4 && s + l < dist.size(); ++l) next[s + l] += dist[s] * hist[l];
    }
    dist.swap(next);
  }
  return dist;
}

double GogField::blocked_fraction_for(int threshold) const {
  const auto dist = level_sum_distribution();
  double blocked = 0.0;
  for (std::size_t s = 0; s < dist.size(); ++s)
    if (static_cast<int>(s) >= threshold) blocked += dist[s];
  return blocked;
}

}  // namespace hpcplan
