"""The corpus (tests/harness/corpus.py) through the harness: each simulator gets the verdict and the cause
it must get, correct ones pass every check that applies, and the corpus runs through the command too."""

import math

import numpy as np
import pytest

from corpus import (N, fft_ocean, gaussian_bump, iwave, normals_from_heights, phillips_h0, random_heights,
                    spectral_model, travelling_packet, webgl_water)
from wavephys import Water
from wavephys.harness import (Record, caustics_flux_check, check_record, group_velocity_check, normals_check,
                              resolution_check, ring_arrival_check, tiling_check)

DEEP = Water(sigma=0.0)
DX, DT = 0.25, 1 / 15


def _sea(**kw):
    return fft_ocean(phillips_h0(N, DX, seed=1, one_way=kw.pop("one_way", True)), DX, DT, 256, **kw)


def _wind_sea(degrees):
    wind = (math.cos(math.radians(degrees)), math.sin(math.radians(degrees)))
    return fft_ocean(phillips_h0(N, DX, wind=wind, seed=2), DX, DT, 256)


def _spectral(**kw):
    e, r = spectral_model(random_heights(N, 3, k_cut=0.5), 0.1, 1 / 30, 256, **kw)
    return e, r


# name -> (record maker, water, claims, {check: expected cause fragment or None for ok})
CORPUS = {
    "tessendorf ocean (correct, one way downwind)": (
        lambda: Record.from_array(_sea(), DX, DT), DEEP, dict(sea=True, direction=0.0),
        {"dispersion": None, "energy": None, "tiling": None, "quantization": None, "standing": None,
         "direction": None}),
    "random-phase sea, symmetric spreading (correct)": (
        lambda: Record.from_array(_sea(one_way=False), DX, DT), DEEP, dict(sea=True),
        {"dispersion": None, "energy": None, "standing": None}),
    "exact spectral step with eta_dot (correct)": (
        lambda: Record.from_array(*_spectral()[:1], 0.1, 1 / 30, eta_dot=_spectral()[1]), DEEP, {},
        {"dispersion": None, "energy": None, "tiling": None, "quantization": None}),
    "FFT ocean, both halves turning one way (standing)": (
        lambda: Record.from_array(_sea(one_way=False, standing=True), DX, DT), DEEP, dict(sea=True),
        {"dispersion": None, "standing": "standing waves"}),
    "FFT ocean released long before the record (standing)": (
        lambda: Record.from_array(_sea(one_way=False, standing=True, t_start=30.0), DX, DT), DEEP, dict(sea=True),
        {"standing": "standing waves"}),
    "FFT ocean with the sign of omega t flipped": (
        lambda: Record.from_array(_sea(sign=+1), DX, DT), DEEP, dict(direction=0.0),
        {"dispersion": None, "direction": "opposite to the claim"}),
    "FFT ocean at 40 deg (correct)": (
        lambda: Record.from_array(_wind_sea(40.0), DX, DT), DEEP, dict(direction=40.0), {"direction": None}),
    "FFT ocean at 40 deg with rows stored top-down": (
        lambda: Record.from_array(_wind_sea(40.0)[:, ::-1, :], DX, DT), DEEP, dict(direction=40.0),
        {"direction": "y axis is flipped"}),
    "WebGL Water, periodic": (
        lambda: Record.from_array(webgl_water(), 0.05, 1 / 60), DEEP, {},
        {"dispersion": "non-dispersive", "energy": "uniform damping", "tiling": None}),
    "WebGL Water, CLAMP_TO_EDGE": (
        lambda: Record.from_array(webgl_water(clamp=True), 0.05, 1 / 60), DEEP, {},
        {"dispersion": "non-dispersive", "energy": "uniform damping", "tiling": "reflecting (edge-clamped)"}),
    "iWave (truncated kernel, damping term)": (
        lambda: Record.from_array(iwave()[0], 1.0, 0.03), Water(sigma=0.0, g=9.8), {},
        {"dispersion": "low-k frequency floor", "energy": "uniform damping"}),
    "velocity *= 0.995 each step": (
        lambda: Record.from_array(_spectral(velocity_factor=0.995)[0], 0.1, 1 / 30), DEEP, {},
        {"dispersion": None, "energy": "uniform damping"}),
    "Laplacian smoothing each step": (
        lambda: Record.from_array(_spectral(smoothing=2e-3)[0], 0.1, 1 / 30), DEEP, {},
        {"dispersion": None, "energy": "proportional to k^2"}),
    "0.3 m deep, claimed deep": (
        lambda: Record.from_array(_spectral(depth=0.3)[0], 0.1, 1 / 30), DEEP, {},
        {"dispersion": "depth h = 0.3 m", "energy": None}),
    "surface tension 10x": (
        lambda: Record.from_array(spectral_model(random_heights(N, 3, k_cut=0.5), 0.01, 1 / 240, 256,
                                                 sigma=0.728)[0], 0.01, 1 / 240), Water(), {},
        {"dispersion": "10 x the claimed"}),
    "frames 1/30 s apart, exported as 1/60": (
        lambda: Record.from_array(_spectral()[0], 0.1, 1 / 60), DEEP, {},
        {"dispersion": "constant factor 2", "energy": "do not trade at theory's rate"}),
    "wave equation recorded every 4th step (aliased)": (
        lambda: Record.from_array(webgl_water(frames=1024)[3::4], 0.05, 4 / 60), DEEP, {},
        {"dispersion": "aliased sampling"}),
    "capillary ripples recorded at 60 fps (aliased)": (
        lambda: Record.from_array(spectral_model(random_heights(N, 4, k_cut=0.6), 0.002, 1 / 60, 256,
                                                 sigma=0.0728, substeps=8)[0], 0.002, 1 / 60), Water(), {},
        {"dispersion": "aliased sampling"}),
    "float16 heights of a calm sea (subnormal)": (
        lambda: Record.from_array((_sea() * 5e-5).astype(np.float16), DX, DT), DEEP, {},
        {"dispersion": None, "quantization": "float16"}),
    "cropped ocean": (
        lambda: Record.from_array(fft_ocean(phillips_h0(96, DX, seed=5), DX, DT, 64)[:, :64, :64], DX, DT,
                                  axes="tyx"), DEEP,
        dict(only=["tiling"]), {"tiling": "a seam"}),
    "stone, gravity-only scheme in capillary water (ring arrival)": (
        lambda: Record.from_array(spectral_model(gaussian_bump(128, 0.005, 0.01), 0.005, 1 / 240, 200)[0], 0.005,
                                  1 / 240), Water(), dict(source=(0.0, 0.0), radius=0.03),
        {"ring_arrival": "too slow", "dispersion": "surface tension missing"}),
    "stone, capillary-gravity (correct)": (
        lambda: Record.from_array(spectral_model(gaussian_bump(128, 0.005, 0.01), 0.005, 1 / 240, 200,
                                                 sigma=0.0728)[0], 0.005, 1 / 240), Water(),
        dict(source=(0.0, 0.0), radius=0.03), {"ring_arrival": None, "dispersion": None}),
    "packet in a wave equation": (
        lambda: Record.from_array(travelling_packet(128, 0.1, 1 / 30, 200, 2 * math.pi / 0.8, 1.0,
                                                    wave_equation_speed=1.12), 0.1, 1 / 30), DEEP,
        dict(packet=True), {"group_velocity": "phase speed, not the group speed"}),
    "packet of water waves (correct)": (
        lambda: Record.from_array(travelling_packet(128, 0.1, 1 / 30, 200, 2 * math.pi / 0.8, 1.0), 0.1, 1 / 30),
        DEEP, dict(packet=True), {"group_velocity": None}),
}


def _verdicts(report, expected):
    for name, cause in expected.items():
        row = report.rows[name]
        if cause is None:
            assert row.ok, f"{name}: {row.report()}"
        else:
            assert not row.ok and cause in row.note, f"{name}: {row.report()}"


@pytest.mark.parametrize("name", list(CORPUS))
def test_corpus_verdict_and_cause(name):
    make, water, claims, expected = CORPUS[name]
    claims = dict(claims)
    only = claims.pop("only", list(expected))
    _verdicts(check_record(make(), water, only=only, **claims), expected)


def test_time_last_export_is_refused_not_measured():
    """The layout many engines export, (n, n, n_t): refused by name, and measured right when named."""
    frames = np.moveaxis(_sea(), 0, -1)
    with pytest.raises(ValueError, match="axes.*time last"):
        Record.from_array(frames, DX, DT)
    with pytest.raises(ValueError, match="axes"):
        Record.from_array(frames[:, :, :64], DX, DT)  # a cube
    report = check_record(Record.from_array(frames, DX, DT, axes="yxt"), DEEP, only=["dispersion"])
    assert report.ok


def test_corpus_through_the_command(tmp_path, capsys):
    """Three corpus records as .npz files through `wavephys check`: exit codes, causes, JSON and JUnit."""
    import json
    import xml.etree.ElementTree as ET

    from wavephys.app.cli import main

    good, bad = tmp_path / "good.npz", tmp_path / "bad.npz"
    CORPUS["tessendorf ocean (correct, one way downwind)"][0]().save(good)
    CORPUS["WebGL Water, CLAMP_TO_EDGE"][0]().save(bad)
    assert main(["check", str(good), "--sigma", "0", "--sea", "--direction", "0"]) == 0
    capsys.readouterr()
    junit, js = tmp_path / "c.xml", tmp_path / "c.json"
    assert main(["check", str(bad), "--sigma", "0", "--junit", str(junit), "--json", str(js)]) == 1
    out = capsys.readouterr().out
    assert "FAILED dispersion" in out and "non-dispersive" in out and "edge-clamped" in out
    suite = ET.parse(junit).getroot()
    assert suite.tag == "testsuite" and int(suite.get("failures")) >= 2
    assert {c.get("name") for c in suite.iter("testcase")} >= {"dispersion", "energy", "tiling"}
    data = json.loads(js.read_text())
    assert data["ok"] is False and data["rows"]["dispersion"]["ok"] is False


def test_command_refuses_a_check_whose_claim_is_missing(tmp_path):
    from wavephys.app.cli import main

    path = tmp_path / "r.npz"
    CORPUS["velocity *= 0.995 each step"][0]().save(path)
    with pytest.raises(SystemExit) as exc:
        main(["check", str(path), "--only", "standing"])
    assert exc.value.code == 2


class TestTextureChecks:
    def test_normals_convention_and_strength(self):
        eta = _sea()[0]
        assert normals_check(eta, normals_from_heights(eta, DX), DX, convention="opengl").ok
        row = normals_check(eta, normals_from_heights(eta, DX, green=-1.0), DX, convention="opengl")
        assert not row.ok and "directx green convention" in row.note
        assert normals_check(eta, normals_from_heights(eta, DX, green=-1.0), DX, convention="directx").ok
        row = normals_check(eta, normals_from_heights(eta, DX, strength=2.0), DX)
        assert not row.ok and "2 x the heights'" in row.note

    def test_resolution_independence(self):
        a = fft_ocean(phillips_h0(64, 0.25, seed=1, cutoff=0.25), 0.25, DT, 1)[0]
        b = fft_ocean(phillips_h0(128, 0.125, seed=2, cutoff=0.25), 0.125, DT, 1)[0]
        assert resolution_check(a, 0.25, b, 0.125).ok
        a = fft_ocean(phillips_h0(64, 0.25, seed=1, cutoff=0.25, normalize=False), 0.25, DT, 1)[0]
        b = fft_ocean(phillips_h0(128, 0.125, seed=2, cutoff=0.25, normalize=False), 0.125, DT, 1)[0]
        row = resolution_check(a, 0.25, b, 0.125)
        assert not row.ok and "amplitudes scale with the grid" in row.note
        a = fft_ocean(phillips_h0(64, 0.25, seed=1), 0.25, DT, 1)[0]  # cutoff one texel: tied to the grid
        b = fft_ocean(phillips_h0(128, 0.125, seed=2), 0.125, DT, 1)[0]
        assert not resolution_check(a, 0.25, b, 0.125).ok

    def test_caustics_flux(self):
        from optics.caustics import floor_irradiance
        from wavephys import Grid

        eta = _sea()[0].astype(np.float32)
        grid = Grid(N, N * DX)
        e = np.asarray(floor_irradiance(eta, grid, 2.0)) / np.asarray(floor_irradiance(0 * eta, grid, 2.0))
        assert caustics_flux_check(e).ok
        top = float(np.quantile(e, 0.5))  # a map that saturates on its brighter half
        row = caustics_flux_check(np.minimum(e, top))
        assert not row.ok and f"clipped at {top:.4g}" in row.note, row.report()
        row = caustics_flux_check(e / e.max())
        assert not row.ok and "normalized to its peak" in row.note

    def test_tiling_duplicate_edge(self):
        eta = _sea()[0]
        row = tiling_check(np.concatenate([eta, eta[:, :1]], axis=1)[:, 1:])  # last column repeats the first
        assert tiling_check(eta).ok
        big = np.concatenate([eta, eta[:, :1]], axis=1)
        row = tiling_check(np.concatenate([big, big[:1]], axis=0))
        assert not row.ok and "repeats the first" in row.note


def test_group_velocity_and_ring_functions_refuse_bad_input():
    rec = CORPUS["packet of water waves (correct)"][0]()
    with pytest.raises(ValueError, match="rtol"):
        group_velocity_check(rec, DEEP, rtol=0.0)
    with pytest.raises(ValueError, match="max_share"):
        ring_arrival_check(rec, DEEP, max_share=1.0)
    with pytest.raises(TypeError, match="record"):
        ring_arrival_check(rec.eta, DEEP)


def test_small_correct_seas_pass_the_direction_check_at_any_heading():
    """Correct one-way seas of 32² and 64² at random headings: the claim passes (a 32² sea's mean direction
    scattered up to 21° before the tolerance took its sampling error), and the opposite claim fails with its
    cause."""
    from wavephys.harness import direction_check

    rng = np.random.default_rng(26)
    for n in (32, 64):
        for seed in range(4):
            deg = float(rng.uniform(-180.0, 180.0))
            wind = (math.cos(math.radians(deg)), math.sin(math.radians(deg)))
            rec = Record.from_array(fft_ocean(phillips_h0(n, DX, wind=wind, seed=seed + 300), DX, DT, 128), DX, DT)
            assert direction_check(rec, deg).ok, (n, deg)
            row = direction_check(rec, deg + 180.0)
            assert not row.ok and "opposite to the claim" in row.note, (n, deg, row.report())
