# SPDX-License-Identifier: MIT
import shutil

import numpy as np
import pytest

import granflow


def _other(value):
    """Candidate values different from a default, for a key whose range is not known here."""
    if value == "auto":
        return [3.5, [2.5, 5]]
    if isinstance(value, list):
        return [[v + 0.5 for v in value], value[:2]]
    if isinstance(value, (int, float)):
        return [value + 1, value * 1.25, value * 0.8, value - 1, 1, 2]
    if isinstance(value, str):  # a word-valued option (velocity.window): its words
        return [w for w in ("height", "run") if w != value]
    return []


def test_every_option_round_trips_and_changes():
    names = granflow.analysis_keys()
    assert len(names) == len(set(names)) >= 28
    assert "window.t0" in names and "velocity.heights" in names
    o = granflow.AnalysisOptions()
    assert list(o.to_dict()) == names
    for key in names:
        text = o.get_text(key)
        o[key] = text  # the default, as text, is accepted back
        assert o.get_text(key) == text
        o[key] = o[key]  # and as the Python value it reads as
        assert o.get_text(key) == text
        for v in _other(o[key]):
            try:
                o[key] = v
            except ValueError:
                continue
            break
        assert o.get_text(key) != text, f"{key}: no other value accepted"
        assert o[key] == v, key
    # A second set of options built from the first by name is the same.
    assert granflow.AnalysisOptions(o.to_dict()).to_dict() == o.to_dict()
    assert repr(granflow.AnalysisOptions()) == "AnalysisOptions({})"
    # Lists, auto and floats bit for bit.
    o["velocity.heights"] = np.array([10.0, 20.25, 30.0])
    assert o["velocity.heights"] == [10, 20.25, 30]
    o["zones.radii"] = "auto"
    assert o["zones.radii"] == "auto"
    o["gr.dr"] = 1 / 30
    assert o["gr.dr"] == 1 / 30
    d = o.copy()
    d["gr.dr"] = 0.5
    assert o["gr.dr"] == 1 / 30


def test_unknown_options_and_bad_values_name_the_key():
    o = granflow.AnalysisOptions()
    with pytest.raises(ValueError, match="nosuch"):
        o["nosuch.key"] = 1
    with pytest.raises(ValueError, match=r"gr.nosuch.*keys of \[gr\]|unknown key 'nosuch' in section \[gr\]"):
        o["gr.nosuch"] = 1
    with pytest.raises(KeyError, match="gr.nosuch"):
        o["gr.nosuch"]
    with pytest.raises(ValueError, match="gr.rmax.*out of range"):
        o["gr.rmax"] = 200
    with pytest.raises(ValueError, match="velocity.heights.*'x' is not a number"):
        o["velocity.heights"] = [1, "x"]
    with pytest.raises(ValueError, match="zones.radii.*increas"):
        o["zones.radii"] = [2, 1]
    with pytest.raises(ValueError, match="window.t0"):
        granflow.AnalysisOptions({"window.t0": "soon"})
    assert o.to_dict() == granflow.AnalysisOptions().to_dict()  # nothing changed


def test_options_change_the_analysis(rundir, tmp_path):
    # The defaults give what `granflow analyze` gave (conftest ran it).
    a = granflow.analyze(rundir.path, name="outflow", outdir=tmp_path / "default")
    assert a["flow_rate"] == rundir.analysis["flow_rate"]
    assert a["window_t0"] == rundir.analysis["window_t0"] != 4
    # A window by option: the flow rate is the slope of the exits inside it.
    w = granflow.analyze(rundir.path, {"window.t0": 4, "window.t1": 6}, name="outflow", outdir=tmp_path / "w")
    assert (w["window_t0"], w["window_t1"]) == (4, 6)
    e = rundir.exits()["time"]
    inside = e[(e >= 4) & (e <= 6)]
    assert w["flow_rate"] == pytest.approx(np.polyfit(inside, np.arange(len(inside)), 1)[0], rel=0.05)
    assert w["flow_rate"] != a["flow_rate"]
    # The density slice by option: the count at rest is the first snapshot's, by hand.
    opts = granflow.AnalysisOptions({"density.z0": 2, "density.z1": 9.5})
    d = granflow.analyze(rundir.path, opts, name="density", outdir=tmp_path / "d")
    z = rundir.snapshot(0)["xyz"][:, 2]
    assert d["density_initial"] == np.count_nonzero((z > 2) & (z < 9.5)) > 100
    # Profile heights by option, as a list.
    granflow.analyze(rundir.path, {"velocity.heights": [4, 8.5], "window.t0": 1}, name="velocity",
                     outdir=tmp_path / "v")
    prof = granflow.read_csv(tmp_path / "v" / "velocity_profiles.csv")
    assert sorted(set(prof["z_d"].tolist())) == [4, 8.5]


def test_run_directory_analyze_and_errors(rundir, tmp_path):
    run = granflow.RunDir(shutil.copytree(rundir.path, tmp_path / "copy"))
    out = run.analyze({"window.t0": 3}, name="outflow")
    assert out == run.analysis and out["window_t0"] == 3
    assert "outflow" in run.tables()
    with pytest.raises(granflow.GranflowError, match="unknown measurement 'nosuch'"):
        run.analyze(name="nosuch")
    with pytest.raises(granflow.GranflowError, match="nothere"):
        granflow.analyze(tmp_path / "nothere", outdir=tmp_path / "x")
