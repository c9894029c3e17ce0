"""``python -m bench optics``: error against cost for the Fresnel family, RGB against
spectral absorption over path length, and the caustics methods against a brute-force
reference; the beam-tracing speed against one N = 512 simulation step.
"""

from __future__ import annotations

import math
import statistics

import jax
import jax.numpy as jnp
import numpy as np

from bench.timing import interleaved, median_seconds
from optics.caustics import floor_irradiance
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


def caustics_rows(progress=print) -> list[dict]:
    grid = Grid(128, 2.0)
    x, y = grid.mesh()
    w = 2 * math.pi / 2.0
    eta = (0.004 * jnp.cos(3 * w * x) * jnp.sin(2 * w * y) + 0.002 * jnp.sin(5 * w * (x + y))
           + 0.0015 * jnp.cos(7 * w * x - 3 * w * y))
    depth = 1.0
    progress("caustics reference (oversample 16)")
    ref = np.asarray(floor_irradiance(eta, grid, depth, method="reference", oversample=16))
    configs = [("beam", dict(samples=s), f"s={s}") for s in (1, 2, 4, 8)]
    configs += [("beam", dict(samples=1, blur=True), "s=1+blur"), ("beam", dict(samples=1, normals="central"), "s=1 central"),
                ("beam", dict(samples=4, normals="central"), "s=4 central")]
    configs += [("photon", dict(photons_per_texel=p), f"{p}/texel") for p in (1, 4, 16, 64)]
    configs += [("blinn_phong", {}, "tr=20"), ("reference", dict(oversample=4), "o=4")]
    rows = []
    for method, kw, label in configs:
        progress(f"caustics {method} {label}")
        f = lambda: floor_irradiance(eta, grid, depth, method=method, **kw)
        seconds = median_seconds(f, 5)
        out = np.asarray(f())
        rows.append(dict(family="caustics", method=method, label=label, n=128, dtype="float32", seconds=seconds,
                         baseline_seconds=None, error=float(np.linalg.norm(out - ref) / np.linalg.norm(ref))))
    return rows


def speed_rows(progress=print) -> list[dict]:
    """Beam tracing 512² → 512² against one N = 512 simulation step (interleaved); photon rate."""
    progress("caustics speed at 512²")
    grid = Grid(512, 16.0)
    sim = Simulation(grid, Water(), dt=1 / 30, margin=64)
    state, _ = sim.run(sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.3, 0.05)), 30)
    eta = sim.surface(state).eta
    fns = {"step": lambda: sim.step(state),
           "beam": lambda: floor_irradiance(eta, grid, 2.0, method="beam", samples=1),
           "beam central": lambda: floor_irradiance(eta, grid, 2.0, method="beam", samples=1, normals="central"),
           "photon": lambda: floor_irradiance(eta, grid, 2.0, method="photon", photons_per_texel=4)}
    times = interleaved(fns, repeats=15, block=3)
    med = {k: statistics.median(v) for k, v in times.items()}
    ratio = lambda k: statistics.median(b / s for b, s in zip(times[k], times["step"]))
    return [dict(family="caustics speed", method="beam (samples=1, spectral normals)", n=512, dtype="float32",
                 seconds=med["beam"], baseline_seconds=med["step"], baseline="simulation step n=512",
                 ratio=ratio("beam"), error=None),
            dict(family="caustics speed", method="beam (samples=1, central normals)", n=512, dtype="float32",
                 seconds=med["beam central"], baseline_seconds=med["step"], baseline="simulation step n=512",
                 ratio=ratio("beam central"), error=None),
            dict(family="caustics speed", method="photon (4/texel, bilateral)", n=512, dtype="float32",
                 seconds=med["photon"], baseline_seconds=med["step"], ratio=ratio("photon"),
                 photons_per_second=4 * 512 * 512 / med["photon"], error=None)]


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
    figs["caustics"] = plot_error_vs_time(ca, "caustics on a 128² surface: error vs time (reference: 16× rays)",
                                          ylabel="relative L2 error of the irradiance")
    return figs
