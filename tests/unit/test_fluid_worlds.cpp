// The fluid's worlds (occupancy grid, particle balls) against brute force, the occupancy graph's
// searches against Dijkstra, and D* Lite's repairs against a fresh search.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <queue>
#include <random>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/occupancy_world.hpp"
#include "hpcplan/env/particle_world.hpp"
#include "hpcplan/graph/occupancy_graph.hpp"
#include "hpcplan/plan/fluid_planner.hpp"
#include "hpcplan/search/best_first.hpp"
#include "hpcplan/search/d_star_lite.hpp"

namespace {

using namespace hpcplan;
using env::Vec;

env::FluidSnapshot random_snapshot(std::uint64_t seed, double side, int particles, int boxes) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, side);
  env::FluidSnapshot s;
  s.domain = {{0, 0, 0}, {side, side, side}};
  for (int i = 0; i < particles; ++i) s.particles.push_back({u(rng), u(rng), u(rng)});
  // Particles exactly on cell faces, edges and box corners (the grid's cell is side / n).
  const int n = static_cast<int>(std::lround(side / 0.2));
  const double c = side / n;
  s.particles.push_back({c, c, c});
  s.particles.push_back({0, 0, 0});
  s.particles.push_back({side, side, side});
  s.particles.push_back({2 * c, 0.5 * c, side});
  for (int b = 0; b < boxes; ++b) {
    const Vec<3> lo{u(rng), u(rng), u(rng)};
    Vec<3> hi;
    for (int k = 0; k < 3; ++k) hi[k] = std::min(side, lo[k] + 0.1 + 0.2 * u(rng) / side);
    s.boxes.push_back({lo, hi});
  }
  s.boxes.push_back({{3 * c, 3 * c, 3 * c}, {4 * c, 4 * c, 4 * c}});  // on cell faces
  return s;
}

// Whether cell (x, y, z) of side h overlaps an obstacle box grown by the inflation, with positive
// volume (the seed's rule for boxes, under either particle rule).
bool in_grown_box(const env::FluidSnapshot& snap, const env::OccupancyConfig& cfg,
                  const std::array<int, 3>& cell, double h) {
  for (const auto& b : snap.boxes) {
    bool overlap = true;
    for (int k = 0; k < 3; ++k)
      overlap = overlap && b.lo[k] - cfg.box_inflation < (cell[k] + 1) * h &&
                b.hi[k] + cfg.box_inflation > cell[k] * h;
    if (overlap) return true;
  }
  return false;
}

TEST(OccupancyWorld, CoversTheBoxExactlyAndMatchesBruteForce) {
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    const double side = 1.0 + 0.37 * static_cast<double>(seed);  // not a multiple of 0.2
    const env::FluidSnapshot snap = random_snapshot(seed, side, 150, 3);
    const env::OccupancyConfig cfg;
    const env::OccupancyWorld w(snap, cfg);
    const auto n = w.cells_per_axis();
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(n[k], std::lround(side / 0.2));
      EXPECT_NEAR(n[k] * w.cell_size()[k], side, 1e-12);
    }
    std::uint64_t occupied = 0;
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x) {
          const double h = w.cell_size()[0];
          const Vec<3> c{(x + 0.5) * h, (y + 0.5) * h, (z + 0.5) * h};
          bool expect = false;
          for (const auto& p : snap.particles) {
            double d2 = 0;
            for (int k = 0; k < 3; ++k) d2 += (p[k] - c[k]) * (p[k] - c[k]);
            expect = expect || d2 <= cfg.particle_radius * cfg.particle_radius;
          }
          expect = expect || in_grown_box(snap, cfg, {x, y, z}, h);
          ASSERT_EQ(w.occupied({x, y, z}), expect) << "cell " << x << "," << y << "," << z;
          occupied += expect;
        }
    EXPECT_EQ(w.occupied_count(), occupied);
    EXPECT_GT(occupied, 0u);
    EXPECT_LT(occupied, w.cell_count());
  }
}

// Adaptive occupancy: the density at every cell centre summed by hand from the poly6 formula
// (not the fluid's kernel object), normalized so a particle on the centre weighs 1.
TEST(OccupancyWorld, DensityRuleMatchesBruteForce) {
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const double side = 1.3 + 0.29 * static_cast<double>(seed);
    const env::FluidSnapshot snap = random_snapshot(seed, side, 400, 2);
    env::OccupancyConfig cfg;
    cfg.rule = env::OccupancyRule::density;
    cfg.density_support = 0.25 + 0.05 * static_cast<double>(seed);
    cfg.density_threshold = 0.3 * static_cast<double>(seed);
    const env::OccupancyWorld w(snap, cfg);
    const auto n = w.cells_per_axis();
    const double h = w.cell_size()[0], s2 = cfg.density_support * cfg.density_support;
    std::uint64_t by_density = 0;
    for (int z = 0; z < n[2]; ++z)
      for (int y = 0; y < n[1]; ++y)
        for (int x = 0; x < n[0]; ++x) {
          const Vec<3> c{(x + 0.5) * h, (y + 0.5) * h, (z + 0.5) * h};
          double rho = 0;
          for (const auto& p : snap.particles) {
            double d2 = 0;
            for (int k = 0; k < 3; ++k) d2 += (p[k] - c[k]) * (p[k] - c[k]);
            if (d2 < s2) rho += std::pow(1.0 - d2 / s2, 3);
          }
          const std::uint32_t i = w.index({x, y, z});
          ASSERT_NEAR(w.density()[i], rho, 1e-5 * (1 + rho));
          const bool in_box = in_grown_box(snap, cfg, {x, y, z}, h);
          // (Far from the threshold, so float rounding cannot flip a cell.)
          if (std::abs(rho - cfg.density_threshold) > 1e-4) {
            ASSERT_EQ(w.occupied(i), in_box || rho >= cfg.density_threshold)
                << "cell " << x << "," << y << "," << z << " rho " << rho;
          }
          by_density += !in_box && rho >= cfg.density_threshold;
        }
    EXPECT_GT(by_density, 0u);
  }
}

// The defaults reproduce the seed's rule for lone particles (blocked out to 0.14), block the gaps
// inside a crowd that the seed's rule leaves open, and a threshold above 1 lets lone particles
// through.
TEST(OccupancyWorld, DensityRuleAgainstTheSeedsRule) {
  env::FluidSnapshot lone;
  lone.domain = {{0, 0, 0}, {2, 2, 2}};
  for (double x : {0.33, 0.97, 1.51}) lone.particles.push_back({x, 0.41 + 0.3 * x, 1.77 - 0.5 * x});
  // Two more whose nearest cell centre (cells of 0.2, centres at 0.1 + 0.2 k) lies 0.139 and
  // 0.141 away: blocked and free under both rules (a threshold off by 0.01 either way, or a
  // support off by 1%, flips one of them).
  lone.particles.push_back({0.3 + 0.139, 1.7, 0.1});
  lone.particles.push_back({1.5 + 0.141, 1.7, 1.7});
  env::OccupancyConfig seed_rule, density_rule;
  density_rule.rule = env::OccupancyRule::density;
  const env::OccupancyWorld a(lone, seed_rule), b(lone, density_rule);
  ASSERT_GT(a.occupied_count(), 0u);
  for (std::uint32_t i = 0; i < a.cell_count(); ++i) EXPECT_EQ(a.occupied(i), b.occupied(i)) << i;
  EXPECT_TRUE(b.occupied({1, 8, 0}));   // centre (0.3, 1.7, 0.1), 0.139 away
  EXPECT_FALSE(b.occupied({7, 8, 8}));  // centre (1.5, 1.7, 1.7), 0.141 away

  // A crowd: particles 0.24 apart; a lattice cube's middle lies 0.21 from its 8 corners, beyond
  // the seed's 0.14, yet their kernels sum there to 8 (1 - 0.21^2 / 0.28^2)^3 = 0.72.
  env::FluidSnapshot crowd;
  crowd.domain = {{0, 0, 0}, {2, 2, 2}};
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k)
        crowd.particles.push_back({0.63 + 0.24 * i, 0.63 + 0.24 * j, 0.63 + 0.24 * k});
  const env::OccupancyWorld c(crowd, seed_rule), d(crowd, density_rule);
  EXPECT_GT(d.occupied_count(), c.occupied_count());
  for (std::uint32_t i = 0; i < c.cell_count(); ++i)
    if (c.occupied(i)) {
      EXPECT_TRUE(d.occupied(i)) << i;  // sums only add
    }

  env::OccupancyConfig sparse = density_rule;
  sparse.density_threshold = 1.01;
  EXPECT_EQ(env::OccupancyWorld(lone, sparse).occupied_count(), 0u);
  EXPECT_GT(env::OccupancyWorld(crowd, sparse).occupied_count(), 0u);

  env::OccupancyConfig bad = density_rule;
  bad.density_threshold = 0;
  EXPECT_THROW(env::OccupancyWorld(lone, bad), InputError);
  bad = density_rule;
  bad.density_support = -1;
  EXPECT_THROW(env::OccupancyWorld(lone, bad), InputError);
  EXPECT_EQ(env::parse_occupancy_rule("density"), env::OccupancyRule::density);
  EXPECT_THROW(env::parse_occupancy_rule("densty"), InputError);
}

TEST(OccupancyWorld, SegmentsFreeOnlyThroughFreeCells) {
  const env::FluidSnapshot snap = random_snapshot(7, 2.0, 60, 1);
  const env::OccupancyWorld w(snap);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  int free = 0, blocked = 0;
  for (int t = 0; t < 3000; ++t) {
    const Vec<3> a{u(rng), u(rng), u(rng)};
    Vec<3> b;
    for (int k = 0; k < 3; ++k) b[k] = std::clamp(a[k] + (u(rng) - 1.0) * 0.5, 0.0, 2.0);
    const bool f = w.segment_free(a, b);
    bool samples_free = true;
    for (int i = 0; i <= 400; ++i)
      samples_free = samples_free && w.point_free(env::lerp<3>(a, b, i / 400.0));
    // (Blocked with every sample free happens: touching an occupied cell's face, edge or corner
    // counts as blocked.)
    if (f) {
      EXPECT_TRUE(samples_free);
    }
    f ? ++free : ++blocked;
  }
  EXPECT_GT(free, 100);
  EXPECT_GT(blocked, 100);
  EXPECT_FALSE(w.segment_free({-0.1, 1, 1}, {1, 1, 1}));
}

// Segments are checked against every ball and box by fine sampling (tolerance 1e-3 for the
// sampling). Short ones (RRT*'s steps) take the world's bounding-box path; long ones (the
// smoother's, across the box) take its voxel-walk path, in a dense and in a sparse field.
bool brute_force_free(const env::FluidSnapshot& snap, double r, const Vec<3>& a, const Vec<3>& b,
                      bool* certain) {
  const int samples = std::max(2000, static_cast<int>(env::distance<3>(a, b) / 5e-4));
  double nearest = 1e300;
  bool in_box = false;
  for (int i = 0; i <= samples; ++i) {
    const Vec<3> p = env::lerp<3>(a, b, static_cast<double>(i) / samples);
    for (const auto& c : snap.particles) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += (p[k] - c[k]) * (p[k] - c[k]);
      nearest = std::min(nearest, d2);
    }
    for (const auto& box : snap.boxes) in_box = in_box || box.contains(p);
  }
  const double d = std::sqrt(nearest);
  *certain = in_box || std::abs(d - r) > 1e-3;
  return !in_box && d > r;
}

TEST(ParticleWorld, PointAndSegmentTestsMatchBruteForce) {
  const env::FluidSnapshot snap = random_snapshot(11, 3.0, 400, 2);
  const env::ParticleWorld w(snap);
  const double r = w.radius();
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 3.0);
  int free = 0;
  for (int t = 0; t < 400; ++t) {
    const Vec<3> a{u(rng), u(rng), u(rng)};
    Vec<3> b;
    for (int k = 0; k < 3; ++k) b[k] = std::clamp(a[k] + (u(rng) - 1.5) * 0.3, 0.0, 3.0);
    bool certain = false;
    const bool expect = brute_force_free(snap, r, a, b, &certain);
    const bool f = w.segment_free(a, b);
    if (certain) {
      EXPECT_EQ(f, expect) << t;
    }
    free += f;
    // Points: exact.
    bool point_blocked = false;
    for (const auto& p : snap.particles) {
      double d2 = 0;
      for (int k = 0; k < 3; ++k) d2 += (p[k] - a[k]) * (p[k] - a[k]);
      point_blocked = point_blocked || d2 <= r * r;
    }
    for (const auto& box : snap.boxes) point_blocked = point_blocked || box.contains(a);
    EXPECT_EQ(w.point_free(a), !point_blocked);
    EXPECT_EQ(w.why_not_free(a).empty(), !point_blocked);
  }
  EXPECT_GT(free, 50);
  EXPECT_LT(free, 390);

  // Long segments, corner to corner of random points, in the dense field and a sparse one.
  for (const int particles : {400, 100, 25}) {
    const env::FluidSnapshot field = random_snapshot(13, 3.0, particles, 1);
    const env::ParticleWorld world(field);
    int long_free = 0, long_blocked = 0;
    for (int t = 0; t < 100; ++t) {
      // From near one corner to near the opposite one: at least 1.8 along every axis, so the
      // grown bounding box spans over 512 cells and the world walks the segment's cells.
      Vec<3> a, b;
      for (int k = 0; k < 3; ++k) {
        a[k] = 0.2 * u(rng), b[k] = 3.0 - 0.2 * u(rng);
        if (u(rng) < 1.5) std::swap(a[k], b[k]);
      }
      bool certain = false;
      const bool expect = brute_force_free(field, r, a, b, &certain);
      const bool f = world.segment_free(a, b);
      if (certain) {
        EXPECT_EQ(f, expect) << particles << " particles, segment " << t;
      }
      f ? ++long_free : ++long_blocked;
    }
    EXPECT_GT(long_blocked, 0) << particles;  // blocked in both fields, free in the sparse one
    EXPECT_GT(particles == 25 ? long_free : long_blocked, 3) << particles;
  }
}

// Dijkstra over the occupancy grid with the graph's move rule, written independently.
double dijkstra(const env::OccupancyWorld& w, std::uint32_t s, std::uint32_t g) {
  std::vector<double> dist(w.cell_count(), INFINITY);
  using Item = std::pair<double, std::uint32_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> pq;
  dist[s] = 0;
  pq.push({0, s});
  while (!pq.empty()) {
    auto [d, u] = pq.top();
    pq.pop();
    if (d > dist[u]) continue;
    if (u == g) return d;
    const auto c = w.cell_of_index(u);
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          if (!dx && !dy && !dz) continue;
          bool ok = true;
          // every cell of the block between c and c + d
          for (int mz = 0; mz <= (dz != 0); ++mz)
            for (int my = 0; my <= (dy != 0); ++my)
              for (int mx = 0; mx <= (dx != 0); ++mx) {
                const env::OccupancyWorld::Cell q{c[0] + mx * dx, c[1] + my * dy, c[2] + mz * dz};
                ok = ok && w.inside(q) && !w.occupied(q);
              }
          if (!ok) continue;
          const std::uint32_t v = w.index({c[0] + dx, c[1] + dy, c[2] + dz});
          const double nd = d + std::sqrt(double(dx * dx + dy * dy + dz * dz));
          if (nd < dist[v]) dist[v] = nd, pq.push({nd, v});
        }
  }
  return INFINITY;
}

struct Octile {
  const env::OccupancyWorld* w;
  LatticeCost operator()(std::uint32_t a, std::uint32_t b) const {
    return full_connectivity_free_distance(occupancy_delta(*w, a, b));
  }
};

std::uint32_t random_free(const env::OccupancyWorld& w, std::mt19937_64& rng) {
  std::uniform_int_distribution<std::uint32_t> pick(0,
                                                    static_cast<std::uint32_t>(w.cell_count() - 1));
  for (;;) {
    const std::uint32_t c = pick(rng);
    if (!w.occupied(c)) return c;
  }
}

TEST(OccupancyGraph, AStarBothHeuristicsEqualDijkstraAndDStarLiteRepairsToTheOptimum) {
  std::mt19937_64 rng(17);
  int solved = 0, unreachable = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    env::FluidSnapshot snap = random_snapshot(seed, 3.0, 900, 2);
    env::OccupancyWorld w(snap);
    OccupancyGraph graph(w);
    const std::uint32_t s = random_free(w, rng), g = random_free(w, rng);
    const double truth = dijkstra(w, s, g);
    search::Options so;
    so.dense_keys = graph.state_count();
    const auto octile = search::best_first_search(graph, s, g, OccupancyOctile{w, g}, so);
    const auto euclid = search::best_first_search(graph, s, g, OccupancyEuclidean{w, g}, so);
    search::DStarLite<OccupancyGraph, Octile> dstar(Octile{&w});
    dstar.reset(graph, s, g);
    const Status ds = dstar.compute(graph, Stop());
    if (std::isinf(truth)) {
      ++unreachable;
      EXPECT_EQ(octile.status, Status::no_path);
      EXPECT_EQ(euclid.status, Status::no_path);
      EXPECT_EQ(ds, Status::no_path);
      continue;
    }
    ++solved;
    ASSERT_EQ(octile.status, Status::solved);
    EXPECT_NEAR(octile.cost, truth, 1e-9);
    EXPECT_NEAR(euclid.cost, truth, 1e-9);
    EXPECT_LE(octile.counters.expanded, euclid.counters.expanded);
    ASSERT_EQ(ds, Status::solved);
    EXPECT_NEAR(dstar.distance_to_goal(s), truth, 1e-9);
    const auto p = dstar.path(graph);
    ASSERT_FALSE(p.empty());
    EXPECT_NEAR(search::validated_length(graph, p), truth, 1e-9);

    // The fluid moves: particles shift a little, the start moves along the path. The repaired
    // search must equal a fresh Dijkstra on the new grid.
    std::uint32_t start = s;
    for (int step = 0; step < 12; ++step) {
      std::normal_distribution<double> jiggle(0.0, step % 2 ? 0.05 : 0.2);
      for (auto& q : snap.particles)
        for (int k = 0; k < 3; ++k) q[k] = std::clamp(q[k] + jiggle(rng), 0.0, 3.0);
      env::OccupancyWorld next(snap);
      OccupancyGraph next_graph(next);
      const auto path_now = dstar.path(graph);
      if (path_now.size() > 2) start = path_now[1];
      if (next.occupied(start) || next.occupied(g)) break;
      std::vector<std::uint32_t> touched;
      for (std::uint32_t i = 0; i < next.cell_count(); ++i)
        if (next.occupied(i) != w.occupied(i)) {
          const auto c = next.cell_of_index(i);
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx)
                if (next.inside({c[0] + dx, c[1] + dy, c[2] + dz}))
                  touched.push_back(next.index({c[0] + dx, c[1] + dy, c[2] + dz}));
        }
      w = next;  // the heuristic reads cell coordinates only; the graph is rebuilt on `w`
      dstar.move_start(start);
      dstar.edges_changed(graph, touched);
      const Status r = dstar.compute(graph, Stop());
      const double fresh = dijkstra(w, start, g);
      if (std::isinf(fresh)) {
        EXPECT_EQ(r, Status::no_path);
      } else {
        ASSERT_EQ(r, Status::solved);
        EXPECT_NEAR(dstar.distance_to_goal(start), fresh, 1e-9)
            << "seed " << seed << " step " << step;
        const auto rp = dstar.path(graph);
        ASSERT_FALSE(rp.empty());
        EXPECT_NEAR(search::validated_length(graph, rp), fresh, 1e-9);
      }
      (void)next_graph;
    }
  }
  EXPECT_GT(solved, 6);
  (void)unreachable;
}

TEST(FluidPlanner, EscapesABlockedStartAndFailsOnASealedGoal) {
  env::FluidSnapshot snap;
  snap.domain = {{0, 0, 0}, {4, 4, 4}};
  snap.particles.push_back({0.52, 0.5, 0.5});  // right next to the robot
  for (const std::string algo : {"astar", "astar_euclid", "dstar_lite", "rrtstar"}) {
    plan::FluidPlanOptions o;
    o.algo = algo;
    plan::FluidReplanner planner(o);
    const auto p = planner.plan(snap, {0.5, 0.5, 0.5}, {3.5, 3.5, 3.5}, 0);
    ASSERT_EQ(p.status, Status::solved) << algo;
    EXPECT_TRUE(p.start_escaped) << algo;
    EXPECT_FALSE(p.goal_escaped) << algo;
    EXPECT_EQ(p.path.front(), (Vec<3>{0.5, 0.5, 0.5}));
    EXPECT_EQ(p.path.back(), (Vec<3>{3.5, 3.5, 3.5}));
    EXPECT_GE(p.cost, std::sqrt(27.0) - 1e-9);
    EXPECT_LE(p.cost, p.raw_length + 1e-9);
  }
  // The goal's cell is blocked and its escape is the robot's own cell: the plan is the robot's
  // position and the exempt leg to the goal (a once-found bug appended the blocked goal as an
  // ordinary, checked segment).
  env::FluidSnapshot near;
  near.domain = {{0, 0, 0}, {4, 4, 4}};
  near.particles.push_back({1.31, 1.1, 1.1});  // within 0.14 of cell (6,5,5)'s centre only
  for (const std::string algo : {"astar", "dstar_lite"}) {
    plan::FluidPlanOptions o;
    o.algo = algo;
    plan::FluidReplanner planner(o);
    const auto p = planner.plan(near, {1.1, 1.1, 1.1}, {1.3, 1.1, 1.1}, 0);
    ASSERT_EQ(p.status, Status::solved) << algo;
    EXPECT_TRUE(p.goal_escaped) << algo;
    EXPECT_FALSE(p.start_escaped) << algo;
    ASSERT_EQ(p.path.size(), 2u) << algo;
    EXPECT_EQ(p.path.back(), (Vec<3>{1.3, 1.1, 1.1})) << algo;
  }
  // The goal inside a closed shell of boxes: every planner fails, none hangs.
  env::FluidSnapshot sealed;
  sealed.domain = {{0, 0, 0}, {4, 4, 4}};
  const double lo = 2.4, hi = 3.6, t = 0.05;
  sealed.boxes = {{{lo, lo, lo}, {hi, hi, lo + t}}, {{lo, lo, hi - t}, {hi, hi, hi}},
                  {{lo, lo, lo}, {hi, lo + t, hi}}, {{lo, hi - t, lo}, {hi, hi, hi}},
                  {{lo, lo, lo}, {lo + t, hi, hi}}, {{hi - t, lo, lo}, {hi, hi, hi}}};
  for (const std::string algo : {"astar", "dstar_lite", "rrtstar"}) {
    plan::FluidPlanOptions o;
    o.algo = algo;
    plan::FluidReplanner planner(o);
    const auto p = planner.plan(sealed, {0.5, 0.5, 0.5}, {3.0, 3.0, 3.0}, 0);
    EXPECT_NE(p.status, Status::solved) << algo;
    EXPECT_FALSE(p.reason().empty()) << algo;
    EXPECT_TRUE(p.path.empty());
  }
}

}  // namespace
