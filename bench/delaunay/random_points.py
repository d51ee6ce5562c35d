#!/usr/bin/env python3
"""Writes a binary PLY point file for point-file measurements: a fraction of a W x H frame's
pixel count as points at random real positions (not on pixel centres), coloured by a smooth
pattern with sharp bands, seeded.

    bench/delaunay/random_points.py WIDTH HEIGHT FRACTION OUT.ply [--seed S]

x and y are floats (pixel centres at integers, in [0, W - 1] x [0, H - 1]); red, green, blue
uchar. 10 % of 16384^2 (26.8 million points, 295 MB) takes about two minutes in CPython.
"""
import argparse
import array
import math
import random
import sys

parser = argparse.ArgumentParser()
parser.add_argument("width", type=int)
parser.add_argument("height", type=int)
parser.add_argument("fraction", type=float)
parser.add_argument("out")
parser.add_argument("--seed", type=int, default=1)
args = parser.parse_args()
w, h = args.width, args.height
count = int(round(args.fraction * w * h))
rng = random.Random(args.seed)

header = (
    "ply\nformat binary_little_endian 1.0\n"
    f"comment {count} random points in a {w}x{h} frame, seed {args.seed}\n"
    f"element vertex {count}\nproperty float x\nproperty float y\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\nend_header\n"
)
if sys.byteorder != "little":
    sys.exit("random_points.py: writes little-endian floats; run it on a little-endian machine")
# Written in chunks: the whole set as Python objects would take gigabytes.
chunk = 1 << 20
with open(args.out, "wb") as out:
    out.write(header.encode())
    done = 0
    while done < count:
        n = min(chunk, count - done)
        record = bytearray(11 * n)
        xy = array.array("f")
        colours = []
        for _ in range(n):
            x, y = rng.random() * (w - 1), rng.random() * (h - 1)
            xy.append(x)
            xy.append(y)
            # Bands of period 64 (sharp steps) over slow ramps: edges for the flips to follow.
            band = 255 if (int(x + y) >> 5) & 1 else 0
            colours.append((band, int(x * 255 / w), int(128 + 127 * math.sin(y / 97.0))))
        raw = xy.tobytes()
        for i, (r, g, b) in enumerate(colours):
            record[11 * i:11 * i + 8] = raw[8 * i:8 * i + 8]
            record[11 * i + 8:11 * i + 11] = bytes((r, g, b))
        out.write(record)
        done += n
