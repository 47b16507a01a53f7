#pragma once
// A textbook A* on a MovingAI .map, the baseline of bench/movingai_bench.cpp: written the way a
// competent student writes it, sharing nothing with hpcplan's engine (its own parser, its own
// search).
//
//   - The map: the .map characters read here; '.', 'G' and 'S' passable, everything else
//     blocked; one byte per cell, row-major (cell = y * width + x).
//   - 8-connected, no corner cutting (a diagonal needs both orthogonal neighbours free), cost 1
//     straight and sqrt(2) diagonal; the octile heuristic.
//   - std::priority_queue (a binary heap) of (f, g, cell) with lazy deletion: a cell is pushed
//     again whenever its g improves, and a popped entry whose cell is closed is skipped. Ties
//     on f go to the larger g.
//   - g in a std::vector<double>, the closed flags in a std::vector<char> and the parents in a
//     std::vector<int>: g and the closed flags are RESET (std::fill over the whole map) at the
//     start of every query, as a textbook does (no generation stamps); the parents need no reset
//     (a parent is written whenever g is). The path is walked back from the goal through them,
//     so the search returns the path's length in moves too.
//
// Plain C++20, header-only; no hpcplan header.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <queue>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace textbook {

struct Map {
  int width = 0, height = 0;
  std::vector<char> passable;  // 1 passable, 0 blocked; width * height, row-major
  bool free(int x, int y) const {
    return x >= 0 && y >= 0 && x < width && y < height &&
           passable[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                    static_cast<std::size_t>(x)] != 0;
  }
};

// "type octile", "height H", "width W", "map", then H rows of W characters. Throws
// std::runtime_error naming the file on anything else.
inline Map read_map(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  auto fail = [&](const std::string& what) { throw std::runtime_error(path + ": " + what); };
  auto next_line = [&](std::string& line) {
    if (!std::getline(in, line)) return false;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return true;
  };
  Map m;
  std::string line;
  bool saw_map = false;
  while (!saw_map && next_line(line)) {
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "type") continue;
    if (key == "height") {
      words >> m.height;
    } else if (key == "width") {
      words >> m.width;
    } else if (key == "map") {
      saw_map = true;
    } else if (!key.empty()) {
      fail("unexpected header line '" + line + "'");
    }
  }
  if (!saw_map || m.width <= 0 || m.height <= 0) fail("no 'height', 'width' and 'map' header");
  m.passable.assign(static_cast<std::size_t>(m.width) * static_cast<std::size_t>(m.height), 0);
  for (int y = 0; y < m.height; ++y) {
    if (!next_line(line))
      fail("has " + std::to_string(y) + " rows, not " + std::to_string(m.height));
    if (static_cast<int>(line.size()) < m.width) fail("row " + std::to_string(y) + " is short");
    for (int x = 0; x < m.width; ++x) {
      const char c = line[static_cast<std::size_t>(x)];
      m.passable[static_cast<std::size_t>(y) * static_cast<std::size_t>(m.width) +
                 static_cast<std::size_t>(x)] = (c == '.' || c == 'G' || c == 'S') ? 1 : 0;
    }
  }
  return m;
}

struct Answer {
  double length = -1.0;  // -1: no path
  std::uint64_t expanded = 0;
  std::uint64_t moves = 0;  // the path's moves, walked back through the parents
};

class AStar {
 public:
  explicit AStar(const Map& map)
      : map_(map),
        g_(map.passable.size()),
        closed_(map.passable.size()),
        parent_(map.passable.size(), -1) {}

  Answer search(int sx, int sy, int gx, int gy) {
    Answer answer;
    if (!map_.free(sx, sy) || !map_.free(gx, gy)) return answer;
    // The textbook reset: every cell's g and closed flag, every query.
    std::fill(g_.begin(), g_.end(), std::numeric_limits<double>::infinity());
    std::fill(closed_.begin(), closed_.end(), 0);
    const int w = map_.width;
    const int start = sy * w + sx, goal = gy * w + gx;
    std::priority_queue<Entry, std::vector<Entry>, Later> open;
    g_[static_cast<std::size_t>(start)] = 0.0;
    parent_[static_cast<std::size_t>(start)] = -1;
    open.push({octile(sx, sy, gx, gy), 0.0, start});
    static constexpr int dx[8] = {1, -1, 0, 0, 1, 1, -1, -1};
    static constexpr int dy[8] = {0, 0, 1, -1, 1, -1, 1, -1};
    const double diagonal = std::sqrt(2.0);
    while (!open.empty()) {
      const Entry top = open.top();
      open.pop();
      const auto cell = static_cast<std::size_t>(top.cell);
      if (closed_[cell]) continue;  // a stale copy (lazy deletion)
      closed_[cell] = 1;
      ++answer.expanded;
      if (top.cell == goal) {
        answer.length = top.g;
        for (int c = goal; c != start; c = parent_[static_cast<std::size_t>(c)]) ++answer.moves;
        return answer;
      }
      const int x = top.cell % w, y = top.cell / w;
      for (int k = 0; k < 8; ++k) {
        const int nx = x + dx[k], ny = y + dy[k];
        if (!map_.free(nx, ny)) continue;
        if (k >= 4 && (!map_.free(nx, y) || !map_.free(x, ny))) continue;  // no corner cutting
        const auto next = static_cast<std::size_t>(ny * w + nx);
        if (closed_[next]) continue;
        const double g = top.g + (k >= 4 ? diagonal : 1.0);
        if (g < g_[next]) {
          g_[next] = g;
          parent_[next] = top.cell;
          open.push({g + octile(nx, ny, gx, gy), g, static_cast<int>(next)});
        }
      }
    }
    return answer;
  }

 private:
  struct Entry {
    double f, g;
    int cell;
  };
  // std::priority_queue pops the largest: an entry is "less" when it should come out later.
  struct Later {
    bool operator()(const Entry& a, const Entry& b) const {
      return a.f > b.f || (a.f == b.f && a.g < b.g);
    }
  };
  static double octile(int x, int y, int gx, int gy) {
    const int ax = std::abs(x - gx), ay = std::abs(y - gy);
    return static_cast<double>(std::max(ax, ay)) +
           (std::sqrt(2.0) - 1.0) * static_cast<double>(std::min(ax, ay));
  }

  const Map& map_;
  std::vector<double> g_;
  std::vector<char> closed_;
  std::vector<int> parent_;
};

}  // namespace textbook
