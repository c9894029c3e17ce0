"""The Jacobian caustics method: its error against the converged reference as the floor goes from
well above to past the first fold, which cases the gather answers itself and which the beam takes
over, and its cost against a simulation step and the default beam (same run, interleaved)."""

from __future__ import annotations

import statistics
import warnings

import numpy as np

from bench.timing import interleaved
from optics.light.directions import sun_direction
from wavephys import Grid, Simulation, Stones, Water

FRACTIONS = (0.1, 0.3, 0.5, 0.7, 0.8, 0.9, 1.0, 1.2, 1.5)
"""Floor depths, as fractions of the first fold of each case's own sun."""


def boundary_rows(progress=print, seeds=(1, 2), n: int = 128) -> list[dict]:
    """Every spectrum × seed × sun (vertical, 55° from a random azimuth) × floor fraction:
    max-norm and L2 error of ``method="jacobian"`` against the converged reference, and
    whether the gather answered (``gather``) or the beam took over (``fallback``)."""
    from optics.caustics import (SURFACE_SPECTRA, converged_floor_irradiance, first_fold_depth, floor_irradiance,
                                 random_surface)

    grid = Grid(n, 3.0)
    rows = []
    for spectrum in SURFACE_SPECTRA:
        for seed in seeds:
            eta = random_surface(grid, spectrum, 0.12, seed)
            az = np.random.default_rng(seed).uniform(0.0, 360.0)
            for elevation in (90.0, 55.0):
                sun = sun_direction(elevation, az)
                fold = first_fold_depth(eta, grid, sun)
                progress(f"jacobian boundary: {spectrum} seed {seed} sun {elevation:.0f} deg (first fold {fold:.3g} m)")
                for fraction in FRACTIONS:
                    ref = converged_floor_irradiance(eta, grid, fraction * fold, sun, tolerance=2e-3)
                    with warnings.catch_warnings(record=True) as caught:
                        warnings.simplefilter("always")
                        out = np.asarray(floor_irradiance(eta, grid, fraction * fold, sun, method="jacobian"),
                                         np.float64)
                    diff = out - ref.irradiance
                    rows.append(dict(family="jacobian boundary", spectrum=spectrum, seed=seed, elevation=elevation,
                                     fraction=fraction, n=n, answered="fallback" if caught else "gather",
                                     error=float(np.max(np.abs(diff)) / ref.irradiance.max()),
                                     l2_error=float(np.linalg.norm(diff) / np.linalg.norm(ref.irradiance)),
                                     reference_bound=ref.bound, reference_converged=ref.converged))
    return rows


def speed_rows(progress=print, sizes=(256, 512)) -> list[dict]:
    """Cost of a jacobian map (n² → n², the bench's rippled pond, far above its first fold)
    against one simulation step and the default beam (refine 3) of the same n, interleaved."""
    from optics.caustics import first_fold_depth, floor_irradiance

    rows = []
    for n in sizes:
        progress(f"jacobian speed at {n}²")
        grid = Grid(n, 16.0)
        sim = Simulation(grid, Water(), dt=1 / 30, margin=n // 8)
        state, _ = sim.run(sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.3, 0.05)), 30)
        eta = sim.surface(state).eta
        fns = {"step": lambda: sim.step(state), "beam (refine 3)": lambda: floor_irradiance(eta, grid, 2.0),
               "jacobian (auto)": lambda: floor_irradiance(eta, grid, 2.0, method="jacobian"),
               "jacobian (supersample 2)": lambda: floor_irradiance(eta, grid, 2.0, method="jacobian", supersample=2)}
        times = interleaved(fns, repeats=3, block=3)
        fold = first_fold_depth(eta, grid)
        for name in fns:
            if name == "step":
                continue
            rows.append(dict(family="jacobian speed", method=name, n=n, seconds=statistics.median(times[name]),
                             baseline_seconds=statistics.median(times["step"]), baseline="simulation step",
                             ratio=statistics.median(b / s for b, s in zip(times[name], times["step"])),
                             depth_over_first_fold=2.0 / fold))
    return rows


def figures(rows) -> dict:
    import matplotlib.pyplot as plt  # figures only

    rows = [r for r in rows if r["family"] == "jacobian boundary"]
    fig, ax = plt.subplots(figsize=(7.0, 4.2), layout="constrained")
    for answered, marker in (("gather", "o"), ("fallback", "x")):
        sel = [r for r in rows if r["answered"] == answered]
        ax.semilogy([r["fraction"] + (0.01 if r["elevation"] < 90 else -0.01) for r in sel],
                    [max(r["error"], 1e-6) for r in sel], marker, ls="none",
                    label="the gather answered" if answered == "gather" else "folded: the beam answered")
    ax.axhline(0.01, color="0.5", ls="--", lw=0.8, label="1 % of the peak")
    ax.axvline(1.0, color="0.7", lw=0.8)
    ax.set(xlabel="floor depth / first-fold depth (of the case's own sun)", ylabel="max |E - E_ref| / peak",
           title=f"jacobian caustics over {len({(r['spectrum'], r['seed'], r['elevation']) for r in rows})} "
                 "generated surfaces and suns")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    return {"boundary": fig}
