"""The GIL is released during long calls, a StopSource cancels them from another thread, and
Ctrl-C stops them through the engine's stop token.

No test here depends on the machine's speed: a stop or a Ctrl-C goes once the call it ends is
seen running (not after a sleep), every call ended so is one that runs for far longer than any
test waits, and a time bound is a guard, far beyond what the call needs, that turns a hang into a
failure, never the assertion (bench/python_stop_latency.py measures the latencies)."""
import contextlib
import ctypes
import faulthandler
import inspect
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

_libc = ctypes.CDLL(None, use_errno=True)


def sigint_handler():
    """SIGINT's handler as the kernel has it: Python's, or the module's Ctrl-C relay."""
    action = ctypes.create_string_buffer(256)  # a struct sigaction: its handler comes first
    if _libc.sigaction(signal.SIGINT, None, action) != 0:
        raise OSError(ctypes.get_errno(), "sigaction")
    return ctypes.c_void_p.from_buffer(action).value


def once_running(then, guard_s=120.0):
    """A thread that calls then(True) once a long call on the main thread is under way in the
    engine: once the call has released the GIL and put the module's Ctrl-C relay in SIGINT's
    place (interrupt_relay.hpp: the relay is there exactly while the engine runs), seen through
    sigaction(2), which ctypes calls without the GIL. A call not seen within guard_s gets
    then(False), so that the test ends, and fails on that."""
    idle = sigint_handler()

    def wait():
        end = time.monotonic() + guard_s
        while sigint_handler() == idle and time.monotonic() < end:
            time.sleep(0.0005)
        then(sigint_handler() != idle)

    t = threading.Thread(target=wait, daemon=True)
    t.start()
    return t


# The same for the child processes below, which get it as source.
RUNNING = "\n".join(["import ctypes, signal, threading, time",
                     "_libc = ctypes.CDLL(None, use_errno=True)",
                     inspect.getsource(sigint_handler), inspect.getsource(once_running)])


@pytest.fixture
def guard(request):
    """guard(seconds): a block past whose `seconds` (far beyond what it needs) every thread's
    stack is printed to the terminal and the process exits: the one way out of a call that
    hangs holding the GIL, and a failure."""
    capture = request.config.pluginmanager.getplugin("capturemanager")
    with capture.global_and_fixture_disabled() if capture else contextlib.nullcontext():
        terminal = os.fdopen(os.dup(sys.stderr.fileno()), "w")

    @contextlib.contextmanager
    def limit(seconds):
        faulthandler.dump_traceback_later(seconds, exit=True, file=terminal)
        try:
            yield
        finally:
            faulthandler.cancel_dump_traceback_later()

    yield limit
    terminal.close()


def test_a_second_thread_runs_during_a_solve(guard):
    # The second thread ends the solve: once the solve runs in the engine it ticks 20 times,
    # a millisecond apart, and then asks for the stop. A solve that held the GIL would keep it
    # from ticking and never end (the guard).
    stop = hpcplan.StopSource()
    ticks = []

    def tick(running):
        while running and len(ticks) < 20:
            ticks.append(time.perf_counter())
            time.sleep(0.001)
        stop.request_stop()

    with guard(120):
        t = once_running(tick)
        r = hpcplan.grid.solve(**LONG, stop=stop)
        t.join()
    assert r.status == "cancelled" and len(ticks) == 20, (r.status, len(ticks))


def test_a_stop_source_cancels_a_solve_within_a_poll(guard):
    stop = hpcplan.StopSource()
    requested = []

    def cancel(running):
        requested.append((running, time.perf_counter(), stop.request_stop()))

    with guard(120):
        t = once_running(cancel)
        r = hpcplan.grid.solve(**LONG, stop=stop)
        returned = time.perf_counter()
        t.join()
    running, at, first = requested[0]
    assert running and first and r.status == "cancelled" and r.cost is None, (requested, r)
    # The engine polls the stop at every expansion (well under a millisecond); the guard only
    # tells "cancelled in time" from a search that would otherwise have gone on for hours.
    assert returned - at < 10.0, returned - at
    assert stop.stop_requested and not stop.request_stop()  # only the first request counts


@pytest.mark.parametrize("call", ["dense", "plan", "fluid", "sim"])
def test_a_stop_source_ends_every_long_call(call, maps, guard):
    stop = hpcplan.StopSource()
    requested = []

    def request(running):
        requested.append((running, time.perf_counter()))
        stop.request_stop()

    # What the call works on is made first: making it is a call too.
    if call == "dense":
        run = lambda: hpcplan.grid.solve(dims=5, algo="bfs", engine="dense", extent=90, stop=stop)
    elif call == "plan":
        world = hpcplan.map3d.load(os.path.join(maps, "forest.txt"))
        # RRT* plans until its time is up: 120 s, far past the guard below.
        run = lambda: world.plan(algo="rrtstar", time=120, stop=stop)
    elif call == "fluid":
        fluid = hpcplan.sph.Fluid(preset="seed", particles=3000)
        run = lambda: fluid.step(frames=100000, stop=stop)
    else:
        run = lambda: hpcplan.sim.run(particles=1500, runs=50, max_sim_s=300, stop=stop)
    with guard(300):
        t = once_running(request)
        r = run()
        returned = time.perf_counter()
        t.join()
    running, at = requested[0]
    assert running, "the call was never seen running"
    if call == "dense":
        assert r.status == "cancelled"
    elif call == "plan":
        assert r.status in ("cancelled", "solved")  # RRT* keeps its best path when stopped
    elif call == "fluid":
        assert r["interrupted"] and r["frame"] < 100000
    else:
        assert r.status == "interrupted"
    # A guard: the call ends at its next poll (an expansion, a level, a frame: well under a
    # second); without the stop each of them would run for minutes or hours.
    assert returned - at < 30.0, returned - at


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



def test_a_fluid_is_used_by_one_thread_at_a_time(guard):
    fluid = hpcplan.sph.Fluid(preset="seed", particles=3000)
    stop = hpcplan.StopSource()
    t = threading.Thread(target=lambda: fluid.step(frames=100000, stop=stop))
    with guard(120):
        t.start()
        try:
            # The step is under way once the fluid refuses to be read (it never ends by
            # itself); a fluid that were never refused fails here, past a guard.
            end = time.monotonic() + 60
            while True:
                try:
                    fluid.frame
                except RuntimeError as e:
                    assert "in use by another thread" in str(e), e
                    break
                assert time.monotonic() < end, "the fluid was never refused during its step"
                time.sleep(0.001)
            with pytest.raises(RuntimeError, match="in use by another thread"):
                fluid.positions
            with pytest.raises(RuntimeError, match="in use by another thread"):
                fluid.step()
            for name in ("probes", "frame", "options", "backend", "boxes", "velocities", "time"):
                with pytest.raises(RuntimeError, match="in use by another thread"):
                    getattr(fluid, name)
        finally:
            stop.request_stop()
            t.join()
    assert fluid.positions.shape == (fluid.size, 3)


# Ctrl-C: a child Python process sends itself SIGINT during a long call, as a terminal does,
# once the call is seen running; the call must end with KeyboardInterrupt, the engine stopped
# through its token (without the relay it would run on for minutes or hours: the guards).
CTRL_C = RUNNING + textwrap.dedent("""
    import os, sys
    import hpcplan
    fired = []
    def interrupt(running):
        fired.append((running, time.perf_counter()))
        os.kill(os.getpid(), signal.SIGINT)
    {setup}
    once_running(interrupt)
    try:
        {call}
    except KeyboardInterrupt:
        running, at = fired[0]
        print("KeyboardInterrupt after", time.perf_counter() - at, "running", running)
        {after}
        sys.exit(0)
    print("no KeyboardInterrupt")
    sys.exit(1)
""")


@pytest.mark.parametrize("setup,call,after", [
    ("pass", "hpcplan.grid.solve(dims=6, algo='dijkstra', engine='sparse', extent=100)", "pass"),
    ("pass", "hpcplan.grid.solve(dims=5, algo='bfs', engine='dense', extent=90)", "pass"),
    # (The fluid is made first: making it is a call too.)
    ("f = hpcplan.sph.Fluid(preset='seed', particles=3000)", "f.step(frames=100000)", "pass"),
    ("pass", "hpcplan.sim.run(particles=1500, runs=50)", "pass"),
    # With a checkpoint, Ctrl-C stops the dense search at its next level with the checkpoint
    # written; a restart then continues to the uninterrupted answer.
    ("pass",
     "hpcplan.grid.solve(dims=4, algo='bfs', extent=100, threads=1, checkpoint=sys.argv[1])",
     "r = hpcplan.grid.solve(dims=4, algo='bfs', extent=100, threads=1, restart=sys.argv[1]); "
     "s = hpcplan.grid.solve(dims=4, algo='bfs', extent=100, threads=1); "
     "assert (r.status, r.hops, r.counters) == (s.status, s.hops, s.counters), (r, s); "
     "print('restarted', r.report['restarted_from'])"),
], ids=["sparse", "dense", "fluid", "sim", "checkpoint"])
def test_ctrl_c_stops_a_long_call(setup, call, after, tmp_path):
    script = CTRL_C.format(setup=setup, call=call, after=after)
    env = dict(os.environ)
    p = subprocess.run([sys.executable, "-c", script, str(tmp_path / "run.ck")],
                       capture_output=True, text=True, timeout=300, env=env)
    assert p.returncode == 0, p.stdout + p.stderr
    assert "running True" in p.stdout, p.stdout  # the signal reached the call under way
    latency = float(p.stdout.split("KeyboardInterrupt after")[1].split()[0])
    if "checkpoint" not in call:
        # A guard (the call ends at its next poll: well under a second).
        assert latency < 30.0, p.stdout
    else:
        # The search stopped part way: a search that ends writes no checkpoint, and this one
        # was written and restarted from. How soon is the disk's to say (a 27 MB file flushed:
        # 0.5 s alone, 4.3 s beside a compiler's writes), so only a hang is a failure here;
        # bench/python_stop_latency.py measures it.
        assert latency < 60.0, p.stdout
        assert "restarted" in p.stdout and (tmp_path / "run.ck").exists()


def test_a_step_ended_by_ctrl_c_still_counts_its_frames(tmp_path):
    script = RUNNING + textwrap.dedent("""
        import os
        import hpcplan
        f = hpcplan.sph.Fluid(preset="seed", particles=2000, threads=1)
        f.step(frames=2)
        once_running(lambda running: os.kill(os.getpid(), signal.SIGINT))
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
