"""`wavephys check` on what engines and other tools write: an EXR folder from a third-party writer
(OpenImageIO's oiiotool), our own textures with their normal and caustics maps, a sea at two resolutions;
and the whole corpus through the pytest fixture, as a user's suite runs it."""

import shutil
import subprocess

import numpy as np
import pytest

from corpus import fft_ocean, phillips_h0
from wavephys.app.cli import main
from wavephys.harness import Record

DX, DT = 0.25, 1 / 15


@pytest.fixture(scope="module")
def sea():
    return fft_ocean(phillips_h0(32, DX, seed=1), DX, DT, 64)


def _pfm(path, frame):
    """A portable float map: the simplest float image; its rows run bottom-up, as the grid convention."""
    with open(path, "wb") as f:
        f.write(f"Pf\n{frame.shape[1]} {frame.shape[0]}\n-1.0\n".encode())
        f.write(np.ascontiguousarray(frame, "<f4").tobytes())


@pytest.mark.skipif(shutil.which("oiiotool") is None, reason="oiiotool (openimageio-tools) not installed")
def test_third_party_exr_folder_through_the_command(sea, tmp_path, capsys):
    """oiiotool writes each frame (channel Y), with dx and dt as header attributes in one folder and none in
    another (half floats, 16 frames): the first is checked as it is, the second needs --dx and --dt (exit 2
    naming them without)."""
    with_meta, bare = tmp_path / "meta", tmp_path / "bare"
    with_meta.mkdir()
    bare.mkdir()
    for i, frame in enumerate(sea):
        _pfm(tmp_path / f"f.{i:04d}.pfm", frame)
    # one oiiotool process a folder (its frame-range loop writes each frame as its own file)
    subprocess.run(["oiiotool", "--frames", f"0-{len(sea) - 1}", str(tmp_path / "f.#.pfm"), "-d", "float",
                    "--attrib:type=float", "dx", str(DX), "--attrib:type=float", "dt", repr(DT), "--attrib", "units",
                    "m", "-o", str(with_meta / "ocean.#.exr")], check=True, capture_output=True)
    subprocess.run(["oiiotool", "--frames", "0-15", str(tmp_path / "f.#.pfm"), "-d", "half", "-o",
                    str(bare / "ocean.#.exr")], check=True, capture_output=True)
    assert main(["check", str(with_meta), "--sigma", "0", "--sea", "--direction", "0"]) == 0
    out = capsys.readouterr().out
    assert "64 frames of 32 x 32, dx = 0.25 m" in out and "FAILED" not in out
    assert main(["check", str(bare)]) == 2
    assert "dx" in capsys.readouterr().err
    assert main(["check", str(bare), "--dx", "0.25", "--dt", "1/15", "--only", "tiling", "quantization"]) == 0


def test_textures_maps_through_the_command(tmp_path, capsys):
    """A periodic scene's frames with its normal map (float EXR and packed 8-bit PNG) and caustics map (the pool's
    frames are its tank alone, smaller than its maps of the whole square)."""
    out = tmp_path / "tx"
    assert main(["textures", "--scene", "calm", "--n", "64", "--frames", "8", "--fps", "15", "--out",
                 str(out)]) == 0
    capsys.readouterr()
    assert main(["check", str(out / "frames"), "--only", "normals", "caustics_flux", "--normals",
                 str(out / "water_normals.exr"), "--caustics", str(out / "caustics.exr")]) == 0
    assert main(["check", str(out / "frames"), "--only", "normals", "--normals", str(out / "water_normals.png"),
                 "--convention", "directx"]) == 1
    assert "opengl green convention" in capsys.readouterr().out
    with pytest.raises(SystemExit) as exc:  # the claim is missing: a usage error
        main(["check", str(out / "frames"), "--only", "normals"])
    assert exc.value.code == 2
    assert main(["check", str(out / "frames"), "--only", "normals", "--normals", str(tmp_path / "none.exr")]) == 2
    assert "--normals" in capsys.readouterr().err


def test_the_pools_own_export_is_checked_as_the_tank_it_is(tmp_path, capsys):
    """The pool's frames are its tank (boundary = walls in their headers, its depth and sigma): every check that
    applies passes with nothing claimed, the periodic ones are not run on it."""
    out = tmp_path / "tx"
    assert main(["textures", "--scene", "pool", "--n", "64", "--frames", "24", "--fps", "15", "--out",
                 str(out)]) == 0
    capsys.readouterr()
    assert main(["check", str(out / "frames")]) == 0
    text = capsys.readouterr().out
    assert "ok     seiche" in text and "ok     wall_reflection" in text and "ok     energy" in text
    assert "skip   tiling: the record is a tank" in text and "FAILED" not in text


def test_resolution_through_the_command(tmp_path, capsys):
    a = fft_ocean(phillips_h0(64, 0.25, seed=1, cutoff=0.25), 0.25, DT, 8)
    b = fft_ocean(phillips_h0(128, 0.125, seed=2, cutoff=0.25), 0.125, DT, 8)
    bad = fft_ocean(phillips_h0(128, 0.125, seed=2, cutoff=0.25, normalize=False), 0.125, DT, 8)
    Record.from_array(a, 0.25, DT).save(tmp_path / "a.npz")
    Record.from_array(b, 0.125, DT).save(tmp_path / "b.npz")
    Record.from_array(bad, 0.125, DT).save(tmp_path / "bad.npz")
    assert main(["check", str(tmp_path / "a.npz"), "--only", "resolution", "--other", str(tmp_path / "b.npz")]) == 0
    assert main(["check", str(tmp_path / "a.npz"), "--only", "resolution", "--other",
                 str(tmp_path / "bad.npz")]) == 1


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_the_corpus_through_the_fixture(pytester, tmp_path):
    """Every corpus record saved as a user would, then checked by `wavephys_check.record` in a user's suite
    (a fresh process with the installed plugin): correct ones pass, broken ones fail naming the cause."""
    from test_corpus import CORPUS

    cases = []
    for i, (name, (make, water, claims, expected)) in enumerate(CORPUS.items()):
        path = tmp_path / f"r{i}.npz"
        make().save(path)
        claims = dict(claims)
        only = claims.pop("only", list(expected))
        for check, cause in expected.items():
            cases.append((name, str(path), water.sigma, water.g, check, cause, claims))
    pytester.makepyfile(test_user_corpus=f"""
import re
import pytest
from wavephys import Water

CASES = {cases!r}

@pytest.mark.parametrize("name, path, sigma, g, check, cause, claims", CASES)
def test_record(wavephys_check, name, path, sigma, g, check, cause, claims):
    water = Water(sigma=sigma, g=g)
    if cause is None:
        wavephys_check.record(path, water, only=[check], **claims)
    else:
        with pytest.raises(AssertionError, match=re.escape(cause)):
            wavephys_check.record(path, water, only=[check], **claims)
""")
    result = pytester.runpytest_subprocess("-q", "-p", "no:cacheprovider", "-p", "no:xdist")
    result.assert_outcomes(passed=len(cases))


def test_one_array_of_frames_time_last_is_refused_not_guessed(sea, tmp_path, capsys):
    """A time-last .npy (the layout many engines write) and a cube are refused by Record.from_files, the
    command and the fixture alike, naming axes; with axes (--axes) named they are read right."""
    from wavephys import Water
    from wavephys.harness import check_record

    longer = fft_ocean(phillips_h0(32, DX, seed=1), DX, DT, 96)
    np.save(tmp_path / "last.npy", np.moveaxis(longer, 0, -1))
    np.save(tmp_path / "cube.npy", np.moveaxis(longer[:32], 0, -1))
    for name in ("last.npy", "cube.npy"):
        with pytest.raises(ValueError, match="axes"):
            Record.from_files(tmp_path / name, dx=DX, dt=DT)
        assert main(["check", str(tmp_path / name), "--dx", "0.25", "--dt", "1/15"]) == 2
        assert "--axes" in capsys.readouterr().err
    rec = Record.from_files(tmp_path / "last.npy", dx=DX, dt=DT, axes="yxt")
    np.testing.assert_allclose(rec.eta, longer)
    assert check_record(rec, Water(sigma=0.0), only=["dispersion"]).ok
    assert main(["check", str(tmp_path / "last.npy"), "--dx", "0.25", "--dt", "1/15", "--axes", "yxt", "--sigma",
                 "0", "--only", "dispersion"]) == 0
    from optics.rendering.textures import export_height_frames

    export_height_frames(list(longer[:8]), 32 * DX, DT, tmp_path / "exr")
    with pytest.raises(ValueError, match="axes"):  # images are one frame each: no layout to name
        Record.from_files(tmp_path / "exr", axes="yxt")


def test_saved_cube_record_reads_back(tmp_path):
    cube = fft_ocean(phillips_h0(16, DX, seed=1), DX, DT, 16)
    back = Record.load(Record(cube, DX, DT).save(tmp_path / "cube.npz"))  # the .npz says its layout
    np.testing.assert_array_equal(back.eta, cube)


def test_a_strip_of_exr_frames_is_checked_by_the_command(tmp_path, capsys):
    """An engine's 64 x 32 strip (another writer's EXR frames, no metadata): the command reads it with --dx and
    --dt and gets a square's verdicts; cropped from a wider sea it has a seam, and says so."""
    import math

    import OpenEXR

    from corpus import strip_frames, strip_h0

    sea = strip_frames(strip_h0(32, 64, DX, np.random.default_rng(2), 0.4), DX, DT, lambda k: np.sqrt(9.81 * k), 64)
    wide = strip_frames(strip_h0(32, 96, DX, np.random.default_rng(2), 0.4), DX, DT, lambda k: np.sqrt(9.81 * k), 64)
    for name, frames in (("strip", sea), ("cropped", wide[:, :, :64])):
        (tmp_path / name).mkdir()
        for i, f in enumerate(frames):
            with OpenEXR.File({"compression": OpenEXR.ZIP_COMPRESSION},
                              {"Y": np.ascontiguousarray(np.flipud(f).astype(np.float32))}) as out:
                out.write(str(tmp_path / name / f"h{i}.exr"))
    direction = f"{math.degrees(0.4):.1f}"
    assert main(["check", str(tmp_path / "strip"), "--dx", "0.25", "--dt", "1/15", "--sigma", "0", "--sea",
                 "--direction", direction]) == 0
    out = capsys.readouterr().out
    assert "64 frames of 64 x 32, dx = 0.25 m" in out and "FAILED" not in out and "ok     dispersion" in out
    assert main(["check", str(tmp_path / "cropped"), "--dx", "0.25", "--dt", "1/15", "--sigma", "0",
                 "--only", "tiling"]) == 1
    assert "seam" in capsys.readouterr().out


def test_options_are_checked_before_the_frames_are_read(tmp_path, capsys):
    """Unknown checks, a named check's missing claim, and wake companions without --wake: exit 2 at once,
    naming the options, for frames that do not even exist."""
    missing = str(tmp_path / "not-read")
    for argv, words in ((["--only", "dispersion", "bogus"], "--only: unknown check(s) bogus"),
                        (["--only", "direction"], "needs --direction"), (["--only", "wake_max", "--wake", "1"],
                                                                          "needs --wake-size"),
                        (["--wake-at", "1,2"], "--wake U")):
        with pytest.raises(SystemExit) as exc:
            main(["check", missing, *argv])
        err = capsys.readouterr().err
        assert exc.value.code == 2 and words in err and "not-read" not in err, (argv, err)
