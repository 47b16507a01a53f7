#pragma once
// What the tree planners (RRT, RRT-Connect, RRT*) share: options, the result, sampling of the
// world's bounding box (and of the informed ellipsoid), steering and path extraction.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "hpcplan/core/check_counter.hpp"
#include "hpcplan/core/error.hpp"
#include "hpcplan/core/result.hpp"
#include "hpcplan/core/splitmix64.hpp"
#include "hpcplan/core/status.hpp"
#include "hpcplan/core/stop.hpp"
#include "hpcplan/core/stopwatch.hpp"
#include "hpcplan/env/point.hpp"
#include "hpcplan/tree/point_index.hpp"

namespace hpcplan::tree {

struct TreeOptions {
  double step = 0.0;              // steering distance eta; 0 = a twentieth of the largest extent
  double goal_bias = 0.1;         // probability of sampling the goal (RRT, RRT*)
  Stop stop;                      // deadline/cancellation; RRT and RRT-Connect end at a path
  std::uint64_t max_samples = 0;  // 0 = unlimited (then `stop` must be able to stop)
  std::uint64_t seed = 1;
  double gamma_factor = 1.1;   // RRT*: multiple of the asymptotically optimal gamma
  bool informed = true;        // RRT*: sample the ellipsoid that can still improve the path
  bool stop_at_first = false;  // RRT*: return the first solution
  // RRT* with fixed neighbourhoods (seed 000's replanner): rewire within this radius instead of
  // the shrinking r(n); 0 = r(n). And join the goal from any vertex within goal_radius that
  // sees it; 0 = within one step.
  double rewire_radius = 0.0;
  double goal_radius = 0.0;
};

// The one Result: path start..goal exactly, cost = its length, counters.peak_states = tree
// vertices, counters.samples, counters.first_solution_ms / first_cost for the first path.
template <int D>
using TreeResult = Result<env::Vec<D>>;

template <int D>
double default_step(const env::Aabb<D>& box) {
  return box.largest_side() / 20.0;
}

// Uniform samples of the world's box, or of the prolate ellipsoid {x : |x-a| + |x-b| <= c}
// (Gammell et al.'s informed set) when a path of length c is known.
template <int D>
class Sampler {
 public:
  Sampler(const env::Aabb<D>& box, const env::Vec<D>& a, const env::Vec<D>& b, std::uint64_t seed)
      : box_(box), a_(a), b_(b), rng_(seed), c_min_(env::distance<D>(a, b)) {
    // Householder reflection taking e1 to the unit vector from a to b.
    env::Vec<D> u{};
    for (int k = 0; k < D; ++k) u[k] = c_min_ > 0 ? (b[k] - a[k]) / c_min_ : (k == 0);
    env::Vec<D> v = u;
    v[0] -= 1.0;
    double vv = 0.0;
    for (double x : v) vv += x * x;
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j)
        rotation_[i][j] = (i == j) - (vv > 1e-20 ? 2.0 * v[i] * v[j] / vv : 0.0);
  }

  double unit() { return rng_.next_unit(); }

  env::Vec<D> uniform() {
    env::Vec<D> p;
    for (int k = 0; k < D; ++k) p[k] = box_.lo[k] + rng_.next_unit() * (box_.hi[k] - box_.lo[k]);
    return p;
  }

  // A uniform sample of the informed set clipped to the box; falls back to the box when the
  // ellipsoid is larger than it.
  env::Vec<D> informed(double c_best) {
    if (!std::isfinite(c_best) || c_best <= c_min_) return uniform();
    const double r1 = c_best / 2.0, rn = std::sqrt(c_best * c_best - c_min_ * c_min_) / 2.0;
    double ellipsoid = r1 * std::pow(rn, D - 1) * unit_ball_volume(), box = box_.volume();
    if (ellipsoid >= box) return uniform();
    for (;;) {
      const env::Vec<D> x = unit_ball();
      env::Vec<D> p;
      for (int i = 0; i < D; ++i) {
        double s = 0.0;
        for (int j = 0; j < D; ++j) s += rotation_[i][j] * x[j] * (j == 0 ? r1 : rn);
        p[i] = 0.5 * (a_[i] + b_[i]) + s;
      }
      if (box_.contains(p)) return p;
    }
  }

  static double unit_ball_volume() {
    return std::pow(std::numbers::pi, D / 2.0) / std::tgamma(D / 2.0 + 1.0);
  }

 private:
  env::Vec<D> unit_ball() {
    env::Vec<D> g;
    double norm = 0.0;
    for (int k = 0; k < D; ++k) {
      // Box-Muller: a standard normal per axis gives a uniform direction.
      const double u1 = 1.0 - rng_.next_unit(), u2 = rng_.next_unit();
      g[k] = std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
      norm += g[k] * g[k];
    }
    norm = std::sqrt(norm);
    const double r = std::pow(rng_.next_unit(), 1.0 / D);
    for (double& x : g) x = norm > 0 ? x / norm * r : 0.0;
    return g;
  }

  env::Aabb<D> box_;
  env::Vec<D> a_, b_;
  SplitMix64 rng_;
  double c_min_;
  double rotation_[D][D];
};

// The point at most `step` from `from` towards `to`.
template <int D>
env::Vec<D> steer(const env::Vec<D>& from, const env::Vec<D>& to, double step) {
  const double d = env::distance<D>(from, to);
  return d <= step ? to : env::lerp<D>(from, to, step / d);
}

// A tree of points with parent links (the root is its own parent) and a KD-tree over them.
template <int D>
struct Tree {
  std::vector<env::Vec<D>> points;
  std::vector<std::uint32_t> parent;
  PointIndex<D> index{points};

  Tree() = default;
  Tree(const Tree&) = delete;  // the index refers to `points`
  Tree& operator=(const Tree&) = delete;

  std::uint32_t add(const env::Vec<D>& p, std::uint32_t from) {
    points.push_back(p);
    parent.push_back(from);
    index.added(points.size() - 1);
    return static_cast<std::uint32_t>(points.size() - 1);
  }
  std::uint32_t add_root(const env::Vec<D>& p) {
    return add(p, static_cast<std::uint32_t>(points.size()));
  }
  // root..leaf
  std::vector<env::Vec<D>> branch(std::uint32_t leaf) const {
    std::vector<env::Vec<D>> path;
    for (std::uint32_t i = leaf;; i = parent[i]) {
      path.push_back(points[i]);
      if (parent[i] == i) break;
    }
    std::reverse(path.begin(), path.end());
    return path;
  }
};

// The steering distance eta the options ask for.
template <int D>
double step_of(const TreeOptions& o, const env::Aabb<D>& box) {
  return o.step > 0 ? o.step : default_step<D>(box);
}

// The run's own copy of the stop condition; a run that nothing could end is bad input.
inline Stop run_stop(const TreeOptions& o) {
  if (!o.stop.can_stop() && o.max_samples == 0)
    throw InputError("a tree planner needs a time limit, a stop token or a sample budget");
  return o.stop;
}

template <class W>
void check_query(const W& world, const env::Vec<W::kDim>& start, const env::Vec<W::kDim>& goal) {
  if (const std::string why = world.why_not_free(start); !why.empty())
    throw InputError("the start " + env::format_point<W::kDim>(start) + " is " + why);
  if (const std::string why = world.why_not_free(goal); !why.empty())
    throw InputError("the goal " + env::format_point<W::kDim>(goal) + " is " + why);
}

// What every tree planner sets up before its first sample: the query checked (InputError if the
// start or goal is not free), its clock, its own stop condition, the thread's check count at the
// start (a run's checks are the change of it) and the steering distance.
template <int D>
struct TreeRun {
  template <class W>
  TreeRun(const W& world, const env::Vec<D>& start, const env::Vec<D>& goal, const TreeOptions& o)
      : stop((check_query(world, start, goal), run_stop(o))), step(step_of<D>(o, world.bounds())) {}

  std::uint64_t checks() const { return CheckCounter::this_thread() - checks0; }

  Stopwatch clock;
  Stop stop;
  std::uint64_t checks0 = CheckCounter::this_thread();
  double step;
};

}  // namespace hpcplan::tree
