#!/usr/bin/env bash
# Builds the two clang trees of the test command: the parsers' libFuzzer targets (build-fuzz)
# and the threaded tests under ThreadSanitizer (build-tsan). scripts/test.sh runs it in the
# background while the ASan tests run; it also serves alone.
# Usage: scripts/build_fuzz_tsan.sh [SANITIZER_FLAGS]  (a -DCMAKE_CXX_FLAGS_RELWITHDEBINFO=...)
set -euo pipefail
cd "$(dirname "$0")/.."
sanitizer_flags=${1:--DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG}

echo "== build (libFuzzer: the parsers' fuzz targets)"
# Clang's libFuzzer in a tree of its own, holding only the fuzz targets: each compiles its
# parsers' sources itself (tests/fuzz/CMakeLists.txt). Their replays over the committed corpus
# run in the Release and ASan stages (label unit); the test command then fuzzes each target
# for a few seconds from it.
bash scripts/fuzz.sh --build

echo "== build (ThreadSanitizer: threaded tests)"
# Built with clang and LLVM's OpenMP runtime: GCC's libgomp is not instrumented, so TSan cannot
# see its barriers and reported the dense engine's hand-offs between barriers as races (CI, stop
# 36). LLVM's runtime with its Archer tool (OMP_TOOL_LIBRARIES in scripts/test.sh) tells TSan
# about every barrier, task and lock, so the OpenMP loops are checked too, not just the
# std::threads. The compilers as cache options, not CC/CXX, which a tree configured earlier with
# g++ ignores. The dense engine is compiled for the 2D to 4D lattices its threaded tests run
# (HPCPLAN_DENSE_DIMS=4; a test on a higher dimension would be refused, and fail): all 16 took
# clang 157 s of one core under TSan, the longest step of this build.
bash scripts/build.sh build-tsan -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "$sanitizer_flags" -DHPCPLAN_SANITIZE=thread \
  -DHPCPLAN_BUILD_BENCH=OFF -DHPCPLAN_BUILD_CLI=OFF -DHPCPLAN_BUILD_PYTHON=OFF \
  -DHPCPLAN_DENSE_DIMS=4 \
  --target hpcplan_thread_tests --target hpcplan_sim_tests --target hpcplan_dense_thread_tests \
  --target hpcplan_sph_tests --target hpcplan_python_relay_tests
