#!/usr/bin/env bash
# Seed 002's planner comparison on this machine: for d in DIMS (default 2 4 6 8 10), `hpcplan
# ompl` runs the grid planner (shortcut and lattice path) and its peers on the same world in
# the same invocation: BIT*, ABIT*, AIT*, RRT-Connect, FMT* with radius connections and FMT*
# (k-nearest, d <= 6: its neighbour computation ignores the time limit and took 83 s of a 5 s
# budget at 10D), RUNS runs each at the largest budget, after one untimed warm-up solve each
# (--warmup 1: otherwise the first planner listed pays for the process's first searches).
# The 2-rank MPI grid planner runs under mpirun. The last table puts them side by side:
# median time to a first solution, success rate, and each peer's time over the grid
# planner's. Budgets below the largest are read from the same runs by the analysis (an
# anytime planner's state at time b does not depend on a limit it has not reached; a one-shot
# planner succeeds within b iff it finished by b). Writes results/ompl/ and prints the tables.
# Usage: bash bench/ompl_sweep.sh [runs] [largest budget in s]   (env: DIMS, OUT)
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
budget=${2:-20}
bin=build/bin/hpcplan
[[ -x $bin ]] || { echo "ompl_sweep: build first (bash scripts/build.sh)" >&2; exit 2; }
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
out=${OUT:-results/ompl}
mkdir -p "$out"
for d in ${DIMS:-2 4 6 8 10}; do
  planners=gridastar,gridastar_lattice,bitstar,abitstar,aitstar,rrtconnect,fmt_radius
  ((d <= 6)) && planners+=,fmt
  echo "== ${d}D: $planners, $runs run(s) of ${budget} s" >&2
  "$bin" ompl --dims "$d" --planners "$planners" --time "$budget" --runs "$runs" --warmup 1 \
    --log "$out/d$d.log" --csv "$out/d$d.csv" >&2
  # The distributed grid planner (lattice path) under mpirun, same field and start/goal.
  tmp=$out/d$d.mpi.csv.tmp
  echo "planner,dims,run,seed,solved,time_first_s,length_first,quality_first,time_best_s,quality_best,quality_final,length_final,time_s,collision_checks,path_valid,improvements" > "$tmp"
  for ((r = 0; r < runs; r++)); do
    mpirun -np 2 "$bin" grid --dims "$d" --json --time-limit "$budget" 2>/dev/null |
      python3 scripts/grid_json_to_csv.py gridastar_mpi2 "$r" >> "$tmp"
  done
  mv "$tmp" "$out/d$d.mpi.csv"
done
py=python3; [[ -x /usr/bin/python3 ]] && py=/usr/bin/python3  # matplotlib comes from Debian
"$py" scripts/ompl_tables.py "$out"/d*.csv --budget "$budget" --plots "$out"
