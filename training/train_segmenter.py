#!/usr/bin/env python3
"""Trains the package's small segmentation network on `stocs synth` scenes and exports it to ONNX.

Reads BOP datasets (rgb/, mask_visib/, scene_gt.json per scene), learns one class per object id
(channel k is obj_id k, channel 0 the background) at the network's input size, and writes logits
NCHW in an ONNX file that OpenCV 4.6's DNN module reads (opset 11). scripts/train_segmenter.sh
runs it; models/README.md records what made the committed file.

With --val, every --val-every epochs the network is run on whole validation images (datasets of
seeds that no training, test, demo or measurement uses) and the pixel precision, recall and F1 of
each object (its probability above 0.5 against its visible mask, pooled over the images) are
printed; the epoch with the best score is the one exported (with --export last, the last epoch: the
validation figures are then only reported, as for the committed network). The score is the lowest
F1 over the objects: the lowest, so that no object is given up for the others' sake (the demo lost
its block to a look-alike, candidates trained on varied looks lost part of the bowl or the long
box); F1 rather than recall, because recall alone rewards marking look-alike distractors as the
object, which is how the demo's block was lost, and precision alone rewards marking too little.
"""
import argparse
import copy
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


def pixel_counts(net, frames, classes, batch=16):
    """Per class: true positive, false positive and false negative pixels of the network's
    probabilities above 0.5 on whole images, summed over the frames."""
    counts = np.zeros((classes, 3), np.int64)
    net.eval()
    with torch.no_grad():
        for i in range(0, len(frames), batch):
            rgb, labels = zip(*frames[i:i + batch])
            x = torch.from_numpy(np.stack(rgb).transpose(0, 3, 1, 2).astype(np.float32) / 255.0)
            marked = F.softmax(net(x), dim=1).numpy() > 0.5
            truth = np.stack(labels)
            for k in range(classes):
                counts[k] += [np.sum(marked[:, k] & (truth == k)),
                              np.sum(marked[:, k] & (truth != k)),
                              np.sum(~marked[:, k] & (truth == k))]
    return counts


def validation_score(counts):
    """Prints each object's precision, recall and F1; returns the lowest F1 over the objects that
    the validation images hold (class 0, the background, is not an object)."""
    f1s = []
    for k, (tp, fp, fn) in enumerate(counts):
        if k == 0 or tp + fn == 0:
            continue
        precision, recall = tp / max(tp + fp, 1), tp / (tp + fn)
        f1s.append(2 * tp / (2 * tp + fp + fn))
        print(f"  obj {k}: precision {precision:.3f} recall {recall:.3f} F1 {f1s[-1]:.3f}",
              flush=True)
    return min(f1s)


def class_weights(frames, classes):
    """Objects cover a few percent of the pixels: weigh them up, mildly, so that recall is not
    traded away, nor precision on look-alike distractors."""
    counts = np.bincount(np.concatenate([l.ravel() for _, l in frames]), minlength=classes)
    weights = torch.tensor((counts.sum() / np.maximum(counts, 1)) ** 0.3, dtype=torch.float32)
    return weights / weights[0]


def dice_loss(logits, y):
    """One minus the soft Dice coefficient, averaged over the object classes: an overlap loss that
    weighs each object alike whatever its size, as the validation score (lowest F1) does."""
    p = F.softmax(logits, dim=1)[:, 1:]
    truth = F.one_hot(y, logits.shape[1]).permute(0, 3, 1, 2)[:, 1:].float()
    overlap = (p * truth).sum(dim=(0, 2, 3))
    return (1 - (2 * overlap + 1) / (p.sum(dim=(0, 2, 3)) + truth.sum(dim=(0, 2, 3)) + 1)).mean()


def train_epoch(net, opt, sched, frames, weights, a, rng):
    net.train()
    total = 0.0
    for x, y in batches(frames, a.batch, a.crop, rng):
        logits = net(x)
        loss = F.cross_entropy(logits, y, weight=weights)
        if a.dice > 0:
            loss = loss + a.dice * dice_loss(logits, y)
        opt.zero_grad()
        loss.backward()
        opt.step()
        sched.step()
        total += loss.item()
    return total / (len(frames) // a.batch)


def train(net, frames, val_frames, a, rng):
    """Trains for a.epochs (or a.minutes) and returns the weights of the epoch with the best
    validation score (the last epoch's without validation images or with --export last)."""
    weights = class_weights(frames, a.classes)
    opt = torch.optim.AdamW(net.parameters(), lr=3e-3, weight_decay=1e-4)
    sched = torch.optim.lr_scheduler.OneCycleLR(
        opt, max_lr=3e-3, total_steps=a.epochs * (len(frames) // a.batch))
    start = time.time()
    best, best_score, best_epoch = None, -1.0, 0
    for epoch in range(1, a.epochs + 1):
        loss = train_epoch(net, opt, sched, frames, weights, a, rng)
        minutes = (time.time() - start) / 60
        print(f"epoch {epoch}: loss {loss:.4f}, {minutes:.1f} min", flush=True)
        last = epoch == a.epochs or minutes > a.minutes
        if val_frames and (epoch % a.val_every == 0 or last):
            score = validation_score(pixel_counts(net, val_frames, a.classes))
            print(f"  validation: lowest F1 {score:.4f}", flush=True)
            if score > best_score and a.export == "best":
                best, best_score, best_epoch = copy.deepcopy(net.state_dict()), score, epoch
        if minutes > a.minutes:
            print("time limit reached", flush=True)
            break
    if best is not None:
        print(f"chosen: epoch {best_epoch}, lowest validation F1 {best_score:.4f}", flush=True)
        net.load_state_dict(best)
    return net


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--data", nargs="+", required=True, help="BOP datasets from stocs synth")
    ap.add_argument("--val", nargs="*", default=[], help="validation datasets (other seeds)")
    ap.add_argument("--val-every", type=int, default=1, help="validate every this many epochs")
    ap.add_argument("--export", choices=("best", "last"), default="best",
                    help="the epoch to export: the best on validation, or the last")
    ap.add_argument("--out", required=True, help="ONNX file to write")
    ap.add_argument("--classes", type=int, default=7, help="background and obj_ids 1..classes-1")
    ap.add_argument("--width", type=int, default=160)
    ap.add_argument("--height", type=int, default=120)
    ap.add_argument("--crop", type=int, nargs=2, default=(112, 88), help="training window w h")
    ap.add_argument("--widths", type=int, nargs=4, default=(8, 16, 32, 48),
                    help="channels at the four resolutions (the ONNX file grows with them)")
    ap.add_argument("--dice", type=float, default=0,
                    help="weight of a Dice loss beside the cross entropy (0: none)")
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
    size = (a.width, a.height)
    frames = [f for d in a.data for f in load_frames(d, size)]
    val_frames = [f for d in a.val for f in load_frames(d, size)]
    print(f"{len(frames)} training images, {len(val_frames)} validation images", flush=True)
    net = SmallUNet(a.classes, tuple(a.widths))
    print(f"{sum(p.numel() for p in net.parameters())} parameters", flush=True)
    net = train(net, frames, val_frames, a, rng).eval()
    dummy = torch.zeros(1, 3, a.height, a.width)
    torch.onnx.export(net, dummy, a.out, opset_version=11, input_names=["rgb"],
                      output_names=["logits"], do_constant_folding=True)
    print(f"wrote {a.out}", flush=True)


if __name__ == "__main__":
    main()
