// The grid engines on occupancy grids users bring, against answers computed by others: every
// row of every MovingAI map in the shared benchmark folder solved by sparse A* (jump points)
// and checked against the published optimal length, its path re-walked move by move on the
// map's own characters by this file's reader (not the library's parser or grid); plain A*,
// weighted A*, Dijkstra and the dense engine on samples of rows; and voxel maps and
// N-dimensional arrays, for which no published answers are stored here, against this file's
// own Dijkstra and BFS (textbook, over a std::vector<char> of the cells).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <queue>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/occupancy_io.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/plan/scenario_run.hpp"

#ifndef HPCPLAN_MOVINGAI_DIR
#define HPCPLAN_MOVINGAI_DIR "/work/shared/benchmarks/movingai"
#endif

namespace hpcplan {
namespace {

namespace fs = std::filesystem;

// Under AddressSanitizer the whole-map runs take every `kSanitizedStride`-th row (a search is
// ~10x slower there, and the sanitizer stage's time is the test command's largest); the Release
// suite runs every row.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr std::size_t kSanitizedStride = 32;
#else
constexpr std::size_t kSanitizedStride = 1;
#endif

std::string movingai_dir() {
  if (const char* dir = std::getenv("HPCPLAN_MOVINGAI_DIR"); dir && *dir) return dir;
  return HPCPLAN_MOVINGAI_DIR;
}

// ---- this file's own reading of a .map: its characters, row y, column x -----------------

struct CharMap {
  int width = 0, height = 0;
  std::vector<std::string> rows;
  bool passable(int x, int y) const {
    if (x < 0 || y < 0 || x >= width || y >= height) return false;
    const char c = rows[y][x];
    return c == '.' || c == 'G' || c == 'S';
  }
};

CharMap read_char_map(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  CharMap m;
  std::string line;
  bool body = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!body) {
      std::istringstream words(line);
      std::string key;
      words >> key;
      if (key == "height") words >> m.height;
      if (key == "width") words >> m.width;
      if (key == "map") body = true;
      continue;
    }
    if (static_cast<int>(m.rows.size()) < m.height) m.rows.push_back(line);
  }
  return m;
}

// The path's length if every step is one of the 8 moves between passable cells without cutting
// a corner, from start to goal; -1 otherwise.
double walk_on_chars(const CharMap& m, const std::vector<std::vector<int>>& path,
                     const std::vector<int>& start, const std::vector<int>& goal) {
  if (path.empty() || path.front() != start || path.back() != goal) return -1.0;
  double length = 0.0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const int x = path[i][0], y = path[i][1];
    if (!m.passable(x, y)) return -1.0;
    if (i == 0) continue;
    const int px = path[i - 1][0], py = path[i - 1][1];
    const int dx = x - px, dy = y - py;
    if (std::abs(dx) > 1 || std::abs(dy) > 1 || (dx == 0 && dy == 0)) return -1.0;
    if (dx != 0 && dy != 0) {
      if (!m.passable(px + dx, py) || !m.passable(px, py + dy)) return -1.0;
      length += std::sqrt(2.0);
    } else {
      length += 1.0;
    }
  }
  return length;
}

// Textbook Dijkstra on the characters: the published optimum's independent check.
double char_dijkstra(const CharMap& m, int sx, int sy, int gx, int gy) {
  std::vector<double> dist(static_cast<std::size_t>(m.width) * m.height, INFINITY);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[sy * m.width + sx] = 0.0;
  open.push({0.0, sy * m.width + sx});
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (d > dist[i]) continue;
    const int x = i % m.width, y = i / m.width;
    if (x == gx && y == gy) return d;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0) continue;
        if (!m.passable(x + dx, y + dy)) continue;
        if (dx != 0 && dy != 0 && (!m.passable(x + dx, y) || !m.passable(x, y + dy))) continue;
        const double nd = d + (dx != 0 && dy != 0 ? std::sqrt(2.0) : 1.0);
        const int j = (y + dy) * m.width + (x + dx);
        if (nd < dist[j]) {
          dist[j] = nd;
          open.push({nd, j});
        }
      }
  }
  return -1.0;
}

struct MapCase {
  const char* map;
};

class EveryRow : public ::testing::TestWithParam<MapCase> {};

std::string PrintMap(const ::testing::TestParamInfo<MapCase>& info) {
  std::string n = info.param.map;
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

struct Loaded {
  std::shared_ptr<const OccupancyGrid> grid;
  env::Scenario scenario;
  CharMap chars;
};

Loaded load(const char* map) {
  const std::string dir = movingai_dir();
  if (!fs::is_directory(dir))
    throw std::runtime_error("the MovingAI benchmark folder '" + dir +
                             "' is missing (set HPCPLAN_MOVINGAI_DIR)");
  Loaded l;
  l.grid = std::make_shared<OccupancyGrid>(env::load_occupancy(dir + "/" + map));
  l.scenario = env::load_scenario(dir + "/" + map + ".scen");
  l.chars = read_char_map(dir + "/" + map);
  return l;
}

std::vector<std::size_t> every(const env::Scenario& s, std::size_t stride) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < s.rows.size(); i += stride) rows.push_back(i);
  return rows;
}

// Runs `rows` with `options` and checks each against the published optimum and, with a path,
// on the characters. Returns the rows run.
std::size_t check_rows(const Loaded& l, const std::vector<std::size_t>& rows,
                       GridSearchOptions options, double weight = 1.0) {
  options.keep_path = true;
  const auto results =
      run_scenario_rows(l.grid, Connectivity::seed_pairs, l.scenario, rows, options);
  EXPECT_EQ(results.size(), rows.size());
  std::size_t bad = 0;
  for (const ScenarioRowResult& r : results) {
    const double length = walk_on_chars(l.chars, r.path, r.start, r.goal);
    const double tol = 1e-6 * std::max(1.0, r.optimal);
    const bool ok = !r.mismatch && r.status == Status::solved && std::abs(length - r.cost) <= tol &&
                    r.cost >= r.optimal - tol && r.cost <= weight * r.optimal + tol;
    if (!ok && ++bad <= 5)
      ADD_FAILURE() << "row " << r.row << ": cost " << r.cost << ", published " << r.optimal
                    << ", path walked on the map's characters " << length;
  }
  return results.size();
}

TEST_P(EveryRow, JumpPointAStarIsOptimalOnEveryPublishedProblem) {
  const Loaded l = load(GetParam().map);
  GridSearchOptions o;  // A*, jump points, sparse
  const std::size_t n = check_rows(l, every(l.scenario, kSanitizedStride), o);
  EXPECT_EQ(n * kSanitizedStride >= l.scenario.rows.size(), true);
  std::printf("[ rows     ] %zu of %zu rows of %s checked\n", n, l.scenario.rows.size(),
              GetParam().map);
}

TEST_P(EveryRow, PlainWeightedAndDijkstraAgreeOnASample) {
  const Loaded l = load(GetParam().map);
  const auto sample = every(l.scenario, 97 * kSanitizedStride);
  GridSearchOptions plain;
  plain.jump_points = false;
  check_rows(l, sample, plain);
  GridSearchOptions weighted;
  weighted.algorithm = GridAlgorithm::wastar;
  weighted.weight = 1.5;
  check_rows(l, sample, weighted, 1.5);
  GridSearchOptions dijkstra;
  dijkstra.algorithm = GridAlgorithm::dijkstra;
  dijkstra.engine = GridEngine::sparse;
  check_rows(l, sample, dijkstra);
}

TEST_P(EveryRow, DenseDijkstraIsOptimalOnASample) {
  const Loaded l = load(GetParam().map);
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::dijkstra;
  o.engine = GridEngine::dense;
  // Threads: the dense engine's own rule (one on a 2D map: a level is a few hundred cells).
  // About 200 rows a map (a dense query floods much of the map: milliseconds each).
  check_rows(
      l,
      every(l.scenario, std::max<std::size_t>(1, l.scenario.rows.size() / 200) * kSanitizedStride),
      o);
}

TEST_P(EveryRow, ThisFilesDijkstraAgreesWithThePublishedLengths) {
  // The oracle itself, against the published answers, so a wrong oracle cannot pass a wrong
  // planner elsewhere.
  const Loaded l = load(GetParam().map);
  for (std::size_t i = 0; i < l.scenario.rows.size(); i += 211 * kSanitizedStride) {
    const env::ScenarioRow& r = l.scenario.rows[i];
    const double d = char_dijkstra(l.chars, r.start[0], r.start[1], r.goal[0], r.goal[1]);
    EXPECT_NEAR(d, r.optimal, 1e-6 * std::max(1.0, r.optimal)) << "row " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(MovingAi, EveryRow,
                         ::testing::Values(MapCase{"random512-40-5.map"},
                                           MapCase{"maze512-4-6.map"}, MapCase{"64room_005.map"},
                                           MapCase{"Boston_0_256.map"}),
                         PrintMap);

// ---- N-dimensional arrays and voxel maps against this file's own searches ----------------

// A random array of `shape` (x first), blocked with probability `density`, its cells listed
// with x fastest.
struct Cells {
  std::vector<int> shape;
  std::vector<char> blocked;
  std::size_t index(const std::vector<int>& c) const {
    std::size_t i = 0;
    for (int a = static_cast<int>(shape.size()) - 1; a >= 0; --a) i = i * shape[a] + c[a];
    return i;
  }
  bool free(const std::vector<int>& c) const {
    for (std::size_t a = 0; a < shape.size(); ++a)
      if (c[a] < 0 || c[a] >= shape[a]) return false;
    return !blocked[index(c)];
  }
};

Cells random_cells(std::vector<int> shape, double density, std::uint64_t seed) {
  Cells c;
  c.shape = std::move(shape);
  std::size_t n = 1;
  for (int s : c.shape) n *= static_cast<std::size_t>(s);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution b(density);
  c.blocked.resize(n);
  for (auto& v : c.blocked) v = b(rng);
  return c;
}

// The grid through the library's byte reader (NumPy order: the shape reversed).
std::shared_ptr<const OccupancyGrid> as_grid(const Cells& c) {
  std::vector<std::int64_t> numpy(c.shape.rbegin(), c.shape.rend());
  std::vector<std::uint8_t> bytes(c.blocked.begin(), c.blocked.end());
  return std::make_shared<OccupancyGrid>(occupancy_from_bytes(bytes.data(), numpy));
}

// Dijkstra (costs sqrt k) or BFS (hops) from `s` to `g` over the seed rule (1 or 2 axes, both
// one-axis intermediates free) or full connectivity (any axes, every corner of the spanned cube
// free). Returns -1 when unreachable.
double cells_search(const Cells& cells, const std::vector<int>& s, const std::vector<int>& g,
                    bool full, bool hops) {
  const int d = static_cast<int>(cells.shape.size());
  std::vector<double> dist(cells.blocked.size(), INFINITY);
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[cells.index(s)] = 0;
  open.push({0, cells.index(s)});
  std::vector<int> c(d), n(d);
  // The moves once: their axes and steps (k axes each).
  struct Move {
    std::vector<int> axes, steps;
  };
  std::vector<Move> moves;
  int count = 1;
  for (int a = 0; a < d; ++a) count *= 3;
  for (int m = 0; m < count; ++m) {
    Move mv;
    for (int a = 0, q = m; a < d; ++a, q /= 3)
      if (q % 3 != 1) {
        mv.axes.push_back(a);
        mv.steps.push_back(q % 3 - 1);
      }
    const std::size_t k = mv.axes.size();
    if (k == 0 || (!full && k > 2)) continue;
    moves.push_back(std::move(mv));
  }
  while (!open.empty()) {
    const auto [dd, i] = open.top();
    open.pop();
    if (dd > dist[i]) continue;
    std::size_t rest = i;
    for (int a = 0; a < d; ++a) {
      c[a] = static_cast<int>(rest % cells.shape[a]);
      rest /= cells.shape[a];
    }
    if (c == g) return dd;
    for (const Move& mv : moves) {
      const int k = static_cast<int>(mv.axes.size());
      bool ok = true;
      for (unsigned sub = 1; sub < (1u << k) && ok; ++sub) {
        n = c;
        for (int j = 0; j < k; ++j)
          if (sub & (1u << j)) n[mv.axes[j]] += mv.steps[j];
        ok = cells.free(n);
      }
      if (!ok) continue;
      n = c;
      for (int j = 0; j < k; ++j) n[mv.axes[j]] += mv.steps[j];
      const double nd = dd + (hops ? 1.0 : std::sqrt(static_cast<double>(k)));
      const std::size_t j = cells.index(n);
      if (nd < dist[j]) {
        dist[j] = nd;
        open.push({nd, j});
      }
    }
  }
  return -1.0;
}

std::vector<int> random_free(const Cells& c, std::mt19937_64& rng) {
  for (;;) {
    std::vector<int> p(c.shape.size());
    for (std::size_t a = 0; a < p.size(); ++a)
      p[a] = std::uniform_int_distribution<int>(0, c.shape[a] - 1)(rng);
    if (c.free(p)) return p;
  }
}

struct ArrayCase {
  std::vector<int> shape;
  double density;
  bool full;
};

class Arrays : public ::testing::TestWithParam<ArrayCase> {};

TEST_P(Arrays, EveryEngineEqualsTheTextbookSearch) {
  const ArrayCase& ac = GetParam();
  const Cells cells = random_cells(ac.shape, ac.density, 7 + ac.shape.size());
  const auto grid = as_grid(cells);
  std::mt19937_64 rng(11);
  int solved = 0, unreachable = 0;
  for (int q = 0; q < 12; ++q) {
    const auto s = random_free(cells, rng), g = random_free(cells, rng);
    const double cost = cells_search(cells, s, g, ac.full, false);
    const double hops = cells_search(cells, s, g, ac.full, true);
    (cost < 0 ? unreachable : solved)++;
    GridProblem p =
        occupancy_problem(grid, ac.full ? Connectivity::full : Connectivity::seed_pairs);
    p.start = s;
    p.goal = g;
    struct Run {
      GridAlgorithm algo;
      GridEngine engine;
      bool hops;
    };
    for (const Run run : {Run{GridAlgorithm::astar, GridEngine::sparse, false},
                          Run{GridAlgorithm::dijkstra, GridEngine::sparse, false},
                          Run{GridAlgorithm::dijkstra, GridEngine::dense, false},
                          Run{GridAlgorithm::bfs, GridEngine::dense, true},
                          Run{GridAlgorithm::bfs, GridEngine::sparse, true}}) {
      GridSearchOptions o;
      o.algorithm = run.algo;
      o.engine = run.engine;
      o.threads = 0;  // the engine's own rule
      const GridReport r = solve_grid(p, o);
      const double want = run.hops ? hops : cost;
      SCOPED_TRACE(std::string(to_string(run.algo)) +
                   (run.engine == GridEngine::dense ? " dense" : " sparse"));
      if (want < 0) {
        EXPECT_EQ(r.result.status, Status::no_path);
      } else {
        ASSERT_EQ(r.result.status, Status::solved);
        if (run.hops)
          EXPECT_EQ(static_cast<double>(r.result.hops), want);
        else
          EXPECT_NEAR(r.result.cost, want, 1e-9 * (1 + want));
      }
    }
  }
  EXPECT_GT(solved, 0);
}

INSTANTIATE_TEST_SUITE_P(
    Occupancy, Arrays,
    ::testing::Values(ArrayCase{{37}, 0.2, false},          // 1D
                      ArrayCase{{45, 23}, 0.3, false},      // 2D, not square, not a tile multiple
                      ArrayCase{{70, 9}, 0.25, false},      // 2D rows wider than a word
                      ArrayCase{{13, 11, 9}, 0.3, true},    // 3D, 26-connected
                      ArrayCase{{12, 10, 9}, 0.3, false},   // 3D, seed rule
                      ArrayCase{{6, 7, 5, 6}, 0.25, true},  // 4D, 80-connected
                      ArrayCase{{5, 4, 6, 5, 4}, 0.2, false},           // 5D
                      ArrayCase{{3, 4, 3, 4, 3, 3, 2}, 0.15, false}));  // 7D

TEST(VoxelMap, AFileOnDiskPlansLikeItsCells) {
  // A .3dmap written here (the format: "voxel W H D", then blocked "x y z"), read back by the
  // loader, 26-connected: against this file's own Dijkstra.
  const Cells cells = random_cells({17, 14, 11}, 0.3, 5);
  const fs::path path = fs::temp_directory_path() / "hpcplan_test_voxels.3dmap";
  {
    std::ofstream out(path);
    out << "voxel 17 14 11\n";
    std::vector<int> c(3);
    for (c[2] = 0; c[2] < 11; ++c[2])
      for (c[1] = 0; c[1] < 14; ++c[1])
        for (c[0] = 0; c[0] < 17; ++c[0])
          if (cells.blocked[cells.index(c)]) out << c[0] << " " << c[1] << " " << c[2] << "\n";
  }
  const auto grid = std::make_shared<OccupancyGrid>(env::load_occupancy(path.string()));
  fs::remove(path);
  ASSERT_EQ(grid->shape(), (std::vector<int>{17, 14, 11}));
  std::mt19937_64 rng(3);
  for (int q = 0; q < 10; ++q) {
    const auto s = random_free(cells, rng), g = random_free(cells, rng);
    const double want = cells_search(cells, s, g, true, false);
    GridProblem p = occupancy_problem(grid, Connectivity::full);
    p.start = s;
    p.goal = g;
    for (GridEngine e : {GridEngine::sparse, GridEngine::dense}) {
      GridSearchOptions o;
      o.algorithm = e == GridEngine::dense ? GridAlgorithm::dijkstra : GridAlgorithm::astar;
      o.engine = e;
      const GridReport r = solve_grid(p, o);
      if (want < 0) {
        EXPECT_EQ(r.result.status, Status::no_path);
      } else {
        ASSERT_EQ(r.result.status, Status::solved);
        EXPECT_NEAR(r.result.cost, want, 1e-9 * (1 + want));
      }
    }
  }
}

TEST(OccupancyProblem, BadEndsAreOneLineInputErrors) {
  const Cells cells = random_cells({8, 6}, 0.0, 1);
  auto bytes = std::vector<std::uint8_t>(48, 0);
  bytes[0] = 1;  // (0, 0) blocked
  const std::int64_t numpy[] = {6, 8};
  const auto grid = std::make_shared<OccupancyGrid>(occupancy_from_bytes(bytes.data(), numpy));
  GridProblem p = occupancy_problem(grid);
  auto message = [&](std::vector<int> s, std::vector<int> g) {
    p.start = s;
    p.goal = g;
    try {
      solve_grid(p, GridSearchOptions{});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message({8, 0}, {1, 1}).find("outside the map [0, 7] x [0, 5]"), std::string::npos);
  EXPECT_NE(message({1, 1, 0}, {1, 1}).find("the map has 2 dimensions"), std::string::npos);
  EXPECT_NE(message({0, 0}, {1, 1}).find("inside an obstacle"), std::string::npos);
  EXPECT_NE(message({1, 1}, {7, 6}).find("outside the map"), std::string::npos);
}

}  // namespace
}  // namespace hpcplan

namespace hpcplan {
namespace {

TEST(OccupancyJumpPoints, WordScansEqualDijkstraOnNarrowAndWideGrids) {
  // Widths around the word and packing boundaries (rows under 32 cells are packed, not padded),
  // heights around the transposed columns' word; random obstacles; jump-point A* (word scans
  // along x and along the sealed grid's columns) against Dijkstra on the same grid, and against
  // A* on an unsealed copy (scans along y cell by cell).
  int compared = 0;
  for (const auto& [w, h] : std::vector<std::pair<int, int>>{
           {5, 70}, {31, 31}, {33, 65}, {64, 64}, {65, 40}, {130, 129}, {200, 7}}) {
    SCOPED_TRACE(std::to_string(w) + " x " + std::to_string(h));
    const Cells cells = random_cells({w, h}, 0.3, static_cast<std::uint64_t>(w * 1000 + h));
    const auto grid = as_grid(cells);
    auto unsealed = std::make_shared<OccupancyGrid>(*grid);
    unsealed->set_free(std::vector<int>{0, 0}, grid->is_free(std::vector<int>{0, 0}));
    ASSERT_TRUE(unsealed->transposed().empty());
    std::mt19937_64 rng(static_cast<std::uint64_t>(w + h));
    for (int q = 0; q < 40; ++q) {
      const auto s = random_free(cells, rng), g = random_free(cells, rng);
      GridSearchOptions dijkstra;
      dijkstra.algorithm = GridAlgorithm::dijkstra;
      dijkstra.engine = GridEngine::sparse;
      GridProblem p = occupancy_problem(grid);
      p.start = s;
      p.goal = g;
      const GridReport want = solve_grid(p, dijkstra);
      const GridReport jps = solve_grid(p, GridSearchOptions{});
      ASSERT_EQ(jps.options.pruning, "jump_points");
      GridProblem pu = occupancy_problem(unsealed);
      pu.start = s;
      pu.goal = g;
      const GridReport cellwise = solve_grid(pu, GridSearchOptions{});
      ASSERT_EQ(jps.result.status, want.result.status);
      ASSERT_EQ(cellwise.result.status, want.result.status);
      if (want.result.status == Status::solved) {
        EXPECT_NEAR(jps.result.cost, want.result.cost, 1e-9 * (1 + want.result.cost));
        EXPECT_NEAR(cellwise.result.cost, want.result.cost, 1e-9 * (1 + want.result.cost));
        ++compared;
      }
    }
  }
  EXPECT_GT(compared, 100);
}

}  // namespace
}  // namespace hpcplan
