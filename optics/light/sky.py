r"""The daylight sky of Preetham, Shirley & Smits (1999): an analytic model with the sun.

Radiance in a direction at zenith angle θ, at angle γ from the sun (zenith angle θ_s),
for each of the CIE quantities Y (luminance) and x, y (chromaticity):

.. math::

    Q(\theta, \gamma) = Q_z \frac{F(\theta, \gamma)}{F(0, \theta_s)},\qquad
    F(\theta, \gamma) = \big(1 + A e^{B/\cos\theta}\big)\big(1 + C e^{D\gamma} + E\cos^2\gamma\big),

with the Perez coefficients A … E linear in the turbidity T (2: very clear, 6: hazy)
and the zenith values Y_z (from χ = (4/9 − T/120)(π − 2θ_s)) and x_z, y_z (cubics in θ_s,
quadratics in T), all from the paper's appendix. xyY goes to linear sRGB (D65) and is
scaled so that the zenith has luminance ``brightness`` (scene units, not cd/m²). Below the
horizon the sky is half its horizon value (light off the ground), as in the gradient sky.
The renderer's shader evaluates the same formulas (``optics/rendering/renderer.py``);
this is the CPU reference's copy, float64.
"""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.inputs import Real, check_array, validate

__all__ = ["preetham_sky", "preetham_constants", "PEREZ", "TURBIDITY_RANGE"]

TURBIDITY_RANGE = (1.7, 10.0)
"""Turbidities the fit covers (the paper's range)."""

PEREZ = {
    "Y": ((0.1787, -1.4630), (-0.3554, 0.4275), (-0.0227, 5.3251), (0.1206, -2.5771), (-0.0670, 0.3703)),
    "x": ((-0.0193, -0.2592), (-0.0665, 0.0008), (-0.0004, 0.2125), (-0.0641, -0.8989), (-0.0033, 0.0452)),
    "y": ((-0.0167, -0.2608), (-0.0950, 0.0092), (-0.0079, 0.2102), (-0.0441, -1.6537), (-0.0109, 0.0529)),
}
"""Perez coefficients A … E as (slope, intercept) in the turbidity T (Preetham et al. 1999, appendix)."""

_ZENITH_X = ((0.00166, -0.00375, 0.00209, 0.0), (-0.02903, 0.06377, -0.03202, 0.00394),
             (0.11693, -0.21196, 0.06052, 0.25886))
_ZENITH_Y = ((0.00275, -0.00610, 0.00317, 0.0), (-0.04214, 0.08970, -0.04153, 0.00516),
             (0.15346, -0.26756, 0.06670, 0.26688))
_XYZ_TO_SRGB = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])
HORIZON_Z = 1e-3
"""Smallest cos θ used (directions at or below the horizon are evaluated just above it)."""


def _perez(cos_theta, gamma, cos_gamma, coeffs):
    a, b, c, d, e = coeffs
    return (1 + a * np.exp(b / cos_theta)) * (1 + c * np.exp(d * gamma) + e * cos_gamma**2)


def _zenith(theta_s, t):
    chi = (4.0 / 9.0 - t / 120.0) * (math.pi - 2 * theta_s)
    big_y = (4.0453 * t - 4.9710) * math.tan(chi) - 0.2155 * t + 2.4192
    powers = np.array([theta_s**3, theta_s**2, theta_s, 1.0])
    tt = np.array([t * t, t, 1.0])
    return big_y, float(tt @ np.array(_ZENITH_X) @ powers), float(tt @ np.array(_ZENITH_Y) @ powers)


@validate(turbidity=Real(lo=TURBIDITY_RANGE[0], hi=TURBIDITY_RANGE[1]), brightness=Real(lo=0.0, hi=1e6))
def preetham_constants(sun, turbidity: float = 3.0, brightness: float = 0.45) -> dict:
    """What the sky depends on besides the view direction, in float64.

    The Perez coefficients A … E of Y, x, y (``coefficients``, (3, 5)) and the factors
    Q_z/F(0, θ_s) (``scale``, (3,)), Y's scaled so the zenith luminance is ``brightness``. The
    shader takes these as uniforms.

    Parameters
    ----------
    sun : array_like (3,)
        Direction toward the sun, z > 0 (normalized here).
    turbidity : float
        T in [1.7, 10] (:data:`TURBIDITY_RANGE`): 2 very clear, 3 clear (default), 6 hazy.
    brightness : float
        Luminance of the zenith in scene units, in [0, 1e6].

    Returns
    -------
    dict
        ``coefficients`` (numpy.ndarray (3, 5)), ``scale`` (numpy.ndarray (3,)) and ``sun``
        (the unit sun direction, numpy.ndarray (3,)).

    References
    ----------
    A. J. Preetham, P. Shirley & B. Smits (1999). A practical analytic model for daylight.
    *SIGGRAPH* (the coefficients from its appendix).
    """
    check_array("sun", sun, ndim=1)
    s = np.asarray(sun, np.float64)
    if s.shape != (3,) or s[2] <= 0:
        raise ValueError(f"sun must be 3 numbers pointing above the horizon (z > 0), got {s.tolist()}")
    s = s / np.linalg.norm(s)
    theta_s = math.acos(min(s[2], 1.0))
    t = float(turbidity)
    zen = _zenith(theta_s, t)
    coefficients = np.array([[a * t + b for a, b in PEREZ[q]] for q in ("Y", "x", "y")])
    norm = np.array([_perez(1.0, theta_s, math.cos(theta_s), k) for k in coefficients])
    scale = np.array([brightness, zen[1], zen[2]]) / norm
    return dict(coefficients=coefficients, scale=scale, sun=s)


@validate(turbidity=Real(lo=TURBIDITY_RANGE[0], hi=TURBIDITY_RANGE[1]), brightness=Real(lo=0.0, hi=1e6))
def preetham_sky(d, sun, turbidity: float = 3.0, brightness: float = 0.45):
    """Linear sRGB sky radiance (..., 3) in unit directions ``d`` (..., 3) for the sun direction ``sun``.

    Parameters
    ----------
    d : array_like (..., 3)
        View directions (unit vectors, z up).
    sun : 3 numbers
        Direction toward the sun, z > 0 (normalized here).
    turbidity : float
        T in [1.7, 10]: 2 very clear, 3 clear (default), 6 hazy.
    brightness : float
        Luminance of the zenith in scene units (the gradient sky's zenith is about 0.45).

    Returns
    -------
    numpy.ndarray (..., 3)
        Linear sRGB radiance, scene units, ≥ 0, float64 (half the horizon value below it).

    References
    ----------
    A. J. Preetham, P. Shirley & B. Smits (1999). A practical analytic model for daylight.
    *SIGGRAPH*.
    """
    check_array("d", d, min_ndim=1)
    if np.shape(d)[-1] != 3:
        raise ValueError(f"d must have shape (..., 3), got {np.shape(d)}")
    c = preetham_constants(sun, turbidity, brightness)
    s = c["sun"]
    d = np.asarray(d, np.float64)
    below = d[..., 2] < 0
    up = np.concatenate([d[..., :2], np.maximum(d[..., 2:3], HORIZON_Z)], axis=-1)
    up = up / np.linalg.norm(up, axis=-1, keepdims=True)
    cos_t = np.maximum(up[..., 2], HORIZON_Z)
    cos_g = np.clip(up @ s, -1.0, 1.0)
    gamma = np.arctan2(np.linalg.norm(np.cross(up, s), axis=-1), up @ s)  # accurate near the sun too
    big_y, x, y = (sc * _perez(cos_t, gamma, cos_g, k) for sc, k in zip(c["scale"], c["coefficients"]))
    xyz = np.stack([x / y * big_y, big_y, (1 - x - y) / y * big_y], axis=-1)
    rgb = np.maximum(xyz @ _XYZ_TO_SRGB.T, 0.0)
    return np.where(below[..., None], 0.5 * rgb, rgb)
