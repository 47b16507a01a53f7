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
config=(-DCMAKE_BUILD_TYPE=Release -DHPCPLAN_BUILD_TESTS=ON -DHPCPLAN_BUILD_BENCH=ON -DHPCPLAN_BUILD_MICROBENCH=ON
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
# The configure step's output is kept in the tree (cmake-configure.log) and shown only in part:
# the project's own status lines (hpcplan: ..., e.g. whether the fluid's CUDA backend is built)
# and CMake's warnings, so the build log says what was built; all of it when configuring fails.
mkdir -p "$dir"
if ! cmake -S . -B "$dir" "${generator[@]}" "${config[@]}" > "$dir/cmake-configure.log" 2>&1; then
  cat "$dir/cmake-configure.log" >&2
  echo "build.sh: configuring $dir failed (above; also in $dir/cmake-configure.log)" >&2
  exit 1
fi
awk -v dir="$dir" '/^CMake (Deprecation )?Warning/ { warning = 1 }
  warning && /^$/ { warning = 0 }
  warning || /^-- hpcplan:/ { print "build.sh: " dir ": " $0 }' "$dir/cmake-configure.log"
cmake --build "$dir" --parallel "$(nproc)" "${targets[@]}"
