# SPDX-License-Identifier: MIT
"""granflow configuration by key name ("spot.radius"), over gf_config_set_key/get_key."""
import ctypes

from ._keyed import Keyed, key_names
from ._lib import check, enc, lib
from .errors import GranflowKeyError


def keys():
    """Every key name, "section.name", in the order of the INI file."""
    return key_names("gf_config")


class Config(Keyed):
    """A granflow configuration: the papers' silo, changed key by key.

    >>> c = Config({"container.width": 12, "packing.particles": 1500})
    >>> c["spot.radius"] = 2.6
    >>> c["spot.radius"]
    2.6
    Values are checked as in an INI file (ValueError naming the key).
    """

    PREFIX = "gf_config"

    def __init__(self, values=None, path=None):
        super().__init__()
        if path is not None:
            self.load(path)
        for key, value in (values or {}).items():
            self[key] = value

    def _get(self, key, buf, size):
        return lib.gf_config_get_key(self._ptr, key, buf, size)

    def _set(self, key, text):
        return lib.gf_config_set_key(self._ptr, key, text)

    def load(self, path):
        """Reads an INI file over the current values: a bad value raises
        GranflowValueError (a ValueError) naming file, line and key; a missing
        file GranflowFileNotFoundError (a FileNotFoundError)."""
        check(lib.gf_config_load(self._ptr, enc(path)))
        return self

    def where(self, key):
        """Where `key` got its value: "FILE:LINE", "gf_config_set_key" (set from
        Python), or "default"; validation errors quote the same places."""
        buf = ctypes.create_string_buffer(4200)
        if lib.gf_config_where(self._ptr, enc(key), buf, len(buf)) != 0:
            raise GranflowKeyError(lib.gf_last_error().decode())
        return buf.value.decode()

    def save(self, path):
        check(lib.gf_config_save(self._ptr, enc(path)))

    def validate(self):
        """Resolves the `auto` keys and checks cross-key constraints (GranflowValueError)."""
        check(lib.gf_config_validate(self._ptr))
        return self
