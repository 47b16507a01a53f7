#!/usr/bin/env python3
"""Markdown tables from `hpcplan grid --simulate-ranks ... --json` results: predicted workload
deviation (seed 002 Table IV: max - min share of expansions, %), imbalance (busiest rank's
expansions over the mean) and cross-rank successors per expansion, one table per shift k."""
import json
import sys

runs = [json.load(open(p)) for p in sys.argv[1:]]
shifts = sorted({s["coarsen_shift"] for r in runs for s in r["rank_simulation"]})
ranks = sorted({s["ranks"] for r in runs for s in r["rank_simulation"]})
for k in shifts:
    head = "state hash" if k == 0 else f"cell hash, k = {k}"
    print(f"**Predicted deviation % / imbalance (max/mean) / remote successors per expansion — "
          f"{head}**\n")
    print("| problem | expanded | " + " | ".join(f"P={p}" for p in ranks) + " |")
    print("|---|---|" + "---|" * len(ranks))
    for r in runs:
        cells = []
        for p in ranks:
            s = [x for x in r["rank_simulation"] if x["ranks"] == p and x["coarsen_shift"] == k]
            cells.append(f"{s[0]['expansion_deviation_percent']:.2f} / {s[0]['imbalance']:.2f} / "
                         f"{s[0]['remote_per_expansion']:.1f}" if s else "-")
        name = f"{r['algo']} {r['dims']}D e{r['extent']}"
        print(f"| {name} | {r['expanded']} | " + " | ".join(cells) + " |")
    print()
