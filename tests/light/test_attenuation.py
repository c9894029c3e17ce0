import math
import numpy as np
import pytest

from optics.checks import plain_numpy_water_srgb
from optics.light.attenuation import (cutoff_distance, fit_rgb_coefficients, pure_water_absorption, rgb_error,
                                transmittance, underwater_radiance, water_srgb)


def test_beer_lambert_and_layers():
    a = np.array([0.3, 0.05, 0.01])
    t = np.asarray(transmittance(2.0, a))
    np.testing.assert_allclose(t, np.exp(-2.0 * a), rtol=1e-6)
    np.testing.assert_allclose(np.asarray(transmittance(0.7, a)) * np.asarray(transmittance(1.3, a)), t, rtol=1e-6)


def test_cutoff_distance_sign_and_value():
    a = np.array([0.34, 0.0581, 0.00808])
    d = cutoff_distance(1e-3, a)
    assert d > 0 and d == pytest.approx(-math.log(1e-3) / 0.00808)
    assert float(transmittance(d, 0.00808)) == pytest.approx(1e-3, rel=1e-5)


def test_in_scatter_limits():
    g, diffuse = np.array([1.0, 0.5, 0.2]), np.array([0.0, 0.1, 0.3])
    np.testing.assert_allclose(underwater_radiance(g, diffuse, 0.0, 0.0, 0.2), g, rtol=1e-6)
    np.testing.assert_allclose(underwater_radiance(g, diffuse, 1e3, 0.0, 0.2), diffuse, atol=1e-6)
    alpha = math.exp(-0.2 * 3.0 - 0.1 * 2.0)
    np.testing.assert_allclose(underwater_radiance(g, diffuse, 3.0, 2.0, 0.2, 0.1), alpha * g + (1 - alpha) * diffuse,
                               rtol=1e-6)


def test_shipped_table_spot_values():
    np.testing.assert_allclose(pure_water_absorption([450, 550, 650, 700]), [0.00808, 0.0581, 0.340, 0.6126])


@pytest.mark.parametrize("d", [1.0, 5.0, 10.0])
def test_spectral_srgb_matches_independent_integration(d):
    np.testing.assert_allclose(water_srgb(d, gamut="none"), plain_numpy_water_srgb(d), atol=1e-4)


def test_gamut_policy():
    raw = water_srgb(10.0, gamut="none")
    assert raw[0] < 0 < raw[1] < raw[2]  # red is out of gamut after 10 m of water
    assert water_srgb(10.0)[0] == 0.0
    np.testing.assert_allclose(water_srgb(0.0), [1.0, 1.0, 1.0])


def test_rgb_approximation_error_grows_with_path():
    coeffs = fit_rgb_coefficients(5.0)
    assert coeffs[0] > coeffs[1] > coeffs[2] >= 0  # red absorbed most
    err = rgb_error(np.array([1.0, 20.0]), coeffs)
    assert err[0] < 0.03 < err[1]


@pytest.mark.parametrize("call,name", [(lambda: transmittance(-1.0, 0.1), "distance"),
                                       (lambda: transmittance(1.0, -0.1), "coefficient"),
                                       (lambda: transmittance(math.nan, 0.1), "distance"),
                                       (lambda: cutoff_distance(0.0, [0.1]), "epsilon"),
                                       (lambda: cutoff_distance(0.01, [0.0, 0.1]), "coefficients"),
                                       (lambda: pure_water_absorption(250.0), "wavelength"),
                                       (lambda: water_srgb(-2.0), "distance"),
                                       (lambda: water_srgb(1.0, gamut="wrap"), "gamut")])
def test_bad_input(call, name):
    with pytest.raises(ValueError, match=name):
        call()


@pytest.mark.parametrize("method", ["spectral", "rgb"])
def test_the_shader_table_draws_every_method_on_every_path(method):
    """Linear interpolation in u = s/(s + scale) through transmittance_table is the method itself
    within 1e-4 (spectral) / 5e-5 (rgb) on paths from 0 to 2 km (measured 5.8e-5, at the kink where the
    spectral colour's gamut clipping sets in near 8.1 m, and 4e-5); the table starts at 1 and ends at 0
    (s = ∞)."""
    from optics.light.attenuation import TABLE_SCALE, WATER_TRANSMITTANCE_METHODS, transmittance_table

    table = transmittance_table(method)
    n = len(table)
    s = np.concatenate([np.linspace(0.0, 2.0, 2001), np.geomspace(2.0, 2000.0, 20001)])
    u = s / (s + TABLE_SCALE) * (n - 1)
    i = np.minimum(np.floor(u).astype(int), n - 2)
    f = (u - i)[:, None]
    drawn = table[i] * (1 - f) + table[i + 1] * f
    error = np.abs(drawn - WATER_TRANSMITTANCE_METHODS[method](s)).max(-1)
    assert error.max() <= (1e-4 if method == "spectral" else 5e-5), (method, error.max(), s[error.argmax()])
    assert np.all(table[0] == 1.0) and np.all(table[-1] == 0.0)
    assert not table.flags.writeable


def test_the_shader_table_refuses_bad_input_by_name():
    from optics.light.attenuation import transmittance_table

    with pytest.raises(ValueError, match="method"):
        transmittance_table("beer")
    with pytest.raises(ValueError, match="size"):
        transmittance_table("rgb", size=4)
    with pytest.raises(ValueError, match="scale"):
        transmittance_table("rgb", scale=0.0)
