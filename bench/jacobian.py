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


def boundary_rows(progress=print, seeds=(1, 2), n: int = 128, max_refine: int = 8) -> list[dict]:
    """Every spectrum × seed × sun (vertical, 55° from a random azimuth) × floor fraction:
    max-norm and L2 error of ``method="jacobian"`` against the converged reference, and
    how it answered: the gather alone (``gather``), the gather with the beam on the folded
    windows (``windows``, and the fraction of the floor they cover), or the beam (``beam``)."""
    from optics.caustics import SURFACE_SPECTRA, converged_floor_irradiance, first_fold_depth, random_surface
    from optics.caustics.jacobian import _jacobian

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
                    out, info = _jacobian(eta, grid, fraction * fold, sun, None, 1.333, True, 1, "auto", 4, "windows")
                    out = np.asarray(out, np.float64)
                    ref = converged_floor_irradiance(eta, grid, fraction * fold, sun, n_water=1.333, tolerance=2e-3,
                                                     max_refine=max_refine)
                    diff = out - ref.irradiance
                    rows.append(dict(family="jacobian boundary", spectrum=spectrum, seed=seed, elevation=elevation,
                                     fraction=fraction, n=n, answered=info["answer"], windows=info["windows"],
                                     error=float(np.max(np.abs(diff)) / ref.irradiance.max()),
                                     l2_error=float(np.linalg.norm(diff) / np.linalg.norm(ref.irradiance)),
                                     reference_bound=ref.bound, reference_converged=ref.converged))
    return rows


def size_rows(progress=print, sizes=(64, 256, 512), fraction: float = 0.5) -> list[dict]:
    """The wind-sea family (Phillips and JONSWAP, a sun at 25° and at 70° from a random azimuth)
    at several grid sizes, the floor at ``fraction`` of the first fold: max-norm and L2 error of the
    jacobian method against the converged beam (refine up to 8), and how it answered."""
    from optics.caustics import converged_floor_irradiance, first_fold_depth, random_surface
    from optics.caustics.jacobian import _jacobian

    rows = []
    for n in sizes:
        grid = Grid(n, 3.0 * n / 128)  # the same waves per sample at every size: more of them
        for spectrum in ("phillips", "jonswap"):
            for elevation in (25.0, 70.0):
                rng = np.random.default_rng(n + int(elevation))
                eta = random_surface(grid, spectrum, 0.12, int(rng.integers(1 << 30)))
                sun = sun_direction(elevation, rng.uniform(0.0, 360.0))
                depth = fraction * first_fold_depth(eta, grid, sun)
                progress(f"jacobian wind seas: {spectrum} at {n}², sun {elevation:.0f} deg")
                ref = converged_floor_irradiance(eta, grid, depth, sun, n_water=1.333, tolerance=2e-3, max_refine=8)
                out, info = _jacobian(eta, grid, depth, sun, None, 1.333, True, 1, "auto", 4, "windows")
                diff = np.asarray(out, np.float64) - ref.irradiance
                rows.append(dict(family="jacobian wind seas", spectrum=spectrum, n=n, elevation=elevation,
                                 fraction=fraction, answered=info["answer"], windows=info["windows"],
                                 supersample=info["supersample"],
                                 error=float(np.max(np.abs(diff)) / ref.irradiance.max()),
                                 l2_error=float(np.linalg.norm(diff) / np.linalg.norm(ref.irradiance)),
                                 reference_bound=ref.bound))
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


def scene_rows(progress=print, n: int = 256, times=(1.0, 2.5), reference: bool = True) -> list[dict]:
    """The built-in scenes' caustics maps (the water at ``times``, over the scene's ground, relative
    to flat water) by the default beam and by the Jacobian gather with its folded windows: cost
    (interleaved, both maps of a frame: wavy and flat), how the gather answered, and with
    ``reference`` the max-norm and L2 errors of both against the converged beam."""
    from optics.caustics import converged_floor_irradiance
    from optics.caustics.jacobian import _jacobian
    from wavephys.app.scenes import SCENES, SUN, _ground, scene_caustics, scene_grid, scene_water

    rows = []
    for name in SCENES:
        for t in times:
            progress(f"jacobian on the {name} scene at {n}², t = {t} s")
            water = scene_water(name, n, t)
            grid = scene_grid(name, n)
            floor = np.minimum(_ground(name, n)[0], water.min() - 0.05).astype(np.float32)
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                _, info = _jacobian(water, grid, floor, SUN, None, 1.333, True, 1, "auto", 4, "windows")
                fns = {"beam (refine 3)": lambda: scene_caustics(name, water, "beam"),
                       "jacobian": lambda: scene_caustics(name, water, "jacobian")}
                timing = interleaved(fns, repeats=3, block=3)
            row = dict(family="jacobian scenes", scene=name, n=n, time=t, answered=info["answer"],
                       windows=info["windows"], beam_seconds=statistics.median(timing["beam (refine 3)"]),
                       jacobian_seconds=statistics.median(timing["jacobian"]),
                       saving=statistics.median(b / j for b, j in zip(timing["beam (refine 3)"], timing["jacobian"])))
            if reference:
                ref = converged_floor_irradiance(water, grid, floor, SUN, n_water=1.333, tolerance=3e-3, max_refine=8)
                r = np.asarray(ref.irradiance, np.float64)
                for method in ("beam", "jacobian"):
                    from optics.caustics import floor_irradiance

                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        out = np.asarray(floor_irradiance(water, grid, floor, SUN, method=method, n_water=1.333),
                                         np.float64)
                    row[f"{method}_error"] = float(np.max(np.abs(out - r)) / r.max())
                    row[f"{method}_l2_error"] = float(np.linalg.norm(out - r) / np.linalg.norm(r))
                row["reference_bound"] = ref.bound
            rows.append(row)
    return rows


def figures(rows) -> dict:
    import matplotlib.pyplot as plt  # figures only

    rows = [r for r in rows if r["family"] == "jacobian boundary"]
    fig, ax = plt.subplots(figsize=(7.0, 4.2), layout="constrained")
    labels = {"gather": "the gather alone", "windows": "the gather, the beam on the folded windows",
              "beam": "folded over half the floor: the beam"}
    for answered, marker in (("gather", "o"), ("windows", "s"), ("beam", "x")):
        sel = [r for r in rows if r["answered"] == answered]
        ax.semilogy([r["fraction"] + (0.01 if r["elevation"] < 90 else -0.01) for r in sel],
                    [max(r["error"], 1e-6) for r in sel], marker, ls="none", mfc="none", label=labels[answered])
    ax.axhline(0.01, color="0.5", ls="--", lw=0.8, label="1 % of the peak")
    ax.axvline(1.0, color="0.7", lw=0.8)
    ax.set(xlabel="floor depth / first-fold depth (of the case's own sun)", ylabel="max |E - E_ref| / peak",
           title=f"jacobian caustics over {len({(r['spectrum'], r['seed'], r['elevation']) for r in rows})} "
                 "generated surfaces and suns")
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    return {"boundary": fig}
