"""Shared by the Python API's tests: the CLI they compare against, and an independent GOG.

The tests run with Debian's python3 and the build tree's package (tests/python/CMakeLists.txt
sets PYTHONPATH, HPCPLAN_BIN and HPCPLAN_MAPS_DIR).
"""
import json
import os
import subprocess

import numpy as np
import pytest

BIN = os.environ.get("HPCPLAN_BIN", "build/bin/hpcplan")
MAPS = os.environ.get("HPCPLAN_MAPS_DIR", "bench/maps")

# Keys of a report that are measurements of the run, not its answer.
TIMING_KEYS = {"time_ms", "setup_ms", "plan_ms", "first_solution_ms", "seconds",
               "ms_per_frame_median", "ms_per_frame_max", "grid_ms_per_frame_median",
               "particle_steps_per_s", "serial", "rank_search_ms"}


def run_cli(*args, check=True):
    """The CLI's exit code, stdout and stderr for these arguments."""
    p = subprocess.run([BIN, *map(str, args)], capture_output=True, text=True, timeout=600)
    if check and p.returncode != 0:
        raise AssertionError(f"hpcplan {' '.join(map(str, args))}: exit {p.returncode}: "
                             f"{p.stderr}")
    return p


def cli_json(*args):
    return json.loads(run_cli(*args, "--json").stdout)


def cli_error(*args):
    """The one-line message of a refused command (exit 2), without the 'hpcplan: error: '."""
    p = run_cli(*args, check=False)
    assert p.returncode == 2, (args, p.returncode, p.stderr)
    line = p.stderr.strip()
    assert line.startswith("hpcplan: error: "), line
    return line[len("hpcplan: error: "):]


def without(d, keys):
    """A nested copy of a report without the given keys at any depth."""
    if isinstance(d, dict):
        return {k: without(v, keys) for k, v in d.items() if k not in keys}
    if isinstance(d, list):
        return [without(v, keys) for v in d]
    return d


# --- An independent GOG (seed 002 Algorithm 1), written from the paper's formula in NumPy ---

MASK = (1 << 64) - 1


def splitmix64(seed, n):
    out, state = [], seed & MASK
    for _ in range(n):
        state = (state + 0x9E3779B97F4A7C15) & MASK
        z = state
        z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & MASK
        z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & MASK
        out.append(z ^ (z >> 31))
    return out


class OracleGog:
    """levels[axis][coord] = ((coord >> b_p) + (coord ^ h_axis)) >> b_v & 3, and a state is
    blocked when its levels sum to the threshold or more; the automatic threshold is the
    smallest whose exact blocked fraction does not exceed the density."""

    def __init__(self, dims, extent, seed=1, shift_p=4, shift_v=3, density=0.40, threshold=0):
        self.dims, self.extent = dims, extent
        coords = np.arange(extent, dtype=np.uint64)
        self.levels = []
        for h in splitmix64(seed, dims):
            v = ((coords >> np.uint64(shift_p)) + (coords ^ np.uint64(h))) >> np.uint64(shift_v)
            self.levels.append((v & np.uint64(3)).astype(np.int64))
        if threshold == 0:
            dist = np.zeros(3 * dims + 1)
            dist[0] = 1.0
            for lv in self.levels:
                hist = np.bincount(lv, minlength=4) / extent
                dist = np.convolve(dist, hist)[: 3 * dims + 1]
            threshold, tail = 3 * dims + 1, 0.0
            for c in range(3 * dims, 0, -1):
                tail += dist[c]
                if tail > density + 1e-12:
                    break
                threshold = c
        self.threshold = threshold

    def free(self, state):
        state = list(state)
        if any(c < 0 or c >= self.extent for c in state):
            return False
        return sum(int(self.levels[k][c]) for k, c in enumerate(state)) < self.threshold


def check_seed_rule_path(oracle, path, start, goal):
    """Re-validates a lattice path move by move under seed 002's rule (one axis, cost 1; two
    axes, cost sqrt 2, both one-axis intermediates free); returns its length."""
    path = [tuple(int(c) for c in s) for s in path]
    assert path[0] == tuple(start) and path[-1] == tuple(goal)
    length = 0.0
    for s in path:
        assert oracle.free(s), f"blocked state {s} on the path"
    for a, b in zip(path, path[1:]):
        moved = [k for k in range(len(a)) if a[k] != b[k]]
        assert all(abs(a[k] - b[k]) == 1 for k in moved) and 1 <= len(moved) <= 2, (a, b)
        if len(moved) == 2:
            for k in moved:
                mid = list(a)
                mid[k] = b[k]
                assert oracle.free(mid), f"corner {mid} cut between {a} and {b}"
        length += np.sqrt(len(moved))
    return length


@pytest.fixture
def maps():
    return MAPS


@pytest.hookimpl(tryfirst=True)
def pytest_configure(config):
    """Every skip prints its reason in the summary (as -rs would): a skip is never silent."""
    chars = config.option.reportchars
    if "s" not in chars and "a" not in chars.lower():
        config.option.reportchars = chars + "s"
