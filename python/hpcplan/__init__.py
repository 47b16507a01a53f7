"""hpcplan: HPC motion planning on implicit grids, continuous worlds and a live SPH fluid.

The engine of the ``hpcplan`` executable, called in-process:

    hpcplan.grid      seed 002's lattice planner (solve) on the GOG field (Field) or on an
                      occupancy array or map file (occupancy=, map=, load_map)
    hpcplan.scen      MovingAI scenario files checked against their published optima (run)
    hpcplan.map3d     3D box maps (load, then plan)
    hpcplan.sphere2d  2D sphere worlds (load, then plan)
    hpcplan.sph       the SPH fluid (Fluid), its particles as NumPy views
    hpcplan.sim       seed 000's replanning simulator (run)
    hpcplan.planners  every planner of the registry, with its options

Every call takes the executable's options as keyword arguments (``--max-states`` is
``max_states``) with its ranges and defaults; bad input raises ValueError with the CLI's
message, a run failure RuntimeError. Long calls release the GIL; Ctrl-C stops them through the
engine's stop token (KeyboardInterrupt), and a StopSource ends them from another thread.
"""
from . import _hpcplan
from ._hpcplan import StopSource, __version__
from ._results import GridResult, PlanResult, ScenResult, SimResult
from . import grid, map3d, scen, sim, sph, sphere2d

__all__ = ["__version__", "StopSource", "GridResult", "PlanResult", "ScenResult", "SimResult",
           "grid", "map3d", "sphere2d", "sph", "sim", "scen", "planners"]


def planners(world=None):
    """The planner registry (``hpcplan planners --json``): each planner's name, family,
    settings and options with their types, ranges, defaults and help; ``world`` (grid, map3d,
    sphere2d, ompl, sim) keeps one setting's."""
    return _hpcplan.planners(world or "")
