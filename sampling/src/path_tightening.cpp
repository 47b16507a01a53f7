#include "hpcplan/sampling/path_tightening.hpp"

#include <vector>

#include <ompl/base/spaces/RealVectorStateSpace.h>

namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace hpcplan::sampling {

namespace {

// Removes waypoint i whenever the motion from its predecessor to its successor is valid.
void drop_redundant(const ob::SpaceInformationPtr& si, std::vector<ob::State*>& states) {
  std::size_t i = 1;
  while (i + 1 < states.size()) {
    if (si->checkMotion(states[i - 1], states[i + 1])) {
      si->freeState(states[i]);
      states.erase(states.begin() + static_cast<long>(i));
    } else {
      ++i;
    }
  }
}

void subdivide(const ob::SpaceInformationPtr& si, std::vector<ob::State*>& states,
               double max_segment) {
  std::vector<ob::State*> out;
  out.reserve(states.size() * 2);
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (i > 0) {
      const double len = si->distance(states[i - 1], states[i]);
      const int pieces = static_cast<int>(len / max_segment);
      for (int k = 1; k <= pieces; ++k) {
        ob::State* s = si->allocState();
        si->getStateSpace()->interpolate(states[i - 1], states[i],
                                         static_cast<double>(k) / (pieces + 1), s);
        out.push_back(s);
      }
    }
    out.push_back(states[i]);
  }
  states.swap(out);
}

double length_of(const ob::SpaceInformationPtr& si, const std::vector<ob::State*>& states) {
  double len = 0.0;
  for (std::size_t i = 1; i < states.size(); ++i) len += si->distance(states[i - 1], states[i]);
  return len;
}

}  // namespace

TighteningStats tighten_path(const ob::SpaceInformationPtr& si, og::PathGeometric& path,
                             const ob::PlannerTerminationCondition& ptc, double max_segment,
                             int max_rounds) {
  auto& states = path.getStates();
  TighteningStats stats;
  stats.length_before = length_of(si, states);
  double length = stats.length_before;
  const auto* real = dynamic_cast<const ob::RealVectorStateSpace*>(si->getStateSpace().get());
  const unsigned dims = si->getStateDimension();
  ob::State* mid = si->allocState();
  ob::State* trial = si->allocState();
  while (stats.rounds < max_rounds && !ptc()) {
    ++stats.rounds;
    subdivide(si, states, max_segment);
    for (std::size_t i = 1; i + 1 < states.size(); ++i) {
      si->getStateSpace()->interpolate(states[i - 1], states[i + 1], 0.5, mid);
      auto accept = [&] {
        if (si->isValid(trial) && si->checkMotion(states[i - 1], trial) &&
            si->checkMotion(trial, states[i + 1])) {
          si->copyState(states[i], trial);
          return true;
        }
        return false;
      };
      bool moved = false;
      for (double step = 1.0; step >= 0.125 && !moved; step *= 0.5) {
        si->getStateSpace()->interpolate(states[i], mid, step, trial);
        moved = accept();
      }
      // Blocked against a face: slide along it, one coordinate at a time (real vector spaces;
      // the GOG obstacles are axis-aligned, so this is the move that stays clear of a face).
      if (!moved && real != nullptr) {
        for (unsigned k = 0; k < dims; ++k) {
          for (double step = 1.0; step >= 0.25; step *= 0.5) {
            si->copyState(trial, states[i]);
            double* t = trial->as<ob::RealVectorStateSpace::StateType>()->values;
            const double* m = mid->as<ob::RealVectorStateSpace::StateType>()->values;
            t[k] += step * (m[k] - t[k]);
            if (accept()) break;
          }
        }
      }
    }
    drop_redundant(si, states);
    const double now = length_of(si, states);
    // Converged when a round gains less than a hundred-thousandth.
    const bool done = length - now <= 1e-5 * length;
    length = now;
    if (done) break;
  }
  si->freeState(mid);
  si->freeState(trial);
  stats.length_after = length;
  return stats;
}

}  // namespace hpcplan::sampling
