"""Configuration spaces from Python: hpcplan.grid.solve(world="chain" | "hypercube", dims=...)
against the CLI (hpcplan grid --world), and spaces defined by a validity function
(valid=fn, bounds=, periodic=) against the same space planned from C++ (the hypercube's rule
written in NumPy), with its errors."""
import numpy as np
import pytest

import hpcplan
from conftest import TIMING_KEYS, cli_json, without


def test_the_chain_and_the_hypercube_answer_as_the_cli_does():
    for world, dims in (("chain", 5), ("hypercube", 6)):
        r = hpcplan.grid.solve(world=world, dims=dims, path=True, max_states=10**7)
        cli = cli_json("grid", "--world", world, "--dims", str(dims), "--path",
                       "--max-states", str(10**7))
        assert r.status == "solved"
        assert without(r.report, TIMING_KEYS) == without(cli, TIMING_KEYS | {"path"})
        # The path in the space's own coordinates: start and goal as asked, radians or [0, 1].
        assert r.path.shape == (len(cli["path_states"]), dims)
        np.testing.assert_allclose(r.path, np.array(cli["path_states"]))
        np.testing.assert_allclose(r.path[0], r.report["cspace"]["start"])
        np.testing.assert_allclose(r.path[-1], r.report["cspace"]["goal"])
        assert r.report["cspace"]["path_rechecked"]


def hypercube_valid(states):
    """OMPL's hypercube rule, vectorised over a (k, d) batch of states."""
    s = np.asarray(states)
    d = s.shape[1]
    ok = np.zeros(len(s), bool)
    for k in range(d):
        low = np.all(s[:, :k] <= 0.1, axis=1)
        high = np.all(s[:, k + 1:] >= 0.9, axis=1)
        inside = (s[:, k] >= 0.0) & (s[:, k] <= 1.0)
        ok |= low & high & inside
    return ok


def test_a_space_defined_in_python_plans_as_the_same_space_in_cpp():
    calls = []

    def valid(states):
        calls.append(len(states))
        return hypercube_valid(states)

    dims = 4
    mine = hpcplan.grid.solve(valid=valid, bounds=[(0.0, 1.0)] * dims, cells=11,
                              start=[0.0] * dims, goal=[1.0] * dims, resolution=0.001, path=True)
    cpp = hpcplan.grid.solve(world="hypercube", dims=dims, cells=11, path=True)
    assert mine.status == cpp.status == "solved"
    assert mine.cost == pytest.approx(cpp.cost, abs=1e-9)
    assert mine.report["expanded"] == cpp.report["expanded"]
    np.testing.assert_allclose(mine.path, cpp.path)
    # Called per batch, not per state: far fewer calls than states tested. (The function also
    # answers the ends' checks and the returned path's re-check, which the search's count
    # leaves out.)
    assert sum(calls) >= mine.report["collision_checks"]
    assert len(calls) < sum(calls) / 4


def test_a_periodic_space_crosses_its_seam():
    def valid(states):
        return np.abs(states[:, 0]) >= 2.0

    r = hpcplan.grid.solve(valid=valid, bounds=[(-np.pi, np.pi)] * 2, periodic=[True, True],
                           cells=64, start=(-2.5, 0.3), goal=(2.5, 0.3), path=True)
    assert r.status == "solved"
    assert np.all(np.abs(r.path[:, 0]) >= 2.0 - 1e-12)
    assert np.any(np.abs(np.diff(r.path[:, 0])) > np.pi), "the path never wraps"
    assert r.cost < 2 * np.pi - 5.0 + 0.25


@pytest.mark.parametrize("fn, message", [
    (lambda q: 1 / 0, "valid= raised ZeroDivisionError"),
    (lambda q: np.ones(len(q) + 1, bool), "valid= must return"),
    (lambda q: np.ones((len(q), 2), bool), "valid= must return"),
    (lambda q: np.full(len(q), 0.5), "valid= must return"),
])
def test_a_validity_function_that_fails_raises_value_error(fn, message):
    with pytest.raises(ValueError, match=message) as e:
        hpcplan.grid.solve(valid=fn, bounds=[(0, 1)] * 2, cells=8, start=(0.1, 0.1),
                           goal=(0.9, 0.9))
    assert "\n" not in str(e.value)


def test_bad_spaces_are_refused_with_one_line():
    ok = dict(bounds=[(0, 1)] * 2, cells=8, start=(0.1, 0.1), goal=(0.9, 0.9))
    cases = [
        (dict(ok, bounds=None), "bounds="),
        (dict(ok, bounds=[(0, 1, 2)] * 2), "pairs"),
        (dict(ok, periodic=[True]), "periodic="),
        (dict(ok, cells=0), "cells="),
        (dict(ok, start=(0.1, 0.1, 0.1)), "--start needs 2 values"),
        (dict(ok, goal=(2.0, 0.5)), "outside the bounds"),
    ]
    for kwargs, message in cases:
        with pytest.raises(ValueError, match=message):
            hpcplan.grid.solve(valid=lambda q: np.ones(len(q), bool), **kwargs)
    with pytest.raises(ValueError, match="in collision"):
        hpcplan.grid.solve(valid=lambda q: q[:, 0] > 0.5, **ok)
    with pytest.raises(ValueError, match="must be in 2..16"):
        hpcplan.grid.solve(world="chain", dims=1)
    with pytest.raises(ValueError, match="unknown configuration space"):
        hpcplan.grid.solve(world="arm", dims=4)


def test_ctrl_c_inside_a_validity_function_is_a_keyboard_interrupt():
    import os
    import signal

    calls = []

    def interrupted(states):
        # Ctrl-C arrives while the engine is inside the function (a handshake, not a timer):
        # Python's handler raises KeyboardInterrupt here, in the function.
        calls.append(len(states))
        if len(calls) == 3:
            os.kill(os.getpid(), signal.SIGINT)
        return np.ones(len(states), bool)

    with pytest.raises(KeyboardInterrupt):
        hpcplan.grid.solve(valid=interrupted, bounds=[(0, 1)] * 3, cells=200, start=(0, 0, 0),
                           goal=(1, 1, 1), algo="dijkstra")
    assert len(calls) == 3

    def leave(states):
        raise SystemExit(3)

    with pytest.raises(SystemExit):
        hpcplan.grid.solve(valid=leave, bounds=[(0, 1)] * 2, cells=8, start=(0, 0), goal=(1, 1))


def test_integer_answers_are_true_when_nonzero():
    r = hpcplan.grid.solve(valid=lambda q: np.full(len(q), 256), bounds=[(0, 1)] * 2, cells=8,
                           start=(0, 0), goal=(1, 1))
    assert r.status == "solved"
    with pytest.raises(ValueError, match="bounds= must be"):
        hpcplan.grid.solve(valid=lambda q: np.ones(len(q), bool), bounds="ab", cells=8,
                           start=(0, 0), goal=(1, 1))
    with pytest.raises(ValueError, match="periodic= must be"):
        hpcplan.grid.solve(valid=lambda q: np.ones(len(q), bool), bounds=[(0, 1)] * 2,
                           periodic=3, cells=8, start=(0, 0), goal=(1, 1))
