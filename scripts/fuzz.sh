#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/fuzz_*.cpp; clang, ASan + UBSan, build/fuzz) and runs each for
# SECONDS (default 300) from its committed seed corpus fuzz/corpus/<target>. New inputs go to
# build/fuzz/corpus/<target>, crashing inputs to build/fuzz/artifacts/, logs to build/fuzz/logs/.
# Exits non-zero when any target crashes, leaks, hangs, runs out of memory or reports UB. Runs
# STOCS_JOBS (default: the number of cores) targets at a time.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (default: every target)
set -euo pipefail
source "$(dirname "$0")/common.sh"

SECONDS_PER_TARGET="${1:-300}"  # not SECONDS: bash's own clock, used below
shift || true
OUT="$REPO/build/fuzz"
mkdir -p "$OUT"

# -O1 with line tables only, as OSS-Fuzz builds its targets: quicker to compile than -O2 -g.
cmake -S "$REPO" -B "$OUT" -DSTOCS_WITH_ROS=OFF -DSTOCS_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -gline-tables-only -DNDEBUG" \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ "${QUICK_LINK[@]}" > "$OUT.cmake.log" 2>&1 ||
  { cat "$OUT.cmake.log"; exit 1; }
cmake --build "$OUT" -j"$JOBS" --target fuzz

if [ $# -gt 0 ]; then
  TARGETS=("$@")
else
  mapfile -t TARGETS < <(cd "$REPO/fuzz" && ls fuzz_*.cpp | sed 's/\.cpp$//')
fi
mkdir -p "$OUT/logs" "$OUT/artifacts"
export ASAN_OPTIONS="detect_leaks=1:abort_on_error=0"
export LSAN_OPTIONS="suppressions=$REPO/scripts/lsan_suppressions.txt"  # assimp's own leak
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
# run_target TARGET: runs it for SECONDS_PER_TARGET and writes its summary line to
# logs/TARGET.result ("ok" or "FAILED" last).
run_target() {
  local t=$1 log="$OUT/logs/$1.log" result=ok start=$SECONDS
  mkdir -p "$OUT/corpus/$t"
  # -timeout: an input that takes 60 s is a hang, reported like a crash (fuzz_model_cache
  # rebuilds the model after every rejected entry, which takes seconds on a loaded machine).
  "$OUT/$t" -max_total_time="$SECONDS_PER_TARGET" -timeout=60 -print_final_stats=1 \
    -artifact_prefix="$OUT/artifacts/$t-" "$OUT/corpus/$t" "$REPO/fuzz/corpus/$t" > "$log" 2>&1 ||
    result=FAILED
  local took=$((SECONDS - start))
  local execs corpus
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  corpus=$(find "$OUT/corpus/$t" "$REPO/fuzz/corpus/$t" -type f | wc -l)
  printf '%-20s %8s %12s %8s %s\n' "$t" "$took" "${execs:-?}" "$corpus" "$result" \
    > "$OUT/logs/$t.result"
}

# JOBS targets at a time (one per core: each fuzzer is a single process of one thread), each for
# the full SECONDS_PER_TARGET; the table follows in the targets' order.
failed=()
ran=()
for t in "${TARGETS[@]}"; do
  if [ ! -x "$OUT/$t" ]; then
    echo "fuzz: no target $t (ROS fuzz targets need the ROS headers and libraries)"
    failed+=("$t")
    continue
  fi
  rm -f "$OUT/logs/$t.result"
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n || true; done
  run_target "$t" &
  ran+=("$t")
done
wait
printf '%-20s %8s %12s %8s %s\n' target seconds executions corpus result
for t in "${ran[@]}"; do
  line=$(cat "$OUT/logs/$t.result" 2>/dev/null || echo "$t ? ? ? FAILED")
  echo "$line"
  if [ "${line##* }" != ok ]; then
    grep -E "ERROR|SUMMARY|runtime error|Test unit written" "$OUT/logs/$t.log" | head -20 || true
    echo "fuzz: full log $OUT/logs/$t.log"
    failed+=("$t")
  fi
done
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzz: FAILED: ${failed[*]}"
  exit 1
fi
echo "fuzz: all ${#TARGETS[@]} targets ran ${SECONDS_PER_TARGET} s without a finding"
