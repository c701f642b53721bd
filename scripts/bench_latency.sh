#!/usr/bin/env bash
# Node latency benchmark (issue 6): a generated 640x480 scene of three objects played at RATE Hz
# through the StoCS node for FRAMES frames; the demo recorder prints the latency from each input
# stamp (set by the player once a frame's messages are built, right before it publishes them) to
# the node's estimates (~objects, published right after TF), p50 and p95, with the share of CPU time
# the hypervisor stole during the run (it stretches every latency on a shared VM). It runs twice:
# publisher and estimator as separate nodes (clouds and images serialized over TCP) and as nodelets
# in one manager (passed as shared pointers). The player decodes the scene's frames before it
# starts (preload), so that it sustains the rate; the node's frame counts say how many frames it
# dropped.
#   scripts/bench_latency.sh [FRAMES [RATE [BASES [CONSENSUS]]]]   (defaults: 60 frames at 5 Hz,
#     the configuration's bases and consensus_bases, i.e. 100 and 8; CONSENSUS 0 runs every base)
# STOCS_LATENCY_TRACKING=true or false sets tracking.enabled (default: the node's, true);
# STOCS_LATENCY_DATASET plays that generated dataset (e.g. a tracking sequence of
# scripts/bench_tracking.sh) instead.
# STOCS_LATENCY_INPUT=depth sends the depth image and camera_info instead of the organized cloud
# (input.source: depth), STOCS_LATENCY_PROBABILITY the maps' encoding (mono16, mono8, 32FC1): a
# six-object frame is about 9.8 MB of cloud and 3.7 MB of mono16 maps, against 1.2 MB of depth.
# Needs the workspace built by scripts/build.sh.
set -euo pipefail
source "$(dirname "$0")/common.sh"
frames=${1:-60}
rate=${2:-5}
bases=${3:-}
consensus=${4:-}
set +u
source "$WS/devel/setup.bash"
set -u
tool="$WS/devel/lib/stocs_ros/stocs"
out="$REPO/build/bench_latency"
rm -rf "$out"
mkdir -p "$out"
scene=${STOCS_LATENCY_DATASET:-$out/scene}
[ -n "${STOCS_LATENCY_DATASET:-}" ] ||
  "$tool" synth --out "$scene" --objects 3 --distractors 2 --seed 1 --quiet
# The demo's configuration, restricted to the objects of the scene.
/usr/bin/python3 - "$REPO/config/demo.yaml" "$scene/test/000000/scene_gt.json" > "$out/config.yaml" <<'PY'
import json, sys
ids = {g["obj_id"] for image in json.load(open(sys.argv[2])).values() for g in image}
for line in open(sys.argv[1]):
    if "id: " in line and int(line.split("id: ")[1].split(",")[0]) not in ids:
        continue
    print(line, end="")
PY
if [ -n "$bases$consensus" ]; then
  printf 'estimation:\n  stocs:\n' >> "$out/config.yaml"
  if [ -n "$bases" ]; then printf '    bases: %s\n' "$bases" >> "$out/config.yaml"; fi
  if [ -n "$consensus" ]; then
    printf '    consensus_bases: %s\n' "$consensus" >> "$out/config.yaml"
  fi
fi
# Busy and stolen CPU time so far (jiffies, all cores): on a virtual machine the hypervisor's steal
# time stretches every latency, so each result says how much of it there was.
cpu_times() {
  local _ user nice system irq softirq steal
  read -r _ user nice system _ _ irq softirq steal _ < /proc/stat  # idle and iowait skipped
  echo "$((user + nice + system + irq + softirq)) $steal"
}
if [ -n "${STOCS_LATENCY_TRACKING:-}" ]; then
  printf 'tracking:\n  enabled: %s\n' "$STOCS_LATENCY_TRACKING" >> "$out/config.yaml"
fi
printf 'input:\n  source: %s\n' "${STOCS_LATENCY_INPUT:-cloud}" >> "$out/config.yaml"
for mode in nodes nodelets; do
  read -r busy0 steal0 <<< "$(cpu_times)"
  nodelet=false
  [ "$mode" = nodelets ] && nodelet=true
  port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')
  export ROS_MASTER_URI="http://localhost:$port" ROS_HOME="$out/ros-$mode"
  roslaunch -p "$port" stocs_ros demo.launch dataset:="$scene" config:="$out/config.yaml" \
    results:="$out/results-$mode.csv" frames:="$frames" rate:="$rate" timeout:=600 \
    nodelet:="$nodelet" preload:=true \
    probability_encoding:="${STOCS_LATENCY_PROBABILITY:-mono16}" > "$out/roslaunch-$mode.log" 2>&1 || true
  line=$(grep -E "^latency " "$out/roslaunch-$mode.log") ||
    { echo "bench_latency: no result as $mode (log: $out/roslaunch-$mode.log)" >&2; exit 1; }
  read -r busy1 steal1 <<< "$(cpu_times)"
  stolen=$((steal1 - steal0))
  echo "$mode: $line; steal $((100 * stolen / (busy1 - busy0 + stolen + 1)))% of the busy time"
  # Frames the node received, estimated and dropped (replaced by a newer one while it was busy).
  grep -oE "at shutdown: [0-9]+ frames matched: [0-9]+ estimated, [0-9]+ replaced" \
    "$out/roslaunch-$mode.log" | sed "s/^at shutdown: /  node: /" || true
done
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
