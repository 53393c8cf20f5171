# SPDX-License-Identifier: MIT
"""Particles as tables: one frame of a LAMMPS dump read by the library's
reader (gf_snapshot_read: plain or .gz, any column order, radius, pass, the
same checks and messages as `granflow analyze`), and the structured arrays
that `pandas.DataFrame(...)` takes as they are."""
import ctypes
import math
import os

import numpy as np

from ._lib import c_void_p, check, enc, lib
from .errors import missing_file

# One row per particle; pandas.DataFrame(array) gives these columns.
SNAPSHOT_DTYPE = np.dtype([("id", np.int64), ("type", np.int32), ("pass", np.int32), ("x", np.float64),
                           ("y", np.float64), ("z", np.float64), ("radius", np.float64)])
PARTICLE_DTYPE = np.dtype([("id", np.int64), ("layer", np.int32), ("pass", np.int32), ("x", np.float64),
                           ("y", np.float64), ("z", np.float64), ("radius", np.float64)])


def _ptr(array, ctype):
    return array.ctypes.data_as(ctypes.POINTER(ctype))


def table(tag_name, ids, tags, passes, xyz, radius):
    """A structured array of PARTICLE_DTYPE (tag_name "layer") or SNAPSHOT_DTYPE ("type")."""
    out = np.empty(len(ids), PARTICLE_DTYPE if tag_name == "layer" else SNAPSHOT_DTYPE)
    out["id"], out[tag_name], out["pass"], out["radius"] = ids, tags, passes, radius
    out["x"], out["y"], out["z"] = xyz[:, 0], xyz[:, 1], xyz[:, 2]
    return out


class Snapshot(dict):
    """One frame of a dump. As a dict (what read_snapshot always returned):
    time (tau; None when the frame has no ITEM: TIME), step, box (3 x 2
    array of lo, hi, d; None without one), id (int64), type (int32; the
    layer tag in granflow's snapshots, 0 without a type column), xyz
    (n x 3, d), radius (d; 0.5 without a radius column), pass (int32; 1
    without a pass column). `particles` is the same as one structured array
    (SNAPSHOT_DTYPE: id, type, pass, x, y, z, radius), which
    `pandas.DataFrame(snap.particles)` takes as it is; `frames` is the
    number of frames in the file."""

    @property
    def particles(self):
        return table("type", self["id"], self["type"], self["pass"], self["xyz"], self["radius"])

    @property
    def time(self):
        return self["time"]

    def __repr__(self):
        return f"Snapshot(time={self['time']!r}, particles={len(self['id'])}, frames={self.frames})"


def read_snapshot(path, frame=-1):
    """Frame `frame` (0 = first, -1 = last) of the LAMMPS text dump `path`
    (granflow's snapshots, a DEM run's dumps; gzip-compressed too) as a
    Snapshot. A missing file raises GranflowFileNotFoundError, a malformed one
    GranflowFormatError (a ValueError) naming the file and line."""
    if not os.path.exists(path):
        raise missing_file(path)
    handle = c_void_p()
    check(lib.gf_snapshot_read(enc(path), int(frame), ctypes.byref(handle)))
    try:
        n = lib.gf_snapshot_count(handle)
        out = Snapshot()
        t = lib.gf_snapshot_time(handle)
        out["time"] = None if math.isnan(t) else t
        out["step"] = int(lib.gf_snapshot_step(handle))
        lo, hi = np.empty(3), np.empty(3)
        has_box = lib.gf_snapshot_box(handle, _ptr(lo, ctypes.c_double), _ptr(hi, ctypes.c_double))
        out["box"] = np.column_stack([lo, hi]) if has_box else None
        cols = {"id": np.empty(n, np.int64), "type": np.empty(n, np.int32), "xyz": np.empty((n, 3)),
                "radius": np.empty(n), "pass": np.empty(n, np.int32)}
        got = ctypes.c_size_t()
        check(lib.gf_snapshot_copy(handle, _ptr(cols["id"], ctypes.c_int64), _ptr(cols["type"], ctypes.c_int32),
                                   _ptr(cols["xyz"], ctypes.c_double), _ptr(cols["radius"], ctypes.c_double),
                                   _ptr(cols["pass"], ctypes.c_int32), n, ctypes.byref(got)))
        out.update(cols)
        out.frames = lib.gf_snapshot_frames(handle)
        return out
    finally:
        lib.gf_snapshot_destroy(handle)
