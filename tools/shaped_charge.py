#!/usr/bin/python3
"""Shaped-charge theory for configs/perforator.yaml's charges: the jet that the classical
analytic model predicts, to check the run's jet against (issue #52; docs/perforator.md,
"Against shaped-charge theory").

    /usr/bin/python3 tools/shaped_charge.py [--elements 200] [--cut 0.2] [--run DIR] [-o PREFIX]

--run DIR measures the run's liner beside the model: per band of the liner, the largest inward
radial speed (90th percentile of its copper cells, over the dumps) about the top charge's axis,
against V0 cos(alpha).

The model, element by element along the conical liner (apex to base):
1. Collapse speed V0 of each liner element from Gurney's asymmetric ("tamped") sandwich: liner
   areal mass M, explosive areal mass C measured along the liner's outward normal to the case,
   case (tamper) areal mass N:
       V0 = sqrt(2E) [ (1 + A^3) / (3 (1 + A)) + (N/C) A^2 + M/C ]^(-1/2),
       A = (1 + 2 M/C) / (1 + 2 N/C)
   (Kennedy, "Gurney energy of explosives", Sandia SC-RR-70-790 (1970); the form as given in
   Cooper, "Explosives Engineering", Wiley-VCH (1996), ch. 27).
2. Jet and slug from the steady Pugh-Eichelberger-Rostoker collapse (Pugh, Eichelberger &
   Rostoker, J. Appl. Phys. 23 (1952) 532; the equations as set out in Walters & Zukas,
   "Fundamentals of Shaped Charges", Wiley (1989), ch. 2): with the liner half-angle alpha, the
   Taylor deflection angle delta (sin delta = V0 / (2 U), U = D / cos(alpha) the speed at which
   the detonation sweeps the liner) and the collapse angle beta = alpha + 2 delta,
       V_jet = V0 cos(alpha + delta - beta/2) / sin(beta/2),
       m_jet / m = sin^2(beta/2).
   With delta = 0 this is the steady theory of Birkhoff, MacDougall, Pugh & Taylor,
   J. Appl. Phys. 19 (1948) 563: V_jet = V0 cot(alpha/2).
3. Penetration of a continuous jet of length l into a target (Birkhoff et al. 1948, the
   hydrodynamic limit): L = l sqrt(rho_jet / rho_target).

Inputs are the deck's (configs/perforator.yaml; docs/perforator.md's table): liner outer cone
radius 0.8636 cm and height 1.905 cm, normal thickness 0.1905 cm, copper 8.93 g/cm^3; explosive
radius 0.8636 cm, 0.25 cm behind the liner apex, Composition B at 1.717 g/cm^3 with
D = 0.798 cm/us (docs/materials.md, comp_b_products) and Gurney sqrt(2E) = 0.270 cm/us (Kennedy
1970, tabulated in Cooper 1996, Table 27.1); steel case wall and back 0.125 cm at 7.81 g/cm^3.
The model's known biases, which the run is not expected to share: V0 is the terminal Gurney
speed, which an element near the apex does not reach before it meets the axis (the apex's jet is
slower than this model says: the "inverse velocity gradient" of real jets' leading part); the
explosive column along the normal ignores the lateral flow of the products (the column's
explosive overestimates the drive where the case is thin); jets break into particles, whose
penetration falls below the continuous jet's (L above).
"""
import argparse
import json
import math
import os
import sys

# configs/perforator.yaml's charge (cm, g/cm^3, cm/us)
LINER = {"radius": 0.8636, "height": 1.905, "thickness": 0.1905, "density": 8.93}
EXPLOSIVE = {"radius": 0.8636, "behind_apex": 0.25, "density": 1.717, "d_cj": 0.798,
             "gurney": 0.270}
CASE = {"wall": 0.125, "density": 7.81}
DENSITY = {"copper": 8.93, "steel": 7.81, "quartz": 2.65}


def gurney_sandwich(m, c, n, sqrt2e):
    """Collapse speed of a flyer of areal mass m driven by explosive c, tamped by n."""
    a = (1 + 2 * m / c) / (1 + 2 * n / c)
    return sqrt2e * ((1 + a ** 3) / (3 * (1 + a)) + (n / c) * a * a + m / c) ** -0.5


def elements(n=200):
    """Per liner element (apex to base): axial position x from the outer apex, V0, delta, beta,
    the jet speed and the element's liner and jet mass (whole charge, g)."""
    alpha = math.atan(LINER["radius"] / LINER["height"])
    m_area = LINER["density"] * LINER["thickness"]
    n_area = CASE["density"] * CASE["wall"]
    out = []
    for q in range(n):
        x0, x1 = q * LINER["height"] / n, (q + 1) * LINER["height"] / n
        x = 0.5 * (x0 + x1)
        r = x * math.tan(alpha)  # outer liner radius
        # explosive along the outward normal (back and out at alpha to the radius): to the case
        # wall, or to the explosive's back face, whichever it meets first
        t_e = min((EXPLOSIVE["radius"] - r) / math.cos(alpha),
                  (x + EXPLOSIVE["behind_apex"]) / math.sin(alpha))
        if t_e <= 1e-6:
            continue
        c_area = EXPLOSIVE["density"] * t_e
        v0 = gurney_sandwich(m_area, c_area, n_area, EXPLOSIVE["gurney"])
        u = EXPLOSIVE["d_cj"] / math.cos(alpha)
        delta = math.asin(min(1.0, v0 / (2 * u)))
        beta = alpha + 2 * delta
        v_jet = v0 * math.cos(alpha + delta - beta / 2) / math.sin(beta / 2)
        # liner mass of the element: the copper between the outer cone and the inner one (the
        # outer moved LINER["thickness"] / sin(alpha) toward the base) in the slab [x0, x1]
        shift = LINER["thickness"] / math.sin(alpha)

        def r_in(z):
            return max(0.0, z - shift) * math.tan(alpha)

        mass = LINER["density"] * math.pi * (x1 - x0) * (
            (0.5 * (x0 + x1) * math.tan(alpha)) ** 2 - r_in(0.5 * (x0 + x1)) ** 2)
        out.append({"x": x, "explosive_normal": t_e, "c_over_m": c_area / m_area, "v0": v0,
                    "delta_deg": math.degrees(delta), "beta_deg": math.degrees(beta),
                    "v_jet": v_jet, "mass": mass, "jet_mass": mass * math.sin(beta / 2) ** 2})
    return alpha, out


def predict(n=200, cut=0.2):
    """The model's jet: tip speed (fastest element), jet mass and momentum above `cut`."""
    alpha, el = elements(n)
    steady = [e["v0"] / math.tan(alpha / 2) for e in el]
    fast = [e for e in el if e["v_jet"] > cut]
    return {
        "liner_half_angle_deg": math.degrees(alpha),
        "liner_mass_g": sum(e["mass"] for e in el),
        "tip_speed": max(e["v_jet"] for e in el),
        "tip_speed_steady_bmpt": max(steady),
        "v0_range": [min(e["v0"] for e in el), max(e["v0"] for e in el)],
        "speed_cut": cut,
        "jet_mass_above_cut_g": sum(e["jet_mass"] for e in fast),
        "jet_momentum_above_cut": sum(e["jet_mass"] * e["v_jet"] for e in fast),
        "jet_mass_g": sum(e["jet_mass"] for e in el),
        "elements": el,
    }


def birkhoff_depth(length, target, jet="copper"):
    """Hydrodynamic penetration depth of a continuous jet of `length` into `target`."""
    return length * math.sqrt(DENSITY[jet] / DENSITY[target])


def penetration_speed_ratio(target, jet="copper"):
    """The hydrodynamic penetration speed over the jet's speed, u / v = 1 / (1 + sqrt(rho_target /
    rho_jet)): Bernoulli's balance at the stagnation point in the frame of the crater's bottom,
    rho_jet (v - u)^2 = rho_target u^2 (Birkhoff et al. 1948, the same theory as birkhoff_depth:
    a jet of length l at constant v is used up in l / (v - u), in which the crater grows u times
    that, l sqrt(rho_jet / rho_target))."""
    return 1.0 / (1.0 + math.sqrt(DENSITY[target] / DENSITY[jet]))


def collapse_speeds(run, apex_x=-4.9814, axis_z=1.27, bins=8, t_max=8.0):
    """The top charge's liner in a run (its dumps up to t_max): per axial band of the liner
    (distance from the outer apex, cm), the largest over the dumps of the 90th percentile of its
    copper cells' inward radial speed about the charge axis (y = 0, z = axis_z; cells with
    copper fraction > 0.5 off the axis), against the model's
    V0 cos(alpha), the radial part of its collapse speed (Gurney's, normal to the liner)."""
    import numpy as np
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import dumps
    alpha, el = elements(400)
    edges = np.linspace(0, LINER["height"], bins + 1)
    best = np.zeros(bins)
    for t, _, path in dumps.list_dumps("shaped_charge", run):
        if t > t_max:
            break
        d = dumps.Dump("shaped_charge", path)
        cu = d.fraction("copper")
        x, y, z = d.centres(0), d.centres(1), d.centres(2)
        uy = dumps.node_to_cells(d.field("velocity_y"))
        uz = dumps.node_to_cells(d.field("velocity_z"))
        Z, Y, X = np.meshgrid(z - axis_z, y, x, indexing="ij")
        r = np.sqrt(Y * Y + Z * Z)
        inward = -(uy * Y + uz * Z) / np.maximum(r, 1e-12)
        keep = (cu > 0.5) & (Z > -1.0) & (r > 0.5 * d.spacing[1])
        sband = X - apex_x
        for b in range(bins):
            m = keep & (sband >= edges[b]) & (sband < edges[b + 1])
            if m.any():
                best[b] = max(best[b], float(np.percentile(inward[m], 90)))
    rows = []
    for b in range(bins):
        inb = [e for e in el if edges[b] <= e["x"] < edges[b + 1]]
        model = sum(e["v0"] for e in inb) / len(inb) * math.cos(alpha)
        # PER's jet speed from the run's collapse speed (V0 = the radial speed / cos(alpha))
        v0 = float(best[b]) / math.cos(alpha)
        u = EXPLOSIVE["d_cj"] / math.cos(alpha)
        delta = math.asin(min(1.0, v0 / (2 * u)))
        beta = alpha + 2 * delta
        rows.append({"from_apex": [float(edges[b]), float(edges[b + 1])],
                     "run_inward_speed": float(best[b]), "model_v0_radial": model,
                     "per_jet_speed_from_run":
                         v0 * math.cos(alpha + delta - beta / 2) / math.sin(beta / 2)})
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--run", default=None,
                    help="a run's output directory (the deck or a cut of it holding the top "
                         "charge): its liner's collapse speeds against the model's")
    ap.add_argument("--elements", type=int, default=200)
    ap.add_argument("--cut", type=float, default=0.2, help="jet speed cut, cm/us")
    ap.add_argument("-o", "--output", default=None, help="prefix of the .json")
    a = ap.parse_args()
    p = predict(a.elements, a.cut)
    print(f"liner half-angle {p['liner_half_angle_deg']:.2f} deg, liner mass "
          f"{p['liner_mass_g']:.3f} g (whole charge)")
    print(f"collapse speed V0 {p['v0_range'][0]:.4f}-{p['v0_range'][1]:.4f} cm/us")
    print(f"jet tip speed: PER {p['tip_speed']:.4f} cm/us, steady BMPT {p['tip_speed_steady_bmpt']:.4f}")
    print(f"jet mass {p['jet_mass_g']:.4f} g; above {a.cut:g} cm/us: "
          f"{p['jet_mass_above_cut_g']:.4f} g, momentum {p['jet_momentum_above_cut']:.5f} g cm/us")
    for t in ("steel", "quartz"):
        print(f"Birkhoff depth per cm of jet into {t}: {birkhoff_depth(1.0, t):.3f} cm")
    if a.run:
        p["collapse"] = collapse_speeds(a.run)
        print("liner band from the apex (cm) | run: largest inward speed (p90) | model V0 cos(alpha)"
              " | PER jet speed from the run's")
        for row in p["collapse"]:
            print(f"{row['from_apex'][0]:.2f}-{row['from_apex'][1]:.2f} | "
                  f"{row['run_inward_speed']:.4f} | {row['model_v0_radial']:.4f} | "
                  f"{row['per_jet_speed_from_run']:.4f}")
    if a.output:
        os.makedirs(os.path.dirname(a.output) or ".", exist_ok=True)
        with open(a.output + ".json", "w") as f:
            json.dump(p, f, indent=1)


if __name__ == "__main__":
    main()
