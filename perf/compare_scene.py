#!/usr/bin/env python3
"""Old vs new minipagosa on one scene, side by side in one run: both binaries continue the same
checkpoint for the same number of cycles, alternating (old first in even repetitions, new first
in odd), so load from other processes hits both alike. Reports the loop time each run prints
("done|stopped (...): N cycles ... in X s"), the medians and their ratio, and checks that the
two binaries end with the same fields (every dataset of the last dump, bit for bit). Writes
NAME.json and NAME.md.

  compare_scene.py OLD NEW --deck DECK --checkpoint CKPT --cycles N [--reps 2] [--threads 2]
                   [--set key=value ...] [--old-commit SHA] [--new-commit SHA] [--note '...']
                   [--out perf/results] [--name scene_side_by_side]

The checkpoint's cycle plus N is passed as time.max_cycles; no checkpoints are written, and each
run's output goes to a temporary directory that is removed afterwards.
"""
import argparse
import glob
import json
import os
import re
import shutil
import statistics
import subprocess
import tempfile

import h5py
import numpy as np


def checkpoint_cycle(path):
    m = re.search(r"_(\d+)\.h5$", path)
    if not m:
        raise SystemExit(f"compare_scene: cannot read the cycle from the name {path}")
    return int(m.group(1))


def run(binary, args, outdir):
    os.makedirs(outdir)
    env = dict(os.environ, OMP_PROC_BIND="false")
    p = subprocess.run([binary] + args + ["-q", "-o", outdir], capture_output=True, text=True,
                       env=env)
    if p.returncode != 0:
        raise SystemExit(f"compare_scene: {binary} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    m = re.search(r"^(?:done|stopped) .*?: (\d+) cycles .* in ([0-9.eE+-]+) s", p.stdout, re.M)
    if not m:
        raise SystemExit(f"compare_scene: no 'done' or 'stopped' line from {binary}")
    return int(m.group(1)), float(m.group(2))


def last_dump(outdir):
    dumps = sorted(f for f in glob.glob(os.path.join(outdir, "*_[0-9]*.h5"))
                   if "checkpoint" not in os.path.basename(f))
    return dumps[-1] if dumps else None


def differing(a_path, b_path):
    out = []
    with h5py.File(a_path) as a, h5py.File(b_path) as b:
        def walk(ga, gb, prefix):
            for k in ga:
                if isinstance(ga[k], h5py.Group):
                    walk(ga[k], gb[k], prefix + k + "/")
                elif k not in gb or not np.array_equal(ga[k][()], gb[k][()], equal_nan=True):
                    out.append(prefix + k)
        walk(a, b, "")
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--deck", required=True)
    ap.add_argument("--checkpoint", required=True)
    ap.add_argument("--cycles", type=int, required=True)
    ap.add_argument("--reps", type=int, default=2)
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--set", action="append", default=[])
    ap.add_argument("--old-commit", default="old")
    ap.add_argument("--new-commit", default="new")
    ap.add_argument("--note", default="")
    ap.add_argument("--out", default="perf/results")
    ap.add_argument("--name", default="scene_side_by_side")
    a = ap.parse_args()

    cycle0 = checkpoint_cycle(a.checkpoint)
    tmp = tempfile.mkdtemp(prefix="compare_scene_")
    try:
        # the run's own output directory holds a link to the checkpoint (restart reads it there)
        args = [a.deck, f"--kokkos-threads={a.threads}"]
        for s in a.set:
            args += ["--set", s]
        args += ["--set", f"time.max_cycles={cycle0 + a.cycles}",
                 "--set", "output.checkpoint_every.seconds=0"]
        times = {"old": [], "new": []}
        ends = {}
        for r in range(a.reps):
            for which in (("old", "new") if r % 2 == 0 else ("new", "old")):
                d = os.path.join(tmp, f"{which}{r}")
                os.makedirs(d)
                link = os.path.join(d, os.path.basename(a.checkpoint))
                os.symlink(os.path.abspath(a.checkpoint), link)
                shutil.rmtree(d + "_o", ignore_errors=True)
                n, t = run(getattr(a, which), args + ["--restart", link], d + "_o")
                if n != cycle0 + a.cycles:
                    raise SystemExit(f"compare_scene: {which} ended at cycle {n}")
                times[which].append(t)
                ends[which] = last_dump(d + "_o")
                print(f"rep {r} {which}: {t:.2f} s", flush=True)
        diff = differing(ends["old"], ends["new"]) if ends["old"] and ends["new"] else None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)

    med = {k: statistics.median(v) for k, v in times.items()}
    res = {"deck": a.deck, "checkpoint": a.checkpoint, "cycle0": cycle0, "cycles": a.cycles,
           "threads": a.threads, "set": a.set, "old_commit": a.old_commit,
           "new_commit": a.new_commit, "note": a.note, "seconds": times,
           "median_seconds": med, "speedup_old_over_new": med["old"] / med["new"],
           "seconds_per_cycle": {k: v / a.cycles for k, v in med.items()},
           "last_dump_fields_differing": diff}
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, a.name + ".json"), "w") as f:
        json.dump(res, f, indent=1)
    lines = [f"# {a.name}: old vs new on one scene, side by side in one run", "",
             f"{a.deck} from {os.path.basename(a.checkpoint)} (cycle {cycle0}), {a.cycles} cycles, "
             f"{a.threads} OpenMP threads, {a.reps} alternating runs each; "
             f"--set {' '.join(a.set) if a.set else '(none)'}. old = {a.old_commit}, "
             f"new = {a.new_commit}. {a.note}", "",
             "| binary | loop seconds (runs) | median s | s per cycle |", "|---|---|---|---|"]
    for k in ("old", "new"):
        lines.append(f"| {k} | {', '.join(f'{t:.2f}' for t in times[k])} | {med[k]:.2f} | "
                     f"{med[k] / a.cycles:.3f} |")
    lines += ["", f"Speed-up old/new: **{res['speedup_old_over_new']:.3f}**.", "",
              "Last dump, old against new: " +
              ("every dataset bit for bit equal." if diff == [] else
               f"differing datasets: {diff}" if diff else "no dump to compare.")]
    with open(os.path.join(a.out, a.name + ".md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
