#pragma once
// The planar kinematic chain in a "horn": OMPL's dimension-scalable benchmark
// (KinematicChainBenchmark), as a ConfigSpace whose batch test vectorises over states.
//
// n links of length 1/n hang from the origin; joint i turns link i by q_i relative to link i-1,
// so link i points at theta_i = q_0 + ... + q_i. A tip segment of length 0.001 continues the
// last link, so a state has n + 1 segments (segments()). The environment is two polylines of
// n - 1 segments (w = 1/n, eps = ln(n)/n): one from (w, -eps), one from (w, +eps), their k-th
// segment (k = 1..n-1) heading at k*pi/n, of length w*(1 + pi*eps) and w*(1 - pi*eps). For
// n <= 5 that second length is negative (1 - pi*ln(n)/n < 0): the polyline is then drawn
// backwards along each heading, as the formula says.
//
// A state is valid when it is finite, no two non-adjacent chain segments (i and j >= i + 2)
// intersect and no chain segment intersects an environment segment. Adjacent segments share a
// joint and are never tested: touching there, or folding back onto each other, is allowed.
//
// Intersection is of CLOSED segments, decided by closed_segments_intersect() below: touching
// (an endpoint on the other segment, a shared endpoint) and collinear overlap both count. It
// is evaluated in double precision with the exact formula documented there, so a
// configuration within round-off (about 1e-15) of touching is decided by that formula, and
// the same way by valid() and valid_batch(). The joint angles' sines and cosines come from a
// polynomial of this space's own (accurate to a few units in the last place for
// |theta| < 2^20), shared by both paths, so their endpoints are identical bit for bit.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "hpcplan/env/config_space.hpp"

namespace hpcplan {

struct PlanarSegment {
  double x0 = 0.0, y0 = 0.0;
  double x1 = 0.0, y1 = 0.0;
};

// Whether closed segments a = [A, B] and b = [C, D] share a point. With
// orient(P, Q, R) = (Q.x - P.x) * (R.y - P.y) - (Q.y - P.y) * (R.x - P.x) evaluated in double
// in that order (no fused multiply-add), they intersect when
//   - their axis-aligned bounding boxes overlap (closed: equal edges overlap),
//   - orient(A, B, C) and orient(A, B, D) are not both > 0 and not both < 0, and
//   - orient(C, D, A) and orient(C, D, B) are not both > 0 and not both < 0.
// In exact arithmetic this is exactly "the closed segments share a point", including an
// endpoint lying on the other segment (an orientation of 0), collinear segments (all four 0:
// the boxes decide whether they overlap) and degenerate, point-like segments. In floating
// point an orientation within round-off of 0 may come out either sign, so segments closer than
// about 1e-15 (relative to their coordinates) to touching are decided by this formula alone.
bool closed_segments_intersect(const PlanarSegment& a, const PlanarSegment& b);

struct KinematicChainModel;  // the tables valid() and valid_batch() read (kinematic_chain.cpp)

class KinematicChain final : public ConfigSpace {
 public:
  static constexpr int kMinLinks = 2;
  static constexpr int kMaxLinks = 64;
  static constexpr double kTipLength = 0.001;

  // links in [kMinLinks, kMaxLinks]; the motion-check resolution is resolution_fraction times
  // maximum_extent() (OMPL's discrete motion validator's default fraction is 0.01). Throws
  // InputError otherwise, or when the fraction is not positive.
  explicit KinematicChain(int links, double resolution_fraction = 0.01);

  int links() const { return links_; }
  double link_length() const { return 1.0 / links_; }
  // The horn: 2 * (links() - 1) segments, the outer polyline's first.
  const std::vector<PlanarSegment>& environment() const { return environment_; }
  // The chain's links() + 1 segments for state q (links() joint angles): links from the base
  // outwards, then the tip.
  std::vector<PlanarSegment> segments(const double* q) const;
  // OMPL's KinematicChainBenchmark start (0, pi/n, ..., pi/n): the chain curled along the horn;
  // and goal (pi - 0.001, 0, ..., 0): the chain straight, pointing back past the base.
  std::vector<double> start() const;
  std::vector<double> goal() const;

  // Public here (protected in ConfigSpace) so that benchmarks can time them without the check
  // counter; planners go through is_valid() / are_valid().
  bool valid(const double* q) const override;
  void valid_batch(const double* states, std::size_t k, std::uint8_t* out) const override;
  // valid_batch() compiled for the build's baseline instruction set; valid_batch() runs an
  // AVX2 build of the same code where the CPU has AVX2. Public so that a test can check both
  // builds against valid() on a machine that has AVX2.
  void valid_batch_baseline(const double* states, std::size_t k, std::uint8_t* out) const;
  // Whether valid_batch() runs the AVX2 build on this CPU.
  static bool batch_uses_avx2();

 private:
  int links_;
  std::vector<PlanarSegment> environment_;
  std::shared_ptr<const KinematicChainModel> model_;
};

}  // namespace hpcplan
