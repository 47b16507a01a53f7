"""Maps and scenarios from Python: hpcplan.grid.solve(occupancy=array | map=file),
grid.Field(occupancy=), grid.load_map and scen.run, against the CLI (hpcplan grid --map,
hpcplan scen) on the MovingAI maps and on arrays written as .npy files.

The MovingAI maps are the shared benchmark set (HPCPLAN_MOVINGAI_DIR, by default
/work/shared/benchmarks/movingai, as the unit tests'); the tests that need them are skipped,
saying so, where it is absent."""
import csv
import inspect
import json
import math
import os
import subprocess
import sys
import textwrap
import threading
import time
import tracemalloc

import numpy as np
import pytest

import hpcplan
from conftest import TIMING_KEYS, cli_error, cli_json, run_cli, without
from test_threads import RUNNING, once_running

MOVINGAI = os.environ.get("HPCPLAN_MOVINGAI_DIR", "/work/shared/benchmarks/movingai")
MAPS = ["Boston_0_256", "random512-40-5", "maze512-4-6", "64room_005"]

# A report's keys that say where the obstacles came from (a file's name and format, or
# "array"), and the measurements of the run.
SOURCE_KEYS = {"map", "obstacles"}
IGNORE = TIMING_KEYS | {"max_states", "path"}


def movingai(name):
    path = os.path.join(MOVINGAI, name)
    if not os.path.exists(path):
        pytest.fail(f"the MovingAI benchmark file {path} is absent (HPCPLAN_MOVINGAI_DIR)")
    return path


def scenario_rows(path):
    """A .scen file's problems, read here: (bucket, start, goal, optimal)."""
    rows = []
    with open(path) as f:
        next(f)  # version 1
        for line in f:
            p = line.split()
            if p:
                rows.append((int(p[0]), (int(p[4]), int(p[5])), (int(p[6]), int(p[7])),
                             float(p[8])))
    return rows


def spread(rows, n):
    """n rows spread over the file (its buckets run from short to long problems)."""
    return [rows[i * (len(rows) - 1) // (n - 1)] for i in range(n)]


def coords(c):
    return ",".join(map(str, c))


# --- grid.solve on maps and arrays, against the CLI ---------------------------------------


@pytest.mark.parametrize("name", MAPS)
def test_map_and_its_array_answer_what_the_cli_answers(name):
    path = movingai(name + ".map")
    array = hpcplan.grid.load_map(path)
    assert array.dtype == np.bool_ and array.flags.c_contiguous
    # (Dijkstra on the sparse engine: the dense one takes seconds a query on a 512 x 512 map
    # on one thread; BFS runs on it.)
    for algo, engine in (("astar", "auto"), ("dijkstra", "sparse"), ("bfs", "auto")):
        for _, start, goal, optimal in spread(scenario_rows(path + ".scen"), 4):
            cli = cli_json("grid", "--map", path, "--start", coords(start), "--goal",
                           coords(goal), "--algo", algo, "--engine", engine, "--path")
            kw = dict(start=start, goal=goal, algo=algo, engine=engine, path=True)
            by_file = hpcplan.grid.solve(map=path, **kw)
            by_array = hpcplan.grid.solve(occupancy=array, **kw)
            # map=: the CLI's report, key for key.
            assert without(by_file.report, IGNORE) == without(cli, IGNORE)
            assert by_file.path.tolist() == cli["path"]
            # The array load_map made of the file: the same grid (its checksum covers the
            # shape and every bit) and the same answer; only its name says "array".
            assert without(by_array.report, IGNORE | SOURCE_KEYS) == \
                without(cli, IGNORE | SOURCE_KEYS)
            assert by_array.report["obstacles"] == by_array.report["map"] == "array"
            assert by_array.path.tolist() == cli["path"]
            if algo != "bfs":
                assert math.isclose(by_array.cost, optimal, rel_tol=1e-6)


def test_coordinates_are_x_first():
    # A 3 x 5 array (H = 3, W = 5): x runs along the last axis, so start=(x, y) is a[y, x].
    a = np.zeros((3, 5), np.uint8)
    a[0, 1:] = 1  # row y = 0 blocked but for x = 0
    r = hpcplan.grid.solve(occupancy=a, start=(4, 2), goal=(0, 0), path=True)
    assert r.status == "solved" and r.report["shape"] == [5, 3]
    assert r.path[0].tolist() == [4, 2] and r.path[-1].tolist() == [0, 0]
    assert all(a[y, x] == 0 for x, y in r.path)
    with pytest.raises(ValueError, match="start"):
        hpcplan.grid.solve(occupancy=a, start=(2, 0), goal=(0, 0))  # a[0, 2] is blocked
    with pytest.raises(ValueError):
        hpcplan.grid.solve(occupancy=a, start=(0, 4), goal=(0, 0))  # y = 4: outside


@pytest.mark.parametrize("shape,kw", [
    ((40, 60), dict(algo="astar")),
    ((40, 60), dict(algo="bfs", connectivity="full")),
    ((12, 14, 16), dict(algo="dijkstra", engine="dense", threads=1)),
    ((12, 14, 16), dict(algo="wastar", weight=1.5, connectivity="full")),
    ((7, 8, 9, 10), dict(algo="bfs", engine="sparse", connectivity="full")),
    ((5, 5, 5, 5, 6), dict(algo="astar")),
], ids=["2d", "2d-full", "3d-dense", "3d-wastar-full", "4d-full", "5d"])
def test_arrays_answer_what_the_cli_answers_on_their_npy(shape, kw, tmp_path):
    rng = np.random.default_rng(sum(shape))
    a = rng.random(shape) < 0.25
    start = tuple([0] * len(shape))
    goal = tuple(s - 1 for s in reversed(shape))  # x first
    a[tuple(reversed(start))] = a[tuple(reversed(goal))] = False
    npy = tmp_path / "a.npy"
    np.save(npy, a)
    args = ["grid", "--map", npy, "--start", coords(start), "--goal", coords(goal), "--path"]
    for name, value in kw.items():
        args += ["--" + name.replace("_", "-"), value]
    cli = cli_json(*args)
    for occupancy in (a, a.view(np.uint8)):
        r = hpcplan.grid.solve(occupancy=occupancy, start=start, goal=goal, path=True, **kw)
        assert without(r.report, IGNORE | SOURCE_KEYS) == without(cli, IGNORE | SOURCE_KEYS)
        assert r.status == cli["status"]
        if r.status == "solved":
            assert r.path.tolist() == cli["path"]


def test_full_connectivity_is_refused_past_four_dimensions_as_the_cli_refuses_it(tmp_path):
    a = np.zeros((3,) * 5, np.uint8)
    np.save(tmp_path / "a.npy", a)
    message = cli_error("grid", "--map", tmp_path / "a.npy", "--connectivity", "full")
    with pytest.raises(ValueError) as e:
        hpcplan.grid.solve(occupancy=a, connectivity="full")
    assert str(e.value) == message


# --- refusals -----------------------------------------------------------------------------


BIG = np.zeros((64, 64), np.uint8)


@pytest.mark.parametrize("array,words", [
    (BIG.astype(np.float64), ["bool or uint8", "float64"]),
    (BIG.astype(np.int8), ["bool or uint8", "int8"]),
    (BIG[:, ::2], ["C-contiguous", "np.ascontiguousarray(a)"]),
    (np.asfortranarray(np.zeros((4, 5), np.uint8)), ["C-contiguous", "np.ascontiguousarray(a)"]),
    (np.zeros((), np.uint8), ["1 to 16 dimensions", "not 0"]),
    (np.zeros((1,) * 17, np.uint8), ["1 to 16 dimensions", "not 17"]),
    (np.zeros((0, 4), np.uint8), ["1 to 65535"]),
], ids=["float64", "int8", "strided", "fortran", "0-d", "17-d", "empty"])
def test_bad_arrays_are_refused_in_one_line(array, words):
    for call in (lambda: hpcplan.grid.solve(occupancy=array),
                 lambda: hpcplan.grid.Field(occupancy=array)):
        with pytest.raises(ValueError) as e:
            call()
        message = str(e.value)
        assert "\n" not in message and message.strip() == message
        for w in words:
            assert w in message, message


def test_gog_options_are_refused_with_an_array():
    a = np.zeros((8, 8), np.uint8)
    for kw in (dict(dims=2), dict(extent=8), dict(seed=3), dict(threshold=2),
               dict(density=0.1), dict(gog_shift_p=1), dict(gog_shift_v=1)):
        name = next(iter(kw))
        with pytest.raises(ValueError, match=f"^{name}= describes the GOG field"):
            hpcplan.grid.solve(occupancy=a, **kw)
        with pytest.raises(ValueError, match=f"^{name}= describes the GOG field"):
            hpcplan.grid.Field(occupancy=a, **kw)
    with pytest.raises(ValueError, match="map= and occupancy="):
        hpcplan.grid.solve(occupancy=a, map=__file__)
    with pytest.raises(TypeError, match="NumPy array"):
        hpcplan.grid.solve(occupancy=[[0, 1], [0, 0]])


# --- no copy ------------------------------------------------------------------------------


def traced_peak(call):
    """The most memory Python's allocators (NumPy's arrays included: NumPy reports its data
    buffers to tracemalloc) held above what they held before, during `call`."""
    tracemalloc.start()
    try:
        tracemalloc.reset_peak()
        before = tracemalloc.get_traced_memory()[0]
        result = call()
        return tracemalloc.get_traced_memory()[1] - before, result
    finally:
        tracemalloc.stop()


@pytest.mark.parametrize("dtype", [np.uint8, np.bool_])
def test_an_array_is_read_in_place_not_copied(dtype):
    a = np.zeros((4096, 4096), dtype)  # 16 MiB
    a[1:, 2] = 1
    # The probe is able to fail: a copy of the array (what a conversion to uint8 or to C order
    # would make) is seen, whole.
    copied, _ = traced_peak(lambda: np.ascontiguousarray(a[:, ::-1]).astype(np.uint8))
    assert copied >= a.nbytes
    peak, r = traced_peak(lambda: hpcplan.grid.solve(occupancy=a, start=(0, 0),
                                                     goal=(3, 0)))
    assert r.status == "solved" and r.hops == 3
    assert peak < a.nbytes // 16, peak
    peak, field = traced_peak(lambda: hpcplan.grid.Field(occupancy=a))
    assert peak < a.nbytes // 16, peak
    # The Field holds the grid's bits (one per cell, rows padded to 64), not the bytes.
    assert field.grid_bytes == a.size // 8


def test_a_field_holds_its_own_grid():
    a = np.zeros((20, 30), np.uint8)
    field = hpcplan.grid.Field(occupancy=a)
    assert field.shape == (20, 30) and field.dims == 2 and field.extent == 30
    assert field.threshold is None and field.seed is None and field.blocked_fraction == 0
    first = field.solve(start=(0, 0), goal=(29, 19))
    a[:, 15] = 1  # the array changes: the field built from it does not
    again = field.solve(start=(0, 0), goal=(29, 19))
    assert again.status == "solved" and without(again.report, IGNORE) == \
        without(first.report, IGNORE)
    assert not field.occupancy().any()
    assert hpcplan.grid.solve(occupancy=a, start=(0, 0), goal=(29, 19)).status == "no_path"
    assert field.free([[15, 0], [30, 0], [-1, 0]]).tolist() == [True, False, False]
    with pytest.raises(ValueError, match="no GOG levels"):
        field.levels(0)
    with pytest.raises(TypeError):
        field.solve(start=(0, 0), goal=(1, 1), map="x.map")


def test_a_field_answers_as_solve_and_is_shared_by_threads():
    path = movingai("random512-40-5.map")
    a = hpcplan.grid.load_map(path)
    field = hpcplan.grid.Field(occupancy=a)
    assert field.shape == a.shape and (field.occupancy() == a).all()
    assert math.isclose(field.blocked_fraction, a.mean(), rel_tol=1e-12)
    queries = spread(scenario_rows(path + ".scen"), 24)
    expected = [hpcplan.grid.solve(occupancy=a, start=s, goal=g, path=True) for _, s, g, _ in
                queries]
    answers = [None] * len(queries)

    def work(k):
        for i in range(k, len(queries), 4):
            _, s, g, _ = queries[i]
            answers[i] = field.solve(start=s, goal=g, path=True)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for (_, _, _, optimal), e, r in zip(queries, expected, answers):
        assert without(r.report, IGNORE) == without(e.report, IGNORE)
        assert r.path.tolist() == e.path.tolist()
        assert math.isclose(r.cost, optimal, rel_tol=1e-6)
    assert field.free(expected[0].path).all()


# --- load_map -----------------------------------------------------------------------------


def test_load_map_reads_a_map_in_numpy_order():
    path = movingai("Boston_0_256.map")
    a = hpcplan.grid.load_map(path)
    with open(path) as f:
        lines = f.read().splitlines()
    rows = [line.rstrip() for line in lines[4:] if line.strip()]
    assert a.shape == (len(rows), len(rows[0])) == (256, 256)
    expected = np.array([[c not in ".GS" for c in row] for row in rows])
    assert (a == expected).all()


def test_load_map_reads_voxel_maps_water_and_npy(tmp_path):
    # A .3dmap: "voxel W H D", then the blocked voxels "x y z"; NumPy order (D, H, W).
    voxels = [(0, 1, 2), (3, 0, 1), (4, 2, 0)]
    (tmp_path / "v.3dmap").write_text("voxel 5 3 4\n" + "".join(f"{x} {y} {z}\n"
                                                                  for x, y, z in voxels))
    v = hpcplan.grid.load_map(tmp_path / "v.3dmap")
    assert v.shape == (4, 3, 5) and v.sum() == 3 and all(v[z, y, x] for x, y, z in voxels)
    # Passed back as an array (with the format's full connectivity) it plans as the file.
    cli = cli_json("grid", "--map", tmp_path / "v.3dmap", "--start", "0,0,0", "--goal", "4,2,3")
    r = hpcplan.grid.solve(occupancy=v, start=(0, 0, 0), goal=(4, 2, 3), connectivity="full")
    assert without(r.report, IGNORE | SOURCE_KEYS) == without(cli, IGNORE | SOURCE_KEYS)
    # Water: a class of its own ("terrain").
    (tmp_path / "w.map").write_text("type octile\nheight 2\nwidth 4\nmap\n.WW@\n..W.\n")
    ground = hpcplan.grid.load_map(tmp_path / "w.map")
    water = hpcplan.grid.load_map(tmp_path / "w.map", terrain="water")
    assert ground.astype(int).tolist() == [[0, 1, 1, 1], [0, 0, 1, 0]]
    assert water.astype(int).tolist() == [[1, 0, 0, 1], [1, 1, 0, 1]]
    with pytest.raises(ValueError, match="ground or water"):
        hpcplan.grid.load_map(tmp_path / "w.map", terrain="lava")
    with pytest.raises(ValueError, match="terrain='water'"):
        hpcplan.grid.load_map(tmp_path / "v.3dmap", terrain="water")
    # .npy, as stored: C or Fortran order, bool or uint8 (any nonzero byte blocked).
    a = np.random.default_rng(1).integers(0, 3, (3, 4, 5)).astype(np.uint8)
    for stored in (a, np.asfortranarray(a), a.astype(bool)):
        np.save(tmp_path / "a.npy", stored)
        back = hpcplan.grid.load_map(tmp_path / "a.npy")
        assert back.shape == a.shape and (back == (a != 0)).all()
    # A file the parser refuses: its one line, as the CLI's.
    (tmp_path / "bad.map").write_text("type octile\nheight 2\nwidth 2\nmap\n..\n.\n")
    with pytest.raises(ValueError) as e:
        hpcplan.grid.load_map(tmp_path / "bad.map")
    assert str(e.value) == cli_error("grid", "--map", tmp_path / "bad.map")


# --- scen.run -----------------------------------------------------------------------------

SCEN_TIMING = TIMING_KEYS | {"load_ms", "wall_ms", "query_us", "states_per_second", "p50_us",
                             "p95_us", "max_us"}


def cli_scen(*args, csv_path):
    p = run_cli("scen", *args, "--json", "--csv", csv_path, check=False)
    with open(csv_path) as f:
        return p.returncode, p.stdout, list(csv.DictReader(f))


def assert_rows_equal(rows, cli_rows):
    assert len(rows) == len(cli_rows)
    for r, c in zip(rows, cli_rows):
        assert r["row"] == int(c["row"]) and r["bucket"] == int(c["bucket"])
        assert r["start"] == (int(c["start_x"]), int(c["start_y"]))
        assert r["goal"] == (int(c["goal_x"]), int(c["goal_y"]))
        assert f"{r['optimal']:.8f}" == c["optimal"] and f"{r['cost']:.8f}" == c["cost"]
        assert (r["status"], r["expanded"], r["hops"], int(r["mismatch"])) == \
            (c["status"], int(c["expanded"]), int(c["hops"]), int(c["mismatch"]))


def test_scen_runs_boston_as_the_cli(tmp_path):
    scen = movingai("Boston_0_256.map.scen")
    r = hpcplan.scen.run(scen)
    assert len(r.rows) == 950 and r.mismatches == 0 and r.ok and r.status == "ok"
    code, out, cli_rows = cli_scen(scen, csv_path=tmp_path / "cli.csv")
    assert code == 0
    assert without(r.report, SCEN_TIMING) == without(json.loads(out), SCEN_TIMING)
    assert_rows_equal(r.rows, cli_rows)
    expected = scenario_rows(scen)
    assert [(x["bucket"], x["start"], x["goal"]) for x in r.rows] == \
        [(b, s, g) for b, s, g, _ in expected]
    assert sum(b["rows"] for b in r.buckets) == 950
    assert all(x["status"] == "solved" and not x["mismatch"] for x in r.rows)
    # csv= and output= write what the CLI writes (the times aside).
    r2 = hpcplan.scen.run(scen, csv=tmp_path / "py.csv", output=tmp_path / "py.json")
    with open(tmp_path / "py.csv") as f:
        assert_rows_equal(r2.rows, list(csv.DictReader(f)))
    with open(tmp_path / "py.json") as f:
        assert without(json.load(f), SCEN_TIMING) == without(r.report, SCEN_TIMING)


@pytest.mark.parametrize("buckets,given", [("10-12", (10, 12)), ("40", 40)])
def test_scen_runs_a_bucket_range_as_the_cli(buckets, given, tmp_path):
    scen = movingai("random512-40-5.map.scen")
    r = hpcplan.scen.run(scen, buckets=given, algo="astar")
    kept = [row for row in scenario_rows(scen) if
            (lambda b: b in range(int(buckets.split("-")[0]),
                                  int(buckets.split("-")[-1]) + 1))(row[0])]
    assert len(r.rows) == len(kept) > 0 and r.mismatches == 0 and r.ok
    code, out, cli_rows = cli_scen(scen, "--buckets", buckets, csv_path=tmp_path / "c.csv")
    assert code == 0
    assert_rows_equal(r.rows, cli_rows)
    # rows= takes the first ones of the selection; other planners keep their promises.
    for algo in ("dijkstra", "bfs", "wastar"):
        s = hpcplan.scen.run(scen, buckets=buckets, rows=7, algo=algo)
        assert len(s.rows) == 7 and s.mismatches == 0, (algo, s.mismatch_rows)
        assert [x["row"] for x in s.rows] == [x["row"] for x in r.rows[:7]]


def test_a_mismatch_is_returned_not_raised(tmp_path):
    scen = movingai("Boston_0_256.map.scen")
    lines = open(scen).read().splitlines()
    # The third problem's published length made wrong (plus one).
    fields = lines[3].split("\t")
    fields[-1] = f"{float(fields[-1]) + 1:.8f}"
    lines[3] = "\t".join(fields)
    (tmp_path / "wrong.scen").write_text("\n".join(lines[:11]) + "\n")
    r = hpcplan.scen.run(tmp_path / "wrong.scen", map=movingai("Boston_0_256.map"))
    assert r.mismatches == 1 and r.mismatch_rows == [2] and not r.ok and r.status == "ok"
    assert [x["mismatch"] for x in r.rows] == [i == 2 for i in range(10)]
    code, _, cli_rows = cli_scen(tmp_path / "wrong.scen", "--map", movingai("Boston_0_256.map"),
                                 csv_path=tmp_path / "c.csv")
    assert code == 1  # the CLI's exit for it
    assert_rows_equal(r.rows, cli_rows)


def test_scen_refusals_are_the_clis(tmp_path):
    boston = movingai("Boston_0_256.map.scen")
    maze = movingai("maze512-4-6.map")
    for args, kw in [((boston, "--map", maze), dict(map=maze)),
                     ((boston, "--buckets", "9-3"), dict(buckets="9-3")),
                     ((boston, "--algo", "rrt"), dict(algo="rrt"))]:
        with pytest.raises(ValueError) as e:
            hpcplan.scen.run(boston, **kw)
        assert str(e.value) == cli_error("scen", *args)
    with pytest.raises(TypeError):
        hpcplan.scen.run(boston, dims=2)
    with pytest.raises(TypeError):
        hpcplan.scen.run(boston, buckets=1.5)


def long_scenario(tmp_path, copies=20000):
    """A scenario that runs far longer than any test waits: random512-40-5's longest problem
    (bucket 523), Dijkstra on the sparse engine, `copies` times."""
    scen = movingai("random512-40-5.map.scen")
    last = open(scen).read().splitlines()[-1]
    path = tmp_path / "long.scen"
    path.write_text("version 1\n" + (last + "\n") * copies)
    return path, movingai("random512-40-5.map")


def test_a_stop_source_ends_a_scenario_run(tmp_path):
    path, map_path = long_scenario(tmp_path)
    stop = hpcplan.StopSource()
    seen = []

    def request(running):
        # Once the run is seen in the engine (a handshake, not a wait for rows to finish: how
        # many are done by then depends on the machine, so the test does not count on any).
        seen.append(running)
        stop.request_stop()

    t = once_running(request)
    started = time.perf_counter()
    r = hpcplan.scen.run(path, map=map_path, algo="dijkstra", engine="sparse", stop=stop)
    t.join()
    assert seen == [True] and r.status == "cancelled" and not r.ok
    assert len(r.rows) < 20000 and r.mismatches == 0, (len(r.rows), r.mismatch_rows)
    assert all(x["status"] == "solved" for x in r.rows)  # the row under way is dropped
    assert r.report["rows"] == len(r.rows)
    assert time.perf_counter() - started < 60  # a guard: 20,000 rows would take minutes
    # A stop already requested: nothing runs.
    r = hpcplan.scen.run(path, map=map_path, stop=stop)
    assert r.rows == [] and r.status == "cancelled"
    # On an array.
    a = hpcplan.grid.load_map(map_path)
    assert hpcplan.grid.solve(occupancy=a, algo="dijkstra", engine="sparse", start=(36, 246),
                              goal=(65, 323), stop=stop).status == "cancelled"


def test_ctrl_c_stops_a_scenario_run(tmp_path):
    path, map_path = long_scenario(tmp_path)
    script = RUNNING + textwrap.dedent(f"""
        import os, sys
        import hpcplan
        once_running(lambda running: (print("running", running, flush=True),
                                      os.kill(os.getpid(), signal.SIGINT)))
        try:
            hpcplan.scen.run({str(path)!r}, map={map_path!r}, algo="dijkstra", engine="sparse")
        except KeyboardInterrupt:
            print("KeyboardInterrupt")
            sys.exit(0)
        print("no KeyboardInterrupt")
        sys.exit(1)
    """)
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True,
                       timeout=300)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "running True" in p.stdout and "KeyboardInterrupt" in p.stdout, p.stdout


def test_the_signatures_and_docs_name_the_new_arguments():
    solve = inspect.signature(hpcplan.grid.solve).parameters
    assert "occupancy" in solve and "map" in solve and "stop" in solve
    assert "x is the array's last axis" in hpcplan.grid.solve.__doc__
    run = inspect.signature(hpcplan.scen.run).parameters
    assert list(run)[0] == "scenario" and {"map", "algo", "buckets", "rows", "stop"} <= set(run)
    assert "occupancy" in inspect.signature(hpcplan.grid.Field).parameters
    assert "(H, W)" in hpcplan.grid.load_map.__doc__


@pytest.mark.parametrize("algo", ["bfs", "dijkstra"])
def test_distance_field_is_the_cli_field_out_file(algo, tmp_path):
    # The same field from a map path, from its array and from hpcplan grid --field-out.
    path = movingai("Boston_0_256.map")
    out = tmp_path / "field.npy"
    run_cli("grid", "--map", path, "--start", "188,1", "--algo", algo, "--field-out", str(out))
    want = np.load(out)
    by_path = hpcplan.grid.distance_field(map=path, start=(188, 1), algo=algo)
    by_array = hpcplan.grid.distance_field(occupancy=hpcplan.grid.load_map(path),
                                           start=(188, 1), algo=algo)
    assert by_path.dtype == want.dtype == (np.int32 if algo == "bfs" else np.float32)
    assert by_path.shape == want.shape == (256, 256)
    assert np.array_equal(by_path, want) and np.array_equal(by_array, want)
    assert by_path[1, 188] == 0 and (by_path == -1).any() and (by_path > 0).any()
