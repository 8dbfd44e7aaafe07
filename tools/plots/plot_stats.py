#!/usr/bin/env python3
"""tools/plots/plot_stats.py - a run's per-step stats (the stats.jsonl output) as a chart.

Top: the in-situ time of each render step on the solver's thread, stacked by pass (each pass
summed over the views; classification and compaction on the host as one band). Bottom: the
particles the solver handed over, the boundary particles voxelized, and the spans stored (all
views), so a cost can be read against what caused it.

    python3 tools/plots/plot_stats.py main-job-output/stats.jsonl main-job-output/stats.png

Needs matplotlib (Debian: python3-matplotlib, installed by `tools/scripts/setup.sh --media`).
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The GPU passes in pipeline order; anything else a view reports goes into "other".
PASSES = ["clear", "upload", "bin", "splat", "compress", "connect", "filter", "normals",
          "deep_ao", "shade", "readback"]


def read(path):
    rows = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            if not line.strip():
                continue
            try:
                rows.append(json.loads(line))
            except json.JSONDecodeError as e:
                sys.exit(f"plot_stats: {path}:{number}: not a JSON line ({e.msg})")
    return [r for r in rows if r.get("views")]


def pass_times(row):
    """Milliseconds per pass over all views, host work first, the rest as 'other'."""
    t = row["timings_ms"]
    out = {"classify + compact": t.get("classify", 0) + t.get("compact", 0)}
    views_total = 0.0
    for view in row["views"].values():
        for name, ms in view["timings_ms"].items():
            key = name if name in PASSES else "other"
            out[key] = out.get(key, 0) + ms
            views_total += ms
    out["other"] = out.get("other", 0) + max(0.0, t.get("render", 0) - views_total)
    return out


def main(argv):
    if len(argv) != 3:
        sys.exit("usage: plot_stats.py STATS.jsonl OUT.png")
    rows = read(argv[1])
    if not rows:
        sys.exit(f"plot_stats: {argv[1]} holds no render step")
    steps = [r["step"] for r in rows]
    times = [pass_times(r) for r in rows]
    bands = ["classify + compact"] + [p for p in PASSES if any(p in t for t in times)] + ["other"]

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(10, 6.5), sharex=True,
                                      gridspec_kw={"height_ratios": [3, 2]})
    colors = plt.get_cmap("tab20").colors
    top.stackplot(steps, [[t.get(b, 0) / 1e3 for t in times] for b in bands], labels=bands,
                  colors=[colors[i % len(colors)] for i in range(len(bands))], step="mid")
    top.set_ylabel("seconds per render step")
    top.set_title("in situ, on the solver's thread")
    top.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=7)
    top.grid(alpha=0.3)

    counters = [r["counters"] for r in rows]
    bottom.plot(steps, [c["particles"] for c in counters], label="particles")
    bottom.plot(steps, [c["boundary"] for c in counters], label="boundary (voxelized)")
    spans = [sum(v["counters"].get("spans.stored", 0) for v in r["views"].values()) for r in rows]
    bottom.plot(steps, spans, label="spans stored (all views)")
    bottom.set_xlabel("solver step")
    bottom.set_ylabel("count")
    bottom.legend(loc="upper left", bbox_to_anchor=(1.01, 1), fontsize=7)
    bottom.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(argv[2], dpi=110)
    print(f"wrote {argv[2]}")


if __name__ == "__main__":
    main(sys.argv)
