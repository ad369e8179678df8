#!/usr/bin/python3
"""Plot a z-slice (or a line along x) of one field of a minipagosa HDF5 dump to PNG, with the
material interfaces (the 0.5 contour of every fraction_<material> field) drawn over it.

    /usr/bin/python3 tools/plot_slice.py output/sedov/sedov_000407.h5 density [--k 0] [-o out.png]
    /usr/bin/python3 tools/plot_slice.py output/triple_point/triple_point_000186.h5 pressure
    /usr/bin/python3 tools/plot_slice.py output/sod_x/sod_x_000193.h5 velocity_x --line

Cell fields are drawn as cells; node fields (velocity_*) at the nodes (the colour of a node
fills the dual cell around it), so nothing is shifted by half a cell. A field that is not in the
dump is an error listing those that are. For lineouts with an exact solution: tools/lineout.py.
"""
import argparse
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("file")
    ap.add_argument("field")
    ap.add_argument("--k", type=int, default=0, help="z index of the slice (default 0)")
    ap.add_argument("--line", action="store_true", help="plot the x line at j = k = 0")
    ap.add_argument("-o", "--output", default=None, help="PNG path (default: FILE_FIELD.png)")
    a = ap.parse_args()
    with h5py.File(a.file, "r") as f:
        names = sorted(k for k in f.keys() if isinstance(f[k], h5py.Dataset))
        if a.field not in names:
            sys.exit(f"plot_slice: {a.file} has no field '{a.field}'; it has: " + ", ".join(names))
        data = np.asarray(f[a.field])
        cells = np.asarray(f.attrs["cells"]) if "cells" in f.attrs else None
        fractions = {n[len("fraction_"):]: np.asarray(f[n]) for n in names
                     if n.startswith("fraction_")}
        origin = np.asarray(f.attrs["origin"])
        spacing = np.asarray(f.attrs["spacing"])
        t = float(f.attrs["time"])
    ncell_x = int(cells[0]) if cells is not None else None
    node = ncell_x is not None and data.shape[2] == ncell_x + 1
    out = a.output or a.file.rsplit(".", 1)[0] + "_" + a.field + ".png"
    fig, ax = plt.subplots(figsize=(6, 5))
    shift = 0.0 if node else 0.5
    if a.line:
        x = origin[0] + (np.arange(data.shape[2]) + shift) * spacing[0]
        ax.plot(x, data[0, 0, :], ".-", ms=3)
        ax.set_xlabel("x")
        ax.set_ylabel(a.field)
    else:
        if a.k >= data.shape[0]:
            sys.exit(f"plot_slice: --k {a.k} is outside the {data.shape[0]} layers of '{a.field}'")
        sl = data[a.k]
        # cell field: edges at the nodes; node field: edges half a cell around each node
        xe = origin[0] + (np.arange(sl.shape[1] + 1) - (0.5 if node else 0.0)) * spacing[0]
        ye = origin[1] + (np.arange(sl.shape[0] + 1) - (0.5 if node else 0.0)) * spacing[1]
        im = ax.pcolormesh(xe, ye, sl, cmap="viridis", shading="flat")
        fig.colorbar(im, ax=ax, label=a.field + (" (nodes)" if node else ""))
        kc = min(a.k, next(iter(fractions.values())).shape[0] - 1) if fractions else 0
        handles = []
        for m, (name, fr) in enumerate(fractions.items()):
            xc = origin[0] + (np.arange(fr.shape[2]) + 0.5) * spacing[0]
            yc = origin[1] + (np.arange(fr.shape[1]) + 0.5) * spacing[1]
            if 0 < fr[kc].max() and fr[kc].min() < 1:
                ax.contour(xc, yc, fr[kc], levels=[0.5], colors=[f"C{m % 10}"], linewidths=1)
                handles.append(plt.Line2D([], [], color=f"C{m % 10}", lw=1, label=name))
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        if handles:
            ax.legend(handles=handles, loc="upper right", fontsize=7, title="interfaces (f = 0.5)")
    ax.set_title(f"{a.field}, t = {t:.4g}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
