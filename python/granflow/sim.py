# SPDX-License-Identifier: MIT
"""A spot-model simulation driven step by step; particles and exits as numpy arrays."""
import ctypes
import threading
import time

import numpy as np

from ._lib import c_void_p, check, enc, lib
from .config import Config


def _ptr(array, ctype):
    return array.ctypes.data_as(ctypes.POINTER(ctype))


class Simulation:
    """The silo of `config` (a Config or a dict of keys), packed and ready at t = 0.

    >>> sim = Simulation({"container.width": 12, "packing.particles": 1500})
    >>> sim.run(until=2.0)      # simulated time, tau
    >>> sim.positions().shape   # (particles left, 3), d

    One object may be used from several threads: every call holds the
    object's lock while it uses the C simulation (ctypes lets go of the GIL
    during a C call, and the C handle is not safe for two callers at once).
    run() holds it one piece (~0.1 s) at a time, so another thread can read
    time, len() or stats() while it runs. close() waits for the piece under
    way; a run() of another thread then raises ValueError.
    """

    def __init__(self, config=None):
        self._lock = threading.RLock()
        cfg = config if isinstance(config, Config) else Config(config)
        self.config = cfg.copy()
        handle = c_void_p()
        check(lib.gf_sim_create_from_config(cfg.handle, ctypes.byref(handle)))
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
            raise ValueError("the simulation is closed")
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
