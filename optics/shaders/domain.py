"""What a shader check feeds a function and what it accepts back: :class:`Domain` and the pieces checks share.

A check's ``domain(**options)`` builds a :class:`Domain`: the inputs of every role over the
whole input domain (the float32 values the shader will receive, as float64), the models of what
a correct function may compute and of the mistakes real code makes (:mod:`optics.shaders.models`),
and the tolerance with how it was set. Tolerances come from physics and from what a display can
show: a radiance term (a reflectance, a transmittance) may err by half a level of the stated
display depth (8 bits unless told) relative to the largest radiance it multiplies
(:func:`display_tolerance`); a direction by the precision of float32 arithmetic on a unit vector.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from wavephys.core.inputs import check_choice, check_int, check_scalar

__internal__ = True  # the registry's and the runner's pieces: users call optics.shaders.check_glsl
__all__ = ["Domain", "display_tolerance", "f32", "unit", "vector_error", "scalar_error", "degrees", "finite_cause",
           "length_cause", "rays", "ray_inputs", "to_up", "samples_option", "tolerance_option", "check_sides",
           "SIDES", "water_models_range"]

SIDES = ("above", "below")


@dataclass(frozen=True)
class Domain:
    """The inputs of one check over its domain and what a function may answer.

    Attributes
    ----------
    inputs : dict
        role → (n, c) float64 array (the float32 values the shader gets) or a
        :class:`~optics.shaders.glsl.Sampler`.
    tolerance : float
        The largest error allowed.
    tolerance_note : str
        How the tolerance was set, in words (shown in the report).
    axis : (str, numpy.ndarray)
        The label and values (n,) a chart puts on its x axis.
    groups : numpy.ndarray
        (n,) labels: "above"/"below" for rays, one label otherwise (one line each in a chart, one fit each).
    context : dict
        name → (n,) values shown at the worst input.
    note : str
        What the domain covers.
    correct : list of Model
        What a correct function may compute (constants free within their physical ranges).
    faults : list of Model
        The mistakes recognized (constants free within wide ranges).
    front_facing : numpy.ndarray or None
        (n,) booleans, true for rays from the air (fed to ``gl_FrontFacing``).
    extra : dict
        Anything a check's own early or late cause reads.
    """

    inputs: dict
    tolerance: float
    tolerance_note: str
    axis: tuple
    groups: np.ndarray
    context: dict
    note: str
    correct: list
    faults: list = field(default_factory=list)
    front_facing: object = None
    extra: dict = field(default_factory=dict)

    @property
    def size(self) -> int:
        """Number of inputs."""
        return len(self.groups)


def display_tolerance(bits: int = 8, radiance: float = 1.0, tolerance=None) -> tuple:
    """(tolerance, words): half a level of a ``bits``-bit display relative to ``radiance`` (the largest
    radiance the term multiplies, in units of display white), or ``tolerance`` when given.

    Parameters
    ----------
    bits : int
        The display's bits a channel.
    radiance : float
        The largest radiance the term multiplies, in display white.
    tolerance : float, optional
        Given: used as it is.

    Returns
    -------
    (float, str)
    """
    if tolerance is not None:
        t = tolerance_option(tolerance)
        return t, f"tolerance {t:.3g} as given"
    check_int("bits", bits, lo=1, hi=32)
    check_scalar("radiance", radiance, lo=0.0, lo_open=True)
    t = 0.5 / (2 ** bits - 1) / float(radiance)
    article = "an" if str(bits).startswith("8") or bits in (11, 18) else "a"
    return t, (f"tolerance {t:.3g}: half a level of {article} {bits}-bit display for a radiance of "
               f"{float(radiance):g} × white (bits=, radiance=)")


def f32(a):
    """The float32 value a shader receives, back in float64.

    Parameters
    ----------
    a : array_like

    Returns
    -------
    numpy.ndarray
        float64.
    """
    return np.asarray(a, np.float64).astype(np.float32).astype(np.float64)


def unit(v):
    """Vectors (…, 3) scaled to unit length.

    Parameters
    ----------
    v : numpy.ndarray (..., 3)

    Returns
    -------
    numpy.ndarray (..., 3)
    """
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def vector_error(values, expected, domain=None):
    """|v − v_ref| per row.

    Parameters
    ----------
    values, expected : numpy.ndarray (n, c)
        Outputs and the answer.
    domain : Domain, optional
        Not used.

    Returns
    -------
    numpy.ndarray (n,)
    """
    return np.linalg.norm(np.asarray(values, np.float64) - expected, axis=-1)


def scalar_error(values, expected, domain=None):
    """max over components |v − v_ref| per row.

    Parameters
    ----------
    values, expected : numpy.ndarray (n, c)
        Outputs and the answer.
    domain : Domain, optional
        Not used.

    Returns
    -------
    numpy.ndarray (n,)
    """
    return np.max(np.abs(np.asarray(values, np.float64) - expected), axis=-1)


def degrees(a, b):
    """Angle between (n, 3) vectors, degrees (NaN where either is zero).

    Parameters
    ----------
    a, b : numpy.ndarray (n, 3)

    Returns
    -------
    numpy.ndarray (n,)
    """
    with np.errstate(invalid="ignore", divide="ignore"):
        c = np.sum(a * b, -1) / (np.linalg.norm(a, axis=-1) * np.linalg.norm(b, axis=-1))
    return np.degrees(np.arccos(np.clip(c, -1.0, 1.0)))


def finite_cause(values, domain):
    """"returns NaN or inf at …" when some outputs are not finite, else "".

    Parameters
    ----------
    values : numpy.ndarray (n, c)
        A function's outputs.
    domain : Domain
        Where they were computed (the worst input is named).

    Returns
    -------
    str
    """
    bad = ~np.isfinite(values).all(axis=-1)
    if not bad.any():
        return ""
    i = int(np.argmax(bad))
    where = ", ".join(f"{k} = {v[i]:.4g}" if np.asarray(v[i]).dtype.kind in "fiu" else f"{k} = {v[i]}"
                      for k, v in domain.context.items())
    return f"returns NaN or inf at {int(bad.sum())} of {bad.size} inputs (first at {where})"


def length_cause(values, mask=None):
    """"returns vectors of length … : not normalized" when the output vectors are not unit, else "".

    Parameters
    ----------
    values : numpy.ndarray (n, 3)
        A function's output vectors.
    mask : numpy.ndarray (n,), optional
        The rows to look at.

    Returns
    -------
    str
    """
    length = np.linalg.norm(np.asarray(values, np.float64), axis=-1)
    if mask is not None:
        length = length[mask]
    if length.size and np.max(np.abs(length - 1.0)) > 1e-3:
        return f"returns vectors of length {length.min():.4g} to {length.max():.4g}: not normalized"
    return ""


def _sphere_tangents(normal, rng):
    """A unit tangent per normal, at a random azimuth."""
    helper = np.where(np.abs(normal[:, 2:3]) < 0.9, [[0.0, 0.0, 1.0]], [[1.0, 0.0, 0.0]])
    t1 = unit(np.cross(normal, helper))
    t2 = np.cross(normal, t1)
    phi = rng.uniform(0.0, 2.0 * math.pi, (len(normal), 1))
    return np.cos(phi) * t1 + np.sin(phi) * t2


def _tilted_normals(n, rng, max_slope=0.5):
    """Unit normals pointing up (+z), tilted by slopes up to ``max_slope`` in random directions."""
    s = rng.uniform(-max_slope, max_slope, (n, 2))
    return unit(np.column_stack([-s, np.ones(n)]))


def check_sides(sides):
    """``sides`` as a tuple drawn from ("above", "below") (a single name is allowed).

    Parameters
    ----------
    sides : str or iterable of str

    Returns
    -------
    tuple of str
    """
    if isinstance(sides, str):
        sides = (sides,)
    if not isinstance(sides, (tuple, list)) or not sides or any(s not in SIDES for s in sides):
        raise ValueError(f"sides must be a non-empty subset of {SIDES}, got {sides!r}")
    return tuple(dict.fromkeys(sides))


def to_up(v, up):
    """Vectors of the z-up domain in the caller's frame: unchanged for ``up="z"``, (x, z, y) for ``"y"``
    (a y-up engine whose texture v runs along world z).

    Parameters
    ----------
    v : numpy.ndarray (..., 3)
    up : str
        ``"z"`` or ``"y"``.

    Returns
    -------
    numpy.ndarray (..., 3)
    """
    return v if up == "z" else v[..., [0, 2, 1]]


def rays(samples: int, sides: tuple, indices: dict, *, tilt: float = 0.5, seed: int = 0):
    """Rays at every incidence angle 0–90° from each side: angle, side, n1, n2, the up normal, the
    facing normal and the incident direction (float32-rounded float64 arrays; z up).

    Parameters
    ----------
    samples : int
        Angles a side.
    sides : tuple of str
        ``"above"``, ``"below"``.
    indices : dict
        The refractive indices fed (``n_air``, ``n_water``).
    tilt : float, keyword-only
        The normals' tilt from up, rad.
    seed : int, keyword-only
        Of the random normals.

    Returns
    -------
    dict of str to numpy.ndarray
    """
    rng = np.random.default_rng(seed)
    theta = np.tile(np.linspace(0.0, 90.0, samples), len(sides))
    side = np.repeat(np.array(sides), samples)
    n1 = np.array([indices[s][0] for s in side])
    n2 = np.array([indices[s][1] for s in side])
    up = _tilted_normals(theta.size, rng, tilt) if tilt > 0 else np.tile([0.0, 0.0, 1.0], (theta.size, 1))
    facing = np.where((side == "above")[:, None], up, -up)
    t = _sphere_tangents(facing, rng)
    c, s = np.cos(np.radians(theta))[:, None], np.sin(np.radians(theta))[:, None]
    incident = unit(-c * facing + s * t)
    return dict(theta=theta, side=side, n1=f32(n1), n2=f32(n2), normal=f32(up), facing=f32(facing),
                incident=f32(incident))


def ray_inputs(r, up="z"):
    """Every ray role (the float32 values) of the rays ``r``, vectors in the ``up`` frame.

    Parameters
    ----------
    r : dict
        :func:`rays`' answer.
    up : str
        ``"z"`` or ``"y"``.

    Returns
    -------
    dict of str to numpy.ndarray
        Role → (n, c) values.
    """
    from optics.light.fresnel import normal_reflectance

    d, nf = r["incident"], r["facing"]
    cos = f32(np.clip(-np.sum(unit(d) * unit(nf), -1), 0.0, 1.0))
    eta = r["n1"] / r["n2"]
    k = 1.0 - eta ** 2 * (1.0 - cos ** 2)
    n = len(cos)
    f0 = f32(normal_reflectance(r["n1"], r["n2"]))
    water = np.where(r["side"] == "above", r["n2"] / r["n1"], r["n1"] / r["n2"])
    return {"cos_theta": cos[:, None], "cos_theta_t": f32(np.sqrt(np.maximum(k, 0.0)))[:, None],
            "n1": r["n1"][:, None], "n2": r["n2"][:, None], "eta": f32(eta)[:, None], "ior": f32(water)[:, None],
            "f0": f0[:, None], "f0_rgb": np.repeat(f0[:, None], 3, 1), "front_facing": (r["side"] == "above")[:, None]
            .astype(np.float64), "incident": to_up(d, up), "view": to_up(-d, up), "normal": to_up(r["normal"], up),
            "facing_normal": to_up(nf, up), "reflected_color": np.ones((n, 3)), "refracted_color": np.zeros((n, 3))}


def samples_option(samples):
    """``samples`` checked: an int in [16, 2²⁰].

    Parameters
    ----------
    samples : int

    Returns
    -------
    int
    """
    return check_int("samples", samples, lo=16, hi=1 << 20)


def tolerance_option(tolerance):
    """``tolerance`` checked: a float > 0.

    Parameters
    ----------
    tolerance : float

    Returns
    -------
    float
    """
    check_scalar("tolerance", tolerance, lo=0.0, lo_open=True)
    return float(tolerance)


def water_models_range(n_air=None, n_water=None):
    """(the range of m = n_water/n_air a correct function may hold, the fed indices (n_air, n_water), words).

    Default: water's whole range (:func:`optics.light.fresnel.water_index_range`), fed at the library's
    nominal indices; with ``n_air`` and/or ``n_water`` given, those exactly.

    Parameters
    ----------
    n_air, n_water : float, optional
        Indices the function must use.

    Returns
    -------
    ((float, float), (float, float), str)
    """
    from optics.light.fresnel import N_AIR, N_WATER, water_index_range

    if n_air is None and n_water is None:
        r = water_index_range()
        return ((r.low, r.high), (N_AIR, N_WATER),
                f"water's m {r.low:.4f}–{r.high:.4f} (f0 {r.f0[0]:.5f}–{r.f0[1]:.5f}; n1/n2 from air "
                f"{r.eta[0]:.4f}–{r.eta[1]:.4f}: 400–700 nm, 0–30 °C, fresh or sea, air 1 or 1.000293)")
    a = N_AIR if n_air is None else n_air
    w = N_WATER if n_water is None else n_water
    check_scalar("n_air", a, lo=1.0, hi=10.0)
    check_scalar("n_water", w, lo=1.0, hi=10.0, lo_open=True)
    if not w > a:
        raise ValueError(f"n_water must exceed n_air (the water is the denser side), got {w} and {a}")
    m = float(w) / float(a)
    return ((m * (1 - 2e-6), m * (1 + 2e-6)), (float(a), float(w)), f"the stated m = {m:.5f} (n_air {a:g}, "
            f"n_water {w:g})")


def check_up(up):
    """``up`` checked: "z" or "y"."""
    check_choice("up", up, ("z", "y"))
    return up
