#!/usr/bin/env bash
# Seed 000's benchmark sweep: every (particle count, scenario, planner) cell runs TRIALS runs of
# `hpcplan sim`, one per-run CSV and one per-replan log per cell. The seed's grid is 18 particle
# counts (500, 2,000, ..., 24,500 and 25,000) x 3 scenarios x its 2 planners x 5 trials = 540
# runs; D* Lite is added here (810 runs).
#
# Resumable: a cell whose CSV exists is skipped (the CLI writes it atomically at the cell's end),
# so rerunning an interrupted sweep finishes it. Progress and an estimate of the time left go to
# stderr.
#
# Usage: bench/sim_sweep.sh [OUT]          every cell, in order (default OUT: results/sim/local)
#        bench/sim_sweep.sh --count        how many cells the settings give
#        bench/sim_sweep.sh --cell K OUT   cell K only (0-based: slurm/sim_sweep.sbatch's task)
# Settings (environment, defaults): PARTICLES (the seed's 18 counts), SCENARIOS ("particles
# static dynamic"), ALGOS ("astar rrtstar dstar_lite"), TRIALS (5), SEED (1), PACE (realtime: the
# seed's, planning latency costs simulated time; lockstep: deterministic and faster than real
# time), MAX_SIM_S (300), THREADS (2), BIN (build/bin/hpcplan).
# The dam break (beyond the seed; water, so far costlier per particle) is its own sweep, e.g.
#   SCENARIOS=dambreak PARTICLES="250 2000 6750" MAX_SIM_S=10 bench/sim_sweep.sh results/sim/dam
# Aggregate with: python3 scripts/sim_report.py OUT [more result folders...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
default_particles="500"
for ((n = 2000; n <= 24500; n += 1500)); do default_particles+=" $n"; done
default_particles+=" 25000"
read -r -a particles <<< "${PARTICLES:-$default_particles}"
read -r -a scenarios <<< "${SCENARIOS:-particles static dynamic}"
read -r -a algos <<< "${ALGOS:-astar rrtstar dstar_lite}"
trials=${TRIALS:-5} seed=${SEED:-1} pace=${PACE:-realtime} max_sim=${MAX_SIM_S:-300}
threads=${THREADS:-2}
bin=${BIN:-$root/build/bin/hpcplan}
die() { echo "sim_sweep: error: $*" >&2; exit 2; }
cells=$((${#particles[@]} * ${#scenarios[@]} * ${#algos[@]}))
((cells > 0)) || die "no cells: PARTICLES, SCENARIOS and ALGOS must not be empty"

# Cell k: particle counts outermost (small fluids first), then scenarios, then planners.
cell_of() {
  local k=$1 na=${#algos[@]} ns=${#scenarios[@]}
  algo=${algos[$((k % na))]}
  scenario=${scenarios[$((k / na % ns))]}
  n=${particles[$((k / na / ns))]}
}

run_cell() {  # run_cell K OUT: prints "ran" or "skipped"
  local k=$1 out=$2
  cell_of "$k"
  local name="${scenario}_${algo}_${n}"
  if [[ -f $out/cells/$name.csv ]]; then echo skipped; return; fi
  mkdir -p "$out/cells"
  "$bin" sim --particles "$n" --scenario "$scenario" --algo "$algo" --runs "$trials" \
    --seed "$seed" --pace "$pace" --max-sim-s "$max_sim" --threads "$threads" \
    --replan-log "$out/cells/$name.replans.csv" --output "$out/cells/$name.json" \
    --csv "$out/cells/$name.csv" > /dev/null 2> "$out/cells/$name.log" ||
    die "cell $k ($name) failed: $(tail -1 "$out/cells/$name.log")"
  echo ran
}

case ${1:-} in
  --count) echo "$cells"; exit 0 ;;
  --cell)
    [[ $# -eq 3 ]] || die "usage: sim_sweep.sh --cell K OUT"
    [[ $2 =~ ^[0-9]+$ ]] && (($2 < cells)) || die "cell $2 is not in 0..$((cells - 1))"
    [[ -x $bin ]] || die "$bin not found: build first (bash scripts/build.sh)"
    run_cell "$2" "$3" > /dev/null
    cell_of "$2"
    echo "sim_sweep: cell $2 ($scenario $algo $n particles) done in $3/cells"
    exit 0 ;;
esac
out=${1:-$root/results/sim/local}
[[ -x $bin ]] || die "$bin not found: build first (bash scripts/build.sh)"
mkdir -p "$out"
echo "sim_sweep: $cells cells x $trials trials, pace $pace, into $out" >&2
start=$SECONDS ran=0
for ((k = 0; k < cells; k++)); do
  t0=$SECONDS
  what=$(run_cell "$k" "$out")
  cell_of "$k"
  if [[ $what == ran ]]; then
    ran=$((ran + 1))
    per=$(((SECONDS - start) / ran))
    left=$(((cells - k - 1) * per))
    printf 'sim_sweep: [%d/%d] %s %s %d: %ds; about %dh%02dm left\n' $((k + 1)) "$cells" \
      "$scenario" "$algo" "$n" $((SECONDS - t0)) $((left / 3600)) $((left % 3600 / 60)) >&2
  else
    printf 'sim_sweep: [%d/%d] %s %s %d: already done\n' $((k + 1)) "$cells" "$scenario" "$algo" "$n" >&2
  fi
done
echo "sim_sweep: done; report: python3 scripts/sim_report.py $out" >&2
