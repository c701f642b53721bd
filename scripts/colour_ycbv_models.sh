#!/usr/bin/env bash
# Colours the YCB-Video point models of ycbv-0000 (which carry no colour) from frames 1 and 2 at
# their ground-truth poses (`stocs colour-models`), leaving frames 3..5, the ones results are
# reported on, unseen. Writes OUT/models (coloured PLYs, models_info.json) and links OUT/test to
# the dataset's, so that OUT is a dataset with coloured models.
#   scripts/colour_ycbv_models.sh TOOL DATASETS OUT   (TOOL: a built `stocs`, DATASETS: the folder
#                                                     holding ycbv-0000/)
set -euo pipefail

if [ $# -ne 3 ]; then
  sed -n '2,7p' "$0" >&2
  exit 2
fi
tool=$1 data=$2/ycbv-0000 out=$3
"$tool" colour-models --dataset "$data" --images 0/1,0/2 --out "$out"
ln -sfn "$(cd "$data" && pwd)/test" "$out/test"
