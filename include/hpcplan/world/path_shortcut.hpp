#pragma once
// Post-processing for any planner's path in a continuous world, keeping its exact ends:
//   shortcut_path  string pulling: from each kept vertex jump to the farthest later vertex
//                  still in view (one pass, linear in the path's length);
//   tighten_path   local relaxation: every interior vertex moves as far as it can towards the
//                  middle of its neighbours while both its segments stay free, vertices whose
//                  neighbours see each other are dropped, and the path is first subdivided so
//                  bends can slide along obstacle edges. Stops when a round gains < tolerance.
// Every segment accepted went through the world's exact segment test.
#include <cmath>
#include <vector>

#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/world/point.hpp"

namespace hpcplan::world {

template <class W>
std::vector<Vec<W::kDim>> shortcut_path(const W& world, const std::vector<Vec<W::kDim>>& path) {
  if (path.size() <= 2) return path;
  std::vector<Vec<W::kDim>> out{path.front()};
  std::size_t anchor = 0;
  while (anchor + 1 < path.size()) {
    std::size_t next = anchor + 1;  // always visible: it is a segment of the input path
    while (next + 1 < path.size() && world.segment_free(path[anchor], path[next + 1])) ++next;
    out.push_back(path[next]);
    anchor = next;
  }
  return out;
}

struct TightenOptions {
  double max_segment = 0.0;  // subdivide longer segments first; 0 = a 40th of the length
  double tolerance = 1e-6;   // relative gain per round below which to stop
  int max_rounds = 200;
  double time_limit_s = 0.05;
};

template <class W>
std::vector<Vec<W::kDim>> tighten_path(const W& world, std::vector<Vec<W::kDim>> path,
                                       const TightenOptions& o = {}) {
  constexpr int D = W::kDim;
  if (path.size() <= 2) return path;
  Stopwatch clock;
  const double total = polyline_length<D>(path);
  const double max_segment = o.max_segment > 0 ? o.max_segment : total / 40.0;
  std::vector<Vec<D>> fine{path.front()};
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int pieces =
        std::max(1, static_cast<int>(std::ceil(distance<D>(path[i - 1], path[i]) / max_segment)));
    for (int j = 1; j <= pieces; ++j)
      fine.push_back(lerp<D>(path[i - 1], path[i], double(j) / pieces));
  }
  path.swap(fine);
  double length = polyline_length<D>(path);
  for (int round = 0; round < o.max_rounds && clock.seconds() < o.time_limit_s; ++round) {
    // Drop vertices whose neighbours see each other.
    std::vector<Vec<D>> kept{path.front()};
    for (std::size_t i = 1; i + 1 < path.size(); ++i)
      if (!world.segment_free(kept.back(), path[i + 1])) kept.push_back(path[i]);
    kept.push_back(path.back());
    path.swap(kept);
    // Pull each interior vertex towards its neighbours' midpoint, as far as stays free.
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      const Vec<D> mid = lerp<D>(path[i - 1], path[i + 1], 0.5);
      const double before = distance<D>(path[i - 1], path[i]) + distance<D>(path[i], path[i + 1]);
      for (double t = 1.0; t > 1.0 / 256; t *= 0.5) {
        const Vec<D> q = lerp<D>(path[i], mid, t);
        if (distance<D>(path[i - 1], q) + distance<D>(q, path[i + 1]) >= before) break;
        if (world.segment_free(path[i - 1], q) && world.segment_free(q, path[i + 1])) {
          path[i] = q;
          break;
        }
      }
    }
    const double now = polyline_length<D>(path);
    const bool converged = length - now < o.tolerance * length;
    length = now;
    if (converged) break;
  }
  return path;
}

}  // namespace hpcplan::world
