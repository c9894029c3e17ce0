"""The moderngl renderer against the CPU reference tracer, and the physics it must show."""

import functools
import math

import numpy as np
import pytest

from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS, fit_rgb_coefficients
from optics.checks import flat_pool, flat_pool_colour, underwater_view
from optics.light.fresnel import N_AIR, N_WATER
from optics.rendering.reference import _shade_rays, psnr, psnr_against_reference, ray_directions, trace
from optics.rendering.renderer import EGL_PACKAGES, Renderer, RendererUnavailable, render_sequence, save_png, to_srgb8
from optics.rendering.scene import DEFAULT_ABSORPTION, Camera, Effects, Scene, look_at
from wavephys import Grid
from wavephys.app.scenes import SCENES, builtin_scene

W, H = 160, 120


@__import__("functools").lru_cache(maxsize=None)
@functools.lru_cache(maxsize=None)
def _scene(name, n=128, caustics=True):
    """A built-in scene, built once per test session (the storm builds 1.5 s of foam history; the shore at 128²
    was built four times): its arrays read-only, so no test can change another's."""
    scene = builtin_scene(name, n=n, caustics=caustics)
    for field in ("ground", "water", "albedo", "caustics", "foam"):
        value = getattr(scene, field, None)
        if isinstance(value, np.ndarray):
            value.flags.writeable = False
    return scene
EFFECTS = ("refraction", "reflection", "fresnel", "absorption", "caustics")


@pytest.fixture(scope="module")
def renderer():
    with Renderer(W, H) as r:  # a missing EGL is an error here, not a skip: CI installs it
        yield r


# Every built-in scene, all effects on, GPU against the reference (≥ 100 dB at 160×120): the
# registry's "builtin-scenes" rows, asserted by tests/app/test_registry.py; each effect off below.


def test_the_reference_allows_a_hundredth_of_a_pixel_at_edges_and_no_more():
    """psnr_against_reference, on waves beside a quay (edges) without a GPU: an image that
    takes the other side of an edge at three pixels (the reference a two-hundredth of a pixel off there) passes,
    where plain PSNR puts it below 90 dB; the whole image half a pixel off, or a two-hundredth of a pixel off (over
    a tenth of its pixels then move by more than 1e-4), or 3e-3 added to 2 % of the pixels where the colour hardly
    changes, fails; bad input is refused by name."""
    n, length = 32, 8.0
    x, y = np.meshgrid((np.arange(n) + 0.5) * length / n - length / 2, (np.arange(n) + 0.5) * length / n - length / 2)
    ground = np.where(x > 1.0, 0.4, -1.0 + 0.05 * y)  # a quay: its edge and its reflection are edges
    water = 0.05 * np.sin(2 * np.pi * (x + 0.5 * y) / 2.0)
    scene = Scene(ground, water, length, camera=look_at((-1.0, -6.0, 2.5), (0.5, 0.0, 0.0), 50.0))
    width, height = 32, 24

    def shifted(offset):
        d = ray_directions(scene.camera, width, height, offset).reshape(-1, 3)
        return _shade_rays(scene, d, height, 256, 10).reshape(height, width, 3).astype(np.float32)

    exact = trace(scene, width, height)
    assert psnr_against_reference(exact, scene) == (math.inf, 0)
    # a renderer that lands on the other side of an edge at three pixels, as float32 does: the reference itself a
    # two-hundredth of a pixel off there
    off = shifted((0.005, 0.0))
    change = np.abs(off - exact).max(-1).ravel()
    edge = np.argsort(change)[-3:]
    near = exact.copy().reshape(-1, 3)
    near[edge] = off.reshape(-1, 3)[edge]
    near = near.reshape(exact.shape)
    plain = psnr(near, exact)
    value, edges = psnr_against_reference(near, scene)
    assert plain < 90.0 and value >= 100.0 and edges == 3, (plain, value, edges)
    assert psnr_against_reference(shifted((0.5, 0.0)), scene)[0] < 60.0  # misplaced rays
    assert np.count_nonzero(change > 1e-4) > width * height // 10  # a two-hundredth of a pixel, everywhere:
    # over 1 % of the pixels, not an edge's few: only the worst 1 % get the shifted samples (measured 73 dB; 96 dB if
    # every pixel got them)
    assert psnr_against_reference(off, scene)[0] < 80.0
    smooth = np.argsort(change)[: width * height // 50]  # 2 % of the pixels, where the colour hardly changes
    worse = exact.copy().reshape(-1, 3)
    worse[smooth] += 3e-3
    assert psnr_against_reference(worse.reshape(exact.shape), scene)[0] < 100.0
    with pytest.raises(ValueError, match="shift"):
        psnr_against_reference(exact, scene, shift=0.0)
    with pytest.raises(ValueError, match="image"):
        psnr_against_reference(exact[..., :2], scene)
    with pytest.raises(TypeError, match="scene"):
        psnr_against_reference(exact, "dambreak")


@pytest.mark.parametrize("name", ["pool", "storm"])  # a walled pool and an open sea to the horizon
@pytest.mark.parametrize("off", EFFECTS + ("foam", "filtering"))  # filtering off: the unfiltered path
def test_gpu_matches_reference_with_each_effect_off(renderer, name, off):
    s = _scene(name, 64).with_effects(**{off: False})
    with Renderer(W // 2, H // 2) as small:
        assert psnr(small.render(s), trace(s, W // 2, H // 2)) >= 100.0


@pytest.mark.parametrize("form", ["schlick", "jensen_golias", "loviscach", "lut"])
def test_gpu_draws_every_fresnel_form_the_planner_can_choose(form):
    """The renderer draws each shader form of the Fresnel family (what a plan may choose),
    matching its CPU reference on the open sea (≥ 100 dB), and the form is visible."""
    s = _scene("storm", 64)
    drawn = s.with_effects(fresnel_form=form)
    with Renderer(W // 2, H // 2) as small:
        image = small.render(drawn)
        assert psnr(image, trace(drawn, W // 2, H // 2)) >= 100.0, form
        assert psnr(image, small.render(s)) < 100.0, form  # not the exact form's picture


def test_every_fresnel_form_of_the_family_has_glsl():
    """A form registered in optics' family must get its GLSL before scenes can draw it."""
    from optics.gpu import GLSL_FRESNEL_FORMS
    from optics.light.fresnel import REFLECTANCE_METHODS
    from optics.rendering import Effects

    assert set(GLSL_FRESNEL_FORMS) == set(REFLECTANCE_METHODS)
    with pytest.raises(ValueError, match="fresnel_form must be one of"):
        Effects(fresnel_form="fresnel")
    assert Effects(fresnel_form="lut").only("fresnel").fresnel_form == "lut"


@pytest.mark.parametrize("form", [m for m in WATER_TRANSMITTANCE_METHODS if m != "rgb"])
def test_gpu_draws_every_absorption_form_the_planner_can_choose(form):
    """The renderer draws each water-transmittance method a plan may choose (other than the scene's own
    RGB coefficients) through its table, matching the CPU reference, which calls the method itself
    (≥ 100 dB), in the pool (short paths) and a wide pool seen from below (long ones); and the form is
    visible."""

    pool = _scene("pool", 64)
    below = underwater_view(70.0).with_effects(absorption=True)  # a 40 m pool seen past Snell's window
    with Renderer(W // 2, H // 2) as small:
        for s in (pool, below):
            drawn = s.with_effects(absorption_form=form)
            image = small.render(drawn)
            assert psnr(image, trace(drawn, W // 2, H // 2)) >= 100.0, form
            assert psnr(image, small.render(s)) < 100.0, form  # not the RGB coefficients' picture


def test_every_absorption_form_of_the_family_can_be_drawn():
    """Every method of the water-transmittance family is an Effects choice (the RGB one by the scene's
    uniform, the others by their tables); a name outside the family is refused by name."""
    from optics.rendering import Effects

    for form in WATER_TRANSMITTANCE_METHODS:
        assert Effects(absorption_form=form).only("absorption").absorption_form == form
    with pytest.raises(ValueError, match="absorption_form must be one of"):
        Effects(absorption_form="beer")


@pytest.mark.slow
def test_each_effect_changes_the_pool(renderer):
    """Every switch does something measurable on the pool (so the PSNR tests compare real effects)."""
    s = _scene("pool", 128)
    full = renderer.render(s)
    for off in EFFECTS:
        assert psnr(renderer.render(s.with_effects(**{off: False})), full) < 60.0, off


def test_foam_is_drawn_alike_and_switches_off(renderer):
    """Foam (a coverage texture) whitens the surface identically on both paths, for several
    patterns and suns; foam=False gives the frame without it."""
    from dataclasses import replace

    base = _scene("storm", 128, False)
    rng = np.random.default_rng(4)
    with Renderer(W // 2, H // 2) as small:  # 4800 pixels, each foam texel under several: the CPU reference's time
        for sun in ((0.35, -0.45, 0.82), (-0.6, 0.2, 0.3)):
            foam = np.clip(rng.uniform(-1.0, 1.5, (32, 32)), 0, 1).astype(np.float32)
            s = replace(base, foam=foam, sun=sun)
            gpu = small.render(s)
            assert psnr(gpu, trace(s, W // 2, H // 2)) >= 100.0
            off = s.with_effects(foam=False)
            assert psnr(gpu, small.render(off)) < 40.0
            assert psnr(small.render(off), trace(off, W // 2, H // 2)) >= 100.0
    with pytest.raises(ValueError, match="foam"):
        replace(base, foam=np.full((8, 8), 1.5))


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_march_is_converged(renderer):
    """The GPU's 256 steps against a reference with 4× the steps, inside the square: on a smooth swell over the
    shore's sand to 100 dB; on the built-in shore (its swell shortening and steepening in the surf zone) all but
    the pixels that graze a crest thinner than a step — at most 4 of 19200 over 1/255 (measured 3 against this
    1024-step reference, 4 against 4096 steps; the reference's own 1024 steps miss 1: the test below)."""
    from dataclasses import replace

    shore = replace(_scene("shore", 128), surroundings="none")
    grid = Grid(128, 16.0)
    x, y = (np.asarray(a) for a in grid.mesh())
    swell = (0.05 * np.cos(2 * np.pi * 4 * x / 16.0) + 0.03 * np.cos(2 * np.pi * (5 * x + y) / 16.0 + 1.3))
    smooth = replace(shore, water=swell.astype(np.float32), caustics=None)
    assert psnr(renderer.render(smooth), trace(smooth, W, H, steps=1024)) >= 100.0
    reference = trace(shore, W, H, steps=1024)
    assert int((np.abs(renderer.render(shore) - reference).max(-1) > 1 / 255).sum()) <= 4


@pytest.mark.slow
def test_the_march_reference_is_converged_on_the_shore():
    """The reference of the test above: 4096 steps are within 1/255 of 16384 on every pixel of the built-in
    shore (measured 2.4e-5), and its 1024 steps differ from them only where a ray grazes a crest thinner than a
    step: 1 pixel of 19200 (measured 0.11 there; 0 before its swell was stepped with the exact-frequency
    leapfrog, which moved a crest)."""
    from dataclasses import replace

    shore = replace(_scene("shore", 128), surroundings="none")
    fine = trace(shore, W, H, steps=4096)
    assert np.abs(fine - trace(shore, W, H, steps=16384)).max() < 1 / 255
    assert int((np.abs(trace(shore, W, H, steps=1024) - fine).max(-1) > 1 / 255).sum()) <= 2


@pytest.mark.slow
def test_march_to_the_horizon_is_near_converged():
    """With surroundings the same 256 steps cover four scene sides from the eye (growing
    quadratically). Against 2048 steps, measured at 160×120: 56.8 dB (storm), 76.7 dB (pool); at
    80×60: 55.5 (storm), 110.4 (shore, its swell over the beach), 112.1 dB (pool). The
    storm's thin grazing crests keep it the least converged (RMS 0.17 % of white)."""
    for name, floor in (("storm", 50.0), ("shore", 60.0), ("pool", 60.0)):
        s = _scene(name, 128, False)
        assert psnr(trace(s, W // 2, H // 2), trace(s, W // 2, H // 2, steps=2048)) >= floor, name


def test_flat_pool_at_normal_view_has_the_analytic_colour(renderer):
    """Straight down on still water 1.5 m deep: R0·sky + (1 − R0)·ground·T(1.5 m)², with the
    ground lit by ambient·T + sun·(1 − R0)·T (T = e^{−a·1.5 m}, exact Fresnel R0)."""
    s = flat_pool()
    r0 = ((N_AIR - N_WATER) / (N_AIR + N_WATER)) ** 2
    t = np.exp(-1.5 * np.asarray(DEFAULT_ABSORPTION))
    ground = np.array([0.8, 0.7, 0.5]) * (0.1 * t + (1 - r0) * t)
    expected = r0 * np.array([0.3, 0.5, 0.9]) + (1 - r0) * ground * t  # written out here, independently
    np.testing.assert_allclose(flat_pool_colour(s), expected, rtol=1e-7)  # albedo is stored in float32
    centre = renderer.render(s)[H // 2 - 2:H // 2 + 2, W // 2 - 2:W // 2 + 2].reshape(-1, 3)
    np.testing.assert_allclose(centre, np.broadcast_to(expected, centre.shape), rtol=2e-4)
    np.testing.assert_allclose(trace(s, W, H)[H // 2, W // 2], expected, rtol=1e-5)


def test_default_absorption_is_the_spectral_fit():
    np.testing.assert_allclose(DEFAULT_ABSORPTION, fit_rgb_coefficients(), rtol=1e-3)


def test_total_internal_reflection_seen_from_below(renderer):
    """Under still water, looking up: inside Snell's window (48.6°) the red sky shows;
    past it the surface is a mirror of the green-blue floor and no red gets through."""
    critical = math.degrees(math.asin(N_AIR / N_WATER))
    for angle, sky_visible in ((0.0, True), (critical - 5.0, True), (critical + 5.0, False), (75.0, False)):
        s = underwater_view(angle)
        # the reference traces 15 × 11 pixels: its middle pixel is the camera's own axis (the full frame's
        # 19200 rays took 2 s a view for the one pixel read)
        for img in (renderer.render(s), trace(s, 15, 11)):
            middle = img[img.shape[0] // 2, img.shape[1] // 2]
            red = float(middle[0])
            if sky_visible:
                assert red > 0.5, (angle, red)
            else:
                assert red == 0.0, (angle, red)
                assert middle[1] > 0.05  # the floor, reflected


@pytest.mark.slow
def test_ship_wake_frame_shows_the_wake(renderer):
    """The wake region's mean image gradient against the same frame without the ship."""
    ship, calm = builtin_scene("ship", n=128), builtin_scene("ship", n=128, ship=False)
    d = ray_directions(ship.camera, W, H)
    eye = np.asarray(ship.camera.eye)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = -eye[2] / d[..., 2]
    x, y = eye[0] + t * d[..., 0], eye[1] + t * d[..., 1]
    xs = -5.0 + 2.0 * 1.0  # ship position at the scene's default time of 1 s
    behind = xs - x
    wake = (t > 0) & (behind > 1.0) & (behind < 15.0) & (np.abs(y) < behind * math.tan(math.radians(19.47)))

    def mean_gradient(img):
        lum = img @ np.array([0.2126, 0.7152, 0.0722])
        gy, gx = np.gradient(lum)
        return float(np.mean(np.hypot(gx, gy)[wake]))

    assert wake.sum() > 200
    # measured 2.75× at 160×120 (the calm frame's gradient is the sea floor seen through the water)
    assert mean_gradient(renderer.render(ship)) > 2.0 * mean_gradient(renderer.render(calm))


def test_nan_heights_are_refused():
    ground = np.full((16, 16), -1.0)
    water = np.zeros((16, 16))
    water[3, 4] = np.nan
    with pytest.raises(ValueError, match="water must be finite"):
        Scene(ground, water, 4.0)


@pytest.mark.parametrize("shape", [(0, 16), (1, 16), (16,)])
def test_texture_sizes_that_are_zero_are_refused(shape):
    with pytest.raises(ValueError, match="ground"):
        Scene(np.zeros(shape), 0.0, 4.0)


def test_texture_too_large_for_the_context(renderer):
    with pytest.raises(ValueError, match="larger than this context allows"):
        renderer.texture("water", np.zeros((2, renderer.max_texture_size + 1), np.float32))
    with pytest.raises(ValueError, match="largest texture"):
        Scene(np.zeros((2, 16385)), 0.0, 4.0)


def test_camera_inside_the_ground_is_refused():
    with pytest.raises(ValueError, match="camera eye .* inside the ground"):
        Scene(np.full((16, 16), 1.0), 0.0, 4.0, camera=look_at((0.0, 0.0, 0.5), (1.0, 1.0, 0.0)))


@pytest.mark.parametrize("kw,name", [(dict(length=0.0), "length"), (dict(sun=(0, 0, -1)), "sun"),
                                     (dict(n_water=0.9), "n_water"), (dict(absorption=(1, -1, 0)), "absorption"),
                                     (dict(albedo=np.zeros((4, 4))), "albedo"), (dict(water=math.nan), "water")])
def test_bad_scene_values_name_the_parameter(kw, name):
    args = dict(ground=np.full((8, 8), -1.0), water=0.0, length=4.0)
    args.update(kw)
    with pytest.raises(ValueError, match=name):
        Scene(**args)


def test_bad_camera():
    with pytest.raises(ValueError, match="fov"):
        Camera(fov=0.0)
    with pytest.raises(ValueError, match="target"):
        Camera(eye=(0, 0, 1), target=(0, 0, 1))


def test_no_gl_context_names_the_egl_packages(monkeypatch):
    import moderngl

    def broken(*a, **k):
        raise Exception("eglGetDisplay failed")

    monkeypatch.setattr(moderngl, "create_context", broken)
    with pytest.raises(RendererUnavailable, match=EGL_PACKAGES):
        Renderer(8, 8)


def test_bad_renderer_arguments():
    with pytest.raises(ValueError, match="width"):
        Renderer(0, 10)


@pytest.mark.slow
def test_render_sequence_writes_frames_with_progress(tmp_path, capsys):
    from wavephys.app.scenes import scene_frames

    with Renderer(48, 36) as r:
        paths = render_sequence(r, scene_frames("shore", 3, n=64), tmp_path, count=3)
    assert [p.name for p in paths] == ["frame_0000.png", "frame_0001.png", "frame_0002.png"]
    assert all(p.stat().st_size > 0 for p in paths)
    assert "3/3 frames" in capsys.readouterr().err


def test_png_is_srgb_encoded(tmp_path):
    from PIL import Image

    assert to_srgb8(np.array([0.0, 0.0031308, 0.5, 1.0, 2.0])).tolist() == [0, 10, 188, 255, 255]
    img = np.linspace(0, 1, 4 * 5 * 3).reshape(4, 5, 3)
    back = np.asarray(Image.open(save_png(img, tmp_path / "a.png")))
    assert back.shape == (4, 5, 3) and (back == to_srgb8(img)).all()


def test_effects_only():
    assert Effects().only("caustics") == Effects(False, False, False, False, True, False, filtering=False)
    with pytest.raises(ValueError, match="unknown effect"):
        Effects().only("bloom")


@pytest.mark.slow
def test_environment_map_matches_reference(renderer):
    """A smooth equirectangular environment (reflected sky) through the GPU and the reference."""
    h, w = 32, 64
    v, u = np.meshgrid(np.linspace(0, 1, h), np.linspace(0, 1, w), indexing="ij")
    env = np.stack([0.5 + 0.4 * np.cos(2 * np.pi * u), 0.6 * (1 - v), 0.3 + 0.5 * v * u], axis=-1)
    s = _scene("shore", 128)
    s = Scene(s.ground, s.water, s.length, s.camera, albedo=s.albedo, caustics=s.caustics, environment=env)
    img = renderer.render(s)
    assert psnr(img, trace(s, W, H)) >= 100.0
    assert psnr(img, renderer.render(_scene("shore", 128))) < 30.0  # the map is really used


def test_uniform_environment_equals_uniform_sky(renderer):
    """Looking down on the wake (every reflected ray goes up): a uniform map = a uniform sky."""
    s = builtin_scene("ship", n=64, camera=look_at((-4.0, 0.0, 6.0), (-4.0, 0.0, 0.0), 60.0))
    sky = Scene(s.ground, s.water, s.length, s.camera, sky_zenith=(0.4, 0.5, 0.6), sky_horizon=(0.4, 0.5, 0.6),
                sun_glow=0.0, albedo=s.albedo)
    env = Scene(s.ground, s.water, s.length, s.camera, environment=np.full((8, 16, 3), (0.4, 0.5, 0.6)),
                albedo=s.albedo)
    np.testing.assert_allclose(renderer.render(env), renderer.render(sky), atol=1e-6)


def test_video_without_imageio_keeps_the_frames(tmp_path, capsys, monkeypatch):
    import builtins

    real_import = builtins.__import__

    def no_imageio(name, *a, **k):
        if name.startswith("imageio"):
            raise ImportError("No module named 'imageio'")
        return real_import(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", no_imageio)
    from wavephys.app.scenes import scene_frames

    with Renderer(24, 18) as r:
        paths = render_sequence(r, scene_frames("ship", 2, n=64, caustics=False), tmp_path, count=2,
                                video="water.mp4", progress=False)
    assert len(paths) == 2 and "imageio-ffmpeg" in capsys.readouterr().err


def test_two_renderers_do_not_disturb_each_other(renderer):
    s = _scene("shore", 64, False)
    before = renderer.render(s)
    with Renderer(16, 12) as other:
        other.render(s)
    np.testing.assert_array_equal(renderer.render(s), before)  # its context is made current again


def test_height_fields_of_different_resolution(renderer):
    """Ground and water need not share a grid: a 48² water over a 128² dune field (emerging ground)."""
    g = np.linspace(-4, 4, 128)
    X, Y = np.meshgrid(g, g)
    ground = -1.0 + 0.8 * np.sin(0.9 * X) * np.cos(0.7 * Y) + 0.1 * X
    w = np.linspace(-4, 4, 48)
    WX, WY = np.meshgrid(w, w)
    water = 0.04 * np.cos(2.5 * WX + 1.5 * WY)
    s = Scene(ground, water, 8.0, look_at((-6.0, -5.0, 3.0), (0.0, 0.0, -0.5)))
    assert psnr(renderer.render(s), trace(s, W, H)) >= 100.0


class TestHorizon:
    """Frames that reach the horizon: tiled or extended surroundings, distance filtering, the analytic sky."""

    def test_sea_reaches_the_horizon_instead_of_a_backdrop(self, renderer):
        from dataclasses import replace

        from optics.rendering.reference import environment

        s = _scene("storm", 128, False)
        assert s.surroundings == "tile" and s.sky == "preetham"
        d = ray_directions(s.camera, W, H)
        backdrop = environment(s, d)  # what a ray that meets nothing shows
        below = d[..., 2] < -0.02  # clearly below the horizon
        for scene, expect_backdrop in ((s, False), (replace(s, surroundings="none"), True)):
            img = renderer.render(scene)
            same = np.all(np.abs(img - backdrop) < 1e-4, axis=-1) & below
            assert bool(same.any()) == expect_backdrop, (scene.surroundings, int(same.sum()))
            assert psnr(img, trace(scene, W, H)) >= 100.0

    def test_a_shore_extended_to_the_horizon_is_land_and_water_where_the_rays_meet_them(self):
        """A straight shore (dry for x > 0) extended past the square, seen obliquely: every ray past the
        marched region is sand or water as the ground is where it meets the water's level (its line
        converges to the horizon). Decided at the far point itself (a fixed distance from the eye), a wedge
        of rays got the other answer: 5 of these 248, a vertical edge down the beach scene's frame."""
        from optics.rendering.scene import FAR_TILES

        L, n = 16.0, 32
        X, _ = (np.asarray(a, np.float64) for a in Grid(n, L).mesh())
        ground = (-1.0 + 2.0 * (X + L / 2) / L).astype(np.float32)
        eye = (-3.0, -6.0, 1.5)
        s = Scene(ground, np.zeros((n, n), np.float32), L, look_at(eye, (12.0, 40.0, -2.0), 60.0),
                  surroundings="extend")
        img = trace(s, 120, 90)
        d = ray_directions(s.camera, 120, 90)
        t = -eye[2] / np.minimum(d[..., 2], -1e-9)  # where each ray meets the water's level, z = 0
        x = eye[0] + t * d[..., 0]
        far = (d[..., 2] < 0) & (t * np.hypot(d[..., 0], d[..., 1]) > 1.05 * FAR_TILES * L) & (np.abs(x) > 1.0)
        sand = img[..., 0] > img[..., 2]  # dry sand is yellow; water shows the blue sky
        assert far.sum() >= 200 and np.array_equal(sand[far], x[far] > 0), int((sand[far] != (x[far] > 0)).sum())

    @pytest.mark.slow
    @pytest.mark.parametrize("sun", [(0.35, -0.45, 0.82), (0.9, 0.1, 0.15), (-0.2, 0.6, 0.4)])
    def test_horizon_modes_match_the_reference_for_any_sun(self, sun):
        from dataclasses import replace

        with Renderer(W // 2, H // 2) as small:
            for name, mode in (("shore", "tile"), ("pool", "extend")):
                s = replace(_scene(name, 128, False), sun=sun, surroundings=mode,
                            turbidity=2.0 + 3 * abs(sun[0]))
                assert psnr(small.render(s), trace(s, W // 2, H // 2)) >= 100.0

    def test_tiled_water_wraps_and_fades_with_distance(self):
        from dataclasses import replace

        from optics.rendering.reference import water_level
        from optics.rendering.scene import FAR_TILES, NEAR_TILES

        s = _scene("shore", 64, False)
        L, eye = s.length, np.asarray(s.camera.eye)
        rng = np.random.default_rng(2)
        xy = eye[:2] + rng.uniform(-0.5, 0.5, (200, 2)) * L * NEAR_TILES
        np.testing.assert_allclose(water_level(s, xy), water_level(s, xy + [L, -2 * L]) * 0 + water_level(
            s, np.mod(xy + L / 2, L) - L / 2), atol=1e-9)  # periodic inside the near radius
        far = eye[:2] + np.stack([np.cos(a := rng.uniform(0, 6.3, 50)), np.sin(a)], 1) * L * (FAR_TILES + 0.1)
        np.testing.assert_allclose(water_level(s, far), float(np.mean(s.water, dtype=np.float64)), atol=1e-9)
        clamp = replace(s, surroundings="none")
        inside = rng.uniform(-0.4, 0.4, (100, 2)) * L + eye[:2] * 0
        near = np.hypot(*(inside - eye[:2]).T) < NEAR_TILES * L
        np.testing.assert_allclose(water_level(s, inside)[near], water_level(clamp, inside)[near], atol=1e-6)


def test_preetham_sky_properties():
    from optics.light.sky import preetham_sky

    sun = np.array([0.3, -0.2, 0.6])
    sun = sun / np.linalg.norm(sun)
    zen = preetham_sky(np.array([0.0, 0.0, 1.0]), sun, 3.0, 0.45)
    xyz_y = 0.2126 * zen[0] + 0.7152 * zen[1] + 0.0722 * zen[2]  # linear sRGB luminance
    assert xyz_y == pytest.approx(0.45, rel=2e-3)
    assert zen[2] > zen[1] > zen[0]  # blue overhead
    rng = np.random.default_rng(0)
    d = rng.normal(size=(2000, 3))
    d[:, 2] = np.abs(d[:, 2])
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    mirror = d.copy()  # reflect about the plane through the sun's azimuth and the zenith
    a = np.arctan2(sun[1], sun[0])
    u = np.array([np.cos(a), np.sin(a), 0.0])
    v = np.array([-np.sin(a), np.cos(a), 0.0])
    mirror -= 2 * (d @ v)[:, None] * v
    np.testing.assert_allclose(preetham_sky(d, sun), preetham_sky(mirror, sun), rtol=1e-10)
    near = preetham_sky(sun * 0.999 + np.array([0, 0, 0.001]), sun).sum()
    away = preetham_sky(np.array([-u[0], -u[1], 0.3]) / np.linalg.norm([u[0], u[1], 0.3]), sun).sum()
    assert near > 2 * away
    ratio = lambda t: (preetham_sky(np.array([-u[0], -u[1], 0.05]), sun, t).sum()
                       / preetham_sky(np.array([0.0, 0.0, 1.0]), sun, t).sum())
    assert ratio(2.0) > 1.5 > ratio(8.0)  # a clear sky brightens toward the horizon; a hazy one far less
    with pytest.raises(ValueError, match="turbidity"):
        preetham_sky(d, sun, 20.0)
    with pytest.raises(ValueError, match="sun"):
        preetham_sky(d, (0.0, 0.0, -1.0))
