"""Reading minipagosa HDF5 dumps: the run's dumps by time, fields with clear errors, plane cuts.

A dump (<scene>_<cycle>.h5) holds cell fields shaped (nz, ny, nx), node fields (velocity_*)
shaped (nz+1, ny+1, nx+1), one fraction_<material> per material, and the attributes cells,
origin, spacing, time, cycle (as tools/plot_slice.py reads them).
"""
import glob
import json
import os
import sys

import h5py
import numpy as np

AXES = "xyz"


def fail(tool, message):
    sys.exit(f"{tool}: {message}")


def list_dumps(tool, source):
    """Sorted [(time, cycle, path)] of the dumps in a run's output directory (or of given files)."""
    paths = source if isinstance(source, list) else None
    if paths is None:
        if not os.path.isdir(source):
            fail(tool, f"{source} is not a directory of dumps")
        paths = [p for p in glob.glob(os.path.join(source, "*.h5")) if "checkpoint" not in p]
    dumps = []
    for p in paths:
        try:
            with h5py.File(p, "r") as f:
                if "time" not in f.attrs or "cells" not in f.attrs:
                    continue
                dumps.append((float(f.attrs["time"]), int(f.attrs["cycle"]), p))
        except OSError as e:
            fail(tool, f"cannot read {p}: {e}")
    if not dumps:
        fail(tool, f"no minipagosa dumps in {source}")
    return sorted(dumps)


def pick_times(tool, dumps, times, tol):
    """The dump at each requested time (within tol); an error lists the times there are."""
    out = []
    for t in times:
        best = min(dumps, key=lambda d: abs(d[0] - t))
        if abs(best[0] - t) > tol * max(1.0, abs(t)):
            have = ", ".join(f"{d[0]:.6g}" for d in dumps)
            fail(tool, f"no dump at t = {t:g} (within {tol:g}); the dumps are at t = {have}")
        out.append(best)
    return out


class Dump:
    """One dump file: attributes, field names, and fields read on demand."""

    def __init__(self, tool, path):
        self.tool, self.path = tool, path
        with h5py.File(path, "r") as f:
            self.names = sorted(k for k in f.keys() if isinstance(f[k], h5py.Dataset))
            self.cells = np.asarray(f.attrs["cells"]).astype(int)
            self.origin = np.asarray(f.attrs["origin"], dtype=float)
            self.spacing = np.asarray(f.attrs["spacing"], dtype=float)
            self.time = float(f.attrs["time"])
            self.cycle = int(f.attrs["cycle"])
        self.materials = [n[len("fraction_"):] for n in self.names if n.startswith("fraction_")]

    def field(self, name):
        if name not in self.names:
            fail(self.tool, f"{self.path} has no field '{name}'; it has: " + ", ".join(self.names))
        with h5py.File(self.path, "r") as f:
            return np.asarray(f[name])

    def fraction(self, material):
        if material not in self.materials:
            fail(self.tool, f"{self.path} has no material '{material}'; it has: "
                 + ", ".join(self.materials))
        return self.field("fraction_" + material)

    def centres(self, axis):
        """Cell-centre coordinates along axis 0/1/2 (x/y/z)."""
        return self.origin[axis] + (np.arange(self.cells[axis]) + 0.5) * self.spacing[axis]

    def edges(self, axis):
        return self.origin[axis] + np.arange(self.cells[axis] + 1) * self.spacing[axis]

    def plane_index(self, axis, value):
        """Index of the cell layer normal to `axis` whose centres lie nearest `value`."""
        lo = self.origin[axis]
        hi = lo + self.cells[axis] * self.spacing[axis]
        if not lo <= value <= hi:
            fail(self.tool, f"the plane {AXES[axis]} = {value:g} is outside the mesh "
                 f"[{lo:g}, {hi:g}]")
        return int(min(self.cells[axis] - 1, max(0, np.floor((value - lo) / self.spacing[axis]))))

    def cut(self, array, axis, index):
        """The 2-D cut of a cell array (z, y, x) normal to `axis`, as (rows, cols) = the two
        remaining axes in order (x-normal: (z, y); y-normal: (z, x); z-normal: (y, x))."""
        return np.take(array, index, axis=2 - axis)


def parse_plane(tool, text):
    """'y=0' -> (1, 0.0)."""
    try:
        name, value = text.split("=")
        axis = AXES.index(name.strip().lower())
        return axis, float(value)
    except ValueError:
        fail(tool, f"--plane '{text}': expected x=VALUE, y=VALUE or z=VALUE")


def node_to_cells(u):
    """A node field (nz+1, ny+1, nx+1) at the cell centres: the mean of each cell's 8 nodes."""
    return 0.125 * (u[:-1, :-1, :-1] + u[1:, :-1, :-1] + u[:-1, 1:, :-1] + u[:-1, :-1, 1:] +
                    u[1:, 1:, :-1] + u[1:, :-1, 1:] + u[:-1, 1:, 1:] + u[1:, 1:, 1:])


def write_report(prefix, data, text):
    """PREFIX.json (data) and PREFIX.md (text), making PREFIX's directory; returns the paths."""
    os.makedirs(os.path.dirname(prefix) or ".", exist_ok=True)
    with open(prefix + ".json", "w") as f:
        json.dump(data, f, indent=1)
    with open(prefix + ".md", "w") as f:
        f.write(text)
    return [prefix + ".json", prefix + ".md"]


def cell_ux(d):
    """A dump's x velocity at the cell centres, shaped (z, y, x)."""
    return node_to_cells(d.field("velocity_x"))
