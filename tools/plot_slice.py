#!/usr/bin/python3
"""Plot a z-slice (or a line along x) of one field of a minipagosa HDF5 dump to PNG.

    /usr/bin/python3 tools/plot_slice.py output/sedov/sedov_000407.h5 density [--k 0] [-o out.png]
    /usr/bin/python3 tools/plot_slice.py output/sod_x/sod_x_000193.h5 density --line
"""
import argparse

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
        data = np.asarray(f[a.field])
        origin = np.asarray(f.attrs["origin"])
        spacing = np.asarray(f.attrs["spacing"])
        t = float(f.attrs["time"])
    out = a.output or a.file.rsplit(".", 1)[0] + "_" + a.field + ".png"
    fig, ax = plt.subplots(figsize=(6, 5))
    if a.line:
        x = origin[0] + (np.arange(data.shape[2]) + 0.5) * spacing[0]
        ax.plot(x, data[0, 0, :], ".-", ms=3)
        ax.set_xlabel("x")
        ax.set_ylabel(a.field)
    else:
        sl = data[a.k]
        ext = [origin[0], origin[0] + spacing[0] * sl.shape[1],
               origin[1], origin[1] + spacing[1] * sl.shape[0]]
        im = ax.imshow(sl, origin="lower", extent=ext, cmap="viridis")
        fig.colorbar(im, ax=ax, label=a.field)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
    ax.set_title(f"{a.field}, t = {t:.4g}")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
