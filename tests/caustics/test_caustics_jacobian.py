"""The Jacobian caustics method: accurate below the first fold on surfaces the test draws, never silently
wrong past it (the beam answers, or CausticsFold), flux conserved, bad options refused by name."""

import functools
import math
import warnings

import jax.numpy as jnp
import numpy as np
import pytest

from optics.light.directions import sun_direction
from optics.caustics import (CausticsFold, SURFACE_SPECTRA, converged_floor_irradiance, first_fold_depth,
                             floor_irradiance, floor_irradiance_beam, random_surface)
from optics.light.fresnel import reflectance
from wavephys import Grid


@functools.lru_cache(maxsize=None)
def _cases(count, seed=11):
    return tuple(_draw(count, seed))


def _draw(count, seed):
    """Generated cases: a spectrum, a steepness, a sun (40–90°), a floor at 0.15–0.85 of the first fold."""
    rng = np.random.default_rng(seed)
    grid = Grid(96, 3.0)
    for i in range(count):
        spectrum = SURFACE_SPECTRA[i % len(SURFACE_SPECTRA)]
        eta = random_surface(grid, spectrum, float(rng.uniform(0.04, 0.15)), int(rng.integers(1 << 30)))
        sun = sun_direction(rng.uniform(40.0, 90.0), rng.uniform(0.0, 360.0))
        fraction = float(rng.uniform(0.15, 0.85))
        yield grid, eta, sun, fraction * first_fold_depth(eta, grid, sun), (spectrum, round(fraction, 2))


@pytest.mark.parametrize("case", [0, 1] + [pytest.param(c, marks=pytest.mark.slow) for c in (2, 3, 4)])
def test_within_one_percent_of_the_reference_below_the_first_fold(case):  # cases 2-4: the slow sweep
    grid, eta, sun, depth, label = _cases(5)[case]
    ref = converged_floor_irradiance(eta, grid, depth, sun, tolerance=2e-3)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = np.asarray(floor_irradiance(eta, grid, depth, sun, method="jacobian"), np.float64)
    peak = float(ref.irradiance.max())
    error = float(np.max(np.abs(out - ref.irradiance))) / peak
    l2 = float(np.linalg.norm(out - ref.irradiance) / np.linalg.norm(ref.irradiance))
    if caught:  # it said why and answered with the exact beam
        assert "beam rasterization is used instead" in str(caught[0].message)
        np.testing.assert_array_equal(out, np.asarray(floor_irradiance_beam(eta, grid, depth, sun), np.float64))
    assert error <= 0.01 and l2 <= 0.005, (label, error, l2)  # measured over the bench family: <= 0.5 % of the peak


def test_most_generated_cases_are_answered_by_the_gather_itself():
    fallbacks = 0
    for grid, eta, sun, depth, _ in _cases(5):
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            floor_irradiance(eta, grid, depth, sun, method="jacobian")
        fallbacks += bool(caught)
    assert fallbacks <= 2  # an oblique sun folds before the vertical sun's first fold does


def _deep_fold():
    grid = Grid(64, 2.0)
    eta = random_surface(grid, "band", 0.1, seed=3)
    return grid, eta, 1.6 * first_fold_depth(eta, grid)


def test_past_the_fold_it_refuses_by_name_or_hands_over_to_the_beam():
    grid, eta, depth = _deep_fold()
    with pytest.raises(CausticsFold, match="depth: .*folds"):
        floor_irradiance(eta, grid, depth, method="jacobian", fold="raise")
    with pytest.warns(UserWarning, match="beam rasterization is used instead"):
        out = floor_irradiance(eta, grid, depth, method="jacobian")
    np.testing.assert_array_equal(np.asarray(out), np.asarray(floor_irradiance_beam(eta, grid, depth)))
    assert issubclass(CausticsFold, ValueError)


def test_an_explicit_supersampling_past_the_fold_is_still_refused():
    grid, eta, depth = _deep_fold()
    with pytest.raises(CausticsFold):
        floor_irradiance(eta, grid, depth, method="jacobian", supersample=4, fold="raise")


def test_automatic_supersampling_is_what_keeps_it_accurate_near_the_fold():
    """At 0.8 of the first fold the point gather alone misses the sharp peaks' texel averages."""
    grid = Grid(96, 3.0)
    eta = random_surface(grid, "band", 0.12, seed=5)
    depth = 0.8 * first_fold_depth(eta, grid)
    ref = converged_floor_irradiance(eta, grid, depth, tolerance=2e-3)
    peak = float(ref.irradiance.max())
    err = {s: float(np.max(np.abs(np.asarray(floor_irradiance(eta, grid, depth, method="jacobian", supersample=s))
                                  - ref.irradiance))) / peak for s in (1, "auto")}
    assert err["auto"] <= 0.005 < err[1], err


@pytest.mark.parametrize("sun", [(0.0, 0.0, 1.0), (0.3, -0.2, 0.9)])
def test_flux_is_conserved(sun):
    grid = Grid(64, 2.0)
    eta = random_surface(grid, "power", 0.08, seed=1)
    depth = 0.5 * first_fold_depth(eta, grid, sun)
    e = floor_irradiance(eta, grid, depth, sun, method="jacobian", fresnel=False)
    assert float(jnp.mean(e)) == pytest.approx(1.0, abs=2e-4)


def test_flat_water_is_uniform_and_fresnel_is_exact():
    sun = np.array([0.4, -0.1, 1.0])
    e = np.asarray(floor_irradiance(jnp.zeros((32, 32)), Grid(32, 2.0), 3.0, sun=sun, method="jacobian"))
    t = 1.0 - float(reflectance(sun[2] / np.linalg.norm(sun)))
    np.testing.assert_allclose(e, t, rtol=1e-5)


def test_sinusoid_peak_matches_the_exact_beam():
    """η = a cos kx at half the focal depth: the same texel averages as the beam, 2 and 2/3 of E0."""
    grid = Grid(64, 1.0)
    x, _ = grid.mesh()
    eta = 0.002 * jnp.cos(2 * math.pi * 2 * (x - grid.origin))
    from optics.caustics import focal_depth

    depth = focal_depth(0.002, 2 * math.pi * 2) / 2
    jac = np.asarray(floor_irradiance(eta, grid, depth, method="jacobian", fresnel=False))
    assert jac.max() == pytest.approx(2.0, rel=0.01) and jac.min() == pytest.approx(2 / 3, rel=0.01)
    ref = converged_floor_irradiance(eta, grid, depth, fresnel=False, tolerance=2e-3)
    assert np.max(np.abs(jac - ref.irradiance)) / ref.irradiance.max() < max(2 * ref.bound, 1e-3)


@pytest.mark.parametrize("kw,name", [(dict(supersample=0), "supersample"), (dict(supersample=9), "supersample"),
                                     (dict(supersample="always"), "supersample"), (dict(iterations=0), "iterations"),
                                     (dict(fold="ignore"), "fold"), (dict(refine=0), "refine"),
                                     (dict(depth=np.full((16, 16), -1.0, np.float32)), "depth")])
def test_bad_options_are_refused_by_name(kw, name):
    args = dict(depth=1.0)
    args.update(kw)
    with pytest.raises((TypeError, ValueError), match=name):
        floor_irradiance(jnp.zeros((16, 16)), Grid(16, 1.0), method="jacobian", **args)
