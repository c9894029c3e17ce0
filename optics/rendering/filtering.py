"""Distance filtering of the water's normals by their slope moments (LEAN-style mip maps).

A pixel far from the eye covers many texels of the water: shading it with the one normal at its
centre aliases (bands where a grazing view meets wave faces that happen to tilt towards the eye)
or, faded to flat water, loses the waves' look. Filtering keeps the look: each pixel is shaded
with the *distribution* of slopes its footprint covers (docs/physics.md §2.6).

- The slopes' first and second moments, (gx, gy, gx², gy², gx·gy), are averaged over 2^k × 2^k
  texels at level k of a pyramid (:func:`slope_moments`), Olano & Baker's LEAN mapping (2010) for
  slopes rather than Toksvig's (2005) single length: the covariance keeps the waves' direction.
- A pixel at distance t sees a footprint t·α across (α: the pixel's angle) and t·α/|d_z| along
  the view (:func:`footprint`); it is read at the level whose texels match the footprint's width,
  trilinearly (the level below 1 is the exact per-point slope, so near the eye the picture is
  unchanged), with up to :data:`MAX_TAPS` taps along the view (one: see there why).
- Beyond a tiled square, where the waves fade to their mean level with distance, the slope
  variance they lose is given back as the whole square's slope covariance (:func:`fade_moments`),
  and the flat far field carries that covariance too: distant water keeps its average roughness.
  Extended water (its border continued) gets none back (:func:`covariance_given_back`).
- The pyramid halves each side to ⌊n/2⌋ down to one texel, as GL's mip maps do: an odd side's
  last texel averages three, so the levels of odd-sized water (129², a node-centred grid) sit up to
  a texel of their level off the level-0 texels they average.
- The shading is averaged over the slope distribution at four sigma points (the unscented
  transform, which keeps its mean and covariance: :func:`sigma_slopes`), each weighted by the
  facet's projected area towards the eye (Smith's visible normals, without shadowing): the
  Fresnel weight and the reflected ray follow each sigma point; the transmitted light is
  taken along the mean normal's refracted ray.

The GPU renderer draws the same model in GLSL (:mod:`optics.rendering.renderer`); the CPU
reference calls these functions; the tests compare the two pixel by pixel.
"""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.inputs import check_array, check_bool, check_scalar

__internal__ = True  # the renderer's and the reference's pieces: users switch Effects(filtering=...)

__all__ = ["MAX_TAPS", "FACING", "facing_normal", "covariance_given_back", "slope_moments", "slope_covariance", "footprint", "fade_moments", "sigma_slopes",
           "covariance_of"]

MAX_TAPS = 1
"""Most taps along a footprint's long axis. GPUs filter textures anisotropically with up to 8 or 16
taps; against the supersampled truth (bench/filtering.py) 4 and 8 taps were worse than one on the
wake scene (RMS +6 % and +16 % at 1.5–2.5 scene sides): at grazing views the long axis runs over the
backs of waves hidden behind the crests in front, which the eye never sees. So one tap, read at the
level of the footprint's width."""

FACING = 0.01
"""Least cosine between the view ray and the mean normal it is shaded with: a footprint's mean normal can
face away from the eye (it averages faces the eye cannot see), and is tipped towards the eye until it does
(:func:`facing_normal`)."""

VARIANCE_FLOOR = 1e-10
"""Slope variance (trace of the covariance) below which a pixel is shaded with its mean normal alone."""


def _slopes(water, length, wrap):
    """Central-difference slopes (gx, gy) at each texel centre, one texel apart (wrapped or clamped edges):
    those of the bilinear surface the renderer draws, at its texel centres."""
    h = np.asarray(water, np.float64)
    ny, nx = h.shape
    if wrap:
        right, left = np.roll(h, -1, axis=1), np.roll(h, 1, axis=1)
        up, down = np.roll(h, -1, axis=0), np.roll(h, 1, axis=0)
    else:
        p = np.pad(h, 1, mode="edge")
        right, left, up, down = p[1:-1, 2:], p[1:-1, :-2], p[2:, 1:-1], p[:-2, 1:-1]
    return (right - left) / (2 * length / nx), (up - down) / (2 * length / ny)


def slope_moments(water, length: float, wrap: bool = False) -> list:
    """The pyramid of the water's slope moments: level k averages 2^k × 2^k texels.

    Parameters
    ----------
    water : array_like (ny, nx)
        Water heights, m, at the texel centres of a square of side ``length`` (the Grid convention).
    length : float
        The square's side, m, > 0.
    wrap : bool, optional
        Periodic edges (tiled water); clamped otherwise (default False).

    Returns
    -------
    list of numpy.ndarray
        Level k: float32 (max(1, ⌊ny / 2^k⌋), max(1, ⌊nx / 2^k⌋), 5) holding the means of gx, gy, gx², gy²,
        gx·gy (slopes dimensionless) over its texels, down to one texel (the sides of GL's mip maps; an odd
        side's last texel averages three of the level below).

    References
    ----------
    M. Olano & D. Baker (2010). LEAN mapping. *Proc. ACM SIGGRAPH Symposium on Interactive 3D
    Graphics and Games*, 181–188.
    """
    check_array("water", water, ndim=2)
    check_scalar("length", length, lo=0.0, lo_open=True)
    check_bool("wrap", wrap)
    gx, gy = _slopes(water, float(length), wrap)
    level = np.stack([gx, gy, gx * gx, gy * gy, gx * gy], axis=-1)
    levels = [level]
    while max(level.shape[:2]) > 1:
        level = _halve(_halve(level, 0), 1)
        levels.append(level)
    return [np.ascontiguousarray(v, np.float32) for v in levels]


def _halve(level, axis):
    """One level coarser along ``axis``: n → ⌊n/2⌋ texels, each the mean of two, the last of an odd side the
    mean of three (as GL's mip maps of odd sizes); a side of one texel stays."""
    n = level.shape[axis]
    if n == 1:
        return level
    a = np.moveaxis(level, axis, 0)
    half = 0.5 * (a[0:n - 1:2] + a[1:n:2])[: n // 2]
    if n % 2:
        half[-1] = (a[n - 3] + a[n - 2] + a[n - 1]) / 3.0
    return np.moveaxis(half, 0, axis)


def covariance_of(moments):
    """Slope covariance (cxx, cyy, cxy) of moments (..., 5) (means of gx, gy, gx², gy², gx·gy).

    Parameters
    ----------
    moments : array_like (..., 5)
        First and raw second moments of the slopes.

    Returns
    -------
    numpy.ndarray (..., 3)
        Variances of gx and gy (clipped at 0) and their covariance, dimensionless.
    """
    m = np.asarray(moments, np.float64)
    cxx = np.maximum(m[..., 2] - m[..., 0] ** 2, 0.0)
    cyy = np.maximum(m[..., 3] - m[..., 1] ** 2, 0.0)
    return np.stack([cxx, cyy, m[..., 4] - m[..., 0] * m[..., 1]], axis=-1)


def slope_covariance(water, length: float, wrap: bool = False):
    """Covariance (cxx, cyy, cxy) of the slopes over the whole square (what distant water keeps).

    Parameters
    ----------
    water : array_like (ny, nx)
        Water heights, m.
    length : float
        The square's side, m, > 0.
    wrap : bool, optional
        Periodic edges (default False: clamped).

    Returns
    -------
    numpy.ndarray (3,)
        float64 variances of gx and gy and their covariance, dimensionless.
    """
    level = slope_moments(water, length, wrap)[0].astype(np.float64)
    return covariance_of(level.reshape(-1, 5).mean(axis=0))


def footprint(distance, direction, pixel_angle: float, texel: float):
    """Where a pixel's footprint on level water is read: (pyramid level, length along the view, taps).

    The footprint is t·α across the view and t·α/|d_z| along it (its stretch capped at
    :data:`MAX_TAPS`); the taps are spaced along it at most one width (or texel) apart, and each is
    read at the level whose texels are one width wide.

    Parameters
    ----------
    distance : array_like
        Distance from the eye to the surface point, m (≥ 0).
    direction : array_like (..., 3)
        Unit view direction.
    pixel_angle : float
        The angle one pixel subtends, rad (2·tan(fov/2)/height), > 0.
    texel : float
        The water texture's texel (the longer side of a texel), m, > 0.

    Returns
    -------
    tuple of numpy.ndarray
        ``lod``: log2(t·α/texel) (≤ 0: the exact slope at the point); ``along``: the footprint's
        length along the view, m; ``taps``: how many taps cover it (int, 1 to :data:`MAX_TAPS`).
    """
    check_scalar("pixel_angle", pixel_angle, lo=0.0, lo_open=True)
    check_scalar("texel", texel, lo=0.0, lo_open=True)
    t = np.asarray(distance, np.float64)
    d = np.asarray(direction, np.float64)
    width = t * pixel_angle
    along = width / np.maximum(np.abs(d[..., 2]), 1.0 / MAX_TAPS)
    horizontal = np.hypot(d[..., 0], d[..., 1]) > 0
    taps = np.clip(np.ceil(along / np.maximum(width, texel) - 1e-6), 1, MAX_TAPS)
    with np.errstate(divide="ignore"):
        lod = np.log2(np.maximum(width, 1e-30) / texel)
    return lod, along, np.where(horizontal, taps, 1).astype(np.int64)


def fade_moments(mean, second, fade, covariance_all):
    """Moments of slopes faded by ``fade`` towards the mean level, their lost variance given back.

    A surface drawn as mean + f·(h − mean) has slopes f·g; the variance (1 − f²)·Σ it loses is
    replaced by the whole square's covariance Σ, so distant water keeps its average roughness.

    Parameters
    ----------
    mean : array_like (..., 2)
        Mean slopes of the unfaded surface.
    second : array_like (..., 3)
        Raw second moments (gx², gy², gx·gy) of the unfaded surface.
    fade : array_like (...)
        f in [0, 1] (1: the waves as they are).
    covariance_all : array_like (3,)
        The whole square's slope covariance (:func:`slope_covariance`).

    Returns
    -------
    tuple of numpy.ndarray
        The faded mean (..., 2) and raw second moments (..., 3).
    """
    f = np.asarray(fade, np.float64)[..., None]
    return f * mean, f * f * second + (1 - f * f) * np.asarray(covariance_all, np.float64)


def sigma_slopes(mean, covariance):
    """Four slopes with the distribution's mean and covariance (unscented transform, weights ¼).

    Parameters
    ----------
    mean : array_like (..., 2)
        Mean slope (gx, gy).
    covariance : array_like (..., 3)
        (cxx, cyy, cxy); the variances clipped at 0 and |cxy| at √(cxx·cyy) (positive semidefinite).

    Returns
    -------
    numpy.ndarray (4, ..., 2)
        m ± √2·L₁ and m ± √2·L₂, where L is the lower Cholesky factor of the covariance.

    References
    ----------
    S. J. Julier & J. K. Uhlmann (1997). A new extension of the Kalman filter to nonlinear systems.
    *Proc. SPIE* 3068 (the unscented transform).
    """
    m = np.asarray(mean, np.float64)
    c = np.asarray(covariance, np.float64)
    a, b = np.maximum(c[..., 0], 0.0), np.maximum(c[..., 1], 0.0)
    cxy = np.clip(c[..., 2], -np.sqrt(a * b), np.sqrt(a * b))  # |cxy| ≤ √(cxx·cyy): positive semidefinite
    l11 = np.sqrt(a)
    with np.errstate(divide="ignore", invalid="ignore"):
        l21 = np.where(l11 > 0, cxy / np.where(l11 > 0, l11, 1.0), 0.0)
    l22 = np.sqrt(np.maximum(b - l21 * l21, 0.0))
    s = math.sqrt(2.0)
    c1 = np.stack([l11, l21], axis=-1) * s
    c2 = np.stack([np.zeros_like(l22), l22], axis=-1) * s
    return np.stack([m + c1, m - c1, m + c2, m - c2])


def facing_normal(normal, direction):
    """The normal tipped towards the eye until −d·n ≥ :data:`FACING` before normalizing (so
    ≥ FACING/√(1 + FACING²) after), unchanged where it already faces the eye that much.

    Parameters
    ----------
    normal : array_like (..., 3)
        Unit normals.
    direction : array_like (..., 3)
        Unit view directions.

    Returns
    -------
    numpy.ndarray (..., 3)
        Unit normals n − max(d·n + FACING, 0)·d, normalized: continuous in n, so the picture has no edge
        where a mean normal turns away.
    """
    n = np.asarray(normal, np.float64)
    d = np.asarray(direction, np.float64)
    k = np.maximum(np.sum(d * n, axis=-1, keepdims=True) + FACING, 0.0)
    out = n - k * d
    return np.where(k > 0, out / np.linalg.norm(out, axis=-1, keepdims=True), n)


def covariance_given_back(water, length: float, surroundings: str):
    """The slope covariance given back where the waves fade, and carried by the flat far field.

    Parameters
    ----------
    water : array_like (ny, nx)
        Water heights, m.
    length : float
        The square's side, m, > 0.
    surroundings : str
        ``"tile"``: the square's waves repeat, and their whole covariance (:func:`slope_covariance`) is given
        back; ``"extend"`` or ``"none"``: nothing (past the square is its border continued, not its waves).

    Returns
    -------
    numpy.ndarray (3,)
        (cxx, cyy, cxy), dimensionless.
    """
    if surroundings == "tile":
        return slope_covariance(water, length, True)
    return np.zeros(3)
