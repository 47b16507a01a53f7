"""The answers of hpcplan's calls: typed views of the CLI's own JSON objects.

Each result keeps ``report``, the object ``hpcplan <command> --json`` prints for the same
options (path aside: the path is a NumPy array, ``path``), and names its parts: the status, the
cost, the counters and the timings.
"""


class GridResult:
    """A GOG lattice search's answer (``hpcplan grid --json``).

    status : str      solved, no_path, budget_exceeded, timeout, cancelled or interrupted
    cost : float      the path's length (None unless solved); hops: its moves
    quality : float   cost / straight line (seed 002 eq. 2)
    path : ndarray    (hops + 1, dims) int32 lattice states, start to goal; None unless solved
                      and path=True was asked
    counters : dict   expanded, generated, reopened, collision_checks, peak_states, peak_open
    timings : dict    time_ms (the search), setup_ms (the field and the rest)
    report : dict     every key of hpcplan grid --json (README.md, "Output")
    """

    __slots__ = ("report", "path")
    _COUNTERS = ("expanded", "generated", "reopened", "collision_checks", "peak_states",
                 "peak_open")

    def __init__(self, report, path):
        self.report, self.path = report, path

    status = property(lambda self: self.report["status"])
    cost = property(lambda self: self.report["cost"])
    hops = property(lambda self: self.report["hops"])
    quality = property(lambda self: self.report["quality"])
    engine = property(lambda self: self.report["engine"])
    start = property(lambda self: tuple(self.report["start"]))
    goal = property(lambda self: tuple(self.report["goal"]))
    counters = property(lambda self: {k: self.report[k] for k in self._COUNTERS
                                      if k in self.report})
    timings = property(lambda self: {k: self.report[k] for k in ("time_ms", "setup_ms")})

    def __repr__(self):
        return (f"GridResult(status={self.status!r}, cost={self.cost!r}, hops={self.hops!r}, "
                f"expanded={self.report['expanded']}, time_ms={self.report['time_ms']:.3f})")


class PlanResult:
    """A plan in a continuous world (``hpcplan map3d|sphere2d --json``).

    status : str     solved, no_path, budget_exceeded, timeout or cancelled
    length : float   the returned path's length (after shortcutting, when asked); raw_length:
                     as the planner returned it; both None unless solved (as GridResult.cost:
                     min() over results cannot pick a failure's 0.0)
    path : ndarray   (waypoints, dims) float64, exactly start to goal, every segment re-checked;
                     (0, dims) unless solved
    counters : dict  expanded, tree_size, collision_checks (and samples where counted)
    timings : dict   time_ms (planning and shortcutting), plan_ms (planning alone),
                     first_solution_ms (anytime planners)
    report : dict    every key of the CLI's JSON
    """

    __slots__ = ("report", "path")

    def __init__(self, report, path):
        self.report, self.path = report, path

    status = property(lambda self: self.report["status"])
    algo = property(lambda self: self.report["algo"])
    length = property(lambda self: self._solved_value("length"))
    raw_length = property(lambda self: self._solved_value("raw_length"))
    counters = property(lambda self: {k: self.report[k] for k in
                                      ("expanded", "tree_size", "collision_checks", "samples")
                                      if k in self.report})
    timings = property(lambda self: {k: self.report[k] for k in
                                     ("time_ms", "plan_ms", "first_solution_ms")
                                     if k in self.report})

    def _solved_value(self, key):
        return self.report[key] if self.report["status"] == "solved" else None

    def __repr__(self):
        return (f"PlanResult(status={self.status!r}, algo={self.algo!r}, "
                f"length={self.length!r}, waypoints={len(self.path)})")


class SimResult:
    """A simulator invocation's answer (``hpcplan sim --json``, and its CSVs' rows).

    status : str      ok, or interrupted (a stop or Ctrl-C ended it; runs holds those
                      finished before)
    runs : list       one dict per run, the columns of ``--csv`` (seed 000's first), with
                      typed values (None where the CSV cell is empty)
    replans : list    one dict per replan, the columns of ``--replan-log``
    aggregate : dict  the JSON's aggregate over the runs (success rate, times, contacts, ...)
    report : dict     the whole JSON, its per-run rows included (report["runs"])
    """

    __slots__ = ("report", "runs", "replans")

    def __init__(self, report, runs, replans):
        self.report, self.runs, self.replans = report, runs, replans

    status = property(lambda self: self.report["status"])
    aggregate = property(lambda self: self.report["aggregate"])

    def __repr__(self):
        return f"SimResult(status={self.status!r}, runs={len(self.runs)})"


class ScenResult:
    """A scenario run's answer (``hpcplan scen --json``, and its ``--csv`` rows).

    rows : list          one dict per problem, in file order: row (0-based among the file's
                         problems), bucket, start and goal (tuples, x first), optimal (the
                         published length), cost (0.0 unless solved), status, expanded, hops,
                         time_us, mismatch (bool)
    mismatches : int     rows whose answer breaks the algorithm's promise against the
                         published optimum (plan/scenario_run.hpp); mismatch_rows: their
                         indices. A mismatch is returned, never raised (the CLI exits 1)
    buckets : list       per bucket: rows, mismatches, p50_us, p95_us, max_us, mean_expanded
    status : str         ok, or cancelled (a stop ended it: rows holds the rows finished
                         before, and the summary is theirs)
    ok : bool            status ok and no mismatch: what the CLI's exit 0 means
    report : dict        the whole ``hpcplan scen --json`` object
    """

    __slots__ = ("report", "rows", "cancelled")

    def __init__(self, report, rows, cancelled=False):
        self.report, self.rows, self.cancelled = report, rows, cancelled

    status = property(lambda self: "cancelled" if self.cancelled else "ok")
    mismatches = property(lambda self: self.report["mismatches"])
    mismatch_rows = property(lambda self: self.report["mismatch_rows"])
    buckets = property(lambda self: self.report["buckets"])
    ok = property(lambda self: not self.cancelled and self.report["mismatches"] == 0)

    def __repr__(self):
        return (f"ScenResult(status={self.status!r}, rows={len(self.rows)}, "
                f"mismatches={self.mismatches}, scenario={self.report['scenario']!r})")
