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
        pfm = tmp_path / f"{i}.pfm"
        _pfm(pfm, frame)
        subprocess.run(["oiiotool", str(pfm), "-d", "float", "--attrib:type=float", "dx", str(DX),
                        "--attrib:type=float", "dt", repr(DT), "--attrib", "units", "m", "-o",
                        str(with_meta / f"ocean.{i:04d}.exr")], check=True, capture_output=True)
        if i < 16:
            subprocess.run(["oiiotool", str(pfm), "-d", "half", "-o", str(bare / f"ocean.{i}.exr")], check=True,
                           capture_output=True)
    assert main(["check", str(with_meta), "--sigma", "0", "--sea", "--direction", "0"]) == 0
    out = capsys.readouterr().out
    assert "64 frames of 32 x 32, dx = 0.25 m" in out and "FAILED" not in out
    assert main(["check", str(bare)]) == 2
    assert "dx" in capsys.readouterr().err
    assert main(["check", str(bare), "--dx", "0.25", "--dt", "1/15", "--only", "tiling", "quantization"]) == 0


def test_textures_maps_through_the_command(tmp_path, capsys):
    """Our pool's frames with its normal map (float EXR and packed 8-bit PNG) and caustics map."""
    out = tmp_path / "tx"
    assert main(["textures", "--scene", "pool", "--n", "64", "--frames", "8", "--fps", "15", "--out",
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
