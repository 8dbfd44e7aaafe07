#!/usr/bin/python3
"""speckle_crops.py OUT.png PICTURE@X,Y,W,H... - crops of pictures, each enlarged without
smoothing to the width of the first, two to a row, so that a speckle at one size sits beside
the same place at twice the size (docs/benchmarks.md, "Speckles on the main job's water").
Needs numpy and Pillow (Debian: python3-numpy, python3-pil)."""
import sys

import numpy as np
from PIL import Image

GAP = 8  # pixels of white between the crops


def crop(spec, width):
    path, box = spec.rsplit("@", 1)
    x, y, w, h = (int(v) for v in box.split(","))
    scale = width // w
    a = np.asarray(Image.open(path).convert("RGB"))[y:y + h, x:x + w]
    return a.repeat(scale, axis=0).repeat(scale, axis=1)


def main(argv):
    if len(argv) < 2 or any("@" not in a for a in argv[1:]):
        print(__doc__, file=sys.stderr)
        return 2
    first = argv[1].rsplit("@", 1)[1].split(",")
    width = int(first[2]) * max(1, 480 // int(first[2]))
    tiles = [crop(spec, width) for spec in argv[1:]]
    height = max(t.shape[0] for t in tiles)
    rows = (len(tiles) + 1) // 2
    out = np.full((rows * (height + GAP) - GAP, 2 * width + GAP, 3), 255, np.uint8)
    for k, t in enumerate(tiles):
        y, x = (k // 2) * (height + GAP), (k % 2) * (width + GAP)
        out[y:y + t.shape[0], x:x + t.shape[1]] = t
    Image.fromarray(out).save(argv[0])
    print("wrote", argv[0])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
