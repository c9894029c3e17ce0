import math

import numpy as np
import pytest

from wavephys import Grid, Water
from wavephys.wake import (KELVIN_ANGLE, GaussianPressure, steady_wake, track_wavelength, transverse_wavelength,
                           wake_angle)

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


@pytest.mark.slow
def test_maximum_amplitude_angle_shrinks_for_larger_sources():
    """The angle of maximum amplitude is a different quantity from the cusp line: it drops
    below Kelvin's angle as the source grows against 2πU²/g (here 0.64 m at U = 1 m/s)."""
    grid = Grid(2048, 40.0)
    small = wake_angle(steady_wake(grid, DEEP, 1.0, GaussianPressure(100.0, 0.05)), grid, method="max",
                       near=2.0, far=16.0, exclude=0.3)
    large = wake_angle(steady_wake(grid, DEEP, 1.0, GaussianPressure(100.0, 0.1)), grid, method="max",
                       near=2.0, far=16.0, exclude=0.3)
    assert large.angle < small.angle


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


def test_unresolved_source():
    with pytest.raises(ValueError, match="size"):
        steady_wake(Grid(64, 8.0), DEEP, 1.0, GaussianPressure(10.0, 0.01))
