# SPDX-License-Identifier: MIT
"""A spot-model simulation driven step by step; particles and exits as numpy arrays."""
import ctypes
import math
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
    """

    def __init__(self, config=None):
        cfg = config if isinstance(config, Config) else Config(config)
        self.config = cfg.copy()
        handle = c_void_p()
        check(lib.gf_sim_create_from_config(cfg.handle, ctypes.byref(handle)))
        self._ptr = handle

    def close(self):
        ptr, self._ptr = getattr(self, "_ptr", None), None
        if ptr:
            lib.gf_sim_destroy(ptr)

    __del__ = close

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def _live(self):
        if not self._ptr:
            raise ValueError("the simulation is closed")
        return self._ptr

    # ---- running -------------------------------------------------------------
    def step(self, n=1):
        """Processes n events (an insertion or a spot move each; fixed mode: steps)."""
        for _ in range(int(n)):
            check(lib.gf_sim_step(self._live()))

    def run(self, until):
        """Runs until the simulated time passes `until` (tau).

        In pieces of about 0.1 s of wall time (the piece of simulated time is
        adjusted as it goes), so Ctrl-C raises KeyboardInterrupt between two
        pieces, the state whole; the pieces give the same result as one call.
        """
        until, piece = float(until), 0.01
        if math.isnan(until):  # every comparison with NaN is false: it would return at once, having done nothing
            raise ValueError("run(until=nan): until must be a number (tau)")
        sim = self._live()
        while self.time < until:
            start, was = time.perf_counter(), self.time
            check(lib.gf_sim_run(sim, min(until, self.time + piece), None))
            if self.time <= was:
                break  # nothing moves any more (the engine returned without advancing)
            spent = time.perf_counter() - start
            piece *= 2.0 if spent <= 0 else min(2.0, max(0.5, 0.1 / spent))

    def set_threads(self, threads):
        """Threads of the spatial fixed step (0: every core); results do not depend on it."""
        lib.gf_sim_set_threads(self._live(), int(threads))

    def save(self, path):
        """Writes a checkpoint (granflow run --resume reads it)."""
        check(lib.gf_sim_save(self._live(), enc(path)))

    # ---- state ---------------------------------------------------------------
    @property
    def time(self):
        """Simulated time, tau."""
        return lib.gf_sim_stat(self._live(), b"time")

    def stats(self):
        """Every counter of gf_sim_stats by name (time, particles_exited, spot_moves, ...)."""
        names = [lib.gf_sim_stat_name(i).decode() for i in range(lib.gf_sim_stat_count())]
        return {n: lib.gf_sim_stat(self._live(), n.encode()) for n in names}

    def __len__(self):
        return lib.gf_sim_particle_count(self._live())

    def particles(self):
        """The particles still in the container, sorted by id: a dict of numpy arrays
        id (int64), layer (int32), xyz (n x 3, d), radius (d)."""
        n = len(self)
        out = {"id": np.empty(n, np.int64), "layer": np.empty(n, np.int32),
               "xyz": np.empty((n, 3), np.float64), "radius": np.empty(n, np.float64)}
        got = ctypes.c_size_t()
        check(lib.gf_sim_copy_particles(self._live(), _ptr(out["id"], ctypes.c_int64),
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
        n = lib.gf_sim_exit_count(self._live())
        ids = np.empty(n, np.int64)
        txy = np.empty((n, 3), np.float64)
        got = ctypes.c_size_t()
        check(lib.gf_sim_copy_exits(self._live(), _ptr(ids, ctypes.c_int64), _ptr(txy, ctypes.c_double), n,
                                    ctypes.byref(got)))
        return {"id": ids, "time": txy[:, 0].copy(), "x": txy[:, 1].copy(), "y": txy[:, 2].copy()}
