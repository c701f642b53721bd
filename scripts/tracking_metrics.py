#!/usr/bin/env python3
"""Issue 30's tracking figures of one generated sequence (stocs synth --sequence), from the files of
two runs on it: tracking (stocs estimate --track true) and detecting every frame.

  tracking_metrics.py --scene DIR --track-results R.csv --track-targets T.csv
                      --track-objects O.csv [--detect-targets T2.csv] [--frames-out FRAMES.dat]

DIR: the scene's folder (scene_events.json, scene_gt.json: which objects each frame holds).
R.csv: the tracking run's BOP results (`time`: the frame's wall time, depth-to-cloud conversion
and every object, which follow their tracks in parallel); T.csv, T2.csv: `stocs eval
--targets-csv` (one row per target with its ADD-S); O.csv: `stocs estimate --per-object` of the
tracking run (each object's CPU seconds and hypotheses). Prints one
`key value` line per figure; --frames-out writes per frame: frame, wall and CPU time (ms), median and largest
ADD-S (% of the diameter) of the present objects (a missing pose counts as 100%), for the plot.
"""
import argparse
import csv
import json
import math
import statistics


def quantile(values, q):
    """Linear interpolation between the order statistics (as stocs's quantile)."""
    v = sorted(values)
    if not v:
        return math.nan
    at = q * (len(v) - 1)
    low = math.floor(at)
    high = min(low + 1, len(v) - 1)
    return v[low] + (v[high] - v[low]) * (at - low)


def read_targets(path, truth):
    """{(im_id, obj_id): (present, found, adds / diameter, success)} of the file's one scene;
    `truth`: scene_gt.json."""
    out = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            im, obj = int(row["im_id"]), int(row["obj_id"])
            present = any(g["obj_id"] == obj for g in truth[str(im)])
            error = float(row["adds_mm"]) / float(row["diameter_mm"])
            out[(im, obj)] = (
                present, row["found"] == "1", error, row["adds_success"] == "1")
    return out


def frame_walls(path):
    """Per frame with a result row: its wall seconds."""
    with open(path) as f:
        return {int(row["im_id"]): float(row["time"]) for row in csv.DictReader(f)}


def frame_cpus(path):
    """Per frame: CPU seconds of all its objects, and whether every one was only followed (no StoCS
    search ran: 0 hypotheses)."""
    cpu, followed = {}, {}
    with open(path) as f:
        for row in csv.DictReader(f):
            im = int(row["im_id"])
            cpu[im] = cpu.get(im, 0.0) + float(row["cpu_seconds"])
            followed[im] = followed.get(im, True) and int(row["hypotheses"]) == 0
    return cpu, followed


def print_times(name, seconds, frames):
    ms = [1000 * seconds[im] for im in frames if im in seconds]
    print(f"{name}_median_ms {quantile(ms, 0.5):.2f}")
    print(f"{name}_p95_ms {quantile(ms, 0.95):.2f}")


def success(targets):
    present = [t for t in targets.values() if t[0]]
    return sum(t[3] for t in present) / len(present)


def median_error(targets, frames):
    return statistics.median(t[2] for (im, _), t in targets.items() if t[0] and im in frames)


def removal_and_return(targets, event, frames):
    """Of the removal: the frames from its first with a pose still (the track not yet lost), the
    later frames of it with a pose again (a detection elsewhere: the map's confusion), and the
    frame of the return, counting the first frame back as 1, at which the object was first posed
    correctly (inf: never)."""
    obj, first, last = event["obj_id"], event["first_frame"], event["last_frame"]
    posed = [targets[(im, obj)][1] for im in range(first, last + 1)]
    stale = posed.index(False) if False in posed else len(posed)
    back = [im for im in range(last + 1, frames) if targets[(im, obj)][3]]
    return stale, sum(posed[stale:]), back[0] - last if back else math.inf


def per_frame(targets, wall, cpu, frames):
    """frame, wall and CPU ms, median and largest ADD-S in % of the diameter (missing: 100)."""
    rows = []
    for im in range(frames):
        errors = [min(100.0, 100 * t[2]) for (i, _), t in targets.items() if i == im and t[0]]
        rows.append((im, 1000 * wall.get(im, math.nan), 1000 * cpu.get(im, math.nan),
                     statistics.median(errors), max(errors)))
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--scene", required=True)
    p.add_argument("--track-results", required=True)
    p.add_argument("--track-targets", required=True)
    p.add_argument("--track-objects", required=True)
    p.add_argument("--detect-targets", help="without it, no comparison with detection")
    p.add_argument("--frames-out")
    a = p.parse_args()
    events = json.load(open(f"{a.scene}/scene_events.json"))
    truth = json.load(open(f"{a.scene}/scene_gt.json"))
    frames = len(events["stamps"])
    track = read_targets(a.track_targets, truth)
    wall = frame_walls(a.track_results)
    cpu, followed = frame_cpus(a.track_objects)
    followed_frames = [im for im in cpu if followed[im]]
    print(f"frames {frames} (with a result row: {len(wall)})")
    print_times("wall_all_frames", wall, cpu.keys())
    print_times("cpu_all_frames", cpu, cpu.keys())
    print(f"frames_all_followed {len(followed_frames)}")
    print_times("wall_all_followed", wall, followed_frames)
    print_times("cpu_all_followed", cpu, followed_frames)
    print(f"success_tracking {100 * success(track):.1f}")
    detect = read_targets(a.detect_targets, truth) if a.detect_targets else None
    if detect:
        print(f"success_detection {100 * success(detect):.1f}")
    first, last = set(range(50)), set(range(frames - 50, frames))
    print(f"drift_first50_median_adds_pct {100 * median_error(track, first):.2f}")
    print(f"drift_last50_median_adds_pct {100 * median_error(track, last):.2f}")
    if detect:  # the same medians of detection, which cannot drift: what the views change
        print(f"detection_first50_median_adds_pct {100 * median_error(detect, first):.2f}")
        print(f"detection_last50_median_adds_pct {100 * median_error(detect, last):.2f}")
    last = [t for (im, _), t in track.items() if im == frames - 1 and t[0]]
    print(f"last_frame_correct {sum(t[3] for t in last)} of {len(last)}")
    for event in events["events"]:
        if event["kind"] != "removal":
            continue
        runs = [("tracking", track)] + ([("detection", detect)] if a.detect_targets else [])
        for name, targets in runs:
            stale, false_poses, back = removal_and_return(targets, event, frames)
            print(f"removal_{name} obj {event['obj_id']}: posed in the first {stale} frames out, "
                  f"{false_poses} later frames out posed elsewhere, correct at frame {back} back")
    if a.frames_out:
        with open(a.frames_out, "w") as f:
            f.write("# frame wall_ms cpu_ms median_adds_pct max_adds_pct\n")
            for row in per_frame(track, wall, cpu, frames):
                f.write("{} {:.3f} {:.3f} {:.2f} {:.2f}\n".format(*row))


if __name__ == "__main__":
    main()
