#!/usr/bin/env bash
# Checks that a change leaves every pose as it was: `record` runs a `stocs` tool at fixed seeds on
# every real frame and on generated scenes and keeps the BOP result files; `compare` checks two
# recordings row by row on everything but the time column (scores and poses to the printed digit).
#   scripts/pose_regression.sh record TOOL DATASETS OUT   (TOOL: a built `stocs`, DATASETS: the
#                                                          folder holding lmo-cat/, ycbv-0000/ ...)
#   scripts/pose_regression.sh compare BEFORE AFTER
set -euo pipefail

record() {
  local tool=$1 data=$2 out=$3
  mkdir -p "$out"
  local cache="$out/cache"
  run() {  # name, then estimate's arguments
    local name=$1
    shift
    "$tool" estimate --cache-dir "$cache" --out "$out/$name.csv" "$@" 2> "$out/$name.log" ||
      { cat "$out/$name.log"; exit 1; }
  }
  for seed in 0 1 2; do
    run "lmo-cat-s$seed" --dataset "$data/lmo-cat" --prob real --seed "$seed"
    run "lmo-cat-b3-s$seed" --dataset "$data/lmo-cat" --prob real --seed "$seed" --bases 3
    run "packed-s$seed" --dataset "$data/rutgers-packed" --prob real --seed "$seed"
    run "packed-i8-s$seed" --dataset "$data/rutgers-packed" --prob real --seed "$seed" --instances 8
    run "ycbv-mild-s$seed" --dataset "$data/ycbv-0000" --prob sim:mild --seed "$seed"
    run "ycbv-noisy-s$seed" --dataset "$data/ycbv-0000" --prob sim:noisy --seed "$seed"
  done
  for seed in 1 2 3 4 5; do
    local scene="$out/generated-$seed"
    rm -rf "$scene"
    "$tool" synth --out "$scene" --objects 6 --distractors 2 --seed "$seed" --quiet > /dev/null
    run "generated-$seed" --dataset "$scene" --prob real
    run "generated-$seed-b5" --dataset "$scene" --prob real --bases 5
    run "generated-$seed-paper" --dataset "$scene" --prob real --consensus 0 --focused-bases 0 \
      --draw-budget 0
  done
}

# The rows without the last column (BOP's time).
poses() { sed 's/,[^,]*$//' "$1"; }

compare() {
  local before=$1 after=$2 differ=0 files=0
  for a in "$before"/*.csv; do
    local name b
    name=$(basename "$a")
    b="$after/$name"
    files=$((files + 1))
    if [ ! -f "$b" ]; then
      echo "missing in $after: $name"
      differ=1
    elif ! diff -q <(poses "$a") <(poses "$b") > /dev/null; then
      echo "poses differ: $name"
      diff <(poses "$a") <(poses "$b") | head -6
      differ=1
    fi
  done
  [ "$differ" = 0 ] || { echo "pose_regression: results differ"; exit 1; }
  echo "pose_regression: $files result files identical (time column aside)"
}

case "${1:-}" in
  record) [ $# -eq 4 ] || { echo "usage: $0 record TOOL DATASETS OUT" >&2; exit 2; }
          record "$2" "$3" "$4" ;;
  compare) [ $# -eq 3 ] || { echo "usage: $0 compare BEFORE AFTER" >&2; exit 2; }
           compare "$2" "$3" ;;
  *) echo "usage: $0 record TOOL DATASETS OUT | compare BEFORE AFTER" >&2; exit 2 ;;
esac
