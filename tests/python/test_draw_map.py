"""scripts/draw_map.py: a MovingAI map with a path from `hpcplan grid --map --path --json`, and a
distance field (.npy, -1 unreachable) drawn over it; the PNG's size; one-line errors (exit 2)."""
import json
import os
import struct
import subprocess

import numpy as np
import pytest

from conftest import run_cli

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
SCRIPT = os.path.join(ROOT, "scripts", "draw_map.py")


def movingai_dir():
    """The shared MovingAI folder, as tests/unit/CMakeLists.txt finds it (a missing one fails)."""
    for d in (os.environ.get("HPCPLAN_MOVINGAI_DIR"),
              os.path.join(ROOT, "shared", "benchmarks", "movingai"),
              os.path.join(ROOT, "..", "shared", "benchmarks", "movingai")):
        if d and os.path.isdir(d):
            return d
    pytest.fail("no shared/benchmarks/movingai beside or inside the checkout")


def draw(*args, stdin=None):
    # Debian's python3, whose matplotlib scripts/setup.sh installs (the scripts' interpreter).
    return subprocess.run(["/usr/bin/python3", SCRIPT, *map(str, args)], input=stdin,
                          capture_output=True, text=True, timeout=300)


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n" and head[12:16] == b"IHDR", head
    return struct.unpack(">II", head[16:24])


def test_draws_a_map_with_a_path_and_a_field(tmp_path):
    boston = os.path.join(movingai_dir(), "Boston_0_256.map")
    result = tmp_path / "path.json"
    p = run_cli("grid", "--map", boston, "--start", "10,10", "--goal", "200,200", "--path",
                "--json")
    result.write_text(p.stdout)
    assert len(json.loads(p.stdout)["path"]) > 100

    out = tmp_path / "boston.png"
    d = draw(boston, out, "--path", result)
    assert d.returncode == 0, d.stderr
    assert png_size(out) == (1024, 1024)  # 256 cells, 4 pixels each
    assert out.stat().st_size > 10000

    # A distance field by the spec (H, W), float32 cost or int32 hops, -1 unreachable: the
    # path from stdin, 2 pixels per cell.
    yy, xx = np.mgrid[0:256, 0:256]
    field = np.hypot(xx - 10, yy - 10).astype(np.float32)
    field[:, 200:] = -1
    np.save(tmp_path / "cost.npy", field)
    np.save(tmp_path / "hops.npy", np.where(field >= 0, field, -1).astype(np.int32))
    for name in ("cost.npy", "hops.npy"):
        out = tmp_path / (name + ".png")
        d = draw(boston, out, "--path", "-", "--field", tmp_path / name, "--px", 2,
                 stdin=p.stdout)
        assert d.returncode == 0, d.stderr
        assert png_size(out) == (512, 512)
    assert not [f for f in os.listdir(tmp_path) if f.startswith(".draw_map.")]


def test_bad_input_is_one_line_and_exit_2(tmp_path):
    boston = os.path.join(movingai_dir(), "Boston_0_256.map")
    np.save(tmp_path / "wrong.npy", np.zeros((3, 4), np.float32))
    (tmp_path / "nopath.json").write_text('{"status": "no_path"}')
    (tmp_path / "bad.map").write_text("type octile\nheight 2\nwidth 3\nmap\n...\n")
    for args, words in (((boston, tmp_path / "a.png", "--field", tmp_path / "wrong.npy"),
                         "is not the map's (256, 256)"),
                        ((boston, tmp_path / "a.png", "--path", tmp_path / "nopath.json"),
                         'no "path"'),
                        ((tmp_path / "bad.map", tmp_path / "a.png"), "1 map rows"),
                        ((boston, tmp_path / "no" / "a.png"), "does not exist")):
        d = draw(*args)
        assert d.returncode == 2, (args, d.stderr)
        lines = d.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("draw_map: error: "), d.stderr
        assert words in lines[0], lines[0]
    assert not (tmp_path / "a.png").exists()
