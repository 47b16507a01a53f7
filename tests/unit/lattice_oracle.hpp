#pragma once
// An independent reference for lattice searches: textbook Dijkstra and BFS over explicit
// coordinate vectors, with the neighbour rule re-derived from the GOG formula (no packed keys,
// level tables, incremental sums or the library's engine). Meant for small lattices.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <queue>
#include <span>
#include <stdexcept>
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
  // The most axes a lattice here has (the GOG field's limit is far above what fits a test).
  static constexpr int kMaxDims = 16;

  Lattice(const hpcplan::GogField& field, bool full) : field_(field), full_(full) {
    if (field.dims() > kMaxDims) throw std::invalid_argument("oracle::Lattice: too many axes");
    // The state count, for the searches below; a lattice too large to count in 64 bits (16
    // axes of 5,000) can still have its paths walked (path_length), never searched.
    n_ = 1;
    for (int i = 0; i < field.dims() && n_ > 0; ++i)
      n_ = n_ > INT64_MAX / field.extent() ? -1 : n_ * field.extent();
  }
  std::int64_t index(std::span<const int> c) const {
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
  double move_length(std::span<const int> a, std::span<const int> b) const {
    // Fixed-size scratch, no allocation: the oracle tries 3^d offsets per state, and a vector
    // per try made it most of the unit suite's time under ASan (8D: 13 s a test, 1.6 s in
    // Release, the allocator's stack traces on top).
    const int dims = field_.dims();
    std::array<int, kMaxDims> axes{};
    int k = 0;
    for (int i = 0; i < dims; ++i) {
      const int d = b[i] - a[i];
      if (d < -1 || d > 1) return -1;
      if (d) axes[static_cast<std::size_t>(k++)] = i;
    }
    if (k == 0 || (!full_ && k > 2)) return -1;
    std::array<int, kMaxDims> corner{};
    for (int mask = 0; mask < (1 << k); ++mask) {
      std::copy(a.begin(), a.end(), corner.begin());
      for (int j = 0; j < k; ++j)
        if (mask & (1 << j)) corner[axes[j]] = b[axes[j]];
      if (!field_.is_free(std::span<const int>(corner.data(), a.size()))) return -1;
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
  void neighbours(std::span<const int> a, F&& f) const {
    // Enumerate all 3^d offsets and keep the legal ones: slow and obviously complete.
    const int d = field_.dims();
    int total = 1;
    for (int i = 0; i < d; ++i) total *= 3;
    std::array<int, kMaxDims> scratch{};
    const std::span<int> b(scratch.data(), static_cast<std::size_t>(d));
    for (int code = 0; code < total; ++code) {
      bool inside = true;
      for (int i = 0, q = code; i < d; ++i, q /= 3) {
        b[i] = a[i] + q % 3 - 1;
        inside = inside && b[i] >= 0 && b[i] < field_.extent();
      }
      if (!inside) continue;
      const double len = move_length(a, b);
      if (len > 0) f(std::span<const int>(b), len);
    }
  }

  Answer dijkstra(const std::vector<int>& s, const std::vector<int>& g) const {
    if (n_ < 0) throw std::invalid_argument("oracle::Lattice: too many states to search");
    std::vector<double> dist(n_, INFINITY);
    using Item = std::pair<double, std::int64_t>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> pq;
    dist[index(s)] = 0;
    pq.push({0.0, index(s)});
    const std::int64_t target = index(g);
    while (!pq.empty()) {
      // Plain variables, not a structured binding: the lambda below captures d, which
      // clang before 16 refuses for a binding.
      const double d = pq.top().first;
      const std::int64_t u = pq.top().second;
      pq.pop();
      if (d > dist[u]) continue;
      if (u == target) return {true, d, -1};
      neighbours(coords(u), [&](std::span<const int> v, double len) {
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
    if (n_ < 0) throw std::invalid_argument("oracle::Lattice: too many states to search");
    std::vector<std::int64_t> hops(n_, -1);
    std::queue<std::int64_t> q;
    hops[index(s)] = 0;
    q.push(index(s));
    while (!q.empty()) {
      const std::int64_t u = q.front();
      q.pop();
      if (u == index(g)) return {true, 0.0, hops[u]};
      neighbours(coords(u), [&](std::span<const int> v, double) {
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
