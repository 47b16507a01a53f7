#include "hpcplan/env/kinematic_chain.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "hpcplan/core/error.hpp"
#include "hpcplan/core/splitmix64.hpp"

// Every loop over a block's states carries this: the lanes are independent, so the compiler
// may vectorise without proving it (the project builds with -fopenmp; without it the loops
// still vectorise where GCC proves it alone).
#if defined(_OPENMP)
#define HPCPLAN_LANES_LOOP _Pragma("omp simd")
#else
#define HPCPLAN_LANES_LOOP
#endif

// valid() and valid_batch() must agree on every state, also within round-off of touching. They
// evaluate the same expressions in the same order, which is only enough if neither fuses a
// multiply and an add that the other rounds twice. The baseline (x86-64-v2) and the AVX2 build
// below have no FMA to fuse with; a build whose baseline has it (-march=x86-64-v3 or native)
// could contract the scalar and the vector code differently, so contraction is off here.
// The lane type below (Lanes4, 32 bytes) is only passed between inlined functions of this file,
// so GCC's note that such arguments change the ABI without AVX does not apply.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif

#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__) && defined(__FMA__)
#pragma GCC optimize("fp-contract=off")
#endif

namespace hpcplan {

// One pair of segments to test: chain segment `segment` against chain segment `other`
// (other >= segment + 2) or against environment segment `other`.
struct ChainPairTest {
  std::uint8_t segment;
  std::uint8_t other;
  bool environment;
};

struct KinematicChainModel {
  int links = 0;
  double link_length = 0.0;
  // The environment in structure-of-arrays form, with each segment's bounding box.
  std::vector<double> env_x0, env_y0, env_x1, env_y1;
  std::vector<double> env_lo_x, env_hi_x, env_lo_y, env_hi_y;
  // Every pair that can intersect at all (see build_tests), in the order both paths test them:
  // the pairs that most often find a collision first, so that an invalid state stops early.
  std::vector<ChainPairTest> tests;
};

namespace {

constexpr int kMaxPoints = KinematicChain::kMaxLinks + 2;  // base, joints, link end, tip end
constexpr std::size_t kLanes = 64;                         // states per block of valid_batch

// ---- Sine and cosine, shared bit for bit by the scalar and the vector path ----------------
// std::sin is a library call the compiler cannot vectorise (and a vector math library would
// round differently from it), so both paths use this one: reduction by the nearest multiple of
// pi/2 with pi/2 split in three (the first two parts have 30 significant bits, so multiples
// up to 2^23 of them are exact), then Taylor polynomials on [-pi/4, pi/4], where the first
// omitted term is below 1e-19. The nearest multiple comes from adding 1.5 * 2^52 (which leaves
// the integer in the low bits of the sum) rather than std::floor, which GCC does not vectorise
// unless trapping math is off.
constexpr double kTwoOverPi = 0x1.45f306dc9c883p-1;
constexpr double kHalfPiHigh = 0x1.921fb54000000p+0;
constexpr double kHalfPiMid = 0x1.10b4611800000p-30;
constexpr double kHalfPiLow = 0x1.313198a2e0370p-61;
constexpr double kRoundingShift = 0x1.8p52;

constexpr double inverse_factorial(int k) {
  double f = 1.0;
  for (int i = 2; i <= k; ++i) f *= i;
  return 1.0 / f;
}

struct SinCos {
  double sin, cos;
};

// Returns by value: in an `omp simd` loop GCC turns a local whose address is taken (an out
// parameter) into a per-lane array, and then does not vectorise the loop.
[[gnu::always_inline]] inline SinCos sin_cos(double theta) {
  const double shifted = theta * kTwoOverPi + kRoundingShift;
  const double quarter_turns = shifted - kRoundingShift;
  double r = theta - quarter_turns * kHalfPiHigh;
  r = r - quarter_turns * kHalfPiMid;
  r = r - quarter_turns * kHalfPiLow;
  const double r2 = r * r;
  constexpr double s3 = -inverse_factorial(3), s5 = inverse_factorial(5);
  constexpr double s7 = -inverse_factorial(7), s9 = inverse_factorial(9);
  constexpr double s11 = -inverse_factorial(11), s13 = inverse_factorial(13);
  constexpr double s15 = -inverse_factorial(15), s17 = inverse_factorial(17);
  constexpr double c4 = inverse_factorial(4), c6 = -inverse_factorial(6);
  constexpr double c8 = inverse_factorial(8), c10 = -inverse_factorial(10);
  constexpr double c12 = inverse_factorial(12), c14 = -inverse_factorial(14);
  constexpr double c16 = inverse_factorial(16);
  const double sin_r =
      r + r * r2 *
              (s3 +
               r2 * (s5 + r2 * (s7 + r2 * (s9 + r2 * (s11 + r2 * (s13 + r2 * (s15 + r2 * s17)))))));
  const double cos_r =
      1.0 - 0.5 * r2 +
      r2 * r2 * (c4 + r2 * (c6 + r2 * (c8 + r2 * (c10 + r2 * (c12 + r2 * (c14 + r2 * c16))))));
  // quarter_turns mod 4 (the low bits of `shifted`, two's complement below 0) picks the
  // quadrant: sin = s, c, -s, -c and cos = c, -s, -c, s.
  const std::uint64_t quadrant = std::bit_cast<std::uint64_t>(shifted) & 3;
  const bool odd = (quadrant & 1) != 0;
  const double sin_mag = odd ? cos_r : sin_r;
  const double cos_mag = odd ? sin_r : cos_r;
  return {quadrant >= 2 ? -sin_mag : sin_mag,
          (quadrant == 1 || quadrant == 2) ? -cos_mag : cos_mag};
}

// ---- The pair predicate (closed_segments_intersect's rule, split in two) -------------------
// Templates over the lane type: double (one state: valid(), closed_segments_intersect()) and
// Lanes4 (four states: valid_batch()), so that both evaluate the very same expressions. With
// double they return bool, with Lanes4 a mask of four all-ones or all-zero 64-bit lanes.
using Lanes4 = double __attribute__((vector_size(32)));
using Mask4 = std::int64_t __attribute__((vector_size(32)));

template <class T>
[[gnu::always_inline]] inline T min_of(T a, T b) {
  return b < a ? b : a;
}
template <class T>
[[gnu::always_inline]] inline T max_of(T a, T b) {
  return a < b ? b : a;
}

template <class T>
[[gnu::always_inline]] inline auto boxes_overlap(T a_lo_x, T a_hi_x, T a_lo_y, T a_hi_y, T b_lo_x,
                                                 T b_hi_x, T b_lo_y, T b_hi_y) {
  return (a_hi_x >= b_lo_x) & (b_hi_x >= a_lo_x) & (a_hi_y >= b_lo_y) & (b_hi_y >= a_lo_y);
}

// Whether C and D are not strictly on one side of line AB, nor A and B strictly on one side of
// line CD. Non-short-circuit operators keep it one straight line of vector code, and it is
// written for few operations (it is most of valid_batch's work):
//   - orient(C, D, A) is computed as -(cdx * (cy - ay) - cdy * (cx - ax)), reusing orient(A, B,
//     C)'s differences: in IEEE arithmetic p - q == -(q - p) exactly, so this is the documented
//     formula's value with its sign flipped, and the test below does not care about the sign;
//     likewise orient(C, D, B) as -(cdx * (cy - by) - cdy * (cx - bx)).
//   - "not both > 0 and not both < 0" is min <= 0 <= max (the same for every non-NaN value;
//     a zero's sign does not matter to either comparison).
template <class T>
[[gnu::always_inline]] inline auto straddle(T ax, T ay, T bx, T by, T cx, T cy, T dx, T dy) {
  const T abx = bx - ax, aby = by - ay;
  const T cdx = dx - cx, cdy = dy - cy;
  const T acx = cx - ax, acy = cy - ay;
  const T abc = abx * acy - aby * acx;
  const T abd = abx * (dy - ay) - aby * (dx - ax);
  const T cda_flipped = cdx * acy - cdy * acx;
  const T cdb_flipped = cdx * (cy - by) - cdy * (cx - bx);
  const T zero{};
  return (min_of(abc, abd) <= zero) & (max_of(abc, abd) >= zero) &
         (min_of(cda_flipped, cdb_flipped) <= zero) & (max_of(cda_flipped, cdb_flipped) >= zero);
}

// ---- The chain's points, one state: the same operations valid_batch applies per lane -------
// Returns false when a joint angle is not finite (such a state is invalid).
bool chain_points(const double* q, int links, double link_length, double* x, double* y) {
  double theta = 0.0, px = 0.0, py = 0.0, s = 0.0, c = 1.0;
  bool finite = true;
  x[0] = 0.0;
  y[0] = 0.0;
  for (int i = 0; i < links; ++i) {
    finite &= q[i] - q[i] == 0.0;
    theta = theta + q[i];
    const SinCos sc = sin_cos(theta);
    s = sc.sin;
    c = sc.cos;
    px = px + link_length * c;
    py = py + link_length * s;
    x[i + 1] = px;
    y[i + 1] = py;
  }
  x[links + 1] = px + KinematicChain::kTipLength * c;
  y[links + 1] = py + KinematicChain::kTipLength * s;
  return finite;
}

// The distance from the origin to segment e, for dropping pairs that no state can bring close.
double distance_from_origin(const PlanarSegment& e) {
  const double dx = e.x1 - e.x0, dy = e.y1 - e.y0;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0.0 ? -(e.x0 * dx + e.y0 * dy) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(e.x0 + t * dx, e.y0 + t * dy);
}

// The pairs to test and their order. A chain point p (0 = base) is never farther than
// reach(p) from the origin, so an environment segment farther than that from the origin
// cannot meet the chain segment ending there, whatever the state: such pairs are left out
// (with a margin far above the round-off of the points). The rest are ordered greedily on
// fixed-seed uniform samples: next the pair that finds a collision in the most samples no
// earlier pair has, then (once no pair adds any) the others by how often they collide. This
// changes which pair stops an invalid state, never whether it is invalid.
std::vector<ChainPairTest> build_tests(const KinematicChainModel& m) {
  const int n = m.links;
  const int segments = n + 1;
  const auto reach = [&](int point) {
    return point <= n ? point * m.link_length : n * m.link_length + KinematicChain::kTipLength;
  };
  std::vector<ChainPairTest> all;
  for (int a = 0; a < segments; ++a)
    for (int b = a + 2; b < segments; ++b)
      all.push_back({static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(b), false});
  for (int a = 0; a < segments; ++a) {
    for (std::size_t e = 0; e < m.env_x0.size(); ++e) {
      const PlanarSegment seg{m.env_x0[e], m.env_y0[e], m.env_x1[e], m.env_y1[e]};
      const double limit = reach(a + 1);
      if (distance_from_origin(seg) > limit * (1.0 + 1e-9) + 1e-9) continue;
      all.push_back({static_cast<std::uint8_t>(a), static_cast<std::uint8_t>(e), true});
    }
  }

  const std::size_t samples = std::clamp<std::size_t>(
      (std::size_t{1} << 20) / std::max<std::size_t>(all.size(), 1), 64, 1024);
  const std::size_t words = (samples + 63) / 64;
  std::vector<std::uint64_t> hits(all.size() * words, 0);  // bit s of pair t: sample s collides
  SplitMix64 rng(0x6b696e636861696eULL);
  std::vector<double> q(n);
  double x[kMaxPoints], y[kMaxPoints];
  for (std::size_t s = 0; s < samples; ++s) {
    for (auto& v : q) v = (2.0 * rng.next_unit() - 1.0) * std::numbers::pi;
    chain_points(q.data(), n, m.link_length, x, y);
    for (std::size_t t = 0; t < all.size(); ++t) {
      const int a = all[t].segment, b = all[t].other;
      const PlanarSegment sa{x[a], y[a], x[a + 1], y[a + 1]};
      const PlanarSegment sb =
          all[t].environment ? PlanarSegment{m.env_x0[b], m.env_y0[b], m.env_x1[b], m.env_y1[b]}
                             : PlanarSegment{x[b], y[b], x[b + 1], y[b + 1]};
      if (closed_segments_intersect(sa, sb))
        hits[t * words + s / 64] |= std::uint64_t{1} << (s % 64);
    }
  }

  std::vector<ChainPairTest> ordered;
  std::vector<bool> taken(all.size(), false);
  std::vector<std::uint64_t> found(words, 0);  // samples some chosen pair already catches
  for (;;) {
    std::size_t best = all.size();
    int best_gain = 0;
    for (std::size_t t = 0; t < all.size(); ++t) {
      if (taken[t]) continue;
      int gain = 0;
      for (std::size_t w = 0; w < words; ++w)
        gain += std::popcount(hits[t * words + w] & ~found[w]);
      if (gain > best_gain) best_gain = gain, best = t;
    }
    if (best == all.size()) break;
    taken[best] = true;
    ordered.push_back(all[best]);
    for (std::size_t w = 0; w < words; ++w) found[w] |= hits[best * words + w];
  }
  std::vector<std::pair<int, std::size_t>> rest;  // (-collisions, original index): stable order
  for (std::size_t t = 0; t < all.size(); ++t) {
    if (taken[t]) continue;
    int count = 0;
    for (std::size_t w = 0; w < words; ++w) count += std::popcount(hits[t * words + w]);
    rest.emplace_back(-count, t);
  }
  std::sort(rest.begin(), rest.end());
  for (const auto& r : rest) ordered.push_back(all[r.second]);
  return ordered;
}

// ---- valid_batch's kernel --------------------------------------------------------------------
// A block of up to kLanes states as structure of arrays: x[p][lane] is point p of that state,
// lo_x[s][lane] .. hi_y[s][lane] the box of its segment s. Each pair test then runs over the
// lanes four at a time (Lanes4: one AVX2 vector, two SSE ones) without a branch, except one:
// a group of four whose boxes all miss skips the orientations, which are most of the work and
// which, in a valid state, most pairs do not need. Lanes found in collision are squeezed out
// once half of the block is, so that the tests after the first few (which catch most
// invalid states) run on the states still in question.
constexpr std::size_t kGroup = 4;

struct Block {
  alignas(64) double x[kMaxPoints][kLanes];
  alignas(64) double y[kMaxPoints][kLanes];
  alignas(64) double lo_x[kMaxPoints][kLanes];
  alignas(64) double hi_x[kMaxPoints][kLanes];
  alignas(64) double lo_y[kMaxPoints][kLanes];
  alignas(64) double hi_y[kMaxPoints][kLanes];
  alignas(64) double angle[KinematicChain::kMaxLinks][kLanes];  // the states, transposed
  alignas(64) std::int64_t hit[kLanes];  // nonzero: this lane's state is known to be invalid
  std::uint32_t state[kLanes];           // which state of the block each lane holds
};

// About 240 KiB: too much for a thread's stack, so one per thread, kept.
Block& thread_block() {
  thread_local const std::unique_ptr<Block> block = std::make_unique<Block>();
  return *block;
}

[[gnu::always_inline]] inline Lanes4 load4(const double* p) {
  Lanes4 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}

[[gnu::always_inline]] inline bool any_lane(Mask4 m) {
  return ((m[0] | m[1]) | (m[2] | m[3])) != 0;
}

// Lanes [lanes, round up to kGroup) repeat the last lane, so that whole groups can be tested;
// they give the same answers as the lane they copy, and only `lanes` lanes are read out.
[[gnu::always_inline]] inline std::size_t pad_lanes(int points, std::size_t lanes, Block& b) {
  const std::size_t padded = (lanes + kGroup - 1) / kGroup * kGroup;
  for (std::size_t l = lanes; l < padded; ++l) {
    for (int p = 0; p < points; ++p) {
      b.x[p][l] = b.x[p][lanes - 1];
      b.y[p][l] = b.y[p][lanes - 1];
      b.lo_x[p][l] = b.lo_x[p][lanes - 1];
      b.hi_x[p][l] = b.hi_x[p][lanes - 1];
      b.lo_y[p][l] = b.lo_y[p][lanes - 1];
      b.hi_y[p][l] = b.hi_y[p][lanes - 1];
    }
    b.hit[l] = b.hit[lanes - 1];
  }
  return padded;
}

[[gnu::always_inline]] inline void segment_boxes(int segments, std::size_t lanes, Block& b) {
  for (int s = 0; s < segments; ++s) {
    const double* x0 = b.x[s];
    const double* x1 = b.x[s + 1];
    const double* y0 = b.y[s];
    const double* y1 = b.y[s + 1];
    double* lo_x = b.lo_x[s];
    double* hi_x = b.hi_x[s];
    double* lo_y = b.lo_y[s];
    double* hi_y = b.hi_y[s];
    HPCPLAN_LANES_LOOP
    for (std::size_t l = 0; l < lanes; ++l) {
      lo_x[l] = min_of(x0[l], x1[l]);
      hi_x[l] = max_of(x0[l], x1[l]);
      lo_y[l] = min_of(y0[l], y1[l]);
      hi_y[l] = max_of(y0[l], y1[l]);
    }
  }
}

[[gnu::always_inline]] inline void load_block(const KinematicChainModel& m, const double* states,
                                              std::size_t lanes, Block& b) {
  const int n = m.links;
  const double link = m.link_length;
  alignas(64) double theta[kLanes], sin_t[kLanes], cos_t[kLanes];
  // The joint angles transposed first: the vectoriser will not load a column of the
  // row-major states itself.
  for (std::size_t l = 0; l < lanes; ++l)
    for (int i = 0; i < n; ++i) b.angle[i][l] = states[l * n + i];
  std::int64_t* hit = b.hit;
  HPCPLAN_LANES_LOOP
  for (std::size_t l = 0; l < lanes; ++l) {
    theta[l] = 0.0;
    b.x[0][l] = 0.0;
    b.y[0][l] = 0.0;
    hit[l] = 0;
  }
  for (int i = 0; i < n; ++i) {
    const double* q = b.angle[i];
    const double* x0 = b.x[i];
    const double* y0 = b.y[i];
    double* x1 = b.x[i + 1];
    double* y1 = b.y[i + 1];
    HPCPLAN_LANES_LOOP
    for (std::size_t l = 0; l < lanes; ++l) {
      hit[l] |= (q[l] - q[l] == 0.0) ? 0 : 1;
      theta[l] = theta[l] + q[l];
      const SinCos sc = sin_cos(theta[l]);
      sin_t[l] = sc.sin;
      cos_t[l] = sc.cos;
      x1[l] = x0[l] + link * sc.cos;
      y1[l] = y0[l] + link * sc.sin;
    }
  }
  HPCPLAN_LANES_LOOP
  for (std::size_t l = 0; l < lanes; ++l) {
    b.x[n + 1][l] = b.x[n][l] + KinematicChain::kTipLength * cos_t[l];
    b.y[n + 1][l] = b.y[n][l] + KinematicChain::kTipLength * sin_t[l];
  }
  std::int64_t any_bad = 0;
  for (std::size_t l = 0; l < lanes; ++l) any_bad |= hit[l];
  if (any_bad) {  // a non-finite state's points would poison the block's boxes: park them at 0
    for (int p = 0; p <= n + 1; ++p)
      for (std::size_t l = 0; l < lanes; ++l)
        if (hit[l]) b.x[p][l] = b.y[p][l] = 0.0;
  }
  segment_boxes(n + 1, lanes, b);
  for (std::size_t l = 0; l < lanes; ++l) b.state[l] = static_cast<std::uint32_t>(l);
}

// Moves the lanes not yet in collision down to the front of the block (the others get their
// answer, 0, now) and returns how many there are.
[[gnu::always_inline]] inline std::size_t squeeze(int points, std::size_t lanes, Block& b,
                                                  std::uint8_t* block_out) {
  std::uint32_t keep[kLanes];
  std::size_t kept = 0;
  for (std::size_t l = 0; l < lanes; ++l) {
    if (b.hit[l])
      block_out[b.state[l]] = 0;
    else
      keep[kept++] = static_cast<std::uint32_t>(l);
  }
  for (int p = 0; p < points; ++p) {
    double* x = b.x[p];
    double* y = b.y[p];
    for (std::size_t l = 0; l < kept; ++l) {
      x[l] = x[keep[l]];
      y[l] = y[keep[l]];
    }
  }
  for (std::size_t l = 0; l < kept; ++l) {
    b.state[l] = b.state[keep[l]];
    b.hit[l] = 0;
  }
  segment_boxes(points - 1, kept, b);
  return kept;
}

[[gnu::always_inline]] inline void chain_batch(const KinematicChainModel& m, const double* states,
                                               std::size_t k, std::uint8_t* out) {
  const int n = m.links;
  const int points = n + 2;
  const int segments = n + 1;
  Block& b = thread_block();
  // The box of each segment over the block's lanes: a pair whose boxes over the whole block do
  // not overlap cannot collide in any lane (the predicate requires overlapping boxes), which
  // skips most pairs for a block of nearby states (the samples of one motion).
  double block_lo_x[kMaxPoints], block_hi_x[kMaxPoints];
  double block_lo_y[kMaxPoints], block_hi_y[kMaxPoints];
  for (std::size_t first = 0; first < k; first += kLanes) {
    std::size_t lanes = std::min(kLanes, k - first);
    load_block(m, states + first * n, lanes, b);
    std::size_t padded = pad_lanes(points, lanes, b);
    std::uint8_t* block_out = out + first;
    for (int s = 0; s < segments; ++s) {
      Lanes4 lo_x = load4(b.lo_x[s]), hi_x = load4(b.hi_x[s]);
      Lanes4 lo_y = load4(b.lo_y[s]), hi_y = load4(b.hi_y[s]);
      for (std::size_t g = kGroup; g < padded; g += kGroup) {
        lo_x = min_of(lo_x, load4(b.lo_x[s] + g));
        hi_x = max_of(hi_x, load4(b.hi_x[s] + g));
        lo_y = min_of(lo_y, load4(b.lo_y[s] + g));
        hi_y = max_of(hi_y, load4(b.hi_y[s] + g));
      }
      block_lo_x[s] = std::min({lo_x[0], lo_x[1], lo_x[2], lo_x[3]});
      block_hi_x[s] = std::max({hi_x[0], hi_x[1], hi_x[2], hi_x[3]});
      block_lo_y[s] = std::min({lo_y[0], lo_y[1], lo_y[2], lo_y[3]});
      block_hi_y[s] = std::max({hi_y[0], hi_y[1], hi_y[2], hi_y[3]});
    }

    std::size_t alive = 0;
    for (std::size_t l = 0; l < lanes; ++l) alive += b.hit[l] == 0;
    for (const ChainPairTest& t : m.tests) {
      if (alive == 0) break;
      const int a = t.segment, o = t.other;
      const double* ax = b.x[a];
      const double* ay = b.y[a];
      const double* bx = b.x[a + 1];
      const double* by = b.y[a + 1];
      const double* a_lo_x = b.lo_x[a];
      const double* a_hi_x = b.hi_x[a];
      const double* a_lo_y = b.lo_y[a];
      const double* a_hi_y = b.hi_y[a];
      std::int64_t* hit = b.hit;
      Mask4 met{};  // whether any lane met this pair: only then can the count of lanes change
      if (t.environment) {
        if (!boxes_overlap(block_lo_x[a], block_hi_x[a], block_lo_y[a], block_hi_y[a],
                           m.env_lo_x[o], m.env_hi_x[o], m.env_lo_y[o], m.env_hi_y[o]))
          continue;
        const Lanes4 e_lo_x = Lanes4{} + m.env_lo_x[o], e_hi_x = Lanes4{} + m.env_hi_x[o];
        const Lanes4 e_lo_y = Lanes4{} + m.env_lo_y[o], e_hi_y = Lanes4{} + m.env_hi_y[o];
        const Lanes4 cx = Lanes4{} + m.env_x0[o], cy = Lanes4{} + m.env_y0[o];
        const Lanes4 dx = Lanes4{} + m.env_x1[o], dy = Lanes4{} + m.env_y1[o];
        for (std::size_t g = 0; g < padded; g += kGroup) {
          Mask4 h;
          __builtin_memcpy(&h, hit + g, sizeof h);
          const Mask4 boxes = boxes_overlap(load4(a_lo_x + g), load4(a_hi_x + g), load4(a_lo_y + g),
                                            load4(a_hi_y + g), e_lo_x, e_hi_x, e_lo_y, e_hi_y) &
                              ~h;  // a lane already in collision needs no more tests
          if (!any_lane(boxes)) continue;
          const Mask4 meet = boxes & straddle(load4(ax + g), load4(ay + g), load4(bx + g),
                                              load4(by + g), cx, cy, dx, dy);
          h |= meet;
          __builtin_memcpy(hit + g, &h, sizeof h);
          met |= meet;
        }
      } else {
        if (!boxes_overlap(block_lo_x[a], block_hi_x[a], block_lo_y[a], block_hi_y[a],
                           block_lo_x[o], block_hi_x[o], block_lo_y[o], block_hi_y[o]))
          continue;
        const double* cx = b.x[o];
        const double* cy = b.y[o];
        const double* dx = b.x[o + 1];
        const double* dy = b.y[o + 1];
        const double* o_lo_x = b.lo_x[o];
        const double* o_hi_x = b.hi_x[o];
        const double* o_lo_y = b.lo_y[o];
        const double* o_hi_y = b.hi_y[o];
        for (std::size_t g = 0; g < padded; g += kGroup) {
          Mask4 h;
          __builtin_memcpy(&h, hit + g, sizeof h);
          const Mask4 boxes = boxes_overlap(load4(a_lo_x + g), load4(a_hi_x + g), load4(a_lo_y + g),
                                            load4(a_hi_y + g), load4(o_lo_x + g), load4(o_hi_x + g),
                                            load4(o_lo_y + g), load4(o_hi_y + g)) &
                              ~h;
          if (!any_lane(boxes)) continue;
          const Mask4 meet =
              boxes & straddle(load4(ax + g), load4(ay + g), load4(bx + g), load4(by + g),
                               load4(cx + g), load4(cy + g), load4(dx + g), load4(dy + g));
          h |= meet;
          __builtin_memcpy(hit + g, &h, sizeof h);
          met |= meet;
        }
      }
      if (!any_lane(met)) continue;
      std::size_t now_alive = 0;
      HPCPLAN_LANES_LOOP
      for (std::size_t l = 0; l < lanes; ++l) now_alive += hit[l] == 0;
      alive = now_alive;
      if (alive != 0 && lanes - alive >= std::max<std::size_t>(8, lanes / 2)) {
        lanes = squeeze(points, lanes, b, block_out);
        padded = pad_lanes(points, lanes, b);
      }
    }
    for (std::size_t l = 0; l < lanes; ++l) block_out[b.state[l]] = b.hit[l] ? 0 : 1;
  }
}

void chain_batch_baseline(const KinematicChainModel& m, const double* states, std::size_t k,
                          std::uint8_t* out) {
  chain_batch(m, states, k, out);
}

// The same kernel with 4 doubles per vector. AVX2 only, not FMA: see the comment at the top.
__attribute__((target("avx2"))) void chain_batch_avx2(const KinematicChainModel& m,
                                                      const double* states, std::size_t k,
                                                      std::uint8_t* out) {
  chain_batch(m, states, k, out);
}

bool cpu_has_avx2() {
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has;
}

std::vector<AxisBounds> joint_axes(int links) {
  if (links < KinematicChain::kMinLinks || links > KinematicChain::kMaxLinks)
    throw InputError("kinematic chain: links must be in [" +
                     std::to_string(KinematicChain::kMinLinks) + ", " +
                     std::to_string(KinematicChain::kMaxLinks) + "], got " + std::to_string(links));
  return std::vector<AxisBounds>(links, AxisBounds{-std::numbers::pi, std::numbers::pi, true});
}

double chain_resolution(int links, double fraction) {
  if (!(fraction > 0.0) || !std::isfinite(fraction))
    throw InputError("kinematic chain: the resolution fraction must be positive, got " +
                     std::to_string(fraction));
  const double extent = 2.0 * std::numbers::pi * std::sqrt(static_cast<double>(links));
  return fraction * extent;
}

}  // namespace

bool closed_segments_intersect(const PlanarSegment& a, const PlanarSegment& b) {
  return boxes_overlap(std::min(a.x0, a.x1), std::max(a.x0, a.x1), std::min(a.y0, a.y1),
                       std::max(a.y0, a.y1), std::min(b.x0, b.x1), std::max(b.x0, b.x1),
                       std::min(b.y0, b.y1), std::max(b.y0, b.y1)) &&
         straddle(a.x0, a.y0, a.x1, a.y1, b.x0, b.y0, b.x1, b.y1);
}

KinematicChain::KinematicChain(int links, double resolution_fraction)
    : ConfigSpace("kinematic_chain_" + std::to_string(links), joint_axes(links),
                  chain_resolution(links, resolution_fraction)),
      links_(links) {
  const double w = 1.0 / links;
  const double eps = std::log(static_cast<double>(links)) / links;
  for (const double side : {-1.0, 1.0}) {  // the outer polyline, then the inner one
    const double length = w * (1.0 - side * std::numbers::pi * eps);
    double x = w, y = side * eps;
    for (int k = 1; k < links; ++k) {
      const double heading = k * std::numbers::pi / links;
      const double nx = x + length * std::cos(heading), ny = y + length * std::sin(heading);
      environment_.push_back({x, y, nx, ny});
      x = nx, y = ny;
    }
  }
  auto model = std::make_shared<KinematicChainModel>();
  model->links = links;
  model->link_length = w;
  for (const auto& e : environment_) {
    model->env_x0.push_back(e.x0);
    model->env_y0.push_back(e.y0);
    model->env_x1.push_back(e.x1);
    model->env_y1.push_back(e.y1);
    model->env_lo_x.push_back(std::min(e.x0, e.x1));
    model->env_hi_x.push_back(std::max(e.x0, e.x1));
    model->env_lo_y.push_back(std::min(e.y0, e.y1));
    model->env_hi_y.push_back(std::max(e.y0, e.y1));
  }
  model->tests = build_tests(*model);
  model_ = std::move(model);
}

std::vector<PlanarSegment> KinematicChain::segments(const double* q) const {
  double x[kMaxPoints], y[kMaxPoints];
  chain_points(q, links_, model_->link_length, x, y);
  std::vector<PlanarSegment> out;
  for (int s = 0; s <= links_; ++s) out.push_back({x[s], y[s], x[s + 1], y[s + 1]});
  return out;
}

std::vector<double> KinematicChain::start() const {
  std::vector<double> q(links_, std::numbers::pi / links_);
  q[0] = 0.0;
  return q;
}

std::vector<double> KinematicChain::goal() const {
  std::vector<double> q(links_, 0.0);
  q[0] = std::numbers::pi - 0.001;
  return q;
}

bool KinematicChain::valid(const double* q) const {
  const KinematicChainModel& m = *model_;
  const int n = links_;
  double x[kMaxPoints], y[kMaxPoints];
  if (!chain_points(q, n, m.link_length, x, y)) return false;
  // Each segment's box once, then a box test before each pair's orientations: most pairs of a
  // state are far apart, and the box test alone turns them away.
  double lo_x[kMaxPoints], hi_x[kMaxPoints], lo_y[kMaxPoints], hi_y[kMaxPoints];
  for (int s = 0; s <= n; ++s) {
    lo_x[s] = min_of(x[s], x[s + 1]);
    hi_x[s] = max_of(x[s], x[s + 1]);
    lo_y[s] = min_of(y[s], y[s + 1]);
    hi_y[s] = max_of(y[s], y[s + 1]);
  }
  for (const ChainPairTest& t : m.tests) {
    const int a = t.segment, o = t.other;
    if (t.environment) {
      if (!boxes_overlap(lo_x[a], hi_x[a], lo_y[a], hi_y[a], m.env_lo_x[o], m.env_hi_x[o],
                         m.env_lo_y[o], m.env_hi_y[o]))
        continue;
      if (straddle(x[a], y[a], x[a + 1], y[a + 1], m.env_x0[o], m.env_y0[o], m.env_x1[o],
                   m.env_y1[o]))
        return false;
    } else {
      if (!boxes_overlap(lo_x[a], hi_x[a], lo_y[a], hi_y[a], lo_x[o], hi_x[o], lo_y[o], hi_y[o]))
        continue;
      if (straddle(x[a], y[a], x[a + 1], y[a + 1], x[o], y[o], x[o + 1], y[o + 1])) return false;
    }
  }
  return true;
}

void KinematicChain::valid_batch(const double* states, std::size_t k, std::uint8_t* out) const {
  if (cpu_has_avx2())
    chain_batch_avx2(*model_, states, k, out);
  else
    chain_batch_baseline(*model_, states, k, out);
}

void KinematicChain::valid_batch_baseline(const double* states, std::size_t k,
                                          std::uint8_t* out) const {
  chain_batch_baseline(*model_, states, k, out);
}

bool KinematicChain::batch_uses_avx2() {
  return cpu_has_avx2();
}

}  // namespace hpcplan
