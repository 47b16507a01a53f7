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

# A job's (or a job array's) states, one per task; its end: every task in a final state.
job_states() { scontrol show job -o "$1" 2> /dev/null | grep -o ' JobState=[^ ]*' | cut -d= -f2; }
finished() { [[ $1 =~ ^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|PREEMPTED|BOOT_FAIL|DEADLINE)$ ]]; }

submit() {  # submit NAME SCRIPT [sbatch args]: waits; prints the job id; fails unless COMPLETED
  # Polled every 0.2 s rather than `sbatch --wait`, which looks at 2 s and then at 10 s: each of
  # these jobs ends within seconds, and the waits were a third of this test's four minutes.
  local name=$1 script=$2 jid states s deadline
  shift 2
  jid=$(timeout 60 sbatch --parsable --chdir "$work" --output "$work/$name-%j.out" "$@" \
    "$root/slurm/$script") || return 1
  jid=${jid%%;*}
  echo "$jid"
  deadline=$((SECONDS + 300))
  while ((SECONDS < deadline)); do
    states=$(job_states "$jid")
    if [[ -n $states ]]; then
      local done=1 ok=0
      for s in $states; do finished "$s" || done=0; [[ $s == COMPLETED ]] || ok=1; done
      ((done)) && return "$ok"
    fi
    sleep 0.2
  done
  echo "job $jid ($name) did not end within 300 s: a hung job?" >&2
  return 1
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

# 6b. The kinematic chain's ranks (issue 48), strong and weak, 2 points each: every row's cost
# equals the serial engine's (the job fails otherwise), the weak study adds a link per doubling.
jid=$(P_LIST="1 2" LINKS=4 REPEATS=1 submit cspace cspace_scaling.sbatch --ntasks 2) ||
  fail "c-space strong job failed"
[[ $(tail -n +2 "$work/results/cspace_strong/$jid/scaling.csv" | wc -l) -eq 2 ]] ||
  fail "c-space strong CSV incomplete"
jid=$(STUDY=weak P_LIST="1 2" LINKS=4 REPEATS=1 submit cspace cspace_scaling.sbatch --ntasks 2) ||
  fail "c-space weak job failed"
[[ $(cut -d, -f2 "$work/results/cspace_weak/$jid/scaling.csv" | tail -n +2 | tr '\n' ' ') == "4 5 " ]] ||
  fail "c-space weak study did not add a link per doubling"

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
  fail "submit.sh succeeded without a configuration"
fi
grep -q "SLURM_CONF=$work/none.conf is not a readable file" "$work/err.txt" ||
  fail "unclear error without a configuration: $(cat "$work/err.txt")"
# The cluster's own configuration with the controller's port moved to one nobody listens on.
sed -E 's/^SlurmctldPort=.*/SlurmctldPort=1/' "$SLURM_CONF" > "$work/dead.conf"
grep -q '^SlurmctldPort=1$' "$work/dead.conf" || echo 'SlurmctldPort=1' >> "$work/dead.conf"
if SLURM_CONF=$work/dead.conf bash "$root/slurm/submit.sh" smoke > /dev/null 2> "$work/err.txt"; then
  fail "submit.sh succeeded without a controller"
fi
grep -q "no SLURM controller" "$work/err.txt" || fail "unclear error without a controller: $(cat "$work/err.txt")"

# 10. Checkpointed jobs interrupted by their warning signal and requeued. The cluster requeues;
# `scancel --batch --signal=USR1` signals the batch shell alone, as `#SBATCH --signal=B:USR1@N`
# does before the time limit (the shell forwards it); SLURM holds a requeued job for about two
# minutes (Reason=BeginTime), so the test releases it 2 s after it is pending again (slurmd
# refuses a job relaunched within the second its credential was revoked by the requeue:
# "Job credential revoked").
grep -Eq '^JobRequeue += 1$' <<< "$(scontrol show config)" || fail "the local cluster does not allow requeueing"
field() { scontrol show job -o "$1" 2> /dev/null | grep -o " $2=[^ ]*" | cut -d= -f2; }
# The events a warning signal waits for. exist FILE...: all there. catching_usr1 N PATTERN: N
# hpcplan processes whose command line holds PATTERN have put their SIGUSR1 handler in place
# (SigCgt in /proc/PID/status, bit 10 - 1): a checkpointing search is under way, and SIGUSR1
# now ends it at its next level or bucket with a checkpoint, however far it has got.
exist() { local f; for f in "$@"; do [[ -e $f ]] || return 1; done; }
catching_usr1() {
  local n=0 p mask
  for p in $(pgrep -f -- "$2"); do
    [[ $(cat "/proc/$p/comm" 2> /dev/null) == hpcplan ]] || continue
    mask=$(awk '/^SigCgt:/ {print $2}' "/proc/$p/status" 2> /dev/null)
    [[ -n $mask ]] && (((16#$mask >> 9) & 1)) && n=$((n + 1))
  done
  ((n == $1))
}
# interrupt_requeue NAME JID EVENT...: once the command EVENT... succeeds, the warning signal
# (the event is polled every 10 ms, the job's state every 0.2 s: a job that ends first fails);
# then the requeued job released, and its end awaited (COMPLETED, else a failure). Each wait is
# bounded by a guard.
interrupt_requeue() {
  local name=$1 jid=$2 state restarts deadline=$((SECONDS + 120))
  shift 2
  for ((t = 0; ; t++)); do
    ! "$@" || break
    if ((t % 20 == 0)); then
      state=$(field "$jid" JobState)
      ! finished "$state" || fail "$name: job $jid ended ($state) before it was interrupted"
    fi
    ((SECONDS < deadline)) || fail "$name: no '$*' within 120 s of job $jid"
    sleep 0.01
  done
  scancel --batch --signal=USR1 "$jid" || fail "$name: scancel --signal=USR1 failed"
  for ((t = 0; ; t++)); do
    state=$(field "$jid" JobState) restarts=$(field "$jid" Restarts)
    if [[ $state == PENDING && ${restarts:-0} -ge 1 ]]; then
      sleep 2
      scontrol update JobId="$jid" StartTime=now 2> /dev/null && break
    fi
    ! finished "$state" || fail "$name: job $jid ended ($state) instead of being requeued"
    ((t < 600)) || fail "$name: job $jid was not requeued within 60 s of its signal (state $state)"
    sleep 0.1
  done
  for ((t = 0; ; t++)); do
    state=$(field "$jid" JobState)
    [[ $state != COMPLETED ]] || break
    ! finished "$state" || fail "$name: the requeued job $jid ended $state"
    ((t < 1800)) || fail "$name: the requeued job $jid did not end within 180 s (state $state)"
    sleep 0.1
  done
  [[ $(field "$jid" Restarts) == 1 ]] || fail "$name: job $jid restarted $(field "$jid" Restarts) times, not once"
  local out=$work/$name-$jid.out
  [[ $(grep -c "requeueing job $jid (restart 1)" "$out") -eq 1 &&
     $(grep -c "restart 1 of job $jid: continuing in" "$out") -eq 1 ]] ||
    fail "$name: the job's output does not show one interruption and one restart: $(cat "$out")"
}
t10=$SECONDS
# The fluid: 256 water particles (the dam break), 60 frames (about 8 s on one core), a
# checkpoint and a VTK file every 5 frames; the MPI stand-in alongside it (2 ranks).
fluid_env=(PRESET=water PARTICLES=300 FRAMES=60 SEED=1 THREADS=1 CHECKPOINT_EVERY=5 VTK_EVERY=5)
fid=$(env "${fluid_env[@]}" timeout 60 sbatch --parsable --chdir "$work" \
  --output "$work/fluid-%j.out" --cpus-per-task 1 "$root/slurm/fluid.sbatch") || fail "fluid job not submitted"
wid=$(timeout 60 sbatch --parsable --chdir "$work" --output "$work/forward-%j.out" --ntasks 2 \
  "$root/tests/slurm/forward_ranks.sbatch") || fail "MPI stand-in job not submitted"
# The same fluid uninterrupted, run directly (bounded), meanwhile.
mkdir -p "$work/fluid_ref"
timeout 300 "$bins/hpcplan" sph --preset water --particles 300 --frames 60 --seed 1 --threads 1 \
  --backend cpu --checkpoint "$work/fluid_ref/fluid.ck" --checkpoint-every 5 \
  --vtk "$work/fluid_ref/vtk" --every 5 > /dev/null 2> "$work/fluid_ref.err" &
ref_pid=$!
fres=$work/results/fluid/$fid
interrupt_requeue fluid "$fid" exist "$fres/fluid.ck"
wait "$ref_pid" || fail "the uninterrupted fluid run failed (exit $?: 124 = over 300 s): $(cat "$work/fluid_ref.err")"
grep -q "fluid: ok (water dambreak, 256 particles, 60 frames; restarts 1, this run from frame [1-9]" \
  "$work/fluid-$fid.out" || fail "fluid: no final report of the restarted run: $(cat "$work/fluid-$fid.out")"
grep -q "hpcplan job: restarting from $fres/fluid.ck" "$work/fluid-$fid.out" ||
  fail "fluid: the requeued run did not restart from the checkpoint"
cmp -s "$work/fluid_ref/fluid.ck" "$fres/fluid.ck" ||
  fail "fluid: the final checkpoint differs from the uninterrupted run's"
for f in "$work"/fluid_ref/vtk/*; do
  cmp -s "$f" "$fres/vtk/$(basename "$f")" || fail "fluid: vtk/$(basename "$f") differs from the uninterrupted run's"
done
[[ $(ls "$work/fluid_ref/vtk" | wc -l) -eq $(ls "$fres/vtk" | wc -l) ]] || fail "fluid: other VTK files"
python3 - "$fres/meta.json" "$fid" <<'PY' || fail "fluid: meta.json does not record both runs"
import json, sys
m = json.load(open(sys.argv[1]))
assert [r["restart_count"] for r in m["runs"]] == [0, 1], m["runs"]
assert all(r["job_id"] == sys.argv[2] for r in m["runs"]), m["runs"]
PY
[[ $(ls "$work/results/fluid" | wc -l) -eq 1 && ! -e $fres/.requeued.$fid ]] ||
  fail "fluid: the requeued job did not keep its one folder: $(ls -a "$work/results/fluid" "$fres")"
echo "fluid requeue ok: the interrupted and requeued job wrote the uninterrupted run's checkpoint and VTK files"
# The MPI stand-in: both ranks had the signal, through mpirun, and the requeued job ended them.
wres=$work/results/forward/$wid
interrupt_requeue forward "$wid" exist "$wres/ready.r0" "$wres/ready.r1"
for r in 0 1; do
  grep -q "rank $r: SIGUSR1" "$work/forward-$wid.out" && grep -q "rank $r: restarted" "$work/forward-$wid.out" ||
    fail "forward: rank $r did not get the signal through mpirun: $(cat "$work/forward-$wid.out")"
done
grep -q "forward: ok (restarts 1" "$work/forward-$wid.out" || fail "forward: no final report"
echo "mpirun forwarding ok: the batch shell's SIGUSR1 reached both ranks, and the job requeued"

# 11. The dense lattice job likewise (2 ranks, a checkpoint per rank): the requeued job ends
# with the uninterrupted search's cost, hops and expansions. The signal goes as soon as both
# ranks catch SIGUSR1, not after the first timed checkpoint (CHECKPOINT_EVERY=1: the first one
# came 1 s in, and a machine a few times faster ended the search first): the whole search is
# then still ahead, and it ends at its next bucket with a checkpoint per rank. The requeued job
# checkpoints every second besides.
if [[ $(id -u) -eq 0 ]]; then export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1; fi
lattice_env=(DIMS=5 EXTENT=40 ALGO=dijkstra SEED=1 THREADS=1 CHECKPOINT_EVERY=1)
lid=$(env "${lattice_env[@]}" timeout 60 sbatch --parsable --chdir "$work" \
  --output "$work/lattice-%j.out" --ntasks 2 "$root/slurm/lattice.sbatch") || fail "lattice job not submitted"
timeout 300 mpirun -np 2 --oversubscribe "$bins/hpcplan" grid --engine dense --dims 5 --extent 40 \
  --algo dijkstra --density 0.40 --seed 1 --threads 1 --json > "$work/lattice_ref.json" \
  2> "$work/lattice_ref.err" &
ref_pid=$!
lres=$work/results/lattice/$lid
interrupt_requeue lattice "$lid" catching_usr1 2 "$lres/lattice.ck"
wait "$ref_pid" || fail "the uninterrupted lattice run failed (exit $?: 124 = over 300 s): $(cat "$work/lattice_ref.err")"
grep -q "hpcplan job: restarting from $lres/lattice.ck" "$work/lattice-$lid.out" ||
  fail "lattice: the requeued run did not restart from the checkpoints"
python3 - "$work/lattice_ref.json" "$lres/result.json" <<'PY' || fail "lattice: the requeued job's answer differs"
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:])
assert a["status"] == b["status"] == "solved", (a["status"], b["status"])
for k in ("cost", "hops", "expanded"):
  assert a[k] == b[k], (k, a[k], b[k])
print("lattice requeue ok: cost", b["cost"], "hops", b["hops"], "expanded", b["expanded"])
PY

# 12. The sweep interrupted in a cell (locally: SIGUSR1 to bench/sim_sweep.sh, as the sbatch's
# forward does): exit 75, the cell's finished runs in its checkpoint and no CSV under the cell's
# name (a CSV there would mark the cell done); run again, it continues the cell to all its runs.
isw=$work/results/sim/interrupted
isw_env=(PARTICLES=3000 SCENARIOS=dynamic ALGOS=astar TRIALS=3 PACE=lockstep MAX_SIM_S=20 THREADS=1
  BIN="$bins/hpcplan")
env "${isw_env[@]}" bash "$root/bench/sim_sweep.sh" "$isw" 2> "$work/isweep.txt" &
isw_pid=$!  # the sweep's own process (under `timeout` it would be timeout's, which dies of SIGUSR1)
cell=$isw/cells/dynamic_astar_3000_lockstep_seed
# The signal goes once the cell's first run is saved, whenever that is (a guard of 300 s; a
# sweep that ends first fails); its two other runs are then still ahead.
deadline=$((SECONDS + 300))
until [[ -e $cell.ck ]]; do
  kill -0 "$isw_pid" 2> /dev/null || fail "sweep interrupted: it ended before its cell's first run was saved: $(cat "$work/isweep.txt")"
  ((SECONDS < deadline)) || { kill "$isw_pid"; fail "sweep interrupted: no cell checkpoint within 300 s"; }
  sleep 0.01
done
kill -USR1 "$isw_pid"
for ((t = 0; t < 600; t++)); do kill -0 "$isw_pid" 2> /dev/null || break; sleep 0.1; done
kill -0 "$isw_pid" 2> /dev/null && { kill "$isw_pid"; fail "sweep interrupted: still running 60 s after SIGUSR1"; }
wait "$isw_pid"
rc=$?
((rc == 75)) || fail "sweep interrupted: exit $rc, not 75 ($(cat "$work/isweep.txt"))"
grep -q "interrupted (SIGUSR1) in cell 0" "$work/isweep.txt" && [[ -f $cell.ck && ! -e $cell.csv ]] ||
  fail "sweep interrupted: no checkpoint, or the cell counted done: $(ls "$isw/cells") $(cat "$work/isweep.txt")"
env "${isw_env[@]}" timeout 300 bash "$root/bench/sim_sweep.sh" "$isw" 2> "$work/isweep.txt" ||
  fail "sweep continued: exit $? (124: over 300 s): $(cat "$work/isweep.txt")"
grep -q "continues from its checkpoint" "$cell.log" && [[ ! -e $cell.ck ]] &&
  [[ $(tail -n +2 "$cell.csv" | wc -l) -eq 3 ]] || fail "sweep continued: the cell is not whole: $(ls "$isw/cells")"
echo "sweep interrupt ok: the cell continued from its checkpoint to its 3 runs"
echo "checkpointed jobs and sweep: $((SECONDS - t10)) s"
echo "slurm: ok"
