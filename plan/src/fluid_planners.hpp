#pragma once
// Inside the fluid replanner (not installed): how each planner of the simulator runs, and the
// two families' entry points. fluid_planner.cpp dispatches; fluid_grid_planners.cpp holds the
// occupancy-grid searches, fluid_particle_planners.cpp the particle-world planners.
#include <cstdint>
#include <optional>
#include <stop_token>
#include <vector>

#include "hpcplan/graph/occupancy_graph.hpp"
#include "hpcplan/plan/fluid_planner.hpp"
#include "hpcplan/search/d_star_lite.hpp"

namespace hpcplan::plan::fluid {

// How a planner runs. The first three search the occupancy grid with the shared engine; rrtstar
// is seed 000's RRT* on the particle world; registry runs any map3d planner of the registry
// through plan_in_world, on the particle world or (world = occupancy) on the grid.
enum class Runner : int { astar_octile, astar_euclid, dstar_lite, rrtstar, registry };

// D* Lite's search between the replans of one run, and the frame it is consistent with.
struct DStarState {
  // The heuristic reads only cell coordinates, which every frame's grid shares (the box does
  // not change), so it may look at whichever frame `world` holds.
  struct Octile {
    const std::optional<env::OccupancyWorld>* world;
    LatticeCost operator()(std::uint32_t a, std::uint32_t b) const {
      return full_connectivity_free_distance(occupancy_delta(**world, a, b));
    }
  };
  std::optional<env::OccupancyWorld> world;
  // One object for the whole run: a restart resets it, keeping its arrays' memory.
  search::DStarLite<OccupancyGraph, Octile> dstar{Octile{&world}};
};

// Occupancy planners (astar_octile, astar_euclid, dstar_lite) from cell s to cell g: sets
// out.status, counters.expanded, search_cost and (D* Lite) incremental / changed_cells; returns
// the cells of the path (empty unless solved).
std::vector<std::uint32_t> search_occupancy(Runner runner, const env::OccupancyWorld& world,
                                            std::uint32_t s, std::uint32_t g, DStarState* dstar,
                                            std::stop_token cancel, FluidPlan& out);

// Seed 000's RRT* from a to b in the particle world: sets out.status (a budget spent without
// the goal is budget_exceeded) and counters.samples; returns its path.
std::vector<env::Vec<3>> rrt_star_in_particles(const env::ParticleWorld& world,
                                               const env::Vec<3>& a, const env::Vec<3>& b,
                                               const FluidPlanOptions& o, std::uint64_t seed,
                                               std::stop_token cancel, FluidPlan& out);

// A map3d planner of the registry through plan_in_world, from a to b in `world` (the particle
// world or the occupancy grid); sets out.status and counters; returns its path.
template <class W>
std::vector<env::Vec<3>> registry_planner(const W& world, const env::Vec<3>& a,
                                          const env::Vec<3>& b, const FluidPlanOptions& o,
                                          std::uint64_t seed, double resolution,
                                          std::stop_token cancel, FluidPlan& out);

}  // namespace hpcplan::plan::fluid
