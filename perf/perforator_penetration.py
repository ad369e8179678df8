#!/usr/bin/python3
"""One of the perforator's charges against zone size (issue #52): what its jet does to the carrier
tube, the casing and the rock, to the end of the penetration, with the cost of each zone and,
where three zones allow it, the converged value by Richardson extrapolation with an uncertainty.

    /usr/bin/python3 perf/perforator_penetration.py --exe build/minipagosa \\
        [--charge bottom|top] [--zones 0.1 0.075 0.05 0.0375] [--order second] [--end 60] \\
        [--box X0 X1] [--threads 2] [--work /tmp/perforator_penetration] [--reuse] \\
        [--set KEY=VALUE ...] [-o perf/results/perforator/penetration_bottom]

The scene is configs/perforator.yaml cut to one charge (perf/perforator_study.py, cut_deck), the
other charge's regions and detonator dropped; the faces the deck does not have are outflow, as
the deck's. Dumps every 2.5 us, the mass ledger on.
- bottom (axis y = 0, z = -1.27, aimed -x; its case spans z -2.26..-0.28): x in [-14, -2.98],
  y in [0, 1.6], z in [-2.5, -0.15]. The jet fires through the carrier wall, which lies flush on
  the casing there, so no well fluid is on its path: the run holds for either well fluid. 7 cm
  of rock lie beyond the casing (the deck has 11).
- top (z = +1.27, aimed +x across the well): x in [-5.45, 12] (the deck's +x face: 5 cm of
  rock beyond the far casing), y in [0, 1.6], z in [0.15, 2.5]; the well's fluid the deck's
  (air) unless --set changes it (water: the deck header's three --set values).

Each run is measured by tools/perforator_check.py (`analyse`, the charge's rows): the first dump
through the carrier, at the casing, in the rock; the fastest tip; the jet (copper faster than
0.2 cm/us) at its largest; the openings when first pierced and at the end; the crater's and the
tip's depth into the rock at the end; whether the tip still moves (its speed over the last
10 us); the hydrodynamic (Birkhoff et al. 1948) check, the tip's advance between dumps in the rock
and in the casing's steel against u = v / (1 + sqrt(rho_target / rho_jet)) of the jet speed v
within 1 cm behind the tip, summed; and each material's mass lost through the faces. Richardson
as perf/perforator_study.py (three finest zones; Roache's GCI as the uncertainty; no claim where
the differences change sign or the order leaves [0.5, 4]).
Writes PREFIX.json, PREFIX.md and PREFIX.png.
"""
import argparse
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
sys.path.insert(0, os.path.join(ROOT, "perf"))
import dumps  # noqa: E402
import perforator_check  # noqa: E402
import perforator_study  # noqa: E402
import shaped_charge  # noqa: E402

TOOL = "perforator_penetration"
# per charge: perforator_check's name, the box's x extent, its (y, z) corners
CHARGES = {"bottom": ("bottom (aimed -x)", (-14.0, -2.98), (0.0, -2.5), (1.6, -0.15)),
           "top": ("top (aimed +x)", (-5.45, 12.0), (0.0, 0.15), (1.6, 2.5))}

# (key, column heading, format): the per-zone quantities, from a bottom-charge analysis
QUANTITIES = [
    ("carrier_through", "through the carrier (us, dump)", "{:.1f}"),
    ("casing_reached", "at the casing (us, dump)", "{:.1f}"),
    ("rock", "in the rock (us, dump)", "{:.1f}"),
    ("max_tip_speed", "fastest tip (cm/us)", "{:.3f}"),
    ("max_jet_mass", "jet > 0.2 cm/us, largest (g)", "{:.4f}"),
    ("max_jet_momentum", "its momentum (g cm/us)", "{:.4f}"),
    ("carrier_hole", "carrier hole when pierced (cm)", "{:.3f}"),
    ("casing_entrance", "casing entrance when pierced (cm)", "{:.3f}"),
    ("casing_exit", "casing exit when pierced (cm)", "{:.3f}"),
    ("casing_entrance_end", "casing entrance at the end (cm)", "{:.3f}"),
    ("crater_depth", "crater depth at the end (cm)", "{:.3f}"),
    ("tip_depth", "tip depth at the end (cm)", "{:.3f}"),
    ("rock_run", "tip's advance in the rock, dump to dump (cm)", "{:.2f}"),
    ("rock_theory", "the same from u = v / (1 + sqrt(rho_t / rho_j)) (cm)", "{:.2f}"),
    ("rock_ratio", "run / hydrodynamic theory, rock", "{:.3f}"),
    ("steel_ratio", "run / hydrodynamic theory, casing steel", "{:.3f}"),
    ("tip_speed_end", "tip speed over the last 10 us (cm/us)", "{:.4f}"),
    ("quartz_lost", "quartz out through the faces (%)", "{:.2f}"),
]


def quantities(result, charge):
    """The per-zone quantities of one run's perforator_check result (None where not reached)."""
    ch = result["charges"][charge]
    s, hist = ch["summary"], ch["history"]
    fd, fl = s["first_dump"], s["final"]
    q = {k: fd[k] for k in ("carrier_through", "casing_reached", "rock")}
    q["max_tip_speed"] = s["max_tip_speed_cell"]
    q["max_jet_mass"] = s["max_jet_mass"]
    q["max_jet_momentum"] = s["max_jet_momentum"]
    q["carrier_hole"] = s["carrier_hole_when_pierced"]
    q["casing_entrance"] = s["casing_entrance_when_pierced"]
    q["casing_exit"] = s["casing_exit_when_pierced"]
    q["casing_entrance_end"] = fl["casing_entrance"][0] if fl["casing_entrance"] else None
    q["crater_depth"] = fl["crater_depth"]
    q["tip_depth"] = fl["tip_depth"]
    pc = s["penetration_check"]
    rock, steel = pc.get("quartz"), pc.get("steel")
    q["rock_run"] = rock["run_depth"] if rock else None
    q["rock_theory"] = rock["theory_depth"] if rock else None
    q["rock_ratio"] = rock["run_depth"] / rock["theory_depth"] if rock else None
    q["steel_ratio"] = steel["run_depth"] / steel["theory_depth"] if steel else None
    # whether the penetration has stopped: the tip's advance over the last 10 us
    tips = [(h["time"], h["tip_x"]) for h in hist if h["tip_x"] is not None]
    back = [p for p in tips if p[0] <= tips[-1][0] - 10.0 + 1e-9]
    sign = -1.0 if charge.startswith("bottom") else 1.0
    q["tip_speed_end"] = (0.0 + sign * (tips[-1][1] - back[-1][1]) / (tips[-1][0] - back[-1][0])
                          if back else None)
    led = result["mass_ledger"] or {}
    q["quartz_lost"] = 100.0 * led["quartz"]["lost_relative"] if "quartz" in led else None
    return q


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "minipagosa"))
    ap.add_argument("--charge", choices=sorted(CHARGES), default="bottom")
    ap.add_argument("--zones", type=float, nargs="+", default=[0.1, 0.075, 0.05, 0.0375])
    ap.add_argument("--order", default="second")
    ap.add_argument("--end", type=float, default=60.0)
    ap.add_argument("--box", type=float, nargs=2, default=None,
                    help="the box's x extent (default: the charge's, above)")
    ap.add_argument("--y-hi", type=float, default=None,
                    help="the box's +y face (default 1.6; the deck's is 3)")
    ap.add_argument("--set", nargs="+", default=[], metavar="KEY=VALUE",
                    help="deck values for every run (e.g. the water well)")
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--work", default="/tmp/perforator_penetration")
    ap.add_argument("--reuse", action="store_true",
                    help="take a run already in --work (its study_run.json: the cost) instead of "
                         "running it; its dumps are measured again")
    ap.add_argument("-o", "--output", default=None, help="prefix of the .json, .md and .png")
    a = ap.parse_args()
    charge, box, lo_yz, hi_yz = CHARGES[a.charge]
    a.box = a.box or list(box)
    if a.y_hi is not None:
        hi_yz = (a.y_hi, hi_yz[1])
    os.makedirs(a.work, exist_ok=True)
    scene = f"perforator_{a.charge}"
    deck_path = os.path.join(a.work, scene + ".yaml")
    with open(deck_path, "w") as f:
        f.write(perforator_study.cut_deck(a.box, a.end, lo_yz, hi_yz, scene, interval=2.5,
                                          ledger=True))
    check = perforator_check.options(charges=a.charge)
    results = []
    for z in sorted(a.zones, reverse=True):
        out = os.path.join(a.work, f"z{z:g}_{a.order}")
        done = os.path.join(out, "study_run.json")
        if a.reuse and os.path.exists(done):
            # (the run's cost as it was measured; its dumps measured again)
            with open(done) as f:
                r = {k: v for k, v in json.load(f).items()
                     if k not in ("quantities", "history", "mass_ledger")}
        else:
            print(f"[{TOOL}] zone {z:g}, {a.order} order", flush=True)
            r = perforator_study.execute(a, deck_path, z, a.order, out, a.set)
        analysis = perforator_check.analyse(out, check)[0]
        r["quantities"] = quantities(analysis, charge)
        r["history"] = [{k: h[k] for k in ("time", "tip_x", "tip_speed_cell", "jet_mass",
                                            "crater_depth", "tip_depth", "casing_entrance")}
                        for h in analysis["charges"][charge]["history"]]
        r["mass_ledger"] = analysis["mass_ledger"]
        with open(done, "w") as f:
            json.dump(r, f, indent=1)
        results.append(r)
        print(f"  {r['cycles']} cycles, {r['wall_seconds']:.1f} s, {r['peak_rss_mib']:.0f} MiB; "
              + ", ".join(f"{k} {v}" for k, v in r["quantities"].items()), flush=True)
    hs = [r["zone"] for r in results]
    conv = {k: perforator_study.richardson(hs, [r["quantities"][k] for r in results])
            for k, *_ in QUANTITIES}
    theory = shaped_charge.predict(cut=check.cut)
    theory.pop("elements")
    doc = {"charge": charge, "box_x": a.box, "box_yz": [lo_yz, hi_yz], "sets": a.set,
           "end": a.end, "order": a.order,
           "threads": a.threads, "exe": a.exe, "machine": os.uname().nodename,
           "runs": results, "richardson": conv, "theory": theory}

    lines = [f"# The perforator's {a.charge} charge against zone size", "",
             f"configs/perforator.yaml cut to x in [{a.box[0]:g}, {a.box[1]:g}], y in "
             f"[{lo_yz[0]:g}, {hi_yz[0]:g}], z in [{lo_yz[1]:g}, {hi_yz[1]:g}] (the {a.charge} "
             f"charge{', ' + ' '.join(a.set) if a.set else ''}), {a.order} order, to "
             f"{a.end:g} us; {a.threads} threads; load average at the end "
             f"{os.getloadavg()[0]:.1f}. Masses whole charge. Arrival times are the first dump "
             "(every 2.5 us) showing the event.", "",
             "| zone (cm) | cells | cycles | wall (s) | core-hours | peak RSS (MiB) |",
             "|---|---|---|---|---|---|"]
    for r in results:
        lines.append(f"| {r['zone']:g} | {perforator_study.cost_cells(r)} |")
    lines += ["", "| quantity | " + " | ".join(f"zone {h:g}" for h in hs) + " | Richardson |",
              "|---|" + "---|" * (len(hs) + 1)]
    for k, name, f in QUANTITIES:
        vals = ["—" if r["quantities"][k] is None else f.format(r["quantities"][k])
                for r in results]
        rc = conv[k]
        if "value" in rc and "note" not in rc and rc.get("order") is not None:
            rtext = f"{f.format(rc['value'])} ± {f.format(rc['gci'])} (p = {rc['order']:.2f})"
        else:
            rtext = rc.get("note", "—")
        lines.append(f"| {name} | " + " | ".join(vals) + f" | {rtext} |")
    lines += ["", "Theory (tools/shaped_charge.py): PER tip speed "
              f"{theory['tip_speed']:.3f} cm/us, "
              f"jet above 0.2 cm/us {theory['jet_mass_above_cut_g']:.3f} g. Hydrodynamic "
              "penetration speed u / v: 0.647 into quartz, 0.517 into steel."]
    text = "\n".join(lines) + "\n"
    print(text)
    if a.output:
        written = dumps.write_report(a.output, doc, text)
        plot(results, a.output + ".png", a.charge)
        print("\n".join(written + [a.output + ".png"]))


def plot(results, path, which):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(15, 4))
    for r in results:
        h = r["history"]
        lab = f"zone {r['zone']:g}"
        axes[0].plot([x["time"] for x in h if x["tip_x"] is not None],
                     [x["tip_x"] for x in h if x["tip_x"] is not None], "-o", ms=3, label=lab)
        axes[1].plot([x["time"] for x in h],
                     [x["crater_depth"] if x["crater_depth"] is not None else 0.0 for x in h],
                     "-o", ms=3, label=lab)
    sx = -1.0 if which == "bottom" else 1.0
    for x, s in ((sx * 6.2103, "casing inside"), (sx * 6.9723, "casing outside")):
        axes[0].axhline(x, color="grey", lw=0.7, ls=":")
        axes[0].text(0.5, x, s, fontsize=7, va="bottom")
    axes[0].set_title(f"{which} jet tip x (cm) against time (us)")
    axes[1].set_title("crater depth in the rock (cm) against time (us)")
    hs = [r["zone"] for r in results]
    for k, style in (("crater_depth", "-o"), ("tip_depth", "--s"), ("rock_theory", ":^")):
        axes[2].plot(hs, [r["quantities"][k] for r in results], style, label=k)
    axes[2].set_xlabel("zone (cm)")
    axes[2].invert_xaxis()
    axes[2].set_title("depth into the rock at the end (cm)")
    for ax in axes:
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


if __name__ == "__main__":
    main()
