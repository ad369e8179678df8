#!/usr/bin/python3
"""One entry for minipagosa's pictures and checks: a subcommand per tool, on a run's output
directory. The tools stay importable and runnable on their own (tools/<name>.py).

    python3 tools/plot.py lineout OUTPUT_DIR [FIELD...] [--exact sod|leblanc|test123|mader]
    python3 tools/plot.py slice   OUTPUT_DIR FIELD [--k K] [--line]
    python3 tools/plot.py history OUTPUT_DIR|LOG
    python3 tools/plot.py interfaces OUTPUT_DIR [--times 0 10 60] [--plane y=0] [--mode contour]
    python3 tools/plot.py tip     OUTPUT_DIR [--charges both|top|bottom]
    python3 tools/plot.py jet     OUTPUT_DIR [--axis-z 1.27]
    python3 tools/plot.py panels  OUT.png DUMP.h5 [DUMP.h5 ...] [--fields F,G] [--z Z] [--log F]

lineout, slice: the run's last dump, or the one chosen with --dump FILE|first|last|CYCLE or
--time T (the dump nearest T); the PNG goes to OUTPUT_DIR/<scene>_lineout.png and
OUTPUT_DIR/<scene>_<FIELD>.png unless -o PATH. history: a directory means its newest *.log (save
a run's log with `build/minipagosa DECK -o DIR | tee DIR/run.log`). interfaces: the materials on
a cut plane at given times (tools/render_interfaces.py). tip: the perforator's jets against the
carrier, casing and rock (tools/perforator_check.py: JSON and Markdown). jet: one charge's jet
tip and fast copper per dump (tools/jet_profile.py). panels: z-slices of several dumps, a row
per field, the interfaces drawn over them (tools/plot_panels.py). `python3 tools/plot.py SUBCOMMAND --help`
lists each tool's own options.
"""
import glob
import importlib
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:
    sys.path.insert(0, HERE)

import dumps  # noqa: E402  (tools/dumps.py)

TOOLS = {
    "lineout": "lineout",
    "slice": "plot_slice",
    "history": "history",
    "interfaces": "render_interfaces",
    "tip": "perforator_check",
    "jet": "jet_profile",
    "panels": "plot_panels",
}


def fail(message):
    sys.exit(f"plot.py: {message}")


def pick_dump(run_dir, args):
    """Takes --dump / --time out of args; returns (dump path, remaining args)."""
    which, time, rest = "last", None, []
    it = iter(args)
    for a in it:
        if a in ("--dump", "--time"):
            value = next(it, None)
            if value is None:
                fail(f"{a} needs a value")
            if a == "--dump":
                which = value
            else:
                time = float(value)
        elif a.startswith("--dump="):
            which = a.split("=", 1)[1]
        elif a.startswith("--time="):
            time = float(a.split("=", 1)[1])
        else:
            rest.append(a)
    if os.path.isfile(which):
        return which, rest
    found = [d for d in dumps.list_dumps("plot.py", run_dir) if "_checkpoint_" not in d[2]]
    if not found:
        fail(f"no dumps (<scene>_<cycle>.h5) in {run_dir}")
    if time is not None:
        return min(found, key=lambda d: abs(d[0] - time))[2], rest
    if which == "last":
        return found[-1][2], rest
    if which == "first":
        return found[0][2], rest
    for t, cycle, path in found:
        if str(cycle) == which or f"{int(cycle):06d}" == which:
            return path, rest
    fail(f"no dump of cycle {which} in {run_dir}; cycles: " +
         ", ".join(str(c) for _, c, _ in found))


def default_output(run_dir, dump, suffix, rest):
    if "-o" in rest or "--output" in rest or any(a.startswith("--output=") for a in rest):
        return rest
    scene = os.path.basename(dump).rsplit("_", 1)[0]
    return rest + ["-o", os.path.join(run_dir, f"{scene}_{suffix}.png")]


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0
    sub = argv[0]
    if sub not in TOOLS:
        fail(f"unknown subcommand '{sub}'; one of: {', '.join(TOOLS)}")
    args = argv[1:]
    if args and args[0] not in ("-h", "--help"):
        target, rest = args[0], args[1:]
        if sub in ("lineout", "slice"):
            if not os.path.isdir(target):
                fail(f"{sub}: {target} is not a run's output directory")
            dump, rest = pick_dump(target, rest)
            if sub == "lineout":
                rest = default_output(target, dump, "lineout", rest)
            else:
                field = next((a for a in rest if not a.startswith("-")), None)
                if field is None:
                    fail("slice: give a FIELD (e.g. density)")
                rest = default_output(target, dump, field, rest)
            args = [dump] + rest
        elif sub == "history" and os.path.isdir(target):
            logs = sorted(glob.glob(os.path.join(target, "*.log")), key=os.path.getmtime)
            if not logs:
                fail(f"history: no *.log in {target}; save the run's output there, e.g. "
                     f"build/minipagosa DECK -o {target} | tee {target}/run.log")
            args = [logs[-1]] + rest
    tool = importlib.import_module(TOOLS[sub])
    old = sys.argv
    sys.argv = [f"tools/plot.py {sub}"] + args
    try:
        return tool.main()
    finally:
        sys.argv = old


if __name__ == "__main__":
    sys.exit(main())
