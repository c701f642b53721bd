#!/usr/bin/env bash
# Installs dependencies, builds, and runs every test: the catkin gtests (unit, CLI and, when
# STOCS_DATASETS names the real-data folder, the real-frame acceptance tests), then the same unit
# tests in an AddressSanitizer + UndefinedBehaviorSanitizer build of the ROS-free core, then a short
# run of every fuzz target (scripts/fuzz.sh).
# Exits non-zero when anything fails. STOCS_SKIP_SANITIZERS=1 skips the sanitizer build,
# STOCS_SKIP_FUZZ=1 the fuzzing; STOCS_FUZZ_SECONDS sets the time per fuzz target (default 15).
set -euo pipefail
source "$(dirname "$0")/common.sh"

# Each stage reports its wall time, so a slow CI run shows where the time went.
stage_start=$SECONDS
stage_done() {
  echo "run_tests: $1 took $((SECONDS - stage_start)) s"
  stage_start=$SECONDS
}

"$REPO/scripts/install_deps.sh"
stage_done "installing dependencies"
if [ -n "${STOCS_DATASETS:-}" ]; then
  echo "run_tests: real-data tests read $STOCS_DATASETS"
else
  echo "run_tests: STOCS_DATASETS is not set; real-data tests will be skipped"
fi

"$REPO/scripts/build.sh"
"$REPO/scripts/build.sh" tests
stage_done "the catkin build (package and tests)"
rm -rf "$WS/build/test_results"
# run_tests exits 0 even when tests fail; catkin_test_results gives the verdict.
catkin_make -C "$WS" -j"$JOBS" run_tests > "$WS/run_tests.log" 2>&1 || true
if ! catkin_test_results --verbose "$WS/build/test_results"; then
  echo "run_tests: catkin tests FAILED (log: $WS/run_tests.log)"
  exit 1
fi
stage_done "the catkin tests"

if [ "${STOCS_SKIP_SANITIZERS:-0}" != 1 ]; then
  SAN="$REPO/build/sanitize"
  # Without the Google Benchmark programs: no test runs them (their sanitized compilation took
  # 27 s of one core on a cold cache).
  cmake -S "$REPO" -B "$SAN" -DSTOCS_WITH_ROS=OFF -DSTOCS_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON \
    -DSTOCS_DATASETS_DIR="${STOCS_DATASETS:-}" > "$SAN.cmake.log" 2>&1 || { cat "$SAN.cmake.log"; exit 1; }
  cmake --build "$SAN" -j"$JOBS"
  stage_done "the sanitizer build"
  # halt_on_error: any sanitizer report fails the test that triggered it.
  ASAN_OPTIONS=detect_leaks=1:halt_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    ctest --test-dir "$SAN" -j"$JOBS" --output-on-failure
  stage_done "the sanitizer tests"
fi
if [ "${STOCS_SKIP_FUZZ:-0}" != 1 ]; then
  # 9 targets x 15 s plus the fuzz build (about 4.6 min of CPU from a cold ccache, seconds when
  # warm) keeps this stage within 5 minutes on 2 cores.
  "$REPO/scripts/fuzz.sh" "${STOCS_FUZZ_SECONDS:-15}"
  stage_done "the fuzz build and runs"
fi
echo "run_tests: all tests passed"
