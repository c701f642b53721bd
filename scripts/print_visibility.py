#!/usr/bin/python3
"""Which targets of a generated BOP dataset show the part of their colour that tells their pose.

For each ground-truth instance whose model PLY carries vertex colours, the vertices whose colour is
not the model's most common one (a label, a print) are moved by the ground-truth pose, projected
with the image's camera, and counted as seen where the depth image holds their depth (within 3 mm).
Prints one CSV row per target: scene_id, im_id, obj_id, gt_index, print_vertices, print_seen.
Usage: print_visibility.py DATASET [SPLIT]
"""
import collections
import json
import pathlib
import sys

import numpy as np
from PIL import Image

DEPTH_TOLERANCE_MM = 3.0
PRINT_DISTANCE = 60  # summed channel levels from the most common colour


def read_depth_png(path):
    """A BOP depth image (16-bit greyscale PNG) as a float array."""
    return np.asarray(Image.open(path), dtype=float)


def read_coloured_ply(path):
    """Vertices (N x 3, mm) and colours (N x 3) of an ASCII PLY; None without colours."""
    with open(path) as f:
        header = []
        for line in f:
            header.append(line.split())
            if line.startswith("end_header"):
                break
        count = next(int(h[2]) for h in header if h[:2] == ["element", "vertex"])
        names = [h[2] for h in header if h[0] == "property" and h[1] != "list"]
        if "red" not in names or ["format", "ascii", "1.0"] not in header:
            return None
        rows = np.array([f.readline().split()[: len(names)] for _ in range(count)], dtype=float)
    xyz = rows[:, [names.index(c) for c in ("x", "y", "z")]]
    rgb = rows[:, [names.index(c) for c in ("red", "green", "blue")]]
    return xyz, rgb


def print_vertices(model):
    xyz, rgb = model
    common = collections.Counter(map(tuple, rgb.astype(int))).most_common(1)[0][0]
    return xyz[np.abs(rgb - np.array(common)).sum(axis=1) > PRINT_DISTANCE]


def main():
    root = pathlib.Path(sys.argv[1])
    split = sys.argv[2] if len(sys.argv) > 2 else "test"
    models = {}
    print("scene_id,im_id,obj_id,gt_index,print_vertices,print_seen")
    for scene in sorted((root / split).iterdir()):
        gt = json.loads((scene / "scene_gt.json").read_text())
        cameras = json.loads((scene / "scene_camera.json").read_text())
        for im, instances in gt.items():
            cam = cameras[im]
            K = np.array(cam["cam_K"]).reshape(3, 3)
            depth = read_depth_png(scene / "depth" / f"{int(im):06d}.png")
            depth *= cam.get("depth_scale", 1.0)
            for k, inst in enumerate(instances):
                obj = inst["obj_id"]
                if obj not in models:
                    model = read_coloured_ply(root / "models" / f"obj_{obj:06d}.ply")
                    models[obj] = None if model is None else print_vertices(model)
                points = models[obj]
                if points is None or len(points) == 0:
                    continue
                R = np.array(inst["cam_R_m2c"]).reshape(3, 3)
                cam_points = points @ R.T + np.array(inst["cam_t_m2c"])
                uvw = cam_points @ K.T
                u = np.round(uvw[:, 0] / uvw[:, 2]).astype(int)
                v = np.round(uvw[:, 1] / uvw[:, 2]).astype(int)
                inside = (u >= 0) & (v >= 0) & (u < depth.shape[1]) & (v < depth.shape[0])
                seen = np.zeros(len(points), bool)
                measured = depth[v[inside], u[inside]]
                seen[inside] = (measured > 0) & (
                    np.abs(measured - cam_points[inside, 2]) < DEPTH_TOLERANCE_MM)
                print(f"{int(scene.name)},{im},{obj},{k},{len(points)},{int(seen.sum())}")


if __name__ == "__main__":
    main()
