#!/usr/bin/python3
"""Figures of issue 45 ("which object it is") from the runs of scripts/lookalike_baseline.sh.

  lookalike_metrics.py tabletop T.targets.csv... : absent targets whose look-alike is visible
      (models/lookalikes.json, scene_gt_info.json px_count_visib > 0) and the other absent ones,
      the share of each with no pose at t (score below t or none)
  lookalike_metrics.py eval EVAL.csv : the overall row of `stocs eval --csv` (the last "all" row)
  lookalike_metrics.py bin LOG... : from `stocs estimate --instances N` logs of packed bins, the
      published poses (confidence >= t) of the bin's object: the share that are distinct right
      instances (ADD-S below 10% of the diameter of an instance no higher pose took), the share of
      the ground-truth instances found, and the ROC AUC of the confidence of every pose written
      (distinct right against the rest); absent targets' poses are counted apart.
t is 0.35 (min_confidence) unless STOCS_T is set. Each targets CSV is `stocs eval --targets-csv`
of one dataset, beside its dataset folder (named in the CSV's dataset column).
"""
import csv
import json
import os
import re
import sys

T = float(os.environ.get("STOCS_T", "0.35"))


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


def bins(logs):
    published = distinct = instances = found = absent_posed = absent = 0
    positive, negative = [], []
    for log in logs:
        dataset = re.sub(r"\.log$", "", log)
        for (scene, im, obj), poses in poses_of(log).items():
            truth = json.load(open(os.path.join(dataset, "test", "%06d" % scene, "scene_gt.json")))
            count = sum(g["obj_id"] == obj for g in truth[str(im)])
            if count == 0:
                absent += 1
                absent_posed += any(c >= T for c, _, _, _ in poses)
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
    print("bin: absent targets posed at t: %d of %d; confidence ROC AUC over every pose "
          "(distinct right against the rest): %.3f" % (absent_posed, absent, roc_auc(positive, negative)))


def overall(files):
    rows = [r for r in csv.DictReader(open(files[0])) if r["object"] == "all"]
    r = rows[-1]
    print("eval: %s present targets, %s absent; ROC AUC %.3f, calibration error %.3f, absent posed "
          "at t %.1f%%, right poses rejected at t %.1f%%" % (
              r["targets"], r["absent_targets"], float(r["score_roc_auc"]), float(r["ece"]),
              100 * float(r["absent_posed_at_t"]), 100 * float(r["correct_rejected_at_t"])))


if __name__ == "__main__":
    modes = {"tabletop": tabletop, "bin": bins, "eval": overall}
    if len(sys.argv) < 3 or sys.argv[1] not in modes:
        sys.exit(__doc__)
    modes[sys.argv[1]](sys.argv[2:])
