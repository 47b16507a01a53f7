#!/usr/bin/env bash
# The largest lattice the dense engine solves per memory budget: for each budget and
# dimension, the largest extent whose planned bytes (the engine's own check, made before
# anything is allocated) fit, found by bisection on the refusal message; then, where
# SOLVE=1 and the run is expected to be short enough, that BFS solved for real with its time,
# peak memory (GNU time's maximum resident set) and answer.
# Usage: bench/largest_per_budget.sh [BIN=build/bin/hpcplan]
#   BUDGETS="64 512 4096" (MiB), DIMS="3 4 5 6", ALGO=bfs, THREADS=2, SOLVE=1,
#   SOLVE_MAX_STATES=3e9 (solve only lattices up to this many states)
set -euo pipefail
bin=${1:-build/bin/hpcplan}
budgets=(${BUDGETS:-64 512 4096})
dims=(${DIMS:-3 4 5 6})
algo=${ALGO:-bfs}
threads=${THREADS:-2}
solve=${SOLVE:-1}
solve_max=${SOLVE_MAX_STATES:-3e9}
needed() {  # needed D EXTENT: the planned bytes per rank (a 1-byte budget makes the engine say)
  local err
  err=$("$bin" grid --dims "$1" --extent "$2" --algo "$algo" --engine dense \
    --threads "$threads" --memory-budget 1 2>&1 > /dev/null || true)
  [[ $err =~ \(([0-9]+)\ bytes\)\ for\ this\ lattice ]] || {
    echo "largest_per_budget: unexpected answer: $err" >&2
    exit 1
  }
  echo "${BASH_REMATCH[1]}"
}
printf '| budget | d | largest extent accepted | states | planned bytes | largest solved: status, time, peak RSS, states reached |\n'
printf '|---|---|---|---|---|---|\n'
for mib in "${budgets[@]}"; do
  budget=$((mib * 1024 * 1024))
  for d in "${dims[@]}"; do
    lo=2 hi=65535
    ((d >= 3)) && hi=5000
    ((d >= 5)) && hi=500
    ((d >= 7)) && hi=100
    if (($(needed "$d" "$lo") > budget)); then
      printf '| %d MiB | %d | none | | | |\n' "$mib" "$d"
      continue
    fi
    while ((lo < hi)); do  # the largest extent that fits: in [lo, hi]
      mid=$(((lo + hi + 1) / 2))
      if (($(needed "$d" "$mid") <= budget)); then lo=$mid; else hi=$((mid - 1)); fi
    done
    accepted=$lo
    # The frontier lists grow beyond the first reserve the check counts, so the largest
    # accepted lattice may end in budget_exceeded: step down 4% at a time until one solves.
    result="" extent=$lo
    if [[ $solve == 1 ]]; then
      for _ in 1 2 3 4 5 6 7 8; do
        python3 -c "import sys; sys.exit(0 if $extent ** $d <= $solve_max else 1)" || break
        out=$(mktemp)
        /usr/bin/time -f '%e %M' -o "$out.time" "$bin" grid --dims "$d" --extent "$extent" \
          --algo "$algo" --engine dense --threads "$threads" --memory-budget "$budget" --json \
          > "$out"
        read -r secs kb < "$out.time"
        result=$(python3 -c "
import json
j = json.load(open('$out'))
print(f\"extent {$extent}: {j['status']}, {$secs:.1f} s, {$kb / 1024:.0f} MiB, {j['expanded']:,} states\")")
        status=$(python3 -c "import json; print(json.load(open('$out'))['status'])")
        rm -f "$out" "$out.time"
        [[ $status == budget_exceeded ]] || break
        extent=$((extent * 96 / 100))
      done
    fi
    states=$(python3 -c "print(f'{$accepted ** $d:.3g}')")
    bytes=$(needed "$d" "$accepted")
    lo=$accepted
    printf '| %d MiB | %d | %d | %s | %s | %s |\n' "$mib" "$d" "$lo" "$states" "$bytes" "$result"
  done
done
