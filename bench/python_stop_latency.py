#!/usr/bin/python3
"""How soon a long call from Python returns after Ctrl-C or a StopSource's request.

  PYTHONPATH=build/python /usr/bin/python3 bench/python_stop_latency.py ctrl-c|stop [NAME...]

NAME: only the calls whose name contains it. Each call is asked to stop 0.5 s after it starts (ctrl-c: a real SIGINT sent to this process,
as a terminal sends it; stop: StopSource.request_stop() from a timer thread), three times;
prints one Markdown row per call: ms from the request to the call's return, min / median / max.
"""
import os
import signal
import sys
import tempfile
import threading
import time

import shutil

import hpcplan

WORK = tempfile.mkdtemp()  # the checkpoint's folder, removed at the end
calls = {
 "grid sparse 6D Dijkstra": lambda s: hpcplan.grid.solve(dims=6, algo='dijkstra', engine='sparse', extent=100, stop=s),
 "grid dense 5D BFS": lambda s: hpcplan.grid.solve(dims=5, algo='bfs', engine='dense', extent=90, stop=s),
 "grid dense 5D BFS, checkpoint=": lambda s: hpcplan.grid.solve(dims=5, algo='bfs', extent=50, checkpoint=os.path.join(WORK, 'run.ck'), stop=s),
 "map3d RRT*": lambda s: hpcplan.map3d.load('bench/maps/forest.txt').plan(algo='rrtstar', time=60, stop=s),
 "sph step": lambda s: hpcplan.sph.Fluid(preset='seed', particles=3000).step(frames=100000, stop=s),
 # A large fluid stops at its frame's end: 35,000 particles with the walls, ~266 substeps a
 # frame. Built once, before its trials (building is not interruptible).
 "sph step, water dam break 2,000": lambda s: water().step(frames=100000, stop=s),
 "sim run": lambda s: hpcplan.sim.run(particles=1500, runs=50, stop=s),
}
_water = []


def water():
    if not _water:
        _water.append(hpcplan.sph.Fluid(preset="water", scenario="dambreak", particles=2000))
    return _water[0]


if len(sys.argv) < 2 or sys.argv[1] not in ("ctrl-c", "stop"):
    sys.exit("usage: python_stop_latency.py ctrl-c|stop [NAME...]")
mode = sys.argv[1]
for name, call in calls.items():
    if len(sys.argv) > 2 and not any(n in name for n in sys.argv[2:]):
        continue
    if "water" in name:
        water()
    lat = []
    for _ in range(3):
        fired = []
        stop = hpcplan.StopSource()
        def go():
            fired.append(time.perf_counter())
            if mode == "ctrl-c":
                os.kill(os.getpid(), signal.SIGINT)
            else:
                stop.request_stop()
        threading.Timer(0.5, go).start()
        try:
            call(stop)
        except KeyboardInterrupt:
            pass
        lat.append((time.perf_counter() - fired[0]) * 1000)
    print(f"| {name} | {mode} | {min(lat):.1f} | {sorted(lat)[1]:.1f} | {max(lat):.1f} |")
shutil.rmtree(WORK)
