#!/usr/bin/env python3
"""minipagosa beside UK-MAC's CloverLeaf3D_ref, run by one script, timed by one clock.

    perf/cloverleaf/side_by_side.py --clover /path/to/clover_leaf [--rounds 5]
        [--minipagosa build/minipagosa] [--sedov-l1 build/perf/sedov_l1]
        [--configs 1x2,2x1] [--sedov-meshes 16,24,32,48,64] [--skip-bm] [--skip-sedov]
        [--bind none|spread] [--baseline OLD_MINIPAGOSA] [--out perf/results/cloverleaf]

CloverLeaf3D_ref (github.com/UK-MAC/CloverLeaf3D_ref, Fortran + OpenMP/MPI) is fetched and
built outside this repository (make COMPILER=GNU, Debian's gfortran and Open MPI); nothing of it
is committed, the script takes its binary.

bm_short: CloverLeaf's own clover_bm_short.in (read from the directory of the binary, or
--clover-deck) at its 96^3 x 87 cycles, and minipagosa on the same problem
(perf/cloverleaf/bm_short.yaml). Sedov: the octant blast of configs/sedov.yaml written for both
codes with the same cells holding the same deposit (CloverLeaf's sphere state takes the cells
whose centre lies within the radius; minipagosa with numerics.samples=1 does the same), at each
mesh the L1 density error of each code's final field (CloverLeaf's own VTK dump) against the
exact solution (perf/cloverleaf/sedov_l1.cpp: tests/exact/norms.hpp, as perf/tradeoff.cpp).

Each run is one process tree under mpirun (ranks x threads: OMP_NUM_THREADS = threads; one rank
per core with --bind-to core when threads = 1, --bind-to none otherwise), timed by the wall clock
around the whole process (start-up, set-up, output included), beside each code's own loop time
(CloverLeaf's final "Wall clock", minipagosa's "cycles ... in X s"). Rounds interleave the two
codes, the first alternating; the 1-minute load average is recorded before every run. Timing
runs write no fields; Sedov's error comes from one extra run per code and mesh with a final dump.
Writes OUT.json (every run) and OUT.md (medians, spreads, ratios).
"""
import argparse
import glob
import json
import math
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(REPO, "tools"))

SEDOV_LENGTH = 1.2  # configs/sedov.yaml: the octant [0, 1.2]^3
SEDOV_RADIUS = 0.07  # the deposit sphere
SEDOV_DEPOSIT = 0.106384  # E / 8 of the octant (E = 0.851072, R = t^(2/5))
SEDOV_END = 0.41
SEDOV_P0 = 1.0e-6  # ambient pressure, rho0 = 1, gamma 1.4: e0 = p0 / 0.4


def fail(msg):
    sys.exit(f"side_by_side.py: {msg}")


def loadavg():
    return round(os.getloadavg()[0], 2)


def launch(argv, ranks, threads, bind, cwd, log):
    env = dict(os.environ, OMP_NUM_THREADS=str(threads), OMPI_ALLOW_RUN_AS_ROOT="1",
               OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    for k in ("OMP_PROC_BIND", "OMP_PLACES"):
        env.pop(k, None)
    if bind == "spread":
        env.update(OMP_PROC_BIND="spread", OMP_PLACES="threads")
    cmd = ["mpirun", "-np", str(ranks), "--bind-to", "core" if threads == 1 else "none"] + argv
    load = loadavg()
    t0 = time.perf_counter()
    with open(log, "w") as out:
        p = subprocess.run(cmd, cwd=cwd, env=env, stdout=out, stderr=subprocess.STDOUT)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        fail(f"{' '.join(cmd)} failed (exit {p.returncode}); its output: {log}")
    return wall, load


# ---------------------------------------------------------------- CloverLeaf
def clover_deck(text, cells=None, extra=()):
    """CloverLeaf's deck with x/y/z_cells replaced and extra 'key=value' lines added."""
    if cells is not None:
        text = re.sub(r"([xyz]_cells)\s*=\s*\d+", lambda m: f"{m.group(1)}={cells}", text)
    lines = text.rstrip().splitlines()
    end = [i for i, l in enumerate(lines) if l.strip() == "*endclover"]
    if not end:
        fail("CloverLeaf deck has no *endclover line")
    return "\n".join(lines[:end[0]] + [f" {e}" for e in extra] + lines[end[0]:]) + "\n"


def sedov_clover_deck(n):
    """The Sedov octant for CloverLeaf: the hot cells are those whose centre is within the
    radius (generate_chunk_kernel.f90, g_sphe), each given deposit / (cells' volume)."""
    h = SEDOV_LENGTH / n
    hot = sum(1 for i in range(n) for j in range(n) for k in range(n)
              if math.sqrt(((i + .5) * h)**2 + ((j + .5) * h)**2 + ((k + .5) * h)**2) <= SEDOV_RADIUS)
    e_hot = SEDOV_DEPOSIT / (hot * h**3)
    e0 = SEDOV_P0 / 0.4
    return (f"*clover\n state 1 density=1.0 energy={e0:.10f}\n"
            f" state 2 density=1.0 energy={e_hot:.10f} geometry=sphere xmin=0.0 ymin=0.0 zmin=0.0"
            f" radius={SEDOV_RADIUS}\n"
            f" x_cells={n}\n y_cells={n}\n z_cells={n}\n xmin=0.0\n ymin=0.0\n zmin=0.0\n"
            f" xmax={SEDOV_LENGTH}\n ymax={SEDOV_LENGTH}\n zmax={SEDOV_LENGTH}\n"
            f" initial_timestep=1.0e-6\n timestep_rise=1.1\n end_time={SEDOV_END}\n"
            f" end_step=100000000\n summary_frequency=100000000\n*endclover\n")


def clover_parse(out_path):
    text = open(out_path).read()
    steps = [(int(m.group(1)), float(m.group(2)), float(m.group(3))) for m in re.finditer(
        r"Step\s+(\d+)\s+time\s+(\S+)\s+control\s+\S+\s+timestep\s+(\S+)", text)]
    clocks = [float(x) for x in re.findall(r"Wall clock\s+(\S+)", text)]
    summaries = re.findall(r"step:\s+(\d+)\s+((?:\S+\s+){6}\S+)", text)
    if not steps or not clocks:
        fail(f"{out_path}: no steps or no 'Wall clock' (did CloverLeaf finish?)")
    first = [float(x) for x in summaries[0][1].split()] if summaries else None
    last_step, t, dt = steps[-1]
    # one "Wall clock" after each step (the hydro loop's own clock), then the final one
    return {"cycles": last_step, "time": t + dt, "own_seconds": clocks[-1],
            "own_per_cycle": [b - a for a, b in zip([0.0] + clocks[:last_step - 1],
                                                      clocks[:last_step])],
            "mass0": first[1] if first else None, "internal_energy0": first[4] if first else None}


def clover_density(workdir, n):
    """The final VTK dump's density on the global n^3 octant (x fastest), chunks placed by
    their coordinates."""
    import numpy as np
    files = sorted(glob.glob(os.path.join(workdir, "clover.*.vtk")))
    if not files:
        fail(f"{workdir}: CloverLeaf wrote no VTK dump")
    last_step = max(int(f.split(".")[-2]) for f in files)
    rho = np.full((n, n, n), np.nan)  # [k, j, i]
    h = SEDOV_LENGTH / n
    for f in files:
        if int(f.split(".")[-2]) != last_step:
            continue
        tok = open(f).read().split()
        dims = [int(x) for x in tok[tok.index("DIMENSIONS") + 1:tok.index("DIMENSIONS") + 4]]
        lo = []
        for ax in "XYZ":
            at = tok.index(f"{ax}_COORDINATES")
            lo.append(float(tok[at + 3]))
        nc = [d - 1 for d in dims]
        at = tok.index("density") + 4
        vals = np.array([float(x) for x in tok[at:at + nc[0] * nc[1] * nc[2]]])
        o = [int(round(x / h)) for x in lo]
        rho[o[2]:o[2] + nc[2], o[1]:o[1] + nc[1], o[0]:o[0] + nc[0]] = vals.reshape(nc[2], nc[1], nc[0])
    if np.isnan(rho).any():
        fail(f"{workdir}: the VTK chunks do not cover the {n}^3 mesh")
    return rho


# ---------------------------------------------------------------- minipagosa
def mp_parse(log_path, out_dir):
    text = open(log_path).read()
    m = re.search(r"(?:stopped|done) \(([^)]*)\): (\d+) cycles to t = (\S+) of \S+ in (\S+) s", text)
    if not m:
        fail(f"{log_path}: no 'stopped/done (...): N cycles ... in X s' line")
    with open(os.path.join(out_dir, "summary.json")) as f:
        summary = json.load(f)
    logged = [(int(a), float(b)) for a, b in re.findall(r"cycle\s+(\d+)\s+t .*? wall\s+(\S+) s", text)]
    per = []
    prev = (0, 0.0)
    for c, w in logged:  # mean seconds per cycle between log lines
        per += [(w - prev[1]) / (c - prev[0])] * (c - prev[0])
        prev = (c, w)
    return {"cycles": int(m.group(2)), "time": summary["time"], "own_seconds": float(m.group(4)),
            "own_per_cycle": per, "mass0": summary["start"]["mass"],
            "internal_energy0": summary["start"]["internal_energy"], "status": m.group(1)}


# ---------------------------------------------------------------- runs
def run_clover(a, deck_text, ranks, threads, tag, keep=False):
    wd = tempfile.mkdtemp(prefix=f"clover_{tag}_", dir=a.scratch)
    with open(os.path.join(wd, "clover.in"), "w") as f:
        f.write(deck_text)
    wall, load = launch([a.clover], ranks, threads, a.bind, wd, os.path.join(wd, "stdout.log"))
    r = clover_parse(os.path.join(wd, "clover.out"))
    r.update(code="cloverleaf", wall_seconds=wall, load1_before=load, load1_after=loadavg())
    if not keep:
        shutil.rmtree(wd)
    return r, wd


def run_mp(a, deck, sets, ranks, threads, tag, keep=False, exe=None, code="minipagosa"):
    wd = tempfile.mkdtemp(prefix=f"mp_{tag}_", dir=a.scratch)
    argv = [exe or a.minipagosa, deck, "-o", os.path.join(wd, "out")]
    for s in sets:
        argv += ["--set", s]
    log = os.path.join(wd, "stdout.log")
    wall, load = launch(argv, ranks, threads, a.bind, wd, log)
    r = mp_parse(log, os.path.join(wd, "out"))
    r.update(code=code, wall_seconds=wall, load1_before=load, load1_after=loadavg())
    if not keep:
        shutil.rmtree(wd)
    return r, wd


def med(xs):
    return statistics.median(xs) if xs else float("nan")


def spread(xs):
    return (min(xs), max(xs)) if xs else (float("nan"), float("nan"))


def bm_short(a, cfg):
    clover_text = open(a.clover_deck).read()
    deck = os.path.join(REPO, "perf/cloverleaf/bm_short.yaml")
    cells = a.cells
    clover_text = clover_deck(clover_text, cells if cells != 96 else None)
    sets = [] if cells == 96 else [f"mesh.cells=[{cells},{cells},{cells}]"]
    runs = []
    for rnd in range(a.rounds):
        for ci, (ranks, threads) in enumerate(cfg):
            order = ["cloverleaf", "minipagosa"] + (["minipagosa_baseline"] if a.baseline else [])
            shift = (rnd + ci) % len(order)  # each code first in turn
            order = order[shift:] + order[:shift]
            for code in order:
                if code == "cloverleaf":
                    r, _ = run_clover(a, clover_text, ranks, threads, "bm")
                elif code == "minipagosa":
                    r, _ = run_mp(a, deck, sets, ranks, threads, "bm")
                else:
                    r, _ = run_mp(a, deck, sets, ranks, threads, "bm", exe=a.baseline, code=code)
                r.update(round=rnd, ranks=ranks, threads=threads, cells=cells**3)
                r["cell_cycles_per_second"] = cells**3 * r["cycles"] / r["wall_seconds"]
                r["own_cell_cycles_per_second"] = cells**3 * r["cycles"] / r["own_seconds"]
                print(f"bm_short {ranks}x{threads} round {rnd} {code:10s}: wall {r['wall_seconds']:.2f} s,"
                      f" own {r['own_seconds']:.2f} s, {r['cycles']} cycles to t = {r['time']:.4g},"
                      f" load {r['load1_before']}", flush=True)
                runs.append(r)
    return runs


def sedov(a, cfg):
    import numpy as np
    deck = os.path.join(REPO, "configs/sedov.yaml")
    runs, errors = [], []
    for n in a.sedov_meshes:
        sets = [f"mesh.cells=[{n},{n},{n}]", "numerics.samples=1"] + a.mp_set
        clover_text = sedov_clover_deck(n)
        for ranks, threads in cfg:
            # the accuracy runs: one per code with its final field
            rc, wd = run_clover(a, clover_deck(clover_text, None, ["visit_frequency=100000000"]),
                                ranks, threads, f"sedov{n}", keep=True)
            rho = clover_density(wd, n)
            shutil.rmtree(wd)
            rm, wd = run_mp(a, deck, sets + ["output.interval=0"], ranks, threads, f"sedov{n}",
                            keep=True)
            from dumps import list_dumps
            import h5py
            t_last, _, path = list_dumps("side_by_side.py", os.path.join(wd, "out"))[-1]
            with h5py.File(path, "r") as f:
                rho_mp = np.array(f["density"])
            shutil.rmtree(wd)
            for code, r, field in (("cloverleaf", rc, rho), ("minipagosa", rm, rho_mp)):
                raw = os.path.join(a.scratch, f"rho_{code}_{n}.bin")
                np.ascontiguousarray(field, dtype=np.float64).tofile(raw)
                out = subprocess.run([a.sedov_l1, "--cells", str(n), "--length", str(SEDOV_LENGTH),
                                      "--time", repr(r["time"]), "--density", raw],
                                     capture_output=True, text=True, check=True).stdout
                os.remove(raw)
                e = json.loads(out)
                errors.append({"code": code, "cells_per_axis": n, "ranks": ranks, "threads": threads,
                               "time": r["time"], "cycles": r["cycles"], "l1": e["l1"],
                               "mass0": r["mass0"], "internal_energy0": r["internal_energy0"]})
                print(f"sedov {n}^3 {ranks}x{threads} {code:10s}: L1 {e['l1']:.5g} at t = {r['time']:.5g},"
                      f" {r['cycles']} cycles", flush=True)
            for rnd in range(a.sedov_rounds):
                order = ["cloverleaf", "minipagosa"]
                if rnd % 2:
                    order.reverse()
                for code in order:
                    if code == "cloverleaf":
                        r, _ = run_clover(a, clover_text, ranks, threads, f"sedov{n}")
                    else:
                        r, _ = run_mp(a, deck, sets + ["output.write=false"], ranks, threads,
                                      f"sedov{n}")
                    r.update(round=rnd, ranks=ranks, threads=threads, cells_per_axis=n)
                    r.pop("own_per_cycle")
                    print(f"sedov {n}^3 {ranks}x{threads} round {rnd} {code:10s}: wall "
                          f"{r['wall_seconds']:.2f} s, own {r['own_seconds']:.2f} s, load {r['load1_before']}",
                          flush=True)
                    runs.append(r)
    return runs, errors


def interp_time(points, err):
    """(wall time at error err on a code's (error, time) points, log-log between neighbours,
    "="), or where err is above all its errors (its coarsest mesh is more accurate already) the
    least time of a point at or below err, "<=" (an upper bound); (None, "") below them all."""
    pts = sorted(points)
    if pts and err > pts[-1][0]:
        return min(t for e, t in pts if e <= err), "<="
    for (e0, t0), (e1, t1) in zip(pts, pts[1:]):
        if e0 <= err <= e1:
            if e1 == e0:
                return t0
            w = math.log(err / e0) / math.log(e1 / e0)
            return math.exp(math.log(t0) + w * (math.log(t1) - math.log(t0))), "="
    return None, ""


def report(a, cfg, scfg, bm, sed, errs):
    md = [f"# minipagosa beside CloverLeaf3D_ref\n",
          f"Written by `perf/cloverleaf/side_by_side.py` ({time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}),"
          f" {platform.node()}, {os.cpu_count()} cores;"
          f"{f' {a.rounds} interleaved rounds (bm_short);' if bm else ''}"
          f"{f' {a.sedov_rounds} (Sedov);' if sed else ''} OpenMP binding: {a.bind}. Load: the 1-minute load average"
          f" before each run (a quiet 2-core machine reads below 1 with one 2-thread run going). {a.note}\n"]
    out = {"machine": {"host": platform.node(), "cores": os.cpu_count(), "bind": a.bind,
                       "note": a.note}, "clover_binary": a.clover, "minipagosa": a.minipagosa,
           "rounds": a.rounds, "bm_short": {"runs": bm, "summary": []},
           "sedov": {"runs": sed, "errors": errs, "summary": []}}
    if bm:
        md.append(f"## bm_short, {a.cells}^3\n\nCell-cycles per second: wall = the whole process"
                  " under one clock; own = each code's reported loop time. Ratio = minipagosa /"
                  " CloverLeaf per round (>1: minipagosa faster); median [min, max] over rounds."
                  " Time to solution: simulated time reached per wall second, ratio the same way.\n")
        md.append("| ranks x threads | code | cycles | t reached | wall s median [min, max] | own s"
                  " median | own ms/cycle first 10 / last 10 | Mcell-cycles/s (wall) | load median"
                  " [min, max] |\n|---|---|---|---|---|---|---|---|---|")
        ratios = []
        for ranks, threads in cfg:
            codes = ("cloverleaf", "minipagosa") + (("minipagosa_baseline",) if a.baseline else ())
            sel = {c: [r for r in bm if r["ranks"] == ranks and r["threads"] == threads and r["code"] == c]
                   for c in codes}
            for c, rs in sel.items():
                w = [r["wall_seconds"] for r in rs]
                loads = [r["load1_before"] for r in rs]
                per = rs[0]["own_per_cycle"]
                first = med([med([r["own_per_cycle"][i] for r in rs]) for i in range(min(10, len(per)))])
                last = med([med([r["own_per_cycle"][i] for r in rs]) for i in range(max(0, len(per) - 10), len(per))])
                md.append(f"| {ranks}x{threads} | {c} | {rs[0]['cycles']} | {rs[0]['time']:.4g} |"
                          f" {med(w):.2f} [{min(w):.2f}, {max(w):.2f}] | {med([r['own_seconds'] for r in rs]):.2f} |"
                          f" {first*1e3:.0f} / {last*1e3:.0f} | {med([r['cell_cycles_per_second'] for r in rs])/1e6:.2f} |"
                          f" {med(loads):.2f} [{min(loads):.2f}, {max(loads):.2f}] |")
            per_round = []
            for rnd in range(a.rounds):
                c = [r for r in sel["cloverleaf"] if r["round"] == rnd][0]
                m = [r for r in sel["minipagosa"] if r["round"] == rnd][0]
                per_round.append({
                    "round": rnd,
                    "wall": m["cell_cycles_per_second"] / c["cell_cycles_per_second"],
                    "own": m["own_cell_cycles_per_second"] / c["own_cell_cycles_per_second"],
                    "time_to_solution": (m["time"] / m["wall_seconds"]) / (c["time"] / c["wall_seconds"])})
                if a.baseline:
                    b = [r for r in sel["minipagosa_baseline"] if r["round"] == rnd][0]
                    per_round[-1]["baseline_wall"] = b["cell_cycles_per_second"] / c["cell_cycles_per_second"]
                    per_round[-1]["new_over_baseline_wall"] = m["cell_cycles_per_second"] / b["cell_cycles_per_second"]
                    per_round[-1]["new_over_baseline_own"] = (m["own_cell_cycles_per_second"]
                                                              / b["own_cell_cycles_per_second"])
            s = {"ranks": ranks, "threads": threads}
            keys = ["wall", "own", "time_to_solution"]
            if a.baseline:
                keys += ["baseline_wall", "new_over_baseline_wall", "new_over_baseline_own"]
            for k in keys:
                xs = [p[k] for p in per_round]
                s[k] = {"median": med(xs), "min": min(xs), "max": max(xs), "rounds": xs}
            out["bm_short"]["summary"].append(s)
            ratios.append(s)
        md.append("\n| ranks x threads | cell-cycles/s ratio, wall | ratio, own loop time | time-to-solution"
                  " ratio (t per wall s) |\n|---|---|---|---|")
        for s in ratios:
            f = lambda k: f"**{s[k]['median']:.2f}** [{s[k]['min']:.2f}, {s[k]['max']:.2f}]"
            md.append(f"| {s['ranks']}x{s['threads']} | {f('wall')} | {f('own')} | {f('time_to_solution')} |")
        if a.baseline:
            md.append(f"\nBaseline build ({a.baseline}) in the same rounds: its ratio to CloverLeaf, and"
                      " the new build's speed over it (cell-cycles/s, per round).\n\n| ranks x threads |"
                      " baseline / CloverLeaf, wall | new / baseline, wall | new / baseline, own |\n|---|---|---|---|")
            for s in ratios:
                f = lambda k: f"**{s[k]['median']:.2f}** [{s[k]['min']:.2f}, {s[k]['max']:.2f}]"
                md.append(f"| {s['ranks']}x{s['threads']} | {f('baseline_wall')} | {f('new_over_baseline_wall')} |"
                          f" {f('new_over_baseline_own')} |")
        m0 = [r["mass0"] for r in bm if r["code"] == "minipagosa"][:1]
        c0 = [r["mass0"] for r in bm if r["code"] == "cloverleaf"][:1]
        if m0 and c0:
            md.append(f"\nSame problem: initial mass minipagosa {m0[0]:.8g}, CloverLeaf {c0[0]:.8g}.")
    if sed:
        md.append("\n## Sedov octant: L1(rho) against the exact solution, and wall time\n\n"
                  "The same cells hold the same deposit in both codes (initial internal energy in"
                  " the table). Wall: whole process, median [min, max] over rounds, no field output;"
                  " the error is from one further run per code and mesh with a final dump. CloverLeaf"
                  " runs until its time passes the end (t below); minipagosa stops at it; each error"
                  " is against the exact solution at that code's own final time. CloverLeaf: its"
                  " default safety factors, first step 1e-6 and growth 1.1 as configs/sedov.yaml;"
                  f" minipagosa: configs/sedov.yaml (cfl 0.4){' with ' + ' '.join(a.mp_set) if a.mp_set else ''}.\n")
        md.append("| mesh | ranks x threads | code | cycles | t | initial IE | L1(rho) | wall s median [min, max] | load median |\n|---|---|---|---|---|---|---|---|---|")
        pts = {}
        for e in errs:
            rs = [r for r in sed if r["code"] == e["code"] and r["cells_per_axis"] == e["cells_per_axis"]
                  and r["ranks"] == e["ranks"] and r["threads"] == e["threads"]]
            w = [r["wall_seconds"] for r in rs]
            e["wall_median"] = med(w)
            e["wall_min"], e["wall_max"] = spread(w)
            key = (e["code"], e["ranks"], e["threads"])
            pts.setdefault(key, []).append((e["l1"], med(w)))
            md.append(f"| {e['cells_per_axis']}^3 | {e['ranks']}x{e['threads']} | {e['code']} | {e['cycles']} |"
                      f" {e['time']:.4g} | {e['internal_energy0']:.6g} | {e['l1']:.5g} | {med(w):.2f}"
                      f" [{min(w):.2f}, {max(w):.2f}] | {med([r['load1_before'] for r in rs]):.2f} |")
        md.append("\nTime to CloverLeaf's error at each of its meshes: minipagosa's wall time at that"
                  " error, log-log between its own meshes; '<=' where minipagosa's coarsest mesh is"
                  " already more accurate (its time then bounds the time to that error from above);"
                  " blank: below minipagosa's errors.\n\n"
                  "| ranks x threads | CloverLeaf mesh | L1 | CloverLeaf s | minipagosa s | ratio |\n|---|---|---|---|---|---|")
        for ranks, threads in scfg:
            cl = pts.get(("cloverleaf", ranks, threads), [])
            mp = pts.get(("minipagosa", ranks, threads), [])
            for e in [x for x in errs if x["code"] == "cloverleaf" and x["ranks"] == ranks and x["threads"] == threads]:
                t, how = interp_time(mp, e["l1"])
                row = {"ranks": ranks, "threads": threads, "clover_cells_per_axis": e["cells_per_axis"],
                       "l1": e["l1"], "clover_seconds": e["wall_median"], "minipagosa_seconds": t,
                       "ratio": t / e["wall_median"] if t else None, "ratio_is": how}
                out["sedov"]["summary"].append(row)
                ts = "" if t is None else f"{'<= ' if how == '<=' else ''}{t:.2f}"
                rs = "" if t is None else f"**{'<= ' if how == '<=' else ''}{row['ratio']:.2f}**"
                md.append(f"| {ranks}x{threads} | {e['cells_per_axis']}^3 | {e['l1']:.4g} |"
                          f" {e['wall_median']:.2f} | {ts} | {rs} |")
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    with open(a.out + ".json", "w") as f:
        json.dump(out, f, indent=1)
    with open(a.out + ".md", "w") as f:
        f.write("\n".join(md) + "\n")
    print(f"wrote {a.out}.json and {a.out}.md")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--clover", required=True, help="CloverLeaf3D_ref's clover_leaf binary")
    p.add_argument("--clover-deck", help="its clover_bm_short.in (default: beside the binary)")
    p.add_argument("--minipagosa", default=os.path.join(REPO, "build/minipagosa"))
    p.add_argument("--baseline", help="another minipagosa build, run in the same bm_short rounds")
    p.add_argument("--sedov-l1", default=None, help="sedov_l1 (default: beside minipagosa, perf/)")
    p.add_argument("--rounds", type=int, default=5, help="interleaved rounds of bm_short")
    p.add_argument("--sedov-rounds", type=int, default=3, help="timed rounds per Sedov mesh")
    p.add_argument("--configs", default="1x2,2x1", help="ranks x threads, comma separated")
    p.add_argument("--sedov-configs", default="1x2", help="ranks x threads of the Sedov runs")
    p.add_argument("--cells", type=int, default=96, help="bm_short cells per axis")
    p.add_argument("--sedov-meshes", default="16,24,32,48,64",
                   help="octant meshes (>= 16: the deposit sphere must hold a cell centre)")
    p.add_argument("--mp-set", action="append", default=[], help="extra --set for minipagosa's Sedov")
    p.add_argument("--bind", choices=["none", "spread"], default="none",
                   help="OpenMP threads unbound, or OMP_PROC_BIND=spread OMP_PLACES=threads")
    p.add_argument("--skip-bm", action="store_true")
    p.add_argument("--skip-sedov", action="store_true")
    p.add_argument("--note", default="", help="a line for the report (e.g. 'machine shared')")
    p.add_argument("--out", default=os.path.join(REPO, "perf/results/cloverleaf"))
    a = p.parse_args()
    a.clover = os.path.abspath(a.clover)
    a.minipagosa = os.path.abspath(a.minipagosa)
    if a.baseline:
        a.baseline = os.path.abspath(a.baseline)
    if a.clover_deck is None:
        a.clover_deck = os.path.join(os.path.dirname(a.clover), "clover_bm_short.in")
    if a.sedov_l1 is None:
        a.sedov_l1 = os.path.join(os.path.dirname(a.minipagosa), "perf", "sedov_l1")
    for what, path in (("--clover", a.clover), ("--minipagosa", a.minipagosa),
                       ("--clover-deck", a.clover_deck)) + ((("--sedov-l1", a.sedov_l1),) if not a.skip_sedov else ()):
        if not os.path.isfile(path):
            fail(f"{what}: {path} does not exist")
    parse_cfg = lambda s: [tuple(int(x) for x in c.split("x")) for c in s.split(",") if c]
    cfg, scfg = parse_cfg(a.configs), parse_cfg(a.sedov_configs)
    a.sedov_meshes = [int(x) for x in a.sedov_meshes.split(",") if x]
    a.scratch = tempfile.mkdtemp(prefix="side_by_side_")
    try:
        bm = [] if a.skip_bm else bm_short(a, cfg)
        sed, errs = ([], []) if a.skip_sedov else sedov(a, scfg)
        report(a, cfg, scfg, bm, sed, errs)
    finally:
        shutil.rmtree(a.scratch, ignore_errors=True)


if __name__ == "__main__":
    main()
