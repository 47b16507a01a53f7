#include "hpcplan/sampling/gog_motion_validator.hpp"

#include <cmath>
#include <limits>

#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>

#include "hpcplan/core/error.hpp"

namespace ob = ompl::base;

namespace hpcplan::sampling {

namespace {
constexpr int kMaxD = 16;
constexpr double kTie = 1e-12;  // crossings this close in t happen at once (edges, corners)
}  // namespace

GogMotionValidator::GogMotionValidator(const ob::SpaceInformationPtr& si,
                                       std::shared_ptr<const GogValidityChecker> checker)
    : ob::MotionValidator(si), checker_(std::move(checker)) {}

bool GogMotionValidator::segment_free(const double* a, const double* b, double* blocked_at) const {
  const GogField& field = checker_->field();
  const int d = field.dims();
  const int extent = field.extent();
  const int threshold = field.threshold();
  if (d > kMaxD) throw RunError("GogMotionValidator: too many dimensions");
  // Both ends must be inside the box; the segment then is too (the box is convex).
  for (int i = 0; i < d; ++i)
    if (!(a[i] >= 0.0 && a[i] <= extent && b[i] >= 0.0 && b[i] <= extent)) {
      *blocked_at = 0.0;
      return false;
    }

  int cell[kMaxD], dir[kMaxD];
  double t_max[kMaxD], t_delta[kMaxD];
  std::uint64_t looked_up = 0;
  // A cell is free when its level sum is below the threshold; cells outside the box are
  // only ever touched along the box's faces and do not block.
  auto blocked = [&](const int* c) {
    int sum = 0;
    for (int i = 0; i < d; ++i) {
      if (c[i] < 0 || c[i] >= extent) return false;
      sum += field.level_table(i)[c[i]];
    }
    ++looked_up;
    return sum >= threshold;
  };
  // Every cell c + sum of dir over a non-empty subset of `axes` (the cells meeting at an
  // edge or corner the segment touches), or c itself for an empty set.
  auto any_blocked_around = [&](int* c, const int* axes, int k) {
    for (unsigned mask = 0; mask < (1u << k); ++mask) {
      int probe[kMaxD] = {};
      for (int i = 0; i < d; ++i) probe[i] = c[i];
      for (int j = 0; j < k; ++j)
        if (mask & (1u << j)) probe[axes[j]] += dir[axes[j]];
      if (blocked(probe)) return true;
    }
    return false;
  };

  // Start: the cell holding a, plus the cells whose boxes a lies on the face of.
  int on_face[kMaxD], faces = 0;
  for (int i = 0; i < d; ++i) {
    const double x = a[i];
    const double fl = std::floor(x);
    dir[i] = b[i] > x ? 1 : (b[i] < x ? -1 : 0);
    cell[i] = static_cast<int>(fl);
    const bool on_boundary = x == fl && x > 0.0 && x < extent;
    if (on_boundary) {
      // Moving down from a face starts in the lower cell; either way both touch a.
      if (dir[i] < 0) cell[i] -= 1;
      on_face[faces++] = i;
    }
    if (cell[i] >= extent) cell[i] = extent - 1;
    const double len = std::abs(b[i] - x);
    if (dir[i] == 0) {
      t_max[i] = t_delta[i] = std::numeric_limits<double>::infinity();
    } else {
      const double next = dir[i] > 0 ? cell[i] + 1.0 : static_cast<double>(cell[i]);
      t_max[i] = std::abs(next - x) / len;
      t_delta[i] = 1.0 / len;
    }
  }
  {
    // The other side of each face a lies on.
    int probe_dir[kMaxD];
    for (int i = 0; i < d; ++i) probe_dir[i] = dir[i];
    for (int j = 0; j < faces; ++j) {
      const int i = on_face[j];
      dir[i] = dir[i] < 0 ? 1 : -1;  // towards the other cell sharing the face
    }
    const bool hit = any_blocked_around(cell, on_face, faces);
    for (int i = 0; i < d; ++i) dir[i] = probe_dir[i];
    if (hit) {
      checker_->add_checks(looked_up);
      *blocked_at = 0.0;
      return false;
    }
  }

  for (;;) {
    double t = std::numeric_limits<double>::infinity();
    for (int i = 0; i < d; ++i) t = std::min(t, t_max[i]);
    if (t > 1.0 + kTie) break;
    int axes[kMaxD], k = 0;
    for (int i = 0; i < d; ++i)
      if (t_max[i] <= t + kTie) axes[k++] = i;
    if (any_blocked_around(cell, axes, k)) {
      checker_->add_checks(looked_up);
      *blocked_at = std::min(1.0, t);
      return false;
    }
    for (int j = 0; j < k; ++j) {
      cell[axes[j]] += dir[axes[j]];
      t_max[axes[j]] += t_delta[axes[j]];
    }
  }
  checker_->add_checks(looked_up);
  return true;
}

bool GogMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2) const {
  double at = 0.0;
  const bool ok = segment_free(s1->as<ob::RealVectorStateSpace::StateType>()->values,
                               s2->as<ob::RealVectorStateSpace::StateType>()->values, &at);
  if (ok)
    valid_++;
  else
    invalid_++;
  return ok;
}

bool GogMotionValidator::checkMotion(const ob::State* s1, const ob::State* s2,
                                     std::pair<ob::State*, double>& last_valid) const {
  double at = 0.0;
  const bool ok = segment_free(s1->as<ob::RealVectorStateSpace::StateType>()->values,
                               s2->as<ob::RealVectorStateSpace::StateType>()->values, &at);
  if (ok) {
    valid_++;
    return true;
  }
  invalid_++;
  // Step back from the first contact so the reported state is strictly valid.
  const double len = si_->distance(s1, s2);
  const double back = len > 0 ? 1e-6 / len : 0.0;
  last_valid.second = std::max(0.0, at - back);
  if (last_valid.first != nullptr)
    si_->getStateSpace()->interpolate(s1, s2, last_valid.second, last_valid.first);
  return false;
}

}  // namespace hpcplan::sampling
