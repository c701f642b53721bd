#!/usr/bin/env bash
# Runs `stocs estimate` with seeds 1..N on BOP frames and prints one markdown row per frame: ADD-S
# (median, max), success (ADD-S < 10% of the diameter) and time per object (median, max). Frames are
# DATASET:SCENE, DATASET relative to STOCS_DATASETS or absolute; by default the two real-map frames
# (LM-O cat; packed bin scene 0, dove). Extra arguments go to every `stocs estimate`.
#   STOCS_DATASETS=../shared/datasets scripts/bench_real_frames.sh [--seeds N] [--frame D:S]... [stocs options]
set -euo pipefail
source "$(dirname "$0")/common.sh"
seeds=10
frames=()
while [ $# -gt 0 ]; do
  case "$1" in
    --seeds) seeds=$2; shift 2 ;;
    --frame) frames+=("$2"); shift 2 ;;
    *) break ;;
  esac
done
[ ${#frames[@]} -gt 0 ] || frames=("lmo-cat:2" "rutgers-packed:0")
data="${STOCS_DATASETS:-}"
tool="${STOCS_TOOL:-$WS/devel/lib/stocs_ros/stocs}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

echo "| frame | seeds | ADD-S median / max (mm) | ADD-S median (% diam.) | success < 10% diam. | time per object median / max (s) |"
echo "|---|---|---|---|---|---|"
for frame in "${frames[@]}"; do
  dir=${frame%:*} scene=${frame##*:}
  case "$dir" in /*) ;; *) dir="${data:?set STOCS_DATASETS for relative frames}/$dir" ;; esac
  name=$(basename "$dir")
  : > "$tmp/lines"
  for seed in $(seq 1 "$seeds"); do
    "$tool" estimate --dataset "$dir" --scenes "$scene" --out "$tmp/r.csv" --cache-dir "$tmp/cache" \
      --seed "$seed" "$@" 2>&1 | grep "ADD-S" >> "$tmp/lines" || true
  done
  awk -v name="$name" -v seeds="$seeds" '
    { for (i = 1; i <= NF; i++) {
        if ($i == "ADD-S") { adds[n] = $(i + 1); pct[n] = substr($(i + 3), 2) + 0 }
        if ($i == "s,") time[n] = $(i - 1)
      }
      n++ }
    function median(a, k,   s, i, j, t) { for (i = 0; i < k; i++) s[i] = a[i];
      for (i = 0; i < k; i++) for (j = i + 1; j < k; j++) if (s[j] < s[i]) { t = s[i]; s[i] = s[j]; s[j] = t }
      return k % 2 ? s[int(k / 2)] : (s[k / 2 - 1] + s[k / 2]) / 2 }
    function maximum(a, k,   i, m) { m = a[0]; for (i = 1; i < k; i++) if (a[i] > m) m = a[i]; return m }
    END { ok = 0; for (i = 0; i < n; i++) ok += pct[i] < 10;
      printf "| %s | %d | %.1f / %.1f | %.1f%% | %d/%d | %.3f / %.3f |\n", name, seeds, median(adds, n),
        maximum(adds, n), median(pct, n), ok, seeds, median(time, n), maximum(time, n) }' "$tmp/lines"
done
