#!/usr/bin/env python3
"""The dense engine against its physical floor and its issue-49 targets, on this machine.

  1. The machine's memory bandwidth (build/bin/hpcplan_memory_bandwidth: streaming reads and
     read-modify-writes on 1 and 2 threads).
  2. The 4D extent-100 BFS on one thread: median time of alternated rounds (against --old, a
     build of an earlier commit, when given: the ratio round by round), the active set's tile
     visits, and from them the bytes the store moves (each visit reads and writes the tile's
     3 words: 48 bytes) per state and the floor time at the measured bandwidth, beside the
     floor of sweeping every tile every level.
  3. Two threads against one, and two MPI ranks of one thread (mpirun --bind-to core) against
     one, alternated round by round: the medians of the per-round ratios.
  4. Dense Dijkstra at 4D extent 60 and 6D extent 11 on one thread (against --old when given).
  5. With --big: the 5D extent-100 BFS on two threads, once: its time and peak resident memory.

Writes results/dense_floor.json (temporary file + rename) and prints Markdown.
Usage: python3 bench/dense_floor.py [--rounds N] [--old PATH/TO/OLD/hpcplan] [--big]
"""
import argparse
import json
import os
import statistics
import subprocess
import sys

import dense_runs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "bin", "hpcplan")
BANDWIDTH = os.path.join(ROOT, "build", "bin", "hpcplan_memory_bandwidth")
BYTES_PER_VISIT = 48  # a BFS tile visit reads and writes its 3 store words


def grid(binary, args, ranks=0, timeout=3600):
    return dense_runs.grid(binary, args, ranks, timeout, who="dense_floor")


def alternated(a, b, rounds):
    return dense_runs.alternated(a, b, rounds, who="dense_floor")


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--old", help="an earlier build's hpcplan, run alternately as the baseline")
    ap.add_argument("--big", action="store_true", help="also the 5D extent-100 BFS (minutes)")
    o = ap.parse_args()
    out = {"rounds": o.rounds, "machine": os.uname().nodename, "cpus": os.cpu_count()}
    bw = json.loads(subprocess.run([BANDWIDTH, "--mib", "1024", "--threads", "2"],
                                   capture_output=True, text=True, check=True).stdout)
    out["bandwidth"] = bw
    md = ["| figure | value |", "|---|---|",
          f"| memory bandwidth, read (1 / 2 threads) | {bw['read_gbs']['1']} / "
          f"{bw['read_gbs']['2']} GB/s |",
          f"| memory bandwidth, read-modify-write (1 / 2 threads) | {bw['rmw_gbs']['1']} / "
          f"{bw['rmw_gbs']['2']} GB/s |"]

    bfs4 = ["--dims", "4", "--extent", "100", "--algo", "bfs", "--engine", "dense"]
    one = (CLI, bfs4 + ["--threads", "1"], 0)
    if o.old:
        r = alternated((o.old, one[1], 0), one, o.rounds)
        new = r["b"]
        out["bfs4_vs_old"] = {k: v for k, v in r.items() if k not in ("a", "b")}
        md.append(f"| 4D e100 BFS, 1 thread: old / new (median ratio, min-max) | "
                  f"{r['a_ms']:.0f} / {r['b_ms']:.0f} ms ({r['ratio']:.2f}x, "
                  f"{r['ratio_min']:.2f}-{r['ratio_max']:.2f}) |")
        t1 = r["b_ms"]
    else:
        runs = [grid(*one) for _ in range(o.rounds)]
        new = runs[-1]
        t1 = statistics.median(x["time_ms"] for x in runs)
        md.append(f"| 4D e100 BFS, 1 thread (median) | {t1:.0f} ms |")
    d = new["dense"]
    visits, reached = d["active_tiles"], d["reached"]
    moved = visits * BYTES_PER_VISIT
    sweep = d["levels"] * d["tiles"] * BYTES_PER_VISIT
    rmw = bw["rmw_gbs"]["1"] * 1e9
    floor = {"tile_visits": visits, "tiles": d["tiles"], "levels": d["levels"],
             "visits_per_tile": visits / d["tiles"], "bytes_moved": moved,
             "bytes_per_state": moved / reached, "floor_ms": moved / rmw * 1e3,
             "sweep_floor_ms": sweep / rmw * 1e3, "median_ms": t1,
             "peak_active": max(d["step_active_tiles"])}
    out["bfs4_floor"] = floor
    md += [f"| 4D e100 BFS: tile visits (per tile), peak per level | {visits} "
           f"({floor['visits_per_tile']:.2f}), {floor['peak_active']} |",
           f"| bytes the store moves per state reached | {floor['bytes_per_state']:.3f} |",
           f"| floor at the measured bandwidth: active set / sweeping every tile | "
           f"{floor['floor_ms']:.1f} / {floor['sweep_floor_ms']:.0f} ms |",
           f"| time over the active-set floor | {t1 / floor['floor_ms']:.1f}x |"]

    r = alternated(one, (CLI, bfs4 + ["--threads", "2"], 0), o.rounds)
    out["threads2"] = {k: v for k, v in r.items() if k not in ("a", "b")}
    md.append(f"| 4D e100 BFS, 2 threads over 1 (median ratio, min-max) | {r['ratio']:.2f}x "
              f"({r['ratio_min']:.2f}-{r['ratio_max']:.2f}) |")
    if dense_runs.MPIRUN:
        r = alternated(one, (CLI, bfs4 + ["--threads", "1"], 2), o.rounds)
        out["ranks2"] = {k: v for k, v in r.items() if k not in ("a", "b")}
        md.append(f"| 4D e100 BFS, 2 ranks x 1 thread over 1 (median ratio, min-max) | "
                  f"{r['ratio']:.2f}x ({r['ratio_min']:.2f}-{r['ratio_max']:.2f}) |")

    for dims, extent in ((4, 60), (6, 11)):
        args = ["--dims", str(dims), "--extent", str(extent), "--algo", "dijkstra",
                "--engine", "dense", "--threads", "1"]
        key = f"dijkstra{dims}d_e{extent}"
        if o.old:
            r = alternated((o.old, args, 0), (CLI, args, 0), o.rounds)
            out[key] = {k: v for k, v in r.items() if k not in ("a", "b")}
            md.append(f"| {dims}D e{extent} Dijkstra, 1 thread: old / new | {r['a_ms']:.0f} / "
                      f"{r['b_ms']:.0f} ms ({r['ratio']:.2f}x) |")
        else:
            t = statistics.median(grid(CLI, args)["time_ms"] for _ in range(o.rounds))
            out[key] = {"median_ms": t}
            md.append(f"| {dims}D e{extent} Dijkstra, 1 thread (median) | {t:.0f} ms |")

    if o.big:
        j = grid(CLI, ["--dims", "5", "--extent", "100", "--algo", "bfs", "--engine", "dense",
                       "--threads", "2"], timeout=7200)
        out["bfs5"] = {"time_ms": j["time_ms"], "rss_bytes": j["_rss_bytes"],
                       "tile_visits": j["dense"]["active_tiles"], "status": j["status"]}
        md.append(f"| 5D e100 BFS, 2 threads | {j['time_ms'] / 1e3:.1f} s, "
                  f"{j['_rss_bytes'] / 2**30:.2f} GiB resident |")

    os.makedirs(os.path.join(ROOT, "results"), exist_ok=True)
    path = os.path.join(ROOT, "results", "dense_floor.json")
    with open(path + ".tmp", "w") as f:
        json.dump(out, f, indent=1)
    os.replace(path + ".tmp", path)
    print("\n".join(md))


if __name__ == "__main__":
    main()
