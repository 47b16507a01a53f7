"""The package as a whole: signatures and help from the CLI's options, the registry."""
import inspect
import json
import re

import pytest

import hpcplan
from conftest import cli_error, run_cli

# The executable's own options, which the Python functions have no use for.
CLI_ONLY = {"grid": {"json", "mode", "owner_coarsen", "owner_slabs", "owner_cuts", "batch",
                     "batch_age_ms", "sync_every", "sent_filter", "compare_serial",
                     "simulate_ranks", "simulate_coarsen", "field_out"},
            "map3d": {"map", "start", "goal", "json", "path_out", "output"},
            "sim": {"json"}}


def cli_options(command):
    """The long option names `hpcplan <command> --help` lists, as keywords."""
    text = run_cli(command, "--help").stdout
    return {m.replace("-", "_") for m in re.findall(r"^\s+(?:-\w,)?--([a-z][a-z0-9-]*)", text,
                                                     re.M)} - {"help"}


@pytest.mark.parametrize("command,function", [
    ("grid", hpcplan.grid.solve), ("map3d", hpcplan.map3d.BoxMap.plan),
    ("sim", hpcplan.sim.run)])
def test_keywords_are_the_cli_options(command, function):
    names = set(inspect.signature(function).parameters) - {"self", "start", "goal", "stop"}
    if command == "grid":  # occupancy= and a space's valid=, bounds=, periodic= are the
        names -= {"occupancy", "valid", "bounds", "periodic"}  # module's own: no command line
    expected = cli_options(command) - CLI_ONLY[command]
    if command != "map3d":
        names |= {"start", "goal"} & cli_options(command)
    assert names == expected


def test_fluid_keywords_are_the_sph_problem_options():
    names = set(inspect.signature(hpcplan.sph.Fluid).parameters) - {"stop"}
    assert names == {"preset", "scenario", "particles", "seed", "threads", "backend", "memory_mb"}
    assert names <= cli_options("sph")


def test_help_shows_types_defaults_ranges_and_choices():
    doc = hpcplan.grid.solve.__doc__
    assert "extent : int, default 100, in [2, 65535]  (--extent)" in doc
    assert "engine : str, default auto, one of auto, dense, sparse  (--engine)" in doc
    # dims is required only without a map (map=, occupancy=): the call says so if missing.
    assert "dims : int, in [1, 16]  (--dims)" in doc
    sig = inspect.signature(hpcplan.grid.solve)
    assert sig.parameters["extent"].default == 100 and sig.parameters["extent"].annotation is int
    assert sig.parameters["density"].default == 0.4
    assert sig.parameters["dims"].default is None  # required only without map= or occupancy=
    assert all(p.kind is inspect.Parameter.KEYWORD_ONLY for p in sig.parameters.values())
    plan = inspect.signature(hpcplan.map3d.BoxMap.plan)
    assert plan.parameters["resolution"].default == 0.1
    assert inspect.signature(hpcplan.sphere2d.SphereMap.plan).parameters["resolution"].default \
        == 0.25
    text = pydoc_text(hpcplan.grid.solve)
    assert "solve(*, dims: Optional[int] = None, map: Optional[str] = None, world: Optional[str] " \
        "= None, cells: int = 0" in text
    assert "algo: str = 'astar'" in text
    # The registry's parameters carry the registry's ranges and defaults.
    declared = {p["name"]: p for planner in hpcplan.planners("map3d")["planners"]
                for p in planner["params"]}
    assert plan.parameters["time"].default == float(declared["time"]["default"])
    lo, hi = declared["time"]["range"]
    assert f"time : float, default {declared['time']['default']}" in hpcplan.map3d.BoxMap.plan.__doc__


def pydoc_text(obj):
    import pydoc
    return pydoc.plaintext.document(obj)


def test_planners_is_the_registry():
    cli = json.loads(run_cli("planners", "--json").stdout)
    assert hpcplan.planners() == cli
    cli = json.loads(run_cli("planners", "--json", "--world", "sim").stdout)
    assert hpcplan.planners("sim") == cli
    message = cli_error("planners", "--world", "nope")
    with pytest.raises(ValueError) as e:
        hpcplan.planners("nope")
    assert str(e.value) == message


def test_the_package_lists_its_parts():
    for name in hpcplan.__all__:
        assert hasattr(hpcplan, name)
    assert re.fullmatch(r"\d+\.\d+\.\d+", hpcplan.__version__)
    assert "hpcplan.grid" in hpcplan.__doc__
