#!/usr/bin/python3
"""Figures of issue 45 ("which object it is") from the runs of scripts/lookalike_baseline.sh.

  lookalike_metrics.py tabletop T.targets.csv... : absent targets whose look-alike is visible
      (models/lookalikes.json, scene_gt_info.json px_count_visib > 0) and the other absent ones,
      the share of each with no pose at t (score below t or none)
  lookalike_metrics.py eval EVAL.csv : the overall row of `stocs eval --csv` (the last "all" row)
  lookalike_metrics.py bin RESULTS.csv... : from `stocs estimate --instances N` results of packed
      bins (beside each, its dataset folder: RESULTS without .csv), the poses with score >= t of the
      bin's object: the share that are distinct right instances (ADD-S below 10% of the diameter,
      on the model file's vertices as `stocs eval` measures it, to an instance that no pose of
      higher score took), the share of the ground-truth instances found, absent targets posed (those
      with a visible look-alike apart), and the ROC AUC of the score of every pose (distinct right
      against the rest)
  lookalike_metrics.py binlog LOG... : the same from the logs of the runs, whose ADD-S is measured
      on the model's surface samples (more lenient for a box: a box turned by 38 degrees about its
      face normal can pass)
t is 0.25 (the default min_confidence) unless STOCS_T is set. Each targets CSV is `stocs eval --targets-csv`
of one dataset, beside its dataset folder (named in the CSV's dataset column).
"""
import csv
import json
import os
import re
import sys

import numpy as np

T = float(os.environ.get("STOCS_T", "0.25"))


def visible_objects(dataset, scene, im):
    """Object ids with a visible instance in the image."""
    folder = os.path.join(dataset, "test", "%06d" % scene)
    gt = json.load(open(os.path.join(folder, "scene_gt.json")))[str(im)]
    info = json.load(open(os.path.join(folder, "scene_gt_info.json")))[str(im)]
    return {g["obj_id"] for g, i in zip(gt, info) if i["px_count_visib"] > 0}


def lookalikes(dataset):
    pairs = json.load(open(os.path.join(dataset, "models", "lookalikes.json")))["pairs"]
    out = {}
    for a, b in pairs:
        out.setdefault(a, set()).add(b)
        out.setdefault(b, set()).add(a)
    return out


def tabletop(files):
    counts = {"fitting": [0, 0], "other": [0, 0]}  # [absent targets, without a pose at t]
    for name in files:
        for row in csv.DictReader(open(name)):
            dataset = os.path.join(os.path.dirname(name), row["dataset"])
            targets = json.load(open(os.path.join(dataset, "test_targets_bop19.json")))
            key = (int(row["scene_id"]), int(row["im_id"]), int(row["obj_id"]))
            inst = {(t["scene_id"], t["im_id"], t["obj_id"]): t["inst_count"] for t in targets}
            if inst[key] != 0:
                continue
            like = lookalikes(dataset).get(key[2], set())
            kind = "fitting" if like & visible_objects(dataset, key[0], key[1]) else "other"
            posed = row["found"] == "1" and float(row["score"]) >= T
            counts[kind][0] += 1
            counts[kind][1] += not posed
    for kind, (n, none) in counts.items():
        if n == 0:
            continue
        share = 100.0 * none / n if n else float("nan")
        print("absent %s: %d targets, %d without a pose at t=%.2f (%.1f%%)" % (kind, n, none, T, share))


LINE = re.compile(r"scene (\d+) image (\d+) object (\d+):")
POSE = re.compile(r"confidence ([0-9.]+)")
ADDS = re.compile(r"ADD-S [0-9.]+ mm \(([0-9.]+)% of diameter\) to instance (\d+)")
RECALL = re.compile(r"instance recall \d+ of (\d+)")


def poses_of(log):
    """Per (scene, image, object): the instances' lines (confidence, accepted, ADD-S %, index)."""
    targets, current = {}, None
    for line in open(log):
        head = LINE.search(line)
        if head:
            current = tuple(int(x) for x in head.groups())
            targets[current] = []
        if current is None or not (head or line.startswith("  instance ")):
            continue
        if line.startswith("  instance recall"):
            continue
        conf = POSE.search(line)
        if not conf:
            continue
        adds = ADDS.search(line)
        targets[current].append((float(conf.group(1)), "rejected:" not in line,
                                 float(adds.group(1)) if adds else None,
                                 int(adds.group(2)) if adds else None))
    return targets


def roc_auc(positive, negative):
    if not positive or not negative:
        return float("nan")
    wins = sum((p > n) + 0.5 * (p == n) for p in positive for n in negative)
    return wins / (len(positive) * len(negative))


def ply_vertices(path):
    """The vertices of an ASCII PLY (as `stocs synth` writes models), mm."""
    lines = open(path).read().split("\n")
    count = int(next(l for l in lines if l.startswith("element vertex")).split()[2])
    start = lines.index("end_header") + 1
    return np.array([[float(x) for x in l.split()[:3]] for l in lines[start:start + count]])


def adds(points, est, truth):
    """ADD-S of pose est=(R, t) against truth=(R, t) over the model points."""
    a = points @ est[0].T + est[1]
    b = points @ truth[0].T + truth[1]
    return np.sqrt(((a[:, None, :] - b[None, :, :]) ** 2).sum(-1)).min(1).mean()


def results_as_poses(csv_file):
    """Per (scene, image, object) of a results file: (score, R, t, None, None) rows."""
    poses = {}
    for r in csv.DictReader(open(csv_file)):
        key = (int(r["scene_id"]), int(r["im_id"]), int(r["obj_id"]))
        R = np.array([float(x) for x in r["R"].split()]).reshape(3, 3)
        t = np.array([float(x) for x in r["t"].split()])
        poses.setdefault(key, []).append((float(r["score"]), R, t))
    return poses


def label_poses(dataset, key, poses):
    """(score, accepted, ADD-S % of the diameter, nearest instance) of each pose, as poses_of()."""
    scene, im, obj = key
    folder = os.path.join(dataset, "test", "%06d" % scene)
    truth = [g for g in json.load(open(os.path.join(folder, "scene_gt.json")))[str(im)]]
    points = ply_vertices(os.path.join(dataset, "models", "obj_%06d.ply" % obj))
    diameter = json.load(open(os.path.join(dataset, "models", "models_info.json")))[str(obj)]["diameter"]
    out = []
    for score, R, t in poses:
        errors = [(adds(points, (R, t), (np.array(g["cam_R_m2c"]).reshape(3, 3), np.array(g["cam_t_m2c"]))), k)
                  for k, g in enumerate(truth) if g["obj_id"] == obj]
        best = min(errors) if errors else (None, None)
        out.append((score, True, None if best[0] is None else 100 * best[0] / diameter, best[1]))
    return out


def bin_results(files):
    per_file = {}
    for name in files:
        dataset = re.sub(r"\.csv$", "", name)
        poses = results_as_poses(name)
        targets = json.load(open(os.path.join(dataset, "test_targets_bop19.json")))
        keys = [(t["scene_id"], t["im_id"], t["obj_id"]) for t in targets]  # a target may have none
        per_file[dataset] = {k: label_poses(dataset, k, poses.get(k, [])) for k in keys}
    bins_of(per_file)


def bin_logs(logs):
    bins_of({re.sub(r"\.log$", "", log): poses_of(log) for log in logs})


def bins_of(per_dataset):
    published = distinct = instances = found = 0
    absent = {"fitting": [0, 0], "other": [0, 0]}  # [absent targets, posed at t]
    positive, negative = [], []
    for dataset, targets in per_dataset.items():
        for (scene, im, obj), poses in targets.items():
            truth = json.load(open(os.path.join(dataset, "test", "%06d" % scene, "scene_gt.json")))
            count = sum(g["obj_id"] == obj for g in truth[str(im)])
            if count == 0:
                like = lookalikes(dataset).get(obj, set())
                kind = "fitting" if like & visible_objects(dataset, scene, im) else "other"
                absent[kind][0] += 1
                absent[kind][1] += any(c >= T for c, _, _, _ in poses)
                negative += [c for c, _, _, _ in poses]
                continue
            instances += count
            taken = set()
            for c, accepted, adds, k in sorted(poses, key=lambda p: -p[0]):
                right = adds is not None and adds < 10 and k not in taken
                if right:
                    taken.add(k)
                (positive if right else negative).append(c)
                if c >= T and accepted:
                    published += 1
                    distinct += right
            found += len({k for c, a, adds, k in poses if c >= T and a and adds is not None and adds < 10})
    print("bin: %d published poses, %d distinct right (%.1f%%); %d of %d instances found (%.1f%%)"
          % (published, distinct, 100.0 * distinct / max(published, 1), found, instances,
             100.0 * found / max(instances, 1)))
    for kind, (n, posed) in absent.items():
        print("bin: absent %s targets posed at t: %d of %d" % (kind, posed, n))
    print("bin: confidence ROC AUC over every pose (distinct right against the rest): %.3f"
          % roc_auc(positive, negative))


def overall(files):
    rows = [r for r in csv.DictReader(open(files[0])) if r["object"] == "all"]
    r = rows[-1]
    print("eval: %s present targets, %s absent; ROC AUC %.3f, calibration error %.3f, absent posed "
          "at t %.1f%%, right poses rejected at t %.1f%%" % (
              r["targets"], r["absent_targets"], float(r["score_roc_auc"]), float(r["ece"]),
              100 * float(r["absent_posed_at_t"]), 100 * float(r["correct_rejected_at_t"])))


if __name__ == "__main__":
    modes = {"tabletop": tabletop, "bin": bin_results, "binlog": bin_logs, "eval": overall}
    if len(sys.argv) < 3 or sys.argv[1] not in modes:
        sys.exit(__doc__)
    modes[sys.argv[1]](sys.argv[2:])
