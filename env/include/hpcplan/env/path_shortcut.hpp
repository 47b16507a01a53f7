#pragma once
// Post-processing for any planner's path in a continuous world, keeping its exact ends:
//   shortcut_path  string pulling: from each kept vertex jump to the farthest later vertex
//                  still in view (one pass, linear in the path's length);
//   tighten_path   local optimisation. Each round drops the vertices whose neighbours see
//                  each other, splits long segments again (so a straight run can bend), and
//                  moves every interior vertex as far as its two segments stay free: towards
//                  its chord, then along each axis to that axis's optimum, which slides a
//                  bend along the box edge it wraps. Stops when a round gains < tolerance.
// Every segment accepted went through the world's exact segment test, and no step lengthens
// the path.
#include <algorithm>
#include <cmath>
#include <vector>

#include "hpcplan/core/stop.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

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
  double tolerance = 1e-7;   // relative gain per round below which to stop
  int max_rounds = 400;
  double time_limit_s = 0.05;  // the tightener's own budget
  Stop stop;                   // and the caller's (OMPL's termination condition, a cancel)
};

namespace detail {

// Length of the two segments meeting at q.
template <int D>
double bend_length(const Vec<D>& a, const Vec<D>& q, const Vec<D>& b) {
  return distance<D>(a, q) + distance<D>(q, b);
}

// Where along axis k, the other coordinates held, a bend a-q-b is shortest: the reflection
// point, which splits b-a in the ratio of the two ends' distances from the axis line.
template <int D>
bool axis_optimum(const Vec<D>& a, const Vec<D>& q, const Vec<D>& b, int k, Vec<D>& out) {
  double da = 0, db = 0;
  for (int j = 0; j < D; ++j) {
    if (j == k) continue;
    da += (a[j] - q[j]) * (a[j] - q[j]);
    db += (b[j] - q[j]) * (b[j] - q[j]);
  }
  da = std::sqrt(da);
  db = std::sqrt(db);
  if (da + db <= 0) return false;
  out = q;
  out[k] = a[k] + (b[k] - a[k]) * da / (da + db);
  return true;
}

// The point of chord a-b nearest to q: the shortest move that would straighten the bend.
template <int D>
Vec<D> chord_foot(const Vec<D>& a, const Vec<D>& q, const Vec<D>& b) {
  double num = 0, den = 0;
  for (int j = 0; j < D; ++j) {
    num += (q[j] - a[j]) * (b[j] - a[j]);
    den += (b[j] - a[j]) * (b[j] - a[j]);
  }
  const double t = den > 0 ? std::clamp(num / den, 0.0, 1.0) : 0.0;
  return lerp<D>(a, b, t);
}

// Moves bend vertex q towards target as far as a halving search allows while both its
// segments stay free and the bend gets shorter. Returns whether q moved.
template <class W>
bool slide_towards(const W& world, const Vec<W::kDim>& a, Vec<W::kDim>& q, const Vec<W::kDim>& b,
                   const Vec<W::kDim>& target) {
  constexpr int D = W::kDim;
  const double before = bend_length<D>(a, q, b);
  for (double t = 1.0; t > 1.0 / 1024; t *= 0.5) {
    const Vec<D> c = lerp<D>(q, target, t);
    if (bend_length<D>(a, c, b) >= before * (1 - 1e-15)) return false;
    if (world.segment_free(a, c) && world.segment_free(c, b)) {
      q = c;
      return true;
    }
  }
  return false;
}

// Keeps a vertex only where its kept predecessor cannot see its successor; once
// `out_of_time()`, keeps the rest unseen.
template <class W, class OutOfTime>
void drop_visible(const W& world, std::vector<Vec<W::kDim>>& path, OutOfTime&& out_of_time) {
  std::vector<Vec<W::kDim>> kept{path.front()};
  for (std::size_t i = 1; i + 1 < path.size(); ++i)
    if (out_of_time() || !world.segment_free(kept.back(), path[i + 1])) kept.push_back(path[i]);
  kept.push_back(path.back());
  path.swap(kept);
}

// Splits every segment longer than max_segment into equal pieces; `inserted` marks the new
// points.
template <int D>
void subdivide(std::vector<Vec<D>>& path, double max_segment, std::vector<char>& inserted) {
  std::vector<Vec<D>> fine{path.front()};
  inserted.assign(1, 0);
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int pieces =
        std::max(1, static_cast<int>(std::ceil(distance<D>(path[i - 1], path[i]) / max_segment)));
    // The last piece ends on the vertex itself: lerp at 1 may miss it by a rounding step, and
    // the path's end must stay exactly the goal.
    for (int j = 1; j < pieces; ++j) {
      fine.push_back(lerp<D>(path[i - 1], path[i], double(j) / pieces));
      inserted.push_back(1);
    }
    fine.push_back(path[i]);
    inserted.push_back(0);
  }
  path.swap(fine);
}

// One sweep over the interior vertices: each slides towards its chord, then along each axis.
// Stops early, between vertices, once `out_of_time()` says so (every accepted slide kept the
// path valid, so a part sweep leaves a valid path too). Returns the index of the first vertex
// it did not relax (the goal's when it finished).
template <class W, class OutOfTime>
std::size_t relax(const W& world, std::vector<Vec<W::kDim>>& path, OutOfTime&& out_of_time) {
  constexpr int D = W::kDim;
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    if (out_of_time()) return i;
    const Vec<D>& a = path[i - 1];
    const Vec<D>& b = path[i + 1];
    slide_towards(world, a, path[i], b, chord_foot<D>(a, path[i], b));
    for (int k = 0; k < D; ++k) {
      Vec<D> target;
      if (axis_optimum<D>(a, path[i], b, k, target)) slide_towards(world, a, path[i], b, target);
    }
  }
  return path.size() - 1;
}

// After a sweep stopped at vertex `from`: nothing from there on moved, so the points the
// round's subdivision put there go again. What is left there are the vertices before the
// subdivision and `from` itself, which lies on one of their segments: pieces of segments the
// path already had, so still free, without the hundreds of idle vertices a high-dimensional
// subdivision leaves.
template <int D>
void drop_unrelaxed_points(std::vector<Vec<D>>& path, const std::vector<char>& inserted,
                           std::size_t from) {
  std::size_t out = from + 1;
  for (std::size_t j = from + 1; j < path.size(); ++j)
    if (!inserted[j]) path[out++] = path[j];
  path.resize(out);
}

}  // namespace detail

// The shortest path among axis-aligned boxes bends only on box edges, which are parallel to
// the axes; a bend caught on such an edge cannot move towards its chord, but it can slide
// along the edge. So each vertex tries the chord, then each axis's own optimum.
// Tightens `path` in place; returns the rounds it ran. `world` needs only segment_free.
template <class W>
int tighten_in_place(const W& world, std::vector<Vec<W::kDim>>& path,
                     const TightenOptions& o = {}) {
  constexpr int D = W::kDim;
  if (path.size() <= 2) return 0;
  Stopwatch clock;
  Stop stop = o.stop;
  const double total = polyline_length<D>(path);
  const double max_segment = o.max_segment > 0 ? o.max_segment : total / 40.0;
  double length = total;
  int round = 0;
  std::vector<char> inserted;
  // A round in high dimensions can cost more than a small budget (at 6D about 1 ms; a 10D
  // segment along a lattice diagonal tests up to 2^10 cells at each step), so the budget is
  // also checked between the vertices of every pass, not only between rounds.
  const auto out_of_time = [&] { return clock.seconds() >= o.time_limit_s || stop.poll(); };
  while (round < o.max_rounds && !out_of_time()) {
    ++round;
    // Big steps: drop the vertices whose neighbours see each other. Small steps: split long
    // segments again, so a straight run has vertices that can bend towards an obstacle edge it
    // should wrap, and relax every vertex.
    detail::drop_visible(world, path, out_of_time);
    detail::subdivide<D>(path, max_segment, inserted);
    const std::size_t stopped_at = detail::relax(world, path, out_of_time);
    if (stopped_at + 1 < path.size()) {
      detail::drop_unrelaxed_points<D>(path, inserted, stopped_at);
      break;
    }
    const double now = polyline_length<D>(path);
    const bool converged = length - now < o.tolerance * length;
    length = now;
    if (converged) break;
  }
  // No vertex left that a straight segment can replace (as far as the budget goes).
  detail::drop_visible(world, path, out_of_time);
  return round;
}

template <class W>
std::vector<Vec<W::kDim>> tighten_path(const W& world, std::vector<Vec<W::kDim>> path,
                                       const TightenOptions& o = {}) {
  tighten_in_place(world, path, o);
  return path;
}

}  // namespace hpcplan::env
