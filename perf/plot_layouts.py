#!/usr/bin/python3
"""Plot the layout study (perf/bench_layouts --json FILE): dense/compact time and memory ratios
against the mixed-cell fraction, one line per material count.

    /usr/bin/python3 perf/plot_layouts.py perf/results/layouts.json perf/results/layouts.png
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(src, dst):
    with open(src) as f:
        data = json.load(f)
    runs = data["runs"]
    mats = sorted({r["materials"] for r in runs})
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    for m in mats:
        rs = sorted((r for r in runs if r["materials"] == m), key=lambda r: r["mixed_fraction_design"])
        x = [100 * r["mixed_fraction_design"] for r in rs]
        axes[0].plot(x, [r["dense_over_compact_time"] for r in rs], "o-", label=f"{m} materials")
        axes[1].plot(x, [r["dense_bytes_per_cell"] / r["compact_bytes_per_cell"] for r in rs], "o-",
                     label=f"{m} materials")
    for ax, title in zip(axes, ["time per cycle, dense / compact", "memory per cell, dense / compact"]):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.axhline(1.0, color="grey", lw=0.8)
        ax.set_xlabel("mixed cells (%)")
        ax.set_title(title)
        ax.legend()
    fig.suptitle(f"minipagosa layouts: {data['cells']} cells, {data['kokkos_execution_space']} "
                 f"{data['threads_per_rank']} threads x {data['ranks']} ranks, "
                 f"STREAM {data['stream_triad_GBs']:.1f} GB/s")
    fig.tight_layout()
    fig.savefig(dst, dpi=110)
    print("wrote", dst)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
