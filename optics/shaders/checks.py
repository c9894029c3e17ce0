r"""The registered shader checks: what each feeds a user's function, and what it accepts back.

A check is one :class:`ShaderCheck` entry in :data:`SHADER_CHECKS`: the argument *roles* it can
feed (each a GLSL type with a meaning, :data:`ROLES`), the result types it accepts, and a
``domain(**options)`` that builds the inputs over the whole domain with the *models* of what a
correct function may compute (its physical constants left free) and of the mistakes real code
makes (:mod:`optics.shaders.models`). A function passes when a correct model, with constants
the physics allows, explains its output within the tolerance; when it fails, the model that
does explain it names the cause, with its fitted constants.

===================  ===========================================  =====================================
check                a correct function computes                  error, default tolerance
===================  ===========================================  =====================================
``fresnel``          exact Fresnel or Schlick's form (``form``),  \|R − R_ref\|, half an 8-bit display level
                     both sides, with water's index (any in        (1/510) of a radiance of 1
                     1.3291–1.3519, f0 0.0200–0.0224)
``refract``          Snell's law with water's index; vec3(0) or   \|t − t_ref\|, 1e-4 (float32 arithmetic)
                     the mirror ray under TIR (``tir``)
``reflect``          r = d − 2(d·n)n                              \|r − r_ref\|, 1e-4
``transmittance``    Beer–Lambert e^{−a d}                        \|T − T_ref\|, half an 8-bit level
``rgb_absorption``   :func:`optics.light.attenuation.water_srgb`  max channel error, the larger of 1.25 ×
                     (spectral pure water, D65)                   the best RGB exponential's and half a level
``normal_decode``    the unit normal behind an encoded texel      \|n − n_ref\|, 1.5 × an exact decoder's
                     (OpenGL or DirectX green, packed or not)     on the same (quantized) texels
``height_normal``    normals of a periodic band-limited height    \|n − n_ref\|, 2 sin 0.5° (1°)
                     (or displacement) texture
===================  ===========================================  =====================================
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

from optics.shaders.absorption import (rgb_absorption_domain, rgb_absorption_late, transmittance_domain,
                                       transmittance_late)
from optics.shaders.domain import Domain, finite_cause, scalar_error, vector_error
from optics.shaders.normals import height_normal_domain, height_normal_late, normal_decode_domain, normal_decode_late
from optics.shaders.rays import (fresnel_domain, fresnel_early, fresnel_late, reflect_domain, reflect_late,
                                 refract_domain, refract_early, refract_error, refract_late)
from optics.shaders.roles import ROLES, SIDE_ROLES

__internal__ = True  # the registry's and the runner's pieces: users call optics.shaders.check_glsl
__all__ = ["ROLES", "SIDE_ROLES", "Domain", "ShaderCheck", "SHADER_CHECKS", "finite_cause"]


def _nothing(values, domain, errors):
    return ""


@dataclass(frozen=True)
class ShaderCheck:
    """One registered check (module doc).

    Attributes
    ----------
    name, quantity, summary : str
        Its name (``against=``), the error it measures, what it checks in words.
    roles : tuple of str
        The roles it can feed (:data:`ROLES`).
    returns : tuple of str
        The result types it accepts.
    takes : tuple of str
        The default roles, in order.
    domain : callable
        ``domain(**options)`` → :class:`~optics.shaders.domain.Domain`.
    error : callable
        ``error(values, expected)`` → (n,) errors.
    early, late : callable
        ``(values, domain, errors)`` → a cause before any fit (NaN where physics has a branch, a constant
        output) / after no model explained the output (a measurement in words), or "".
    sided : bool
        Whether its inputs come from both sides of the surface (rays): a function that cannot tell the side is
        checked from the air.
    per_channel : bool
        A scalar quantity that a function may return as a colour: each channel is checked (and fitted) alone.
    """

    name: str
    quantity: str
    summary: str
    roles: tuple
    returns: tuple
    takes: tuple
    domain: Callable
    error: Callable
    early: Callable = _nothing
    late: Callable = _nothing
    sided: bool = False
    per_channel: bool = False


_RAY_ROLES = ("cos_theta", "cos_theta_t", "n1", "n2", "eta", "ior", "f0", "f0_rgb", "front_facing", "incident", "view",
              "normal", "facing_normal")

SHADER_CHECKS = {c.name: c for c in (
    ShaderCheck("fresnel", "|R − R_ref|", "Fresnel reflectance from both sides",
                _RAY_ROLES + ("reflected_color", "refracted_color"), ("float", "vec3"), ("cos_theta", "n1", "n2"),
                fresnel_domain, scalar_error, fresnel_early, fresnel_late, sided=True, per_channel=True),
    ShaderCheck("refract", "|t − t_ref|", "refracted direction, with total internal reflection", _RAY_ROLES,
                ("vec3",), ("incident", "facing_normal", "eta"), refract_domain, refract_error, refract_early,
                refract_late, sided=True),
    ShaderCheck("reflect", "|r − r_ref|", "mirror direction", _RAY_ROLES, ("vec3",), ("incident", "facing_normal"),
                reflect_domain, vector_error, late=reflect_late, sided=True),
    ShaderCheck("transmittance", "|T − e^(-a d)|", "Beer–Lambert transmittance",
                ("distance", "coefficient", "coefficients", "color"), ("float", "vec3"), ("distance", "coefficients"),
                transmittance_domain, scalar_error, transmittance_late),
    ShaderCheck("rgb_absorption", "max channel |T − T_spectral|", "RGB water colour against the spectral answer",
                ("distance", "color"), ("vec3",), ("distance",), rgb_absorption_domain, scalar_error,
                late=rgb_absorption_late),
    ShaderCheck("normal_decode", "|n − n_ref|", "normal-map texel to unit normal", ("texel", "texel_rgb", "texel_rg"),
                ("vec3",), ("texel",), normal_decode_domain, vector_error, late=normal_decode_late),
    ShaderCheck("height_normal", "|n − n_ref|", "normal from a height or displacement texture",
                ("heights", "displacement", "uv", "texel_uv", "texel_size"), ("vec3",),
                ("heights", "uv", "texel_uv", "texel_size"), height_normal_domain, vector_error,
                late=height_normal_late),
)}
"""The shader checks by name (``against=``). A new check is one entry here and its corpus entries."""
