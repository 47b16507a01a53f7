#!/usr/bin/env bash
# hpcplan ompl --world chain end to end: the OMPL log must load in the real
# ompl_benchmark_statistics (experiment chain-4, its num_links parameter, every planner and run in
# the database); the CSV must hold one valid, solved row per run; bad c-space input must give one
# line on stderr, exit 2 and write nothing.
set -uo pipefail
bin=${1:?usage: test_cspace_ompl_cli.sh path/to/hpcplan}
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# Both planners end at a path: the lattice's in milliseconds, RRT-Connect's in well under the
# 5 s guard on the 4-link chain.
"$bin" ompl --world chain --dims 4 --planners gridastar,rrtconnect --runs 2 --time 5 --seed 1 \
  --log "$dir/chain.log" --csv "$dir/chain.csv" > "$dir/out.txt" || fail "ompl --world chain failed"
head -1 "$dir/out.txt" | grep -q "world chain" || fail "summary header does not name the world: $(head -1 "$dir/out.txt")"
grep -q "rrtconnect" "$dir/out.txt" || fail "no summary table"
command -v ompl_benchmark_statistics >/dev/null || fail "ompl_benchmark_statistics missing (ompl-demos)"
ompl_benchmark_statistics "$dir/chain.log" -d "$dir/chain.db" > "$dir/stats.txt" 2>&1 ||
  { cat "$dir/stats.txt"; fail "ompl_benchmark_statistics rejected the log"; }
/usr/bin/python3 - "$dir/chain.db" "$dir/chain.csv" <<'PY' || exit 1
import csv, sqlite3, sys
db = sqlite3.connect(sys.argv[1])
planners = {name for (name,) in db.execute("SELECT name FROM plannerConfigs")}
want = {"geometric_GridAStar", "geometric_RRTConnect"}
if want - planners:
    sys.exit(f"FAIL: planners missing from the database: {want - planners} (have {planners})")
runs = db.execute("SELECT COUNT(*) FROM runs").fetchone()[0]
if runs != 4:
    sys.exit(f"FAIL: {runs} runs in the database, expected 4")
exps = [r[0] for r in db.execute("SELECT name FROM experiments")]
if exps != ["chain-4"]:
    sys.exit(f"FAIL: experiments {exps}, expected ['chain-4']")
cols = [r[1] for r in db.execute("PRAGMA table_info(experiments)")]
if "num_links" not in cols:
    sys.exit(f"FAIL: no num_links experiment parameter: {cols}")
if db.execute("SELECT num_links FROM experiments").fetchone()[0] != 4:
    sys.exit("FAIL: num_links is not 4")
cols = [r[1] for r in db.execute("PRAGMA table_info(runs)")]
for c in ("collision_checks", "path_valid", "time_first"):
    if c not in cols:
        sys.exit(f"FAIL: column {c} missing from the runs table: {cols}")
rows = list(csv.DictReader(open(sys.argv[2])))
if len(rows) != 4:
    sys.exit(f"FAIL: {len(rows)} CSV rows, expected 4")
for r in rows:
    if r["solved"] != "1" or r["path_valid"] != "1":
        sys.exit(f"FAIL: {r['planner']} run {r['run']}: solved {r['solved']}, valid {r['path_valid']}")
    if r["dims"] != "4" or int(r["collision_checks"]) <= 0:
        sys.exit(f"FAIL: {r['planner']} run {r['run']}: dims {r['dims']}, checks {r['collision_checks']}")
    if float(r["quality_final"]) < 1.0 - 1e-9:
        sys.exit(f"FAIL: {r['planner']} quality {r['quality_final']} below the straight line")
print("cspace_ompl_cli: database and CSV ok")
PY

# Bad input: exit 2, one line on stderr, no output files.
bad() {
  local what=$1; shift
  rm -f "$dir/bad.csv" "$dir/bad.log"
  "$bin" ompl "$@" --log "$dir/bad.log" --csv "$dir/bad.csv" > /dev/null 2> "$dir/err.txt"
  local rc=$?
  [[ $rc -eq 2 ]] || fail "$what: exit $rc, expected 2 ($(cat "$dir/err.txt"))"
  [[ $(wc -l < "$dir/err.txt") -eq 1 ]] || fail "$what: stderr is not one line: $(cat "$dir/err.txt")"
  [[ ! -e $dir/bad.csv && ! -e $dir/bad.log ]] || fail "$what: wrote output on bad input"
}
bad "unknown world" --world torus --dims 4
bad "seventeen links" --world chain --dims 17
bad "one dimension" --world hypercube --dims 1
bad "eleven GOG dimensions" --world gog --dims 11
bad "--extent with the chain" --world chain --dims 4 --extent 50
bad "--density with the hypercube" --world hypercube --dims 4 --density 0.3
bad "--cells with GOG" --world gog --dims 2 --cells 8
bad "one cell" --world chain --dims 4 --cells 1
bad "c-space planner on GOG" --world gog --dims 2 --planners kpiece
bad "the 2-link chain's start is in collision" --world chain --dims 2
echo "cspace_ompl_cli: ok"
