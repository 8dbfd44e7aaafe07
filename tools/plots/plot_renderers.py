#!/usr/bin/env python3
"""tools/plots/plot_renderers.py - how the two renderers' render step grows with particles and with
pixels, on log-log axes (docs/benchmarks.md, "The CPU renderer").

Reads the CSVs that `bench_renderers --csv FILE` writes (particles, width, height, mode,
renderer, pass, median_ms), any number of them, and draws two panels of the `step` time (the
classification to the picture in host memory): against the particle count at the most common
image size, and against the pixel count at the most common particle count; a line per renderer
and shading mode.

    python3 tools/plots/plot_renderers.py OUT.png RUN1.csv RUN2.csv ...

Needs matplotlib (Debian: python3-matplotlib, installed by `tools/scripts/setup.sh --media`).
"""
import collections
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {"gl": "-", "cpu": "--"}
COLOUR = {"opaque": "tab:blue", "translucent": "tab:green", "refractive": "tab:red"}


def read(paths):
    """{(renderer, mode): {(particles, pixels): ms}} of the step times."""
    rows = collections.defaultdict(dict)
    for path in paths:
        with open(path, newline="") as f:
            for r in csv.DictReader(f):
                if r["pass"] != "step":
                    continue
                key = (int(r["particles"]), int(r["width"]) * int(r["height"]))
                rows[(r["renderer"], r["mode"])][key] = float(r["median_ms"])
    return rows


def most_common(values):
    return collections.Counter(values).most_common(1)[0][0]


def panel(ax, rows, axis, fixed, label):
    for (renderer, mode), points in sorted(rows.items()):
        line = sorted((k[axis], ms) for k, ms in points.items() if k[1 - axis] == fixed)
        if len(line) < 2:
            continue
        xs, ys = zip(*line)
        ax.plot(xs, ys, STYLE.get(renderer, ":"), color=COLOUR.get(mode, "black"), marker="o",
                label=f"{renderer} {mode}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel(label)
    ax.set_ylabel("render step, ms (median)")
    ax.grid(True, which="both", alpha=0.3)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    rows = read(sys.argv[2:])
    keys = [k for points in rows.values() for k in points]
    pixels = most_common(k[1] for k in keys)
    particles = most_common(k[0] for k in keys)
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 5))
    panel(a, rows, 0, pixels, f"particles (images of {pixels} pixels)")
    panel(b, rows, 1, particles, f"pixels ({particles} particles)")
    a.legend(fontsize=8)
    fig.suptitle("GL renderer (solid) and CPU renderer (dashed)")
    fig.tight_layout()
    fig.savefig(sys.argv[1], dpi=100)


if __name__ == "__main__":
    main()
