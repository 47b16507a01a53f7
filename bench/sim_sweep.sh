#!/usr/bin/env bash
# Seed 000's benchmark sweep: every (particle count, scenario, planner, pacing, controller) cell
# runs TRIALS runs of `hpcplan sim`, one per-run CSV and one per-replan log per cell. The seed's
# grid is 18 particle counts (500, 2,000, ..., 24,500 and 25,000) x 3 scenarios x its 2 planners
# x 5 trials = 540 runs; D* Lite is added here (810 runs per pacing and controller).
#
# Resumable: a cell whose CSV exists is skipped (written, under its final name, only once every
# run of the cell is made), so rerunning an interrupted sweep finishes it. Interrupted (SIGUSR1,
# SLURM's warning before the time limit; SIGTERM; Ctrl-C), the cell in progress stops after its
# current frame with its finished runs saved in cells/NAME.ck (hpcplan sim --checkpoint) and the
# sweep exits 75; rerunning it continues that cell from its checkpoint (--restart). Progress and
# an estimate of the time left go to stderr.
#
# Usage: bench/sim_sweep.sh [OUT]          every cell, in order (default OUT: results/sim/local)
#        bench/sim_sweep.sh --count        how many cells the settings give
#        bench/sim_sweep.sh --cell K OUT   cell K only (0-based: slurm/sim_sweep.sbatch's task)
# Settings (environment, defaults): PARTICLES (the seed's 18 counts), SCENARIOS ("particles
# static dynamic"), ALGOS ("astar rrtstar dstar_lite"), TRIALS (5), SEED (1), PACES (one or
# both of realtime and lockstep; default: PACE, else realtime. realtime: the seed's, planning
# latency costs simulated time; lockstep: deterministic and faster than real time), CONTROLLERS
# ("seed"; "seed reactive" runs both), OCCUPANCIES ("particles": the seed's occupancy grid;
# "density:T" thresholds the SPH-interpolated density at T particle equivalents, e.g.
# "particles density:0.42 density:1"), MAX_SIM_S (300), THREADS (2), BIN (build/bin/hpcplan).
# Cells are named SCENARIO_ALGO_N_PACE_CONTROLLER (with _densityT appended for a density
# occupancy), so one folder holds every pacing, controller and occupancy and resuming it
# completes each of them.
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
read -r -a paces <<< "${PACES:-${PACE:-realtime}}"
read -r -a controllers <<< "${CONTROLLERS:-seed}"
read -r -a occupancies <<< "${OCCUPANCIES:-particles}"
trials=${TRIALS:-5} seed=${SEED:-1} max_sim=${MAX_SIM_S:-300}
threads=${THREADS:-2}
bin=${BIN:-$root/build/bin/hpcplan}
die() { echo "sim_sweep: error: $*" >&2; exit 2; }
for p in "${paces[@]}"; do [[ $p == realtime || $p == lockstep ]] || die "unknown pace $p"; done
for c in "${controllers[@]}"; do [[ $c == seed || $c == reactive ]] || die "unknown controller $c"; done
for o in "${occupancies[@]}"; do
  [[ $o == particles || ($o =~ ^density:[0-9.eE+-]+$ &&
    $(awk -v t="${o#density:}" 'BEGIN { print (t + 0 >= 1e-6 && t + 0 <= 1e9) }') == 1) ]] ||
    die "unknown occupancy $o (expected particles or density:THRESHOLD, 1e-6 <= THRESHOLD <= 1e9)"
  # Only the grid planners read the occupancy grid; RRT* and the particle world's planners would
  # rerun the same runs under another label.
  if [[ $o != particles ]]; then
    for a in "${algos[@]}"; do
      [[ $a == astar || $a == astar_euclid || $a == dstar_lite ]] ||
        die "occupancy $o applies to the grid planners (astar, astar_euclid, dstar_lite), not $a"
    done
  fi
done
cells=$((${#particles[@]} * ${#scenarios[@]} * ${#algos[@]} * ${#paces[@]} * ${#controllers[@]} *
  ${#occupancies[@]}))
((cells > 0)) || die "no cells: PARTICLES, SCENARIOS, ALGOS, PACES, CONTROLLERS and OCCUPANCIES must not be empty"

# Cell k: particle counts outermost (small fluids first), then scenarios, planners, pacings,
# controllers and occupancies (innermost: the settings compared run one after the other). With one
# occupancy the numbering is the one before occupancies existed, so older sweeps still resume.
cell_of() {
  local k=$1 no=${#occupancies[@]} nc=${#controllers[@]} np=${#paces[@]} na=${#algos[@]}
  local ns=${#scenarios[@]}
  occupancy=${occupancies[$((k % no))]}
  k=$((k / no))
  controller=${controllers[$((k % nc))]}
  pace=${paces[$((k / nc % np))]}
  algo=${algos[$((k / nc / np % na))]}
  scenario=${scenarios[$((k / nc / np / na % ns))]}
  n=${particles[$((k / nc / np / na / ns))]}
}

# Signals: the first SIGUSR1, SIGTERM or SIGINT asks the cell in progress to stop (one SIGUSR1
# to hpcplan sim, which runs in the background so that the trap runs at once) and the sweep to
# start no other cell.
stop=""      # the signal that asked the sweep to stop
sim_pid=""   # the cell in progress
forwarded=0  # it has had its SIGUSR1 (a second one would end it at once)
trapped=0    # a trap ran since `wait` began
on_signal() {
  [[ -n $stop ]] || stop=$1
  trapped=1
  if [[ -n $sim_pid ]] && ((!forwarded)); then
    forwarded=1
    kill -USR1 "$sim_pid" 2> /dev/null || true
  fi
}
trap 'on_signal USR1' USR1
trap 'on_signal TERM' TERM
trap 'on_signal INT' INT

run_cell() {  # run_cell K OUT: sets cell_result to ran, skipped or interrupted
  local k=$1 out=$2
  cell_of "$k"
  local name="${scenario}_${algo}_${n}_${pace}_${controller}" occupancy_args=()
  if [[ $occupancy != particles ]]; then
    name+="_density${occupancy#density:}"
    occupancy_args=(--occupancy density --density-threshold "${occupancy#density:}")
  fi
  cell_name=$name
  if [[ -f $out/cells/$name.csv ]]; then cell_result=skipped; return; fi
  mkdir -p "$out/cells"
  local base=$out/cells/$name restart=()
  if [[ -f $base.ck ]]; then
    restart=(--restart "$base.ck")
    echo "sim_sweep: cell $k ($name) continues from its checkpoint" >> "$base.log"
  else
    : > "$base.log"
  fi
  # The CSV goes to NAME.csv.part (an interrupted invocation writes the runs it finished) and
  # takes its name once the cell is whole.
  rm -f "$base.json"
  "$bin" sim --particles "$n" --scenario "$scenario" --algo "$algo" --runs "$trials" \
    --seed "$seed" --pace "$pace" --controller "$controller" --max-sim-s "$max_sim" \
    --threads "$threads" "${occupancy_args[@]}" \
    --replan-log "$base.replans.csv" --output "$base.json" --checkpoint "$base.ck" \
    "${restart[@]}" --csv "$base.csv.part" > /dev/null 2>> "$base.log" &
  sim_pid=$! forwarded=0 trapped=0
  local rc=0 again
  wait "$sim_pid" || rc=$?
  while ((trapped)); do  # a trap ended `wait` early: wait for hpcplan sim itself
    trapped=0 again=0
    wait "$sim_pid" 2> /dev/null || again=$?
    ((again != 127)) || break
    rc=$again
  done
  sim_pid=""
  # Asked before it had installed its handler (while setting up), hpcplan sim ends at once with
  # SIGUSR1's default action; its last checkpoint, if any, is still there.
  if ((forwarded && rc == 138)); then cell_result=interrupted; return; fi
  ((rc == 0)) || die "cell $k ($name) failed: $(tail -1 "$base.log")"
  if python3 -c 'import json, sys; sys.exit(json.load(open(sys.argv[1])).get("status") != "interrupted")' \
    "$base.json" 2> /dev/null; then
    cell_result=interrupted
    return
  fi
  mv -f "$base.csv.part" "$base.csv"
  rm -f "$base.ck"
  cell_result=ran
}

cell_result=""
interrupted() {  # interrupted K: the message and exit status of a sweep stopped in or before cell K
  if [[ $cell_result == interrupted ]]; then
    echo "sim_sweep: interrupted (SIG$stop) in cell $1 ($cell_name): its finished runs are in" \
      "cells/$cell_name.ck; run the sweep again to continue" >&2
  else
    echo "sim_sweep: interrupted (SIG$stop) before cell $1; run the sweep again to continue" >&2
  fi
  exit 75
}

case ${1:-} in
  --count) echo "$cells"; exit 0 ;;
  --cell)
    [[ $# -eq 3 ]] || die "usage: sim_sweep.sh --cell K OUT"
    [[ $2 =~ ^[0-9]+$ ]] && (($2 < cells)) || die "cell $2 is not in 0..$((cells - 1))"
    [[ -x $bin ]] || die "$bin not found: build first (bash scripts/build.sh)"
    run_cell "$2" "$3"
    [[ $cell_result != interrupted ]] || interrupted "$2"
    cell_of "$2"
    echo "sim_sweep: cell $2 ($scenario $algo $n particles, $pace, $controller, $occupancy) done in $3/cells"
    exit 0 ;;
esac
out=${1:-$root/results/sim/local}
[[ -x $bin ]] || die "$bin not found: build first (bash scripts/build.sh)"
mkdir -p "$out"
echo "sim_sweep: $cells cells x $trials trials, pacing ${paces[*]}, controller ${controllers[*]}, occupancy ${occupancies[*]}, into $out" >&2
start=$SECONDS ran=0
for ((k = 0; k < cells; k++)); do
  [[ -z $stop ]] || interrupted "$k"
  t0=$SECONDS
  run_cell "$k" "$out"
  [[ $cell_result != interrupted ]] || interrupted "$k"
  cell_of "$k"
  if [[ $cell_result == ran ]]; then
    ran=$((ran + 1))
    per=$(((SECONDS - start) / ran))
    left=$(((cells - k - 1) * per))
    printf 'sim_sweep: [%d/%d] %s %s %d %s %s %s: %ds; about %dh%02dm left\n' $((k + 1)) \
      "$cells" "$scenario" "$algo" "$n" "$pace" "$controller" "$occupancy" $((SECONDS - t0)) \
      $((left / 3600)) $((left % 3600 / 60)) >&2
  else
    printf 'sim_sweep: [%d/%d] %s %s %d %s %s %s: already done\n' $((k + 1)) "$cells" \
      "$scenario" "$algo" "$n" "$pace" "$controller" "$occupancy" >&2
  fi
done
echo "sim_sweep: done; report: python3 scripts/sim_report.py $out" >&2
