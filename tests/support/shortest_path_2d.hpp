#pragma once
// The exact shortest path between two points of a 2D world whose obstacles are unit cells, an
// oracle for the smoothing and the taut path. A shortest path bends only at convex obstacle
// corners: lattice points with exactly one blocked cell among their four. The worlds' cells are
// closed, so a path only comes arbitrarily close to a corner; each corner vertex sits `eps`
// inside the free cell diagonally opposite the blocked one. Dijkstra on the visibility graph of
// those points and the two ends, every edge tested with the world's exact segment test:
// quadratic in the corners, for test-sized grids.
#include <cmath>
#include <limits>
#include <vector>

#include "hpcplan/env/point.hpp"

namespace hpcplan::test_support {

// `blocked(x, y)`: cell (x, y) of the n x n grid, false outside it. Infinity when the goal
// cannot be reached.
template <class W, class Blocked>
double shortest_length_2d(const W& world, const Blocked& blocked, int n, const env::Vec<2>& s,
                          const env::Vec<2>& g, double eps) {
  std::vector<env::Vec<2>> v{s, g};
  for (int x = 1; x < n; ++x)
    for (int y = 1; y < n; ++y) {
      // The four cells around lattice point (x, y): (x-1+i, y-1+j).
      int count = 0, bi = 0, bj = 0;
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j)
          if (blocked(x - 1 + i, y - 1 + j)) ++count, bi = i, bj = j;
      if (count == 1) v.push_back({x + (bi ? -eps : eps), y + (bj ? -eps : eps)});
    }
  std::vector<double> dist(v.size(), std::numeric_limits<double>::infinity());
  std::vector<bool> done(v.size(), false);
  dist[0] = 0;
  for (;;) {
    std::size_t u = v.size();
    for (std::size_t i = 0; i < v.size(); ++i)
      if (!done[i] && (u == v.size() || dist[i] < dist[u])) u = i;
    if (u == v.size() || std::isinf(dist[u]) || u == 1) return dist[1];
    done[u] = true;
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (done[i]) continue;
      const double through = dist[u] + env::distance<2>(v[u], v[i]);
      if (through < dist[i] && world.segment_free(v[u], v[i])) dist[i] = through;
    }
  }
}

}  // namespace hpcplan::test_support
