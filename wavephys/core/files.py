"""Writing files so that an interruption loses nothing and leaves nothing half-written.

Every file the library writes goes through :func:`atomic_path`: the content is written to
a temporary file in the same folder and renamed over the target only when complete
(``os.replace`` is atomic on one file system), so a reader sees the old file or the new
one, never a truncated one that looks valid. :func:`output_file` and
:func:`output_folder` check a destination before any long work starts.
"""

from __future__ import annotations

import contextlib
import os
import tempfile
from pathlib import Path

from wavephys.core.inputs import describe

__internal__ = True  # tooling for the library's own modules (users call the Grid's methods)
__all__ = ["atomic_path", "output_file", "output_folder"]


def _new_file_mode() -> int:
    """The mode ``open(path, "w")`` would give a new file here: 0666 less the umask."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


_NEW_FILE_MODE = _new_file_mode()


def _as_path(name: str, path) -> Path:
    if not isinstance(path, (str, os.PathLike)) or (isinstance(path, str) and not path.strip()):
        raise TypeError(f"{name} must be a file system path (str or pathlib.Path), got {describe(path)}")
    return Path(path)


def output_file(path, name: str = "path", suffixes: tuple[str, ...] = ()) -> Path:
    """Check that a file can be written at ``path``: its folder exists and is writable,
    the path is not a folder, and its suffix is one of ``suffixes`` (if given).

    Parameters
    ----------
    path : str or os.PathLike
        Where the file goes (TypeError naming ``name`` for another kind).
    name : str
        The parameter's name in messages.
    suffixes : tuple of str
        Allowed suffixes, lower case with the dot (``(".png",)``); empty: any.

    Returns
    -------
    pathlib.Path
        ``path``; ValueError naming ``name`` for a wrong suffix, a folder, a missing or read-only folder.
    """
    p = _as_path(name, path)
    if suffixes and p.suffix.lower() not in suffixes:
        raise ValueError(f"{name} must end in {' or '.join(suffixes)}, got {str(p)!r}")
    if p.is_dir():
        raise ValueError(f"{name} {str(p)!r} is a folder, not a file")
    parent = p.parent if str(p.parent) else Path(".")
    if not parent.is_dir():
        raise ValueError(f"{name}: the folder {str(parent)!r} does not exist (it is not created for you)")
    if not os.access(parent, os.W_OK):
        raise ValueError(f"{name}: the folder {str(parent)!r} is not writable")
    return p


def output_folder(path, name: str = "out_dir") -> Path:
    """Check (and create, one level) an output folder: its parent must exist and be writable.

    Parameters
    ----------
    path : str or os.PathLike
        The folder (TypeError naming ``name`` for another kind).
    name : str
        The parameter's name in messages.

    Returns
    -------
    pathlib.Path
        The folder, existing and writable; ValueError naming ``name`` where it cannot be.
    """
    p = _as_path(name, path)
    if p.exists() and not p.is_dir():
        raise ValueError(f"{name} {str(p)!r} exists and is not a folder")
    parent = p.parent if str(p.parent) else Path(".")
    if not p.exists():
        if not parent.is_dir():
            raise ValueError(f"{name}: the folder {str(parent)!r} does not exist (only {p.name!r} would be created)")
        if not os.access(parent, os.W_OK):
            raise ValueError(f"{name}: cannot create {str(p)!r}: {str(parent)!r} is not writable")
        p.mkdir()
    elif not os.access(p, os.W_OK):
        raise ValueError(f"{name}: the folder {str(p)!r} is not writable")
    return p


@contextlib.contextmanager
def atomic_path(path):
    """Yield a temporary path beside ``path``; on success it replaces ``path`` atomically,
    on any error (or interruption) it is removed and ``path`` is left as it was.

    Parameters
    ----------
    path : str or os.PathLike
        The file to write.

    Yields
    ------
    pathlib.Path
        A fresh file beside ``path`` (same suffix, ``.part`` added) to write to.
    """
    target = Path(path)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.stem}.", suffix=target.suffix + ".part", dir=target.parent or ".")
    os.close(fd)
    tmp = Path(tmp)
    try:
        yield tmp
        os.chmod(tmp, _NEW_FILE_MODE)  # mkstemp makes it private (0600); a written file gets the usual mode
        os.replace(tmp, target)
    finally:
        with contextlib.suppress(FileNotFoundError):
            tmp.unlink()
