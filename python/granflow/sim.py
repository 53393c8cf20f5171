# SPDX-License-Identifier: MIT
"""A spot-model simulation driven step by step; particles and exits as numpy arrays."""
import ctypes
import math
import os
import threading
import time
from pathlib import Path

import numpy as np

from ._lib import c_void_p, check, enc, lib
from .config import Config
from .errors import GranflowValueError, missing_file
from .rundir import RunDir
from .snapshot import table


def _ptr(array, ctype):
    return array.ctypes.data_as(ctypes.POINTER(ctype))


class Simulation:
    """The silo of `config` (a Config or a dict of keys), packed and ready at t = 0.

    >>> sim = Simulation({"container.width": 12, "packing.particles": 1500})
    >>> sim.run(until=2.0)      # simulated time, tau
    >>> sim.positions().shape   # (particles left, 3), d

    With `positions` (n x 3, d) the particles are those, not a packing of
    the config: `radii` (n; default 0.5) and `ids` (n, unique, >= 1;
    default 1..n) may go with them. With `checkpoint` (a file gf_sim_save
    wrote) the simulation goes on from it; see load().

    One object may be used from several threads: every call holds the
    object's lock while it uses the C simulation (ctypes lets go of the GIL
    during a C call, and the C handle is not safe for two callers at once).
    run() holds it one piece (~0.1 s) at a time, so another thread can read
    time, len() or stats() while it runs. close() waits for the piece under
    way; a run() of another thread then raises ValueError.
    """

    def __init__(self, config=None, *, positions=None, radii=None, ids=None, checkpoint=None):
        self._lock = threading.RLock()
        cfg = config if isinstance(config, Config) else Config(config)
        self.config = cfg.copy()
        handle = c_void_p()
        _create(cfg, handle, positions, radii, ids, checkpoint)
        self._ptr = handle

    def close(self):
        """Frees the C simulation; later calls raise ValueError. Safe from any thread."""
        lock = getattr(self, "_lock", None)
        if lock is None:  # __init__ failed before the lock existed
            return
        with lock:
            ptr, self._ptr = getattr(self, "_ptr", None), None
            if ptr:
                lib.gf_sim_destroy(ptr)

    __del__ = close

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _live(self):
        """The C handle; the caller holds self._lock for as long as it uses it."""
        if not getattr(self, "_ptr", None):
            raise GranflowValueError("the simulation is closed")  # as a closed file: ValueError
        return self._ptr

    # ---- running -------------------------------------------------------------
    def step(self, n=1):
        """Processes n events (an insertion or a spot move each; fixed mode: steps)."""
        for _ in range(int(n)):
            with self._lock:
                check(lib.gf_sim_step(self._live()))

    def run(self, until):
        """Runs until the simulated time passes `until` (tau).

        In pieces of about 0.1 s of wall time (the piece of simulated time is
        adjusted as it goes), so Ctrl-C raises KeyboardInterrupt between two
        pieces, the state whole; the pieces give the same result as one call.
        Each piece holds the object's lock: a close() from another thread
        waits for the piece under way, and this run then raises ValueError.
        """
        until, piece = float(until), 0.01
        if math.isnan(until):  # every comparison with NaN is false: it would return at once, having done nothing
            raise ValueError("run(until=nan): until must be a number (tau)")
        while True:
            with self._lock:
                sim = self._live()  # ValueError once another thread has closed it
                was = lib.gf_sim_stat(sim, b"time")
                if was >= until:
                    return
                start = time.perf_counter()
                check(lib.gf_sim_run(sim, min(until, was + piece), None))
                if lib.gf_sim_stat(sim, b"time") <= was:
                    return  # nothing moves any more (the engine returned without advancing)
            spent = time.perf_counter() - start
            piece *= 2.0 if spent <= 0 else min(2.0, max(0.5, 0.1 / spent))

    def set_threads(self, threads):
        """Threads of the spatial fixed step (0: every core); results do not depend on it."""
        with self._lock:
            lib.gf_sim_set_threads(self._live(), int(threads))

    def save(self, path):
        """Writes a checkpoint (granflow run --resume reads it)."""
        with self._lock:
            check(lib.gf_sim_save(self._live(), enc(path)))

    # ---- state ---------------------------------------------------------------
    @property
    def time(self):
        """Simulated time, tau."""
        with self._lock:
            return lib.gf_sim_stat(self._live(), b"time")

    def stats(self):
        """Every counter of gf_sim_stats by name (time, particles_exited, spot_moves, ...)."""
        names = [lib.gf_sim_stat_name(i).decode() for i in range(lib.gf_sim_stat_count())]
        with self._lock:  # one consistent set of counters
            sim = self._live()
            return {n: lib.gf_sim_stat(sim, n.encode()) for n in names}

    def __len__(self):
        with self._lock:
            return lib.gf_sim_particle_count(self._live())

    def particles(self):
        """The particles still in the container, sorted by id: a dict of numpy arrays
        id (int64), layer (int32), xyz (n x 3, d), radius (d)."""
        with self._lock:  # the count and the copy of the same moment
            sim = self._live()
            n = lib.gf_sim_particle_count(sim)
            out = {"id": np.empty(n, np.int64), "layer": np.empty(n, np.int32),
                   "xyz": np.empty((n, 3), np.float64), "radius": np.empty(n, np.float64)}
            got = ctypes.c_size_t()
            check(lib.gf_sim_copy_particles(sim, _ptr(out["id"], ctypes.c_int64),
                                            _ptr(out["layer"], ctypes.c_int32), _ptr(out["xyz"], ctypes.c_double),
                                            _ptr(out["radius"], ctypes.c_double), n, ctypes.byref(got)))
        assert got.value == n
        return out

    def positions(self):
        """Centres of the particles left, (n, 3), sorted by id."""
        return self.particles()["xyz"]

    def ids(self):
        return self.particles()["id"]

    def exits(self):
        """The particles that left, sorted by time: dict of id (int64), time (tau), x, y (d)."""
        with self._lock:  # the count and the copy of the same moment
            sim = self._live()
            n = lib.gf_sim_exit_count(sim)
            ids = np.empty(n, np.int64)
            txy = np.empty((n, 3), np.float64)
            got = ctypes.c_size_t()
            check(lib.gf_sim_copy_exits(sim, _ptr(ids, ctypes.c_int64), _ptr(txy, ctypes.c_double), n,
                                        ctypes.byref(got)))
        return {"id": ids, "time": txy[:, 0].copy(), "x": txy[:, 1].copy(), "y": txy[:, 2].copy()}

    # ---- notebooks: tables and files -----------------------------------------
    def passes(self):
        """The pass each particle left is on (1 + times it went round; always 1
        without run.recirculate), sorted by id as particles()."""
        with self._lock:  # the count and the copy of the same moment
            n = len(self)
            out = np.empty(n, np.int32)
            check(lib.gf_sim_passes(self._live(), _ptr(out, ctypes.c_int32), n))
        return out

    def particle_table(self):
        """The particles left as one structured array (PARTICLE_DTYPE: id, layer,
        pass, x, y, z, radius), sorted by id; `pandas.DataFrame(t)` takes it as
        it is, and t["z"] is a column."""
        with self._lock:
            p = self.particles()
            passes = self.passes()
        return table("layer", p["id"], p["layer"], passes, p["xyz"], p["radius"])

    def write_snapshot(self, path):
        """Writes the particles left as a snapshot frame (a LAMMPS text dump, as
        snapshots/snap_*.dump of a run): read_snapshot, `granflow analyze` and
        `render` read it."""
        with self._lock:
            check(lib.gf_sim_write_snapshot(self._live(), enc(path)))

    def write_vtk(self, path):
        """Writes the particles left as a VTK XML unstructured grid (.vtu) for
        ParaView: point data id, radius, pass, layer; the time as field data."""
        with self._lock:
            check(lib.gf_sim_write_vtk(self._live(), enc(path)))

    def write_run_dir(self, path, force=False):
        """Writes the state as a run directory, as if `granflow run` had stopped
        here: config.ini, checkpoint.bin, exits.csv, summary.json (status
        "saved") and the snapshot of now; RunDir, load(), `granflow analyze`,
        `render` and `run --resume` read it. A directory holding a run raises
        GranflowFileExistsError (a FileExistsError) unless `force`. Returns a
        RunDir."""
        with self._lock:
            check(lib.gf_sim_write_run_dir(self._live(), enc(path), 1 if force else 0))
        return RunDir(path)


def _create(cfg, handle, positions, radii, ids, checkpoint):
    """Makes the C simulation for Simulation.__init__ into `handle`."""
    if checkpoint is not None:
        if positions is not None:
            raise GranflowValueError("give positions or a checkpoint, not both")
        if not os.path.exists(checkpoint):
            raise missing_file(checkpoint)
        check(lib.gf_sim_load(cfg.handle, enc(checkpoint), ctypes.byref(handle)))
        return
    if positions is None:
        if radii is not None or ids is not None:
            raise GranflowValueError("radii and ids go with positions")
        check(lib.gf_sim_create_from_config(cfg.handle, None, ctypes.byref(handle)))  # default packing options
        return
    xyz = np.ascontiguousarray(positions, dtype=np.float64)
    if xyz.ndim != 2 or xyz.shape[1] != 3:
        raise GranflowValueError(f"positions must be an (n, 3) array of particle centres, got shape {xyz.shape}")
    n = len(xyz)
    r = None if radii is None else np.ascontiguousarray(np.broadcast_to(np.asarray(radii, np.float64), (n,)))
    if ids is not None:
        raw = np.asarray(ids)
        if raw.shape != (n,) or not np.issubdtype(raw.dtype, np.integer):
            raise GranflowValueError(f"ids must be {n} integers, got shape {raw.shape} of {raw.dtype}")
        ids = np.ascontiguousarray(raw, dtype=np.int64)
    check(lib.gf_sim_create_from_arrays(cfg.handle, n, _ptr(xyz, ctypes.c_double),
                                        None if r is None else _ptr(r, ctypes.c_double),
                                        None if ids is None else _ptr(ids, ctypes.c_int64), ctypes.byref(handle)))


def load(path, config=None):
    """The simulation saved in a run directory (its config.ini and
    checkpoint.bin, as `granflow run` or write_run_dir left them), or in a
    checkpoint file `path`: then with `config` (a Config, a dict or an INI
    path; default: config.ini beside the file). `config` may change only the
    [run] and [output] keys of the saved run. Missing files raise
    GranflowFileNotFoundError (a FileNotFoundError), a corrupt checkpoint
    GranflowStateError."""
    path = Path(path)
    if path.is_dir():
        ini, ckpt = path / "config.ini", path / "checkpoint.bin"
    else:
        ini, ckpt = path.parent / "config.ini", path
    if not ckpt.exists():
        raise missing_file(ckpt, "checkpoint (a run directory holds checkpoint.bin)")
    if isinstance(config, Config):
        cfg = config
    elif isinstance(config, dict):
        if not ini.exists():
            raise missing_file(ini)
        cfg = Config(config, path=ini)
    else:
        ini = Path(config) if config is not None else ini
        if not ini.exists():
            raise missing_file(ini)
        cfg = Config(path=ini)
    return Simulation(cfg, checkpoint=ckpt)
