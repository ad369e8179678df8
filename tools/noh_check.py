#!/usr/bin/python3
"""Measure a 3-D Noh octant dump against the exact solution (Noh 1987, J. Comput. Phys. 72:78).

    /usr/bin/python3 tools/noh_check.py output/noh/noh_000123.h5 [--json] [--angles]

gamma = 5/3, rho0 = 1, inflow speed 1, shock radius R = t/3; inside rho = 64, e = 1/2;
outside rho = (1 + t/r)^2. Prints: plateau mean density over cells with 0.3 R < r < 0.8 R,
the checkerboard measure (mean |rho - mean of its 6 face neighbours| / 64 over the same cells),
the shock radius from the volume of cells above rho = 40 (halfway between 16 and 64, octant
volume pi R^3 / 6), the plateau energy mean, and the radial profile of the innermost cells
(wall heating: the density deficit next to the origin). With --angles also the plateau's
anisotropy (docs/numerics.md, "Tensor viscosity"): mean density and energy of the plateau cells
within 20 degrees of an axis and of the diagonal (1,1,1), and the mean density of the plateau
cells by their distance in cells from the nearest axis (0, 1, ... 9: the axis band).
"""
import argparse
import json

import h5py
import numpy as np


def analyse(path):
    with h5py.File(path, "r") as f:
        rho = np.asarray(f["density"], dtype=float)  # (k, j, i)
        e = np.asarray(f["energy"], dtype=float)
        origin = np.asarray(f.attrs["origin"])
        dx = np.asarray(f.attrs["spacing"])
        t = float(f.attrs["time"])
    nz, ny, nx = rho.shape
    x = origin[0] + (np.arange(nx) + 0.5) * dx[0]
    y = origin[1] + (np.arange(ny) + 0.5) * dx[1]
    z = origin[2] + (np.arange(nz) + 0.5) * dx[2]
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")
    r = np.sqrt(X * X + Y * Y + Z * Z)
    R = t / 3.0
    win = (r > 0.3 * R) & (r < 0.8 * R)
    # checkerboard: interior cells only (all 6 neighbours exist)
    nb = np.zeros_like(rho)
    nb[1:-1, 1:-1, 1:-1] = (rho[2:, 1:-1, 1:-1] + rho[:-2, 1:-1, 1:-1] + rho[1:-1, 2:, 1:-1] +
                            rho[1:-1, :-2, 1:-1] + rho[1:-1, 1:-1, 2:] + rho[1:-1, 1:-1, :-2]) / 6
    inner = np.zeros_like(win)
    inner[1:-1, 1:-1, 1:-1] = True
    cw = win & inner
    vol = float(np.prod(dx)) * np.count_nonzero(rho > 40.0)
    rs = (6.0 * vol / np.pi) ** (1.0 / 3.0)
    # radial profile of the first cells along the diagonal-free shells
    shells = []
    h = dx[0]
    for s in range(6):
        m = (r >= s * h) & (r < (s + 1) * h)
        if np.any(m):
            shells.append(float(rho[m].mean()))
    # anisotropy over the plateau window: cones about the axes and the diagonal, and the band
    # about the nearest axis (the axis of the largest coordinate)
    rs_ = np.where(r > 0, r, 1.0)
    along = np.maximum(np.maximum(X, Y), Z)
    cos20 = np.cos(np.radians(20.0))
    ax = win & (along / rs_ > cos20)
    dg = win & ((X + Y + Z) / (np.sqrt(3.0) * rs_) > cos20)
    dist = np.sqrt(r * r - along ** 2) / h
    band = []
    for b in range(10):
        m = win & (dist >= b) & (dist < b + 1)
        band.append(float(rho[m].mean()) if np.any(m) else None)
    return {
        "file": path,
        "axis_cone": [float(rho[ax].mean()), float(e[ax].mean())] if np.any(ax) else None,
        "diagonal_cone": [float(rho[dg].mean()), float(e[dg].mean())] if np.any(dg) else None,
        "axis_band": band,
        "cells": [int(nx), int(ny), int(nz)],
        "t": t,
        "plateau_mean": float(rho[win].mean()),
        "plateau_rel_error": float(rho[win].mean() / 64.0 - 1.0),
        "plateau_energy": float(e[win].mean()),
        "checkerboard": float(np.abs(rho - nb)[cw].mean() / 64.0),
        "shock_radius": rs,
        "shock_radius_rel_error": rs / R - 1.0,
        "inner_shells": shells,
    }


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("files", nargs="+")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("--angles", action="store_true", help="also the axis/diagonal anisotropy")
    a = ap.parse_args()
    res = [analyse(p) for p in a.files]
    if a.json:
        print(json.dumps(res, indent=1))
        return
    for d in res:
        print(f"{d['cells'][0]:4d}^3 t={d['t']:.3f} plateau {d['plateau_mean']:7.3f} "
              f"({100 * d['plateau_rel_error']:+6.2f} %) e {d['plateau_energy']:.4f} "
              f"checker {100 * d['checkerboard']:5.2f} % R_s {d['shock_radius']:.4f} "
              f"({100 * d['shock_radius_rel_error']:+5.2f} %) inner "
              + " ".join(f"{v:.1f}" for v in d["inner_shells"]))
        if a.angles:
            ac, dc = d["axis_cone"], d["diagonal_cone"]
            cone = lambda c: f"{c[0]:.1f} / {c[1]:.3f}" if c else "-"
            print(f"      within 20 deg of an axis rho/e {cone(ac)}, of the diagonal {cone(dc)}; "
                  "by cells from the nearest axis "
                  + " ".join("-" if v is None else f"{v:.1f}" for v in d["axis_band"]))


if __name__ == "__main__":
    main()
