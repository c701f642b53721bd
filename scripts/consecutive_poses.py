#!/usr/bin/env python3
"""Issue 43's steadiness of published poses on one generated sequence (stocs synth --sequence):
per object, the pairs of consecutive frames whose published pose differs from the previous one
moved as the object truly moved by more than 5% of the diameter, by ADD over the model file's
vertices (so a declared symmetry's jump counts).

  consecutive_poses.py DATASET RESULTS.csv

DATASET: the sequence's folder (models/, test/000000/scene_gt.json); RESULTS.csv: the BOP results
of `stocs estimate --track true` on it (the highest-scoring row per frame and object is the
published pose). Pairs count where both frames have a pose and the ground truth one instance of
the object. Prints a line per object: pairs off, pairs, worst share of the diameter, the frames off.
"""
import json
import sys

import numpy as np

from lookalike_metrics import ply_vertices, results_as_poses

OFF = 0.05  # share of the diameter


def published(path):
    """(object, frame) -> (R, t) of the highest-scoring row."""
    return {(obj, im): max(rows, key=lambda row: row[0])[1:3]
            for (_, im, obj), rows in results_as_poses(path).items()}


def main(dataset, results):
    info = json.load(open(f"{dataset}/models/models_info.json"))
    gt = json.load(open(f"{dataset}/test/000000/scene_gt.json"))
    poses = published(results)

    def truth(obj, frame):
        found = [g for g in gt.get(str(frame), []) if g["obj_id"] == obj]
        if len(found) != 1:
            return None
        return np.array(found[0]["cam_R_m2c"]).reshape(3, 3), np.array(found[0]["cam_t_m2c"])

    for obj in sorted({k[0] for k in poses}):
        model = ply_vertices(f"{dataset}/models/obj_{obj:06d}.ply")
        diameter = info[str(obj)]["diameter"]
        pairs, off, worst = 0, [], 0.0
        for frame in sorted(k[1] for k in poses if k[0] == obj):
            before, now = truth(obj, frame - 1), truth(obj, frame)
            if (obj, frame - 1) not in poses or before is None or now is None:
                continue
            r0, t0 = poses[(obj, frame - 1)]
            r1, t1 = poses[(obj, frame)]
            motion_r = now[0] @ before[0].T  # the true motion between the frames
            motion_t = now[1] - motion_r @ before[1]
            moved = model @ (motion_r @ r0).T + (motion_r @ t0 + motion_t)
            error = np.linalg.norm(moved - (model @ r1.T + t1), axis=1).mean() / diameter
            pairs += 1
            if error > OFF:
                off.append(frame)
                worst = max(worst, error)
        print(f"object {obj}: {len(off)} of {pairs} pairs off by more than {OFF:.0%} of the "
              f"diameter (worst {worst:.0%}); frames {off}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
