#!/usr/bin/env bash
# The whole test suite: install, build, run every test; then the unit, CLI, OMPL, MPI, fluid and
# simulator suites again under AddressSanitizer + UndefinedBehaviorSanitizer (the fuzz targets'
# corpus replays among them), and the threaded tests (stop token, cancellation,
# planners sharing a world, the simulator's planner thread, the dense engine's and the fluid's
# OpenMP loops) under ThreadSanitizer.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
bash scripts/setup.sh
jobs=$(nproc)
# Each stage's start is printed with the command's elapsed time, and at the end every stage's
# length, so a CI log tells where a cold run's minutes went.
stage_names=() stage_starts=()
stage() {
  printf '== [%d:%02d] %s\n' $((SECONDS / 60)) $((SECONDS % 60)) "$*"
  stage_names+=("$*") stage_starts+=("$SECONDS")
}
# Printed on every exit, a failed stage's too (its time runs to the failure).
stage_summary() {
  local i t n=${#stage_names[@]}
  stage_starts+=("$SECONDS")
  echo "== stage times (m:ss)"
  for ((i = 0; i < n; ++i)); do
    t=$((stage_starts[i + 1] - stage_starts[i]))
    printf '  %3d:%02d  %s\n' $((t / 60)) $((t % 60)) "${stage_names[i]}"
  done
  printf '  %3d:%02d  total\n' $((SECONDS / 60)) $((SECONDS % 60))
}
trap stage_summary EXIT
# After a build: its ten slowest steps (ninja's log); after a test stage: its ten slowest tests.
slowest() { python3 "$root/scripts/build_report.py" "$@" --top 10; }
# Every ctest call fails when it selects no test (a stale cache or a wrong label would
# otherwise pass silently). ctest never shows a skipped test's output: each run's skips and
# their reasons are printed from its JUnit report (scripts/ctest_skips.py), pass or fail.
# A tree's first run starts the longest tests first, from the costs an earlier cold run
# measured in a tree of that name (tests/ctest_costs/<tree>.txt: ctest's own cost file, which
# it updates after every run), so that no long test starts last and leaves a core idle at the
# end of a stage.
ctest_run() {
  local rc=0 costs=$root/tests/ctest_costs/${PWD##*/}.txt
  mkdir -p Testing/Temporary
  if [[ ! -f Testing/Temporary/CTestCostData.txt && -f $costs ]]; then
    cp "$costs" Testing/Temporary/CTestCostData.txt
  fi
  # (A passing test's output is kept whole, not cut at ctest's default 1,024 bytes: the skip
  # lines of a binary that runs many cases come at its end.)
  ctest --no-tests=error --output-on-failure --output-junit "$PWD/ctest-junit.xml" \
    --test-output-size-passed 4194304 -j "$jobs" "$@" || rc=$?
  python3 "$root/scripts/ctest_skips.py" "$PWD/ctest-junit.xml" || rc=1
  slowest tests "$PWD"
  return $rc
}
# ctest runs two tests at once and each fluid test runs one OpenMP thread per core; with
# libgomp's default (spin at every barrier) the two programs' threads spun through each other's
# time slices: the hydrostatic tank and the dam-break crossing took 111 s and 121 s side by
# side against 13 s each alone, and 25 s side by side with passive waiting.
export OMP_WAIT_POLICY=passive

# The ThreadSanitizer stage's OpenMP tool, checked before half an hour of other stages: clang's
# resource directory is <llvm>/lib/clang/<version>, and Archer sits in <llvm>/lib.
archer=$(dirname "$(dirname "$(clang++ -print-resource-dir)")")/libarcher.so
if [[ ! -f $archer ]]; then
  echo "test: clang's libarcher.so (Debian's libomp-dev) is missing; run scripts/setup.sh" >&2
  exit 1
fi

stage "build (Release)"
# Where a CUDA compiler is installed (the CI image has one), the CUDA backend must build: its
# kernels include the CPU's physics source, so this is the check that the GPU side still
# compiles after a CPU change. Without one, the build is the CPU one.
cuda_required=()
if command -v nvcc >/dev/null; then
  cuda_required=(-DHPCPLAN_REQUIRE_CUDA=ON)
elif [[ -x /usr/local/cuda/bin/nvcc ]]; then  # installed off the PATH: name it
  cuda_required=(-DHPCPLAN_REQUIRE_CUDA=ON -DCMAKE_CUDA_COMPILER=/usr/local/cuda/bin/nvcc)
fi
# The Google Benchmark programs are left out: no test runs them (HPCPLAN_BUILD_MICROBENCH).
bash scripts/build.sh build "${cuda_required[@]}" -DHPCPLAN_BUILD_MICROBENCH=OFF
slowest steps build

# The sanitizer builds compile at -O1 with line tables only (-g1: enough for the sanitizers'
# stack traces). At -O2 -g the ASan build cost twice the compile time (2,067 s of CPU against
# 1,091 s, one translation unit 345 s against 125 s), while its tests ran no faster (343 s
# against 327 s).
sanitizer_flags="-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG"

stage "tests (Release)"
(cd build && ctest_run --timeout 600)

stage "build (ASan + UBSan)"
# The Python module is left out here: its seven binding files cost about 140 s of CPU under
# ASan and its tests 63 s, over the 30-minute mark of a cold run once the configuration-space
# work landed. The bindings parse the CLI's own options and call the same cli-layer functions
# the executable does (both run under ASan here through the CLI suites), and the Python tests
# run in the Release stage.
bash scripts/build.sh build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo "$sanitizer_flags" \
  -DHPCPLAN_SANITIZE=address,undefined -DHPCPLAN_BUILD_BENCH=OFF -DHPCPLAN_BUILD_PYTHON=OFF
slowest steps build-asan
stage "tests (ASan + UBSan)"
# (The MPI suites run without leak checks: tests/mpi/CMakeLists.txt says why.)
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Cli.EveryNumericOptionRefusesBadValues is a table of 500 CLI launches that tests option
# parsing (the same code in every build); it ran in the Release stage above, and under ASan
# its launches alone cost four minutes of CI. The fluid's experiment validations and the
# simulator's dam-break crossing (over three minutes under ASan) run long stretches of the
# same step that Presets.* and the short Simulator.* tests already drive under ASan; so does
# the fluid's thread-count determinism check (three 260-frame runs: 162 s under ASan on the
# 2-core VM, the longest test of the stage, against 68 s for the invariants test that drives
# every scenario's step). The MPI suite runs on 1, 2, 3 and 4 ranks here; on 8 (oversubscribed
# four times over on the CI's 2 cores) it took 150 s under ASan, the stage's longest test, and
# it runs on 8 in the Release stage. Under ASan it runs on 2 ranks (35 s; 1, 3 and 4 ranks added
# 161 s more of the same code paths, and run in the Release stage). The 9D-16D dense
# engine check (32 s) and the Verlet skin check (28 s) run the same kernels as the shorter dense
# and neighbour-list tests of this stage, over more states. The MPI maps test (mpi_maps: 25 mpirun launches of the CLI
# on MovingAI maps and an array) runs in the Release stage only: the occupancy code it drives
# (expansions, dense windows, scenario rows) runs under ASan in the unit tests, and the
# distributed engines in the MPI suite. The MPI failure tests (killed and hung ranks under
# mpirun: 35 s under ASan) exercise the CLI's error paths, which the CLI suites here also reach.
(cd build-asan && ctest_run --timeout 900 -L "unit|cli|ompl|mpi|sph|sim" \
  -E '^(Cli\.EveryNumericOptionRefusesBadValues|WaterValidation\..*|Simulator\.DamBreakCrossing|Invariants\.ThreadCountDoesNotChangeTheResult|mpi_distributed_np[1348]|mpi_maps|mpi_cli_failures|DenseHighDims\..*|VerletLists\.ASkinChangesNothingButRoundOff)$')

# (The libFuzzer stage, a clang tree of the fuzz targets fuzzing each for a few seconds, ran here
# until issue 48: 1:32 of a cold run that had reached 30:05 on the 2-core VM. Every target's
# replay over its committed corpus still runs in both stages above (label unit, under ASan in
# the second); `bash scripts/fuzz.sh [SECONDS]` builds that tree and fuzzes.)

stage "build (ThreadSanitizer: threaded tests)"
# Built with clang and LLVM's OpenMP runtime: GCC's libgomp is not instrumented, so TSan cannot
# see its barriers and reported the dense engine's hand-offs between barriers as races (CI, stop
# 36). LLVM's runtime with its Archer tool (OMP_TOOL_LIBRARIES below) tells TSan about every
# barrier, task and lock, so the OpenMP loops are checked too, not just the std::threads.
# The compilers as cache options, not CC/CXX, which a tree configured earlier with g++ ignores.
# The dense engine is compiled for the 2D to 4D lattices the threaded tests run
# (HPCPLAN_DENSE_DIMS=4; a test on a higher dimension would be refused, and fail): all 16 took
# clang 157 s of one core under TSan, the longest step of this build.
bash scripts/build.sh build-tsan -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo "$sanitizer_flags" -DHPCPLAN_SANITIZE=thread \
  -DHPCPLAN_BUILD_BENCH=OFF -DHPCPLAN_BUILD_CLI=OFF -DHPCPLAN_BUILD_PYTHON=OFF \
  -DHPCPLAN_DENSE_DIMS=4 \
  --target hpcplan_thread_tests --target hpcplan_sim_tests --target hpcplan_dense_thread_tests \
  --target hpcplan_sph_tests --target hpcplan_python_relay_tests
slowest steps build-tsan
stage "tests (ThreadSanitizer)"
# ignore_noninstrumented_modules: accesses inside the uninstrumented runtime itself are Archer's
# to describe, not TSan's to report.
export TSAN_OPTIONS=halt_on_error=1:second_deadlock_stack=1:ignore_noninstrumented_modules=1
export OMP_TOOL_LIBRARIES=$archer ARCHER_OPTIONS=verbose=1
(cd build-tsan && ctest_run --timeout 900 -L '^threads')
echo "== [$((SECONDS / 60)):$(printf %02d $((SECONDS % 60)))] done: every stage passed"
