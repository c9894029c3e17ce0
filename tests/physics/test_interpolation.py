import math

import numpy as np
import pytest

from wavephys.physics.interpolation import hermite_error, hermite_frame, hermite_weights


def test_weights_at_one_third():
    np.testing.assert_allclose([float(w) for w in hermite_weights(1 / 3)], [20 / 27, 7 / 27, 4 / 27, -2 / 27], atol=1e-7)
    np.testing.assert_allclose([float(w) for w in hermite_weights(2 / 3)], [7 / 27, 20 / 27, 2 / 27, -4 / 27], atol=1e-7)


def test_reproduces_cubics_exactly():
    t0, dt = 0.0, 0.5
    f = lambda t: 2 * t**3 - t**2 + 0.5 * t - 1
    df = lambda t: 6 * t**2 - 2 * t + 0.5
    for s in (0.0, 1 / 3, 2 / 3, 1.0):
        got = hermite_frame(f(t0), f(dt), df(t0), df(dt), dt, s)
        assert float(got) == pytest.approx(f(s * dt), abs=1e-6)


def test_fourth_order_convergence():
    errs = [hermite_error(x) for x in (0.4, 0.2, 0.1, 0.05)]
    slopes = [math.log2(a / b) for a, b in zip(errs, errs[1:])]
    assert all(abs(s - 4) < 0.1 for s in slopes), slopes


def test_error_grows_with_omega_dt():
    """Failure boundary: the frame error reaches 10 % of the amplitude near ωΔt ≈ 2.8."""
    assert hermite_error(1.0) < 0.003
    assert hermite_error(3.0) > 0.1


@pytest.mark.parametrize("kw,name", [(dict(dt=0.0), "dt"), (dict(s=1.5), "s"), (dict(s=math.nan), "s")])
def test_bad_input(kw, name):
    args = dict(eta0=0.0, eta1=1.0, eta_dot0=0.0, eta_dot1=0.0, dt=0.1, s=0.5)
    args.update(kw)
    with pytest.raises(ValueError, match=name):
        hermite_frame(**args)


def test_shape_mismatch():
    with pytest.raises(ValueError, match="shape"):
        hermite_frame(np.zeros(3), np.zeros(4), np.zeros(3), np.zeros(3), 0.1, 0.5)
