#pragma once
// A textbook Dijkstra over every cell of an n x n bitmap with the seed rule written out again
// (8 moves; a diagonal only where both one-axis cells are free): the oracle for the 2D lattice
// searches and the source of lattice paths for the 2D smoothing tests.
#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <utility>
#include <vector>

namespace hpcplan::test_support {

struct BitmapPath {
  double cost = INFINITY;                  // infinity when the goal cannot be reached
  std::vector<std::pair<int, int>> cells;  // start to goal
};

// `blocked(x, y)` for 0 <= x, y < n.
template <class Blocked>
BitmapPath bitmap_dijkstra(int n, const Blocked& blocked, int sx, int sy, int gx, int gy) {
  std::vector<double> dist(static_cast<std::size_t>(n) * n, INFINITY);
  std::vector<int> parent(dist.size(), -1);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> pq;
  dist[sy * n + sx] = 0.0;
  pq.push({0.0, sy * n + sx});
  BitmapPath out;
  while (!pq.empty()) {
    const auto [d, u] = pq.top();
    pq.pop();
    if (d > dist[u]) continue;
    const int x = u % n, y = u / n;
    if (x == gx && y == gy) {
      out.cost = d;
      for (int v = u; v != -1; v = parent[v]) out.cells.push_back({v % n, v / n});
      std::reverse(out.cells.begin(), out.cells.end());
      return out;
    }
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= n || ny >= n) continue;
        if (blocked(nx, ny) || (dx && dy && (blocked(nx, y) || blocked(x, ny)))) continue;
        const double nd = d + (dx && dy ? std::sqrt(2.0) : 1.0);
        if (nd < dist[ny * n + nx] - 1e-12) {
          dist[ny * n + nx] = nd;
          parent[ny * n + nx] = u;
          pq.push({nd, ny * n + nx});
        }
      }
  }
  return out;
}

}  // namespace hpcplan::test_support
