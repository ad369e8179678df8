#!/usr/bin/python3
"""Render the materials of a minipagosa run on a cut plane, one colour per material, at given
times (the pictures of the PAGOSA paper's Figures 1-2 for configs/perforator.yaml).

    /usr/bin/python3 tools/render_interfaces.py output/perforator --times 0 10 60 \\
        -o docs/images/perforator
    ... --plane y=0            the cut (default y=0: the plane through both charge axes)
    ... --mode contour         the 0.5-contour of each fraction instead of filled colours
    ... --materials copper steel   draw only these (the rest white)
    ... --field pressure       a field in grey under the 0.5-contours (implies --mode contour)

Filled mode colours each cell by its material of largest volume fraction. Writes
<prefix>_t<time>.png per time and <prefix>_panels.png with every time side by side; prints the
paths. A time with no dump, an unknown material or field is an error naming what there is.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import ListedColormap  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dumps  # noqa: E402

TOOL = "render_interfaces"
# Fixed colours for the usual material names (so every picture of a scene matches); others
# take the tab10 cycle.
COLOURS = {"copper": "#c8702a", "steel": "#7b8794", "quartz": "#d9c79a", "water": "#9cc8ea",
           "air": "#ffffff", "well_fluid": "#e4eef6", "comp_b": "#d6404e", "he": "#d6404e", "products": "#d6404e"}


def colours_for(materials):
    out, k = {}, 0
    for m in materials:
        if m in COLOURS:
            out[m] = COLOURS[m]
        else:
            out[m] = f"C{k % 10}"
            k += 1
    return out


def draw(ax, d, axis, index, mats, shown, mode, field, colours):
    rows_axis, cols_axis = [a for a in (2, 1, 0) if a != axis]
    xe, ye = d.edges(cols_axis), d.edges(rows_axis)
    xc, yc = d.centres(cols_axis), d.centres(rows_axis)
    fr = np.stack([d.cut(d.fraction(m), axis, index) for m in mats])
    if field:
        data = d.field(field)
        if data.shape != tuple(d.cells[::-1]):
            data = data[:-1, :-1, :-1]  # node field: the node at each cell's low corner
        im = ax.pcolormesh(xe, ye, d.cut(data, axis, index), cmap="Greys", shading="flat")
        plt.colorbar(im, ax=ax, label=field, orientation="horizontal", shrink=0.6, pad=0.25)
    if mode == "filled" and not field:
        top = np.argmax(fr, axis=0)
        cmap = ListedColormap([colours[m] if m in shown else "#ffffff" for m in mats])
        ax.pcolormesh(xe, ye, top, cmap=cmap, vmin=-0.5, vmax=len(mats) - 0.5, shading="flat")
    else:
        for q, m in enumerate(mats):
            if m not in shown:
                continue
            f = fr[q]
            if f.max() > 0.5 and f.min() < 0.5:
                c = "black" if colours[m] == "#ffffff" else colours[m]
                ax.contour(xc, yc, f, levels=[0.5], colors=[c], linewidths=1.0)
    ax.set_aspect("equal")
    ax.set_xlabel(dumps.AXES[cols_axis] + " (cm)")
    ax.set_ylabel(dumps.AXES[rows_axis] + " (cm)")
    ax.set_title(f"t = {d.time:.4g} us")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("run", help="the run's output directory (or dump files)", nargs="+")
    ap.add_argument("--times", type=float, nargs="+", default=[0.0, 10.0, 60.0])
    ap.add_argument("--tol", type=float, default=1e-6, help="time match, relative (default 1e-6)")
    ap.add_argument("--plane", default="y=0", help="cut plane, AXIS=VALUE (default y=0)")
    ap.add_argument("--mode", choices=["filled", "contour"], default="filled")
    ap.add_argument("--materials", nargs="+", default=None, help="draw only these")
    ap.add_argument("--field", default=None, help="a field in grey under the contours")
    ap.add_argument("-o", "--output", default=None, help="PNG prefix (default RUN/interfaces)")
    a = ap.parse_args()

    source = a.run[0] if len(a.run) == 1 and os.path.isdir(a.run[0]) else a.run
    runs = dumps.list_dumps(TOOL, source)
    picked = dumps.pick_times(TOOL, runs, a.times, a.tol)
    axis, value = dumps.parse_plane(TOOL, a.plane)
    prefix = a.output or os.path.join(a.run[0] if isinstance(source, str) else ".", "interfaces")
    first = dumps.Dump(TOOL, picked[0][2])
    mats = first.materials
    if not mats:
        dumps.fail(TOOL, f"{first.path} has no fraction_<material> fields")
    shown = set(mats)
    if a.materials:
        for m in a.materials:
            if m not in mats:
                dumps.fail(TOOL, f"no material '{m}' in the run; it has: " + ", ".join(mats))
        shown = set(a.materials)
    if a.field:
        first.field(a.field)  # the error names the fields there are
    colours = colours_for(mats)
    index = first.plane_index(axis, value)
    where = f"{dumps.AXES[axis]} = {first.centres(axis)[index]:.4g} (layer {index})"

    legend = [Patch(facecolor=colours[m], edgecolor="black", lw=0.5, label=m) for m in mats
              if m in shown]
    rows_axis, cols_axis = [q for q in (2, 1, 0) if q != axis]
    extent = [first.cells[cols_axis] * first.spacing[cols_axis],
              first.cells[rows_axis] * first.spacing[rows_axis]]
    width = 7.0
    height = max(2.5, width * extent[1] / extent[0] + 1.2)
    outputs = []
    fig_all, axes = plt.subplots(len(picked), 1, figsize=(width, height * len(picked)),
                                 squeeze=False)
    for n, (_, _, path) in enumerate(picked):
        d = dumps.Dump(TOOL, path)
        if d.materials != mats:
            dumps.fail(TOOL, f"{path} has materials {d.materials}, the first dump {mats}")
        fig, ax = plt.subplots(figsize=(width, height))
        for target in (ax, axes[n][0]):
            draw(target, d, axis, index, mats, shown, a.mode, a.field, colours)
            target.legend(handles=legend, loc="upper left", bbox_to_anchor=(1.01, 1.0),
                          fontsize=8, frameon=False)
        ax.set_title(f"t = {d.time:.4g} us, cut {where}")
        fig.tight_layout()
        out = f"{prefix}_t{d.time:g}.png"
        fig.savefig(out, dpi=120, bbox_inches="tight")
        plt.close(fig)
        outputs.append(out)
    fig_all.suptitle(f"materials on the cut {where}")
    fig_all.tight_layout()
    out = f"{prefix}_panels.png"
    fig_all.savefig(out, dpi=110, bbox_inches="tight")
    outputs.append(out)
    for o in outputs:
        print(o)


if __name__ == "__main__":
    main()
