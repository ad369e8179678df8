#!/usr/bin/env python3
"""Old vs new bench_hydro side by side in one run (issue #15): the two binaries alternate,
`--reps` times each, on the same machine state, so load from other processes hits both alike.
Writes perf/results/hydro.json (every run's JSON, old and new, and the medians) and
perf/results/hydro.md (the comparison, then the new binary's full report of its last run).

  compare_hydro.py OLD_BENCH NEW_BENCH --old-commit SHA --new-commit SHA [--sizes 64]
                   [--old-label TEXT] [--new-label TEXT]
                   [--cycles 10] [--reps 3] [--note '...'] [--out perf/results] [--name hydro]
"""
import argparse
import json
import os
import statistics
import subprocess
import tempfile


def run(binary, sizes, cycles, json_path):
    out = subprocess.run([binary, "--sizes", sizes, "--cycles", str(cycles), "--json", json_path],
                         capture_output=True, text=True, check=True).stdout
    with open(json_path) as f:
        return json.load(f), out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--old-commit", required=True)
    ap.add_argument("--new-commit", required=True)
    ap.add_argument("--sizes", default="64")
    ap.add_argument("--cycles", type=int, default=10)
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--note", default="")
    ap.add_argument("--old-label", default="main at the start of the perf branch",
                    help="what the old binary is, printed beside its commit")
    ap.add_argument("--new-label", default="", help="what the new binary is, if not the branch")
    ap.add_argument("--out", default="perf/results")
    ap.add_argument("--name", default="hydro", help="basename of the .md and .json written")
    a = ap.parse_args()
    res = {"old": [], "new": []}
    last_new = ""
    tmp = tempfile.mkdtemp()
    for r in range(a.reps):
        order = ("old", "new") if r % 2 == 0 else ("new", "old")  # alternate who goes first
        for which in order:
            js, out = run(getattr(a, which), a.sizes, a.cycles, os.path.join(tmp, f"{which}{r}.json"))
            res[which].append(js)
            if which == "new":
                last_new = out
    sizes = [int(s) for s in a.sizes.split(",")]
    md = ["# bench_hydro: old vs new, side by side in one run", ""]
    new_label = f" ({a.new_label})" if a.new_label else ""
    md.append(f"old = {a.old_commit} ({a.old_label}), new = {a.new_commit}{new_label}; "
              f"{a.reps} alternating runs each (old first in even runs, new first in odd), "
              f"{a.cycles} timed cycles per run; medians over runs. {a.note}")
    md.append("")
    md.append("| size | old ms/cycle (runs) | new ms/cycle (runs) | old median | new median | "
              "speed-up (old/new) | old launches/cycle | new launches/cycle | "
              "STREAM GB/s (runs, old; new) |")
    md.append("|---|---|---|---|---|---|---|---|---|")
    summary = {}
    for i, s in enumerate(sizes):
        t = {w: [js["runs"][i]["seconds_per_cycle"] * 1e3 for js in res[w]] for w in res}
        lc = {w: sum(k["calls_per_cycle"] for k in res[w][0]["runs"][i]["breakdown"]["kernels"].values())
              for w in res}
        st = {w: [js["stream_triad_GBs"] for js in res[w]] for w in res}
        med = {w: statistics.median(t[w]) for w in t}
        summary[str(s)] = {"old_ms_per_cycle_median": med["old"], "new_ms_per_cycle_median": med["new"],
                           "speedup": med["old"] / med["new"], "old_launches_per_cycle": lc["old"],
                           "new_launches_per_cycle": lc["new"]}
        md.append(f"| {s}^3 | {', '.join(f'{x:.1f}' for x in t['old'])} | "
                  f"{', '.join(f'{x:.1f}' for x in t['new'])} | {med['old']:.1f} | {med['new']:.1f} | "
                  f"{med['old'] / med['new']:.2f} | {lc['old']:g} | {lc['new']:g} | "
                  f"{', '.join(f'{x:.1f}' for x in st['old'])}; {', '.join(f'{x:.1f}' for x in st['new'])} |")
    md += ["", "## New binary, last run (its own report)", "", "```", last_new.strip(), "```", ""]
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, a.name + ".md"), "w") as f:
        f.write("\n".join(md))
    with open(os.path.join(a.out, a.name + ".json"), "w") as f:
        json.dump({"old_commit": a.old_commit, "new_commit": a.new_commit, "note": a.note,
                   "summary": summary, "runs": res}, f, indent=1)
    print("\n".join(md))


if __name__ == "__main__":
    main()
