#!/usr/bin/env bash
# Installs dependencies, lints the package (catkin_lint) and the markdown links (check_md_links.py),
# builds, and runs every test: the ROS tests in the catkin build (gtests of the wrappers, rostests,
# the launch file check), README's ROS commands as written (scripts/check_readme_ros.sh, when
# STOCS_DATASETS names the real-data folder), then the core's tests (unit, CLI and, with
# STOCS_DATASETS, the real-frame acceptance tests) in an AddressSanitizer +
# UndefinedBehaviorSanitizer build of the ROS-free core, then a short run of every fuzz target
# (scripts/fuzz.sh).
# Exits non-zero when anything fails. STOCS_SKIP_SANITIZERS=1 runs the core's tests in a build
# without sanitizers, STOCS_SKIP_FUZZ=1 skips the fuzzing; STOCS_FUZZ_SECONDS sets the time per
# fuzz target (default 15).
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
  echo "run_tests: STOCS_DATASETS is not set; real-data tests and README's ROS commands are skipped"
fi

# catkin_lint on the package, as a workspace holds it (a folder named after the package); any
# finding fails. CMakeLists.txt turns off, each with its reason, the few that are wrong here.
lint_dir=$(mktemp -d)
ln -s "$REPO" "$lint_dir/stocs_ros"
lint_status=0
catkin_lint -W2 --strict --offline "$lint_dir/stocs_ros" || lint_status=$?
rm -r "$lint_dir"
if [ $lint_status -ne 0 ]; then
  echo "run_tests: catkin_lint FAILED"
  exit 1
fi
# Relative links of README.md and docs/: every file and heading anchor they name exists.
if ! python3 "$REPO/scripts/check_md_links.py"; then
  echo "run_tests: markdown links FAILED"
  exit 1
fi
stage_done "catkin_lint and the markdown links"

# The catkin build holds the ROS tests; the core's tests (unit, CLI, real data) run once, in the
# sanitizer build below, rather than in both builds.
"$REPO/scripts/build.sh" -DSTOCS_CORE_TESTS=OFF
"$REPO/scripts/build.sh" -DSTOCS_CORE_TESTS=OFF tests
stage_done "the catkin build (package and ROS tests)"
rm -rf "$WS/build/test_results"
# Tests run $JOBS at a time, each with OpenMP threads: threads that spin between parallel regions
# (libgomp's default) take the cores the other tests need, and the programs would re-execute
# themselves to wait passively (stocs/util/openmp_wait.h). The OpenMP wait test unsets it.
export OMP_WAIT_POLICY=passive
# run_tests exits 0 even when tests fail; catkin_test_results gives the verdict.
catkin_make -C "$WS" -j"$JOBS" run_tests > "$WS/run_tests.log" 2>&1 || true
if ! catkin_test_results --verbose "$WS/build/test_results"; then
  echo "run_tests: catkin tests FAILED (log: $WS/run_tests.log)"
  exit 1
fi
stage_done "the ROS tests"

# README's ROS commands, run as written on the real LM-O frame, in the catkin build above.
if [ -n "${STOCS_DATASETS:-}" ]; then
  "$REPO/scripts/check_readme_ros.sh"
  stage_done "README's ROS commands"
fi

# The core's tests, in an AddressSanitizer + UndefinedBehaviorSanitizer build unless
# STOCS_SKIP_SANITIZERS=1 (then in a plain build). -O1 with line tables only (-g1), as OSS-Fuzz
# builds, compiles much faster than -O2 -g under the sanitizers, and the reports keep their file
# and line. Without the Google Benchmark programs: no test runs them.
if [ "${STOCS_SKIP_SANITIZERS:-0}" != 1 ]; then
  CORE="$REPO/build/sanitize"
  SANITIZE=ON
else
  CORE="$REPO/build/core-tests"
  SANITIZE=OFF
fi
cmake -S "$REPO" -B "$CORE" -DSTOCS_WITH_ROS=OFF -DSTOCS_SANITIZE=$SANITIZE \
  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DCMAKE_DISABLE_FIND_PACKAGE_benchmark=ON "${QUICK_LINK[@]}" \
  -DSTOCS_DATASETS_DIR="${STOCS_DATASETS:-}" > "$CORE.cmake.log" 2>&1 || { cat "$CORE.cmake.log"; exit 1; }
cmake --build "$CORE" -j"$JOBS"
stage_done "the core's test build (sanitizers: $SANITIZE)"
# halt_on_error: any sanitizer report fails the test that triggered it.
# LSAN_OPTIONS: a leak inside assimp on a malformed STL (scripts/lsan_suppressions.txt).
ASAN_OPTIONS=detect_leaks=1:halt_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  LSAN_OPTIONS="suppressions=$REPO/scripts/lsan_suppressions.txt" \
  ctest --test-dir "$CORE" -j"$JOBS" --output-on-failure
stage_done "the core's tests"

# The C++ interface from outside: the core installed, examples/estimate_pose built against it as a
# plain CMake project (find_package(stocs)) and run on a generated scene. The sanitizer build's
# libraries need the sanitizers at link time too.
"$REPO/scripts/check_cpp_example.sh" "$CORE" "$SANITIZE"
stage_done "the C++ example"

if [ "${STOCS_SKIP_FUZZ:-0}" != 1 ]; then
  # The fuzz build (long from an empty ccache, quick when warm), then every target for
  # STOCS_FUZZ_SECONDS (default 15).
  "$REPO/scripts/fuzz.sh" "${STOCS_FUZZ_SECONDS:-15}"
  stage_done "the fuzz build and runs"
fi
echo "run_tests: all tests passed"
