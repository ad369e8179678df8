#!/usr/bin/env python3
"""Time-step rules at equal wall time (issue #54).

Runs, back to back in one process each,
  1. perf/tradeoff --rules RULES --repeat N: every verification scene with an exact solution at
     2-3 meshes under each time.rule (the error measure the tests use; the least wall time of N
     runs), and
  2. perf/timestep_study --rules RULES: every shipped deck to its end (or --max-cycles) under
     each rule at its own cfl: healthy or not, cycles, energy change,
then compares the rules' error at equal wall time: per scene and rule the error is interpolated
against wall time in log-log (piecewise linear through the meshes' points) at the reference wall
time t*, the geometric mean of the range every rule's points cover (outside a rule's range its
end segment is extended, and the row says so). Writes JSON and Markdown.

  perf/timestep_study.py --build BUILD [--rules combined,separate,cloverleaf] [--repeat 3]
                         [--scenes sod,...] [--max-cycles N] [--out perf/results/timestep_rules]
                         [--skip-stability] [--from-json FILE]

One rank, OMP_NUM_THREADS=1 (set here). Wall times are from whatever machine runs it: compare
only within one run of this script.
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time


def run(cmd, env):
    print("+", " ".join(cmd), file=sys.stderr, flush=True)
    t0 = time.time()
    r = subprocess.run(cmd, env=env, stdout=subprocess.PIPE, text=True)
    print(f"  ({time.time() - t0:.0f} s, rc {r.returncode})", file=sys.stderr, flush=True)
    return r


def interp_loglog(points, t):
    """Error at wall time t from (wall, error) points, piecewise linear in log-log; the end
    segments extended beyond the points. Returns (error, extrapolated)."""
    pts = sorted((w, e) for w, e in points if w > 0 and e is not None and e > 0)
    if not pts:
        return None, False
    if len(pts) == 1:
        return pts[0][1], t != pts[0][0]
    lt = math.log(t)
    extrap = t < pts[0][0] or t > pts[-1][0]
    if t <= pts[0][0]:
        a, b = pts[0], pts[1]
    elif t >= pts[-1][0]:
        a, b = pts[-2], pts[-1]
    else:
        a, b = next((p, q) for p, q in zip(pts, pts[1:]) if p[0] <= t <= q[0])
    la, lb = math.log(a[0]), math.log(b[0])
    if lb == la:
        return min(a[1], b[1]), extrap
    f = (lt - la) / (lb - la)
    return math.exp(math.log(a[1]) + f * (math.log(b[1]) - math.log(a[1]))), extrap


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", required=True, help="build directory (perf/tradeoff, perf/timestep_study)")
    ap.add_argument("--rules", default="combined,separate,cloverleaf")
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--scenes", default="", help="tradeoff scenes (default: all of --rules')")
    ap.add_argument("--decks", default="", help="timestep_study decks (default: all configs)")
    ap.add_argument("--max-cycles", type=int, default=0)
    ap.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "results", "timestep_rules"))
    ap.add_argument("--skip-stability", action="store_true")
    ap.add_argument("--from-json", default="", help="re-tabulate a previous run's JSON")
    ap.add_argument("--stability-json", default="",
                    help="comma-separated timestep_study --json files to use as the stability part "
                         "(e.g. the long decks run apart with --max-cycles)")
    ap.add_argument("--stability-note", default="", help="a sentence on how the stability runs were made")
    a = ap.parse_args()
    rules = a.rules.split(",")
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_WAIT_POLICY="passive", OMP_PROC_BIND="false")

    if a.from_json:
        with open(a.from_json) as f:
            data = json.load(f)
    else:
        data = {"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "rules": rules,
                "repeat": a.repeat, "cfl_transport": "the deck's cfl (the default)", "machine": os.uname().nodename + ", " + str(os.cpu_count()) + " cores",
                "commit": subprocess.run(["git", "rev-parse", "--short", "HEAD"], stdout=subprocess.PIPE,
                                         text=True, cwd=os.path.dirname(os.path.abspath(__file__))).stdout.strip()}
        tj = a.out + "_accuracy_raw.json"
        cmd = [os.path.join(a.build, "perf", "tradeoff"), "--rules", a.rules, "--repeat", str(a.repeat),
               "--json", tj]
        if a.scenes:
            cmd += ["--scenes", a.scenes]
        r = run(cmd, env)
        with open(tj) as f:
            data["accuracy"] = json.load(f)["points"]
        os.remove(tj)
        data["accuracy_rc"] = r.returncode
        if not a.skip_stability:
            sj = a.out + "_stability_raw.json"
            cmd = [os.path.join(a.build, "perf", "timestep_study"), "--rules", a.rules, "--json", sj]
            if a.decks:
                cmd += ["--scenes", a.decks]
            if a.max_cycles:
                cmd += ["--max-cycles", str(a.max_cycles)]
            run(cmd, env)
            with open(sj) as f:
                data["stability"] = json.load(f)
            os.remove(sj)

    if a.stability_json:
        data["stability"] = []
        for fn in a.stability_json.split(","):
            with open(fn) as f:
                data["stability"] += json.load(f)
    if a.stability_note:
        data["stability_note"] = a.stability_note

    # equal wall time, and equal work (cell-cycles: the same comparison without the machine's
    # noise, the rules' cycles costing the same)
    for p in data["accuracy"]:
        p["cell_cycles"] = p["cell_cycles_per_s"] * p["wall_s"]
    scenes = []
    for p in data["accuracy"]:
        if p["scene"] not in scenes:
            scenes.append(p["scene"])

    def compare(key):
        table = []
        for s in scenes:
            by = {r: [p for p in data["accuracy"] if p["scene"] == s and p["options"] == "time.rule=" + r]
                  for r in rules}
            ok = all(by[r] and all(p["ok"] for p in by[r]) for r in rules)
            have = [r for r in rules if by[r]]
            lo = max(min(p[key] for p in by[r]) for r in have)
            hi = min(max(p[key] for p in by[r]) for r in have)
            t_ref = math.sqrt(lo * hi) if lo > 0 and hi > 0 else None
            row = {"scene": s, "measure": by[rules[0]][0]["measure"] if by[rules[0]] else "",
                   "reference": t_ref, "overlap": hi >= lo, "all_ok": ok, "rules": {}}
            for r in rules:
                e, ex = (interp_loglog([(p[key], p["error"]) for p in by[r] if p["ok"]], t_ref)
                         if t_ref else (None, False))
                row["rules"][r] = {"error": e, "extrapolated": ex,
                                   "points": [{"cells": p["cells"], "wall_s": p["wall_s"], "error": p["error"],
                                               "cycles": p["cycles"], "cell_cycles": p["cell_cycles"],
                                               "ok": p["ok"]} for p in by[r]]}
            base = row["rules"][rules[0]]["error"]
            for r in rules:
                e = row["rules"][r]["error"]
                row["rules"][r]["ratio"] = e / base if e and base else None
            table.append(row)
        gm = {}
        for r in rules:
            rs = [row["rules"][r]["ratio"] for row in table if row["rules"][r]["ratio"]]
            gm[r] = math.exp(sum(math.log(x) for x in rs) / len(rs)) if rs else None
        return table, gm

    data["equal_wall_time"], data["geomean_ratio_wall"] = compare("wall_s")
    data["equal_work"], data["geomean_ratio_work"] = compare("cell_cycles")

    with open(a.out + ".json", "w") as f:
        json.dump(data, f, indent=1)
        f.write("\n")

    md = [f"# Time-step rules at equal wall time (perf/timestep_study.py)\n",
          f"{data['date']}, commit {data['commit']}, {data['machine']} (shared with other agents: loaded), "
          f"1 OpenMP thread, one rank; each point the least wall time of {data['repeat']} rounds (the rules of a mesh in turn) "
          "(perf/tradeoff --rules, quasi-1-D scenes on cubic cells). Rules (docs/numerics.md, \"Time step\"): "
          "combined `cfl dx / (c_eff + |u|)`; separate `min(cfl dx / c_eff, cfl_transport dx / |u|)`; "
          "cloverleaf CloverLeaf3D_ref's sound, face-velocity and divergence limits; every deck at its own "
          f"cfl, cfl_transport {data.get('cfl_transport', '0.5 (the default then)')}.\n",
          "Each rule's error interpolated in log-log against wall time (or work) at the reference, the "
          "geometric mean of the range all rules cover (`*`: a rule's end segment extended to reach it). "
          "Ratio: that error over the first rule's (below 1: more accurate for the same time).\n",
          ]

    def md_table(table, gm, unit, fmt):
        md.append(f"| scene | measure | reference {unit} | " + " | ".join(f"{r} error (ratio)" for r in rules) + " |")
        md.append("|---|---|---|" + "---|" * len(rules))
        for row in table:
            cells = []
            for r in rules:
                x = row["rules"][r]
                cells.append("n/a" if x["error"] is None else
                             f"{x['error']:.3e}{'*' if x['extrapolated'] else ''} ({x['ratio']:.3f})")
            ref = fmt(row["reference"]) if row["reference"] else ""
            md.append(f"| {row['scene']} | {row['measure'].replace('|', '')} | {ref} | " + " | ".join(cells) + " |")
        md.append("| geometric mean of the ratios | | | " +
                  " | ".join(f"{gm[r]:.3f}" if gm[r] else "n/a" for r in rules) + " |\n")

    same = []
    for row in data["equal_wall_time"]:
        for i, r in enumerate(rules):
            for q in rules[i + 1:]:
                pr, pq = row["rules"][r]["points"], row["rules"][q]["points"]
                if pr and len(pr) == len(pq) and all(
                        x["cycles"] == y["cycles"] and x["error"] is not None and y["error"] is not None and
                        abs(x["error"] - y["error"]) <= 1e-12 * abs(x["error"]) for x, y in zip(pr, pq)):
                    same.append(f"{row['scene']} ({r} = {q})")
    if same:
        md.append("Runs the same to the error's 12th digit and the cycle at every mesh (their wall-time gap is "
                  "the machine's noise, their equal-wall-time ratios differ only by it): " + ", ".join(same) + ".\n")
    md.append("## Error at equal wall time\n")
    md_table(data["equal_wall_time"], data["geomean_ratio_wall"], "wall s", lambda x: f"{x:.3g}")
    md.append("## Error at equal work (cell-cycles; the same without the machine's noise)\n")
    md_table(data["equal_work"], data["geomean_ratio_work"], "cell-cycles", lambda x: f"{x:.3g}")
    table = data["equal_wall_time"]
    md.append("## The points (cells: wall s, error, cycles)\n")
    md.append("| scene | cells | " + " | ".join(rules) + " |")
    md.append("|---|---|" + "---|" * len(rules))
    for row in table:
        cells_list = [p["cells"] for p in row["rules"][rules[0]]["points"]]
        for i, n in enumerate(cells_list):
            parts = []
            for r in rules:
                ps = row["rules"][r]["points"]
                p = ps[i] if i < len(ps) else None
                parts.append(f"{p['wall_s']:.4f} s, {p['error']:.4e}, {p['cycles']}{'' if p['ok'] else ' FAILED'}"
                             if p and p["error"] is not None else "failed")
            md.append(f"| {row['scene']} | {n} | " + " | ".join(parts) + " |")
    if "stability" in data:
        md.append("\n## Stability: every shipped deck under each rule at its own cfl\n")
        md.append("The 3-D Noh and Sedov at half their deck resolution. " + data.get("stability_note", "") +
                  " ok: the run reached its end "
                  + (f"(or {a.max_cycles} cycles) " if a.max_cycles else "(t the time reached) ")
                  + "with every cell physical (the health check); dE/E the relative change of total energy "
                  "(open boundaries, plastic work and inflow change it on some decks: compare across rules).\n")
        decks = []
        for o in data["stability"]:
            if o["scene"] not in decks:
                decks.append(o["scene"])
        md.append("| deck | cfl | " + " | ".join(f"{r}: ok, cycles, t, dE/E" for r in rules) +
                  " | " + " | ".join(f"L1(rho-rho_{rules[0]})/mean, {r}" for r in rules[1:]) + " |")
        md.append("|---|---|" + "---|" * (2 * len(rules) - 1))
        for d in decks:
            os_ = {o["rule"]: o for o in data["stability"] if o["scene"] == d}
            parts, diffs = [], []
            for r in rules:
                o = os_.get(r)
                if not o:
                    parts.append("n/a")
                    continue
                parts.append(f"{'ok' if o['ok'] else 'FAILED: ' + o['what'][:60]}, {o['cycles']}, {o['time']:.4g}, "
                             f"{o['energy_change']:.2e}")
                if r != rules[0]:
                    diffs.append(f"{o['l1_rho_vs_first']:.2e}" if o["l1_rho_vs_first"] is not None else "n/a")
            cfl = next(iter(os_.values()))["cfl"]
            md.append(f"| {d} | {cfl:g} | " + " | ".join(parts) + " | " + " | ".join(diffs) + " |")
    with open(a.out + ".md", "w") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md))


if __name__ == "__main__":
    main()
