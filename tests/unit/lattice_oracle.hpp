#pragma once
// An independent reference for lattice searches: textbook Dijkstra and BFS over explicit
// coordinate vectors, with the neighbour rule re-derived from the GOG formula (no packed keys,
// level tables, incremental sums or the library's engine). Meant for small lattices.
#include <cmath>
#include <cstdint>
#include <queue>
#include <span>
#include <vector>

#include "hpcplan/env/gog.hpp"

namespace oracle {

struct Answer {
  bool reachable = false;
  double cost = 0.0;       // Dijkstra: optimal Euclidean length
  std::int64_t hops = -1;  // BFS: fewest moves
};

class Lattice {
 public:
  Lattice(const hpcplan::GogField& field, bool full) : field_(field), full_(full) {
    n_ = 1;
    for (int i = 0; i < field.dims(); ++i) n_ *= field.extent();
  }
  std::int64_t index(const std::vector<int>& c) const {
    std::int64_t idx = 0;
    for (int i = field_.dims() - 1; i >= 0; --i) idx = idx * field_.extent() + c[i];
    return idx;
  }
  std::vector<int> coords(std::int64_t idx) const {
    std::vector<int> c(field_.dims());
    for (int i = 0; i < field_.dims(); ++i) {
      c[i] = static_cast<int>(idx % field_.extent());
      idx /= field_.extent();
    }
    return c;
  }
  bool free(const std::vector<int>& c) const { return field_.is_free(c); }

  // Legal move a->b under the rule, with its length; -1 if illegal.
  double move_length(const std::vector<int>& a, const std::vector<int>& b) const {
    std::vector<int> axes;
    for (int i = 0; i < field_.dims(); ++i) {
      const int d = b[i] - a[i];
      if (d < -1 || d > 1) return -1;
      if (d) axes.push_back(i);
    }
    const int k = static_cast<int>(axes.size());
    if (k == 0 || (!full_ && k > 2)) return -1;
    for (int mask = 0; mask < (1 << k); ++mask) {
      std::vector<int> corner = a;
      for (int j = 0; j < k; ++j)
        if (mask & (1 << j)) corner[axes[j]] = b[axes[j]];
      if (!free(corner)) return -1;
    }
    return std::sqrt(static_cast<double>(k));
  }

  // Length of a path of lattice states, move by move under the rule; -1 at its first illegal
  // move, whose index goes to *illegal_step when given.
  double path_length(const std::vector<std::vector<int>>& path,
                     std::size_t* illegal_step = nullptr) const {
    double length = 0.0;
    for (std::size_t i = 1; i < path.size(); ++i) {
      const double len = move_length(path[i - 1], path[i]);
      if (len <= 0) {
        if (illegal_step) *illegal_step = i;
        return -1.0;
      }
      length += len;
    }
    return length;
  }

  template <class F>
  void neighbours(const std::vector<int>& a, F&& f) const {
    // Enumerate all 3^d offsets and keep the legal ones: slow and obviously complete.
    const int d = field_.dims();
    int total = 1;
    for (int i = 0; i < d; ++i) total *= 3;
    std::vector<int> b(d);
    for (int code = 0; code < total; ++code) {
      bool inside = true;
      for (int i = 0, q = code; i < d; ++i, q /= 3) {
        b[i] = a[i] + q % 3 - 1;
        inside = inside && b[i] >= 0 && b[i] < field_.extent();
      }
      if (!inside) continue;
      const double len = move_length(a, b);
      if (len > 0) f(b, len);
    }
  }

  Answer dijkstra(const std::vector<int>& s, const std::vector<int>& g) const {
    std::vector<double> dist(n_, INFINITY);
    using Item = std::pair<double, std::int64_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> pq;
    dist[index(s)] = 0;
    pq.push({0.0, index(s)});
    const std::int64_t target = index(g);
    while (!pq.empty()) {
      auto [d, u] = pq.top();
      pq.pop();
      if (d > dist[u]) continue;
      if (u == target) return {true, d, -1};
      neighbours(coords(u), [&](const std::vector<int>& v, double len) {
        const std::int64_t vi = index(v);
        if (d + len < dist[vi] - 1e-12) {
          dist[vi] = d + len;
          pq.push({dist[vi], vi});
        }
      });
    }
    return {};
  }

  Answer bfs(const std::vector<int>& s, const std::vector<int>& g) const {
    std::vector<std::int64_t> hops(n_, -1);
    std::queue<std::int64_t> q;
    hops[index(s)] = 0;
    q.push(index(s));
    while (!q.empty()) {
      const std::int64_t u = q.front();
      q.pop();
      if (u == index(g)) return {true, 0.0, hops[u]};
      neighbours(coords(u), [&](const std::vector<int>& v, double) {
        const std::int64_t vi = index(v);
        if (hops[vi] < 0) {
          hops[vi] = hops[u] + 1;
          q.push(vi);
        }
      });
    }
    return {};
  }

 private:
  const hpcplan::GogField& field_;
  bool full_;
  std::int64_t n_;
};

}  // namespace oracle
