"""hpcplan.sphere2d: 2D sphere worlds (seed 003's format; ``hpcplan sphere2d``).

    >>> import hpcplan
    >>> world = hpcplan.sphere2d.load("bench/maps/sphere_world.txt")
    >>> world.plan(algo="rrtstar", time=0.5).length
"""
from . import _hpcplan, _world

SphereMap = _world.make_world_class("SphereMap", "sphere2d", _hpcplan.SphereMap, 2,
                                    "(n, 3): each obstacle's centre x, y and radius")
SphereMap.__module__ = __name__
SphereMap.boundary = property(lambda self: self._native.boundary,
                              doc="(3,): the circular boundary's centre x, y and radius")


def load(path):
    """Loads a sphere world file (ValueError naming the file and line of anything malformed)."""
    return SphereMap(path)
