#pragma once
// The planner options of hpcplan map3d and hpcplan sphere2d that every front end shares (the
// executable; the Python module's Map3D.plan and Sphere2D.plan): --algo and the registry's
// parameters of the world planners. The executable adds the map, the query and its outputs.
#include <string>

#include <CLI/CLI.hpp>

#include "hpcplan/plan/world_planner.hpp"

namespace hpcplan::cli {

// The grid searches' default cell of `world` ("map3d" 0.1, "sphere2d" 0.25).
double default_resolution(const std::string& world);

// Registers --algo and the planners' parameters on `command`, their defaults those of `world`.
void add_world_planner_options(CLI::App* command, plan::WorldPlanOptions& options,
                               const std::string& world);

}  // namespace hpcplan::cli
