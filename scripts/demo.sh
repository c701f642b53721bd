#!/usr/bin/env bash
# The README's main command. Installs the Debian packages, builds, generates a cluttered tabletop
# scene of the project's own meshes (once, in build/demo/scene), plays it through the StoCS node
# with roslaunch (scene publisher -> stocs_node -> demo recorder), prints per object the pose,
# score and latency of each frame and the ADD-S error of the last against the ground truth, writes
# build/demo/overlay.png, and exits 0 only if every object was found (ADD-S < 10% of its diameter).
#   scripts/demo.sh [--rviz] [--network] [--track]
#     --rviz: also open rviz, on a machine with a display; the scene plays until rviz is closed.
#     --network: the maps come from the package's segmentation network (segmentation_node on the
#                colour image; models/segmenter.onnx, never trained on this scene) instead of prob/
#     --track: then also track a generated 90-frame sequence (build/demo/sequence: an object
#       pushed, one lifted, one removed and put back, one occluded) with `stocs estimate --track
#       true`, and print the tracking counts, the share of correct poses and, for the removed
#       object, the frames posed after it left and the frame it was found again (about a minute
#       more); the exit code also requires every object correct in the sequence's last frame.
set -euo pipefail
source "$(dirname "$0")/common.sh"
rviz=false
network=false
track=false
for arg in "$@"; do
  case "$arg" in
    --rviz) rviz=true ;;
    --network) network=true ;;
    --track) track=true ;;
    *) echo "usage: $0 [--rviz] [--network] [--track]" >&2; exit 2 ;;
  esac
done
"$REPO/scripts/install_deps.sh"
mkdir -p "$REPO/build"
"$REPO/scripts/build.sh" > "$REPO/build/build.log" 2>&1 || { tail -50 "$REPO/build/build.log"; exit 1; }
set +u
source "$WS/devel/setup.bash"
set -u
tool="$WS/devel/lib/stocs_ros/stocs"
demo="$REPO/build/demo"
scene="$demo/scene"
# Generated once; again when the generating command changes.
synth=(synth --out "$scene" --objects 6 --distractors 2 --seed 1 --quiet)
if [ ! -f "$scene/test/000000/scene_gt.json" ] || [ "$(cat "$demo/scene.cmd" 2>/dev/null)" != "${synth[*]}" ]; then
  rm -rf "$scene"
  mkdir -p "$demo"
  "$tool" "${synth[@]}"
  echo "${synth[*]}" > "$demo/scene.cmd"
fi
rm -f "$demo/results.csv"

# A ROS master of the demo's own on a free port: no roscore needed, none disturbed.
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')
export ROS_MASTER_URI="http://localhost:$port" ROS_HOME="$demo/ros"
# The whole launch output goes to a log; the terminal shows the recorder's report.
if $rviz; then
  echo "demo: rviz shows the estimates (object colours) and the ground truth (green); the scene"
  echo "plays until you close rviz, then the report follows"
fi
roslaunch -p "$port" stocs_ros demo.launch dataset:="$scene" results:="$demo/results.csv" \
  rviz:="$rviz" network:="$network" > "$demo/roslaunch.log" 2>&1 || true
grep -E "^(frame |  |latency |results )|ERROR|FATAL" "$demo/roslaunch.log" || true
if [ ! -s "$demo/results.csv" ]; then
  echo "demo: FAILED, no estimates were recorded (log: $demo/roslaunch.log)" >&2
  exit 1
fi

"$tool" eval --dataset "$scene" --results "$demo/results.csv" --targets-csv "$demo/targets.csv" \
  --markdown "$demo/metrics.md" > /dev/null
"$tool" overlay --dataset "$scene" --results "$demo/results.csv" --out "$demo/overlay.png"
# targets.csv: obj_id $5, found $6, diameter_mm $9, adds_mm $12, adds_success $16.
awk -F, 'NR > 1 {
    n++; ok += $16
    if ($6 == 1) printf "object %d: ADD-S %.1f mm (%.1f%% of its %.0f mm diameter) %s\n", $5, $12, 100 * $12 / $9, $9, ($16 ? "found" : "WRONG")
    else printf "object %d: no pose\n", $5 }
  END { printf "%d of %d objects found\n", ok, n; exit (n > 0 && ok == n) ? 0 : 1 }' "$demo/targets.csv"
$track || exit 0
"$REPO/scripts/demo_tracking.sh" "$tool" "$demo"
