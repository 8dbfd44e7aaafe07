#!/usr/bin/python3
"""measure_speckles.py MASK.png PICTURE.png... - the share of a refractive picture's water pixels
that are speckled (docs/benchmarks.md, "The refraction's speckles").

MASK: the same view rendered translucent with a huge absorption (the water black, so water
pixels are those darker than 90/255). A water pixel at least two pixels inside the silhouette is
speckled when its luminance departs from its 5x5 neighbourhood's median by more than 40/255, or
its blue-minus-red by more than 30/255. Needs numpy, scipy and Pillow (Debian: python3-numpy,
python3-scipy, python3-pil)."""
import sys

import numpy as np
from PIL import Image
from scipy.ndimage import binary_erosion, median_filter


def main(argv):
    if len(argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    water = np.asarray(Image.open(argv[1]).convert("L")) < 90
    inner = binary_erosion(water, iterations=2)
    for path in argv[2:]:
        a = np.asarray(Image.open(path).convert("RGB")).astype(float)
        lum = a.mean(axis=2)
        tint = a[..., 2] - a[..., 0]
        speckled = (np.abs(tint - median_filter(tint, size=5)) > 30) | (
            np.abs(lum - median_filter(lum, size=5)) > 40)
        n = int((speckled & inner).sum())
        print(f"{path}: {n} of {int(inner.sum())} water pixels speckled ({100 * n / inner.sum():.2f} %)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
