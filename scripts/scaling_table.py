#!/usr/bin/env python3
"""Prints the rows of a hpcplan_mpi_scaling CSV as a Markdown table."""
import csv
import sys

rows = list(csv.DictReader(open(sys.argv[1])))
cols = ["label", "ranks", "dims", "extent", "scheme", "batch", "coarsen", "sent_filter", "status", "expanded",
        "serial_median_ms", "median_ms", "ratio_of_medians", "speedup_vs_serial", "efficiency",
        "messages_per_expansion", "bytes_per_expansion", "workload_deviation_percent",
        "search_overhead"]
print("| " + " | ".join(cols) + " |")
print("|" + "---|" * len(cols))
for r in rows:
    print("| " + " | ".join(r[c] for c in cols) + " |")
