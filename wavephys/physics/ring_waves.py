r"""Ring-wave (Huygens) propagation, exact in Fourier space (Loviscach 2003, eq. 1).

Propagating a complex wave field ψ by Δt is a convolution with the ring-wave kernel Ψ,
done as a multiplication in Fourier space:

.. math::

    \hat\psi(\mathbf k, t + \Delta t) = \hat\psi(\mathbf k, t)\, e^{-i\omega(|\mathbf k|)\Delta t},
    \qquad \Psi(\mathbf x) = \mathcal F^{-1}\left[e^{-i\omega\Delta t}\right]

The operator is unitary: it is exact for any Δt (no CFL limit) and conserves energy to
rounding. Each Fourier component of ψ is a wave travelling along its own k.

Relation to the physical fields (docs/physics.md §1.2): write ψ = φ + iχ with φ, χ real. φ is the
surface velocity potential (m²/s) and the height is η̂ = −(K/ω) χ̂ = Re-part of
(iK/ω) ψ̂ with K = |k| tanh(|k| h); see :mod:`wavephys.heights`.
"""

from __future__ import annotations

import jax.numpy as jnp

from wavephys.core.inputs import check_array, validate
from wavephys.core.specs import BOOL, COMPLEX_FIELD, GRID, POSITIVE, WATER
from wavephys.physics.dispersion import angular_frequency
from wavephys.core.grid import Grid
from wavephys.core.water import Water

__all__ = ["propagator", "kernel", "propagate"]


@validate(grid=GRID, water=WATER, dt=POSITIVE, real=BOOL)
def propagator(grid: Grid, water: Water, dt, real: bool = False):
    """Fourier multiplier exp(−i ω(|k|) Δt) on the grid's spectrum.

    Parameters
    ----------
    grid : Grid
    water : Water
    dt : float
        Time step Δt, s, finite and > 0.
    real : bool
        ``True`` for the ``rfft2`` half spectrum, shape ``(n, n//2 + 1)``; else the full
        ``fft2`` spectrum ``(n, n)``.

    Returns
    -------
    jax.Array
        Complex multiplier (complex64 for float32 grids).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 1.
    """
    omega = angular_frequency(grid.wavenumber_magnitude(real), water)
    return jnp.exp(-1j * omega * dt)


@validate(grid=GRID, water=WATER, dt=POSITIVE)
def kernel(grid: Grid, water: Water, dt):
    """The ring-wave kernel Ψ for a step Δt as convolution weights by offset, zero offset at
    index ``[n // 2, n // 2]``.

    Discrete and periodic: ``propagate(f)`` is the circular convolution of f with Ψ,
    entry ``[n//2 + a, n//2 + b]`` being the weight of the sample ``a`` rows and ``b``
    columns away.

    Parameters
    ----------
    grid : Grid
    water : Water
    dt : float
        Time step Δt, s, finite and > 0.

    Returns
    -------
    jax.Array (n, n), complex
        Ψ = F⁻¹[e^{−iωΔt}], fftshifted; dimensionless (a weight per sample).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 1.
    """
    psi = jnp.fft.ifft2(propagator(grid, water, dt))
    return jnp.fft.fftshift(psi, axes=(-2, -1))


@validate(grid=GRID, water=WATER, dt=POSITIVE, field=COMPLEX_FIELD)
def propagate(field, grid: Grid, water: Water, dt):
    """Propagate a complex wave field by Δt exactly: ψ(t + Δt) = F⁻¹[F[ψ]·e^{−iωΔt}].

    Parameters
    ----------
    field : array_like
        Complex field ψ of shape ``(..., n, n)`` on ``grid`` (leading axes are batched).
    grid : Grid
    water : Water
    dt : float
        Time step, s, finite and > 0. Any size: the propagator is exact.

    Returns
    -------
    jax.Array
        ψ(t + Δt), complex, same shape.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, eq. 1.

    Examples
    --------
    >>> import jax.numpy as jnp
    >>> from wavephys import Grid, Water
    >>> g = Grid(64, 1.0)
    >>> psi = jnp.zeros((64, 64), complex).at[32, 32].set(1.0)
    >>> out = propagate(psi, g, Water(), 0.1)
    >>> round(float(jnp.sum(jnp.abs(out) ** 2)), 5)   # unitary
    1.0
    """
    field = jnp.asarray(field)
    if not jnp.iscomplexobj(field):
        field = field.astype(jnp.result_type(field.dtype, jnp.complex64))
    return jnp.fft.ifft2(jnp.fft.fft2(field) * propagator(grid, water, dt))


def rotate_pair(phi_hat, chi_hat, cos_wt, sin_wt):
    """Exact propagation of ψ = φ + iχ written for the half spectra of the real fields.

    With ψ̂(k) → ψ̂(k)·e^{−iωΔt} and ω even in k, the real and imaginary parts rotate:
    φ̂' = φ̂ cos ωΔt + χ̂ sin ωΔt,  χ̂' = −φ̂ sin ωΔt + χ̂ cos ωΔt. This lets the simulation
    use real FFTs (``rfft2``) for the two real fields instead of a complex FFT.
    """
    return phi_hat * cos_wt + chi_hat * sin_wt, chi_hat * cos_wt - phi_hat * sin_wt
