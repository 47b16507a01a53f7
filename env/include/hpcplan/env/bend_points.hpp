#pragma once
// Where a shortest path may bend. Among closed convex obstacles a shortest path is straight
// except where it wraps an obstacle's boundary: on the edges and corners of boxes, on the rims
// of discs. These are sampled (every `spacing` along each box edge, every `spacing` of arc
// along each disc) and lifted just off the obstacle into free space, so a visibility graph
// over them (graph/visibility_graph.hpp) approximates the shortest path's homotopy and length,
// and tightening then slides its bends to the exact place.
//
// Each point also carries the outward normals of the surfaces meeting there. A segment through
// a bend of a shortest path is tangent to the obstacle: the line neither enters it just ahead
// of the point nor just behind it. A segment that points into the obstacle's solid angle, or
// straight out of it, cannot belong to a shortest path through that point, and the visibility
// graph skips it without a collision test.
#include <array>
#include <cmath>
#include <vector>

#include "hpcplan/env/box_world.hpp"
#include "hpcplan/env/point.hpp"
#include "hpcplan/env/sphere_world.hpp"

namespace hpcplan::env {

template <int D>
struct BendPoint {
  Vec<D> point{};
  std::array<Vec<D>, D> normals{};  // unit outward normals of the surfaces meeting here
  int normal_count = 0;
  // Segments along a surface (between neighbouring samples of one edge or polygon side) are
  // exactly tangent; the rounding of their direction must not decide against them.
  double slack = 1e-7;

  // False when the line through the point along d (not normalised) enters the obstacle right
  // ahead of the point or right behind it.
  bool tangent(const Vec<D>& d) const {
    double len = 0;
    for (int k = 0; k < D; ++k) len += d[k] * d[k];
    len = std::sqrt(len);
    if (!(len > 0)) return true;
    bool ahead = true, behind = true;
    for (int i = 0; i < normal_count; ++i) {
      double c = 0;
      for (int k = 0; k < D; ++k) c += normals[i][k] * d[k];
      c /= len;
      ahead = ahead && c < -slack;
      behind = behind && c > slack;
    }
    return !ahead && !behind;
  }
};

// Corners and edge samples of every block, `spacing` apart along each edge, lifted off the
// block by `lift` along each outward normal; points that are not free (inside a neighbouring
// block, outside the boundary) are left out: no free path bends there.
std::vector<BendPoint<3>> bend_points(const BoxWorld& world, double spacing, double lift);

// The corners of a polygon circumscribing every obstacle disc (sides at most `spacing` long,
// at least eight), pushed out by `lift`: the sides between neighbouring corners clear the
// disc, and each corner's normals are its two sides'.
std::vector<BendPoint<2>> bend_points(const SphereWorld& world, double spacing, double lift);

}  // namespace hpcplan::env
