r"""The registered shader checks: what each feeds a user's GLSL function, and what it expects back.

A check is one :class:`ShaderCheck` entry in :data:`SHADER_CHECKS`: the argument *roles*
it can feed (each a GLSL type with a meaning, :data:`ROLES`), the return types it accepts,
a ``domain(**options)`` that builds the inputs over the whole domain and the reference
answer from the library's float64 physics, and the *alternatives*: the answers that known
mistakes would give. When a function fails, the first alternative that its output matches
names the cause. The reference is evaluated at the float32 values the shader received,
so what is left is the function's own error.

===================  ===========================================  =====================================
check                reference                                    error, default tolerance
===================  ===========================================  =====================================
``fresnel``          :func:`optics.light.fresnel.reflectance`     \|R − R_ref\|, 2e-4 (float32 arithmetic)
                     (``form``: exact, schlick, …), both sides
``refract``          :func:`optics.light.directions.refract`;     \|t − t_ref\|, 1e-4; under TIR vec3(0)
                     vec3(0) or the mirror ray under TIR          or the mirror ray (``tir``)
``reflect``          :func:`optics.light.directions.reflect`      \|r − r_ref\|, 1e-4
``transmittance``    Beer–Lambert e^{−a d}                        \|T − T_ref\|, 1e-5
``rgb_absorption``   :func:`optics.light.attenuation.water_srgb`  max channel error, 1.25 × the best RGB
                     (spectral pure water, D65)                   exponential's (``fit_rgb_coefficients``)
``normal_decode``    the unit normal behind an encoded texel      \|n − n_ref\|, 1.5 × an exact decoder's
                     (OpenGL or DirectX green, packed or not)     on the same (quantized) texels
``height_normal``    normals from spectral slopes of a periodic   \|n − n_ref\|, 2 sin 0.5° (1°)
                     band-limited height texture
===================  ===========================================  =====================================
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from optics.light.fresnel import N_AIR, N_WATER, REFLECTANCE_METHODS, normal_reflectance

__internal__ = True  # the registry's and the runner's pieces: users call optics.shaders.check_glsl
__all__ = ["ROLES", "Domain", "ShaderCheck", "SHADER_CHECKS"]

ROLES = {
    "cos_theta": ("float", "cos θ of the incoming ray against the normal, in the incident medium (0 grazing, 1 normal)"),
    "n1": ("float", "refractive index of the incident medium"),
    "n2": ("float", "refractive index beyond the surface"),
    "eta": ("float", "n1 / n2"),
    "f0": ("float", "reflectance at normal incidence, ((n1 − n2)/(n1 + n2))²"),
    "incident": ("vec3", "unit direction of travel of the incoming ray (towards the surface)"),
    "view": ("vec3", "unit vector from the surface back along the incoming ray (−incident; engines' V)"),
    "normal": ("vec3", "unit surface normal pointing into the air, whichever side the ray comes from"),
    "facing_normal": ("vec3", "unit surface normal facing the incoming ray (dot(incident, N) < 0), as GLSL's "
                              "refract and reflect want it"),
    "distance": ("float", "path length through the water, m"),
    "coefficient": ("float", "absorption coefficient, 1/m"),
    "coefficients": ("vec3", "RGB absorption coefficients, 1/m"),
    "texel": ("vec4", "the normal map's texel as the shader samples it (alpha 1)"),
    "texel_rgb": ("vec3", "the normal map's texel, RGB only"),
    "texel_rg": ("vec2", "a two-channel normal map's texel (z to be reconstructed)"),
    "heights": ("sampler2D", "height texture: metres in red, repeat wrap, linear filter, row 0 at v = 0"),
    "uv": ("vec2", "texture coordinate of a texel centre"),
    "texel_uv": ("vec2", "one texel in texture coordinates (1/width, 1/height)"),
    "texel_size": ("float", "one texel, m"),
}
"""Argument roles: name → (GLSL type, meaning). A user says which role each parameter plays (``takes``)."""


@dataclass(frozen=True)
class Domain:
    """The inputs of one check over its domain and the answer expected for each.

    ``inputs``: role → (n, c) float64 array (the float32 values the shader gets) or a
    :class:`~optics.shaders.glsl.Sampler`; ``expected``: (n, c) reference; ``axis``: the
    label and values (n,) a chart puts on its x axis; ``groups``: (n,) labels (one line each in
    a chart, e.g. "above", "below"); ``context``: name → (n,) values shown at the worst input;
    ``alternatives``: (cause, (n, c) answer of that mistake) in the order they are tried;
    ``valid``: (n,) mask of the samples whose error counts (all by default).
    """

    inputs: dict
    expected: np.ndarray
    tolerance: float
    axis: tuple
    groups: np.ndarray
    context: dict
    note: str
    alternatives: list = field(default_factory=list)
    extra: dict = field(default_factory=dict)


def _nothing(values, domain, errors):
    return ""


@dataclass(frozen=True)
class ShaderCheck:
    """One registered check (module doc).

    ``error(values, expected, domain)`` → (n,) errors; ``early(values, domain, errors)`` → a
    cause that takes precedence over the alternatives (NaN where the physics has a branch, a
    constant output), or ""; ``late(values, domain, errors)`` → a cause tried when no
    alternative matches (a fitted scale, a wrong f0), or ""."""

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


# -- shared pieces -------------------------------------------------------------------------
def _f32(a):
    """The float32 value a shader receives, back in float64."""
    return np.asarray(a, np.float64).astype(np.float32).astype(np.float64)


def _unit(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _vector_error(values, expected, domain=None):
    return np.linalg.norm(np.asarray(values, np.float64) - expected, axis=-1)


def _scalar_error(values, expected, domain=None):
    return np.max(np.abs(np.asarray(values, np.float64) - expected), axis=-1)


def _degrees(a, b):
    """Angle between (n, 3) vectors, degrees (NaN where either is zero)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.sum(a * b, -1) / (np.linalg.norm(a, axis=-1) * np.linalg.norm(b, axis=-1))
    return np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))


def _finite_cause(values, domain):
    bad = ~np.isfinite(values).all(axis=-1)
    if not bad.any():
        return ""
    i = int(np.argmax(bad))
    where = ", ".join(f"{k} = {v[i]:.4g}" if np.asarray(v[i]).dtype.kind in "fiu" else f"{k} = {v[i]}"
                      for k, v in domain.context.items())
    return f"returns NaN or inf at {int(bad.sum())} of {bad.size} inputs (first at {where})"


def _length_cause(values, mask=None):
    length = np.linalg.norm(np.asarray(values, np.float64), axis=-1)
    if mask is not None:
        length = length[mask]
    if length.size and np.max(np.abs(length - 1.0)) > 1e-3:
        return f"returns vectors of length {length.min():.4g} to {length.max():.4g}: not normalized"
    return ""


def _sphere_tangents(normal, rng):
    """A unit tangent per normal, at a random azimuth."""
    helper = np.where(np.abs(normal[:, 2:3]) < 0.9, [[0.0, 0.0, 1.0]], [[1.0, 0.0, 0.0]])
    t1 = _unit(np.cross(normal, helper))
    t2 = np.cross(normal, t1)
    phi = rng.uniform(0.0, 2.0 * math.pi, (len(normal), 1))
    return np.cos(phi) * t1 + np.sin(phi) * t2


def _tilted_normals(n, rng, max_slope=0.5):
    """Unit normals pointing up (+z), tilted by slopes up to ``max_slope`` in random directions."""
    s = rng.uniform(-max_slope, max_slope, (n, 2))
    return _unit(np.column_stack([-s, np.ones(n)]))


_SIDES = {"above": (N_AIR, N_WATER), "below": (N_WATER, N_AIR)}


def _check_sides(sides):
    if isinstance(sides, str):
        sides = (sides,)
    if not isinstance(sides, (tuple, list)) or not sides or any(s not in _SIDES for s in sides):
        raise ValueError(f"sides must be a non-empty subset of {tuple(_SIDES)}, got {sides!r}")
    return tuple(dict.fromkeys(sides))


def _indices(n_air, n_water):
    from wavephys.core.inputs import check_scalar

    check_scalar("n_air", n_air, lo=1.0, hi=10.0)
    check_scalar("n_water", n_water, lo=1.0, hi=10.0, lo_open=True)
    if not n_water > n_air:
        raise ValueError(f"n_water must exceed n_air (the water is the denser side), got {n_water} and {n_air}")
    return {"above": (float(n_air), float(n_water)), "below": (float(n_water), float(n_air))}


def _rays(samples, sides, indices, seed=0):
    """Rays at every incidence angle 0–90° from each side: angle, side, n1, n2, the up normal,
    the facing normal, the incident direction (float32-rounded, float64 arrays)."""
    rng = np.random.default_rng(seed)
    theta = np.tile(np.linspace(0.0, 90.0, samples), len(sides))
    side = np.repeat(np.array(sides), samples)
    n1 = np.array([indices[s][0] for s in side])
    n2 = np.array([indices[s][1] for s in side])
    up = _tilted_normals(theta.size, rng)
    facing = np.where((side == "above")[:, None], up, -up)
    t = _sphere_tangents(facing, rng)
    c, s = np.cos(np.radians(theta))[:, None], np.sin(np.radians(theta))[:, None]
    incident = _unit(-c * facing + s * t)
    return dict(theta=theta, side=side, n1=_f32(n1), n2=_f32(n2), normal=_f32(up), facing=_f32(facing),
                incident=_f32(incident))


def _ray_inputs(r):
    """Every ray role (the float32 values) of the rays ``r``."""
    d, nf = r["incident"], r["facing"]
    cos = _f32(np.clip(-np.sum(_unit(d) * _unit(nf), -1), 0.0, 1.0))
    return {"cos_theta": cos[:, None], "n1": r["n1"][:, None], "n2": r["n2"][:, None],
            "eta": _f32(r["n1"] / r["n2"])[:, None], "f0": _f32(normal_reflectance(r["n1"], r["n2"]))[:, None],
            "incident": d, "view": -d, "normal": r["normal"], "facing_normal": nf}


def _cos_t(cos_i, n1, n2):
    k = 1.0 - (n1 / n2) ** 2 * (1.0 - cos_i ** 2)
    return np.sqrt(np.maximum(k, 0.0)), k < 0


# -- fresnel ---------------------------------------------------------------------------------
def _schlick_cos(cos, n1, n2):
    f0 = normal_reflectance(n1, n2)
    return f0 + (1.0 - f0) * (1.0 - cos) ** 5


def fresnel_domain(*, form="exact", sides=None, n_air=N_AIR, n_water=N_WATER, samples=2048, tolerance=2e-4):
    """Reflectance at every incidence angle from each side against ``form`` (a name in
    :data:`~optics.light.fresnel.REFLECTANCE_METHODS`; "jensen_golias" and "loviscach" are
    forms for viewing from air: their default ``sides`` is above only)."""
    REFLECTANCE_METHODS.check(form, "form")
    sides = _check_sides(sides or (("above",) if form in ("jensen_golias", "loviscach") else ("above", "below")))
    r = _rays(_samples(samples), sides, _indices(n_air, n_water))
    inputs = _ray_inputs(r)
    cos, n1, n2 = inputs["cos_theta"][:, 0], inputs["n1"][:, 0], inputs["n2"][:, 0]

    def ref(name, c=cos, a=n1, b=n2):
        with np.errstate(invalid="ignore", divide="ignore"):  # 0/0 at grazing incidence, masked by the TIR branch
            return np.asarray(REFLECTANCE_METHODS[name](c, a, b), np.float64)[:, None]

    ct, tir = _cos_t(cos, n1, n2)
    below = n1 > n2
    alternatives = [
        ("the index ratio is inverted: it computes with n2/n1 where n1/n2 is due", ref(form, cos, n2, n1)),
        ("no total internal reflection from below: past the critical angle it gives R < 1 where R = 1 "
         "(Schlick's formula with the water side's cos θi and no TIR test)",
         np.where(below, _schlick_cos(cos, n1, n2), ref(form)[:, 0])[:, None]),
        ("cos θ of the wrong ray: it uses the refracted ray's cos θt where the incident ray's cos θi is due",
         np.where(tir, 1.0, _schlick_cos(ct, n1, n2))[:, None] if form == "schlick" else ref(form, ct)),
    ]
    alternatives += [(f"this is the {name} form, not {form}: check it with form={name!r}", ref(name))
                     for name in REFLECTANCE_METHODS if name not in (form, "lut")]
    crit = math.degrees(math.asin(n_air / n_water))
    return Domain(inputs, ref(form), _tolerance(tolerance), ("incidence angle θ (degrees)", r["theta"]), r["side"],
                  dict(theta_deg=r["theta"], side=r["side"], n1=n1, n2=n2), f"{form} reflectance over 0–90° from "
                  f"{' and '.join(sides)} ({len(cos)} rays; critical angle {crit:.2f}° from below)", alternatives)


def _fresnel_early(values, domain, errors):
    v = values[:, 0]
    for side in np.unique(domain.groups):
        on = domain.groups == side
        if np.ptp(v[on]) < 1e-6 and np.ptp(domain.expected[on, 0]) > 1e-3:
            return (f"gives a constant {v[on][0]:.4g} on the {side} side, whatever the angle: a clamp such as "
                    f"max(dot(V, N), 0.0) hides a negative cosine (the view or the normal faces the wrong way there)")
    if v.min() < -1e-6 or v.max() > 1.0 + 1e-6:
        return f"gives R outside [0, 1] ({v.min():.4g} to {v.max():.4g}): a missing clamp or a wrong sign"
    return ""


def _fresnel_late(values, domain, errors):
    v = values[:, 0]
    normal = domain.context["theta_deg"] == 0.0
    f0 = normal_reflectance(domain.context["n1"][normal], domain.context["n2"][normal])
    got = v[normal]
    if normal.any() and np.max(np.abs(got - f0)) > max(domain.tolerance, 0.1 * float(f0.max())):
        g = float(got[0])
        hint = (" (f0 = (n1 − n2)/(n1 + n2) not squared)" if abs(g - math.sqrt(f0[0])) < 1e-3 else
                f" ({g:.4g} is the f0 of an index {(1 + math.sqrt(max(g, 0))) / (1 - math.sqrt(min(max(g, 0), 0.99))):.4g} "
                f"against 1)")
        return f"F0 from the wrong indices: at normal incidence it gives {g:.4g} where f0 = {float(f0[0]):.4g}{hint}"
    return ""


# -- refraction and reflection --------------------------------------------------------------
def refract_domain(*, sides=("above", "below"), n_air=N_AIR, n_water=N_WATER, samples=1024, tir="either",
                   tolerance=1e-4):
    """Refracted directions at every incidence angle from each side, against
    :func:`optics.light.directions.refract`; under total internal reflection the function
    may return ``tir``: "zero" (vec3(0), as GLSL's refract), "reflect" (the mirror ray) or "either"."""
    from optics.light.directions import reflect, refract
    from wavephys.core.inputs import check_choice

    check_choice("tir", tir, ("zero", "reflect", "either"))
    sides = _check_sides(sides)
    r = _rays(_samples(samples), sides, _indices(n_air, n_water))
    inputs = _ray_inputs(r)
    d, nf, n1, n2 = inputs["incident"], inputs["facing_normal"], inputs["n1"][:, 0], inputs["n2"][:, 0]
    t, is_tir = refract(d, nf, n1, n2)
    t, mirror = np.asarray(t), np.asarray(reflect(d, nf))
    zero = np.zeros_like(t)
    expected = np.where(is_tir[:, None], mirror if tir == "reflect" else zero, t)
    alternatives = [
        ("the index ratio is inverted: it refracts with n2/n1 where eta = n1/n2 is due",
         _glsl_refract(d, nf, n2 / n1)),
        ("from below, the normal faces the wrong way: GLSL's refract(I, N, eta) wants N against I (use −N for "
         "rays from the water)", _glsl_refract(d, inputs["normal"], n1 / n2)),
        ("the normal faces the wrong way: GLSL's refract(I, N, eta) wants N against I",
         _glsl_refract(d, -nf, n1 / n2)),
        ("it refracts the view vector (towards the eye) where the incident direction (−V) is due",
         _glsl_refract(-d, -nf, n1 / n2)),
    ]
    said = {"zero": "vec3(0)", "reflect": "the mirror ray", "either": "vec3(0) or the mirror ray"}[tir]
    return Domain(inputs, expected, _tolerance(tolerance), ("incidence angle θ (degrees)", r["theta"]), r["side"],
                  dict(theta_deg=r["theta"], side=r["side"], n1=n1, n2=n2),
                  f"refraction over 0–90° from {' and '.join(sides)} ({len(d)} rays, tilted normals; under total "
                  f"internal reflection: {said})", alternatives, dict(tir=is_tir, mirror=mirror, mode=tir))


def _glsl_refract(d, n, eta):
    """GLSL's refract(I, N, eta) as the spec writes it (vec3(0) past the critical angle)."""
    eta = np.asarray(eta, np.float64).reshape(-1, 1)
    c = np.sum(n * d, -1, keepdims=True)
    k = 1.0 - eta * eta * (1.0 - c * c)
    return np.where(k < 0, 0.0, eta * d - (eta * c + np.sqrt(np.maximum(k, 0.0))) * n)


def _refract_error(values, expected, domain):
    err = _vector_error(values, expected)
    if domain.extra["mode"] == "either":
        err = np.where(domain.extra["tir"], np.minimum(err, _vector_error(values, domain.extra["mirror"])), err)
    return err


def _refract_early(values, domain, errors):
    tir = domain.extra["tir"]
    if tir.any() and not np.isfinite(values[tir]).all() and np.isfinite(values[~tir]).all():
        return ("NaN past the critical angle: sqrt of a negative k (1 − eta²(1 − cos²θ)) without a total "
                "internal reflection test")
    return ""


def _refract_late(values, domain, errors):
    return _length_cause(values, ~domain.extra["tir"])


def reflect_domain(*, sides=("above", "below"), samples=1024, tolerance=1e-4):
    """Mirror directions at every incidence angle from each side, against
    :func:`optics.light.directions.reflect`."""
    from optics.light.directions import reflect

    sides = _check_sides(sides)
    r = _rays(_samples(samples), sides, _indices(N_AIR, N_WATER))
    inputs = _ray_inputs(r)
    d, nf = inputs["incident"], inputs["facing_normal"]
    expected = np.asarray(reflect(d, nf))
    alternatives = [("it returns the mirrored view vector −r (reflect(V, N) with V towards the eye) where r = "
                     "reflect(I, N) is due", -expected)]
    return Domain(inputs, expected, _tolerance(tolerance), ("incidence angle θ (degrees)", r["theta"]), r["side"],
                  dict(theta_deg=r["theta"], side=r["side"]),
                  f"reflection over 0–90° from {' and '.join(sides)} ({len(d)} rays, tilted normals)", alternatives)


def _length_late(values, domain, errors):
    return _length_cause(values)


# -- absorption ----------------------------------------------------------------------------------
def transmittance_domain(*, max_distance=20.0, samples=4096, tolerance=1e-5, seed=0):
    """Beer–Lambert e^{−a d} over path lengths 0 to ``max_distance`` m and coefficients
    0.005–5 1/m (a different one per channel when the function takes ``coefficients``)."""
    from wavephys.core.inputs import check_scalar

    check_scalar("max_distance", max_distance, lo=0.0, lo_open=True, hi=1e4)
    rng = np.random.default_rng(seed)
    n = _samples(samples)
    d = _f32(np.linspace(0.0, max_distance, n))
    a = _f32(np.exp(rng.uniform(math.log(0.005), math.log(5.0), (n, 3))))
    expected = np.exp(-a * d[:, None])

    def scaled(s):
        return np.exp(-s * a * d[:, None])

    alternatives = [
        ("the RGB channels are reversed (coefficients read as BGR)", np.exp(-a[:, ::-1] * d[:, None])),
        ("not exponential: T falls linearly, 1 − a·d (clamped), where Beer–Lambert gives e^{−a d}",
         np.clip(1.0 - a * d[:, None], 0.0, 1.0)),
        ("the path length is counted twice (2d: down and back up?) where the path d is due", scaled(2.0)),
        ("half the path length is used (d/2) where the path d is due", scaled(0.5)),
        ("the coefficients are taken per cm (×100): they are per metre", scaled(100.0)),
        ("the coefficients are taken as 1/(100 m) (×0.01): they are per metre", scaled(0.01)),
        ("it uses exp2 (2^{−a d}) where e^{−a d} is due", np.exp2(-a * d[:, None])),
        ("it uses 10^{−a d} (a decadic coefficient) where e^{−a d} is due", 10.0 ** (-a * d[:, None])),
    ]
    inputs = {"distance": d[:, None], "coefficient": a[:, :1], "coefficients": a}
    return Domain(inputs, expected, _tolerance(tolerance), ("path length d (m)", d), np.full(n, "T"),
                  dict(distance=d, a_r=a[:, 0], a_g=a[:, 1], a_b=a[:, 2]),
                  f"e^(-a d) for d = 0–{max_distance:g} m, a = 0.005–5 1/m ({n} samples)", alternatives)


def _transmittance_early(values, domain, errors):
    if values.min() < -1e-6 or values.max() > 1.0 + 1e-6:
        return f"gives T outside [0, 1] ({values.min():.4g} to {values.max():.4g}): a wrong sign in the exponent?"
    return ""


def _transmittance_late(values, domain, errors):
    v = values
    ref = domain.expected[:, :v.shape[1]]
    use = (ref > 1e-6) & (ref < 1.0 - 1e-4) & (v > 1e-30) & (v < 1.0)
    if use.sum() > 10:
        s = float(np.median(np.log(v[use]) / np.log(ref[use])))
        if abs(s - 1.0) > 0.01 and np.max(np.abs(v - ref ** s)) <= max(3 * domain.tolerance, 1e-4):
            return (f"the path length (or the coefficient) is scaled by {s:.4g}: −ln T = {s:.4g}·a·d "
                    f"where a·d is due")
    return ""


def rgb_absorption_domain(*, max_distance=5.0, illuminant="D65", samples=256, tolerance=None):
    """The linear-sRGB transmittance of pure water over path lengths 0 to ``max_distance`` m,
    against the spectral answer :func:`optics.light.attenuation.water_srgb`; the default
    tolerance is 1.25 × the error of the best RGB exponential over the same path lengths."""
    from optics.light.attenuation import fit_rgb_coefficients, rgb_error, water_srgb
    from wavephys.core.inputs import check_scalar

    check_scalar("max_distance", max_distance, lo=0.05, hi=100.0)
    n = _samples(samples)
    d = _f32(np.linspace(0.0, max_distance, n))
    expected = np.asarray(water_srgb(d, illuminant), np.float64).reshape(n, 3)
    best_a = np.asarray(fit_rgb_coefficients(max_distance, illuminant))
    best = float(np.max(rgb_error(d, best_a, illuminant)))
    tol = 1.25 * best if tolerance is None else _tolerance(tolerance)

    def fit(a):
        return np.exp(-np.asarray(a)[None, :] * d[:, None])

    alternatives = [
        ("the RGB channels are reversed (blue absorbed most): water absorbs red most", fit(best_a[::-1])),
        ("the coefficients are per cm (×100 too large): they are per metre", fit(100.0 * best_a)),
        ("the coefficients are 100× too small (per 100 m?): they are per metre", fit(0.01 * best_a)),
        ("the path length is counted twice (2d) where d is due", fit(2.0 * best_a)),
    ]
    return Domain({"distance": d[:, None]}, expected, tol, ("path length d (m)", d), np.full(n, "RGB"),
                  dict(distance=d), f"pure water, {illuminant}, d = 0–{max_distance:g} m ({n} samples); the best RGB "
                  f"exponential (a = {', '.join(f'{x:.4g}' for x in best_a)} 1/m) errs {best:.4g}", alternatives)


def _rgb_absorption_late(values, domain, errors):
    d = domain.context["distance"]
    use = (d > 0.05) & np.all((values > 1e-6) & (values < 1.0), axis=1)
    if use.sum() < 4:
        return ""
    a = -np.log(values[use]).T @ d[use] / (d[use] @ d[use])
    ref = -np.log(np.clip(domain.expected[use], 1e-9, 1.0)).T @ d[use] / (d[use] @ d[use])
    if np.argmax(a) != np.argmax(ref):
        return (f"the channels absorb in the wrong order: fitted a = ({', '.join(f'{x:.3g}' for x in a)}) 1/m, "
                f"water's ({', '.join(f'{x:.3g}' for x in ref)}) 1/m")
    ratio = a / ref
    return (f"the fitted coefficients are ({', '.join(f'{x:.3g}' for x in a)}) 1/m where pure water's are "
            f"({', '.join(f'{x:.3g}' for x in ref)}) 1/m (ratios {', '.join(f'{x:.3g}' for x in ratio)})")


# -- normals ---------------------------------------------------------------------------------------
def _hemisphere(n, max_angle=80.0):
    """Unit normals on the upper hemisphere up to ``max_angle`` from +z (a Fibonacci spiral)."""
    i = np.arange(n) + 0.5
    cos = 1.0 - (1.0 - math.cos(math.radians(max_angle))) * i / n
    phi = i * math.pi * (3.0 - math.sqrt(5.0))
    s = np.sqrt(1.0 - cos ** 2)
    return np.column_stack([s * np.cos(phi), s * np.sin(phi), cos])


def _encode(normals, convention, packed, bits, channels):
    e = normals * np.array([1.0, -1.0 if convention == "directx" else 1.0, 1.0])
    t = 0.5 + 0.5 * e if packed else e
    if bits is not None:
        q = 2 ** bits - 1
        t = np.round(t * q) / q
    if channels == 2:
        t[:, 2] = 0.0
    return _f32(t)


def _decode_exact(texel, convention, packed, channels):
    e = 2.0 * texel - 1.0 if packed else texel.copy()
    if channels == 2:
        e[:, 2] = np.sqrt(np.clip(1.0 - e[:, 0] ** 2 - e[:, 1] ** 2, 0.0, None))
    e[:, 1] *= -1.0 if convention == "directx" else 1.0
    return _unit(e)


def normal_decode_domain(*, convention="opengl", packed=True, bits=8, channels=3, samples=4096, tolerance=None):
    """Decoding a normal map's texel: unit normals up to 80° from +z, encoded as the texture
    holds them (``convention`` "opengl": green = +y, "directx": green = −y; ``packed``:
    rgb = 0.5 + 0.5 n, else n itself; ``bits``: 8, 16 or None (float); ``channels`` 3 or 2,
    z reconstructed). The decoded normal must be the world normal, y up in the texture."""
    from wavephys.core.inputs import check_bool, check_choice

    check_choice("convention", convention, ("opengl", "directx"))
    check_bool("packed", packed)
    check_choice("bits", bits, (8, 10, 16, None))
    check_choice("channels", channels, (2, 3))
    if bits is not None and not packed:
        raise ValueError("bits must be None when packed is False (an unpacked normal map is a float texture)")
    n = _samples(samples)
    normals = _hemisphere(n)
    texel = _encode(normals, convention, packed, bits, channels)
    exact = _decode_exact(texel, convention, packed, channels)
    floor = float(np.max(_vector_error(exact, normals)))
    tol = 1.5 * floor + 1e-5 if tolerance is None else _tolerance(tolerance)
    other = "directx" if convention == "opengl" else "opengl"
    e = 2.0 * texel - 1.0 if packed else texel

    def flip_y(v):
        return v * np.array([1.0, -1.0, 1.0])

    alternatives = [
        (f"the green channel is flipped: the texture is {convention} (green = {'+' if convention == 'opengl' else '−'}y)"
         f" and the function decodes {other}", flip_y(normals)),
        ("the texel is not unpacked: n = 2·rgb − 1 is missing (the texture is packed)" if packed else
         "the texel is unpacked (2·rgb − 1) but the texture holds n itself (a float normal map)",
         _unit(texel) if packed else _unit(2.0 * texel - 1.0)),
        ("it unpacks twice (2·(2·rgb − 1) − 1)", _unit(2.0 * e - 1.0)),
        ("x and y are swapped (red holds x, green y)", normals[:, [1, 0, 2]]),
    ]
    inputs = {"texel": np.column_stack([texel, np.ones(n)]), "texel_rgb": texel, "texel_rg": texel[:, :2]}
    polar = np.degrees(np.arccos(normals[:, 2]))
    return Domain(inputs, normals, tol, ("normal's angle from +z (degrees)", polar), np.full(n, convention),
                  dict(polar_deg=polar, azimuth_deg=np.degrees(np.arctan2(normals[:, 1], normals[:, 0]))),
                  f"{convention}, {'packed 0.5 + 0.5 n' if packed else 'unpacked n'}, "
                  f"{f'{bits}-bit' if bits else 'float'}, {channels} channels; {n} normals up to 80° from +z "
                  f"(an exact decoder errs {floor:.3g})", alternatives)


def height_normal_domain(*, n=128, texel_size=0.05, max_slope=0.35, up="z", seed=0, tolerance=None):
    """Normals of a periodic band-limited height texture (n × n texels of ``texel_size`` m,
    shortest wave 16 texels, steepest slope ``max_slope``), against spectral slopes:
    normalize(−∂η/∂x, −∂η/∂y, 1) for ``up`` = "z", normalize(−∂η/∂x, 1, −∂η/∂v) for "y"
    (texture v along world z). Default tolerance: 1° (2 sin 0.5°)."""
    from wavephys.core.grid import Grid
    from wavephys.core.inputs import check_choice, check_int, check_scalar

    from optics.shaders.glsl import Sampler

    n = check_int("n", n, lo=32, hi=1024)
    check_scalar("texel_size", texel_size, lo=1e-4, hi=100.0)
    check_scalar("max_slope", max_slope, lo=0.01, hi=2.0)
    check_choice("up", up, ("z", "y"))
    grid = Grid(n, n * float(texel_size))
    eta = _band_limited(grid, max_slope, seed)
    gx, gy = (np.asarray(g, np.float64) for g in grid.gradient(eta))

    def normals(sx, sy, y_up=up == "y"):
        v = np.stack([-sx, -sy, np.ones_like(sx)], -1) if not y_up else np.stack([-sx, np.ones_like(sx), -sy], -1)
        return _unit(v).reshape(-1, 3)

    h = np.asarray(eta, np.float64)
    fx, fy = (np.roll(h, -1, 1) - h) / texel_size, (np.roll(h, -1, 0) - h) / texel_size
    alternatives = [
        ("the slopes have the wrong sign: the normal leans uphill", normals(-gx, -gy)),
        ("x and y are swapped", normals(gy, gx)),
        (f"the normal's up axis is {'z' if up == 'y' else 'y'}: pass up={('z' if up == 'y' else 'y')!r} if that is "
         "your convention", normals(gx, gy, y_up=up != "y")),
        ("the difference is not divided by 2: slopes twice too steep ((h₊ − h₋)/Δx for a central difference)",
         normals(2 * gx, 2 * gy)),
        ("one-sided differences (h₊ − h)/Δx: the normal is half a texel off", normals(fx, fy)),
    ]
    j, i = np.meshgrid(np.arange(n), np.arange(n))
    uv = np.column_stack([(j.ravel() + 0.5) / n, (i.ravel() + 0.5) / n])
    inputs = {"heights": Sampler(h.astype(np.float32)), "uv": _f32(uv), "texel_uv": _f32(np.full((n * n, 2), 1.0 / n)),
              "texel_size": _f32(np.full((n * n, 1), texel_size))}
    slope = np.degrees(np.arctan(np.hypot(gx, gy))).ravel()
    border = np.minimum.reduce([i, j, n - 1 - i, n - 1 - j]).ravel()
    tol = 2.0 * math.sin(math.radians(0.5)) if tolerance is None else _tolerance(tolerance)
    return Domain(inputs, normals(gx, gy), tol, ("slope angle (degrees)", slope), np.full(n * n, f"{up} up"),
                  dict(u=uv[:, 0], v=uv[:, 1], slope_deg=slope, texels_from_border=border.astype(float)),
                  f"{n}² texels of {texel_size:g} m, shortest wave 16 texels, slopes up to {slope.max():.1f}°, "
                  f"{up} up", alternatives)


def _band_limited(grid, max_slope, seed):
    """A random periodic surface with wavelengths of 16 texels and longer, scaled to ``max_slope``."""
    rng = np.random.default_rng(seed)
    ky, kx = (np.asarray(k, np.float64) for k in grid.wavenumbers(real=False))
    k = np.hypot(kx, ky)
    k_max = 2.0 * math.pi / (16.0 * float(grid.dx))
    spec = (rng.standard_normal(k.shape) + 1j * rng.standard_normal(k.shape)) * np.where(
        (k > 0) & (k <= k_max), 1.0 / np.maximum(k, 1e-9) ** 1.5, 0.0)
    eta = np.fft.ifft2(spec).real
    gx, gy = (np.asarray(g, np.float64) for g in grid.gradient(eta))
    return eta * (max_slope / np.max(np.hypot(gx, gy)))


def _height_normal_late(values, domain, errors):
    border = domain.context["texels_from_border"]
    inside = errors[border >= 2]
    if errors.max() > domain.tolerance and inside.size and inside.max() <= domain.tolerance:
        return ("errors only at the texture's border: the heights are not sampled periodically there "
                "(a clamped sampler or uv clamped; the texture tiles)")
    ref = domain.expected
    s_ref = -ref[:, :2] / ref[:, 2:3] if domain.groups[0] == "z up" else -ref[:, [0, 2]] / ref[:, 1:2]
    v = np.asarray(values, np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        s_user = -v[:, :2] / v[:, 2:3] if domain.groups[0] == "z up" else -v[:, [0, 2]] / v[:, 1:2]
    ok = np.isfinite(s_user).all(1) & (np.abs(s_ref).sum(1) > 1e-3)
    if ok.sum() > 10:
        scale = float(np.sum(s_user[ok] * s_ref[ok]) / np.sum(s_ref[ok] ** 2))
        if abs(scale - 1.0) > 0.02 and np.max(np.abs(s_user[ok] - scale * s_ref[ok])) < 0.05 * np.abs(s_ref).max() * abs(scale):
            return (f"the slopes are scaled by {scale:.4g}: check the division by the texel size in metres "
                    f"(texel_size) and the height units")
    return _length_cause(values)


# -- helpers and the registry -----------------------------------------------------------------
def _samples(samples):
    from wavephys.core.inputs import check_int

    return check_int("samples", samples, lo=16, hi=1 << 20)


def _tolerance(tolerance):
    from wavephys.core.inputs import check_scalar

    check_scalar("tolerance", tolerance, lo=0.0, lo_open=True)
    return float(tolerance)


_RAY_ROLES = ("cos_theta", "n1", "n2", "eta", "f0", "incident", "view", "normal", "facing_normal")

SHADER_CHECKS = {c.name: c for c in (
    ShaderCheck("fresnel", "|R − R_ref|", "Fresnel reflectance from both sides", _RAY_ROLES, ("float",),
                ("cos_theta", "n1", "n2"), fresnel_domain, _scalar_error, _fresnel_early, _fresnel_late),
    ShaderCheck("refract", "|t − t_ref|", "refracted direction, with total internal reflection", _RAY_ROLES,
                ("vec3",), ("incident", "facing_normal", "eta"), refract_domain, _refract_error, _refract_early,
                _refract_late),
    ShaderCheck("reflect", "|r − r_ref|", "mirror direction", _RAY_ROLES, ("vec3",), ("incident", "facing_normal"),
                reflect_domain, _vector_error, late=_length_late),
    ShaderCheck("transmittance", "|T − e^(-a d)|", "Beer–Lambert transmittance",
                ("distance", "coefficient", "coefficients"), ("float", "vec3"), ("distance", "coefficients"),
                transmittance_domain, _scalar_error, _transmittance_early, _transmittance_late),
    ShaderCheck("rgb_absorption", "max channel |T − T_spectral|", "RGB water colour against the spectral answer",
                ("distance",), ("vec3",), ("distance",), rgb_absorption_domain, _scalar_error,
                late=_rgb_absorption_late),
    ShaderCheck("normal_decode", "|n − n_ref|", "normal-map texel to unit normal", ("texel", "texel_rgb", "texel_rg"),
                ("vec3",), ("texel",), normal_decode_domain, _vector_error, late=_length_late),
    ShaderCheck("height_normal", "|n − n_ref|", "normal from a height texture", ("heights", "uv", "texel_uv",
                "texel_size"), ("vec3",), ("heights", "uv", "texel_uv", "texel_size"), height_normal_domain,
                _vector_error, late=_height_normal_late),
)}
"""The shader checks by name (``against=``). A new check is one entry here and its test."""
