# SPDX-License-Identifier: MIT
"""One exception hierarchy for everything granflow raises.

Every error is a GranflowError, and also the builtin exception a Python
user expects, so `except FileNotFoundError` or `except ValueError` works as
it does with any other library:

    GranflowError                   base; .status (gf_status name or None), .message
    +-- GranflowValueError          ValueError: a bad argument or key value (GF_ERR_PARAM)
    |   +-- GranflowFormatError     a malformed data file (GF_ERR_FORMAT; names file and line)
    +-- GranflowKeyError            KeyError: reading an unknown key
    +-- GranflowOSError             OSError: a file that cannot be read or written (GF_ERR_IO)
    |   +-- GranflowFileNotFoundError   FileNotFoundError
    |   +-- GranflowFileExistsError     FileExistsError: a directory already holds a run (GF_ERR_EXISTS)
    +-- GranflowMemoryError         MemoryError (GF_ERR_NOMEM)
    +-- GranflowStateError          RuntimeError: a corrupt checkpoint, a silo that cannot drain,
                                    an interrupted call (GF_ERR_STATE, GF_ERR_INTERRUPTED)
"""
import errno
import os


class GranflowError(Exception):
    """Base of every granflow error. `message` is the library's text (it names
    the file, line and key where it knows them); `status` the gf_status name
    ("invalid parameter", "I/O error", ...) when the error came from the C
    library, else None."""

    def __init__(self, message, status=None):
        super().__init__(message)
        self.message = message
        self.status = status

    def __str__(self):
        return self.message


class GranflowValueError(GranflowError, ValueError):
    """A bad value: an argument, a key's value, an array (GF_ERR_PARAM); also
    a call on a closed Simulation, as on a closed file."""


class GranflowFormatError(GranflowValueError):
    """A data file that is malformed or truncated (GF_ERR_FORMAT)."""


class GranflowKeyError(GranflowError, KeyError):
    """An unknown key name."""


class GranflowOSError(GranflowError, OSError):
    """A file that cannot be opened, read, written or renamed (GF_ERR_IO).
    `filename` is the path when it is known."""

    def __init__(self, message, status=None, filename=None):
        super().__init__(message, status)
        if filename is not None:
            self.filename = os.fspath(filename)


class GranflowFileNotFoundError(GranflowOSError, FileNotFoundError):
    """A file or directory that does not exist."""

    def __init__(self, message, status=None, filename=None):
        super().__init__(message, status, filename)
        self.errno = errno.ENOENT


class GranflowFileExistsError(GranflowOSError, FileExistsError):
    """A directory that already holds a run (GF_ERR_EXISTS): force it, or use another."""


class GranflowMemoryError(GranflowError, MemoryError):
    """An allocation failed (GF_ERR_NOMEM)."""


class GranflowStateError(GranflowError, RuntimeError):
    """The call does not fit the state: a corrupt checkpoint, a silo that
    cannot drain, an interrupted call (GF_ERR_STATE, GF_ERR_INTERRUPTED)."""


# gf_status value -> class (the order of enum gf_status in granflow/core.h).
_BY_STATUS = {1: GranflowValueError, 2: GranflowOSError, 3: GranflowFormatError, 4: GranflowMemoryError,
              5: GranflowStateError, 6: GranflowStateError, 7: GranflowFileExistsError}
_ENOENT_TEXT = os.strerror(errno.ENOENT)  # the library's messages end in strerror(errno)


def from_status(code, status_name, message):
    """The exception for a non-zero gf_status `code` with the library's message."""
    cls = _BY_STATUS.get(code, GranflowStateError)
    if cls is GranflowOSError and _ENOENT_TEXT in message:
        cls = GranflowFileNotFoundError
    return cls(message, status_name)


def missing_file(path, what="file"):
    """The error for a path that does not exist (checked before calling the library)."""
    path = os.fspath(path)
    return GranflowFileNotFoundError(f"{path}: no such {what}", None, path)
