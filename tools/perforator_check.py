#!/usr/bin/python3
"""The perforator's engineering answer from a run of configs/perforator.yaml (issue #52): per
charge and per dump, what the jet has done to the carrier tube, the casing and the rock, and how
the run compares with shaped-charge theory (tools/shaped_charge.py).

    /usr/bin/python3 tools/perforator_check.py output/perforator -o perf/results/perforator

Per charge and dump (a charge's half of the mesh is z > 0 for the top charge, z < 0 for the
bottom one; masses are the whole charge's: twice the y >= 0 half mesh's):
- tip: the farthest cell along the charge's direction on its axis (cell centres within --radius
  of the line y = 0, z = z_charge) with copper fraction > 0.5; its speed as the tip's advance
  between dumps (dx/dt) and as the tip cell's axial velocity (the mean of its 8 nodes);
- arrival: the first dump whose tip lies beyond the carrier's inner surface, through the carrier
  (beyond its outer surface with less than half a cell of steel ahead of the tip along its row),
  beyond the casing's inner surface, and in the rock (beyond the casing's outer surface, pierced
  in the same sense: a casing bulged into the rock ahead of the copper is not);
- hole diameters, once that wall is pierced: on a cylinder a quarter of the wall's thickness
  inside each of its surfaces, the cells whose steel fraction is below 0.5, connected (4-way, on
  the cylinder's y-z grid) to the charge axis; the area (doubled for y < 0) as the diameter of the
  circle of that area (the casing's entrance: its inner surface; the exit: the outer one);
- penetration into the rock: along the axis row, from the casing's outer surface to the first
  0.5 crossing of the quartz fraction (the crater's depth), and the tip's own depth;
- copper mass beyond each wall, and the jet: copper mass, axial momentum and axial extent on the
  axis row of the copper moving faster than --cut along the charge's direction. Copper mass is
  the copper fraction x 8.93 g/cm^3 x the cell volume: the dumps carry no per-material density,
  and the jet's copper, near zero pressure, stays within a few per cent of its reference density;
- theory (tools/shaped_charge.py): the PER tip speed and jet mass above --cut; the Birkhoff
  hydrodynamic depth L = l sqrt(rho_jet / rho_target) of the fast jet's length l on the axis row
  at the dump where the tip enters the rock, against the crater's final depth.
- mass ledger (from summary.json beside the dumps): each material's mass at the start and end;
  the Eulerian mesh changes a material's mass only through the boundaries.
Writes PREFIX.json and PREFIX.md; prints the Markdown.

The geometry defaults are configs/perforator.yaml's (cm): carrier axis x = -4.2164, radii 1.5494
/ 1.9939; casing axis x = 0, radii 6.2103 / 6.9723; charges on y = 0 at z = +1.27 aimed +x (top)
and z = -1.27 aimed -x (bottom), mouths at x = -3.0764 and -5.3564.
"""
import argparse
import json
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import dumps  # noqa: E402
import shaped_charge  # noqa: E402

TOOL = "perforator_check"
CHARGES = [  # name, z of the axis, direction along x, x of the liner mouth
    ("top (aimed +x)", 1.27, +1.0, -3.0764),
    ("bottom (aimed -x)", -1.27, -1.0, -5.3564),
]
RHO_COPPER = 8.93
EVENTS = ("carrier_reached", "carrier_through", "casing_reached", "rock")


class Walls:
    """The walls one charge's jet meets, as surfaces along its direction."""

    def __init__(self, a, direction):
        s = direction
        self.carrier = (a.carrier_x, a.carrier_inner, a.carrier_outer)
        self.casing = (0.0, a.casing_inner, a.casing_outer)
        # x of each surface on the charge axis (y = 0), in the jet's direction
        self.x = {"carrier_inner": a.carrier_x + s * a.carrier_inner,
                  "carrier_outer": a.carrier_x + s * a.carrier_outer,
                  "casing_inner": s * a.casing_inner,
                  "casing_outer": s * a.casing_outer}


def steel_ahead(steel, k, j, i, step):
    """Steel fractions summed over the contiguous cells beyond (k, j, i) along x that hold steel."""
    cap, n = 0.0, i + step
    while 0 <= n < steel.shape[2] and steel[k, j, n] > 0.05:
        cap += float(steel[k, j, n])
        n += step
    return cap


def hole(d, steel, axis_x, radius, z0, direction):
    """Equivalent diameter (cm) and height/width of the opening in a wall about the z-parallel
    axis (axis_x, 0) on the cylinder of `radius`, around the point facing the charge axis
    (y = 0, z = z0); 0 if that point is steel."""
    y, z = d.centres(1), d.centres(2)
    x0, dx = d.origin[0], d.spacing[0]
    open_ = np.zeros((len(z), len(y)), dtype=bool)
    for jj, yy in enumerate(y):
        if yy >= radius:
            continue
        x = axis_x + direction * math.sqrt(radius * radius - yy * yy)
        i = int(math.floor((x - x0) / dx))
        if 0 <= i < steel.shape[2]:
            open_[:, jj] = steel[:, jj, i] < 0.5
    k0 = d.plane_index(2, z0)
    if not open_[k0, 0]:
        return 0.0, 0.0, 0.0
    seen = np.zeros_like(open_)
    stack, cells = [(k0, 0)], []
    seen[k0, 0] = True
    while stack:
        k, j = stack.pop()
        cells.append((k, j))
        for kk, jj in ((k + 1, j), (k - 1, j), (k, j + 1), (k, j - 1)):
            if 0 <= kk < open_.shape[0] and 0 <= jj < open_.shape[1] and open_[kk, jj] \
                    and not seen[kk, jj]:
                seen[kk, jj] = True
                stack.append((kk, jj))
    ks = np.array([c[0] for c in cells])
    js = np.array([c[1] for c in cells])
    area = 2.0 * len(cells) * d.spacing[1] * d.spacing[2]
    height = (ks.max() - ks.min() + 1) * d.spacing[2]
    width = 2.0 * (js.max() + 1) * d.spacing[1]
    return math.sqrt(4 * area / math.pi), float(height), float(width)


def crater_depth(d, quartz, k, j, x_outer, direction):
    """Depth beyond the casing's outer surface, along the row (k, j), of the first 0.5 crossing
    of the quartz fraction (linear between cell centres)."""
    x = d.centres(0)
    row = quartz[k, j, :]
    order = np.argsort(direction * x)
    prev = None
    for i in order:
        if direction * (x[i] - x_outer) < 0:
            continue
        if row[i] >= 0.5:
            if prev is None:
                return 0.0
            f0, f1 = row[prev], row[i]
            xc = x[prev] + (0.5 - f0) / (f1 - f0) * (x[i] - x[prev])
            return max(0.0, float(direction * (xc - x_outer)))
        prev = i
    return float(direction * (x[order[-1]] - x_outer))


def measure(d, a, name, z0, direction, mouth, walls, cut):
    copper, steel, quartz = d.fraction("copper"), d.fraction("steel"), d.fraction("quartz")
    ux = dumps.cell_ux(d)
    x, y, z = d.centres(0), d.centres(1), d.centres(2)
    vol = float(np.prod(d.spacing))
    zone = float(d.spacing.max())
    radius = a.radius if a.radius is not None else zone
    near = (np.abs(z[:, None] - z0) ** 2 + y[None, :] ** 2) <= radius ** 2
    if not near.any():
        dumps.fail(TOOL, f"no cell centre within {radius:g} of the axis z = {z0:g}; raise --radius")
    row = {"time": d.time, "cycle": d.cycle}
    half = (z > 0) if z0 > 0 else (z < 0)
    cu = np.where(half[:, None, None], copper, 0.0)
    mass = cu * RHO_COPPER * vol * 2.0  # whole charge
    sx = direction * x[None, None, :]
    row["copper_beyond"] = {w: float(mass[np.broadcast_to(sx > direction * walls.x[w],
                                                          mass.shape)].sum())
                            for w in ("carrier_outer", "casing_inner", "casing_outer")}
    fast = direction * ux > cut
    row["jet_mass"] = float(mass[fast].sum())
    row["jet_momentum"] = float((mass * direction * ux)[fast].sum())
    k, j = d.plane_index(2, z0), 0
    on_row = np.nonzero((copper[k, j, :] > 0.5) & (direction * ux[k, j, :] > cut))[0]
    row["jet_length"] = float(x[on_row].max() - x[on_row].min() + d.spacing[0]) \
        if on_row.size else 0.0
    mask = (copper > 0.5) & near[:, :, None]
    row.update(tip_x=None, tip_speed_cell=None, beyond_mouth=None, steel_ahead=None,
               jet_speed_behind_tip=None)
    row["events"] = {}
    if mask.any():
        ks, js, iis = np.nonzero(mask)
        n = int(np.argmax(direction * x[iis]))
        kt, jt, it = ks[n], js[n], iis[n]
        row["tip_x"] = float(x[it])
        row["tip_speed_cell"] = float(direction * ux[kt, jt, it])
        # the jet feeding the tip: the fastest copper (fraction > 0.5) on the axis row within
        # --behind of the tip, behind it
        back = (copper[k, j, :] > 0.5) & (direction * (x[it] - x) >= 0) & \
            (direction * (x[it] - x) <= a.behind)
        row["jet_speed_behind_tip"] = float((direction * ux[k, j, :])[back].max()) \
            if back.any() else None
        row["beyond_mouth"] = float(direction * (x[it] - mouth))
        cap = steel_ahead(steel, kt, jt, it, 1 if direction > 0 else -1)
        row["steel_ahead"] = cap
        past = {w: bool(direction * (x[it] - walls.x[w]) > 0) for w in walls.x}
        row["events"] = {"carrier_reached": past["carrier_inner"],
                         "carrier_through": past["carrier_outer"] and bool(cap < 0.5),
                         "casing_reached": past["casing_inner"],
                         "rock": past["casing_outer"] and bool(cap < 0.5)}
    ev = row["events"]
    cx, ci, co = walls.carrier
    t = (co - ci) / 4
    row["carrier_hole"] = hole(d, steel, cx, ci + t, z0, direction)[0] \
        if ev.get("carrier_through") else None
    _, ci, co = walls.casing
    t = (co - ci) / 4
    if ev.get("rock"):
        row["casing_entrance"] = hole(d, steel, 0.0, ci + t, z0, direction)
        row["casing_exit"] = hole(d, steel, 0.0, co - t, z0, direction)
        row["crater_depth"] = crater_depth(d, quartz, k, j, walls.x["casing_outer"], direction)
        row["tip_depth"] = float(direction * (row["tip_x"] - walls.x["casing_outer"]))
    else:
        row["casing_entrance"] = row["casing_exit"] = None
        row["crater_depth"] = row["tip_depth"] = None
    return row


def ledger(run):
    path = os.path.join(run, "summary.json")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        s = json.load(f)
    start, end = s.get("start", {}), s.get("end", {})
    m0, m1 = start.get("material_mass"), end.get("material_mass")
    if not m0 or not m1:
        return None
    return {m: {"start": m0[m], "end": m1[m], "lost_relative": (m0[m] - m1[m]) / m0[m]
                if m0[m] else 0.0} for m in m0}


def fmt(v, f="{:.3f}"):
    return "—" if v is None else f.format(v + 0.0)


def parser():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("run", help="the run's output directory")
    ap.add_argument("-o", "--output", default=None, help="prefix of the .json and .md")
    ap.add_argument("--radius", type=float, default=None,
                    help="probe radius about the axis, cm (default: one zone)")
    ap.add_argument("--cut", type=float, default=0.2, help="jet speed cut, cm/us (default 0.2)")
    ap.add_argument("--behind", type=float, default=1.0,
                    help="how far behind the tip the jet feeding it is sought, cm (default 1)")
    ap.add_argument("--carrier-x", type=float, default=-4.2164)
    ap.add_argument("--carrier-inner", type=float, default=1.5494)
    ap.add_argument("--carrier-outer", type=float, default=1.9939)
    ap.add_argument("--casing-inner", type=float, default=6.2103)
    ap.add_argument("--casing-outer", type=float, default=6.9723)
    ap.add_argument("--charges", choices=("both", "top", "bottom"), default="both",
                    help="which charges to probe (a cut-down deck such as "
                         "perf/studies/perforator_top_across_well.yaml holds one)")
    return ap


def options(**kw):
    """perforator_check's options as the command line's defaults, with `kw` changed (for a
    study that measures its runs with `analyse`)."""
    a = parser().parse_args(["."])
    for k, v in kw.items():
        setattr(a, k, v)
    return a


def analyse(run, a):
    """Every dump of `run` measured per charge (a.charges): (result, rows, runs, charges), the
    result as this tool's JSON."""
    charges = [c for c in CHARGES if a.charges == "both" or c[0].startswith(a.charges)]

    runs = dumps.list_dumps(TOOL, run)
    rows = {name: [] for name, *_ in charges}
    walls = {name: Walls(a, direction) for name, _, direction, _ in charges}
    zone = None
    for t, cycle, path in runs:
        d = dumps.Dump(TOOL, path)
        zone = float(d.spacing.max())
        for name, z0, direction, mouth in charges:
            rows[name].append(measure(d, a, name, z0, direction, mouth, walls[name], a.cut))
    theory = shaped_charge.predict(cut=a.cut)
    theory.pop("elements")
    result = {"run": os.path.abspath(run), "zone_cm": zone, "speed_cut": a.cut,
              "last_time": runs[-1][0], "theory": theory, "mass_ledger": ledger(run),
              "charges": {}}
    for name, z0, direction, mouth in charges:
        r = rows[name]
        for n in range(len(r)):
            r[n]["tip_speed_dxdt"] = None
            if n and r[n]["tip_x"] is not None and r[n - 1]["tip_x"] is not None:
                dt = r[n]["time"] - r[n - 1]["time"]
                if dt > 0:
                    r[n]["tip_speed_dxdt"] = direction * (r[n]["tip_x"] - r[n - 1]["tip_x"]) / dt
        # the hydrodynamic check: between dumps with the tip in one target (the rock, or the
        # casing's steel), the tip's advance against u = v / (1 + sqrt(rho_t / rho_jet)) of the
        # jet speed v behind the tip (the mean of the two dumps')
        wall = walls[name]
        for n in range(1, len(r)):
            p, c = r[n - 1], r[n]
            c["penetration"] = None
            if c["tip_speed_dxdt"] is None or p["jet_speed_behind_tip"] is None \
                    or c["jet_speed_behind_tip"] is None:
                continue
            if p["events"].get("rock"):
                target = "quartz"
            elif direction * (p["tip_x"] - wall.x["casing_inner"]) >= 0 and \
                    direction * (c["tip_x"] - wall.x["casing_outer"]) <= 0:
                target = "steel"
            else:
                continue
            v = 0.5 * (p["jet_speed_behind_tip"] + c["jet_speed_behind_tip"])
            c["penetration"] = {"target": target, "speed": c["tip_speed_dxdt"], "jet_speed": v,
                                "theory": v * shaped_charge.penetration_speed_ratio(target)}
        r[0]["penetration"] = None
        first = {e: next((x["time"] for x in r if x["events"].get(e)), None) for e in EVENTS}
        entry = next((x for x in r if x["events"].get("rock")), None)
        last = r[-1]
        speeds = [x["tip_speed_cell"] for x in r if x["tip_speed_cell"] is not None]
        pierced = next((x for x in r if x["events"].get("carrier_through")), None)
        summary = {
            "first_dump": first,
            # the openings when the jet first shows through: at the end the carrier may have
            # burst around the charge and the casing's hole grown with the crater
            "carrier_hole_when_pierced": pierced["carrier_hole"] if pierced else None,
            "casing_entrance_when_pierced": entry["casing_entrance"][0] if entry else None,
            "casing_exit_when_pierced": entry["casing_exit"][0] if entry else None,
            "max_tip_speed_cell": max(speeds) if speeds else None,
            "max_jet_mass": max(x["jet_mass"] for x in r),
            "max_jet_momentum": max(x["jet_momentum"] for x in r),
            "final": {k: last[k] for k in ("time", "tip_x", "crater_depth", "tip_depth",
                                           "casing_entrance", "casing_exit", "carrier_hole",
                                           "copper_beyond")},
            "birkhoff": None,
            # the tip's advance through each target against the hydrodynamic speed, summed over
            # the dumps (cm): the depth the run made and the depth u = v / (1 + sqrt(rho_t /
            # rho_jet)) of its own jet would have made in the same intervals
            "penetration_check": {},
        }
        for n in range(1, len(r)):
            pc = r[n]["penetration"]
            if pc:
                dt = r[n]["time"] - r[n - 1]["time"]
                acc = summary["penetration_check"].setdefault(
                    pc["target"], {"run_depth": 0.0, "theory_depth": 0.0, "intervals": 0})
                acc["run_depth"] += pc["speed"] * dt
                acc["theory_depth"] += pc["theory"] * dt
                acc["intervals"] += 1
        if entry is not None:
            summary["birkhoff"] = {
                "at_time": entry["time"], "jet_length": entry["jet_length"],
                "depth_quartz": shaped_charge.birkhoff_depth(entry["jet_length"], "quartz"),
                "crater_depth_final": last["crater_depth"]}
        result["charges"][name] = {"summary": summary, "history": r}

    return result, rows, runs, charges


def main():
    a = parser().parse_args()
    result, rows, runs, charges = analyse(a.run, a)
    zone, theory = result["zone_cm"], result["theory"]

    lines = [f"# Perforator: {a.run}", "",
             f"zone {zone:g} cm, dumps to t = {runs[-1][0]:g} us, jet speed cut {a.cut:g} cm/us. "
             "Masses are the whole charge's (twice the half mesh). Times are the first dump "
             "showing the event.", "",
             "| charge | carrier reached | through carrier | casing reached | in rock | "
             "max tip speed (cm/us) | max jet mass (g) | max jet momentum (g cm/us) |",
             "|---|---|---|---|---|---|---|---|"]
    for name, *_ in charges:
        s = result["charges"][name]["summary"]
        f = s["first_dump"]
        lines.append(f"| {name} | " + " | ".join(fmt(f[e], "{:g}") for e in EVENTS) +
                     f" | {fmt(s['max_tip_speed_cell'])} | {fmt(s['max_jet_mass'], '{:.4f}')} "
                     f"| {fmt(s['max_jet_momentum'], '{:.4f}')} |")
    lines += ["", "Openings when first pierced (cm, equivalent diameter): " + "; ".join(
        f"{name}: carrier {fmt(result['charges'][name]['summary']['carrier_hole_when_pierced'])}"
        f", casing entrance "
        f"{fmt(result['charges'][name]['summary']['casing_entrance_when_pierced'])}, exit "
        f"{fmt(result['charges'][name]['summary']['casing_exit_when_pierced'])}"
        for name, *_ in charges) + "."]
    lines += ["", f"At t = {runs[-1][0]:g} us (a wall's opening now includes its burst around the "
              "charge and the crater's growth; copper \"beyond\" a wall is past its original "
              "surface, bulge or not):", "",
              "| charge | carrier hole (cm) | casing entrance (cm) | casing exit (cm) | crater "
              "depth (cm) | tip depth (cm) | Cu beyond carrier / casing in / casing out (g) |",
              "|---|---|---|---|---|---|---|"]
    for name, *_ in charges:
        fl = result["charges"][name]["summary"]["final"]
        cb = fl["copper_beyond"]
        lines.append(f"| {name} | {fmt(fl['carrier_hole'])} | "
                     f"{fmt(fl['casing_entrance'][0] if fl['casing_entrance'] else None)} | "
                     f"{fmt(fl['casing_exit'][0] if fl['casing_exit'] else None)} | "
                     f"{fmt(fl['crater_depth'])} | {fmt(fl['tip_depth'])} | "
                     f"{cb['carrier_outer']:.4f} / {cb['casing_inner']:.4f} / "
                     f"{cb['casing_outer']:.4f} |")
    lines += ["", "Against theory (tools/shaped_charge.py): PER tip speed "
              f"{theory['tip_speed']:.3f} cm/us (steady BMPT {theory['tip_speed_steady_bmpt']:.3f}), "
              f"jet mass above the cut {theory['jet_mass_above_cut_g']:.3f} g, momentum "
              f"{theory['jet_momentum_above_cut']:.4f} g cm/us."]
    for name, *_ in charges:
        b = result["charges"][name]["summary"]["birkhoff"]
        if b and b["jet_length"] == 0:
            lines.append(f"- {name}: no copper faster than {a.cut:g} cm/us on the axis row on "
                         f"entering the rock (t = {b['at_time']:g} us): no Birkhoff depth from "
                         "the jet's length (see the interval check below).")
        elif b:
            lines.append(f"- {name}: fast jet {b['jet_length']:.2f} cm long on entering the rock "
                         f"(t = {b['at_time']:g} us): Birkhoff depth {b['depth_quartz']:.2f} cm; "
                         f"crater at the end {fmt(b['crater_depth_final'], '{:.2f}')} cm.")
    for name, *_ in charges:
        for target, pc in result["charges"][name]["summary"]["penetration_check"].items():
            lines.append(f"- {name}, through the {target}: the tip advanced "
                         f"{pc['run_depth']:.2f} cm "
                         f"over {pc['intervals']} dump intervals, where u = v / (1 + sqrt(rho_t / "
                         f"rho_jet)) of the jet behind it (within {a.behind:g} cm) gives "
                         f"{pc['theory_depth']:.2f} cm.")
    if result["mass_ledger"]:
        lines += ["", "| material | mass at start (g) | at end (g) | lost through the "
                  "boundaries |", "|---|---|---|---|"]
        for m, v in result["mass_ledger"].items():
            lines.append(f"| {m} | {v['start']:.6g} | {v['end']:.6g} | "
                         f"{100 * v['lost_relative']:.3f} % |")
    lines += ["", "| t (us) | charge | tip x (cm) | tip speed dx/dt | tip cell u | jet behind the "
              "tip | steel ahead (cells) | jet mass (g) | jet length (cm) |",
              "|---|---|---|---|---|---|---|---|---|"]
    for n in range(len(runs)):
        for name, *_ in charges:
            r = rows[name][n]
            lines.append(f"| {r['time']:g} | {name} | {fmt(r['tip_x'])} | "
                         f"{fmt(r['tip_speed_dxdt'])} | {fmt(r['tip_speed_cell'])} | "
                         f"{fmt(r['jet_speed_behind_tip'])} | "
                         f"{fmt(r['steel_ahead'], '{:.2f}')} | {r['jet_mass']:.4f} | "
                         f"{r['jet_length']:.2f} |")
    text = "\n".join(lines) + "\n"
    print(text)
    if a.output:
        print("\n".join(dumps.write_report(a.output, result, text)))


if __name__ == "__main__":
    main()
