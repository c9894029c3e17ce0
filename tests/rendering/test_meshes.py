"""The mesh path (optics.rendering.meshes): the water as a displaced mesh, laid three ways, against
the ray-marcher's exact surface, over generated seas."""

import math
from dataclasses import replace

import numpy as np
import pytest

from optics.rendering.meshes import (BANDS, MAX_VERTICES, WaterMesh, clipmap_mesh, displaced_mesh, height_errors,
                                     mesh_coverage,
                                     mesh_errors, mesh_heights, mesh_region, mesh_seconds, projected_grid,
                                     render_mesh,
                                     uniform_mesh, water_mesh, water_pixels)
from optics.rendering.renderer import Renderer
from optics.rendering.scene import Camera, Scene, look_at

W, H = 64, 48
N, L = 64, 16.0


def _sea(seed, amp=0.08, surroundings="none", eye=(0.0, -9.0, 3.0), up=(0.0, 0.0, 1.0), n=N):
    """Six plane waves of random direction, wavelength L/1 to L/5 and phase (a family per seed)."""
    rng = np.random.default_rng(seed)
    x = (np.arange(n) + 0.5) * L / n - L / 2
    X, Y = np.meshgrid(x, x)
    h = np.zeros((n, n))
    for _ in range(6):
        k = 2 * np.pi / L * rng.integers(1, 6, 2) * rng.choice([-1, 1], 2)
        h += amp / 6 * np.cos(k[0] * X + k[1] * Y + rng.uniform(0, 2 * np.pi))
    cam = look_at(eye, (0.0, 0.0, 0.0), 50.0)
    return Scene(np.full((n, n), -2.0), h.astype(np.float32), L, camera=Camera(cam.eye, cam.target, up, cam.fov),
                 surroundings=surroundings)


@pytest.fixture(scope="module")
def renderer():
    with Renderer(W, H) as r:
        yield r


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_a_uniform_mesh_converges_to_the_exact_surface_at_second_order(seed):
    """Linear triangles over the bilinear texture: the height error falls 4x per halving of the
    spacing (the bilinear twist over a cell shrinks with its area), in every band."""
    scene = _sea(seed)
    texel = L / N
    errs = [[b["max"] for b in height_errors(scene, uniform_mesh(scene, texel / 2**k)) if b["points"]]
            for k in range(3)]
    for coarse, fine in zip(errs, errs[1:]):
        for a, b in zip(coarse, fine):
            assert 3.6 < a / b < 4.4, (a, b)
    assert max(errs[0]) < 0.05 * 0.08  # at texel spacing the mesh is within 5 % of the waves' amplitude


def test_the_mesh_path_draws_what_the_march_draws_as_the_mesh_refines(renderer):
    scene = _sea(3)
    psnrs = []
    for k in range(3):
        res = mesh_errors(scene, uniform_mesh(scene, L / N / 2**k), W, H, renderer=renderer, repeats=1,
                          heights=False)
        psnrs.append(res["psnr"])
        assert res["bare"] == 0
    assert psnrs[0] > 80 and psnrs[1] > psnrs[0] + 8 and psnrs[2] > psnrs[1] + 8, psnrs


def _edges(tris):
    e = np.sort(np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]]), axis=1)
    _, counts = np.unique(e, axis=0, return_counts=True)
    return counts


@pytest.mark.parametrize("cells, levels", [(4, 3), (8, 2), (16, 4)])
def test_clipmap_rings_are_watertight_and_tile_the_region(cells, levels):
    """Every edge inside the rings is shared by two triangles (the zero-area triangles close each
    ring's T-junctions), the rest is the outer square's border, and the triangles' area is the rings'."""
    scene = _sea(0)
    mesh = clipmap_mesh(scene, 0.5, cells=cells, levels=levels)
    counts = _edges(mesh.triangles.astype(np.int64))
    outer = 2 * cells * 4  # the last level's border: 2·cells edges a side
    assert np.all(counts <= 2) and int(np.sum(counts == 1)) == outer
    p = mesh.positions[mesh.triangles].astype(np.float64)
    a, b = p[:, 1] - p[:, 0], p[:, 2] - p[:, 0]
    signed = 0.5 * (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    side = 2 * cells * 0.5 * 2 ** (levels - 1)
    assert signed.sum() == pytest.approx(side**2, rel=1e-9)
    assert np.all(signed >= 0)  # counter-clockwise from above, none overlapping


def _coarse_surface(scene, xy, s):
    """The linear surface on the lattice of spacing s through a texel centre (cells cut along their
    (i, j)-(i+1, j+1) diagonal) at points xy: written here from the lattice alone."""
    from optics.rendering.reference import water_level

    origin = -0.5 * scene.length + 0.5 * scene.length / N
    u, v = (xy[:, 0] - origin) / s, (xy[:, 1] - origin) / s
    i, j = np.floor(u), np.floor(v)
    fu, fv = u - i, v - j
    corner = lambda di, dj: water_level(scene, np.stack([origin + (i + di) * s, origin + (j + dj) * s], -1))
    h00, h11 = corner(0, 0), corner(1, 1)
    below = fu >= fv  # the triangle (i, j), (i+1, j), (i+1, j+1)
    return np.where(below, h00 + fu * (corner(1, 0) - h00) + fv * (h11 - corner(1, 0)),
                    h00 + fv * (corner(0, 1) - h00) + fu * (h11 - corner(0, 1)))


@pytest.mark.parametrize("seed", [1, 2])
def test_clipmap_levels_meet_on_the_coarser_surface(seed):
    """At level 0's outer edge every vertex lies on level 1's surface (blend 1), the linear surface of
    the lattice twice as coarse (computed here from that lattice, not from the mesh's parents); inside
    the band the height is between its own and that surface's."""
    scene = _sea(seed)
    s0 = L / N
    mesh = clipmap_mesh(scene, s0, cells=8, levels=3)
    z = mesh_heights(scene, mesh)
    xy = mesh.positions.astype(np.float64)
    ring0 = mesh.morph == 1
    centre = xy[ring0 & (np.abs(xy - xy[ring0].mean(axis=0)).max(axis=1) < 8 * s0 * 1.01)].mean(axis=0)
    level0 = np.abs(np.abs(xy - centre).max(axis=1) - 8 * s0) < 1e-9  # level 0's edge, 2·cells cells a side
    assert level0.sum() == 4 * 16
    assert np.allclose(z[level0], _coarse_surface(scene, xy[level0], 2 * s0), rtol=0, atol=1e-12)
    from optics.rendering.reference import water_level

    mid = (mesh.morph > 0) & (mesh.morph < 1)
    inner = mid & (np.abs(xy - centre).max(axis=1) < 8 * s0)  # level 0's band
    own, coarse = water_level(scene, xy[inner]), _coarse_surface(scene, xy[inner], 2 * s0)
    w = mesh.morph[inner]
    assert inner.sum() > 0 and np.allclose(z[inner], own + w * (coarse - own), rtol=0, atol=1e-12)


def test_land_in_front_of_the_water_hides_it_as_in_the_march(renderer):
    """A bank rising out of the water between the eye and the sea: the background pass's depth hides
    the mesh behind it as the march does, and the heights are measured only where water stands."""
    scene = _sea(7)
    y = (np.arange(N) + 0.5) * L / N - L / 2
    ground = np.where((y > -3.0) & (y < -1.0), 0.6, -2.0)[:, None] * np.ones((1, N))
    bank = Scene(ground.astype(np.float32), scene.water, L, camera=scene.camera)
    res = mesh_errors(bank, uniform_mesh(bank, L / N / 4), W, H, renderer=renderer, repeats=1)
    assert res["psnr"] > 90 and res["bare"] == 0
    plain = height_errors(scene, uniform_mesh(scene, L / N))
    banked = height_errors(bank, uniform_mesh(bank, L / N))
    assert sum(b["points"] for b in banked) < sum(b["points"] for b in plain)


def test_a_released_renderer_is_named():
    scene = _sea(0)
    mesh = uniform_mesh(scene)
    r = Renderer(16, 12)
    r.release()
    for call in (lambda: render_mesh(r, scene, mesh), lambda: mesh_coverage(r, scene, mesh),
                 lambda: mesh_seconds(r, scene, mesh, 1)):
        with pytest.raises(RuntimeError, match="released"):
            call()


def test_a_clipmap_draws_its_finest_level_as_a_uniform_mesh_does():
    """Inside level 0, away from its blended band, a clipmap is a uniform mesh of its finest spacing."""
    scene = _sea(2)
    s = L / N
    clip = height_errors(scene, clipmap_mesh(scene, s, cells=64), bands=(0.0, 2.0))
    uni = height_errors(scene, uniform_mesh(scene, s), bands=(0.0, 2.0))
    assert clip[0]["max"] == pytest.approx(uni[0]["max"], rel=1e-6)


def test_the_projected_grid_spreads_its_rows_as_r_squared_over_h():
    """Johanson's grid from an eye H above the water: a row step of δ rad lands δ·r²/H apart along
    the view at r ≫ H (shared/SPEC.md §2.8), measured on the grid's centre column."""
    eye_h = 3.0
    scene = _sea(0, surroundings="tile", eye=(0.0, -20.0, eye_h))
    rows, margin = 256, 0.0
    mesh = projected_grid(scene, 2, rows, aspect=W / H, margin=margin)
    cam = scene.camera
    f, _, _ = cam.basis()
    tan_half = math.tan(math.radians(cam.fov) / 2)
    col = np.array([p for p in mesh.positions.astype(np.float64) if abs(p[0] - cam.eye[0]) < 1e-3])
    r = np.sort(np.hypot(col[:, 0] - cam.eye[0], col[:, 1] - cam.eye[1]))
    r = r[r < mesh_region(scene)[2] * 0.999]
    mid, dr = 0.5 * (r[1:] + r[:-1]), np.diff(r)
    sy = np.arange(rows + 1) * 2 / rows - 1  # the rows' screen heights; the angle per row at height sy:
    # dθ = tan_half·(2/rows)/(1 + (sy·tan_half)²); the grid has no roll, so each row is one distance
    angles = np.arctan(sy * tan_half) + math.asin(-f[2])
    delta = np.diff(angles)
    below = np.sin(0.5 * (angles[1:] + angles[:-1])) > 0  # rows that see the water
    far = mid > 5 * eye_h
    got = dr[far]
    want = (delta[below][::-1][:len(dr)] * mid**2 / eye_h)[far]
    assert np.allclose(got, want, rtol=0.06), np.max(np.abs(got / want - 1))


def _crests_across(wavelength, amp, eye_h, n=256, side=64.0):
    """One wave of length λ tiled to the horizon, its crests across the view of an eye eye_h above it."""
    x = (np.arange(n) + 0.5) * side / n - side / 2
    _, Y = np.meshgrid(x, x)
    water = (amp * np.cos(2 * np.pi * Y / wavelength)).astype(np.float32)
    return Scene(np.full((n, n), -5.0), water, side, camera=look_at((0.0, 0.0, eye_h), (0.0, 30.0, 0.0), 50.0),
                 surroundings="tile")


@pytest.mark.parametrize("wavelength, rows", [(4.0, 120), (8.0, 120), (4.0, 240)])
def test_the_projected_grid_fails_where_its_rows_pass_half_a_wavelength(wavelength, rows):
    """Grazing views: crests across the view, a wave of length λ is sampled below its Nyquist rate where the
    grid's rows are more than λ/2 apart, δ·r²/H > λ/2, past r_max = √(λH/2δ). Inside 0.4 r_max the mesh
    holds the wave within a tenth of its amplitude; from 1.1 to 2 r_max its RMS error is over 0.4 of it
    (measured 0.66-0.80 for λ = 4 m, 120 rows). The boundary moves with √λ and √rows as the law says."""
    amp, eye_h = 0.1, 3.0
    scene = _crests_across(wavelength, amp, eye_h)
    delta = 2 * math.tan(math.radians(25)) / rows  # rad a row at the screen's centre
    r_max = math.sqrt(wavelength * eye_h / (2 * delta))
    near, beyond = height_errors(scene, projected_grid(scene, 32, rows, aspect=4 / 3, margin=0.0),
                                 bands=(0.0, 0.4 * r_max / eye_h, 1.1 * r_max / eye_h, 2 * r_max / eye_h))[::2]
    assert near["points"] > 1000 and near["max"] < 0.1 * amp
    assert beyond["points"] > 1000 and beyond["rms"] > 0.4 * amp


@pytest.mark.parametrize("wavelength, cells", [(4.0, 8), (4.0, 16), (8.0, 8), (2.0, 16)])
def test_a_clipmap_holds_a_wave_out_to_cells_times_half_its_length(wavelength, cells):
    """Level k of a clipmap of m cells has spacing s₀2ᵏ and reaches m·s₀2ᵏ: the last level that samples a
    wave of length λ at least twice a wavelength (spacing λ/2) ends at r_b = m·λ/2, and past it the wave
    is missed. Measured: RMS 0.07-0.25 of the amplitude inside 0.75 r_b, 0.86-1.14 from r_b to 2 r_b."""
    amp, eye_h = 0.1, 3.0
    scene = _crests_across(wavelength, amp, eye_h)
    r_b = cells * wavelength / 2
    inside, _, beyond = height_errors(scene, clipmap_mesh(scene, cells=cells),
                                      bands=(0.0, 0.75 * r_b / eye_h, r_b / eye_h, 2 * r_b / eye_h))
    assert inside["points"] > 500 and inside["rms"] < 0.3 * amp
    assert beyond["points"] > 500 and beyond["rms"] > 0.8 * amp


def test_high_waves_near_the_eye_leave_the_projected_grid_short_of_the_screen(renderer):
    """The grid is laid on the mean level and lifted by the waves: crests near the eye lift its
    nearest rows off the screen's bottom edge, which stays bare; a margin of screen around the grid
    covers it. Calm water is covered with no margin."""
    eye = (0.0, -9.0, 1.2)
    calm, rough = (_sea(4, amp=a, eye=eye, surroundings="tile") for a in (0.02, 0.9))

    def bare(scene, margin):
        seen = water_pixels(scene, W, H)
        return seen & ~mesh_coverage(renderer, scene, projected_grid(scene, 64, 64, aspect=W / H, margin=margin))

    assert bare(calm, 0.0).sum() == 0
    assert bare(rough, 0.0)[-1].sum() > W // 4  # the bottom row
    assert bare(rough, 1.0).sum() == 0


def test_a_rolled_camera_is_still_covered_by_the_projected_grid(renderer):
    """Camera roll (a tilted up vector): the screen's grid turns with it and still meets the water."""
    scene = _sea(5, amp=0.02, up=(0.5, 0.0, 1.0))
    res = mesh_errors(scene, projected_grid(scene, 64, 96, aspect=W / H), W, H, renderer=renderer, repeats=1,
                      heights=False)
    assert res["bare"] == 0 and res["psnr"] > 60


def test_the_mesh_image_changes_where_the_mesh_is_coarse(renderer):
    """A coarse clipmap and a coarse projected grid are measurably off where they are coarse."""
    scene = _sea(6, surroundings="tile")
    img = render_mesh(renderer, scene, clipmap_mesh(scene, 2.0, cells=4))
    assert img.shape == (H, W, 3) and np.isfinite(img).all()
    res = mesh_errors(scene, clipmap_mesh(scene, 2.0, cells=4), W, H, renderer=renderer, repeats=1)
    assert res["psnr"] < 60 and max(b["height_max"] for b in res["bands"] if b["water"]) > 0.01
    mesh = clipmap_mesh(scene, 2.0, cells=4)
    assert res["passes"] == 2 and res["texel_reads"] == 4 * (mesh.vertices + 2 * int((mesh.morph > 0).sum()))


def _choppy(seed, choppiness=0.6):
    """A choppy sea on the texels: rest heights z, displacement Δ, and the scene of the resampled heights."""
    import jax.numpy as jnp

    from wavephys import Grid
    from wavephys.surfaces.choppy import displacement
    from wavephys.surfaces.resample import resample_heights

    z = _sea(seed, amp=0.5).water.astype(np.float64)
    grid = Grid(N, L)
    d = np.asarray(displacement(jnp.asarray(z), grid, choppiness), np.float64)
    h = np.asarray(resample_heights(d, z, grid), np.float32)
    return z, d, Scene(np.full((N, N), -2.0), h, L, camera=_sea(seed).camera, surroundings="tile")


@pytest.mark.parametrize("seed", [0, 1])
def test_a_displaced_mesh_puts_each_vertex_where_its_rest_point_went(seed):
    """An engine's choppy vertex: rest point p moved to p + Δ(p) at height z(p). Drawn over the resampled
    heights, each moved vertex takes the height there, z(p) up to the resampling's error; moved the wrong
    way (p − Δ) it would not. As the spacing halves, the surface's error falls."""
    z, d, scene = _choppy(seed)
    mesh = displaced_mesh(scene, uniform_mesh(scene, L / N), d)
    rest = uniform_mesh(scene, L / N)
    inside = np.all(np.abs(rest.positions) < L / 2, axis=1)  # rest points on texel centres inside the square
    ij = np.rint((rest.positions[inside].astype(np.float64) + L / 2) / (L / N) - 0.5).astype(int)
    zi = z[ij[:, 1], ij[:, 0]]  # the rest heights z(p)
    span = float(z.max() - z.min())

    def rms(m):
        return float(np.sqrt(np.mean((mesh_heights(scene, m)[inside] - zi) ** 2)))

    assert rms(mesh) < 0.01 * span  # measured 0.41-0.52 % (the texture's bilinear reading of steep crests)
    assert rms(displaced_mesh(scene, rest, -d)) > 5 * rms(mesh)  # measured ×15-18
    square = replace(scene, surroundings="none")  # the convergence on the square alone (a small mesh)
    errs = [max(b["max"] for b in height_errors(square, displaced_mesh(square, uniform_mesh(square, L / N / 2**k), d))
                if b["points"]) for k in range(3)]
    # slow at first: moved vertices straddle the bilinear texture's texel edges (measured on the square, seeds 0-3:
    # ×1.59-1.80 the first halving, ×1.75-2.38 the second, ×3.05-4.29 over both)
    assert errs[0] / errs[1] > 1.4 and errs[1] / errs[2] > 1.4 and errs[0] / errs[2] > 2.7, errs
    # tiled: a rest point and its copy a side away move alike; past FAR_TILES sides (faded out) nothing moves,
    # even for a displacement whose mean is not 0
    rest_xy = rest.positions.astype(np.float64)
    move = mesh.positions.astype(np.float64) - rest_xy
    j = np.nonzero(np.all(np.abs(rest_xy) < L / 4, axis=1))[0][:50]
    far = displaced_mesh(scene, WaterMesh(np.concatenate([rest_xy[j], rest_xy[j] + (L, 0.0),
                                                           scene.camera.eye[:2] + np.array([[5 * L, 0.0]])]),
                                          np.zeros((2 * len(j) + 1, 4)), np.zeros(2 * len(j) + 1),
                                          np.zeros((0, 3), np.uint32), "uniform", 1.0), d + 0.3)
    shift = far.positions.astype(np.float64) - np.concatenate([rest_xy[j], rest_xy[j] + (L, 0.0),
                                                              scene.camera.eye[:2] + np.array([[5 * L, 0.0]])])
    assert np.allclose(shift[:len(j)], move[j] + 0.3, atol=1e-5)  # within 1.5 sides of the eye: unfaded
    assert np.allclose(shift[:len(j)], shift[len(j):2 * len(j)], atol=1e-5)
    assert np.allclose(shift[-1], 0.0, atol=1e-6)


def test_bad_input_is_refused_by_name():
    scene = _sea(0)
    for call, word in ((lambda: uniform_mesh(scene, 0.0), "spacing"),
                       (lambda: uniform_mesh(scene, 1e-5), "MAX_VERTICES"),
                       (lambda: clipmap_mesh(scene, cells=5), "cells"),
                       (lambda: clipmap_mesh(scene, band=0.5), "band"),
                       (lambda: clipmap_mesh(scene, levels=0), "levels"),
                       (lambda: projected_grid(scene, 0), "columns"),
                       (lambda: projected_grid(scene, aspect=-1.0), "aspect"),
                       (lambda: water_mesh(scene, "octree"), "technique"),
                       (lambda: mesh_errors(scene, uniform_mesh(scene), bands=(4.0, 1.0)), "bands"),
                       (lambda: projected_grid(_sea(0, eye=(0.0, -9.0, -1.0))), "below")):
        with pytest.raises(ValueError, match=word):
            call()
    with pytest.raises(TypeError, match="technique"):
        water_mesh(scene, 3)
    with pytest.raises(ValueError, match="displacement"):
        displaced_mesh(scene, uniform_mesh(scene), np.zeros((2, 8, 8)))
    with pytest.raises(ValueError, match="displacement"):
        displaced_mesh(scene, uniform_mesh(scene), np.full((2, N, N), np.nan))
    with pytest.raises(TypeError, match="mesh"):
        mesh_heights(scene, "mesh")
    assert MAX_VERTICES == 1 << 24 and BANDS[0] == 0.0
    assert isinstance(uniform_mesh(scene), WaterMesh)


def test_the_docs_table_recommends_only_what_held_on_every_scene_with_water_there():
    """bench/meshes.py's recommendations from synthetic rows: the fewest vertices that met the budget with no bare
    pixel on every scene with water in the band; a setting measured on one scene of two (the choppy ones), or
    with a bare pixel, is never recommended; a band without water is left out."""
    from bench.meshes import recommendations

    def row(scene, setting, vertices, psnr, water=100, bare=0, band=(0.0, 4.0), choppy=False):
        return dict(scene=scene, technique="t", setting=setting, vertices=vertices, psnr=psnr, water=water, bare=bare,
                    band=band, choppy=choppy)

    rows = [row("a", "small", 10, 45.0), row("b", "small", 10, 39.0),      # fails 40 dB on b
            row("a", "mid", 100, 45.0), row("b", "mid", 100, 41.0),        # holds 40 on both
            row("a", "tiny", 1, 70.0, bare=3), row("b", "tiny", 1, 70.0),  # bare on a
            row("a", "choppy", 2, 80.0, choppy=True),                      # choppy: reported, not recommended
            row("a", "partial", 5, 90.0),                                   # measured on a alone
            row("a", "mid", 100, 20.0, water=0, band=(4.0, 16.0)), row("b", "mid", 100, 20.0, water=0, band=(4.0, 16.0))]
    recs = {(tuple(r["band"]), r["budget"]): r for r in recommendations(rows, budgets=(40.0, 50.0))}
    assert set(recs) == {((0.0, 4.0), 40.0), ((0.0, 4.0), 50.0)}
    assert recs[(0.0, 4.0), 40.0]["setting"] == "mid" and recs[(0.0, 4.0), 40.0]["worst_psnr"] == 41.0
    assert recs[(0.0, 4.0), 50.0]["setting"] is None
