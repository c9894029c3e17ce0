import json
import math

import numpy as np
import pytest

from wavephys import Water
from wavephys.harness import (Check, assert_check, bound, compare, measure_dispersion, measure_energy)


def _travelling(nt, ny, nx, dx, dt, modes):
    t = np.arange(nt)[:, None, None] * dt
    y = np.arange(ny)[None, :, None] * dx
    x = np.arange(nx)[None, None, :] * dx
    eta = np.zeros((nt, ny, nx))
    for (mx, my, omega, amp) in modes:
        kx, ky = 2 * np.pi * mx / (nx * dx), 2 * np.pi * my / (ny * dx)
        eta += amp * np.cos(kx * x + ky * y - omega * t + 0.3)
    return eta


class TestMeasureDispersion:
    def test_recovers_known_frequencies(self):
        modes = [(3, 0, 1.234, 1.0), (0, 5, 2.5, 0.5), (4, 4, 3.3, 0.8)]
        eta = _travelling(1024, 32, 32, 0.5, 0.05, modes)
        s = measure_dispersion(eta, 0.5, 0.05)
        assert s.k.size == 3
        for (mx, my, omega, _), k, w in zip(sorted(modes, key=lambda m: m[0] ** 2 + m[1] ** 2), s.k, s.omega):
            assert k == pytest.approx(2 * np.pi * math.hypot(mx, my) / 16.0)
            assert w == pytest.approx(omega, rel=2e-3)

    def test_rectangular_grid(self):
        eta = _travelling(256, 16, 32, 0.5, 0.05, [(2, 1, 2.0, 1.0)])
        s = measure_dispersion(eta, 0.5, 0.05)
        assert s.k.size == 1 and s.omega[0] == pytest.approx(2.0, rel=2e-3)

    def test_standing_wave_folds_both_directions(self):
        eta = _travelling(256, 16, 16, 1.0, 0.05, [(2, 0, 2.0, 1.0), (-2, 0, 2.0, 1.0)])
        s = measure_dispersion(eta, 1.0, 0.05)
        assert s.omega[0] == pytest.approx(2.0, rel=2e-3)

    @pytest.mark.parametrize("shape", [(16, 16), (4, 8, 8), (8, 8, 8, 8)])
    def test_bad_shapes(self, shape):
        with pytest.raises(ValueError, match="eta"):
            measure_dispersion(np.zeros(shape), 1.0, 0.1)

    @pytest.mark.parametrize("dx,dt,name", [(0.0, 0.1, "dx"), (1.0, -1.0, "dt"), (math.nan, 0.1, "dx")])
    def test_bad_steps(self, dx, dt, name):
        with pytest.raises(ValueError, match=name):
            measure_dispersion(np.zeros((16, 8, 8)), dx, dt)

    def test_nan_rejected(self):
        eta = np.zeros((16, 8, 8))
        eta[3, 2, 1] = np.nan
        with pytest.raises(ValueError, match="eta"):
            measure_dispersion(eta, 1.0, 0.1)


class TestMeasureEnergy:
    def test_capillary_energy_of_a_sinusoid(self):
        """½σ⟨|∇η|²⟩ = ¼σk²A² for η = A cos kx."""
        n, dx, A, m = 64, 0.001, 1e-4, 5
        k = 2 * np.pi * m / (n * dx)
        x = np.arange(n) * dx
        eta = A * np.cos(k * x)[None, :] * np.ones((n, 1))
        e = measure_energy(eta, np.zeros_like(eta), dx, Water())
        assert e.capillary == pytest.approx(0.25 * 0.0728 * k * k * A * A, rel=1e-9)
        assert e.potential == pytest.approx(0.25 * 1000 * 9.81 * A * A, rel=1e-9)
        assert e.kinetic == 0.0

    def test_shape_mismatch(self):
        with pytest.raises(ValueError, match="eta"):
            measure_energy(np.zeros((8, 8)), np.zeros((8, 4)), 1.0, Water())


class TestChecks:
    def test_compare_and_bound(self):
        assert compare("x", 1.0005, 1.0, rtol=1e-3).ok
        assert not compare("x", 1.01, 1.0, rtol=1e-3).ok
        assert bound("r", 0.5, 1.0).ok and not bound("r", 1.5, 1.0).ok
        assert bound("r", 1.5, 1.0, relation=">=").ok
        assert not compare("x", math.nan, 1.0, atol=1.0).ok
        with pytest.raises(ValueError, match="relation"):
            bound("r", 1.5, 1.0, relation="≥")  # relations are ASCII

    def test_check_has_the_argument_order_of_compare(self):
        row = compare("speed", 3.0, 2.0, rtol=0.6, unit="m/s")
        assert row == Check("speed", 3.0, 2.0, 0.6, "~=", True, "m/s")
        assert row.measured == 3.0 and row.expected == 2.0 and row.error == pytest.approx(0.5)
        assert row.margin == pytest.approx(0.1) and bound("r", 0.25, 1.0).margin == 0.75
        assert bound("r", 0.25, 1.0).error is None  # an error means nothing for a bound

    def test_assert_reports_expected_measured_tolerance(self):
        with pytest.raises(AssertionError, match=r"expected 2 m/s, measured 3 m/s, error 0.5, tolerance \+-0.1"):
            assert_check(compare("speed", 3.0, 2.0, rtol=0.1, unit="m/s"))

    def test_json_round_trip(self):
        d = compare("speed", 2.0, 2.0, atol=0.1, unit="m/s").as_dict()
        assert json.loads(json.dumps(d))["ok"] is True

    def test_needs_one_tolerance(self):
        with pytest.raises(ValueError, match="rtol"):
            compare("x", 1.0, 1.0)


def test_pytest_plugin_fixtures(pytester):
    """A user's test suite gets the fixtures from the installed entry point."""
    pytester.makepyfile(
        """
        import numpy as np
        from wavephys import Grid, Simulation, Water

        def _run(water):
            grid = Grid(32, 32.0)
            sim = Simulation(grid, water, dt=0.4)
            eta0 = np.random.default_rng(0).normal(size=(32, 32)) * 1e-3
            _, surf = sim.run(sim.add_height(sim.initial_state(), eta0), 256)
            return np.asarray(surf.eta), float(grid.dx)

        def test_good(wavephys_check, wavephys_water):
            eta, dx = _run(Water(sigma=0.0))
            wavephys_check.dispersion(eta, dx, 0.4, Water(sigma=0.0), rtol=0.005)

        def test_wrong_physics_fails(wavephys_check):
            eta, dx = _run(Water(sigma=0.0))
            wavephys_check.dispersion(eta, dx, 0.4, Water(sigma=0.0, depth=0.5), rtol=0.005)
        """
    )
    result = pytester.runpytest_subprocess("-p", "no:cacheprovider")
    result.assert_outcomes(passed=1, failed=1)
    result.stdout.fnmatch_lines(["*max |omega_measured/omega_theory - 1|: expected 0*FAILED*"])
