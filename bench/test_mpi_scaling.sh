#!/usr/bin/env bash
# The strong-scaling driver as bench/strong_scaling.sh uses it, on a problem of a second:
# a 2-rank sweep with slabs, balanced cuts and the ceiling; the best scheme picked from its CSV
# and rerun alone ("confirm"); the summary tables; and bad options refused with exit 2.
# Usage: test_mpi_scaling.sh HPCPLAN_MPI_SCALING SOURCE_DIR
set -uo pipefail
bin=$1 src=$2
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fail() { echo "FAIL: $*" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
csv=$tmp/s.csv
run() { timeout 300 mpirun -np 2 --oversubscribe "$bin" --dims 4 --extent 12 --algo dijkstra "$@" \
  --csv "$csv" 2>"$tmp/err" || fail "mpi_scaling $*: exit $? ($(tail -1 "$tmp/err"))"; }

run --repeats 3 --modes async,bulk --slabs 0,6 --balanced-cuts --ceiling --label d4
python3 - "$csv" <<'EOF' || fail "sweep CSV"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
schemes = [(r["scheme"], r["slabs"], r["cuts"]) for r in rows]
# hash and slabs of 6 and the balanced cut, per mode, then the ceiling
assert len(rows) == 7, schemes
assert rows[-1]["scheme"] == "ceiling", schemes
assert sum(1 for r in rows if r["cuts"]) == 2, schemes
for r in rows[:-1]:
    assert r["status"] == "solved", r
    assert abs(float(r["cost"]) - float(rows[-1]["cost"])) < 1e-6, r  # the serial optimum
    q1, med, q3 = float(r["of_ceiling_q1"]), float(r["of_ceiling"]), float(r["of_ceiling_q3"])
    lo, hi = float(r["of_ceiling_min"]), float(r["of_ceiling_max"])
    assert 0 < lo <= q1 <= med <= q3 <= hi, r
    assert 0 < float(r["serial_min_ms"]) <= float(r["serial_median_ms"]) <= float(r["serial_max_ms"]), r
EOF
echo "ok: sweep rows with quartiles and the serial spread"

args=$(python3 "$src/scripts/scaling_table.py" --best-args "$csv" d4) || fail "--best-args"
[[ $args == "--modes "*" --batches 512 --"@(slabs|coarsen|cuts)" "* ]] || fail "--best-args gave '$args'"
# shellcheck disable=SC2086  # the options are words
run --repeats 3 $args --ceiling --label "confirm d4"
python3 - "$csv" <<'EOF' || fail "confirm rows"
import csv, sys
rows = [r for r in csv.DictReader(open(sys.argv[1])) if r["label"] == "confirm d4"]
assert [r["scheme"] for r in rows][-1] == "ceiling" and len(rows) == 2, rows
EOF
python3 "$src/scripts/scaling_table.py" "$csv" >"$tmp/table" || fail "scaling_table.py"
grep -q "^| d4 | 2 | .* | 3 | " "$tmp/table" || fail "no confirmation row: $(cat "$tmp/table")"
echo "ok: the best scheme ($args) rerun alone and tabulated"

# Cuts alone: no hash row. Bad cuts: exit 2 with the reason.
rm -f "$csv"
run --repeats 1 --modes bulk --cuts 70 --ceiling --label cuts
[[ $(grep -c ",bulk_sync," "$csv") == 1 ]] || fail "--cuts alone ran $(grep -c ",bulk_sync," "$csv") configurations"
timeout 60 mpirun -np 2 --oversubscribe "$bin" --dims 4 --extent 12 --cuts 70,80 >/dev/null 2>"$tmp/err"
rc=$?
((rc == 2)) || fail "two cuts for two ranks: exit $rc"
grep -q "P - 1 positions" "$tmp/err" || fail "bad cuts: $(cat "$tmp/err")"
echo "ok: cuts alone, and bad cuts refused"

# The dense engine's slabs: one configuration beside the ceiling, at the serial optimum; its
# best arguments rerun it.
rm -f "$csv"
run --repeats 2 --engine dense --threads 1 --ceiling --label dense4
python3 - "$csv" <<'EOF2' || fail "dense rows"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [r["scheme"] for r in rows] == ["dense_slabs", "ceiling"], rows
assert rows[0]["engine"] == "dense" and rows[0]["threads"] == "1", rows[0]
assert rows[0]["status"] == "solved", rows[0]
assert abs(float(rows[0]["cost"]) - float(rows[1]["cost"])) < 1e-9, rows
EOF2
args=$(python3 "$src/scripts/scaling_table.py" --best-args "$csv" dense4) || fail "dense --best-args"
[[ $args == "--engine dense --threads 1" ]] || fail "dense --best-args gave '$args'"
echo "ok: the dense engine's slabs timed and rerun from their best arguments"
