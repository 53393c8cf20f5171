# SPDX-License-Identifier: MIT
"""Shared fixtures: a small silo config, and a run directory made by the CLI."""
import os
import subprocess
from pathlib import Path

import pytest

import granflow

# A silo 12 d x 6 d with an orifice of 5 d and 1,500 particles: drains ~40 per tau.
SMALL = {"container.width": 12, "container.depth": 6, "container.orifice_diameter": 5,
         "packing.particles": 1500, "run.seed": 5}


@pytest.fixture
def small():
    return granflow.Config(SMALL)


def cli():
    exe = os.environ.get("GRANFLOW_CLI") or str(Path(granflow.library_path).parent / "granflow")
    if not os.path.exists(exe):
        pytest.fail(f"granflow CLI not found at {exe} (set GRANFLOW_CLI)")
    return exe


@pytest.fixture(scope="session")
def rundir(tmp_path_factory):
    """`granflow run` (6 tau, a snapshot every tau) + `granflow analyze` of the small silo."""
    d = tmp_path_factory.mktemp("run") / "silo"
    sets = [a for k, v in SMALL.items() for a in ("--set", f"{k}={v}")]
    subprocess.run([cli(), "run", "-q", *sets, "--set", "run.duration=6", "--set", "output.snapshot_interval=1",
                    "-o", str(d)], check=True)
    subprocess.run([cli(), "analyze", "--no-plots", str(d)], check=True, capture_output=True)
    return granflow.RunDir(d)
