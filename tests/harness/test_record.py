"""Records: layouts, files (EXR, 16-bit PNG, npy, npz, a third-party writer), η̇ from frames, the
textures command's time series read back and checked."""

import math

import numpy as np
import pytest

from corpus import fft_ocean, phillips_h0
from wavephys import Water
from wavephys.core.frames import read_frames
from wavephys.harness import Record, check_record, time_derivative

DX, DT = 0.25, 1 / 15


@pytest.fixture(scope="module")
def sea():
    return fft_ocean(phillips_h0(32, DX, seed=1), DX, DT, 64)


class TestLayout:
    @pytest.mark.parametrize("axes", ["tyx", "yxt", "xyt", "txy"])
    def test_named_axes_give_one_record(self, sea, axes):
        data = np.transpose(sea, ["tyx".index(c) for c in axes])
        np.testing.assert_array_equal(Record.from_array(data, DX, DT, axes=axes).eta, sea)

    def test_ambiguous_layouts_are_refused(self, sea):
        with pytest.raises(ValueError, match="time last"):
            Record.from_array(np.moveaxis(sea, 0, -1), DX, DT)
        with pytest.raises(ValueError, match="cube"):
            Record.from_array(np.zeros((32, 32, 32)), DX, DT)
        with pytest.raises(ValueError, match="no two equal axes"):
            Record.from_array(np.zeros((40, 32, 24)), DX, DT)
        with pytest.raises(ValueError, match="axes must be one of"):
            Record.from_array(sea, DX, DT, axes="tyy")

    def test_measure_dispersion_refuses_time_last(self, sea):
        from wavephys.harness import measure_dispersion

        with pytest.raises(ValueError, match="eta: axes"):
            measure_dispersion(np.moveaxis(sea, 0, -1), DX, DT)


class TestRate:
    def test_fd4_error_is_what_it_says(self, sea):
        k = 2 * math.pi * 3 / (32 * DX)
        w = math.sqrt(9.81 * k)
        t = np.arange(64)[:, None, None] * DT
        x = (np.arange(32) + 0.5) * DX
        eta = 0.01 * np.cos(k * x[None, None, :] - w * t) * np.ones((1, 32, 1))
        exact = 0.01 * w * np.sin(k * x[None, None, :] - w * t) * np.ones((1, 32, 1))
        r = time_derivative(eta, DT, method="fd4")
        err = np.abs(r.eta_dot - exact[r.frames]).max() / (0.01 * w)
        assert r.method == "fd4" and r.error / 3 <= err <= 1.05 * r.error  # an upper estimate, within 3x

    def test_spectral_for_a_loop_only(self, sea):
        loop = fft_ocean(phillips_h0(32, DX, seed=1), DX, 2 * math.pi / math.sqrt(9.81 * 2 * math.pi / (32 * DX)) / 64,
                         64)
        assert time_derivative(sea, DT).method == "fd4"
        with pytest.raises(ValueError, match="loops"):
            time_derivative(sea, DT, method="spectral")
        assert time_derivative(loop[:, :, :], DT).method in ("spectral", "fd4")


class TestFiles:
    def test_exr_series_round_trip_with_its_header(self, sea, tmp_path):
        from optics.rendering.textures import export_height_frames

        paths = export_height_frames(sea, 32 * DX, DT, tmp_path / "f")
        assert len(paths) == 64 and paths[10].name == "water_height_0010.exr"
        rec = Record.from_files(tmp_path / "f")
        assert rec.dx == DX and rec.dt == pytest.approx(DT) and rec.shape == sea.shape
        np.testing.assert_allclose(rec.eta, sea.astype(np.float32))
        with pytest.raises(ValueError, match="dx: 0.5 was given but"):
            Record.from_files(tmp_path / "f", dx=0.5)
        assert Record.from_files(str(tmp_path / "f" / "water_height_00[0-5]*.exr")).shape[0] == 60

    def test_third_party_exr_needs_dx_dt_and_a_channel(self, sea, tmp_path):
        import OpenEXR

        folder = tmp_path / "tp"
        folder.mkdir()
        for i, f in enumerate(sea):  # another writer: RGB channels, no metadata, numbered without padding
            rgb = {c: np.ascontiguousarray(np.flipud(f).astype(np.float32)) for c in "RGB"}
            with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION}, rgb) as out:
                out.write(str(folder / f"h{i}.exr"))
        with pytest.raises(ValueError, match="channel"):
            Record.from_files(folder, dx=DX, dt=DT)
        with pytest.raises(ValueError, match="dt: the frames"):
            Record.from_files(folder, dx=DX, channel="G")
        rec = Record.from_files(folder, dx=DX, dt=DT, channel="G")
        np.testing.assert_allclose(rec.eta, sea.astype(np.float32))  # h2 before h10: natural order
        assert check_record(rec, Water(sigma=0.0), only=["dispersion"]).ok

    def test_png16_with_sidecar_and_raw(self, sea, tmp_path):
        from optics.rendering.textures import encode_height, save_height_png
        from wavephys import Grid

        grid = Grid(32, 32 * DX)
        for i, f in enumerate(sea):
            save_height_png(encode_height(f, grid, 16), tmp_path / f"p_{i:03d}.png")
        frames = read_frames(str(tmp_path / "p_*.png"), dt=DT)
        assert frames.dx == DX and frames.units == "m"
        assert np.abs(frames.heights - sea).max() < 2 * (sea.max() - sea.min()) / 65535
        from PIL import Image

        Image.fromarray(np.zeros((8, 8), np.uint8)).save(tmp_path / "eight.png")
        with pytest.raises(ValueError, match="16-bit grayscale"):
            read_frames(tmp_path / "eight.png")

    def test_bad_files_are_refused_by_name(self, sea, tmp_path):
        (tmp_path / "bad.exr").write_bytes(b"not an exr")
        with pytest.raises(ValueError, match="not a readable OpenEXR"):
            read_frames(tmp_path / "bad.exr")
        with pytest.raises(ValueError, match="matches no files"):
            read_frames(str(tmp_path / "none_*.exr"))
        np.save(tmp_path / "a.npy", sea[0])
        np.save(tmp_path / "b.npy", sea[0, :16])
        with pytest.raises(ValueError, match="one size"):
            read_frames([tmp_path / "a.npy", tmp_path / "b.npy"])
        nan = sea.copy()
        nan[3, 1, 1] = np.nan
        np.save(tmp_path / "nan.npy", nan)
        with pytest.raises(ValueError, match="frame 3.*non-finite"):
            read_frames(tmp_path / "nan.npy")
        with pytest.raises(TypeError, match="source"):
            read_frames(3)

    def test_saved_record_keeps_its_claims(self, sea, tmp_path):
        rec = Record(sea, DX, DT, depth=2.0, sigma=0.0)
        back = Record.load(rec.save(tmp_path / "r.npz"))
        assert back.depth == 2.0 and back.sigma == 0.0 and back.dx == DX
        np.testing.assert_array_equal(back.eta, sea)
        assert back.water().depth == 2.0


def test_textures_frames_command_is_a_record_the_check_reads(tmp_path, capsys):
    """`wavephys textures --frames` then `wavephys check` on its folder: the frames, spacing and step come back
    from the files; the shore's swell runs over a beach (it shortens and is damped in the surf), so the
    flat-floor dispersion row fails it — rightly — while the storage rows pass."""
    from wavephys.app.cli import main

    out = tmp_path / "tx"
    assert main(["textures", "--scene", "shore", "--n", "64", "--frames", "256", "--fps", "15", "--out",
                 str(out)]) == 0
    capsys.readouterr()
    assert main(["check", str(out / "frames"), "--sigma", "0", "--only", "quantization"]) == 0
    printed = capsys.readouterr().out
    assert "256 frames of 64 x 64, dx = 0.25 m, dt = 0.0666667 s" in printed and "FAILED" not in printed
    assert main(["check", str(out / "frames"), "--sigma", "0", "--sea", "--only", "dispersion"]) == 1
    assert "FAILED dispersion" in capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["textures", "--scene", "shore", "--frames", "8", "--fps", "0.001", "--time", "3599", "--out",
              str(tmp_path / "late")])
    assert main(["check", str(tmp_path / "nothing")]) == 2
