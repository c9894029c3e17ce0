"""Shader checks of light at the surface: Fresnel reflectance, refraction and reflection.

Rays come from every incidence angle 0–90°, from the air and from the water, with normals tilted
in random directions (untilted when the function takes no normal: it assumes flat water). The
relative index m = n_water/n_air a correct function may hold is water's whole range
(:func:`optics.light.fresnel.water_index_range`: 1.3291–1.3519, f0 0.0200–0.0224), found from
the function's own output: a Schlick term with ``F0 = 0.02`` and ``refract(I, N, 1.0/1.333)``
are water; ``F0 = 0.04`` is not. The causes are models fitted the same way (module
:mod:`optics.shaders.models`): the index ratio inverted, no total internal reflection from below,
the refracted ray's cosine, another form than the one named, and the artistic curves engines
use in place of Fresnel (powers of 1 − cos θ, linear ramps, square roots), named with their fitted
shape and how far it is from any Schlick or exact curve for water.
"""

from __future__ import annotations

import math

import numpy as np

from optics.shaders.domain import (Domain, check_sides, check_up, display_tolerance, length_cause, ray_inputs, rays,
                                   samples_option, to_up, tolerance_option, vector_error, water_models_range)
from optics.shaders.models import Model, Param

__internal__ = True  # the registry's pieces: users call optics.shaders.check_glsl
__all__ = ["fresnel_domain", "refract_domain", "reflect_domain", "fresnel_early", "fresnel_late", "refract_early",
           "refract_late", "reflect_late", "refract_error", "FRESNEL_FORMS"]

FRESNEL_FORMS = ("auto", "exact", "schlick", "jensen_golias", "loviscach", "lut")
"""``form=`` of the fresnel check: a name in :data:`~optics.light.fresnel.REFLECTANCE_METHODS`, or ``auto``
(default): any correct form for water, exact or Schlick's (each with water's index)."""

_AIR_ONLY = ("jensen_golias", "loviscach")


def _f0_of(m):
    return ((m - 1) / (m + 1)) ** 2


def _m_param(m_range, words):
    def show(m):
        return f"F0 = {_f0_of(m):.4f} (m = n_water/n_air = {m:.4f})"

    def outside(m):
        f0, lo, hi = _f0_of(m), _f0_of(m_range[0]), _f0_of(m_range[1])
        hint = ""
        if abs(f0 - 0.04) < 2e-3:
            hint = " (0.04 is a PBR engine's default for non-metals, and glass's)"
        elif lo <= f0 ** 2 <= hi * 1.02:
            hint = " (f0 = (n1 − n2)/(n1 + n2) not squared)"
        return (f"F0 from the wrong indices: F0 = {f0:.4f}, the f0 of an index {m:.4g} against 1{hint}, where "
                f"{words}")
    return Param("m", (1.0005, 4.0), m_range, True, show, words, outside)


def _indices(m, above):
    """(n1, n2) per row for a relative index m: air to water above, water to air below."""
    return np.where(above, 1.0, m), np.where(above, m, 1.0)


def _cos_t(c, n1, n2):
    k = 1.0 - (n1 / n2) ** 2 * (1.0 - c * c)
    return np.sqrt(np.maximum(k, 0.0)), k < 0


def _exact(c, n1, n2):
    ct, tir = _cos_t(c, n1, n2)
    with np.errstate(invalid="ignore", divide="ignore"):
        rs = ((n1 * c - n2 * ct) / (n1 * c + n2 * ct)) ** 2
        rp = ((n1 * ct - n2 * c) / (n1 * ct + n2 * c)) ** 2
    return np.where(tir, 1.0, np.nan_to_num(0.5 * (rs + rp), nan=1.0))


def _f0(n1, n2):
    return ((n1 - n2) / (n1 + n2)) ** 2


def _schlick(c, n1, n2, tir_test=True, transmitted=True):
    """Schlick's form; from the denser side with cos θt and R = 1 past the critical angle (``transmitted``)."""
    ct, tir = _cos_t(c, n1, n2)
    used = np.where((n1 > n2) & transmitted, ct, c)
    r = _f0(n1, n2) + (1.0 - _f0(n1, n2)) * (1.0 - used) ** 5
    return np.where(tir & tir_test, 1.0, r)


def _lut(c, n1, n2, size):
    """The exact R tabulated at ``size`` values of cos θ and linearly interpolated (per pair of indices)."""
    out = np.empty_like(c)
    pairs = np.stack([n1 * np.ones_like(c), n2 * np.ones_like(c)], -1)
    for a, b in np.unique(pairs, axis=0):
        on = (pairs[:, 0] == a) & (pairs[:, 1] == b)
        nodes = np.linspace(0.0, 1.0, size)
        out[on] = np.interp(c[on], nodes, _exact(nodes, np.full(size, a), np.full(size, b)))
    return out


def _form(name, c, n1, n2, size=64):
    if name == "exact":
        return _exact(c, n1, n2)
    if name == "schlick":
        return _schlick(c, n1, n2)
    if name == "jensen_golias":
        return 1.0 / (1.0 + c) ** 8
    if name == "loviscach":
        return np.clip(1.0 - 2.5 * c, 0.0, 1.0)
    return _lut(c, n1, n2, size)


_LABELS = {"exact": "exact Fresnel", "schlick": "Schlick's approximation", "lut": "a lookup table of exact Fresnel",
           "jensen_golias": "Jensen & Goliáš' 1/(1 + cos θ)⁸", "loviscach": "Loviscach's clamp(1 − 2.5 cos θ)"}


def _fresnel_models(form, c, above, m_param, size):
    """The correct forms and the faults of the fresnel check, as fitted models over rows (c, above)."""
    def col(a):
        return np.asarray(a, np.float64)[:, None]

    def form_model(name, correct):
        if name in _AIR_ONLY:
            return Model(_LABELS[name], lambda v, n=name: col(_form(n, c, *_indices(1.333, above))), (), correct,
                         f"it computes {_LABELS[name]}" + ("" if correct else f", not {_LABELS.get(form, 'Fresnel')}: "
                                                           f"check it with form={name!r} if that is what you mean"))
        return Model(_LABELS[name], lambda v, n=name: col(_form(n, c, *_indices(v[0], above), size)), (m_param,),
                     correct, f"it computes {_LABELS[name]}, not {_LABELS.get(form, 'exact Fresnel or Schlick')}: "
                              f"check it with form={name!r} if that is what you mean")

    names = ("exact", "schlick") if form == "auto" else (form,)
    correct = [form_model(n, True) for n in names]
    faults = [form_model(n, False) for n in ("exact", "schlick", "jensen_golias", "loviscach") if n not in names]
    for base in [n for n in names if n in ("exact", "schlick", "lut")] or ["exact"]:
        faults += _transform_faults("exact" if base == "lut" else base, c, above, m_param)
    faults += _artistic(c, above)
    return correct, faults


def _transform_faults(base, c, above, m_param):
    def col(a):
        return np.asarray(a, np.float64)[:, None]

    def inverted(v):
        n1, n2 = _indices(v[0], above)
        return col(_form(base, c, n2, n1))

    def no_tir(v):  # Schlick's F0 is symmetric in n1, n2: an inverted ratio without a TIR test is this curve
        n1, n2 = _indices(v[0], above)
        return col(_schlick(c, n1, n2, tir_test=False, transmitted=False))

    def wrong_ray(v):
        n1, n2 = _indices(v[0], above)
        ct, tir = _cos_t(c, n1, n2)
        r = _schlick(ct, n1, n2, transmitted=False) if base == "schlick" else _exact(ct, n1, n2)
        return col(np.where(tir, 1.0, r))

    def typo(v):
        n1, n2 = _indices(v[0], above)
        return col(_f0(n1, n2) + (1 - _f0(n1, n2)) * c ** 5)

    critical = "(its critical angle from below: {:.2f}°)"
    faults = [
        Model("inverted ratio", inverted, (m_param,), False,
              "the index ratio is inverted: it computes with n2/n1 where n1/n2 is due"),
        Model("no TIR", no_tir, (m_param,), False,
              lambda v: "no total internal reflection from below: past the critical angle "
                        + critical.format(math.degrees(math.asin(1 / v[0]))) + " it gives R < 1 where R = 1 "
                        "(Schlick's formula with the water side's cos θi and no TIR test)"),
        Model("wrong ray", wrong_ray, (m_param,), False,
              "cos θ of the wrong ray: it uses the refracted ray's cos θt where the incident ray's cos θi is due"),
        Model("cos^5 typo", typo, (m_param,), False,
              "it raises cos θ to the 5th power where (1 − cos θ)⁵ is due (the misprint of Schneider & Westermann "
              "2001): R = 1 at normal incidence"),
    ]
    if base == "exact":  # the no-TIR faults are Schlick's; exact Fresnel without a TIR test gives NaN (early)
        faults = [f for f in faults if f.name not in ("no TIR", "cos^5 typo")]
    return faults


def _nearest(curve, c, above):
    """How far a curve (n,) is from Schlick's and the exact curve for any water, over the rows from the air."""
    from optics.light.fresnel import water_index_range

    r = water_index_range()
    ms = np.linspace(r.low, r.high, 9)
    up = above
    worst = {}
    for name in ("schlick", "exact"):
        worst[name] = min(float(np.max(np.abs(curve[up] - _form(name, c[up], *_indices(m, up[up]))))) for m in ms)
    return worst


def _artistic(c, above):
    """Curves engines use in place of Fresnel, each with two fitted constants."""
    def col(a):
        return np.asarray(a, np.float64)[:, None]

    families = {
        "power": (lambda v: v[0] + (1 - v[0]) * (1 - c) ** v[1], "R = f0 + (1 − f0)(1 − cos θ)^p",
                  (Param("f0", (0.0, 1.0)), Param("p", (0.25, 16.0), log=True))),
        "scaled power": (lambda v: v[0] * (1 - c) ** v[1], "R = b (1 − cos θ)^p",
                         (Param("b", (0.01, 2.0), log=True), Param("p", (0.25, 16.0), log=True))),
        "bias, scale and power": (lambda v: v[0] + v[1] * (1 - c) ** v[2],
                                  "R = bias + scale (1 − cos θ)^power (the Cg tutorial's empirical form)",
                                  (Param("bias", (-0.5, 1.0)), Param("scale", (0.01, 4.0), log=True),
                                   Param("power", (0.25, 16.0), log=True))),
        "linear": (lambda v: np.clip(v[0] + v[1] * (1 - c), 0, 1), "a linear ramp R = a + b (1 − cos θ)",
                   (Param("a", (-1.0, 1.0)), Param("b", (-2.0, 4.0)))),
        "square root": (lambda v: np.clip(v[0] + v[1] * np.sqrt(1 - c), 0, 1), "R = a + b √(1 − cos θ)",
                        (Param("a", (-1.0, 1.0)), Param("b", (-2.0, 4.0)))),
    }

    def cause(name, shape, params):
        def text(v):
            curve = families[name][0](v)
            far = _nearest(curve, c, above)
            values = ", ".join(f"{p.name} = {x:.4g}" for p, x in zip(params, v))
            return (f"the curve is not Fresnel's shape: it computes {shape} with {values} (Schlick's power is 5); "
                    f"from the air it is up to {far['schlick']:.3g} from Schlick's curve and {far['exact']:.3g} from "
                    f"the exact one for any water")
        return text

    return [Model(f"curve: {name}", lambda v, f=f: col(f(v)), params, False, cause(name, shape, params))
            for name, (f, shape, params) in families.items()]


def fresnel_domain(*, form="auto", sides=None, n_air=None, n_water=None, samples=2048, bits=8, radiance=1.0,
                   tolerance=None, up="z", tilt=0.5, size=64):
    """Reflectance at every incidence angle from each side, against ``form``: ``"auto"`` (default: exact
    Fresnel or Schlick's approximation, with water's index), or a name in
    :data:`~optics.light.fresnel.REFLECTANCE_METHODS` ("jensen_golias" and "loviscach" are forms for
    viewing from air: their default ``sides`` is above only). The index a correct function may hold is
    water's range unless ``n_air``/``n_water`` state one; the tolerance is half a level of a ``bits``-bit
    display relative to ``radiance`` (``tolerance`` overrides). ``up``: the frame of vector inputs ("z"
    or "y"); ``tilt``: the largest slope of the normals; ``size``: the table size of form "lut".

    Parameters
    ----------
    form : str, keyword-only
        ``"auto"`` or a Fresnel method's name.
    sides : tuple of str, optional, keyword-only
        ``"above"``, ``"below"``.
    n_air, n_water : float, optional, keyword-only
        Indices a function must use (default: water's range).
    samples : int, keyword-only
        Angles checked.
    bits : int, keyword-only
        The display's bits a channel.
    radiance : float, keyword-only
        The light R scales.
    tolerance : float, optional, keyword-only
        Overrides the default.
    up : str, keyword-only
        ``"z"`` or ``"y"``.
    tilt : float, keyword-only
        The normals' tilt from up, rad.
    size : int, keyword-only
        Entries of a LUT form.

    Returns
    -------
    Domain
        The inputs, the tolerance, and the correct and faulty models.
    """
    from wavephys.core.inputs import check_choice, check_int, check_scalar

    check_choice("form", form, FRESNEL_FORMS)
    check_up(up)
    check_scalar("tilt", tilt, lo=0.0, hi=2.0)
    check_int("size", size, lo=2, hi=1 << 16)
    sides = check_sides(sides or (("above",) if form in _AIR_ONLY else ("above", "below")))
    m_range, (n_a, n_w), words = water_models_range(n_air, n_water)
    tol, tol_note = display_tolerance(bits, radiance, tolerance)
    r = rays(samples_option(samples), sides, {"above": (n_a, n_w), "below": (n_w, n_a)}, tilt=tilt)
    inputs = ray_inputs(r, up)
    c = inputs["cos_theta"][:, 0]
    above = r["side"] == "above"
    correct, faults = _fresnel_models(form, c, above, _m_param(m_range, words), size)
    crit = math.degrees(math.asin(n_a / n_w))
    return Domain(inputs, tol, tol_note, ("incidence angle θ (degrees)", r["theta"]), r["side"],
                  dict(theta_deg=r["theta"], side=r["side"], n1=inputs["n1"][:, 0], n2=inputs["n2"][:, 0]),
                  f"{'exact or Schlick' if form == 'auto' else form} reflectance over 0–90° from "
                  f"{' and '.join(sides)} ({len(c)} rays; critical angle {crit:.2f}° from below at the fed indices); "
                  f"constants allowed: {words}", correct, faults, above, dict(cos=c, above=above))


def fresnel_early(values, domain, errors):
    """A cause that comes before any fit: a constant output on one side.

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
    str or tuple
        "" when this does not explain it; else the cause (with the group it is on).
    """
    v = values[:, 0]
    for side in np.unique(domain.groups):
        on = domain.groups == side
        expected = domain.extra.get("expected")
        spread = np.ptp(expected[on, 0]) if expected is not None else 1.0
        if np.ptp(v[on]) < 1e-6 and spread > 1e-3:
            return side, (f"a constant {v[on][0]:.4g} whatever the angle: a clamp such as max(dot(V, N), 0.0) hides "
                          f"a negative cosine (the view or the normal faces the wrong way there)")
    return ""


def fresnel_late(values, domain, errors):
    """A cause when no model explains the output: R outside [0, 1], or what it gives at normal incidence
    against water's f0.

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
    from optics.light.fresnel import water_index_range

    v = values[:, 0]
    if v.min() < -1e-6 or v.max() > 1.0 + 1e-6:
        return f"gives R outside [0, 1] ({v.min():.4g} to {v.max():.4g}): a missing clamp or a wrong sign"
    normal = np.isclose(domain.extra["cos"], 1.0) & domain.extra["above"]
    if not normal.any():
        return ""
    g = float(np.median(v[normal]))
    lo, hi = water_index_range().f0
    if lo <= g <= hi:
        return ""
    hint = ""
    if 0 < g < 1:
        m = (1 + math.sqrt(g)) / (1 - math.sqrt(g))
        hint = f" (the f0 of an index {m:.4g} against 1)"
    return f"at normal incidence it gives {g:.4g} where water's f0 is {lo:.4f}–{hi:.4f}{hint}"


# -- refraction and reflection --------------------------------------------------------------
def _glsl_refract(d, n, eta):
    """GLSL's refract(I, N, eta) as the spec writes it (vec3(0) past the critical angle)."""
    eta = np.asarray(eta, np.float64).reshape(-1, 1)
    c = np.sum(n * d, -1, keepdims=True)
    k = 1.0 - eta * eta * (1.0 - c * c)
    return np.where(k < 0, 0.0, eta * d - (eta * c + np.sqrt(np.maximum(k, 0.0))) * n), (k < 0)[:, 0]


def refract_domain(*, sides=("above", "below"), n_air=None, n_water=None, samples=1024, tir="either",
                   tolerance=1e-4, up="z", tilt=0.5):
    """Refracted directions at every incidence angle from each side, against Snell's law (GLSL's
    ``refract`` with the facing normal) for water's index (any in its range, found from the output,
    unless ``n_air``/``n_water`` state one); under total internal reflection the function may return
    ``tir``: "zero" (vec3(0), as GLSL's refract), "reflect" (the mirror ray) or "either".
    ``tolerance`` (default 1e-4) is float32 arithmetic on a unit vector; ``up``: the frame of the vectors.

    Parameters
    ----------
    sides : tuple of str, keyword-only
        ``"above"``, ``"below"``.
    n_air, n_water : float, optional, keyword-only
        Indices a function must use (default: found from its output).
    samples : int, keyword-only
        Angles checked.
    tir : str, keyword-only
        ``"zero"``, ``"reflect"`` or ``"either"``.
    tolerance : float, keyword-only
        The largest error.
    up : str, keyword-only
        ``"z"`` or ``"y"``.
    tilt : float, keyword-only
        The normals' tilt from up, rad.

    Returns
    -------
    Domain
        The inputs, the tolerance, and the correct and faulty models.
    """
    from wavephys.core.inputs import check_choice, check_scalar

    check_choice("tir", tir, ("zero", "reflect", "either"))
    check_up(up)
    check_scalar("tilt", tilt, lo=0.0, hi=2.0)
    sides = check_sides(sides)
    m_range, (n_a, n_w), words = water_models_range(n_air, n_water)
    r = rays(samples_option(samples), sides, {"above": (n_a, n_w), "below": (n_w, n_a)}, tilt=tilt)
    inputs = ray_inputs(r, up)
    above = r["side"] == "above"
    d, nf, nu = r["incident"], r["facing"], r["normal"]
    mirror = d - 2.0 * np.sum(d * nf, -1, keepdims=True) * nf
    m_param = Param("m", (1.0005, 4.0), m_range, True, lambda m: f"its index ratio is that of m = {m:.4f} "
                                                                f"(n1/n2 = {1 / m:.4f} from the air)", words)

    def eta(m):
        return np.where(above, 1.0 / m, m)

    def answer(t, is_tir):
        t = to_up(t, up)
        if tir == "zero":
            return np.where(is_tir[:, None], 0.0, t)
        if tir == "reflect":
            return np.where(is_tir[:, None], to_up(mirror, up), t)
        return np.where(is_tir[:, None], 0.0, t), np.where(is_tir[:, None], to_up(mirror, up), np.nan)

    def model(name, direction, normal, ratio, cause, correct=False):
        return Model(name, lambda v: answer(*_glsl_refract(direction, normal, ratio(v[0]))), (m_param,), correct,
                     cause)

    correct = [model("Snell's law", d, nf, eta, "", True)]
    faults = [
        model("inverted", d, nf, lambda m: 1.0 / eta(m),
              "the index ratio is inverted: it refracts with n2/n1 where eta = n1/n2 is due"),
        model("up normal", d, nu, eta, "from below, the normal faces the wrong way: GLSL's refract(I, N, eta) wants "
                                       "N against I (use −N for rays from the water)"),
        model("flipped normal", d, -nf, eta, "the normal faces the wrong way on every ray: GLSL's refract(I, N, "
                                             "eta) wants N against I"),
        model("view vector", -d, nf, eta, "it refracts the view vector (towards the eye) where the incident "
                                          "direction (−V) is due"),
        model("view vector, flipped normal", -d, -nf, eta, "it refracts the view vector (towards the eye) where the "
                                                           "incident direction (−V) is due, and the normal faces "
                                                           "the wrong way"),
        model("inverted, up normal", d, nu, lambda m: 1.0 / eta(m), "the index ratio is inverted and, from below, "
                                                                     "the normal faces the wrong way"),
    ]
    t0, tir0 = _glsl_refract(d, nf, eta(n_w / n_a))
    said = {"zero": "vec3(0)", "reflect": "the mirror ray", "either": "vec3(0) or the mirror ray"}[tir]
    return Domain(inputs, tolerance_option(tolerance), f"tolerance {tolerance:.3g}: float32 arithmetic on a unit "
                  f"vector", ("incidence angle θ (degrees)", r["theta"]), r["side"],
                  dict(theta_deg=r["theta"], side=r["side"], n1=inputs["n1"][:, 0], n2=inputs["n2"][:, 0]),
                  f"refraction over 0–90° from {' and '.join(sides)} ({len(d)} rays, "
                  f"{'tilted normals' if tilt > 0 else 'flat water'}; under total internal reflection: {said}); "
                  f"constants allowed: {words}", correct, faults, above, dict(tir=tir0, mode=tir))


def refract_error(values, expected, domain=None):
    """|t − t_ref| per row.

    Parameters
    ----------
    values, expected : numpy.ndarray (n, 3)
        Directions.
    domain : Domain, optional
        Not used.

    Returns
    -------
    numpy.ndarray (n,)
    """
    return vector_error(values, expected)


def refract_early(values, domain, errors):
    """NaN past the critical angle (a hand-written refract without a TIR test).

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
    str or tuple
        "" when this does not explain it; else the cause (with the group it is on).
    """
    tir = domain.extra["tir"]
    if tir.any() and not np.isfinite(values[tir]).all() and np.isfinite(values[~tir]).all():
        return ("NaN past the critical angle: sqrt of a negative k (1 − eta²(1 − cos²θ)) without a total "
                "internal reflection test")
    return ""


def refract_late(values, domain, errors):
    """Vectors that are not unit length outside total internal reflection.

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
    return length_cause(values, ~domain.extra["tir"])


def reflect_domain(*, sides=("above", "below"), samples=1024, tolerance=1e-4, up="z", tilt=0.5):
    """Mirror directions at every incidence angle from each side, against r = d − 2(d·n)n.
    ``tolerance`` (default 1e-4) is float32 arithmetic on a unit vector.

    Parameters
    ----------
    sides : tuple of str, keyword-only
        ``"above"``, ``"below"``.
    samples : int, keyword-only
        Angles checked.
    tolerance : float, keyword-only
        The largest error.
    up : str, keyword-only
        ``"z"`` or ``"y"``.
    tilt : float, keyword-only
        The normals' tilt from up, rad.

    Returns
    -------
    Domain
        The inputs, the tolerance, and the correct and faulty models.
    """
    from optics.light.fresnel import N_AIR, N_WATER
    from wavephys.core.inputs import check_scalar

    check_up(up)
    check_scalar("tilt", tilt, lo=0.0, hi=2.0)
    sides = check_sides(sides)
    r = rays(samples_option(samples), sides, {"above": (N_AIR, N_WATER), "below": (N_WATER, N_AIR)}, tilt=tilt)
    inputs = ray_inputs(r, up)
    d, nf = r["incident"], r["facing"]
    expected = to_up(d - 2.0 * np.sum(d * nf, -1, keepdims=True) * nf, up)
    correct = [Model("the mirror ray", lambda v: expected, (), True)]
    faults = [Model("view vector", lambda v: -expected, (), False,
                    "it returns the mirrored view vector −r (reflect(V, N) with V towards the eye) where r = "
                    "reflect(I, N) is due")]
    return Domain(inputs, tolerance_option(tolerance), f"tolerance {tolerance:.3g}: float32 arithmetic on a unit "
                  f"vector", ("incidence angle θ (degrees)", r["theta"]), r["side"],
                  dict(theta_deg=r["theta"], side=r["side"]),
                  f"reflection over 0–90° from {' and '.join(sides)} ({len(d)} rays, "
                  f"{'tilted normals' if tilt > 0 else 'flat water'})", correct, faults, r["side"] == "above")


def reflect_late(values, domain, errors):
    """Vectors that are not unit length.

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
    return length_cause(values)

