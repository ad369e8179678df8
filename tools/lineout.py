#!/usr/bin/python3
"""Plot a line of fields along x (row j = k = 0) of a minipagosa HDF5 dump, with the exact
solution overlaid where one is known, to PNG.

    /usr/bin/python3 tools/lineout.py output/sod_x/sod_x_000193.h5 --exact sod
    /usr/bin/python3 tools/lineout.py DUMP density pressure --exact leblanc -o out.png
    /usr/bin/python3 tools/lineout.py DUMP --exact mader

Fields default to density, pressure, velocity_x and energy (node fields are drawn at the nodes,
cell fields at the cell centres). --exact: sod, leblanc, test123 (ideal-gas Riemann problems of
configs/sod_x.yaml, leblanc.yaml, test123.yaml; E. F. Toro, ch. 4, via tools/riemann_check.py)
or mader (configs/mader.yaml: gamma = 3, D = 1, p_cj = 0.25; the Taylor wave behind a CJ front
lit at x = 0, Fickett & Davis). A field that is not in the dump is an error listing those that
are.
"""
import argparse
import math
import os
import sys

import h5py
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import riemann_check  # noqa: E402

# name: (left state, right state (rho, u, p), gamma, membrane x)
RIEMANN = {
    "sod": ((1.0, 0.0, 1.0), (0.125, 0.0, 0.1), 1.4, 0.5),
    "leblanc": ((1.0, 0.0, (5 / 3 - 1) * 0.1), (1e-3, 0.0, (5 / 3 - 1) * 1e-10), 5 / 3, 3.0),
    "test123": ((1.0, -2.0, 0.4), (1.0, 2.0, 0.4), 1.4, 0.5),
}


def riemann_exact(name, x, t):
    left, right, g, x0 = RIEMANN[name]
    out = {"density": [], "pressure": [], "velocity_x": [], "energy": []}
    for xx in x:
        rho, u, p = riemann_check.sample(left, right, g, (xx - x0) / t) if t > 0 else (
            left if xx < x0 else right)
        out["density"].append(rho)
        out["pressure"].append(p)
        out["velocity_x"].append(u)
        out["energy"].append(p / ((g - 1) * rho))
    return {k: np.asarray(v) for k, v in out.items()}


def mader_exact(x, t, g=3.0, d=1.0, pcj=0.25):
    rho0 = (g + 1) * pcj / d**2
    rcj, ucj, ccj = rho0 * (g + 1) / g, d / (g + 1), g * d / (g + 1)
    j = ucj - 2 * ccj / (g - 1)
    out = {"density": [], "pressure": [], "velocity_x": [], "energy": []}
    for xx in x:
        s = xx / t if t > 0 else math.inf
        if s > d:
            rho, u, p = rho0, 0.0, 0.0
        else:
            if s <= (g - 1) / 2 * (0 - j):  # at rest behind the fan's tail
                u, c = 0.0, (g - 1) / 2 * (0 - j)
            else:
                u = (2 * s + (g - 1) * j) / (g + 1)
                c = s - u
            r = c / ccj
            rho, p = rcj * r ** (2 / (g - 1)), pcj * r ** (2 * g / (g - 1))
        out["density"].append(rho)
        out["pressure"].append(p)
        out["velocity_x"].append(u)
        out["energy"].append(np.nan)  # the explosive's e includes its chemical energy
    return {k: np.asarray(v) for k, v in out.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("file")
    ap.add_argument("fields", nargs="*", default=["density", "pressure", "velocity_x", "energy"])
    ap.add_argument("--exact", choices=sorted(list(RIEMANN) + ["mader"]))
    ap.add_argument("-o", "--output", default=None, help="PNG path (default: FILE_lineout.png)")
    a = ap.parse_args()
    with h5py.File(a.file, "r") as f:
        names = sorted(k for k in f.keys() if isinstance(f[k], h5py.Dataset))
        missing = [n for n in a.fields if n not in names]
        if missing:
            sys.exit(f"lineout: {a.file} has no field {', '.join(missing)}; it has: "
                     + ", ".join(names))
        data = {n: np.asarray(f[n], dtype=float) for n in a.fields}
        origin = np.asarray(f.attrs["origin"], dtype=float)
        h = float(f.attrs["spacing"][0])
        t = float(f.attrs["time"])
    fig, axes = plt.subplots(len(a.fields), 1, figsize=(7, 2.2 * len(a.fields)), sharex=True,
                             squeeze=False)
    for ax, n in zip(axes[:, 0], a.fields):
        v = data[n][0, 0, :]
        node = v.size == data[n].shape[2] and n.startswith("velocity")
        x = origin[0] + (np.arange(v.size) + (0.0 if node else 0.5)) * h
        ax.plot(x, v, ".", ms=3, label="minipagosa")
        if a.exact:
            xe = np.linspace(x[0], x[-1], 2000)
            ex = mader_exact(xe, t) if a.exact == "mader" else riemann_exact(a.exact, xe, t)
            if n in ex and not np.all(np.isnan(ex[n])):
                ax.plot(xe, ex[n], "-", lw=1, color="k", label="exact")
        ax.set_ylabel(n)
        if n == a.fields[0]:
            ax.legend(loc="best", fontsize=8)
    axes[-1, 0].set_xlabel("x")
    fig.suptitle(f"{os.path.basename(a.file)}, t = {t:.4g}")
    fig.tight_layout()
    out = a.output or a.file.rsplit(".", 1)[0] + "_lineout.png"
    fig.savefig(out, dpi=110)
    print(out)


if __name__ == "__main__":
    main()
