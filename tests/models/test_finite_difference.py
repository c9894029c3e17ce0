import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys.core.stepper import TwoLevelState
from wavephys.models.finite_difference import (STABILITY_LIMIT, FiniteDifferenceStepper, courant_number,
                                               fd_angular_frequency, find_stability_limit, laplacian)


def test_laplacian_of_plane_wave():
    n, m = 32, 3
    x = np.arange(n)
    f = np.cos(2 * np.pi * m * x / n)[None, :] * np.ones((n, 1))
    expected = -4 * np.sin(np.pi * m / n) ** 2 * f
    np.testing.assert_allclose(laplacian(jnp.asarray(f)), expected, atol=1e-6)


def test_blows_up_past_the_limit_and_stays_bounded_below():
    eta0 = jax.random.normal(jax.random.PRNGKey(0), (32, 32))
    start = TwoLevelState(eta0, eta0)
    below = FiniteDifferenceStepper(0.98 * STABILITY_LIMIT, 1.0).advance(start, 400).eta
    above = FiniteDifferenceStepper(1.02 * STABILITY_LIMIT, 1.0, check_stability=False).advance(start, 400).eta
    assert float(jnp.max(jnp.abs(below))) < 10 * float(jnp.max(jnp.abs(eta0)))
    assert not bool(jnp.all(jnp.abs(above) < 1e6))


def test_single_mode_follows_discrete_dispersion():
    n, m, c = 32, 2, 0.6
    x = np.arange(n)
    k = 2 * np.pi * m / n
    w = float(fd_angular_frequency(k, 0.0, 1.0, c, 1.0)) * c  # phase per step (Δt = c for c = Δx = 1)
    eta_prev = np.cos(k * x + w)[None, :] * np.ones((n, 1))  # time −1
    eta = np.cos(k * x)[None, :] * np.ones((n, 1))
    out = FiniteDifferenceStepper(c, 1.0).advance(TwoLevelState(eta, eta_prev), 50).eta
    np.testing.assert_allclose(out[0], np.cos(k * x - 50 * w), atol=1e-4)


def test_unstable_courant_rejected_by_default():
    with pytest.raises(ValueError, match="courant"):
        FiniteDifferenceStepper(0.8, 1.0)


@pytest.mark.parametrize("args,name", [((0.0, 0.1, 1.0), "speed"), ((1.0, -0.1, 1.0), "dt"), ((1.0, 0.1, math.nan), "dx")])
def test_bad_courant_inputs(args, name):
    with pytest.raises(ValueError, match=name):
        courant_number(*args)


def test_shape_mismatch():
    with pytest.raises(ValueError, match="eta"):
        TwoLevelState(jnp.zeros((8, 8)), jnp.zeros((8, 9)))
