"""hpcplan.map3d: 3D box maps (seeds 001 and 004's format; ``hpcplan map3d``).

    >>> import hpcplan
    >>> world = hpcplan.map3d.load("bench/maps/forest.txt")
    >>> r = world.plan(algo="thetastar")          # the map's own start and goal
    >>> r.status, r.length, r.path.shape
"""
from . import _hpcplan, _world

BoxMap = _world.make_world_class("BoxMap", "map3d", _hpcplan.BoxMap, 3,
                                 "(n, 6): each block's lower x, y, z and upper x, y, z")
BoxMap.__module__ = __name__
BoxMap.colours = property(lambda self: self._native.colours,
                          doc="(n, 3): each block's colour as the file gives it (grey: none)")


def load(path):
    """Loads a box map file (ValueError naming the file and line of anything malformed)."""
    return BoxMap(path)
