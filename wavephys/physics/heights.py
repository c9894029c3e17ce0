r"""Surface heights from the complex wave field ψ = φ + iχ (docs/physics.md §1.2 and §1.5).

First order (kinematic condition η_t = φ_z), per Fourier mode:

.. math::

    \eta_c = \mathcal F^{-1}\!\left[\frac{iK}{\omega}\hat\psi\right],\quad
    \eta = \operatorname{Re}\eta_c,\quad
    \dot\eta = \operatorname{Re}\mathcal F^{-1}\!\left[K\hat\psi\right],\quad
    K = |k|\tanh(|k|h)

Second order (Loviscach 2003, eq. 3): for ψ = a·e^{iθ}, θ = k·x − ωt,

.. math::

    \eta = a\,i\frac{|k|}{\omega}e^{i\theta} - a^2\frac{|k|^3}{2\omega^2}e^{2i\theta}
         = \eta_c + \tfrac12 |k|\,\eta_c^2 .

The paper leaves the general field to the reader ("can easily be done in the Fourier
domain"). We use η₂ = ½·Re[η_c · Λη_c] with Λ = F⁻¹|k|F, which equals eq. 3 exactly on a
single wave, costs three extra real inverse FFTs, and for deep gravity waves is the
Stokes result η = A cos θ + (kA²/2) cos 2θ, A = a|k|/ω. It is a deep-water formula
(docs/physics.md §1.5): at finite depth (kh < π) Stokes' coefficient is larger by
cosh(kh)(2 + cosh 2kh)/(2 sinh³ kh); it breaks down for steep waves (kA ≳ 0.3, measured
by :func:`second_order_error` against the exact waves of :mod:`wavephys.physics.stokes`).
"""

from __future__ import annotations

import math

import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import Array, Int, Real, check_array, check_int, check_scalar, validate
from wavephys.core.specs import BOOL, COMPLEX_FIELD, FIELD, GRID, POSITIVE, WATER
from wavephys.physics.dispersion import _compiled, angular_frequency, surface_operator
from wavephys.core.grid import Grid
from wavephys.core.water import Water

__all__ = [
    "height_multiplier",
    "first_order_height",
    "height_rate",
    "second_order_height",
    "potential_from_height",
    "monochromatic_wave",
    "second_order_error",
    "second_order_breakdown",
    "STEEPNESS",
]


@validate(k=Array(lo=0.0), water=WATER)
@_compiled
def height_multiplier(k, water: Water):
    """K(k)/ω(k), s/m: η̂_c = i·(K/ω)·ψ̂. Set to 0 at k = 0 (the mean level is fixed).

    Deep gravity waves: K/ω = sqrt(k/g).

    Parameters
    ----------
    k : array_like
        Angular wavenumber magnitude, rad/m, ≥ 0, any shape.
    water : Water
        g (m/s²), ρ (kg/m³), σ (N/m), depth h (m, ``inf`` for deep water).

    Returns
    -------
    jax.Array
        K/ω, s/m, shape of ``k``; 0 where ω = 0.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 3 (docs/physics.md §1.2).
    """
    K = surface_operator(k, water)
    omega = angular_frequency(k, water)
    pos = omega > 0
    return jnp.where(pos, K / jnp.where(pos, omega, 1.0), 0.0)


def _check_field(psi, grid):
    psi = jnp.asarray(psi)
    return psi if jnp.iscomplexobj(psi) else psi.astype(jnp.result_type(psi.dtype, jnp.complex64))


def _complex_height(psi_hat, grid, water):
    k = grid.wavenumber_magnitude()
    return jnp.fft.ifft2(1j * height_multiplier(k, water) * psi_hat)


@validate(grid=GRID, water=WATER, psi=COMPLEX_FIELD)
def first_order_height(psi, grid: Grid, water: Water):
    """Linear height η = Re F⁻¹[(iK/ω)ψ̂], m, from a complex field ψ (m²/s), ``(..., n, n)``.

    Parameters
    ----------
    psi : array_like (..., n, n)
        Complex wave field ψ = φ + iχ on ``grid``, m²/s (a real array is read as complex).
    grid : Grid
    water : Water

    Returns
    -------
    jax.Array (..., n, n)
        η, m.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 3 (docs/physics.md §1.2).
    """
    psi = _check_field(psi, grid)
    return _complex_height(jnp.fft.fft2(psi), grid, water).real


@validate(grid=GRID, water=WATER, psi=COMPLEX_FIELD)
def height_rate(psi, grid: Grid, water: Water):
    """Linear vertical surface velocity η̇ = Re F⁻¹[K ψ̂], m/s (= ∂φ/∂z at the surface).

    Parameters
    ----------
    psi : array_like (..., n, n)
        Complex wave field ψ = φ + iχ on ``grid``, m²/s (a real array is read as complex).
    grid : Grid
    water : Water

    Returns
    -------
    jax.Array (..., n, n)
        η̇, m/s.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 3 (docs/physics.md §1.2).
    """
    psi = _check_field(psi, grid)
    k = grid.wavenumber_magnitude()
    return jnp.fft.ifft2(surface_operator(k, water) * jnp.fft.fft2(psi)).real


def second_order_correction(eta, q, lam_eta, lam_q):
    """η₂ = ½·Re[η_c·Λη_c] = ½(η·Λη − q·Λq), m, with η_c = η + iq and Λ = |k|.

    Parameters are real arrays (m, m, 1, 1): the real and imaginary parts of the complex
    first-order height and their images under Λ. Pure; shared by the simulation's
    real-FFT path and :func:`second_order_height`.
    """
    return 0.5 * (eta * lam_eta - q * lam_q)


@validate(grid=GRID, water=WATER, psi=COMPLEX_FIELD)
def second_order_height(psi, grid: Grid, water: Water):
    """Height to second order η + η₂, m (Loviscach 2003 eq. 3, generalized; module doc).

    η₂ = ½·Re[η_c·Λη_c], Λ = F⁻¹|k|F: exact for a single wave, a deep-water formula
    (docs/physics.md §1.5).

    Parameters
    ----------
    psi : array_like (..., n, n)
        Complex wave field ψ = φ + iχ on ``grid``, m²/s (a real array is read as complex).
    grid : Grid
    water : Water

    Returns
    -------
    jax.Array (..., n, n)
        η + η₂, m.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 3.
    """
    psi = _check_field(psi, grid)
    eta_c = _complex_height(jnp.fft.fft2(psi), grid, water)
    lam = jnp.fft.ifft2(grid.wavenumber_magnitude() * jnp.fft.fft2(eta_c))
    return eta_c.real + second_order_correction(eta_c.real, eta_c.imag, lam.real, lam.imag)


@validate(grid=GRID, water=WATER, travelling=BOOL)
def potential_from_height(eta, grid: Grid, water: Water, travelling: bool = False):
    """A complex field ψ whose first-order height is ``eta``.

    Parameters
    ----------
    eta : array_like
        Height, m, shape ``(..., n, n)``. The mean (k = 0 mode) cannot be represented by
        waves and is dropped.
    grid, water
    travelling : bool
        ``False`` (default): real η, fluid at rest (φ = 0, ψ = iχ with χ̂ = −(ω/K)η̂):
        the Cauchy–Poisson initial value problem; the disturbance spreads both ways like
        a dropped stone. ``True``: ``eta`` is read as a complex field whose every Fourier
        component travels along its own k (ψ̂ = −i(ω/K)η̂, used for wind seas); only its
        real part is a height.

    Returns
    -------
    jax.Array
        Complex ψ, m²/s.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 3 (docs/physics.md §1.2).
    """
    check_array("eta", eta, complex_ok=travelling, min_ndim=2, shape_tail=(grid.n, grid.n))
    k = grid.wavenumber_magnitude()
    m = height_multiplier(k, water)
    pos = m > 0
    inv = jnp.where(pos, 1.0 / jnp.where(pos, m, 1.0), 0.0)  # ω/K, 0 at k = 0
    eta_hat = jnp.fft.fft2(jnp.asarray(eta))
    if travelling:
        return jnp.fft.ifft2(-1j * inv * eta_hat)
    chi = jnp.fft.ifft2(-inv * eta_hat).real
    return 1j * chi


@validate(grid=GRID, water=WATER, steepness=POSITIVE)
def monochromatic_wave(grid: Grid, water: Water, steepness: float, mode: int = 4):
    """ψ = a·e^{ik(x + L/2)} travelling in +x with first-order height amplitude A = steepness/k.

    ``mode`` wavelengths fit the grid (k = 2π·mode/L). Its first-order height is
    η = −A sin(k(x + L/2)).

    Parameters
    ----------
    grid : Grid
    water : Water
    steepness : float
        kA, dimensionless, > 0.
    mode : int
        Wavelengths across the grid, 1 … n/2 − 1.

    Returns
    -------
    (psi, k, A) : (jax.Array (n, n), float, float)
        Complex ψ (m²/s) on the grid, k (rad/m) and A (m).
    """
    mode = check_int("mode", mode, lo=1, hi=grid.n // 2 - 1)
    k = 2 * math.pi * mode / float(grid.length)
    amplitude = steepness / k
    omega = float(angular_frequency(k, water))
    x, _ = grid.mesh()
    psi = (amplitude * omega / k) * jnp.exp(1j * k * (x + float(grid.length) / 2))
    return psi, k, amplitude


@validate(steepness=Real(lo=0.0, hi=0.33, lo_open=True), water=WATER, n=Int(lo=32, hi=4096, even=True))
def second_order_error(steepness: float, water: Water = Water(sigma=0.0), n: int = 256) -> dict:
    """Errors of first- and second-order heights against the exact Stokes wave (deep water).

    A wave of first-harmonic amplitude A (kA = ``steepness``) is built in ψ
    (:func:`monochromatic_wave`); its second-order height is compared with the exact
    steady Stokes wave whose η(x) has the same first harmonic
    (:func:`wavephys.physics.stokes.stokes_wave`), at the same phase.

    Parameters
    ----------
    steepness : float
        kA, dimensionless, in (0, 0.33].
    water : Water
        Deep water is assumed by the comparison (default: gravity only, σ = 0).
    n : int
        Grid points per side, even, 32 … 4096.

    Returns
    -------
    dict
        ``{"first": max|η₁ − η_exact|/A, "second": max|η₁ + η₂ − η_exact|/A}``, dimensionless.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 3.
    """
    from wavephys.physics.stokes import stokes_wave

    grid = Grid(n, 2 * np.pi * 4)
    psi, k, amplitude = monochromatic_wave(grid, water, steepness)
    eta2 = np.asarray(second_order_height(psi, grid, water), np.float64)[0]
    xs = np.asarray(grid.coordinates, np.float64) + float(grid.length) / 2
    # our first harmonic is −A sin(kx) = A cos(kx + π/2): the exact crest sits at kx = 3π/2
    exact = stokes_wave(steepness, k)(xs - 1.5 * np.pi / k)
    eta1 = -amplitude * np.sin(k * xs)
    return dict(first=np.abs(eta1 - exact).max() / amplitude, second=np.abs(eta2 - exact).max() / amplitude)


STEEPNESS = tuple(float(s) for s in np.round(np.arange(0.02, 0.331, 0.02), 3))
"""Steepness values kA at which second-order heights are compared with exact Stokes waves."""


@validate(tolerance=Real(lo=0.0, hi=1.0, lo_open=True), steepness=Array(lo=0.0, hi=0.33, lo_open=True, ndim=1))
def second_order_breakdown(tolerance: float = 0.1, steepness=STEEPNESS) -> float:
    """Smallest kA at which the second-order height error (max |Δη| / A) reaches ``tolerance``.

    Linear interpolation between the sampled ``steepness`` values; ``inf`` if never.

    Parameters
    ----------
    tolerance : float
        Relative error max |Δη|/A, in (0, 1].
    steepness : array_like (m,)
        kA values tried, each in (0, 0.33], at least two, increasing (default :data:`STEEPNESS`).

    Returns
    -------
    float
        kA, dimensionless; ``inf`` if the error stays below ``tolerance``.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 3.
    """
    if len(steepness) < 2 or np.any(np.diff(steepness) <= 0):
        raise ValueError(f"steepness must hold at least two increasing values, got {steepness!r}")
    errs = [second_order_error(float(s))["second"] for s in steepness]
    for (s0, e0), (s1, e1) in zip(zip(steepness, errs), zip(steepness[1:], errs[1:])):
        if e0 < tolerance <= e1:
            return float(s0 + (tolerance - e0) * (s1 - s0) / (e1 - e0))
    return math.inf
