# SPDX-License-Identifier: MIT
"""One implementation of a struct of the library set and read by key name
("section.name"), shared by Config (gf_config_*) and AnalysisOptions
(gf_analysis_opts_*): the C functions differ, the Python side does not."""
import ctypes
import os

from ._lib import check, enc, lib
from .errors import GranflowKeyError, GranflowMemoryError, GranflowValueError


def key_names(prefix):
    """Every key name of the table of gf_PREFIX_key_count / _key_name, in table order."""
    count, name = getattr(lib, prefix + "_key_count"), getattr(lib, prefix + "_key_name")
    buf = ctypes.create_string_buffer(128)
    out = []
    for i in range(count()):
        check(name(i, buf, len(buf)))
        out.append(buf.value.decode())
    return out


def parse_number(text):
    """Text as the library writes it -> int, float or str ("2.6" -> 2.6, "55000" -> 55000, "auto" stays text)."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def to_text(value):
    """A Python value as the library reads it: on/off, shortest float round trip, paths, lists "a,b,c"."""
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float):
        return repr(value)  # shortest round trip, as the library writes it
    if isinstance(value, (list, tuple)):
        return ",".join(to_text(v) for v in value)
    if hasattr(value, "tolist"):  # a numpy array or number
        return to_text(value.tolist())
    return os.fspath(value) if isinstance(value, os.PathLike) else str(value)


class Keyed:
    """Base of a struct of the library behind a handle, by key name.

    A subclass sets PREFIX ("gf_config", "gf_analysis_opts"), whose C
    functions PREFIX_create, _destroy, _copy, _key_count, _key_name and
    _key_default are declared in _lib, and defines _get and _set over its
    getter and setter (their signatures differ).
    """

    PREFIX = None

    def __init__(self, values=None):
        self._ptr = self._fn("_create")()
        if not self._ptr:
            raise GranflowMemoryError(self.PREFIX + "_create: out of memory")
        for key, value in (values or {}).items():
            self[key] = value

    @classmethod
    def _fn(cls, suffix):
        return getattr(lib, cls.PREFIX + suffix)

    def __del__(self):
        ptr, self._ptr = getattr(self, "_ptr", None), None
        if ptr:
            self._fn("_destroy")(ptr)

    @property
    def handle(self):
        """The C pointer for other ctypes calls."""
        return self._ptr

    @classmethod
    def keys(cls):
        return key_names(cls.PREFIX)

    def _get(self, key, buf, size):
        raise NotImplementedError

    def _set(self, key, text):
        raise NotImplementedError

    def get_text(self, key):
        """The value of `key` as the library writes it (KeyError naming an unknown key)."""
        buf = ctypes.create_string_buffer(1024 + 64)
        if self._get(enc(key), buf, len(buf)) != 0:
            raise GranflowKeyError(lib.gf_last_error().decode())
        return buf.value.decode()

    def _parse(self, text):
        return parse_number(text)

    def __getitem__(self, key):
        return self._parse(self.get_text(key))

    def __setitem__(self, key, value):
        """Checked as in a file: GranflowValueError (a ValueError) naming the key (an unknown key too), the value unchanged."""
        if self._set(enc(key), enc(to_text(value))) != 0:
            raise GranflowValueError(lib.gf_last_error().decode(), "invalid parameter")

    def __contains__(self, key):
        return key in self.keys()

    def to_dict(self):
        return {k: self[k] for k in self.keys()}

    def copy(self):
        other = type(self)()
        check(self._fn("_copy")(other._ptr, self._ptr))
        return other

    def _default(self, key):
        return self._fn("_key_default")(self.keys().index(key)).decode()

    def __repr__(self):
        changed = {k: self.get_text(k) for k in self.keys() if self.get_text(k) != self._default(k)}
        return f"{type(self).__name__}({changed!r})"
