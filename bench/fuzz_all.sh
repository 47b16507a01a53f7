#!/usr/bin/env bash
# Every parser's fuzz target (tests/fuzz/) to RUNS executions, one target at a time, each from its
# committed corpus alone (a fresh working corpus, so that a measurement does not depend on earlier
# runs), under nice. Prints per target the executions, seconds, executions per second, the
# corpus libFuzzer grew and whether it crashed; exits 1 if any did (the input is then in
# build-fuzz/crashes/). docs/PERFORMANCE.md (issue 34) records a run.
# Usage: bench/fuzz_all.sh [RUNS=1000000] [TARGET...]   every target when none is named
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-1000000}
shift || true
bash scripts/fuzz.sh --build
mkdir -p build-fuzz/crashes build-fuzz/bench
echo "fuzz_all: $runs executions per target, $(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | xargs)), $(date -u +%Y-%m-%d)"
printf '%-24s %12s %9s %9s %8s %s\n' target executions seconds exec/s corpus crashed
# One OpenMP thread: the fluid checkpoint's target runs OpenMP loops over a few particles.
export OMP_NUM_THREADS=1
failed=0
while read -r target dirs; do
  if (($#)) && [[ " $* " != *" $target "* ]]; then continue; fi
  work=build-fuzz/bench/$target
  rm -rf "$work"
  mkdir -p "$work"
  start=$(date +%s.%N)
  status=0
  # shellcheck disable=SC2086  # dirs: the corpus directories, one word each
  nice -n 10 "build-fuzz/bin/$target" -runs="$runs" -timeout=10 -malloc_limit_mb=512 \
    -artifact_prefix="build-fuzz/crashes/$target-" -print_final_stats=1 "$work" $dirs \
    > "build-fuzz/bench/$target.log" 2>&1 || status=$?
  seconds=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { print b - a }')
  executed=$(sed -n 's/^stat::number_of_executed_units: *//p' "build-fuzz/bench/$target.log")
  crashed=no
  if ((status != 0)); then
    crashed="yes (exit $status; build-fuzz/bench/$target.log)"
    failed=1
  fi
  printf '%-24s %12s %9.1f %9.0f %8s %s\n' "$target" "${executed:-?}" "$seconds" \
    "$(awk -v n="${executed:-0}" -v s="$seconds" 'BEGIN { print n / s }')" \
    "$(find "$work" -type f | wc -l)" "$crashed"
done < build-fuzz/fuzz_targets.txt
exit $failed
