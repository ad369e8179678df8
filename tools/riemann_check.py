#!/usr/bin/python3
"""Measure a quasi-1-D shock-tube dump (row j = k = 0) against the exact ideal-gas Riemann solution.

    /usr/bin/python3 tools/riemann_check.py leblanc output/leblanc/leblanc_000123.h5
    /usr/bin/python3 tools/riemann_check.py vacuum  DUMP   # Sod with rho_R = 1e-8, p_R = 1e-10

leblanc (configs/leblanc.yaml, gamma 5/3, membrane at x = 3): the shock position (crossing of the
density halfway between the right state and the shocked state) in cells from the exact one, the
peak specific internal energy beside the contact against the exact e*R, L1(rho).
vacuum (configs/sod_x.yaml with `--set regions.0.density=1e-8 --set regions.0.pressure=1e-10`,
membrane at x = 0.5): the crossings of rho = 1e-2 and 1e-4 against the exact fan, and the peak
node velocity next to cells above 1e-4 and 1e-6 against the exact star velocity u*.
Exact solver: the ideal-gas Riemann problem as in E. F. Toro, Riemann Solvers and Numerical
Methods for Fluid Dynamics, ch. 4 (pressure function, bisection for p*, fan sampling).
"""
import argparse
import math

import h5py
import numpy as np


def _f(p, rho, pk, g):
    if p > pk:  # shock
        a, b = 2 / ((g + 1) * rho), (g - 1) / (g + 1) * pk
        return (p - pk) * math.sqrt(a / (p + b))
    c = math.sqrt(g * pk / rho)  # rarefaction
    return 2 * c / (g - 1) * ((p / pk) ** ((g - 1) / (2 * g)) - 1)


def star(left, right, g):
    (rl, ul, pl), (rr, ur, pr) = left, right
    lo, hi = 1e-300, 10 * max(pl, pr)
    fun = lambda p: _f(p, rl, pl, g) + _f(p, rr, pr, g) + ur - ul
    for _ in range(400):  # bisection in log p: the star pressure spans many decades here
        mid = math.sqrt(lo * hi)
        if fun(mid) > 0:
            hi = mid
        else:
            lo = mid
    ps = math.sqrt(lo * hi)
    return ps, 0.5 * (ul + ur) + 0.5 * (_f(ps, rr, pr, g) - _f(ps, rl, pl, g))


def sample(left, right, g, s):
    """(rho, u, p) at x/t = s."""
    (rl, ul, pl), (rr, ur, pr) = left, right
    ps, us = star(left, right, g)
    gm = (g - 1) / (g + 1)
    if s < us:
        rho, u, p, sign = rl, ul, pl, 1
    else:
        rho, u, p, sign = rr, ur, pr, -1
    c = math.sqrt(g * p / rho)
    if ps > p:  # shock on this side
        rs = rho * (ps / p + gm) / (gm * ps / p + 1)
        speed = u - sign * c * math.sqrt((g + 1) / (2 * g) * ps / p + (g - 1) / (2 * g))
        behind = s > speed if sign > 0 else s < speed
        return (rs, us, ps) if behind else (rho, u, p)
    cs = c * (ps / p) ** ((g - 1) / (2 * g))
    head, tail = u - sign * c, us - sign * cs
    if (s < head) if sign > 0 else (s > head):
        return (rho, u, p)
    if (s > tail) if sign > 0 else (s < tail):
        return (rho * (ps / p) ** (1 / g), us, ps)
    uf = 2 / (g + 1) * (sign * c + (g - 1) / 2 * u + s)
    cf = 2 / (g + 1) * (c + sign * (g - 1) / 2 * (u - s))
    return (rho * (cf / c) ** (2 / (g - 1)), uf, p * (cf / c) ** (2 * g / (g - 1)))


def profile(path):
    with h5py.File(path, "r") as f:
        rho = np.asarray(f["density"], dtype=float)[0, 0, :]
        e = np.asarray(f["energy"], dtype=float)[0, 0, :]
        u = np.asarray(f["velocity_x"], dtype=float)[0, 0, :]
        h = float(f.attrs["spacing"][0])
        x0 = float(f.attrs["origin"][0])
        t = float(f.attrs["time"])
    return x0 + (np.arange(rho.size) + 0.5) * h, rho, e, u, h, t


def crossing(x, rho, level):
    """Rightmost x where rho falls through `level`; None where it does not fall through it
    inside the profile (every cell above it up to the last, or none above it)."""
    above = np.where(rho > level)[0]
    if above.size == 0 or int(above.max()) + 1 >= rho.size:
        return None
    i = int(above.max())
    return x[i] + (x[i + 1] - x[i]) * (rho[i] - level) / (rho[i] - rho[i + 1])


def leblanc(path):
    g = 5 / 3
    left, right = (1.0, 0.0, (g - 1) * 0.1), (1e-3, 0.0, (g - 1) * 1e-10)
    x, rho, e, u, h, t = profile(path)
    ps, us = star(left, right, g)
    rs = sample(left, right, g, us + 1e-9)[0]
    shock_speed = us * rs / (rs - right[0])
    xs, xn = 3 + shock_speed * t, crossing(x, rho, 0.5 * (right[0] + rs))
    es = ps / ((g - 1) * rs)
    near = (x > 3 + us * t - 0.5) & (x < xs - 0.2)
    ex = np.array([sample(left, right, g, (xi - 3) / t)[0] for xi in x])
    print(f"LeBlanc {x.size} cells t={t:g}: shock {xn:.4f} exact {xs:.4f} ({(xn - xs) / h:+.1f} "
          f"cells); contact e peak {e[near].max():.4f} vs e*R {es:.4f} "
          f"({100 * (e[near].max() / es - 1):+.1f} %); L1(rho) {np.abs(rho - ex).sum() * h:.3e}")


def vacuum(path):
    g = 1.4
    left, right = (1.0, 0.0, 1.0), (1e-8, 0.0, 1e-10)
    x, rho, e, u, h, t = profile(path)
    ps, us = star(left, right, g)
    fine = np.linspace(0.5, x[-1], 200001)
    exf = np.array([sample(left, right, g, (xi - 0.5) / t)[0] for xi in fine])
    out = [f"near-vacuum Sod {x.size} cells t={t:g}: u* {us:.4f}"]
    for level in (1e-2, 1e-4):
        xe = crossing(fine, exf, level)
        xn = crossing(x, rho, level)
        if xe is None:  # (the exact fan's point at this level has left the box: a wall's)
            out.append(f"rho={level:g}: the exact front has passed the box's end by t={t:g}, "
                       "not measured (use an earlier dump)")
        elif xn is None:
            out.append(f"rho={level:g}: the run's gas is above it up to the last cell "
                       f"(exact {xe:.4f})")
        else:
            out.append(f"rho={level:g} at {xn:.4f} vs {xe:.4f} ({(xn - xe) / h:+.1f} cells)")
    # node velocities (one more than cells); a node's neighbour density is its lighter cell's
    side = np.concatenate([[rho[0]], np.minimum(rho[:-1], rho[1:]), [rho[-1]]])[: u.size]
    for level in (1e-4, 1e-6):
        peak = u[side > level].max()
        out.append(f"peak u (cells > {level:g}) {peak:.4f} ({100 * (peak / us - 1):+.1f} %)")
    print("; ".join(out))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("problem", choices=["leblanc", "vacuum"])
    ap.add_argument("files", nargs="+")
    a = ap.parse_args()
    for p in a.files:
        (leblanc if a.problem == "leblanc" else vacuum)(p)


if __name__ == "__main__":
    main()
