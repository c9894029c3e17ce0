"""Reflecting walls' primitives: the cosine transforms, seiche frequencies, images, side names."""

import math

import numpy as np
import pytest
import scipy.fft as sf
from hypothesis import given, settings
from hypothesis import strategies as st

from wavephys import Water
from wavephys.core.spectral import (cosine_transform, cosine_transform2, inverse_cosine_transform,
                                    inverse_cosine_transform2, inverse_mode_transform, mode_transform,
                                    mode_wavenumbers)
from wavephys.physics.boundary import cutoff_mask
from wavephys.physics.walls import check_walls, image_points, seiche_frequencies, wall_axes

WALLS = [(False, False), (True, True), (True, False), (False, True)]


@pytest.mark.slow
@settings(max_examples=8, deadline=None)
@given(half=st.integers(1, 40), batch=st.integers(1, 3), seed=st.integers(0, 2**31 - 1))
def test_makhouls_cosine_transform_in_jax_is_scipys_type_2_and_its_inverse_is_exact(half, batch, seed):
    """The JAX path (one real FFT after Makhoul's reordering, 1-D and 2-D) against SciPy's DCT-II, float64."""
    import jax
    import jax.numpy as jnp

    n = 2 * half
    x = np.random.default_rng(seed).standard_normal((batch, n, n))
    with jax.enable_x64(True):
        xj = jnp.asarray(x)
        for axis in (-1, -2):
            X = np.asarray(cosine_transform(xj, axis))
            assert np.abs(X - 0.5 * sf.dct(x, type=2, axis=axis)).max() <= 1e-12 * n * np.abs(x).max()
            assert np.abs(np.asarray(inverse_cosine_transform(jnp.asarray(X), axis)) - x).max() <= 1e-12 * n
        X2 = np.asarray(cosine_transform2(xj))
        assert np.abs(X2 - 0.25 * sf.dctn(x, type=2, axes=(-2, -1))).max() <= 1e-12 * n * n * np.abs(x).max()
        assert np.abs(np.asarray(inverse_cosine_transform2(jnp.asarray(X2))) - x).max() <= 1e-12 * n


@pytest.mark.parametrize("n", [2, 16, 64])
def test_makhouls_cosine_transform_matches_scipy_at_a_few_sizes(n):
    import jax
    import jax.numpy as jnp

    x = np.random.default_rng(n).standard_normal((2, n, n))
    with jax.enable_x64(True):
        X2 = np.asarray(cosine_transform2(jnp.asarray(x)))
        X1 = np.asarray(cosine_transform(jnp.asarray(x), -2))
        back = np.asarray(inverse_cosine_transform2(jnp.asarray(X2)))
    assert np.abs(X2 - 0.25 * sf.dctn(x, type=2, axes=(-2, -1))).max() <= 1e-12 * n * n
    assert np.abs(X1 - 0.5 * sf.dct(x, type=2, axis=-2)).max() <= 1e-12 * n
    assert np.abs(back - x).max() <= 1e-12 * n


def test_cosine_transform_in_jax_float32_matches_numpy():
    import jax.numpy as jnp

    x = np.random.default_rng(1).standard_normal((2, 64, 64))
    for walls in WALLS:
        got = np.asarray(mode_transform(jnp.asarray(x, jnp.float32), walls))
        want = mode_transform(x, walls)
        assert np.abs(got - want).max() <= 2e-5 * np.abs(want).max(), walls
        back = np.asarray(inverse_mode_transform(jnp.asarray(got), 64, walls))
        assert np.abs(back - x).max() <= 1e-5


@pytest.mark.parametrize("walls", WALLS)
def test_mode_transform_diagonalises_the_laplacian_with_no_flux_walls(walls):
    """The layout's wavenumbers are the modes' own: a cosine mode of the tank (even about the walls)
    or a Fourier mode comes out as one coefficient at its k."""
    n, length = 32, 2.0
    dx = length / n
    x = -length / 2 + (np.arange(n) + 0.5) * dx
    rng = np.random.default_rng(3)
    for _ in range(5):
        m, q = rng.integers(1, n // 2, 2)
        fx = np.cos(m * np.pi * (x + length / 2) / length) if walls[0] else np.cos(2 * np.pi * m * x / length)
        fy = np.cos(q * np.pi * (x + length / 2) / length) if walls[1] else np.cos(2 * np.pi * q * x / length)
        field = fy[:, None] * fx[None, :]
        spec = mode_transform(field, walls)
        ky, kx = mode_wavenumbers(n, dx, walls, xp=np)
        k2 = np.broadcast_to(ky ** 2 + kx ** 2, spec.shape)
        want = (np.pi * m / length * (1 if walls[0] else 2)) ** 2 + (np.pi * q / length * (1 if walls[1] else 2)) ** 2
        power = np.abs(spec) ** 2
        assert np.sum(power[np.isclose(k2, want)]) >= (1 - 1e-12) * power.sum()


def test_odd_sizes_work_in_numpy_and_are_refused_by_name_in_jax():
    import jax.numpy as jnp

    x = np.random.default_rng(0).standard_normal((5, 7))
    assert np.abs(inverse_cosine_transform(cosine_transform(x, 0), 0) - x).max() < 1e-12
    with pytest.raises(ValueError, match="even number of samples"):
        cosine_transform(jnp.ones((5, 5)))


def test_seiche_frequencies_are_the_published_dispersion_relation_at_k_mn():
    """Lamb §191: ω² = g k tanh(kh) at k = π√((m/Lx)² + (n/Ly)²), written out here independently;
    Merian's shallow-water period T = 2L/(m√(gh)) in the limit."""
    g, h = 9.81, 0.3
    for lx, ly in ((1.0, 1.0), (2.0, 0.7), (5.0, 3.0)):
        w = seiche_frequencies(lx, ly, Water(sigma=0.0, depth=h), modes=5)
        for q in range(5):
            for m in range(5):
                k = math.pi * math.hypot(m / lx, q / ly)
                assert w[q, m] == pytest.approx(math.sqrt(g * k * math.tanh(k * h)), rel=1e-6, abs=1e-12)
    shallow = seiche_frequencies(20.0, 20.0, Water(sigma=0.0, depth=0.01), modes=2)
    merian = 2 * math.pi / (2 * 20.0 / math.sqrt(g * 0.01))
    assert shallow[0, 1] == pytest.approx(merian, rel=1e-4)


def test_image_points_of_a_corner_are_the_point_two_mirrors_and_the_double_image():
    xs, ys, sign = image_points(0.8, 0.9, 2.0, ("right", "top"))
    assert sorted(zip(np.round(xs, 12), np.round(ys, 12))) == sorted(
        [(0.8, 0.9), (1.2, 0.9), (0.8, 1.1), (1.2, 1.1)])
    assert np.all(sign == 1)


def test_check_walls_names_and_shorthands():
    assert check_walls("all") == ("left", "right", "bottom", "top")
    assert check_walls("x") == ("left", "right")
    assert check_walls(["top", "bottom"]) == ("bottom", "top")
    assert check_walls("none") == ()
    assert wall_axes("y") == (False, True)
    with pytest.raises(ValueError, match="unknown side 'north'"):
        check_walls("north")
    with pytest.raises(TypeError, match="walls must be"):
        check_walls(3)
    with pytest.raises(ValueError, match="cannot be periodic opposite a wall"):
        check_walls("top", margin=0)
    assert check_walls("top", margin=4) == ("top",)


def test_the_cutoff_margin_sits_only_on_sides_that_are_not_walls():
    mask = np.asarray(cutoff_mask(32, 4, walls=("bottom",)))
    assert np.all(mask[0, 4:-4] == 1.0)  # the bottom row is a wall: no margin there
    assert np.all(mask[-1] < 1.0)  # the top is open
    assert np.all(mask[:, 0] < 1.0) and np.all(mask[:, -1] < 1.0)  # left and right open
    assert np.array_equal(np.asarray(cutoff_mask(32, 4)), np.asarray(cutoff_mask(32, 4, walls=())))
