#!/usr/bin/env bash
# Strong scaling on this machine: P = 1 and P = 2 for one problem per dimension (d = 4, 6, 8,
# 10; Dijkstra, sized to take >= 2 s on one rank), state-hash, coarse-cell and slab ownership
# and prefix cuts balanced on a serial run (hpcplan_mpi_scaling --balanced-cuts),
# asynchronous vs bulk-synchronous, the machine's own ceiling (the serial search on both cores
# at once), and the effect of the batch size at 6D. Every row is timed against the serial
# engine in the same mpirun job, interleaved round by round (median of --repeats ratios, with
# their lowest and highest, and the fraction of the ceiling measured in the same rounds). Then
# each problem's best scheme runs again, beside the balanced cuts, in more rounds (label
# "confirm dD"), so its fraction of the ceiling comes with quartiles from runs next to the
# crowded ones, and the serial engine's spread shows how far the machine's speed moved.
# Writes results/strong_scaling.csv and prints a Markdown summary.
# Usage: bash bench/strong_scaling.sh [repeats [confirmation rounds, default 3 x repeats]]
set -euo pipefail
cd "$(dirname "$0")/.."
repeats=${1:-5}
confirm_repeats=${2:-$((3 * repeats))}
bin=build/bin/hpcplan_mpi_scaling
[[ -x $bin ]] || { echo "strong_scaling: build first (bash scripts/build.sh)" >&2; exit 2; }
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
mkdir -p results
csv=results/strong_scaling.csv.tmp
rm -f "$csv"
# "dims extent coarsening-shifts slab-widths": k = 2 leaves too few cells at extent 4 (one per
# axis); slabs of half the extent (two contiguous halves) and of about a quarter (dealt
# alternately, for balance), 0 = the hash.
problems=("4 40 0,1,2 0,20,10" "6 11 0,1,2 0,6,3" "8 6 0,1,2 0,3,2" "10 4 0,1 0,2,1")
for pr in "${problems[@]}"; do
  set -- $pr
  mpirun -np 1 "$bin" --dims "$1" --extent "$2" --algo dijkstra --repeats "$repeats" \
    --label "d$1" --csv "$csv" 2>/dev/null
  mpirun -np 2 "$bin" --dims "$1" --extent "$2" --algo dijkstra --repeats "$repeats" \
    --modes async,bulk --coarsen "$3" --slabs "$4" --balanced-cuts --ceiling --label "d$1" --csv "$csv" \
    2>/dev/null
done
# Batch size (async) at 6D.
mpirun -np 2 "$bin" --dims 6 --extent 11 --algo dijkstra --repeats "$repeats" --modes async \
  --batches 16,128,2048,16384 --label batch --csv "$csv" 2>/dev/null
# The best scheme of each problem, confirmed, beside the balanced cuts in the same mode (the
# sweep's pick is the highest of noisy medians: at 6D it once picked slabs that the same
# rounds then put 10 points below the cuts).
for pr in "${problems[@]}"; do
  set -- $pr
  best=$(python3 scripts/scaling_table.py --best-args "$csv" "d$1")
  [[ $best == *--cuts* ]] || best+=" --balanced-cuts"
  # shellcheck disable=SC2086  # the options are words
  mpirun -np 2 "$bin" --dims "$1" --extent "$2" --algo dijkstra --repeats "$confirm_repeats" \
    $best --ceiling --label "confirm d$1" --csv "$csv" 2>/dev/null
done
mv "$csv" results/strong_scaling.csv
python3 scripts/scaling_table.py results/strong_scaling.csv
