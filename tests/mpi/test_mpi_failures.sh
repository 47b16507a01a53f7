#!/usr/bin/env bash
# The CLI under mpirun when things go wrong: bad input, a time limit, a killed rank. Every
# case must end (bounded by `timeout`) with the right exit code; none may hang.
set -uo pipefail
bin=$1
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fail() { echo "FAIL: $*" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# 1. Bad input: every rank refuses it, one line on stderr from rank 0, non-zero exit.
timeout 60 mpirun -np 2 --oversubscribe "$bin" grid --dims 2 --mode sometimes >"$tmp/out" 2>"$tmp/err"
rc=$?
((rc != 0 && rc != 124)) || fail "bad --mode: exit $rc"
[[ $(grep -c "hpcplan: error" "$tmp/err") == 1 ]] || fail "bad --mode: expected one error line, got: $(cat "$tmp/err")"
grep -q "unknown --mode 'sometimes'" "$tmp/err" || fail "bad --mode: message does not name the problem"
timeout 60 mpirun -np 2 --oversubscribe "$bin" grid --dims 3 --start 0,0 >/dev/null 2>"$tmp/err"
rc=$?
((rc != 0 && rc != 124)) || fail "bad --start: exit $rc"
echo "ok: bad input exits $rc with one line"

# 2. Output comes from rank 0 only, and the JSON is complete.
timeout 120 mpirun -np 2 --oversubscribe "$bin" grid --dims 4 --json >"$tmp/out" || fail "2-rank run failed"
[[ $(wc -l <"$tmp/out") == 1 ]] || fail "expected one JSON line, got $(wc -l <"$tmp/out")"
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert len(j['distributed']['per_rank'])==2" "$tmp/out" ||
  fail "JSON lacks per-rank figures"
echo "ok: one JSON object with per-rank figures"
# Prefix-cut ownership is reported as given, and the run solves.
timeout 120 mpirun -np 2 --oversubscribe "$bin" grid --dims 4 --owner-cuts 40 --json >"$tmp/out" ||
  fail "2-rank run with --owner-cuts failed"
python3 -c "import json,sys; j=json.load(open(sys.argv[1])); assert j['status']=='solved'; \
assert j['distributed']['ownership']=={'prefix_cuts': {'axes': [3, 2], 'at': [40]}}, j['distributed']['ownership']" \
  "$tmp/out" || fail "--owner-cuts: JSON ownership is not the cuts given"
echo "ok: prefix cuts reported in the JSON"

# 3. A search far too big for its time limit ends with status timeout on all ranks.
start=$(date +%s)
timeout 60 mpirun -np 2 --oversubscribe "$bin" grid --dims 6 --extent 40 --algo dijkstra \
  --time-limit 1 --json >"$tmp/out"
rc=$?
((rc == 0)) || fail "time-limited run: exit $rc (124 = hang)"
grep -q '"status":"timeout"' "$tmp/out" || fail "time-limited run: status is not timeout"
echo "ok: time limit honoured in $(($(date +%s) - start)) s"

# 4. Killing one rank mid-search ends the whole job with a non-zero exit within seconds.
timeout 120 mpirun -np 2 --oversubscribe "$bin" grid --dims 6 --extent 40 --algo dijkstra \
  --time-limit 100 --json >"$tmp/out" 2>"$tmp/err" &
job=$!
victim=""
for _ in $(seq 1 100); do
  victim=$(pgrep -f "^$bin grid --dims 6 --extent 40" | tail -n 1 || true)
  [[ -n $victim && $(pgrep -f "^$bin grid --dims 6 --extent 40" | wc -l) -ge 2 ]] && break
  sleep 0.1
done
[[ -n $victim ]] || fail "could not find a rank to kill"
sleep 1
killed_at=$(date +%s)
kill -9 "$victim"
wait "$job"
rc=$?
took=$(($(date +%s) - killed_at))
((rc != 0 && rc != 124)) || fail "killed rank: job exit $rc"
((took <= 30)) || fail "killed rank: job took $took s to end"
echo "ok: killing a rank ended the job in $took s with exit $rc"

# 5. Ranks that derive different limits agree on one engine and one layout (an MPMD launch
#    stands in for nodes with different memory or cores): a budget that fits the dense
#    engine on one rank only, and 1 against 8 threads, once hung or answered no_path.
timeout 120 mpirun --oversubscribe -np 1 "$bin" grid --dims 4 --extent 40 --algo bfs --memory-budget 400000 \
  --json : -np 1 "$bin" grid --dims 4 --extent 40 --algo bfs --memory-budget 600000 --json \
  >"$tmp/out" 2>"$tmp/err" || fail "ranks with different budgets: exit $? (124 = hang)"
grep -q '"status":"solved"' "$tmp/out" || fail "ranks with different budgets: not solved"
timeout 120 mpirun --oversubscribe -np 1 "$bin" grid --dims 3 --extent 200 --algo bfs --engine dense \
  --threads 1 --json : -np 1 "$bin" grid --dims 3 --extent 200 --algo bfs --engine dense \
  --threads 8 --json >"$tmp/out" 2>"$tmp/err" || fail "ranks with 1 and 8 threads: exit $?"
python3 -c "import json,sys; j=json.loads(open(sys.argv[1]).read()); \
assert j['status'] == 'solved' and j['dense']['threads'] == 1, j" "$tmp/out" ||
  fail "ranks with 1 and 8 threads did not agree on one thread and solve"
echo "ok: ranks with different budgets and thread counts agreed"

# 6. --compare-serial where only the ranks' slabs fit the budget: no serial reference, and
#    the job ends (once rank 0 alone refused while the other waited).
timeout 120 mpirun -np 2 --oversubscribe "$bin" grid --dims 4 --extent 40 --algo bfs \
  --engine dense --threads 1 --memory-budget 700000 --compare-serial --json >"$tmp/out" \
  2>"$tmp/err" || fail "--compare-serial over the serial budget: exit $? (124 = hang)"
grep -q '"serial_reference"' "$tmp/out" && fail "--compare-serial over the budget still ran it"
echo "ok: --compare-serial without room for the serial dense engine ends cleanly"
