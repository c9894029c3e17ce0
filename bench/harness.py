"""``python -m bench harness``: every check of a record, timed cold and warm on 128² × 256 and 256² × 512
records, a correct one and a faulty one each, against the time to read the frames from EXR files; with what
each check measures on a correct record (its floor) and the smallest fault it sees at its default tolerance.

Cold is a check's first run in the process (its imports and first allocations included); warm the median of
three later runs. The faulty records are the real bugs of the corpus at full strength (a wave equation, damping
per step, a cropped sea, a flipped sign, a standing sea, a wave-equation packet, a gravity-only stone, …): a check
must cost no more on them than on a correct record (its searches are bounded).

The records are generated here (numpy, seeded): a one-way Phillips sea (dispersion, energy,
tiling, quantization, standing waves, direction), a Gaussian packet (group velocity), a dropped
stone (ring arrival), an engine's steady wake (both wake angles), the sea's normal map, a caustics
map and the sea at half the resolution. Faults are scaled versions of the real bugs the corpus
holds: Δt mislabelled by a factor (dispersion), a velocity multiplier per step (energy), a
direction error (direction), a normal-map strength (normals), a wave speed (wake edge).
Run time is the second of two runs (the first compiles).
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests" / "harness"))  # the corpus's simulators: engine-style numpy

N, FRAMES, DX, DT = 128, 256, 0.25, 1 / 15


def _records():
    import corpus as c

    from wavephys.harness import Record

    sea = c.fft_ocean(c.phillips_h0(N, DX, seed=1), DX, DT, FRAMES)
    half = c.fft_ocean(c.phillips_h0(N // 2, 2 * DX, seed=2, cutoff=2 * DX), 2 * DX, DT, 8)
    full = c.fft_ocean(c.phillips_h0(N, DX, seed=1, cutoff=2 * DX), DX, DT, 8)
    packet = c.travelling_packet(N, 0.1, 1 / 30, FRAMES, 2 * math.pi / 0.8, 1.0)
    stone = c.spectral_model(c.gaussian_bump(N, 0.005, 0.01), 0.005, 1 / 240, FRAMES, sigma=0.0728)[0]
    wake = c.steady_wake_engine(2 * N, 0.0625, 1.0, 0.15)  # 16 m: arcs from 8 b = 5.3 m
    normals = c.normals_from_heights(full[0], DX)
    return dict(sea=Record.from_array(sea, DX, DT), packet=Record.from_array(packet, 0.1, 1 / 30),
                stone=Record.from_array(stone, 0.005, 1 / 240),
                wake=Record.from_array(np.repeat(wake[None], 8, 0), 0.0625, 0.05),
                full=Record.from_array(full, DX, DT), half=Record.from_array(half, 2 * DX, DT), normals=normals)


CASES = (  # check, record, water, claims
    ("dispersion", "sea", "deep", {}),
    ("energy", "sea", "deep", {}),
    ("tiling", "sea", "deep", {}),
    ("quantization", "sea", "deep", {}),
    ("standing", "sea", "deep", dict(sea=True)),
    ("direction", "sea", "deep", dict(direction=0.0)),
    ("group_velocity", "packet", "deep", dict(packet=True)),
    ("ring_arrival", "stone", "capillary", dict(source=(0.0, 0.0), radius=0.03)),
    ("wake_edge", "wake", "deep", dict(wake=dict(speed=1.0))),
    ("wake_max", "wake", "deep", dict(wake=dict(speed=1.0, size=0.15))),
    ("normals", "full", "deep", dict(normals="normals")),
    ("resolution", "full", "deep", dict(other="half")),
)


def _faults(n, frames):
    """For each check, a faulty record of the given size (and its claims), from the corpus's real bugs."""
    import corpus as c

    from wavephys.harness import Record

    sea = c.fft_ocean(c.phillips_h0(n, DX, seed=1), DX, DT, frames)
    h0 = c.phillips_h0(n, DX, seed=1)
    wave_eq = c.fft_ocean(h0, DX, DT, frames, depth=0.05)  # shallow: every k at one speed
    damped = sea * np.exp(-0.02 * np.arange(frames))[:, None, None]
    crop = c.fft_ocean(c.phillips_h0(n + n // 2, DX, seed=5), DX, DT, frames)[:, :n, :n]
    standing = c.fft_ocean(c.phillips_h0(n, DX, seed=1, one_way=False), DX, DT, frames, standing=True)
    flipped = c.fft_ocean(h0, DX, DT, frames, sign=+1)
    packet = c.travelling_packet(n, 0.1, 1 / 30, frames, 2 * math.pi / 0.8, 1.0, wave_equation_speed=1.12)
    stone = c.spectral_model(c.gaussian_bump(n, 0.005, 0.01), 0.005, 1 / 240, frames)[0]
    return {
        "dispersion": (Record.from_array(wave_eq, DX, DT, axes="tyx"), {}),
        "energy": (Record.from_array(damped, DX, DT, axes="tyx"), {}),
        "tiling": (Record.from_array(crop, DX, DT, axes="tyx"), {}),
        "quantization": (Record.from_array((sea * 5e-5).astype(np.float16) * 1.0, DX, DT, axes="tyx"), {}),
        "standing": (Record.from_array(standing, DX, DT, axes="tyx"), dict(sea=True)),
        "direction": (Record.from_array(flipped, DX, DT, axes="tyx"), dict(direction=0.0)),
        "group_velocity": (Record.from_array(packet, 0.1, 1 / 30, axes="tyx"), dict(packet=True)),
        "ring_arrival": (Record.from_array(stone, 0.005, 1 / 240, axes="tyx"), dict(source=(0.0, 0.0), radius=0.03)),
    }


def _corrects(n, frames):
    import corpus as c

    from wavephys.harness import Record

    sea = Record.from_array(c.fft_ocean(c.phillips_h0(n, DX, seed=1), DX, DT, frames), DX, DT, axes="tyx")
    packet = c.travelling_packet(n, 0.1, 1 / 30, frames, 2 * math.pi / 0.8, 1.0)
    stone = c.spectral_model(c.gaussian_bump(n, 0.005, 0.01), 0.005, 1 / 240, frames, sigma=0.0728)[0]
    return {name: (sea, claims) for name, claims in (("dispersion", {}), ("energy", {}), ("tiling", {}),
                                                     ("quantization", {}), ("standing", dict(sea=True)),
                                                     ("direction", dict(direction=0.0)))} | {
        "group_velocity": (Record.from_array(packet, 0.1, 1 / 30, axes="tyx"), dict(packet=True)),
        "ring_arrival": (Record.from_array(stone, 0.005, 1 / 240, axes="tyx"), dict(source=(0.0, 0.0), radius=0.03))}


def _read_seconds(record) -> float:
    """Seconds to read the record back from one EXR file a frame (as an engine exports it)."""
    import tempfile
    import time

    from optics.rendering.textures import export_height_frames
    from wavephys.harness import Record

    with tempfile.TemporaryDirectory() as tmp:
        export_height_frames(record.eta, record.shape[2] * record.dx, record.dt, Path(tmp) / "frames")
        start = time.perf_counter()
        Record.from_files(Path(tmp) / "frames")
        return time.perf_counter() - start


def cost_rows(sizes=((128, 256), (256, 512)), progress=print) -> list[dict]:
    """Every check cold and warm on a correct and a faulty record of each size, with the frames' read time."""
    import time

    from wavephys import Water
    from wavephys.harness import check_record

    rows = []
    for n, frames in sizes:
        good, bad = _corrects(n, frames), _faults(n, frames)
        read = _read_seconds(good["dispersion"][0])
        progress(f"{n}^2 x {frames}: reading the frames from EXR takes {read:.2f} s")
        for name in good:
            water = Water() if name == "ring_arrival" else Water(sigma=0.0)
            times = {}
            for kind, (record, claims) in (("correct", good[name]), ("faulty", bad[name])):
                runs = []
                for _ in range(4):
                    start = time.perf_counter()
                    report = check_record(record, water, only=[name], **claims)
                    runs.append(time.perf_counter() - start)
                times[kind] = (runs[0], float(np.median(runs[1:])), report.rows[name].ok)
            rows.append(dict(check=name, size=f"{n}^2 x {frames}", read_seconds=read,
                             correct_cold=times["correct"][0], correct_warm=times["correct"][1],
                             faulty_cold=times["faulty"][0], faulty_warm=times["faulty"][1],
                             correct_ok=times["correct"][2], faulty_ok=times["faulty"][2]))
            r = rows[-1]
            progress(f"  {name:15s} correct {r['correct_warm']:.3f} s warm ({r['correct_cold']:.3f} cold), faulty "
                     f"{r['faulty_warm']:.3f} s ({r['faulty_cold']:.3f}); verdicts {r['correct_ok']}/{r['faulty_ok']}")
    return rows


def timing_rows(progress=print) -> list[dict]:
    """Each check on a correct record: seconds (warm), the row's measured value (the floor) and tolerance."""
    from wavephys import Water
    from wavephys.harness import check_record

    recs = _records()
    waters = dict(deep=Water(sigma=0.0), capillary=Water())
    rows = []
    for name, which, water, claims in CASES:
        claims = {k: (recs[v] if isinstance(v, str) and k in ("normals", "other") else v) for k, v in claims.items()}
        for _ in range(2):
            report = check_record(recs[which], waters[water], only=[name], **claims)
        row = report.rows[name]
        r = recs[which]
        rows.append(dict(check=name, record=f"{r.shape[2]}x{r.shape[1]} x {r.shape[0]} frames",
                         seconds=report.seconds[name], ok=row.ok, measured=row.measured, error=row.error, expected=row.expected,
                         tolerance=row.tolerance, relation=row.relation, unit=row.unit))
        progress(f"{name}: {report.seconds[name]:.3f} s, {row.report()}")
    return rows


def _first_failure(make, levels, check):
    """The smallest fault level at which ``check(make(level))`` fails (None: none of them)."""
    for level in levels:
        if not check(make(level)).ok:
            return level
    return None


def sensitivity_rows(frames=(64, 256), progress=print) -> list[dict]:
    """The smallest fault each check sees at its default tolerance (through :func:`check_record`), per record
    length where the record's length matters."""
    import corpus as c

    from wavephys import Water
    from wavephys.harness import Record, check_record

    deep = Water(sigma=0.0)

    def fails(name, **claims):
        return lambda r: check_record(r, deep, only=[name], **claims).rows[name]

    rows = []
    for nt in frames:
        sea = c.fft_ocean(c.phillips_h0(N, DX, seed=1), DX, DT, nt)
        eta0 = c.random_heights(N, 3, k_cut=0.5)
        cases = (
            ("dispersion", "dt mislabelled by a factor 1 + f", (0.005, 0.01, 0.02, 0.03, 0.05),
             lambda f: Record.from_array(sea, DX, DT * (1 + f)), fails("dispersion")),
            ("energy", "eta_dot *= 1 - f each step", (1e-5, 3e-5, 1e-4, 3e-4, 1e-3),
             lambda f: Record.from_array(c.spectral_model(eta0, 0.1, 1 / 30, nt, velocity_factor=1 - f)[0], 0.1,
                                         1 / 30), fails("energy")),
            ("standing", "a standing part of relative amplitude f", (0.1, 0.2, 0.3, 0.5, 0.7, 1.0),
             lambda f: Record.from_array(sea + f * c.fft_ocean(c.phillips_h0(N, DX, seed=1, one_way=False), DX, DT,
                                                                 nt, standing=True), DX, DT), fails("standing", sea=True)),
        )
        for name, fault, levels, make, check in cases:
            rows.append(dict(check=name, frames=nt, fault=fault, smallest=_first_failure(make, levels, check)))
            progress(f"{name} ({nt} frames): smallest fault seen {rows[-1]['smallest']} ({fault})")
        direction = lambda f: check_record(Record.from_array(sea, DX, DT), deep, only=["direction"],  # noqa: E731
                                           direction=f).rows["direction"]
        rows.append(dict(check="direction", frames=nt, fault="claimed direction off by f degrees",
                         smallest=_first_failure(lambda f: f, (2.0, 5.0, 10.0, 15.0, 20.0, 30.0), direction)))
        progress(f"direction ({nt} frames): smallest fault seen {rows[-1]['smallest']}")
    from wavephys.harness import normals_check

    steep = 10 * c.fft_ocean(c.phillips_h0(N, DX, seed=1, cutoff=2 * DX), DX, DT, 1)[0]  # rms slope 0.1
    level = _first_failure(lambda f: f, (0.01, 0.02, 0.05, 0.1, 0.2),
                           lambda f: normals_check(steep, c.normals_from_heights(steep, DX, strength=1 + f), DX))
    rows.append(dict(check="normals", frames=1, fault="normal strength 1 + f (a sea of rms slope "
                                                     f"{float(np.std(np.gradient(steep, DX))):.2g})", smallest=level))
    progress(f"normals: smallest fault seen {level}")
    return rows
