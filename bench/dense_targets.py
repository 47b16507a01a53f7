#!/usr/bin/env python3
"""The dense engine's targets (issue 31), measured on this machine in one run.

  A. dense against sparse, the same query alternated round by round (median of the per-round
     ratios, with the lowest and highest): BFS and Dijkstra at 4D extent 40, Dijkstra at 6D
     extent 11; one thread each.
  B. 4D extent-100 BFS on one core (median of rounds).
  C. two OpenMP threads against one in one process, alternated, and
  D. two MPI ranks against one (hpcplan_mpi_scaling --engine dense --ceiling): the machine's
     ceiling (the serial search on both cores at once, same rounds) beside both, on the 4D
     extent-100 BFS, a 5D BFS and a 4D Dijkstra.
  E. with --big: the 5D extent-100 BFS (10^10 states) on two threads, once, with its wall time
     and peak resident memory, and a 6D extent-40 BFS; from their figures a prediction of the
     6D extent-100 BFS per rank count (stated as a prediction, never run here).

Rates are edges examined (generated successors) per second per core, to set beside Graph500's
per-core TEPS. Writes results/dense_targets.json (temporary file + rename) and prints Markdown.
Usage: python3 bench/dense_targets.py [--repeats N] [--big]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import time

import dense_runs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "bin", "hpcplan")
SCALING = os.path.join(ROOT, "build", "bin", "hpcplan_mpi_scaling")


def grid(args, timeout=3600):
    """One `hpcplan grid --json` run; returns the JSON object and the wall time and peak RSS."""
    return dense_runs.grid(CLI, args, timeout=timeout, who="dense_targets")


def alternated(a_args, b_args, repeats):
    """Runs a and b alternately; returns medians and the per-round a/b time ratios."""
    return dense_runs.alternated((CLI, a_args, 0), (CLI, b_args, 0), repeats, who="dense_targets")


def mpi_scaling(problem, repeats):
    env = dict(os.environ)
    if os.getuid() == 0:
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    csv = os.path.join(ROOT, "results", "dense_targets_mpi.csv.tmp")
    if os.path.exists(csv):
        os.remove(csv)
    cmd = ["mpirun", "-np", "2", SCALING, "--engine", "dense", *problem, "--repeats", str(repeats),
           "--ceiling", "--csv", csv]
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"dense_targets: {' '.join(cmd)} failed: {p.stderr.strip()[-500:]}")
    with open(csv) as f:
        header = f.readline().strip().split(",")
        rows = [dict(zip(header, line.strip().split(","))) for line in f if line.strip()]
    os.remove(csv)
    dist = next(r for r in rows if r["scheme"] == "dense_slabs")
    ceiling = next(r for r in rows if r["scheme"] == "ceiling")
    return {"serial_ms": float(dist["serial_median_ms"]), "ranks_ms": float(dist["median_ms"]),
            "speedup": float(dist["speedup_vs_serial"]), "speedup_min": float(dist["speedup_min"]),
            "speedup_max": float(dist["speedup_max"]), "ceiling": float(ceiling["speedup_vs_serial"]),
            "of_ceiling": float(dist["of_ceiling"]), "deviation": float(dist["workload_deviation_percent"])}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--big", action="store_true", help="also the 5D extent-100 and 6D extent-40 BFS")
    o = ap.parse_args()
    if o.repeats < 1:
        sys.exit("dense_targets: --repeats must be at least 1")
    for exe in (CLI, SCALING, "/usr/bin/time"):
        if not os.access(exe, os.X_OK):
            sys.exit(f"dense_targets: {exe} missing; build first (bash scripts/build.sh)")
    os.makedirs(os.path.join(ROOT, "results"), exist_ok=True)
    out = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "cores": os.cpu_count(),
           "repeats": o.repeats}
    one = ["--threads", "1"]

    # A. dense against sparse.
    engines = []
    for d, e, algo, target in [(4, 40, "bfs", 50), (4, 40, "dijkstra", 10), (6, 11, "dijkstra", 10)]:
        q = ["--dims", str(d), "--extent", str(e), "--algo", algo, *one]
        r = alternated([*q, "--engine", "sparse"], [*q, "--engine", "dense"], o.repeats)
        engines.append({"dims": d, "extent": e, "algo": algo, "target": target,
                        "sparse_ms": r["a_ms"], "dense_ms": r["b_ms"], "ratio": r["ratio"],
                        "ratio_min": r["ratio_min"], "ratio_max": r["ratio_max"],
                        "edges": r["b"]["generated"]})
    out["engines"] = engines

    # B. 4D extent 100 on one core.
    runs = [grid(["--dims", "4", "--extent", "100", "--algo", "bfs", "--engine", "dense", *one])
            for _ in range(o.repeats)]
    t = statistics.median(r["time_ms"] for r in runs)
    out["bfs4d100"] = {"ms": t, "edges": runs[0]["generated"], "states": runs[0]["expanded"],
                       "bytes": runs[0]["dense"]["bytes_per_rank"]}

    # C. threads; D. ranks, each beside the machine's ceiling.
    problems = [("4D e100 BFS", ["--dims", "4", "--extent", "100", "--algo", "bfs"]),
                ("5D e40 BFS", ["--dims", "5", "--extent", "40", "--algo", "bfs"]),
                ("4D e60 Dijkstra", ["--dims", "4", "--extent", "60", "--algo", "dijkstra"])]
    parallel = []
    for name, q in problems:
        r = alternated([*q, "--engine", "dense", *one], [*q, "--engine", "dense", "--threads", "2"],
                       o.repeats)
        m = mpi_scaling(q, o.repeats)
        parallel.append({"problem": name, "one_thread_ms": r["a_ms"], "two_threads_ms": r["b_ms"],
                         "threads_speedup": r["ratio"], "threads_min": r["ratio_min"],
                         "threads_max": r["ratio_max"], **{"ranks_" + k: v for k, v in m.items()}})
    out["parallel"] = parallel

    # E. the big runs, once each.
    if o.big:
        big = []
        for d, e in [(5, 100), (6, 40)]:
            r = grid(["--dims", str(d), "--extent", str(e), "--algo", "bfs", "--engine", "dense",
                      "--threads", "2", "--memory-budget", str(6 * 10**9)], timeout=7200)
            big.append({"dims": d, "extent": e, "status": r["status"], "ms": r["time_ms"],
                        "wall_s": r["_wall_s"], "rss_bytes": r["_rss_bytes"],
                        "bytes_per_rank": r["dense"]["bytes_per_rank"], "states": r["expanded"],
                        "edges": r["generated"], "levels": r["dense"]["levels"]})
        out["big"] = big
        # 6D extent 100, predicted: the 6D extent-40 run's core-seconds per lattice state and
        # bytes per lattice state, scaled to 10^12 states and divided over P ranks of 2 cores'
        # worth of this machine each (perfect division: an upper bound on speed).
        r6 = big[1]
        lattice6 = 40**6
        core_ns = r6["ms"] * 1e6 * 2 / lattice6
        byte_per_state = r6["bytes_per_rank"] / lattice6
        out["prediction_6d100"] = [
            {"ranks": p, "bytes_per_rank": byte_per_state * 1e12 / p,
             "hours": core_ns * 1e12 / (p * 2) / 1e9 / 3600} for p in (1, 16, 64, 256, 1024)]

    path = os.path.join(ROOT, "results", "dense_targets.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path + ".tmp", "w") as f:
        json.dump(out, f, indent=1)
    os.replace(path + ".tmp", path)
    report(out)


def report(out):
    print(f"Dense engine targets, {out['date']}, {out['cores']} cores, {out['repeats']} rounds\n")
    print("| query | sparse ms | dense ms | dense / sparse speed (min-max) | target | edges/s/core (dense) |")
    print("|---|---|---|---|---|---|")
    for r in out["engines"]:
        rate = r["edges"] / (r["dense_ms"] / 1e3)
        print(f"| {r['dims']}D e{r['extent']} {r['algo']} | {r['sparse_ms']:.0f} | {r['dense_ms']:.1f} | "
              f"{r['ratio']:.1f}x ({r['ratio_min']:.1f}-{r['ratio_max']:.1f}) | >= {r['target']}x | {rate / 1e6:.0f} M |")
    b = out["bfs4d100"]
    print(f"\n4D extent-100 BFS, one core: {b['ms']:.0f} ms (target <= 1000), {b['states']:,} states, "
          f"{b['edges'] / (b['ms'] / 1e3) / 1e6:.0f} M edges/s, {b['bytes'] / 1e6:.1f} MB\n")
    print("| problem | 1 thread ms | 2 threads | 1 rank ms | 2 ranks | ceiling (2 serial at once) | ranks of ceiling | deviation % |")
    print("|---|---|---|---|---|---|---|---|")
    for r in out["parallel"]:
        print(f"| {r['problem']} | {r['one_thread_ms']:.0f} | {r['threads_speedup']:.2f}x "
              f"({r['threads_min']:.2f}-{r['threads_max']:.2f}) | {r['ranks_serial_ms']:.0f} | "
              f"{r['ranks_speedup']:.2f}x ({r['ranks_speedup_min']:.2f}-{r['ranks_speedup_max']:.2f}) | "
              f"{r['ranks_ceiling']:.2f}x | {100 * r['ranks_of_ceiling']:.0f}% | {r['ranks_deviation']:.1f} |")
    for r in out.get("big", []):
        print(f"\n{r['dims']}D extent-{r['extent']} BFS, 2 threads: {r['status']}, {r['ms'] / 1e3:.1f} s search "
              f"({r['wall_s']:.1f} s wall), {r['states']:,} states over {r['levels']} levels, "
              f"{r['bytes_per_rank'] / 1e9:.2f} GB store, {r['rss_bytes'] / 1e9:.2f} GB peak resident, "
              f"{r['edges'] / (r['ms'] / 1e3) / 2 / 1e6:.0f} M edges/s per core")
    if "prediction_6d100" in out:
        print("\n6D extent-100 BFS (10^12 states), PREDICTED from the 6D extent-40 run (perfect division over "
              "ranks of 2 cores):")
        for p in out["prediction_6d100"]:
            print(f"- {p['ranks']} ranks: {p['bytes_per_rank'] / 1e9:.1f} GB per rank, {p['hours']:.2f} h")


if __name__ == "__main__":
    main()
