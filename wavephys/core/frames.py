"""Frames read back from files: OpenEXR, 16-bit PNG, ``.npy`` and ``.npz`` height images.

Engines export a water surface as one image per frame. :func:`read_frames` turns a folder,
a glob pattern or a list of such files into a time series of heights ``(n_t, n_y, n_x)``
in the grid convention (array row 0 = the lowest y; image files store the top row first,
so their rows are flipped back), with what the files say about themselves: the grid
spacing (an EXR header's ``length`` or ``dx``, a PNG's JSON sidecar), the time between
frames (``dt``, or the ``time`` of each frame), and the units of the values. Reading files
is not optics: the harness builds its records on this module, and
:func:`optics.rendering.textures.load_exr` is :func:`read_exr`.

Nothing here guesses: a file whose heights could sit in more than one channel, frames of
different shapes or formats, non-uniform times, an 8-bit PNG (256 levels cannot hold a
wave record), metadata that contradicts an argument, or non-finite heights are refused
with an error that names the argument and the file.
"""

from __future__ import annotations

import glob as _glob
import json
import math
import os
import re
import zipfile
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from typing import Optional

from wavephys.core.inputs import check_array, check_choice, check_int, check_scalar, describe

__all__ = ["FRAME_SUFFIXES", "UNITS", "AXES", "Frames", "read_exr", "read_frames", "read_map", "resolve_axes"]

FRAME_SUFFIXES = (".exr", ".png", ".npy", ".npz")
"""The file types :func:`read_frames` reads."""

UNITS = {"m": 1.0, "cm": 0.01, "mm": 0.001}
"""Height units a file may declare (its ``units`` entry), with their size in metres."""

_NPZ_HEIGHTS = ("eta", "heights", "height", "frames")
_PNG_MODES = {"L": "8-bit grayscale", "RGB": "8-bit RGB", "RGBA": "8-bit RGBA", "P": "palette", "1": "1-bit",
              "LA": "8-bit grayscale with alpha"}

AXES = ("tyx", "txy", "yxt", "xyt", "ytx", "xty")
"""The layouts :meth:`Record.from_array` takes: t (time), y (rows), x (columns) in array order."""

def resolve_axes(shape, axes: Optional[str]) -> str:
    """The layout of a 3-D array: ``axes`` when given, else inferred only where one reading is possible.

    Parameters
    ----------
    shape : tuple of int
        The array's shape (three axes).
    axes : str or None
        One of :data:`AXES`, or None to infer: only ``(n_t, n, n)`` with n_t ≠ n is unambiguous.

    Returns
    -------
    str
        The layout, one of :data:`AXES`.

    Raises
    ------
    ValueError
        When ``axes`` is not a layout, or is None and the shape can be read more than one way.
    """
    if (not isinstance(shape, tuple) or len(shape) != 3
            or not all(isinstance(s, (int, np.integer)) and not isinstance(s, bool) and s > 0 for s in shape)):
        raise TypeError(f"shape must be a tuple of three positive ints (an array's shape), got {describe(shape)}")
    if axes is not None:
        return check_choice("axes", axes, AXES)
    a, b, c = shape
    if b == c and a != b:
        return "tyx"
    if a == b == c:
        raise ValueError(f"axes: a cube of shape {tuple(shape)} could hold time on any axis; say which with "
                         f"axes='tyx' (time first) or axes='yxt' (time last)")
    if a == b:
        raise ValueError(f"axes: shape {tuple(shape)} looks like time last (n, n, n_t), the layout many engines "
                         f"export; say axes='yxt' to read it so (or axes='tyx' if it really is {a} frames of "
                         f"{b} x {c})")
    raise ValueError(f"axes: shape {tuple(shape)} has no two equal axes, so the time axis cannot be told from it; "
                     f"say which with axes='tyx', 'yxt', ... (t = time, y = rows, x = columns)")


def _to_tyx(data: np.ndarray, axes: str) -> np.ndarray:
    return np.transpose(data, [axes.index(c) for c in "tyx"])


@dataclass(frozen=True)
class Frames:
    """A time series of height images read from files.

    Attributes
    ----------
    heights : numpy.ndarray (n_t, n_y, n_x)
        Heights in metres (converted from the files' declared units), float64, grid convention.
    dx : float or None
        Grid spacing, m, from the files' metadata (None when they do not say).
    dt : float or None
        Time between frames, s, from the files' metadata (None when they do not say).
    units : str
        The units the files declared (``"m"``, ``"cm"``, ``"mm"``), or ``"unknown"`` (values taken as metres).
    paths : tuple of str
        The files, in time order.
    metadata : dict
        The first file's own entries (EXR header attributes, JSON sidecar, npz scalars).
    """

    heights: np.ndarray
    dx: float | None
    dt: float | None
    units: str
    paths: tuple
    metadata: dict = field(default_factory=dict)


def read_exr(path) -> tuple[dict, dict]:
    """(channels, attributes) of an OpenEXR file, in the grid convention (rows flipped back).

    Parameters
    ----------
    path : str or os.PathLike
        An existing OpenEXR file.

    Returns
    -------
    channels : dict of str to numpy.ndarray (ny, nx)
        The channels by name, row 0 = the lowest y.
    attributes : dict
        The header entries with str, int or float values.

    Raises
    ------
    ValueError
        When ``path`` is not a file, or not a readable OpenEXR image (corrupt or truncated).
    """
    return _read_exr(path, "path")


def _read_exr(path, name: str) -> tuple[dict, dict]:
    """:func:`read_exr`, its errors naming the caller's argument ``name``."""
    import OpenEXR

    path = _path(name, path)
    if not path.is_file():
        raise ValueError(f"{name} {str(path)!r} is not a file")
    try:
        with OpenEXR.File(str(path), separate_channels=True) as f:
            channels = {c_name: np.flipud(np.asarray(c.pixels)) for c_name, c in f.channels().items()}
            attributes = {k: v for k, v in f.header().items() if isinstance(v, (str, int, float))}
    except (RuntimeError, OSError) as exc:
        raise ValueError(f"{name} {str(path)!r} is not a readable OpenEXR image ({exc})") from None
    return channels, attributes


def _path(name, value) -> Path:
    if not isinstance(value, (str, os.PathLike)) or (isinstance(value, str) and not value.strip()):
        raise TypeError(f"{name} must be a file system path (str or pathlib.Path), got {describe(value)}")
    return Path(value)


def _natural(path: Path):
    """Sort key that puts frame_2 before frame_10."""
    return [int(p) if p.isdigit() else p for p in re.split(r"(\d+)", path.name)]


def _expand(source) -> list[Path]:
    """The frame files named by ``source``: a folder, a glob pattern, one file, or a list of files."""
    if isinstance(source, (list, tuple)):
        if not source:
            raise ValueError("source: the list of frame files is empty")
        paths = [_path(f"source[{i}]", p) for i, p in enumerate(source)]
        for i, p in enumerate(paths):
            if not p.is_file():
                raise ValueError(f"source[{i}]: {str(p)!r} is not a file")
        return paths
    p = _path("source", source)
    if p.is_dir():
        paths = sorted((q for q in p.iterdir() if q.is_file() and q.suffix.lower() in FRAME_SUFFIXES
                        and not q.name.startswith(".")), key=_natural)
        if not paths:
            raise ValueError(f"source: the folder {str(p)!r} holds no frames ({', '.join(FRAME_SUFFIXES)} files)")
        kinds = {q.suffix.lower() for q in paths}
        if len(kinds) > 1:
            raise ValueError(f"source: the folder {str(p)!r} mixes {', '.join(sorted(kinds))} files; name the ones "
                             f"to read with a pattern such as {str(p / ('*' + sorted(kinds)[0]))!r}")
        return paths
    if p.is_file():
        return [p]
    if any(c in str(p) for c in "*?["):
        paths = sorted((Path(q) for q in _glob.glob(str(p)) if Path(q).is_file()), key=_natural)
        if not paths:
            raise ValueError(f"source: the pattern {str(p)!r} matches no files")
        return paths
    raise ValueError(f"source: {str(p)!r} is not a file, a folder or a glob pattern that matches files")


def _units(name: str, value, where: str) -> float:
    if value is None:
        return 1.0
    if not isinstance(value, str) or value.strip() not in UNITS:
        raise ValueError(f"{name}: {where} declares units {value!r}; heights in {', '.join(UNITS)} can be read "
                         f"(convert the file, or give heights in metres)")
    return UNITS[value.strip()]


def _exr_frame(path: Path, channel):
    channels, attrs = _read_exr(path, "source")
    if channel is not None:
        if channel not in channels:
            raise ValueError(f"channel: {str(path)!r} has no channel {channel!r} (it has {', '.join(channels)})")
        name = channel
    elif "Y" in channels:
        name = "Y"
    elif len(channels) == 1:
        (name,) = channels
    else:
        raise ValueError(f"channel: {str(path)!r} has channels {', '.join(channels)}; name the one that holds the "
                         f"heights (channel='G', or --channel G)")
    return np.asarray(channels[name], np.float64), dict(attrs, channel=name)


def _png_frame(path: Path, channel, png_range=None):
    from PIL import Image

    try:
        with Image.open(path) as im:
            mode = im.mode
            data = np.asarray(im)
    except (OSError, ValueError) as exc:
        raise ValueError(f"source: {str(path)!r} is not a readable PNG ({exc})") from None
    if data.ndim != 2 or data.dtype not in (np.uint16, np.int32):
        raise ValueError(f"source: {str(path)!r} is a {_PNG_MODES.get(mode, mode)} PNG (mode {mode}); heights need a 16-bit grayscale PNG "
                         f"(8 bits hold 256 levels: too coarse for a wave record)")
    if channel is not None:
        raise ValueError(f"channel: {str(path)!r} is a grayscale PNG with one channel; leave channel unset")
    meta = {}
    sidecar = path.with_suffix(".json")
    if sidecar.is_file():
        try:
            meta = json.loads(sidecar.read_text(encoding="utf-8"))
        except (UnicodeDecodeError, json.JSONDecodeError) as exc:
            raise ValueError(f"source: the sidecar {str(sidecar)!r} of {str(path)!r} is not JSON ({exc})") from None
        if not isinstance(meta, dict):
            raise ValueError(f"source: the sidecar {str(sidecar)!r} must hold a JSON object")
    q = np.flipud(data).astype(np.float64) / 65535.0
    stated = "offset" in meta and "amplitude" in meta
    if png_range is not None:
        if stated and (meta["offset"], meta["amplitude"]) != tuple(png_range):
            raise ValueError(f"png_range: {tuple(png_range)} was given but the sidecar {str(sidecar)!r} says offset "
                             f"{meta['offset']!r} and amplitude {meta['amplitude']!r}; leave png_range out to use it")
        meta = dict(meta, offset=float(png_range[0]), amplitude=float(png_range[1]), units=meta.get("units", "m"))
    elif not stated:
        said = f"its sidecar {str(sidecar)!r} has no offset and amplitude" if sidecar.is_file() else \
            f"it has no JSON sidecar ({sidecar.name} with offset and amplitude in metres)"
        raise ValueError(f"source: {str(path)!r} is a 16-bit PNG and {said}: its levels do not say metres. Give "
                         f"heights = offset + amplitude × level/65535 with png_range=(offset, amplitude) "
                         f"(--png-range OFFSET,AMPLITUDE), or write the sidecar")
    offset, amplitude = meta["offset"], meta["amplitude"]
    for key, value in (("offset", offset), ("amplitude", amplitude)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ValueError(f"source: {key} in {str(sidecar)!r} must be a finite number, got {value!r}")
    if amplitude <= 0:
        raise ValueError(f"source: the amplitude of {str(path)!r} must be > 0 (m per full level range), got "
                         f"{amplitude!r}")
    return offset + amplitude * q, meta


def _np_frames(path: Path):
    try:
        if path.suffix.lower() == ".npy":
            data, meta = np.load(path, allow_pickle=False), {}
        else:
            with np.load(path, allow_pickle=False) as f:
                keys = [k for k in _NPZ_HEIGHTS if k in f.files]
                if not keys:
                    raise ValueError(f"source: {str(path)!r} holds {', '.join(f.files) or 'nothing'}; a record's "
                                     f"heights must be under one of {', '.join(_NPZ_HEIGHTS)}")
                data = f[keys[0]]
                meta = {k: f[k].item() for k in f.files if k != keys[0] and f[k].ndim == 0}
                meta.update({k: f[k] for k in f.files if k != keys[0] and f[k].ndim > 0})
    except (OSError, EOFError, zipfile.BadZipFile) as exc:
        raise ValueError(f"source: {str(path)!r} is not a readable numpy file ({type(exc).__name__}: {exc}): a "
                         f"damaged or partly written file?") from None
    except ValueError as exc:
        if str(exc).startswith("source:"):
            raise
        raise ValueError(f"source: {str(path)!r} is not a readable numpy file ({exc})") from None
    if not np.issubdtype(data.dtype, np.number) or np.iscomplexobj(data):
        raise ValueError(f"source: {str(path)!r} holds {data.dtype} values, not real heights")
    return np.asarray(data, np.float64), meta


def _meta_number(meta: dict, key: str, where: str):
    value = meta.get(key)
    if value is None or (isinstance(value, str) and not value.strip()):
        return None
    if isinstance(value, np.ndarray):
        return None
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise ValueError(f"source: {where} has {key} = {value!r}, not a number")
    value = float(value)
    if not math.isfinite(value) or value <= 0 and key != "time":
        raise ValueError(f"source: {where} has {key} = {value!r}; it must be a finite number > 0")
    return value


def _agree(name: str, given, found, where: str):
    """The argument if given (it must match the file's), else the file's value."""
    if given is not None:
        given = check_scalar(name, given, lo=0.0, lo_open=True)
        if found is not None and not math.isclose(given, found, rel_tol=1e-5):
            raise ValueError(f"{name}: {given:g} was given but {where} says {found:g}; leave {name} out to use "
                             f"the file's, or fix the file")
        return float(given)
    return found


def _times(metas, paths):
    times = [_meta_number(m, "time", str(p)) for m, p in zip(metas, paths)]
    if len(times) < 2 or any(t is None for t in times):
        return None
    steps = np.diff(times)
    if np.any(steps <= 0) or not np.allclose(steps, steps.mean(), rtol=1e-4, atol=1e-9):
        raise ValueError(f"source: the frames' times are not uniformly spaced (steps {steps.min():.6g} to "
                         f"{steps.max():.6g} s); a record needs frames at equal time steps")
    return float(steps.mean())


def read_frames(source, *, channel: str | None = None, dx: float | None = None, dt: float | None = None,
                max_frames: int = 65536, axes: Optional[str] = None, png_range=None) -> Frames:
    """Read a time series of height images: one frame per file, or one ``.npy``/``.npz`` array of frames.

    Parameters
    ----------
    source : str, os.PathLike or list of them
        A folder (every ``.exr``, ``.png``, ``.npy`` or ``.npz`` file in it, of one kind, in natural order:
        frame_2 before frame_10), a glob pattern (``"out/height_*.exr"``), a list of files in time order, or
        one file. One ``.npy``/``.npz`` file may hold all frames as an array ``(n_t, n_y, n_x)`` (in an
        ``.npz`` under ``eta``, ``heights``, ``height`` or ``frames``, with scalar ``dx``, ``dt``, ``units``
        beside it); an image file is one frame.
    channel : str, optional, keyword-only
        The EXR channel holding the heights (default: ``Y``, or the only channel; a file with several channels
        and no ``Y`` needs it).
    dx : float, optional, keyword-only
        Grid spacing, m, > 0, when the files do not say (an EXR's ``dx`` or ``length`` entry, a PNG sidecar's
        ``length``); if both do, they must agree.
    dt : float, optional, keyword-only
        Time between frames, s, > 0, when the files do not say (``dt``, or each frame's ``time``); if both do,
        they must agree.
    max_frames : int, optional, keyword-only
        Most frames read, >= 1 (default 65536): a guard against a pattern that matches far more than meant.
    axes : str, optional, keyword-only
        The layout of one ``.npy``/``.npz`` array of frames, one of :data:`AXES` (``"yxt"``: time last). Needed
        when the shape can be read more than one way (time last, a cube), unless the ``.npz`` says (``axes``
        beside the heights, as ``Record.save`` writes); refused for image files, which are one frame each.
    png_range : (float, float), optional, keyword-only
        For 16-bit PNGs: (offset, amplitude), m: heights = offset + amplitude × level/65535. Needed when a PNG has
        no JSON sidecar saying them; a sidecar that says otherwise is refused, never overridden. Without either,
        such PNGs are refused: their levels do not say metres.

    Returns
    -------
    Frames
        The heights (m), what the files say of dx, dt and units, the paths in order and the first file's entries.

    Raises
    ------
    ValueError
        When nothing matches, frames differ in shape or kind, a channel is ambiguous, the metadata contradicts
        ``dx``/``dt`` or is not uniform, a file is unreadable, 8-bit, or holds non-finite heights.
    TypeError
        When ``source`` is not a path or a list of paths.

    Examples
    --------
    >>> frames = read_frames("export/water_height_*.exr")          # doctest: +SKIP
    >>> frames.heights.shape, frames.dx, frames.dt                  # doctest: +SKIP
    ((256, 128, 128), 0.0625, 0.016666666666666666)
    """
    max_frames = check_int("max_frames", max_frames, lo=1)
    if png_range is not None:
        check_array("png_range", png_range, ndim=1, shape_tail=(2,))
    if channel is not None and (not isinstance(channel, str) or not channel):
        raise TypeError(f"channel must be a non-empty string (an EXR channel name), got {describe(channel)}")
    paths = _expand(source)
    if len(paths) > max_frames:
        raise ValueError(f"source matches {len(paths)} files, more than max_frames = {max_frames}")
    kinds = {p.suffix.lower() for p in paths}
    if len(kinds) > 1 or not kinds <= set(FRAME_SUFFIXES):
        raise ValueError(f"source: frames must be files of one kind ({', '.join(FRAME_SUFFIXES)}), got "
                         f"{', '.join(sorted(kinds))}")
    (kind,) = kinds
    if axes is not None:
        check_choice("axes", axes, AXES)
        if not (kind in (".npy", ".npz") and len(paths) == 1):
            raise ValueError(f"axes: only one .npy/.npz array of frames has a layout to name; {len(paths)} "
                             f"{kind} file(s) are one frame each")
    if kind in (".npy", ".npz") and len(paths) == 1:
        data, meta = _np_frames(paths[0])
        if data.ndim != 3:
            raise ValueError(f"source: {str(paths[0])!r} holds an array of shape {data.shape}; a record is "
                             f"(n_t, n_y, n_x), or another layout named with axes=")
        saved = meta.get("axes") if isinstance(meta.get("axes"), str) else None
        try:  # one array: its time axis is never guessed (a time-last export must say so)
            layout = resolve_axes(data.shape, axes if axes is not None else saved)
        except ValueError as exc:
            raise ValueError(f"{exc} (the array in {str(paths[0])!r}; --axes on the command line)") from None
        data = _to_tyx(data, layout)
        frames, metas = list(data), [meta] * data.shape[0]
    else:
        frames, metas = [], []
        for p in paths:
            if kind == ".exr":
                f, m = _exr_frame(p, channel)
            elif kind == ".png":
                f, m = _png_frame(p, channel, png_range)
            else:
                f, m = _np_frames(p)
                if f.ndim != 2:
                    raise ValueError(f"source: {str(p)!r} holds shape {f.shape}; one frame per file is (n_y, n_x)")
            if frames and f.shape != frames[0].shape:
                raise ValueError(f"source: {str(p)!r} is {f.shape[1]}x{f.shape[0]} but {str(paths[0])!r} is "
                                 f"{frames[0].shape[1]}x{frames[0].shape[0]}; every frame must have one size")
            frames.append(f)
            metas.append(m)
    return _assemble(frames, metas, paths, dx, dt)


def _assemble(frames, metas, paths, dx, dt) -> Frames:
    heights = np.stack(frames)
    where = str(paths[0])
    bad = ~np.isfinite(heights)
    if bad.any():
        t = int(np.argwhere(bad)[0][0])
        raise ValueError(f"source: frame {t} ({str(paths[min(t, len(paths) - 1)])!r}) holds {int(bad.sum())} "
                         f"non-finite heights (NaN or inf)")
    meta = metas[0]
    unit_names = {str(m.get("units")) for m in metas}
    if len(unit_names) > 1:
        raise ValueError(f"source: the frames declare different units ({', '.join(sorted(unit_names))})")
    declared = meta.get("units")
    if declared is None or (isinstance(declared, str) and declared.startswith("unknown")):
        scale, units = 1.0, "unknown"
    else:
        scale, units = _units("source", declared, where), declared.strip()
    n_x = heights.shape[-1]
    found_dx = _meta_number(meta, "dx", where)
    length = _meta_number(meta, "length", where)
    if found_dx is None and length is not None:
        found_dx = length / n_x
    found_dt = _meta_number(meta, "dt", where)
    from_times = _times(metas, paths) if len(metas) > 1 and metas[0] is not metas[-1] else None
    if found_dt is not None and from_times is not None and not math.isclose(found_dt, from_times, rel_tol=1e-4):
        raise ValueError(f"source: {where} says dt = {found_dt:g} s but the frames' times are {from_times:g} s apart")
    found_dt = found_dt if found_dt is not None else from_times
    return Frames(heights * scale, _agree("dx", dx, found_dx, where), _agree("dt", dt, found_dt, where),
                  units, tuple(str(p) for p in paths), meta)


def read_map(path, *, name: str = "path", channels: int | None = None) -> np.ndarray:
    """One texture (a normal map, a caustics map) read from an EXR, PNG, ``.npy`` or ``.npz`` file.

    Rows come back in the grid convention (an image's top row is the highest y, so image rows are flipped).
    PNG values are divided by their largest level (255 or 65535), so a packed normal map reads as 0.5 + 0.5 n;
    EXR channels are stacked R, G, B (or the one channel, Y, of a scalar map); npz takes the first array.

    Parameters
    ----------
    path : str or os.PathLike
        The file.
    name : str, optional, keyword-only
        The argument's name for error messages (default ``"path"``).
    channels : int, optional, keyword-only
        1 for a scalar map (returned (n_y, n_x)), 3 for a vector map ((n_y, n_x, 3)); default as the file holds.

    Returns
    -------
    numpy.ndarray
        The values, float64.

    Raises
    ------
    ValueError
        When the file is missing or unreadable, holds another number of channels, or a non-finite value.
    """
    if not isinstance(name, str) or not name:
        raise TypeError(f"name must be a non-empty string (the argument's name for messages), got {describe(name)}")
    if channels is not None and (not isinstance(channels, int) or isinstance(channels, bool) or channels not in (1, 3)):
        raise ValueError(f"channels must be 1 (a scalar map), 3 (a vector map) or None, got {channels!r}")
    p = _path(name, path)
    if not p.is_file():
        raise ValueError(f"{name}: {str(p)!r} is not a file")
    suffix = p.suffix.lower()
    if suffix == ".exr":
        data, _ = _read_exr(p, name)
        if channels == 1 or len(data) == 1:
            key = "Y" if "Y" in data else (next(iter(data)) if len(data) == 1 else None)
            if key is None:
                raise ValueError(f"{name}: {str(p)!r} has channels {', '.join(data)}; a scalar map needs Y or one "
                                 f"channel")
            values = np.asarray(data[key], np.float64)
        else:
            missing = [c for c in "RGB" if c not in data]
            if missing:
                raise ValueError(f"{name}: {str(p)!r} lacks channel(s) {', '.join(missing)} (it has "
                                 f"{', '.join(data)})")
            values = np.stack([np.asarray(data[c], np.float64) for c in "RGB"], -1)
    elif suffix == ".png":
        from PIL import Image

        try:
            with Image.open(p) as im:
                raw = np.asarray(im)
        except (OSError, ValueError) as exc:
            raise ValueError(f"{name}: {str(p)!r} is not a readable PNG ({exc})") from None
        top = 65535.0 if raw.dtype in (np.uint16, np.int32) else 255.0
        values = np.flipud(raw).astype(np.float64) / top
        if values.ndim == 3 and values.shape[-1] == 4:
            values = values[..., :3]
    elif suffix in (".npy", ".npz"):
        try:
            values, _ = _np_frames(p)
        except ValueError as exc:
            raise ValueError(re.sub(r"^source:", f"{name}:", str(exc))) from None
    else:
        raise ValueError(f"{name}: {str(p)!r} is not an .exr, .png, .npy or .npz file")
    if channels == 1 and values.ndim != 2:
        raise ValueError(f"{name}: {str(p)!r} holds shape {values.shape}; a scalar map is one channel (n_y, n_x)")
    if channels == 3 and (values.ndim != 3 or values.shape[-1] != 3):
        raise ValueError(f"{name}: {str(p)!r} holds shape {values.shape}; a vector map is RGB (n_y, n_x, 3)")
    if not np.all(np.isfinite(values)):
        raise ValueError(f"{name}: {str(p)!r} holds non-finite values")
    return values
