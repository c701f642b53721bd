#!/usr/bin/env bash
# The main job until the self-contained demo exists: installs dependencies, builds, and runs
# `stocs estimate` on a BOP dataset you give, printing per-object poses and errors.
#   scripts/estimate.sh DATASET_DIR [more stocs estimate options]
set -euo pipefail
source "$(dirname "$0")/common.sh"
if [ $# -lt 1 ] || [ ! -d "$1" ]; then
  echo "usage: $0 DATASET_DIR [stocs estimate options]   (a BOP dataset with prob/ maps)" >&2
  exit 2
fi
dataset=$1
shift
"$REPO/scripts/install_deps.sh"
"$REPO/scripts/build.sh" > "$REPO/build/build.log" 2>&1 || { tail -50 "$REPO/build/build.log"; exit 1; }
out="$REPO/build/results/$(basename "$dataset").csv"
mkdir -p "$(dirname "$out")"
"$WS/devel/lib/stocs_ros/stocs" estimate --dataset "$dataset" --out "$out" "$@"
