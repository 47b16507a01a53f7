#!/usr/bin/env bash
# hpcplan ompl end to end: the OMPL log must load in the real ompl_benchmark_statistics and its
# SQLite database must hold every requested planner and run; the CSV must hold one valid row per
# run; bad options must give one line on stderr, exit 2 and write nothing.
set -uo pipefail
bin=${1:?usage: test_ompl_cli.sh path/to/hpcplan}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# Two invocations, so that no outcome depends on the machine's speed: the planners that end at a
# path under a 30 s guard (they must solve), the anytime and batch ones for 0.3 s (recorded
# whatever they found).
"$bin" ompl --dims 2 --planners gridastar,rrtconnect --time 30 --runs 2 --seed 1 \
  --log "$dir/run.log" --csv "$dir/run.csv" > "$dir/out.txt" || fail "ompl run failed"
grep -q "gridastar" "$dir/out.txt" || fail "no summary table"
"$bin" ompl --dims 2 --planners bitstar,fmt --time 0.3 --runs 2 --seed 1 \
  --log "$dir/run2.log" --csv "$dir/run2.csv" > /dev/null || fail "ompl anytime run failed"
command -v ompl_benchmark_statistics >/dev/null || fail "ompl_benchmark_statistics missing (ompl-demos)"
ompl_benchmark_statistics "$dir/run.log" "$dir/run2.log" -d "$dir/run.db" > "$dir/stats.txt" 2>&1 ||
  { cat "$dir/stats.txt"; fail "ompl_benchmark_statistics rejected the log"; }
python3 - "$dir/run.db" "$dir/run.csv" "$dir/run2.csv" <<'PY' || exit 1
import csv, sqlite3, sys
db = sqlite3.connect(sys.argv[1])
planners = {name for (name,) in db.execute("SELECT name FROM plannerConfigs")}
want = {"geometric_GridAStar", "geometric_kBITstar", "geometric_FMT", "geometric_RRTConnect"}
missing = want - planners
if missing:
    sys.exit(f"FAIL: planners missing from the database: {missing} (have {planners})")
runs = db.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
if runs != 8:
    sys.exit(f"FAIL: {runs} runs in the database, expected 8")
cols = [r[1] for r in db.execute("PRAGMA table_info(runs)")]
for c in ("collision_checks", "path_valid", "time_first"):
    if c not in cols:
        sys.exit(f"FAIL: column {c} missing from the runs table: {cols}")
rows = list(csv.DictReader(open(sys.argv[2]))) + list(csv.DictReader(open(sys.argv[3])))
need = ["planner", "dims", "run", "seed", "solved", "time_first_s", "length_first",
        "quality_first", "time_best_s", "quality_best", "quality_final", "collision_checks",
        "smoothing_s"]
for c in need:
    if c not in rows[0]:
        sys.exit(f"FAIL: CSV column {c} missing")
if len(rows) != 8:
    sys.exit(f"FAIL: {len(rows)} CSV rows, expected 8")
for r in rows:
    if r["planner"] in ("gridastar", "rrtconnect") and r["solved"] != "1":
        sys.exit(f"FAIL: {r['planner']} (ends at a path) did not solve run {r['run']}")
    if r["path_valid"] != "1":
        sys.exit(f"FAIL: invalid path in {r['planner']} run {r['run']}")
    if r["planner"] == "gridastar" and r["solved"] != "1":
        sys.exit("FAIL: the grid planner must solve the default 2D problem")
    if r["planner"] == "gridastar" and not 0 < float(r["smoothing_s"]) < float(r["time_first_s"]):
        sys.exit(f"FAIL: the grid planner's smoothing time {r['smoothing_s']} is not within its answer time")
    if not r["planner"].startswith("gridastar") and r["smoothing_s"] != "":
        sys.exit(f"FAIL: {r['planner']} reports a smoothing time")
print("ompl_cli: database and CSV ok")
PY

# Warm-up solves are untimed and unrecorded: the CSV holds only the timed runs, numbered from 0.
"$bin" ompl --dims 2 --planners gridastar,rrtconnect --time 30 --runs 2 --warmup 1 --seed 1 \
  --csv "$dir/warm.csv" > /dev/null || fail "ompl run with --warmup failed"
python3 - "$dir/warm.csv" <<'PY' || exit 1
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
got = sorted((r["planner"], r["run"]) for r in rows)
want = [("gridastar", "0"), ("gridastar", "1"), ("rrtconnect", "0"), ("rrtconnect", "1")]
if got != want:
    sys.exit(f"FAIL: --warmup 1 gave rows {got}, expected {want}")
if any(r["solved"] != "1" or r["path_valid"] != "1" for r in rows):
    sys.exit("FAIL: a run after the warm-up did not solve with a valid path")
PY

# Bad input: exit 2, one line on stderr, no output files.
bad() {
  local what=$1; shift
  rm -f "$dir/bad.csv" "$dir/bad.log"
  "$bin" ompl "$@" --log "$dir/bad.log" --csv "$dir/bad.csv" > /dev/null 2> "$dir/err.txt"
  local rc=$?
  [[ $rc -eq 2 ]] || fail "$what: exit $rc, expected 2"
  [[ $(wc -l < "$dir/err.txt") -eq 1 ]] || fail "$what: stderr is not one line: $(cat "$dir/err.txt")"
  [[ ! -e $dir/bad.csv && ! -e $dir/bad.log ]] || fail "$what: wrote output on bad input"
}
bad "unknown planner" --dims 2 --planners gridastar,warpdrive
bad "zero time" --dims 2 --time 0
bad "zero runs" --dims 2 --runs 0
bad "too many warm-ups" --dims 2 --warmup 101
bad "one dimension" --dims 1
bad "eleven dimensions" --dims 11
bad "bad resolution" --dims 2 --resolution 2
bad "duplicate planner" --dims 2 --planners fmt,fmt
bad "missing dims" --planners fmt
# An output that cannot be written is refused before the (possibly long) run starts: with
# progress lines asked for, stderr holds the error alone, no run's line.
HPCPLAN_PROGRESS=1 "$bin" ompl --dims 2 --planners gridastar --time 30 --runs 100 \
  --csv /nonexistent-dir/x.csv > /dev/null 2> "$dir/err.txt"
rc=$?
[[ $rc -eq 2 ]] || fail "unwritable --csv: exit $rc, expected 2"
grep -q "does not exist" "$dir/err.txt" || fail "unwritable --csv: $(cat "$dir/err.txt")"
[[ $(wc -l < "$dir/err.txt") -eq 1 ]] || fail "unwritable --csv was only noticed after a run: $(cat "$dir/err.txt")"
echo "ompl_cli: ok"

# Progress: silent when stderr is not a terminal, one line per run when asked.
"$bin" ompl --dims 2 --planners gridastar --time 0.2 --runs 2 > /dev/null 2> "$dir/quiet.txt" ||
  fail "quiet run failed"
[[ ! -s $dir/quiet.txt ]] || fail "progress printed to a non-terminal: $(cat "$dir/quiet.txt")"
HPCPLAN_PROGRESS=1 "$bin" ompl --dims 2 --planners gridastar --time 0.2 --runs 2 > /dev/null \
  2> "$dir/progress.txt" || fail "progress run failed"
grep -q "2/2 gridastar run 1" "$dir/progress.txt" && grep -q "s left" "$dir/progress.txt" ||
  fail "no progress with HPCPLAN_PROGRESS=1: $(cat "$dir/progress.txt")"
echo "ompl_cli: progress ok"
