#!/usr/bin/env bash
# Against a real single-node SLURM (slurm/local_cluster.sh): submit the smoke job and a
# two-point strong-scaling job with sbatch, wait for them, check their outputs, check that an
# impossible rank count fails with a clear message, then stop the cluster.
# Usage: test_slurm.sh REPO_ROOT BIN_DIR
set -uo pipefail
root=${1:?usage: test_slurm.sh REPO_ROOT BIN_DIR}
bins=${2:?usage: test_slurm.sh REPO_ROOT BIN_DIR}
work=$(mktemp -d /tmp/hpcplan-slurm-test.XXXXXX)
cluster=$work/cluster
fail() { echo "FAIL: $*" >&2; for f in "$cluster"/*.log "$work"/*.out; do [[ -f $f ]] && { echo "--- $f" >&2; tail -20 "$f" >&2; }; done; exit 1; }
cleanup() { bash "$root/slurm/local_cluster.sh" stop "$cluster" >/dev/null 2>&1; rm -rf "$work"; }
trap cleanup EXIT

line=$(bash "$root/slurm/local_cluster.sh" start "$cluster") || fail "the local cluster did not start"
eval "$line"
export HPCPLAN_ROOT=$root HPCPLAN_BIN_DIR=$bins HPCPLAN_RESULTS=$work/results

submit() {  # submit NAME SCRIPT [sbatch args]: waits; prints the job id
  local name=$1 script=$2 rc=0
  shift 2
  timeout 300 sbatch --parsable --wait --chdir "$work" --output "$work/$name-%j.out" "$@" \
    "$root/slurm/$script" || rc=$?
  ((rc != 124)) || echo "sbatch --wait ($name) did not return within 300 s: a hung job?" >&2
  return "$rc"
}

# 1. Smoke: 2 ranks, cost equal to the serial engine's.
jid=$(submit smoke smoke.sbatch --ntasks 2) || fail "smoke job failed"
grep -q "smoke: ok" "$work"/smoke-"$jid".out || fail "smoke job did not report ok"
res=$work/results/smoke/$jid
[[ -f $res/result.json && -f $res/meta.json ]] || fail "smoke results missing in $res"
python3 - "$res" <<'PY' || exit 1
import json, sys
r = json.load(open(sys.argv[1] + "/result.json")); m = json.load(open(sys.argv[1] + "/meta.json"))
assert r["ranks"] == 2, r["ranks"]
assert abs(r["cost"] - r["serial_reference"]["cost"]) < 1e-9 * (1 + r["cost"]), "cost differs"
assert m["nodelist"] and m["git_revision"] and m["job_id"], m
print("smoke results ok:", r["cost"], m["nodelist"])
PY

# 2. Strong scaling at P = 1, 2 on a small problem.
jid=$(P_LIST="1 2" DIMS=3 EXTENT=40 REPEATS=1 MODES=bulk COARSEN=0 \
  submit strong strong_scaling.sbatch --ntasks 2) || fail "strong-scaling job failed"
csv=$work/results/strong/$jid/strong.csv
[[ -f $csv ]] || fail "no $csv"
python3 - "$csv" <<'PY' || exit 1
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
ranks = sorted(int(r["ranks"]) for r in rows)
assert ranks == [1, 2], ranks
for r in rows:
    assert r["status"] == "solved", r
    assert float(r["speedup_vs_serial"]) > 0, r
print("strong results ok:", [(r["ranks"], r["speedup_vs_serial"]) for r in rows])
PY

# 3. An impossible rank count fails with a message naming it, and writes no results.
if submit bad strong_scaling.sbatch --ntasks 1 --export=ALL,P_LIST=4 >/dev/null; then
  fail "P = 4 on a 1-task job was accepted"
fi
grep -q "P = 4 exceeds the job's 1 tasks" "$work"/bad-*.out || fail "no clear message for an impossible P"

# 4. Reruns never overwrite: a second smoke run gets its own folder.
submit smoke smoke.sbatch --ntasks 2 >/dev/null || fail "second smoke job failed"
[[ $(ls "$work/results/smoke" | wc -l) -eq 2 ]] || fail "smoke results were overwritten"
# 5. A rerun study skips the points it already has.
jid=$(P_LIST="1 2" DIMS=3 EXTENT=40 REPEATS=1 MODES=bulk COARSEN=0 \
  submit strong strong_scaling.sbatch --ntasks 2) || fail "strong rerun failed"
grep -q "P = 2 already measured, skipped" "$work"/strong-"$jid".out || fail "rerun did not skip"

# 6. Weak scaling (2 points) and the dimension sweep as a 2-task array.
jid=$(P_LIST="1 2" DIMS=3 EXTENT1=30 REPEATS=1 submit weak weak_scaling.sbatch --ntasks 2) ||
  fail "weak-scaling job failed"
[[ $(tail -n +2 "$work/results/weak/$jid/weak.csv" | wc -l) -eq 2 ]] || fail "weak CSV incomplete"
jid=$(DIMS_LIST="2 3" submit dims dimension_sweep.sbatch --ntasks 2 --array 0-1) ||
  fail "dimension-sweep array failed"
[[ -f $work/results/dims/${jid}_0/result.json && -f $work/results/dims/${jid}_1/result.json ]] ||
  fail "dimension-sweep results missing"

# 7. Aggregation over all of it: strong speedup rows for P = 1, 2, weak, Table IV.
python3 "$root/scripts/scaling_report.py" "$work/results" > "$work/report.md" ||
  fail "scaling_report failed"
grep -q "strong scaling — 3D extent 40" "$work/report.md" && grep -q "weak scaling — 3D" \
  "$work/report.md" && grep -q "Table IV" "$work/report.md" || fail "report incomplete: $(cat "$work/report.md")"

# 8. Seed 000's sweep as a job array (4 cells: 500 particles, 2 scenarios, 2 planners), all tasks
# writing into one folder, then its tables and figures; a resubmission skips every cell.
sweep() {  # submit with the small sweep's settings in the job's environment
  PARTICLES=500 SCENARIOS="particles dynamic" ALGOS="astar rrtstar" TRIALS=1 PACE=lockstep \
    MAX_SIM_S=20 THREADS=1 submit "$@"
}
jid=$(sweep sim sim_sweep.sbatch --array 0-3 --cpus-per-task 1) ||
  fail "sim sweep array failed"
sweep=$work/results/sim/$jid
[[ $(ls "$sweep"/cells/*_*_500_lockstep_seed.csv 2>/dev/null | grep -vc replans) -eq 4 ]] ||
  fail "sim sweep cells missing: $(ls "$sweep/cells" 2>&1)"
/usr/bin/python3 "$root/scripts/sim_report.py" "$sweep" --out "$work/simreport" > "$work/sim.md" ||
  fail "sim_report failed"
grep -q "Table II" "$work/sim.md" && grep -q "Table III" "$work/sim.md" &&
  grep -q "Table IV" "$work/sim.md" && [[ -f $work/simreport/fig3_scaling.png ]] ||
  fail "sim report incomplete: $(cat "$work/sim.md")"
# Resuming (locally, same settings): every cell is already there, nothing is rerun; a cell
# beyond the settings' grid is refused with a clear message.
touch "$work/marker"
sleep 1
PARTICLES=500 SCENARIOS="particles dynamic" ALGOS="astar rrtstar" TRIALS=1 PACE=lockstep \
  BIN=$bins/hpcplan bash "$root/bench/sim_sweep.sh" "$sweep" 2> "$work/resume.txt" ||
  fail "resuming the sweep failed"
[[ $(grep -c "already done" "$work/resume.txt") -eq 4 ]] || fail "resume did not skip: $(cat "$work/resume.txt")"
[[ -z $(find "$sweep/cells" -newer "$work/marker" -type f) ]] || fail "the resumed sweep reran cells"
if PARTICLES=500 SCENARIOS="particles dynamic" ALGOS="astar rrtstar" \
  bash "$root/bench/sim_sweep.sh" --cell 4 "$sweep" 2> "$work/err.txt"; then
  fail "a cell beyond the sweep's grid was accepted"
fi
grep -q "cell 4 is not in 0..3" "$work/err.txt" || fail "unclear error for a cell beyond the grid"
# Both pacings and both controllers in one folder: resuming after an interrupted realtime cell
# reruns that cell only (the lockstep ones and the finished realtime one stay as they were).
mixed=$work/results/sim/mixed
mix() {
  PARTICLES=300 SCENARIOS=particles ALGOS=astar TRIALS=1 PACES="lockstep realtime" \
    CONTROLLERS="seed reactive" MAX_SIM_S=2 THREADS=1 BIN=$bins/hpcplan \
    bash "$root/bench/sim_sweep.sh" "$mixed" 2> "$work/mix.txt"
}
mix || fail "the mixed sweep failed: $(cat "$work/mix.txt")"
[[ $(ls "$mixed"/cells/particles_astar_300_*.csv | grep -vc replans) -eq 4 ]] ||
  fail "mixed sweep cells missing: $(ls "$mixed/cells")"
for c in lockstep_seed lockstep_reactive realtime_seed realtime_reactive; do
  grep -q "${c%_*},${c#*_}," "$mixed/cells/particles_astar_300_$c.csv" ||
    fail "cell $c does not record its pacing and controller"
done
rm "$mixed/cells/particles_astar_300_realtime_reactive.csv"  # as if killed before its end
touch "$work/marker2"
sleep 1
mix || fail "resuming the mixed sweep failed: $(cat "$work/mix.txt")"
[[ $(grep -c "already done" "$work/mix.txt") -eq 3 ]] || fail "mixed resume: $(cat "$work/mix.txt")"
[[ $(find "$mixed/cells" -name '*.csv' -newer "$work/marker2" | grep -vc replans) -eq 1 &&
   -n $(find "$mixed/cells" -name 'particles_astar_300_realtime_reactive.csv' -newer "$work/marker2") ]] ||
  fail "the mixed resume did not rerun exactly the missing realtime cell"
# A density occupancy added to the lockstep settings: only its 2 cells run (named by their
# threshold, recording the rule), the seed-occupancy ones are kept; the report compares them.
touch "$work/marker3"
sleep 1
PARTICLES=300 SCENARIOS=particles ALGOS=astar TRIALS=1 PACES=lockstep CONTROLLERS="seed reactive" \
  OCCUPANCIES="particles density:0.8" MAX_SIM_S=2 THREADS=1 BIN=$bins/hpcplan \
  bash "$root/bench/sim_sweep.sh" "$mixed" 2> "$work/occ.txt" || fail "occupancy sweep: $(cat "$work/occ.txt")"
[[ $(grep -c "already done" "$work/occ.txt") -eq 2 &&
   $(find "$mixed/cells" -name '*.csv' -newer "$work/marker3" | grep -vc replans) -eq 2 ]] ||
  fail "the occupancy sweep did not add exactly its 2 cells: $(cat "$work/occ.txt")"
grep -q ",density:0.28:0.8$" "$mixed/cells/particles_astar_300_lockstep_seed_density0.8.csv" ||
  fail "the density cell does not record its occupancy"
if OCCUPANCIES="density" bash "$root/bench/sim_sweep.sh" --count 2> "$work/err.txt"; then
  fail "an occupancy without a threshold was accepted"
fi
grep -q "unknown occupancy density" "$work/err.txt" || fail "unclear error for a bad occupancy"
/usr/bin/python3 "$root/scripts/sim_report.py" "$mixed" --out "$work/mixreport" > "$work/mix.md" ||
  fail "sim_report failed on the mixed sweep"
grep -q "Adaptive occupancy" "$work/mix.md" && grep -q "density:0.28:0.8" "$work/mix.md" &&
  [[ -f $work/mixreport/fig6_occupancy.png ]] || fail "no occupancy table: $(cat "$work/mix.md")"

# 9. submit.sh: clear errors for a missing binary and when no controller answers.
if HPCPLAN_BIN_DIR=$work/nowhere bash "$root/slurm/submit.sh" smoke > /dev/null 2> "$work/err.txt"; then
  fail "submit.sh accepted a missing binary"
fi
grep -q "hpcplan not found" "$work/err.txt" || fail "unclear error for a missing binary: $(cat "$work/err.txt")"
if SLURM_CONF=$work/none.conf bash "$root/slurm/submit.sh" smoke > /dev/null 2> "$work/err.txt"; then
  fail "submit.sh succeeded without a controller"
fi
grep -q "no SLURM controller" "$work/err.txt" || fail "unclear error without a controller: $(cat "$work/err.txt")"
echo "slurm: ok"
