"""``python -m bench optics``: error against cost for the Fresnel family, RGB against
spectral absorption over path length, and the caustics methods against a brute-force
reference; the beam-tracing speed against one N = 512 simulation step.
"""

from __future__ import annotations

import statistics

import jax
import jax.numpy as jnp
import numpy as np

from bench.timing import interleaved, median_seconds
from optics.light.directions import sun_direction
from optics.caustics import floor_irradiance
from optics.gpu import RendererUnavailable
from optics.light.attenuation import fit_rgb_coefficients, rgb_error
from optics.light.fresnel import N_AIR, N_WATER, approximation_errors, reflectance
from wavephys import Grid, Simulation, Stones, Water
from wavephys.plot import plot_curves, plot_error_vs_time


def fresnel_rows(progress=print) -> list[dict]:
    rows = []
    c = jnp.asarray(np.random.default_rng(0).uniform(0, 1, 1_000_000), jnp.float32)
    variants = [("schlick", {}), ("jensen_golias", {}), ("loviscach", {}), ("lut", dict(size=16)),
                ("lut", dict(size=64)), ("lut", dict(size=256))]
    for side, (n1, n2) in (("above", (N_AIR, N_WATER)), ("below", (N_WATER, N_AIR))):
        fns = {"exact": jax.jit(lambda c: reflectance(c, n1, n2))}
        for m, kw in variants:
            fns[f"{m}{kw.get('size', '')}"] = jax.jit(lambda c, m=m, kw=kw: reflectance(c, n1, n2, method=m, **kw))
        progress(f"Fresnel timing, {side}")
        times = interleaved({k: (lambda f=f: f(c)) for k, f in fns.items()}, repeats=7, block=3)
        base = statistics.median(times["exact"])
        for (m, kw) in variants:
            key = f"{m}{kw.get('size', '')}"
            e = approximation_errors(m, n1, n2, **kw)
            rows.append(dict(family="fresnel", method=key, side=side, worst_error=e["worst"], worst_angle=e["angle"],
                             weighted_mean_error=e["weighted_mean"], seconds_per_1M=statistics.median(times[key]),
                             baseline_seconds=base, n=1_000_000, dtype="float32", seconds=statistics.median(times[key]),
                             error=abs(e["worst"])))
    return rows


def absorption_rows() -> list[dict]:
    coeffs = fit_rgb_coefficients(5.0)
    d = np.geomspace(0.1, 50.0, 30)
    err = rgb_error(d, coeffs)
    return [dict(family="absorption", method="rgb fitted on (0, 5] m", distance=float(a), error=float(b),
                 coefficients=coeffs.tolist()) for a, b in zip(d, err)]


CAUSTICS_CONFIGS = ([("beam", dict(refine=r), f"refine={r}") for r in (1, 2, 3, 4)]
                    + [("jacobian", {}, "auto")]
                    + [("beam", dict(refine=r, normals="central"), f"refine={r} central") for r in (1, 3)]
                    + [("gl", dict(supersample=s), f"supersample={s}") for s in (1, 4, 8)]
                    + [("gl", dict(refine=3, supersample=s), f"refine=3 ss={s}") for s in (4, 8)]
                    + [("photon", dict(photons_per_texel=p), f"{p}/texel") for p in (1, 4, 16, 64)]
                    + [("blinn_phong", {}, "tr=20")])
"""Caustics methods and settings measured over the surface family."""


def _family(count: int, seed: int = 2024):
    """``count`` cases nobody picked: a spectrum, a steepness, a sun, a depth (fraction of the
    first fold), a 90° turn, on Grid(128, 2 m)."""
    from optics.caustics import SURFACE_SPECTRA, first_fold_depth, random_surface

    rng = np.random.default_rng(seed)
    grid = Grid(128, 2.0)
    for i in range(count):
        spectrum = SURFACE_SPECTRA[i % len(SURFACE_SPECTRA)]
        eta = random_surface(grid, spectrum, float(rng.uniform(0.03, 0.15)), int(rng.integers(1 << 30)))
        if rng.random() < 0.5:
            eta = jnp.rot90(eta)
        elevation, azimuth = rng.uniform(40.0, 90.0), rng.uniform(0.0, 360.0)
        sun = sun_direction(elevation, azimuth)
        fraction = (0.3, 0.6, 0.9)[i % 3]
        depth = fraction * first_fold_depth(eta, grid, sun)
        yield dict(case=i, spectrum=spectrum, elevation=elevation, fraction=fraction, depth=depth), \
            grid, eta, sun


def caustics_rows(progress=print, count: int = 9) -> list[dict]:
    """Every method and setting against the converged reference over ``count`` generated 2-D
    surfaces: max-norm and L2 error (relative to the peak and to the map), seconds per map
    and that cost relative to one simulation step on the same 128² grid."""
    from optics.caustics import converged_floor_irradiance

    sim = Simulation(Grid(128, 2.0), Water(), dt=1 / 30, margin=16)
    state = sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.1, 0.005))
    step = median_seconds(lambda: sim.step(state), 9)
    rows = []
    for info, grid, eta, sun in _family(count):
        progress(f"caustics case {info['case']}: {info['spectrum']}, sun {info['elevation']:.0f} deg, "
                 f"{info['fraction']} of the first fold")
        ref = converged_floor_irradiance(eta, grid, info["depth"], sun, tolerance=1e-3, max_refine=32)
        peak = float(ref.irradiance.max())
        rows.append(dict(family="caustics reference", **info, bound=ref.bound, refine=ref.refine,
                         converged=ref.converged, peak=peak))
        for method, kw, label in CAUSTICS_CONFIGS:
            f = lambda: floor_irradiance(eta, grid, info["depth"], sun, method=method, **kw)
            try:
                seconds = median_seconds(f, 3)
            except RendererUnavailable as exc:
                progress(f"  {method}: {exc}")
                continue
            out = np.asarray(f(), np.float64)
            diff = out - ref.irradiance
            rows.append(dict(family="caustics", method=method, label=label, **info, n=128, dtype="float32",
                             seconds=seconds, baseline_seconds=step, ratio=seconds / step,
                             error=float(np.max(np.abs(diff)) / peak),
                             l2_error=float(np.linalg.norm(diff) / np.linalg.norm(ref.irradiance)),
                             min_value=float(out.min()), reference_bound=ref.bound))
    return rows


def speed_rows(progress=print) -> list[dict]:
    """The caustics methods on 512² → 512² against one N = 512 simulation step (interleaved)."""
    progress("caustics speed at 512²")
    grid = Grid(512, 16.0)
    sim = Simulation(grid, Water(), dt=1 / 30, margin=64)
    state, _ = sim.run(sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.3, 0.05)), 30)
    eta = sim.surface(state).eta
    configs = {"beam (refine=1)": dict(method="beam", refine=1), "beam (refine=3, default)": dict(method="beam"),
               "jacobian (auto)": dict(method="jacobian"),
               "gl (supersample=4, llvmpipe)": dict(method="gl", supersample=4),
               "photon (4/texel, bilateral)": dict(method="photon", photons_per_texel=4)}
    fns = {"step": lambda: sim.step(state)}
    for name, kw in configs.items():
        fns[name] = lambda kw=kw: floor_irradiance(eta, grid, 2.0, **kw)
    try:
        floor_irradiance(eta, grid, 2.0, method="gl", supersample=1)
    except RendererUnavailable:
        fns.pop("gl (supersample=4, llvmpipe)")
    times = interleaved(fns, repeats=3, block=3)
    med = {k: statistics.median(v) for k, v in times.items()}
    rows = []
    for name in fns:
        if name == "step":
            continue
        ratio = statistics.median(b / s for b, s in zip(times[name], times["step"]))
        row = dict(family="caustics speed", method=name, n=512, dtype="float32", seconds=med[name],
                   baseline_seconds=med["step"], baseline="simulation step n=512", ratio=ratio, error=None)
        if name.startswith("photon"):
            row["photons_per_second"] = 4 * 512 * 512 / med[name]
        rows.append(row)
    return rows


def figures(rows) -> dict:
    figs = {}
    for side in ("above", "below"):
        fr = [dict(method=r["method"], seconds=r["seconds"], error=max(r["error"], 1e-7), label="")
              for r in rows if r.get("family") == "fresnel" and r["side"] == side]
        figs[f"fresnel_{side}"] = plot_error_vs_time(fr, f"Fresnel approximations, light from {side}: worst error vs time (1M)",
                                                   ylabel="worst |R - R_exact| over the angles")
    ab = [r for r in rows if r.get("family") == "absorption"]
    figs["absorption"] = plot_curves({"RGB fitted on (0, 5] m": ([r["distance"] for r in ab], [r["error"] for r in ab])},
                                     "path length in pure water (m)", "max |RGB − spectral| (linear sRGB)",
                                     "RGB Beer–Lambert against the spectral reference", logx=True)
    ca = [r for r in rows if r.get("family") == "caustics"]
    if ca:
        figs["caustics"] = _caustics_figure(ca)
    return figs


def _caustics_figure(rows):
    """Error (max norm and L2, worst over the family) against cost relative to a step."""
    import matplotlib.pyplot as plt  # figures only

    fig, axes = plt.subplots(1, 2, figsize=(11.0, 4.4), layout="constrained")
    series = lambda r: (f"{r['method']} (central normals)" if "central" in r["label"] else
                        f"{r['method']} refine=3" if r["method"] == "gl" and "refine=3" in r["label"] else r["method"])
    keys = sorted({(series(r), r["label"]) for r in rows})
    for ax, (field, title) in zip(axes, (("error", "max |E - E_ref| / peak (worst case)"),
                                         ("l2_error", "||E - E_ref|| / ||E_ref|| (worst case)"))):
        for method in sorted({k[0] for k in keys}):
            pts = []
            for m, label in keys:
                if m != method:
                    continue
                sel = [r for r in rows if series(r) == m and r["label"] == label]
                pts.append((statistics.median(r["ratio"] for r in sel), max(r[field] for r in sel), label))
            pts.sort()
            ax.loglog([p[0] for p in pts], [p[1] for p in pts], "o-", label=method)
            for x, y, label in pts:
                ax.annotate(label, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
        ax.axhline(0.01, color="0.5", lw=0.8, ls="--")
        ax.set_xlabel("cost, in simulation steps on the same 128² grid (median over the family)")
        ax.set_ylabel(title)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Caustics on {len({r['case'] for r in rows})} generated 2-D surfaces (3 spectra, suns 40-90 deg, "
                 "0.3-0.9 of the first fold) against the converged reference", fontsize=9)
    return fig
