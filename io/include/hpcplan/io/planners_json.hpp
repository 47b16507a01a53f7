#pragma once
// The planner registry as JSON (hpcplan planners --json) and as a readable listing.
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "hpcplan/plan/planner_registry.hpp"

namespace hpcplan {

// `world` empty: every planner; else only those of that setting (grid, map3d, sphere2d, ompl).
nlohmann::json to_json(const plan::PlannerRegistry& registry, std::string_view world = {});
std::string to_summary(const plan::PlannerRegistry& registry, std::string_view world = {});

}  // namespace hpcplan
