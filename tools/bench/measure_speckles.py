#!/usr/bin/python3
"""measure_speckles.py MASK.png PICTURE.png... - the share of a refractive picture's water pixels
that are speckled (docs/benchmarks.md, "The refraction's speckles").
measure_speckles.py --median [--mask MASK.png] PICTURE.png... - the pixels of a picture more than
40/255 off their 3x3 median (docs/benchmarks.md, "Speckles where the water meets the walls").

MASK: the same view rendered translucent with a huge absorption (the water black, so water
pixels are those darker than 90/255). A water pixel at least two pixels inside the silhouette is
speckled when its luminance departs from its 5x5 neighbourhood's median by more than 40/255, or
its blue-minus-red by more than 30/255.

--median: a pixel is speckled when any of its red, green and blue values departs from the median
of that channel over its 3x3 neighbourhood (the picture's edge repeated) by more than 40/255; the
200 x 14 pixels at the top left, where a view draws its caption, are left out. With --mask, the
mask view of tools/scenes/speckles/main-job.yaml (the water opaque and blue, the walls red): a
pixel is on the water where the mask's blue exceeds its red by more than 40/255, or next to
such a pixel; and inside the water's outline where it is three pixels or more inside the
mask's water (the top surface and what lies on it, not its edges against walls and sky). Needs numpy, scipy and Pillow (Debian: python3-numpy, python3-scipy,
python3-pil)."""
import sys

import numpy as np
from PIL import Image
from scipy.ndimage import binary_dilation, binary_erosion, median_filter


def water_share(argv):
    water = np.asarray(Image.open(argv[0]).convert("L")) < 90
    inner = binary_erosion(water, iterations=2)
    for path in argv[1:]:
        a = np.asarray(Image.open(path).convert("RGB")).astype(float)
        lum = a.mean(axis=2)
        tint = a[..., 2] - a[..., 0]
        speckled = (np.abs(tint - median_filter(tint, size=5)) > 30) | (
            np.abs(lum - median_filter(lum, size=5)) > 40)
        n = int((speckled & inner).sum())
        print(f"{path}: {n} of {int(inner.sum())} water pixels speckled ({100 * n / inner.sum():.2f} %)")
    return 0


def off_median(argv):
    water = inside = None
    if argv[:1] == ["--mask"]:
        m = np.asarray(Image.open(argv[1]).convert("RGB")).astype(float)
        water = binary_dilation(m[..., 2] - m[..., 0] > 40, iterations=1)
        inside = binary_erosion(m[..., 2] - m[..., 0] > 40, iterations=3)
        argv = argv[2:]
    for path in argv:
        a = np.asarray(Image.open(path).convert("RGB")).astype(float)
        median = np.stack([median_filter(a[..., c], size=3, mode="nearest") for c in range(3)], -1)
        speckled = (np.abs(a - median) > 40).any(axis=2)
        speckled[:14, :200] = False
        line = f"{path}: {int(speckled.sum())} pixels more than 40/255 off their 3x3 median"
        if water is not None:
            line += (f", {int((speckled & water).sum())} on the water, "
                     f"{int((speckled & inside).sum())} inside its outline")
        print(line)
    return 0


def main(argv):
    if argv[1:2] == ["--median"] and len(argv) > 2:
        return off_median(argv[2:])
    if len(argv) < 3:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    return water_share(argv[1:])


if __name__ == "__main__":
    sys.exit(main(sys.argv))
