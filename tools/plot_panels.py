#!/usr/bin/python3
"""Panels of z-slices: one column per dump, one row per field, with the material interfaces (the
0.5 contour of every fraction_<material> field) over each, to one PNG.

    /usr/bin/python3 tools/plot_panels.py OUT.png DUMP.h5 [DUMP.h5 ...] --fields pressure,burn_fraction
        [--z 0.6] [--log pressure]

--z picks the slice by position (cm; default the middle of the box); --log lists fields drawn on
a log scale. Cell fields only (node fields: tools/plot_slice.py).
"""
import argparse

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import LogNorm  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("output")
    ap.add_argument("dumps", nargs="+")
    ap.add_argument("--fields", default="pressure,density")
    ap.add_argument("--z", type=float, default=None, help="slice position along z (cm)")
    ap.add_argument("--log", default="", help="comma-separated fields on a log scale")
    a = ap.parse_args()
    fields = a.fields.split(",")
    logf = set(filter(None, a.log.split(",")))
    files = [h5py.File(d, "r") for d in a.dumps]
    f0 = files[0]
    n = f0.attrs["cells"]  # nx, ny, nz
    o, h = f0.attrs["origin"], f0.attrs["spacing"]
    z = a.z if a.z is not None else o[2] + 0.5 * n[2] * h[2]
    k = int(np.clip(np.floor((z - o[2]) / h[2]), 0, n[2] - 1))
    ext = [o[0], o[0] + n[0] * h[0], o[1], o[1] + n[1] * h[1]]
    xc = o[0] + (np.arange(n[0]) + 0.5) * h[0]
    yc = o[1] + (np.arange(n[1]) + 0.5) * h[1]
    fig, axes = plt.subplots(len(fields), len(files), figsize=(3.2 * len(files), 2.6 * len(fields)),
                             squeeze=False, constrained_layout=True)
    for r, name in enumerate(fields):
        for f in files:
            if name not in f:
                raise SystemExit("%s: no field '%s' (has: %s)" % (f.filename, name, ", ".join(f)))
        vals = [f[name][k, :, :] for f in files]
        lo = min(float(np.nanmin(v)) for v in vals)
        hi = max(float(np.nanmax(v)) for v in vals)
        norm = LogNorm(max(lo, hi * 1e-4), hi) if name in logf else None
        if norm is not None:  # below the scale (tension, the cold ambient) drawn at its floor
            vals = [np.clip(v, norm.vmin, None) for v in vals]
        for c, (f, v) in enumerate(zip(files, vals)):
            ax = axes[r][c]
            im = ax.imshow(v, origin="lower", extent=ext, norm=norm, cmap="viridis",
                           vmin=None if norm else lo, vmax=None if norm else hi)
            for m in (x for x in f if x.startswith("fraction_")):
                ax.contour(xc, yc, f[m][k, :, :], levels=[0.5], colors="w", linewidths=0.6)
            ax.set_title("%s, t = %.3g us" % (name, f.attrs["time"]), fontsize=8)
            ax.tick_params(labelsize=6)
        fig.colorbar(im, ax=axes[r].tolist(), shrink=0.8)
    fig.suptitle("z = %.3g cm slice" % (o[2] + (k + 0.5) * h[2]), fontsize=9)
    fig.savefig(a.output, dpi=110)
    print("wrote", a.output)


if __name__ == "__main__":
    main()
