r"""Open-ocean boundary: the margin cutoff of Loviscach (2003), §3 (docs/physics.md §1.4).

Each step the field is multiplied by h(p)·h(q) (p along x, q along y) with margin M:

.. math::

    h(p) = \begin{cases}
        1 - (p/M - 1)^2 & p < M \\
        1 & M \le p < N - M \\
        1 - ((N - 1 - p)/M - 1)^2 & p \ge N - M
    \end{cases}

(:func:`cutoff_quadratic`, the paper's choice), or h(p) = p/M on the same margins
(:func:`cutoff_linear`, the earlier choice of Loviscach 2002). Only the inner (N − 2M)²
points are meant to be shown. How much of a wave the margin reflects, as a function of
λ/M, is measured by :func:`cutoff_reflection`; :func:`cutoff_boundary` finds the λ/M
where it passes a threshold (the method's failure boundary).
"""

from __future__ import annotations

import functools
import math

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import Array, Choice, Real, check_array, check_int, check_scalar, validate
from wavephys.core.methods import Methods
from wavephys.core.spectral import angular_wavenumbers
from wavephys.core.water import Water
from wavephys.physics.dispersion import angular_frequency, group_speed

__all__ = ["cutoff_quadratic", "cutoff_linear", "CUTOFF_METHODS", "cutoff_profile", "cutoff_mask", "interior",
           "cutoff_reflection", "cutoff_boundary"]


_S = Array(lo=0.0, hi=1.0)
_DTYPE = Choice(("float32", "float64"))


def _dtype_name(dtype):
    import numpy

    if dtype is None:
        return dtype
    try:
        return numpy.dtype(dtype).name
    except TypeError:
        return dtype  # not a dtype: the Choice check says so


@validate(s=_S)
def cutoff_quadratic(s):
    """Quadratic cutoff weight 1 − (s − 1)² at s = p/M ∈ [0, 1) (Loviscach 2003).

    Parameters
    ----------
    s : array_like
        s = p/M, the distance p (points) to the nearer edge over the margin M, dimensionless,
        in [0, 1].

    Returns
    -------
    array_like
        The weights 1 − (s − 1)², dimensionless, in [0, 1], shape of ``s``.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (docs/physics.md
    §1.4).
    """
    return 1.0 - (s - 1.0) ** 2


@validate(s=_S)
def cutoff_linear(s):
    """Linear cutoff weight s at s = p/M ∈ [0, 1) (Loviscach 2002).

    Parameters
    ----------
    s : array_like
        s = p/M, the distance p (points) to the nearer edge over the margin M, dimensionless,
        in [0, 1].

    Returns
    -------
    array_like
        The weights s (``s`` itself), dimensionless, in [0, 1].

    References
    ----------
    J. Loviscach (2002), the earlier choice of the margin cutoff. The quadratic one: J. Loviscach
    (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (docs/physics.md §1.4).
    """
    return s


CUTOFF_METHODS = Methods("open-ocean cutoff", quadratic=cutoff_quadratic, linear=cutoff_linear)
"""Cutoff shapes by name: s = p/M in [0, 1) ↦ weight."""


def _check_margin(n, margin):
    n = check_int("n", n, lo=2)
    margin = check_int("margin", margin, lo=0)
    if 2 * margin >= n:
        raise ValueError(f"margin must be < n/2 = {n / 2}, got {margin}")
    return n, margin


def cutoff_profile(n: int, margin: int, method: str = "quadratic", dtype=jnp.float32, ends=(True, True)):
    """The 1-D cutoff weights h(p), p = 0 … n − 1 (dimensionless, in [0, 1]).

    Parameters
    ----------
    n : int
        Grid points per side, ≥ 2.
    margin : int
        M, points, 0 ≤ M < n/2 (0: no cutoff, all weights 1).
    method : {"quadratic", "linear"}
        A name in :data:`CUTOFF_METHODS`.
    dtype : dtype of the result.
    ends : (bool, bool)
        Whether the low (p = 0) and the high (p = n − 1) end are open (get the margin); an end
        that is a reflecting wall keeps weight 1 (docs/physics.md §1.11).

    Returns
    -------
    jax.Array (n,)
        h(p), dimensionless, in [0, 1], of ``dtype``.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (docs/physics.md §1.4).
    """
    n, margin = _check_margin(n, margin)
    shape = CUTOFF_METHODS.check(method)
    dtype = _DTYPE("dtype", _dtype_name(dtype), {})
    if margin == 0:
        return jnp.ones(n, dtype)
    if not isinstance(ends, (tuple, list)) or len(ends) != 2 or not all(isinstance(e, (bool, np.bool_)) for e in ends):
        raise TypeError(f"ends must be a pair (low, high) of bools, got {ends!r}")
    return _profile(n, margin, method, dtype, bool(ends[0]), bool(ends[1]))


@functools.partial(jax.jit, static_argnums=(0, 1, 2, 3, 4, 5))
def _profile(n: int, margin: int, method: str, dtype: str, low: bool, high: bool):
    """:func:`cutoff_profile` past its checks: one program per size and options."""
    shape = CUTOFF_METHODS.check(method)
    p = jnp.arange(n, dtype=dtype)
    big = jnp.asarray(n, dtype)
    dist = jnp.minimum(p if low else big, n - 1 - p if high else big)  # distance to the nearer open edge
    return jnp.where(dist < margin, shape(jnp.minimum(dist / margin, 1.0)), 1.0).astype(dtype)


def cutoff_mask(n: int, margin: int, method: str = "quadratic", dtype=jnp.float32, walls=()):
    """The 2-D weights h(q)·h(p) of shape ``(n, n)`` (rows q = y, columns p = x).

    Parameters
    ----------
    n : int
        Grid points per side, ≥ 2.
    margin : int
        M, points, 0 ≤ M < n/2 (0: no cutoff, all weights 1).
    method : {"quadratic", "linear"}
        A name in :data:`CUTOFF_METHODS`.
    dtype : dtype
        Of the result, float32 or float64.
    walls : str or iterable of str
        Sides that are reflecting walls (no margin there; :func:`wavephys.physics.walls.check_walls`).

    Returns
    -------
    jax.Array (n, n)
        The weights h(q)·h(p), dimensionless, in [0, 1] (:func:`cutoff_profile` per axis).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (docs/physics.md
    §1.4).
    """
    from wavephys.physics.walls import check_walls

    sides = check_walls(walls, margin=1)
    hx = cutoff_profile(n, margin, method, dtype, ("left" not in sides, "right" not in sides))
    hy = cutoff_profile(n, margin, method, dtype, ("bottom" not in sides, "top" not in sides))
    return hy[:, None] * hx[None, :]


def interior(field, margin: int):
    """The visible inner ``(n − 2M)²`` part of ``field`` (last two axes).

    Parameters
    ----------
    field : array_like (..., n, n)
        Any field on the grid, square on its last two axes (n ≥ 2).
    margin : int
        M, points, 0 ≤ M < n/2.

    Returns
    -------
    array_like (..., n − 2M, n − 2M)
        ``field[..., M:n − M, M:n − M]``, in the units of ``field``.
    """
    check_array("field", field, min_ndim=2)
    if np.shape(field)[-1] != np.shape(field)[-2]:
        raise ValueError(f"field must be square on its last two axes, got shape {np.shape(field)}")
    _check_margin(np.shape(field)[-1], margin)
    n = field.shape[-1]
    return field[..., margin:n - margin, margin:n - margin]


def cutoff_reflection(ratio: float, method: str = "quadratic", margin: int = 32,
                      group_cells_per_step: float = 0.5) -> float:
    """Energy fraction of a wave packet that the margin cutoff reflects (1-D, deep gravity).

    A packet of wavelength λ = ``ratio``·M cells (Gaussian envelope of width 2λ) travels
    toward the right margin; the cutoff is applied every step, and the step moves the
    group ``group_cells_per_step`` cells (the reflection grows when the cutoff is applied
    more often per crossing). Once the reflection is back in the middle of the domain,
    the energy of the left-moving components (kx < 0, weighted by K = |k|) over the
    initial energy is the reflected fraction. A y-uniform wave on the 2-D grid separates
    into exactly this 1-D problem.

    Parameters
    ----------
    ratio : float
        λ/M, the packet's wavelength over the margin, dimensionless, in (0, 64].
    method : {"quadratic", "linear"}
        A name in :data:`CUTOFF_METHODS`.
    margin : int
        M, cells, ≥ 1.
    group_cells_per_step : float
        Cells the packet's group moves per step, in (0, 8].

    Returns
    -------
    float
        The reflected energy fraction, dimensionless, ≥ 0.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (docs/physics.md
    §1.4).
    """
    check_scalar("ratio", ratio, lo=0.0, lo_open=True, hi=64.0)
    margin = check_int("margin", margin, lo=1)
    check_scalar("group_cells_per_step", group_cells_per_step, lo=0.0, hi=8.0, lo_open=True)
    water = Water(sigma=0.0)
    lam = ratio * margin
    n = 1 << int(np.ceil(np.log2(2 * (9 * lam + margin))))
    k0 = 2 * np.pi / lam
    k = np.asarray(angular_wavenumbers((1, n), 1.0, xp=np)[1][0])
    x = np.arange(n, dtype=np.float64)
    env = np.exp(-0.5 * ((x - n / 2) / (2 * lam)) ** 2)
    dt = group_cells_per_step / float(group_speed(k0, water))
    steps = int(1.5 * (n / 2 - margin) / group_cells_per_step)
    kabs = np.abs(k)
    omega = np.asarray(angular_frequency(kabs.astype(np.float32), water), np.float64)
    mult = jnp.asarray(np.exp(-1j * omega * dt), jnp.complex64)
    h = cutoff_profile(n, margin, method, jnp.float32)

    @jax.jit
    def run(f):
        return jax.lax.scan(lambda f, _: (jnp.fft.ifft(jnp.fft.fft(f * h) * mult), None), f, None, length=steps)[0]

    f0 = jnp.asarray(env * np.exp(1j * k0 * x), jnp.complex64)
    e0 = float(jnp.sum(jnp.abs(jnp.fft.fft(f0)) ** 2 * kabs))
    spec = jnp.fft.fft(run(f0))
    return float(jnp.sum(jnp.where(k < 0, jnp.abs(spec) ** 2 * kabs, 0.0))) / e0


def cutoff_boundary(method: str = "quadratic", threshold: float = 1e-3, lo: float = 0.125,
                    hi: float = 2.0, iterations: int = 6, **kw) -> float:
    """The λ/M above which the margin reflects more than ``threshold`` of the energy.

    Bisection in log(λ/M) on :func:`cutoff_reflection` (which grows with λ/M), a fixed
    number of ``iterations``; ``RuntimeError`` if [lo, hi] does not bracket the threshold.

    Parameters
    ----------
    method : {"quadratic", "linear"}
        A name in :data:`CUTOFF_METHODS`.
    threshold : float
        Reflected energy fraction, in (0, 1).
    lo, hi : float
        The bracket of λ/M searched, each in (0, 64], hi > lo.
    iterations : int
        Bisection steps, 1 … 60.
    **kw
        Passed on to :func:`cutoff_reflection` (``margin``, ``group_cells_per_step``).

    Returns
    -------
    float
        λ/M where the reflection passes ``threshold``, dimensionless.

    Raises
    ------
    RuntimeError
        If [lo, hi] does not bracket the threshold.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (docs/physics.md
    §1.4).
    """
    check_scalar("threshold", threshold, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
    check_scalar("lo", lo, lo=0.0, hi=64.0, lo_open=True)
    check_scalar("hi", hi, lo=0.0, hi=64.0, lo_open=True)
    if hi <= lo:
        raise ValueError(f"hi must be larger than lo = {lo}, got {hi}")
    iterations = check_int("iterations", iterations, lo=1, hi=60)
    a, b = math.log(lo), math.log(hi)
    if cutoff_reflection(lo, method, **kw) > threshold or cutoff_reflection(hi, method, **kw) < threshold:
        raise RuntimeError(f"reflection boundary of the {method} cutoff not in [{lo}, {hi}]")
    for _ in range(iterations):
        m = 0.5 * (a + b)
        a, b = (a, m) if cutoff_reflection(math.exp(m), method, **kw) > threshold else (m, b)
    return math.exp(0.5 * (a + b))
