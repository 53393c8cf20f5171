# SPDX-License-Identifier: MIT
"""granflow configuration by key name ("spot.radius"), over gf_config_set_key/get_key."""
import ctypes
import os

from ._lib import check, enc, lib


def keys():
    """Every key name, "section.name", in the order of the INI file."""
    buf = ctypes.create_string_buffer(128)
    out = []
    for i in range(lib.gf_config_key_count()):
        check(lib.gf_config_key_name(i, buf, len(buf)))
        out.append(buf.value.decode())
    return out


def _parse(text):
    """INI text -> int, float or str ("2.6" -> 2.6, "55000" -> 55000, "auto" and names stay text)."""
    for kind in (int, float):
        try:
            return kind(text)
        except ValueError:
            pass
    return text


def _text(value):
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, float):
        return repr(value)  # shortest round trip, as the library writes it
    return os.fspath(value) if isinstance(value, os.PathLike) else str(value)


class Config:
    """A granflow configuration: the papers' silo, changed key by key.

    >>> c = Config({"container.width": 12, "packing.particles": 1500})
    >>> c["spot.radius"] = 2.6
    >>> c["spot.radius"]
    2.6
    Values are checked as in an INI file (ValueError naming the key).
    """

    def __init__(self, values=None, path=None):
        self._ptr = lib.gf_config_create()
        if not self._ptr:
            raise MemoryError("gf_config_create")
        if path is not None:
            self.load(path)
        for key, value in (values or {}).items():
            self[key] = value

    def __del__(self):
        ptr, self._ptr = getattr(self, "_ptr", None), None
        if ptr:
            lib.gf_config_destroy(ptr)

    @property
    def handle(self):
        """The gf_config * for other ctypes calls."""
        return self._ptr

    def get_text(self, key):
        """The value of `key` as the INI file writes it."""
        buf = ctypes.create_string_buffer(1024 + 64)
        status = lib.gf_config_get_key(self._ptr, enc(key), buf, len(buf))
        if status != 0:
            raise KeyError(lib.gf_last_error().decode())
        return buf.value.decode()

    def __getitem__(self, key):
        return _parse(self.get_text(key))

    def __setitem__(self, key, value):
        if lib.gf_config_set_key(self._ptr, enc(key), enc(_text(value))) != 0:
            raise ValueError(lib.gf_last_error().decode())

    def __contains__(self, key):
        return key in keys()

    def keys(self):
        return keys()

    def to_dict(self):
        return {k: self[k] for k in keys()}

    def copy(self):
        other = Config()
        check(lib.gf_config_copy(other._ptr, self._ptr))
        return other

    def load(self, path):
        """Reads an INI file over the current values (error names file, line, key)."""
        if lib.gf_config_load(self._ptr, enc(path)) != 0:
            raise ValueError(lib.gf_last_error().decode())
        return self

    def save(self, path):
        check(lib.gf_config_save(self._ptr, enc(path)))

    def validate(self):
        """Resolves the `auto` keys and checks cross-key constraints."""
        if lib.gf_config_validate(self._ptr) != 0:
            raise ValueError(lib.gf_last_error().decode())
        return self

    def __repr__(self):
        changed = {k: self.get_text(k) for k in keys() if self.get_text(k) != _default(k)}
        return f"Config({changed!r})"


def _default(key):
    return lib.gf_config_key_default(keys().index(key)).decode()
