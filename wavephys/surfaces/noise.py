r"""Gradient noise and fBm: the procedural water of Schneider & Westermann (2001), measured.

Gradient noise (Perlin 1985, "improved" 2002; docs/physics.md §1.9). Pseudo-random unit
gradients g_c sit at the integer lattice points c, picked by hashing c through a
permutation table; inside a cell, for p = c₀ + f (f ∈ [0, 1)^d),

.. math::

    n(p) = \sum_{c \in \{0,1\}^d} W_c(f)\, g_c\cdot(f - c), \qquad
    W_c(f) = \prod_a \big(c_a\, s(f_a) + (1 - c_a)(1 - s(f_a))\big),

with the quintic fade s(t) = 6t⁵ − 15t⁴ + 10t³ (C² across cells). n vanishes on the
lattice and its derivative is analytic (:func:`gradient_noise` with ``derivatives``).
Value noise puts random values v_c ∈ [−1, 1] at the lattice instead:
n(p) = Σ_c W_c(f) v_c.

fBm (fractional Brownian motion) sums octaves of doubling frequency with weights
2^{−H·i}:

.. math::

    h(x, y, t) = a \sum_{i=0}^{O-1} 2^{-H i}\, n\big(2^i f_0 x,\ 2^i f_0 y,\ \tau_i(t)\big),

a the amplitude (m), f₀ the lattice frequency of octave 0 (1/m). Animation, two ways:
``"dimension"`` — time is the third noise coordinate, τ_i = r·2^{e·i}·t (r lattice cells
per second, e the ``time_exponent``: e = 1 is S&W's 2^i t, e = ½ makes the octaves'
frequencies scale like deep-water waves); ``"lattices"`` — S&W's hardware form, two 2-D
gradient lattices at successive integer times blended linearly (noise is linear in its
gradients, so this equals interpolating the gradients).

Periodicity: with ``period`` (lattice cells) the lattice indices wrap, so noise tiles a
square; :func:`fbm` with ``tile`` (m) gives every octave an integer number of cells over
the tile (f₀·tile must be an integer), so it tiles a :class:`~wavephys.Grid` of that side.

Normals three ways (:data:`NORMAL_METHODS`): ``"exact"`` (analytic derivative);
``"shifted"`` — S&W's forward differences with the interpolation weights shifted by a
step ds inside the same lattice cell (one gradient lookup; wrong where p + ds leaves the
cell); ``"central"`` — central differences of full noise evaluations. Their errors
against the exact normal are measured in ``python -m bench surfaces`` and the tests.

The S&W base surface is a low-frequency octave of gradient noise sampled on an 8 × 8
control grid and drawn as a smooth tensor-product surface; here a periodic uniform cubic
B-spline (:func:`bspline_surface`, C², tiles the square), with exact derivatives.

Everything is JAX (jit/vmap/grad-able, float32 or float64 from the coordinates' dtype).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.inputs import (Array, Bool, Choice, Instance, Int, Maybe, Real, check_array, check_int,
                                  check_scalar, validate)
from wavephys.core.methods import Methods

__all__ = ["gradient_noise", "value_noise", "fbm", "fbm_spectrum_slope", "bspline_surface", "base_control_grid",
           "noise_gradient", "NORMAL_METHODS", "NoiseSea", "TABLE_SIZE", "MAX_OCTAVES"]

TABLE_SIZE = 256
"""Entries of the permutation table (lattice periods up to this many cells)."""
MAX_OCTAVES = 24
"""Most octaves accepted (2^24 lattice frequency ratio: beyond float32's resolution)."""
_MAX_COORD = 1e6
"""Largest |lattice coordinate| accepted: float32 keeps the fraction to ~0.06 cells there."""

_POINTS = Array()
_SEED = Int(lo=0, hi=2**31 - 1)
_PERIOD = Maybe(Int(lo=1, hi=TABLE_SIZE))


# -- tables ---------------------------------------------------------------------------
@functools.lru_cache(maxsize=256)
def _tables(seed: int):
    """(permutation doubled to 2·TABLE_SIZE, random angles, random values) from ``seed`` (NumPy)."""
    rng = np.random.default_rng(seed)
    perm = rng.permutation(TABLE_SIZE)
    angles = rng.uniform(0, 2 * np.pi, TABLE_SIZE)
    values = rng.uniform(-1.0, 1.0, TABLE_SIZE)
    gauss = rng.normal(size=(TABLE_SIZE, 3))
    return (np.concatenate([perm, perm]).astype(np.int32), angles, values,
            gauss / np.linalg.norm(gauss, axis=1, keepdims=True))


def _hash(perm, corner, period):
    """Table index of the lattice point ``corner`` (tuple of int arrays), wrapped by ``period``
    (cells; may be traced)."""
    h = jnp.zeros_like(corner[0])
    for c in corner:
        h = perm[h + jnp.mod(c, period)]
    return h


def _gradients(tables, index, dim, dtype):
    """Unit lattice gradients (dim, ...) at table ``index``: uniform angles in 2-D, normalized
    Gaussian directions in 3-D (isotropic)."""
    _, angles, _, gauss = tables
    if dim == 2:
        a = jnp.asarray(angles, dtype)[index]
        return jnp.stack([jnp.cos(a), jnp.sin(a)])
    return jnp.moveaxis(jnp.asarray(gauss, dtype)[index], -1, 0)


def _fade(t):
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0)


def _fade_prime(t):
    return 30.0 * t * t * (t * (t - 2.0) + 1.0)


def _lattice(coords, dtype):
    p = [jnp.asarray(c, dtype) for c in coords]
    base = [jnp.floor(c) for c in p]
    return [b.astype(jnp.int32) for b in base], [c - b for c, b in zip(p, base)]


def _noise(coords, tables, period, kind, derivatives, shift=None):
    """Noise of ``kind`` ("gradient"/"value") at ``coords`` (tuple of arrays, lattice units),
    from ``tables`` (:func:`_tables`; arrays, so one compiled program serves every seed).

    ``shift`` (axis, ds): evaluate the cell's own polynomial at f + ds·e_axis with the same
    corners (S&W's shifted weights)."""
    dim = len(coords)
    dtype = jnp.result_type(*[jnp.asarray(c).dtype for c in coords], jnp.float32)
    cell, frac = _lattice(coords, dtype)
    if shift is not None:
        frac = [f + shift[1] if a == shift[0] else f for a, f in enumerate(frac)]
    perm = jnp.asarray(tables[0])
    values = jnp.asarray(tables[2], dtype)
    s = [_fade(f) for f in frac]
    ds = [_fade_prime(f) for f in frac]
    total = 0.0
    grads = [0.0] * dim
    for bits in range(2 ** dim):
        corner = [(bits >> a) & 1 for a in range(dim)]
        idx = _hash(perm, tuple(cell[a] + corner[a] for a in range(dim)), period)
        w = [s[a] if corner[a] else 1.0 - s[a] for a in range(dim)]
        dw = [ds[a] if corner[a] else -ds[a] for a in range(dim)]
        weight = math.prod(w) if dim else 1.0
        if kind == "gradient":
            g = _gradients(tables, idx, dim, dtype)
            offs = [frac[a] - corner[a] for a in range(dim)]
            dot = sum(g[a] * offs[a] for a in range(dim))
        else:
            g = None
            dot = values[idx]
        total = total + weight * dot
        if derivatives:
            for a in range(dim):
                others = math.prod([w[b] for b in range(dim) if b != a])
                grads[a] = grads[a] + dw[a] * others * dot + (weight * g[a] if g is not None else 0.0)
    return (total, tuple(grads)) if derivatives else total


def _check_coords(x, y, z):
    for name, c in (("x", x), ("y", y), ("z", z)):
        if c is None:
            continue
        check_array(name, c, lo=-_MAX_COORD, hi=_MAX_COORD)
    shapes = [np.shape(c) for c in (x, y, z) if c is not None]
    try:
        return np.broadcast_shapes(*shapes)
    except ValueError:
        raise ValueError(f"x, y (and z) must broadcast to one shape, got {shapes}") from None


@validate(x=_POINTS, y=_POINTS, z=Maybe(_POINTS), seed=_SEED, period=_PERIOD, derivatives=Bool())
def gradient_noise(x, y, z=None, *, seed: int = 0, period: int | None = None, derivatives: bool = False):
    """Perlin gradient noise at lattice coordinates (x, y) or (x, y, z) (module doc).

    Parameters
    ----------
    x, y, z : array_like
        Lattice coordinates (one cell = 1), broadcastable; ``z`` (a third axis, e.g. time)
        optional. |coordinate| ≤ 1e6.
    seed : int
        Picks the permutation table and the gradients (0 ≤ seed < 2³¹).
    period : int, optional
        Lattice cells after which the noise repeats on every axis (1–256); default the
        table size, 256.
    derivatives : bool
        Also return the analytic gradient (∂n/∂x, ∂n/∂y[, ∂n/∂z]).

    Returns
    -------
    n, or (n, gradient) : arrays of the broadcast shape; |n| < 1, n = 0 on the lattice.

    References
    ----------
    K. Perlin (1985). An image synthesizer. *SIGGRAPH*; (2002) Improving noise. *ACM TOG* 21(3).
    """
    _check_coords(x, y, z)
    coords = (x, y) if z is None else (x, y, z)
    return _noise(jnp.broadcast_arrays(*[jnp.asarray(c) for c in coords]), _tables(seed), period or TABLE_SIZE,
                  "gradient", derivatives)


@validate(x=_POINTS, y=_POINTS, z=Maybe(_POINTS), seed=_SEED, period=_PERIOD, derivatives=Bool())
def value_noise(x, y, z=None, *, seed: int = 0, period: int | None = None, derivatives: bool = False):
    """Value noise (random lattice values in [−1, 1], quintic-faded) at lattice coordinates.

    The same arguments and returns as :func:`gradient_noise`.

    Parameters
    ----------
    x, y, z : array_like
        Lattice coordinates (one cell = 1), broadcastable; ``z`` (a third axis, e.g. time)
        optional. |coordinate| ≤ 1e6.
    seed : int
        Picks the permutation table and the lattice values (0 ≤ seed < 2³¹).
    period : int, optional
        Lattice cells after which the noise repeats on every axis (1–256); default the
        table size, 256.
    derivatives : bool
        Also return the analytic gradient (∂n/∂x, ∂n/∂y[, ∂n/∂z]).

    Returns
    -------
    n, or (n, gradient) : arrays of the broadcast shape; |n| ≤ 1.

    References
    ----------
    K. Perlin (1985). An image synthesizer. *SIGGRAPH*; (2002) Improving noise. *ACM TOG* 21(3).
    """
    _check_coords(x, y, z)
    coords = (x, y) if z is None else (x, y, z)
    return _noise(jnp.broadcast_arrays(*[jnp.asarray(c) for c in coords]), _tables(seed), period or TABLE_SIZE,
                  "value", derivatives)


_BASES = ("gradient", "value")
_ANIMATIONS = ("dimension", "lattices")


def _octave_period(tile, frequency, i, name="tile"):
    if tile is None:
        return None
    cells = frequency * tile * 2**i
    if abs(cells - round(cells)) > 1e-6 * max(1.0, cells) or round(cells) < 1:
        raise ValueError(f"{name}: frequency × tile must be a whole number of lattice cells to tile, got "
                         f"{frequency} 1/m × {tile} m = {frequency * tile:g}")
    if round(cells) > TABLE_SIZE:
        raise ValueError(f"{name}: octave {i} needs {int(round(cells))} lattice cells over the tile, more than the "
                         f"table's {TABLE_SIZE}; use fewer octaves or a lower frequency")
    return int(round(cells))


def _lattice_step(t, i, evolution, time_exponent):
    """Index of the gradient lattice in time just before ``t`` (``animation="lattices"``)."""
    if isinstance(t, jax.core.Tracer):
        raise ValueError("t: animation='lattices' needs a concrete time (not traced); use 'dimension' under jit")
    return int(np.floor(float(t) * evolution * 2.0 ** (time_exponent * i)))


@functools.partial(jax.jit, static_argnames=("basis", "derivatives", "shift_axis"))
def _octave_core(x, y, tau, scale, tables, period, shift, *, basis, derivatives, shift_axis):
    """One octave's noise n(scale·x, scale·y[, τ]) and its world gradient: one compiled program
    for every octave, seed, period and time (they are arguments, not constants)."""
    u, v = x * scale, y * scale
    coords = (u, v) if tau is None else (u, v, jnp.broadcast_to(tau, jnp.shape(u)).astype(u.dtype))
    res = _noise(jnp.broadcast_arrays(*coords), tables, period, basis, derivatives,
                 None if shift_axis is None else (shift_axis, shift))
    if derivatives:
        value, grad = res
        return value, (grad[0] * scale, grad[1] * scale)
    return res


def _octave(x, y, t, i, frequency, seed, period, basis, animation, evolution, time_exponent, derivatives, shift=None):
    """Octave i (unweighted) at world points and time t: time as a third axis, or two lattices
    at successive whole time steps blended (S&W)."""
    scale = float(frequency) * 2.0**i
    oseed = (int(seed) + 7919 * i) % 2**31
    period = TABLE_SIZE if period is None else period
    axis, amount = (None, 0.0) if shift is None else shift
    core = functools.partial(_octave_core, basis=basis, derivatives=derivatives, shift_axis=axis)
    if t is None:
        return core(x, y, None, scale, _tables(oseed), period, amount)
    rate = float(evolution) * 2.0 ** (float(time_exponent) * i)
    if animation == "dimension":
        return core(x, y, t * rate, scale, _tables(oseed), period, amount)
    step = _lattice_step(t, i, evolution, time_exponent)
    a = t * rate - step
    r0 = core(x, y, None, scale, _tables((oseed + 104729 * step) % 2**31), period, amount)
    r1 = core(x, y, None, scale, _tables((oseed + 104729 * (step + 1)) % 2**31), period, amount)
    if derivatives:
        return (1 - a) * r0[0] + a * r1[0], tuple((1 - a) * g0 + a * g1 for g0, g1 in zip(r0[1], r1[1]))
    return (1 - a) * r0 + a * r1


_FBM_SPECS = dict(x=_POINTS, y=_POINTS, t=Maybe(Real()), octaves=Int(lo=1, hi=MAX_OCTAVES), hurst=Real(lo=0.0, hi=4.0, lo_open=True),
                  frequency=Real(lo=0.0, lo_open=True, hi=1e6), amplitude=Real(lo=0.0, lo_open=True, hi=1e6), seed=_SEED,
                  basis=Choice(_BASES), animation=Choice(_ANIMATIONS), evolution=Real(lo=0.0, hi=1e6),
                  time_exponent=Real(lo=0.0, hi=2.0), tile=Maybe(Real(lo=0.0, lo_open=True, hi=1e7)),
                  derivatives=Bool())


@validate(**_FBM_SPECS)
def fbm(x, y, t=None, *, octaves: int = 2, hurst: float = 1.0, frequency: float = 1.0, amplitude: float = 1.0,
        seed: int = 0, basis: str = "gradient", animation: str = "dimension", evolution: float = 1.0,
        time_exponent: float = 1.0, tile: float | None = None, derivatives: bool = False):
    """fBm height (m) at world points (x, y) (m) and time ``t`` (s): Σ_i a·2^{−H i}·n(2^i f₀ p, τ_i).

    Parameters
    ----------
    x, y : array_like
        Points, m (broadcastable).
    t : float, optional
        Time, s; None gives a still 2-D surface.
    octaves : int
        Number of octaves O, 1–24 (S&W use two).
    hurst : float
        H in (0, 4] (H = 0 weighs every octave alike: no fBm): octave i weighs 2^{−H·i}. The height spectrum falls as k^{−(2H+2)}
        (:func:`fbm_spectrum_slope`); H = 1 matches a wind sea's k⁻⁴ tail.
    frequency : float
        f₀, lattice cells per metre of octave 0 (its features are ~1/f₀ m across).
    amplitude : float
        a, m (heights stay below a·Σ 2^{−H i}).
    seed : int
    basis : {"gradient", "value"}
    animation : {"dimension", "lattices"}
        Time as a third noise axis, or two gradient lattices blended (module doc).
    evolution : float
        r, lattice cells per second along time for octave 0, ≥ 0 (0: still).
    time_exponent : float
        e in 0–2: octave i evolves at r·2^{e·i} (1: S&W; ½: like deep-water waves).
    tile : float, optional
        Side (m) of a square the surface must tile (f₀·tile whole; each octave ≤ 256 cells).
    derivatives : bool
        Also return the exact gradient (∂h/∂x, ∂h/∂y), dimensionless.

    Returns
    -------
    h, or (h, (gx, gy)) : jax.Array of the broadcast shape of ``x`` and ``y``
        Heights, m; with ``derivatives`` also ∂h/∂x, ∂h/∂y, dimensionless.

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces.
    *VMV*. K. Perlin (1985). An image synthesizer. *SIGGRAPH*; (2002) Improving noise. *ACM TOG* 21(3).
    """
    shape = _check_coords(x, y, None)
    dtype = jnp.result_type(jnp.asarray(x).dtype, jnp.asarray(y).dtype, jnp.float32)
    xs, ys = (jnp.broadcast_to(jnp.asarray(c, dtype), shape) for c in (x, y))
    periods = [_octave_period(tile, frequency, i) for i in range(octaves)]
    if tile is None and not (isinstance(x, jax.core.Tracer) or isinstance(y, jax.core.Tracer)):
        reach = float(max(np.max(np.abs(x)), np.max(np.abs(y)))) * frequency * 2 ** (octaves - 1)
        if reach > _MAX_COORD:
            raise ValueError(f"octaves: the finest octave reaches lattice coordinate {reach:.3g}, beyond "
                             f"{_MAX_COORD:g} where float32 loses the cell fraction; use fewer octaves")
    h = jnp.zeros(shape, dtype)
    gx = gy = jnp.zeros(shape, dtype)
    for i in range(octaves):
        w = amplitude * 2.0 ** (-hurst * i)
        r = _octave(xs, ys, t, i, frequency, seed, periods[i], basis, animation, evolution, time_exponent,
                    derivatives)
        if derivatives:
            h, gx, gy = h + w * r[0], gx + w * r[1][0], gy + w * r[1][1]
        else:
            h = h + w * r
    return (h, (gx, gy)) if derivatives else h


@validate(hurst=Real(lo=0.0, hi=4.0))
def fbm_spectrum_slope(hurst: float) -> float:
    """Slope d ln F / d ln k of fBm's 2-D height spectrum F(k), m⁴: −(2H + 2).

    Octave i carries variance ∝ 2^{−2H i} over a wavenumber band of area ∝ 4^i, so the
    variance density per unit k-area falls as k^{−2H−2}.

    Parameters
    ----------
    hurst : float
        H, dimensionless, in [0, 4] (as in :func:`fbm`).

    Returns
    -------
    float
        −(2H + 2), dimensionless.

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces. *VMV*.
    """
    return -(2.0 * hurst + 2.0)


# -- normals three ways -----------------------------------------------------------------
def _gradient_exact(x, y, t, step, **params):
    return fbm(x, y, t, derivatives=True, **params)[1]


def _gradient_shifted(x, y, t, step, **params):
    """S&W: forward differences with the interpolation weights shifted by ``step`` (m) in the same cell."""
    octaves, frequency, amplitude, hurst = (params["octaves"], params["frequency"], params["amplitude"],
                                            params["hurst"])
    tile = params.get("tile")
    dtype = jnp.result_type(jnp.asarray(x).dtype, jnp.float32)
    x, y = jnp.broadcast_arrays(jnp.asarray(x, dtype), jnp.asarray(y, dtype))
    gx = gy = jnp.zeros(x.shape, dtype)
    opts = {k: params[k] for k in ("seed", "basis", "animation", "evolution", "time_exponent")}
    for i in range(octaves):
        w = amplitude * 2.0 ** (-hurst * i)
        scale = frequency * 2.0**i
        period = _octave_period(tile, frequency, i)
        args = (x, y, t, i, frequency, opts["seed"], period, opts["basis"], opts["animation"], opts["evolution"],
                opts["time_exponent"], False)
        h0 = _octave(*args)
        hx = _octave(*args, shift=(0, float(step * scale)))
        hy = _octave(*args, shift=(1, float(step * scale)))
        gx, gy = gx + w * (hx - h0) / step, gy + w * (hy - h0) / step
    return gx, gy


def _gradient_central(x, y, t, step, **params):
    f = lambda a, b: fbm(a, b, t, **params)
    return (f(x + step, y) - f(x - step, y)) / (2 * step), (f(x, y + step) - f(x, y - step)) / (2 * step)


NORMAL_METHODS = Methods("noise normals", exact=_gradient_exact, shifted=_gradient_shifted, central=_gradient_central)
"""How :func:`noise_gradient` differentiates: ``exact``, ``shifted`` (S&W), ``central``."""


@validate(x=_POINTS, y=_POINTS, t=Maybe(Real()), method=Choice(tuple(NORMAL_METHODS)),
          step=Real(lo=0.0, lo_open=True, hi=1e3))
def noise_gradient(x, y, t=None, *, method: str = "exact", step: float = 0.01, **params):
    """(∂h/∂x, ∂h/∂y) of :func:`fbm` with ``params`` by ``method`` in :data:`NORMAL_METHODS`.

    ``step`` (m) is the difference step of ``shifted`` and ``central`` (ignored by
    ``exact``). The unit normal is (−∂h/∂x, −∂h/∂y, 1)/norm.

    Parameters
    ----------
    x, y : array_like
        Points, m (broadcastable).
    t : float, optional
        Time, s; None gives a still 2-D surface.
    method : {"exact", "shifted", "central"}
        A name in :data:`NORMAL_METHODS`.
    step : float
        Difference step, m, in (0, 1e3].
    **params
        :func:`fbm`'s keyword parameters (``octaves``, ``hurst``, ``frequency``, ``amplitude``,
        ``seed``, ``basis``, ``animation``, ``evolution``, ``time_exponent``, ``tile``), checked
        as there; unknown names raise TypeError.

    Returns
    -------
    (gx, gy) : tuple of jax.Array
        ∂h/∂x and ∂h/∂y, dimensionless, of the broadcast shape of ``x`` and ``y``.

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces.
    *VMV* (the ``shifted`` differences). K. Perlin (1985). An image synthesizer. *SIGGRAPH*;
    (2002) Improving noise. *ACM TOG* 21(3).
    """
    params = {**dict(octaves=2, hurst=1.0, frequency=1.0, amplitude=1.0, seed=0, basis="gradient",
                     animation="dimension", evolution=1.0, time_exponent=1.0, tile=None), **params}
    unknown = set(params) - set(_FBM_SPECS) - {"tile"}
    if unknown:
        raise TypeError(f"noise_gradient: unknown fbm parameter(s) {sorted(unknown)}")
    fbm(jnp.zeros(()), jnp.zeros(()), t, **params)  # checks every parameter by name, cheaply
    return NORMAL_METHODS[method](x, y, t, step, **params)


# -- the S&W base surface ----------------------------------------------------------------
def _bspline_weights(t):
    t2, t3 = t * t, t * t * t
    w = ((1 - t) ** 3 / 6, (3 * t3 - 6 * t2 + 4) / 6, (-3 * t3 + 3 * t2 + 3 * t + 1) / 6, t3 / 6)
    dw = (-((1 - t) ** 2) / 2, (9 * t2 - 12 * t) / 6, (-9 * t2 + 6 * t + 3) / 6, t2 / 2)
    return w, dw


@validate(control=Array(ndim=2), length=Real(lo=0.0, lo_open=True, hi=1e7), x=_POINTS, y=_POINTS,
          derivatives=Bool())
def bspline_surface(control, length: float, x, y, *, derivatives: bool = False):
    """The periodic uniform cubic B-spline surface of a control grid, at points (x, y), m.

    ``control`` (m, m) holds heights (m) of control points spaced ``length``/m over the
    square [−L/2, L/2)², point (i, j) at the cell centre −L/2 + (j + ½)L/m (the grid
    convention). The surface is C², tiles the square, and lies within the control
    values' range. With ``derivatives`` also returns (∂h/∂x, ∂h/∂y).

    Parameters
    ----------
    control : array_like (m, m)
        Control-point heights, m, square, m ≥ 4.
    length : float
        L, side of the square, m, in (0, 1e7].
    x, y : array_like
        Points, m (broadcastable), |x|, |y| ≤ 1e6.
    derivatives : bool
        Also return the exact gradient (keyword only).

    Returns
    -------
    h, or (h, (gx, gy)) : jax.Array of the broadcast shape
        Heights, m; gradient ∂h/∂x, ∂h/∂y, dimensionless.

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces.
    *VMV* (a smooth base surface from an 8 × 8 control grid).
    """
    c = jnp.asarray(control)
    m = c.shape[0]
    if c.shape != (m, m) or m < 4:
        raise ValueError(f"control must be a square grid of at least 4 × 4 points, got shape {c.shape}")
    _check_coords(x, y, None)
    dtype = jnp.result_type(c.dtype, jnp.asarray(x).dtype, jnp.float32)
    c = c.astype(dtype)
    u = (jnp.asarray(x, dtype) + 0.5 * length) / length * m - 0.5
    v = (jnp.asarray(y, dtype) + 0.5 * length) / length * m - 0.5
    u, v = jnp.broadcast_arrays(u, v)
    iu, iv = jnp.floor(u).astype(jnp.int32), jnp.floor(v).astype(jnp.int32)
    wu, dwu = _bspline_weights(u - iu)
    wv, dwv = _bspline_weights(v - iv)
    h = gx = gy = jnp.zeros(u.shape, dtype)
    for a in range(4):
        for b in range(4):
            cij = c[jnp.mod(iv + a - 1, m), jnp.mod(iu + b - 1, m)]
            h = h + wv[a] * wu[b] * cij
            if derivatives:
                gx = gx + wv[a] * dwu[b] * cij
                gy = gy + dwv[a] * wu[b] * cij
    if derivatives:
        return h, (gx * m / length, gy * m / length)
    return h


@validate(length=Real(lo=0.0, lo_open=True, hi=1e7), size=Int(lo=4, hi=TABLE_SIZE), amplitude=Real(lo=0.0, lo_open=True, hi=1e6),
          seed=_SEED)
def base_control_grid(length: float, size: int = 8, amplitude: float = 1.0, seed: int = 0):
    """S&W's control grid: one low-frequency octave of gradient noise on ``size`` × ``size`` points.

    Over a square of side ``length`` (m), two lattice cells across (periodic), times
    ``amplitude`` (m). Draw it with :func:`bspline_surface`.

    Parameters
    ----------
    length : float
        Side of the square, m, in (0, 1e7] (checked; the grid itself depends only on ``size``).
    size : int
        Control points per side, 4 … 256 (:data:`TABLE_SIZE`).
    amplitude : float
        m, in (0, 1e6].
    seed : int
        Picks the noise (0 ≤ seed < 2³¹).

    Returns
    -------
    jax.Array (size, size)
        Control-point heights, m.

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces. *VMV*.
    """
    c = (jnp.arange(size) + 0.5) / size * 2.0  # lattice coordinates, period 2 cells
    n = gradient_noise(c[None, :], c[:, None] + 0.37, seed=seed, period=2)
    return amplitude * n


@dataclass(frozen=True)
class NoiseSea:
    """A calm procedural sea in the style of Schneider & Westermann: a B-spline base surface
    from an 8 × 8 control grid plus an animated fBm, tiling a square of side ``length``.

    Parameters
    ----------
    length : float
        Side of the tile, m.
    amplitude : float
        fBm amplitude a, m.
    frequency : float
        Lattice cells per metre of the first fBm octave (rounded so the tile holds a whole number).
    octaves, hurst, seed, evolution, time_exponent, basis, animation
        As :func:`fbm`.
    base_amplitude : float
        Height scale of the base surface, m (0: none).

    References
    ----------
    J. Schneider & R. Westermann (2001). Towards real-time visual simulation of water surfaces.
    *VMV*.
    """

    length: float = 16.0
    amplitude: float = 0.03
    frequency: float = 0.5
    octaves: int = 2
    hurst: float = 1.0
    seed: int = 0
    evolution: float = 0.4
    time_exponent: float = 0.5
    basis: str = "gradient"
    animation: str = "dimension"
    base_amplitude: float = 0.05

    def __post_init__(self):
        check_scalar("length", self.length, lo=0.0, lo_open=True, hi=1e7)
        check_scalar("amplitude", self.amplitude, lo=0.0, lo_open=True, hi=1e6)
        check_scalar("frequency", self.frequency, lo=0.0, lo_open=True, hi=1e6)
        cells = max(1, round(self.frequency * self.length))
        object.__setattr__(self, "frequency", cells / self.length)
        check_int("octaves", self.octaves, lo=1, hi=MAX_OCTAVES)
        _octave_period(self.length, self.frequency, self.octaves - 1, "octaves")
        check_scalar("hurst", self.hurst, lo=0.0, hi=4.0, lo_open=True)
        _SEED("seed", self.seed, {})
        check_scalar("evolution", self.evolution, lo=0.0, hi=1e6)
        check_scalar("time_exponent", self.time_exponent, lo=0.0, hi=2.0)
        Choice(_BASES)("basis", self.basis, {})
        Choice(_ANIMATIONS)("animation", self.animation, {})
        check_scalar("base_amplitude", self.base_amplitude, lo=0.0, hi=1e6)

    def _params(self):
        return dict(octaves=self.octaves, hurst=self.hurst, frequency=self.frequency, amplitude=self.amplitude,
                    seed=self.seed, basis=self.basis, animation=self.animation, evolution=self.evolution,
                    time_exponent=self.time_exponent, tile=self.length)

    def _grid(self, grid):
        Instance(Grid, "wavephys.Grid")("grid", grid, {})
        if abs(float(grid.length) - self.length) > 1e-9 * self.length:
            raise ValueError(f"grid: the sea tiles {self.length} m, the grid is {float(grid.length)} m")
        cell = 1.0 / (self.frequency * 2 ** (self.octaves - 1))
        if cell < 2 * float(grid.dx):
            raise ValueError(f"grid: the finest octave's lattice cell ({cell:.3g} m) spans fewer than 2 grid cells "
                             f"(dx = {float(grid.dx):.3g} m), so it aliases; use a finer grid or fewer octaves")
        return grid.mesh()

    @validate(t=Real(lo=0.0, hi=1e6))
    def heights(self, grid: Grid, t: float = 0.0):
        """Heights (n, n), m, on ``grid`` (of side ``length``) at time ``t``, s."""
        x, y = self._grid(grid)
        h = fbm(x, y, t, **self._params())
        if self.base_amplitude:
            h = h + bspline_surface(base_control_grid(self.length, 8, self.base_amplitude, self.seed), self.length, x, y)
        return h

    @validate(t=Real(lo=0.0, hi=1e6), method=Choice(tuple(NORMAL_METHODS)), step=Maybe(Real(lo=0.0, lo_open=True)))
    def gradient(self, grid: Grid, t: float = 0.0, method: str = "exact", step: float | None = None):
        """(∂h/∂x, ∂h/∂y) on ``grid`` by ``method`` (step default: the grid spacing)."""
        x, y = self._grid(grid)
        gx, gy = noise_gradient(x, y, t, method=method, step=float(step or grid.dx), **self._params())
        if self.base_amplitude:
            _, (bx, by) = bspline_surface(base_control_grid(self.length, 8, self.base_amplitude, self.seed),
                                          self.length, x, y, derivatives=True)
            gx, gy = gx + bx, gy + by
        return gx, gy
