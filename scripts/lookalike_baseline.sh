#!/usr/bin/env bash
# Issue 45's figures ("which object it is") on generated confusions that fit, seeds 201-210 (used
# by no other figure, calibration or test): per simulator preset,
#  - tabletop: `stocs synth --catalogue lookalike --objects 6` scenes (each holds one object of each
#    look-alike pair; its absent targets are drawn among the partners first, their maps mark the
#    present look-alike), estimated at --min-confidence 0 and scored by `stocs eval --targets`
#    (ROC AUC, calibration error, right poses rejected at min_confidence) and lookalike_metrics.py tabletop
#    (absent targets with a visible look-alike without a pose, and the other absent ones);
#  - packed bin: `--packed-bin 1` (2 x 4 boxes, every one in scene_gt.json; absent targets the small
#    box, whose map marks the bin's boxes, and one other), `--instances 8` at the default
#    min_confidence, scored by lookalike_metrics.py bin (ADD-S on the model file's vertices, as
#    `stocs eval`) and binlog (the estimate log's ADD-S, on surface samples); once more at
#    --min-confidence 0 for the confidence's ROC AUC over every pose.
#   scripts/lookalike_baseline.sh [--summary-only] OUT [SEEDS...]   (STOCS: the `stocs` tool)
#   --summary-only: the figures again from the runs already in OUT.
set -euo pipefail
source "$(dirname "$0")/common.sh"
summary_only=false
if [ "${1:-}" = --summary-only ]; then
  summary_only=true
  shift
fi
[ $# -ge 1 ] || { echo "usage: $0 [--summary-only] OUT [SEEDS...]" >&2; exit 2; }
out=$1
shift
seeds=${*:-$(seq 201 210)}
tool=${STOCS:-$WS/devel/lib/stocs_ros/stocs}
metrics="$(dirname "$0")/lookalike_metrics.py"
mkdir -p "$out"
cache="$out/cache"

for preset in clean mild noisy very-noisy; do
  pairs=()
  targets=()
  bin_runs=()
  bin_all_runs=()
  bin_logs=()
  for seed in $seeds; do
    d="$out/table-$preset-$seed"
    b="$out/bin-$preset-$seed"
    pairs+=(--dataset "$d" --results "$d.csv" --targets "$d/test_targets_bop19.json")
    targets+=("$d.targets.csv")
    bin_runs+=("$b.csv")
    bin_all_runs+=("$b-all.csv")
    bin_logs+=("$b.log")
    $summary_only && continue
    rm -rf "$d"
    "$tool" synth --out "$d" --catalogue lookalike --objects 6 --distractors 2 --images 3 \
      --segmentation "$preset" --seed "$seed" --quiet 2> /dev/null
    "$tool" estimate --dataset "$d" --targets "$d/test_targets_bop19.json" --out "$d.csv" \
      --min-confidence 0 --seed "$seed" --cache-dir "$cache" 2> "$d.log"
    "$tool" eval --dataset "$d" --results "$d.csv" --targets "$d/test_targets_bop19.json" \
      --targets-csv "$d.targets.csv" > /dev/null
    rm -rf "$b"
    "$tool" synth --out "$b" --catalogue lookalike --packed-bin 1 --images 3 \
      --segmentation "$preset" --seed "$seed" --quiet 2> /dev/null
    "$tool" estimate --dataset "$b" --targets "$b/test_targets_bop19.json" --out "$b.csv" \
      --instances 8 --seed "$seed" --cache-dir "$cache" 2> "$b.log"
    ln -sfn "$(basename "$b")" "$b-all"
    "$tool" estimate --dataset "$b" --targets "$b/test_targets_bop19.json" --out "$b-all.csv" \
      --instances 8 --min-confidence 0 --seed "$seed" --cache-dir "$cache" 2> "$b-all.log"
  done
  {
    echo "## $preset"
    "$tool" eval "${pairs[@]}" --csv "$out/eval-$preset.csv" > "$out/eval-$preset.md"
    python3 "$metrics" eval "$out/eval-$preset.csv"
    python3 "$metrics" tabletop "${targets[@]}"
    python3 "$metrics" bin "${bin_runs[@]}" | grep -v 'ROC AUC'  # of the published poses only
    python3 "$metrics" bin "${bin_all_runs[@]}" | grep 'ROC AUC' | sed 's/^bin:/bin, every pose:/'
    python3 "$metrics" binlog "${bin_logs[@]}" | sed 's/^bin:/bin, by the log:/'
  } | tee "$out/summary-$preset.txt"
done
