# SPDX-License-Identifier: MIT
"""A run's VTK output read back by the readers users open it with: VTK
(python3-vtk9, what ParaView is built on) and meshio (python3-meshio). The
.vtu snapshots must carry the dump's particles, arrays and the time in tau
as TimeValue; snapshots.pvd must list them with those times; container.vtp
must be a surface around the particles. Both encodings (binary by default,
output.vtk_encoding = ascii) are read."""
import subprocess
import xml.etree.ElementTree as ET

import meshio
import numpy as np
import pytest
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLUnstructuredGridReader

from conftest import cli


def read_dump(path):
    """time, id and x y z of one granflow dump, read here (not through the
    package) so that the check does not lean on the code it checks."""
    lines = path.read_text().splitlines()
    time = float(lines[lines.index("ITEM: TIME") + 1])
    k = next(i for i, ln in enumerate(lines) if ln.startswith("ITEM: ATOMS"))
    cols = lines[k].split()[2:]
    rows = np.array([ln.split() for ln in lines[k + 1:] if ln.strip()], dtype=np.float64).reshape(-1, len(cols))
    c = {name: rows[:, j] for j, name in enumerate(cols)}
    return {"time": time, "id": c["id"].astype(np.int64), "x": c["x"], "y": c["y"], "z": c["z"]}


def dump_of(vtu):
    return read_dump(vtu.with_suffix(".dump"))


@pytest.fixture(scope="module", params=["binary", "ascii"])
def vtkrun(request, tmp_path_factory):
    d = tmp_path_factory.mktemp("vtk") / request.param
    subprocess.run([cli(), "run", "-q", "--set", "container.width=10", "--set", "container.depth=6",
                    "--set", "container.orifice_diameter=4", "--set", "packing.particles=600",
                    "--set", "run.duration=1.5", "--set", "output.snapshot_interval=0.5",
                    "--set", "output.format=both", "--set", f"output.vtk_encoding={request.param}",
                    "-o", str(d)], check=True)
    return d


def pvd_entries(run):
    root = ET.parse(run / "snapshots.pvd").getroot()
    assert root.get("type") == "Collection"
    return [(float(e.get("timestep")), run / e.get("file")) for e in root.iter("DataSet")]


def test_pvd_lists_every_snapshot_with_its_time(vtkrun):
    entries = pvd_entries(vtkrun)
    assert len(entries) == len(list((vtkrun / "snapshots").glob("snap_*.dump"))) == 4
    assert [t for t, _ in entries] == pytest.approx([0.0, 0.5, 1.0, 1.5])
    assert [f.name for _, f in entries] == [f"snap_{k:06d}.vtu" for k in range(4)]


def test_vtk_reads_particles_arrays_and_time(vtkrun):
    for t, f in pvd_entries(vtkrun):
        r = vtkXMLUnstructuredGridReader()
        r.SetFileName(str(f))
        r.Update()
        g = r.GetOutput()
        snap = dump_of(f)
        n = len(snap["id"])
        assert g.GetNumberOfPoints() == n and g.GetNumberOfCells() == n
        assert g.GetFieldData().GetArray("TimeValue").GetValue(0) == pytest.approx(t)
        assert snap["time"] == pytest.approx(t)
        pd = g.GetPointData()
        ids = vtk_to_numpy(pd.GetArray("id"))
        assert np.array_equal(ids, snap["id"])
        pts = vtk_to_numpy(g.GetPoints().GetData())
        assert np.allclose(pts[:, 2], snap["z"], atol=1e-6)
        assert np.allclose(vtk_to_numpy(pd.GetArray("radius")), 0.5)
        assert set(np.unique(vtk_to_numpy(pd.GetArray("pass")))) == {1}
        assert vtk_to_numpy(pd.GetArray("layer")).min() >= 1


def test_meshio_reads_particles_arrays_and_time(vtkrun):
    for t, f in pvd_entries(vtkrun):
        m = meshio.read(f)
        snap = dump_of(f)
        assert m.points.shape == (len(snap["id"]), 3)
        assert np.allclose(m.points[:, 0], snap["x"], atol=1e-6)
        assert sorted(m.point_data) == ["id", "layer", "pass", "radius"]
        assert np.array_equal(m.point_data["id"], snap["id"])
        assert float(np.ravel(m.field_data["TimeValue"])[0]) == pytest.approx(t)
        assert sum(len(c.data) for c in m.cells) == len(snap["id"])  # one vertex cell each


def test_container_vtp_surrounds_the_particles(vtkrun):
    r = vtkXMLPolyDataReader()
    r.SetFileName(str(vtkrun / "container.vtp"))
    r.Update()
    s = r.GetOutput()
    assert s.GetNumberOfPolys() > 0
    x0, x1, y0, y1, z0, z1 = s.GetBounds()
    assert (x0, x1, y0, y1, z0) == pytest.approx((-5, 5, -3, 3, 0))
    top = read_dump(vtkrun / "snapshots" / "snap_000000.dump")["z"].max()
    assert z1 > top
