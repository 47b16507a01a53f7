#!/usr/bin/env bash
# Builds the parsers' fuzz targets with clang (libFuzzer + ASan + UBSan; tests/fuzz/CMakeLists.txt
# lists them and says what each must hold) in build-fuzz, and runs each for SECONDS, starting
# from its committed corpus (tests/fuzz/corpus/<target>/); what libFuzzer adds is kept in
# build-fuzz/corpus/<target>/, so that later runs continue from it. A crash stops the script
# with its input in build-fuzz/crashes/<target>-crash-<hash> (replay it: build-fuzz/bin/<target>
# FILE).
# Usage: scripts/fuzz.sh [SECONDS=60] [TARGET...]   every target when none is named
#        scripts/fuzz.sh --build                    only configure and build (the test command's
#                                                   stage; its smoke tests are ctest -L fuzz)
# bench/fuzz_all.sh runs every target to a million executions instead.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang++ >/dev/null || { echo "fuzz: clang++ is needed (apt-get install clang)" >&2; exit 2; }
# Only the fuzz targets are built: each compiles the parsers' sources itself (no layer library),
# at -O1 with line tables like the sanitizer builds of scripts/test.sh.
bash scripts/build.sh build-fuzz -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
  -DHPCPLAN_BUILD_BENCH=OFF -DHPCPLAN_BUILD_CLI=OFF -DHPCPLAN_BUILD_PYTHON=OFF --target hpcplan_fuzz
[[ ${1:-} == --build ]] && exit 0
seconds=${1:-60}
shift || true
# One OpenMP thread: the fluid checkpoint's target runs OpenMP loops over a few particles.
export OMP_NUM_THREADS=1
while read -r target dirs; do
  if (($#)) && [[ " $* " != *" $target "* ]]; then continue; fi
  mkdir -p "build-fuzz/corpus/$target" build-fuzz/crashes
  echo "== $target ($seconds s)"
  # shellcheck disable=SC2086  # dirs: the corpus directories, one word each
  "build-fuzz/bin/$target" -max_total_time="$seconds" -timeout=10 -malloc_limit_mb=512 \
    -artifact_prefix="build-fuzz/crashes/$target-" -print_final_stats=1 \
    "build-fuzz/corpus/$target" $dirs
done < build-fuzz/fuzz_targets.txt
