#pragma once
// The exact shortest path of a path's homotopy class in a 2D world whose obstacles are unit
// cells (the GOG field at 2D): what the tightener (path_shortcut.hpp) approaches by sliding
// bends, in a few passes of a closed-form step.
//
// The step: a string a-q-b pulled towards its chord a-b catches on the obstacles inside the
// triangle a-q-b, and comes to rest on the convex chain of their corners on q's side of the
// chord. So each pass visits every interior vertex q, with a = the vertex kept before it and
// b = the one after, and puts that chain in q's place; where a sees b, q is simply dropped,
// which may leave the class for a shorter one (past an obstacle island inside the triangle). A
// path where no vertex can be replaced is locally shortest, and in the plane a locally
// shortest path is the shortest of its homotopy class.
//
// These worlds count touching a blocked cell as a collision, so a chain through a corner is
// blocked by the corner itself: each chain vertex is moved off its corner by `hair` (cell
// widths) along the chain's outward bisector. Every new segment then goes through the world's
// own exact segment test, and a replacement that fails it or does not shorten the path is not
// made: the result is as valid as the input and never longer.
//
// Cost: a visit reads the cells around every lattice corner inside its triangle, so the first
// pass costs about the area between the path and its chords, and later passes little more
// than the thin triangles left at the wrapped corners.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "hpcplan/core/stop.hpp"
#include "hpcplan/env/point.hpp"

namespace hpcplan::env {

struct TautOptions {
  double hair = 1e-7;   // how far each chain vertex stays off its corner, cell widths
  int max_passes = 64;  // a pass that replaces nothing ends the run earlier
  Stop stop;
};

struct TautStats {
  int passes = 0;
  bool converged = false;          // the last pass replaced nothing
  std::uint64_t cells_read = 0;    // cells looked up to find the corners
  std::uint64_t replacements = 0;  // vertices replaced by a chain (or dropped)
};

namespace detail {

inline double cross2(const Vec<2>& o, const Vec<2>& u, const Vec<2>& v) {
  return (u[0] - o[0]) * (v[1] - o[1]) - (u[1] - o[1]) * (v[0] - o[0]);
}

// The corners of blocked cells strictly on q's side of chord a-b and inside triangle a-q-b.
// `blocked(x, y)` answers for cell (x, y), which spans [x, x + 1] x [y, y + 1], including
// cells outside the world (free there, as in the exact walk: a convex box never holds a taut
// path on its walls).
template <class Blocked>
std::vector<Vec<2>> corners_inside(const Blocked& blocked, const Vec<2>& a, const Vec<2>& q,
                                   const Vec<2>& b, std::uint64_t& cells_read) {
  const double sign = cross2(a, q, b) > 0 ? 1.0 : -1.0;
  const auto inside = [&](const Vec<2>& p) {
    return sign * cross2(a, q, p) >= 0 && sign * cross2(q, b, p) >= 0 && sign * cross2(b, a, p) > 0;
  };
  std::vector<Vec<2>> corners;
  const double y_lo = std::min({a[1], q[1], b[1]}), y_hi = std::max({a[1], q[1], b[1]});
  const Vec<2>* edges[3][2] = {{&a, &q}, {&q, &b}, {&b, &a}};
  for (double y = std::ceil(y_lo); y <= y_hi; y += 1.0) {
    // The triangle's extent along this row: where its edges cross the line.
    double x_lo = INFINITY, x_hi = -INFINITY;
    for (const auto& e : edges) {
      const Vec<2>& u = *e[0];
      const Vec<2>& v = *e[1];
      if ((u[1] - y) * (v[1] - y) > 0) continue;  // the edge does not reach this row
      if (u[1] == v[1]) {                         // the edge lies on the row
        x_lo = std::min({x_lo, u[0], v[0]});
        x_hi = std::max({x_hi, u[0], v[0]});
      } else {
        const double x = u[0] + (v[0] - u[0]) * (y - u[1]) / (v[1] - u[1]);
        x_lo = std::min(x_lo, x);
        x_hi = std::max(x_hi, x);
      }
    }
    for (double x = std::ceil(x_lo); x <= x_hi; x += 1.0) {
      const Vec<2> p{x, y};
      if (!inside(p)) continue;
      const int ix = static_cast<int>(x), iy = static_cast<int>(y);
      bool corner = false;
      for (int k = 0; k < 4 && !corner; ++k) {
        ++cells_read;
        corner = blocked(ix - 1 + (k & 1), iy - 1 + (k >> 1));
      }
      if (corner) corners.push_back(p);
    }
  }
  return corners;
}

// The convex hull of `points`, counter-clockwise, without collinear vertices (Andrew's
// monotone chain).
inline std::vector<Vec<2>> convex_hull(std::vector<Vec<2>> points) {
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Vec<2>> hull(2 * points.size());
  std::size_t k = 0;
  for (const Vec<2>& p : points) {
    while (k >= 2 && cross2(hull[k - 2], hull[k - 1], p) <= 0) --k;
    hull[k++] = p;
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {
    while (k >= lower && cross2(hull[k - 2], hull[k - 1], points[i]) <= 0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

// What replaces q between a and b (which do not see each other): the chain's interior
// vertices, each moved off its corner. Empty where there is no chain to take: a degenerate
// triangle, or a chord blocked only by a cell outside the triangle (at an end).
template <class Blocked>
std::vector<Vec<2>> wrap_chain(const Blocked& blocked, const Vec<2>& a, const Vec<2>& q,
                               const Vec<2>& b, double hair, std::uint64_t& cells_read) {
  const double turn = cross2(a, q, b);
  if (turn == 0) return {};
  std::vector<Vec<2>> points = corners_inside(blocked, a, q, b, cells_read);
  if (points.empty()) return {};
  points.push_back(a);
  points.push_back(b);
  const std::vector<Vec<2>> hull = convex_hull(std::move(points));
  const auto ia = std::find(hull.begin(), hull.end(), a) - hull.begin();
  const auto ib = std::find(hull.begin(), hull.end(), b) - hull.begin();
  const auto n = static_cast<std::ptrdiff_t>(hull.size());
  if (ia == n || ib == n) return {};
  // One way round from a to b is the chord itself; the other is the chain.
  std::vector<Vec<2>> chain;
  const std::ptrdiff_t forward = (ib - ia + n) % n;
  const std::ptrdiff_t step = forward > 1 ? 1 : -1;
  for (std::ptrdiff_t i = (ia + step + n) % n; i != ib; i = (i + step + n) % n)
    chain.push_back(hull[i]);
  // The obstacles lie on the chord's side of every chain edge; "outward" is the other side.
  const double out = turn < 0 ? 1.0 : -1.0;  // left of a -> b when q is
  const auto left_normal = [](const Vec<2>& u, const Vec<2>& v) {
    const double dx = v[0] - u[0], dy = v[1] - u[1], l = std::hypot(dx, dy);
    return Vec<2>{-dy / l, dx / l};
  };
  std::vector<Vec<2>> moved(chain.size());
  for (std::size_t k = 0; k < chain.size(); ++k) {
    const Vec<2>& p = k == 0 ? a : chain[k - 1];
    const Vec<2>& c = chain[k];
    const Vec<2>& s = k + 1 == chain.size() ? b : chain[k + 1];
    const Vec<2> n1 = left_normal(p, c), n2 = left_normal(c, s);
    Vec<2> dir{out * (n1[0] + n2[0]), out * (n1[1] + n2[1])};
    const double l = std::hypot(dir[0], dir[1]);
    if (!(l > 0)) return {};
    moved[k] = {c[0] + hair * dir[0] / l, c[1] + hair * dir[1] / l};
  }
  return moved;
}

}  // namespace detail

// Replaces `path` by the shortest path of its homotopy class (up to `hair` at each corner),
// or by a shorter valid path when stopped early. `world.segment_free` is the exact test every
// new segment must pass.
template <class W, class Blocked>
TautStats taut_path_2d(const W& world, const Blocked& blocked, std::vector<Vec<2>>& path,
                       const TautOptions& o = {}) {
  static_assert(W::kDim == 2, "taut_path_2d is for 2D worlds");
  TautStats stats;
  const Stop& stop = o.stop;
  // A replacement must gain more than moving a few vertices by a hair could.
  const double gain = 16 * o.hair;
  stats.converged = path.size() <= 2;  // no bend to replace
  // A pass is long enough to read the clock before each one (check, not poll).
  while (!stats.converged && stats.passes < o.max_passes && !stop.check()) {
    ++stats.passes;
    bool replaced = false;
    std::vector<Vec<2>> out{path.front()};
    for (std::size_t i = 1; i + 1 < path.size(); ++i) {
      const Vec<2>& a = out.back();
      const Vec<2>& q = path[i];
      const Vec<2>& b = path[i + 1];
      // Where a sees b, q goes: the class may change for a shorter one (an obstacle island
      // inside the triangle, which the chain would wrap).
      if (world.segment_free(a, b)) {
        ++stats.replacements;
        replaced = true;
        continue;
      }
      const auto chain = detail::wrap_chain(blocked, a, q, b, o.hair, stats.cells_read);
      bool take = !chain.empty();
      if (take) {
        double length = 0;
        Vec<2> from = a;
        for (const Vec<2>& c : chain) {
          length += distance<2>(from, c);
          from = c;
        }
        length += distance<2>(from, b);
        take = length < distance<2>(a, q) + distance<2>(q, b) - gain;
      }
      if (take) {
        Vec<2> from = a;
        for (const Vec<2>& c : chain) {
          take = take && world.segment_free(from, c);
          from = c;
        }
        take = take && world.segment_free(from, b);
      }
      if (!take) {
        out.push_back(q);
        continue;
      }
      out.insert(out.end(), chain.begin(), chain.end());
      ++stats.replacements;
      replaced = true;
    }
    out.push_back(path.back());
    path.swap(out);
    stats.converged = !replaced || path.size() <= 2;
  }
  return stats;
}

}  // namespace hpcplan::env
