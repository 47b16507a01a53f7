#!/usr/bin/env python3
"""The dense engine's blocks over many ranks: what P <= 16 ranks measure here, and the model
it checks, stated for the 6D extent-100 BFS on 64 to 512 ranks.

  1. Measured (mpirun, oversubscribed past the cores): the 5D BFS on P = 1..16 ranks of one
     thread: levels, halo bytes and messages, the slowest rank's time in exchanges, each rank's
     search time and expansions, the cut and the peers; beside the decomposition of the same
     lattice (build/bin/hpcplan_dense_decomposition: each rank's ghost tiles, the tiles of other
     ranks next to its own).
  2. The halo model: merged, a step sends at most one 16-byte entry per ghost tile, and over a
     run a ghost tile is a target in about v levels (the wavefront takes a few levels to cross
     a tile). So halo bytes = 16 x v x (ghost tiles summed over ranks); v is fitted at P = 2
     and checked at every other P (the ratio measured / predicted).
  3. The compute model: a rank's search time is t_state x (its expansions), t_state from the
     one-rank run of a larger lattice (4D extent 100), checked against the busiest rank's
     expansions at P <= 16 (oversubscribed, so the measured wall also holds waiting for cores).
  4. The 6D extent-100 BFS on 64..512 ranks: the decomposition (memory per rank, peers, ghost
     tiles), levels extrapolated linearly in the extent from 6D extents 8..16 measured here,
     halo per level from the model, and the time: compute t_state x states / P x (tile
     imbalance), plus per level 2 messages per peer and an allreduce at a stated network
     latency and bandwidth (not measured here: no cluster).

Writes results/dense_blocks.json (temporary file + rename) and prints Markdown.
Usage: python3 bench/dense_blocks.py [--dims 5 --extent 24] [--max-ranks 16]
"""
import argparse
import json
import math
import os
import statistics
import subprocess
import sys

import dense_runs

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLI = os.path.join(ROOT, "build", "bin", "hpcplan")
DECOMP = os.path.join(ROOT, "build", "bin", "hpcplan_dense_decomposition")
ENTRY_BYTES = 16  # a BFS halo entry: tile index and a word of states
# The network the 6D prediction assumes (an InfiniBand cluster under Open MPI): one-way latency
# per message and bandwidth per rank. Stated, not measured.
ALPHA_S = 2e-6
BETA_BPS = 10e9


def grid(args, ranks=0):
    return dense_runs.grid(CLI, args, ranks, timeout=1800, who="dense_blocks")


def decomposition(dims, extent, ranks, threads=1):
    p = subprocess.run([DECOMP, "--dims", str(dims), "--extent", str(extent), "--ranks",
                        ",".join(map(str, ranks)), "--threads", str(threads)],
                       capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f"dense_blocks: {DECOMP} failed: {p.stderr.strip()}")
    return {j["ranks"]: j for j in map(json.loads, p.stdout.splitlines())}


def bfs_args(dims, extent):
    return ["--dims", str(dims), "--extent", str(extent), "--algo", "bfs", "--engine", "dense",
            "--threads", "1"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dims", type=int, default=5)
    ap.add_argument("--extent", type=int, default=24)
    ap.add_argument("--max-ranks", type=int, default=16)
    ap.add_argument("--rounds", type=int, default=3, help="runs per P (medians of times)")
    o = ap.parse_args()
    out = {"machine": os.uname().nodename, "cpus": os.cpu_count(), "dims": o.dims,
           "extent": o.extent, "alpha_s": ALPHA_S, "beta_bps": BETA_BPS}

    # 1. Measured at P <= max ranks.
    ps = [p for p in (1, 2, 3, 4, 6, 8, 12, 16) if p <= o.max_ranks]
    plans = decomposition(o.dims, o.extent, ps)
    rows = []
    for p in ps:
        runs = [grid(bfs_args(o.dims, o.extent), ranks=p if p > 1 else 0)
                for _ in range(o.rounds)]
        j, d = runs[-1], runs[-1]["dense"]
        if any(r["status"] != j["status"] or r["hops"] != j["hops"] for r in runs):
            sys.exit("dense_blocks: runs disagree")
        plan = plans[p]
        rows.append({"ranks": p, "status": j["status"], "hops": j["hops"],
                     "expanded": j["expanded"], "levels": d["levels"],
                     "cut_axis": d["cut_axis"], "peers_max": max(d["rank_peers"] or [0]),
                     "halo_bytes": d["halo_bytes"], "halo_messages": d["halo_messages"],
                     "exchange_ms": statistics.median(r["dense"]["exchange_ms"] for r in runs),
                     "time_ms": statistics.median(r["time_ms"] for r in runs),
                     "rank_expanded": d.get("rank_expanded") or [j["expanded"]],
                     "rank_search_ms": d.get("rank_search_ms") or [j["time_ms"]],
                     "ghost_tiles": sum(plan["ghost_tiles"]),
                     "tiles_max": max(plan["tiles"]), "tiles_mean": statistics.mean(plan["tiles"])})
    one = rows[0]
    if any(r["hops"] != one["hops"] or r["expanded"] != one["expanded"] for r in rows):
        sys.exit("dense_blocks: the ranks' answers differ from one rank's")

    # 2. The halo model, fitted at the first P > 1.
    fit = next((r for r in rows if r["ranks"] > 1 and r["ghost_tiles"]), None)
    v = fit["halo_bytes"] / (ENTRY_BYTES * fit["ghost_tiles"]) if fit else 0.0
    for r in rows:
        r["halo_predicted"] = ENTRY_BYTES * v * r["ghost_tiles"]
        r["halo_ratio"] = r["halo_bytes"] / r["halo_predicted"] if r["halo_predicted"] else None

    # 3. The compute model: t_state from a one-rank run of a larger lattice.
    big = grid(bfs_args(4, 100))
    t_state = big["time_ms"] / 1e3 / big["expanded"]
    for r in rows:
        r["busiest_expanded"] = max(r["rank_expanded"])
        r["compute_s_predicted"] = t_state * r["busiest_expanded"]
        # P ranks time-share the cores here: the busiest rank waits for the others' work too.
        r["shared_cores_s_predicted"] = max(t_state * r["busiest_expanded"],
                                            t_state * r["expanded"] / min(r["ranks"], out["cpus"]))
        r["rank_search_s_max"] = max(r["rank_search_ms"]) / 1e3
        r["sync_ms_per_level"] = (r["exchange_ms"] / r["levels"]) if r["levels"] else 0.0
    out.update({"measured": rows, "v_levels_per_ghost_tile": v, "t_state_ns": t_state * 1e9,
                "t_state_from": {"dims": 4, "extent": 100, "time_ms": big["time_ms"],
                                 "expanded": big["expanded"]}})

    # 4. 6D extent 100 on 64..512 ranks.
    level_runs = {e: grid(bfs_args(6, e))["dense"]["levels"] for e in (8, 12, 16)}
    es = sorted(level_runs)
    slope = (level_runs[es[-1]] - level_runs[es[0]]) / (es[-1] - es[0])
    levels100 = level_runs[es[-1]] + slope * (100 - es[-1])
    big_ps = [64, 128, 256, 512]
    plans6 = decomposition(6, 100, big_ps)
    # The states a BFS from the corner reaches: the lattice's free states, times the share of
    # them the measured lattice's BFS reached.
    states = plans6[big_ps[0]]["free_states"] * one["expanded"] / plans[1]["free_states"]
    model = []
    for p in big_ps:
        pl = plans6[p]
        peers = max(pl["peers"])
        ghost_max = max(pl["ghost_tiles"])
        halo_total = ENTRY_BYTES * v * sum(pl["ghost_tiles"])
        halo_rank_level = ENTRY_BYTES * v * ghost_max / levels100
        # A level's halo is held twice (the outboxes, then the bytes received and the inboxes),
        # and a busy level carries a few times the mean: 3 x the mean, twice.
        halo_buffers = 2 * 3 * halo_rank_level
        imbalance = max(pl["tiles"]) / statistics.mean(pl["tiles"])
        compute = t_state * states / p * imbalance
        sync = levels100 * (2 * peers * ALPHA_S + 2 * ALPHA_S * math.log2(p)
                            + halo_rank_level / BETA_BPS)
        model.append({"ranks": p, "cut_axis": pl["cut_axis"], "section_tiles": pl["section_tiles"],
                      "block_sections": pl["block_sections"], "blocks": pl["blocks"],
                      "bytes_per_rank_max": max(pl["planned_bytes"]),
                      "halo_buffer_bytes": halo_buffers,
                      "bytes_total": sum(pl["planned_bytes"]), "peers_max": peers,
                      "ghost_tiles_max": ghost_max, "ghost_bytes_max": ENTRY_BYTES * ghost_max,
                      "halo_bytes_total": halo_total,
                      "halo_bytes_per_rank_level": halo_rank_level,
                      "tile_imbalance": imbalance, "compute_s": compute, "sync_s": sync,
                      "time_s": compute + sync})
    out["model6d"] = {"levels_measured": level_runs, "levels_extent100": levels100,
                      "states": states, "rows": model}

    path = os.path.join(ROOT, "results", "dense_blocks.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path + ".tmp", "w") as f:
        json.dump(out, f, indent=1)
    os.replace(path + ".tmp", path)

    print(f"## Dense blocks: {o.dims}D extent {o.extent} BFS, P = 1..{o.max_ranks} ranks of one "
          f"thread on {out['cpus']} cores ({o.rounds} runs each)\n")
    print("| P | cut axis | peers (max) | ghost tiles | halo MB | predicted MB | ratio | "
          "levels | exchange ms/level | busiest rank's expansions | its compute (model) s | "
          "compute on the cores shared (model) s | slowest rank s | run s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        ratio = f"{r['halo_ratio']:.2f}" if r["halo_ratio"] else "-"
        print(f"| {r['ranks']} | {r['cut_axis']} | {r['peers_max']} | {r['ghost_tiles']} | "
              f"{r['halo_bytes'] / 1e6:.2f} | {r['halo_predicted'] / 1e6:.2f} | {ratio} | "
              f"{r['levels']} | {r['sync_ms_per_level']:.2f} | {r['busiest_expanded']} | "
              f"{r['compute_s_predicted']:.3f} | {r['shared_cores_s_predicted']:.3f} | "
              f"{r['rank_search_s_max']:.3f} | "
              f"{r['time_ms'] / 1e3:.3f} |")
    print(f"\nv = {v:.2f} levels per ghost tile (fitted at P = {fit['ranks'] if fit else '-'}); "
          f"t_state = {t_state * 1e9:.1f} ns (4D extent 100, one rank: "
          f"{big['time_ms']:.0f} ms for {big['expanded']} states)\n")
    print(f"## Model: 6D extent 100 BFS (levels {levels100:.0f}, extrapolated from "
          f"{level_runs}; {states:.3g} states; network {ALPHA_S * 1e6:.0f} us, "
          f"{BETA_BPS / 1e9:.0f} GB/s)\n")
    print("| P | cut axis | blocks | store GiB per rank | + halo buffers GiB | peers | "
          "ghost MiB (max) | halo MB per rank and level | tile imbalance | compute s | sync s | "
          "time s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    for m in model:
        print(f"| {m['ranks']} | {m['cut_axis']} | {m['blocks']} | "
              f"{m['bytes_per_rank_max'] / 2**30:.2f} | {m['halo_buffer_bytes'] / 2**30:.2f} | "
              f"{m['peers_max']} | "
              f"{m['ghost_bytes_max'] / 2**20:.1f} | {m['halo_bytes_per_rank_level'] / 1e6:.2f} | "
              f"{m['tile_imbalance']:.3f} | {m['compute_s']:.1f} | {m['sync_s']:.2f} | "
              f"{m['time_s']:.1f} |")


if __name__ == "__main__":
    main()
