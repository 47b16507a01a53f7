"""hpcplan.grid: seed 002's planner on the GOG lattice (``hpcplan grid``), and the field; or on
an occupancy grid the caller brings (a NumPy array, a map file).

    >>> import hpcplan
    >>> r = hpcplan.grid.solve(dims=4, algo="astar", extent=40, path=True)
    >>> r.status, r.cost, r.path.shape
    >>> field = hpcplan.grid.Field(dims=4, extent=40)
    >>> field.free(r.path).all()

    >>> a = hpcplan.grid.load_map("Boston_0_256.map")     # (256, 256) bool, True = blocked
    >>> hpcplan.grid.solve(occupancy=a, start=(188, 1), goal=(12, 231)).cost

Coordinates on an occupancy grid are x first, as on the command line: x is the array's LAST
axis (a .map's column), y the one before it, so start=(x, y) is the cell a[y, x].

The keyword arguments are hpcplan grid's options (``--max-states`` is ``max_states``), with its
ranges and defaults; the distributed options (MPI ranks) and ``--json`` are the executable's.
"""
import inspect

import numpy as np

from . import _hpcplan, _options
from ._results import GridResult

_TABLE = _hpcplan.grid_options()
_SOLVE = _options.Options(_TABLE, sequences=("start", "goal"))
_FIELD_NAMES = ("dims", "extent", "seed", "threshold", "density", "gog_shift_p", "gog_shift_v")
_FIELD = _options.Options(_TABLE, only=_FIELD_NAMES)
_FIELD_SOLVE = _options.Options(_TABLE, exclude=_FIELD_NAMES + ("map",),
                                sequences=("start", "goal"))

_OCCUPANCY = inspect.Parameter("occupancy", inspect.Parameter.KEYWORD_ONLY, default=None)
_OCCUPANCY_DOC = """occupancy : numpy.ndarray, optional
    Plan on this array instead of GOG: bool or uint8 (nonzero = blocked), 1 to 16 dimensions,
    C-contiguous (read in place, never copied; anything else is refused with a ValueError
    saying what to pass). start and goal are x first: x is the array's last axis. dims, map
    and GOG's options (extent, seed, threshold, density, gog_shift_p, gog_shift_v) are
    refused with it; connectivity is seed unless given ("full" up to 4 dimensions)."""


_VALID = inspect.Parameter("valid", inspect.Parameter.KEYWORD_ONLY, default=None)
_BOUNDS = inspect.Parameter("bounds", inspect.Parameter.KEYWORD_ONLY, default=None)
_PERIODIC = inspect.Parameter("periodic", inspect.Parameter.KEYWORD_ONLY, default=None)
_VALID_DOC = """valid : callable, optional
    Plan on a configuration space of your own: valid(states) takes a (k, d) float64 array of
    states and returns k booleans (True = collision-free). The lattice engines call it once per
    batch (an expansion's successors, then the samples of their edges), holding the GIL only
    for the call. An exception from it, or an answer of the wrong shape, raises ValueError.
    Needs bounds=, cells=, start= and goal= (states in the space's coordinates);
    resolution= is the motion-check step as a fraction of the bounds' diagonal (0.01).
    The path comes back in the space's coordinates (start, lattice vertices, goal).
bounds : sequence of (low, high), optional
    valid='s axes.
periodic : sequence of bool, optional
    Which of valid='s axes wrap (angles): the lattice and every motion take the short way."""


def solve(**kwargs):
    given = _options.bind(_SOLVE_SIGNATURE, "solve", kwargs)
    stop = given.pop("stop", None)
    occupancy = given.pop("occupancy", None)
    valid = given.pop("valid", None)
    bounds = given.pop("bounds", None)
    periodic = given.pop("periodic", None)
    report, path = _hpcplan.grid_solve(_SOLVE.tokens(given), stop, occupancy, valid, bounds,
                                       periodic)
    return GridResult(report, path)


_SOLVE_SIGNATURE = _options.make(solve, _SOLVE, returns=GridResult,
                                 trailing=(_OCCUPANCY, _VALID, _BOUNDS, _PERIODIC, _options.STOP),
                                 extra_doc=_OCCUPANCY_DOC + "\n" + _VALID_DOC + "\n" +
                                 _options.STOP_DOC, summary="""
Solves one query on the GOG field, a map file (map=), an array (occupancy=), OMPL's kinematic
chain or hypercube (world="chain", dims=8) or a space of your own (valid=fn), as
``hpcplan grid`` does; returns a GridResult.

BFS and Dijkstra run on the dense engine where they fit (engine="auto"), A* and weighted A* on
the best-first one. The GIL is released while it runs; Ctrl-C cancels it within one expansion
or level (with checkpoint=, the dense search stops at its next level with the checkpoint
written), and KeyboardInterrupt is raised. Bad options raise ValueError with the CLI's message.""")


_DISTANCE = _options.Options(_TABLE, exclude=("algo", "weight", "heuristic", "no_jump_points",
                                            "checkpoint", "checkpoint_every", "restart", "path"),
                             sequences=("start", "goal"))
_ALGO = inspect.Parameter("algo", inspect.Parameter.KEYWORD_ONLY, default="bfs", annotation=str)


def distance_field(**kwargs):
    given = _options.bind(_DISTANCE_SIGNATURE, "distance_field", kwargs)
    stop = given.pop("stop", None)
    occupancy = given.pop("occupancy", None)
    with_report = given.pop("report", False)
    algo = _options.text("algo", given.pop("algo", "bfs"))
    tokens = _DISTANCE.tokens(given) + [f"--algo={algo}"]
    report, values = _hpcplan.grid_distance_field(tokens, stop, occupancy)
    return (values, report) if with_report else values


_REPORT = inspect.Parameter("report", inspect.Parameter.KEYWORD_ONLY, default=False,
                            annotation=bool)
_DISTANCE_SIGNATURE = _options.make(
    distance_field, _DISTANCE, leading=(), trailing=(_ALGO, _OCCUPANCY, _REPORT, _options.STOP),
    extra_doc="""algo : str, default bfs, one of bfs, dijkstra
    bfs: each cell's hop count (int32); dijkstra: its path cost (float32)
""" + _OCCUPANCY_DOC + """
report : bool, default False
    Also return the run's report (hpcplan grid --json's keys, with field_complete and
    field_reached): (values, report).
""" + _options.STOP_DOC, summary="""
The distance field of start: every cell's distance from it, as ``hpcplan grid --field-out``
writes it, on an array (occupancy=), a map file (map=) or the GOG field; returns a NumPy array
in NumPy order (the map's or the array's shape: a[y, x]): int32 hop counts (algo="bfs") or
float32 path costs (algo="dijkstra"), -1 for blocked and unreachable cells. start is x first.
The dense engine settles every reachable cell (goal is optional, and only reported). A stop,
time_limit or max_states ends it early: the cells not settled then read -1, and report=True's
field_complete is False. The GIL is released; Ctrl-C raises KeyboardInterrupt.""")


def load_map(path, terrain="ground"):
    """The occupancy grid of a map file as a new NumPy bool array (True = blocked), read by the
    engine's own parser (what ``hpcplan grid --map`` plans on).

    Shapes are NumPy order: (H, W) for a MovingAI .map (a[y, x]), (D, H, W) for a .3dmap voxel
    map (a[z, y, x]), the stored shape for a .npy. ``terrain="water"`` (.map only) gives the
    grid of the map's water cells, free where the file has 'W'; "ground" (the default) has
    '.', 'G' and 'S' free. Passed back as ``occupancy=``, it plans as the file does (give
    connectivity="full" for a .3dmap: map= uses the format's own, an array seed unless told).
    A file that cannot be read or parsed raises ValueError naming it (and the line)."""
    return _hpcplan.load_map(_options.text("path", path), _options.text("terrain", terrain))


class Field:
    """A GOG field (seed 002 Algorithm 1) built once, for bulk queries and repeated solves; or,
    with ``occupancy=array``, an occupancy grid built once from the array (one bit per cell:
    the Field keeps no reference to the array, which may change afterwards without changing
    the Field).

    Immutable: any number of threads may query or solve on it at once.
    """

    def __init__(self, **kwargs):
        given = _options.bind(_FIELD_SIGNATURE, "Field", kwargs)
        occupancy = given.pop("occupancy", None)
        if occupancy is None:
            self._given = given
            self._native = _hpcplan.Field(_FIELD.tokens(given))
            return
        for name, value in given.items():
            if value is not None:
                raise ValueError(f"{name}= describes the GOG field; occupancy= plans on the "
                                 "array's own shape and obstacles")
        self._given = {}
        self._native = _hpcplan.Field.from_occupancy(occupancy)

    dims = property(lambda self: self._native.dims)
    extent = property(lambda self: self._native.extent,
                      doc="the lattice's side (an occupancy grid's largest side)")
    seed = property(lambda self: self._native.seed, doc="GOG's seed (None on an occupancy grid)")
    threshold = property(lambda self: self._native.threshold,
                         doc="c_v: a state is blocked when its per-axis levels sum to it or more "
                             "(None on an occupancy grid)")
    blocked_fraction = property(lambda self: self._native.blocked_fraction,
                                doc="the exact blocked fraction of the lattice (of the array's "
                                    "cells on an occupancy grid)")
    shape = property(lambda self: self._native.shape,
                     doc="an occupancy grid's array shape, NumPy order (None for GOG)")
    grid_bytes = property(lambda self: self._native.grid_bytes,
                          doc="the bytes an occupancy grid's bits take (one bit per cell, rows "
                              "of 32 cells or more padded to 64); 0 for GOG")

    def occupancy(self):
        """An occupancy grid's cells as a new NumPy bool array (True = blocked) in the array's
        shape; ValueError on a GOG field."""
        return self._native.occupancy()

    def free(self, states):
        """Whether each lattice state is free: an integer array of shape (n, dims) gives a bool
        array of shape (n,), one state of shape (dims,) a bool. States outside the box are not
        free. On an occupancy grid a state is x first (x = the array's last axis)."""
        return self._native.free(np.asarray(states))

    def blocked(self, states):
        """The opposite of free()."""
        result = self._native.free(np.asarray(states))
        return not result if isinstance(result, bool) else ~result

    def levels(self, axis):
        """Axis ``axis``'s level (0..3) per coordinate: a read-only uint8 view of the field's
        table, valid as long as the field."""
        return self._native.levels(_options.whole("axis", axis))

    def solve(self, **kwargs):
        given = _options.bind(_FIELD_SOLVE_SIGNATURE, "Field.solve", kwargs)
        stop = given.pop("stop", None)
        tokens = _FIELD.tokens(self._given) + _FIELD_SOLVE.tokens(given)
        report, path = self._native.solve(tokens, stop)
        return GridResult(report, path)

    def __repr__(self):
        if self.shape is not None:
            return (f"Field(occupancy shape={self.shape}, "
                    f"blocked_fraction={self.blocked_fraction:.4f})")
        return (f"Field(dims={self.dims}, extent={self.extent}, seed={self.seed}, "
                f"threshold={self.threshold}, blocked_fraction={self.blocked_fraction:.4f})")


_FIELD_SIGNATURE = _options.make(Field.__init__, _FIELD, trailing=(_OCCUPANCY,),
                                 extra_doc="""occupancy : numpy.ndarray, optional
    An occupancy grid instead of GOG (then no other argument): bool or uint8 (nonzero =
    blocked), 1 to 16 dimensions, C-contiguous, read in place once.""",
                                 method=True, summary="""
The field of hpcplan grid's field options, or the occupancy grid of an array.""")
_FIELD_SOLVE_SIGNATURE = _options.make(Field.solve, _FIELD_SOLVE, returns=GridResult, method=True,
                                       summary="""
Solves one query on this field (built once: no set-up per query), as grid.solve does with the
field's own options (or its occupancy grid: start and goal x first).""")
