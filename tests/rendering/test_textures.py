import json

import numpy as np
import pytest

from optics.rendering.textures import (absorption_texture, decode_height, encode_height, fresnel_texture, height_precision,
                             load_npz, normal_map, save_height_png, save_npz)
from wavephys import Grid

GRID = Grid(256, 64.0)


def _swell():
    x, y = (np.asarray(a) for a in GRID.mesh())
    return 0.5 * np.cos(2 * np.pi * 2 * x / 64) + 0.3 * np.sin(2 * np.pi * 3 * (x + y) / 64)


def test_round_trip_within_half_a_quantum():
    eta = _swell()
    for bits in (8, 16):
        tex = encode_height(eta, GRID, bits)
        quantum = tex.amplitude / (2**bits - 1)
        assert np.max(np.abs(decode_height(tex) - eta)) <= 0.5 * quantum + 1e-12
    assert np.array_equal(decode_height(encode_height(eta, GRID, 32)), eta.astype(np.float32))


def _gentle_swell(texels_per_wavelength):
    """A 5 cm swell (kA ≤ 0.08) of two trains, the longer with the given texels per wavelength."""
    x, y = (np.asarray(a) for a in GRID.mesh())
    m = 256 // texels_per_wavelength
    return 0.05 * np.cos(2 * np.pi * m * x / 64) + 0.03 * np.sin(2 * np.pi * m * (x + y) / 64)


def test_eight_bits_make_stair_steps_sixteen_do_not():
    """A long swell (128 texels per wavelength): 8-bit curvature is wrong by more than its own size."""
    e8, e16 = height_precision(_swell(), GRID, 8), height_precision(_swell(), GRID, 16)
    assert e8["curvature"] > 1.0
    assert e16["curvature"] < e8["curvature"] / 100 and e16["slope"] < 1e-3 and e16["height"] < 2e-5


def test_sixteen_bits_within_a_thousandth_on_curvature():
    """A gentle swell of 16 texels per wavelength: 16-bit normalized curvature within 0.1 %
    (RMS and worst texel), 8-bit 100× worse, float32 at rounding."""
    eta = _gentle_swell(16)
    e8, e16, e32 = (height_precision(eta, GRID, b, norm="rms") for b in (8, 16, 32))
    assert e16["curvature"] < 1e-3 and height_precision(eta, GRID, 16)["curvature"] < 1e-3
    assert e8["curvature"] > 100 * e16["curvature"]
    assert e32["curvature"] < 1e-5


def test_sixteen_bit_curvature_boundary():
    """The failure boundary: the relative curvature error grows as (λ/Δx)², so 16 bits
    miss 0.1 % beyond about 20 texels per wavelength (float32 does not)."""
    errs = {t: height_precision(_gentle_swell(t), GRID, 16, norm="rms")["curvature"] for t in (8, 16, 32, 64)}
    assert errs[32] > 1e-3 and errs[64] > 1e-3 and errs[16] < 1e-3
    assert 3.0 < errs[64] / errs[32] < 5.0  # ×4 per doubling of the wavelength
    assert height_precision(_gentle_swell(64), GRID, 32, norm="rms")["curvature"] < 1e-4


def test_normals_are_unit_and_flat_is_up():
    nrm = normal_map(_swell(), GRID)
    np.testing.assert_allclose(np.linalg.norm(nrm, axis=-1), 1.0, atol=1e-6)
    np.testing.assert_allclose(normal_map(np.zeros((256, 256)), GRID)[..., 2], 1.0)


def test_files_carry_what_decoding_needs(tmp_path):
    eta = _swell()
    tex = encode_height(eta, GRID, 16)
    png = save_height_png(tex, tmp_path / "h.png")
    meta = json.loads(png.with_suffix(".json").read_text())
    from PIL import Image

    data = np.flipud(np.asarray(Image.open(png)))
    back = meta["offset"] + meta["amplitude"] * data / (2 ** meta["bits"] - 1)
    np.testing.assert_allclose(back, decode_height(tex), atol=1e-12)
    path = save_npz(tmp_path / "t.npz", height=tex, normals=normal_map(eta, GRID))
    loaded = load_npz(path)
    np.testing.assert_allclose(loaded["height"], decode_height(tex))
    assert loaded["normals"].shape == (256, 256, 3)


def test_lookup_textures():
    f = fresnel_texture(64)
    assert f.shape == (64,) and f[0] == pytest.approx(1.0) and f[-1] == pytest.approx(0.02033, abs=1e-4)
    a = absorption_texture(20.0, 32)
    assert a.shape == (32, 3) and np.all(a[0] == 1.0) and a[-1, 0] == 0.0
    assert a.max() <= 1.0 and np.all(np.diff(a, axis=0) <= 0)  # a transmittance: never above 1, falling


def test_exported_files_describe_themselves(tmp_path):
    """Units, axes and conventions travel with every exported file."""
    from optics.checks import flat_pool
    from optics.rendering.textures import CAUSTICS_UNITS, GRID_CONVENTION, NORMAL_CONVENTION, export_scene
    from dataclasses import replace

    scene = flat_pool()
    scene = replace(scene, caustics=np.full(np.shape(scene.water) if np.ndim(scene.water) == 2 else (2, 2), 1.0))
    paths = export_scene(scene, tmp_path / "out")
    sidecar = lambda name: json.loads((tmp_path / "out" / name).read_text())
    assert sidecar("water_height.json")["units"] == "m" and sidecar("water_height.json")["grid"] == GRID_CONVENTION
    assert sidecar("caustics.json")["units"] == CAUSTICS_UNITS
    assert sidecar("water_normals.json")["convention"] == NORMAL_CONVENTION and "green" in NORMAL_CONVENTION
    assert "cos(theta)" in sidecar("fresnel.json")["axes"][0]
    assert len(sidecar("absorption.json")["axes"]) == 2
    assert np.load(paths["absorption"]).max() <= 1.0


@pytest.mark.parametrize("bits", [4, 12])
def test_bad_bits(bits):
    with pytest.raises(ValueError, match="bits"):
        encode_height(_swell(), GRID, bits)


def test_bad_height():
    bad = _swell()
    bad[3, 3] = np.nan
    with pytest.raises(ValueError, match="eta"):
        encode_height(bad, GRID)
    with pytest.raises(ValueError, match="eta"):
        encode_height(np.zeros((8, 8)), GRID)


class TestOpenEXR:
    """Float textures for pipelines: OpenEXR, read back by our loader and by OpenImageIO's oiiotool
    (an independent reader; .ci/run installs it), units and conventions in the header."""

    @pytest.fixture(scope="class")
    def exported(self, tmp_path_factory):
        from wavephys.app.scenes import builtin_scene
        from optics.rendering.textures import export_scene

        scene = builtin_scene("pool", n=64)
        out = tmp_path_factory.mktemp("exr")
        return scene, export_scene(scene, out / "full"), export_scene(scene, out / "half", half=True)

    def test_round_trip_full_and_half_float(self, exported):
        from optics.rendering.textures import load_exr

        scene, full, half = exported
        channels, attrs = load_exr(full["water_height_exr"])
        np.testing.assert_array_equal(channels["Y"], np.asarray(scene.water, np.float32))  # float32: exact
        assert attrs["units"] == "m" and attrs["length"] == float(scene.length)
        channels, _ = load_exr(half["water_height_exr"])
        water = np.asarray(scene.water, np.float64)
        assert channels["Y"].dtype == np.float16
        np.testing.assert_allclose(channels["Y"], water, rtol=2.0**-11, atol=2.0**-24)
        normals, attrs = load_exr(full["water_normals_exr"])
        assert "green" in attrs["convention"]
        n = np.stack([normals[c] for c in "RGB"], -1)
        np.testing.assert_allclose(np.linalg.norm(n, axis=-1), 1.0, atol=1e-6)
        # the header tells the truth: the file holds n itself (a decoder that applied 2 rgb - 1 to it would
        # no longer have unit normals)
        assert "not packed" in attrs["convention"] and "0.5 + 0.5 n for" not in attrs["convention"]
        assert np.abs(np.linalg.norm(2 * n - 1, axis=-1) - 1).max() > 0.5
        table, attrs = load_exr(full["absorption_exr"])
        assert table["R"].shape == (1, 256) and "path length" in attrs["axis_x"] and table["G"].max() <= 1.0

    def test_independent_reader_sees_the_same_pixels_and_header(self, exported):
        import shutil
        import subprocess

        if shutil.which("oiiotool") is None:
            pytest.skip("oiiotool (Debian openimageio-tools) is not installed; .ci/run installs it")
        scene, full, _ = exported
        info = subprocess.run(["oiiotool", "--info", "-v", str(full["caustics_exr"])], capture_output=True,
                              text=True, check=True).stdout
        assert "relative irradiance" in info and "length: 8" in info and "64 x   64" in info
        dump = subprocess.run(["oiiotool", "--dumpdata", str(full["water_height_exr"])], capture_output=True,
                              text=True, check=True).stdout
        values = {}
        for line in dump.splitlines():
            if line.strip().startswith("Pixel ("):
                xy, value = line.split(":")
                x, y = (int(v) for v in xy.strip()[7:-1].split(","))
                values[(x, y)] = float(value)
        assert len(values) == 64 * 64
        image = np.array([[values[(x, y)] for x in range(64)] for y in range(64)])
        # image row 0 is the top (highest y): the grid's last row
        np.testing.assert_allclose(np.flipud(image), np.asarray(scene.water, np.float32), rtol=1e-7, atol=1e-9)

    def test_vector_displacement_round_trip_rebuilds_the_storm(self, tmp_path):
        """The storm's choppy surface as engines load it (R, G, B = dx, dy, dz in m): read back by
        our loader and by oiiotool, resampled onto the grid it gives the scene's own heights."""
        import shutil
        import subprocess

        from optics.rendering.textures import load_exr, save_vector_displacement
        from wavephys.app.scenes import builtin_scene, scene_displacement, scene_grid
        from wavephys.surfaces import resample_heights

        d = scene_displacement("storm", n=64, time=2.0)
        grid = scene_grid("storm", 64)
        path = save_vector_displacement(tmp_path / "d.exr", d, grid)
        channels, attrs = load_exr(path)
        back = np.stack([channels[c] for c in "RGB"])
        np.testing.assert_array_equal(back, d)
        assert attrs["units"] == "m" and "R = dx" in attrs["convention"]
        heights = resample_heights(back[:2], back[2], grid, refine=2)
        np.testing.assert_allclose(heights, builtin_scene("storm", n=64, time=2.0, caustics=False).water, atol=1e-5)
        assert scene_displacement("pool", n=64) is None
        with pytest.raises(ValueError, match="displacement"):
            save_vector_displacement(tmp_path / "e.exr", d[:2], grid)
        if shutil.which("oiiotool") is not None:
            info = subprocess.run(["oiiotool", "--info", "-v", str(path)], capture_output=True, text=True,
                                  check=True).stdout
            assert "3 channel" in info and "vector displacement" in info

    def test_bad_exr_input_is_named(self, tmp_path):
        from optics.rendering.textures import save_exr

        with pytest.raises(ValueError, match="path"):
            save_exr(tmp_path / "x.png", {"Y": np.zeros((4, 4))})
        with pytest.raises(ValueError, match="one shape"):
            save_exr(tmp_path / "x.exr", {"R": np.zeros((4, 4)), "G": np.zeros((4, 5))})
        with pytest.raises(ValueError, match="channels"):
            save_exr(tmp_path / "x.exr", {"Y": np.full((4, 4), np.nan)})
        with pytest.raises(TypeError, match="attributes"):
            save_exr(tmp_path / "x.exr", {"Y": np.zeros((4, 4))}, attributes={"units": None})
        assert not list(tmp_path.iterdir())  # nothing half-written
