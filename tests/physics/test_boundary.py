import numpy as np
import pytest

from wavephys.physics.boundary import CUTOFF_METHODS, cutoff_mask, cutoff_profile, cutoff_reflection, interior


def test_quadratic_profile_values():
    h = np.asarray(cutoff_profile(16, 4, "quadratic"))
    # h(p) = 1 − (p/M − 1)² on the left margin, mirrored (N − 1 − p) on the right
    np.testing.assert_allclose(h[:4], [0.0, 1 - 0.75**2, 1 - 0.5**2, 1 - 0.25**2])
    np.testing.assert_allclose(h[4:12], 1.0)
    np.testing.assert_allclose(h[12:], h[:4][::-1])


def test_linear_profile_and_mask():
    h = np.asarray(cutoff_profile(16, 4, "linear"))
    np.testing.assert_allclose(h[:4], [0.0, 0.25, 0.5, 0.75])
    m = np.asarray(cutoff_mask(16, 4, "linear"))
    np.testing.assert_allclose(m, h[:, None] * h[None, :])
    assert interior(m, 4).shape == (8, 8) and np.all(interior(m, 4) == 1.0)


def test_zero_margin_is_identity():
    assert np.all(np.asarray(cutoff_profile(8, 0)) == 1.0)


@pytest.mark.parametrize("margin", [8, 9, -1])
def test_bad_margin(margin):
    with pytest.raises(ValueError, match="margin"):
        cutoff_profile(16, margin)


def test_bad_method():
    with pytest.raises(ValueError, match="method"):
        cutoff_profile(16, 2, "cubic")
    with pytest.raises(TypeError, match="method"):
        cutoff_profile(16, 2, None)


def test_methods_are_a_family():
    assert set(CUTOFF_METHODS) == {"quadratic", "linear"}
    assert float(CUTOFF_METHODS["quadratic"](0.5)) == 0.75


@pytest.mark.parametrize("ratio", [0.25, 0.5, 1.0, 2.0])
def test_linear_reflects_more_at_every_wavelength(ratio):
    """Over a family of λ/M (the registry checks λ/M = 0.5 and the boundaries)."""
    assert cutoff_reflection(ratio, "linear") > cutoff_reflection(ratio, "quadratic")


def test_reflection_grows_with_wavelength():
    r = [cutoff_reflection(x, "quadratic") for x in (0.25, 0.5, 1.0, 2.0)]
    assert all(a < b for a, b in zip(r, r[1:])), r
