#!/usr/bin/env python3
"""Markdown tables from hpcplan_world_sweep CSVs (medians and interquartile ranges).

  world_tables.py map3d SWEEP.csv REFERENCE.csv   every planner on every box map against the
                                                  stand-in optimum (best RRT* run) and the best
                                                  known length, and the issue-6 targets
  world_tables.py sphere SWEEP.csv [PLOT.png]     A* against the seed 003 hybrids: success,
                                                  time and length, median [q1, q3]
"""
import csv
import statistics as st
import sys
from collections import defaultdict


def quartiles(values):
    if len(values) == 1:
        return values[0], values[0], values[0]
    q = st.quantiles(values, n=4, method="inclusive")
    return q[0], st.median(values), q[2]


def fmt(x, digits=3):
    return f"{x:.{digits}f}"


def ms(x):
    """Milliseconds: two decimals below 10 ms, so sub-millisecond plans do not read as 0."""
    return f"{x:.2f}" if x < 10 else f"{x:.1f}"


def load(path):
    groups = defaultdict(list)
    for r in csv.DictReader(open(path)):
        groups[(r["map"], r["config"])].append(r)
    return groups


def map3d(sweep, reference):
    ref = defaultdict(list)
    for r in csv.DictReader(open(reference)):
        ref[r["map"]].append(r)
    groups = load(sweep)
    maps = sorted({m for m, _ in groups})
    targets = []
    for m in maps:
        rrt = [r for r in ref[m] if r["planner"] == "rrtstar"]
        cross = [r for r in ref[m] if r["planner"] != "rrtstar"]
        stand_in = min(float(r["length"]) for r in rrt)
        best = min([stand_in] + [float(r["length"]) for r in cross])
        seconds = "/".join(sorted({r["seconds"] for r in rrt}))
        cross_text = "".join(f"; {r['planner']}+shortcut {float(r['length']):.4f}" for r in cross)
        print(f"\n**{m}** — stand-in optimum {stand_in:.4f} (best of {len(rrt)} RRT* runs of "
              f"{seconds} s, shortcut){cross_text}; best known {best:.4f}\n")
        print("| planner | solved | time ms median [q1, q3] | length median | / stand-in | / best known | expanded or tree |")
        print("|---|---|---|---|---|---|---|")
        fast_within = []
        for (mm, c), rows in groups.items():
            if mm != m:
                continue
            ok = [r for r in rows if r["status"] == "solved"]
            t = quartiles([float(r["time_ms"]) for r in rows])
            if ok:
                lengths = [float(r["length"]) for r in ok]
                L = st.median(lengths)
                work = st.median([int(r["expanded"]) or int(r["tree_size"]) for r in ok])
                print(f"| {c} | {len(ok)}/{len(rows)} | {ms(t[1])} [{ms(t[0])}, {ms(t[2])}] | "
                      f"{fmt(L, 4)} | {fmt(L / stand_in, 4)} | {fmt(L / best, 4)} | {int(work)} |")
                # The target is judged against the best known length, the stricter reference.
                if len(ok) == len(rows) and max(lengths) <= 1.01 * best and t[1] <= 100:
                    fast_within.append((t[1], c, L / best))
            else:
                print(f"| {c} | 0/{len(rows)} | {ms(t[1])} | – | – | – | – |")
        astar = [float(r["time_ms"]) for r in groups.get((m, "astar@0.1"), [])]
        targets.append((m, min(fast_within) if fast_within else None, st.median(astar) if astar else None))
    print("\n**Targets** (every run within 1% of the best known length, median ≤ 100 ms; "
          "26-connected A* at 0.1 in ≤ 1 s)\n")
    print("| map | fastest planner within 1% | its median ms | / best known | A*@0.1 median ms |")
    print("|---|---|---|---|---|")
    for m, fast, a in targets:
        f = f"{fast[1]} | {ms(fast[0])} | {fmt(fast[2], 4)}" if fast else "none | – | –"
        print(f"| {m} | {f} | {ms(a) if a is not None else '–'} |")


def sphere(sweep, plot=None):
    groups = load(sweep)
    print("| world | planner | success | time ms median [q1, q3] | length median [q1, q3] |")
    print("|---|---|---|---|---|")
    series = defaultdict(dict)
    for (m, c), rows in sorted(groups.items()):
        ok = [r for r in rows if r["status"] == "solved"]
        t = quartiles([float(r["time_ms"]) for r in rows])
        L = quartiles([float(r["length"]) for r in ok]) if ok else (0, 0, 0)
        print(f"| {m} | {c} | {len(ok)}/{len(rows)} | {fmt(t[1])} [{fmt(t[0])}, {fmt(t[2])}] | "
              f"{fmt(L[1])} [{fmt(L[0])}, {fmt(L[2])}] |")
        series[m][c] = ([float(r["time_ms"]) for r in rows], [float(r["length"]) for r in ok])
    if plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        worlds = sorted(series)
        fig, axes = plt.subplots(2, len(worlds), figsize=(7 * len(worlds), 8))
        for j, m in enumerate(worlds):
            cs = [c for c in series[m] if c != "rrtstar"]
            for i, what in enumerate(("time (ms)", "length")):
                ax = axes[i][j] if len(worlds) > 1 else axes[i]
                ax.boxplot([series[m][c][i] for c in cs], labels=cs, showfliers=False)
                ax.set_title(f"{m}: {what}, {len(series[m][cs[0]][0])} trials each")
                ax.tick_params(axis="x", rotation=45)
                if i == 0:
                    ax.set_yscale("log")
        fig.tight_layout()
        fig.savefig(plot, dpi=100)


if __name__ == "__main__":
    if len(sys.argv) >= 4 and sys.argv[1] == "map3d":
        map3d(sys.argv[2], sys.argv[3])
    elif len(sys.argv) >= 3 and sys.argv[1] == "sphere":
        sphere(sys.argv[2], sys.argv[3] if len(sys.argv) > 3 else None)
    else:
        print(__doc__, file=sys.stderr)
        sys.exit(2)
