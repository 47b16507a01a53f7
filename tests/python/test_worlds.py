"""hpcplan.map3d and hpcplan.sphere2d against the CLI and an independent check of each path."""
import os

import numpy as np
import pytest

import hpcplan
from conftest import TIMING_KEYS, cli_error, cli_json, run_cli, without


def inside_block(blocks, points):
    """Points inside (or on) any block: an independent test from the blocks' corners."""
    lo, hi = blocks[:, :3], blocks[:, 3:]
    p = points[:, None, :]
    return ((p >= lo) & (p <= hi)).all(-1).any(-1)


def segment_samples(path, per_unit=200):
    out = []
    for a, b in zip(path, path[1:]):
        n = max(2, int(np.linalg.norm(b - a) * per_unit))
        t = np.linspace(0.0, 1.0, n)[:, None]
        out.append(a + t * (b - a))
    return np.concatenate(out)


@pytest.mark.parametrize("world,map_file,kw", [
    ("map3d", "forest.txt", dict(algo="astar")),
    ("map3d", "maze.txt", dict(algo="thetastar", resolution=0.25)),
    ("map3d", "window.txt", dict(algo="rrt", seed=3, time=60)),
    ("map3d", "single_box.txt", dict(algo="astar", shortcut=True)),
    ("sphere2d", "sphere_world.txt", dict(algo="astar")),
    ("sphere2d", "sphere_dense.txt", dict(algo="visgraph")),
])
def test_plan_answers_what_the_cli_answers(maps, world, map_file, kw):
    path = os.path.join(maps, map_file)
    module = getattr(hpcplan, world)
    r = module.load(path).plan(**kw)
    args = []
    for k, v in kw.items():
        option = "--" + k.replace("_", "-")
        args += [option] if v is True else [option, str(v)]
    cli = cli_json(world, "--map", path, *args)
    assert without(r.report, TIMING_KEYS) == without(cli, TIMING_KEYS | {"path"})
    assert r.status == "solved"
    assert r.path.tolist() == cli["path"]
    assert r.length == cli["length"]


def test_every_box_map_path_is_free(maps):
    world = hpcplan.map3d.load(os.path.join(maps, "forest.txt"))
    blocks = world.obstacles
    assert blocks.shape == (150, 6)
    for algo in ("astar", "thetastar", "rrtstar", "birrt", "visgraph"):
        # time is only a guard: every planner ends at its first path (a wall-clock limit
        # fails on a loaded machine, as birrt's 1 s default did under ASan in CI).
        r = world.plan(algo=algo, seed=2, time=60, stop_at_first=True)
        assert r.status == "solved", algo
        assert (r.path[0] == world.start).all() and (r.path[-1] == world.goal).all()
        samples = segment_samples(r.path)
        assert not inside_block(blocks, samples).any(), algo
        assert world.free(samples).all()
        assert all(world.segment_free(a, b) for a, b in zip(r.path, r.path[1:]))
        assert np.isclose(np.linalg.norm(np.diff(r.path, axis=0), axis=1).sum(), r.length)


def test_every_sphere_world_path_is_free(maps):
    world = hpcplan.sphere2d.load(os.path.join(maps, "sphere_world.txt"))
    circles = world.obstacles
    for algo in ("astar", "rrtstar", "visgraph"):
        r = world.plan(algo=algo, time=60, stop_at_first=True)
        assert r.status == "solved", algo
        samples = segment_samples(r.path)
        gap = np.linalg.norm(samples[:, None, :] - circles[None, :, :2], axis=-1) - circles[:, 2]
        assert (gap > 0).all(), algo


def test_a_query_of_ones_own(maps):
    world = hpcplan.map3d.load(os.path.join(maps, "forest.txt"))
    r = world.plan((1.0, 1.0, 1.0), [19, 19, 5], algo="astar")
    cli = cli_json("map3d", "--map", world.path, "--start", "1,1,1", "--goal", "19,19,5")
    assert r.path.tolist() == cli["path"]
    assert world.bounds.tolist() == [[0, 0, 0], [20, 20, 6]]


def test_bad_input_is_a_value_error_with_the_cli_message(maps, tmp_path):
    forest = os.path.join(maps, "forest.txt")
    world = hpcplan.map3d.load(forest)
    inside = world.obstacles[0, :3] + 0.5 * (world.obstacles[0, 3:] - world.obstacles[0, :3])
    text = ",".join(repr(float(c)) for c in inside)
    message = cli_error("map3d", "--map", forest, "--start", text)
    with pytest.raises(ValueError) as e:
        world.plan(start=inside)
    assert str(e.value) == message
    message = cli_error("map3d", "--map", forest, "--algo", "nope")
    with pytest.raises(ValueError) as e:
        world.plan(algo="nope")
    assert str(e.value) == message
    message = cli_error("map3d", "--map", forest, "--resolution", "-1")
    with pytest.raises(ValueError) as e:
        world.plan(resolution=-1)
    assert str(e.value) == message
    bad = tmp_path / "bad.txt"
    bad.write_text("boundary 0 0 0 1 1 1\nblock 0 0 0 2\n")
    message = cli_error("map3d", "--map", bad)
    with pytest.raises(ValueError) as e:
        hpcplan.map3d.load(bad)
    assert str(e.value) == message
    # Points and files get the CLI's words for the same mistake.
    for start, text in (((1, 2), "1,2"), ((1, float("nan"), 2), "1,nan,2")):
        message = cli_error("map3d", "--map", forest, "--start", text)
        with pytest.raises(ValueError) as e:
            world.plan(start=start)
        assert str(e.value) == message
    for missing in (tmp_path / "missing.txt", tmp_path):
        message = cli_error("map3d", "--map", missing)
        with pytest.raises(ValueError) as e:
            hpcplan.map3d.load(missing)
        assert str(e.value) == message
    nogoal = tmp_path / "nogoal.txt"
    nogoal.write_text("boundary 0 0 0 10 10 10\nstart 1 1 1\n")
    message = cli_error("map3d", "--map", nogoal)
    with pytest.raises(ValueError) as e:
        hpcplan.map3d.load(nogoal).plan()
    assert str(e.value) == message
    for bad in (None, 5, b"/x"):
        with pytest.raises(TypeError, match="path must be a str or a path"):
            hpcplan.map3d.load(bad)


def test_free_answers_the_exact_test_and_nothing_not_finite_is_free(maps):
    world = hpcplan.map3d.load(os.path.join(maps, "single_box.txt"))
    lo, hi = world.obstacles[0, :3], world.obstacles[0, 3:]
    inside, outside = (lo + hi) / 2, world.bounds[0] + 0.01
    assert world.free(outside) and not world.free(inside)
    assert world.free([[np.nan, 1, 1], [1, np.inf, 1]]).tolist() == [False, False]
    disc = hpcplan.sphere2d.load(os.path.join(maps, "sphere_world.txt"))
    assert not disc.free([np.nan, 0.0])


def test_no_path_is_an_answer(tmp_path):
    walled = tmp_path / "walled.txt"
    walled.write_text("boundary 0 0 0 10 10 10\nblock 4 -1 -1 5 11 11\nstart 1 1 1\ngoal 9 9 9\n")
    world = hpcplan.map3d.load(walled)
    r = world.plan(algo="astar", resolution=0.5)
    cli = run_cli("map3d", "--map", walled, "--resolution", "0.5", "--json")
    assert r.status == "no_path" and r.path.shape == (0, 3)
    assert r.length is None and r.raw_length is None  # not 0.0, which min() would pick
    assert cli.returncode == 0 and '"status":"no_path"' in cli.stdout


def test_an_underflowing_coordinate_is_read_as_the_map_parser_reads_it(tmp_path):
    # 5e-324 is a subnormal double and 1e-400 rounds to 0: both finite, and refused before as
    # "not a finite number" (the CLI's point option read them with stod, which throws on them).
    box = tmp_path / "box.txt"
    box.write_text("boundary 0 0 0 10 10 10\nstart 1 1 1\ngoal 9 9 9\n")
    world = hpcplan.map3d.load(box)
    for x in (5e-324, 1e-400):
        r = world.plan((x, 1, 1), (9, 9, 9), algo="astar", resolution=0.5)
        assert r.status == "solved" and r.path[0][0] == x, (x, r)
    cli = run_cli("map3d", "--map", box, "--start", "1e-400,1,1", "--json")
    assert cli.returncode == 0 and '"status":"solved"' in cli.stdout, cli.stderr
