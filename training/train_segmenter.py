#!/usr/bin/env python3
"""Trains the package's small segmentation network on `stocs synth` scenes and exports it to ONNX.

Reads BOP datasets (rgb/, mask_visib/, scene_gt.json per scene), learns one class per object id
(channel k is obj_id k, channel 0 the background) at the network's input size, and writes logits
NCHW in an ONNX file that OpenCV 4.6's DNN module reads (opset 11). scripts/train_segmenter.sh
runs it; models/README.md records what made the committed file.
"""
import argparse
import json
import pathlib
import random
import time

import numpy as np
import torch
import torch.nn as nn
import torch.nn.functional as F
from PIL import Image


def conv_block(cin, cout):
    return nn.Sequential(
        nn.Conv2d(cin, cout, 3, padding=1, bias=False), nn.BatchNorm2d(cout), nn.ReLU(inplace=True),
        nn.Conv2d(cout, cout, 3, padding=1, bias=False), nn.BatchNorm2d(cout), nn.ReLU(inplace=True))


class SmallUNet(nn.Module):
    """A U-Net of three downsamplings: about 100k parameters, logits at the input's size."""

    def __init__(self, classes, widths=(8, 16, 32, 48)):
        super().__init__()
        self.down = nn.ModuleList()
        cin = 3
        for w in widths:
            self.down.append(conv_block(cin, w))
            cin = w
        self.up = nn.ModuleList()
        for w in reversed(widths[:-1]):
            self.up.append(conv_block(cin + w, w))
            cin = w
        self.head = nn.Conv2d(cin, classes, 1)

    def forward(self, x):
        skips = []
        for i, block in enumerate(self.down):
            x = block(x if i == 0 else F.max_pool2d(x, 2))
            skips.append(x)
        for block, skip in zip(self.up, reversed(skips[:-1])):
            x = F.interpolate(x, scale_factor=2.0, mode="nearest")
            x = block(torch.cat([x, skip], dim=1))
        return self.head(x)


def load_frames(dataset, size):
    """Every image of the dataset's test/ scenes: (RGB uint8 HxWx3, labels uint8 HxW) at `size`."""
    frames = []
    for scene in sorted((pathlib.Path(dataset) / "test").iterdir()):
        gt = json.loads((scene / "scene_gt.json").read_text())
        for im, objects in gt.items():
            rgb = Image.open(scene / "rgb" / f"{int(im):06d}.png").convert("RGB")
            labels = np.zeros((rgb.height, rgb.width), np.uint8)
            for k, o in enumerate(objects):
                mask = np.array(Image.open(scene / "mask_visib" / f"{int(im):06d}_{k:06d}.png"))
                labels[mask > 0] = o["obj_id"]
            rgb = np.array(rgb.resize(size, Image.BILINEAR))
            labels = np.array(Image.fromarray(labels).resize(size, Image.NEAREST))
            frames.append((rgb, labels))
    return frames


def augment(rgb, labels, rng):
    """Lighting (gain, a slight colour cast, gamma), sensor noise and a horizontal flip: the
    generated scenes have one light and one table colour, which the network must not take as
    given. The cast stays small: distractors coloured within 20 levels of an object's colour differ
    from it mostly in the ratio of the channels, which a strong cast would blur."""
    x = rgb.astype(np.float32) / 255.0
    x = x ** rng.uniform(0.8, 1.25)
    x = x * rng.uniform(0.6, 1.4) * rng.uniform(0.96, 1.04, size=3)
    x = x + rng.uniform(-0.1, 0.1)
    x = x + rng.normal(0, rng.uniform(0, 0.03), size=x.shape)
    if rng.random() < 0.5:
        x, labels = x[:, ::-1], labels[:, ::-1]
    return np.clip(x, 0, 1), labels


def crop(rgb, labels, size, rng):
    """A random window of `size` (w, h): the network is fully convolutional, and smaller windows
    train faster on 2 cores."""
    w, h = size
    u = rng.integers(0, rgb.shape[1] - w + 1)
    v = rng.integers(0, rgb.shape[0] - h + 1)
    return rgb[v:v + h, u:u + w], labels[v:v + h, u:u + w]


def batches(frames, batch, size, rng):
    order = rng.permutation(len(frames))
    for i in range(0, len(order) - batch + 1, batch):
        xs, ys = zip(*(augment(*crop(*frames[j], size, rng), rng) for j in order[i:i + batch]))
        x = torch.from_numpy(np.ascontiguousarray(np.stack(xs).transpose(0, 3, 1, 2)))
        y = torch.from_numpy(np.ascontiguousarray(np.stack(ys))).long()
        yield x.float(), y


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--data", nargs="+", required=True, help="BOP datasets from stocs synth")
    ap.add_argument("--out", required=True, help="ONNX file to write")
    ap.add_argument("--classes", type=int, default=7, help="background and obj_ids 1..classes-1")
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--crop", type=int, nargs=2, default=(112, 88), help="training window w h")
    ap.add_argument("--epochs", type=int, default=40)
    ap.add_argument("--batch", type=int, default=8)
    ap.add_argument("--minutes", type=float, default=25, help="stop training after this long")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--threads", type=int, default=1)
    a = ap.parse_args()

    torch.manual_seed(a.seed)
    random.seed(a.seed)
    rng = np.random.default_rng(a.seed)
    torch.set_num_threads(a.threads)
    frames = [f for d in a.data for f in load_frames(d, (a.width, a.height))]
    print(f"{len(frames)} images", flush=True)
    # Objects cover a few percent of the pixels: weigh them up, mildly, so that recall is not traded
    # away, nor precision on look-alike distractors.
    counts = np.bincount(np.concatenate([l.ravel() for _, l in frames]), minlength=a.classes)
    weights = torch.tensor((counts.sum() / np.maximum(counts, 1)) ** 0.3, dtype=torch.float32)
    weights = weights / weights[0]

    net = SmallUNet(a.classes)
    print(f"{sum(p.numel() for p in net.parameters())} parameters", flush=True)
    opt = torch.optim.AdamW(net.parameters(), lr=3e-3, weight_decay=1e-4)
    sched = torch.optim.lr_scheduler.OneCycleLR(
        opt, max_lr=3e-3, total_steps=a.epochs * (len(frames) // a.batch))
    start = time.time()
    for epoch in range(a.epochs):
        net.train()
        total = 0.0
        for x, y in batches(frames, a.batch, a.crop, rng):
            loss = F.cross_entropy(net(x), y, weight=weights)
            opt.zero_grad()
            loss.backward()
            opt.step()
            sched.step()
            total += loss.item()
        minutes = (time.time() - start) / 60
        print(f"epoch {epoch + 1}: loss {total / (len(frames) // a.batch):.4f}, {minutes:.1f} min",
              flush=True)
        if minutes > a.minutes:
            print("time limit reached", flush=True)
            break

    net.eval()
    dummy = torch.zeros(1, 3, a.height, a.width)
    torch.onnx.export(net, dummy, a.out, opset_version=11, input_names=["rgb"],
                      output_names=["logits"], do_constant_folding=True)
    print(f"wrote {a.out}", flush=True)


if __name__ == "__main__":
    main()
