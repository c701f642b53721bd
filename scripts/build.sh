#!/usr/bin/env bash
# Builds stocs_ros as a catkin package in a workspace under build/ (the repository is the package).
# Extra arguments go to catkin_make, e.g. `scripts/build.sh tests`.
set -euo pipefail
source "$(dirname "$0")/common.sh"

mkdir -p "$WS/src" "$REPO/build"
touch "$REPO/build/CATKIN_IGNORE"  # never crawl the workspace from inside the package
ln -sfn "$REPO" "$WS/src/stocs_ros"
catkin_make -C "$WS" -j"$JOBS" -DCMAKE_BUILD_TYPE=Release "$@"
