# SPDX-License-Identifier: MIT
import os

import numpy as np

import granflow
from granflow._lib import check, lib

from conftest import SMALL


def test_particles_and_exits_account_for_everyone(small):
    with granflow.Simulation(small) as sim:
        assert len(sim) == 1500 and sim.time == 0
        sim.run(until=3.0)
        assert sim.time >= 3.0
        p, e = sim.particles(), sim.exits()
        assert len(e["id"]) > 0
        assert len(p["id"]) + len(e["id"]) == 1500
        assert sim.stats()["particles_exited"] == len(e["id"])
        assert np.all(np.diff(p["id"]) > 0)                    # sorted by id
        assert np.array_equal(np.sort(np.concatenate([p["id"], e["id"]])), np.arange(1, 1501))
        assert np.all(np.diff(e["time"]) >= 0) and np.all((e["time"] > 0) & (e["time"] <= sim.time))
        assert np.all(np.hypot(e["x"], e["y"]) <= 2.5 + 0.5)   # left through the orifice (diameter 5)
        xyz = p["xyz"]
        assert xyz.shape == (len(p["id"]), 3)
        assert np.all(np.abs(xyz[:, 0]) <= 6) and np.all(np.abs(xyz[:, 1]) <= 3)  # between the walls
        assert np.all(p["radius"] == 0.5) and np.all(p["layer"] >= 1)


def test_step_by_step_is_one_event_each(small):
    sim = granflow.Simulation(small)
    for k in range(1, 6):
        sim.step()
        assert sim.stats()["events"] == k
    sim.step(10)
    assert sim.stats()["events"] == 15
    sim.close()


def test_same_seed_same_flow_other_seed_other_flow(small):
    def drain(seed):
        c = small.copy()
        c["run.seed"] = seed
        sim = granflow.Simulation(c)
        sim.run(2.0)
        return sim.positions(), sim.exits()["id"]

    a, b, c = drain(5), drain(5), drain(6)
    assert np.array_equal(a[0], b[0]) and np.array_equal(a[1], b[1])
    assert a[0].shape != c[0].shape or not np.array_equal(a[0], c[0])


def test_run_in_pieces_is_one_run(small):
    # run() goes in pieces of ~0.1 s (so Ctrl-C can stop it): the same state
    # as one gf_sim_run call to the same time, bit for bit.
    a, b = granflow.Simulation(small), granflow.Simulation(small)
    a.run(3.0)
    check(lib.gf_sim_run(b._ptr, 3.0, None))
    assert a.time == b.time and a.stats()["events"] == b.stats()["events"]
    assert np.array_equal(a.positions(), b.positions())
    assert np.array_equal(a.exits()["time"], b.exits()["time"])


def test_ctrl_c_stops_a_long_run(small):
    # SIGINT during run(until=10,000 tau) raises KeyboardInterrupt within a
    # few seconds, the simulation still usable (particles put back on the
    # surface, so the silo never empties).
    import os
    import signal
    import threading
    import time
    c = small.copy()
    c["run.recirculate"] = "on"
    sim = granflow.Simulation(c)
    timer = threading.Timer(0.5, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    start = time.monotonic()
    try:
        sim.run(until=10000.0)
        assert False, "run() was not interrupted"
    except KeyboardInterrupt:
        pass
    finally:
        timer.cancel()
    assert time.monotonic() - start < 5.0
    assert 0 < sim.time < 10000.0
    t = sim.time
    sim.run(until=t + 0.5)
    assert sim.time >= t + 0.5


def test_python_run_matches_the_cli_run(rundir):
    # The same config and seed through Python step by step and through
    # `granflow run` give the same exits (exits.csv prints 9 digits).
    sim = granflow.Simulation(granflow.Config(SMALL))
    sim.run(6.0)
    mine, theirs = sim.exits(), rundir.exits()
    assert np.array_equal(mine["id"], theirs["id"])
    assert np.allclose(mine["time"], theirs["time"], rtol=1e-8, atol=0)


def test_import_reports_dropped_particles_as_a_warning(tmp_path):
    # A simple cubic packing of 12 x 6 x 10 spheres plus one already below the
    # base: the import keeps 720, counts the other as exited, and says so in
    # a warning (the library never prints).
    xs, ys, zs = np.arange(-5.5, 6), np.arange(-2.5, 3), np.arange(0.5, 10)
    grid = np.array([(x, y, z) for z in zs for y in ys for x in xs])
    rows = np.vstack([grid, [[0.0, 0.0, -0.3]]])
    path = tmp_path / "cubic.csv"
    np.savetxt(path, rows, delimiter=",", header="x,y,z", comments="", fmt="%.3f")
    cfg = granflow.Config(SMALL)
    cfg["packing.file"] = path
    granflow.clear_warnings()
    sim = granflow.Simulation(cfg)
    assert len(sim) == 720
    w = granflow.warnings()
    assert len(w) == 1 and "720 of 721 particles kept (1 below the base" in w[0], w
    granflow.clear_warnings()
    assert granflow.warnings() == []


def test_run_nan_is_refused(small):
    # Issue 26: run(nan) returned at once, having done nothing, without a word.
    import pytest

    with granflow.Simulation(small) as sim:
        with pytest.raises(ValueError, match="nan"):
            sim.run(float("nan"))
        assert sim.time == 0
        assert lib.gf_sim_run(sim._live(), float("nan"), None) != 0  # the library refuses it too
        assert "NaN" in lib.gf_last_error().decode()


# One Simulation shared between threads (issue 26). Each case runs in a
# python of its own: on the tree before the fix it died of SIGSEGV, which
# would take pytest down with it.
def _in_subprocess(body):
    import subprocess
    import sys
    import textwrap
    code = "import granflow, threading, numpy as np\nfrom conftest import SMALL\n" + textwrap.dedent(body)
    here = os.path.dirname(os.path.abspath(__file__))
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([here] + os.environ.get("PYTHONPATH", "").split(os.pathsep)))
    r = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, timeout=240)
    assert r.returncode == 0, f"rc {r.returncode}\n{r.stdout}\n{r.stderr}"
    return r.stdout


def test_close_from_another_thread_during_run():
    # threading.Timer(0.5, s.close) while s.run() goes: close waits for the
    # piece under way, then run raises ValueError; nothing crashes.
    out = _in_subprocess("""
        c = granflow.Config(SMALL)
        c["run.recirculate"] = "on"
        # The 2009 paper's free-surface walk: without it the surface loosens
        # pass after pass and a fast machine reaches the run's room limit
        # (GranflowStateError) before the timer closes the simulation.
        c["spot.bias_exponent"] = 3
        c["spot.weighting"] = "on"
        s = granflow.Simulation(c)
        t = threading.Timer(0.5, s.close)
        t.start()
        try:
            s.run(10000.0)
            print("run returned")
        except ValueError as e:
            print("ValueError:", e)
        t.join()
        try:
            len(s)
        except ValueError:
            print("closed")
        s.close()  # twice is fine
    """)
    assert "ValueError: the simulation is closed" in out and "closed\n" in out


def test_two_threads_running_one_simulation():
    # Two threads each calling s.run(5) while a third reads it: the state is
    # that of one run(5), bit for bit, and every read is whole.
    out = _in_subprocess("""
        s, ref = granflow.Simulation(SMALL), granflow.Simulation(SMALL)
        ref.run(5.0)
        bad = []
        def reader():
            # The particles first, the exits after: a piece run between the
            # two can only count a particle twice, never lose one.
            while not done.is_set():
                try:
                    p, e = s.particles(), s.exits()
                    if len(p["id"]) + len(e["id"]) < SMALL["packing.particles"]:
                        bad.append((len(p["id"]), len(e["id"])))
                    s.stats()
                except Exception as x:
                    bad.append(repr(x))
        done = threading.Event()
        threads = [threading.Thread(target=s.run, args=(5.0,)) for _ in range(2)]
        r = threading.Thread(target=reader)
        r.start()
        for t in threads: t.start()
        for t in threads: t.join()
        done.set()
        r.join()
        assert not bad, bad
        assert s.time == ref.time, (s.time, ref.time)
        assert np.array_equal(s.positions(), ref.positions())
        assert np.array_equal(s.exits()["time"], ref.exits()["time"])
        print("same")
    """)
    assert "same" in out
