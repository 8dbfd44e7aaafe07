#!/usr/bin/env python3
"""tools/plots/plot_psnr.py - the PSNR curves of docs/benchmarks.md ("Surfaces and shading") as a chart.

Reads the CSV that `bench_shading --accuracy FILE.csv` writes (scene, alpha, layers, mode,
PSNR against the exact reference with the same Sobel normals and with exact sphere normals) and
draws one panel per shading mode: PSNR against the angle resolution alpha (finer to the right),
a line per scene, solid against the same-normal reference, dashed against the sphere-normal
one, with the bounds the tests hold at 14 degrees.

    python3 tools/plots/plot_psnr.py psnr.csv docs/images/psnr_vs_alpha.png

Needs matplotlib (Debian: python3-matplotlib, installed by `tools/scripts/setup.sh --media`).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import figures  # noqa: E402 (tools/plots/figures.py)

MODES = ["opaque", "translucent", "refractive"]
BOUNDS = {"opaque": 32, "translucent": 32, "refractive": 26}


def read(path):
    rows = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            key = (r["scene"], r["mode"])
            rows.setdefault(key, []).append(
                (float(r["alpha"]), float(r["psnr_same_normals"]), float(r["psnr_sphere_normals"])))
    return rows


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    rows = read(argv[1])
    scenes = sorted({scene for scene, _ in rows}, key=lambda s: list(k[0] for k in rows).index(s))
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.8), sharex=True)
    for ax, mode in zip(axes, MODES):
        for i, scene in enumerate(scenes):
            points = sorted(rows.get((scene, mode), []), reverse=True)
            if not points:
                continue
            alphas = [p[0] for p in points]
            c = colors[i % len(colors)]
            ax.plot(alphas, [p[1] for p in points], "-o", color=c, markersize=3, label=scene)
            ax.plot(alphas, [p[2] for p in points], "--", color=c, alpha=0.6)
        ax.axhline(BOUNDS[mode], color="grey", linewidth=0.8, linestyle=":")
        ax.set_xscale("log")
        ax.invert_xaxis()
        ax.set_xticks([14, 7, 3.5, 2, 1])
        ax.get_xaxis().set_major_formatter(matplotlib.ticker.FormatStrFormatter("%g"))
        ax.set_title(mode)
        ax.set_xlabel("angle resolution alpha (degrees, finer to the right)")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("PSNR (dB) against the exact reference")
    axes[0].legend(fontsize=8, loc="upper left")
    return figures.save(fig, "GPU picture against the exact CPU reference, 160x120, filter off: "
                        "solid = same (Sobel) normals, dashed = exact sphere normals, dotted = "
                        "test bound", argv[2])


if __name__ == "__main__":
    sys.exit(main(sys.argv))
