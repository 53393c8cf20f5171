# SPDX-License-Identifier: MIT
"""Loading libgranflow and declaring the C functions the package calls.

Only functions that take handles, strings, numbers and flat arrays are used,
so nothing here depends on the layout of a granflow struct.
"""
import ctypes
import ctypes.util
import os
from pathlib import Path

from .errors import GranflowError, from_status  # noqa: F401 (GranflowError: importable from here, as before)

_HERE = Path(__file__).resolve().parent


def _candidates():
    env = os.environ.get("GRANFLOW_LIB")
    if env:
        yield env
        return
    # An installed wheel or pip install: the library built with the package, beside it.
    yield str(_HERE / "libgranflow.so")
    # A source checkout: python/granflow -> ../../build/libgranflow.so
    yield str(_HERE.parent.parent / "build" / "libgranflow.so")
    # An installed prefix: <prefix>/lib/pythonX/... or <prefix>/share/granflow/python/granflow
    for up in (_HERE.parents[i] for i in range(1, min(5, len(_HERE.parents)))):
        yield str(up / "lib" / "libgranflow.so")
    found = ctypes.util.find_library("granflow")
    if found:
        yield found
    yield "libgranflow.so.0"


def _load():
    errors = []
    for path in _candidates():
        if "/" in path and not os.path.exists(path):
            continue
        try:
            return ctypes.CDLL(path), path
        except OSError as e:
            errors.append(f"{path}: {e}")
    raise ImportError("granflow: libgranflow.so not found (set GRANFLOW_LIB to its path); tried: "
                      + "; ".join(errors or ["nothing"]))


lib, path = _load()

c_char_p, c_size_t, c_int, c_double, c_void_p = (ctypes.c_char_p, ctypes.c_size_t, ctypes.c_int,
                                                 ctypes.c_double, ctypes.c_void_p)
_pd = ctypes.POINTER(ctypes.c_double)
_pi64 = ctypes.POINTER(ctypes.c_int64)
_pi32 = ctypes.POINTER(ctypes.c_int32)
_psize = ctypes.POINTER(ctypes.c_size_t)

_SIGNATURES = {
    # core
    "gf_status_str": (c_char_p, [c_int]),
    "gf_last_error": (c_char_p, []),
    "gf_version": (c_char_p, []),
    "gf_bytes_allocated": (c_size_t, []),
    "gf_warning_count": (c_size_t, []),
    "gf_warning": (c_char_p, [c_size_t]),
    "gf_warnings_clear": (None, []),
    # config by name
    "gf_config_create": (c_void_p, []),
    "gf_config_destroy": (None, [c_void_p]),
    "gf_config_copy": (c_int, [c_void_p, c_void_p]),
    "gf_config_set_key": (c_int, [c_void_p, c_char_p, c_char_p]),
    "gf_config_get_key": (c_int, [c_void_p, c_char_p, c_char_p, c_size_t]),
    "gf_config_key_count": (c_size_t, []),
    "gf_config_key_name": (c_int, [c_size_t, c_char_p, c_size_t]),
    "gf_config_key_doc": (c_char_p, [c_size_t]),
    "gf_config_key_default": (c_char_p, [c_size_t]),
    "gf_config_load": (c_int, [c_void_p, c_char_p]),
    "gf_config_save": (c_int, [c_void_p, c_char_p]),
    "gf_config_validate": (c_int, [c_void_p]),
    "gf_config_where": (c_int, [c_void_p, c_char_p, c_char_p, c_size_t]),
    # analysis options by name, and `granflow analyze`
    "gf_analysis_opts_create": (c_void_p, []),
    "gf_analysis_opts_destroy": (None, [c_void_p]),
    "gf_analysis_opts_copy": (c_int, [c_void_p, c_void_p]),
    "gf_analysis_opts_set": (c_int, [c_void_p, c_char_p]),
    "gf_analysis_opts_get": (c_int, [c_void_p, c_char_p, c_char_p, c_size_t]),
    "gf_analysis_opts_key_count": (c_size_t, []),
    "gf_analysis_opts_key_name": (c_int, [c_size_t, c_char_p, c_size_t]),
    "gf_analysis_opts_key_doc": (c_char_p, [c_size_t]),
    "gf_analysis_opts_key_default": (c_char_p, [c_size_t]),
    "gf_dem_analyze_outdir": (c_int, [c_char_p, c_char_p, c_size_t]),
    "gf_dem_analyze": (c_int, [c_char_p, c_void_p, c_void_p, c_char_p, c_char_p, ctypes.c_bool, c_void_p]),
    # simulation
    "gf_sim_create_from_config": (c_int, [c_void_p, c_void_p, ctypes.POINTER(c_void_p)]),
    "gf_sim_destroy": (None, [c_void_p]),
    "gf_sim_step": (c_int, [c_void_p]),
    "gf_sim_run": (c_int, [c_void_p, c_double, c_void_p]),
    "gf_sim_particle_count": (c_size_t, [c_void_p]),
    "gf_sim_copy_particles": (c_int, [c_void_p, _pi64, _pi32, _pd, _pd, c_size_t, _psize]),
    "gf_sim_exit_count": (c_size_t, [c_void_p]),
    "gf_sim_copy_exits": (c_int, [c_void_p, _pi64, _pd, c_size_t, _psize]),
    "gf_sim_stat": (c_double, [c_void_p, c_char_p]),
    "gf_sim_stat_count": (c_size_t, []),
    "gf_sim_stat_name": (c_char_p, [c_size_t]),
    "gf_sim_set_threads": (None, [c_void_p, c_int]),
    "gf_sim_save": (c_int, [c_void_p, c_char_p]),
    # notebooks: a simulation from arrays or a checkpoint, its state as files
    "gf_sim_create_from_arrays": (c_int, [c_void_p, c_size_t, _pd, _pd, _pi64, ctypes.POINTER(c_void_p)]),
    "gf_sim_load": (c_int, [c_void_p, c_char_p, ctypes.POINTER(c_void_p)]),
    "gf_sim_passes": (c_int, [c_void_p, _pi32, c_size_t]),
    "gf_sim_write_snapshot": (c_int, [c_void_p, c_char_p]),
    "gf_sim_write_vtk": (c_int, [c_void_p, c_char_p]),
    "gf_sim_write_run_dir": (c_int, [c_void_p, c_char_p, c_int]),
    # one frame of a dump (the C reader: plain or .gz, radius, pass)
    "gf_snapshot_read": (c_int, [c_char_p, ctypes.c_long, ctypes.POINTER(c_void_p)]),
    "gf_snapshot_destroy": (None, [c_void_p]),
    "gf_snapshot_count": (c_size_t, [c_void_p]),
    "gf_snapshot_frames": (c_size_t, [c_void_p]),
    "gf_snapshot_time": (c_double, [c_void_p]),
    "gf_snapshot_step": (ctypes.c_int64, [c_void_p]),
    "gf_snapshot_box": (c_int, [c_void_p, _pd, _pd]),
    "gf_snapshot_copy": (c_int, [c_void_p, _pi64, _pi32, _pd, _pd, _pi32, c_size_t, _psize]),
}

for _name, (_res, _args) in _SIGNATURES.items():
    _f = getattr(lib, _name)
    _f.restype = _res
    _f.argtypes = _args


def check(status):
    """Raises the GranflowError subclass of a non-zero gf_status (granflow.errors)."""
    if status != 0:
        raise from_status(status, lib.gf_status_str(status).decode(), lib.gf_last_error().decode())


def enc(text):
    """Text (or a path) as bytes for the library. A NUL would end the C string
    there, so "2\\0junk" would be read as 2 without a word: refused, as
    Python's own open() refuses one."""
    data = os.fsencode(text) if isinstance(text, os.PathLike) else str(text).encode()
    if b"\0" in data:
        raise ValueError("%r: a NUL character cannot be passed to granflow (the text would end there)" % (text,))
    return data


def warnings():
    """The library's warnings of this thread since the last clear_warnings(), oldest first."""
    return [lib.gf_warning(i).decode() for i in range(lib.gf_warning_count())]


def clear_warnings():
    lib.gf_warnings_clear()
