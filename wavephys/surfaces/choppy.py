r"""Choppy waves: the horizontal displacement of a spectral sea (Tessendorf 2001), its Jacobian, foam.

A height field h on a periodic :class:`~wavephys.Grid` with spectrum ĥ = F[h] moves each
surface point sideways by λ·D (docs/physics.md §1.9),

.. math::

    \mathbf X = \mathbf x + \lambda\,\mathbf D(\mathbf x),\qquad
    \mathbf D = \mathcal F^{-1}\!\big[\,i\,\tfrac{\mathbf k}{|\mathbf k|}\,\hat h\,\big],

so that one component h = A cos(k·x) gives D = −A k̂ sin(k·x): with λ = 1 exactly the
deep-water Gerstner wave of steepness Q = 1, crests sharpened and troughs flattened.
*Sign.* Tessendorf prints D = Σ −i (k/k) h̃ e^{ik·x}; with the same synthesis
convention (numpy's ``ifft``) that moves points *away* from the crests for λ > 0 —
crests flatten and the surface folds in the troughs — which is why engines run it with
λ < 0. Here the sign sits in D and λ ≥ 0 is the choppiness (tested against Gerstner).

The Jacobian of the horizontal map,

.. math::

    J = (1 + \lambda D_{x,x})(1 + \lambda D_{y,y}) - \lambda^2 D_{x,y} D_{y,x},\qquad
    \hat D_{a,b} = -\frac{k_a k_b}{|k|}\hat h ,

is the ratio of a small patch's displaced area to its rest area: J = 1 undisturbed, J < 1
compressed (near crests), J ≤ 0 folded (the surface loops; heights multi-valued). To first
order in λ, J ≈ 1 − λ F⁻¹[|k| ĥ], a Gaussian variable for a Gaussian sea with standard
deviation λσ₁, σ₁² = ⟨(F⁻¹[|k|ĥ])²⟩ (:func:`jacobian_std`).

Foam: :func:`foam` marks where J < ``threshold`` — where the surface is compressed to less
than that fraction of its rest area, the steep crests about to break (threshold 1 would
mark every compressed point, 0 only folds) — with a linear ramp of width ``softness``;
:func:`accumulate_foam` builds it up at once and lets it decay exponentially over frames.
"""

from __future__ import annotations

import math

import jax.numpy as jnp
import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.inputs import Array, Instance, Int, Real, field_of, validate
from wavephys.core.water import Water
from wavephys.physics.dispersion import angular_frequency

__all__ = ["displacement", "jacobian", "jacobian_std", "foam", "accumulate_foam", "foam_fraction_estimate",
           "fold_choppiness", "sea_height", "MAX_CHOPPINESS"]

MAX_CHOPPINESS = 100.0
"""Largest choppiness λ accepted (beyond it any visible sea folds everywhere)."""

_GRID = Instance(Grid, "wavephys.Grid")
_HEIGHT = field_of("grid")
_LAMBDA = Real(lo=0.0, hi=MAX_CHOPPINESS)


def _spectra(height, grid):
    h = jnp.asarray(height)
    dtype = jnp.result_type(h.dtype, jnp.float32)
    ky, kx = grid.wavenumbers(real=True)
    kx, ky = kx.astype(dtype), ky.astype(dtype)
    k = jnp.sqrt(kx * kx + ky * ky)
    inv = jnp.where(k > 0, 1.0 / jnp.where(k > 0, k, 1.0), 0.0)
    return jnp.fft.rfft2(h.astype(dtype)), kx, ky, k, inv


@validate(grid=_GRID, height=_HEIGHT, choppiness=_LAMBDA)
def displacement(height, grid: Grid, choppiness: float = 1.0):
    """λ·D (2, ..., n, n), m: the horizontal displacement (x, y) of each grid point of ``height``.

    ``height`` (..., n, n), m, is a real periodic field on ``grid``; its mean is ignored.
    Points are displaced to X = x + λD (module doc: D = F⁻¹[i k̂ ĥ], crests sharpened).

    Parameters
    ----------
    height : array_like (..., n, n)
        Real periodic height field on ``grid``, m (its mean is ignored).
    grid : Grid
    choppiness : float
        λ, dimensionless, in [0, 100] (:data:`MAX_CHOPPINESS`).

    Returns
    -------
    jax.Array (2, ..., n, n)
        λD, the (x, y) displacements, m.

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water (docs/physics.md §1.10). Tessendorf prints D with
    the opposite sign (module docstring).
    """
    spec, kx, ky, _, inv = _spectra(height, grid)
    s = (grid.n, grid.n)
    dx = jnp.fft.irfft2(1j * kx * inv * spec, s=s)
    dy = jnp.fft.irfft2(1j * ky * inv * spec, s=s)
    return choppiness * jnp.stack([dx, dy])


@validate(grid=_GRID, height=_HEIGHT, choppiness=_LAMBDA)
def jacobian(height, grid: Grid, choppiness: float = 1.0):
    """J (..., n, n) of the map x ↦ x + λD at each grid point (module doc; ≤ 0 where it folds).

    Parameters
    ----------
    height : array_like (..., n, n)
        Real periodic height field on ``grid``, m (its mean is ignored).
    grid : Grid
    choppiness : float
        λ, dimensionless, in [0, 100] (:data:`MAX_CHOPPINESS`).

    Returns
    -------
    jax.Array (..., n, n)
        J, dimensionless (1 undisturbed, < 1 compressed, ≤ 0 folded).

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water (docs/physics.md §1.10).
    """
    spec, kx, ky, _, inv = _spectra(height, grid)
    s = (grid.n, grid.n)
    dxx = jnp.fft.irfft2(-kx * kx * inv * spec, s=s)
    dyy = jnp.fft.irfft2(-ky * ky * inv * spec, s=s)
    dxy = jnp.fft.irfft2(-kx * ky * inv * spec, s=s)
    lam = choppiness
    return (1 + lam * dxx) * (1 + lam * dyy) - lam * lam * dxy * dxy


@validate(grid=_GRID, height=_HEIGHT)
def jacobian_std(height, grid: Grid) -> float:
    """σ₁ = rms of F⁻¹[|k| ĥ] (dimensionless): J ≈ 1 − λ·(that field), so λσ₁ is the spread of J.

    Parameters
    ----------
    height : array_like (..., n, n)
        Real periodic height field on ``grid``, m (its mean is ignored).
    grid : Grid

    Returns
    -------
    float
        σ₁, dimensionless.

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water (docs/physics.md §1.10).
    """
    spec, _, _, k, _ = _spectra(height, grid)
    field = jnp.fft.irfft2(k * spec, s=(grid.n, grid.n))
    return float(jnp.sqrt(jnp.mean(field * field)))


@validate(grid=_GRID, height=_HEIGHT)
def fold_choppiness(height, grid: Grid) -> float:
    """The smallest λ at which the surface folds somewhere (min J = 0).

    By bisection on :func:`jacobian` (relative accuracy 1e-4; ``inf`` for a flat field).

    Parameters
    ----------
    height : array_like (..., n, n)
        Real periodic height field on ``grid``, m (its mean is ignored).
    grid : Grid

    Returns
    -------
    float
        λ, dimensionless; ``inf`` means the surface never folds: no λ ≤ :data:`MAX_CHOPPINESS` folds it
        (a flat or nearly flat sea).

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water (docs/physics.md §1.10).
    """
    def jmin(lam):
        return float(jnp.min(jacobian(height, grid, lam)))

    hi = 1.0
    while jmin(hi) > 0:
        hi *= 2
        if hi > MAX_CHOPPINESS:
            return math.inf
    lo = 0.0
    while hi - lo > 1e-4 * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if jmin(mid) > 0 else (lo, mid)
    return hi


_J = Array(allow_inf=False)


@validate(jacobian=_J, threshold=Real(lo=-10.0, hi=10.0), softness=Real(lo=0.0, hi=10.0))
def foam(jacobian, threshold: float = 0.3, softness: float = 0.1):
    """Foam coverage in [0, 1] from the Jacobian: clip((threshold − J)/softness, 0, 1).

    ``threshold``: foam where the surface is compressed below this fraction of its rest
    area (J < threshold; 0 = folds only). ``softness`` (≥ 0): width of the ramp in J
    from none to full cover (0: a hard mask).

    Parameters
    ----------
    jacobian : array_like
        J (:func:`jacobian`), dimensionless, finite, any shape.
    threshold : float
        J below which foam appears, in [−10, 10].
    softness : float
        Width of the ramp in J, in [0, 10] (0: a hard mask).

    Returns
    -------
    jax.Array
        Foam coverage, dimensionless, in [0, 1], shape of ``jacobian``.
    """
    j = jnp.asarray(jacobian)
    if softness == 0:
        return (j < threshold).astype(jnp.result_type(j.dtype, jnp.float32))
    return jnp.clip((threshold - j) / softness, 0.0, 1.0)


@validate(previous=Array(lo=0.0, hi=1.0), coverage=Array(lo=0.0, hi=1.0), dt=Real(lo=0.0, lo_open=True, hi=1e6),
          decay_time=Real(lo=0.0, lo_open=True, hi=1e6))
def accumulate_foam(previous, coverage, dt: float, decay_time: float = 2.0):
    """The foam map one frame later: max(previous·e^{−dt/τ}, coverage), in [0, 1].

    New foam appears at once where ``coverage`` (this frame's :func:`foam`) is high; old
    foam fades with time constant ``decay_time`` τ, s (a crest's foam outlives the crest).

    Parameters
    ----------
    previous : array_like
        Last frame's foam map, in [0, 1].
    coverage : array_like
        This frame's :func:`foam`, in [0, 1], shape of ``previous``.
    dt : float
        Time since the last frame, s, in (0, 1e6].
    decay_time : float
        τ, s, in (0, 1e6].

    Returns
    -------
    jax.Array
        The new foam map, dimensionless, in [0, 1], shape of ``previous``.
    """
    p, c = jnp.asarray(previous), jnp.asarray(coverage)
    if np.shape(p) != np.shape(c):
        raise ValueError(f"previous and coverage must have one shape, got {np.shape(p)} and {np.shape(c)}")
    return jnp.maximum(p * math.exp(-dt / decay_time), c)


@validate(grid=_GRID, height=_HEIGHT, choppiness=_LAMBDA, threshold=Real(lo=-10.0, hi=10.0), order=Int(lo=1, hi=2))
def foam_fraction_estimate(height, grid: Grid, choppiness: float, threshold: float = 0.3, order: int = 1) -> float:
    """Fraction of the surface with J < ``threshold`` predicted from the sea's statistics alone.

    ``order=1``: J ≈ 1 − λ·F⁻¹[|k|ĥ] is Gaussian: Φ((threshold − 1)/(λσ₁)) (:func:`jacobian_std`).
    ``order=2``: the full J = (1 + λa)(1 + λb) − λ²c² with (a, b, c) = (D_x,x, D_y,y, D_x,y)
    jointly Gaussian with the covariance of the field, by a fixed-seed Monte Carlo of 2·10⁵
    draws (±0.001). Both treat the sea as Gaussian and infinite; a grid holding few
    dominant waves departs from them (measured over seeded Phillips seas: docs/physics.md §1.9).

    Parameters
    ----------
    height : array_like (..., n, n)
        Real periodic height field on ``grid``, m (its mean is ignored).
    grid : Grid
    choppiness : float
        λ, dimensionless, in [0, 100] (:data:`MAX_CHOPPINESS`).
    threshold : float
        J below which a point counts, in [−10, 10].
    order : {1, 2}
        1: the linear Gaussian estimate; 2: the full J by Monte Carlo.

    Returns
    -------
    float
        The predicted fraction, dimensionless, in [0, 1].

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water (docs/physics.md §1.10).
    """
    lam = choppiness
    if order == 1:
        sigma = jacobian_std(height, grid) * lam
        if sigma == 0:
            return float(threshold > 1)
        return 0.5 * math.erfc(-(threshold - 1) / (sigma * math.sqrt(2)))
    spec, kx, ky, _, inv = _spectra(height, grid)
    s = (grid.n, grid.n)
    fields = jnp.stack([jnp.fft.irfft2(-p * q * inv * spec, s=s).reshape(-1) for p, q in ((kx, kx), (ky, ky), (kx, ky))])
    cov = np.asarray(fields @ fields.T, np.float64) / fields.shape[1]
    a, b, c = np.random.default_rng(0).multivariate_normal(np.zeros(3), cov, 200_000, method="eigh").T
    return float(np.mean((1 + lam * a) * (1 + lam * b) - lam * lam * c * c < threshold))


@validate(grid=_GRID, sea=Array(complex_ok=True, min_ndim=2, shape=lambda a: (a["grid"].n, a["grid"].n)),
          water=Instance(Water, "wavephys.Water"), t=Real(lo=-1e6, hi=1e6))
def sea_height(sea, grid: Grid, water: Water, t: float):
    """Height (n, n), m, of a travelling linear sea at time ``t``, s: Re F⁻¹[F[sea]·e^{−iω(k)t}].

    ``sea`` is the complex field of :func:`wavephys.physics.wind.synthesize_height` (each
    Fourier component travels along its own k); ω(k) from the dispersion relation.

    Parameters
    ----------
    sea : array_like (..., n, n), complex
        The complex sea at t = 0, m.
    grid : Grid
    water : Water
    t : float
        Time, s, in [−1e6, 1e6].

    Returns
    -------
    jax.Array (..., n, n)
        The height at ``t``, m.
    """
    s = jnp.asarray(sea)
    dtype = jnp.result_type(s.dtype, jnp.complex64)
    k = grid.wavenumber_magnitude().astype(jnp.finfo(dtype).dtype)
    omega = angular_frequency(k, water)
    return jnp.real(jnp.fft.ifft2(jnp.fft.fft2(s.astype(dtype)) * jnp.exp(-1j * omega * t)))
