import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Water
from wavephys.physics.dispersion import angular_frequency
from wavephys.core.stepper import TwoLevelState
from wavephys.models.truncated_kernel import (KernelStepper, convolve_periodic, max_stable_dt, stencil_symbol,
                                              truncated_kernel)

GRID = Grid(64, 6.4)
WATER = Water(sigma=0.0)


def _band_error(size):
    st = truncated_kernel(GRID, WATER, size)
    sym = np.asarray(stencil_symbol(st, GRID))
    k = np.asarray(GRID.wavenumber_magnitude())
    exact = np.asarray(angular_frequency(GRID.wavenumber_magnitude(), WATER)) ** 2
    band = (k > 4 * 2 * np.pi / 6.4) & (k < 0.5 * np.pi / float(GRID.dx))
    return np.abs(np.sqrt(np.maximum(sym[band], 0)) / np.sqrt(exact[band]) - 1).max()


def test_stencil_sums_to_zero_and_is_symmetric():
    st = np.asarray(truncated_kernel(GRID, WATER, 9))
    assert abs(st.sum()) < 1e-3 * np.abs(st).max()
    np.testing.assert_allclose(st, st[::-1, ::-1], atol=1e-5 * np.abs(st).max())


def test_error_shrinks_with_size():
    errs = [_band_error(p) for p in (3, 9, 33, 63)]
    assert all(b < a for a, b in zip(errs, errs[1:])), errs
    assert errs[-1] < 0.05 < errs[0]


def test_convolution_matches_fft():
    st = truncated_kernel(GRID, WATER, 7)
    eta = jax.random.normal(jax.random.PRNGKey(0), (64, 64))
    via_fft = jnp.fft.ifft2(jnp.fft.fft2(eta) * stencil_symbol(st, GRID)).real
    np.testing.assert_allclose(convolve_periodic(eta, st), via_fft, atol=1e-3 * float(jnp.abs(via_fft).max()))


def test_leapfrog_stability_limit():
    st = truncated_kernel(GRID, WATER, 9)
    dt = max_stable_dt(st, GRID)
    eta = jax.random.normal(jax.random.PRNGKey(1), (64, 64))
    start = TwoLevelState(eta, eta)
    ok = KernelStepper(st, 0.95 * dt).advance(start, 400).eta
    bad = KernelStepper(st, 1.05 * dt, check_stability=False).advance(start, 400).eta
    with pytest.raises(ValueError, match="stability limit of this stencil"):
        KernelStepper(st, 1.05 * dt).advance(start, 1)  # refused by default, by name
    with pytest.raises(ValueError, match="stability limit of this stencil"):  # and under jit (the grid is static)
        jax.jit(lambda e: KernelStepper(st, 1.05 * dt).advance(TwoLevelState(e, e), 1).eta)(eta)
    assert float(jnp.abs(ok).max()) < 20 * float(jnp.abs(eta).max())
    assert not bool(jnp.all(jnp.abs(bad) < 1e6))


@pytest.mark.parametrize("size", [4, 0, 64])
def test_bad_size(size):
    with pytest.raises(ValueError, match="size"):
        truncated_kernel(GRID, WATER, size)
