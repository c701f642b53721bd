#!/usr/bin/env bash
# Runs the commands of README.md's ROS sections as a user copies them, in the catkin workspace of
# scripts/build.sh and on the real datasets of STOCS_DATASETS (README's placeholders replaced by
# them), each with a time limit and a check of what it prints. Everything runs on a virtual display
# (xvfb-run), so the rviz of `rviz:=true` starts as on a desktop, and on a ROS master of its own.
# The commands come from README itself (scripts/readme_commands.py): each must match one step below
# and each step one command, so README and this list cannot drift apart. Exits non-zero naming the
# first command that fails, or the commands and steps without a partner.
#   STOCS_DATASETS=../shared/datasets scripts/check_readme_ros.sh
#
# Adding a README command is one step line, placed where it should run:
#   step KIND SECONDS 'README command (a bash glob)' 'pattern' ...
# Every pattern, an extended regular expression, must show in the command's output; one may span
# lines (\s matches a line break). KINDS:
#   env    run in this shell (export, source); SECONDS and patterns unused
#   start  a launch left running for the steps after it, on a new master (what a previous start
#          left running is stopped first); the patterns must show within SECONDS
#   also   the same beside what runs, on its master (rosbag play -l next to a launch)
#   run    a command that ends by itself (rosservice call, rostopic echo -n 1); it must exit 0 and
#          show the patterns, and is run again until it does (as a user retries while a node starts
#          up) or SECONDS pass
#   watch  a command that runs until Ctrl-C (tf_echo, rostopic echo); stopped with Ctrl-C once the
#          patterns show within SECONDS, run again if it ends before
#   skip   a README mention not meant to be run as written; the pattern says why
# What start and also leave running stays up at least MIN_UP seconds; when it is stopped, its
# output (console, rviz's and every node's log messages) must show no error, no FATAL, no died
# process and no Traceback.
set -euo pipefail
source "$(dirname "$0")/common.sh"

KINDS=() LIMITS=() GLOBS=() PATTERNS=()
step() {
  KINDS+=("$1") LIMITS+=("$2") GLOBS+=("$3")
  local IFS=$'\n'
  PATTERNS+=("${*:4}")
}

step env 0 'export PATH=/usr/bin:$PATH'
step env 0 'source ../stocs_ros_ws/devel/setup.bash'
step start 180 'roslaunch stocs_ros bop_playback.launch dataset:=* rviz:=true' \
  'stocs: 1 objects \(cat\)' 'OpenGl version: [0-9]'
step run 60 'rosservice call /stocs/estimate "{objects: \[cat\]*' \
  'success: True' 'objects:\s+-\s+name: "cat"' 'orientation:\s+x: -?[0-9]'
# poses tracked: the first example engages the node's default, tracking (issue 42: at 1 Hz every
# frame came after tracking.max_gap and ended the tracks).
step run 60 'rostopic echo -n 1 /stocs/statistics' \
  'key: "received /camera/\S+"\s+value: "[1-9]' 'key: "frames estimated"\s+value: "[1-9]' \
  'key: "service calls"' 'key: "poses tracked"\s+value: "[1-9]'
step start 120 'roslaunch stocs_ros stocs.launch config:=* cloud:=*' \
  'stocs: 1 objects \(cat\) from .*; waiting for 2 synchronized inputs'
step run 30 'rosrun dynamic_reconfigure dynparam set /stocs min_confidence 0.6'
step skip 0 'rosbag play -l' 'a mention in the text of the bag command below'
step start 60 'roslaunch stocs_ros scene_publisher.launch dataset:=*' \
  'scene_publisher: [0-9]+ frames of .*lmo-cat'
step run 60 'rosbag record -O lmo-cat.bag --duration=5 *' 'Recording to'
step start 120 'roslaunch stocs_ros stocs.launch dataset:=* use_sim_time:=true' \
  'stocs: 1 objects \(cat\) from .*; waiting for'
step also 60 'rosbag play -l --clock lmo-cat.bag' 'Bag Time'
# Exit 0 is the check: it prints nothing.
step run 30 'rosparam set /use_sim_time false'

OUT="$REPO/build/readme_ros"
# README's placeholders and what they stand for here.
PLACEHOLDERS=(
  "/path/to/datasets=${STOCS_DATASETS:-}"
  "../stocs_ros_ws=$WS"
  "/path/to/objects.yaml=$OUT/objects.yaml"
  "lmo-cat.bag=$OUT/lmo-cat.bag"
)
MIN_UP=5
FAILURE='\[(ERROR|FATAL)\]|^[0-9.]+ (ERROR|FATAL) |has died|Traceback|Segmentation fault'
# What start and also left running: process (group leader), folder, command, start time.
BG_PIDS=() BG_DIRS=() BG_COMMANDS=() BG_STARTED=()

fail() {
  echo "check_readme_ros: FAILED: $1" >&2
  if [ -n "${2:-}" ]; then
    echo "--- last lines of its output ($2):" >&2
    tail -40 "$2" >&2
  fi
  exit 1
}

# shows_all PATTERNS: the text on stdin matches each of the patterns (one a line; grep -z: a
# pattern may span lines).
shows_all() {
  local text pattern patterns
  text=$(cat)
  mapfile -t patterns <<< "$1"
  for pattern in "${patterns[@]}"; do
    grep -Ezq -- "$pattern" <<< "$text" || return 1
  done
}

# Pairs README's commands with the steps: STEP_COMMAND[i] is the command step i runs.
pair_steps() {
  local commands problems=() i c n
  mapfile -t commands < <(python3 "$REPO/scripts/readme_commands.py" "$REPO/README.md")
  [ ${#commands[@]} -gt 0 ] || fail "found no command in README.md's ROS sections"
  STEP_COMMAND=()
  for c in "${commands[@]}"; do
    n=0
    for i in "${!GLOBS[@]}"; do [[ $c == ${GLOBS[i]} ]] && n=$((n + 1)); done
    [ $n -eq 1 ] || problems+=("README command matching $n steps (not 1): $c")
  done
  for i in "${!GLOBS[@]}"; do
    n=0
    for c in "${commands[@]}"; do
      if [[ $c == ${GLOBS[i]} ]]; then
        n=$((n + 1))
        STEP_COMMAND[i]=$c
      fi
    done
    [ $n -eq 1 ] || problems+=("step matching $n README commands (not 1): ${GLOBS[i]}")
  done
  if [ ${#problems[@]} -gt 0 ]; then
    printf 'check_readme_ros: %s\n' "${problems[@]}" >&2
    fail "README.md's ROS commands and this script's steps differ (see the step list's comment)"
  fi
}

# The command as a user runs it here: README's placeholders replaced.
as_written() {
  local command=$1 p
  for p in "${PLACEHOLDERS[@]}"; do command=${command//"${p%%=*}"/"${p#*=}"}; done
  printf '%s' "$command"
}

# spawn COMMAND LOG: in the background, from the repository's root, as the leader of a process group
# of its own (its pid is $!), with Ctrl-C's default action as in a terminal: a script started in
# the background inherits SIGINT ignored, and rosbag play then fails on Ctrl-C with a TypeError.
spawn() {
  : > "$2"
  (cd "$REPO" && exec setsid env --default-signal=INT bash -c "$1") > "$2" 2>&1 &
}

# stop_group PID TARGET: Ctrl-C to TARGET (PID alone, or -PID: the whole process group PID leads,
# as a terminal's Ctrl-C), then a kill of what is left of the group after 30 s.
stop_group() {
  local waited=0
  kill -INT -- "$2" 2> /dev/null || true
  while kill -0 -- -"$1" 2> /dev/null && [ $waited -lt 60 ]; do
    sleep 0.5
    waited=$((waited + 1))
  done
  kill -KILL -- -"$1" 2> /dev/null || true
  wait "$1" 2> /dev/null || true
}

# background_output DIR: what a process that start or also left running shows: its console, and
# what ROS writes to files: the output of nodes with output="log" (rviz) and every node's log
# messages (rosout.log). Not the master's and roslaunch's own logs: their errors at shutdown are
# ROS's races (a node gone before the master told it of a topic change), never shown to a user.
background_output() {
  cat "$1/console.log"
  find "$1/log" \( -name '*-stdout.log' -o -name rosout.log \) -exec cat {} + 2> /dev/null || true
}

# Stops what start and also left running, the latest first; with "check", fails on its errors.
stop_background() {
  local k up
  for ((k = ${#BG_PIDS[@]} - 1; k >= 0; k--)); do
    up=$((SECONDS - BG_STARTED[k]))
    if [ "${1:-}" = check ] && [ $up -lt $MIN_UP ]; then sleep $((MIN_UP - up)); fi
    # Ctrl-C to the command alone: roslaunch stops its nodes itself, the master last.
    stop_group "${BG_PIDS[k]}" "${BG_PIDS[k]}"
    background_output "${BG_DIRS[k]}" > "${BG_DIRS[k]}/all.log"
    if [ "${1:-}" = check ] && grep -Eq "$FAILURE" "${BG_DIRS[k]}/all.log"; then
      grep -E "$FAILURE" "${BG_DIRS[k]}/all.log" | head -20 >&2
      BG_PIDS=("${BG_PIDS[@]:0:k}")
      fail "reported errors while it ran: ${BG_COMMANDS[k]}" "${BG_DIRS[k]}/all.log"
    fi
  done
  BG_PIDS=() BG_DIRS=() BG_COMMANDS=() BG_STARTED=()
}

# background_step I COMMAND: step I's command left running, once its output shows the patterns.
background_step() {
  local i=$1 command=$2 deadline=$((SECONDS + LIMITS[$1])) dir="$OUT/step$1" pid
  mkdir -p "$dir"
  ROS_HOME="$dir" ROS_LOG_DIR="$dir/log" spawn "$command" "$dir/console.log"
  pid=$!
  BG_PIDS+=("$pid") BG_DIRS+=("$dir") BG_COMMANDS+=("$command") BG_STARTED+=("$SECONDS")
  until background_output "$dir" | shows_all "${PATTERNS[i]}"; do
    background_output "$dir" > "$dir/all.log"
    ! grep -Eq "$FAILURE" "$dir/all.log" || fail "reported an error while starting: $command" \
      "$dir/all.log"
    kill -0 "$pid" 2> /dev/null || fail "ended before it showed what it must: $command" \
      "$dir/all.log"
    [ $SECONDS -lt $deadline ] || fail "did not show what it must within ${LIMITS[i]} s: $command" \
      "$dir/all.log"
    sleep 1
  done
}

# foreground_step I COMMAND: step I's command run (again) until it passes, as its kind says.
foreground_step() {
  local i=$1 command=$2 deadline=$((SECONDS + LIMITS[$1])) log="$OUT/step$1.log" pid status
  while :; do
    spawn "$command" "$log"
    pid=$!
    while kill -0 "$pid" 2> /dev/null && [ $SECONDS -lt $deadline ]; do
      if [ "${KINDS[i]}" = watch ] && shows_all "${PATTERNS[i]}" < "$log"; then break; fi
      sleep 0.5
    done
    if [ "${KINDS[i]}" = watch ]; then
      stop_group "$pid" -"$pid"
      shows_all "${PATTERNS[i]}" < "$log" && return 0
    else
      status=0
      kill -0 "$pid" 2> /dev/null && stop_group "$pid" -"$pid"  # over time
      wait "$pid" 2> /dev/null || status=$?
      [ $status -eq 0 ] && shows_all "${PATTERNS[i]}" < "$log" && return 0
    fi
    [ $SECONDS -lt $deadline ] || fail "did not show what it must within ${LIMITS[i]} s: $command" \
      "$log"
    sleep 1  # a user's second try
  done
}

free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("", 0)); print(s.getsockname()[1])'
}

pair_steps
if [ -z "${STOCS_DATASETS:-}" ] || [ ! -d "$STOCS_DATASETS/lmo-cat" ]; then
  fail "STOCS_DATASETS ('${STOCS_DATASETS:-}') must name the folder holding lmo-cat/"
fi
[ -f "$WS/devel/setup.bash" ] || fail "no catkin workspace at $WS: run scripts/build.sh first"
# One virtual display for every step: stopping a launch then never takes the display from its rviz.
if [ -z "${STOCS_README_XVFB:-}" ]; then
  STOCS_README_XVFB=1 exec xvfb-run -a -s "-screen 0 1280x800x24" "$0" "$@"
fi

rm -rf "$OUT"
mkdir -p "$OUT"
# "Your own configuration" of the live-camera example: the default one with the cat's model named
# by its path, as a configuration without a dataset to play names it.
sed "s|\$(dataset)|$STOCS_DATASETS/lmo-cat|" "$REPO/config/default.yaml" > "$OUT/objects.yaml"
trap stop_background EXIT
# Nodes' output as a terminal shows it, line by line, rather than in blocks when a file takes it;
# ROS's files of the foreground commands in the output folder.
export ROSCONSOLE_STDOUT_LINE_BUFFERED=1 PYTHONUNBUFFERED=1 ROS_HOME="$OUT/ros"
# Until a step starts a launch, no master: a command needing one fails instead of finding another's.
export ROS_MASTER_URI="http://localhost:$(free_port)"
passed=0 skipped=0
for i in "${!KINDS[@]}"; do
  command=$(as_written "${STEP_COMMAND[i]}")
  step_start=$SECONDS
  case ${KINDS[i]} in
    env)
      set +u  # setup.bash reads unset variables
      eval "$command" || fail "failed: $command"
      set -u
      ;;
    start)
      stop_background check
      export ROS_MASTER_URI="http://localhost:$(free_port)"
      background_step "$i" "$command"
      ;;
    also) background_step "$i" "$command" ;;
    run | watch) foreground_step "$i" "$command" ;;
    skip)
      echo "check_readme_ros: skipped (${PATTERNS[i]}): $command"
      skipped=$((skipped + 1))
      continue
      ;;
    *) fail "step $i has an unknown kind '${KINDS[i]}'" ;;
  esac
  echo "check_readme_ros: ok ($((SECONDS - step_start)) s): $command"
  passed=$((passed + 1))
done
stop_background check
echo "check_readme_ros: $passed passed, 0 failed, $skipped skipped"
