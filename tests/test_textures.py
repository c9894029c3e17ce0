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
