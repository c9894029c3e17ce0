import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Simulation, Water
from wavephys.physics.wind import jonswap_frequency_spectrum, jonswap_spectrum, phillips_spectrum

WATER = Water(sigma=0.0)
GRID = Grid(256, 200.0)


def _grid_variance(f):
    dk = 2 * math.pi / float(GRID.length)
    return float(jnp.sum(f)) * dk * dk


def test_phillips_variance_matches_closed_form():
    """∫ A e^{−1/(kL)²} k⁻⁴ cos²θ d²k over the downwind half plane = A π L² / 4."""
    ky, kx = GRID.wavenumbers()
    u, a = 5.0, 1e-3
    big = u * u / 9.81
    f = phillips_spectrum(kx, ky, WATER, u, amplitude=a)
    assert _grid_variance(f) == pytest.approx(a * math.pi * big**2 / 4, rel=0.03)
    assert float(jnp.min(f)) >= 0 and float(jnp.sum(jnp.where(kx < 0, f, 0))) == 0.0  # downwind only


def test_jonswap_peak_and_variance_conversion():
    u, fetch = 10.0, 50e3
    om = np.linspace(0.05, 20, 100000)
    s = np.asarray(jonswap_frequency_spectrum(jnp.asarray(om), WATER, u, fetch))
    assert om[s.argmax()] == pytest.approx(22 * (9.81**2 / (u * fetch)) ** (1 / 3), rel=1e-3)
    ky, kx = GRID.wavenumbers()
    # the k-space spectrum (Jacobian c_g/k, cos² spreading) carries the same variance
    assert _grid_variance(jonswap_spectrum(kx, ky, WATER, u, fetch)) == pytest.approx(np.trapezoid(s, om), rel=0.01)


def test_synthesized_sea_has_the_spectrum_variance():
    sim = Simulation(GRID, WATER, dt=0.1)
    ky, kx = GRID.wavenumbers()
    expected = _grid_variance(jonswap_spectrum(kx, ky, WATER, 10.0, 50e3))
    v = [float(jnp.var(sim.surface(sim.add_wind(sim.initial_state(), jax.random.PRNGKey(i), "jonswap",
                                                  wind_speed=10.0, fetch=50e3)).eta)) for i in range(8)]
    sem = np.std(v, ddof=1) / math.sqrt(len(v))
    assert abs(np.mean(v) - expected) < 4 * sem + 1e-3 * expected


def test_wind_sea_travels_downwind():
    sim = Simulation(GRID, WATER, dt=0.5)
    st = sim.add_wind(sim.initial_state(), jax.random.PRNGKey(0), "phillips", wind_speed=5.0, direction=0.0)
    s0 = sim.surface(st).eta
    st2, _ = sim.run(st, 2)
    s1 = sim.surface(st2).eta
    # cross-correlation peak shifts toward +x
    xc = np.real(np.fft.ifft2(np.fft.fft2(np.asarray(s1)) * np.conj(np.fft.fft2(np.asarray(s0)))))
    iy, ix = np.unravel_index(np.argmax(xc), xc.shape)
    assert 0 < ix < 128 and (iy == 0 or iy == 255 or iy == 1)


@pytest.mark.parametrize("kw,name", [(dict(wind_speed=0.0), "wind_speed"), (dict(wind_speed=math.nan), "wind_speed"),
                                     (dict(wind_speed=5.0, amplitude=-1.0), "amplitude")])
def test_bad_phillips(kw, name):
    with pytest.raises(ValueError, match=name):
        phillips_spectrum(1.0, 0.0, WATER, **kw)


def test_bad_jonswap_and_name():
    with pytest.raises(ValueError, match="fetch"):
        jonswap_frequency_spectrum(1.0, WATER, 10.0, -5.0)
    sim = Simulation(GRID, WATER, dt=0.1)
    with pytest.raises(ValueError, match="spectrum"):
        sim.add_wind(sim.initial_state(), jax.random.PRNGKey(0), "pm", wind_speed=5.0)
