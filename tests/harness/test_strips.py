"""Strips: engines export frames that are not square (512 x 256, a river, a corridor of a harbour). The
harness reads a strip as it reads a square (one dx along both axes): every law gets the verdict it gets on a
square, and the wake checks, which measure on squares, say so instead of guessing. The frames are written
here mode by mode, exactly, with the scheme's ω(k) (no library step), over a family of shapes, seeds and
directions."""

import math

import numpy as np
import pytest

from wavephys import Water
from corpus import strip_frames as _frames, strip_h0
from wavephys.harness import Record, check_record

G, DX, DT = 9.81, 0.25, 1 / 15
SHAPES = [(32, 64), (64, 32), (24, 64), (48, 40)]  # (n_y, n_x): either way round, odd ratios


def _deep(k):
    return np.sqrt(G * k)


@pytest.mark.parametrize("shape", SHAPES, ids=lambda s: f"{s[0]}x{s[1]}")
def test_a_sea_on_a_strip_gets_the_verdicts_it_gets_on_a_square(shape):
    rng = np.random.default_rng(sum(shape))
    heading = rng.uniform(-math.pi, math.pi)
    h0 = strip_h0(*shape, DX, rng, heading)
    record = Record(_frames(h0, DX, DT, _deep), DX, DT)
    report = check_record(record, Water(sigma=0.0), direction=math.degrees(heading), sea=True)
    assert report.ok, report.report()
    assert {"dispersion", "energy", "tiling", "quantization", "direction", "standing"} <= set(report.rows)
    broken = {
        "constant factor 1.05": lambda k: 1.05 * _deep(k),
        "non-dispersive": lambda k: k * math.sqrt(G * 0.3),
    }
    for cause, omega in broken.items():
        row = check_record(Record(_frames(h0, DX, DT, omega), DX, DT), Water(sigma=0.0), only=["dispersion"]).rows[
            "dispersion"]
        assert not row.ok and cause in row.note, (cause, row.note)
    standing = check_record(Record(_frames(h0, DX, DT, _deep, standing=True), DX, DT), Water(sigma=0.0), sea=True,
                            only=["standing"]).rows["standing"]
    assert not standing.ok, standing.report()
    backwards = check_record(record, Water(sigma=0.0), direction=math.degrees(heading) + 180.0,
                             only=["direction"]).rows["direction"]
    assert not backwards.ok, backwards.report()


@pytest.mark.parametrize("shape", SHAPES[:2], ids=lambda s: f"{s[0]}x{s[1]}")
def test_a_strips_normal_map_and_its_other_resolution_are_read_along_the_right_axes(shape):
    rng = np.random.default_rng(3)
    h0 = strip_h0(*shape, DX, rng, rng.uniform(-math.pi, math.pi))
    eta = _frames(h0, DX, DT, _deep, nt=16)
    sx = (np.roll(eta[0], -1, 1) - np.roll(eta[0], 1, 1)) / (2 * DX)
    sy = (np.roll(eta[0], -1, 0) - np.roll(eta[0], 1, 0)) / (2 * DX)

    def packed(gx, gy):
        n = np.stack([-gx, -gy, np.ones_like(gx)], -1)
        return 0.5 + 0.5 * n / np.linalg.norm(n, axis=-1, keepdims=True)

    record = Record(eta, DX, DT)
    good = check_record(record, Water(sigma=0.0), normals=packed(sx, sy), only=["normals"]).rows["normals"]
    assert good.ok, good.report()
    bad = check_record(record, Water(sigma=0.0), normals=packed(sy, sx), only=["normals"]).rows["normals"]
    assert not bad.ok, bad.report()  # x and y slopes swapped
    # the same sea exported at twice the resolution: its modes on the finer grid, the same waves
    ny, nx = shape
    fine = np.zeros((2 * ny, 2 * nx), complex)
    iy, ix = (np.fft.fftfreq(ny) * ny).astype(int), (np.fft.fftfreq(nx) * nx).astype(int)
    fine[np.ix_(iy % (2 * ny), ix % (2 * nx))] = h0
    other = Record(_frames(fine, DX / 2, DT, _deep, nt=16), DX / 2, DT)
    row = check_record(record, Water(sigma=0.0), other=other, only=["resolution"]).rows["resolution"]
    assert row.ok, row.report()


def test_the_wake_checks_say_they_measure_on_squares():
    record = Record(np.zeros((8, 32, 64)), DX, DT)
    report = check_record(record, Water(sigma=0.0), wake=dict(speed=1.0), sea=False)
    assert "wake_edge" not in report.rows and "square" in report.skipped["wake_edge"]
    assert "32 x 64" in report.skipped["wake_edge"]
    with pytest.raises(ValueError, match="wake_edge check cannot run: measures on square frames"):
        check_record(record, Water(sigma=0.0), wake=dict(speed=1.0), only=["wake_edge"])


@pytest.mark.parametrize("shape", [(12, 40), (40, 12)], ids=lambda s: f"{s[0]}x{s[1]}")
def test_shallow_water_on_a_strip_keeps_its_mass_and_its_lake_at_rest(shape):
    """Depth frames over a bed on a strip: a lake at rest and one that leaks (0.1 % a frame)."""
    rng = np.random.default_rng(5)
    ny, nx = shape
    bed = 0.3 * rng.random((ny, nx))
    still = np.maximum(0.5 - bed, 0.0)
    frames = np.repeat(still[None], 10, axis=0) + bed
    report = check_record(Record(frames, DX, DT), Water(sigma=0.0), bed=bed, at_rest=True)
    assert report.rows["mass"].ok and report.rows["lake_at_rest"].ok, report.report()
    leaking = bed + still[None] * (1 - 1e-3 * np.arange(10))[:, None, None]
    row = check_record(Record(leaking, DX, DT), Water(sigma=0.0), bed=bed, only=["mass"]).rows["mass"]
    assert not row.ok, row.report()


def _capillary(k, sigma=0.0728):
    return np.sqrt(G * k + sigma / 1000.0 * k ** 3)


@pytest.mark.parametrize("shape", [(64, 128), (128, 64)], ids=lambda s: f"{s[0]}x{s[1]}")
def test_a_stone_and_a_packet_on_a_strip(shape):
    """A stone off the strip's centre (ring arrival: capillary-gravity passes, a gravity-only scheme in
    capillary water is too slow) and a packet along the strip's long axis (group velocity: water passes, a
    wave equation moves its energy at the phase speed)."""
    ny, nx = shape
    dx, dt = 0.005, 1 / 240
    x = -0.5 * nx * dx + (np.arange(nx) + 0.5) * dx
    y = -0.5 * ny * dx + (np.arange(ny) + 0.5) * dx
    source = (0.25 * nx * dx * 0.5, -0.1 * ny * dx * 0.5)
    bump = 1e-3 * np.exp(-((x[None, :] - source[0]) ** 2 + (y[:, None] - source[1]) ** 2) / 0.01 ** 2)
    k = np.hypot(2 * np.pi * np.fft.fftfreq(nx, dx)[None, :], 2 * np.pi * np.fft.fftfreq(ny, dx)[:, None])
    t = np.arange(120)[:, None, None] * dt
    for omega, cause in ((_capillary, None), (lambda kk: np.sqrt(G * kk), "too slow")):
        eta = np.real(np.fft.ifft2(np.fft.fft2(bump) * np.cos(omega(k) * t), axes=(1, 2)))
        row = check_record(Record(eta, dx, dt), Water(), source=source, radius=0.03, only=["ring_arrival"]).rows[
            "ring_arrival"]
        assert row.ok if cause is None else (not row.ok and cause in row.note), row.report()
    # a packet along the long axis, 0.1 m cells (deep gravity water)
    dx, dt = 0.1, 1 / 30
    along_x = nx >= ny
    x = -0.5 * nx * dx + (np.arange(nx) + 0.5) * dx
    y = -0.5 * ny * dx + (np.arange(ny) + 0.5) * dx
    u, v = (x[None, :], y[:, None]) if along_x else (y[:, None], x[None, :])
    k0 = 2 * math.pi / 0.8
    eta0 = 1e-3 * np.exp(-(u ** 2 + v ** 2) / 1.0) * np.cos(k0 * u)
    kx, ky = 2 * np.pi * np.fft.fftfreq(nx, dx)[None, :], 2 * np.pi * np.fft.fftfreq(ny, dx)[:, None]
    ku, k = (kx if along_x else ky), np.hypot(kx, ky)
    t = np.arange(200)[:, None, None] * dt
    heading = 0.0 if along_x else 90.0
    for omega, cause in ((lambda kk: np.sqrt(G * kk), None), (lambda kk: 1.12 * kk, "phase speed")):
        eta = np.real(np.fft.ifft2(np.fft.fft2(eta0) * 2 * (ku > 0) * np.exp(-1j * omega(k) * t), axes=(1, 2)))
        row = check_record(Record(eta, dx, dt), Water(sigma=0.0), packet=True, direction=heading,
                           only=["group_velocity"]).rows["group_velocity"]
        assert row.ok if cause is None else (not row.ok and cause in row.note), row.report()
