"""hpcplan.sim.run against hpcplan sim: the same rows, replans and aggregate."""
import csv
import json

import pytest

import hpcplan
from conftest import TIMING_KEYS, cli_error, run_cli, without

# Lockstep runs are deterministic (timings aside, left empty here as with --no-timings).
KW = dict(particles=400, scenario="dynamic", algo="astar", runs=2, seed=4, max_sim_s=4.0,
          settle_frames=20, no_timings=True, threads=2)


def argv(kw):
    out = []
    for k, v in kw.items():
        option = "--" + k.replace("_", "-")
        out += [option] if v is True else [option, str(v)]
    return out


def typed(row):
    """A CSV row's cells as the module types them (empty: None)."""
    out = {}
    for k, v in row.items():
        if v == "":
            out[k] = None
            continue
        try:
            out[k] = int(v)
        except ValueError:
            try:
                out[k] = float(v)
            except ValueError:
                out[k] = v
    return out


def close(a, b):
    """Equal, reals to the CSV's 6 significant digits (an empty text is an empty cell)."""
    a, b = (None if x == "" else x for x in (a, b))
    if isinstance(a, float) or isinstance(b, float):
        return a is not None and b is not None and abs(a - b) <= 5e-6 * max(1.0, abs(a), abs(b))
    return a == b


def test_run_equals_the_cli(tmp_path):
    r = hpcplan.sim.run(**KW)
    run_cli("sim", *argv(KW), "--csv", tmp_path / "runs.csv", "--replan-log",
            tmp_path / "replans.csv", "--output", tmp_path / "out.json")
    with open(tmp_path / "runs.csv") as f:
        rows = [typed(row) for row in csv.DictReader(f)]
    with open(tmp_path / "replans.csv") as f:
        replans = [typed(row) for row in csv.DictReader(f)]
    assert [list(row) for row in r.runs] == [list(row) for row in rows]  # same columns, order
    for mine, theirs in zip(r.runs, rows):
        for column in mine:
            assert close(mine[column], theirs[column]), (column, mine[column], theirs[column])
    assert len(r.replans) == len(replans) > 0
    for mine, theirs in zip(r.replans, replans):
        assert all(close(mine[c], theirs[c]) for c in mine), (mine, theirs)
    cli = json.load(open(tmp_path / "out.json"))
    # The JSON's timings are measured in any case (--no-timings empties the CSVs' only).
    timings = TIMING_KEYS | {"plan_time_us", "snapshot_ms", "sph_ms_per_frame", "wall_time_s"}
    timings |= {k for k in cli["aggregate"] if k.startswith(("plan_time_us", "sph_ms"))}
    assert without(r.report, timings) == without(cli, timings)
    assert r.status == "ok" and len(r.runs) == 2 and r.report["runs"][1]["run_number"] == 2


def test_the_seeds_columns_come_first():
    r = hpcplan.sim.run(**dict(KW, runs=1))
    assert list(r.runs[0])[:14] == [
        "scenario", "algorithm", "run_number", "success", "time_to_goal_s", "total_replans",
        "failed_replans", "avg_plan_time_us", "min_plan_time_us", "max_plan_time_us",
        "avg_path_length", "avg_path_nodes", "avg_path_divergence", "particle_count"]
    assert r.runs[0]["avg_plan_time_us"] is None  # no_timings=True


@pytest.mark.parametrize("kw,args", [
    (dict(algo="nope"), ["--algo", "nope"]),
    (dict(pace="fast"), ["--pace", "fast"]),
    (dict(particles=1), ["--particles", "1"]),
    (dict(density_threshold=2.0), ["--density-threshold", "2"]),
    (dict(checkpoint=""), ["--checkpoint", ""]),
    (dict(restart=""), ["--restart", ""]),
])
def test_bad_input_is_a_value_error_with_the_cli_message(kw, args):
    message = cli_error("sim", *args)
    with pytest.raises(ValueError) as e:
        hpcplan.sim.run(**kw)
    assert str(e.value) == message
