// The kinematic chain's and the hypercube's validity tests (env/kinematic_chain.hpp,
// env/hypercube.hpp) against references written here from their definitions, and their batch
// tests against their one-at-a-time tests on every state.
//
// The chain's reference is deliberately another formulation: long double throughout, the horn
// built from the definition's words, the library's sines and cosines, and segment intersection
// by solving A + t (B - A) = C + u (D - C) for t, u in [0, 1]. Where a pair of segments is
// within kAmbiguity of touching (the least distance from an endpoint of one to the other
// segment), rounding may legitimately decide either way, so such a state is left out of the
// comparison (unless another pair clearly collides) and counted; the tests require that to be
// rare.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/env/hypercube.hpp"
#include "hpcplan/env/kinematic_chain.hpp"

namespace {

using hpcplan::Hypercube;
using hpcplan::KinematicChain;
using hpcplan::PlanarSegment;
using hpcplan::SplitMix64;

using Real = long double;
constexpr Real kPi = 3.141592653589793238462643383279502884L;
// Far above the difference between the library's double endpoints and these long double ones
// (a few 1e-16 per link), far below the near-touching states' 1e-9 and up.
constexpr Real kAmbiguity = 1e-12L;

struct Point {
  Real x, y;
};
struct Seg {
  Point a, b;
};

Real distance_to_segment(Point p, const Seg& s) {
  const Real dx = s.b.x - s.a.x, dy = s.b.y - s.a.y;
  const Real len2 = dx * dx + dy * dy;
  Real t = len2 > 0 ? ((p.x - s.a.x) * dx + (p.y - s.a.y) * dy) / len2 : 0;
  t = std::clamp<Real>(t, 0, 1);
  return std::hypot(p.x - (s.a.x + t * dx), p.y - (s.a.y + t * dy));
}

// Closed segments share a point: the parametric solution, or for parallel segments, collinear
// and overlapping in their projection on the common line.
bool segments_meet(const Seg& p, const Seg& q) {
  const Real rx = p.b.x - p.a.x, ry = p.b.y - p.a.y;
  const Real sx = q.b.x - q.a.x, sy = q.b.y - q.a.y;
  const Real qpx = q.a.x - p.a.x, qpy = q.a.y - p.a.y;
  const Real denom = rx * sy - ry * sx;
  if (denom != 0) {
    const Real t = (qpx * sy - qpy * sx) / denom;
    const Real u = (qpx * ry - qpy * rx) / denom;
    return t >= 0 && t <= 1 && u >= 0 && u <= 1;
  }
  if (qpx * ry - qpy * rx != 0) return false;  // parallel, apart
  const Real len2 = rx * rx + ry * ry;
  const Real u0 = (qpx * rx + qpy * ry) / len2;
  const Real u1 = ((q.b.x - p.a.x) * rx + (q.b.y - p.a.y) * ry) / len2;
  return std::max(u0, u1) >= 0 && std::min(u0, u1) <= 1;
}

// How near the pair is to touching (or to no longer touching): the least distance from an
// endpoint of one segment to the other segment.
Real clearance(const Seg& p, const Seg& q) {
  return std::min({distance_to_segment(p.a, q), distance_to_segment(p.b, q),
                   distance_to_segment(q.a, p), distance_to_segment(q.b, p)});
}

enum class Verdict { kValid, kInvalid, kAmbiguous };

struct ChainReference {
  int n;
  std::vector<Seg> horn;

  explicit ChainReference(int links) : n(links) {
    const Real w = 1.0L / n, eps = std::log(static_cast<Real>(n)) / n;
    // Two polylines of n - 1 segments: from (w, -eps) with length w (1 + pi eps), from
    // (w, +eps) with length w (1 - pi eps); the k-th segment heads at k pi / n.
    for (int polyline = 0; polyline < 2; ++polyline) {
      Point p{w, polyline == 0 ? -eps : eps};
      const Real length = polyline == 0 ? w * (1 + kPi * eps) : w * (1 - kPi * eps);
      for (int k = 1; k <= n - 1; ++k) {
        const Real heading = k * kPi / n;
        const Point next{p.x + length * std::cos(heading), p.y + length * std::sin(heading)};
        horn.push_back({p, next});
        p = next;
      }
    }
  }

  std::vector<Seg> chain(const std::vector<double>& q) const {
    std::vector<Seg> segs;
    Point p{0, 0};
    Real theta = 0;
    for (int i = 0; i < n; ++i) {
      theta += q[i];
      const Point next{p.x + std::cos(theta) / n, p.y + std::sin(theta) / n};
      segs.push_back({p, next});
      p = next;
    }
    segs.push_back({p, {p.x + 0.001L * std::cos(theta), p.y + 0.001L * std::sin(theta)}});
    return segs;
  }

  // Also reports the least clearance over the pairs it looked at (pairs whose boxes are
  // farther apart than kAmbiguity are skipped: they are clearly apart).
  Verdict verdict(const std::vector<double>& q, Real* least_clearance = nullptr) const {
    const std::vector<Seg> segs = chain(q);
    bool ambiguous = false;
    Real least = std::numeric_limits<Real>::infinity();
    const auto look = [&](const Seg& p, const Seg& r) {
      const Real gap_x = std::max(std::min(p.a.x, p.b.x) - std::max(r.a.x, r.b.x),
                                  std::min(r.a.x, r.b.x) - std::max(p.a.x, p.b.x));
      const Real gap_y = std::max(std::min(p.a.y, p.b.y) - std::max(r.a.y, r.b.y),
                                  std::min(r.a.y, r.b.y) - std::max(p.a.y, p.b.y));
      if (gap_x > kAmbiguity || gap_y > kAmbiguity) return false;
      const Real c = clearance(p, r);
      least = std::min(least, c);
      if (c < kAmbiguity) {
        ambiguous = true;
        return false;
      }
      return segments_meet(p, r);
    };
    bool clear_hit = false;
    for (std::size_t i = 0; i < segs.size() && !clear_hit; ++i) {
      for (std::size_t j = i + 2; j < segs.size() && !clear_hit; ++j)
        clear_hit = look(segs[i], segs[j]);
      for (std::size_t e = 0; e < horn.size() && !clear_hit; ++e)
        clear_hit = look(segs[i], horn[e]);
    }
    if (least_clearance) *least_clearance = least;
    if (clear_hit) return Verdict::kInvalid;
    return ambiguous ? Verdict::kAmbiguous : Verdict::kValid;
  }
};

std::vector<double> random_joints(SplitMix64& rng, int n) {
  std::vector<double> q(n);
  for (auto& v : q) v = -std::numbers::pi + 2.0 * std::numbers::pi * rng.next_unit();
  return q;
}

double wrap(double v) {
  if (v >= std::numbers::pi) v -= 2.0 * std::numbers::pi;
  if (v < -std::numbers::pi) v += 2.0 * std::numbers::pi;
  return v;
}

// Every state's valid() against valid_batch() and valid_batch_baseline(), in chunks of each
// size, so that every block remainder is met.
template <class Space>
void expect_batch_matches_scalar(const Space& space, const std::vector<double>& states) {
  const std::size_t d = space.dims();
  const std::size_t count = states.size() / d;
  std::vector<std::uint8_t> scalar(count);
  for (std::size_t i = 0; i < count; ++i) scalar[i] = space.valid(states.data() + i * d) ? 1 : 0;
  for (const std::size_t chunk : {1, 3, 8, 17, 64, 1000}) {
    std::vector<std::uint8_t> batch(count, 2);
    for (std::size_t i = 0; i < count; i += chunk)
      space.valid_batch(states.data() + i * d, std::min(chunk, count - i), batch.data() + i);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < count; ++i) differ += batch[i] != scalar[i];
    EXPECT_EQ(differ, 0u) << space.name() << ", chunks of " << chunk;
    if constexpr (requires { space.valid_batch_baseline(nullptr, 0, nullptr); }) {
      std::fill(batch.begin(), batch.end(), 2);
      for (std::size_t i = 0; i < count; i += chunk)
        space.valid_batch_baseline(states.data() + i * d, std::min(chunk, count - i),
                                   batch.data() + i);
      differ = 0;
      for (std::size_t i = 0; i < count; ++i) differ += batch[i] != scalar[i];
      EXPECT_EQ(differ, 0u) << space.name() << ", baseline build, chunks of " << chunk;
    }
  }
}

PlanarSegment seg(double x0, double y0, double x1, double y1) {
  return {x0, y0, x1, y1};
}

// ---- The pair predicate ----------------------------------------------------------------------

TEST(CSpaceSegments, ClosedSegmentsTouchingCountAsIntersecting) {
  using hpcplan::closed_segments_intersect;
  EXPECT_TRUE(closed_segments_intersect(seg(0, 0, 2, 2), seg(0, 2, 2, 0)));  // crossing
  EXPECT_TRUE(closed_segments_intersect(seg(0, 0, 2, 0), seg(1, 0, 1, 5)));  // T: endpoint on
  EXPECT_TRUE(closed_segments_intersect(seg(0, 0, 1, 1), seg(1, 1, 2, 0)));  // shared endpoint
  EXPECT_TRUE(closed_segments_intersect(seg(0, 0, 2, 0), seg(1, 0, 3, 0)));  // collinear overlap
  EXPECT_TRUE(closed_segments_intersect(seg(0, 0, 1, 0), seg(1, 0, 3, 0)));  // collinear, touching
  EXPECT_TRUE(closed_segments_intersect(seg(0, 0, 4, 0), seg(1, 0, 2, 0)));  // one inside other
  EXPECT_TRUE(closed_segments_intersect(seg(0, 0, 2, 2), seg(1, 1, 1, 1)));  // point on segment
  EXPECT_FALSE(closed_segments_intersect(seg(0, 0, 1, 0), seg(1.5, 0, 3, 0)));  // collinear, apart
  EXPECT_FALSE(closed_segments_intersect(seg(0, 0, 2, 0), seg(0, 1, 2, 1)));    // parallel
  EXPECT_FALSE(closed_segments_intersect(seg(0, 0, 1, 0), seg(2, -1, 2, 1)));  // lines cross beyond
  EXPECT_FALSE(closed_segments_intersect(seg(0, 0, 2, 2), seg(1, 1.5, 1, 1.5)));   // point off it
  EXPECT_FALSE(closed_segments_intersect(seg(0, 0, 2, 0), seg(1, 1e-300, 1, 5)));  // just above
  EXPECT_TRUE(closed_segments_intersect(seg(0, 0, 2, 0), seg(1, -1e-300, 1, 5)));  // just across
}

// ---- Kinematic chain -------------------------------------------------------------------------

TEST(KinematicChainValidity, GeometryFollowsTheDefinition) {
  for (int n : {2, 3, 5, 8, 16}) {
    const KinematicChain chain(n);
    const ChainReference ref(n);
    ASSERT_EQ(chain.dims(), n);
    ASSERT_EQ(chain.environment().size(), ref.horn.size());
    for (std::size_t e = 0; e < ref.horn.size(); ++e) {
      const PlanarSegment& s = chain.environment()[e];
      EXPECT_NEAR(s.x0, static_cast<double>(ref.horn[e].a.x), 1e-14);
      EXPECT_NEAR(s.y0, static_cast<double>(ref.horn[e].a.y), 1e-14);
      EXPECT_NEAR(s.x1, static_cast<double>(ref.horn[e].b.x), 1e-14);
      EXPECT_NEAR(s.y1, static_cast<double>(ref.horn[e].b.y), 1e-14);
    }
    SplitMix64 rng(17 + n);
    for (int trial = 0; trial < 100; ++trial) {
      // Angles well outside [-pi, pi) too: the reduction of the shared sine and cosine.
      std::vector<double> q = random_joints(rng, n);
      q[0] *= 7.0;
      const auto segs = chain.segments(q.data());
      const auto want = ref.chain(q);
      ASSERT_EQ(segs.size(), static_cast<std::size_t>(n + 1));
      for (int s = 0; s <= n; ++s) {
        EXPECT_NEAR(segs[s].x1, static_cast<double>(want[s].b.x), 1e-14);
        EXPECT_NEAR(segs[s].y1, static_cast<double>(want[s].b.y), 1e-14);
      }
    }
    EXPECT_NEAR(chain.resolution(), 0.01 * 2.0 * std::numbers::pi * std::sqrt(n), 1e-15);
  }
}

// OMPL's KinematicChainBenchmark start (0, pi/n, ..., pi/n) and goal (pi - 0.001, 0, ..., 0).
// For n = 2 the start is NOT valid under the rule here: the horn's inner polyline is then one
// segment from (0.5, 0.347) back down to (0.5, 0.302) (its length w (1 - pi ln(2)/2) is
// negative), lying on the line x = 0.5 along which the chain's second link runs from (0.5, 0)
// to (0.5, 0.5): collinear overlap, which closed segments count as intersecting.
TEST(KinematicChainValidity, StartAndGoalOfTheBenchmark) {
  for (int n = 2; n <= 16; ++n) {
    const KinematicChain chain(n);
    const ChainReference ref(n);
    const auto start = chain.start();
    const auto goal = chain.goal();
    ASSERT_EQ(start.size(), static_cast<std::size_t>(n));
    EXPECT_EQ(start[0], 0.0);
    EXPECT_DOUBLE_EQ(start[n - 1], std::numbers::pi / n);
    EXPECT_DOUBLE_EQ(goal[0], std::numbers::pi - 0.001);
    EXPECT_TRUE(chain.valid(goal.data())) << "goal, n = " << n;
    EXPECT_EQ(ref.verdict(goal), Verdict::kValid) << "goal, n = " << n;
    if (n == 2) {
      EXPECT_FALSE(chain.valid(start.data()));
      EXPECT_NE(ref.verdict(start), Verdict::kValid);
    } else {
      EXPECT_TRUE(chain.valid(start.data())) << "start, n = " << n;
      EXPECT_EQ(ref.verdict(start), Verdict::kValid) << "start, n = " << n;
    }
    std::uint8_t out[2];
    std::vector<double> both = start;
    both.insert(both.end(), goal.begin(), goal.end());
    chain.valid_batch(both.data(), 2, out);
    EXPECT_EQ(out[0], n == 2 ? 0 : 1);
    EXPECT_EQ(out[1], 1);
  }
}

// Pairs of a valid and an invalid state, bisected along the straight line between them down to
// 1e-15 of the parameter; then states at 1e-9 .. 1e-6 (in joint angle) on either side of the
// boundary, along the line and off it at random.
std::vector<double> near_touching_states(const ChainReference& ref, SplitMix64& rng, int pairs,
                                         const std::vector<double>& valid_pool,
                                         const std::vector<double>& invalid_pool) {
  const int n = ref.n;
  const std::size_t valid_count = valid_pool.size() / n, invalid_count = invalid_pool.size() / n;
  std::vector<double> out;
  std::vector<double> q(n);
  for (int p = 0; p < pairs; ++p) {
    const double* v = valid_pool.data() + rng.next_below(valid_count) * n;
    const double* u = invalid_pool.data() + rng.next_below(invalid_count) * n;
    std::vector<double> delta(n);
    double span = 0;
    for (int i = 0; i < n; ++i) {
      delta[i] = std::remainder(u[i] - v[i], 2.0 * std::numbers::pi);
      span = std::max(span, std::abs(delta[i]));
    }
    const auto at = [&](double t, std::vector<double>& s) {
      for (int i = 0; i < n; ++i) s[i] = wrap(v[i] + t * delta[i]);
    };
    double lo = 0.0, hi = 1.0;  // valid at lo, not valid at hi
    for (int it = 0; it < 60 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      at(mid, q);
      (ref.verdict(q) == Verdict::kValid ? lo : hi) = mid;
    }
    for (double step : {1e-9, 1e-8, 1e-7, 1e-6}) {
      for (double t : {lo - step / span, hi + step / span}) {
        at(t, q);
        out.insert(out.end(), q.begin(), q.end());
      }
      at(lo, q);
      for (auto& a : q) a = wrap(a + (2.0 * rng.next_unit() - 1.0) * step);
      out.insert(out.end(), q.begin(), q.end());
    }
  }
  return out;
}

TEST(KinematicChainValidity, MatchesAnIndependentReferenceAndBatchMatchesScalar) {
  std::size_t compared = 0, excluded = 0, near_compared = 0, near_excluded = 0;
  std::size_t near_valid = 0, near_invalid = 0, near_below_1e6 = 0;
  for (int n : {2, 3, 5, 8, 12, 16}) {
    const KinematicChain chain(n);
    const ChainReference ref(n);
    SplitMix64 rng(0xc4a1 + n);
    std::vector<double> uniform, near_start, valid_pool, invalid_pool;
    std::vector<double> q(n);
    for (int i = 0; i < 20000; ++i) {
      q = random_joints(rng, n);
      uniform.insert(uniform.end(), q.begin(), q.end());
    }
    const auto start = chain.start();
    for (int i = 0; i < 4000; ++i) {  // mostly valid: the chain curled in the horn
      for (int j = 0; j < n; ++j) q[j] = wrap(start[j] + (2.0 * rng.next_unit() - 1.0) * 0.05);
      near_start.insert(near_start.end(), q.begin(), q.end());
    }

    const auto compare = [&](const std::vector<double>& states, bool near) {
      for (std::size_t i = 0; i < states.size() / n; ++i) {
        const std::vector<double> s(states.begin() + i * n, states.begin() + (i + 1) * n);
        Real least = 0;
        const Verdict want = ref.verdict(s, &least);
        const bool got = chain.valid(s.data());
        if (want == Verdict::kAmbiguous) {
          ++(near ? near_excluded : excluded);
          continue;
        }
        ++(near ? near_compared : compared);
        if (near) {
          ++(want == Verdict::kValid ? near_valid : near_invalid);
          near_below_1e6 += least < 2e-6L;
        } else {
          (want == Verdict::kValid ? valid_pool : invalid_pool)
              .insert((want == Verdict::kValid ? valid_pool : invalid_pool).end(), s.begin(),
                      s.end());
        }
        EXPECT_EQ(got, want == Verdict::kValid) << "n = " << n << ", state " << i;
      }
    };
    compare(uniform, false);
    compare(near_start, false);
    ASSERT_GT(valid_pool.size(), 100u * n) << "n = " << n;
    ASSERT_GT(invalid_pool.size(), 100u * n) << "n = " << n;
    const auto near = near_touching_states(ref, rng, 250, valid_pool, invalid_pool);
    compare(near, true);

    expect_batch_matches_scalar(chain, uniform);
    expect_batch_matches_scalar(chain, near_start);
    expect_batch_matches_scalar(chain, near);
  }
  std::printf(
      "chain: %zu random states compared, %zu excluded as within %.0Le of touching; "
      "%zu near-touching compared (%zu valid, %zu invalid, %zu within 2e-6), %zu "
      "excluded\n",
      compared, excluded, kAmbiguity, near_compared, near_valid, near_invalid, near_below_1e6,
      near_excluded);
  EXPECT_GE(compared, 100000u);
  EXPECT_LE(excluded, compared / 10000);  // rare: under 0.01 %
  EXPECT_GE(near_compared, 10000u);
  EXPECT_LE(near_excluded, near_compared / 100);
  // The near set is what it claims: both sides of the boundary, mostly within 2e-6 of touching.
  EXPECT_GE(near_valid, near_compared / 4);
  EXPECT_GE(near_invalid, near_compared / 4);
  EXPECT_GE(near_below_1e6, near_compared / 2);
}

TEST(KinematicChainValidity, NonFiniteStatesAreInvalid) {
  const KinematicChain chain(8);
  std::vector<double> states;
  for (int i = 0; i < 70; ++i) {
    auto s = chain.goal();
    if (i % 7 == 3) s[i % 8] = std::numeric_limits<double>::quiet_NaN();
    if (i % 7 == 5) s[i % 8] = std::numeric_limits<double>::infinity();
    states.insert(states.end(), s.begin(), s.end());
  }
  std::vector<std::uint8_t> out(70);
  chain.valid_batch(states.data(), 70, out.data());
  for (int i = 0; i < 70; ++i) {
    const bool finite = i % 7 != 3 && i % 7 != 5;
    EXPECT_EQ(chain.valid(states.data() + i * 8), finite) << i;
    EXPECT_EQ(out[i], finite ? 1 : 0) << i;
  }
}

TEST(KinematicChainValidity, BadInputIsAnInputError) {
  EXPECT_THROW(KinematicChain(1), hpcplan::InputError);
  EXPECT_THROW(KinematicChain(65), hpcplan::InputError);
  EXPECT_THROW(KinematicChain(8, 0.0), hpcplan::InputError);
  EXPECT_THROW(KinematicChain(8, -0.01), hpcplan::InputError);
  EXPECT_THROW(KinematicChain(8, std::numeric_limits<double>::quiet_NaN()), hpcplan::InputError);
  EXPECT_NO_THROW(KinematicChain(2));
  EXPECT_NO_THROW(KinematicChain(64));
  try {
    KinematicChain bad(65);
  } catch (const hpcplan::InputError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("links"), std::string::npos);
  }
}

TEST(CSpaceValidity, CheckCounterCountsStates) {
  const KinematicChain chain(5);
  const auto s = chain.start();
  const auto before = chain.checks().value();
  EXPECT_TRUE(chain.is_valid(s.data()));
  EXPECT_EQ(chain.checks().value(), before + 1);
  std::vector<double> states;
  for (int i = 0; i < 10; ++i) states.insert(states.end(), s.begin(), s.end());
  std::uint8_t out[10];
  chain.are_valid(states.data(), 10, out);
  EXPECT_EQ(chain.checks().value(), before + 11);

  const Hypercube cube(4);
  const auto z = cube.start();
  cube.is_valid(z.data());
  std::vector<double> zs(4 * 7, 0.0);
  std::uint8_t zo[7];
  cube.are_valid(zs.data(), 7, zo);
  EXPECT_EQ(cube.checks().value(), 8u);
}

// ---- Hypercube -------------------------------------------------------------------------------

bool cube_reference(const std::vector<double>& s, double e) {
  const int d = static_cast<int>(s.size());
  for (int k = 0; k < d; ++k) {
    bool ok = s[k] >= 0.0 && s[k] <= 1.0;
    for (int i = 0; i < k && ok; ++i) ok = s[i] <= e;
    for (int i = k + 1; i < d && ok; ++i) ok = s[i] >= 1.0 - e;
    if (ok) return true;
  }
  return false;
}

TEST(HypercubeValidity, MatchesTheDefinitionAndBatchMatchesScalar) {
  std::size_t total = 0, valid = 0;
  for (int d = 2; d <= 16; ++d) {
    const Hypercube cube(d);
    EXPECT_EQ(cube.dims(), d);
    EXPECT_NEAR(cube.resolution(), 0.001 * std::sqrt(d), 1e-15);
    SplitMix64 rng(0x6375 + d);
    // Values on and next to the corridor's walls, the cube's faces and beyond them.
    const double lo = 0.1, hi = 1.0 - 0.1;
    const double edges[] = {0.0,
                            lo,
                            hi,
                            1.0,
                            std::nextafter(lo, 1.0),
                            std::nextafter(lo, 0.0),
                            std::nextafter(hi, 1.0),
                            std::nextafter(hi, 0.0),
                            -1e-12,
                            1.0 + 1e-12,
                            lo + 1e-9,
                            hi - 1e-9,
                            std::nextafter(0.0, -1.0),
                            std::nextafter(1.0, 2.0)};
    const auto pick = [&](double a, double b) {
      const std::uint64_t r = rng.next_below(4);
      if (r == 0) return edges[rng.next_below(std::size(edges))];
      return a + (b - a) * rng.next_unit();
    };
    std::vector<double> states;
    std::vector<double> s(d);
    for (int i = 0; i < 7000; ++i) {
      const int mode = static_cast<int>(rng.next_below(3));
      const int k = static_cast<int>(rng.next_below(d));
      for (int a = 0; a < d; ++a) {
        if (mode == 0)  // anywhere in the cube: almost always invalid
          s[a] = rng.next_unit();
        else if (a < k)  // near the corridor of axis k: low before it, high after it
          s[a] = pick(-0.01, lo + 0.02);
        else if (a > k)
          s[a] = pick(hi - 0.02, 1.01);
        else
          s[a] = pick(-0.05, 1.05);
      }
      if (mode == 2) s[rng.next_below(d)] = edges[rng.next_below(std::size(edges))];
      states.insert(states.end(), s.begin(), s.end());
      const bool want = cube_reference(s, 0.1);
      EXPECT_EQ(cube.valid(s.data()), want) << "d = " << d << ", state " << i;
      valid += want;
      ++total;
    }
    expect_batch_matches_scalar(cube, states);
    const auto start = cube.start(), goal = cube.goal();
    EXPECT_TRUE(cube.valid(start.data()));
    EXPECT_TRUE(cube.valid(goal.data()));
    EXPECT_EQ(start, std::vector<double>(d, 0.0));
    EXPECT_EQ(goal, std::vector<double>(d, 1.0));
  }
  std::printf("hypercube: %zu states, %zu valid\n", total, valid);
  EXPECT_GE(total, 100000u);
  EXPECT_GE(valid, total / 20);
  EXPECT_LE(valid, total * 4 / 5);
}

TEST(HypercubeValidity, BadInputIsAnInputError) {
  EXPECT_THROW(Hypercube(1), hpcplan::InputError);
  EXPECT_THROW(Hypercube(65), hpcplan::InputError);
  EXPECT_THROW(Hypercube(4, 0.0), hpcplan::InputError);
  EXPECT_THROW(Hypercube(4, 0.5), hpcplan::InputError);
  EXPECT_THROW(Hypercube(4, 0.1, 0.0), hpcplan::InputError);
  EXPECT_THROW(Hypercube(4, 0.1, -1.0), hpcplan::InputError);
  EXPECT_NO_THROW(Hypercube(2));
  EXPECT_NO_THROW(Hypercube(64));
}

}  // namespace
