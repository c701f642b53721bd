#!/usr/bin/env bash
# The demo's tracking run (scripts/demo.sh --track): a generated 90-frame sequence of the six
# meshes (once, in DEMO/sequence) tracked with `stocs estimate --track true`; prints the tracking
# counts and scripts/tracking_metrics.py's figures (time per frame, share of correct poses, drift,
# removal and return), and exits 0 only if every object is correct in the last frame.
#   scripts/demo_tracking.sh TOOL DEMO   (TOOL: the stocs program; DEMO: the demo's build folder)
set -euo pipefail
source "$(dirname "$0")/common.sh"
tool=$1
demo=$2
sequence="$demo/sequence"
synth=(synth --out "$sequence" --sequence --frames 90 --objects 6 --distractors 2 --seed 1
  --push-start 10 --push-frames 15 --lift-start 25 --lift-frames 20 --removal-start 45
  --removal-frames 15 --occlusion-start 65 --occlusion-frames 15 --quiet)
if [ ! -f "$sequence/test_targets_bop19.json" ] ||
  [ "$(cat "$demo/sequence.cmd" 2>/dev/null)" != "${synth[*]}" ]; then
  rm -rf "$sequence"
  "$tool" "${synth[@]}"
  echo "${synth[*]}" > "$demo/sequence.cmd"
fi
targets="$sequence/test_targets_bop19.json"
"$tool" estimate --dataset "$sequence" --targets "$targets" --track true --warm-up \
  --out "$demo/tracking.csv" --per-object "$demo/tracking_objects.csv" > "$demo/tracking.log" 2>&1 ||
  { tail -5 "$demo/tracking.log"; exit 1; }
"$tool" eval --dataset "$sequence" --targets "$targets" --results "$demo/tracking.csv" \
  --targets-csv "$demo/tracking_targets.csv" > /dev/null
echo "tracking a 90-frame sequence: $(grep -E '^tracking:' "$demo/tracking.log")"
figures=$(python3 "$REPO/scripts/tracking_metrics.py" --scene "$sequence/test/000000" \
  --track-results "$demo/tracking.csv" --track-targets "$demo/tracking_targets.csv" \
  --track-objects "$demo/tracking_objects.csv")
echo "$figures"
# "last_frame_correct K of N"
echo "$figures" | awk '$1 == "last_frame_correct" { exit ($2 == $4 && $4 > 0) ? 0 : 1 }'
