import math

import jax.numpy as jnp
import numpy as np
import pytest
from colour.phenomena import polarised_light_reflection_coefficient

from optics.light.fresnel import (N_AIR, N_WATER, fresnel_lut, normal_reflectance, reflectance, reflectance_sp,
                            sun_glint, water_refractive_index)

ANGLES = np.radians(np.linspace(0.0, 89.9, 2000))


def _err(method, n1, n2):
    c = jnp.asarray(np.cos(ANGLES))
    e = np.asarray(reflectance(c, n1, n2, method=method)) - np.asarray(reflectance(c, n1, n2))
    i = int(np.argmax(np.abs(e)))
    return e[i], math.degrees(ANGLES[i])


class TestExact:
    def test_normal_incidence(self):
        # ((1.3333 − 1.000293)/(1.3333 + 1.000293))² = 0.142701² = 0.020364 (SPEC prints
        # 0.02037, which is the value for n1 = 1.000, n2 = 1.333: 0.020373)
        assert float(reflectance(1.0, N_AIR, 1.3333)) == pytest.approx(0.020364, abs=1e-6)
        assert float(reflectance(1.0, 1.0, 1.333)) == pytest.approx(0.020373, abs=1e-6)
        assert float(reflectance(1.0)) == pytest.approx(normal_reflectance(N_AIR, N_WATER), rel=1e-6)
        assert float(reflectance(1.0, 1.333, N_AIR)) == pytest.approx(float(reflectance(1.0)), rel=1e-6)

    def test_brewster_angle(self):
        theta_b = math.atan(N_WATER / N_AIR)
        assert math.degrees(theta_b) == pytest.approx(53.1, abs=0.05)
        _, rp = reflectance_sp(math.cos(theta_b), N_AIR, N_WATER)
        assert float(rp) < 1e-10

    def test_total_internal_reflection(self):
        crit = math.asin(N_AIR / N_WATER)
        assert math.degrees(crit) == pytest.approx(48.6, abs=0.05)
        assert float(reflectance(math.cos(crit + 1e-4), N_WATER, N_AIR)) == 1.0
        assert float(reflectance(math.cos(crit - 1e-2), N_WATER, N_AIR)) < 1.0

    def test_agrees_with_colour_science(self, x64):
        th = np.linspace(0.0, 89.0, 90)
        tt = np.degrees(np.arcsin(N_AIR / N_WATER * np.sin(np.radians(th))))
        ref = np.real(polarised_light_reflection_coefficient(N_AIR, N_WATER, th, tt))
        rs, rp = reflectance_sp(jnp.cos(jnp.radians(jnp.asarray(th))), N_AIR, N_WATER)
        np.testing.assert_allclose(rs, ref[..., 0], atol=1e-6)
        np.testing.assert_allclose(rp, ref[..., 1], atol=1e-6)

    def test_grazing_is_total(self):
        assert float(reflectance(0.0)) == pytest.approx(1.0)


class TestApproximations:
    def test_schlick_worst_error_from_above(self):
        err, deg = _err("schlick", N_AIR, N_WATER)
        assert err == pytest.approx(0.059, abs=0.002) and 82 < deg < 86

    def test_schlick_from_below_uses_cos_t(self):
        err, _ = _err("schlick", N_WATER, N_AIR)
        assert abs(err) < 0.07  # same worst error, mirrored to the transmitted angle
        assert float(reflectance(math.cos(math.radians(60)), N_WATER, N_AIR, method="schlick")) == 1.0

    def test_naive_schlick_from_below_fails_near_critical_angle(self):
        """Documented failure: Schlick with cos θi under water misses TIR (error ≈ −0.97)."""
        c = jnp.asarray(np.cos(ANGLES))
        f0 = normal_reflectance(N_WATER, N_AIR)
        naive = f0 + (1 - f0) * (1 - c) ** 5
        e = np.asarray(naive) - np.asarray(reflectance(c, N_WATER, N_AIR))
        i = int(np.argmax(np.abs(e)))
        assert e[i] == pytest.approx(-0.97, abs=0.01) and 48 < math.degrees(ANGLES[i]) < 49.5

    def test_jensen_golias_and_loviscach_errors(self):
        jg, _ = _err("jensen_golias", N_AIR, N_WATER)
        lv, _ = _err("loviscach", N_AIR, N_WATER)
        assert abs(jg) < 0.08 and lv > 0.2

    def test_lut_converges(self):
        errs = [abs(float(np.max(np.abs(np.asarray(reflectance(jnp.asarray(np.cos(ANGLES)), method="lut", size=s))
                                         - np.asarray(reflectance(jnp.asarray(np.cos(ANGLES)))))))) for s in (16, 64, 256)]
        assert errs[0] > errs[1] > errs[2]
        assert fresnel_lut(N_AIR, N_WATER, 8).shape == (8,)

    def test_sun_glint(self):
        assert float(sun_glint(1.0)) == pytest.approx(1.0) and float(sun_glint(0.98)) == 0.0


def test_refractive_index_of_water():
    n = water_refractive_index([400.0, 589.0, 700.0])
    assert n[1] == pytest.approx(1.333, abs=0.001) and n[0] > n[1] > n[2]


@pytest.mark.parametrize("kw,name", [(dict(cos_theta=1.5), "cos_theta"), (dict(cos_theta=math.nan), "cos_theta"),
                                     (dict(cos_theta=0.5, n1=0.0), "n1"), (dict(cos_theta=0.5, n2=-1.0), "n2"),
                                     (dict(cos_theta=0.5, method="fast"), "method")])
def test_bad_input(kw, name):
    with pytest.raises(ValueError, match=name):
        reflectance(**kw)


def test_bad_wavelength():
    with pytest.raises(ValueError, match="wavelength"):
        water_refractive_index(50.0)
