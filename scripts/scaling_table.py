#!/usr/bin/env python3
"""Prints the rows of a hpcplan_mpi_scaling CSV as a Markdown table."""
import csv
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
cols = ["label", "ranks", "dims", "extent", "scheme", "batch", "coarsen", "sent_filter", "status", "expanded",
        "serial_median_ms", "median_ms", "ratio_of_medians", "speedup_vs_serial", "efficiency",
        "messages_per_expansion", "bytes_per_expansion", "workload_deviation_percent",
        "search_overhead", "speedup_min", "speedup_max", "of_ceiling", "of_ceiling_min",
        "of_ceiling_max", "slabs", "cuts"]
# Older CSVs lack the spread, slab and cut columns.
cols = [c for c in cols if all(c in r for r in rows)]
print("| " + " | ".join(cols) + " |")
print("|" + "---|" * len(cols))
for r in rows:
    print("| " + " | ".join(r[c] for c in cols) + " |")

# The best scheme per problem against the machine's ceiling measured in the same rounds.
best = {}
for r in rows:
    if r.get("scheme") in ("ceiling", "serial") or not r.get("of_ceiling"):
        continue
    key = (r["label"], r["ranks"])
    if float(r["of_ceiling"]) > 0 and (key not in best or
                                       float(r["of_ceiling"]) > float(best[key]["of_ceiling"])):
        best[key] = r
if best:
    print()
    print("| problem | P | best scheme | speedup (min-max) | ceiling | of ceiling, median (min-max) |")
    print("|---|---|---|---|---|---|")
    ceilings = {(r["label"], r["ranks"]): r for r in rows if r.get("scheme") == "ceiling"}
    for key, r in best.items():
        c = ceilings.get(key)
        cell = f"{c['speedup_vs_serial']} ({c['speedup_min']}-{c['speedup_max']})" if c else "-"
        if r.get("cuts"):
            owner = f"cuts={r['cuts']}"
        elif r.get("slabs", "0") not in ("", "0"):
            owner = f"slabs={r['slabs']}"
        else:
            owner = f"k={r['coarsen']}"
        print(f"| {key[0]} | {key[1]} | {r['scheme']} {owner} batch={r['batch']} | "
              f"{r['speedup_vs_serial']} ({r['speedup_min']}-{r['speedup_max']}) | {cell} | "
              f"{float(r['of_ceiling']):.1%} ({float(r['of_ceiling_min']):.1%}-"
              f"{float(r['of_ceiling_max']):.1%}) |")
