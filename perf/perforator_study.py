#!/usr/bin/python3
"""The perforator's top jet against zone size and advection order (issues #52 and #53): the
jet's tip, speed, fast copper and momentum at given times, each with its cost, and where three
zones or more allow it the converged value by Richardson extrapolation with an uncertainty.

    /usr/bin/python3 perf/perforator_study.py --exe build/minipagosa \\
        [--zones 0.1 0.075 0.05 0.0375] [--orders second third] [--end 20] [--times 8 10 20] \\
        [--box -5.45 2.5] [--threads 2] [--work /tmp/perforator_study] \\
        [--variant NAME KEY=VALUE...]... [--variant-zone 0.05] [-o perf/results/perforator_convergence]

The scene is configs/perforator.yaml itself, cut as the CI guard cuts it (tests/test_perforator.cpp,
top_charge_scene): the box x in [--box], y in [0, 1.3], z in [0.15, 2.45] around the top charge
(its case spans z 0.28..2.26 and radius 0.99); every region and detonator wholly outside the box
dropped (the bottom charge); every other value the deck's. The default box runs from the case's
back through the carrier wall into the well's air, where the jet flies free to 20 us. Each run
is `minipagosa CUT --set mesh.zone=Z --set numerics.advection=O` with dumps every 1 us; its cost
is the wall time and cycles from summary.json and the peak resident memory (/usr/bin/time).

Measured on the top charge's axis row (the cells nearest y = 0, z = 1.27), at each --times:
- tip_x: where the copper fraction last falls through 0.5 along x (linear between the centres of
  the last cell above 0.5 and the next), and tip_u, that cell's x velocity (mean of its nodes);
(each linear in time between the dumps either side of the time asked for)
- fast copper: the copper mass (whole charge: twice the half mesh's; fraction x 8.93 g/cm^3 x
  cell volume) in cells faster than 0.2 and 0.4 cm/us along x, and the axial momentum of the
  copper faster than 0.2.
Richardson: with the three finest zones h1 > h2 > h3 and values q1, q2, q3, the order p solves
(q1 - q2) / (q2 - q3) = (h1^p - h2^p) / (h2^p - h3^p); q_inf = q3 + (q3 - q2) / ((h2/h3)^p - 1);
the uncertainty is Roache's grid-convergence index on the finest zone, 1.25 |q3 - q2| /
((h2/h3)^p - 1) (P. J. Roache, J. Fluids Eng. 116 (1994) 405). Where the differences change sign
(oscillatory) or p falls outside [0.5, 4], no extrapolation is claimed: the table says why.
Sensitivity (--variant): the same scene at one zone with some deck values changed, e.g. the
paper's elastic-perfectly-plastic metals, SLIC interfaces, pressure relaxation.
Writes PREFIX.json, PREFIX.md and PREFIX.png.
"""
import argparse
import json
import os
import subprocess
import sys
import time

import numpy as np
import yaml

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import dumps  # noqa: E402

TOOL = "perforator_study"
Y_HI, Z_LO, Z_HI = 1.3, 0.15, 2.45
AXIS_Z = 1.27
RHO_COPPER = 8.93


def outside(p, q, pad, lo, hi):
    for d in range(3):
        a = min(p[d], q[d]) - pad
        b = max(p[d], q[d]) + pad
        if b < lo[d] or a > hi[d]:
            return True
    return False


def cut_deck(box, end, lo_yz=(0.0, Z_LO), hi_yz=(Y_HI, Z_HI), scene="perforator_top",
             interval=1.0, ledger=False):
    """configs/perforator.yaml cut to the box x in `box`, (y, z) from lo_yz to hi_yz, as YAML text:
    every region and point detonator wholly outside it dropped, every other value the deck's."""
    with open(os.path.join(ROOT, "configs", "perforator.yaml")) as f:
        deck = yaml.safe_load(f)
    lo, hi = [box[0], *lo_yz], [box[1], *hi_yz]
    deck["regions"] = [r for r in deck["regions"]
                       if "base" not in r or not outside(r["base"], r["top"], r["radius"], lo, hi)]
    for m in deck["materials"]:
        if "burn" in m:
            m["burn"]["detonators"] = [d for d in m["burn"]["detonators"]
                                       if d["type"] != "point" or not outside(d["at"], d["at"], 0,
                                                                              lo, hi)]
    deck["scene"] = scene
    deck["mesh"]["lo"], deck["mesh"]["hi"] = lo, hi
    deck["time"]["end"] = end
    deck["output"] = {"dir": f"output/{scene}", "interval": interval, "log_every": 100}
    if ledger:
        deck["output"]["mass_ledger"] = True
    return yaml.safe_dump(deck, sort_keys=False)


def measure(d):
    cu = d.fraction("copper")
    ux = dumps.cell_ux(d)
    h = d.spacing[0]
    vol = float(np.prod(d.spacing))
    k = d.plane_index(2, AXIS_Z)
    row = cu[k, 0, :]
    on = np.nonzero(row > 0.5)[0]
    out = {"time": d.time, "cycle": d.cycle, "tip_x": None, "tip_u": None}
    if on.size:
        i = int(on.max())
        nxt = row[i + 1] if i + 1 < row.size else 0.0
        x = d.centres(0)
        out["tip_x"] = float(x[i] + h * (row[i] - 0.5) / (row[i] - nxt))
        out["tip_u"] = float(ux[k, 0, i])
    mass = 2.0 * cu * RHO_COPPER * vol
    out["fast_mass_0.2"] = float(mass[ux > 0.2].sum())
    out["fast_mass_0.4"] = float(mass[ux > 0.4].sum())
    out["fast_momentum_0.2"] = float((mass * ux)[ux > 0.2].sum())
    return out


def measure_at(out, runs, t):
    """The measurements at time t: linear in time between the dumps either side (a dump lands
    on the first cycle past each interval, not on it; the tip moves about 0.02 cm in that gap)."""
    after = next((r for r in runs if r[0] >= t - 1e-9), None)
    before = next((r for r in reversed(runs) if r[0] <= t + 1e-9), None)
    if after is None or before is None:
        dumps.fail(TOOL, f"{out}: no dumps around t = {t:g}")
    m1 = measure(dumps.Dump(TOOL, after[2]))
    if after[0] - before[0] < 1e-12:
        return m1
    m0 = measure(dumps.Dump(TOOL, before[2]))
    w = (t - before[0]) / (after[0] - before[0])
    out_ = {"time": t, "between_dumps": [before[0], after[0]]}
    for k, v in m1.items():
        if k in ("time", "cycle"):
            continue
        out_[k] = None if v is None or m0[k] is None else m0[k] + w * (v - m0[k])
    return out_


def richardson(hs, qs):
    """Observed order, extrapolated value and GCI from the three finest (h, q); or a reason."""
    if len(hs) < 3 or any(q is None for q in qs[-3:]):
        return {"note": "fewer than three zones"}
    (h1, h2, h3), (q1, q2, q3) = hs[-3:], qs[-3:]
    d12, d23 = q1 - q2, q2 - q3
    if d23 == 0:
        return {"note": "the two finest zones agree", "value": q3, "gci": 0.0, "order": None}
    if d12 * d23 <= 0:
        return {"note": "oscillatory (the differences change sign): no extrapolation",
                "spread": max(q1, q2, q3) - min(q1, q2, q3)}
    target = d12 / d23

    def f(p):
        return (h1 ** p - h2 ** p) / (h2 ** p - h3 ** p) - target
    lo, hi = 0.05, 8.0
    if f(lo) * f(hi) > 0:
        return {"note": "no order in [0.05, 8] fits", "spread": max(q1, q2, q3) - min(q1, q2, q3)}
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        if f(lo) * f(mid) <= 0:
            hi = mid
        else:
            lo = mid
    p = 0.5 * (lo + hi)
    r = (h2 / h3) ** p - 1
    res = {"order": p, "value": q3 + (q3 - q2) / r, "gci": 1.25 * abs(q3 - q2) / r}
    if not 0.5 <= p <= 4:
        res["note"] = f"observed order {p:.2f} outside [0.5, 4]: extrapolation not claimed"
    return res


def execute(a, deck_path, zone, order, out, sets=()):
    """One run of the cut deck at `zone` and advection `order` into `out` (a.exe, a.threads):
    its cost (cells, cycles, wall and core-hours from summary.json, peak resident memory from
    /usr/bin/time)."""
    cmd = ["/usr/bin/time", "-f", "%M", a.exe, deck_path, "--set", f"mesh.zone={zone:g}",
           "--set", f"numerics.advection={order}", "-o", out, "--overwrite", "-q"]
    for kv in sets:
        cmd += ["--set", kv]
    env = dict(os.environ, OMP_NUM_THREADS=str(a.threads))
    t0 = time.time()
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    wall = time.time() - t0
    if p.returncode != 0:
        dumps.fail(TOOL, f"{' '.join(cmd)} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    rss_kb = int(p.stderr.strip().splitlines()[-1])
    with open(os.path.join(out, "summary.json")) as f:
        s = json.load(f)
    return {"zone": zone, "order": order, "sets": list(sets), "cells": s["cells"],
            "cycles": s["cycles"], "wall_seconds": s["wall_seconds"], "process_seconds": wall,
            "core_hours": s["wall_seconds"] * a.threads / 3600.0, "peak_rss_mib": rss_kb / 1024.0,
            "load_average": os.getloadavg()[0]}


def run_one(a, deck_path, zone, order, work, variant=None):
    name, sets = variant if variant else ("default", [])
    out = os.path.join(work, f"z{zone:g}_{order}" + ("" if not variant else f"_{name}"))
    done = os.path.join(out, "study_run.json")
    if a.reuse and os.path.exists(done):
        with open(done) as f:
            return json.load(f)
    res = execute(a, deck_path, zone, order, out, sets)
    runs = dumps.list_dumps(TOOL, out)
    res["variant"] = name
    res["at"] = {f"{t:g}": measure_at(out, runs, t) for t in a.times}
    with open(done, "w") as f:
        json.dump(res, f, indent=1)
    return res


def cost_cells(r):
    """A run's cost (`execute`) as Markdown table cells: cells, cycles, wall (s), core-hours and
    peak RSS (MiB)."""
    c = r["cells"]
    return (f"{c[0]}×{c[1]}×{c[2]} = {c[0] * c[1] * c[2]:,} | {r['cycles']} | "
            f"{r['wall_seconds']:.1f} | {r['core_hours']:.4f} | {r['peak_rss_mib']:.0f}")


QUANTITIES = [("tip_x", "tip x (cm)", "{:.3f}"), ("tip_u", "tip u (cm/us)", "{:.3f}"),
              ("fast_mass_0.2", "Cu > 0.2 cm/us (g)", "{:.4f}"),
              ("fast_mass_0.4", "Cu > 0.4 cm/us (g)", "{:.4f}"),
              ("fast_momentum_0.2", "momentum > 0.2 (g cm/us)", "{:.4f}")]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "minipagosa"))
    ap.add_argument("--zones", type=float, nargs="+", default=[0.1, 0.075, 0.05, 0.0375])
    ap.add_argument("--orders", nargs="+", default=["second", "third"])
    ap.add_argument("--end", type=float, default=20.0)
    ap.add_argument("--times", type=float, nargs="+", default=[8.0, 10.0, 20.0])
    ap.add_argument("--box", type=float, nargs=2, default=[-5.45, 2.5])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--work", default="/tmp/perforator_study")
    ap.add_argument("--variant", nargs="+", action="append", default=[], metavar="NAME KEY=VALUE",
                    help="a sensitivity run at --variant-zone and the first of --orders: its name "
                         "and the --set values that make it (repeatable)")
    ap.add_argument("--variant-zone", type=float, default=0.05)
    ap.add_argument("--reuse", action="store_true",
                    help="take a run already in --work (its study_run.json) instead of running it")
    ap.add_argument("-o", "--output", default=None, help="prefix of the .json, .md and .png")
    a = ap.parse_args()
    if any(t > a.end for t in a.times):
        dumps.fail(TOOL, "every --times must be at or before --end")
    os.makedirs(a.work, exist_ok=True)
    deck_path = os.path.join(a.work, "perforator_top.yaml")
    with open(deck_path, "w") as f:
        f.write(cut_deck(a.box, a.end))
    zones = sorted(a.zones, reverse=True)
    results = []
    for order in a.orders:
        for z in zones:
            print(f"[{TOOL}] zone {z:g}, {order} order", flush=True)
            results.append(run_one(a, deck_path, z, order, a.work))
            r = results[-1]
            print(f"  {r['cycles']} cycles, {r['wall_seconds']:.1f} s, "
                  f"{r['peak_rss_mib']:.0f} MiB; " +
                  ", ".join(f"t={t}: tip {v['tip_x']}" for t, v in r["at"].items()), flush=True)
    variants = []
    for v in a.variant:
        print(f"[{TOOL}] zone {a.variant_zone:g}, {a.orders[0]} order, variant {v[0]}", flush=True)
        variants.append(run_one(a, deck_path, a.variant_zone, a.orders[0], a.work, (v[0], v[1:])))
    conv = {}
    for order in a.orders:
        rs = [r for r in results if r["order"] == order]
        hs = [r["zone"] for r in rs]
        conv[order] = {t: {q: richardson(hs, [r["at"][t][q] for r in rs]) for q, *_ in QUANTITIES}
                       for t in rs[0]["at"]}
    doc = {"box_x": a.box, "end": a.end, "threads": a.threads, "exe": a.exe,
           "machine": os.uname().nodename, "load_average_at_end": os.getloadavg(),
           "runs": results, "richardson": conv, "variants": variants}

    lines = ["# The perforator's top jet against zone size and order", "",
             f"configs/perforator.yaml cut to x in [{a.box[0]:g}, {a.box[1]:g}], y in [0, 1.3], "
             f"z in [0.15, 2.45] (the top charge), to {a.end:g} us; {a.threads} threads; load "
             f"average at the end {os.getloadavg()[0]:.1f}. Masses whole charge.", "",
             "| order | zone (cm) | cells | cycles | wall (s) | core-hours | peak RSS (MiB) |",
             "|---|---|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r['order']} | {r['zone']:g} | {cost_cells(r)} |")
    for t in results[0]["at"]:
        lines += ["", f"At t = {t} us:", "",
                  "| order | zone | " + " | ".join(n for _, n, _ in QUANTITIES) + " |",
                  "|---|---|" + "---|" * len(QUANTITIES)]
        for r in results:
            v = r["at"][t]
            lines.append(f"| {r['order']} | {r['zone']:g} | " + " | ".join(
                "—" if v[q] is None else f.format(v[q]) for q, _, f in QUANTITIES) + " |")
        for order in a.orders:
            cells = []
            for q, _, f in QUANTITIES:
                rc = conv[order][t][q]
                if "value" in rc and "note" not in rc:
                    cells.append(f"{f.format(rc['value'])} ± {f.format(rc['gci'])} "
                                 f"(p = {rc['order']:.2f})")
                else:
                    cells.append(rc.get("note", "—"))
            lines.append(f"| {order} | Richardson | " + " | ".join(cells) + " |")
    if variants:
        base = next((r for r in results if r["order"] == a.orders[0]
                     and abs(r["zone"] - a.variant_zone) < 1e-12), None)
        rows = ([base] if base else []) + variants
        t = list(rows[0]["at"])[-1]
        lines += ["", f"Sensitivity at zone {a.variant_zone:g}, {a.orders[0]} order, t = {t} us:",
                  "", "| variant | --set | cycles | wall (s) | " +
                  " | ".join(n for _, n, _ in QUANTITIES) + " |",
                  "|---|---|---|---|" + "---|" * len(QUANTITIES)]
        for r in rows:
            v = r["at"][t]
            lines.append(f"| {r['variant']} | {' '.join(r['sets']) or '(the deck)'} | "
                         f"{r['cycles']} | {r['wall_seconds']:.1f} | " + " | ".join(
                             "—" if v[q] is None else f.format(v[q]) for q, _, f in QUANTITIES)
                         + " |")
    text = "\n".join(lines) + "\n"
    print(text)
    if a.output:
        written = dumps.write_report(a.output, doc, text)
        plot(a, results, a.output + ".png")
        print("\n".join(written + [a.output + ".png"]))


def plot(a, results, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 4, figsize=(18, 4))
    # the tip against time, per zone and order, from every dump of each run
    for r in results:
        out = os.path.join(a.work, f"z{r['zone']:g}_{r['order']}")
        hist = [measure(dumps.Dump(TOOL, path)) for _, _, path in dumps.list_dumps(TOOL, out)]
        hist = [h for h in hist if h["tip_x"] is not None]
        axes[3].plot([h["time"] for h in hist], [h["tip_x"] for h in hist],
                     "-" if r["order"] == a.orders[0] else "--",
                     label=f"{r['order']}, zone {r['zone']:g}")
    axes[3].set_xlabel("t (us)")
    axes[3].set_title("jet tip x (cm) against time")
    axes[3].legend(fontsize=6)
    for order, style in zip(a.orders, ("-o", "--s", ":^")):
        rs = [r for r in results if r["order"] == order]
        hs = [r["zone"] for r in rs]
        for t in rs[0]["at"]:
            axes[0].plot(hs, [r["at"][t]["tip_x"] for r in rs], style, label=f"{order}, {t} us")
            axes[1].plot(hs, [r["at"][t]["fast_mass_0.2"] for r in rs], style,
                         label=f"{order}, {t} us")
        axes[2].loglog(hs, [r["wall_seconds"] for r in rs], style, label=order)
    for ax, title in zip(axes[:3], ("jet tip x (cm)", "copper faster than 0.2 cm/us (g)",
                                    "wall time (s), as the machine's load allowed")):
        ax.set_xlabel("zone (cm)")
        ax.set_title(title)
        ax.invert_xaxis()
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
