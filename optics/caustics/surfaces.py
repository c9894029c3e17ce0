"""Families of smooth random surfaces to test caustics methods on cases nobody picked.

A caustics method that is right on one sinusoid can be wrong on a 2-D sea. These surfaces
are random fields of three spectral shapes, scaled to a given steepest slope, so that a
test or a bench draws as many as it likes (seeded) and puts the floor anywhere up to the
first fold (:func:`optics.caustics.first_fold_depth`).
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp

from wavephys.core.grid import Grid
from wavephys.core.inputs import check_choice, check_instance, check_int, check_scalar

__all__ = ["SURFACE_SPECTRA", "random_surface"]


def _wind_sea(grid: Grid, spectrum: str, seed: int):
    """Amplitude shape √F of a wind sea peaked at k_p = 4·2π/L, wind from a direction drawn from ``seed``."""
    from wavephys.core.water import Water
    from wavephys.physics.wind import wind_spectrum

    water = Water(sigma=0.0)
    length = float(grid.length)
    kp = 4 * 2 * math.pi / length
    direction = float(jax.random.uniform(jax.random.PRNGKey(seed + 1), (), minval=0.0, maxval=2 * math.pi))
    ky, kx = grid.wavenumbers()
    if spectrum == "phillips":  # peak at k = 1/(√2 L_w), L_w = U²/g
        speed = math.sqrt(water.g / (math.sqrt(2.0) * kp))
        f = wind_spectrum(kx, ky, water, "phillips", wind_speed=speed, direction=direction)
    else:  # fetch chosen for U = 10 m/s so that ω_p = 22 (g²/(U F))^(1/3) = √(g k_p)
        speed = 10.0
        fetch = water.g ** 2 / speed * (22.0 / math.sqrt(water.g * kp)) ** 3
        f = wind_spectrum(kx, ky, water, "jonswap", wind_speed=speed, fetch=fetch, direction=direction)
    ell = 2.0 * float(grid.dx)
    k = jnp.hypot(kx, ky)
    return jnp.sqrt(jnp.maximum(f, 0.0)) * jnp.exp(-0.5 * (k * ell) ** 2)

SURFACE_SPECTRA = ("band", "power", "swell", "phillips", "jonswap")
"""Spectral shapes: ``"band"`` — a ring around a fifth of the domain (a sea of one
wavelength, all directions); ``"power"`` — k⁻² from a third of the domain down to a
sixteenth (many scales, a wind sea's slope); ``"swell"`` — long waves, a Gaussian below a
quarter of the domain; ``"phillips"`` and ``"jonswap"`` — wind seas
(:data:`wavephys.physics.wind.SPECTRA`), peaked at a quarter of the domain and travelling
with a wind from a random direction (cos² spreading), their short waves damped below five
samples per wavelength (exp(−k²ℓ²), ℓ = 2Δx) so that they are resolved on any grid."""


def random_surface(grid: Grid, spectrum: str = "band", steepness: float = 0.1, seed: int = 0):
    """A periodic random height field (m) on ``grid`` whose steepest slope is ``steepness``.

    Gaussian random Fourier amplitudes shaped by the spectrum, then scaled.

    Parameters
    ----------
    grid : Grid
    spectrum : str
        A name in :data:`SURFACE_SPECTRA`.
    steepness : float
        The steepest slope max |∇η|, in (0, 1].
    seed : int
        The random draw, ≥ 0.

    Returns
    -------
    jax.Array (n, n)
        Heights, m, float32.
    """
    check_instance("grid", grid, Grid, "wavephys.Grid")
    check_choice("spectrum", spectrum, SURFACE_SPECTRA)
    check_scalar("steepness", steepness, lo=0.0, hi=1.0, lo_open=True)
    seed = check_int("seed", seed, lo=0, hi=2**31 - 1)
    n, length = grid.n, float(grid.length)
    k = grid.wavenumber_magnitude()
    k0 = 2 * math.pi / length
    if spectrum == "band":
        shape = jnp.exp(-0.5 * ((k - 5 * k0) / (1.5 * k0)) ** 2)
    elif spectrum == "power":
        shape = jnp.where(k > 0, (jnp.maximum(k, k0) / (3 * k0)) ** -2.0, 0.0) * jnp.exp(-((k / (16 * k0)) ** 2))
    elif spectrum == "swell":
        shape = jnp.exp(-0.5 * (k / (4 * k0)) ** 2) * (k > 0)
    else:
        shape = _wind_sea(grid, spectrum, seed)
    a, b = jax.random.normal(jax.random.PRNGKey(seed), (2, n, n))
    eta = jnp.real(jnp.fft.ifft2((a + 1j * b) * shape))
    gx, gy = grid.gradient(eta)
    return (eta * (steepness / jnp.max(jnp.hypot(gx, gy)))).astype(jnp.float32)
