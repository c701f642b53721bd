#!/usr/bin/env bash
# Reproduces the `stocs bench` / `stocs eval` figures of BENCHMARKS.md. Builds nothing: runs the
# `stocs` tool given by STOCS_TOOL (default: the catkin workspace's, from scripts/build.sh).
#   scripts/bench_all.sh DATASETS OUT        e.g. scripts/bench_all.sh ../shared/datasets /tmp/bench
# OUT receives:
#   real/    every method on every dataset with its real network maps (only lmo-cat and
#            rutgers-packed scene 0 have them; the others are skipped with a note), with the
#            segmentation-threshold sweep (0.3 to 0.9: below 0.3 the cat's segment is most of the
#            image and PCL's K4PCS takes too long per object) and the time-budget sweep
#   sim/     every method on every dataset with simulator maps where no real map exists
#            (presets mild and noisy, all frames), main table only, at most 10 s per object
#            (`--time-budget 10`: never reached by StoCS at 100 bases; PCL's 4PCS stops after the
#            base that passes it; OpenCV's PPF has no budget)
#   seeds/   StoCS with seeds 1..10, ICP on and off (`stocs estimate` + `stocs eval`), on the two
#            real-map frames and on a generated frame with exact truth (`stocs synth`, clean
#            segmentation, noise-free depth), and the dove bin without its boundary map;
#            summarised in seeds/summary.md
#   equal/   issue 6's side by side at equal accuracy: every method at its defaults beside StoCS at
#            2, 3, 4, 5, 10, 20, 50 and 100 bases (`--base-counts`), on the real maps (real/: all seven
#            methods, both StoCS variants swept) and on the simulator presets of lmo-cat,
#            rutgers-packed and ycbv-0000 (sim/: StoCS swept beside PPF, the fastest baseline; the
#            4PCS methods are too slow to sweep on these presets, see sim/ above); every image is
#            processed 5 times and times are medians (`--repeats 5`); each report's "Speed at equal
#            or better accuracy" table gives the ratios
# and log.txt with the load average before and after each part. STOCS_BENCH_PARTS selects parts
# (default "real sim seeds equal"), e.g. to finish an interrupted run into the same OUT.
set -euo pipefail
source "$(dirname "$0")/common.sh"
[ $# -eq 2 ] || { echo "usage: $0 DATASETS OUT" >&2; exit 2; }
data=$(cd "$1" && pwd)
out=$2
tool="${STOCS_TOOL:-$WS/devel/lib/stocs_ros/stocs}"
[ -x "$tool" ] || { echo "no stocs tool at $tool (build it, or set STOCS_TOOL)" >&2; exit 2; }
for d in lmo-cat rutgers-packed ycbv-0000 pcl-milk; do
  [ -d "$data/$d" ] || { echo "$data/$d is missing" >&2; exit 2; }
done
mkdir -p "$out"
log="$out/log.txt"
note() { echo "$(date -u '+%F %T') load $(cut -d' ' -f1-3 /proc/loadavg): $*" | tee -a "$log"; }

datasets=(--dataset "$data/lmo-cat" --dataset "$data/rutgers-packed" --dataset "$data/ycbv-0000"
          --dataset "$data/pcl-milk")
# One model cache for all parts, so that no run pays for preprocessing; a run (one method on one
# dataset and source) that takes over 5 minutes is killed and its targets count as missing.
common=(--methods stocs,stocs-hard,fpcs,kfpcs,ppf,o3d-ransac,o3d-fgr --cache-dir "$out/cache"
        --run-timeout 300)

parts=" ${STOCS_BENCH_PARTS:-real sim seeds equal} "

if [[ $parts == *" real "* ]]; then
  note "real maps: start"
  "$tool" bench "${datasets[@]}" --prob real --out "$out/real" "${common[@]}" \
    --thresholds 0.3,0.5,0.7,0.9 --budgets 0.1,0.5,1 --no-bases-sweep
  note "real maps: done"
fi

if [[ $parts == *" sim "* ]]; then
  note "simulator presets: start"
  "$tool" bench "${datasets[@]}" --prob sim:mild --prob sim:noisy --out "$out/sim" \
    --no-threshold-sweep --no-budget-sweep --no-bases-sweep --time-budget 10 "${common[@]}"
  note "simulator presets: done"
fi

if [[ $parts == *" equal "* ]]; then
  note "equal accuracy: start"
  # Every image 5 times in a row, times the medians (`--repeats`): at a few bases StoCS takes
  # milliseconds per object, and single runs that short vary too much from run to run.
  swept=(--no-threshold-sweep --no-budget-sweep --base-counts 2,3,4,5,10,20,50,100 --cache-dir "$out/cache"
         --run-timeout 300 --repeats 5)
  "$tool" bench --dataset "$data/lmo-cat" --dataset "$data/rutgers-packed" --prob real \
    --methods stocs,stocs-hard,fpcs,kfpcs,ppf,o3d-ransac,o3d-fgr --sweep-methods stocs,stocs-hard \
    "${swept[@]}" --out "$out/equal/real"
  "$tool" bench --dataset "$data/lmo-cat" --dataset "$data/rutgers-packed" \
    --dataset "$data/ycbv-0000" --prob sim:mild --prob sim:noisy --methods stocs,ppf \
    --sweep-methods stocs --time-budget 10 "${swept[@]}" --out "$out/equal/sim"
  note "equal accuracy: done"
fi

[[ $parts == *" seeds "* ]] || exit 0

# StoCS's spread over seeds: one `stocs estimate` per seed, scored by `stocs eval`; per-object
# times come from --per-object. A row per frame and setting: ICP on (the default) and off, and the
# dove bin without its boundary map.
note "seeds: start"
seeds="$out/seeds"
mkdir -p "$seeds"
generated="$seeds/generated"
rm -rf "$generated"
"$tool" synth --out "$generated" --objects 4 --distractors 0 --depth-noise 0 \
  --segmentation clean --seed 1 --quiet
summary="$seeds/summary.md"
echo "| frame | setting | targets (seeds x objects) | ADD-S median / max (mm) | ADD-S < 10% diam. | < 2 cm, 10° | time median / max (s) | CPU median (s) |" > "$summary"
echo "|---|---|---|---|---|---|---|---|" >> "$summary"

# seedRow DATASET SCENE SETTING [stocs estimate options...]: seeds 1..10, one summary row.
seedRow() {
  local dir=$1 scene=$2 setting=$3
  shift 3
  local name run seed
  name=$(basename "$dir")
  run="$seeds/$name-${setting// /-}"
  mkdir -p "$run"
  for seed in $(seq 1 10); do
    "$tool" estimate --dataset "$dir" --scenes "$scene" --prob real --seed "$seed" \
      --cache-dir "$out/cache" --out "$run/$seed.csv" --per-object "$run/$seed.objects.csv" \
      "$@" 2> "$run/$seed.log"
    "$tool" eval --dataset "$dir" --results "$run/$seed.csv" --prob real \
      --targets-csv "$run/$seed.targets.csv" --markdown "$run/$seed.md" 2>> "$run/$seed.log"
  done
  # Columns by name: targets.csv (errors) and objects.csv (times), one row per target each.
  awk -F, -v frame="$name" -v setting="$setting" '
    FNR == 1 { for (i = 1; i <= NF; i++) col[FILENAME, $i] = i; next }
    FILENAME ~ /targets.csv$/ { adds[na++] = $col[FILENAME, "adds_mm"];
      ok += $col[FILENAME, "adds_success"]; rt += $col[FILENAME, "rt_success"] }
    FILENAME ~ /objects.csv$/ { t[nt++] = $col[FILENAME, "seconds"]; c[nc++] = $col[FILENAME, "cpu_seconds"] }
    function sorted(a, n,   i, j, x) { for (i = 1; i < n; i++) { x = a[i];
        for (j = i - 1; j >= 0 && a[j] > x; j--) a[j + 1] = a[j]; a[j + 1] = x } }
    function median(a, n) { sorted(a, n); return n % 2 ? a[int(n / 2)] : (a[n / 2 - 1] + a[n / 2]) / 2 }
    function maximum(a, n) { sorted(a, n); return a[n - 1] }
    END { printf "| %s | %s | %d | %.1f / %.1f | %d/%d | %d/%d | %.3f / %.3f | %.3f |\n",
            frame, setting, na, median(adds, na), maximum(adds, na), ok, na, rt, na,
            median(t, nt), maximum(t, nt), median(c, nc) }' \
    "$run"/*.targets.csv "$run"/*.objects.csv >> "$summary"
}

for frame in "$data/lmo-cat:2" "$data/rutgers-packed:0" "$generated:0"; do
  seedRow "${frame%:*}" "${frame##*:}" "ICP on" --icp true
  seedRow "${frame%:*}" "${frame##*:}" "ICP off" --icp false
done
seedRow "$data/rutgers-packed" 0 "no boundary map" --boundaries off
note "seeds: done"
cat "$summary"
echo "reports: $out/real/results.md, $out/sim/results.md, $summary"
