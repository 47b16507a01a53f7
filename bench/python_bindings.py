#!/usr/bin/python3
"""The Python package against the executable it wraps, and against the work's own limits.

  PYTHONPATH=build/python /usr/bin/python3 bench/python_bindings.py [--bin build/bin/hpcplan]
      [--rounds 5] [--json OUT]

Measures, as medians of alternated rounds:
  1. a small query's cost from Python: hpcplan.grid.solve (field built per call), Field.solve
     (built once), and the CLI started per query (what a script parsing CLI output pays),
     against the engine's own search and set-up time reported inside each answer;
  2. Field.free on a million 4D states against the same lookup written in NumPy on the field's
     level tables, and against reading the input once (8 bytes a coordinate);
  3. a zero-copy view's cost (fluid.positions) at two particle counts, against copying it;
  4. a fluid stepped frame by frame from Python against hpcplan sph running the same frames;
  5. the simulator from Python against the CLI, for the same runs.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import numpy as np

import hpcplan


def median_time(fn, repeat):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bin", default="build/bin/hpcplan")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--json", default=None)
    a = ap.parse_args()
    out = {"machine": os.uname().nodename, "cpus": os.cpu_count(), "rounds": a.rounds}
    rows = []

    # 1. Small queries: 2D A* on the default field (extent 100), 200 queries a round.
    field = hpcplan.grid.Field(dims=2)
    rng = np.random.default_rng(1)
    cand = rng.integers(0, 100, size=(4000, 2))
    free = cand[field.free(cand)]
    queries = [(tuple(map(int, free[2 * k])), tuple(map(int, free[2 * k + 1]))) for k in range(200)]
    engine_ms, per = [], {"grid.solve": [], "Field.solve": [], "CLI per query": []}
    for _ in range(a.rounds):
        t = time.perf_counter()
        for s, g in queries:
            r = hpcplan.grid.solve(dims=2, start=s, goal=g)
        per["grid.solve"].append((time.perf_counter() - t) / len(queries))
        t = time.perf_counter()
        for s, g in queries:
            r = field.solve(start=s, goal=g)
            engine_ms.append(r.timings["time_ms"] + r.timings["setup_ms"])
        per["Field.solve"].append((time.perf_counter() - t) / len(queries))
        t = time.perf_counter()
        for s, g in queries[:20]:  # a process per query: 20 are enough
            json.loads(subprocess.run([a.bin, "grid", "--dims", "2", "--start",
                                       ",".join(map(str, s)), "--goal", ",".join(map(str, g)),
                                       "--json"], capture_output=True, text=True).stdout)
        per["CLI per query"].append((time.perf_counter() - t) / 20)
    engine = statistics.median(engine_ms) / 1000
    out["queries"] = {k: statistics.median(v) for k, v in per.items()}
    out["queries"]["engine"] = engine
    for k, v in per.items():
        m = statistics.median(v)
        rows.append((f"2D A* query, {k}", f"{m * 1e6:.0f} µs", f"{m / engine:.1f}× the engine's "
                     f"{engine * 1e6:.0f} µs", f"{per['CLI per query'][0] / m:.1f}× faster than "
                     "the CLI" if k != "CLI per query" else "—"))

    # 2. Field.free on 10^6 4D states.
    f4 = hpcplan.grid.Field(dims=4, extent=100)
    states = rng.integers(0, 100, size=(1_000_000, 4))
    tables = np.stack([f4.levels(k) for k in range(4)])
    t_free = median_time(lambda: f4.free(states), a.rounds)
    t_numpy = median_time(lambda: tables[np.arange(4), states].sum(axis=1) < f4.threshold,
                          a.rounds)
    assert (f4.free(states) == (tables[np.arange(4), states].sum(axis=1) < f4.threshold)).all()
    t_read = median_time(lambda: states.sum(), a.rounds)  # one pass over the input
    out["field_free"] = {"states": len(states), "s": t_free, "numpy_s": t_numpy,
                         "read_s": t_read}
    rows.append(("Field.free, 10^6 4D states", f"{len(states) / t_free / 1e6:.1f} M states/s",
                 f"{t_numpy / t_free:.1f}× NumPy on the same tables",
                 f"{t_free / t_read:.1f}× one read of the input "
                 f"({states.nbytes / t_read / 1e9:.1f} GB/s)"))

    # 3. Views: fluid.positions at two sizes, against a copy.
    for n in (1500, 100_000):
        fluid = hpcplan.sph.Fluid(preset="seed", particles=n)
        t_view = median_time(lambda: fluid.positions, 200)
        t_copy = median_time(lambda: np.array(fluid.positions), 20)
        out[f"view_{n}"] = {"view_s": t_view, "copy_s": t_copy}
        rows.append((f"fluid.positions, {n} particles", f"{t_view * 1e6:.1f} µs",
                     f"a copy: {t_copy * 1e6:.0f} µs ({t_copy / t_view:.0f}×)", "no copy made"))

    # 4. Stepping: 20 frames of the seed preset's 25,000 particles, frame by frame from Python
    # (the whole call, mean) against hpcplan sph --frames 20 (its median frame).
    py_ms, cli_ms = [], []
    for _ in range(a.rounds):
        fluid = hpcplan.sph.Fluid(preset="seed", particles=25000)
        t = time.perf_counter()
        for _ in range(20):
            fluid.step()
        py_ms.append((time.perf_counter() - t) / 20 * 1000)
        cli = json.loads(subprocess.run([a.bin, "sph", "--particles", "25000", "--frames", "20",
                                         "--json"], capture_output=True, text=True).stdout)
        cli_ms.append(cli["ms_per_frame_median"])
    out["step"] = {"python_ms_per_frame": statistics.median(py_ms),
                   "cli_ms_per_frame": statistics.median(cli_ms)}
    rows.append(("fluid.step() per frame, 25,000 particles",
                 f"{statistics.median(py_ms):.2f} ms",
                 f"{statistics.median(py_ms) / statistics.median(cli_ms):.2f}× hpcplan sph's "
                 f"{statistics.median(cli_ms):.2f} ms", "the whole call, from Python"))

    # 5. The simulator: 3 runs of the seed's particles scenario, from Python and from the CLI.
    kw = dict(particles=1500, runs=3, seed=1, max_sim_s=20)
    t_py = median_time(lambda: hpcplan.sim.run(**kw), a.rounds)
    t_cli = median_time(lambda: subprocess.run(
        [a.bin, "sim", "--particles", "1500", "--runs", "3", "--seed", "1", "--max-sim-s", "20",
         "--json"], capture_output=True, check=True), a.rounds)
    out["sim"] = {"python_s": t_py, "cli_s": t_cli}
    rows.append(("sim.run, 3 runs of 1,500 particles", f"{t_py:.2f} s",
                 f"{t_py / t_cli:.2f}× the CLI's {t_cli:.2f} s", ""))

    print("| measure | from Python | against | note |\n|---|---:|---|---|")
    for r in rows:
        print("| " + " | ".join(r) + " |")
    if a.json:
        with open(a.json + ".tmp", "w") as fh:
            json.dump(out, fh, indent=1)
        os.replace(a.json + ".tmp", a.json)


if __name__ == "__main__":
    sys.exit(main())
