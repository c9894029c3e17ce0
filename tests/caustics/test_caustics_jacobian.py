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


@pytest.mark.slow
@pytest.mark.parametrize("case", [0, 1, 2, 3, 4])
def test_within_one_percent_of_the_reference_below_the_first_fold(case):  # cases 2-4: the slow sweep
    grid, eta, sun, depth, label = _cases(5)[case]
    ref = converged_floor_irradiance(eta, grid, depth, sun, tolerance=2e-3)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = np.asarray(floor_irradiance(eta, grid, depth, sun, method="jacobian"), np.float64)
    peak = float(ref.irradiance.max())
    error = float(np.max(np.abs(out - ref.irradiance))) / peak
    l2 = float(np.linalg.norm(out - ref.irradiance) / np.linalg.norm(ref.irradiance))
    assert not caught  # the gather, or the gather and the beam's windows: answers, not hand-overs
    assert error <= 0.01 and l2 <= 0.005, (label, error, l2)  # measured over the bench family: <= 0.5 % of the peak


@pytest.mark.slow
def test_the_light_is_the_ratio_of_the_splines_of_its_exact_samples():
    """E at the preimage is the numerator over det ∂X/∂x, each from the spline of its exact samples:
    on six generated seas with sharp light (k⁻², Phillips, JONSWAP; 96², floors at 0.3–0.5 of the
    first fold; the fields on the surface's own samples, refine 1) the largest L2 error is 5.3e-4 of
    the reference's (this family, seed 29; 5.9e-4 on another, seed 31), where the spline of D's own
    area ratio (its derivative, third order) gave 9.1e-4 (9.9e-4); the max norm within 1 % of the peak
    either way. (With ``refine="auto"``, which refines the steepest of them: 3.5e-4 and 5.9e-4 against
    4.9e-4 and 9.9e-4.)"""
    rng = np.random.default_rng(29)
    grid = Grid(96, 3.0)
    worst = 0.0
    for spectrum in ("power", "phillips", "jonswap") * 2:
        eta = random_surface(grid, spectrum, float(rng.uniform(0.08, 0.15)), int(rng.integers(1 << 30)))
        sun = sun_direction(rng.uniform(40.0, 90.0), rng.uniform(0.0, 360.0))
        depth = float(rng.uniform(0.3, 0.5)) * first_fold_depth(eta, grid, sun)
        ref = converged_floor_irradiance(eta, grid, depth, sun, tolerance=2e-3).irradiance
        out = np.asarray(floor_irradiance(eta, grid, depth, sun, method="jacobian", refine=1, fold="raise"), np.float64)
        assert np.max(np.abs(out - ref)) <= 0.01 * ref.max(), spectrum
        worst = max(worst, float(np.linalg.norm(out - ref) / np.linalg.norm(ref)))
    assert worst <= 7e-4, worst


@pytest.mark.slow
def test_most_generated_cases_are_answered_by_the_gather_itself():
    from optics.caustics.jacobian import _jacobian

    answers = [_jacobian(eta, grid, depth, sun, None, 1.333, True, 1, "auto", 4, "windows")[1]["answer"]
               for grid, eta, sun, depth, _ in _cases(5)]
    assert answers.count("gather") >= 3, answers  # an oblique sun folds before the vertical sun's first fold does


def _deep_fold():
    grid = Grid(64, 2.0)
    eta = random_surface(grid, "band", 0.1, seed=3)
    return grid, eta, 1.6 * first_fold_depth(eta, grid)


def test_past_the_fold_it_refuses_by_name_or_hands_over_to_the_beam():
    grid, eta, depth = _deep_fold()
    with pytest.raises(CausticsFold, match="depth: .*folds"):
        floor_irradiance(eta, grid, depth, method="jacobian", fold="raise")
    with pytest.warns(UserWarning, match="beam rasterization is used instead"):
        out = floor_irradiance(eta, grid, depth, method="jacobian", fold="beam")
    np.testing.assert_array_equal(np.asarray(out), np.asarray(floor_irradiance_beam(eta, grid, depth)))
    assert issubclass(CausticsFold, ValueError)


@functools.lru_cache(maxsize=None)
def _past_fold_cases(count=4, seed=23):
    """Generated surfaces whose floor lies 1.02–1.25 × the first fold of their own sun."""
    rng = np.random.default_rng(seed)
    grid = Grid(96, 3.0)
    cases = []
    for i in range(count):
        eta = random_surface(grid, SURFACE_SPECTRA[i % 3], float(rng.uniform(0.05, 0.12)), int(rng.integers(1 << 30)))
        sun = sun_direction(rng.uniform(50.0, 90.0), rng.uniform(0.0, 360.0))
        cases.append((grid, eta, sun, float(rng.uniform(1.02, 1.25)) * first_fold_depth(eta, grid, sun)))
    return tuple(cases)


@pytest.mark.slow
@pytest.mark.parametrize("case", [0, 1, 2, 3])
def test_past_the_fold_the_folded_windows_are_the_beam_and_the_rest_is_gathered(case):
    """fold='windows' (the default): the texels the folded sheets reach are the exact beam's, the
    rest the gather's; the whole map is as close to the converged reference as the beam itself."""
    from optics.caustics.jacobian import _jacobian

    grid, eta, sun, depth = _past_fold_cases()[case]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the windows are an answer, not a hand-over
        out, info = _jacobian(eta, grid, depth, sun, None, 1.333, True, 1, "auto", 4, "windows")
    out = np.asarray(out, np.float64)
    beam = np.asarray(floor_irradiance_beam(eta, grid, depth, sun, n_water=1.333), np.float64)
    if info["answer"] == "beam":  # the folds reach more than MAX_WINDOWS of the floor: the beam draws it all
        np.testing.assert_array_equal(out, beam)
        return
    assert info["answer"] == "windows" and 0.0 < info["windows"] <= 0.6, info
    same = np.isclose(out, beam, rtol=1e-4, atol=1e-5)
    assert same.mean() >= info["windows"] - 1e-9  # every window texel (and, by chance, some others)
    ref = converged_floor_irradiance(eta, grid, depth, sun, n_water=1.333, tolerance=2e-3)
    peak = float(ref.irradiance.max())
    gathered = ~same
    error = float(np.max(np.abs(out - ref.irradiance)[gathered], initial=0.0)) / peak
    assert error <= 0.005, (case, error)  # the gathered texels: within 0.5 % of the peak
    beam_error = float(np.max(np.abs(beam - ref.irradiance))) / peak
    assert float(np.max(np.abs(out - ref.irradiance))) / peak <= beam_error + 0.005


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_just_past_the_fold_the_windows_answer_the_smooth_seas():
    from optics.caustics.jacobian import _jacobian

    answers = [_jacobian(eta, grid, depth, sun, None, 1.333, True, 1, "auto", 4, "windows")[1]
               for grid, eta, sun, depth in _past_fold_cases()]
    assert sum(a["answer"] == "windows" for a in answers) >= 2, answers  # 22-45 % of the floor on the bench family


@pytest.mark.slow
@pytest.mark.parametrize("spectrum,seed", [("jonswap", 2)])
def test_a_low_sun_is_answered_as_closely_as_the_beam(spectrum, seed):
    """At 15° steep crests shadow parts of the troughs; where the light grazes a facet it changes
    fast, so those texels go to the beam and the map is as close to the reference as the beam's."""
    from optics.caustics.jacobian import _jacobian

    grid = Grid(96, 3.0)
    eta = random_surface(grid, spectrum, 0.3, seed)
    sun = sun_direction(15.0, 30.0 * seed)
    depth = 0.3 * first_fold_depth(eta, grid, sun)
    out, info = _jacobian(eta, grid, depth, sun, None, 1.333, True, 1, "auto", 4, "windows")
    assert info["answer"] == "windows", info
    ref = converged_floor_irradiance(eta, grid, depth, sun, n_water=1.333, tolerance=2e-3)
    beam = np.asarray(floor_irradiance_beam(eta, grid, depth, sun, n_water=1.333), np.float64)
    peak = float(ref.irradiance.max())
    error = float(np.max(np.abs(np.asarray(out, np.float64) - ref.irradiance))) / peak
    assert error <= float(np.max(np.abs(beam - ref.irradiance))) / peak + 0.002, (info, error)


@pytest.mark.slow
@pytest.mark.parametrize("resolution", [128, 256])
def test_a_finer_floor_map_over_a_flat_floor_is_still_gathered(resolution):
    """A k^-2 sea on 64² (4 samples on its shortest waves) mapped onto a 2-4× finer floor: the
    map is smooth (the jump test is the ground's), so the gather answers; refine="auto" builds
    the fields as fine as the floor map, within 1 % of the reference, where refine 1 errs 2 %."""
    from optics.caustics.jacobian import _jacobian

    grid = Grid(64, 3.0)
    eta = random_surface(grid, "power", 0.08, seed=2)
    depth = 0.3 * first_fold_depth(eta, grid)
    ref = converged_floor_irradiance(eta, grid, depth, resolution=resolution, n_water=1.333, tolerance=2e-3)
    peak = float(ref.irradiance.max())
    errors = {}
    for refine in ("auto", 1):
        out, info = _jacobian(eta, grid, depth, (0.0, 0.0, 1.0), resolution, 1.333, True, refine, "auto", 4, "raise")
        assert info["answer"] == "gather"
        errors[refine] = float(np.max(np.abs(np.asarray(out, np.float64) - ref.irradiance))) / peak
    assert errors["auto"] <= 0.01 < errors[1], errors


@pytest.mark.slow  # 25 s a case: the README's pytest must stay under 10 min on 2 cores (CI runs the slow ones)
@pytest.mark.parametrize("kx, ky", [(20, 3), (19, 7), (21, 0)])
def test_waves_at_the_grid_scale_are_gathered_at_the_fields_resolution(kx, ky):
    """Two crossed waves of about 3 samples on 64² (a light breeze on a coarse shore grid, as the
    planner's generated scenes have them): the fields are refined twice, and the light has
    wavenumbers past a 64² floor map's Nyquist. At floors where log E changes by 0.18-0.41 per
    texel (the sharpness rule alone takes one point a texel), that point gather errs 0.9-2.4 %
    of the peak (measured), so "auto" gathers as many points a side as the fields have samples."""
    from optics.caustics.jacobian import SHARPNESS_LIMIT, _auto_refine, _jacobian, _supersampling

    grid = Grid(64, 24.0)
    x, y = (np.asarray(a) for a in grid.mesh())
    eta = jnp.asarray(2e-4 * (np.cos(2 * np.pi * (kx * x + ky * y) / 24.0)
                              + np.cos(2 * np.pi * (ky * x - kx * y) / 24.0 + 1.0)), jnp.float32)
    assert _auto_refine(eta, 64)[0] == 2
    sun = sun_direction(10.0, 180.0)
    fold = first_fold_depth(eta, grid, sun)
    coarse = []
    for fraction in (0.12, 0.16):
        ref = converged_floor_irradiance(eta, grid, fraction * fold, sun, n_water=1.333, tolerance=2e-3)
        peak = float(ref.irradiance.max())
        error, chosen = {}, {}
        for s in ("auto", 1):
            out, info = _jacobian(eta, grid, fraction * fold, sun, None, 1.333, True, "auto", s, 4, "raise")
            assert info["answer"] == "gather"
            error[s] = float(np.max(np.abs(np.asarray(out, np.float64) - ref.irradiance))) / peak
            chosen[s] = info["supersample"]
        assert chosen["auto"] == 2 and error["auto"] <= 0.005, (error, chosen)  # SHARPNESS_LIMIT's promise
        coarse.append(error[1])
    assert max(coarse) > 0.015, coarse  # what one point a texel gives
    assert _supersampling(0.0, 0.1, "auto", 64, 128) == 2 and _supersampling(0.0, 0.1, "auto", 128, 128) == 1
    assert _supersampling(SHARPNESS_LIMIT / 0.1 * 3, 0.1, "auto", 64, 128) == 4


@pytest.mark.slow  # 18 s: the README's pytest must stay under 10 min on 2 cores (CI runs it)
def test_past_the_fold_the_gathered_texels_take_the_grid_scale_waves_too():
    """The same ripples (weaker) on a swell that folds: the folded windows are the beam, and the
    rest is gathered at the fields' resolution, within 2e-4 of the peak (one point a texel:
    4-8e-4, measured)."""
    from optics.caustics.jacobian import _jacobian

    grid = Grid(64, 24.0)
    x, y = (np.asarray(a) for a in grid.mesh())
    eta = jnp.asarray(4e-5 * (np.cos(2 * np.pi * (20 * x + 3 * y) / 24.0) + np.cos(2 * np.pi * (3 * x - 20 * y) / 24.0 + 1.0))
                      + 0.02 * np.cos(2 * np.pi * 3 * x / 24.0), jnp.float32)
    sun = sun_direction(10.0, 180.0)
    depth = 0.9 * first_fold_depth(eta, grid, sun)
    out, info = _jacobian(eta, grid, depth, sun, None, 1.333, True, "auto", "auto", 4, "windows")
    assert info["answer"] == "windows" and info["supersample"] == 2, info
    ref = converged_floor_irradiance(eta, grid, depth, sun, n_water=1.333, tolerance=2e-3)
    outside = ~np.asarray(info["mask"])
    error = np.abs(np.asarray(out, np.float64) - ref.irradiance)[outside].max() / ref.irradiance.max()
    assert outside.mean() > 0.5 and error <= 2e-4, (outside.mean(), error)


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_a_coarse_floor_map_of_a_fine_surface_is_still_gathered():
    """Fields of 256 samples a side on a 16-texel floor map: 8 points a texel (the most) gather it;
    the rule of as many points as the fields have samples cannot hold and does not refuse it."""
    grid = Grid(256, 4.0)
    x, y = (np.asarray(a) for a in grid.mesh())
    eta = jnp.asarray(0.002 * np.cos(2 * np.pi * (x + 2 * y) / 4.0), jnp.float32)
    depth = 0.3 * first_fold_depth(eta, grid)
    out, info = floor_irradiance(eta, grid, depth, method="jacobian", resolution=16, fold="raise", explain=True)
    beam = np.asarray(floor_irradiance_beam(eta, grid, depth, resolution=16))
    assert info["answer"] == "gather" and info["supersample"] == 8, info
    assert np.abs(np.asarray(out) - beam).max() <= 0.01 * beam.max()


def test_automatic_supersampling_stays_within_the_largest_map():
    from optics.caustics.jacobian import _supersampling

    assert _supersampling(10.0, 0.1, "auto", 1024) == 4   # 4 resolves it and 4096 texels fit
    assert _supersampling(10.0, 0.1, "auto", 4096) is None  # 4 does not fit: a window, not an error
    assert _supersampling(10.0, 0.1, 2, 4096) == 2


def _walled_ground(grid, depth=1.0, rim=0.05, width=0.12):
    """A square pool: a flat floor ``depth`` down, walls rising over ``width`` m to ``rim`` below the water."""
    x, y = (np.asarray(a, np.float64) for a in grid.mesh())
    r = np.maximum(np.abs(x), np.abs(y)) / (0.5 * float(grid.length))
    t = np.clip((r - 0.8) / (width / (0.5 * float(grid.length))), 0.0, 1.0)
    return (-depth + (depth - rim) * t * t * (3 - 2 * t)).astype(np.float32)


@pytest.mark.parametrize("seed", [pytest.param(0, marks=pytest.mark.slow), 1])  # 0: 17 s, to the slow run
def test_a_ground_height_field_is_landed_on_as_the_beam_does(seed):
    """A gently sloping, rippled ground below a generated sea: the gather alone, within 1 % of the reference."""
    grid = Grid(96, 3.0)
    rng = np.random.default_rng(seed)
    x, y = (np.asarray(a, np.float64) for a in grid.mesh())
    eta = random_surface(grid, "band", 0.05, seed)
    mx, my = rng.integers(-2, 3, size=2)  # periodic, as the surface is
    ground = (-1.0 + 0.05 * np.sin(2 * np.pi * (mx * x + my * y) / 3.0 + rng.uniform(0, 6.3))
              + 0.03 * np.cos(2 * np.pi * 2 * y / 3.0)).astype(np.float32)
    sun = sun_direction(rng.uniform(55.0, 90.0), rng.uniform(0.0, 360.0))
    from optics.caustics.jacobian import _jacobian

    out, info = _jacobian(eta, grid, ground, sun, None, 1.333, True, 1, "auto", 4, "raise")
    ref = converged_floor_irradiance(eta, grid, ground, sun, n_water=1.333, tolerance=2e-3)
    error = float(np.max(np.abs(np.asarray(out, np.float64) - ref.irradiance))) / float(ref.irradiance.max())
    assert info["answer"] == "gather" and error <= 0.01, (info, error)


@pytest.mark.parametrize("elevation,azimuth", [pytest.param(90.0, 0.0, marks=pytest.mark.slow),
                                               pytest.param(60.0, 30.0, marks=pytest.mark.slow), (55.0, 200.0)])
def test_the_walls_of_a_pool_go_to_the_beam_and_no_texel_is_wrong(elevation, azimuth):
    """Light either side of a steep wall's edge lands a metre apart: the map jumps between samples.
    The jump (and the spline's ringing around it) is left to the beam; every texel within 1 % of the
    peak of the default beam, against 5 % and more if the jump were gathered."""
    grid = Grid(128, 4.0)
    eta = random_surface(grid, "swell", 0.03, seed=int(elevation))
    ground = _walled_ground(grid)
    sun = sun_direction(elevation, azimuth)
    out = np.asarray(floor_irradiance(eta, grid, ground, sun, method="jacobian"), np.float64)
    beam = np.asarray(floor_irradiance_beam(eta, grid, ground, sun), np.float64)
    assert float(np.max(np.abs(out - beam))) / float(beam.max()) <= 0.01


@pytest.mark.parametrize("elevation,azimuth", [(50.0, 10.0), (65.0, 160.0)])
def test_a_kinked_ground_goes_to_the_beam_where_the_light_jumps(elevation, azimuth):
    """A ledge meeting a slope (a corner in the ground, as a clamped floor has): E jumps there by
    the slope change × tan of the refracted ray; the gather would round it off by several % of
    the peak, so the kink is a window and every texel stays within 1 % of the default beam."""
    grid = Grid(128, 4.0)
    x, y = (np.asarray(a, np.float64) for a in grid.mesh())
    ramp = np.maximum(0.0, 1.0 - np.abs(x) / 1.0) + 0.5 * np.maximum(0.0, 1.0 - np.abs(y - 0.5) / 0.8)
    ground = (-0.4 - 0.8 * ramp).astype(np.float32)
    eta = random_surface(grid, "swell", 0.02, seed=int(azimuth))
    sun = sun_direction(elevation, azimuth)
    out = np.asarray(floor_irradiance(eta, grid, ground, sun, method="jacobian"), np.float64)
    beam = np.asarray(floor_irradiance_beam(eta, grid, ground, sun), np.float64)
    assert float(np.max(np.abs(out - beam))) / float(beam.max()) <= 0.01


def test_an_unresolved_sea_on_a_ground_goes_to_the_beam():
    """Waves of 4 samples want finer fields, which a ground given on the surface's grid cannot have."""
    grid = Grid(64, 2.0)
    eta = random_surface(grid, "power", 0.05, seed=4)
    ground = np.full((64, 64), -0.8, np.float32)
    with pytest.raises(CausticsFold, match="not resolved.*ground height field"):
        floor_irradiance(eta, grid, ground, method="jacobian", fold="raise")
    out = floor_irradiance(eta, grid, ground, method="jacobian")
    np.testing.assert_array_equal(np.asarray(out), np.asarray(floor_irradiance_beam(eta, grid, ground)))


def test_flux_is_conserved_on_a_ground_height_field():
    grid = Grid(64, 2.0)
    x, _ = grid.mesh()
    ground = (-0.8 + 0.1 * jnp.sin(2 * math.pi * (x - grid.origin) / 2.0)).astype(jnp.float32)
    eta = random_surface(grid, "band", 0.05, seed=4)
    e = floor_irradiance(eta, grid, ground, (0.2, 0.1, 1.0), method="jacobian", fresnel=False, fold="raise")
    assert float(jnp.mean(e)) == pytest.approx(1.0, abs=5e-4)


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
                                     (dict(depth=np.full((16, 16), -1.0, np.float32), refine=2), "refine"),
                                     (dict(depth=np.full((16, 16), 1.0, np.float32)), "depth")])
def test_bad_options_are_refused_by_name(kw, name):
    args = dict(depth=1.0)
    args.update(kw)
    with pytest.raises((TypeError, ValueError), match=name):
        floor_irradiance(jnp.zeros((16, 16)), Grid(16, 1.0), method="jacobian", **args)


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_mild_floors_reach_the_float32_floor_after_the_chord_step():
    """Far from the fold the first Newton step and the chord step do most of the work: on 30
    generated seas (5 spectra, steepness 0.04–0.15, suns 40–90°, floors at 0.1–0.5 of the first fold,
    96²) every residual ends at the float32 floor (measured ≤ 8.6e-6 texel), and the swell where the
    points the chord step left behind had stayed at 1.1e-3 texel (refused as unconverged) is gathered."""
    from optics.caustics.common import prepare, shadow_steps
    from optics.caustics.jacobian import _coefficients, _derivatives, _fields, _gather

    grid = Grid(96, 3.0)
    rng = np.random.default_rng(7)
    worst = 0.0
    for i in range(30):
        eta = random_surface(grid, SURFACE_SPECTRA[i % len(SURFACE_SPECTRA)], float(rng.uniform(0.04, 0.15)),
                             int(rng.integers(1 << 30)))
        sun = sun_direction(rng.uniform(40.0, 90.0), rng.uniform(0.0, 360.0))
        light = prepare(eta, grid, float(rng.uniform(0.1, 0.5)) * first_fold_depth(eta, grid, sun), sun, None, 1.333,
                        True, check_values=False)
        planes, *_ = _fields(light.eta, _derivatives(light.eta, grid.dx), jnp.asarray(light.direction, jnp.float32),
                             light.floor, light.n_water, True, shadow_steps(light.eta, grid, light.direction), 3.0,
                             False, 96)
        worst = max(worst, float(jnp.max(_gather(_coefficients(planes), 3.0, 96, 4)[1])))
    assert worst < 1e-4, worst
    eta = random_surface(grid, "swell", 0.1, 5)
    sun = sun_direction(60.0, 0.0)
    floor_irradiance(eta, grid, 0.3 * first_fold_depth(eta, grid, sun), sun, method="jacobian", fold="raise")


@pytest.mark.parametrize("spectrum", SURFACE_SPECTRA)
def test_newton_reaches_the_float32_floor_under_a_slanted_sun_near_the_fold(spectrum):
    """Started from X − D(X − D̄) (D̄: the slanted sun's mean shift), four Newton steps reach the float32
    floor (measured 1.1e-5–4.3e-5 texel) at 0.8 of the first fold under a 40° sun; from X − D(X) they
    had left up to 8.2e-4. The steps stop early once converged, which changes nothing: 16 allowed
    give the same residuals and the same map."""
    from optics.caustics.common import prepare, shadow_steps
    from optics.caustics.jacobian import _coefficients, _derivatives, _fields, _gather

    grid = Grid(128, 3.0)
    eta = random_surface(grid, spectrum, 0.12, 3)
    sun = sun_direction(40.0, 30.0)
    light = prepare(eta, grid, 0.8 * first_fold_depth(eta, grid, sun), sun, None, 1.333, True, check_values=False)
    planes, *_ = _fields(light.eta, _derivatives(light.eta, grid.dx), jnp.asarray(light.direction, jnp.float32),
                         light.floor, light.n_water, True, shadow_steps(light.eta, grid, light.direction), 3.0,
                         False, 128)
    coefficients = _coefficients(planes)
    point, residual, _, _ = _gather(coefficients, 3.0, 128, 4)
    assert float(jnp.max(residual)) < 1e-4
    point16, residual16, _, _ = _gather(coefficients, 3.0, 128, 16)
    assert float(jnp.max(residual16)) < 1e-4
    assert float(jnp.max(jnp.abs(point16 - point))) <= 1e-4 * float(jnp.max(point))
    if spectrum == "power":  # a NaN in one spline window spoils its few points, not the first guess of all
        broken = coefficients.at[0, 0, 0].set(jnp.nan)
        _, residual_nan, _, _ = _gather(broken, 3.0, 128, 4)
        finite = np.isfinite(np.asarray(residual_nan))
        assert 0 < (~finite).sum() < 100 and float(np.max(np.asarray(residual_nan)[finite])) < 1e-4



def _x64_case(i):
    """Case ``i`` of a generated family: a sea over a flat floor, in a walled tank, over a sloping
    ground, and on a map twice finer than the surface; what the method answers there."""
    rng = np.random.default_rng(64 + i)
    grid = Grid(48, 3.0)
    eta = np.asarray(random_surface(grid, SURFACE_SPECTRA[i % len(SURFACE_SPECTRA)], float(rng.uniform(0.04, 0.1)),
                                    int(rng.integers(1 << 30))))
    sun = sun_direction(rng.uniform(50.0, 90.0), rng.uniform(0.0, 360.0))
    depth = float(rng.uniform(0.2, 0.6)) * first_fold_depth(eta, grid, sun)
    ground = (-depth - 0.03 * depth * np.sin(2 * np.pi * np.asarray(grid.coordinates) / 3.0))[None, :] * np.ones((48, 1))
    kw = [dict(depth=depth), dict(depth=depth, walls="all"), dict(depth=ground), dict(depth=depth, resolution=96)][i]
    return grid, eta, sun, kw, "windows" if i == 1 else "gather"


@pytest.mark.slow  # 7-16 s a case (each compiled in both modes)
@pytest.mark.parametrize("case", [0, 1, 2, 3])
def test_float64_mode_gives_the_float32_maps(case):
    """With ``jax_enable_x64`` on, the method runs (its mesh and spectral derivatives in eta's own
    dtype: before, the forward-mode derivatives refused the mixed dtypes) and answers float32 and
    float64 surfaces as float32 mode does, the same way (the method computes in float32 either way:
    measured differences ≤ 4.1e-6 of the peak over the four cases)."""
    import jax

    from optics.caustics import floor_irradiance_jacobian

    grid, eta, sun, kw, answer = _x64_case(case)

    def run(dtype):
        args = {k: (np.asarray(v, dtype) if isinstance(v, np.ndarray) else v) for k, v in kw.items()}
        out, info = floor_irradiance_jacobian(eta.astype(dtype), grid, sun=sun, explain=True, **args)
        assert info["answer"] == answer
        return np.asarray(out, np.float64)

    single = run(np.float32)
    with jax.enable_x64(True):
        for dtype in (np.float32, np.float64):
            double = run(dtype)
            assert np.all(np.isfinite(double))
            assert np.max(np.abs(double - single)) <= 1e-4 * single.max(), dtype
