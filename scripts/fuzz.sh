#!/usr/bin/env bash
# Builds the map-parser fuzz target with clang (libFuzzer + ASan + UBSan) and runs it.
# Usage: scripts/fuzz.sh [SECONDS=60]. The corpus starts from bench/maps and grows in build-fuzz/corpus.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
command -v clang++ >/dev/null || { echo "fuzz: clang++ is needed (apt-get install clang)" >&2; exit 2; }
cmake -S . -B build-fuzz -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DHPCPLAN_BUILD_BENCH=OFF -DHPCPLAN_BUILD_CLI=OFF >/dev/null
cmake --build build-fuzz --target fuzz_map_parsers
mkdir -p build-fuzz/corpus
cp -n bench/maps/*.txt build-fuzz/corpus/ 2>/dev/null || true
./build-fuzz/bin/fuzz_map_parsers -max_total_time="$seconds" -max_len=4096 build-fuzz/corpus
