r"""Absorption of light in water: Beer–Lambert, in-scatter, and spectral colour.

Beer–Lambert per wavelength (docs/physics.md §2.3; Premože & Ashikhmin as used by Baboud & Décoret
2006): light from a point under water reaching the surface after a path d (m) through
water and a depth difference z (m) is

.. math::

    L(p_w) = \alpha\,L(p_g) + (1 - \alpha)\,L_d,\qquad \alpha = e^{-a d - b z},

with absorption a and a depth coefficient b (1/m) and the diffuse in-scattered radiance
L_d; the simplified model is α = e^{−a d}. The cut-off distance where α drops below ε is

.. math:: d_{max} = -\ln\varepsilon / \min_\lambda a_\lambda

(correction to the source: Baboud & Décoret print log(ε)/min a, which is negative).

Spectral reference: the pure-water absorption a(λ) of WOPP v3 (Röttgers et al. 2016,
shipped in ``optics/data``) is integrated as e^{−a(λ)d} against an illuminant and the
CIE 1931 2° observer and converted to linear sRGB, all with colour-science
(:func:`water_srgb`). RGB Beer–Lambert with three effective coefficients
(:func:`fit_rgb_coefficients`) approximates it; its error grows with d
(:func:`rgb_error`).

Gamut policy: the light left after a few metres of water is a narrow blue-green band
whose chromaticity lies outside sRGB, so the linear red channel goes negative (from
about 8 m with D65). :func:`water_srgb` clips negative channels to 0 by default
(``gamut="clip"``), which keeps every value a valid transmittance for a shader;
``gamut="none"`` returns the raw values.
"""

from __future__ import annotations

import functools
from importlib import resources

import numpy as np

from wavephys.core.inputs import check_array, check_choice, check_int, check_scalar
from wavephys.core.methods import Methods

__all__ = [
    "transmittance",
    "underwater_radiance",
    "cutoff_distance",
    "pure_water_absorption",
    "ABSORPTION_RANGE_NM",
    "water_srgb",
    "fit_rgb_coefficients",
    "rgb_error",
    "water_transmittance_spectral",
    "water_transmittance_rgb",
    "WATER_TRANSMITTANCE_METHODS",
    "transmittance_table",
    "TABLE_SIZE",
    "TABLE_SCALE",
]

ABSORPTION_RANGE_NM = (300.0, 4000.0)
"""Wavelengths covered by the shipped pure-water absorption table, nm."""


def transmittance(distance, coefficient):
    """Beer–Lambert transmittance e^{−a d} (dimensionless).

    Parameters
    ----------
    distance : array_like
        Path length d in water, m, ≥ 0.
    coefficient : array_like
        Absorption (or attenuation) coefficient a, 1/m, ≥ 0; broadcasts with
        ``distance`` (e.g. shape (3,) for RGB).

    Returns
    -------
    jax.Array
        e^{−a d}, dimensionless, in [0, 1], of the broadcast shape.

    References
    ----------
    L. Baboud & X. Décoret (2006). Realistic water volumes in real-time. *Eurographics Workshop on
    Natural Phenomena* (docs/physics.md §2.3).
    """
    check_array("distance", distance, lo=0.0)
    check_array("coefficient", coefficient, lo=0.0)
    import jax.numpy as jnp

    return jnp.exp(-jnp.asarray(coefficient) * jnp.asarray(distance))


def underwater_radiance(ground, diffuse, distance, depth, absorption, depth_coefficient=0.0):
    """L = α·L_ground + (1 − α)·L_diffuse with α = e^{−a d − b z} (radiance units of the inputs).

    Parameters
    ----------
    ground, diffuse : array_like
        Radiance leaving the ground point and the diffuse in-scattered radiance (same
        units, e.g. W/(m²·sr) or linear RGB).
    distance : array_like
        Path length d through water, m, ≥ 0.
    depth : array_like
        Depth difference z between ground point and surface point, m, ≥ 0.
    absorption, depth_coefficient : array_like
        a and b, 1/m, ≥ 0 (b = 0: the simplified model).

    Returns
    -------
    jax.Array
        L, in the radiance units of ``ground`` and ``diffuse``, of the broadcast shape.

    References
    ----------
    L. Baboud & X. Décoret (2006). Realistic water volumes in real-time. *Eurographics Workshop on
    Natural Phenomena* (after Premože & Ashikhmin; docs/physics.md §2.3).
    """
    check_array("ground", ground, lo=0.0)
    check_array("diffuse", diffuse, lo=0.0)
    check_array("distance", distance, lo=0.0)
    check_array("depth", depth, lo=0.0)
    check_array("absorption", absorption, lo=0.0)
    check_array("depth_coefficient", depth_coefficient, lo=0.0)
    import jax.numpy as jnp

    try:
        np.broadcast_shapes(*(np.shape(a) for a in (ground, diffuse, distance, depth)))
    except ValueError:
        raise ValueError(f"ground, diffuse, distance and depth must broadcast together, got shapes "
                         f"{[np.shape(a) for a in (ground, diffuse, distance, depth)]}") from None

    alpha = transmittance(distance, absorption) * jnp.exp(-jnp.asarray(depth_coefficient) * jnp.asarray(depth))
    return alpha * jnp.asarray(ground) + (1.0 - alpha) * jnp.asarray(diffuse)


def cutoff_distance(epsilon, coefficients):
    """d_max = −ln ε / min a, m: beyond it less than ε of the light survives in every band.

    ``epsilon`` in (0, 1); ``coefficients`` > 0, 1/m (any shape: the minimum is taken).

    Parameters
    ----------
    epsilon : float
        ε, the transmittance threshold, dimensionless, in (0, 1).
    coefficients : array_like
        Absorption coefficients a, 1/m, > 0, any shape (the minimum is taken).

    Returns
    -------
    float
        d_max, m.

    References
    ----------
    L. Baboud & X. Décoret (2006). Realistic water volumes in real-time. *Eurographics Workshop on
    Natural Phenomena* (docs/physics.md §2.3).
    """
    check_scalar("epsilon", epsilon, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
    check_array("coefficients", coefficients, lo=0.0, lo_open=True)
    return float(-np.log(epsilon) / np.min(coefficients))


@functools.lru_cache(maxsize=1)
def _table():
    with resources.files("optics").joinpath("data/purewater_absorption_wopp_v3.dat").open("rb") as f:
        data = np.loadtxt(f, comments="%")
    return data[:, 0], data[:, 1]


def pure_water_absorption(wavelength_nm):
    """Absorption coefficient of pure water a(λ), 1/m, at 20 °C (WOPP v3, linear interpolation).

    Source: Röttgers, Doerffer, McKee & Schönfeld (2011), WOPP v1.7 table v3 (2016);
    300–510 nm from Mason, Cone & Fry (2016), Appl. Opt. 55, 7163. Spot values:
    a(450) = 0.00808, a(550) = 0.0581, a(650) = 0.340, a(700) = 0.6126 1/m.

    Parameters
    ----------
    wavelength_nm : array_like
        Wavelengths, nm, within :data:`ABSORPTION_RANGE_NM`.

    Returns
    -------
    numpy.ndarray
        a(λ), 1/m, float64, shape of ``wavelength_nm``.

    References
    ----------
    R. Röttgers, R. Doerffer, D. McKee & W. Schönfeld (2011/2016). Pure water spectral
    absorption, scattering, and real part of refractive index model (WOPP). Mason, Cone & Fry
    (2016), *Appl. Opt.* 55, 7163 (300–510 nm).
    """
    check_array("wavelength_nm", wavelength_nm, lo=ABSORPTION_RANGE_NM[0], hi=ABSORPTION_RANGE_NM[1])
    wl, a = _table()
    return np.interp(np.asarray(wavelength_nm, float), wl, a)


@functools.lru_cache(maxsize=8)
def _colorimetry(illuminant: str, step: float):
    import colour

    if illuminant not in colour.SDS_ILLUMINANTS:
        raise ValueError(f"illuminant must be one of colour.SDS_ILLUMINANTS, got {illuminant!r}")
    shape = colour.SpectralShape(380, 780, step)
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"].copy().align(shape)
    ill = colour.SDS_ILLUMINANTS[illuminant].copy().align(shape)
    wl, a = _table()
    keep = (wl >= 380) & (wl <= 780)
    absorption = colour.SpectralDistribution(dict(zip(wl[keep], a[keep])), name="pure water a(λ)")
    absorption = absorption.copy().align(shape)
    return shape, cmfs, ill, absorption


def water_srgb(distance, illuminant: str = "D65", gamut: str = "clip", step: float = 5.0):
    """Linear sRGB transmittance of a path through pure water, from the spectrum.

    e^{−a(λ)d} is integrated against the illuminant and the CIE 1931 2° observer
    (colour-science, ``method="Integration"``) and converted to linear sRGB
    (``colour.XYZ_to_sRGB``, no transfer function), then divided by the result for
    d = 0 so that no water is exactly (1, 1, 1).

    Parameters
    ----------
    distance : array_like
        Path length(s), m, ≥ 0; the result has shape ``distance.shape + (3,)``.
    illuminant : str
        A name in ``colour.SDS_ILLUMINANTS`` (default D65, sRGB's white).
    gamut : {"clip", "none"}
        Channels clipped to [0, 1], or returned raw. Raw values leave [0, 1] at both ends:
        negative on long paths (module doc), and up to 1.001 in blue for paths of 0–2.6 m,
        where the red light water removes made sRGB's blue primary (whose colour-matching
        response is negative there) larger than white's; a transmittance is not a gain, so
        ``"clip"`` caps it at 1.
    step : float
        Spectral sampling, nm (1 to 20).

    Returns
    -------
    numpy.ndarray (..., 3)
        Linear sRGB transmittance, dimensionless (1 for d = 0), shape ``distance.shape + (3,)``.

    References
    ----------
    R. Röttgers, R. Doerffer, D. McKee & W. Schönfeld (2011/2016). Pure water spectral
    absorption, scattering, and real part of refractive index model (WOPP).

    Examples
    --------
    >>> import numpy as np
    >>> [round(float(c), 2) for c in water_srgb(np.array([0.0, 5.0]))[1]]   # 5 m: red goes first
    [0.17, 0.78, 0.99]
    """
    check_array("distance", distance, lo=0.0)
    check_choice("gamut", gamut, ("clip", "none"))
    check_scalar("step", step, lo=1.0, hi=20.0)
    import colour

    shape, cmfs, ill, absorption = _colorimetry(illuminant, float(step))
    d = np.asarray(distance, float)
    trans = np.exp(-np.multiply.outer(d.ravel(), absorption.values))  # (m, λ)
    # every path in one call (colour-science's integration over an array of spectra; sd_to_XYZ per path
    # was a Python loop, seconds for a render's rays)
    xyz = np.atleast_2d(colour.colorimetry.msds_to_XYZ_integration(
        np.vstack([np.ones(len(shape.wavelengths)), trans]), cmfs, ill, shape=shape))
    rgb = colour.XYZ_to_sRGB(xyz / 100.0, apply_cctf_encoding=False)
    rgb = rgb[1:] / rgb[0]
    if gamut == "clip":  # a transmittance: never negative, never a gain (module doc)
        rgb = np.clip(rgb, 0.0, 1.0)
    return rgb.reshape(d.shape + (3,))


def fit_rgb_coefficients(max_distance: float = 5.0, illuminant: str = "D65", samples: int = 50):
    """Effective RGB absorption coefficients (1/m) for shaders: e^{−a_c d} ≈ water_srgb(d)_c.

    Least squares of ln(rgb_c) = −a_c d through the origin over d ∈ (0, max_distance]
    (channels that are not positive are left out of their own fit).

    Parameters
    ----------
    max_distance : float
        Longest path fitted, m, > 0.
    illuminant : str
        A name in ``colour.SDS_ILLUMINANTS`` (default D65).
    samples : int
        Distances sampled, equally spaced in (0, max_distance], 2 … 100000.

    Returns
    -------
    numpy.ndarray (3,)
        a_c for linear sRGB (r, g, b), 1/m.

    Raises
    ------
    ValueError
        If a channel is not positive anywhere on (0, max_distance].

    References
    ----------
    R. Röttgers, R. Doerffer, D. McKee & W. Schönfeld (2011/2016). Pure water spectral
    absorption, scattering, and real part of refractive index model (WOPP).
    """
    check_scalar("max_distance", max_distance, lo=0.0, lo_open=True)
    samples = check_int("samples", samples, lo=2, hi=100000)
    d = np.linspace(max_distance / samples, max_distance, samples)
    rgb = water_srgb(d, illuminant, gamut="none")
    coeffs = []
    for c in range(3):
        ok = rgb[:, c] > 0
        if not ok.any():
            raise ValueError(f"channel {c} is not positive on (0, {max_distance}] m: shorten max_distance")
        coeffs.append(-np.sum(d[ok] * np.log(rgb[ok, c])) / np.sum(d[ok] ** 2))
    return np.asarray(coeffs)


def rgb_error(distance, coefficients, illuminant: str = "D65"):
    """max over channels |e^{−a_c d} − water_srgb(d)_c| (clipped gamut), per distance.

    ``coefficients``: a_c, 1/m, three numbers ≥ 0 (e.g. :func:`fit_rgb_coefficients`).

    Parameters
    ----------
    distance : array_like
        Path lengths d, m, ≥ 0.
    coefficients : array_like (3,)
        a_c, 1/m, ≥ 0.
    illuminant : str
        A name in ``colour.SDS_ILLUMINANTS`` (default D65).

    Returns
    -------
    numpy.ndarray
        The largest channel error, dimensionless (a transmittance difference), shape of
        ``distance``.

    References
    ----------
    R. Röttgers, R. Doerffer, D. McKee & W. Schönfeld (2011/2016). Pure water spectral
    absorption, scattering, and real part of refractive index model (WOPP).
    """
    check_array("coefficients", coefficients, ndim=1, shape_tail=(3,), lo=0.0)
    rgb = water_srgb(distance, illuminant)
    approx = np.exp(-np.multiply.outer(np.asarray(distance, float), np.asarray(coefficients)))
    return np.max(np.abs(approx - rgb), axis=-1)


def water_transmittance_spectral(distance, max_distance: float = 5.0):
    """Linear-sRGB transmittance of clear water over path lengths ``distance``: the absorption
    spectrum integrated against the eye (:func:`water_srgb`, D65, clipped to the gamut).

    Parameters
    ----------
    distance : array_like
        Path lengths, m, ≥ 0.
    max_distance : float
        The longest path the caller uses, m, > 0 (not needed here; the family's methods share
        one signature).

    Returns
    -------
    numpy.ndarray (..., 3)
        Transmittance per channel, [0, 1].
    """
    check_scalar("max_distance", max_distance, lo=0.0, lo_open=True)
    return water_srgb(distance)


def water_transmittance_rgb(distance, max_distance: float = 5.0):
    """Linear-sRGB transmittance by three Beer–Lambert coefficients, e^{−a_c d}, fitted to the
    spectral answer over (0, ``max_distance``] (:func:`fit_rgb_coefficients`): what a shader
    with one RGB absorption uniform draws.

    Parameters
    ----------
    distance : array_like
        Path lengths, m, ≥ 0.
    max_distance : float
        The longest path fitted, m, > 0.

    Returns
    -------
    numpy.ndarray (..., 3)
        Transmittance per channel, [0, 1].
    """
    check_array("distance", distance, lo=0.0)
    check_scalar("max_distance", max_distance, lo=0.0, lo_open=True)
    return np.exp(-np.asarray(distance, np.float64)[..., None] * _rgb_fit(float(max_distance)))


@functools.lru_cache(maxsize=64)
def _rgb_fit(max_distance: float):
    return fit_rgb_coefficients(max_distance)


WATER_TRANSMITTANCE_METHODS = Methods("water transmittance", spectral=water_transmittance_spectral,
                                      rgb=water_transmittance_rgb)
"""How the colour of clear water over a path is computed, by name: the spectral integral or
three fitted RGB coefficients. The planner's absorption term offers every entry."""


TABLE_SIZE = 4096
"""Entries of :func:`transmittance_table` (what the renderer's absorption texture holds). With
:data:`TABLE_SCALE` linear interpolation in u draws the spectral method within 5.8e-5 of it (at the
kink near 8.1 m where its gamut clipping sets in; 1.1e-5 elsewhere) and the RGB method within 4e-5 on
every path from 0 to 2 km (measured; tests/light/test_attenuation.py); 1024 entries at a 1 m scale
erred 1.1e-3 (at 83 m)."""

TABLE_SCALE = 16.0
"""Path length, m, at the middle of :func:`transmittance_table` (u = s/(s + scale) = 1/2)."""


@functools.lru_cache(maxsize=16)
def _shader_table(method: str, size: int, scale: float) -> np.ndarray:
    u = np.arange(size, dtype=np.float64) / (size - 1)
    paths = scale * u[:-1] / (1.0 - u[:-1])
    table = np.zeros((size, 3))
    table[:-1] = WATER_TRANSMITTANCE_METHODS[method](paths)
    table.setflags(write=False)
    return table


def transmittance_table(method: str, size: int = TABLE_SIZE, scale: float = TABLE_SCALE) -> np.ndarray:
    """Any water-transmittance method tabulated for a shader: RGB transmittance at ``size`` path
    lengths s = scale·u/(1 − u), u evenly spaced in [0, 1] (every path from 0 to ∞; the last
    entry, s = ∞, is 0), so that linear interpolation in u draws the method at any path.

    Parameters
    ----------
    method : str
        A name in :data:`WATER_TRANSMITTANCE_METHODS`.
    size : int, optional
        Entries, 16 to 65536 (default :data:`TABLE_SIZE`).
    scale : float, optional
        Path at u = 1/2, m, > 0 (default :data:`TABLE_SCALE`).

    Returns
    -------
    numpy.ndarray (size, 3)
        Transmittance per channel, float64, read-only.

    Examples
    --------
    >>> t = transmittance_table("spectral", size=64)
    >>> t.shape, float(t[0].min()), float(t[-1].max())
    ((64, 3), 1.0, 0.0)
    """
    WATER_TRANSMITTANCE_METHODS.check(method)
    size = check_int("size", size, lo=16, hi=65536)
    check_scalar("scale", scale, lo=0.0, lo_open=True)
    return _shader_table(method, size, float(scale))
