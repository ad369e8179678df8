#!/usr/bin/python3
"""Scene check for configs/perforator.yaml (issue #13; not a CTest test): from the copper
volume fraction of every dump, whether each charge's jet has perforated the carrier tube wall
and the casing wall and entered the rock, and the copper jet tip's position and speed over time.

    /usr/bin/python3 tools/perforator_check.py output/perforator -o perf/results/perforator

A wall counts as perforated at the first dump where a cell with copper fraction > 0.5 lies
beyond the wall's outer surface along the charge axis (centre within --radius of the axis line,
y = 0 the symmetry plane); beyond the casing's outer surface is the rock, where the casing also
has to be pierced: less than half a cell of steel left ahead of the tip along its row (a casing
pushed into the rock ahead of the copper, with steel still between them, is not; since
2026-12-03, before which a bulge counted). The jet tip is the
farthest such cell along the charge's direction; its speed is the tip's advance between dumps
(dx/dt) and the copper-carrying cell's own axial velocity (the mean of its 8 node velocities).
Writes PREFIX.json and PREFIX.md; prints the table.

The geometry defaults are configs/perforator.yaml's (cm): carrier axis x = -4.2164, outer
radius 1.9939; casing axis x = 0, inner radius 6.2103, outer radius 6.9723; charges on y = 0 at
z = +1.27 aimed +x (top) and z = -1.27 aimed -x (bottom), mouths at x = -3.0764 and -5.3564.
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dumps  # noqa: E402

TOOL = "perforator_check"
CHARGES = [  # name, z of the axis, direction along x, x of the liner mouth
    ("top (aimed +x)", 1.27, +1.0, -3.0764),
    ("bottom (aimed -x)", -1.27, -1.0, -5.3564),
]


def walls(a):
    """Per direction: the x of the carrier's outer surface, the casing's inner and outer."""
    return {+1.0: (a.carrier_x + a.carrier_outer, a.casing_inner, a.casing_outer),
            -1.0: (a.carrier_x - a.carrier_outer, -a.casing_inner, -a.casing_outer)}


def probe(d, copper, vx, steel, z0, direction, radius):
    """The tip (farthest copper cell centre along `direction`) on the axis line y = 0, z = z0,
    that cell's axial velocity, and the steel cap ahead of it: the sum of the steel fractions of
    the contiguous cells beyond the tip along its row that hold steel (> 0.05), in cells; None if
    no copper cell there."""
    y, z = d.centres(1), d.centres(2)
    near = (np.abs(z[:, None] - z0) ** 2 + y[None, :] ** 2) <= radius ** 2  # (nz, ny)
    if not near.any():
        dumps.fail(TOOL, f"no cell centre within {radius:g} of the axis z = {z0:g}; "
                   "raise --radius")
    x = d.centres(0)
    mask = (copper > 0.5) & near[:, :, None]
    if not mask.any():
        return None
    ks, js, iis = np.nonzero(mask)
    s = direction * x[iis]
    n = int(np.argmax(s))
    k, j, i = ks[n], js[n], iis[n]
    u = vx[k:k + 2, j:j + 2, i:i + 2].mean()
    step = 1 if direction > 0 else -1
    cap, n = 0.0, i + step
    while 0 <= n < len(x) and steel[k, j, n] > 0.05:
        cap += float(steel[k, j, n])
        n += step
    return float(x[i]), float(direction * u), cap


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("run", help="the run's output directory")
    ap.add_argument("-o", "--output", default=None, help="prefix of the .json and .md")
    ap.add_argument("--radius", type=float, default=None,
                    help="probe radius about the axis, cm (default: one zone)")
    ap.add_argument("--carrier-x", type=float, default=-4.2164)
    ap.add_argument("--carrier-outer", type=float, default=1.9939)
    ap.add_argument("--casing-inner", type=float, default=6.2103)
    ap.add_argument("--casing-outer", type=float, default=6.9723)
    ap.add_argument("--charges", choices=("both", "top", "bottom"), default="both",
                    help="which charges to probe (a cut-down deck such as "
                         "perf/studies/perforator_top_across_well.yaml holds one)")
    a = ap.parse_args()
    global CHARGES
    if a.charges != "both":
        CHARGES = [c for c in CHARGES if c[0].startswith(a.charges)]

    runs = dumps.list_dumps(TOOL, a.run)
    wall = walls(a)
    rows = {name: [] for name, *_ in CHARGES}
    first_cross = {name: {"carrier": None, "casing_inner": None, "rock": None}
                   for name, *_ in CHARGES}
    zone = None
    for t, cycle, path in runs:
        d = dumps.Dump(TOOL, path)
        zone = float(d.spacing.max())
        radius = a.radius if a.radius is not None else zone
        copper = d.fraction("copper")
        vx = d.field("velocity_x")
        steel = d.fraction("steel")
        for name, z0, direction, mouth in CHARGES:
            tip = probe(d, copper, vx, steel, z0, direction, radius)
            row = {"time": t, "cycle": cycle, "tip_x": None, "tip_speed_cell": None,
                   "beyond_mouth": None, "steel_cap_cells": None}
            if tip:
                row["tip_x"], row["tip_speed_cell"], row["steel_cap_cells"] = tip
                row["beyond_mouth"] = direction * (tip[0] - mouth)
                for key, x_wall in zip(("carrier", "casing_inner", "rock"), wall[direction]):
                    beyond = direction * (tip[0] - x_wall) > 0
                    # in the rock: beyond the casing's outer surface with less than half a
                    # cell of steel ahead (a casing bulged into the rock ahead of the copper
                    # is not pierced)
                    if key == "rock":
                        beyond = beyond and tip[2] < 0.5
                    if first_cross[name][key] is None and beyond:
                        first_cross[name][key] = t
            rows[name].append(row)
    # tip speed from the advance between dumps (centred on the later dump)
    for name, *_ in CHARGES:
        r = rows[name]
        for n in range(len(r)):
            r[n]["tip_speed_dxdt"] = None
            if n and r[n]["tip_x"] is not None and r[n - 1]["tip_x"] is not None:
                dt = r[n]["time"] - r[n - 1]["time"]
                if dt > 0:
                    direction = next(c[2] for c in CHARGES if c[0] == name)
                    r[n]["tip_speed_dxdt"] = direction * (r[n]["tip_x"] - r[n - 1]["tip_x"]) / dt

    result = {
        "run": os.path.abspath(a.run),
        "zone_cm": zone,
        "probe_radius_cm": a.radius if a.radius is not None else zone,
        "criterion": "copper fraction > 0.5 in a cell centred within the probe radius of the "
                     "charge axis (y = 0) beyond the wall's outer surface; for the rock also "
                     "less than half a cell of steel ahead of that cell along its row",
        "walls_x": {"+x": list(wall[+1.0]), "-x": list(wall[-1.0])},
        "last_time": runs[-1][0],
        "charges": {name: {"first_dump_beyond": first_cross[name], "history": rows[name]}
                    for name, *_ in CHARGES},
    }

    def fmt(v, f="{:.3f}"):
        return "—" if v is None else f.format(v + 0.0)

    lines = [f"# Perforator check: {a.run}", "",
             f"zone {zone:g} cm, probe radius {result['probe_radius_cm']:g} cm, "
             f"dumps to t = {runs[-1][0]:g} us. Criterion: {result['criterion']}.", "",
             "| charge | carrier perforated (us) | casing interior reached (us) | "
             "casing perforated, in rock (us) |", "|---|---|---|---|"]
    for name, *_ in CHARGES:
        c = first_cross[name]
        lines.append(f"| {name} | {fmt(c['carrier'], '{:g}')} | {fmt(c['casing_inner'], '{:g}')}"
                     f" | {fmt(c['rock'], '{:g}')} |")
    lines += ["", "Times are the first dump showing it (the crossing happened since the dump "
              "before).", "",
              "| t (us) | charge | tip x (cm) | tip beyond mouth (cm) | tip speed dx/dt (cm/us) | "
              "tip cell u (cm/us) | steel ahead (cells) |", "|---|---|---|---|---|---|---|"]
    for n in range(len(runs)):
        for name, *_ in CHARGES:
            r = rows[name][n]
            lines.append(f"| {r['time']:g} | {name} | {fmt(r['tip_x'])} | "
                         f"{fmt(r['beyond_mouth'])} | {fmt(r['tip_speed_dxdt'])} | "
                         f"{fmt(r['tip_speed_cell'])} | {fmt(r['steel_cap_cells'], '{:.2f}')} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if a.output:
        os.makedirs(os.path.dirname(a.output) or ".", exist_ok=True)
        with open(a.output + ".json", "w") as f:
            json.dump(result, f, indent=1)
        with open(a.output + ".md", "w") as f:
            f.write(text)
        print(a.output + ".json\n" + a.output + ".md")


if __name__ == "__main__":
    main()
