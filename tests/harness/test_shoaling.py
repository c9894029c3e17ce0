"""The harness's shoaling check on wave trains written out from theory (WKB: phase ∫k dx, amplitude
√(c_g,0/c_g)) over generated floors, and on broken ones (amplitude ignoring the floor, the wrong way)."""

import math

import numpy as np
import pytest

from wavephys import Water
from wavephys.harness import Record
from wavephys.harness.shoaling import shoaling_check
from wavephys.physics.depth import shoaling_coefficient
from wavephys.physics.dispersion import wavenumber


def _train(depth, omega, dx, dt, nt, water, amplitude_law):
    """η(x, t) = A(x) cos(∫k dx − ωt) over the floor ``depth`` (per column), 8 rows in y."""
    import jax

    with jax.enable_x64(True):  # one vectorized call over the columns
        ks = np.asarray(jax.vmap(lambda h: wavenumber(omega, Water(water.g, water.rho, water.sigma, h)))(
            jax.numpy.asarray(depth)))
    phase = np.cumsum(ks) * dx
    amp = 1e-3 * amplitude_law(depth)
    t = np.arange(nt)[:, None, None] * dt
    eta = amp[None, None, :] * np.cos(phase[None, None, :] - omega * t) * np.ones((1, 8, 1))
    return eta


@pytest.mark.parametrize("seed", [0, pytest.param(1, marks=pytest.mark.slow), pytest.param(2, marks=pytest.mark.slow)])
def test_trains_that_shoal_pass_and_broken_ones_fail_with_their_cause(seed):
    rng = np.random.default_rng(seed)
    water = Water(sigma=0.0)
    n = 64
    dx = 0.5
    h0, h1 = rng.uniform(2.0, 5.0), rng.uniform(0.2, 0.8)
    x = np.arange(n) * dx
    depth = np.clip(h0 + (h1 - h0) * (x - 8.0) / rng.uniform(6.0, 14.0), h1, h0)
    omega = rng.uniform(1.0, 2.5)
    period = 2 * math.pi / omega
    nt, dt = 64, period / 16  # four whole periods
    law = lambda d: shoaling_coefficient(omega, h0, d, water)
    cases = {"right": law, "flat": lambda d: np.ones_like(d), "wrong way": lambda d: 1.0 / law(d)}
    for name, rule in cases.items():
        eta = _train(depth, omega, dx, dt, nt, water, rule)
        frames = np.repeat(eta, n // 8, axis=1)  # square frames
        row = shoaling_check(Record.from_array(frames, dx, dt, axes="tyx"), water, depth)
        if name == "right":
            assert row.ok, row.report()
            assert abs(row.measured) < 2e-3
        else:
            assert not row.ok, (name, row.report())
            assert {"flat": "hardly changes", "wrong way": "wrong way"}[name] in row.note


def test_shoaling_check_refuses_bad_floors_by_name():
    rec = Record.from_array(np.random.default_rng(0).standard_normal((16, 16, 16)) * 1e-3, 0.1, 0.05, axes="tyx")
    with pytest.raises(ValueError, match="depth"):
        shoaling_check(rec, Water(), np.ones(15))
    with pytest.raises(ValueError, match="depth"):
        shoaling_check(rec, Water(), np.zeros(16))
