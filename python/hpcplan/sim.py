"""hpcplan.sim: seed 000's simulator, a robot replanning through the live fluid
(``hpcplan sim``).

    >>> import hpcplan
    >>> r = hpcplan.sim.run(particles=1500, scenario="particles", algo="astar", runs=3, seed=1)
    >>> r.aggregate["success_rate"], [row["time_to_goal_s"] for row in r.runs]
"""
from . import _hpcplan, _options
from ._results import SimResult

_OPTIONS = _options.Options(_hpcplan.sim_options())


def run(**kwargs):
    given = _options.bind(_SIGNATURE, "run", kwargs)
    stop = given.pop("stop", None)
    report, runs, replans = _hpcplan.sim_run(_OPTIONS.tokens(given), stop)
    return SimResult(report, runs, replans)


_SIGNATURE = _options.make(run, _OPTIONS, returns=SimResult, summary="""
Runs the simulator as ``hpcplan sim`` does; returns a SimResult (the per-run rows, the per-replan
rows and the aggregate). The GIL is released; a stop or Ctrl-C ends it after the current frame
(the run under way dropped, the finished ones kept; Ctrl-C then raises KeyboardInterrupt).
File options (csv=, trajectory=, vtk=, checkpoint=, ...) write what the CLI writes.""")
