"""hpcplan.sph: the SPH fluid (seed 000's dynamic obstacles; ``hpcplan sph``), stepped from
Python, its particles read as NumPy views of the engine's own arrays.

    >>> import hpcplan
    >>> fluid = hpcplan.sph.Fluid(preset="water", scenario="dambreak", particles=4000)
    >>> fluid.step(frames=10)
    >>> x = fluid.positions            # (n, 3) float64, read-only, no copy
    >>> fluid.write_vtk("out")         # the current frame into out/fluid.pvd
    >>> fluid.checkpoint("run.ck")     # hpcplan sph --restart run.ck continues it, and so does
    >>> again = hpcplan.sph.Fluid.restart("run.ck")

Views and their lifetime: ``positions``, ``velocities`` (both (n, 3)), ``density``,
``pressure``, ``ids`` and ``wall`` (both (n,)) are read-only arrays over the particles'
storage, made without a copy; they keep the fluid alive. They are valid until the next step:
the fluid reorders its particles by cell as it steps (``ids`` names each particle's index at
creation), and afterwards a view taken before shows an earlier ordering's storage, not the
current state. Take them again after each step. Walls (water preset) are particles too:
``fluid.wall == 0`` selects the fluid.
"""
import inspect

from . import _hpcplan, _options

_OPTIONS = _options.Options(_hpcplan.fluid_options())
_RESTART = _options.Options(_hpcplan.fluid_options(), only=("threads", "backend", "memory_mb"))


class Fluid:
    """A fluid and its run: the problem, the frames so far, the scenario's probes (the dam
    break's front, the MARIN gauges).

    One thread uses a Fluid at a time (a step on one thread while another reads or steps it
    raises RuntimeError).
    """

    def __init__(self, **kwargs):
        given = _options.bind(_INIT_SIGNATURE, "Fluid", kwargs)
        self._native = _hpcplan.Fluid(_OPTIONS.tokens(given))

    @classmethod
    def restart(cls, path, **kwargs):
        """The run saved in checkpoint ``path`` (by checkpoint() or ``hpcplan sph
        --checkpoint``), continued bit for bit; threads, backend and memory_mb as for a new
        fluid."""
        given = _options.bind(_RESTART_SIGNATURE, "Fluid.restart", kwargs)
        fluid = cls.__new__(cls)
        fluid._native = _hpcplan.Fluid.restart(_options.text("path", path),
                                               _RESTART.tokens(given))
        return fluid

    def step(self, frames=1, *, stop=None):
        """Advances ``frames`` frames of 0.02 s (CFL-limited substeps) with the GIL released.
        Returns this call's report: frame (the number of the last frame done), substeps,
        frame_ms, stable (False, with problem, once a frame ends unsound), interrupted (a stop
        or Ctrl-C ended it at a frame's end; Ctrl-C then raises KeyboardInterrupt)."""
        frames = _options.whole("frames", frames)
        if frames < 1:
            raise ValueError("frames must be at least 1")
        return self._native.step(frames, stop)

    def report(self):
        """``hpcplan sph --json``'s object for the frames run so far."""
        return self._native.report()

    def write_vtk(self, dir):
        """Writes the current frame into ``dir`` (fluid_<frame>.vtu, boxes_<frame>.vtu and the
        series fluid.pvd, as hpcplan sph --vtk does; ParaView opens fluid.pvd). Repeated calls
        add frames to the series."""
        self._native.write_vtk(_options.text("dir", dir))

    def checkpoint(self, path):
        """Saves the whole state, atomically (RuntimeError if the state is unsound)."""
        self._native.checkpoint(_options.text("path", path))

    frame = property(lambda self: self._native.frame, doc="frames done")
    time = property(lambda self: self._native.time, doc="simulated seconds")
    substeps = property(lambda self: self._native.substeps)
    size = property(lambda self: self._native.size, doc="particles, walls included")
    fluid_count = property(lambda self: self._native.fluid_count)
    backend = property(lambda self: self._native.backend)
    threads = property(lambda self: self._native.threads, doc="OpenMP threads a step runs")
    options = property(lambda self: self._native.options,
                       doc="the problem: preset, scenario, particles, seed")
    restarted_at_frame = property(lambda self: self._native.restarted_at_frame)
    positions = property(lambda self: self._native.positions,
                         doc="(n, 3) float64 view, read-only, valid until the next step")
    velocities = property(lambda self: self._native.velocities,
                          doc="(n, 3) float64 view, read-only, valid until the next step")
    density = property(lambda self: self._native.density,
                       doc="(n,) float64 view, read-only, valid until the next step")
    pressure = property(lambda self: self._native.pressure,
                        doc="(n,) float64 view, read-only, valid until the next step")
    ids = property(lambda self: self._native.ids,
                   doc="(n,) uint32 view: each particle's index at creation")
    wall = property(lambda self: self._native.wall,
                    doc="(n,) uint8 view: 0 for fluid, else a wall particle")
    boxes = property(lambda self: self._native.boxes,
                     doc="(boxes, 9) copy: lower x, y, z, upper x, y, z, velocity x, y, z")
    probes = property(lambda self: self._native.probes,
                      doc="the scenario's probe columns and rows so far (front or gauges)")

    def __repr__(self):
        o = self.options
        return (f"Fluid(preset={o['preset']!r}, scenario={o['scenario']!r}, "
                f"particles={self.fluid_count}, frame={self.frame}, time={self.time:.3f})")


_INIT_SIGNATURE = _options.make(Fluid.__init__, _OPTIONS, method=True, trailing=(), extra_doc="",
                                summary="""
A new fluid of hpcplan sph's problem options, built with the GIL released.""")
_RESTART_SIGNATURE = _options.make(Fluid.restart.__func__, _RESTART, trailing=(), extra_doc="",
                                   summary=Fluid.restart.__doc__)
Fluid.restart.__func__.__signature__ = inspect.Signature(
    [inspect.Parameter("cls", inspect.Parameter.POSITIONAL_ONLY),
     inspect.Parameter("path", inspect.Parameter.POSITIONAL_OR_KEYWORD)]
    + list(_RESTART_SIGNATURE.parameters.values()))
