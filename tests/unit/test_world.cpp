// Continuous worlds: the exact segment tests against independent oracles, the file formats,
// and the broad phase against brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "hpcplan/core/error.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/env/segment_box.hpp"
#include "hpcplan/env/sphere_world.hpp"

namespace hpcplan::env {
namespace {

using V3 = Vec<3>;

// Oracle 1: distance from the segment to the box, minimised over t by ternary search (the
// distance from a moving point to a convex set is convex in t). No slabs involved.
double segment_box_distance(const V3& a, const V3& b, const Aabb<3>& box) {
  auto dist = [&](double t) {
    double s = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double x = a[k] + t * (b[k] - a[k]);
      const double d = std::max({box.lo[k] - x, 0.0, x - box.hi[k]});
      s += d * d;
    }
    return std::sqrt(s);
  };
  double lo = 0.0, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    (dist(m1) < dist(m2) ? hi : lo) = dist(m1) < dist(m2) ? m2 : m1;
  }
  return std::min({dist(lo), dist(0.0), dist(1.0)});
}

// Oracle 2: dense sampling; finds a point inside when the overlap is not tiny.
bool sampled_hit(const V3& a, const V3& b, const Aabb<3>& box, int samples = 4000) {
  for (int i = 0; i <= samples; ++i)
    if (box.contains(lerp<3>(a, b, static_cast<double>(i) / samples))) return true;
  return false;
}

TEST(SegmentBox, HandPickedCasesIncludingTouchingAndZeroDirections) {
  const Aabb<3> box{{1, 1, 1}, {2, 2, 2}};
  EXPECT_TRUE(segment_hits_box<3>({0, 1.5, 1.5}, {3, 1.5, 1.5}, box));   // through, dy=dz=0
  EXPECT_FALSE(segment_hits_box<3>({0, 2.5, 1.5}, {3, 2.5, 1.5}, box));  // parallel, outside
  EXPECT_TRUE(segment_hits_box<3>({0, 2, 1.5}, {3, 2, 1.5}, box));       // slides along a face
  EXPECT_TRUE(segment_hits_box<3>({0, 2, 2}, {3, 2, 2}, box));           // along an edge
  EXPECT_TRUE(segment_hits_box<3>({0, 0, 0}, {1, 1, 1}, box));           // ends on a corner
  EXPECT_FALSE(segment_hits_box<3>({0, 0, 0}, {0.999, 0.999, 0.999}, box));
  EXPECT_TRUE(segment_hits_box<3>({0, 3, 1.5}, {3, 0, 1.5}, box));  // diagonal in a plane
  EXPECT_TRUE(segment_hits_box<3>({0, 3, 0}, {3, 0, 3}, box));      // through the centre
  EXPECT_TRUE(
      segment_hits_box<3>({0.5, 3, 1.5}, {2.5, 1, 1.5}, box));  // meets the face y = 2 at (1.5, 2)
  EXPECT_TRUE(segment_hits_box<3>({1.5, 1.5, 1.5}, {1.5, 1.5, 1.5}, box));  // a point inside
  EXPECT_FALSE(segment_hits_box<3>({0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, box));
  EXPECT_FALSE(segment_hits_box<3>({3, 3, 3}, {4, 4, 4}, box));  // beyond the far end
  EXPECT_FALSE(segment_hits_box<3>({2.5, 0, 1.5}, {3.5, 1, 1.5}, box));
  EXPECT_TRUE(segment_hits_box<3>({2, 0, 1.5}, {2, 3, 1.5}, box));  // on the face plane x=2
}

TEST(SegmentBox, AgreesWithDistanceAndSamplingOracles) {
  std::mt19937_64 rng(11);
  // Coordinates on a coarse lattice make faces, edges and corners touch often.
  std::uniform_int_distribution<int> coarse(0, 8);
  std::uniform_real_distribution<double> fine(0.0, 4.0);
  int hits = 0, touches = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    auto value = [&] { return trial % 2 ? coarse(rng) * 0.5 : fine(rng); };
    Aabb<3> box;
    for (int k = 0; k < 3; ++k) {
      double u = value(), v = value();
      box.lo[k] = std::min(u, v);
      box.hi[k] = std::max(u, v);
    }
    V3 a, b;
    for (int k = 0; k < 3; ++k) a[k] = value(), b[k] = value();
    if (trial % 7 == 0) b[trial % 3] = a[trial % 3];  // a zero direction component
    const bool slab = segment_hits_box<3>(a, b, box);
    const double d = segment_box_distance(a, b, box);
    if (d > 1e-7) {
      EXPECT_FALSE(slab) << "trial " << trial << " distance " << d;
    }
    if (d == 0.0) {
      EXPECT_TRUE(slab) << "trial " << trial;
    }
    if (sampled_hit(a, b, box)) {
      EXPECT_TRUE(slab) << "trial " << trial;
    }
    hits += slab;
    touches += slab && !sampled_hit(a, b, box, 200);
  }
  EXPECT_GT(hits, 2000);
  EXPECT_GT(touches, 50);  // the grazing cases were really exercised
}

TEST(BoxWorld, BroadPhaseAgreesWithBruteForce) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 20.0), size(0.1, 3.0);
  std::vector<Block> blocks;
  for (int i = 0; i < 120; ++i) {
    Block b;
    for (int k = 0; k < 3; ++k) b.box.lo[k] = u(rng), b.box.hi[k] = b.box.lo[k] + size(rng);
    blocks.push_back(b);
  }
  const BoxWorld world({{0, 0, 0}, {20, 20, 20}}, blocks);
  std::uniform_real_distribution<double> p(-0.5, 20.5), step(-2.0, 2.0);
  for (int trial = 0; trial < 20000; ++trial) {
    V3 a{p(rng), p(rng), p(rng)}, b = a;
    if (trial % 2)
      for (int k = 0; k < 3; ++k) b[k] += step(rng);  // short segments: the bucket path
    else
      b = {p(rng), p(rng), p(rng)};  // long ones: the linear scan
    auto padded = [](Aabb<3> box) {
      for (int k = 0; k < 3; ++k)
        box.lo[k] -= 20 * kContactMargin, box.hi[k] += 20 * kContactMargin;
      return box;
    };
    bool expected = world.bounds().contains(a) && world.bounds().contains(b);
    for (const Block& blk : blocks)
      expected = expected && !segment_hits_box<3>(a, b, padded(blk.box));
    ASSERT_EQ(world.segment_free(a, b), expected) << "trial " << trial;
    bool point = world.bounds().contains(a);
    for (const Block& blk : blocks) point = point && !padded(blk.box).contains(a);
    ASSERT_EQ(world.point_free(a), point);
  }
}

TEST(BoxWorld, ClosedObstaclesAndBoundary) {
  const BoxWorld world({{0, 0, 0}, {10, 10, 10}}, {Block{{{4, 4, 4}, {6, 6, 6}}}});
  EXPECT_TRUE(world.point_free({0, 0, 0}));   // the boundary itself is free
  EXPECT_FALSE(world.point_free({4, 5, 5}));  // an obstacle's face is not
  EXPECT_FALSE(world.point_free({10.0000001, 5, 5}));
  EXPECT_FALSE(world.point_free({3.99999999995, 5, 5}));  // within the contact margin
  EXPECT_TRUE(world.point_free({3.9999999, 5, 5}));
  EXPECT_EQ(world.why_not_free({5, 5, 5}), "inside a block");
  EXPECT_EQ(world.why_not_free({-1, 5, 5}), "outside the boundary");
  EXPECT_NEAR(world.free_volume(), 1000 - 8, 3.0);  // a stratified estimate
}

TEST(BoxMapFormat, AcceptsCommentsBlankLinesTabsAndCrlf) {
  const BoxMap m = parse_box_map(
      "# a map\r\n\r\nboundary 0 0 0 10 10 10 120 120 120\r\n\tblock 1 1 1 2 2 2 255 0 0 # red\r\n"
      "block 3 3 3 4 4 4\nstart 0.5 0.5 0.5\ngoal 9 9 9\n",
      "m.txt");
  EXPECT_EQ(m.world.blocks().size(), 2u);
  EXPECT_EQ(m.world.blocks()[0].line, 4);
  EXPECT_DOUBLE_EQ(m.world.blocks()[0].rgb[0], 1.0);
  ASSERT_TRUE(m.start && m.goal);
  EXPECT_EQ((*m.goal)[2], 9.0);
}

TEST(BoxMapFormat, MalformedLinesNameFileAndLine) {
  auto error = [](const std::string& text) {
    try {
      parse_box_map(text, "bad.txt");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string b = "boundary 0 0 0 1 1 1\n";
  EXPECT_NE(error(b + "block 0 0 0 1 1\n").find("bad.txt:2:"), std::string::npos);
  EXPECT_NE(error(b + "block 0 0 0 1 1 x\n").find("'x' is not a finite number"), std::string::npos);
  EXPECT_NE(error(b + "block 0 0 0 1 1 nan\n").find("bad.txt:2:"), std::string::npos);
  EXPECT_NE(error(b + "block 0 0 0 1 1 1e999\n").find("not a finite"), std::string::npos);
  EXPECT_NE(error(b + "wall 0 0 0 1 1 1\n").find("unknown directive 'wall'"), std::string::npos);
  EXPECT_NE(error(b + "block 2 0 0 1 1 1\n").find("min > max on axis x"), std::string::npos);
  EXPECT_NE(error("block 0 0 0 1 1 1\n").find("no boundary"), std::string::npos);
  EXPECT_NE(error(b + b).find("bad.txt:2: a second boundary"), std::string::npos);
  EXPECT_NE(error("boundary 0 0 0 0 1 1\n").find("empty along axis x"), std::string::npos);
  EXPECT_NE(error(b + "block 0 0 0 1 1 1 300 0 0\n").find("0..255"), std::string::npos);
  EXPECT_NE(error(b + "start 1 2\n").find("start needs x y z"), std::string::npos);
  EXPECT_NE(error("").find("no boundary"), std::string::npos);
  EXPECT_THROW(load_box_map("/nonexistent/map.txt"), InputError);
}

TEST(SphereWorld, SegmentTestAgreesWithSampling) {
  const SphereMap m = parse_sphere_map(
      "boundary 0 0 10\nsphere 2 0 1.5\nsphere -3 3 1\nsphere 0 -5 2\nstart -8 0\ngoal 8 0\n",
      "s.txt");
  const SphereWorld& w = m.world;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-10.5, 10.5);
  int blocked = 0, rejected_but_sampled_free = 0;
  for (int trial = 0; trial < 5000; ++trial) {
    const Vec<2> a{u(rng), u(rng)}, b{u(rng), u(rng)};
    bool any_bad = false;
    for (int i = 0; i <= 2000 && !any_bad; ++i) any_bad = !w.point_free(lerp<2>(a, b, i / 2000.0));
    if (any_bad) {
      EXPECT_FALSE(w.segment_free(a, b)) << trial;
    } else if (!w.segment_free(a, b)) {
      ++rejected_but_sampled_free;  // clips a disc between two samples (~0.015 apart)
    }
    blocked += any_bad;
  }
  EXPECT_GT(blocked, 1000);
  // False rejections would show as many sampled-free segments rejected; a clipped disc is rare.
  EXPECT_LE(rejected_but_sampled_free, 50);
  EXPECT_FALSE(w.segment_free({-1, 1.5}, {5, 1.5}));  // tangent to the first sphere: touching
  EXPECT_TRUE(w.segment_free({-1, 1.5001}, {5, 1.5001}));
  EXPECT_EQ(w.why_not_free({2, 0}), "inside the sphere of line 2");
  EXPECT_EQ(w.why_not_free({11, 0}), "outside the boundary");
}

TEST(SphereWorld, MalformedFilesAreRejected) {
  EXPECT_THROW(parse_sphere_map("sphere 0 0 1\n", "s"), InputError);
  EXPECT_THROW(parse_sphere_map("boundary 0 0 -1\n", "s"), InputError);
  EXPECT_THROW(parse_sphere_map("boundary 0 0 1\nsphere 0 0\n", "s"), InputError);
  EXPECT_THROW(parse_sphere_map("boundary 0 0 1\nsphere 0 0 -2\n", "s"), InputError);
  EXPECT_THROW(parse_sphere_map("boundary 0 0 1\ncircle 0 0 2\n", "s"), InputError);
}

}  // namespace
}  // namespace hpcplan::env
