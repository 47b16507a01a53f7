#!/usr/bin/env bash
# The per-map benchmark against a textbook A* (bench/movingai_bench.cpp, docs/MAPS.md):
# hpcplan_movingai_bench over every MovingAI scenario found, one map at a time (never two timing
# jobs at once). Writes results/movingai/ (not committed: results/ is ignored but for seed000):
#   <map>.groups.csv   per bucket group: median µs of each engine, textbook / ours ratios
#   <map>.rows.csv     per row: each engine's µs, cost and expansions
#   <map>.md           the Markdown table the binary prints
#   summary.csv        every map's groups.csv rows, one header
#
# Usage: bench/movingai_bench.sh [BUILD_DIR]
#   ROWS=N        rows per map, spread evenly over its buckets (default 1000; 0: all)
#   WEIGHT=W      weighted A*'s weight (default 1.5)
#   MAPS_DIRS="D1 D2"  where to look for *.scen (default: the shared benchmarks folder beside
#                 or inside the checkout, then bench/data/movingai: four more maps, README there)
#   OUT=DIR       default results/movingai
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build}
bin=$build/bin/hpcplan_movingai_bench
rows=${ROWS:-1000}
weight=${WEIGHT:-1.5}
out=${OUT:-$root/results/movingai}
dirs=${MAPS_DIRS:-"$root/../shared/benchmarks/movingai $root/shared/benchmarks/movingai $root/bench/data/movingai"}
[[ -x $bin ]] || { echo "movingai_bench: error: $bin is not built (cmake --build $build --target hpcplan_movingai_bench)" >&2; exit 2; }
mkdir -p "$out"

echo "# $(date -u +%FT%TZ) $(uname -n), $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg); commit $(git -C "$root" rev-parse --short HEAD 2>/dev/null || echo '?')"
found=0
summary=$out/summary.csv
: >"$summary.tmp"
for dir in $dirs; do
  [[ -d $dir ]] || continue
  for scen in "$dir"/*.scen; do
    [[ -f $scen ]] || continue
    found=1
    name=$(basename "$scen" .map.scen)
    load=$(cut -d' ' -f1 /proc/loadavg)
    if awk -v l="$load" 'BEGIN { exit !(l > 1.5) }'; then
      echo "# warning: load average $load before $name: other jobs share the cores; re-run if the figures look noisy" >&2
    fi
    # MovingAI's files print lengths with 8 decimals. An octile length a + b sqrt(2) is an
    # integer or irrational, so a non-integer printed with fewer than 8 significant digits was
    # rounded (GPPC 2023's AcrosstheCape.map.scen: 6, "1179.8"): such a file is checked to 1e-5
    # relative instead of 1e-6.
    tol=1e-6
    if awk -F'\t' 'NR > 1 && NF >= 9 { v = $9; sub(/\r$/, "", v); n = split(v, p, "."); f = p[2]; sub(/0+$/, "", f); i = p[1]; sub(/^0+/, "", i); if (n == 2 && f != "" && length(i) + length(f) < 8) { found = 1; exit } } END { exit !found }' "$scen"; then
      tol=1e-5
      echo "# $name: the scenario rounds lengths to fewer than 8 significant digits; optimum checks to $tol relative"
    fi
    "$bin" "$scen" --rows "$rows" --weight "$weight" --tolerance "$tol" --csv "$out/$name.groups.csv" \
      --rows-csv "$out/$name.rows.csv" | tee "$out/$name.md"
    echo
    if [[ ! -s $summary.tmp ]]; then head -n 1 "$out/$name.groups.csv" >"$summary.tmp"; fi
    tail -n +2 "$out/$name.groups.csv" | grep -v '^#' >>"$summary.tmp"
  done
done
[[ $found == 1 ]] || { echo "movingai_bench: error: no *.scen in $dirs" >&2; rm -f "$summary.tmp"; exit 2; }
mv "$summary.tmp" "$summary"
echo "# wrote $out"
