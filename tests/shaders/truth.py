"""The truth about a corpus entry (tests/shader_corpus.py), decided without the checker's fitting code.

The entry's numpy transcription is evaluated on the inputs the checker fed; the function is correct
when some water the physics allows explains that output within the tolerance on every side (and
colour channel) the checker judged: the relative index m = n_water/n_air is scanned by brute force
over water's range, against optics.light's reference formulas (exact and Schlick's Fresnel, Snell's
refraction, the mirror ray, e^(−ad), the spectral colour of pure water), or the known normals.
"""

from __future__ import annotations

import inspect

import numpy as np

from optics.light.fresnel import (reflectance_exact, reflectance_jensen_golias, reflectance_loviscach,
                                  reflectance_schlick, water_index_range)

_FORMS = {"exact": reflectance_exact, "schlick": reflectance_schlick, "jensen_golias": reflectance_jensen_golias,
          "loviscach": reflectance_loviscach}


def domain_for(entry, report):
    """The domain the checker used for ``entry`` (its options, the sides and flat water its notes say)."""
    from optics.shaders import SHADER_CHECKS

    check = SHADER_CHECKS[entry.against]
    names = set(inspect.signature(check.domain).parameters)
    options = {k: v for k, v in entry.options.items() if k in names}
    notes = " ".join(report.notes)
    if "checked from the air only" in notes:
        options["sides"] = ("above",)
    if "flat water" in notes:
        options["tilt"] = 0.0
    if "roles" in names:
        options["roles"] = tuple(report.takes)
    return check.domain(**options)


def transcribed(entry, report, domain):
    """The numpy transcription's output on the checker's inputs, (n, c)."""
    args = [np.full((domain.size, 1), t) if isinstance(t, float) else domain.inputs[t] for t in report.takes]
    kwargs = {"front": domain.front_facing.astype(float)[:, None]} if "gl_FrontFacing" in entry.source else {}
    with np.errstate(all="ignore"):
        values = np.asarray(entry.numpy(*args, **kwargs), np.float64)
    return values.reshape(domain.size, -1)


def _scan(errors) -> float:
    """The smallest worst error over water's index: a scan of 61 indices on the mean error, then scipy's
    bounded search on the worst error near the best (a ray at the critical angle needs the index to ~1e-9)."""
    from scipy.optimize import minimize_scalar

    r = water_index_range()
    ms = np.linspace(r.low, r.high, 61)
    means = [float(np.mean(np.minimum(errors(m), 10.0))) for m in ms]
    i = int(np.argmin(means))
    lo, hi = ms[max(i - 2, 0)], ms[min(i + 2, ms.size - 1)]
    found = minimize_scalar(lambda m: float(np.max(errors(m))), bounds=(lo, hi), method="bounded",
                            options=dict(xatol=1e-11))
    return min(float(found.fun), float(np.max(errors(ms[i]))))


def _fresnel_ok(values, domain, form):
    cos = domain.inputs["cos_theta"][:, 0]
    forms = ("exact", "schlick") if form in (None, "auto") else (form,)
    for side in np.unique(domain.groups):
        on = domain.groups == side
        for ch in range(values.shape[1]):
            best = np.inf
            for name in forms:
                def errors(m, name=name):
                    n1, n2 = (1.0, m) if side == "above" else (m, 1.0)
                    with np.errstate(all="ignore"):
                        ref = np.asarray(_FORMS[name](cos[on], n1, n2), np.float64)
                    return np.nan_to_num(np.abs(values[on, ch] - ref), nan=np.inf)
                best = min(best, _scan(errors) if name in ("exact", "schlick") else float(np.max(errors(1.333))))
            if not best <= domain.tolerance:
                return False
    return True


def _refract_ok(values, domain):
    from optics.light.directions import refract

    d, n = domain.inputs["incident"], domain.inputs["facing_normal"]
    mirror = d - 2 * np.sum(d * n, -1, keepdims=True) * n
    for side in np.unique(domain.groups):
        on = domain.groups == side

        def errors(m):
            n1, n2 = (1.0, m) if side == "above" else (m, 1.0)
            t, tir = refract(d[on], n[on], n1, n2)
            t, tir = np.asarray(t), np.asarray(tir)
            err = np.linalg.norm(values[on] - t, axis=1)
            err = np.where(tir, np.minimum(np.linalg.norm(values[on], axis=1),
                                           np.linalg.norm(values[on] - mirror[on], axis=1)), err)
            return np.where(np.isfinite(err), err, np.inf)
        if not _scan(errors) <= domain.tolerance:
            return False
    return True


def is_correct(entry, report) -> bool:
    """Whether ``entry``'s function is correct on the domain ``report`` was judged on (module doc)."""
    from optics.light.attenuation import water_srgb
    from optics.light.directions import reflect

    domain = domain_for(entry, report)
    values = transcribed(entry, report, domain)
    if not np.isfinite(values).all():
        return False
    tol = domain.tolerance
    if entry.against == "fresnel":
        return _fresnel_ok(values, domain, entry.options.get("form"))
    if entry.against == "refract":
        return _refract_ok(values, domain)
    if entry.against == "reflect":
        ref = np.asarray(reflect(domain.inputs["incident"], domain.inputs["facing_normal"]))
    elif entry.against == "transmittance":
        a = domain.inputs["coefficients"][:, :values.shape[1]]
        ref = np.exp(-a * domain.inputs["distance"])
    elif entry.against == "rgb_absorption":
        ref = np.asarray(water_srgb(domain.inputs["distance"][:, 0]), np.float64).reshape(-1, 3)
    else:  # the normals the texels or the texture were made from
        ref = domain.correct[0].answer(())
    err = np.linalg.norm(values - ref, axis=1) if entry.against in ("reflect", "normal_decode", "height_normal") \
        else np.max(np.abs(values - ref), axis=1)
    return bool(np.max(err) <= tol)
