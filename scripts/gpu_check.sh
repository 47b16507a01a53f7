#!/usr/bin/env bash
# The CUDA backend's checks on a machine with an NVIDIA GPU, in one go (issue 16):
#   1. a smoke run of the CPU/CUDA agreement on small fluids;
#   2. the full check (hpcplan_sph_gpu_check): agreement over 1,000 frames, the dam-break front,
#      particle-steps per second at 25k / 100k / 1M / 4M particles for both presets, CUDA against
#      the CPU backend on all cores, in the same process;
#   3. compute-sanitizer memcheck and racecheck on the small runs of step 1;
#   4. the CLI with --backend cuda (hpcplan sph and hpcplan sim), when hpcplan is there (where
#      it is not, the summary says so).
# Every run of the check verifies (--verify: what it checks is in bench/sph_gpu_check.cpp), and
# HPCPLAN_EXPECT_GPU=1 makes a CUDA backend that cannot run a failure, not a skip.
# Each step has its own time limit and log; a failing step does not stop the others, but the
# script ends with exit 1 and names every step that failed (a non-zero exit, a time limit hit).
# Usage: scripts/gpu_check.sh BIN_DIR OUT_DIR [FULL_BUDGET_S=180]
#   FULL_BUDGET_S: the full check's seconds after which it starts no more speed measurements
#   (each left out is listed in full.log); the agreement and dam-break runs always run.
#   BIN_DIR holds hpcplan_sph_gpu_check (and hpcplan); a lib/ folder beside it, if any, is
#   put on LD_LIBRARY_PATH (libraries carried from the build machine).
set -uo pipefail
export HPCPLAN_EXPECT_GPU=1
bin=${1:?BIN_DIR} out=${2:?OUT_DIR} budget=${3:-180}
mkdir -p "$out"
# Carried libraries: lib/ for hpcplan, libomp/ (OpenMP's runtime alone) for the check, so that
# compute-sanitizer itself never loads a carried libstdc++.
libs=$bin/../lib omp=$bin/../libomp
[[ -d $libs ]] && libs=$(cd "$libs" && pwd)
[[ -d $omp ]] && omp=$(cd "$omp" && pwd)
check=(env "LD_LIBRARY_PATH=$omp${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$bin/hpcplan_sph_gpu_check")
cli=(env "LD_LIBRARY_PATH=$libs${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" "$bin/hpcplan")
export OMP_NUM_THREADS=${OMP_NUM_THREADS:-$(nproc)}
sanitizer=$(command -v compute-sanitizer || echo /usr/local/cuda/bin/compute-sanitizer)
failed=()
: > "$out/steps.txt"
step() {  # step NAME LIMIT_S COMMAND...
  local name=$1 limit=$2
  shift 2
  local t0=$SECONDS
  timeout "$limit" "$@" > "$out/$name.log" 2>&1
  local rc=$? verdict=ok
  if ((rc == 124)); then
    verdict="FAILED (over its limit of $limit s)"
  elif ((rc != 0)); then
    verdict=FAILED
  fi
  [[ $verdict == ok ]] || failed+=("$name")
  echo "step $name: $verdict, rc=$rc in $((SECONDS - t0)) s" | tee -a "$out/steps.txt"
  tail -n 30 "$out/$name.log"
}
{ nvidia-smi -L; nproc; } > "$out/machine.txt" 2>&1
cat "$out/machine.txt"
step smoke 90 "${check[@]}" --quick --frames 20 --verify
step full $((budget + 120)) "${check[@]}" --frames 1000 --budget-s "$budget" --verify
step memcheck 100 env "LD_LIBRARY_PATH=$omp" "$sanitizer" --tool memcheck --error-exitcode 3 \
  "$bin/hpcplan_sph_gpu_check" --quick --frames 2 --verify
step racecheck 80 env "LD_LIBRARY_PATH=$omp" "$sanitizer" --tool racecheck --error-exitcode 3 \
  "$bin/hpcplan_sph_gpu_check" --quick --frames 1 --verify
if [[ ! -x $bin/hpcplan ]]; then
  echo "steps cli_sph, cli_sim, cli_sim_cpu: not run ($bin has no hpcplan)" | tee -a "$out/steps.txt"
else
  step cli_sph 60 "${cli[@]}" sph --backend cuda --preset water --scenario dambreak \
    --particles 13500 --frames 9 --front-csv "$out/front_cuda.csv" --json
  step cli_sim 60 "${cli[@]}" sim --backend cuda --scenario dynamic --particles 25000 \
    --algo astar --runs 1 --max-sim-s 4 --settle-frames 50 --json
  step cli_sim_cpu 60 "${cli[@]}" sim --backend cpu --scenario dynamic --particles 25000 \
    --algo astar --runs 1 --max-sim-s 4 --settle-frames 50 --json
fi
if ((${#failed[@]})); then
  echo "gpu_check: FAILED: ${failed[*]} (logs in $out)" | tee -a "$out/steps.txt" >&2
  exit 1
fi
echo "gpu_check: every step passed" | tee -a "$out/steps.txt"
