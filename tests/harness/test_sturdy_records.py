"""Ordinary records, read sturdily: 16-bit PNGs without a sidecar, corrupt and complex files, fractions, the
frames named FRAMES, bounded searches on faulty records, and a failing fixture that shows the rows, not the
plugin."""

import time

import numpy as np
import pytest
from PIL import Image

from wavephys import Water
from wavephys.harness import Record, check_record


def _png(path, levels, sidecar=None):
    Image.fromarray(levels.astype(np.uint16)).save(path)
    if sidecar is not None:
        import json

        path.with_suffix(".json").write_text(json.dumps(sidecar))


def test_sixteen_bit_pngs_need_their_metres_said(tmp_path, capsys):
    from wavephys.app.cli import main

    rng = np.random.default_rng(0)
    for i in range(8):
        _png(tmp_path / f"h_{i}.png", rng.integers(0, 65535, (16, 16)))
    with pytest.raises(ValueError, match="no JSON sidecar .* png_range=\\(offset, amplitude\\)"):
        Record.from_files(tmp_path, dx=0.1, dt=0.1)
    record = Record.from_files(tmp_path, dx=0.1, dt=0.1, png_range=(-0.5, 1.0))
    assert -0.5 <= record.eta.min() and record.eta.max() <= 0.5
    assert main(["check", str(tmp_path), "--dx", "1/10", "--dt", "1/10", "--only", "quantization"]) == 2
    assert "FRAMES:" in capsys.readouterr().err
    assert main(["check", str(tmp_path), "--dx", "1/10", "--dt", "1/10", "--png-range=-0.5,1",
                 "--only", "quantization"]) in (0, 1)
    _png(tmp_path / "h_0.png", rng.integers(0, 65535, (16, 16)), sidecar=dict(offset=0.0, amplitude=2.0))
    with pytest.raises(ValueError, match="png_range.*sidecar"):  # a sidecar that says otherwise is not overridden
        Record.from_files([tmp_path / "h_0.png"] * 8, dx=0.1, dt=0.1, png_range=(-0.5, 1.0))


def test_damaged_and_foreign_files_are_named(tmp_path):
    (tmp_path / "bad.npz").write_bytes(b"PK\x03\x04 a zip cut short")
    with pytest.raises(ValueError, match="bad.npz.*not a readable numpy file.*BadZipFile"):
        Record.from_files(tmp_path / "bad.npz", dx=0.1, dt=0.1)
    np.save(tmp_path / "c.npy", np.ones((16, 8, 8), complex))
    with pytest.raises(ValueError, match="complex128 values, not real heights"):
        Record.from_files(tmp_path / "c.npy", dx=0.1, dt=0.1)
    from wavephys.core.frames import read_map

    np.save(tmp_path / "n.npy", np.ones((8, 8, 3), complex))
    with pytest.raises(ValueError, match="--normals: .*complex128"):
        read_map(tmp_path / "n.npy", name="--normals", channels=3)
    for bad in (np.ones((16, 8, 8), complex), np.ones((16, 8, 8), object)):
        with pytest.raises(TypeError, match="data must be"):
            Record.from_array(bad, 0.1, 0.1)


def test_a_faulty_record_costs_about_what_a_correct_one_does():
    """The peak refinements stay in their bin and the release-time search is bounded: the standing and direction
    checks took 157 s and 140 s on a faulty 64² x 128 record before (0.4 s on a correct one)."""
    rng = np.random.default_rng(0)
    noise = Record.from_array(rng.normal(size=(128, 64, 64)), 0.05, 1 / 60)
    start = time.perf_counter()
    check_record(noise, Water(), only=["standing", "direction"], sea=True, direction=0.0)
    assert time.perf_counter() - start < 10.0  # bounded; bench/harness.py measures the ratio


def test_a_failing_fixture_shows_the_table_of_rows_not_the_plugin(pytester, monkeypatch):
    # pytest prints each failure's whole message again in its summary when CI or BUILD_NUMBER
    # is set; the user's terminal (neither set) is what this counts lines of.
    monkeypatch.delenv("CI", raising=False)
    monkeypatch.delenv("BUILD_NUMBER", raising=False)
    pytester.makepyfile(test_user="""
import numpy as np
from wavephys import Water

def test_waves(wavephys_check):
    rng = np.random.default_rng(0)
    h, v = 1e-3 * rng.standard_normal((32, 32)), np.zeros((32, 32))
    frames = []
    for _ in range(128):
        avg = 0.25 * (np.roll(h, 1, 0) + np.roll(h, -1, 0) + np.roll(h, 1, 1) + np.roll(h, -1, 1))
        v = (v + 2.0 * (avg - h)) * 0.995
        h = h + v
        frames.append(h.copy())
    wavephys_check.record(np.array(frames), Water(), dx=0.05, dt=1 / 60, axes="tyx")
""")
    result = pytester.runpytest_subprocess("-q", "-p", "no:cacheprovider")
    result.assert_outcomes(failed=1)
    text = result.stdout.str()
    assert "FAILED dispersion" in text and "non-dispersive" in text
    assert "pytest_plugin.py" not in text and "def record(self" not in text
    assert len(text.splitlines()) < 60
