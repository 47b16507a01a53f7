#pragma once
// A configuration space that a user (or a benchmark) defines by its validity test: the world
// of the lattice engines' c-space graph (graph/cspace_graph.hpp) and of the OMPL adapter
// (sampling/cspace_ompl.hpp). The kinematic chain and the hypercube
// (env/kinematic_chain.hpp, env/hypercube.hpp) are two of them; docs/CSPACE.md shows how to
// write another.
//
// A state is `dims()` doubles. Each axis has bounds; a periodic axis (a joint angle) wraps, its
// upper bound the same point as its lower one, and the straight motion between two states
// takes each periodic axis's shorter way round (motion.hpp's interpolation). The metric of
// every planner that reads a space is the Euclidean length in these coordinates, periodic axes
// measured the short way: the lattice's edge costs, its heuristic, and the length OMPL's
// planners report through the adapter.
//
// Validity is asked one state at a time (`valid`) or for a batch of states at once
// (`valid_batch`, row-major k x dims): the lattice engines hand a whole expansion's successors,
// and then the samples of their edges, as one batch, so a space whose test vectorises over
// states (VAMP's idea) overrides it; the default loops over `valid`. Both must give the same
// answer for every state.
//
// Threads: a space is immutable once built; `valid` and `valid_batch` are const and must be
// safe from any number of threads at once (the OMPL adapter's planners, the Python module's
// calls). Each state tested counts as one collision check on the space's CheckCounter.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hpcplan/core/check_counter.hpp"

namespace hpcplan {

// The most samples a motion across a whole space may take: resolution >= extent / 1e7.
inline constexpr double kMaxMotionSamples = 1e7;

struct AxisBounds {
  double lower = 0.0;
  double upper = 1.0;
  bool periodic = false;  // the axis wraps: upper is lower again
};

class ConfigSpace {
 public:
  virtual ~ConfigSpace() = default;

  const std::string& name() const { return name_; }
  int dims() const { return static_cast<int>(axes_.size()); }
  const std::vector<AxisBounds>& axes() const { return axes_; }
  // The longest step between two states tested along a motion (absolute, in the space's
  // coordinates): the edge checks of the lattice and of the OMPL adapter both sample at it.
  double resolution() const { return resolution_; }
  // The diagonal of the bounds box: OMPL's "maximum extent" (resolution fractions refer to it).
  double maximum_extent() const;

  // Whether one state is valid (in collision with nothing). Counts one check.
  bool is_valid(const double* state) const {
    checks_.add();
    return valid(state);
  }
  // out[i] = whether states[i * dims() .. ] is valid, for i < k. Counts k checks.
  void are_valid(const double* states, std::size_t k, std::uint8_t* out) const {
    checks_.add(k);
    valid_batch(states, k, out);
  }
  const CheckCounter& checks() const { return checks_; }

  // Whether a state lies in the bounds (periodic axes: in [lower, upper)).
  bool in_bounds(std::span<const double> state) const;

 protected:
  // Throws InputError if the axes are empty, a bound is not finite or lower >= upper, the
  // bounds' diagonal is not finite, or the resolution is not positive or finer than
  // maximum_extent() / kMaxMotionSamples.
  ConfigSpace(std::string name, std::vector<AxisBounds> axes, double resolution);

  // For a space whose resolution depends on what the base computes (a fraction of
  // maximum_extent()): InputError if not positive or finer than extent / kMaxMotionSamples.
  void set_resolution(double resolution);

  virtual bool valid(const double* state) const = 0;
  virtual void valid_batch(const double* states, std::size_t k, std::uint8_t* out) const;

 private:
  std::string name_;
  std::vector<AxisBounds> axes_;
  double resolution_;
  CheckCounter checks_;
};

// The straight motion between two states in a space: each periodic axis the short way round.
// Used by the lattice's edges, the off-lattice start and goal connections, the path re-check
// and the OMPL adapter's interpolation, so all agree on what a motion is.
class Motion {
 public:
  Motion(const ConfigSpace& space, std::span<const double> from, std::span<const double> to);
  // The motion's Euclidean length (periodic axes the short way).
  double length() const { return length_; }
  // The state at fraction t in [0, 1], wrapped back into the bounds on periodic axes.
  void at(double t, double* out) const;
  // Fills `out` with the m states at t = 1/m, 2/m, ..., 1 (m x dims, row-major), where m is the
  // fewest steps no longer than the space's resolution (at least 1): the samples a motion check
  // tests (its start is the previous state of a path, already tested).
  std::size_t samples(std::vector<double>& out) const;

 private:
  const ConfigSpace& space_;
  std::vector<double> from_, to_, delta_;
  double length_ = 0.0;
};

// The pieces of a motion, for callers that sample many motions without building one (the
// lattice's edges): the number of samples of a motion of `length` (the fewest steps no longer
// than `resolution`, at least 1), and the state at fraction t of the motion from `from` by
// `delta` (each axis's axis_difference), wrapped into the bounds on periodic axes. Motion uses
// the same two, so a lattice edge and a re-check of it test the very same states.
std::size_t motion_steps(double length, double resolution);
void motion_point(const std::vector<AxisBounds>& axes, const double* from, const double* delta,
                  double t, double* out);

// Whether the motion's samples are all valid, as one batch (counts each sample as a check).
bool motion_valid(const ConfigSpace& space, std::span<const double> from,
                  std::span<const double> to);

// The short-way difference to - from on an axis (periodic: in [-period/2, period/2]).
double axis_difference(const AxisBounds& axis, double from, double to);

}  // namespace hpcplan
