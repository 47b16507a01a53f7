// The distance field (plan/distance_field.hpp): the dense engine run past the goal, every cell's
// hop count (BFS) or exact path cost (Dijkstra), -1 for blocked and unreachable cells, checked
// cell by cell against an independent oracle on a plain array (Dijkstra with sqrt(k) moves and
// no corner cutting; BFS by hops), on hand-made and random grids in 2D and 3D, a real MovingAI
// map, for 1, 2 and 3 OpenMP threads and several slab layouts; and the .npy bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <queue>
#include <random>
#include <string>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/occupancy_io.hpp"
#include "hpcplan/plan/distance_field.hpp"

#ifndef HPCPLAN_MOVINGAI_DIR
#define HPCPLAN_MOVINGAI_DIR "/work/shared/benchmarks/movingai"
#endif

namespace hpcplan {
namespace {

std::string movingai_dir() {
  if (const char* dir = std::getenv("HPCPLAN_MOVINGAI_DIR"); dir && *dir) return dir;
  return HPCPLAN_MOVINGAI_DIR;
}

// The oracle's world: free flags in grid order (axis 0 fastest).
struct Plain {
  std::vector<int> shape;
  std::vector<char> free;
  std::size_t index(const std::vector<int>& c) const {
    std::size_t i = 0, stride = 1;
    for (std::size_t a = 0; a < shape.size(); ++a) {
      i += static_cast<std::size_t>(c[a]) * stride;
      stride *= static_cast<std::size_t>(shape[a]);
    }
    return i;
  }
  bool ok(const std::vector<int>& c) const {
    for (std::size_t a = 0; a < shape.size(); ++a)
      if (c[a] < 0 || c[a] >= shape[a]) return false;
    return free[index(c)] != 0;
  }
  std::vector<int> coords(std::size_t i) const {
    std::vector<int> c(shape.size());
    for (std::size_t a = 0; a < shape.size(); ++a) {
      c[a] = static_cast<int>(i % static_cast<std::size_t>(shape[a]));
      i /= static_cast<std::size_t>(shape[a]);
    }
    return c;
  }
};

Plain plain_of(const OccupancyGrid& g) {
  Plain p;
  p.shape = g.shape();
  p.free.resize(g.cells());
  // (The grid's bit index pads narrow rows: go by coordinates.)
  for (std::size_t i = 0; i < p.free.size(); ++i) p.free[i] = g.is_free(p.coords(i)) ? 1 : 0;
  return p;
}

// Moves: every offset in {-1,0,1}^d but 0 with at most `max_axes` non-zero axes (2: the seed
// rule; d: full connectivity).
std::vector<std::vector<int>> offsets(int dims, int max_axes) {
  std::vector<std::vector<int>> out;
  int count = 1;
  for (int a = 0; a < dims; ++a) count *= 3;
  for (int code = 0; code < count; ++code) {
    std::vector<int> o(dims);
    int k = 0;
    for (int a = 0, q = code; a < dims; ++a, q /= 3) {
      o[a] = q % 3 - 1;
      k += o[a] != 0;
    }
    if (k > 0 && k <= max_axes) out.push_back(o);
  }
  return out;
}

// Plain Dijkstra (costs sqrt(k)) or BFS (hops) from start: -1 where not reached. A move is legal
// when every cell of the unit cube it spans is free (no corner cutting).
std::vector<double> oracle(const Plain& p, const std::vector<int>& start, int max_axes, bool hops) {
  const int dims = static_cast<int>(p.shape.size());
  std::vector<std::int64_t> stride(dims);
  for (int a = 0, s = 1; a < dims; s *= p.shape[a], ++a) stride[a] = s;
  struct Move {
    std::vector<int> o;
    std::vector<std::int64_t> corners;  // index offsets of the spanned cube's cells
    std::int64_t delta = 0;
    double cost = 1.0;
  };
  std::vector<Move> moves;
  for (const auto& o : offsets(dims, max_axes)) {
    Move m;
    m.o = o;
    std::vector<int> axes;
    for (int a = 0; a < dims; ++a)
      if (o[a]) axes.push_back(a);
    for (unsigned s = 0; s < (1u << axes.size()); ++s) {
      std::int64_t d = 0;
      for (std::size_t j = 0; j < axes.size(); ++j)
        if (s & (1u << j)) d += o[axes[j]] * stride[axes[j]];
      m.corners.push_back(d);
    }
    for (int a = 0; a < dims; ++a) m.delta += o[a] * stride[a];
    m.cost = hops ? 1.0 : std::sqrt(static_cast<double>(axes.size()));
    moves.push_back(std::move(m));
  }
  std::vector<double> dist(p.free.size(), -1.0), best(p.free.size(), INFINITY);
  using Item = std::pair<double, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  best[p.index(start)] = 0.0;
  open.push({0.0, p.index(start)});
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (dist[i] >= 0) continue;
    dist[i] = d;
    const std::vector<int> c = p.coords(i);
    for (const Move& m : moves) {
      bool inside = true;
      for (int a = 0; a < dims && inside; ++a) {
        const int n = c[a] + m.o[a];
        inside = n >= 0 && n < p.shape[a];
      }
      if (!inside) continue;
      bool ok = true;
      for (std::int64_t k : m.corners) ok = ok && p.free[static_cast<std::int64_t>(i) + k];
      if (!ok) continue;
      const auto j = static_cast<std::size_t>(static_cast<std::int64_t>(i) + m.delta);
      const double nd = d + m.cost;
      if (dist[j] < 0 && nd < best[j]) {
        best[j] = nd;
        open.push({nd, j});
      }
    }
  }
  return dist;
}

struct Layout {
  int threads = 1;
  int slab_layers = 0;
  bool contiguous = false;
};

DistanceFieldRun run_field(std::shared_ptr<const OccupancyGrid> grid, Connectivity c,
                           const std::vector<int>& start, bool hops, const Layout& s,
                           std::optional<std::vector<int>> goal = std::nullopt) {
  GridProblem problem = occupancy_problem(std::move(grid), c);
  problem.start = start;
  problem.goal = std::move(goal);
  GridSearchOptions o;
  o.algorithm = hops ? GridAlgorithm::bfs : GridAlgorithm::dijkstra;
  o.engine = GridEngine::dense;
  o.threads = s.threads;
  o.slab_layers = s.slab_layers;
  o.contiguous_slabs = s.contiguous;
  o.memory_budget = std::uint64_t{1} << 30;
  return distance_field(problem, o);
}

// The field equals the oracle cell by cell.
void expect_field(const OccupancyGrid& grid, Connectivity c, const std::vector<int>& start,
                  bool hops, const Layout& s) {
  auto shared = std::make_shared<OccupancyGrid>(grid);
  const DistanceFieldRun run = run_field(shared, c, start, hops, s);
  const Plain p = plain_of(grid);
  const int max_axes = c == Connectivity::full ? grid.dims() : 2;
  const std::vector<double> want = oracle(p, start, max_axes, hops);
  const DistanceField& f = run.field;
  ASSERT_TRUE(f.complete);
  ASSERT_EQ(f.hops, hops);
  ASSERT_EQ(f.shape, grid.shape());
  ASSERT_EQ(f.cells(), want.size());
  std::uint64_t reached = 0, mismatches = 0;
  for (std::size_t i = 0; i < want.size(); ++i) {
    const double got = hops ? f.levels[i] : f.costs[i];
    reached += want[i] >= 0;
    const bool same =
        want[i] < 0 ? got == -1.0 : std::abs(got - want[i]) <= 1e-4 * std::max(1.0, want[i]);
    if (!same && ++mismatches <= 5)
      ADD_FAILURE() << "cell " << i << " (threads " << s.threads << ", slab layers "
                    << s.slab_layers << "): field " << got << ", oracle " << want[i];
  }
  EXPECT_EQ(mismatches, 0u);
  EXPECT_EQ(f.reached, reached);
  EXPECT_EQ(run.report.dense->reached, reached);
}

// Threads, layers per dealt block (0: the engine's choice), contiguous slabs.
const Layout kSetups[] = {{1, 0, false}, {2, 0, false}, {3, 0, false}, {3, 1, false}, {2, 0, true}};

OccupancyGrid random_grid(std::vector<int> shape, double blocked, std::uint64_t seed,
                          const std::vector<int>& keep) {
  OccupancyGrid g(shape);
  std::mt19937_64 rng(seed);
  std::bernoulli_distribution b(blocked);
  Plain p;
  p.shape = shape;
  for (std::uint64_t i = 0; i < g.cells(); ++i)
    if (b(rng)) g.set_free(p.coords(i), false);
  g.set_free(keep, true);
  g.seal();
  return g;
}

TEST(DistanceField, HandMadeGridWithAPocketAndCorners) {
  // 13 x 9 (not square: the lattice is 13 x 13 with the rows past 9 blocked), a wall with one
  // gap, a diagonal squeeze (no corner cutting) and a walled-in pocket.
  const char* rows[] = {
      ".............",  //
      ".....#.......",  //
      ".....#..###..",  //
      ".....#..#.#..",  //
      "..#..#..###..",  //
      "...#.#.......",  //
      ".....#...#...",  //
      "........#....",  //
      ".....#.......",  //
  };
  OccupancyGrid g({13, 9});
  for (int y = 0; y < 9; ++y)
    for (int x = 0; x < 13; ++x)
      if (rows[y][x] == '#') g.set_free(std::vector<int>{x, y}, false);
  g.seal();
  for (bool hops : {true, false})
    for (const Layout& s : kSetups) expect_field(g, Connectivity::seed_pairs, {0, 0}, hops, s);
  // The pocket's cell (9, 3) is unreachable: -1, as every blocked cell.
  auto shared = std::make_shared<OccupancyGrid>(g);
  const DistanceFieldRun run = run_field(shared, Connectivity::seed_pairs, {0, 0}, false, {});
  EXPECT_EQ(run.field.at(std::vector<int>{9, 3}), -1.0);
  EXPECT_EQ(run.field.at(std::vector<int>{5, 0}), 5.0);
  EXPECT_EQ(run.field.at(std::vector<int>{5, 1}), -1.0);
  EXPECT_EQ(run.field.at(std::vector<int>{0, 0}), 0.0);
  EXPECT_FALSE(run.goal_given);
}

TEST(DistanceField, RandomGrids2D) {
  for (std::uint64_t seed = 1; seed <= 2; ++seed) {
    const OccupancyGrid g = random_grid({70, 45}, 0.3, seed, {3, 4});
    for (bool hops : {true, false})
      for (const Layout& s : kSetups) expect_field(g, Connectivity::seed_pairs, {3, 4}, hops, s);
  }
}

TEST(DistanceField, RandomGrids3DFullAndSeedConnectivity) {
  const OccupancyGrid g = random_grid({19, 14, 11}, 0.25, 7, {2, 3, 1});
  for (Connectivity c : {Connectivity::full, Connectivity::seed_pairs})
    for (bool hops : {true, false})
      for (const Layout& s : kSetups) expect_field(g, c, {2, 3, 1}, hops, s);
}

TEST(DistanceField, OneDimension) {
  const OccupancyGrid g = random_grid({150}, 0.05, 3, {70});
  for (bool hops : {true, false})
    expect_field(g, Connectivity::seed_pairs, {70}, hops, {2, 0, false});
}

TEST(DistanceField, BostonMapEqualsTheOracle) {
  const std::string path = movingai_dir() + "/Boston_0_256.map";
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing (set HPCPLAN_MOVINGAI_DIR)";
  const OccupancyGrid g = env::load_occupancy(path);
  for (bool hops : {true, false})
    for (int threads : {1, 2, 3})
      expect_field(g, Connectivity::seed_pairs, {188, 1}, hops, {threads, 0, false});
}

TEST(DistanceField, GoalIsReportedAndTheSearchGoesPastIt) {
  const OccupancyGrid g = random_grid({60, 50}, 0.3, 11, {1, 1});
  auto shared = std::make_shared<OccupancyGrid>(g);
  const Plain p = plain_of(g);
  const std::vector<double> want = oracle(p, {1, 1}, 2, false);
  // The farthest reached cell as the goal, and a near one: the field is whole either way.
  std::size_t far = 0, near = 0;
  for (std::size_t i = 0; i < want.size(); ++i) {
    if (want[i] > want[far]) far = i;
    if (want[i] > 0 && want[i] < 3) near = i;
  }
  for (std::size_t goal : {far, near}) {
    for (int threads : {1, 3}) {
      const DistanceFieldRun run = run_field(shared, Connectivity::seed_pairs, {1, 1}, false,
                                             {threads, 0, false}, p.coords(goal));
      EXPECT_TRUE(run.goal_given);
      EXPECT_EQ(run.report.result.status, Status::solved);
      EXPECT_NEAR(run.report.result.cost, want[goal], 1e-9);
      EXPECT_NEAR(run.field.at(p.coords(goal)), want[goal], 1e-4);
      std::uint64_t reached = 0;
      for (double v : want) reached += v >= 0;
      EXPECT_EQ(run.field.reached, reached);
      // BFS: the goal's hops are its level in the field.
      const DistanceFieldRun bfs = run_field(shared, Connectivity::seed_pairs, {1, 1}, true,
                                             {threads, 0, false}, p.coords(goal));
      EXPECT_EQ(bfs.report.result.status, Status::solved);
      EXPECT_EQ(static_cast<double>(bfs.report.result.hops), bfs.field.at(p.coords(goal)));
      EXPECT_EQ(bfs.field.reached, reached);
    }
  }
  // An unreachable goal: no_path, the field still whole.
  OccupancyGrid walled = g;
  for (int y = 0; y < 50; ++y) walled.set_free(std::vector<int>{30, y}, false);
  walled.seal();
  auto w = std::make_shared<OccupancyGrid>(walled);
  const DistanceFieldRun run =
      run_field(w, Connectivity::seed_pairs, {1, 1}, true, {2, 0, false}, std::vector<int>{59, 0});
  EXPECT_EQ(run.report.result.status, Status::no_path);
  EXPECT_TRUE(run.field.complete);
  EXPECT_EQ(run.field.at(std::vector<int>{59, 0}), -1.0);
}

TEST(DistanceField, NpyBytes) {
  OccupancyGrid g({5, 3});
  g.set_free(std::vector<int>{4, 2}, false);
  g.seal();
  auto shared = std::make_shared<OccupancyGrid>(g);
  for (bool hops : {true, false}) {
    const DistanceFieldRun run = run_field(shared, Connectivity::seed_pairs, {0, 0}, hops, {});
    const std::string bytes = distance_field_npy(run.field);
    ASSERT_EQ(bytes.substr(0, 6), "\x93NUMPY");
    const std::size_t header =
        10 + (static_cast<unsigned char>(bytes[8]) | static_cast<unsigned char>(bytes[9]) << 8);
    EXPECT_EQ(header % 64, 0u);
    const std::string dict = bytes.substr(10, header - 10);
    EXPECT_NE(dict.find(hops ? "'<i4'" : "'<f4'"), std::string::npos) << dict;
    EXPECT_NE(dict.find("'shape': (3, 5)"), std::string::npos) << dict;
    ASSERT_EQ(bytes.size(), header + 15 * 4);
    // Cell (x=3, y=1) is row 1, column 3 of the (3, 5) array: hops 3, cost 2 + sqrt2.
    const std::size_t i = 1 * 5 + 3;
    if (hops) {
      std::int32_t v;
      std::memcpy(&v, bytes.data() + header + i * 4, 4);
      EXPECT_EQ(v, 3);
      std::memcpy(&v, bytes.data() + header + 14 * 4, 4);
      EXPECT_EQ(v, -1);  // (4, 2) blocked
    } else {
      float v;
      std::memcpy(&v, bytes.data() + header + i * 4, 4);
      EXPECT_NEAR(v, 2 + std::sqrt(2.0), 1e-5);
    }
  }
}

TEST(DistanceField, ThreadsFollowTheLevelsWidthUnlessGiven) {
  // A 2D map's levels are a few hundred states: one thread (more only wait at the barriers).
  const OccupancyGrid map = env::load_occupancy(movingai_dir() + "/Boston_0_256.map");
  GridSearchOptions o;
  EXPECT_EQ(distance_field_threads(map, o, 1), 1);
  o.threads = 3;
  EXPECT_EQ(distance_field_threads(map, o, 1), 3);  // --threads is obeyed
  // A wide lattice: one per 32768 states of the average level, at most the process's cores.
  OccupancyGrid wide({256, 256, 256});
  wide.seal();
  o.threads = 0;
  const int cores = dense_threads(o, 1);
  EXPECT_EQ(distance_field_threads(wide, o, 1), std::min(cores, 65536 / 32768));
}

TEST(DistanceField, RefusesWhatCannotMakeAField) {
  GridProblem problem = occupancy_problem(std::make_shared<OccupancyGrid>(std::vector<int>{8, 8}));
  GridSearchOptions o;
  o.algorithm = GridAlgorithm::astar;
  EXPECT_THROW(validate_distance_field(problem, o), InputError);
  o.algorithm = GridAlgorithm::bfs;
  o.engine = GridEngine::sparse;
  EXPECT_THROW(validate_distance_field(problem, o), InputError);
  o.engine = GridEngine::automatic;
  o.checkpoint = "x.ckpt";
  EXPECT_THROW(validate_distance_field(problem, o), InputError);
  o.checkpoint.clear();
  EXPECT_NO_THROW(validate_distance_field(problem, o));
}

}  // namespace
}  // namespace hpcplan
