"""pytest plugin (entry point ``pytest11: wavephys``): physics checks as fixtures.

Installed with wavephys; any test suite can then ask for these fixtures::

    def test_my_waves(wavephys_check):
        eta = run_my_simulator(...)              # (n_t, n, n) heights, m
        wavephys_check.dispersion(eta, dx, dt, Water(sigma=0.0), rtol=0.01,
                                  k_range=(1.0, 20.0))

    def test_my_fresnel(wavephys_check):
        wavephys_check.glsl(open("water.glsl").read(), function="fresnel", against="fresnel",
                            form="schlick")

Fixtures: ``wavephys_water`` (default :class:`~wavephys.Water`) and ``wavephys_check``
(a :class:`Checker`). Each method returns the row or report it made and fails the test
with expected / measured / tolerance (and the likely cause) when it is not ok. This module
imports nothing heavy: JAX, NumPy and OpenGL load when a fixture is first used.

The plugin lives in the application layer because it uses both the wave harness
(:mod:`wavephys.harness`) and the optics (:mod:`optics.shaders`); its old path
``wavephys.harness.pytest_plugin`` still imports, with a ``DeprecationWarning``.
"""

from __future__ import annotations

import pytest

__all__ = ["Checker"]


class Checker:
    """Assertion helpers over :mod:`wavephys.harness` for use in tests."""

    def close(self, quantity, measured, expected, *, rtol=None, atol=None, unit=""):
        """Assert measured ≈ expected (exactly one of ``rtol``, ``atol``, ≥ 0)."""
        from wavephys.harness.checks import assert_check, compare

        return assert_check(compare(quantity, measured, expected, rtol=rtol, atol=atol, unit=unit))

    def at_most(self, quantity, measured, limit, unit=""):
        """Assert measured <= limit."""
        from wavephys.harness.checks import assert_check, bound

        return assert_check(bound(quantity, measured, limit, unit=unit))

    def dispersion(self, eta, dx, dt, water, *, rtol=0.005, k_range=(0.0, float("inf")), min_samples=3):
        """Assert the measured ω(k) of ``eta`` (n_t, n, n) matches ``water``'s theory.

        The largest relative error over the shells with k in ``k_range`` (rad/m) must be
        <= ``rtol``, and at least ``min_samples`` shells must be measured there.
        """
        from wavephys.core.inputs import check_instance
        from wavephys.core.water import Water
        from wavephys.harness.checks import assert_check
        from wavephys.harness.dispersion import dispersion_check, measure_dispersion

        check_instance("water", water, Water, "wavephys.Water")
        samples = measure_dispersion(eta, dx, dt)
        return assert_check(dispersion_check(samples, water, dt, rtol=rtol, k_range=k_range,
                                             min_samples=min_samples))

    def energy_conserved(self, eta, eta_dot, dx, water, *, rtol=1e-3):
        """Assert the total energy of a time series (n_t, n, n) stays within ``rtol``."""
        import numpy as np

        from wavephys.harness.checks import assert_check, compare
        from wavephys.harness.energy import measure_energy

        from wavephys.core.inputs import check_scalar

        check_scalar("rtol", rtol, lo=0.0)
        if np.ndim(eta) != 3:
            raise ValueError(f"eta must be a time series (n_t, n_y, n_x), got shape {np.shape(eta)}")
        e = np.asarray(measure_energy(eta, eta_dot, dx, water).total)
        drift = np.max(np.abs(e / e[0] - 1.0))
        return assert_check(compare("energy drift", drift, 0.0, atol=rtol))

    def glsl(self, source, function, against, *, takes=None, returns=None, uniforms=None, tolerance=None,
             chart=None, **options):
        """Assert that the GLSL ``function`` in ``source`` meets the physics of the check ``against``
        over its whole input domain (:func:`optics.shaders.check_glsl`, same arguments).

        Fails the test with the worst error, the input where it occurs and the likely cause;
        returns the :class:`~optics.shaders.ShaderReport` when it passes. A source that does
        not compile, or a function that is missing or has another signature, raises
        :class:`~optics.shaders.GLSLError` (a ValueError) with the driver's message.
        """
        from optics.shaders import check_glsl

        report = check_glsl(source, function, against, takes=takes, returns=returns, uniforms=uniforms,
                            tolerance=tolerance, chart=chart, **options)
        if not report.ok:
            raise AssertionError(report.report())
        return report


@pytest.fixture
def wavephys_water():
    """Deep, clean water with the SI defaults of docs/physics.md."""
    from wavephys.core.water import Water

    return Water()


@pytest.fixture
def wavephys_check() -> Checker:
    """Physics assertion helpers (:class:`Checker`)."""
    return Checker()
