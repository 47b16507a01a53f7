"""The project's scripts that read the engine through the package instead of files or CLI
output: the fluid renderer, the world drawer, the simulator report."""
import os
import subprocess
import sys

import hpcplan

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def script(name, *args):
    return subprocess.run([sys.executable, os.path.join(ROOT, "scripts", name), *map(str, args)],
                          capture_output=True, text=True, timeout=600)


def test_render_sph_draws_the_fluid_from_its_views(tmp_path):
    # A plain import: the test command's machines have matplotlib (python3-matplotlib, installed
    # by scripts/setup.sh), so a missing or broken one is a failure here, never a skip.
    import matplotlib  # noqa: F401
    p = script("render_sph.py", "--fluid", "preset=seed,scenario=dynamic,particles=500,seed=2",
               "--frames", "6", "--every", "3", "--out", tmp_path / "r", "--gif")
    assert p.returncode == 0, p.stderr
    assert "3 frames" in p.stdout
    assert all((tmp_path / f"r_{k:05d}.png").stat().st_size > 1000 for k in range(3))
    bad = script("render_sph.py", "--fluid", "preset=lava", "--out", tmp_path / "x")
    assert bad.returncode != 0 and "render_sph: error: --fluid:" in bad.stderr, bad.stderr


def test_draw_paths_reads_the_world_with_the_engine(tmp_path, maps):
    for world, plan in (("forest.txt", "thetastar"), ("sphere_world.txt", "astar")):
        out = tmp_path / (world + ".png")
        p = script("draw_paths.py", os.path.join(maps, world), out, "--plan", plan)
        assert p.returncode == 0, p.stderr
        assert out.stat().st_size > 10000
    (tmp_path / "bad.txt").write_text("boundary 0 0\n")
    p = script("draw_paths.py", tmp_path / "bad.txt", tmp_path / "bad.png")
    assert p.returncode == 2 and "draw_paths: error:" in p.stderr and "bad.txt:1:" in p.stderr


def test_sim_report_runs_its_sweep_in_process(tmp_path):
    p = script("sim_report.py", "--simulate",
               "scenario=particles,dynamic;algo=astar,dstar_lite;particles=300;runs=2;"
               "max_sim_s=3;settle_frames=10", "--out", tmp_path)
    assert p.returncode == 0, p.stderr
    report = (tmp_path / "sim_report.md").read_text()
    assert "Particles Only" in report and "Dynamic Obstacles" in report
    assert "D* Lite" in report and "A*" in report
    # The same rows as hpcplan.sim.run gives.
    r = hpcplan.sim.run(scenario="dynamic", algo="astar", particles=300, runs=2, max_sim_s=3,
                        settle_frames=10)
    assert len(r.runs) == 2
    bad = script("sim_report.py", "--simulate", "algo=nope", "--out", tmp_path)
    assert bad.returncode != 0 and "unknown" in bad.stderr
