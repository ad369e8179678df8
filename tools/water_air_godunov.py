#!/usr/bin/python3
"""Reference 1-D Lagrangian Godunov runs of the water-air shock tube (configs/water_air.yaml).

Answers one question with numbers: does a textbook Godunov scheme keep the pure water's pressure
non-negative in this tube? The exact star pressure is 4.8e-6 Mbar, 0.05 % of the 1e-2 Mbar
jump, so any scheme whose rarefaction tail undershoots by more than that goes negative there.

Both schemes are cell-centred and Lagrangian (the contact is a cell face, so there is no mixed
cell and no interface error): conservative updates of momentum and total energy in the mass
coordinate, with the face pressure and velocity from the exact two-stiffened-gas Riemann solver
(Toro, "Riemann Solvers and Numerical Methods for Fluid Dynamics", 3rd ed. 2009, ch. 4, with
p -> p + p_inf on each side). Order 1 takes the cell states; order 2 is MUSCL-Hancock: minmod
slopes of (specific volume, u, p) in each cell, a half-step predictor from the Lagrangian
equations in primitive form, then the same Riemann solver. The initial state, the mesh, the end
time, the first time step (0.01 us, growth 1.1) and the Courant number (0.5) are the deck's;
the Godunov steps use their own Courant limit dx/c (the code's is dx/(c_eff + |u|)).

For comparison it also runs a 1-D model of minipagosa's own Lagrangian step without the remap
(`--staggered`): node velocities, cell pressures, predictor-corrector, the viscosity
q = rho (c_Q du^2 - c_L c du) in compression with Christensen's limiter (c_Q 0.75, c_L 0.2,
docs/numerics.md), and the same step with an unlimited 0.5 rho c |du| in compression and
expansion instead (acoustic Riemann dissipation between two nodes).

    /usr/bin/python3 tools/water_air_godunov.py [--cells 200 400 800] [--json out.json]
"""
import argparse
import json

import numpy as np

# Deck values: water_stiffened (gamma 4.4, p_inf 6e-3 Mbar) at rho 1, p 1e-2 for x < 70 cm;
# air (gamma 1.4) at rho 1e-3, p 1e-6; 100 cm, reflective ends, t = 240 us. Units cm g us Mbar.
LENGTH, X0, T_END = 100.0, 70.0, 240.0
WATER = dict(gamma=4.4, p_inf=6e-3, rho=1.0, p=1e-2)
AIR = dict(gamma=1.4, p_inf=0.0, rho=1e-3, p=1e-6)


def side_function(p, rho, pk, gamma, p_inf):
    """Toro's f_K(p) and its derivative for a stiffened gas, element-wise."""
    big_p, big_pk = p + p_inf, pk + p_inf
    c = np.sqrt(gamma * big_pk / rho)
    a = 2.0 / ((gamma + 1.0) * rho)
    b = (gamma - 1.0) / (gamma + 1.0) * big_pk
    shock = big_p > big_pk
    safe = np.maximum(big_p, 1e-300)
    f_shock = (big_p - big_pk) * np.sqrt(a / (big_p + b))
    d_shock = np.sqrt(a / (b + big_p)) * (1.0 - (big_p - big_pk) / (2.0 * (b + big_p)))
    expo = (gamma - 1.0) / (2.0 * gamma)
    f_fan = 2.0 * c / (gamma - 1.0) * ((safe / big_pk) ** expo - 1.0)
    d_fan = (safe / big_pk) ** (-(gamma + 1.0) / (2.0 * gamma)) / (rho * c)
    return np.where(shock, f_shock, f_fan), np.where(shock, d_shock, d_fan)


def riemann(left, right):
    """Exact star pressure and velocity for arrays of (rho, u, p, gamma, p_inf) states."""
    rl, ul, pl, gl, il = left
    rr, ur, pr, gr, ir = right
    floor = -np.minimum(il, ir) + 1e-14
    p = np.maximum(0.5 * (pl + pr), floor + 1e-12)
    for _ in range(100):
        f1, d1 = side_function(p, rl, pl, gl, il)
        f2, d2 = side_function(p, rr, pr, gr, ir)
        new = p - (f1 + f2 + ur - ul) / (d1 + d2)
        new = np.where(new <= floor, 0.5 * (p + floor), new)
        done = np.all(np.abs(new - p) <= 1e-14 * np.maximum(np.abs(new), 1e-10))
        p = new
        if done:
            break
    f1, _ = side_function(p, rl, pl, gl, il)
    f2, _ = side_function(p, rr, pr, gr, ir)
    return p, 0.5 * (ul + ur) + 0.5 * (f2 - f1)


def minmod(a, b):
    return np.where(a * b > 0, np.sign(a) * np.minimum(np.abs(a), np.abs(b)), 0.0)


def initial_state(cells):
    """The deck's mesh and initial state: nodes x, the water mask, gamma, p_inf, rho, p."""
    x = np.linspace(0.0, LENGTH, cells + 1)
    water = 0.5 * (x[1:] + x[:-1]) < X0
    pick = lambda key: np.where(water, WATER[key], AIR[key])
    return x, water, pick("gamma"), pick("p_inf"), pick("rho"), pick("p")


def run(cells, order):
    x, water, gamma, p_inf, rho, p = initial_state(cells)
    mass = rho * np.diff(x)
    u = np.zeros(cells)
    energy = (p + gamma * p_inf) / ((gamma - 1.0) * rho)  # total specific energy, u = 0

    def pad(a, parity=1.0):  # one mirror ghost each end (reflective walls)
        return np.concatenate([[parity * a[0]], a, [parity * a[-1]]])

    t, dt, cycles = 0.0, 0.01, 0
    while t < T_END * (1 - 1e-14):
        rho = mass / np.diff(x)
        p = (gamma - 1.0) * rho * (energy - 0.5 * u * u) - gamma * p_inf
        c = np.sqrt(gamma * (p + p_inf) / rho)
        if cycles > 0:
            dt = min(0.5 * np.min(np.diff(x) / c), 1.1 * dt)
        dt = min(dt, T_END - t)
        tau = 1.0 / rho
        if order == 2:
            tg, ug, pg = pad(tau), pad(u, -1.0), pad(p)
            d_tau = minmod(tg[1:-1] - tg[:-2], tg[2:] - tg[1:-1])
            d_u = minmod(ug[1:-1] - ug[:-2], ug[2:] - ug[1:-1])
            d_p = minmod(pg[1:-1] - pg[:-2], pg[2:] - pg[1:-1])
            # Hancock half step of tau_t = u_m, u_t = -p_m, p_t = -(rho c)^2 u_m
            tau_h = tau + 0.5 * dt * d_u / mass
            u_h = u - 0.5 * dt * d_p / mass
            p_h = p - 0.5 * dt * (rho * c) ** 2 * d_u / mass
            lo = (tau_h - 0.5 * d_tau, u_h - 0.5 * d_u, p_h - 0.5 * d_p)
            hi = (tau_h + 0.5 * d_tau, u_h + 0.5 * d_u, p_h + 0.5 * d_p)
            ok = (lo[0] > 0) & (hi[0] > 0) & (lo[2] + p_inf > 0) & (hi[2] + p_inf > 0)
            lo = tuple(np.where(ok, a, b) for a, b in zip(lo, (tau, u, p)))
            hi = tuple(np.where(ok, a, b) for a, b in zip(hi, (tau, u, p)))
        else:
            lo = hi = (tau, u, p)
        g, i = pad(gamma), pad(p_inf)
        # face f lies between cell f-1 (its high side) and cell f (its low side)
        left = (1 / np.r_[lo[0][0], hi[0]], np.r_[-lo[1][0], hi[1]], np.r_[lo[2][0], hi[2]],
                g[:-1], i[:-1])
        right = (1 / np.r_[lo[0], hi[0][-1]], np.r_[lo[1], -hi[1][-1]], np.r_[lo[2], hi[2][-1]],
                 g[1:], i[1:])
        p_face, u_face = riemann(left, right)
        u_face[0] = u_face[-1] = 0.0
        u = u - dt * np.diff(p_face) / mass
        energy = energy - dt * np.diff(p_face * u_face) / mass
        x = x + dt * u_face
        t += dt
        cycles += 1
    rho = mass / np.diff(x)
    p = (gamma - 1.0) * rho * (energy - 0.5 * u * u) - gamma * p_inf
    k = int(np.argmin(np.where(water, p, np.inf)))
    return dict(cells=cells, order=order, cycles=cycles, p_water_min=float(p[k]),
                x_min=float(0.5 * (x[k] + x[k + 1])), rho_at_min=float(rho[k]),
                air_p_min=float(p[~water].min()))


def run_staggered(cells, acoustic=False):
    """1-D staggered Lagrangian step (no remap); acoustic: q = -0.5 rho c du both ways."""
    x, water, gamma, p_inf, rho, p = initial_state(cells)
    e = (p + gamma * p_inf) / ((gamma - 1.0) * rho)
    mass = rho * np.diff(x)
    node_mass = np.zeros(cells + 1)
    node_mass[1:] += 0.5 * mass
    node_mass[:-1] += 0.5 * mass
    u = np.zeros(cells + 1)
    eos = lambda r, en: (gamma - 1.0) * r * en - gamma * p_inf
    t, dt, cycles = 0.0, 0.01, 0
    while t < T_END * (1 - 1e-14):
        vol = np.diff(x)
        rho = mass / vol
        p = eos(rho, e)
        c = np.sqrt(gamma * (p + p_inf) / rho)
        du = np.diff(u)
        if acoustic:
            q = -0.5 * rho * c * du
        else:  # Christensen's limiter on the jump, compression only
            with np.errstate(divide="ignore", invalid="ignore"):
                left = np.where(du != 0, np.r_[du[0], du[:-1]] / du, 1.0)
                right = np.where(du != 0, np.r_[du[1:], du[-1]] / du, 1.0)
            psi = np.clip(np.minimum(np.minimum(0.5 * (left + right), 2 * left),
                                     np.minimum(2 * right, 1.0)), 0.0, 1.0)
            jump = du * (1 - psi)
            q = np.where(du < 0, rho * (0.75 * jump**2 - 0.2 * c * jump), 0.0)
        c_eff = np.sqrt(c**2 + 2 * np.abs(q) / rho)
        if cycles > 0:
            speed = c_eff + np.maximum(np.abs(u[1:]), np.abs(u[:-1]))
            dt = min(0.5 * np.min(vol / speed), 1.1 * dt)
        dt = min(dt, T_END - t)
        # predictor: half-step volume and energy, pressure there
        vol_h = np.diff(x + 0.5 * dt * u)
        p_h = eos(mass / vol_h, e - (p + q) * (vol_h - vol) / mass)
        force = np.zeros(cells + 1)
        force[1:-1] = (p_h + q)[:-1] - (p_h + q)[1:]
        u_new = u + dt * force / node_mass
        u_new[0] = u_new[-1] = 0.0
        x_new = x + 0.5 * dt * (u + u_new)
        e = e - (p_h + q) * (np.diff(x_new) - vol) / mass
        x, u = x_new, u_new
        t += dt
        cycles += 1
    rho = mass / np.diff(x)
    p = eos(rho, e)
    k = int(np.argmin(np.where(water, p, np.inf)))
    return dict(cells=cells, order="acoustic" if acoustic else "staggered", cycles=cycles,
                p_water_min=float(p[k]), x_min=float(0.5 * (x[k] + x[k + 1])),
                rho_at_min=float(rho[k]), air_p_min=float(p[~water].min()))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--cells", type=int, nargs="+", default=[200, 400, 800])
    ap.add_argument("--json", default=None, help="also write the results here")
    ap.add_argument("--staggered", action="store_true",
                    help="also run the 1-D model of minipagosa's Lagrangian step")
    a = ap.parse_args()
    one = lambda s: tuple(np.array([v]) for v in (s["rho"], 0.0, s["p"], s["gamma"], s["p_inf"]))
    p_star, u_star = (float(v[0]) for v in riemann(one(WATER), one(AIR)))
    print(f"exact star state: p* {p_star:.4e} Mbar, u* {u_star:.5f} cm/us")
    rows = []
    runs = [(order, cells) for order in (1, 2) for cells in a.cells]
    if a.staggered:
        runs += [(kind, cells) for kind in ("staggered", "acoustic") for cells in a.cells]
    names = {1: "Godunov order 1", 2: "MUSCL-Hancock", "staggered": "staggered (limited q)",
             "acoustic": "staggered (0.5 rho c |du|)"}
    for order, cells in runs:
        if order in (1, 2):
            r = run(cells, order)
        else:
            r = run_staggered(cells, acoustic=order == "acoustic")
        rows.append(r)
        print(f"{names[order]:27s} {cells:4d} cells, {r['cycles']:5d} cycles: least pure-water p "
              f"{r['p_water_min']:+.3e} Mbar at x {r['x_min']:.2f} (rho {r['rho_at_min']:.5f}), "
              f"{r['p_water_min'] / p_star:+.2f} p*; least air p {r['air_p_min']:.3e}")
    if a.json:
        with open(a.json, "w") as f:
            json.dump(dict(p_star=p_star, u_star=u_star, runs=rows), f, indent=1)


if __name__ == "__main__":
    main()
