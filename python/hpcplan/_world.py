"""What hpcplan.map3d and hpcplan.sphere2d share: a world file loaded once, planned in with
any world planner of the registry (the options of ``hpcplan map3d|sphere2d``), and queried."""
import inspect

import numpy as np

from . import _hpcplan, _options
from ._results import PlanResult


def make_world_class(name, world, native, dims, obstacles_doc):
    table = getattr(_hpcplan, f"{world}_options")()
    options = _options.Options(table)
    point = inspect.Parameter

    class World:
        __doc__ = f"""A {dims}D world file loaded once ({world}); immutable, so any number of
        threads may plan in it at once (each plan releases the GIL).

        path : str          the file
        bounds : ndarray    (2, {dims}): the boundary's lower and upper corners
        obstacles : ndarray {obstacles_doc}
        start, goal : ndarray or None   the file's own query, if it has one
        """

        def __init__(self, path):
            self._native = native(_options.text("path", path))

        path = property(lambda self: self._native.path)
        bounds = property(lambda self: self._native.bounds)
        obstacles = property(lambda self: self._native.obstacles)
        start = property(lambda self: self._native.start)
        goal = property(lambda self: self._native.goal)

        def free(self, points):
            """Whether each point is free (the world's exact test; touching a face counts as
            blocked): an (n, dims) array gives a bool array, one point a bool."""
            return self._native.free(np.asarray(points, dtype=float))

        def segment_free(self, a, b):
            """Whether the straight segment from a to b is free (the exact test every
            returned path passed)."""
            return self._native.segment_free(a, b)

        def plan(self, start=None, goal=None, **kwargs):
            given = _options.bind(signature, f"{name}.plan", kwargs)
            stop = given.pop("stop", None)
            report, path = self._native.plan(start, goal, options.tokens(given), stop)
            return PlanResult(report, path)

        def __repr__(self):
            return f"{name}({self.path!r}, obstacles={len(self.obstacles)})"

    signature = _options.make(World.plan, options, method=True, returns=PlanResult, summary=f"""
Plans from start to goal (sequences of {dims} numbers; None: the file's own), as
``hpcplan {world}`` does; returns a PlanResult. Ctrl-C cancels it (KeyboardInterrupt).""")
    shown = [point("self", point.POSITIONAL_ONLY),
             point("start", point.POSITIONAL_OR_KEYWORD, default=None),
             point("goal", point.POSITIONAL_OR_KEYWORD, default=None)]
    World.plan.__signature__ = signature.replace(
        parameters=shown + list(signature.parameters.values()))
    World.__name__ = World.__qualname__ = name
    return World
