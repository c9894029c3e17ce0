"""Shader checks of absorption: Beer–Lambert transmittance, and the RGB colour of a path through water.

``transmittance`` feeds path lengths and coefficients and expects e^{−a d}; the mistakes real
code makes are fitted models, each with its constant: a scaled path (twice for down and back,
half, per-cm coefficients), an offset added to the path, another base (2^{−ad}, 10^{−ad}), a
transmittance scaled by a factor, a linear fall-off, channels reversed. ``rgb_absorption`` feeds
path lengths alone and expects pure water's colour from the spectrum; a function that fails is
named by its fitted coefficients against water's.
"""

from __future__ import annotations

import math

import numpy as np

from optics.shaders.domain import Domain, display_tolerance, f32, samples_option, tolerance_option
from optics.shaders.models import Model, Param

__internal__ = True  # the registry's pieces: users call optics.shaders.check_glsl
__all__ = ["transmittance_domain", "transmittance_late", "rgb_absorption_domain", "rgb_absorption_late"]


def _scale_words(s: float) -> str:
    named = {2.0: "the path length is counted twice (2d: down and back up?) where the path d is due",
             0.5: "half the path length is used (d/2) where the path d is due",
             100.0: "the coefficients are taken per cm (×100): they are per metre",
             0.01: "the coefficients are taken as 1/(100 m) (×0.01): they are per metre",
             math.log(10.0): "it uses 10^{−a d} (a decadic coefficient) where e^{−a d} is due",
             math.log(2.0): "it uses exp2 (2^{−a d}) where e^{−a d} is due"}
    for value, words in named.items():
        if abs(math.log(s / value)) < 0.01:
            return words
    return f"the path length (or the coefficient) is scaled by {s:.4g}: −ln T = {s:.4g}·a·d where a·d is due"


def transmittance_domain(*, max_distance=20.0, samples=4096, bits=8, radiance=1.0, tolerance=None, seed=0):
    """Beer–Lambert e^{−a d} over path lengths 0 to ``max_distance`` m and coefficients 0.005–5 1/m (a
    different one per channel when the function takes ``coefficients``). The tolerance is half a level
    of a ``bits``-bit display relative to ``radiance`` (``tolerance`` overrides).

    Parameters
    ----------
    max_distance : float, keyword-only
        Longest path, m.
    samples : int, keyword-only
        Inputs checked.
    bits : int, keyword-only
        The display's bits a channel.
    radiance : float, keyword-only
        The light the transmittance scales.
    tolerance : float, optional, keyword-only
        Overrides the display's half level.
    seed : int, keyword-only
        Of the random coefficients.

    Returns
    -------
    Domain
        The inputs, the tolerance, and the correct and faulty models.
    """
    from wavephys.core.inputs import check_scalar

    check_scalar("max_distance", max_distance, lo=0.0, lo_open=True, hi=1e4)
    tol, tol_note = display_tolerance(bits, radiance, tolerance)
    rng = np.random.default_rng(seed)
    n = samples_option(samples)
    d = f32(np.linspace(0.0, max_distance, n))
    a = f32(np.exp(rng.uniform(math.log(0.005), math.log(5.0), (n, 3))))
    ad = a * d[:, None]
    correct = [Model("e^(−a d)", lambda v: np.exp(-ad), (), True)]
    faults = [
        Model("channels reversed", lambda v: np.exp(-a[:, ::-1] * d[:, None]), (), False,
              "the RGB channels are reversed (coefficients read as BGR)"),
        Model("scaled path", lambda v: np.exp(-v[0] * ad), (Param("s", (1e-3, 1e3), log=True),), False,
              lambda v: _scale_words(v[0])),
        Model("offset path", lambda v: np.exp(-a * (d[:, None] + v[0])), (Param("d0", (-20.0, 20.0)),), False,
              lambda v: f"an offset of {v[0]:.4g} m is added to the path: T = e^(−a (d + d0)) with d0 = {v[0]:.4g} m "
                        f"(T at d = 0 is {'above' if v[0] < 0 else 'below'} 1)"),
        Model("scaled transmittance", lambda v: v[0] * np.exp(-ad), (Param("c", (0.0, 4.0)),), False,
              lambda v: f"the transmittance is scaled by {v[0]:.4g} (T = {v[0]:.4g} e^(−a d): it does not start at 1 "
                        f"for no water)"),
        Model("linear", lambda v: np.clip(1.0 - v[0] * ad, 0.0, 1.0), (Param("s", (0.05, 20.0), log=True),), False,
              lambda v: f"not exponential: T falls linearly, 1 − {v[0]:.3g}·a·d (clamped), where Beer–Lambert gives "
                        f"e^(−a d)"),
        Model("scaled and offset path", lambda v: np.exp(-v[0] * a * (d[:, None] + v[1])),
              (Param("s", (1e-2, 1e2), log=True), Param("d0", (-20.0, 20.0))), False,
              lambda v: f"the path is scaled by {v[0]:.4g} and offset by {v[1]:.4g} m: T = e^(−{v[0]:.4g} a (d + "
                        f"{v[1]:.4g}))"),
    ]
    inputs = {"distance": d[:, None], "coefficient": a[:, :1], "coefficients": a, "color": np.ones((n, 3))}
    return Domain(inputs, tol, tol_note, ("path length d (m)", d), np.full(n, "T"),
                  dict(distance=d, a_r=a[:, 0], a_g=a[:, 1], a_b=a[:, 2]),
                  f"e^(-a d) for d = 0–{max_distance:g} m, a = 0.005–5 1/m ({n} samples)", correct, faults,
                  extra=dict(scalar_coefficient=False))


def transmittance_late(values, domain, errors):
    """A transmittance above 1 or below 0 that no fitted model explained.

    Parameters
    ----------
    values : numpy.ndarray (n, c)
        The function's outputs over the domain.
    domain : Domain
        The check's domain.
    errors : numpy.ndarray (n,)
        Each row's error against the correct answer.

    Returns
    -------
    str
        The cause in words ("" when this does not explain it).
    """
    if values.min() < -1e-6 or values.max() > 1.0 + 1e-6:
        return (f"gives T outside [0, 1] ({values.min():.4g} to {values.max():.4g}): a wrong sign in the exponent, "
                f"or an offset that makes the path negative?")
    return ""


def rgb_absorption_domain(*, max_distance=5.0, illuminant="D65", samples=256, bits=8, radiance=1.0, tolerance=None):
    """The linear-sRGB transmittance of pure water over path lengths 0 to ``max_distance`` m,
    against the spectral answer :func:`optics.light.attenuation.water_srgb`; the default
    tolerance is the larger of 1.25 × the error of the best RGB exponential over the same path
    lengths and half a level of a ``bits``-bit display relative to ``radiance``.

    Parameters
    ----------
    max_distance : float, keyword-only
        Longest path, m.
    illuminant : str, keyword-only
        The light's spectrum (a colour-science illuminant name).
    samples : int, keyword-only
        Inputs checked.
    bits : int, keyword-only
        The display's bits a channel.
    radiance : float, keyword-only
        The light the transmittance scales.
    tolerance : float, optional, keyword-only
        Overrides the default.

    Returns
    -------
    Domain
        The inputs, the tolerance, and the correct and faulty models.
    """
    from optics.light.attenuation import fit_rgb_coefficients, rgb_error, water_srgb
    from wavephys.core.inputs import check_scalar

    check_scalar("max_distance", max_distance, lo=0.05, hi=100.0)
    n = samples_option(samples)
    d = f32(np.linspace(0.0, max_distance, n))
    expected = np.asarray(water_srgb(d, illuminant), np.float64).reshape(n, 3)
    best_a = np.asarray(fit_rgb_coefficients(max_distance, illuminant))
    best = float(np.max(rgb_error(d, best_a, illuminant)))
    shown, shown_note = display_tolerance(bits, radiance)
    if tolerance is None:
        tol = max(1.25 * best, shown)
        tol_note = (f"tolerance {tol:.3g}: the larger of 1.25 × the best RGB exponential's error ({best:.3g}) and half "
                    f"a level of a {bits}-bit display")
    else:
        tol, tol_note = tolerance_option(tolerance), f"tolerance {tolerance:.3g} as given"

    def exponential(a):
        return np.exp(-np.asarray(a)[None, :] * d[:, None])

    correct = [Model("pure water's colour", lambda v: expected, (), True)]
    faults = [
        Model("reversed", lambda v: exponential(v[0] * best_a[::-1]), (Param("s", (1e-3, 1e3), log=True),), False,
              "the RGB channels are reversed (blue absorbed most): water absorbs red most"),
        Model("scaled", lambda v: exponential(v[0] * best_a), (Param("s", (1e-3, 1e3), log=True),), False,
              lambda v: _scale_words(v[0]).replace("the path length (or the coefficient)", "water's coefficients")),
    ]
    return Domain({"distance": d[:, None], "color": np.ones((n, 3))}, tol, tol_note, ("path length d (m)", d), np.full(n, "RGB"),
                  dict(distance=d), f"pure water, {illuminant}, d = 0–{max_distance:g} m ({n} samples); the best RGB "
                  f"exponential (a = {', '.join(f'{x:.4g}' for x in best_a)} 1/m) errs {best:.4g}", correct, faults,
                  extra=dict(expected=expected))


def rgb_absorption_late(values, domain, errors):
    """The function's coefficients, fitted per channel, against water's.

    Parameters
    ----------
    values : numpy.ndarray (n, c)
        The function's outputs over the domain.
    domain : Domain
        The check's domain.
    errors : numpy.ndarray (n,)
        Each row's error against the correct answer.

    Returns
    -------
    str
        The cause in words ("" when this does not explain it).
    """
    d = domain.context["distance"]
    use = (d > 0.05) & np.all((values > 1e-6) & (values < 1.0), axis=1)
    if use.sum() < 4:
        return ""
    a = -np.log(values[use]).T @ d[use] / (d[use] @ d[use])
    ref = -np.log(np.clip(domain.extra["expected"][use], 1e-9, 1.0)).T @ d[use] / (d[use] @ d[use])
    if np.argmax(a) != np.argmax(ref):
        return (f"the channels absorb in the wrong order: fitted a = ({', '.join(f'{x:.3g}' for x in a)}) 1/m, "
                f"water's ({', '.join(f'{x:.3g}' for x in ref)}) 1/m")
    ratio = a / ref
    return (f"the fitted coefficients are ({', '.join(f'{x:.3g}' for x in a)}) 1/m where pure water's are "
            f"({', '.join(f'{x:.3g}' for x in ref)}) 1/m (ratios {', '.join(f'{x:.3g}' for x in ratio)})")
