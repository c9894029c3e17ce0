import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Water
from wavephys.physics.ring_waves import kernel, propagate, propagator, rotate_pair

GRID = Grid(32, 1.0)
WATER = Water()


def _random_field(n, seed=0, dtype=jnp.complex64):
    k1, k2 = jax.random.split(jax.random.PRNGKey(seed))
    return (jax.random.normal(k1, (n, n)) + 1j * jax.random.normal(k2, (n, n))).astype(dtype)


def test_propagator_is_unit_modulus_phase():
    m = propagator(GRID, WATER, 0.3)
    omega = np.asarray(jnp.sqrt(9.81 * GRID.wavenumber_magnitude() + 0.0728e-3 * GRID.wavenumber_magnitude() ** 3))
    np.testing.assert_allclose(np.abs(m), 1.0, atol=1e-6)
    np.testing.assert_allclose(np.asarray(m), np.exp(-1j * omega * 0.3), atol=2e-5)


def test_kernel_convolution_equals_propagation():
    """Huygens: direct circular convolution with the ring-wave kernel Ψ = Fourier step."""
    n = 16
    g = Grid(n, 0.5)
    f = np.asarray(_random_field(n, 1), np.complex128)
    psi = np.asarray(kernel(g, WATER, 0.05), np.complex128)
    out = np.zeros((n, n), complex)
    for a in range(n):
        for b in range(n):
            out += f[a, b] * np.roll(np.roll(psi, a - n // 2, 0), b - n // 2, 1)
    np.testing.assert_allclose(out, np.asarray(propagate(f, g, WATER, 0.05)), atol=1e-5)


def test_unitary_and_composition_float64(x64):
    f = _random_field(32, 2, jnp.complex128)
    out = f
    for _ in range(10):
        out = propagate(out, GRID, WATER, 0.01)
    one = propagate(f, GRID, WATER, 0.1)
    assert float(jnp.max(jnp.abs(out - one))) < 1e-12
    assert abs(float(jnp.sum(jnp.abs(one) ** 2) / jnp.sum(jnp.abs(f) ** 2)) - 1) < 1e-13


def test_batched_leading_axes():
    f = jnp.stack([_random_field(32, 3), _random_field(32, 4)])
    out = propagate(f, GRID, WATER, 0.2)
    np.testing.assert_allclose(out[1], propagate(f[1], GRID, WATER, 0.2), atol=1e-6)


def test_rotation_of_real_parts_equals_complex_step():
    f = _random_field(32, 5)
    phi_hat, chi_hat = jnp.fft.rfft2(f.real), jnp.fft.rfft2(f.imag)
    omega_dt = jnp.angle(propagator(GRID, WATER, 0.7, real=True)) * -1
    p2, c2 = rotate_pair(phi_hat, chi_hat, jnp.cos(omega_dt), jnp.sin(omega_dt))
    out = jnp.fft.irfft2(p2, s=(32, 32)) + 1j * jnp.fft.irfft2(c2, s=(32, 32))
    np.testing.assert_allclose(out, propagate(f, GRID, WATER, 0.7), atol=1e-5)


def test_single_mode_moves_at_phase_speed():
    """A plane wave e^{ikx} after Δt is e^{i(kx − ωΔt)}: its crest moves c·Δt."""
    g = Grid(64, 2.0)
    k = 2 * np.pi / 2.0 * 5
    x, _ = g.mesh()
    f = jnp.exp(1j * k * x)
    dt = 0.013
    omega = math.sqrt(9.81 * k + 0.0728e-3 * k**3)
    np.testing.assert_allclose(propagate(f, g, WATER, dt), np.exp(1j * (k * np.asarray(x) - omega * dt)), atol=2e-5)


@pytest.mark.parametrize("dt", [0.0, -0.1, math.nan, math.inf])
def test_bad_dt(dt):
    with pytest.raises(ValueError, match="dt"):
        propagate(jnp.zeros((32, 32), complex), GRID, WATER, dt)


@pytest.mark.parametrize("shape", [(31, 32), (32,), (16, 16)])
def test_bad_shape(shape):
    with pytest.raises(ValueError, match="field"):
        propagate(jnp.zeros(shape, complex), GRID, WATER, 0.1)


def test_nan_field_rejected():
    with pytest.raises(ValueError, match="field"):
        propagate(jnp.full((32, 32), jnp.nan, complex), GRID, WATER, 0.1)
