// Plans on a box map, runs lattice A* on the GOG field, links the MPI layer and steps the fluid:
// the things a downstream user of the installed package is most likely to do first.
#include <cstdio>

#include "hpcplan/distributed/grid_planner_mpi.hpp"
#include "hpcplan/env/box_map_io.hpp"
#include "hpcplan/mpi/communicator.hpp"
#include "hpcplan/plan/grid_planner.hpp"
#include "hpcplan/plan/world_planner.hpp"
#include "hpcplan/sph/fluid.hpp"
#include "hpcplan/sph/presets.hpp"

int main() {
  using namespace hpcplan;
  const env::BoxMap map = env::parse_box_map(
      "boundary 0 0 0 10 10 10\nblock 4 0 0 6 8 10\nstart 1 1 1\ngoal 9 1 1\n", "consumer.txt");
  plan::WorldPlanOptions o;
  o.algo = "astar";
  o.resolution = 0.5;
  const auto p = plan::plan_in_world(map.world, *map.start, *map.goal, o);

  GridProblem problem;
  problem.dims = 3;
  problem.extent = 30;
  const GridReport g = solve_grid(problem, {});

  sph::FluidOptions fo;
  fo.particles = 200;
  sph::Fluid fluid(sph::make_fluid(fo), sph::make_cpu_backend());
  const bool fluid_ok = fluid.advance_frame().problem.empty();

  std::printf("box map: %s %.3f; lattice: %s %.3f; launched by MPI: %d; fluid: %s\n",
              std::string(to_string(p.status)).c_str(), p.cost,
              std::string(to_string(g.result.status)).c_str(), g.result.cost,
              mpi::launched_by_mpi() ? 1 : 0, fluid_ok ? "ok" : "unsound");
  return p.status == Status::solved && g.result.status == Status::solved && fluid_ok ? 0 : 1;
}
