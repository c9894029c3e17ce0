r"""Fresnel reflectance of the water surface: exact, and the approximations shaders use.

Exact unpolarized dielectric reflectance (SPEC §2.2):

.. math::

    R_s = \left(\frac{n_1\cos\theta_i - n_2\cos\theta_t}{n_1\cos\theta_i + n_2\cos\theta_t}\right)^2,\quad
    R_p = \left(\frac{n_1\cos\theta_t - n_2\cos\theta_i}{n_1\cos\theta_t + n_2\cos\theta_i}\right)^2,\quad
    R = \tfrac12(R_s + R_p),\ T = 1 - R,

R = 1 under total internal reflection. Approximations, measured against it by
:func:`approximation_errors` and ``python -m bench optics``:

* ``"schlick"``: R ≈ f0 + (1 − f0)(1 − cos θ)⁵, f0 = ((n1 − n2)/(n1 + n2))². From the
  denser side (n1 > n2) it uses cos θt and gives 1 past the critical angle. Correction to
  the source: Schneider & Westermann (2001) print ⟨N, V⟩⁵ for (1 − ⟨N, V⟩)⁵, which gives
  R = 1 at normal incidence.
* ``"jensen_golias"``: R ≈ 1/(1 + cos θ)⁸ (Jensen & Goliáš 2001), for viewing water from air.
* ``"loviscach"``: sky reflection factor clamp(1 − 2.5 cos θ) (Loviscach 2003, §4).
* ``"lut"``: the exact R tabulated at N cos θ samples, linearly interpolated.

``cos_theta`` is always the cosine of the angle between the incoming ray and the normal,
in the incident medium n1 (0 at grazing, 1 at normal incidence).
"""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np

from wavephys._inputs import check_array, check_choice, check_int

__all__ = ["N_AIR", "N_WATER", "normal_reflectance", "reflectance_sp", "reflectance",
           "fresnel_lut", "sun_glint", "water_refractive_index", "METHODS"]

N_AIR = 1.000293
"""Refractive index of air (SPEC)."""
N_WATER = 1.333
"""Refractive index of water (SPEC)."""


def normal_reflectance(n1, n2):
    """f0 = ((n1 − n2)/(n1 + n2))², the reflectance at normal incidence (0.0204 for water)."""
    return ((n1 - n2) / (n1 + n2)) ** 2


def _cos_t(cos_i, eta):
    """cos θt by Snell (η = n1/n2) and the TIR mask."""
    k = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
    tir = k < 0
    return jnp.sqrt(jnp.where(tir, 0.0, k)), tir


def _check(cos_theta, n1, n2):
    check_array("cos_theta", cos_theta, lo=0.0, hi=1.0)
    check_array("n1", n1, lo=1.0)
    check_array("n2", n2, lo=1.0)
    return jnp.asarray(cos_theta, dtype=jnp.result_type(float, cos_theta))


def reflectance_sp(cos_theta, n1, n2):
    """Exact (R_s, R_p) reflectances; both 1 under total internal reflection."""
    c = _check(cos_theta, n1, n2)
    return _sp(c, n1, n2)


def _sp(c, n1, n2):
    ct, tir = _cos_t(c, n1 / n2)
    rs = ((n1 * c - n2 * ct) / (n1 * c + n2 * ct)) ** 2
    rp = ((n1 * ct - n2 * c) / (n1 * ct + n2 * c)) ** 2
    return jnp.where(tir, 1.0, rs), jnp.where(tir, 1.0, rp)


def _exact(c, n1, n2):
    rs, rp = _sp(c, n1, n2)
    return 0.5 * (rs + rp)


def _schlick(c, n1, n2):
    ct, tir = _cos_t(c, n1 / n2)
    cos_used = jnp.where(jnp.asarray(n1) > jnp.asarray(n2), ct, c)
    f0 = normal_reflectance(n1, n2)
    return jnp.where(tir, 1.0, f0 + (1.0 - f0) * (1.0 - cos_used) ** 5)


def _jensen_golias(c, n1, n2):
    return 1.0 / (1.0 + c) ** 8


def _loviscach(c, n1, n2):
    return jnp.clip(1.0 - 2.5 * c, 0.0, 1.0)


def fresnel_lut(n1, n2, size: int = 64):
    """The exact R at ``size`` equally spaced cos θ in [0, 1] (a texture for shaders)."""
    size = check_int("size", size, lo=2)
    check_array("n1", n1, lo=1.0)
    check_array("n2", n2, lo=1.0)
    return _exact(jnp.linspace(0.0, 1.0, size), n1, n2)


def _lut(c, n1, n2, size=64):
    """Linear interpolation in a uniform table: index arithmetic, as a shader does."""
    table = _exact(jnp.linspace(0.0, 1.0, size), n1, n2)
    u = c * (size - 1)
    i = jnp.clip(jnp.floor(u).astype(jnp.int32), 0, size - 2)
    f = u - i
    return (1.0 - f) * table[i] + f * table[i + 1]


METHODS = {"exact": _exact, "schlick": _schlick, "jensen_golias": _jensen_golias,
           "loviscach": _loviscach, "lut": _lut}
"""Reflectance methods by name."""


def reflectance(cos_theta, n1=N_AIR, n2=N_WATER, method: str = "exact", lut_size: int = 64):
    """Unpolarized reflectance R (dimensionless, in [0, 1]) by the chosen method.

    Parameters
    ----------
    cos_theta : array_like
        cos θi in [0, 1], in the incident medium.
    n1, n2 : float
        Refractive indices of the incident and transmitting media, ≥ 1 (default air to
        water; swap them for light from under water).
    method : {"exact", "schlick", "jensen_golias", "loviscach", "lut"}
    lut_size : int
        Table entries for ``"lut"`` (≥ 2).

    Examples
    --------
    >>> round(float(reflectance(1.0, 1.0, 1.333)), 4)   # f0 of water from vacuum
    0.0204
    >>> round(float(reflectance(1.0)), 5)              # from air (n = 1.000293)
    0.02033
    >>> float(reflectance(0.5, 1.333, 1.000293))      # 60° from below: past 48.6°
    1.0
    """
    check_choice("method", method, METHODS)
    c = _check(cos_theta, n1, n2)
    if method == "lut":
        return _lut(c, n1, n2, check_int("lut_size", lut_size, lo=2))
    return METHODS[method](c, n1, n2)


def sun_glint(n_dot_h):
    """Loviscach's (2003) sun highlight g = clamp(100·n·h − 98.95), n·h in [−1, 1]."""
    check_array("n_dot_h", n_dot_h, lo=-1.0, hi=1.0)
    return jnp.clip(100.0 * jnp.asarray(n_dot_h) - 98.95, 0.0, 1.0)


def water_refractive_index(wavelength_nm, temperature_k: float = 293.15):
    """Refractive index of water vs wavelength (Schiebener et al. 1990, via colour-science).

    Parameters
    ----------
    wavelength_nm : array_like
        Wavelength in vacuum, nm, within [200, 1100] (the model's range of validity).
    temperature_k : float
        Water temperature, K (default 20 °C).
    """
    check_array("wavelength_nm", wavelength_nm, lo=200.0, hi=1100.0)
    from colour.phenomena import light_water_refractive_index_Schiebener1990

    return np.asarray(light_water_refractive_index_Schiebener1990(np.asarray(wavelength_nm, float),
                                                                    temperature_k))
