r"""Fresnel reflectance of the water surface: exact, and the approximations shaders use.

Exact unpolarized dielectric reflectance (docs/physics.md §2.2):

.. math::

    R_s = \left(\frac{n_1\cos\theta_i - n_2\cos\theta_t}{n_1\cos\theta_i + n_2\cos\theta_t}\right)^2,\quad
    R_p = \left(\frac{n_1\cos\theta_t - n_2\cos\theta_i}{n_1\cos\theta_t + n_2\cos\theta_i}\right)^2,\quad
    R = \tfrac12(R_s + R_p),\ T = 1 - R,

R = 1 under total internal reflection. The methods (:data:`REFLECTANCE_METHODS`), each
its own function, measured against the exact one by :func:`approximation_errors` and
``python -m bench optics``:

* :func:`reflectance_exact` — the formula above;
* :func:`reflectance_schlick` — R ≈ f0 + (1 − f0)(1 − cos θ)⁵, f0 = ((n1 − n2)/(n1 + n2))².
  From the denser side (n1 > n2) it uses cos θt and gives 1 past the critical angle.
  Correction to the source: Schneider & Westermann (2001) print ⟨N, V⟩⁵ for
  (1 − ⟨N, V⟩)⁵, which gives R = 1 at normal incidence;
* :func:`reflectance_jensen_golias` — R ≈ 1/(1 + cos θ)⁸ (Jensen & Goliáš 2001), for
  viewing water from air;
* :func:`reflectance_loviscach` — sky reflection factor clamp(1 − 2.5 cos θ) (Loviscach 2003, §4);
* :func:`reflectance_lut` — the exact R tabulated at ``size`` values of cos θ, linearly
  interpolated (a shader's lookup texture).

``cos_theta`` is always the cosine of the angle between the incoming ray and the normal,
in the incident medium n1 (0 at grazing, 1 at normal incidence). NumPy in → NumPy out,
JAX in → JAX out.
"""

from __future__ import annotations

import math

import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_array, check_int
from wavephys.core.methods import Methods, shader_form
from wavephys.core.sampling import array_module

__all__ = ["N_AIR", "N_WATER", "normal_reflectance", "reflectance_sp", "reflectance_exact", "reflectance_schlick",
           "reflectance_jensen_golias", "reflectance_loviscach", "reflectance_lut", "REFLECTANCE_METHODS",
           "reflectance", "fresnel_lut", "approximation_errors", "sun_glint", "water_refractive_index",
           "water_refractive_index_quan_fry", "WATER_CONDITIONS", "IndexRange", "water_index_range"]

N_AIR = 1.000293
"""Refractive index of air (docs/physics.md)."""
N_WATER = 1.333
"""Refractive index of water (docs/physics.md)."""


def normal_reflectance(n1, n2):
    """f0 = ((n1 − n2)/(n1 + n2))², the reflectance at normal incidence (0.0204 for water).

    ``n1``, ``n2``: refractive indices in [1, 10].

    Parameters
    ----------
    n1, n2 : float or array_like
        Refractive indices of the two media, in [1, 10].

    Returns
    -------
    float or array_like
        f0, dimensionless, in [0, 1).
    """
    _check_indices(n1, n2)
    return ((n1 - n2) / (n1 + n2)) ** 2


MAX_INDEX = 10.0
"""Largest refractive index accepted (water 1.333, diamond 2.42)."""


def _check_indices(n1, n2):
    check_array("n1", n1, lo=1.0, hi=MAX_INDEX)
    check_array("n2", n2, lo=1.0, hi=MAX_INDEX)


def _check(cos_theta, n1, n2):
    check_array("cos_theta", cos_theta, lo=0.0, hi=1.0)
    _check_indices(n1, n2)
    xp = array_module(cos_theta, n1, n2)
    return xp, xp.asarray(cos_theta, dtype=xp.result_type(float, cos_theta))


def _cos_t(xp, cos_i, eta):
    """cos θt by Snell (η = n1/n2) and the TIR mask."""
    k = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
    tir = k < 0
    return xp.sqrt(xp.where(tir, 0.0, k)), tir


def _sp(xp, c, n1, n2):
    ct, tir = _cos_t(xp, c, n1 / n2)
    rs = ((n1 * c - n2 * ct) / (n1 * c + n2 * ct)) ** 2
    rp = ((n1 * ct - n2 * c) / (n1 * ct + n2 * c)) ** 2
    return xp.where(tir, 1.0, rs), xp.where(tir, 1.0, rp)


def reflectance_sp(cos_theta, n1=N_AIR, n2=N_WATER):
    """Exact (R_s, R_p) reflectances; both 1 under total internal reflection.

    Parameters
    ----------
    cos_theta : array_like
        cos θi, in [0, 1], in the incident medium (0 at grazing, 1 at normal incidence).
    n1, n2 : float or array_like
        Refractive indices of the incident and transmitting media, in [1, 10] (default air to
        water; swap them for light from under water).

    Returns
    -------
    (R_s, R_p) : tuple of array_like
        The s- and p-polarized reflectances, dimensionless, in [0, 1], shape of ``cos_theta``.
    """
    xp, c = _check(cos_theta, n1, n2)
    return _sp(xp, c, n1, n2)


@shader_form("fresnel_exact", """
float fresnel_exact(float cos_i, float n1, float n2) {  // unpolarized dielectric reflectance
    float c = clamp(cos_i, 0.0, 1.0);
    float sin_t2 = (n1 / n2) * (n1 / n2) * (1.0 - c * c);
    if (sin_t2 >= 1.0) return 1.0;
    float ct = sqrt(max(1.0 - sin_t2, 0.0));
    float rs = (n1 * c - n2 * ct) / max(n1 * c + n2 * ct, 1e-30);
    float rp = (n1 * ct - n2 * c) / max(n1 * ct + n2 * c, 1e-30);
    return 0.5 * (rs * rs + rp * rp);
}
""")
def reflectance_exact(cos_theta, n1=N_AIR, n2=N_WATER):
    """Exact unpolarized reflectance R = (R_s + R_p)/2 (1 under total internal reflection).

    Parameters
    ----------
    cos_theta : array_like
        cos θi, in [0, 1], in the incident medium (0 at grazing, 1 at normal incidence).
    n1, n2 : float or array_like
        Refractive indices of the incident and transmitting media, in [1, 10] (default air to
        water; swap them for light from under water).

    Returns
    -------
    array_like
        R, dimensionless, in [0, 1], shape of ``cos_theta`` (NumPy in → NumPy out, JAX in → JAX
        out).
    """
    xp, c = _check(cos_theta, n1, n2)
    rs, rp = _sp(xp, c, n1, n2)
    return 0.5 * (rs + rp)


@shader_form("fresnel_schlick", """
float fresnel_schlick(float cos_i, float n1, float n2) {  // cos(theta_t) from the denser side, 1 under TIR
    float c = clamp(cos_i, 0.0, 1.0);
    float f = (n1 - n2) / (n1 + n2);
    if (n1 > n2) {
        float sin_t2 = (n1 / n2) * (n1 / n2) * (1.0 - c * c);
        if (sin_t2 >= 1.0) return 1.0;
        c = sqrt(max(1.0 - sin_t2, 0.0));
    }
    return f * f + (1.0 - f * f) * pow(1.0 - c, 5.0);
}
""")
def reflectance_schlick(cos_theta, n1=N_AIR, n2=N_WATER):
    """Schlick's R ≈ f0 + (1 − f0)(1 − cos θ)⁵, with cos θt from the denser side (module doc).

    Parameters
    ----------
    cos_theta : array_like
        cos θi, in [0, 1], in the incident medium (0 at grazing, 1 at normal incidence).
    n1, n2 : float or array_like
        Refractive indices of the incident and transmitting media, in [1, 10] (default air to
        water; swap them for light from under water).

    Returns
    -------
    array_like
        R, dimensionless, in [0, 1] (1 past the critical angle), shape of ``cos_theta`` (NumPy
        in → NumPy out, JAX in → JAX out).

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces.
    *VMV* (printed with ⟨N, V⟩⁵ for (1 − ⟨N, V⟩)⁵; corrected here, module docstring).
    """
    xp, c = _check(cos_theta, n1, n2)
    ct, tir = _cos_t(xp, c, n1 / n2)
    cos_used = xp.where(xp.asarray(n1) > xp.asarray(n2), ct, c)
    f0 = normal_reflectance(n1, n2)
    return xp.where(tir, 1.0, f0 + (1.0 - f0) * (1.0 - cos_used) ** 5)


@shader_form("fresnel_jensen_golias", """
float fresnel_jensen_golias(float cos_i, float n1, float n2) {  // the indices are not used
    return 1.0 / pow(1.0 + clamp(cos_i, 0.0, 1.0), 8.0);
}
""")
def reflectance_jensen_golias(cos_theta, n1=N_AIR, n2=N_WATER):
    """Jensen & Goliáš's R ≈ 1/(1 + cos θ)⁸ (from air; the indices are not used).

    Parameters
    ----------
    cos_theta : array_like
        cos θi, in [0, 1], in the incident medium (0 at grazing, 1 at normal incidence).
    n1, n2 : float or array_like
        Refractive indices, in [1, 10]; checked but not used.

    Returns
    -------
    array_like
        R, dimensionless, in [0, 1], shape of ``cos_theta`` (NumPy in → NumPy out, JAX in → JAX
        out).

    References
    ----------
    L. S. Jensen & R. Goliáš (2001). Deep-water animation and rendering. *Gamasutra*.
    """
    xp, c = _check(cos_theta, n1, n2)
    return 1.0 / (1.0 + c) ** 8


@shader_form("fresnel_loviscach", """
float fresnel_loviscach(float cos_i, float n1, float n2) {  // the indices are not used
    return clamp(1.0 - 2.5 * clamp(cos_i, 0.0, 1.0), 0.0, 1.0);
}
""")
def reflectance_loviscach(cos_theta, n1=N_AIR, n2=N_WATER):
    """Loviscach's sky reflection factor clamp(1 − 2.5 cos θ) (the indices are not used).

    Parameters
    ----------
    cos_theta : array_like
        cos θi, in [0, 1], in the incident medium (0 at grazing, 1 at normal incidence).
    n1, n2 : float or array_like
        Refractive indices, in [1, 10]; checked but not used.

    Returns
    -------
    array_like
        R, dimensionless, in [0, 1], shape of ``cos_theta`` (NumPy in → NumPy out, JAX in → JAX
        out).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §4.
    """
    xp, c = _check(cos_theta, n1, n2)
    return xp.clip(1.0 - 2.5 * c, 0.0, 1.0)


def fresnel_lut(n1=N_AIR, n2=N_WATER, size: int = 64):
    """The exact R at ``size`` equally spaced cos θ in [0, 1] (a texture for shaders).

    Parameters
    ----------
    n1, n2 : float
        Refractive indices of the incident and transmitting media, in [1, 10].
    size : int
        Table entries, 2 … 2²⁰.

    Returns
    -------
    jax.Array (size,)
        R at cos θ = 0, 1/(size − 1), …, 1, dimensionless.
    """
    size = check_int("size", size, lo=2, hi=1 << 20)
    return reflectance_exact(jnp.linspace(0.0, 1.0, size), n1, n2)


@shader_form("fresnel_lut", """
float fresnel_lut(float cos_i, float n1, float n2) {  // the exact R at 64 nodes, linearly interpolated
    float u = clamp(cos_i, 0.0, 1.0) * 63.0;
    float i = clamp(floor(u), 0.0, 62.0);
    float a = fresnel_exact(i / 63.0, n1, n2), b = fresnel_exact((i + 1.0) / 63.0, n1, n2);
    return mix(a, b, u - i);
}
""")
def reflectance_lut(cos_theta, n1=N_AIR, n2=N_WATER, *, size: int = 64):
    """R by linear interpolation in a uniform table of ``size`` exact values.

    Index arithmetic, as a shader does.

    Parameters
    ----------
    cos_theta : array_like
        cos θi, in [0, 1], in the incident medium (0 at grazing, 1 at normal incidence).
    n1, n2 : float or array_like
        Refractive indices of the incident and transmitting media, in [1, 10] (default air to
        water; swap them for light from under water).
    size : int
        Table entries, 2 … 2²⁰ (keyword only).

    Returns
    -------
    array_like
        R, dimensionless, in [0, 1], shape of ``cos_theta`` (NumPy in → NumPy out, JAX in → JAX
        out).
    """
    xp, c = _check(cos_theta, n1, n2)
    size = check_int("size", size, lo=2, hi=1 << 20)
    u = c * (size - 1)
    i = xp.clip(xp.floor(u).astype(xp.int32), 0, size - 2)
    f = u - i
    if np.ndim(n1) == 0 and np.ndim(n2) == 0:  # one table for every sample
        table = xp.asarray(reflectance_exact(xp.linspace(0.0, 1.0, size), n1, n2))
        return (1.0 - f) * table[i] + f * table[i + 1]
    # indices per sample (a table per pair of media): the two table entries, evaluated directly
    nodes = lambda j: reflectance_exact(j / (size - 1), n1, n2)
    return (1.0 - f) * nodes(i) + f * nodes(i + 1)


REFLECTANCE_METHODS = Methods("Fresnel reflectance", exact=reflectance_exact, schlick=reflectance_schlick,
                              jensen_golias=reflectance_jensen_golias, loviscach=reflectance_loviscach,
                              lut=reflectance_lut)
"""Reflectance methods by name."""


def reflectance(cos_theta, n1=N_AIR, n2=N_WATER, method: str = "exact", **options):
    """Unpolarized reflectance R (dimensionless, in [0, 1]) by ``method``.

    Parameters
    ----------
    cos_theta : array_like
        cos θi in [0, 1], in the incident medium.
    n1, n2 : float
        Refractive indices of the incident and transmitting media, ≥ 1 (default air to
        water; swap them for light from under water).
    method : str
        A name in :data:`REFLECTANCE_METHODS`; ``options`` go to it (``size`` for "lut").
    **options
        The method's own options (``size`` for "lut"; the old name ``lut_size`` is accepted).

    Returns
    -------
    array_like
        R, dimensionless, in [0, 1], shape of ``cos_theta`` (NumPy in → NumPy out, JAX in → JAX
        out).

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces.
    *VMV* (Schlick's form); L. S. Jensen & R. Goliáš (2001). Deep-water animation and rendering.
    *Gamasutra*; J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*,
    §4 (docs/physics.md §2.2).

    Examples
    --------
    >>> round(float(reflectance(1.0, 1.0, 1.333)), 4)   # f0 of water from vacuum
    0.0204
    >>> round(float(reflectance(1.0)), 5)              # from air (n = 1.000293)
    0.02033
    >>> float(reflectance(0.5, 1.333, 1.000293))      # 60° from below: past 48.6°
    1.0
    """
    from wavephys.core.aliases import renamed_options

    options = renamed_options("reflectance", options, {"lut_size": "size"}, since="0.2")
    return REFLECTANCE_METHODS(method, cos_theta, n1, n2, **options)


def approximation_errors(method: str, n1=N_AIR, n2=N_WATER, samples: int = 20000, **options) -> dict:
    """Error of a reflectance method against the exact one over the incidence angle.

    Returns the signed worst error, its angle (degrees) and the cosine-weighted mean
    absolute error (weight cos θ sin θ: the irradiance-weighted average over the
    hemisphere). Evaluated in float32, as a shader would.

    Parameters
    ----------
    method : str
        A name in :data:`REFLECTANCE_METHODS`.
    n1, n2 : float
        Refractive indices of the incident and transmitting media, in [1, 10].
    samples : int
        Incidence angles, equally spaced in [0°, 90°], 3 … 10⁷.
    **options
        Passed on to the method (``size`` for "lut").

    Returns
    -------
    dict
        ``worst`` (signed R_method − R_exact of largest size, dimensionless), ``angle`` (its
        incidence angle, degrees) and ``weighted_mean`` (dimensionless).

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces.
    *VMV* (Schlick's form); L. S. Jensen & R. Goliáš (2001). Deep-water animation and rendering.
    *Gamasutra*; J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*,
    §4 (docs/physics.md §2.2).
    """
    samples = check_int("samples", samples, lo=3, hi=10**7)
    _check_indices(n1, n2)
    theta = np.linspace(0.0, math.pi / 2, samples)
    c = jnp.asarray(np.cos(theta), jnp.float32)
    err = (np.asarray(reflectance(c, n1, n2, method, **options), float)
           - np.asarray(reflectance_exact(c, n1, n2), float))
    i = int(np.argmax(np.abs(err)))
    w = np.cos(theta) * np.sin(theta)
    return dict(worst=float(err[i]), angle=math.degrees(theta[i]),
                weighted_mean=float(np.sum(np.abs(err) * w) / np.sum(w)))


def sun_glint(n_dot_h):
    """Loviscach's (2003) sun highlight g = clamp(100·n·h − 98.95), n·h in [−1, 1].

    Parameters
    ----------
    n_dot_h : array_like
        n·h, the cosine between normal and half vector, in [−1, 1].

    Returns
    -------
    array_like
        g, dimensionless, in [0, 1], shape of ``n_dot_h``.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §4.
    """
    check_array("n_dot_h", n_dot_h, lo=-1.0, hi=1.0)
    xp = array_module(n_dot_h)
    return xp.clip(100.0 * xp.asarray(n_dot_h) - 98.95, 0.0, 1.0)


def water_refractive_index(wavelength_nm, temperature_k: float = 293.15):
    """Refractive index of water vs wavelength (Schiebener et al. 1990, via colour-science).

    Parameters
    ----------
    wavelength_nm : array_like
        Wavelength in vacuum, nm, within [200, 1100] (the model's range of validity).
    temperature_k : float
        Water temperature, K, in [261.15, 773.15] (default 20 °C).

    Returns
    -------
    numpy.ndarray
        n, dimensionless, shape of ``wavelength_nm``.

    References
    ----------
    Schiebener et al. (1990), as implemented by colour-science
    (``light_water_refractive_index_Schiebener1990``).
    """
    from wavephys.core.inputs import check_scalar

    check_array("wavelength_nm", wavelength_nm, lo=200.0, hi=1100.0)
    check_scalar("temperature_k", temperature_k, lo=261.15, hi=773.15)  # the formula's range
    from colour.phenomena import light_water_refractive_index_Schiebener1990

    return np.asarray(light_water_refractive_index_Schiebener1990(np.asarray(wavelength_nm, float),
                                                                    temperature_k))


def water_refractive_index_quan_fry(wavelength_nm, temperature_c=20.0, salinity=0.0):
    r"""Refractive index of fresh or sea water relative to air (Quan & Fry 1995).

    .. math::

        n = n_0 + (n_1 + n_2 T + n_3 T^2) S + n_4 T^2 + \frac{n_5 + n_6 S + n_7 T}{\lambda}
            + \frac{n_8}{\lambda^2} + \frac{n_9}{\lambda^3}

    with n₀ = 1.31405, n₁ = 1.779e-4, n₂ = −1.05e-6, n₃ = 1.6e-8, n₄ = −2.02e-6, n₅ = 15.868,
    n₆ = 0.01155, n₇ = −0.00423, n₈ = −4382, n₉ = 1.1455e6 (λ in nm, T in °C, S in ‰). A fit to
    the measurements Austin & Halikas (1976) selected, within their error; the index is relative
    to air at standard pressure (the absolute index is n × 1.000293 at sea level).

    Parameters
    ----------
    wavelength_nm : array_like
        Wavelength in air, nm, in [400, 700] (the fit's range).
    temperature_c : array_like, optional
        Water temperature, °C, in [0, 30] (default 20).
    salinity : array_like, optional
        Salinity, ‰ (g/kg), in [0, 35]: 0 fresh water, 35 the mean ocean (default 0).

    Returns
    -------
    numpy.ndarray
        n relative to air, dimensionless (1.329–1.352 over the ranges above), the broadcast shape
        of the arguments.

    References
    ----------
    X. Quan & E. S. Fry (1995). Empirical equation for the index of refraction of seawater.
    *Applied Optics* 34(18), 3477–3480.

    Examples
    --------
    >>> round(float(water_refractive_index_quan_fry(589.0, 20.0, 0.0)), 4)   # sodium D line, fresh
    1.333
    """
    check_array("wavelength_nm", wavelength_nm, lo=400.0, hi=700.0)
    check_array("temperature_c", temperature_c, lo=0.0, hi=30.0)
    check_array("salinity", salinity, lo=0.0, hi=35.0)
    lam = np.asarray(wavelength_nm, np.float64)
    t = np.asarray(temperature_c, np.float64)
    s = np.asarray(salinity, np.float64)
    return (1.31405 + (1.779e-4 - 1.05e-6 * t + 1.6e-8 * t * t) * s - 2.02e-6 * t * t
            + (15.868 + 0.01155 * s - 0.00423 * t) / lam - 4382.0 / lam ** 2 + 1.1455e6 / lam ** 3)


WATER_CONDITIONS = dict(wavelength_nm=(400.0, 700.0), temperature_c=(0.0, 30.0), salinity=(0.0, 35.0),
                        n_air=(1.0, N_AIR))
"""The conditions under which water is still "water" for a check of a user's code: the visible
spectrum, 0–30 °C, fresh or sea water, and air as 1 (what real-time code writes) or 1.000293."""


class IndexRange:
    """A range of relative refractive indices m = n_water / n_air (water seen from air).

    Parameters
    ----------
    low, high : float
        The smallest and largest m, > 1.

    Attributes
    ----------
    low, high : float
        The range of m.
    eta : (float, float)
        The range of n1/n2 from the air side, 1/high to 1/low.
    f0 : (float, float)
        The range of the normal-incidence reflectance ((m − 1)/(m + 1))².
    """

    def __init__(self, low: float, high: float):
        from wavephys.core.inputs import check_scalar

        check_scalar("low", low, lo=1.0, lo_open=True, hi=MAX_INDEX)
        check_scalar("high", high, lo=1.0, lo_open=True, hi=MAX_INDEX)
        if not 1.0 < low <= high:
            raise ValueError(f"low and high must satisfy 1 < low <= high, got {low} and {high}")
        self.low, self.high = float(low), float(high)

    @property
    def eta(self) -> tuple:
        return (1.0 / self.high, 1.0 / self.low)

    @property
    def f0(self) -> tuple:
        return (((self.low - 1) / (self.low + 1)) ** 2, ((self.high - 1) / (self.high + 1)) ** 2)

    def __contains__(self, m) -> bool:
        return self.low <= float(m) <= self.high

    def f0_contains(self, f0) -> bool:
        """Whether a normal-incidence reflectance belongs to the range.

        Parameters
        ----------
        f0 : float
            A reflectance at normal incidence, in [0, 1].

        Returns
        -------
        bool
        """
        from wavephys.core.inputs import check_scalar

        check_scalar("f0", f0, lo=0.0, hi=1.0)
        lo, hi = self.f0
        return lo <= float(f0) <= hi

    def __repr__(self) -> str:
        return (f"IndexRange(m {self.low:.4f}–{self.high:.4f}; n1/n2 from air {self.eta[0]:.4f}–{self.eta[1]:.4f}; "
                f"f0 {self.f0[0]:.5f}–{self.f0[1]:.5f})")


def water_index_range(**conditions) -> IndexRange:
    """Every relative index m = n_water/n_air that water has under :data:`WATER_CONDITIONS`.

    Evaluates :func:`water_refractive_index_quan_fry` (relative to real air) over the
    wavelength, temperature and salinity ranges; code that takes air as 1 with water's
    absolute index has m larger by the factor 1.000293, so both readings of air are in.

    Parameters
    ----------
    **conditions
        Narrower ranges than :data:`WATER_CONDITIONS`, as (low, high) pairs under the same
        names (``temperature_c=(15, 25)``, ``salinity=(0, 0)`` for fresh water only, ``n_air=(1.0, 1.0)``).

    Returns
    -------
    IndexRange
        m 1.3291–1.3519 over the default conditions (n1/n2 from air 0.7397–0.7524, f0
        0.01997–0.02239), the bounds of SPEC §2.7 before rounding.

    Examples
    --------
    >>> water_index_range()
    IndexRange(m 1.3291–1.3519; n1/n2 from air 0.7397–0.7524; f0 0.01997–0.02238)
    """
    unknown = sorted(set(conditions) - set(WATER_CONDITIONS))
    if unknown:
        raise ValueError(f"{unknown} are not conditions of water_index_range; they are {sorted(WATER_CONDITIONS)}")
    box = dict(WATER_CONDITIONS, **conditions)
    for name, (lo, hi) in box.items():
        full = WATER_CONDITIONS[name]
        if not (full[0] <= lo <= hi <= full[1]):
            raise ValueError(f"{name} must be a range (low, high) within {full}, got {(lo, hi)}")
    lam = np.linspace(*box["wavelength_nm"], 61)[:, None, None]
    t = np.linspace(*box["temperature_c"], 31)[None, :, None]
    s = np.linspace(*box["salinity"], 8)[None, None, :]
    n = water_refractive_index_quan_fry(lam, t, s)  # relative to real air
    air = box["n_air"]
    # a program that takes air as n_air holds water at its absolute index n × N_AIR: m = n × N_AIR / n_air
    return IndexRange(float(n.min()) * N_AIR / air[1], float(n.max()) * N_AIR / air[0])
