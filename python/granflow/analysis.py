# SPDX-License-Identifier: MIT
"""The analysis options by key name ("window.t0", "velocity.heights"), over
gf_analysis_opts_set/get, and `granflow analyze` as a call (gf_dem_analyze)."""
import ctypes
import os
from pathlib import Path

from ._keyed import Keyed, key_names, parse_number
from ._lib import check, enc, lib
from .rundir import read_json


def analysis_keys():
    """Every analysis option, "section.name", in the order of docs/analysis.md."""
    return key_names("gf_analysis_opts")


class AnalysisOptions(Keyed):
    """The options of `granflow analyze` (regions, heights, the window), the
    papers' values by default, set and read by name as a Config is.

    >>> o = AnalysisOptions({"window.t0": 24, "velocity.heights": [10, 20, 30]})
    >>> o["velocity.heights"]
    [10, 20, 30]
    >>> o["window.t1"]
    'auto'
    A list option reads back as a list when it holds two values or more.
    Values are checked as by `granflow analyze --set` (ValueError naming the key).
    """

    PREFIX = "gf_analysis_opts"

    def _get(self, key, buf, size):
        return lib.gf_analysis_opts_get(self._ptr, key, buf, size)

    def _set(self, key, text):
        return lib.gf_analysis_opts_set(self._ptr, key + b"=" + text)

    def _parse(self, text):
        if "," in text:
            return [parse_number(v) for v in text.split(",")]
        return parse_number(text)


def analyze(path, options=None, name=None, outdir=None, plots=False):
    """`granflow analyze [NAME] PATH`: measures a run directory, a directory of
    LAMMPS dumps or one dump with `options` (an AnalysisOptions or a dict of
    option -> value; None: the defaults) and writes the CSV tables (and, with
    `plots`, the PNG plots) into `outdir` (default PATH/analysis). Returns the
    headline numbers, summary.json of `outdir`, as a dict; `name` (e.g.
    "velocity") runs one measurement only. A failure raises GranflowError."""
    opts = options if isinstance(options, AnalysisOptions) else AnalysisOptions(options)
    path = os.fspath(path)
    if outdir is None:
        buf = ctypes.create_string_buffer(len(enc(path)) + 64)
        check(lib.gf_dem_analyze_outdir(enc(path), buf, len(buf)))
        outdir = os.fsdecode(buf.value)
    check(lib.gf_dem_analyze(enc(path), None, opts.handle, None if name is None else enc(name), enc(outdir),
                             bool(plots), None))
    return read_json(Path(outdir) / "summary.json")
