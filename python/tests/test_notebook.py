# SPDX-License-Identifier: MIT
"""What a notebook needs: a simulation from arrays or a checkpoint, its state
as files, particles as tables, read_snapshot through the C reader, and one
exception hierarchy."""
import gzip
import shutil

import numpy as np
import pytest

import granflow

from conftest import SMALL


def drained(sim, until):
    sim.run(until)
    return sim.exits()


# ---- a simulation from numpy arrays ------------------------------------------------

def test_from_arrays_runs_as_the_packed_silo_does(small):
    # The particles of a packed silo handed back as arrays give the same run,
    # bit for bit (same seed): nothing of the packing is lost on the way.
    packed = granflow.Simulation(small)
    p = packed.particles()
    mine = granflow.Simulation(small, positions=p["xyz"], radii=p["radius"], ids=p["id"])
    assert np.array_equal(mine.particle_table(), packed.particle_table())
    a, b = drained(packed, 2.0), drained(mine, 2.0)
    assert len(a["id"]) > 0
    assert np.array_equal(a["id"], b["id"]) and np.array_equal(a["time"], b["time"])
    assert np.array_equal(packed.positions(), mine.positions())


def test_from_arrays_defaults_and_layers():
    cfg = {"container.width": 12, "container.depth": 6, "packing.layer_thickness": 2}
    xyz = np.array([[0, 0, 0.5], [2, 0, 0.5], [0, 0, 2.5], [-2, 1, 4.5]])
    sim = granflow.Simulation(cfg, positions=xyz)
    t = sim.particle_table()
    assert t["id"].tolist() == [1, 2, 3, 4]                  # ids 1..n
    assert np.all(t["radius"] == 0.5) and np.all(t["pass"] == 1)
    assert t["layer"].tolist() == [1, 1, 2, 3]               # 1 + floor(z / 2)
    assert np.array_equal(np.column_stack([t["x"], t["y"], t["z"]]), xyz)
    sim = granflow.Simulation(cfg, positions=xyz.tolist(), radii=0.6, ids=[10, 20, 30, 40])
    t = sim.particle_table()
    assert t["id"].tolist() == [10, 20, 30, 40] and np.all(t["radius"] == 0.6)


@pytest.mark.parametrize("kwargs, match", [
    ({"positions": np.zeros((3, 2))}, r"\(n, 3\) array"),
    ({"positions": [[0, 0, 1], [100, 0, 1]]}, r"positions\[1\] = \(100, 0, 1\) is outside the container"),
    ({"positions": [[0, 0, 1], [0, 0, np.nan]]}, r"positions\[1\] .* not finite"),
    ({"positions": [[0, 0, 1], [2, 0, 1]], "radii": [0.5, -1]}, r"radii\[1\] = -1"),
    ({"positions": [[0, 0, 1], [2, 0, 1]], "ids": [4, 4]}, r"ids\[0\] = ids\[1\] = 4: ids must be unique"),
    ({"positions": [[0, 0, 1], [2, 0, 1]], "ids": [1, 0]}, r"ids\[1\] = 0"),
    ({"positions": [[0, 0, 1]], "ids": [1.5]}, r"ids must be 1 integers"),
    ({"positions": np.empty((0, 3))}, r"no particles"),
    ({"radii": [0.5]}, r"radii and ids go with positions"),
])
def test_from_arrays_bad_values(kwargs, match):
    with pytest.raises(granflow.GranflowValueError, match=match) as e:
        granflow.Simulation({"container.width": 12, "container.depth": 6}, **kwargs)
    assert isinstance(e.value, ValueError) and isinstance(e.value, granflow.GranflowError)


# ---- load() from a checkpoint --------------------------------------------------------

def test_load_a_cli_run_directory(rundir):
    # `granflow run` left checkpoint.bin at t = 6: the loaded simulation holds
    # the particles of the last snapshot and goes on.
    sim = granflow.load(rundir.path)
    assert sim.time == pytest.approx(6.0)
    last = rundir.snapshot(-1)
    t = sim.particle_table()
    assert np.array_equal(t["id"], np.sort(last["id"]))
    order = np.argsort(last["id"])
    assert np.allclose(t["z"], last["xyz"][order, 2], atol=1e-6)   # the dump keeps 7 decimals
    assert np.array_equal(sim.exits()["id"], rundir.exits()["id"])
    sim.run(7.0)
    assert sim.time >= 7.0 and len(sim.exits()["id"]) > len(rundir.exits()["id"])


def test_write_run_dir_then_load_is_the_same_simulation(small, tmp_path):
    sim = granflow.Simulation(small)
    sim.run(1.5)
    run = sim.write_run_dir(tmp_path / "saved")
    assert isinstance(run, granflow.RunDir)
    assert run.summary["status"] == "saved" and run.summary["particles_exited"] == len(sim.exits()["id"])
    assert run.config.to_dict() == sim.config.copy().validate().to_dict()
    assert np.array_equal(run.exits()["id"], sim.exits()["id"])
    snap = run.snapshot(-1)
    assert snap["time"] == sim.time and len(snap["id"]) == len(sim)
    again = granflow.load(run.path)
    assert again.time == sim.time and np.array_equal(again.particle_table(), sim.particle_table())
    # Both go on alike: the checkpoint holds the random state too.
    a, b = drained(sim, 3.0), drained(again, 3.0)
    assert np.array_equal(a["id"], b["id"]) and np.array_equal(a["time"], b["time"])
    # A checkpoint file with a config that changes a [run] key only.
    other = granflow.load(run.path / "checkpoint.bin", {"run.duration": 50})
    assert other.config["run.duration"] == 50 and other.time == pytest.approx(1.5, abs=0.1)
    # The directory is a run: analyze reads it.
    granflow.analyze(run.path, name="outflow", outdir=tmp_path / "a")
    assert len(granflow.read_csv(tmp_path / "a" / "outflow.csv")["time_tau"]) > 0


def test_write_run_dir_refuses_a_run_unless_forced(small, tmp_path):
    sim = granflow.Simulation(small)
    sim.write_run_dir(tmp_path / "r")
    with pytest.raises(granflow.GranflowFileExistsError, match="already holds a run") as e:
        sim.write_run_dir(tmp_path / "r")
    assert isinstance(e.value, FileExistsError)
    sim.step(100)
    sim.write_run_dir(tmp_path / "r", force=True)
    assert granflow.load(tmp_path / "r").stats()["events"] == 100


def test_load_errors(small, tmp_path):
    with pytest.raises(FileNotFoundError, match="checkpoint"):
        granflow.load(tmp_path)
    sim = granflow.Simulation(small)
    sim.write_run_dir(tmp_path / "r")
    (tmp_path / "r" / "config.ini").unlink()
    with pytest.raises(granflow.GranflowFileNotFoundError, match="config.ini"):
        granflow.load(tmp_path / "r")
    shutil.copy(tmp_path / "r" / "checkpoint.bin", tmp_path / "bad.bin")
    with open(tmp_path / "bad.bin", "r+b") as f:
        f.seek(200)
        f.write(b"\xff\xfe\xfd")
    with pytest.raises(granflow.GranflowError) as e:
        granflow.load(tmp_path / "bad.bin", small)
    assert "bad.bin" in str(e.value)
    assert isinstance(e.value, (granflow.GranflowStateError, granflow.GranflowFormatError)), type(e.value)
    with pytest.raises(ValueError, match="container.width"):  # a saved run's geometry cannot change
        granflow.load(tmp_path / "r" / "checkpoint.bin", granflow.Config(dict(SMALL, **{"container.width": 14})))


# ---- particles as tables ---------------------------------------------------------------

def test_particle_table_takes_the_shape_pandas_wants(small):
    sim = granflow.Simulation(small)
    sim.run(1.0)
    t = sim.particle_table()
    assert t.dtype == granflow.PARTICLE_DTYPE and t.dtype.names == ("id", "layer", "pass", "x", "y", "z", "radius")
    p = sim.particles()
    assert np.array_equal(t["id"], p["id"]) and np.array_equal(t["z"], p["xyz"][:, 2])
    # What pandas.DataFrame(dict) needs: 1-D columns of one length.
    cols = {name: t[name] for name in t.dtype.names}
    assert {c.shape for c in cols.values()} == {(len(sim),)}
    e = sim.exits()
    assert {np.shape(c) for c in e.values()} == {(len(e["id"]),)}


def test_pandas_dataframes(small, tmp_path):
    pd = pytest.importorskip("pandas")
    sim = granflow.Simulation(small)
    sim.run(1.0)
    df = pd.DataFrame(sim.particle_table())
    assert list(df.columns) == ["id", "layer", "pass", "x", "y", "z", "radius"] and len(df) == len(sim)
    assert len(pd.DataFrame(sim.exits())) == len(sim.exits()["id"])
    sim.write_snapshot(tmp_path / "s.dump")
    assert len(pd.DataFrame(granflow.read_snapshot(tmp_path / "s.dump").particles)) == len(sim)


# ---- files: snapshots, VTK, read_snapshot through the C reader ----------------------------

def test_write_snapshot_read_snapshot_round_trip_and_gz(small, tmp_path):
    sim = granflow.Simulation(small)
    sim.run(1.0)
    sim.write_snapshot(tmp_path / "s.dump")
    snap = granflow.read_snapshot(tmp_path / "s.dump")
    t = sim.particle_table()
    assert snap["time"] == sim.time and snap["step"] == sim.stats()["events"] and snap.frames == 1
    assert snap["box"].shape == (3, 2) and snap["box"][0].tolist() == [-6, 6]
    assert np.array_equal(snap["id"], t["id"]) and np.array_equal(snap["type"], t["layer"])
    assert np.allclose(snap["xyz"], np.column_stack([t["x"], t["y"], t["z"]]), atol=1e-7)
    assert np.all(snap["radius"] == 0.5) and np.all(snap["pass"] == 1)
    assert snap.particles.dtype == granflow.SNAPSHOT_DTYPE
    with open(tmp_path / "s.dump", "rb") as f, gzip.open(tmp_path / "s.dump.gz", "wb") as g:
        g.write(f.read())
    gz = granflow.read_snapshot(tmp_path / "s.dump.gz")
    assert np.array_equal(gz.particles, snap.particles) and gz["time"] == snap["time"]


def test_read_snapshot_radius_pass_and_frames(tmp_path):
    # A recirculating bidisperse silo: the pass and radius columns come back.
    cfg = dict(SMALL, **{"run.recirculate": "on"})
    xyz = granflow.Simulation(cfg).positions()
    radii = np.where(np.arange(len(xyz)) % 2 == 0, 0.5, 0.45)
    sim = granflow.Simulation(cfg, positions=xyz, radii=radii)
    sim.run(4.0)
    passes = sim.passes()
    assert passes.max() >= 2                                 # some went round
    sim.write_snapshot(tmp_path / "a.dump")
    snap = granflow.read_snapshot(tmp_path / "a.dump")
    assert np.array_equal(snap["pass"], passes)
    assert np.allclose(snap["radius"], sim.particle_table()["radius"])
    assert set(np.round(snap["radius"], 6)) == {0.5, 0.45}
    # Two frames in one file: the first, the last, and no third.
    first = (tmp_path / "a.dump").read_text()
    sim.run(5.0)
    sim.write_snapshot(tmp_path / "b.dump")
    (tmp_path / "ab.dump").write_text(first + (tmp_path / "b.dump").read_text())
    f0 = granflow.read_snapshot(tmp_path / "ab.dump", frame=0)
    f1 = granflow.read_snapshot(tmp_path / "ab.dump")
    assert f0.frames == f1.frames == 2 and f0["time"] == snap["time"] and f1["time"] == sim.time
    with pytest.raises(granflow.GranflowValueError, match="has 2 frames: there is no frame 2"):
        granflow.read_snapshot(tmp_path / "ab.dump", frame=2)


def test_write_vtk(small, tmp_path):
    sim = granflow.Simulation(small)
    sim.run(0.5)
    sim.write_vtk(tmp_path / "s.vtu")
    # The arrays are zlib-compressed raw appended data by default (the XML
    # head is text; what follows <AppendedData> is binary): read the head.
    head = (tmp_path / "s.vtu").read_bytes().split(b"<AppendedData")[0].decode()
    import re
    assert int(re.search(r'NumberOfPoints="(\d+)"', head).group(1)) == len(sim)
    point_data = head.split("<PointData")[1].split("</PointData>")[0]
    names = set(re.findall(r'Name="([^"]+)"', point_data))
    assert {"id", "radius", "pass", "layer"} <= names


# ---- one exception hierarchy ---------------------------------------------------------

def test_errors_are_granflow_errors_and_builtins(tmp_path):
    with pytest.raises(granflow.GranflowFileNotFoundError) as e:
        granflow.read_snapshot(tmp_path / "none.dump")
    assert isinstance(e.value, FileNotFoundError) and e.value.filename == str(tmp_path / "none.dump")
    (tmp_path / "bad.dump").write_text("ITEM: TIMESTEP\n0\nITEM: NUMBER OF ATOMS\n2\nITEM: ATOMS id x y z\n1 0 0 x\n")
    with pytest.raises(granflow.GranflowFormatError, match=r"bad.dump:6: column 'z'") as e:
        granflow.read_snapshot(tmp_path / "bad.dump")
    assert isinstance(e.value, ValueError) and e.value.status == "malformed data"
    with pytest.raises(granflow.GranflowFileNotFoundError):
        granflow.Config(path=tmp_path / "none.ini")
    with pytest.raises(granflow.GranflowFileNotFoundError):
        granflow.RunDir(tmp_path)
    with pytest.raises(granflow.GranflowValueError):
        granflow.Config({"spot.radius": -1})
    with pytest.raises(granflow.GranflowKeyError) as e:
        granflow.Config()["spot.nosuch"]
    assert isinstance(e.value, KeyError)
    sim = granflow.Simulation({"packing.particles": 200, "container.width": 10})
    sim.close()
    with pytest.raises(granflow.GranflowValueError, match="closed"):
        len(sim)
    for cls in (granflow.GranflowValueError, granflow.GranflowFormatError, granflow.GranflowKeyError,
                granflow.GranflowOSError, granflow.GranflowFileNotFoundError, granflow.GranflowFileExistsError,
                granflow.GranflowMemoryError, granflow.GranflowStateError):
        assert issubclass(cls, granflow.GranflowError)
    assert issubclass(granflow.GranflowFileNotFoundError, OSError)
