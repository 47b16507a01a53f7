#!/usr/bin/env python3
"""Seed 002's Tables I, II, III and V (and the issue's targets) from `hpcplan ompl` CSVs.

Every run is assumed to have used the largest budget (--budget, default 20 s); smaller budgets
are read from the same runs: a one-shot planner succeeds within b iff its first solution came
by b, and an anytime planner's quality at b is that of its last improvement by b.

Usage: ompl_tables.py results/ompl/d*.csv [--budget 20] [--plots DIR]
"""
import argparse
import csv
import math
import statistics
from collections import defaultdict

BUDGETS = [0.5, 1, 2, 5, 10, 20]
ORDER = ["gridastar", "gridastar_lattice", "gridastar_mpi2", "fmt", "fmt_radius", "bitstar",
         "abitstar", "aitstar", "rrtconnect", "rrtstar", "informedrrtstar", "prmstar"]
LABEL = {"gridastar": "Grid A* + shortcut", "gridastar_lattice": "Grid A* (lattice path)",
         "gridastar_mpi2": "Grid A*, 2 MPI ranks", "fmt": "FMT* (k-nearest)",
         "fmt_radius": "FMT* (radius)", "bitstar": "BIT*", "abitstar": "ABIT*", "aitstar": "AIT*",
         "rrtconnect": "RRT-Connect"}
PEERS = ["bitstar", "abitstar", "aitstar", "rrtconnect"]


def num(x):
    return float(x) if x not in ("", None) else None


def med(values):
    v = [x for x in values if x is not None]
    return statistics.median(v) if v else None


def fmt(x, spec):
    return "-" if x is None else format(x, spec)


def load(paths):
    rows = []
    for p in paths:
        with open(p) as f:
            for r in csv.DictReader(f):
                r["dims"] = int(r["dims"])
                r["solved"] = r["solved"] == "1"
                for k in ("time_first_s", "quality_first", "time_best_s", "quality_best",
                          "quality_final", "time_s", "length_first", "smoothing_s"):
                    r[k] = num(r.get(k))
                r["collision_checks"] = int(r["collision_checks"])
                trace = []
                for item in (r.get("improvements") or "").split(";"):
                    if item:
                        t, length = item.split(":")
                        trace.append((float(t), float(length)))
                r["trace"] = trace
                rows.append(r)
    return rows


def quality_at(r, b):
    """Quality of run r at time b (None if unsolved by then)."""
    if not r["solved"] or r["time_first_s"] is None or r["time_first_s"] > b:
        return None
    if not r["trace"] or r["quality_first"] is None:
        return r["quality_final"]
    straight = r["length_first"] / r["quality_first"]
    best = None
    for t, length in r["trace"]:
        if t <= b:
            best = length / straight
    return best if best is not None else r["quality_final"]


def table(title, header, lines):
    out = [f"**{title}**", "", "| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    out += ["| " + " | ".join(line) + " |" for line in lines]
    return "\n".join(out) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("csv", nargs="+")
    ap.add_argument("--budget", type=float, default=20.0)
    ap.add_argument("--plots", help="write PNG plots into this folder")
    a = ap.parse_args()
    rows = load(a.csv)
    dims = sorted({r["dims"] for r in rows})
    by = defaultdict(list)
    for r in rows:
        by[(r["planner"], r["dims"])].append(r)
    planners = [p for p in ORDER if any(k[0] == p for k in by)]
    planners += sorted({k[0] for k in by} - set(planners))
    budgets = [b for b in BUDGETS if b <= a.budget + 1e-9]
    dh = [f"{d}D" for d in dims]
    anytime = {p for p in planners if any(r["trace"] and len(r["trace"]) > 1 or r["time_best_s"]
                                          for k, rs in by.items() if k[0] == p for r in rs)}

    def runs(p, d):
        return by.get((p, d), [])

    # Table I: median planning time (ms) over solved runs.
    lines = []
    for p in planners:
        name = LABEL.get(p, p)
        if p in anytime:
            lines.append([f"{name} - first"] + [fmt(med([r["time_first_s"] * 1e3 for r in runs(p, d) if r["solved"]]), ".2f") for d in dims])
            lines.append([f"{name} - best"] + [fmt(med([r["time_best_s"] * 1e3 for r in runs(p, d) if r["time_best_s"] is not None]), ".1f") for d in dims])
            lines.append([f"{name} - final"] + [fmt(med([r["time_s"] * 1e3 for r in runs(p, d) if r["solved"]]), ".0f") for d in dims])
        else:
            lines.append([name] + [fmt(med([r["time_first_s"] * 1e3 for r in runs(p, d) if r["solved"]]), ".2f") for d in dims])
    print(table("Table I — median planning time (ms), solved runs", ["planner"] + dh, lines))

    # Table II: success rate at the largest budget, and by budget.
    lines = []
    for p in planners:
        lines.append([LABEL.get(p, p)] + [fmt(sum(r["solved"] for r in runs(p, d)) / len(runs(p, d)) if runs(p, d) else None, ".2f") for d in dims])
    print(table(f"Table II — success rate within {a.budget:g} s (runs per cell: "
                f"{max(len(v) for v in by.values())})", ["planner"] + dh, lines))
    lines = []
    for p in planners:
        for b in budgets:
            cells = []
            for d in dims:
                rs = runs(p, d)
                cells.append(fmt(sum(1 for r in rs if r["solved"] and r["time_first_s"] <= b) / len(rs) if rs else None, ".2f"))
            lines.append([LABEL.get(p, p), f"{b:g}"] + cells)
    print(table("Table II-b — success rate by budget", ["planner", "budget s"] + dh, lines))

    # Table III: quality.
    lines = []
    for p in planners:
        name = LABEL.get(p, p)
        if p in anytime:
            lines.append([f"{name} - first"] + [fmt(med([r["quality_first"] for r in runs(p, d) if r["solved"]]), ".3f") for d in dims])
            lines.append([f"{name} - best"] + [fmt(med([r["quality_best"] for r in runs(p, d) if r["quality_best"] is not None]), ".3f") for d in dims])
            lines.append([f"{name} - final"] + [fmt(med([r["quality_final"] for r in runs(p, d) if r["solved"]]), ".3f") for d in dims])
        else:
            lines.append([name] + [fmt(med([r["quality_final"] for r in runs(p, d) if r["solved"]]), ".3f") for d in dims])
    print(table("Table III — solution quality (length / straight line), medians", ["planner"] + dh, lines))

    lines = []
    for p in [p for p in planners if p in anytime]:
        for b in budgets:
            lines.append([LABEL.get(p, p), f"{b:g}"] + [fmt(med([quality_at(r, b) for r in runs(p, d)]), ".3f") for d in dims])
    if lines:
        print(table("Table III-b — anytime planners' quality at each budget (runs solved by then)",
                    ["planner", "budget s"] + dh, lines))

    # Table V: collision checks.
    lines = []
    for p in planners:
        lines.append([LABEL.get(p, p)] + [fmt(med([r["collision_checks"] for r in runs(p, d)]), ".3g") for d in dims])
    print(table("Table V — collision checks per run (medians; anytime planners: whole budget)",
                ["planner"] + dh, lines))

    # The issue's targets.
    if "gridastar" in planners and "bitstar" in planners:
        lines = []
        for d in dims:
            g = med([r["time_first_s"] for r in runs("gridastar", d) if r["solved"]])
            gl = med([r["time_first_s"] for r in runs("gridastar_lattice", d) if r["solved"]])
            bf = med([r["time_first_s"] for r in runs("bitstar", d) if r["solved"]])
            gq = med([r["quality_final"] for r in runs("gridastar", d) if r["solved"]])
            # The smoothed answer over the lattice answer within each run (older CSVs lack it).
            sx = med([r["time_first_s"] / (r["time_first_s"] - r["smoothing_s"])
                      for r in runs("gridastar", d)
                      if r["solved"] and r.get("smoothing_s") and r["time_first_s"] > r["smoothing_s"]])
            bq = med([r["quality_final"] for r in runs("bitstar", d) if r["solved"]])
            worst = None  # the budget where BIT* comes closest to the grid quality
            for b in budgets:
                q = med([quality_at(r, b) for r in runs("bitstar", d)])
                if q is not None and (worst is None or q < worst):
                    worst = q
            lines.append([f"{d}D", fmt(g and g * 1e3, ".2f"), fmt(gl and gl * 1e3, ".2f"),
                          fmt(bf and bf * 1e3, ".2f"),
                          fmt(bf / g if bf and g else None, ".1f"),
                          fmt(bf / gl if bf and gl else None, ".1f"),
                          fmt(sx, ".2f"), fmt(gq, ".3f"), fmt(bq, ".3f"),
                          "yes" if gq is not None and (bq is None or gq <= bq + 1e-9) else "no"])
        print(table("Targets — grid A* vs BIT* (medians)",
                    ["d", "grid+shortcut ms", "grid lattice ms", "BIT* first ms",
                     "ratio (shortcut)", "ratio (lattice)", "smoothed ÷ lattice, same run",
                     "grid+shortcut quality",
                     "BIT* final quality", "grid ≤ BIT* final"], lines))

    # Peers side by side: every planner's median time to a first solution and success rate on
    # the same world, and each peer's time over the grid planner's (lattice path and smoothed).
    shown = [p for p in ["gridastar_lattice", "gridastar"] + PEERS if p in planners]
    if len(shown) > 1:
        lines = []
        for d in dims:
            cells = []
            for p in shown:
                rs = runs(p, d)
                t = med([r["time_first_s"] * 1e3 for r in rs if r["solved"]])
                rate = sum(r["solved"] for r in rs) / len(rs) if rs else None
                cells.append(f"{fmt(t, '.2f')} ({fmt(rate, '.0%')})" if rs else "-")
            gl = med([r["time_first_s"] for r in runs("gridastar_lattice", d) if r["solved"]])
            gs = med([r["time_first_s"] for r in runs("gridastar", d) if r["solved"]])
            for p in [p for p in PEERS if p in shown]:
                t = med([r["time_first_s"] for r in runs(p, d) if r["solved"]])
                cells.append(f"{fmt(t / gl if t and gl else None, '.1f')} / "
                             f"{fmt(t / gs if t and gs else None, '.1f')}")
            lines.append([f"{d}D"] + cells)
        header = ["d"] + [f"{LABEL.get(p, p)} ms (solved)" for p in shown] + \
                 [f"{LABEL.get(p, p)} ÷ grid lattice / smoothed" for p in PEERS if p in shown]
        print(table("Peers side by side — median time to a first solution (ms) and success rate; "
                    "ratios > 1: the grid planner is faster", header, lines))

    if a.plots:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for p in planners:
            ys = [med([r["time_first_s"] * 1e3 for r in runs(p, d) if r["solved"]]) for d in dims]
            xs = [d for d, y in zip(dims, ys) if y is not None]
            ys = [y for y in ys if y is not None]
            if ys:
                ax.plot(xs, ys, marker="o", label=LABEL.get(p, p) + (" (first)" if p in anytime else ""))
        ax.set_yscale("log")
        ax.set_xlabel("dimension d")
        ax.set_ylabel("median time to (first) solution, ms")
        ax.set_xticks(dims)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(f"{a.plots}/planning_time.png", dpi=120)
        fig, ax = plt.subplots(figsize=(7, 4.5))
        for p in planners:
            ys = [med([r["quality_final"] for r in runs(p, d) if r["solved"]]) for d in dims]
            xs = [d for d, y in zip(dims, ys) if y is not None]
            ys = [y for y in ys if y is not None]
            if ys:
                ax.plot(xs, ys, marker="o", label=LABEL.get(p, p) + (" (final)" if p in anytime else ""))
        ax.plot(dims, [math.sqrt(d / 2) for d in dims], "k:", label="lattice limit sqrt(d/2)")
        ax.set_xlabel("dimension d")
        ax.set_ylabel("median quality (length / straight line)")
        ax.set_xticks(dims)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
        fig.tight_layout()
        fig.savefig(f"{a.plots}/quality.png", dpi=120)
        print(f"plots: {a.plots}/planning_time.png, {a.plots}/quality.png")


if __name__ == "__main__":
    main()
