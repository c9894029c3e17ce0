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

SURFACE_SPECTRA = ("band", "power", "swell")
"""Spectral shapes: ``"band"`` — a ring around a fifth of the domain (a sea of one
wavelength, all directions); ``"power"`` — k⁻² from a third of the domain down to a
sixteenth (many scales, a wind sea's slope); ``"swell"`` — long waves, a Gaussian below a
quarter of the domain."""


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
    else:
        shape = jnp.exp(-0.5 * (k / (4 * k0)) ** 2) * (k > 0)
    a, b = jax.random.normal(jax.random.PRNGKey(seed), (2, n, n))
    eta = jnp.real(jnp.fft.ifft2((a + 1j * b) * shape))
    gx, gy = grid.gradient(eta)
    return (eta * (steepness / jnp.max(jnp.hypot(gx, gy)))).astype(jnp.float32)
