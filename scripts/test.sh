#!/usr/bin/env bash
# The whole test suite: install, build, run every test, then the unit, CLI and OMPL suites
# again under AddressSanitizer + UndefinedBehaviorSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
jobs=$(nproc)

echo "== build (Release)"
bash scripts/build.sh build
echo "== tests (Release)"
(cd build && ctest --output-on-failure -j "$jobs" --timeout 600)

echo "== build (ASan + UBSan)"
bash scripts/build.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DHPCPLAN_SANITIZE=address,undefined -DHPCPLAN_BUILD_BENCH=OFF
echo "== tests (ASan + UBSan)"
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
(cd build-asan && ctest --output-on-failure -j "$jobs" --timeout 900 -L "unit|cli|ompl")
