#!/usr/bin/env python3
"""tools/plots/plot_volume_accuracy.py - the volume views' error against their time, one point per
`sampling` (docs/benchmarks.md, "Volume views").

Reads the CSV that `bench_volume --convergence --csv FILE` writes (scene, particles, width,
height, mode, sampling, median ms per frame, samples, the largest and the 99th-percentile
channel error against the converged integral) and draws, per mode, the error (log scale)
against the milliseconds per frame: solid the largest error, dashed the 99th percentile, each
point labelled with its sampling, the default (sampling 1) in front, ringed; 1/255 and 1/1020
as dotted lines (a PNG's step, and a quarter of it).

    python3 tools/plots/plot_volume_accuracy.py accuracy.csv docs/images/volume_accuracy.png

Needs matplotlib (Debian: python3-matplotlib, installed by `tools/scripts/setup.sh --media`).
"""
import collections
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import figures  # noqa: E402 (tools/plots/figures.py)


def read(path):
    """{mode: [(sampling, ms, max_err, p99_err)]} and a title from the first row."""
    rows = collections.defaultdict(list)
    title = ""
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            rows[r["mode"]].append((float(r["sampling"]), float(r["ms"]), float(r["max_err"]),
                                    float(r["p99_err"])))
            title = "%s dam break, %s particles, %sx%s" % (r["scene"], r["particles"], r["width"],
                                                          r["height"])
    return rows, title


def main(argv):
    if len(argv) != 3:
        print(__doc__)
        return 2
    rows, title = read(argv[1])
    fig, axes = plt.subplots(1, len(rows), figsize=(6 * len(rows), 4.6), squeeze=False)
    for ax, (mode, points) in zip(axes[0], rows.items()):
        points.sort()
        ms = [p[1] for p in points]
        ax.plot(ms, [p[2] for p in points], "-o", color="tab:blue", label="largest error")
        ax.plot(ms, [p[3] for p in points], "--o", color="tab:orange", label="99th percentile")
        for sampling, t, worst, p99 in points:
            ax.annotate("sampling %g" % sampling, (t, worst), textcoords="offset points",
                        xytext=(4, 4), fontsize=8)
            if sampling == 1:
                for e in (worst, p99):
                    ax.plot([t], [e], "o", markersize=12, markerfacecolor="none",
                            markeredgecolor="black", zorder=5)
        for level, name in ((1 / 255, "1/255"), (1 / 1020, "1/1020")):
            ax.axhline(level, color="grey", linewidth=0.8, linestyle=":")
            ax.annotate(name, (ms[-1], level), fontsize=8, color="grey")
        ax.set_yscale("log")
        ax.set_title("mode %s" % mode)
        ax.set_xlabel("milliseconds per frame (median, 2 cores)")
        ax.grid(alpha=0.3)
    axes[0][0].set_ylabel("channel error against the converged integral")
    axes[0][0].legend(fontsize=8)
    return figures.save(
        fig, "Volume views, %s: error against time per sampling (the default ringed)" % title,
        argv[2])


if __name__ == "__main__":
    sys.exit(main(sys.argv))
