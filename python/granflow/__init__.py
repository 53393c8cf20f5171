# SPDX-License-Identifier: MIT
"""granflow from Python: configs and analysis options by key name,
simulations step by step with numpy arrays, `granflow analyze` as a call, and
the files of run directories (ctypes over libgranflow).

    import granflow
    sim = granflow.Simulation({"container.width": 12, "packing.particles": 1500})
    sim.run(until=5.0)
    exits = sim.exits()                 # id, time, x, y arrays
    run = granflow.RunDir("runs/silo")  # what `granflow run` + `analyze` wrote
    run.analysis["flow_rate"], run.table("outflow")["exited"]
    run.analyze({"window.t0": 2, "velocity.heights": [10, 20]})  # granflow analyze --set ...
    sim = granflow.Simulation(cfg, positions=xyz, radii=r)   # your own particles
    sim.write_run_dir("runs/mine"); sim = granflow.load("runs/mine")
    pandas.DataFrame(sim.particle_table()), granflow.read_snapshot("snap.dump.gz").particles

Errors are granflow.GranflowError, each also the builtin a user expects
(FileNotFoundError, ValueError, ...): see granflow.errors.

The library is found via $GRANFLOW_LIB, the copy installed with the package
(pip, wheel), a source checkout's build/, an installed prefix, or the
system's library path; see docs/python.md.
"""
from ._lib import clear_warnings, warnings
from ._lib import lib as _lib
from ._lib import path as library_path
from .analysis import AnalysisOptions, analysis_keys, analyze
from .config import Config, keys
from .errors import (GranflowError, GranflowFileExistsError, GranflowFileNotFoundError, GranflowFormatError,
                     GranflowKeyError, GranflowMemoryError, GranflowOSError, GranflowStateError, GranflowValueError)
from .rundir import RunDir, read_csv, read_json
from .sim import Simulation, load
from .snapshot import PARTICLE_DTYPE, SNAPSHOT_DTYPE, Snapshot, read_snapshot

__version__ = _lib.gf_version().decode()

__all__ = ["AnalysisOptions", "Config", "GranflowError", "GranflowFileExistsError", "GranflowFileNotFoundError",
           "GranflowFormatError", "GranflowKeyError", "GranflowMemoryError", "GranflowOSError", "GranflowStateError",
           "GranflowValueError", "PARTICLE_DTYPE", "RunDir", "SNAPSHOT_DTYPE", "Simulation", "Snapshot",
           "analysis_keys", "analyze", "clear_warnings", "keys", "library_path", "load", "read_csv", "read_json",
           "read_snapshot", "warnings", "__version__"]
