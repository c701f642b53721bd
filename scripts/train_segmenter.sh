#!/usr/bin/env bash
# Trains a segmentation network (training/train_segmenter.py) on scenes from `stocs synth`.
#   scripts/train_segmenter.sh [OUT.onnx]
#     the package's network, of the project's six meshes: writes models/segmenter.onnx byte for
#     byte (models/README.md). CI never runs this: it loads the committed file.
#   scripts/train_segmenter.sh --models DIR --out FILE.onnx
#     a network of your own meshes: DIR is a BOP models folder (obj_*.ply meshes with faces in mm,
#     models_info.json). Writes FILE.onnx and beside it FILE.yaml, its settings, which
#     `launch/segmentation.launch config:=FILE.yaml` and `stocs estimate --prob onnx:FILE.yaml` take
#     as they are (channel k is named obj_00000k, after obj_id k's model file: name the StoCS
#     node's objects so, or edit `channels`).
#   STOCS: the `stocs` tool (default: the catkin workspace's).
#   STOCS_TRAIN_THREADS: torch threads, default 1, which trains fastest on a machine others use;
#   STOCS_TRAIN_MINUTES: training time limit, default 25 (the committed file needs all 60 epochs).
#   Runs under `nice`.
set -euo pipefail
source "$(dirname "$0")/common.sh"

OUT="$REPO/models/segmenter.onnx"
MODELS=""
usage() {
  echo "usage: $0 [OUT.onnx] | --models DIR --out FILE.onnx" >&2
  exit 2
}
while [ $# -gt 0 ]; do
  case "$1" in
    --models) [ $# -ge 2 ] || usage; MODELS=$(realpath "$2"); shift 2 ;;
    --out) [ $# -ge 2 ] || usage; OUT=$2; shift 2 ;;
    -*) usage ;;
    *) OUT=$1; shift ;;
  esac
done
CLASSES=7
MODEL_OPTIONS=()
if [ -n "$MODELS" ]; then
  [ -f "$MODELS/models_info.json" ] || { echo "$0: $MODELS has no models_info.json" >&2; exit 2; }
  [ "$OUT" != "$REPO/models/segmenter.onnx" ] || usage
  # Channel k is obj_id k: as many classes as the largest obj_id and the background.
  CLASSES=$(/usr/bin/python3 -c 'import json, sys
print(max(int(k) for k in json.load(open(sys.argv[1]))) + 1)' "$MODELS/models_info.json")
  MODEL_OPTIONS=(--models "$MODELS")
fi
DATA="$REPO/build/segmenter_training"
STOCS="${STOCS:-$WS/devel/lib/stocs_ros/stocs}"

# Training only: Debian's PyTorch and ONNX exporter (not in install_deps.sh, which CI runs).
TRAINING_PACKAGES=(python3-torch python3-onnx python3-pil python3-numpy)
missing=()
for p in "${TRAINING_PACKAGES[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  SUDO=""
  if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
[ -x "$STOCS" ] || "$REPO/scripts/build.sh"

# Training seeds 1001-1006, validation seeds 2001-2003: the scenes of seeds 1-140 (tests, demo,
# measurements, calibration) stay unseen. Six mixes: crowding, distractors and views (closer,
# farther, lower and higher than the defaults) in the default look, every distractor a look-alike,
# and varied light, tables and backgrounds. The recipe (these sets, 60 epochs, a Dice loss beside
# the cross entropy, the epoch with the best validation score exported) scored best of eleven on
# the validation sets' lowest per-object F1 (docs/simulator.md).
rm -rf "$DATA"
mkdir -p "$DATA"
synth() { nice -n 10 "$STOCS" synth --quiet --absent 0 --segmentation clean "${MODEL_OPTIONS[@]}" "$@"; }
WIDE=(--min-distance 0.45 --max-distance 1.1 --min-elevation 20 --max-elevation 85)
VARIED=(--light-direction 45 --light-intensity 0.35 --light-colour 0.12 --backgrounds true)
synth --out "$DATA/a" --seed 1001 --scenes 40 --images 3 --objects 4 --distractors 3 "${WIDE[@]}"
synth --out "$DATA/b" --seed 1002 --scenes 30 --images 3 --objects 6 --distractors 2
synth --out "$DATA/c" --seed 1003 --scenes 20 --images 3 --objects 2 --distractors 5 \
  --min-distance 0.5 --max-distance 1.0
synth --out "$DATA/d" --seed 1004 --scenes 30 --images 3 --objects 6 --distractors 4
synth --out "$DATA/lookalikes" --seed 1005 --scenes 30 --images 3 --objects 6 --distractors 3 \
  --lookalike-share 1
synth --out "$DATA/varied" --seed 1006 --scenes 50 --images 3 --objects 6 --distractors 3 \
  "${WIDE[@]}" "${VARIED[@]}" --lookalike-share 0.8
# Validation: the demo's and the tests' kind of scene in the default look, varied looks, and
# every distractor a look-alike.
synth --out "$DATA/val_default" --seed 2001 --scenes 20 --images 3 --objects 6 --distractors 2
synth --out "$DATA/val_varied" --seed 2002 --scenes 15 --images 3 --objects 6 --distractors 3 \
  "${WIDE[@]}" "${VARIED[@]}" --lookalike-share 0.8
synth --out "$DATA/val_lookalikes" --seed 2003 --scenes 15 --images 3 --objects 4 \
  --distractors 3 "${WIDE[@]}" --lookalike-share 1

mkdir -p "$(dirname "$OUT")"
OMP_NUM_THREADS="${STOCS_TRAIN_THREADS:-1}" nice -n 10 /usr/bin/python3 \
  "$REPO/training/train_segmenter.py" --out "$OUT" \
  --data "$DATA"/{a,b,c,d,varied,lookalikes} --epochs 60 --dice 1 --export best \
  --val "$DATA"/{val_default,val_varied,val_lookalikes} \
  --seed 1 --threads "${STOCS_TRAIN_THREADS:-1}" --minutes "${STOCS_TRAIN_MINUTES:-25}" \
  --classes "$CLASSES"
[ -n "$MODELS" ] || exit 0

# The settings beside the network: the package network's (config/segmenter.yaml) with this file's
# absolute path (the node resolves a relative one against its working folder), its classes, and its
# channels named after the model files (ROS topic names cannot begin with a digit).
settings="${OUT%.onnx}.yaml"
channels=$(/usr/bin/python3 -c 'import json, sys
ids = {int(k) for k in json.load(open(sys.argv[1]))}
print(", ".join(f"obj_{k:06d}" if k in ids else "\"-\"" for k in range(max(ids) + 1)))' \
  "$MODELS/models_info.json")
{
  echo "# Trained by scripts/train_segmenter.sh --models $MODELS on $(date -u +%F)."
  echo "model: $(realpath "$OUT")"
  sed -n '/^input_width:/,/^classes:/p' "$REPO/config/segmenter.yaml" | grep -v '^classes:'
  echo "classes: $CLASSES"
  echo "# Channel k is obj_id k of $MODELS, named as its model file (obj_00000k.ply)."
  echo "channels: [$channels]"
  echo "threads: 0"
} > "$settings"
echo "train_segmenter: wrote $OUT and $settings"
