"""Distance filtering of the normals: the slope pyramid, the footprint, the sigma points, and the picture
against a supersampled truth per distance band (docs/physics.md §2.6)."""

import math
from dataclasses import replace

import numpy as np
import pytest

from optics.rendering.filtering import (FACING, MAX_TAPS, covariance_of, facing_normal, footprint, sigma_slopes,
                                        slope_covariance, slope_moments)
from optics.rendering.reference import _water_slope, march, psnr, ray_directions, trace
from optics.rendering.renderer import Renderer
from optics.rendering.scene import Scene, look_at

from test_render import _scene  # the built-in scenes, built once per session


@pytest.mark.parametrize("seed", range(4))
@pytest.mark.parametrize("wrap", [False, True])
def test_each_level_holds_the_mean_moments_of_its_texels(seed, wrap):
    """Level k averages the 2^k × 2^k texels under it where the sides divide; odd sides halve to ⌊n/2⌋ as GL's
    mip maps do, down to one texel, every level a mean (inside the range of level 0, second moments at least
    the squares of the means)."""
    rng = np.random.default_rng(seed)
    ny, nx = rng.choice([16, 32, 48, 33, 47, 100, 129], 2)
    L = float(rng.uniform(2.0, 50.0))
    h = rng.normal(0, rng.uniform(0.01, 1.0), (ny, nx))
    levels = slope_moments(h, L, wrap)
    base = levels[0].astype(np.float64)
    gx, gy = base[..., 0], base[..., 1]
    np.testing.assert_allclose(base[..., 2:], np.stack([gx * gx, gy * gy, gx * gy], -1), rtol=1e-6, atol=1e-12)
    assert len(levels) == 1 + int(math.log2(max(ny, nx)))  # down to one texel
    lo, hi = base.reshape(-1, 5).min(0), base.reshape(-1, 5).max(0)
    scale = np.abs(base).max()
    for k, level in enumerate(levels[1:], 1):
        assert level.shape[:2] == (max(1, ny >> k), max(1, nx >> k))
        assert (level >= lo - 1e-6 * scale).all() and (level <= hi + 1e-6 * scale).all()
        assert (level[..., 2] >= level[..., 0] ** 2 * (1 - 1e-5)).all()
        assert (level[..., 3] >= level[..., 1] ** 2 * (1 - 1e-5)).all()
        b = 2 ** k
        if ny % b == 0 and nx % b == 0:
            blocks = base.reshape(ny // b, b, nx // b, b, 5).mean(axis=(1, 3))
            np.testing.assert_allclose(level, blocks, rtol=1e-5, atol=1e-7 * scale)
    np.testing.assert_allclose(slope_covariance(h, L, wrap), covariance_of(base.reshape(-1, 5).mean(0)), rtol=1e-5)


@pytest.mark.parametrize("surroundings", ["none", "tile"])
def test_the_pyramid_starts_from_the_slopes_the_renderer_draws(surroundings):
    """Level 0 is the central difference one texel apart of the bilinear surface at each texel centre: the
    slope the renderer shades a near pixel with (clamped or wrapped at the edges alike)."""
    rng = np.random.default_rng(7)
    n, L = 32, 8.0
    water = rng.normal(0, 0.1, (n, n)).astype(np.float32)
    s = Scene(np.full((n, n), -2.0, np.float32), water, L, look_at((0, -1, 30), (0, 0, 0), 40.0),
              surroundings=surroundings)
    centres = (np.arange(n) + 0.5) * L / n - L / 2
    X, Y = np.meshgrid(centres, centres)
    inside = np.hypot(X - s.camera.eye[0], Y - s.camera.eye[1]) < 1.4 * L  # no fade there
    drawn = _water_slope(s, np.stack([X, Y], -1))
    level = slope_moments(water, L, wrap=surroundings == "tile")[0]
    np.testing.assert_allclose(level[..., :2][inside], drawn[inside], rtol=1e-5, atol=1e-5)


@pytest.mark.parametrize("seed", range(6))
def test_sigma_slopes_keep_the_mean_and_covariance(seed):
    rng = np.random.default_rng(seed)
    m = rng.normal(0, 0.3, (50, 2))
    A = rng.normal(0, 0.2, (50, 2, 2))
    C = A @ np.swapaxes(A, 1, 2)
    C[:5] = 0.0  # a smooth surface: four copies of the mean
    C[5:10, 1, 1] = C[5:10, 0, 1] = C[5:10, 1, 0] = 0.0  # rank one
    cov = np.stack([C[:, 0, 0], C[:, 1, 1], C[:, 0, 1]], -1)
    g = sigma_slopes(m, cov)
    assert g.shape == (4, 50, 2)
    np.testing.assert_allclose(g.mean(0), m, atol=1e-12)
    dev = g - m
    np.testing.assert_allclose(np.einsum("kni,knj->nij", dev, dev) / 4, C, atol=1e-12)


def test_footprint_reads_the_level_that_matches_the_pixel():
    alpha, texel = 0.002, 0.05
    lod, along, taps = footprint(100.0, np.array([0.0, 0.0, -1.0]), alpha, texel)  # straight down
    assert taps == 1 and along == pytest.approx(0.2) and lod == pytest.approx(math.log2(0.2 / texel))
    d = np.array([0.0, math.cos(0.05), -math.sin(0.05)])  # grazing: the long axis capped at MAX_TAPS widths
    lod, along, taps = footprint(100.0, d, alpha, texel)
    assert along == pytest.approx(0.2 * min(1 / math.sin(0.05), MAX_TAPS))
    assert taps == min(MAX_TAPS, math.ceil(along / 0.2 - 1e-6))
    lod, along, taps = footprint(1.0, d, alpha, texel)  # near: under a texel across
    assert lod < 0 and taps == min(MAX_TAPS, math.ceil(along / texel - 1e-6))
    with pytest.raises(ValueError, match="pixel_angle"):
        footprint(1.0, d, 0.0, texel)
    with pytest.raises(TypeError, match="texel"):
        footprint(1.0, d, alpha, "0.1")
    with pytest.raises(ValueError, match="water"):
        slope_moments(np.zeros(8), 1.0)


def test_a_mean_normal_facing_away_is_tipped_just_enough():
    rng = np.random.default_rng(3)
    n = rng.normal(0, 1, (500, 3))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    d = rng.normal(0, 1, (500, 3))
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    out = facing_normal(n, d)
    np.testing.assert_allclose(np.linalg.norm(out, axis=1), 1.0, atol=1e-12)
    assert (-np.sum(out * d, 1) >= FACING / math.hypot(1.0, FACING) - 1e-12).all()  # FACING before normalizing
    facing = -np.sum(n * d, 1) >= FACING
    np.testing.assert_allclose(out[facing], n[facing], atol=1e-15)


def test_near_pixels_are_drawn_as_without_filtering():
    """Where a pixel covers under a texel across and along (lod ≤ 0, one tap), filtering changes nothing:
    in the reference exactly, on the GPU to rounding."""
    s = _scene("shore", 128, False)
    off = s.with_effects(filtering=False)
    W, H = 120, 90
    d = ray_directions(s.camera, W, H).reshape(-1, 3)
    o = np.broadcast_to(np.asarray(s.camera.eye, float), d.shape)
    t, hit, which = march(s, o, d, 0, 256, 10)
    lod, _, taps = footprint(np.where(hit, t, 0.0), d, 2 * math.tan(math.radians(s.camera.fov) / 2) / H,
                             s.length / 128)
    water = hit & (which == 1)
    near = (water & (lod <= -0.1) & (taps == 1)).reshape(H, W)
    far = (water & (lod > 0.5)).reshape(H, W)
    assert near.sum() > 1000 and far.sum() > 80
    on_ref, off_ref = trace(s, W, H), trace(off, W, H)
    np.testing.assert_array_equal(on_ref[near], off_ref[near])
    assert np.abs(on_ref[far] - off_ref[far]).max() > 0.02  # and it does act far away
    with Renderer(W, H) as r:
        np.testing.assert_allclose(r.render(s)[near], r.render(off)[near], atol=2e-6)


@pytest.mark.parametrize("yaw", [0.0, 2.2])
def test_filtered_frames_are_nearer_the_supersampled_truth_in_every_far_band(yaw):
    """The storm seen from two headings at 80×60: against the truth (4×4 samples per pixel, waves never
    faded), filtering lowers the RMS error by at least a quarter in every band from one scene side out,
    and from 2.5 sides (where
    the waves fade, and the flat far field) at least threefold (bench/filtering.py measures it at 240×180:
    ×1.4–1.8 inside 2.5 sides, ×3.6 and ×6.3 beyond). The mesh path (clipmap rings of 64 cells), which
    shades with the same filtering, gains alike (at 160×120: RMS 0.024 → 0.018, 0.045 → 0.032,
    0.135 → 0.043 and 0.219 → 0.035 from one side out)."""
    from bench.filtering import BANDS, band_errors, truth_scene, _downsample

    s = _scene("storm", 128, False)
    eye, target = np.asarray(s.camera.eye), np.asarray(s.camera.target)
    c, si = math.cos(yaw), math.sin(yaw)
    rot = np.array([[c, -si, 0], [si, c, 0], [0, 0, 1]])
    s = replace(s, camera=look_at(tuple(rot @ eye), tuple(rot @ target), s.camera.fov)).with_effects(foam=False)
    off = s.with_effects(filtering=False)
    W, H, ss = 80, 60, 4
    d = ray_directions(s.camera, W, H)
    level = float(np.mean(s.water, dtype=np.float64))
    with np.errstate(divide="ignore"):
        t = np.where(d[..., 2] < 0, (level - s.camera.eye[2]) / d[..., 2], np.inf)
    distance = t * np.hypot(d[..., 0], d[..., 1]) / s.length
    with Renderer(W * ss, H * ss, steps=1024) as r:
        truth = _downsample(r.render(truth_scene(off, 9)), ss)
    from optics.rendering.meshes import clipmap_mesh, render_mesh

    mesh = clipmap_mesh(s, cells=64)  # the mesh path shades with the same filtering (issue 54, item 2)
    with Renderer(W, H) as r:
        rows = {m: {b["band"]: b for b in band_errors(draw(x), truth, distance)}
                for m, x, draw in (("off", off, r.render), ("on", s, r.render),
                                   ("mesh off", off, lambda x: render_mesh(r, x, mesh)),
                                   ("mesh on", s, lambda x: render_mesh(r, x, mesh)))}
    far = [b for b in rows["off"] if b[0] >= 1.0]
    assert len(far) >= 3
    for path in ("", "mesh "):
        for band in far:
            # at least a quarter lower (measured here: 0.56-0.61 of the unfiltered RMS by the march, 0.50-0.65
            # by the mesh, inside 2.5 sides; the mesh's footprint ignored, 0.86-0.99)
            assert rows[path + "on"][band]["rms"] < 0.75 * rows[path + "off"][band]["rms"], (path, band)
            if band[0] >= BANDS[4][0]:
                assert rows[path + "on"][band]["rms"] < rows[path + "off"][band]["rms"] / 3, (path, band)


@pytest.mark.parametrize("shape", [(67, 130)])  # odd and oblong at once
def test_odd_and_oblong_water_is_filtered_alike_on_the_gpu(shape):
    """Water of odd and unequal sides (the pyramid's ⌊n/2⌋ levels, rectangular texels) tiled to the horizon: the
    GPU draws the filtered frame as the reference does, and the filtering acts."""
    ny, nx = shape
    L = 20.0
    y, x = (np.arange(ny) + 0.5) / ny * L - L / 2, (np.arange(nx) + 0.5) / nx * L - L / 2
    X, Y = np.meshgrid(x, y)
    rng = np.random.default_rng(ny)
    water = sum(a * np.sin(2 * np.pi * (kx * X + ky * Y) / L + p) for a, kx, ky, p in
                zip(rng.uniform(0.05, 0.2, 6), rng.integers(-6, 7, 6), rng.integers(1, 7, 6), rng.uniform(0, 6, 6)))
    s = Scene(np.full((8, 8), -4.0, np.float32), water.astype(np.float32), L,
              look_at((0.0, -L / 2, 2.5), (0.0, 2 * L, -1.0), 60.0), surroundings="tile")
    with Renderer(80, 60) as r:
        image = r.render(s)
        unfiltered = r.render(s.with_effects(filtering=False))
    assert psnr(image, trace(s, 80, 60)) >= 100.0
    assert psnr(image, unfiltered) < 50.0
