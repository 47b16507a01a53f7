#!/usr/bin/env bash
# Predicted splits for rank counts this machine cannot run (hpcplan grid --simulate-ranks): seed
# 002's default A* problems (d = 2..10, extent 100) and the strong-scaling Dijkstra problems of
# bench/strong_scaling.sh, for P = 2 .. 4096 and the state-hash (k = 0) and cell (k = 1, 2)
# ownerships. Writes results/rank_prediction/*.json and prints Markdown tables.
# Usage: bash bench/rank_prediction.sh
set -euo pipefail
cd "$(dirname "$0")/.."
bin=build/bin/hpcplan
[[ -x $bin ]] || { echo "rank_prediction: build first (bash scripts/build.sh)" >&2; exit 2; }
out=results/rank_prediction
mkdir -p "$out"
ranks=2,4,8,16,32,64,128,512,4096
for d in 2 4 6 8 10; do
  "$bin" grid --dims "$d" --simulate-ranks "$ranks" --simulate-coarsen 0,1,2 --json \
    --output "$out/astar_d$d.json" >/dev/null
done
for pr in "4 40" "6 11" "8 6" "10 4"; do
  set -- $pr
  "$bin" grid --dims "$1" --extent "$2" --algo dijkstra --simulate-ranks "$ranks" \
    --simulate-coarsen 0,1 --json --output "$out/dijkstra_d$1.json" >/dev/null
done
python3 scripts/rank_prediction_table.py "$out"/astar_d*.json "$out"/dijkstra_d*.json
