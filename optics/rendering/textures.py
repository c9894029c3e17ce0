"""Textures for renderers: height (float32, 16-bit normalized, 8-bit), normals, caustics,
Fresnel and absorption lookups, as arrays and as files (16-bit PNG + .npz with metadata).

Heights stored in integers are normalized by an offset and an amplitude (Baboud &
Décoret 2006): h = offset + amplitude · q / (2^bits − 1). :func:`height_precision`
measures what each encoding does to heights, slopes and curvature (caustics depend on
curvature): 8 bits make visible stair steps, 16 bits normalized do not (docs/physics.md §2.5).
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from optics.light.attenuation import water_srgb
from optics.light.fresnel import N_AIR, N_WATER, fresnel_lut
from wavephys.core.files import atomic_path, output_file, output_folder
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_array, check_bool, check_choice, check_instance, check_int, check_scalar
from wavephys.core.spectral import central_gradient, spectral_gradient

__all__ = ["save_exr", "load_exr", "save_vector_displacement", "EncodedHeight", "encode_height", "decode_height", "normal_map", "height_precision",
           "fresnel_texture", "absorption_texture", "save_height_png", "save_npz", "load_npz", "export_scene", "export_height_frames"]

BITS = (8, 16, 32)
HALF_MAX = 65504.0
"""The largest finite 16-bit float: ``save_exr(..., half=True)`` refuses larger magnitudes (not written as inf)."""
MAX_EXR_NAME = 255
"""The longest channel or attribute name OpenEXR stores (a longer one would be cut)."""
GRID_CONVENTION = ("cell-centred: texel (row i, column j) of an n x n texture over a square of side L is "
                   "centred at x = -L/2 + (j + 1/2) L/n, y = -L/2 + (i + 1/2) L/n; array row 0 is the lowest y, "
                   "so the top row of a PNG or EXR image (rows flipped on writing) is the highest y")
NORMAL_CONVENTION = ("OpenGL (y up, green = +y): rgb = 0.5 + 0.5 n for the unit normal n = (nx, ny, nz), "
                     "z up out of the water; DirectX engines flip green (g' = 1 - g)")
NORMAL_CONVENTION_FLOAT = ("OpenGL (y up, green = +y): R, G, B = the unit normal n = (nx, ny, nz) itself, float, "
                           "not packed (no 0.5 + 0.5 n), z up out of the water; DirectX engines negate G")
CAUSTICS_UNITS = "relative irradiance E/E0 (1 = the light on flat water)"
DISPLACEMENT_CONVENTION = ("vector displacement, m, world axes (z up): R = dx along +x, G = dy along +y, B = dz up; "
                           "texel (i, j) moves the surface point resting at that texel's centre (grid convention) "
                           "to (x + dx, y + dy, dz); y-up engines swap G and B")
FOAM_UNITS = "foam coverage 0..1 of the water surface, in the grid convention (over the resampled heights)"


@dataclass(frozen=True)
class EncodedHeight:
    """A height texture: ``data`` (uint8, uint16 or float32) and how to decode it.

    value = offset + amplitude · data / (2^bits − 1) for integers; data itself for 32.
    ``length`` is the side length of the square it covers, m; ``units`` those of the
    decoded value ("m" for heights; caustics maps hold irradiance relative to E0).

    Parameters
    ----------
    data : numpy.ndarray (ny, nx)
        The stored texels: uint8 for ``bits=8``, uint16 for 16, float32 for 32.
    bits : {8, 16, 32}
        Bits per texel (32: float32, stored as is).
    offset : float
        Decoded value of q = 0, in ``units``, finite.
    amplitude : float
        Decoded range, in ``units``, > 0 (value = offset + amplitude · q / (2^bits − 1)).
    length : float
        Side length of the square the texture covers, m, > 0.
    units : str, optional
        Units of the decoded value, a non-empty string (default ``"m"``).

    Raises
    ------
    ValueError
        When ``data``'s dtype does not match ``bits``, or a value is out of range.
    TypeError
        When ``units`` is not a non-empty string.
    """

    data: np.ndarray
    bits: int
    offset: float
    amplitude: float
    length: float
    units: str = "m"

    def __post_init__(self):
        check_choice("bits", self.bits, BITS)
        check_array("data", self.data, ndim=2)
        want = {8: np.uint8, 16: np.uint16, 32: np.float32}[self.bits]
        if np.asarray(self.data).dtype != want:
            raise ValueError(f"data must be {np.dtype(want).name} for bits={self.bits}, got {np.asarray(self.data).dtype}")
        check_scalar("offset", self.offset)
        check_scalar("amplitude", self.amplitude, lo=0.0, lo_open=True)
        check_scalar("length", self.length, lo=0.0, lo_open=True)
        if not isinstance(self.units, str) or not self.units.strip():
            raise TypeError(f"units must be a non-empty string, got {self.units!r}")

    def metadata(self) -> dict:
        """How to decode the texture and where it lies: JSON-ready."""
        return dict(bits=self.bits, offset=self.offset, amplitude=self.amplitude, length=self.length,
                    units=self.units, decode="offset + amplitude * data / (2**bits - 1)" if self.bits != 32 else "data",
                    grid=GRID_CONVENTION)


def encode_height(eta, grid: Grid, bits: int = 16, units: str = "m") -> EncodedHeight:
    """Encode a height field (m, ``(n, n)``) as float32 (``bits=32``) or normalized integers
    (any other field with its ``units``, e.g. a caustics map).

    Integers span the field's range: offset = min, amplitude = max − min (1 for a constant field), rounded to the
    nearest of 2^bits − 1 levels.

    Parameters
    ----------
    eta : array_like (n, n)
        The field on ``grid``, in ``units``, finite.
    grid : Grid
        The grid of ``eta`` (its length becomes the texture's).
    bits : {8, 16, 32}, optional
        Bits per texel (default 16; 32 stores float32).
    units : str, optional
        Units of the field (default ``"m"``).

    Returns
    -------
    EncodedHeight
        The texture with its decoding offset and amplitude.

    References
    ----------
    L. Baboud & X. Décoret (2006). Realistic water volumes in real-time. *Eurographics Workshop on Natural
    Phenomena* (heights normalized by an offset and an amplitude).
    """
    check_choice("bits", bits, BITS)
    check_instance("grid", grid, Grid, "wavephys.Grid")
    check_array("eta", eta, ndim=2, shape_tail=(grid.n, grid.n))
    eta = np.asarray(eta, np.float64)
    if bits == 32:
        return EncodedHeight(eta.astype(np.float32), 32, 0.0, 1.0, float(grid.length), units)
    lo, hi = float(eta.min()), float(eta.max())
    amp = hi - lo if hi > lo else 1.0
    levels = 2**bits - 1
    q = np.rint((eta - lo) / amp * levels)
    return EncodedHeight(q.astype(np.uint8 if bits == 8 else np.uint16), bits, lo, amp, float(grid.length), units)


def decode_height(tex: EncodedHeight) -> np.ndarray:
    """Heights in m (float64) from an :class:`EncodedHeight`.

    Parameters
    ----------
    tex : EncodedHeight
        The texture to decode.

    Returns
    -------
    numpy.ndarray (ny, nx)
        Decoded values, float64, in ``tex.units`` (m for heights).
    """
    check_instance("tex", tex, EncodedHeight, "optics.rendering.textures.EncodedHeight")
    if tex.bits == 32:
        return tex.data.astype(np.float64)
    return tex.offset + tex.amplitude * tex.data.astype(np.float64) / (2**tex.bits - 1)


def normal_map(eta, grid: Grid) -> np.ndarray:
    """Unit surface normals (n, n, 3) from spectral slopes, float32.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights, m, on ``grid``, finite.
    grid : Grid
        The periodic grid of ``eta``.

    Returns
    -------
    numpy.ndarray (n, n, 3)
        Unit normals (−∂η/∂x, −∂η/∂y, 1)/|·|, z up, dimensionless, float32.
    """
    check_instance("grid", grid, Grid, "wavephys.Grid")
    check_array("eta", eta, ndim=2, shape_tail=(grid.n, grid.n))
    gx, gy = spectral_gradient(np.asarray(eta, np.float64), float(grid.dx))
    nrm = np.stack([-gx, -gy, np.ones_like(gx)], axis=-1)
    return (nrm / np.linalg.norm(nrm, axis=-1, keepdims=True)).astype(np.float32)


def height_precision(eta, grid: Grid, bits: int, norm: str = "max") -> dict:
    """Errors an encoding makes, relative to the field's own size of each quantity.

    Returns |Δ| / |·| for height, slope (|∇η|) and curvature (∇²η), derivatives taken in
    the same way (central differences, as a shader would) on the original and the
    decoded field; ``norm`` "max" (worst texel over largest value) or "rms".

    Quantization noise (step q = range/(2^bits − 1)) is amplified by 1/Δx² in the
    curvature while the signal is A·k², so the relative curvature error grows as
    (λ/Δx)²: measured for 16 bits (RMS), 7.6e-5 at 8 texels per wavelength, 4.8e-4 at 16,
    1.5e-3 at 32, 2.4e-2 at 128. 16 bits meet 0.1 % on curvature up to about 20 texels
    per wavelength; longer swells need float32 (1e-4 at 128 texels).

    Parameters
    ----------
    eta : array_like (n, n)
        Heights, m, on ``grid``, finite.
    grid : Grid
        The grid of ``eta``.
    bits : {8, 16, 32}
        The encoding to measure.
    norm : {"max", "rms"}, optional
        "max" (worst texel over largest value) or "rms" (default "max").

    Returns
    -------
    dict
        ``bits``, ``norm`` and the relative errors ``height``, ``slope`` and ``curvature`` (floats,
        dimensionless).

    References
    ----------
    L. Baboud & X. Décoret (2006). Realistic water volumes in real-time. *Eurographics Workshop on Natural
    Phenomena* (heights normalized by an offset and an amplitude).
    """
    check_choice("norm", norm, ("max", "rms"))
    tex = encode_height(eta, grid, bits)
    a = np.asarray(eta, np.float64)
    b = decode_height(tex)
    h = float(grid.dx)

    def fd(f):
        from wavephys.core.spectral import central_laplacian

        gx, gy = central_gradient(f, h)
        return np.hypot(gx, gy), central_laplacian(f, h)

    sa, ca = fd(a)
    sb, cb = fd(b)
    if norm == "max":
        rel = lambda x, y: float(np.max(np.abs(x - y)) / np.max(np.abs(x)))
    else:
        rel = lambda x, y: float(np.sqrt(np.mean((x - y) ** 2) / np.mean(x * x)))
    return dict(bits=bits, norm=norm, height=rel(a - a.mean(), b - a.mean()), slope=rel(sa, sb), curvature=rel(ca, cb))


def fresnel_texture(size: int = 256, n1: float = N_AIR, n2: float = N_WATER) -> np.ndarray:
    """Exact reflectance at ``size`` cos θ samples in [0, 1], float32 (a 1-D texture).

    Parameters
    ----------
    size : int, optional
        Table entries, in [2, 2²⁰] (default 256).
    n1, n2 : float, optional
        Refractive indices of the incident and transmitting media, in [1, 10] (default air to water).

    Returns
    -------
    numpy.ndarray (size,)
        Unpolarized Fresnel reflectance R at cos θ = 0, 1/(size − 1), …, 1, dimensionless, float32.
    """
    return np.asarray(fresnel_lut(n1, n2, check_int("size", size, lo=2)), np.float32)


def absorption_texture(max_distance: float = 20.0, size: int = 256) -> np.ndarray:
    """Linear sRGB transmittance of pure water at ``size`` distances in [0, max_distance] m,
    shape (size, 3) float32 (spectral, colour-science; clipped gamut).

    Parameters
    ----------
    max_distance : float, optional
        Longest path length through water, m, > 0 (default 20).
    size : int, optional
        Table entries, >= 2 (default 256).

    Returns
    -------
    numpy.ndarray (size, 3)
        Transmittance per RGB channel, dimensionless, in [0, 1] (exactly 1 at d = 0), float32.
    """
    check_scalar("max_distance", max_distance, lo=0.0, lo_open=True)
    size = check_int("size", size, lo=2)
    t = water_srgb(np.linspace(0.0, max_distance, size))
    # transmittance relative to the light that enters: exactly 1 at d = 0 (the illuminant's white
    # point lands at 1.001 in sRGB through the colour matrices' rounding)
    return np.clip(t / t[0], 0.0, 1.0).astype(np.float32)


def write_png(array, path) -> Path:
    """Write an image array (uint8/uint16 grey, uint8 RGB) as a PNG atomically; rows flipped so
    that y points up in viewers (row 0 of the array is the lowest y)."""
    from PIL import Image

    with atomic_path(path) as tmp:
        Image.fromarray(np.ascontiguousarray(np.flipud(array))).save(tmp, format="PNG")
    return Path(path)


def _write_text(text: str, path) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)


def _write_npy(array, path) -> Path:
    with atomic_path(path) as tmp, open(tmp, "wb") as f:
        np.save(f, array)
    return Path(path)


def save_exr(path, channels: dict, *, half: bool = False, attributes: dict | None = None) -> Path:
    """Write 2-D float channels as one OpenEXR image (zip compression), atomically.

    ``channels`` maps channel names ("Y"; "R", "G", "B"; ...) to arrays of one shape
    (ny, nx) on the grid convention (row 0 = lowest y); rows are flipped on writing so
    that image viewers show +y up, as for PNG. ``half`` stores 16-bit floats (3 decimal
    digits: 5e-4 m steps on a 1 m swell) instead of 32-bit. ``attributes`` (str, int or
    float values) go into the header, so units, extent and conventions travel with the
    file. Read back with :func:`load_exr` or any EXR reader.

    Parameters
    ----------
    path : str or os.PathLike
        Output file; must end in ``.exr``.
    channels : dict of str to array_like (ny, nx)
        Non-empty; non-empty channel names to finite 2-D arrays of one shape (any unit).
    half : bool, optional, keyword-only
        Store 16-bit floats instead of 32-bit (default False).
    attributes : dict, optional, keyword-only
        Header entries: str keys not already in the header, str, int or float values (not bool) (default none).

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    TypeError
        When ``channels`` is not a non-empty dict with non-empty string names, or an attribute is not a str, int
        or float under a new name.
    ValueError
        When the channels differ in shape.
    """
    import OpenEXR

    path = output_file(path, "path", (".exr",))
    check_bool("half", half)
    if not isinstance(channels, dict) or not channels:
        raise TypeError(f"channels must be a non-empty dict of name -> 2-D array, got {type(channels).__name__}")
    shapes = set()
    for name, value in channels.items():
        if not isinstance(name, str) or not name:
            raise TypeError(f"channels: names must be non-empty strings, got {name!r}")
        if len(name) > MAX_EXR_NAME or not name.isprintable():
            raise ValueError(f"channels: a channel name must be 1-{MAX_EXR_NAME} printable characters (OpenEXR "
                             f"would cut a longer one), got one of {len(name)}")
        check_array(f"channels[{name[:40]!r}]", value, ndim=2)
        if half and np.max(np.abs(np.asarray(value, np.float64))) > HALF_MAX:
            raise ValueError(f"channels[{name!r}]: values up to {np.max(np.abs(np.asarray(value, np.float64))):.4g} "
                             f"do not fit 16-bit floats (largest {HALF_MAX:g}; they would be written as inf): "
                             f"write 32-bit floats (half=False) or rescale")
        shapes.add(np.shape(value))
    if len(shapes) != 1:
        raise ValueError(f"channels must all have one shape, got {sorted(shapes)}")
    if attributes is not None and not isinstance(attributes, dict):
        raise TypeError(f"attributes must be a dict of header entries (or None), got {type(attributes).__name__}")
    header = {"compression": OpenEXR.ZIP_COMPRESSION, "type": OpenEXR.scanlineimage}
    for key, value in (attributes or {}).items():
        if not isinstance(key, str) or key in header or not isinstance(value, (str, int, float)) or isinstance(value, bool):
            raise TypeError(f"attributes[{key!r}] must be a str, int or float under a new name, got {value!r}")
        if not key or len(key) > MAX_EXR_NAME or not key.isprintable():
            raise ValueError(f"attributes: a name must be 1-{MAX_EXR_NAME} printable characters (OpenEXR would cut a "
                             f"longer one), got one of {len(key)}")
        if isinstance(value, float) and not math.isfinite(value):
            raise ValueError(f"attributes[{key!r}] must be finite, got {value!r}")
        header[key] = value
    from wavephys.core.halffloat import to_float16

    def stored(v):  # float32 values stay float32 before halving (no double rounding either way)
        v = np.asarray(v)
        v = v if v.dtype in (np.float32, np.float64) else v.astype(np.float64)
        return np.ascontiguousarray(np.flipud(to_float16(v) if half else v.astype(np.float32)))

    pixels = {name: stored(v) for name, v in channels.items()}
    with atomic_path(path) as tmp, OpenEXR.File(header, pixels) as f:
        f.write(str(tmp))
    return path


def save_vector_displacement(path, displacement, grid: Grid, *, half: bool = False) -> Path:
    """Write a displaced surface as an OpenEXR vector-displacement texture (the form engines load).

    ``displacement`` (3, n, n), m: (Δx, Δy, z) of the surface point resting at each texel
    of ``grid`` — e.g. ``np.stack([*wavephys.choppy.displacement(h, grid), h])`` or
    ``GerstnerWaves.displacement(*grid.mesh(), t)``. Channels R, G, B = Δx, Δy, z
    (:data:`DISPLACEMENT_CONVENTION` in the header, with the units, extent and the grid
    convention); 32-bit float, or 16-bit with ``half``. Atomic.

    Parameters
    ----------
    path : str or os.PathLike
        Output file; must end in ``.exr``.
    displacement : array_like (3, n, n)
        (Δx, Δy, z) of the surface point resting at each texel, m, finite.
    grid : Grid
        The grid of the texels.
    half : bool, optional, keyword-only
        Store 16-bit floats instead of 32-bit (default False).

    Returns
    -------
    pathlib.Path
        The path written.
    """
    check_instance("grid", grid, Grid, "wavephys.Grid")
    check_array("displacement", displacement, ndim=3, shape_tail=(3, grid.n, grid.n))
    check_bool("half", half)
    d = np.asarray(displacement, np.float64)
    return save_exr(path, {c: d[i] for i, c in enumerate("RGB")}, half=half, attributes=dict(
        units="m", quantity="vector displacement of the water surface", convention=DISPLACEMENT_CONVENTION,
        length=float(grid.length), grid=GRID_CONVENTION, precision="half" if half else "float"))


def load_exr(path) -> tuple[dict, dict]:
    """(channels, attributes) of an OpenEXR file: float arrays in the grid convention (rows
    flipped back, row 0 = lowest y) and the header's own attributes.

    Parameters
    ----------
    path : str or os.PathLike
        An existing OpenEXR file.

    Returns
    -------
    channels : dict of str to numpy.ndarray (ny, nx)
        The channels by name, in the grid convention.
    attributes : dict
        The header entries with str, int or float values.

    Raises
    ------
    ValueError
        When ``path`` is not a file, or not a readable OpenEXR image (corrupt or truncated).
    """
    from wavephys.core.frames import read_exr

    return read_exr(path)


def save_height_png(tex: EncodedHeight, path) -> Path:
    """Write an 8- or 16-bit height texture as a grayscale PNG and its metadata as JSON beside it.

    Parameters
    ----------
    tex : EncodedHeight
        The texture, with ``bits`` 8 or 16.
    path : str or os.PathLike
        Output file; must end in ``.png`` (the JSON goes to the same name with ``.json``).

    Returns
    -------
    pathlib.Path
        The PNG's path.

    Raises
    ------
    ValueError
        When ``tex.bits`` is 32.
    """
    check_instance("tex", tex, EncodedHeight, "optics.rendering.textures.EncodedHeight")
    if tex.bits == 32:
        raise ValueError("tex.bits must be 8 or 16 for PNG, got 32 (use save_npz for float32)")
    path = output_file(path, "path", (".png",))
    # uint8 → mode "L", uint16 → mode "I;16"
    write_png(tex.data, path)
    _write_text(json.dumps(tex.metadata(), indent=2), path.with_suffix(".json"))
    return path


def save_npz(path, **textures) -> Path:
    """Save textures (arrays or EncodedHeight) and their decoding metadata in one .npz (atomically).

    Parameters
    ----------
    path : str or os.PathLike
        Output file; must end in ``.npz``.
    **textures : array_like or EncodedHeight
        At least one; each by its name. Arrays have no NaN (±inf allowed).

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    ValueError
        When no texture is given.
    """
    path = output_file(path, "path", (".npz",))
    if not textures:
        raise ValueError("textures: give at least one array to save, as name=array")
    arrays, meta = {}, {}
    for name, value in textures.items():
        if isinstance(value, EncodedHeight):
            arrays[name] = value.data
            meta[name] = value.metadata()
        else:
            check_array(name, value, allow_inf=True)
            arrays[name] = np.asarray(value)
    with atomic_path(path) as tmp, open(tmp, "wb") as f:
        np.savez_compressed(f, **arrays, metadata=json.dumps(meta))
    return path


def load_npz(path) -> dict:
    """Load what :func:`save_npz` wrote; EncodedHeight entries are decoded to metres.

    Parameters
    ----------
    path : str or os.PathLike
        An existing ``.npz`` file written by :func:`save_npz`.

    Returns
    -------
    dict of str to numpy.ndarray
        The textures by name; EncodedHeight entries decoded (float64, in their units), other arrays as stored.

    Raises
    ------
    ValueError
        When ``path`` is not a file, or has no metadata (not written by :func:`save_npz`).
    """
    from wavephys.core.files import _as_path

    path = _as_path("path", path)
    if not path.is_file():
        raise ValueError(f"path {str(path)!r} is not a file")
    try:
        f = np.load(path, allow_pickle=False)
    except (OSError, EOFError, ValueError) as exc:
        raise ValueError(f"path {str(path)!r} is not a readable .npz file ({str(exc)[:100]})") from None
    with f:
        if not hasattr(f, "files") or "metadata" not in f.files:
            raise ValueError(f"path {str(path)!r} is not a texture file written by save_npz (no metadata)")
        try:
            meta = json.loads(str(f["metadata"]))
        except (ValueError, json.JSONDecodeError) as exc:
            raise ValueError(f"path {str(path)!r} has unreadable metadata ({str(exc)[:100]})") from None
        out = {}
        for name in f.files:
            if name == "metadata":
                continue
            if name in meta:
                m = meta[name]
                out[name] = decode_height(EncodedHeight(f[name], m["bits"], m["offset"], m["amplitude"], m["length"]))
            else:
                out[name] = f[name]
    return out


def _normals_rgb8(normals) -> np.ndarray:
    """Unit normals → the usual 8-bit RGB normal-map encoding 0.5 + 0.5·n."""
    return np.round((0.5 + 0.5 * np.asarray(normals, np.float64)) * 255).astype(np.uint8)


def export_scene(scene, out_dir, *, exr: bool = True, half: bool = False) -> dict:
    """Write every texture a renderer needs for ``scene`` (an :class:`optics.rendering.Scene`) to ``out_dir``.

    Files: ``water_height.png`` and ``ground_height.png`` (16-bit normalized, with JSON
    sidecars holding offset, amplitude, length and units), ``water_normals.png`` (8-bit
    RGB, 0.5 + 0.5·n), ``caustics.png`` (16-bit, relative irradiance scaled by its JSON
    ``amplitude``) when the scene has a caustics map, ``fresnel.npy`` (exact R at 256
    values of cos θ in [0, 1]), ``absorption.npy`` (RGB transmittance at 256 distances in
    0–20 m), ``foam.png`` (16-bit coverage) when the scene has foam, each with a JSON
    sidecar naming its axes, units and conventions (grid, normal map), and ``textures.npz``
    with all of them (heights and caustics as stored, 16-bit
    integers with their decoding metadata; normals and lookup tables float32). With ``exr``
    (default) every texture is also written as OpenEXR (32-bit float, or 16-bit with
    ``half``): ``*_height.exr`` (channel Y, m), ``water_normals.exr`` (R, G, B = the unit
    normal's x, y, z), ``caustics.exr`` (Y, relative irradiance), ``foam.exr``, ``fresnel.exr`` and
    ``absorption.exr`` (one-row images along their table axis), each with units, extent,
    axes and conventions in its header (docs/textures.md).
    Returns {name: path}.

    Parameters
    ----------
    scene : optics.rendering.Scene
        The scene; its water and ground height fields must be square.
    out_dir : str or os.PathLike
        Folder the files are written to.
    exr : bool, optional, keyword-only
        Also write every texture as OpenEXR (default True).
    half : bool, optional, keyword-only
        OpenEXR in 16-bit floats instead of 32-bit (default False).

    Returns
    -------
    dict of str to pathlib.Path
        The files written, by name (``water_height``, ``water_normals``, ``fresnel``, ``npz``, ...).

    Raises
    ------
    ValueError
        When the water or ground height field is not square.

    Examples
    --------
    >>> from wavephys.app.scenes import builtin_scene                 # doctest: +SKIP
    >>> export_scene(builtin_scene("pool"), "out/pool")               # doctest: +SKIP
    """
    from optics.rendering.scene import Scene

    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    check_bool("exr", exr)
    check_bool("half", half)
    out = output_folder(out_dir, "out_dir")
    paths = {}
    heights = {}
    for name in ("water", "ground"):
        h = np.asarray(getattr(scene, name), np.float64)
        ny, nx = h.shape
        if ny != nx:
            raise ValueError(f"{name} must be square to export, got {h.shape}")
        tex = encode_height(h, Grid(nx, float(scene.length)), 16)
        heights[name] = tex
        paths[f"{name}_height"] = save_height_png(tex, out / f"{name}_height.png")
    w = np.asarray(scene.water, np.float64)
    normals = normal_map(w, Grid(w.shape[0], float(scene.length)))
    paths["water_normals"] = write_png(_normals_rgb8(normals), out / "water_normals.png")
    _write_text(json.dumps(dict(encoding="8-bit RGB", convention=NORMAL_CONVENTION, length=float(scene.length),
                                grid=GRID_CONVENTION), indent=2), out / "water_normals.json")
    arrays = dict(water=heights["water"], ground=heights["ground"], water_normals=normals,
                  fresnel=fresnel_texture(256, scene.n_air, scene.n_water), absorption=absorption_texture())
    if scene.caustics is not None:
        c = np.asarray(scene.caustics, np.float64)
        tex = encode_height(c, Grid(c.shape[0], float(scene.length)), 16, units=CAUSTICS_UNITS)
        paths["caustics"] = save_height_png(tex, out / "caustics.png")
        arrays["caustics"] = tex
    if scene.foam is not None:
        f = np.asarray(scene.foam, np.float64)
        tex = encode_height(f, Grid(f.shape[0], float(scene.length)), 16, units=FOAM_UNITS)
        paths["foam"] = save_height_png(tex, out / "foam.png")
        arrays["foam"] = tex
    paths["fresnel"] = _write_npy(arrays["fresnel"], out / "fresnel.npy")
    _write_text(json.dumps(dict(values="exact Fresnel reflectance R (unpolarized), 0..1",
                                axes=["cos(theta) of the incidence angle, 256 samples from 0 to 1"],
                                n1=float(scene.n_air), n2=float(scene.n_water)), indent=2), out / "fresnel.json")
    paths["absorption"] = _write_npy(arrays["absorption"], out / "absorption.npy")
    _write_text(json.dumps(dict(values="transmittance of pure water, linear sRGB, 0..1 (1 at d = 0)",
                                axes=["path length d through water, m, 256 samples from 0 to 20",
                                      "channel: R, G, B"]), indent=2), out / "absorption.json")
    paths["npz"] = save_npz(out / "textures.npz", **arrays)
    if exr:
        paths.update(_export_exr(scene, arrays, normals, out, half))
    return paths


def _export_exr(scene, arrays, normals, out, half) -> dict:
    """The OpenEXR twins of :func:`export_scene`'s textures."""
    common = dict(length=float(scene.length), grid=GRID_CONVENTION, precision="half" if half else "float")
    paths = {}
    for name in ("water", "ground"):  # the scene's own float heights, not the 16-bit PNG's
        paths[f"{name}_height_exr"] = save_exr(out / f"{name}_height.exr", {"Y": np.asarray(getattr(scene, name))},
                                               half=half, attributes=dict(common, units="m", quantity=f"{name} height"))
    paths["water_normals_exr"] = save_exr(out / "water_normals.exr",
                                          {c: normals[..., i] for i, c in enumerate("RGB")}, half=half,
                                          attributes=dict(common, units="1", quantity="unit surface normal (x, y, z)",
                                                          convention=NORMAL_CONVENTION_FLOAT))
    if "foam" in arrays:
        paths["foam_exr"] = save_exr(out / "foam.exr", {"Y": np.asarray(scene.foam)}, half=half,
                                     attributes=dict(common, units="1", quantity=FOAM_UNITS))
    if "caustics" in arrays:
        paths["caustics_exr"] = save_exr(out / "caustics.exr", {"Y": np.asarray(scene.caustics)}, half=half,
                                         attributes=dict(common, units=CAUSTICS_UNITS, quantity="floor irradiance"))
    paths["fresnel_exr"] = save_exr(out / "fresnel.exr", {"Y": arrays["fresnel"][None, :]}, half=half, attributes=dict(
        units="1", quantity="exact Fresnel reflectance R", axis_x="cos(theta), 0 to 1, 256 samples",
        n1=float(scene.n_air), n2=float(scene.n_water)))
    a = arrays["absorption"]
    paths["absorption_exr"] = save_exr(out / "absorption.exr", {c: a[None, :, i] for i, c in enumerate("RGB")},
                                       half=half, attributes=dict(units="1", quantity="transmittance of pure water, "
                                                                  "linear sRGB", axis_x="path length, m, 0 to 20, 256 samples"))
    return paths


def export_height_frames(heights, length: float, dt: float, out_dir, *, start: float = 0.0, half: bool = False,
                         prefix: str = "water_height", attributes: dict | None = None) -> list:
    """Write a time series of height fields as numbered OpenEXR frames, each saying what it is.

    ``OUT/PREFIX_0000.exr``, ``_0001``, …: channel Y = the heights, m, in the grid convention; the header holds
    ``units`` (m), ``length`` and ``dx`` (m), ``dt`` (s), the frame's ``time`` (s) and index, so that
    :meth:`wavephys.harness.Record.from_files` (``wavephys check OUT``) reads it back with nothing else given.
    Each frame is written atomically, as it is made.

    Parameters
    ----------
    heights : iterable of array_like (n, n)
        The frames, m, finite, all of one square shape (a generator is drawn one frame at a time).
    length : float
        Side of the square they cover, m, > 0.
    dt : float
        Time between frames, s, > 0.
    out_dir : str or os.PathLike
        Folder the frames go to (created, one level, if its parent exists).
    start : float, optional, keyword-only
        Time of the first frame, s, finite (default 0).
    half : bool, optional, keyword-only
        16-bit floats instead of 32-bit (default False; heights below 6.1e-5 m are subnormal in half floats).
    prefix : str, optional, keyword-only
        File name before the frame number: letters, digits, ``_`` and ``-`` (default ``"water_height"``).
    attributes : dict, optional, keyword-only
        More header entries that say what the frames are, str keys and str, int or float values: ``boundary``
        (``"walls"``: a tank, read as ``tank=True``; ``"periodic"``; ``"open"``), ``depth`` (m), ``sigma`` (N/m).

    Returns
    -------
    list of pathlib.Path
        The frames written, in order.

    Raises
    ------
    ValueError
        When a frame is not square or differs in shape from the first, or a value is out of range.
    """
    import re

    check_scalar("length", length, lo=0.0, lo_open=True)
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    check_scalar("start", start)
    check_bool("half", half)
    if not isinstance(prefix, str) or not re.fullmatch(r"[A-Za-z0-9_-]+", prefix):
        raise ValueError(f"prefix must be letters, digits, _ and - only, got {prefix!r}")
    if attributes is not None and not isinstance(attributes, dict):
        raise TypeError(f"attributes must be a dict of header entries (or None), got {type(attributes).__name__}")
    clash = sorted(set(attributes or {}) & {"units", "quantity", "length", "dx", "dt", "time", "frame", "grid",
                                            "precision"})
    if clash:
        raise ValueError(f"attributes: {clash} are written by the export itself")
    if isinstance(heights, (str, bytes)) or not hasattr(heights, "__iter__"):
        raise TypeError(f"heights must be an iterable of (n, n) height arrays, got {type(heights).__name__}")
    if hasattr(heights, "__len__") and len(heights) == 0:
        raise ValueError("heights holds no frames")
    out = output_folder(out_dir, "out_dir")
    paths, shape = [], None
    for i, frame in enumerate(heights):
        check_array(f"heights[{i}]", frame, ndim=2)
        h = np.asarray(frame, np.float64)
        if h.shape[0] != h.shape[1] or (shape is not None and h.shape != shape):
            raise ValueError(f"heights[{i}] has shape {h.shape}; frames must be square and of one shape"
                             f"{'' if shape is None else f' {shape}'}")
        shape = h.shape
        paths.append(save_exr(out / f"{prefix}_{i:04d}.exr", {"Y": h}, half=half, attributes=dict(
            units="m", quantity="water height", length=float(length), dx=float(length) / h.shape[0],
            dt=float(dt), time=float(start + i * dt), frame=i, grid=GRID_CONVENTION,
            precision="half" if half else "float", **(attributes or {}))))
    if not paths:
        raise ValueError("heights holds no frames")
    return paths
