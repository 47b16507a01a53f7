"""hpcplan.grid: seed 002's planner on the GOG lattice (``hpcplan grid``), and the field.

    >>> import hpcplan
    >>> r = hpcplan.grid.solve(dims=4, algo="astar", extent=40, path=True)
    >>> r.status, r.cost, r.path.shape
    >>> field = hpcplan.grid.Field(dims=4, extent=40)
    >>> field.free(r.path).all()

The keyword arguments are hpcplan grid's options (``--max-states`` is ``max_states``), with its
ranges and defaults; the distributed options (MPI ranks) and ``--json`` are the executable's.
"""
import numpy as np

from . import _hpcplan, _options
from ._results import GridResult

_TABLE = _hpcplan.grid_options()
_SOLVE = _options.Options(_TABLE, sequences=("start", "goal"))
_FIELD_NAMES = ("dims", "extent", "seed", "threshold", "density", "gog_shift_p", "gog_shift_v")
_FIELD = _options.Options(_TABLE, only=_FIELD_NAMES)
_FIELD_SOLVE = _options.Options(_TABLE, exclude=_FIELD_NAMES, sequences=("start", "goal"))


def solve(**kwargs):
    given = _options.bind(_SOLVE_SIGNATURE, "solve", kwargs)
    stop = given.pop("stop", None)
    report, path = _hpcplan.grid_solve(_SOLVE.tokens(given), stop)
    return GridResult(report, path)


_SOLVE_SIGNATURE = _options.make(solve, _SOLVE, returns=GridResult, summary="""
Solves one query on the GOG field, as ``hpcplan grid`` does; returns a GridResult.

BFS and Dijkstra run on the dense engine where they fit (engine="auto"), A* and weighted A* on
the best-first one. The GIL is released while it runs; Ctrl-C cancels it within one expansion
or level (with checkpoint=, the dense search stops at its next level with the checkpoint
written), and KeyboardInterrupt is raised. Bad options raise ValueError with the CLI's message.""")


class Field:
    """A GOG field (seed 002 Algorithm 1) built once, for bulk queries and repeated solves.

    Immutable: any number of threads may query or solve on it at once.
    """

    def __init__(self, **kwargs):
        self._given = _options.bind(_FIELD_SIGNATURE, "Field", kwargs)
        self._native = _hpcplan.Field(_FIELD.tokens(self._given))

    dims = property(lambda self: self._native.dims)
    extent = property(lambda self: self._native.extent)
    seed = property(lambda self: self._native.seed)
    threshold = property(lambda self: self._native.threshold,
                         doc="c_v: a state is blocked when its per-axis levels sum to it or more")
    blocked_fraction = property(lambda self: self._native.blocked_fraction,
                                doc="the exact blocked fraction of the lattice")

    def free(self, states):
        """Whether each lattice state is free: an integer array of shape (n, dims) gives a bool
        array of shape (n,), one state of shape (dims,) a bool. States outside the box are not
        free."""
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
        return (f"Field(dims={self.dims}, extent={self.extent}, seed={self.seed}, "
                f"threshold={self.threshold}, blocked_fraction={self.blocked_fraction:.4f})")


_FIELD_SIGNATURE = _options.make(Field.__init__, _FIELD, trailing=(), extra_doc="",
                                 method=True, summary="The field of hpcplan grid's field options.")
_FIELD_SOLVE_SIGNATURE = _options.make(Field.solve, _FIELD_SOLVE, returns=GridResult, method=True,
                                       summary="""
Solves one query on this field (built once: no set-up per query), as grid.solve does with the
field's own options.""")
