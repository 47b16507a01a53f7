#!/usr/bin/env python3
"""Prints the rows of a hpcplan_mpi_scaling CSV as a Markdown table, the best scheme per
problem against the machine's ceiling, and the confirmation rounds (labels "confirm ...").

  scaling_table.py CSV                  the tables
  scaling_table.py --best-args CSV LBL  hpcplan_mpi_scaling options that rerun the best
                                        scheme of problem LBL (by its median fraction of
                                        the ceiling), for bench/strong_scaling.sh
"""
import csv
import sys


def best_rows(rows):
    """The row with the highest median fraction of the ceiling per (label, ranks)."""
    best = {}
    for r in rows:
        if r.get("scheme") in ("ceiling", "serial") or not r.get("of_ceiling"):
            continue
        key = (r["label"], r["ranks"])
        if float(r["of_ceiling"]) > 0 and (key not in best or
                                           float(r["of_ceiling"]) > float(best[key]["of_ceiling"])):
            best[key] = r
    return best


def owner_args(r):
    if r.get("engine") == "dense":
        return ["--engine", "dense", "--threads", r.get("threads", "1")]
    if r.get("cuts"):
        return ["--cuts", r["cuts"].replace(";", ",")]
    if r.get("slabs", "0") not in ("", "0"):
        return ["--slabs", r["slabs"]]
    return ["--coarsen", r["coarsen"]]


def owner_name(r):
    """The ownership in words: "slabs 6", "cuts 53", "coarsen 1", "engine dense --threads 1"."""
    return " ".join(owner_args(r))[2:]


if sys.argv[1] == "--best-args":
    rows = list(csv.DictReader(open(sys.argv[2])))
    for (label, _), r in best_rows(rows).items():
        if label == sys.argv[3]:
            mode = [] if r.get("engine") == "dense" else ["--modes", r["scheme"], "--batches", r["batch"]]
            print(" ".join(mode + owner_args(r)))
            sys.exit(0)
    sys.exit(f"scaling_table: no best row for {sys.argv[3]}")

rows = list(csv.DictReader(open(sys.argv[1])))
cols = ["label", "ranks", "dims", "extent", "scheme", "batch", "coarsen", "sent_filter", "status", "expanded",
        "serial_median_ms", "median_ms", "ratio_of_medians", "speedup_vs_serial", "efficiency",
        "messages_per_expansion", "bytes_per_expansion", "workload_deviation_percent",
        "search_overhead", "speedup_min", "speedup_max", "of_ceiling", "of_ceiling_min",
        "of_ceiling_max", "slabs", "cuts", "of_ceiling_q1", "of_ceiling_q3", "serial_min_ms",
        "serial_max_ms", "engine", "threads"]
# Older CSVs lack the spread, slab, cut, engine and thread columns.
cols = [c for c in cols if all(c in r for r in rows)]
print("| " + " | ".join(cols) + " |")
print("|" + "---|" * len(cols))
for r in rows:
    print("| " + " | ".join(r[c] for c in cols) + " |")

# The best scheme per problem against the machine's ceiling measured in the same rounds.
sweep = [r for r in rows if not r["label"].startswith("confirm")]
confirm = [r for r in rows if r["label"].startswith("confirm")]
best = best_rows(sweep)
if best:
    print()
    print("| problem | P | best scheme | speedup (min-max) | ceiling | of ceiling, median (min-max) |")
    print("|---|---|---|---|---|---|")
    ceilings = {(r["label"], r["ranks"]): r for r in rows if r.get("scheme") == "ceiling"}
    for key, r in best.items():
        c = ceilings.get(key)
        cell = f"{c['speedup_vs_serial']} ({c['speedup_min']}-{c['speedup_max']})" if c else "-"
        print(f"| {key[0]} | {key[1]} | {r['scheme']} {owner_name(r)} batch={r['batch']} | "
              f"{r['speedup_vs_serial']} ({r['speedup_min']}-{r['speedup_max']}) | {cell} | "
              f"{float(r['of_ceiling']):.1%} ({float(r['of_ceiling_min']):.1%}-"
              f"{float(r['of_ceiling_max']):.1%}) |")

# The confirmation: each problem's best scheme (and the balanced cuts beside it) against the
# serial engine and the ceiling, in more rounds. The quartiles say how steady the fraction is; the serial engine's
# own lowest and highest time say how far this machine's speed moved meanwhile.
if confirm:
    print()
    print("| problem | P | scheme | rounds | speedup, median (min-max) | ceiling, median (min-max) "
          "| of ceiling, median (quartiles; min-max) | serial ms, min-max |")
    print("|---|---|---|---|---|---|---|---|")
    # Each job writes its configurations and then its ceiling row.
    waiting = []
    for row in confirm:
        if row.get("scheme") != "ceiling":
            waiting.append(row)
            continue
        c = row
        for r in waiting:
            frac = (f"{float(r['of_ceiling']):.1%} ({float(r['of_ceiling_q1']):.1%}-"
                    f"{float(r['of_ceiling_q3']):.1%}; {float(r['of_ceiling_min']):.1%}-"
                    f"{float(r['of_ceiling_max']):.1%})")
            print(f"| {r['label'].removeprefix('confirm ')} | {r['ranks']} | {r['scheme']} "
                  f"{owner_name(r)} | {r['repeats']} | {r['speedup_vs_serial']} "
                  f"({r['speedup_min']}-{r['speedup_max']}) | {c['speedup_vs_serial']} "
                  f"({c['speedup_min']}-{c['speedup_max']}) | {frac} | "
                  f"{float(r['serial_min_ms']):.0f}-{float(r['serial_max_ms']):.0f} |")
        waiting = []
