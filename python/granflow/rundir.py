# SPDX-License-Identifier: MIT
"""Reading what `granflow run`, `analyze`, `render`, `compare` and `report` write."""
import json
import os
import stat
from pathlib import Path

import numpy as np

from .config import Config
from .errors import GranflowFileNotFoundError
from .snapshot import read_snapshot


def open_run_file(path):
    """Opens a file a run wrote, for reading text, if it is a regular file: a
    FIFO (opened without waiting for a writer), a device such as /dev/zero
    or a directory in its place raises OSError naming it, as the library does."""
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        mode = os.fstat(fd).st_mode
        if not stat.S_ISREG(mode):
            kind = ("a FIFO" if stat.S_ISFIFO(mode) else "a character device" if stat.S_ISCHR(mode)
                    else "a directory" if stat.S_ISDIR(mode) else "not a file")
            raise OSError(f"{path}: not a regular file ({kind})")
        os.set_blocking(fd, True)
        return os.fdopen(fd, "r")
    except BaseException:
        os.close(fd)
        raise


def read_csv(path):
    """A granflow CSV file (header line, then numbers; `nan` allowed) as a dict
    of column name -> float64 numpy array, in file order."""
    path = Path(path)
    with open_run_file(path) as f:
        header = f.readline().strip().split(",")
        data = np.loadtxt(f, delimiter=",", ndmin=2)
    if data.size == 0:
        data = np.empty((0, len(header)))
    if data.shape[1] != len(header):
        raise ValueError(f"{path}: {data.shape[1]} columns of numbers, {len(header)} names in the header")
    return {name: data[:, i].copy() for i, name in enumerate(header)}


def read_json(path):
    with open_run_file(path) as f:
        return json.load(f)


class RunDir:
    """A run directory: config.ini, summary.json, exits.csv, snapshots/, and,
    when made, analysis/ (summary.json, CSV), render/ (PNG) and report.html."""

    def __init__(self, path):
        self.path = Path(path)
        if not (self.path / "config.ini").exists():
            raise GranflowFileNotFoundError(f"{self.path}: not a granflow run directory (no config.ini)", None,
                                            self.path / "config.ini")

    @property
    def config(self):
        return Config(path=self.path / "config.ini")

    @property
    def summary(self):
        """summary.json of the run (counters, status, wall time)."""
        return read_json(self.path / "summary.json")

    def exits(self):
        """exits.csv: id, time (tau), x, y (d) of every particle that left."""
        t = read_csv(self.path / "exits.csv")
        t["id"] = t["id"].astype(np.int64)
        return t

    def snapshots(self):
        """Paths of the snapshots (snap_*.dump, or .dump.gz when compressed), in time order."""
        d = self.path / "snapshots"
        return sorted(list(d.glob("snap_*.dump")) + list(d.glob("snap_*.dump.gz")))

    def snapshot(self, k):
        """Snapshot k (index in snapshots()) as read_snapshot returns it (a Snapshot)."""
        return read_snapshot(self.snapshots()[k])

    @property
    def analysis(self):
        """analysis/summary.json (the headline numbers of `granflow analyze`), {} if not analysed."""
        p = self.path / "analysis" / "summary.json"
        return read_json(p) if p.exists() else {}

    def analyze(self, options=None, name=None, plots=False):
        """Runs `granflow analyze` on this run with `options` (an AnalysisOptions
        or a dict, e.g. {"window.t0": 2}) into analysis/; returns self.analysis."""
        from .analysis import analyze  # analysis imports this module
        return analyze(self.path, options, name=name, outdir=self.path / "analysis", plots=plots)

    def tables(self):
        """Names of the analysis CSV tables (outflow, velocity_field, ...)."""
        return sorted(p.stem for p in (self.path / "analysis").glob("*.csv"))

    def table(self, name):
        """analysis/NAME.csv as a dict of numpy columns."""
        return read_csv(self.path / "analysis" / f"{name}.csv")

    def pictures(self):
        """Every PNG the analysis and render steps drew."""
        return sorted(self.path.glob("analysis/*.png")) + sorted(self.path.glob("render/*.png"))

    def __repr__(self):
        return f"RunDir({os.fspath(self.path)!r})"
