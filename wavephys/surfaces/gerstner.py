r"""Gerstner (trochoidal) wave sums: positions, exact normals, the Jacobian and folds.

Each surface point is labelled by its rest position x₀ = (x₀, y₀) and moves on an orbit
(docs/physics.md §1.9):

.. math::

    \mathbf x = \mathbf x_0 - \sum_i Q_i\,c_i\,A_i\,\hat{\mathbf k}_i \sin\theta_i,\qquad
    z = \sum_i A_i \cos\theta_i,\qquad \theta_i = \mathbf k_i\cdot\mathbf x_0 - \omega_i t + \varphi_i,

with ω_i = ω(|k_i|) from :func:`wavephys.physics.dispersion.angular_frequency` (deep or
finite depth, capillarity included), steepness Q_i ∈ [0, 1] and c_i = coth(|k_i| h)
(1 in deep water): Q = 1 is the orbit of linear (Airy) theory, Q = 0 a plain sum of
cosines. The horizontal map x₀ ↦ x has the Jacobian

.. math::

    J = \Big(1 - \sum_i Q_i c_i A_i \tfrac{k_{x,i}^2}{k_i}\cos\theta_i\Big)
        \Big(1 - \sum_i Q_i c_i A_i \tfrac{k_{y,i}^2}{k_i}\cos\theta_i\Big)
      - \Big(\sum_i Q_i c_i A_i \tfrac{k_{x,i}k_{y,i}}{k_i}\cos\theta_i\Big)^2 ;

J ≤ 0 where the surface folds into loops (multi-valued heights). One wave folds when
Q·c·k·A ≥ 1: :class:`GerstnerWaves` refuses that (ValueError). A sum can fold where crests
meet once Σ Q_i c_i k_i A_i ≥ 1: it warns (:class:`FoldWarning`) and
:meth:`GerstnerWaves.fold_fraction` measures how much of a grid folds.

Sampled on a fixed grid (Eulerian heights, :meth:`GerstnerWaves.heights`), one deep-water
wave with Q = 1 has its mean level at −kA²/2 and crest and trough at A(1 ± kA/2) about it:
Stokes' crest-trough asymmetry. At equal crest-to-trough height the trochoid and the exact
Stokes wave agree through third order in elevation (both crests a + ka²/2 + 3k²a³/8, a
Stokes' first harmonic); the crests part at relative order (kA)³ — measured −0.065 % at
kA = 0.1, −2.3 % at kA = 0.3, the trochoid's crest lower (:func:`crest_comparison`).
"""

from __future__ import annotations

import functools
import warnings
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.inputs import (Array, Instance, Int, Real, check_array, check_instance, check_key, check_scalar,
                                  validate)
from wavephys.core.water import Water
from wavephys.physics.dispersion import angular_frequency, depth_factor

__all__ = ["GerstnerWaves", "FoldWarning", "crest_comparison"]

_POINTS = Array()


class FoldWarning(UserWarning):
    """A Gerstner sum steep enough that its crests may fold where they meet (Σ Q c k A ≥ 1).

    Raised (as a warning) by :class:`GerstnerWaves`; :meth:`GerstnerWaves.fold_fraction`
    measures how much of a grid folds.

    Parameters
    ----------
    *args
        The warning message, as for any :class:`UserWarning`.
    """


@dataclass(frozen=True, eq=False)
class GerstnerWaves:
    """A sum of Gerstner waves (module doc).

    Parameters
    ----------
    wavevectors : array_like (m, 2)
        (k_x, k_y) of each wave, rad/m, non-zero.
    amplitudes : array_like (m,)
        Vertical amplitudes A_i, m, ≥ 0.
    phases : array_like (m,), optional
        φ_i, rad (default 0).
    steepness : float or array_like (m,)
        Q_i in [0, 1] (1: the linear particle orbit; 0: no horizontal motion).
    water : Water
        g, σ and depth for ω(k) and the depth factor coth(kh).
    """

    wavevectors: object
    amplitudes: object
    phases: object = None
    steepness: object = 1.0
    water: Water = Water(sigma=0.0)

    def __post_init__(self):
        set_ = lambda k, v: object.__setattr__(self, k, v)
        check_array("wavevectors", self.wavevectors, ndim=2, lo=-1e6, hi=1e6)
        k = np.asarray(self.wavevectors, np.float64)
        if k.shape[1:] != (2,) or k.shape[0] < 1:
            raise ValueError(f"wavevectors must have shape (waves, 2), got {k.shape}")
        m = k.shape[0]
        kmag = np.hypot(k[:, 0], k[:, 1])
        if (kmag == 0).any():
            raise ValueError(f"wavevectors must be non-zero, wave(s) {np.flatnonzero(kmag == 0).tolist()} are 0")
        check_array("amplitudes", self.amplitudes, ndim=1, lo=0.0, hi=1e4)
        a = np.asarray(self.amplitudes, np.float64)
        if a.shape != (m,):
            raise ValueError(f"amplitudes must have one entry per wave, shape ({m},), got {a.shape}")
        phases = np.zeros(m) if self.phases is None else self.phases
        check_array("phases", phases, ndim=1, lo=-1e6, hi=1e6)
        if np.shape(phases) != (m,):
            raise ValueError(f"phases must have one entry per wave, shape ({m},), got {np.shape(phases)}")
        check_array("steepness", self.steepness, lo=0.0, hi=1.0)
        shape_ok = np.ndim(self.steepness) == 0 or np.shape(self.steepness) == (m,)
        q = np.broadcast_to(np.asarray(self.steepness, np.float64), (m,)) if shape_ok else None
        if q is None:
            raise ValueError(f"steepness must be a number or one per wave, shape ({m},), got {np.shape(self.steepness)}")
        check_instance("water", self.water, Water, "wavephys.Water")
        c = 1.0 / np.asarray(depth_factor(kmag, self.water), np.float64)
        reach = q * c * kmag * a  # per wave: the fold measure Q c k A
        if (reach >= 1).any():
            i = int(np.argmax(reach))
            raise ValueError(f"steepness: wave {i} has Q·c·k·A = {reach[i]:.3g} ≥ 1 (Q={q[i]:.3g}, k={kmag[i]:.3g} "
                             f"rad/m, A={a[i]:.3g} m, coth(kh)={c[i]:.3g}): it loops, its surface is multi-valued; "
                             "lower Q or A")
        if reach.sum() >= 1:
            warnings.warn(f"Gerstner sum: Σ Q·c·k·A = {reach.sum():.3g} ≥ 1, the surface may fold where crests meet "
                          "(see fold_fraction)", FoldWarning, stacklevel=3)
        set_("wavevectors", k)
        set_("amplitudes", a)
        set_("phases", np.asarray(phases, np.float64))
        set_("steepness", np.array(q))
        set_("_kmag", kmag)
        set_("_horizontal", q * c * a)  # horizontal orbit amplitudes, m
        set_("_omega", np.asarray(angular_frequency(kmag, self.water), np.float64))
        set_("_cache", {})

    @property
    def frequencies(self) -> np.ndarray:
        """ω_i, rad/s."""
        return self._omega.copy()

    @property
    def fold_measure(self) -> float:
        """Σ Q_i c_i k_i A_i: below 1 the map cannot fold anywhere."""
        return float((self._horizontal * self._kmag).sum())

    # -- evaluation ------------------------------------------------------------------
    def _params(self, dtype):
        """The arrays the pure evaluation needs, in ``dtype`` (made once per dtype)."""
        key = jnp.dtype(dtype).name
        if key not in self._cache:
            self._cache[key] = tuple(jnp.asarray(v, dtype) for v in (self.wavevectors, self._kmag, self.amplitudes,
                                                                      self.phases, self._horizontal, self._omega))
        return self._cache[key]

    def _points(self, x, y):
        check_array("x", x, lo=-1e7, hi=1e7)
        check_array("y", y, lo=-1e7, hi=1e7)
        try:
            shape = np.broadcast_shapes(np.shape(x), np.shape(y))
        except ValueError:
            raise ValueError(f"x and y must broadcast to one shape, got {np.shape(x)} and {np.shape(y)}") from None
        dtype = jnp.result_type(jnp.asarray(x).dtype, jnp.asarray(y).dtype, jnp.float32)
        x, y = jnp.broadcast_arrays(jnp.asarray(x, dtype), jnp.asarray(y, dtype))
        return x, y, self._params(dtype)

    @validate(t=Real(lo=-1e6, hi=1e6))
    def displacement(self, x, y, t: float = 0.0):
        """(Δx, Δy, z) (3, ...) of the points with rest positions (x, y), m, at time ``t``, s."""
        x, y, params = self._points(x, y)
        return _displace(params, x, y, t)

    def _derivatives(self, x, y, t):
        """∂(Δx, Δy, z)/∂(x₀, y₀): (3, 2, ...)."""
        x, y, params = self._points(x, y)
        return _evaluate(params, x, y, t)[1]

    @validate(t=Real(lo=-1e6, hi=1e6))
    def jacobian(self, x, y, t: float = 0.0):
        """J = det ∂x/∂x₀ of the horizontal map at rest positions (x, y), m (≤ 0: folded)."""
        d = self._derivatives(x, y, t)
        return (1 + d[0, 0]) * (1 + d[1, 1]) - d[0, 1] * d[1, 0]

    @validate(t=Real(lo=-1e6, hi=1e6))
    def normals(self, x, y, t: float = 0.0):
        """Exact unit normals (3, ...) of the displaced surface at rest positions (x, y), m:
        the cross product of the tangents ∂P/∂x₀ × ∂P/∂y₀ (z > 0 wherever J > 0)."""
        d = self._derivatives(x, y, t)
        tx = jnp.stack([1 + d[0, 0], d[1, 0], d[2, 0]])
        ty = jnp.stack([d[0, 1], 1 + d[1, 1], d[2, 1]])
        n = jnp.cross(tx, ty, axis=0)
        return n / jnp.linalg.norm(n, axis=0, keepdims=True)

    def _check_grid(self, grid):
        check_instance("grid", grid, Grid, "wavephys.Grid")
        dx = float(grid.dx)
        kmax = np.abs(self.wavevectors).max(axis=1)
        bad = np.flatnonzero(kmax * dx >= np.pi)
        if bad.size:
            i = int(bad[0])
            raise ValueError(f"grid: wave {i} (wavelength {2 * np.pi / self._kmag[i]:.3g} m) is not resolved by "
                             f"spacing {dx:.3g} m (needs |k_x|, |k_y| < π/dx = {np.pi / dx:.3g} rad/m)")

    @validate(grid=Instance(Grid, "wavephys.Grid"), t=Real(lo=-1e6, hi=1e6), iterations=Int(lo=1, hi=100))
    def heights(self, grid: Grid, t: float = 0.0, iterations: int = 8):
        """Eulerian heights (n, n), m, on ``grid`` at time ``t``: the surface over each grid
        point, found by inverting the horizontal map with Newton's method on the exact
        displacement (converged to rounding in ≤ 8 iterations for
        fold measures ≤ 0.9). Refuses folded surfaces (J ≤ 0 somewhere)."""
        self._check_grid(grid)
        x, y, params = self._points(*grid.mesh())
        return _finish(*_newton(params, x, y, t, iterations))

    @validate(grid=Instance(Grid, "wavephys.Grid"), t=Real(lo=-1e6, hi=1e6))
    def fold_fraction(self, grid: Grid, t: float = 0.0) -> float:
        """Fraction of ``grid``'s rest points where J ≤ 0 (the surface loops over them)."""
        x, y = grid.mesh()
        return float((self.jacobian(x, y, t) <= 0).mean())

    @classmethod
    def from_spectrum(cls, spectrum, grid: Grid, key, *, count: int = 32, steepness=0.5,
                      water: Water = Water(sigma=0.0)) -> "GerstnerWaves":
        """The ``count`` strongest components of a height spectrum as Gerstner waves.

        ``spectrum`` is F(k) (m⁴) on ``grid``'s full ``fft2`` wavenumbers (n, n), e.g.
        :func:`wavephys.physics.wind.wind_spectrum`; each chosen bin becomes a wave of
        amplitude A = sqrt(2 F Δk²) (the bin's variance) with a random phase from ``key``,
        so the sum tiles ``grid``. Non-finite spectra are refused.
        """
        check_instance("grid", grid, Grid, "wavephys.Grid")
        check_array("spectrum", spectrum, ndim=2, shape_tail=(grid.n, grid.n), lo=0.0)
        check_key("key", key)
        count = Int(lo=1, hi=grid.n * grid.n)("count", count, {})
        check_instance("water", water, Water, "wavephys.Water")
        f = np.asarray(spectrum, np.float64)
        ky, kx = (np.asarray(a, np.float64) for a in grid.wavenumbers())
        kx, ky = np.broadcast_to(kx, f.shape), np.broadcast_to(ky, f.shape)
        f = np.where((kx == 0) & (ky == 0), 0.0, f)
        order = np.argsort(f.ravel())[::-1][:count]
        order = order[f.ravel()[order] > 0]
        if order.size == 0:
            raise ValueError("spectrum is zero on every non-zero wavenumber of the grid")
        amps = np.sqrt(2.0 * f.ravel()[order]) * float(grid.dk)
        phases = np.asarray(jax.random.uniform(key, (order.size,), minval=0.0, maxval=2 * np.pi), np.float64)
        return cls(np.stack([kx.ravel()[order], ky.ravel()[order]], 1), amps, phases, steepness, water)


@jax.jit
def _displace(params, x, y, t):
    """(Δx, Δy, z) (3, ...) alone (half the work of :func:`_evaluate`)."""
    k, kmag, amp, phase, hor, omega = params
    theta = k[:, 0, None] * x.ravel()[None] + k[:, 1, None] * y.ravel()[None] - omega[:, None] * t + phase[:, None]
    hs = hor[:, None] * jnp.sin(theta)
    disp = jnp.stack([-((k[:, 0] / kmag)[:, None] * hs).sum(0), -((k[:, 1] / kmag)[:, None] * hs).sum(0),
                      (amp[:, None] * jnp.cos(theta)).sum(0)])
    return disp.reshape((3,) + x.shape)


@jax.jit
def _evaluate(params, x, y, t):
    """(Δx, Δy, z) (3, ...) and their derivatives (3, 2, ...) at rest points (x, y): the module's formulas."""
    k, kmag, amp, phase, hor, omega = params
    shape = x.shape
    theta = k[:, 0, None] * x.ravel()[None] + k[:, 1, None] * y.ravel()[None] - omega[:, None] * t + phase[:, None]
    cos, sin = jnp.cos(theta), jnp.sin(theta)
    ux, uy = (k[:, 0] / kmag)[:, None], (k[:, 1] / kmag)[:, None]
    hs, hc = hor[:, None] * sin, hor[:, None] * cos
    kx, ky = k[:, 0, None], k[:, 1, None]
    disp = jnp.stack([-(ux * hs).sum(0), -(uy * hs).sum(0), (amp[:, None] * cos).sum(0)])
    az = amp[:, None] * sin
    der = jnp.stack([jnp.stack([-(ux * kx * hc).sum(0), -(ux * ky * hc).sum(0)]),
                     jnp.stack([-(uy * kx * hc).sum(0), -(uy * ky * hc).sum(0)]),
                     jnp.stack([-(kx * az).sum(0), -(ky * az).sum(0)])])
    return disp.reshape((3,) + shape), der.reshape((3, 2) + shape)


@functools.partial(jax.jit, static_argnums=4)
def _newton(params, x, y, t, iterations):
    """Newton's method for x₀ + Δ(x₀) = x: (z(x₀), max residual, max |Δ|, min J)."""
    _, m = _evaluate(params, x, y, t)
    jrest = jnp.min((1 + m[0, 0]) * (1 + m[1, 1]) - m[0, 1] * m[1, 0])  # folds show on the rest points too
    def newton(_, p):
        x0, y0 = p
        d, m = _evaluate(params, x0, y0, t)
        rx, ry = x0 + d[0] - x, y0 + d[1] - y
        a, b, c, e = 1 + m[0, 0], m[0, 1], m[1, 0], 1 + m[1, 1]
        det = a * e - b * c
        det = jnp.where(jnp.abs(det) > 1e-6, det, jnp.where(det < 0, -1e-6, 1e-6))
        return x0 - (e * rx - b * ry) / det, y0 - (-c * rx + a * ry) / det

    x0, y0 = jax.lax.fori_loop(0, iterations, newton, (x, y))
    d, m = _evaluate(params, x0, y0, t)
    residual = jnp.max(jnp.hypot(x0 + d[0] - x, y0 + d[1] - y))
    jmin = jnp.minimum(jnp.min((1 + m[0, 0]) * (1 + m[1, 1]) - m[0, 1] * m[1, 0]), jrest)
    reach = jnp.max(jnp.abs(x)) + jnp.max(jnp.abs(y))
    floor = 16 * jnp.finfo(x.dtype).eps * reach  # rounding of the positions themselves
    return d[2], residual, 1e-4 * jnp.max(jnp.abs(d[:2])) + floor, jmin


def _finish(z, residual, allowed, jmin):
    residual, allowed, jmin = float(residual), float(allowed), float(jmin)
    if jmin <= 0:
        raise ValueError(f"the surface folds (Jacobian {jmin:.3g} ≤ 0): heights are multi-valued there; "
                         "lower the steepness")
    if residual > allowed:
        raise ValueError(f"iterations: Newton's method did not converge (residual {residual:.3g} m); "
                         "give more iterations")
    return z


@validate(steepness=Real(lo=0.0, hi=0.33, lo_open=True), wavenumber=Real(lo=0.0, lo_open=True, hi=1e4))
def crest_comparison(steepness: float, wavenumber: float = 1.0) -> dict:
    """A Q = 1 deep-water Gerstner wave against the exact Stokes wave of the same height.

    Both are scaled to crest-to-trough height H with kH/2 = ``steepness``·(Stokes' H/2A):
    the Stokes wave of first-harmonic steepness kA = ``steepness``
    (:func:`wavephys.physics.stokes.stokes_wave`) and the trochoid of the same H (its
    vertical amplitude H/2). Returns crest and trough elevations about each mean level (m)
    and their relative differences.

    Parameters
    ----------
    steepness : float
        kA of the Stokes wave, dimensionless, in (0, 0.33] (checked by ``stokes_wave``).
    wavenumber : float
        k, rad/m, > 0.

    Returns
    -------
    dict
        ``steepness``; ``height`` H, m; ``stokes_crest``, ``stokes_trough``, ``gerstner_crest``,
        ``gerstner_trough`` (elevations about each wave's mean level, m); ``gerstner_mean`` (the
        trochoid's Eulerian mean level, m); ``crest_error``, ``trough_error`` (Gerstner over
        Stokes − 1, dimensionless).

    References
    ----------
    K. I. Babenko (1987), with Dyachenko, Lushnikov & Korotkevich (2016), for the exact Stokes wave
    (docs/physics.md §1.5, §1.10).
    """
    from wavephys.physics.stokes import stokes_wave

    stokes = stokes_wave(steepness, wavenumber, 64)
    k = wavenumber
    a = stokes.height / 2  # trochoid amplitude with the same crest-to-trough height
    wave = GerstnerWaves(np.array([[k, 0.0]]), np.array([a]), steepness=1.0, water=Water(sigma=0.0))
    line = Grid(512, 2 * np.pi / k).coordinates  # one wavelength: the periodic mean is spectrally accurate
    x, y, params = wave._points(jnp.concatenate([jnp.array([0.0, np.pi / k]), line]), jnp.zeros(line.size + 2))
    z = np.asarray(_finish(*_newton(params, x, y, 0.0, 12)), np.float64)  # crest, trough (rest phases 0, π), line
    zmean = float(np.mean(z[2:]))  # the Eulerian mean level
    crest, trough = float(np.max(stokes._y)) / k, -float(np.min(stokes._y)) / k  # Stokes' mean level is 0
    g_crest, g_trough = float(z[0] - zmean), float(zmean - z[1])
    return dict(steepness=steepness, height=stokes.height, stokes_crest=crest, stokes_trough=trough,
                gerstner_crest=g_crest, gerstner_trough=g_trough, gerstner_mean=zmean,
                crest_error=g_crest / crest - 1, trough_error=g_trough / trough - 1)


