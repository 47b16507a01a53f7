#!/usr/bin/python3
"""Seed 000's tables and figures from `hpcplan sim` results (bench/sim_sweep.sh folders, SLURM
sweep folders, or single CSVs), as Markdown and PNG.

Usage: sim_report.py RESULT [RESULT ...] [--out DIR]
       sim_report.py --simulate 'KEY=V1,V2;KEY=V;...' --out DIR
RESULT: a folder (its */*.csv and *.csv per-run files, with the matching *.replans.csv logs) or
a per-run CSV. Writes DIR/sim_report.md and DIR/fig{1,2,3,4}_*.png (DIR default: the first
folder) and prints the Markdown. --simulate runs the sweep itself, in this process, through the
Python package (hpcplan.sim.run: one run per combination of the values given, e.g.
'scenario=particles,dynamic;algo=astar,dstar_lite;particles=500,1500;runs=3'), and builds the
same tables from the rows it returns, with no CLI run and no CSV between.

Tables (the paper's numbering):
  II   time to goal by scenario (successful runs; mean +- sd), and the success rate
  III  planning time per replan call: mean (the paper's figure), p50, p99; failed replan rate
  IV   path length over successful replans, the paper's failure-weighted length, divergence
Figures: 1 time-to-goal distributions, 2 plan-time distributions, 3 scaling with particle
count (time to goal, mean plan time, failed replan rate), 4 the winner of each metric.
These come from the seed's controller, once per pacing present (figure names get a _realtime
suffix when lockstep runs are there too).

Beyond the paper: contacts (sim/safety.hpp): per scenario, planner and pacing, the frames in
contact with the seed's controller and with the reactive layer, their times to goal and the
ratio, and figure 5 (fig5_contacts.png): frames in contact against particle count, per planner,
pacing and controller.

Adaptive occupancy (beyond the paper; env/occupancy_world.hpp): when runs with a density
occupancy are present, a table compares each with the seed's occupancy on the settings both
ran (failed replans and why, frames in contact, time to goal, success) and figure 6
(fig6_occupancy.png) plots failed replans and frames in contact against particle count. The
seed's tables and the contact table use the seed's occupancy only.
"""
import argparse
import csv
import glob
import math
import os
import statistics
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from hpcplan_package import import_hpcplan, value  # noqa: E402

SCENARIOS = ["particles", "static", "dynamic", "dambreak"]
NAMES = {"particles": "Particles Only", "static": "Static Obstacles", "dynamic": "Dynamic Obstacles",
         "dambreak": "Dam Break"}
LABEL = {"astar": "A*", "astar_euclid": "A* (Euclid)", "dstar_lite": "D* Lite", "rrtstar": "RRT*"}


def run_files(paths):
    for p in paths:
        if os.path.isdir(p):
            found = sorted(set(glob.glob(os.path.join(p, "**", "*.csv"), recursive=True)))
            for f in found:
                if not f.endswith(".replans.csv"):
                    yield f
        elif p.endswith(".csv"):
            yield p
        else:
            sys.exit(f"sim_report: error: {p} is neither a folder nor a CSV")


def load(paths):
    runs, replans = [], []
    for f in run_files(paths):
        with open(f) as fh:
            rows = list(csv.DictReader(fh))
        if not rows or "time_to_goal_s" not in rows[0]:
            continue  # another kind of CSV in the folder
        for r in rows:
            r.setdefault("controller", "seed")  # CSVs from before the reactive layer
            if r["controller"] in ("", None):
                r["controller"] = "seed"
            if r.get("occupancy") in ("", None):  # CSVs from before adaptive occupancy
                r["occupancy"] = "particles"
        runs += rows
        log = f[:-4] + ".replans.csv"
        if os.path.exists(log):
            with open(log) as fh:
                rp = list(csv.DictReader(fh))
            first = rows[0]
            for r in rp:
                for k in ("scenario", "particle_count", "pace", "controller", "occupancy"):
                    r[k] = first.get(k, "")
            replans += rp
    if not runs:
        sys.exit("sim_report: error: no per-run CSV of hpcplan sim found")
    return runs, replans


def simulate(spec):
    """Every combination of the spec's values run through hpcplan.sim.run; the per-run and
    per-replan rows, each value as its CSV cell would read (the tables below take text)."""
    import itertools
    hpcplan = import_hpcplan("sim_report", "--simulate")

    keys, choices = [], []
    for item in filter(None, (x.strip() for x in spec.split(";"))):
        key, sep, values = item.partition("=")
        if not sep or not values:
            sys.exit(f"sim_report: error: --simulate: '{item}' is not KEY=V1,V2,...")
        keys.append(key.strip())
        choices.append([value(v.strip()) for v in values.split(",")])

    def text(v):
        return "" if v is None else str(v)

    runs, replans = [], []
    for combination in itertools.product(*choices):
        options = dict(zip(keys, combination))
        try:
            result = hpcplan.sim.run(**options)
        except (TypeError, ValueError) as e:
            sys.exit(f"sim_report: error: --simulate {options}: {e}")
        rows = [{k: text(v) for k, v in r.items()} for r in result.runs]
        print(f"sim_report: {options}: {len(rows)} runs", file=sys.stderr)
        for r in result.replans:
            r = {k: text(v) for k, v in r.items()}
            for k in ("scenario", "particle_count", "pace", "controller", "occupancy"):
                r[k] = rows[0].get(k, "") if rows else ""
            replans.append(r)
        runs += rows
    if not runs:
        sys.exit("sim_report: error: --simulate made no run")
    return runs, replans


def f(x):
    return float(x) if x not in ("", None) else math.nan


def mean_sd(xs):
    xs = [x for x in xs if not math.isnan(x)]
    if not xs:
        return math.nan, math.nan
    return statistics.fmean(xs), statistics.stdev(xs) if len(xs) > 1 else 0.0


def quantile(xs, q):
    xs = sorted(x for x in xs if not math.isnan(x))
    if not xs:
        return math.nan
    pos = q * (len(xs) - 1)
    i = int(pos)
    return xs[i] + (pos - i) * (xs[min(i + 1, len(xs) - 1)] - xs[i])


def fmt(x, d=2):
    return "–" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{d}f}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("results", nargs="*")
    ap.add_argument("--out", default=None)
    ap.add_argument("--simulate", default=None,
                    help="run this sweep in-process (hpcplan.sim.run) instead of reading RESULT")
    a = ap.parse_args()
    if bool(a.results) == bool(a.simulate):
        sys.exit("sim_report: error: give RESULT folders or CSVs, or --simulate, not both")
    if a.simulate and not a.out:
        sys.exit("sim_report: error: --simulate needs --out DIR")
    runs, replans = simulate(a.simulate) if a.simulate else load(a.results)
    all_runs, all_replans = runs, replans
    runs = [r for r in runs if r["occupancy"] == "particles"]
    replans = [r for r in replans if r["occupancy"] == "particles"]
    if not runs:  # a density-only folder: its own runs stand in for the seed's tables
        runs, replans = all_runs, all_replans
    out = a.out or (a.results[0] if os.path.isdir(a.results[0]) else os.path.dirname(a.results[0]) or ".")
    os.makedirs(out, exist_ok=True)
    md = []
    paces = sorted({r["pace"] for r in runs})
    seed_paces = [p for p in paces if any(r["pace"] == p and r["controller"] == "seed" for r in runs)]
    for i, pace in enumerate(seed_paces):
        seed_tables([r for r in runs if r["pace"] == pace and r["controller"] == "seed"],
                    [r for r in replans if r["pace"] == pace and r["controller"] == "seed"],
                    out, "" if i == 0 else f"_{pace}", md)
    contact_tables(runs, out, md)
    occupancy_tables(all_runs, all_replans, out, md)
    md.append(f"\nFigures: {', '.join(sorted(n for n in os.listdir(out) if n.startswith('fig')))} in {out}.\n")
    text = "\n".join(md)
    tmp = os.path.join(out, "sim_report.md.tmp")
    with open(tmp, "w") as fh:
        fh.write(text)
    os.replace(tmp, os.path.join(out, "sim_report.md"))
    print(text)


def contact_tables(runs, out, md):
    """Frames in contact per setting, and the reactive layer against the seed's controller."""
    # Runs from before the safety metrics have no contact columns: left out here.
    runs = [r for r in runs if r.get("contact_frames") not in (None, "")]
    if not runs:
        return
    lab = lambda x: LABEL.get(x, x)  # noqa: E731
    algos = sorted({r["algorithm"] for r in runs}, key=lambda x: list(LABEL).index(x) if x in LABEL else 99)
    scenarios = [s for s in SCENARIOS if any(r["scenario"] == s for r in runs)]
    paces = sorted({r["pace"] for r in runs})
    controllers = [c for c in ("seed", "reactive") if any(r["controller"] == c for r in runs)]
    radius = {r.get("robot_radius", "") for r in runs}

    def pooled(rs):  # frames in contact over every frame of these runs
        frames = sum(int(r["frames"]) for r in rs)
        return sum(int(r["contact_frames"]) for r in rs) / frames if frames else math.nan

    def ttg(rs):
        ok = [f(r["time_to_goal_s"]) for r in rs if r["success"] == "1"]
        return statistics.fmean(ok) if ok else math.nan

    md.append("\n## Contacts: does the robot touch the fluid? (beyond the paper)\n")
    md.append("Frames in contact: frames whose clearance (robot ball of radius 0.05 against particle "
              "balls of 0.05 and the boxes, on the physics frame) is negative, over every frame of "
              "the runs; p95: the 95th percentile of the runs' own rates; contacts: entries into "
              "contact per run. Time to goal: successful runs, mean (s). Where both controllers "
              "ran a planner and pacing, only the scenarios and particle counts both ran count.\n")
    head = "| Scenario | Planner | Pacing | " + " | ".join(
        f"{c}: frames in contact (p95) | {c}: contacts/run | {c}: max overlap | {c}: time to goal | {c}: success"
        for c in controllers)
    if len(controllers) == 2:
        head += " | time to goal, reactive / seed |"
    else:
        head += " |"
    md.append(head)
    md.append("|" + "---|" * (3 + 5 * len(controllers) + (len(controllers) == 2)))
    for pace in paces:
        for x in algos:
            for s in scenarios + ["all"]:
                cells, t = [], {}
                # With both controllers, the settings both ran (scenario and particle count), so
                # that the ratio compares like with like while a sweep is incomplete.
                ran = [{(r["scenario"], r["particle_count"]) for r in runs if r["pace"] == pace and
                        r["algorithm"] == x and r["controller"] == c} for c in controllers]
                both = set.intersection(*ran) if len(controllers) == 2 and all(ran) else None
                for c in controllers:
                    rs = [r for r in runs if r["pace"] == pace and r["algorithm"] == x and
                          r["controller"] == c and (s == "all" or r["scenario"] == s) and
                          (both is None or (r["scenario"], r["particle_count"]) in both)]
                    if not rs:
                        cells += ["–"] * 5
                        t[c] = math.nan
                        continue
                    rates = [int(r["contact_frames"]) / int(r["frames"]) for r in rs if int(r["frames"])]
                    t[c] = ttg(rs)
                    cells += [f"{fmt(100 * pooled(rs), 2)}% ({fmt(100 * quantile(rates, .95), 1)}%)",
                              fmt(statistics.fmean(int(r["contacts"]) for r in rs), 2),
                              fmt(max(f(r["max_overlap"]) for r in rs), 3), fmt(t[c]),
                              f"{sum(r['success'] == '1' for r in rs)}/{len(rs)}"]
                if all(c == "–" for c in cells):
                    continue
                row = f"| {NAMES.get(s, 'All scenarios')} | {lab(x)} | {pace} | " + " | ".join(cells)
                if len(controllers) == 2:
                    ratio = t["reactive"] / t["seed"] if t["seed"] and not math.isnan(t["seed"]) else math.nan
                    row += f" | {fmt(ratio)}× |"
                else:
                    row += " |"
                md.append(row)
    # Figure 5: frames in contact against particle count.
    counts = sorted({int(r["particle_count"]) for r in runs})
    colours = {x: c for x, c in zip(algos, ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"])}
    fig, axes = plt.subplots(1, len(paces), figsize=(6 * len(paces), 4), squeeze=False)
    for ax, pace in zip(axes[0], paces):
        for x in algos:
            for c in controllers:
                ys = []
                for n in counts:
                    rs = [r for r in runs if r["pace"] == pace and r["algorithm"] == x and
                          r["controller"] == c and int(r["particle_count"]) == n]
                    ys.append(100 * pooled(rs) if rs else math.nan)
                if all(math.isnan(y) for y in ys):
                    continue
                ax.plot(counts, ys, "-" if c == "seed" else "--", marker="o" if c == "seed" else "s",
                        ms=3, color=colours[x], label=f"{lab(x)}, {c} controller")
        ax.axhline(1.0, color="grey", lw=0.8, ls=":")
        ax.set_xlabel("particles")
        ax.set_ylabel("frames in contact (%)")
        ax.set_title(f"{pace} pacing, all scenarios")
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig5_contacts.png"), dpi=100)
    plt.close(fig)


def occupancy_tables(runs, replans, out, md):
    """Each density occupancy against the seed's, on the settings (scenario, planner, pacing,
    controller, particle count) both ran."""
    runs = [r for r in runs if r.get("contact_frames") not in (None, "")]
    rules = sorted({r["occupancy"] for r in runs} - {"particles"})
    if not rules:
        return
    lab = lambda x: LABEL.get(x, x)  # noqa: E731
    key = lambda r: (r["scenario"], r["algorithm"], r["pace"], r["controller"], r["particle_count"])  # noqa: E731
    base = {key(r) for r in runs if r["occupancy"] == "particles"}

    def stats(rs, ps):
        frames = sum(int(r["frames"]) for r in rs)
        ok = [f(r["time_to_goal_s"]) for r in rs if r["success"] == "1"]
        ends = sum(p["reason"] in ("start_blocked", "goal_blocked") for p in ps)
        failed = sum(p["status"] != "solved" for p in ps)
        return {"fail": failed / len(ps) if ps else math.nan,
                "ends": ends / len(ps) if ps else math.nan,
                "contact": sum(int(r["contact_frames"]) for r in rs) / frames if frames else math.nan,
                "ttg": statistics.fmean(ok) if ok else math.nan,
                "success": f"{len(ok)}/{len(rs)}"}

    md.append("\n## Adaptive occupancy: the SPH density thresholded on the grid (beyond the paper)\n")
    md.append("Each density rule (density:SUPPORT:THRESHOLD, in particle equivalents) against the "
              "seed's occupancy (a cell blocked by any particle within 0.14 of its centre), on the "
              "same settings and particle counts. Failed: replans that found no path (blocked ends: "
              "those where the robot or the goal had no free cell within reach); contact: frames in "
              "contact; time to goal: successful runs, mean (s).\n")
    md.append("| Scenario | Planner | Pacing | Controller | Occupancy | counts | failed replans "
              "(blocked ends) | frames in contact | time to goal | success | failed, density / seed "
              "| time to goal, density / seed |")
    md.append("|" + "---|" * 12)
    groups = sorted({key(r)[:4] for r in runs if r["occupancy"] != "particles"})
    for g in groups:
        for rule in rules:
            keys = {key(r) for r in runs if r["occupancy"] == rule and key(r)[:4] == g} & base
            if not keys:
                continue
            counts = sorted({int(k[4]) for k in keys})
            res = {}
            for o in ("particles", rule):
                rs = [r for r in runs if r["occupancy"] == o and key(r) in keys]
                ps = [p for p in replans if p["occupancy"] == o and key(p) in keys and
                      p["reason"] != "cancelled"]
                res[o] = stats(rs, ps)
            for o in ("particles", rule):
                x = res[o]
                row = (f"| {NAMES.get(g[0], g[0])} | {lab(g[1])} | {g[2]} | {g[3]} | {o} | "
                       f"{len(counts)} ({counts[0]}–{counts[-1]}) | {fmt(100 * x['fail'], 1)}% "
                       f"({fmt(100 * x['ends'], 1)}%) | {fmt(100 * x['contact'], 2)}% | "
                       f"{fmt(x['ttg'])} | {x['success']} | ")
                if o == rule:
                    b = res["particles"]
                    row += (f"{fmt(x['fail'] / b['fail']) if b['fail'] else '–'}× | "
                            f"{fmt(x['ttg'] / b['ttg']) if b['ttg'] else '–'}× |")
                else:
                    row += " | |"
                md.append(row)
    # Figure 6: failed replans and frames in contact against particle count, all scenarios.
    settings = sorted({(r["algorithm"], r["pace"], r["controller"]) for r in runs
                       if r["occupancy"] != "particles"})
    fig, axes = plt.subplots(1, 2, figsize=(12, 4))
    styles = ["-", "--", ":", "-."]
    for i, (x, pace, c) in enumerate(settings):
        for j, o in enumerate(["particles"] + rules):
            keys = {key(r) for r in runs if (r["algorithm"], r["pace"], r["controller"]) == (x, pace, c)
                    and r["occupancy"] == o}
            counts = sorted({int(k[4]) for k in keys})
            if not counts:
                continue
            fail, contact = [], []
            for n in counts:
                rs = [r for r in runs if r["occupancy"] == o and key(r)[1:4] == (x, pace, c) and
                      int(r["particle_count"]) == n]
                ps = [p for p in replans if p["occupancy"] == o and key(p)[1:4] == (x, pace, c) and
                      int(p["particle_count"]) == n and p["reason"] != "cancelled"]
                st = stats(rs, ps)
                fail.append(100 * st["fail"])
                contact.append(100 * st["contact"])
            lbl = f"{lab(x)}, {c}, {o}"
            axes[0].plot(counts, fail, styles[j % 4], marker="o", ms=3, color=f"C{i}", label=lbl)
            axes[1].plot(counts, contact, styles[j % 4], marker="o", ms=3, color=f"C{i}", label=lbl)
    for ax, title in zip(axes, ("failed replans (%)", "frames in contact (%)")):
        ax.set_xlabel("particles")
        ax.set_title(title + ", all scenarios")
    axes[1].legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(out, "fig6_occupancy.png"), dpi=100)
    plt.close(fig)


def seed_tables(runs, replans, out, suffix, md):
    """Seed 000's Tables II-IV and Figures 1-4 for one pacing (the seed's controller)."""
    algos = sorted({r["algorithm"] for r in runs}, key=lambda x: list(LABEL).index(x) if x in LABEL else 99)
    scenarios = [s for s in SCENARIOS if any(r["scenario"] == s for r in runs)]
    counts = sorted({int(r["particle_count"]) for r in runs})
    by = defaultdict(list)
    for r in runs:
        by[(r["scenario"], r["algorithm"])].append(r)
    plans = defaultdict(list)
    for r in replans:
        if r.get("reason") != "cancelled":
            plans[(r["scenario"], r["algorithm"])].append(r)
    lab = lambda x: LABEL.get(x, x)  # noqa: E731
    paces = sorted({r["pace"] for r in runs})
    md.append(f"# hpcplan sim: seed 000's tables, {', '.join(paces)} pacing\n\n{len(runs)} runs "
              "with the seed's controller, "
              f"particle counts {', '.join(map(str, counts))}; planners {', '.join(map(lab, algos))}. "
              "Failed runs (the cap reached) count in the success rate, never in time-to-goal means.\n")

    # Table II
    ref = algos[0]
    md.append("## Table II: time to goal by scenario (s, successful runs, mean ± sd)\n")
    head = "| Scenario | " + " | ".join(f"{lab(x)}" for x in algos) + " | " + \
        " | ".join(f"{lab(ref)} / {lab(x)}" for x in algos[1:]) + " | success rate |"
    md.append(head)
    md.append("|" + "---|" * (2 + 2 * len(algos) - 1))
    ttg = {}
    for s in scenarios:
        cells, rates = [], []
        for x in algos:
            rs = by[(s, x)]
            m, sd = mean_sd([f(r["time_to_goal_s"]) for r in rs if r["success"] == "1"])
            ttg[(s, x)] = m
            cells.append(f"{fmt(m)} ± {fmt(sd)}")
            rates.append(f"{lab(x)} {sum(r['success'] == '1' for r in rs)}/{len(rs)}")
        ratios = [f"{fmt(ttg[(s, ref)] / ttg[(s, x)])}×" if ttg[(s, x)] else "–" for x in algos[1:]]
        md.append(f"| {NAMES[s]} | " + " | ".join(cells) + " | " + " | ".join(ratios) + f" | {', '.join(rates)} |")

    # Table III
    md.append("\n## Table III: planning time per replan call (ms; mean, p50, p99) and failed replans\n")
    md.append("| Scenario | " + " | ".join(f"{lab(x)} mean / p50 / p99" for x in algos) + " | " +
              " | ".join(f"{lab(x)} failed" for x in algos) + " |")
    md.append("|" + "---|" * (1 + 2 * len(algos)))
    plan_mean = {}
    fail_rate = {}
    for s in scenarios:
        cells, fails = [], []
        for x in algos:
            ps = plans[(s, x)]
            t = [f(p["plan_us"]) / 1e3 for p in ps]
            plan_mean[(s, x)] = statistics.fmean(t) if t else math.nan
            cells.append(f"{fmt(plan_mean[(s, x)], 3)} / {fmt(quantile(t, .5), 3)} / {fmt(quantile(t, .99), 3)}")
            nfail = sum(p["status"] != "solved" for p in ps)
            fail_rate[(s, x)] = nfail / len(ps) if ps else math.nan
            fails.append(f"{fmt(100 * fail_rate[(s, x)], 1)}%")
        md.append(f"| {NAMES[s]} | " + " | ".join(cells) + " | " + " | ".join(fails) + " |")
    md.append("\nThe paper's Table III (its published code, A* and RRT*, successful runs only, "
              "placeholder replans before the robot exists included): Particles Only 466.2 / 40.6 ms, "
              "Static 569.9 / 47.9 ms, Dynamic 1159.3 / 47.8 ms.\n")
    reasons = defaultdict(lambda: defaultdict(int))
    for (s, x), ps in plans.items():
        for p in ps:
            if p["status"] != "solved":
                reasons[x][p["reason"]] += 1
    esc = []
    for x in algos:
        ps = [p for (s2, x2), lst in plans.items() if x2 == x for p in lst]
        if ps and "start_escaped" in ps[0]:
            se = sum(p["start_escaped"] == "1" for p in ps) / len(ps)
            ge = sum(p["goal_escaped"] == "1" for p in ps) / len(ps)
            esc.append(f"{lab(x)}: start {100 * se:.1f}%, goal {100 * ge:.1f}%")
    if esc:
        md.append("Blocked ends moved to a free spot (share of replans): " + "; ".join(esc) + ".\n")
    if reasons:
        md.append("Why replans failed (all scenarios): " + "; ".join(
            f"{lab(x)}: " + ", ".join(f"{k} {v}" for k, v in sorted(reasons[x].items())) for x in algos if reasons[x]) + ".\n")

    # Table IV
    md.append("## Table IV: path length and divergence by scenario\n")
    md.append("| Scenario | " + " | ".join(f"{lab(x)} len" for x in algos) + " | " +
              " | ".join(f"{lab(x)} len (paper's weighting)" for x in algos) + " | " +
              " | ".join(f"{lab(x)} div" for x in algos) + " |")
    md.append("|" + "---|" * (1 + 3 * len(algos)))
    length, div = {}, {}
    for s in scenarios:
        a1, a2, a3 = [], [], []
        for x in algos:
            ps = plans[(s, x)]
            ok = [f(p["length"]) for p in ps if p["status"] == "solved"]
            length[(s, x)] = statistics.fmean(ok) if ok else math.nan
            weighted = sum(ok) / len(ps) if ps else math.nan
            d = [f(p["divergence"]) for p in ps if p["status"] == "solved" and p["divergence"] != ""]
            div[(s, x)] = statistics.fmean(d) if d else math.nan
            a1.append(fmt(length[(s, x)], 3)); a2.append(fmt(weighted, 3)); a3.append(fmt(div[(s, x)], 3))
        md.append(f"| {NAMES[s]} | " + " | ".join(a1 + a2 + a3) + " |")

    colours = {x: c for x, c in zip(algos, ["tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple"])}
    # Figure 1 and 2: distributions per scenario.
    for name, values, ylabel, log in (
            (f"fig1_time_to_goal{suffix}.png", lambda s, x: [f(r["time_to_goal_s"]) for r in by[(s, x)] if r["success"] == "1"], "time to goal (s)", False),
            (f"fig2_plan_time{suffix}.png", lambda s, x: [f(p["plan_us"]) / 1e3 for p in plans[(s, x)]], "plan time per replan (ms)", True)):
        fig, axes = plt.subplots(1, len(scenarios), figsize=(4 * len(scenarios), 4), squeeze=False)
        for ax, s in zip(axes[0], scenarios):
            data = [values(s, x) or [math.nan] for x in algos]
            bp = ax.boxplot(data, labels=[lab(x) for x in algos], patch_artist=True)
            for patch, x in zip(bp["boxes"], algos):
                patch.set_facecolor(colours[x])
            ax.set_title(NAMES[s])
            ax.set_ylabel(ylabel)
            if log:
                ax.set_yscale("log")
        fig.tight_layout()
        fig.savefig(os.path.join(out, name), dpi=100)
        plt.close(fig)
    # Figure 3: scaling with particle count.
    fig, axes = plt.subplots(1, 3, figsize=(14, 4))
    for x in algos:
        for s in scenarios:
            style = {"particles": "-", "static": "--", "dynamic": ":", "dambreak": "-."}[s]
            t, p, fr = [], [], []
            for n in counts:
                rs = [r for r in by[(s, x)] if int(r["particle_count"]) == n]
                ok = [f(r["time_to_goal_s"]) for r in rs if r["success"] == "1"]
                t.append(statistics.fmean(ok) if ok else math.nan)
                ps = [q for q in plans[(s, x)] if int(q["particle_count"]) == n]
                p.append(statistics.fmean(f(q["plan_us"]) / 1e3 for q in ps) if ps else math.nan)
                fr.append(sum(q["status"] != "solved" for q in ps) / len(ps) if ps else math.nan)
            for ax, y in zip(axes, (t, p, fr)):
                ax.plot(counts, y, style, marker="o", ms=3, color=colours[x], label=f"{lab(x)}, {s}")
    for ax, title in zip(axes, ("time to goal (s)", "mean plan time (ms)", "failed replan rate")):
        ax.set_xlabel("particles")
        ax.set_title(title)
    axes[1].set_yscale("log")
    axes[2].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"fig3_scaling{suffix}.png"), dpi=100)
    plt.close(fig)
    # Figure 4 (and its table): the winner of each metric per scenario.
    metrics = [("Time to Goal", ttg, min), ("Plan Time", plan_mean, min),
               ("Failed Replan Rate", fail_rate, min), ("Path Length", length, min),
               ("Path Divergence", div, min)]
    md.append("\n## Figure 4: winner per metric and scenario\n")
    md.append("| Scenario | " + " | ".join(m for m, _, _ in metrics) + " |")
    md.append("|" + "---|" * (1 + len(metrics)))
    grid = []
    for s in scenarios:
        row = []
        for _, table, pick in metrics:
            vals = {x: table.get((s, x), math.nan) for x in algos}
            vals = {x: v for x, v in vals.items() if not math.isnan(v)}
            row.append(pick(vals, key=vals.get) if vals else None)
        grid.append(row)
        md.append(f"| {NAMES[s]} | " + " | ".join(lab(w) if w else "–" for w in row) + " |")
    fig, ax = plt.subplots(figsize=(2 + 1.8 * len(metrics), 0.8 + 0.6 * len(scenarios)))
    ax.axis("off")
    tab = ax.table(cellText=[[lab(w) if w else "–" for w in row] for row in grid],
                   rowLabels=[NAMES[s] for s in scenarios], colLabels=[m for m, _, _ in metrics],
                   cellColours=[[colours.get(w, "white") if w else "white" for w in row] for row in grid],
                   loc="center")
    tab.scale(1, 1.6)
    fig.tight_layout()
    fig.savefig(os.path.join(out, f"fig4_winners{suffix}.png"), dpi=100)
    plt.close(fig)


if __name__ == "__main__":
    main()
