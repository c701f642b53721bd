#!/usr/bin/env bash
# Builds stocs_ros as a catkin package in the workspace $WS (default: <checkout>_ws beside the
# checkout; the repository is the package, linked in as src/stocs_ros).
# Extra arguments go to catkin_make, e.g. `scripts/build.sh tests`.
set -euo pipefail
source "$(dirname "$0")/common.sh"

mkdir -p "$WS/src" "$REPO/build"
touch "$REPO/build/CATKIN_IGNORE"  # never crawl build trees from inside the package
ln -sfn "$REPO" "$WS/src/stocs_ros"
catkin_make -C "$WS" -j"$JOBS" -DCMAKE_BUILD_TYPE=Release "$@"
