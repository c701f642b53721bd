#!/usr/bin/python3
"""Instance-boundary maps (BOP `edge/`, 255 = interior) from a BOP dataset's visible masks.

Each image's map is 255 except on a 1 px band along the outline of every ground-truth instance's
`mask_visib/`: the boundaries a perfect boundary network would give, to measure what StoCS's
boundary regions (`stocs estimate --boundaries auto`) make of them. Writes DATASET/SPLIT/SCENE/edge/.
Usage: boundary_maps_from_masks.py DATASET [SPLIT]
"""
import json
import pathlib
import sys

import numpy as np
from PIL import Image


def outline(mask):
    """The pixels of `mask` with a 4-neighbour outside it."""
    inner = mask.copy()
    inner[1:, :] &= mask[:-1, :]
    inner[:-1, :] &= mask[1:, :]
    inner[:, 1:] &= mask[:, :-1]
    inner[:, :-1] &= mask[:, 1:]
    return mask & ~inner


def main():
    if len(sys.argv) not in (2, 3):
        sys.exit(__doc__)
    split = pathlib.Path(sys.argv[1]) / (sys.argv[2] if len(sys.argv) == 3 else "test")
    scenes = sorted(p for p in split.iterdir() if (p / "scene_gt.json").is_file())
    if not scenes:
        sys.exit(f"{split}: no scene with a scene_gt.json")
    for scene in scenes:
        (scene / "edge").mkdir(exist_ok=True)
        for im, instances in json.load(open(scene / "scene_gt.json")).items():
            interior = None
            for k in range(len(instances)):
                path = scene / "mask_visib" / f"{int(im):06d}_{k:06d}.png"
                if not path.is_file():
                    sys.exit(f"{path}: missing (the map needs every instance's visible mask)")
                mask = np.asarray(Image.open(path)) > 0
                if interior is None:
                    interior = np.ones(mask.shape, bool)
                interior &= ~outline(mask)
            if interior is not None:
                image = Image.fromarray(interior.astype(np.uint8) * 255)
                image.save(scene / "edge" / f"{int(im):06d}.png")


if __name__ == "__main__":
    main()
