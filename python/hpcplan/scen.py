"""hpcplan.scen: a MovingAI scenario file solved on its map, every row checked against its
published optimal length (``hpcplan scen``).

    >>> import hpcplan
    >>> r = hpcplan.scen.run("Boston_0_256.map.scen", algo="astar")
    >>> len(r.rows), r.mismatches, r.buckets[0]["p50_us"]
    >>> [row for row in r.rows if row["mismatch"]]

The keyword arguments are hpcplan scen's options (``--buckets`` is ``buckets``), with its ranges
and defaults; the distributed options (--split, MPI ranks) and ``--json`` are the executable's.
A mismatch is an answer, not an exception: it is in the result (``r.mismatches``,
``r.ok``), where the CLI exits 1.
"""
import inspect
import numbers

from . import _hpcplan, _options
from ._results import ScenResult

_OPTIONS = _options.Options(_hpcplan.scen_options())
_SCENARIO = inspect.Parameter("scenario", inspect.Parameter.POSITIONAL_OR_KEYWORD)


def _buckets(value):
    # "A-B" or "A" as the CLI takes them; an int, or a pair (first, last), for convenience.
    if value is None or isinstance(value, str):
        return value
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return str(int(value))
    if isinstance(value, (tuple, list)) and len(value) == 2:
        return f"{_options.whole('buckets', value[0])}-{_options.whole('buckets', value[1])}"
    raise TypeError(f"buckets must be 'A-B', 'A', an int or a pair (first, last), not "
                    f"{type(value).__name__}")


def run(scenario, **kwargs):
    given = _options.bind(_SIGNATURE, "run", dict(kwargs, scenario=scenario))
    path = _options.text("scenario", given.pop("scenario"))
    stop = given.pop("stop", None)
    if "buckets" in given:
        given["buckets"] = _buckets(given["buckets"])
    # The scenario is the command's positional argument: after "--", so that a name starting
    # with '-' is still a file.
    report, rows, cancelled = _hpcplan.scen_run(_OPTIONS.tokens(given) + ["--", path], stop)
    return ScenResult(report, rows, cancelled)


_SIGNATURE = _options.make(run, _OPTIONS, leading=(_SCENARIO,), returns=ScenResult, summary="""
Solves every problem of a MovingAI scenario file (.scen, or .3dscen for voxel maps) on its map
and checks each against its published optimal length, as ``hpcplan scen`` does (serially);
returns a ScenResult: the rows and the summary (mismatches, per-bucket times).

``scenario`` is the file; its map is the one it names, beside it, unless map= gives one.
``buckets`` takes "A-B", "A", an int or a pair. A mismatch does not raise: it is counted in the
result (r.mismatches, r.mismatch_rows, each row's "mismatch"), where the CLI exits 1. Bad input
(a missing map, a scenario for another map, a bad option) raises ValueError with the CLI's
message. The GIL is released; a stop ends it after the row under way (status 'cancelled', the
finished rows kept); Ctrl-C does the same and raises KeyboardInterrupt. csv= and output= write
what the CLI writes.""")
