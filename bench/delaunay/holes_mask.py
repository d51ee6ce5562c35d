#!/usr/bin/env python3
"""Writes a holes mask for --mask measurements: a white W x H PGM with black discs (radius 2 to
R) and scratches (1 to 4 pixels wide, 20 to 600 long) at random, seeded.

    bench/delaunay/holes_mask.py WIDTH HEIGHT HOLES OUT.pgm [--largest R] [--seed S]

Half the holes are discs, half scratches; at a few hundred they cross any tile grid's borders.
"""
import argparse
import math
import random

parser = argparse.ArgumentParser()
parser.add_argument("width", type=int)
parser.add_argument("height", type=int)
parser.add_argument("holes", type=int)
parser.add_argument("out")
parser.add_argument("--largest", type=int, default=60, help="largest disc radius")
parser.add_argument("--seed", type=int, default=1)
args = parser.parse_args()
w, h = args.width, args.height
rng = random.Random(args.seed)
pixels = bytearray(b"\xff" * (w * h))


def disc(cx, cy, r):
    for y in range(max(0, int(cy - r)), min(h - 1, int(cy + r)) + 1):
        half = math.sqrt(max(0.0, r * r - (y - cy) ** 2))
        x0, x1 = max(0, int(math.ceil(cx - half))), min(w - 1, int(math.floor(cx + half)))
        if x0 <= x1:
            pixels[y * w + x0:y * w + x1 + 1] = bytes(x1 - x0 + 1)


for i in range(args.holes):
    cx, cy = rng.uniform(0, w - 1), rng.uniform(0, h - 1)
    if i % 2 == 0:
        disc(cx, cy, rng.uniform(2, args.largest))
    else:
        length, angle, width = rng.uniform(20, 600), rng.uniform(0, math.pi), rng.uniform(0.5, 2)
        for t in range(int(length)):
            disc(cx + t * math.cos(angle), cy + t * math.sin(angle), width)
with open(args.out, "wb") as f:
    f.write(b"P5\n%d %d\n255\n" % (w, h))
    f.write(pixels)
