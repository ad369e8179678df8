#!/usr/bin/env python3
"""Every field of every shipped deck, bit for bit, between two minipagosa builds.

Runs each case (a deck from configs/ with its overrides, on 1 or 2 ranks) with the old and the
new executable and compares every dataset of every dump the two runs wrote (the first and the
last: output.interval=0), value for value (NaNs equal where both are NaN). A refactor that
claims "the arithmetic does not change" must show 0 differing values here.

  tools/compare_builds.py OLD_EXE NEW_EXE [--cases quick|full] [--only NAME,...] [--json FILE]

A dataset that differs is reported with the count of differing values, the largest |difference|
and the field's largest finite |value| (the scale to read the difference against).
Exit status 1 when any case differs or fails to run. The cases: every shipped deck a few cycles,
the multi-material ones in both layouts, 1 and 2 ranks; with --cases full the issue's set at
length (perforator 60 cycles; charge_3d, Taylor, Mader, Sedov, triple point further).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time

import h5py
import numpy as np
import yaml

HERE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))



def multi_material(deck):
    with open(os.path.join(HERE, "configs", deck + ".yaml")) as f:
        return len(yaml.safe_load(f)["materials"]) > 1


def cases(kind):
    """[(name, deck, overrides, ranks)]"""
    out = []
    decks = sorted(f[:-5] for f in os.listdir(os.path.join(HERE, "configs")) if f.endswith(".yaml"))
    cycles = {"quick": 12, "full": 40}[kind]
    small = {"noh": "mesh.cells=[24,24,24]", "sedov": "mesh.cells=[24,24,24]",
             "sphere_advection": "mesh.cells=[16,16,16]"}
    for d in decks:
        base = ["time.max_cycles=%d" % (60 if d == "perforator" else cycles)]
        if d in small and kind == "quick":
            base.append(small[d])
        layouts = [None]
        if multi_material(d):
            layouts = ["compact", "dense"]
        for lay in layouts:
            ov = base + (["numerics.layout=" + lay] if lay else [])
            for ranks in (1, 2):
                if d == "perforator" and ranks == 2 and kind == "quick":
                    continue
                name = "%s%s np%d" % (d, " " + lay if lay else "", ranks)
                out.append((name, d, ov, ranks))
    return out


def run(exe, deck, overrides, ranks, outdir):
    cmd = []
    if ranks > 1:
        cmd = ["mpirun", "--oversubscribe", "-np", str(ranks)]
    cmd += [exe, os.path.join(HERE, "configs", deck + ".yaml"), "--quiet", "--output", outdir]
    for o in overrides + ["output.interval=0", "output.write=true"]:
        cmd += ["--set", o]
    env = dict(os.environ, OMP_NUM_THREADS="1", OMP_PROC_BIND="false",
               OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    p = subprocess.run(cmd, env=env, capture_output=True, text=True)
    return p.returncode, p.stdout + p.stderr


def dumps(outdir):
    return sorted(f for f in os.listdir(outdir) if f.endswith(".h5") and "checkpoint" not in f)


def compare(a_dir, b_dir):
    """(values compared, values differing, [what differs])"""
    fa, fb = dumps(a_dir), dumps(b_dir)
    if fa != fb:
        return 0, 1, ["dump files differ: %s vs %s" % (fa, fb)]
    n = bad = 0
    what = []
    for f in fa:
        with h5py.File(os.path.join(a_dir, f), "r") as ha, h5py.File(os.path.join(b_dir, f), "r") as hb:
            ka, kb = sorted(ha.keys()), sorted(hb.keys())
            if ka != kb:
                what.append("%s: datasets %s vs %s" % (f, ka, kb))
                bad += 1
                continue
            for k in ka:
                x, y = ha[k][()], hb[k][()]
                n += x.size
                if x.shape != y.shape:
                    what.append("%s/%s: shape %s vs %s" % (f, k, x.shape, y.shape))
                    bad += x.size
                    continue
                same = (x == y) | (np.isnan(x) & np.isnan(y)) if x.dtype.kind == "f" else x == y
                d = int(np.size(same) - np.count_nonzero(same))
                if d:
                    size = ""
                    if x.dtype.kind == "f":
                        diff = np.abs(x.astype(np.float64) - y.astype(np.float64))[~same]
                        diff = diff[np.isfinite(diff)]
                        scale = np.abs(x[np.isfinite(x)]).max() if np.isfinite(x).any() else 0.0
                        if diff.size:
                            size = ", max |diff| %.3g (field's max |value| %.3g)" % (diff.max(), scale)
                    what.append("%s/%s: %d values differ%s" % (f, k, d, size))
                    bad += d
    return n, bad, what


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--cases", choices=["quick", "full"], default="quick")
    ap.add_argument("--only", default="", help="comma-separated deck names")
    ap.add_argument("--json", default="")
    a = ap.parse_args()
    only = set(x for x in a.only.split(",") if x)
    rows = []
    ok = True
    for name, deck, ov, ranks in cases(a.cases):
        if only and deck not in only:
            continue
        with tempfile.TemporaryDirectory() as tmp:
            od, nd = os.path.join(tmp, "old"), os.path.join(tmp, "new")
            t0 = time.time()
            ro, lo = run(a.old, deck, ov, ranks, od)
            rn, ln = run(a.new, deck, ov, ranks, nd)
            if ro != 0 or rn != 0:
                ok = False
                rows.append({"case": name, "error": "exit %d / %d" % (ro, rn),
                             "log": (lo if ro else ln)[-600:]})
                print("%-34s FAILED to run (exit %d / %d)\n%s" % (name, ro, rn, (lo if ro else ln)[-600:]))
                continue
            n, bad, what = compare(od, nd)
            ok = ok and bad == 0
            rows.append({"case": name, "values": n, "differ": bad, "what": what[:10],
                         "seconds": round(time.time() - t0, 1)})
            print("%-34s %12d values  %s" % (name, n, "identical" if bad == 0 else
                                             "%d DIFFER: %s" % (bad, "; ".join(what[:4]))), flush=True)
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"old": a.old, "new": a.new, "cases": rows, "identical": ok}, f, indent=1)
    print("all identical" if ok else "DIFFERENCES FOUND")
    sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
