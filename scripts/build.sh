#!/usr/bin/env bash
# Configures and builds one build tree.
# Usage: scripts/build.sh [BUILD_DIR] [cmake -D options...] [--target T...]
# Every run states the full configuration (defaults first, then the caller's -D options), so a
# tree configured earlier with other options (no CLI, no benchmarks, a sanitizer) cannot leave
# its choices behind in the cache.
set -euo pipefail
cd "$(dirname "$0")/.."
dir=${1:-build}
shift || true
config=(-DCMAKE_BUILD_TYPE=Release -DHPCPLAN_BUILD_TESTS=ON -DHPCPLAN_BUILD_BENCH=ON
  -DHPCPLAN_BUILD_CLI=ON -DHPCPLAN_BUILD_PYTHON=ON -DHPCPLAN_SANITIZE= -DHPCPLAN_REQUIRE_CUDA=OFF -DHPCPLAN_DENSE_DIMS=16)
targets=()
while (($#)); do
  case $1 in
    --target) targets+=(--target "$2"); shift 2 ;;
    *) config+=("$1"); shift ;;
  esac
done
generator=()
if [[ ! -f "$dir/CMakeCache.txt" ]] && command -v ninja >/dev/null; then generator=(-G Ninja); fi
cmake -S . -B "$dir" "${generator[@]}" "${config[@]}" >/dev/null
cmake --build "$dir" --parallel "$(nproc)" "${targets[@]}"
