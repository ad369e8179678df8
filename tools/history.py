#!/usr/bin/python3
"""Plot a run's time history from its log (the cycle lines minipagosa prints every
output.log_every cycles): time step, what limited it, and wall time against simulated time.

    build/minipagosa configs/sedov.yaml | tee sedov.log
    /usr/bin/python3 tools/history.py sedov.log [-o sedov_history.png] [--json history.json]

A log with no cycle lines is an error saying so.
"""
import argparse
import json
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LINE = re.compile(r"^cycle\s+(\d+)\s+t\s+(\S+)\s+dt\s+(\S+)\s+\((\S+) at (-?\d+),(-?\d+),(-?\d+)\)"
                  r"\s+wall\s+(\S+) s")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("log")
    ap.add_argument("-o", "--output", default=None, help="PNG path (default: LOG_history.png)")
    ap.add_argument("--json", default=None, help="also write the parsed history as JSON")
    a = ap.parse_args()
    rows = []
    with open(a.log, errors="replace") as f:
        for line in f:
            m = LINE.match(line.strip())
            if m:
                rows.append({"cycle": int(m[1]), "t": float(m[2]), "dt": float(m[3]),
                             "limit": m[4], "cell": [int(m[5]), int(m[6]), int(m[7])],
                             "wall": float(m[8])})
    if not rows:
        sys.exit(f"history: {a.log} holds no cycle lines (was the run quiet, -q?)")
    t = [r["t"] for r in rows]
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(7, 5), sharex=True)
    for lim in sorted({r["limit"] for r in rows}):
        pts = [(r["t"], r["dt"]) for r in rows if r["limit"] == lim]
        ax1.semilogy([p[0] for p in pts], [p[1] for p in pts], ".", ms=4, label=lim)
    ax1.set_ylabel("dt")
    ax1.legend(title="limited by", fontsize=8)
    ax2.plot(t, [r["wall"] for r in rows], "-")
    ax2.set_ylabel("wall time (s)")
    ax2.set_xlabel("t")
    fig.tight_layout()
    out = a.output or a.log.rsplit(".", 1)[0] + "_history.png"
    fig.savefig(out, dpi=110)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(rows, f, indent=1)
    print(out)


if __name__ == "__main__":
    main()
