#!/usr/bin/env python3
"""Speedup, efficiency and workload-deviation tables (and PNG plots) from any set of result
folders written by the slurm/ templates or bench/ drivers.

Reads every strong.csv, weak.csv (hpcplan_mpi_scaling rows) and dims result.json under the
given folders (searched recursively); rows of the same configuration and rank count from
several jobs are pooled (median).
  strong: speedup(P) = T(1) / T(P), with T(1) the one-rank row (or the serial reference timed
          in the same job when there is none); efficiency = speedup / P
  weak:   efficiency(P) = T(1) / T(P) (work per rank held constant by the template)
  Table IV (seed 002): workload deviation, max - min share of expansions in percent, per P, d
Usage: scaling_report.py results/strong results/weak ... [--plots DIR]
"""
import argparse
import csv
import glob
import json
import os
import statistics
from collections import defaultdict


def files(roots, name):
    out = []
    for r in roots:
        if os.path.isfile(r) and os.path.basename(r) == name:
            out.append(r)
        out += glob.glob(os.path.join(r, "**", name), recursive=True)
    return sorted(set(out))


def load_csv(paths, study):
    rows = []
    for p in paths:
        for r in csv.DictReader(open(p)):
            if r.get("scheme") == "ceiling":
                continue
            r["study"] = study
            rows.append(r)
    return rows


def med(v):
    return statistics.median(v) if v else None


def table(title, header, lines):
    print(f"**{title}**\n")
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for line in lines:
        print("| " + " | ".join(line) + " |")
    print()


def scaling(rows, study, plots):
    groups = defaultdict(lambda: defaultdict(list))
    for r in rows:
        scheme = "serial" if r["scheme"] == "serial" else r["scheme"]
        key = (r["dims"], r["extent"] if study == "strong" else "-", r["algo"])
        cfg = (scheme, r["coarsen"])
        groups[key][(int(r["ranks"]), cfg)].append(r)
    for key, by in sorted(groups.items()):
        base = med([float(r["median_ms"]) for (p, _), rs in by.items() if p == 1 for r in rs])
        if base is None:
            base = med([float(r["serial_median_ms"]) for rs in by.values() for r in rs
                        if float(r.get("serial_median_ms") or 0) > 0])
        lines, series = [], defaultdict(list)
        for (p, cfg), rs in sorted(by.items()):
            t = med([float(r["median_ms"]) for r in rs])
            dev = med([float(r["workload_deviation_percent"]) for r in rs])
            sp = base / t if base and t else None
            extents = sorted({r["extent"] for r in rs})
            scale = f"{sp / p:.2f}" if sp and study == "strong" else ",".join(extents)
            lines.append([str(p), f"{cfg[0]} k={cfg[1]}", f"{t:.1f}",
                          f"{sp:.2f}" if sp else "-", scale, f"{dev:.2f}", str(len(rs))])
            if sp:
                series[cfg].append((p, sp))
        what = "speedup" if study == "strong" else "weak efficiency T(1)/T(P)"
        title = f"{study} scaling — {key[0]}D" + (f" extent {key[1]}" if key[1] != "-" else "")
        title += f", {key[2]}" + (f" (T(1) = {base:.1f} ms)" if base else " (no one-rank time)")
        table(title, ["P", "configuration", "median ms", what,
                      "efficiency" if study == "strong" else "extent", "deviation %", "runs"],
              lines)
        if plots and series:
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
            fig, ax = plt.subplots(figsize=(6, 4))
            for cfg, pts in sorted(series.items()):
                pts.sort()
                ax.plot([p for p, _ in pts], [s for _, s in pts], marker="o",
                        label=f"{cfg[0]} k={cfg[1]}")
            ps = sorted({p for pts in series.values() for p, _ in pts})
            if study == "strong":
                ax.plot(ps, ps, "k:", label="ideal")
            else:
                ax.axhline(1.0, color="k", linestyle=":", label="ideal")
            ax.set_xscale("log", base=2)
            ax.set_xlabel("ranks P")
            ax.set_ylabel(what)
            ax.grid(True, alpha=0.3)
            ax.legend(fontsize=8)
            fig.tight_layout()
            name = f"{plots}/{study}_d{key[0]}_{key[1]}_{key[2]}.png"
            fig.savefig(name, dpi=110)
            print(f"plot: {name}\n")


def table_iv(rows, dims_results):
    dev = defaultdict(list)
    for r in rows:
        if int(r["ranks"]) > 1:
            dev[(int(r["ranks"]), int(r["dims"]))].append(float(r["workload_deviation_percent"]))
    for d in dims_results:
        if d.get("ranks", 1) > 1 and "distributed" in d:
            dev[(d["ranks"], d["dims"])].append(d["distributed"]["workload_deviation_percent"])
    if not dev:
        return
    ps = sorted({p for p, _ in dev})
    ds = sorted({d for _, d in dev})
    lines = [[str(p)] + [f"{med(dev[(p, d)]):.2f}" if dev.get((p, d)) else "-" for d in ds]
             for p in ps]
    table("Table IV — workload deviation % (max - min share of expansions), medians",
          ["P"] + [f"{d}D" for d in ds], lines)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("roots", nargs="+")
    ap.add_argument("--plots")
    a = ap.parse_args()
    strong = load_csv(files(a.roots, "strong.csv"), "strong")
    weak = load_csv(files(a.roots, "weak.csv"), "weak")
    dims = [json.load(open(p)) for p in files(a.roots, "result.json")]
    if not (strong or weak or dims):
        raise SystemExit("scaling_report: no strong.csv, weak.csv or result.json under " +
                         ", ".join(a.roots))
    if strong:
        scaling(strong, "strong", a.plots)
    if weak:
        scaling(weak, "weak", a.plots)
    table_iv(strong + weak, dims)


if __name__ == "__main__":
    main()
