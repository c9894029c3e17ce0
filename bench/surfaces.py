"""``python -m bench surfaces``: every surface model's cost per frame against its physics error.

One instrument for all: each model's own output (64 × 64 over 32 m, 192 frames) goes
through :func:`wavephys.harness.measure_dispersion`, and the physics error is the relative
ω(k) error against capillary-free deep water over the shells that carry the sea (power ≥
1e-3 of the strongest), in the max norm and as an rms. The cost is one frame of heights on
an N × N grid, timed interleaved with the spectral simulation's step on the same grid
(ratios: machines are noisy). Also: the normals three ways for noise, the Gerstner crest
against Stokes, and the choppy resampling error against a fine reference.
"""

from __future__ import annotations

import statistics
import warnings

import jax
import jax.numpy as jnp
import numpy as np

from bench.timing import interleaved
from wavephys import Grid, Simulation, Water
from wavephys.checks.surfaces import crest_parting, normal_orders, random_sea
from wavephys.harness import measure_dispersion
from wavephys.physics.dispersion import angular_frequency, phase_speed
from wavephys.physics.wind import synthesize_height, wind_spectrum

WATER = Water(sigma=0.0)
WIND = dict(wind_speed=4.0, amplitude=3e-3)
RECORD = dict(n=64, length=32.0, frames=192)


def _spectrum(grid):
    ky, kx = grid.wavenumbers()
    return wind_spectrum(kx, ky, WATER, "phillips", small_wave_length=4 * float(grid.dx), **WIND)


def _models(grid, dt, key=jax.random.PRNGKey(0)):
    """name → (make(t) returning heights (n, n) at time t, label, the model object or None)."""
    from wavephys.surfaces import choppy
    from wavephys.surfaces.gerstner import GerstnerWaves
    from wavephys.surfaces.noise import NoiseSea
    from wavephys.surfaces.resample import resample_heights

    spec = _spectrum(grid)
    sea = synthesize_height(spec, grid, key)
    exact = jax.jit(lambda t: choppy.sea_height(sea, grid, WATER, t))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        gerstner = {c: GerstnerWaves.from_spectrum(spec, grid, key, count=c, steepness=0.5, water=WATER)
                    for c in (8, 32)}
    lam = min(1.0, 0.5 * choppy.fold_choppiness(exact(0.0), grid))  # the physical orbit, unless it folds

    def chop(t):
        h = exact(t)
        return resample_heights(choppy.displacement(h, grid, lam), h, grid, refine=1)

    noise = {o: NoiseSea(length=float(grid.length), amplitude=0.05, frequency=4 / float(grid.length), octaves=o,
                         base_amplitude=0.0, evolution=0.5) for o in (2, 4)}
    return {"gerstner 8 waves": (lambda t: gerstner[8].heights(grid, t), "exact inversion", gerstner[8]),
            "gerstner 32 waves": (lambda t: gerstner[32].heights(grid, t), "exact inversion", gerstner[32]),
            "choppy (resampled)": (chop, f"lambda = {lam:.2f}", None),
            "fbm 2 octaves": (lambda t: noise[2].heights(grid, t), "S&W", None),
            "fbm 4 octaves": (lambda t: noise[4].heights(grid, t), "", None)}


def _error(eta, dx, dt):
    s = measure_dispersion(np.asarray(eta), dx, dt, axes="tyx")
    keep = s.power >= 1e-3 * s.power.max()
    k, w = s.k[keep], s.omega[keep]
    err = w / np.asarray(angular_frequency(k, WATER), np.float64) - 1
    return float(np.max(np.abs(err))), float(np.sqrt(np.mean(err**2))), int(k.size)


def accuracy_rows(progress=print) -> list[dict]:
    """Physics error of each model from its own output, measured by the harness."""
    grid = Grid(RECORD["n"], RECORD["length"])
    dt = 0.1
    rows = []
    frames = RECORD["frames"]
    progress("surfaces: spectral simulation record")
    sim = Simulation(grid, WATER, dt=dt)
    state = sim.add_wind(sim.initial_state(), jax.random.PRNGKey(0), "phillips",
                         small_wave_length=4 * float(grid.dx), **WIND)
    _, surf = sim.run(state, frames)
    rows.append(("spectral simulation", np.asarray(surf.eta), "the reference"))
    progress("surfaces: finite differences record")
    from wavephys.core.stepper import TwoLevelState
    from wavephys.models.finite_difference import FiniteDifferenceStepper

    kp = 2 * np.pi / 10.0
    c = float(phase_speed(kp, WATER))
    sub = 2  # FD steps per frame, for a stable Courant number
    courant = c * dt / sub / float(grid.dx)
    h0 = np.asarray(surf.eta[0])
    end, states = FiniteDifferenceStepper(courant, dt / sub).trajectory(TwoLevelState(h0, h0), sub * frames)
    eta = np.concatenate([np.asarray(states.eta)[1:], np.asarray(end.eta)[None]])  # from rest: waves both ways
    rows.append(("finite differences", np.asarray(eta)[sub - 1::sub], f"c = {c:.2f} m/s, Courant {courant:.2f}"))
    for name, (make, label, _) in _models(grid, dt).items():
        progress(f"surfaces: {name} record")
        rows.append((name, np.stack([np.asarray(make(i * dt)) for i in range(frames)]), label))
    out = []
    for name, eta, label in rows:
        worst, rms, shells = _error(eta, float(grid.dx), dt)
        out.append(dict(family="surface physics", method=name, error=worst, rms_error=rms, shells=shells,
                        label=label, n=RECORD["n"], frames=frames))
    return out


def cost_rows(sizes=(256, 512), progress=print) -> list[dict]:
    """Seconds per frame of heights for each model on N × N, against the spectral step."""
    rows = []
    for n in sizes:
        grid = Grid(n, 128.0)
        dt = 1 / 30
        sim = Simulation(grid, WATER, dt=dt)
        state = sim.add_wind(sim.initial_state(), jax.random.PRNGKey(0), "phillips", **WIND)
        models = _models(grid, dt)
        from wavephys.models.finite_difference import fd_step

        h0 = sim.surface(state).eta
        courant = float(phase_speed(2 * np.pi / 10.0, WATER)) * dt / float(grid.dx)
        fd = jax.jit(lambda a, b: fd_step(a, b, min(courant, 0.7)))
        fns = {"spectral simulation": lambda: sim.surface(sim.step(state)[0]).eta,
               "finite differences": lambda: fd(h0, h0)}
        for name, (make, *_) in models.items():
            fns[name] = lambda make=make: make(0.5)
        mesh = models["gerstner 32 waves"][2]
        x, y = grid.mesh()
        fns["gerstner 32 waves, displaced mesh"] = lambda: mesh.displacement(x, y, 0.5)
        progress(f"surfaces: timing at N = {n}")
        times = interleaved(fns, repeats=5, block=3, warmup=1)
        base = statistics.median(times["spectral simulation"])
        for name, t in times.items():
            rows.append(dict(family="surface cost", method=name, n=n, seconds=statistics.median(t),
                             baseline_seconds=base, ratio=statistics.median(t) / base, dtype="float32"))
    return rows


def detail_rows(progress=print) -> list[dict]:
    """Normals three ways (noise), the Gerstner crest against Stokes, choppy resampling error."""
    from wavephys.surfaces import choppy
    from wavephys.surfaces.gerstner import crest_comparison
    from wavephys.surfaces.resample import resample_heights

    rows = []
    progress("surfaces: noise normals")
    for seed in range(3):
        o = normal_orders(seed=seed)
        for m, v in o.items():
            rows.append(dict(family="noise normals", method=m, seed=seed, error=v["error"], error_half=v["error_half"],
                             order=v["order"], step=0.04))
    progress("surfaces: Gerstner crest vs Stokes")
    for s in (0.05, 0.1, 0.15, 0.2, 0.25, 0.3):
        c = crest_comparison(s)
        rows.append(dict(family="gerstner crest", steepness=s, crest_error=c["crest_error"],
                         trough_error=c["trough_error"], mean_level=c["gerstner_mean"], height=c["height"]))
    rows.append(dict(family="gerstner crest parting", tolerance=0.01, steepness=crest_parting(0.01)))
    progress("surfaces: choppy resampling")
    for seed in range(3):
        sea, grid = random_sea(n=128, length=64.0, seed=seed)
        fold = choppy.fold_choppiness(sea, grid)
        for frac in (0.25, 0.5, 0.75, 0.9):
            d = choppy.displacement(sea, grid, frac * fold)
            ref = resample_heights(d, sea, grid, refine=8, iterations=16)
            span = float(jnp.ptp(sea))
            for r in (1, 2, 4):
                diff = resample_heights(d, sea, grid, refine=r) - ref
                rows.append(dict(family="choppy resampling", seed=seed, fraction_of_fold=frac, refine=r,
                                 max_error=float(jnp.max(jnp.abs(diff))) / span,
                                 rms_error=float(jnp.sqrt(jnp.mean(diff**2))) / span))
    progress("surfaces: choppy fold boundary")
    for wind in (4.0, 6.0, 8.0):
        for seed in range(3):
            sea, grid = random_sea(n=128, length=64.0, seed=seed, wind_speed=wind)
            fold = choppy.fold_choppiness(sea, grid)
            m = jnp.fft.irfft2(grid.wavenumber_magnitude(True) * jnp.fft.rfft2(sea), s=(grid.n, grid.n))
            sigma = choppy.jacobian_std(sea, grid)
            rows.append(dict(family="choppy fold", wind_speed=wind, seed=seed, fold_choppiness=fold, sigma1=sigma,
                             product=fold * sigma, first_order=1.0 / float(jnp.max(m))))
    return rows


def figures(rows) -> dict:
    from wavephys.plot import plot_curves, plot_error_vs_time

    acc = {r["method"]: r for r in rows if r["family"] == "surface physics"}
    cost = [r for r in rows if r["family"] == "surface cost"]
    figs = {}
    if acc and cost:
        n = max(r["n"] for r in cost)
        pts = [dict(method=r["method"], seconds=r["seconds"], error=max(acc[r["method"]]["error"], 1e-5),
                    label=f"{r['ratio']:.2g}x step") for r in cost if r["n"] == n and r["method"] in acc]
        floor = acc["spectral simulation"]["error"] if "spectral simulation" in acc else None
        figs["cost_vs_error"] = plot_error_vs_time(
            pts, f"surface models on {n}x{n}: dispersion error against cost per frame",
            ylabel="max |omega_measured / omega_water - 1| (harness)", floor=floor)
    crest = [r for r in rows if r["family"] == "gerstner crest"]
    if crest:
        figs["crest"] = plot_curves({"crest": ([r["steepness"] for r in crest], [abs(r["crest_error"]) for r in crest]),
                                     "trough": ([r["steepness"] for r in crest],
                                                [abs(r["trough_error"]) for r in crest])},
                                    "steepness kA", "relative elevation difference",
                                    "Gerstner vs exact Stokes, same height", logx=True)
    fold = [r for r in rows if r["family"] == "choppy fold"]
    if fold:
        curves = {}
        for wind in sorted({r["wind_speed"] for r in fold}):
            pts = sorted((r["sigma1"], r["fold_choppiness"]) for r in fold if r["wind_speed"] == wind)
            curves[f"U = {wind:g} m/s"] = ([p[0] for p in pts], [p[1] for p in pts])
        s = np.array([r["sigma1"] for r in fold])
        mean = float(np.mean([r["product"] for r in fold]))
        grid_s = np.geomspace(s.min() * 0.8, s.max() * 1.25, 20)
        curves[f"lambda = {mean:.2f} / sigma1 (mean)"] = (grid_s, mean / grid_s)
        figs["fold"] = plot_curves(curves, "sigma1 = rms of F^-1[|k| h] (steepness)", "fold choppiness lambda_f",
                                   "choppy waves fold where lambda > lambda_f: the boundary", logx=True)
    return figs
