#!/usr/bin/env bash
# The README's rviz screenshots, made headless as a person would see them: rviz with
# config/stocs.rviz on a 1280x800 Xvfb screen, taken once the node's estimates and the scene
# publisher's ground truth have arrived and rviz has drawn them.
#   OUT/rviz_lmo_cat.png  the real LM-O cat frame, as the README's
#                         `roslaunch stocs_ros bop_playback.launch dataset:=$STOCS_DATASETS/lmo-cat rviz:=true`
#   OUT/rviz_demo.png     the demo's generated scene (build/demo/scene), as `scripts/demo.sh --rviz`
# Needs the built workspace (scripts/build.sh), STOCS_DATASETS naming the folder holding lmo-cat/,
# the demo's scene (run scripts/demo.sh once) and the Debian packages rviz, xvfb and imagemagick.
#   scripts/rviz_screenshots.sh [OUT]      (default: docs)
set -euo pipefail
source "$(dirname "$0")/common.sh"
set +u
source "$WS/devel/setup.bash"
set -u

# Seconds rviz gets to draw once every marker has arrived: it renders slowly in software (Mesa
# llvmpipe) on busy cores.
settle=15

# Inside Xvfb: runs `roslaunch stocs_ros ARGS...`, waits for both kinds of markers, and saves the
# whole screen as FILE.
if [ "${1:-}" = "--inside" ]; then
  file=$2
  shift 2
  roslaunch -p "$STOCS_SHOT_PORT" stocs_ros "$@" > "$file.log" 2>&1 &
  launch=$!
  fail() {
    echo "rviz_screenshots: $1 (log: $file.log)" >&2
    kill -INT "$launch" 2> /dev/null || true
    wait "$launch" || true
    exit 1
  }
  # rostopic needs the master, which roslaunch starts.
  until rostopic list > /dev/null 2>&1; do
    kill -0 "$launch" 2> /dev/null || fail "roslaunch ended"
    sleep 1
  done
  for topic in /stocs/markers /scene_publisher/ground_truth_markers; do
    timeout 600 rostopic echo -n 1 "$topic" > /dev/null 2>&1 || fail "no message on $topic in 600 s"
  done
  sleep "$settle"
  import -window root "$file"
  kill -INT "$launch"
  wait "$launch" || true
  exit 0
fi

out=$(realpath -m "${1:-$REPO/docs}")
for tool in rviz xvfb-run import convert; do
  command -v "$tool" > /dev/null || {
    echo "rviz_screenshots: $tool is missing; apt-get install -y rviz xvfb imagemagick" >&2
    exit 1
  }
done
lmo="${STOCS_DATASETS:-}/lmo-cat"
if [ -z "${STOCS_DATASETS:-}" ] || [ ! -d "$lmo" ]; then
  echo "rviz_screenshots: STOCS_DATASETS must name the folder holding lmo-cat/" >&2
  exit 1
fi
scene="$REPO/build/demo/scene"
if [ ! -f "$scene/test/000000/scene_gt.json" ]; then
  echo "rviz_screenshots: $scene is missing; run scripts/demo.sh once to generate it" >&2
  exit 1
fi
work="$REPO/build/rviz_screenshots"
mkdir -p "$work" "$out"

# NAME ROSLAUNCH-ARGS...: one screenshot, with a ROS master of its own on a free port.
shoot() {
  local name=$1
  shift
  STOCS_SHOT_PORT=$(python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])')
  export STOCS_SHOT_PORT ROS_MASTER_URI="http://localhost:$STOCS_SHOT_PORT" ROS_HOME="$work/ros"
  xvfb-run -a -s "-screen 0 1280x800x24" "$0" --inside "$work/$name.png" "$@"
  # 64 colours keep a screenshot under 300 KB; the cloud's colours suffer most.
  convert "$work/$name.png" +dither -colors 64 "PNG8:$out/$name.png"
  echo "$out/$name.png"
}

shoot rviz_lmo_cat bop_playback.launch dataset:="$lmo" rviz:=true
shoot rviz_demo demo.launch dataset:="$scene" results:="$work/results.csv" rviz:=true
