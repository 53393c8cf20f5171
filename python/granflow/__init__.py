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

The library is found via $GRANFLOW_LIB, a source checkout's build/, an
installed prefix, or the system's library path; see docs/python.md.
"""
from ._lib import GranflowError, clear_warnings, warnings
from ._lib import lib as _lib
from ._lib import path as library_path
from .analysis import AnalysisOptions, analysis_keys, analyze
from .config import Config, keys
from .rundir import RunDir, read_csv, read_json, read_snapshot
from .sim import Simulation

__version__ = _lib.gf_version().decode()

__all__ = ["AnalysisOptions", "Config", "GranflowError", "RunDir", "Simulation", "analysis_keys", "analyze",
           "clear_warnings", "keys", "library_path", "read_csv", "read_json", "read_snapshot", "warnings",
           "__version__"]
