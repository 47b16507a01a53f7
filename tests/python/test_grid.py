"""hpcplan.grid against the CLI, an independent GOG and Dijkstra's costs."""
import math

import numpy as np
import pytest

import hpcplan
from conftest import TIMING_KEYS, OracleGog, check_seed_rule_path, cli_error, cli_json, without

# Each row: the keyword arguments, and the same options on the command line.
CASES = [
    dict(dims=2),
    dict(dims=3, algo="bfs", extent=30),
    dict(dims=4, algo="dijkstra", extent=16, engine="sparse"),
    dict(dims=4, algo="dijkstra", extent=16, engine="dense", threads=1),
    dict(dims=3, algo="wastar", weight=1.5, extent=40, seed=7),
    dict(dims=2, extent=60, start=(0, 5), goal=(45, 47), heuristic="euclidean"),
    dict(dims=5, extent=12, threshold=9, gog_shift_v=2),
    dict(dims=2, extent=50, no_jump_points=True, connectivity="full"),
]


def argv(kw):
    out = []
    for name, value in kw.items():
        option = "--" + name.replace("_", "-")
        if value is True:
            out.append(option)
        elif isinstance(value, tuple):
            out += [option, ",".join(map(str, value))]
        else:
            out += [option, str(value)]
    return out


@pytest.mark.parametrize("kw", CASES, ids=lambda kw: ",".join(f"{k}={v}" for k, v in kw.items()))
def test_solve_answers_what_the_cli_answers(kw):
    r = hpcplan.grid.solve(**kw, path=True)
    cli = cli_json("grid", *argv(kw), "--path")
    # max_states is derived from the memory available when each process started.
    ignore = TIMING_KEYS | {"max_states", "path"}
    assert without(r.report, ignore) == without(cli, ignore)
    assert r.status == cli["status"] == "solved"
    assert r.path.dtype == np.int32 and r.path.shape == (cli["hops"] + 1, kw["dims"])
    assert r.path.tolist() == cli["path"]


def test_the_result_names_its_parts():
    r = hpcplan.grid.solve(dims=3, extent=40, path=True)
    assert r.cost == r.report["cost"] and r.hops == len(r.path) - 1
    assert set(r.counters) == {"expanded", "generated", "reopened", "collision_checks",
                               "peak_states", "peak_open"}
    assert r.timings["time_ms"] > 0 and r.timings["setup_ms"] >= 0
    assert r.start == tuple(r.path[0]) and r.goal == tuple(r.path[-1])
    assert "solved" in repr(r)
    assert hpcplan.grid.solve(dims=3, extent=40).path is None  # path=False: none kept


@pytest.mark.parametrize("dims,extent,seed", [(2, 80, 1), (3, 30, 5), (4, 14, 3)])
def test_astar_equals_dijkstra_and_every_path_is_valid(dims, extent, seed):
    oracle = OracleGog(dims, extent, seed)
    results = {}
    for algo, engine in [("astar", "sparse"), ("dijkstra", "sparse"), ("dijkstra", "dense")]:
        r = hpcplan.grid.solve(dims=dims, extent=extent, seed=seed, algo=algo, engine=engine,
                               path=True)
        assert r.status == "solved"
        length = check_seed_rule_path(oracle, r.path, r.start, r.goal)
        assert math.isclose(length, r.cost, rel_tol=1e-12)
        results[(algo, engine)] = r.cost
    assert len({round(c, 9) for c in results.values()}) == 1, results
    w = hpcplan.grid.solve(dims=dims, extent=extent, seed=seed, algo="wastar", weight=2.0,
                           path=True)
    check_seed_rule_path(oracle, w.path, w.start, w.goal)
    assert results[("dijkstra", "sparse")] <= w.cost <= 2.0 * results[("dijkstra", "sparse")] + 1e-9


def test_bfs_gives_the_fewest_moves():
    a = hpcplan.grid.solve(dims=3, extent=30, algo="bfs", engine="dense", path=True)
    b = hpcplan.grid.solve(dims=3, extent=30, algo="bfs", engine="sparse", path=True)
    assert a.hops == b.hops
    check_seed_rule_path(OracleGog(3, 30), a.path, a.start, a.goal)


@pytest.mark.parametrize("dims,extent,kw", [(2, 200, {}), (4, 20, {"seed": 9}),
                                            (6, 8, {"gog_shift_p": 1, "gog_shift_v": 1}),
                                            (3, 50, {"density": 0.25})])
def test_field_answers_the_formula(dims, extent, kw):
    field = hpcplan.grid.Field(dims=dims, extent=extent, **kw)
    oracle = OracleGog(dims, extent, kw.get("seed", 1), kw.get("gog_shift_p", 4),
                       kw.get("gog_shift_v", 3), kw.get("density", 0.40))
    assert field.threshold == oracle.threshold
    rng = np.random.default_rng(1)
    states = rng.integers(-2, extent + 2, size=(5000, dims))
    free = field.free(states)
    assert free.dtype == np.bool_ and free.shape == (5000,)
    assert free.tolist() == [oracle.free(s) for s in states]
    assert (field.blocked(states) == ~free).all()
    assert field.free(states[0]) == oracle.free(states[0])  # one state: a bool
    for axis in range(dims):
        levels = field.levels(axis)
        assert levels.tolist() == oracle.levels[axis].tolist()
        assert not levels.flags.writeable
    # The exact blocked fraction, counted over the whole lattice where it is small.
    if extent ** dims <= 1_000_000:
        grid = np.stack(np.meshgrid(*[np.arange(extent)] * dims, indexing="ij"), -1)
        blocked = ~field.free(grid.reshape(-1, dims))
        assert math.isclose(blocked.mean(), field.blocked_fraction, rel_tol=1e-9)


def test_field_refuses_what_is_not_a_lattice_state():
    field = hpcplan.grid.Field(dims=3, extent=10)
    with pytest.raises(TypeError, match="integer array"):
        field.free(np.zeros((4, 3)))
    with pytest.raises(ValueError, match=r"shape \(3,\) or \(n, 3\)"):
        field.free(np.zeros((4, 2), dtype=int))
    with pytest.raises(ValueError, match=r"axis 3 is not in \[0, 3\)"):
        field.levels(3)


def test_field_solve_equals_solve():
    field = hpcplan.grid.Field(dims=3, extent=40, seed=4)
    for algo in ("astar", "bfs", "dijkstra"):
        a = field.solve(algo=algo, path=True)
        b = hpcplan.grid.solve(dims=3, extent=40, seed=4, algo=algo, path=True)
        ignore = TIMING_KEYS | {"max_states"}
        assert without(a.report, ignore) == without(b.report, ignore)
        assert (a.path == b.path).all()
        assert field.free(a.path).all()
    with pytest.raises(TypeError, match="unexpected keyword argument 'extent'"):
        field.solve(extent=50)


def test_output_file_is_the_cli_json(tmp_path):
    out = tmp_path / "r.json"
    r = hpcplan.grid.solve(dims=2, output=str(out))
    import json
    assert without(json.load(open(out)), TIMING_KEYS) == without(r.report, TIMING_KEYS)


@pytest.mark.parametrize("kw,args", [
    (dict(dims=0), ["--dims", "0"]),
    (dict(dims=2, extent=1), ["--dims", "2", "--extent", "1"]),
    (dict(dims=2, algo="nope"), ["--dims", "2", "--algo", "nope"]),
    (dict(dims=2, engine="fast"), ["--dims", "2", "--engine", "fast"]),
    (dict(dims=2, start=(0,)), ["--dims", "2", "--start", "0"]),
    (dict(dims=2, density=float("nan")), ["--dims", "2", "--density", "nan"]),
    (dict(dims=2, seed=-1), ["--dims", "2", "--seed=-1"]),
    (dict(dims=2, extent=60, start=(8, 16)), ["--dims", "2", "--extent", "60", "--start", "8,16"]),
    (dict(dims=3, algo="astar", checkpoint="/tmp/x.ck"),
     ["--dims", "3", "--algo", "astar", "--checkpoint", "/tmp/x.ck"]),
])
def test_bad_input_is_a_value_error_with_the_cli_message(kw, args):
    message = cli_error("grid", *args)
    with pytest.raises(ValueError) as e:
        hpcplan.grid.solve(**kw)
    assert str(e.value) == message


def test_empty_texts_are_what_the_cli_makes_of_them(tmp_path):
    # An empty --output is "none" to the CLI, an empty --algo unknown, as from the shell.
    assert hpcplan.grid.solve(dims=2, output="").status == "solved"
    message = cli_error("grid", "--dims", "2", "--algo", "")
    with pytest.raises(ValueError) as e:
        hpcplan.grid.solve(dims=2, algo="")
    assert str(e.value) == message
    assert hpcplan.grid.solve(dims=2, path=np.bool_(True)).path is not None


def test_wrong_types_are_type_errors():
    with pytest.raises(ValueError, match=r"--dims is required \(or --map FILE to plan on a map\)"):
        hpcplan.grid.solve()
    with pytest.raises(TypeError, match="unexpected keyword argument 'dim'"):
        hpcplan.grid.solve(dims=2, dim=2)
    with pytest.raises(TypeError, match="dims must be an integer, not float"):
        hpcplan.grid.solve(dims=2.0)
    with pytest.raises(TypeError, match="path must be a bool"):
        hpcplan.grid.solve(dims=2, path=1)
    with pytest.raises(TypeError, match="start must be a sequence"):
        hpcplan.grid.solve(dims=2, start="0,0")
    with pytest.raises(TypeError, match="start must be a sequence of numbers, not set"):
        hpcplan.grid.solve(dims=2, start={0, 1})  # no order: which axis is 0?
    with pytest.raises(TypeError, match="dims must be an integer, not bool"):
        hpcplan.grid.solve(dims=np.True_)  # as dims=True
    assert hpcplan.grid.solve(dims=np.int64(2), extent=np.uint16(20)).status == "solved"
