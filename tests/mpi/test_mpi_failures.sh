#!/usr/bin/env bash
# The CLI under mpirun when things go wrong: bad input, a time limit, a killed rank, a rank that
# throws. Every case must end (bounded by `timeout`) with the right exit code; none may hang.
set -uo pipefail
bin=$1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fail() { echo "FAIL: $*" >&2; exit 1; }
# Every mpirun here runs under `timeout` (a hang guard): exit 124 means it did not end in time.
hung() { (($1 != 124)) || echo " (124: mpirun did not end within its timeout: a hang)"; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# 1. Bad input: every rank refuses it, exit 2 (bad input, as without mpirun), one line on
#    stderr from rank 0 naming the problem.
bad_mpi() {  # what-the-line-says args...
  local expect=$1; shift
  timeout 60 mpirun -np 2 --oversubscribe "$bin" "$@" >"$tmp/out" 2>"$tmp/err"
  local rc=$?
  ((rc == 2)) || fail "'$*' under mpirun: exit $rc, not 2$(hung $rc) ($(cat "$tmp/err"))"
  [[ $(grep -c "hpcplan: error" "$tmp/err") == 1 ]] ||
    fail "'$*' under mpirun: expected one error line, got: $(cat "$tmp/err")"
  grep -q -- "$expect" "$tmp/err" || fail "'$*' under mpirun: '$expect' not in: $(cat "$tmp/err")"
  [[ ! -s $tmp/out ]] || fail "'$*' under mpirun wrote output"
}
bad_mpi "unknown --mode 'sometimes'" grid --dims 2 --mode sometimes
bad_mpi "--start" grid --dims 3 --start 0,0
bad_mpi "--dims" grid --dims 0
# The subcommands that run in one process refuse a distributed launch, each in one line.
bad_mpi "runs in one process" sph --particles 500 --frames 1
bad_mpi "runs in one process" sim --particles 500 --max-sim-s 1
bad_mpi "runs in one process" ompl --dims 2 --runs 1
bad_mpi "runs in one process" map3d --map "$(dirname "$0")/../../bench/maps/single_box.txt"
bad_mpi "runs in one process" sphere2d --map "$(dirname "$0")/../../bench/maps/sphere_world.txt"
echo "ok: bad input and single-process subcommands exit 2 with one line"

# 2. Output comes from rank 0 only, and the JSON is complete.
timeout 120 mpirun -np 2 --oversubscribe "$bin" grid --dims 4 --json >"$tmp/out" ||
  fail "2-rank run failed: exit $?$(hung $?)"
[[ $(wc -l <"$tmp/out") == 1 ]] || fail "expected one JSON line, got $(wc -l <"$tmp/out")"
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert len(j['distributed']['per_rank'])==2" "$tmp/out" ||
  fail "JSON lacks per-rank figures"
echo "ok: one JSON object with per-rank figures"
# Prefix-cut ownership is reported as given, and the run solves.
timeout 120 mpirun -np 2 --oversubscribe "$bin" grid --dims 4 --owner-cuts 40 --json >"$tmp/out" ||
  fail "2-rank run with --owner-cuts failed: exit $?$(hung $?)"
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['status']=='solved'; \
assert j['distributed']['ownership']=={'prefix_cuts': {'axes': [3, 2], 'at': [40]}}, j['distributed']['ownership']" \
  "$tmp/out" || fail "--owner-cuts: JSON ownership is not the cuts given"
echo "ok: prefix cuts reported in the JSON"

# 3. A time limit no machine can meet (1 ns) ends the search with status timeout on all ranks.
timeout 60 mpirun -np 2 --oversubscribe "$bin" grid --dims 6 --extent 40 --algo dijkstra \
  --time-limit 1e-9 --json >"$tmp/out"
rc=$?
((rc == 0)) || fail "time-limited run: exit $rc$(hung $rc)"
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['status']=='timeout', j['status']" \
  "$tmp/out" || fail "time-limited run: status is not timeout"
echo "ok: time limit honoured"

# 4. A rank killed mid-search (HPCPLAN_FAULT_KILL=RANK:EXPANSIONS: it raises SIGKILL once it
#    has expanded that many states, no polling for its process and no sleeps) ends the whole
#    job with a non-zero exit; `timeout` only guards against a hang (exit 124).
HPCPLAN_FAULT_KILL=1:2000 timeout 120 mpirun -np 2 --oversubscribe -x HPCPLAN_FAULT_KILL "$bin" \
  grid --dims 6 --extent 40 --algo dijkstra --engine sparse --time-limit 100 --json >"$tmp/out" 2>"$tmp/err"
rc=$?
((rc != 0 && rc != 124)) || fail "killed rank: job exit $rc$(hung $rc)"
[[ ! -s $tmp/out ]] || fail "killed rank: a result was printed"
echo "ok: killing a rank ended the job with exit $rc"

# 4b. A rank that throws mid-search (fault injection: HPCPLAN_FAULT_THROW=RANK:EXPANSIONS) ends
#     the whole job with exit 1 (a run failure), its message on stderr, while the other rank
#     waits for it in the exchange; under each schedule. (Once, the unwinding freed the pending
#     termination wave's request, which MPI forbids: Open MPI aborted with its own error, exit
#     7, before the rank could say why.)
for fault in "1:dijkstra:async" "0:dijkstra:bulk_sync" "1:bfs:async"; do
  IFS=: read -r rank algo mode <<<"$fault"
  HPCPLAN_FAULT_THROW=$rank:2000 timeout 120 mpirun -np 2 --oversubscribe -x HPCPLAN_FAULT_THROW \
    "$bin" grid --dims 6 --extent 40 --algo "$algo" --mode "$mode" --engine sparse --time-limit 100 \
    --json >"$tmp/out" 2>"$tmp/err"
  rc=$?
  ((rc == 1)) || fail "throwing rank ($fault): job exit $rc, not 1$(hung $rc) ($(cat "$tmp/err"))"
  grep -q "hpcplan: error: rank $rank: injected fault after 2000 expansions" "$tmp/err" ||
    fail "throwing rank ($fault): its message is not on stderr: $(cat "$tmp/err")"
  [[ ! -s $tmp/out ]] || fail "throwing rank ($fault): a result was printed"
done
HPCPLAN_FAULT_THROW=oops timeout 60 mpirun -np 2 --oversubscribe -x HPCPLAN_FAULT_THROW "$bin" \
  grid --dims 2 >/dev/null 2>"$tmp/err"
rc=$?
((rc == 2)) || fail "a malformed HPCPLAN_FAULT_THROW is not bad input: exit $rc$(hung $rc)"
echo "ok: a rank throwing mid-search ended the job with exit 1 and its message"

# 5. Ranks that derive different limits agree on one engine and one layout (an MPMD launch
#    stands in for nodes with different memory or cores): a budget that fits the dense
#    engine on one rank only, and 1 against 8 threads, once hung or answered no_path.
timeout 120 mpirun --oversubscribe -np 1 "$bin" grid --dims 4 --extent 40 --algo bfs --memory-budget 400000 \
  --json : -np 1 "$bin" grid --dims 4 --extent 40 --algo bfs --memory-budget 600000 --json \
  >"$tmp/out" 2>"$tmp/err" || fail "ranks with different budgets: exit $?$(hung $?)"
python3 -c "import json,sys; assert json.load(open(sys.argv[1]))['status']=='solved'" "$tmp/out" ||
  fail "ranks with different budgets: not solved"
timeout 120 mpirun --oversubscribe -np 1 "$bin" grid --dims 3 --extent 200 --algo bfs --engine dense \
  --threads 1 --json : -np 1 "$bin" grid --dims 3 --extent 200 --algo bfs --engine dense \
  --threads 8 --json >"$tmp/out" 2>"$tmp/err" || fail "ranks with 1 and 8 threads: exit $?$(hung $?)"
python3 -c "import json,sys; j=json.loads(open(sys.argv[1]).read()); \
assert j['status'] == 'solved' and j['dense']['threads'] == 1, j" "$tmp/out" ||
  fail "ranks with 1 and 8 threads did not agree on one thread and solve"
echo "ok: ranks with different budgets and thread counts agreed"

# 6. --compare-serial where only the ranks' slabs fit the budget: no serial reference, and
#    the job ends (once rank 0 alone refused while the other waited).
timeout 120 mpirun -np 2 --oversubscribe "$bin" grid --dims 4 --extent 40 --algo bfs \
  --engine dense --threads 1 --memory-budget 700000 --compare-serial --json >"$tmp/out" \
  2>"$tmp/err" || fail "--compare-serial over the serial budget: exit $?$(hung $?)"
grep -q '"serial_reference"' "$tmp/out" && fail "--compare-serial over the budget still ran it"
echo "ok: --compare-serial without room for the serial dense engine ends cleanly"
