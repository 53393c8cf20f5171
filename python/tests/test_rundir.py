# SPDX-License-Identifier: MIT
import numpy as np
import pytest

import granflow


def test_run_directory_files_agree(rundir):
    s = rundir.summary
    e = rundir.exits()
    assert s["status"] == "complete"
    assert s["particles_exited"] == len(e["id"]) > 0
    assert s["particles_initial"] == 1500
    assert rundir.config["packing.particles"] == 1500
    snaps = rundir.snapshots()
    assert len(snaps) == 7  # t = 0, 1, ..., 6
    for k in (0, 3, 6):
        snap = rundir.snapshot(k)
        assert snap["time"] == pytest.approx(k)
        gone = np.count_nonzero(e["time"] <= snap["time"])
        assert len(snap["id"]) == 1500 - gone
        assert not np.isin(snap["id"], e["id"][e["time"] <= snap["time"]]).any()
        assert snap["box"][0].tolist() == [-6, 6]


def test_analysis_results(rundir):
    a = rundir.analysis
    e = rundir.exits()
    assert a["particles_exited"] == len(e["id"])
    out = rundir.table("outflow")
    assert list(out) == ["time_tau", "exited", "fit_exited"]
    assert out["exited"][-1] == len(e["id"])
    assert np.all(np.diff(out["exited"]) >= 0)
    # The flow rate is the slope of the exits in the window: check it by hand.
    t0, t1 = a["window_t0"], a["window_t1"]
    inside = e["time"][(e["time"] >= t0) & (e["time"] <= t1)]
    slope = np.polyfit(inside, np.arange(len(inside)), 1)[0]
    assert a["flow_rate"] == pytest.approx(slope, rel=0.05)
    assert "velocity_field" in rundir.tables()


def test_not_a_run_directory(tmp_path):
    with pytest.raises(FileNotFoundError, match="no config.ini"):
        granflow.RunDir(tmp_path)


def test_run_files_are_read_only_when_regular(tmp_path):
    # A FIFO or /dev/zero in place of a file a run wrote raises at once,
    # naming it (issue 26: open() of a FIFO waited for a writer for ever,
    # and /dev/zero was read until memory ran out).
    import os
    d = tmp_path / "run"
    d.mkdir()
    (d / "config.ini").write_text("[run]\nseed = 1\n")
    os.mkfifo(d / "summary.json")
    os.symlink("/dev/zero", d / "exits.csv")
    r = granflow.RunDir(d)
    with pytest.raises(OSError, match="summary.json: not a regular file \\(a FIFO\\)"):
        r.summary
    with pytest.raises(OSError, match="exits.csv: not a regular file \\(a character device\\)"):
        r.exits()
    (d / "ok.csv").write_text("a,b\n1,2\n3,4\n")
    t = granflow.read_csv(d / "ok.csv")
    assert list(t["a"]) == [1.0, 3.0] and list(t["b"]) == [2.0, 4.0]
