#!/usr/bin/env python3
"""The copper jet of one shaped charge aimed +x, dump by dump: its tip on the charge axis, how much
copper moves fast, and when it is through a wall (issue #13's jet-formation resolution study,
perf/studies/perforator_top_charge.yaml; docs/perforator.md "Jet formation against zone size").

Per dump:
- tip: the largest x of a cell on the axis row (the cell layer nearest y = --axis-y, z = --axis-z)
  with copper fraction > 0.5, and that cell's x velocity (the mean of its 8 nodes);
- fast copper: the copper volume (fraction x cell volume, summed over the whole mesh, which is the
  half charge of a y >= 0 mesh) in cells whose x velocity exceeds each of --speeds, in mm^3 so the
  numbers stay readable, and the axial extent (max x - min x) of the axis cells with copper > 0.5
  moving faster than the first of --speeds (the fast jet's length);
- through the wall: the first dump whose tip lies beyond --wall-x.

  tools/jet_profile.py RUN_DIR [-o PREFIX] [--axis-y 0] [--axis-z 1.27] [--speeds 0.2 0.28 0.4]
                       [--wall-x -2.2225]
writes PREFIX.json and PREFIX.md (or prints the Markdown).
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dumps  # noqa: E402

TOOL = "jet_profile"


def profile(d, axis_y, axis_z, speeds):
    cu = d.fraction("copper")
    ux = dumps.cell_ux(d)
    j, k = d.plane_index(1, axis_y), d.plane_index(2, axis_z)
    x = d.centres(0)
    row_f, row_u = cu[k, j, :], ux[k, j, :]
    row = {"time": d.time, "cycle": d.cycle}
    on = np.nonzero(row_f > 0.5)[0]
    if on.size:
        i = on.max()
        row["tip_x"], row["tip_u"] = float(x[i]), float(row_u[i])
    else:
        row["tip_x"] = row["tip_u"] = None
    vol = float(np.prod(d.spacing)) * 1e3  # mm^3 per cell (cm^3 x 1000)
    row["fast_volume_mm3"] = {f"{s:g}": float(np.sum(cu[ux > s]) * vol) for s in speeds}
    fast = np.nonzero((row_f > 0.5) & (row_u > speeds[0]))[0]
    row["fast_length"] = float(x[fast.max()] - x[fast.min()] + d.spacing[0]) if fast.size else 0.0
    row["copper_volume_mm3"] = float(np.sum(cu) * vol)
    return row


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("run", help="the run's output directory")
    ap.add_argument("-o", "--output", default=None, help="prefix of the .json and .md")
    ap.add_argument("--axis-y", type=float, default=0.0)
    ap.add_argument("--axis-z", type=float, default=1.27)
    ap.add_argument("--speeds", type=float, nargs="+", default=[0.2, 0.28, 0.4],
                    help="x-speed thresholds, cm/us (the first also sets the fast length)")
    ap.add_argument("--wall-x", type=float, default=-2.2225,
                    help="the outer surface of the wall in front of the charge (carrier: -2.2225)")
    a = ap.parse_args()
    rows = []
    first = None
    listed = dumps.list_dumps(TOOL, a.run)
    for t, _, path in listed:
        d = dumps.Dump(TOOL, path)
        r = profile(d, a.axis_y, a.axis_z, a.speeds)
        rows.append(r)
        if first is None and r["tip_x"] is not None and r["tip_x"] > a.wall_x:
            first = r["time"]
    d0 = dumps.Dump(TOOL, listed[0][2])
    out = {"run": a.run, "cells": [int(c) for c in d0.cells], "spacing": list(d0.spacing),
           "axis": [a.axis_y, a.axis_z], "speeds": a.speeds, "wall_x": a.wall_x,
           "through_wall_time": first, "dumps": rows}
    s = a.speeds
    md = [f"# Jet profile: {a.run}", "",
          f"cells {' x '.join(str(int(c)) for c in d0.cells)}, spacing "
          f"{', '.join(f'{v:.4g}' for v in d0.spacing)} cm; axis y = {a.axis_y:g}, "
          f"z = {a.axis_z:g}; through the wall (tip beyond x = {a.wall_x:g}): "
          + (f"first at t = {first:.3g} us" if first is not None else "not in these dumps"), "",
          "Copper volumes in mm^3 of the half charge (y >= 0); fast length: axial extent of the "
          f"axis cells with copper > 0.5 moving faster than {s[0]:g} cm/us.", "",
          "| t (us) | tip x (cm) | tip cell u (cm/us) | fast length (cm) | "
          + " | ".join(f"copper u > {v:g} (mm^3)" for v in s) + " | copper (mm^3) |",
          "|---|---|---|---|" + "---|" * len(s) + "---|"]
    for r in rows:
        tip = f"{r['tip_x']:.3f} | {r['tip_u']:.3f}" if r["tip_x"] is not None else "— | —"
        md.append(f"| {r['time']:.3g} | {tip} | {r['fast_length']:.3f} | "
                  + " | ".join(f"{r['fast_volume_mm3'][f'{v:g}']:.2f}" for v in s)
                  + f" | {r['copper_volume_mm3']:.1f} |")
    text = "\n".join(md) + "\n"
    if a.output:
        with open(a.output + ".json", "w") as f:
            json.dump(out, f, indent=1)
        with open(a.output + ".md", "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
