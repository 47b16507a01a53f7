#!/usr/bin/env bash
# hpcplan grid --checkpoint / --restart end to end with real signals: a dense BFS ended by
# SIGUSR1 (SLURM's warning) or SIGTERM at a level boundary reports status interrupted with exit
# 0, and its restart ends with the uninterrupted run's cost, hops and counts; a two-rank
# Dijkstra under mpirun, interrupted through mpirun, likewise (one file per rank); bad input.
# Usage: test_grid_checkpoint.sh HPCPLAN [MPIRUN]
set -uo pipefail
bin=$1
mpirun=${2:-}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "grid_checkpoint: FAIL: $*" >&2; exit 1; }
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1

# 4D, extent 80: 41 million states, 158 levels; about a second on two cores of the 2-core VM.
# The interrupted runs checkpoint at every level (--checkpoint-every 1e-6: due at each
# boundary) and are signalled once the first checkpoint is there, i.e. after their first level:
# whatever the machine's speed, a run is then well inside, with each of its remaining levels
# writing a 14 MB checkpoint (a run that finished first would fail the status check, not pass).
problem=(--dims 4 --extent 80 --engine dense)
every=(--checkpoint-every 0.000001)
same() {  # same REFERENCE.json RESTARTED.json: answer and counts equal
  python3 - "$1" "$2" <<'PY' || fail "the restarted run differs from the uninterrupted one"
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
for k in ["status", "cost", "hops", "expanded", "generated", "peak_states", "peak_open",
          "collision_checks"]:
    assert a[k] == b[k], (k, a[k], b[k])
assert a["dense"]["levels"] == b["dense"]["levels"]
assert b["restarted_from"], b
print("grid_checkpoint: restart equals the uninterrupted run:", b["cost"], b["hops"], b["expanded"])
PY
}
interrupted() {  # interrupted OUT.json SIGNAL CHECKPOINT
  python3 - "$@" <<'PY' || fail "the interrupted run's report is wrong: $(cat "$1")"
import json, sys
j = json.load(open(sys.argv[1]))
assert j["status"] == "interrupted" and j["interrupted_by"] == sys.argv[2], j
assert j["checkpoint"] == sys.argv[3] and j["cost"] is None, j
PY
}
wait_for() {  # wait_for FILE PID: until FILE exists (the run is past its first level); fails
  # if the run ends first, or after 120 s (a guard: the first level takes well under a second)
  local deadline=$((SECONDS + 120))
  until [[ -e $1 ]]; do
    kill -0 "$2" 2>/dev/null && ((SECONDS < deadline)) || return 1
    sleep 0.01
  done
}

timeout 300 "$bin" grid "${problem[@]}" --threads 2 --algo bfs --json > "$dir/ref.json" || fail "reference run failed"
for sig in USR1 TERM; do
  ck=$dir/bfs_$sig.ckpt
  # (Not under timeout, which would take the signal itself; ctest's limit guards it.)
  "$bin" grid "${problem[@]}" --threads 2 --algo bfs --json --checkpoint "$ck" "${every[@]}" \
    > "$dir/int.json" &
  pid=$!
  wait_for "$ck" "$pid" || fail "no checkpoint appeared"
  kill -"$sig" "$pid"
  wait "$pid" || fail "the interrupted run exited $? (SIG$sig)"
  interrupted "$dir/int.json" "SIG$sig" "$ck"
  compgen -G "$dir/*.tmp*" > /dev/null && fail "a temporary file was left: $(ls "$dir")"
  timeout 300 "$bin" grid "${problem[@]}" --threads 2 --algo bfs --json --restart "$ck" > "$dir/res.json" ||
    fail "the restart failed"
  same "$dir/ref.json" "$dir/res.json"
done

# Bad input: exit 2 with one line naming the problem.
refuse() {  # refuse "MESSAGE PART" ARGS...
  local want=$1
  shift
  local err
  err=$("$bin" grid "$@" 2>&1 > /dev/null)
  local rc=$?
  [[ $rc -eq 2 ]] || fail "exit $rc for: $* ($err)"
  [[ $(wc -l <<< "$err") -eq 1 && $err == *"$want"* ]] || fail "unclear error for $*: $err"
}
refuse "--checkpoint and --restart need the dense engine" --dims 2 --algo astar --checkpoint "$dir/x"
refuse "--checkpoint-every needs --checkpoint" --dims 2 --algo bfs --checkpoint-every 5
refuse "is not a readable regular file" --dims 2 --algo bfs --restart "$dir/none"
refuse "is not an hpcplan dense lattice checkpoint" --dims 2 --algo bfs --restart "$dir/ref.json"
refuse "(engine = bfs; this run has engine = dijkstra)" "${problem[@]}" --threads 2 --algo dijkstra \
  --restart "$dir/bfs_USR1.ckpt"
refuse "(extent = 80; this run has extent = 79)" --dims 4 --extent 79 --engine dense \
  --threads 2 --algo bfs --restart "$dir/bfs_USR1.ckpt"
refuse "--checkpoint" --dims 2 --algo bfs --checkpoint "$dir/no/such/dir/ck"
echo "grid_checkpoint: bad input refused"

[[ -n $mpirun ]] || exit 0
# Under AddressSanitizer, memory errors but not leaks: Open MPI's components leak at start-up
# and are unloaded before LeakSanitizer reports (tests/mpi/CMakeLists.txt says more).
[[ -z ${ASAN_OPTIONS:-} ]] || export ASAN_OPTIONS=$ASAN_OPTIONS:detect_leaks=0
# Two ranks (Dijkstra at extent 60, with its path, 166 buckets): SIGUSR1 to mpirun, which
# passes it on to both ranks, once both have checkpointed their first bucket (as above: every
# bucket writes one, so the run is well inside).
timeout 300 "$mpirun" -np 2 "$bin" grid --dims 4 --extent 60 --engine dense --threads 1 --algo dijkstra --path \
  --json > "$dir/mref.json" || fail "two-rank reference run failed"
ck=$dir/dij.ckpt
"$mpirun" -np 2 "$bin" grid --dims 4 --extent 60 --engine dense --threads 1 --algo dijkstra --path \
  --json --checkpoint "$ck" "${every[@]}" > "$dir/mint.json" &
pid=$!
wait_for "$ck.r1" "$pid" || fail "no two-rank checkpoint appeared"
kill -USR1 "$pid"
wait "$pid" || fail "the interrupted two-rank run exited $?"
interrupted "$dir/mint.json" SIGUSR1 "$ck"
timeout 300 "$mpirun" -np 2 "$bin" grid --dims 4 --extent 60 --engine dense --threads 1 --algo dijkstra --path \
  --json --restart "$ck" > "$dir/mres.json" || fail "the two-rank restart failed"
same "$dir/mref.json" "$dir/mres.json"
python3 -c "import json,sys; a,b=(json.load(open(f)) for f in sys.argv[1:]); assert a['path']==b['path']" \
  "$dir/mref.json" "$dir/mres.json" || fail "the restarted path differs"
err=$(timeout 300 "$mpirun" -np 3 "$bin" grid --dims 4 --extent 60 --engine dense --threads 1 --algo dijkstra --path \
  --restart "$ck" 2>&1 > /dev/null)
rc=$?
[[ $rc -eq 2 && $err == *"rank 0: --restart '$ck.r0': was written for another run (ranks = 2; this run has ranks = 3)"* ]] ||
  fail "three ranks on a two-rank checkpoint: exit $rc, $err"
echo "grid_checkpoint: two ranks ok"
