#!/usr/bin/python3
"""Pareto plots of the speed/accuracy sweep (perf/tradeoff): error against wall time, one panel
per scene (three to a row), one marker per option set, the Pareto front of each input file drawn
as a line.

    /usr/bin/python3 perf/plot_tradeoff.py perf/results/tradeoff_double.json \
        [perf/results/tradeoff_float.json] -o perf/results/tradeoff.png

Several inputs (the double and the float build's sweeps) share the axes; their precision labels
the points.
"""
import argparse
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("-o", "--output", default="tradeoff.png")
    a = ap.parse_args()
    runs = []
    for path in a.files:
        with open(path) as f:
            d = json.load(f)
        if "points" not in d:
            sys.exit(f"plot_tradeoff: {path} is not a perf/tradeoff JSON file (no 'points')")
        runs.append(d)
    scenes = []
    for d in runs:
        for p in d["points"]:
            if p["scene"] not in scenes:
                scenes.append(p["scene"])
    ncols = min(3, len(scenes))
    nrows = (len(scenes) + ncols - 1) // ncols
    fig, axes = plt.subplots(nrows, ncols, figsize=(4.6 * ncols, 4 * nrows), squeeze=False)
    for ax in axes.flat[len(scenes):]:
        ax.set_visible(False)
    markers = "os^vDP*X"
    for ax, scene in zip(axes.flat, scenes):
        for r, d in enumerate(runs):
            pts = [p for p in d["points"] if p["scene"] == scene and p["ok"] and p["error"]]
            opts = []
            for p in pts:
                if p["options"] not in opts:
                    opts.append(p["options"])
            for k, o in enumerate(opts):
                sel = [p for p in pts if p["options"] == o]
                # the values, but "ke_fix=false" for a switch (a bare "false" says nothing)
                short = " ".join(s.split(".")[-1] if s.split("=")[1] in ("true", "false")
                                 else s.split("=")[1] for s in o.split())
                ax.loglog([p["wall_s"] for p in sel], [p["error"] for p in sel],
                          markers[k % len(markers)], color=f"C{k}", mfc="none" if r else None,
                          label=f"{short} ({d['real']})")
            front = sorted((p for p in pts if p["pareto"]), key=lambda p: p["wall_s"])
            ax.loglog([p["wall_s"] for p in front], [p["error"] for p in front], "-",
                      color="k" if r == 0 else "0.5", lw=1)
        measure = next(p["measure"] for d in runs for p in d["points"] if p["scene"] == scene)
        ax.set_title(scene)
        ax.set_xlabel("wall time of the run (s)")
        ax.set_ylabel(measure)
        ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    print(a.output)


if __name__ == "__main__":
    main()
