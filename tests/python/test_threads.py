"""The GIL is released during long calls, a StopSource cancels them from another thread, and
Ctrl-C stops them through the engine's stop token."""
import json
import os
import signal
import subprocess
import sys
import textwrap
import threading
import time

import pytest

import hpcplan

# A search that takes far longer than any test waits: the sparse engine's 6D Dijkstra.
LONG = dict(dims=6, algo="dijkstra", engine="sparse", extent=100)


def test_a_second_thread_runs_during_a_solve():
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=count)
    t.start()
    start = time.perf_counter()
    r = hpcplan.grid.solve(dims=4, algo="dijkstra", engine="sparse", extent=40)
    end = time.perf_counter()
    done.set()
    t.join()
    assert r.status == "solved" and end - start > 0.3, end - start
    during = [x for x in ticks if start + 0.05 < x < end - 0.05]
    # The ticker wakes every millisecond; with the GIL held it would not run at all.
    assert len(during) >= 20, (len(during), end - start)


def test_a_stop_source_cancels_a_solve_within_a_poll():
    stop = hpcplan.StopSource()
    requested = []

    def cancel():
        time.sleep(0.3)
        requested.append(time.perf_counter())
        assert stop.request_stop()

    t = threading.Thread(target=cancel)
    t.start()
    r = hpcplan.grid.solve(**LONG, stop=stop)
    returned = time.perf_counter()
    t.join()
    assert r.status == "cancelled" and r.cost is None
    assert returned - requested[0] < 0.25, returned - requested[0]
    assert stop.stop_requested and not stop.request_stop()  # only the first request counts


@pytest.mark.parametrize("call", ["dense", "plan", "fluid", "sim"])
def test_a_stop_source_ends_every_long_call(call, maps):
    stop = hpcplan.StopSource()
    threading.Timer(0.3, stop.request_stop).start()
    t0 = time.perf_counter()
    if call == "dense":
        r = hpcplan.grid.solve(dims=5, algo="bfs", engine="dense", extent=90, stop=stop)
        assert r.status == "cancelled"
    elif call == "plan":
        world = hpcplan.map3d.load(os.path.join(maps, "forest.txt"))
        r = world.plan(algo="rrtstar", time=30, stop=stop)
        assert r.status in ("cancelled", "solved")  # RRT* keeps its best path when stopped
    elif call == "fluid":
        fluid = hpcplan.sph.Fluid(preset="seed", particles=3000)
        r = fluid.step(frames=100000, stop=stop)
        assert r["interrupted"] and r["frame"] < 100000
    else:
        r = hpcplan.sim.run(particles=1500, runs=50, max_sim_s=300, stop=stop)
        assert r.status == "interrupted"
    assert time.perf_counter() - t0 < 3.0


def test_solves_from_several_threads_agree():
    field = hpcplan.grid.Field(dims=3, extent=40)
    expected = [field.solve(algo=a, path=True) for a in ("astar", "bfs", "dijkstra")] * 3
    results = [None] * len(expected)

    def work(k):
        results[k] = field.solve(algo=("astar", "bfs", "dijkstra")[k % 3], path=True)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(len(expected))]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for a, b in zip(expected, results):
        assert a.cost == b.cost and (a.path == b.path).all()


def test_a_fluid_is_used_by_one_thread_at_a_time():
    fluid = hpcplan.sph.Fluid(preset="seed", particles=3000)
    stop = hpcplan.StopSource()
    t = threading.Thread(target=lambda: fluid.step(frames=100000, stop=stop))
    t.start()
    time.sleep(0.2)
    with pytest.raises(RuntimeError, match="in use by another thread"):
        fluid.positions
    with pytest.raises(RuntimeError, match="in use by another thread"):
        fluid.step()
    for name in ("probes", "frame", "options", "backend", "boxes", "velocities", "time"):
        with pytest.raises(RuntimeError, match="in use by another thread"):
            getattr(fluid, name)
    stop.request_stop()
    t.join()
    assert fluid.positions.shape == (fluid.size, 3)


# Ctrl-C: a child Python process sends itself SIGINT during a long call, as a terminal does;
# the call must end with KeyboardInterrupt soon after, the engine stopped through its token.
CTRL_C = textwrap.dedent("""
    import os, signal, sys, threading, time
    import hpcplan
    fired = []
    def interrupt():
        fired.append(time.perf_counter())
        os.kill(os.getpid(), signal.SIGINT)
    threading.Timer(0.5, interrupt).start()
    started = time.perf_counter()
    try:
        {call}
    except KeyboardInterrupt:
        print("KeyboardInterrupt after", time.perf_counter() - fired[0])
        {after}
        sys.exit(0)
    print("no KeyboardInterrupt; returned after", time.perf_counter() - started)
    sys.exit(1)
""")


@pytest.mark.parametrize("call,after", [
    ("hpcplan.grid.solve(dims=6, algo='dijkstra', engine='sparse', extent=100)", "pass"),
    ("hpcplan.grid.solve(dims=5, algo='bfs', engine='dense', extent=90)", "pass"),
    ("hpcplan.sph.Fluid(preset='seed', particles=3000).step(frames=100000)", "pass"),
    ("hpcplan.sim.run(particles=1500, runs=50)", "pass"),
    # With a checkpoint, Ctrl-C stops the dense search at its next level with the checkpoint
    # written; a restart then continues to the uninterrupted answer.
    ("hpcplan.grid.solve(dims=4, algo='bfs', extent=100, threads=1, checkpoint=sys.argv[1])",
     "r = hpcplan.grid.solve(dims=4, algo='bfs', extent=100, threads=1, restart=sys.argv[1]); "
     "s = hpcplan.grid.solve(dims=4, algo='bfs', extent=100, threads=1); "
     "assert (r.status, r.hops, r.counters) == (s.status, s.hops, s.counters), (r, s); "
     "print('restarted', r.report['restarted_from'])"),
], ids=["sparse", "dense", "fluid", "sim", "checkpoint"])
def test_ctrl_c_stops_a_long_call(call, after, tmp_path):
    script = CTRL_C.format(call=call, after=after)
    env = dict(os.environ)
    p = subprocess.run([sys.executable, "-c", script, str(tmp_path / "run.ck")],
                       capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == 0, p.stdout + p.stderr
    latency = float(p.stdout.split("KeyboardInterrupt after")[1].split()[0])
    if "checkpoint" not in call:
        assert latency < 1.0, p.stdout
    else:
        # The search stopped part way: a search that ends writes no checkpoint, and this one
        # was written and restarted from. How soon is the disk's to say (a 27 MB file flushed:
        # 0.5 s alone, 4.3 s beside a compiler's writes), so only a hang is a failure here;
        # bench/python_stop_latency.py measures it.
        assert latency < 60.0, p.stdout
        assert "restarted" in p.stdout and (tmp_path / "run.ck").exists()


def test_a_step_ended_by_ctrl_c_still_counts_its_frames(tmp_path):
    script = textwrap.dedent("""
        import os, signal, threading
        import hpcplan
        f = hpcplan.sph.Fluid(preset="seed", particles=2000, threads=1)
        f.step(frames=2)
        threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT)).start()
        try:
            f.step(frames=100000)
        except KeyboardInterrupt:
            pass
        r = f.report()
        assert r["frames"] == f.frame > 2 and r["substeps"] == f.substeps, (r, f.frame)
        assert abs(r["simulated_s"] - f.time) < 1e-9
        print("ok", f.frame)
    """)
    p = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert p.returncode == 0 and p.stdout.startswith("ok"), p.stdout + p.stderr


def test_a_failed_call_leaves_the_threads_as_they_were(tmp_path):
    before = hpcplan.sph.Fluid(preset="seed", particles=100).report()["threads"]
    with pytest.raises(RuntimeError):
        hpcplan.sim.run(particles=200, runs=1, max_sim_s=0.2, threads=1, csv="/proc/version")
    assert hpcplan.sph.Fluid(preset="seed", particles=100).report()["threads"] == before


def test_calls_from_other_threads_run_there():
    out = {}
    t = threading.Thread(target=lambda: out.update(r=hpcplan.grid.solve(dims=2)))
    t.start()
    t.join()
    assert out["r"].status == "solved"


# multiprocessing's default start method on Linux is fork. GNU OpenMP's threads do not survive
# it: a child whose parent had run the engine's parallel loops waited forever in its first one.
# Such a child runs every call on one thread instead, and says so.
FORKED = textwrap.dedent("""
    import multiprocessing as mp, sys
    import hpcplan
    def child(seed):
        r = hpcplan.grid.solve(dims=3, extent=30, algo="bfs", engine="dense", seed=seed)
        f = hpcplan.sph.Fluid(preset="seed", particles=300, threads=2)
        f.step(frames=2)
        f.checkpoint(sys.argv[1] + f".{seed}")  # its soundness check is an OpenMP loop too
        return r.status, r.hops, r.report["dense"]["threads"], f.threads, f.frame
    parent = [hpcplan.grid.solve(dims=3, extent=30, algo="bfs", engine="dense", seed=s)
              for s in (1, 2)]
    hpcplan.sph.Fluid(preset="seed", particles=300, threads=2).step(frames=2)
    with mp.get_context("fork").Pool(2) as pool:
        got = pool.map(child, [1, 2])
    assert [g[:2] for g in got] == [(p.status, p.hops) for p in parent], (got, parent)
    assert all(g[2:] == (1, 1, 2) for g in got), got
    print("ok", got)
""")


def test_a_child_forked_after_the_engine_ran_runs_on_one_thread(tmp_path):
    # In a session of its own, so that a hang kills the pool's children too, not just their
    # parent (orphans would hold the machine's cores for the rest of the suite).
    p = subprocess.Popen([sys.executable, "-c", FORKED, str(tmp_path / "child.ck")],
                         stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        out, err = p.communicate(timeout=120)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, err = p.communicate()
        pytest.fail("the forked children hung: " + out + err)
    assert p.returncode == 0 and out.startswith("ok"), out + err


def test_threads_writing_one_output_each_leave_a_whole_file(tmp_path):
    out = tmp_path / "same.json"
    errors, seen = [], []

    def write(seed):
        for _ in range(10):
            try:
                hpcplan.grid.solve(dims=3, extent=30, seed=seed, path=True, output=str(out))
                seen.append(json.loads(out.read_text())["seed"])
            except Exception as e:  # a failed rename or a torn file
                errors.append(repr(e))

    threads = [threading.Thread(target=write, args=(s,)) for s in (1, 2, 3, 4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors, errors[:3]
    assert len(seen) == 40 and set(seen) <= {1, 2, 3, 4}
    assert [p.name for p in tmp_path.iterdir()] == ["same.json"]  # no temporary left
