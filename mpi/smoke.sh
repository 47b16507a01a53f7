#!/usr/bin/env bash
# 2-rank smoke test of the distributed grid search: solves a few problems serially and with
# `mpirun -np 2`, and exits non-zero unless both agree (equal cost; equal hops for BFS).
# Usage: bash mpi/smoke.sh [path/to/hpcplan]   (default: build/bin/hpcplan)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
bin=${1:-$root/build/bin/hpcplan}
[[ -x $bin ]] || { echo "smoke: $bin is not built (run: bash scripts/build.sh)" >&2; exit 2; }
command -v mpirun >/dev/null || { echo "smoke: mpirun not found (apt-get install openmpi-bin)" >&2; exit 2; }
# Open MPI refuses to run as root unless told that this is intended.
if [[ $(id -u) -eq 0 ]]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi

cases=(
  "--dims 2 --algo astar"
  "--dims 4 --algo astar --density 0.7"
  "--dims 3 --algo dijkstra --extent 40"
  "--dims 3 --algo bfs --extent 40"
  "--dims 6 --algo astar --mode bulk"
  "--dims 5 --algo dijkstra --extent 10 --owner-coarsen 1"
  "--dims 5 --algo astar --extent 10 --owner-slabs 3"
)
failures=0
for c in "${cases[@]}"; do
  # shellcheck disable=SC2086
  serial=$("$bin" grid $c --json)
  rc=0
  # shellcheck disable=SC2086
  distributed=$(timeout 120 mpirun -np 2 --oversubscribe "$bin" grid $c --json) || rc=$?
  if ((rc != 0)); then  # (set -e would end the script here without a word)
    ((rc != 124)) || echo "smoke: FAIL $c: mpirun did not end within 120 s (a hang?)" >&2
    ((rc == 124)) || echo "smoke: FAIL $c: mpirun exit $rc" >&2
    failures=$((failures + 1))
    continue
  fi
  if ! python3 - "$c" "$serial" "$distributed" <<'PY'; then failures=$((failures + 1)); fi
import json, sys
case, s, d = sys.argv[1], json.loads(sys.argv[2]), json.loads(sys.argv[3])
ok = d["ranks"] == 2 and s["status"] == d["status"] == "solved"
if s["algo"] == "bfs":
    ok = ok and s["hops"] == d["hops"]
else:
    ok = ok and abs(s["cost"] - d["cost"]) <= 1e-9 * (1 + s["cost"])
if "--owner-slabs" in case:  # the report names the ownership that ran
    width = int(case.split("--owner-slabs")[1].split()[0])
    ok = ok and d["distributed"]["ownership"] == {"slabs": {"axis": d["dims"] - 1, "width": width}}
print(f"smoke: {'ok  ' if ok else 'FAIL'} {case:50s} serial cost {s['cost']:.4f} hops {s['hops']}"
      f" | 2 ranks ({d['scheme']}) cost {d['cost']:.4f} hops {d['hops']},"
      f" deviation {d['distributed']['workload_deviation_percent']:.2f}%")
sys.exit(0 if ok else 1)
PY
done
if ((failures > 0)); then
  echo "smoke: $failures case(s) failed or disagree" >&2
  exit 1
fi
echo "smoke: all ${#cases[@]} cases agree"
