import math

import numpy as np
import pytest

from wavephys import Grid, Water
from wavephys.harness.wake import WAKE_ANGLE_METHODS, track_wavelength, wake_angle
from wavephys.physics.wake import KELVIN_ANGLE, GaussianPressure, cusp_line, steady_wake, transverse_wavelength

DEEP = Water(sigma=0.0)


@pytest.fixture(scope="module")
def point_wake():
    grid = Grid(2048, 40.0)
    return grid, np.asarray(steady_wake(grid, DEEP, 1.0, GaussianPressure(100.0, 0.05)))


def test_hydrostatic_limit():
    grid = Grid(128, 64.0)
    eta = np.asarray(steady_wake(grid, DEEP, 0.0, GaussianPressure(100.0, 4.0), damping=1e-3))
    p = 100.0 * np.exp(-0.5 * (np.asarray(grid.mesh()[0]) ** 2 + np.asarray(grid.mesh()[1]) ** 2) / 16.0)
    # broad source: η = −(p − mean p)/(ρg) (the mean level is fixed)
    np.testing.assert_allclose(eta, -(p - p.mean()) / (1000 * 9.81), atol=2e-3 * p.max() / (1000 * 9.81))


@pytest.mark.slow
def test_kelvin_angle_of_a_point_source(point_wake):
    grid, eta = point_wake
    m = wake_angle(eta, grid, method="max", near=2.0, far=16.0, exclude=0.3)
    assert abs(m.angle - KELVIN_ANGLE) < 0.3 and m.uncertainty < 0.3


@pytest.mark.slow
def test_transverse_wavelength(point_wake):
    grid, eta = point_wake
    assert track_wavelength(eta, grid, near=4.0, far=16.0) == pytest.approx(transverse_wavelength(1.0), rel=0.01)


def test_cusp_line_of_deep_water_is_kelvins():
    cusp = cusp_line(1.0)
    assert cusp.angle == pytest.approx(KELVIN_ANGLE, abs=1e-4)
    assert cusp.wavenumber == pytest.approx(1.5 * 9.81, rel=1e-5)  # k_c = 1.5 g/U²
    assert cusp.wave_angle == pytest.approx(math.degrees(math.atan(1 / math.sqrt(2))), abs=1e-3)  # 35.26°


def test_cusp_line_widens_in_shallow_water():
    """Havelock: the wedge stays at 19.47° for U ≪ sqrt(g h) and opens as U → sqrt(g h)."""
    deep_enough = cusp_line(1.0, Water(sigma=0.0, depth=2.0)).angle
    assert deep_enough == pytest.approx(KELVIN_ANGLE, abs=1e-3)
    angles = [cusp_line(1.0, Water(sigma=0.0, depth=h)).angle for h in (0.3, 0.2, 0.15, 0.12, 0.105)]
    assert all(b > a for a, b in zip(angles, angles[1:])) and angles[-1] > 60.0


@pytest.mark.parametrize("kw,name", [(dict(speed=math.nan), "speed"), (dict(speed=-1.0), "speed"),
                                     (dict(speed=1.0, samples=1), "samples")])
def test_cusp_line_bad_input(kw, name):
    with pytest.raises(ValueError, match=name):
        cusp_line(**kw)


def test_no_cusp_line_below_c_min():
    with pytest.raises(ValueError, match="no stationary"):
        cusp_line(0.2, Water())


@pytest.mark.slow
@pytest.mark.parametrize("size", [0.05, 0.3])
def test_outer_edge_is_kelvins_angle_for_point_and_moderate_sources(size):
    """The cusp line stays at 19.47° whatever the source size (here σ/λ = 0.08 and 0.47, λ = 2πU²/g)."""
    grid = Grid(2048, 40.0)
    eta = steady_wake(grid, DEEP, 1.0, GaussianPressure(100.0, size))
    m = wake_angle(eta, grid, method="cusp", speed=1.0, near=3.0, far=14.0)
    assert abs(m.angle - KELVIN_ANGLE) < 0.3 and m.uncertainty < 0.3, m
    assert abs(m.angle - KELVIN_ANGLE) < 1.5 * m.uncertainty, m  # the stated uncertainty covers the bias


@pytest.mark.slow
def test_maximum_amplitude_angle_is_not_the_outer_edge_for_larger_sources():
    """The angle of maximum amplitude is a different quantity from the cusp line: once the
    source is not small against 2πU²/g (0.64 m here), its short diverging waves are weak,
    the transverse waves carry the maximum, and the angle falls far below Kelvin's."""
    grid = Grid(2048, 40.0)
    eta = steady_wake(grid, DEEP, 1.0, GaussianPressure(100.0, 0.3))
    largest = wake_angle(eta, grid, method="max", near=2.0, far=16.0, exclude=0.3)
    edge = wake_angle(eta, grid, method="cusp", speed=1.0, near=3.0, far=14.0)
    assert largest.angle < KELVIN_ANGLE - 5.0
    assert abs(edge.angle - KELVIN_ANGLE) < 0.3


@pytest.mark.slow
def test_outer_edge_in_finite_depth_follows_havelock():
    water = Water(sigma=0.0, depth=0.2)  # depth Froude number 0.71: cusp at 20.82°
    grid = Grid(2048, 40.0)
    eta = steady_wake(grid, water, 1.0, GaussianPressure(100.0, 0.1))
    m = wake_angle(eta, grid, method="cusp", speed=1.0, water=water, near=3.0, far=14.0)
    assert abs(m.angle - cusp_line(1.0, water).angle) < 0.3 and abs(m.angle - KELVIN_ANGLE) > 1.0, m


def test_no_stationary_capillary_gravity_wake_below_c_min():
    grid, water = Grid(1024, 1.0), Water()
    n, dx = 1024, float(grid.dx)

    def behind(u):
        eta = np.asarray(steady_wake(grid, water, u, GaussianPressure(10.0, 0.005)))
        return np.abs(eta[:, n // 2 - int(0.4 / dx):n // 2 - int(0.1 / dx)]).max() / np.abs(eta).max()

    below, above = behind(0.22), behind(0.26)  # c_min = 0.2312 m/s
    assert below < 1e-3 and above / below > 100


@pytest.mark.parametrize("kw,name", [(dict(speed=-1.0), "speed"), (dict(speed=math.nan), "speed"),
                                     (dict(damping=0.0), "damping")])
def test_bad_input(kw, name):
    args = dict(speed=1.0)
    args.update(kw)
    with pytest.raises(ValueError, match=name):
        steady_wake(Grid(64, 8.0), DEEP, source=GaussianPressure(10.0, 0.5), **args)


@pytest.mark.parametrize("kw,name", [(dict(method="cusp", speed=-1.0), "speed"),
                                     (dict(method="cusp", speed=1.0, bandwidth=0.0), "bandwidth"),
                                     (dict(method="edge"), "method"), (dict(near=3.0, far=2.0), "far")])
def test_wake_angle_bad_input(kw, name):
    grid = Grid(64, 8.0)
    args = dict(near=1.0, far=3.0)
    args.update(kw)
    with pytest.raises(ValueError, match=name):
        wake_angle(np.zeros((64, 64)), grid, **args)


def test_cusp_needs_the_speed():
    with pytest.raises(TypeError, match="speed"):
        wake_angle(np.zeros((64, 64)), Grid(64, 8.0), method="cusp", near=1.0, far=3.0)
    assert set(WAKE_ANGLE_METHODS) == {"max", "cusp"}


def test_unresolved_cusp_waves():
    with pytest.raises(ValueError, match="Nyquist"):
        wake_angle(np.zeros((64, 64)), Grid(64, 8.0), method="cusp", speed=0.2, near=1.0, far=3.0)


def test_unresolved_source():
    with pytest.raises(ValueError, match="size"):
        steady_wake(Grid(64, 8.0), DEEP, 1.0, GaussianPressure(10.0, 0.01))
