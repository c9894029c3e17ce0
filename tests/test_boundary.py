import numpy as np
import pytest

from wavephys import checks
from wavephys.boundary import cutoff_mask, cutoff_profile, interior


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


def test_bad_kind():
    with pytest.raises(ValueError, match="kind"):
        cutoff_profile(16, 2, "cubic")


class TestReflection:
    def test_quadratic_absorbs_short_waves(self):
        assert checks.cutoff_reflection(0.5, "quadratic") < 1e-3

    def test_linear_reflects_more(self):
        for ratio in (0.25, 0.5, 1.0):
            assert checks.cutoff_reflection(ratio, "linear") > checks.cutoff_reflection(ratio, "quadratic")

    def test_long_waves_reflect_failure_boundary(self):
        """Documented failure: waves as long as the margin reflect visibly (> 1 %)."""
        assert checks.cutoff_reflection(1.0, "quadratic") > 0.01

    @pytest.mark.slow
    def test_boundaries(self):
        bq = checks.cutoff_boundary("quadratic")
        bl = checks.cutoff_boundary("linear")
        assert 0.5 < bq < 0.75 and 0.2 < bl < 0.3 and bq > 2 * bl
