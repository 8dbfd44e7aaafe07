#!/usr/bin/env python3
"""tools/plots/plot_peers.py - the charts of docs/results.md from the CSVs `bench_peers --csv` writes.

For each CSV (one scene each) a panel of first-hit error (99th percentile, particle radii)
against time per frame, every configuration of every method a point, on log-log axes, the
Pareto front (no other point both faster and more exact) drawn through its points and our
defaults starred; a second figure of PSNR against time (the same shading for all); and a third
of stacked per-stage bars of each method's default (or first) configuration. The front and
whether each of our defaults lies on it are printed, and written as FRONT.csv beside the chart.

    python3 tools/plots/plot_peers.py OUT_PREFIX RUN1.csv [RUN2.csv ...]

writes OUT_PREFIX_pareto.png, OUT_PREFIX_psnr.png, OUT_PREFIX_stages.png, OUT_PREFIX_front.csv
and OUT_PREFIX_tables.md (every row of every scene as a Markdown table, front rows marked).
Errors at float rounding (under 1e-4 radii) are drawn at 1e-4.

    python3 tools/plots/plot_peers.py --scaling OUT.png RUN1.csv [RUN2.csv ...]

draws each family's default (or first) configuration's time against the particle count (at the
most common image size) and against the pixel count (at the most common particle count), on
log-log axes. Needs matplotlib.
"""
import collections
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

COLOUR = {"exact": "black", "cpu": "tab:blue", "gl": "tab:green", "openvdb": "tab:red",
          "vtk": "tab:purple"}
FLOOR = 1e-4


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("total_ms", "first_hit_p99_r", "first_hit_median_r", "raw_first_hit_p99_r",
                  "psnr_opaque_db", "psnr_translucent_db"):
            r[k] = float(r[k])
        r["default"] = r["default"] == "1"
        r["missed"] = int(r["missed"])
        r["extra"] = int(r["extra"])
    return rows


# Times within 5 % are one time on a shared machine (medians of a few frames), errors within
# 1e-3 of a radius (or 0.1 dB) one error: a row is off the front only when another is at least as
# exact and clearly faster, or as fast and clearly more exact.
TIME_TIE = 1.05


def dominates(o, r, error, tie):
    faster = o["total_ms"] * TIME_TIE < r["total_ms"]
    as_fast = o["total_ms"] <= r["total_ms"] * TIME_TIE
    return (faster and error(o) <= error(r) + tie) or (as_fast and error(o) + tie < error(r))


def front(rows, error, tie):
    """The rows no other row dominates."""
    out = [r for r in rows if not any(dominates(o, r, error, tie) for o in rows if o is not r)]
    return sorted(out, key=lambda r: r["total_ms"])


def p99(r):
    return max(FLOOR, r["first_hit_p99_r"])


def inv_psnr(r):
    return -min(r["psnr_opaque_db"], 99.0)


def title(rows, path):
    r = rows[0]
    return f"{path.rsplit('/', 1)[-1]}: {r['particles']} particles, {r['width']}x{r['height']}"


def scatter(ax, rows, y, on_front):
    for fam in COLOUR:
        pts = [r for r in rows if r["family"] == fam]
        if pts:
            ax.scatter([r["total_ms"] for r in pts], [y(r) for r in pts], c=COLOUR[fam],
                       s=22, label=fam, zorder=3)
    for r in rows:
        if r["default"]:
            ax.scatter([r["total_ms"]], [y(r)], marker="*", s=260, facecolors="none",
                       edgecolors=COLOUR[r["family"]], linewidths=1.5, zorder=4)
            ax.annotate(f"{r['family']} default", (r["total_ms"], y(r)), textcoords="offset points",
                        xytext=(6, 6), fontsize=8)
    ax.plot([r["total_ms"] for r in on_front], [y(r) for r in on_front], "k:", lw=1,
            label="Pareto front", zorder=2)
    ax.set_xscale("log")
    ax.set_xlabel("time per frame, ms (median)")
    ax.grid(True, which="both", alpha=0.3)


def scaling(out, paths):
    rows = [r for p in paths for r in read(p)]
    picks = {}
    for r in rows:
        key = (r["family"], int(r["particles"]), int(r["width"]) * int(r["height"]))
        if r["default"] or key not in picks:
            if r["default"] or not picks.get(key, {}).get("default"):
                picks[key] = r
    sizes = collections.Counter(k[2] for k in picks)
    counts = collections.Counter(k[1] for k in picks)
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.8))
    for fam in COLOUR:
        by_n = sorted((k[1], r["total_ms"]) for k, r in picks.items()
                      if k[0] == fam and k[2] == sizes.most_common(1)[0][0])
        by_px = sorted((k[2], r["total_ms"]) for k, r in picks.items()
                       if k[0] == fam and k[1] == counts.most_common(1)[0][0])
        if len(by_n) > 1:
            a.plot(*zip(*by_n), "o-", color=COLOUR[fam], label=fam)
        if len(by_px) > 1:
            b.plot(*zip(*by_px), "o-", color=COLOUR[fam], label=fam)
    a.set_xlabel(f"particles ({sizes.most_common(1)[0][0]} pixels)")
    b.set_xlabel(f"pixels ({counts.most_common(1)[0][0]} particles)")
    for ax in (a, b):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_ylabel("ms per frame (median), default settings")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    return 0


def main(argv):
    if len(argv) >= 3 and argv[1] == "--scaling":
        return scaling(argv[2], argv[3:])
    if len(argv) < 3:
        print(__doc__)
        return 2
    prefix, paths = argv[1], argv[2:]
    scenes = [(p, read(p)) for p in paths]
    fig, axes = plt.subplots(1, len(scenes), figsize=(6.4 * len(scenes), 5), squeeze=False)
    fig2, axes2 = plt.subplots(1, len(scenes), figsize=(6.4 * len(scenes), 5), squeeze=False)
    front_rows = []
    for i, (path, rows) in enumerate(scenes):
        f = front(rows, p99, 1e-3)
        scatter(axes[0][i], rows, p99, f)
        axes[0][i].set_yscale("log")
        axes[0][i].set_ylabel("first-hit error after the filter, p99 (particle radii)")
        axes[0][i].set_title(title(rows, path), fontsize=9)
        f2 = front(rows, inv_psnr, 0.1)
        scatter(axes2[0][i], rows, lambda r: min(r["psnr_opaque_db"], 99.0), f2)
        axes2[0][i].set_ylabel("PSNR of the opaque picture, dB (identical drawn at 99)")
        axes2[0][i].set_title(title(rows, path), fontsize=9)
        for r in rows:
            if r["default"] or r["family"] == "exact":
                on1, on2 = r in f, r in f2
                print(f"{path}: {r['family']} {r['settings']}: {r['total_ms']:.1f} ms, p99 "
                      f"{r['first_hit_p99_r']:.3g} r, PSNR {r['psnr_opaque_db']:.1f} dB; on the "
                      f"p99 front: {on1}, on the PSNR front: {on2}")
        for fam in ("cpu", "gl"):
            own = [r for r in rows if r["family"] in (fam, "openvdb", "vtk")]
            fo = front(own, p99, 1e-3)
            for r in own:
                if r["default"]:
                    print(f"{path}: {fam} default on the front of the {fam} renderer's settings "
                          f"and the peers': {r in fo}")
        print(f"{path}: time ratios at equal error (each other method's configuration against the "
              "fastest of ours at least as exact in first-hit p99 and opaque PSNR):")
        ours = [r for r in rows if r["family"] in ("cpu", "gl")]
        for r in rows:
            if r["family"] in ("cpu", "gl"):
                continue
            match = [o for o in ours if o["first_hit_p99_r"] <= r["first_hit_p99_r"] + 1e-3 and
                     o["psnr_opaque_db"] >= r["psnr_opaque_db"] - 0.1]
            if match:
                best = min(match, key=lambda o: o["total_ms"])
                print(f"  {r['family']} {r['settings']}: {r['total_ms']:.1f} ms, p99 "
                      f"{r['first_hit_p99_r']:.3g} r, {r['psnr_opaque_db']:.1f} dB; ours "
                      f"{best['family']} {best['settings']}: {best['total_ms']:.1f} ms: "
                      f"{r['total_ms'] / best['total_ms']:.1f}x")
            else:
                print(f"  {r['family']} {r['settings']}: none of ours as exact")
        for r in f:
            front_rows.append((path, r["family"], r["settings"], r["total_ms"],
                               r["first_hit_p99_r"], r["psnr_opaque_db"]))
    with open(prefix + "_tables.md", "w") as md:
        for path, rows in scenes:
            f = front(rows, p99, 1e-3)
            md.write(f"#### {title(rows, path)}\n\n| method | settings | ms | first hit p99 (r) | "
                     "raw p99 (r) | missed / extra px | thickness p99 (r) | PSNR opaque / "
                     "translucent (dB) | on the front |\n|---|---|---|---|---|---|---|---|---|\n")
            for r in rows:
                star = " (default)" if r["default"] else ""
                md.write(f"| {r['family']} | {r['settings']}{star} | {r['total_ms']:.1f} | "
                         f"{r['first_hit_p99_r']:.3f} | {r['raw_first_hit_p99_r']:.3f} | "
                         f"{r['missed']} / {r['extra']} | {float(r['thickness_p99_r']):.3f} | "
                         f"{r['psnr_opaque_db']:.1f} / {r['psnr_translucent_db']:.1f} | "
                         f"{'yes' if r in f else ''} |\n")
            md.write("\n")
    axes[0][0].legend(fontsize=8)
    axes2[0][0].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(prefix + "_pareto.png", dpi=110)
    fig2.tight_layout()
    fig2.savefig(prefix + "_psnr.png", dpi=110)
    with open(prefix + "_front.csv", "w", newline="") as out:
        w = csv.writer(out)
        w.writerow(["scene", "family", "settings", "total_ms", "first_hit_p99_r", "psnr_opaque_db"])
        w.writerows(front_rows)

    # Stacked stages of each family's default (or first) configuration, first scene.
    path, rows = scenes[0]
    picks = []
    for fam in COLOUR:
        pts = [r for r in rows if r["family"] == fam]
        if pts:
            picks.append(next((r for r in pts if r["default"]), pts[0]))
    fig3, ax = plt.subplots(figsize=(8, 4.5))
    stage_names = []
    for r in picks:
        parts = r["stages"].split()
        r["stage_ms"] = {parts[k]: float(parts[k + 1]) for k in range(0, len(parts) - 1, 2)}
        for s in r["stage_ms"]:
            if s not in stage_names:
                stage_names.append(s)
    cmap = plt.get_cmap("tab20")
    for j, r in enumerate(picks):
        bottom = 0.0
        for k, s in enumerate(stage_names):
            v = r["stage_ms"].get(s, 0.0)
            if v > 0:
                ax.bar(j, v, bottom=bottom, color=cmap(k % 20),
                       label=s if s not in ax.get_legend_handles_labels()[1] else None)
                bottom += v
        if not r["stage_ms"]:
            ax.bar(j, r["total_ms"], color="grey")
    ax.set_xticks(range(len(picks)))
    ax.set_xticklabels([f"{r['family']}\n{r['settings']}" for r in picks], fontsize=8)
    ax.set_ylabel("ms per frame (median)")
    ax.set_title(title(rows, path) + ": stages", fontsize=9)
    ax.legend(fontsize=7, ncol=2)
    fig3.tight_layout()
    fig3.savefig(prefix + "_stages.png", dpi=110)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
