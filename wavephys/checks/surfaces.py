"""Validations of the cheap surface models against the wave physics: what each gets right,
what it gets wrong, and by how much (docs/physics.md §1.9).

Every scene is seeded, so the rows are reproducible; the tests run the same measurements
over families of seeds, directions, depths and steepnesses.
"""

from __future__ import annotations

import math

import jax
import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.water import Water
from wavephys.harness.checks import Check, bound, compare
from wavephys.harness.dispersion import dispersion_error, measure_dispersion

__all__ = ["check_noise_surfaces", "check_gerstner", "check_choppy"]  # the helpers below are the scenes' own


def fbm_spectrum(hurst: float, n: int = 256, length: float = 64.0, octaves: int = 7, seed: int = 0) -> float:
    """Measured slope d ln F/d ln k of a still fBm's radially averaged height spectrum, fitted
    over the wavenumbers of octaves 1–5 (the first and last octave have no neighbours)."""
    from wavephys.surfaces.noise import fbm

    grid = Grid(n, length)
    x, y = grid.mesh()
    f0 = 4.0 / length
    h = np.asarray(fbm(x, y, None, octaves=octaves, frequency=f0, tile=length, hurst=hurst, seed=seed), np.float64)
    power = np.abs(np.fft.fft2(h)) ** 2
    k = np.asarray(grid.wavenumber_magnitude(), np.float64).ravel()
    k0 = 2 * np.pi * f0
    bins = np.geomspace(1.5 * k0, k0 * 2**5, 16)
    idx = np.digitize(k, bins)
    kc, pc = [], []
    for b in range(1, len(bins)):
        sel = idx == b
        if sel.any():
            kc.append(k[sel].mean())
            pc.append(power.ravel()[sel].mean())
    return float(np.polyfit(np.log(kc), np.log(pc), 1)[0])


def noise_dispersion(time_exponent: float = 1.0, n: int = 64, length: float = 16.0, frames: int = 128,
                     dt: float = 0.1, seed: int = 0) -> dict:
    """ω(k) measured by :func:`~wavephys.harness.measure_dispersion` from an animated fBm
    (4 octaves, time as a noise axis): the fitted slope d ln ω/d ln k and the worst
    relative distance from capillary-gravity waves over 0.5–6 rad/m."""
    from wavephys.surfaces.noise import fbm

    grid = Grid(n, length)
    x, y = grid.mesh()
    frame = jax.jit(lambda t: fbm(x, y, t, octaves=4, frequency=4.0 / length, tile=length, evolution=0.5,
                                  time_exponent=time_exponent, seed=seed))
    eta = np.stack([np.asarray(frame(i * dt)) for i in range(frames)])
    samples = measure_dispersion(eta, float(grid.dx), dt, axes="tyx").select(0.5, 6.0)
    slope = float(np.polyfit(np.log(samples.k), np.log(samples.omega), 1)[0])
    return dict(slope=slope, worst=float(np.max(np.abs(dispersion_error(samples, Water())))), shells=samples.k.size)


def normal_orders(seed: int = 0, points: int = 4096) -> dict:
    """Errors of the ``shifted`` (S&W) and ``central`` fBm slopes against the exact one at
    random points, at steps h and h/2, and the observed orders log₂(e(h)/e(h/2))."""
    from wavephys.surfaces.noise import noise_gradient

    rng = np.random.default_rng(seed)
    x, y = (rng.uniform(-8, 8, points).astype(np.float32) for _ in range(2))
    params = dict(octaves=2, frequency=0.5, amplitude=0.05, seed=seed)
    gx, gy = (np.asarray(g, np.float64) for g in noise_gradient(x, y, 0.7, method="exact", **params))
    scale = float(np.max(np.hypot(gx, gy)))
    out = {}
    for method in ("shifted", "central"):
        errs = []
        for step in (0.04, 0.02):
            ax, ay = (np.asarray(g, np.float64) for g in noise_gradient(x, y, 0.7, method=method, step=step, **params))
            errs.append(float(np.max(np.hypot(ax - gx, ay - gy))) / scale)
        out[method] = dict(error=errs[0], error_half=errs[1], order=math.log2(errs[0] / errs[1]))
    return out


def check_noise_surfaces() -> list[Check]:
    """fBm: its height spectrum's slope, its (absent) dispersion, and its normals three ways.

    Returns
    -------
    list of Check
        Six rows: the height spectrum slope d ln F/d ln k of a still fBm at H = 0.5 and 1 against
        −(2H + 2) (atol 0.2); the H = 1 slope against a wind sea's k⁻⁴ tail; the animated fBm's worst
        |ω/ω_water − 1| over 0.5–6 rad/m, which must be large (≥ 0.3: it has no dispersion relation);
        and the observed order of the slope error of Schneider & Westermann's shifted-weight normals
        (1) and of central differences (2), against the exact gradient.

    References
    ----------
    Schneider, J. & Westermann, R. (2001). Towards real-time visual simulation of water surfaces. *VMV*.
    """
    slopes = {h: fbm_spectrum(h) for h in (0.5, 1.0)}
    rows = [compare(f"fBm (H={h}) height spectrum slope d ln F/d ln k", slope, -(2 * h + 2), atol=0.2,
                    note="octave i: variance 2^-2Hi over area 4^i of k-space") for h, slope in slopes.items()]
    rows.append(compare("fBm H=1 spectrum slope vs a wind sea's k^-4 tail (Phillips)", slopes[1.0], -4.0,
                        atol=0.2))
    nd = noise_dispersion()
    rows.append(bound("animated fBm: worst |omega/omega_water - 1| (it has no dispersion relation)", nd["worst"],
                      0.3, relation=">=", note=f"measured d ln w/d ln k = {nd['slope']:.2f} over {nd['shells']} "
                                               "shells; deep water 0.5"))
    orders = normal_orders()
    rows.append(compare("S&W shifted-weight normals: order of the slope error", orders["shifted"]["order"], 1.0,
                        atol=0.05, note=f"max error {100 * orders['shifted']['error']:.1f} % of the largest slope at "
                                        "ds = 0.04 m"))
    rows.append(compare("central-difference normals: order of the slope error", orders["central"]["order"], 2.0,
                        atol=0.1, note=f"max error {100 * orders['central']['error']:.2f} % at ds = 0.04 m"))
    return rows


def gerstner_dispersion(water: Water, seed: int = 0, n: int = 64, length: float = 16.0, frames: int = 192,
                        steepness: float = 0.8) -> np.ndarray:
    """Relative ω error measured back (harness) at each wave of a random Gerstner sum on a grid."""
    from wavephys.surfaces.gerstner import GerstnerWaves

    grid = Grid(n, length)
    rng = np.random.default_rng(seed)
    m = rng.integers(-8, 9, size=(8, 2))
    m = np.unique(m[(m != 0).any(1)], axis=0)
    k = m * float(grid.dk)
    kk = np.hypot(k[:, 0], k[:, 1])
    _, first = np.unique(np.round(kk, 9), return_index=True)  # one wave per shell
    k, kk = k[first], kk[first]
    amp = 0.3 / kk / kk.size * rng.uniform(0.5, 1.0, kk.size)
    waves = GerstnerWaves(k, amp, rng.uniform(0, 2 * np.pi, kk.size), steepness, water)
    omega = waves.frequencies
    dt = float(2 * np.pi / omega.max() / 6)
    eta = np.stack([np.asarray(waves.heights(grid, i * dt)) for i in range(frames)])
    s = measure_dispersion(eta, float(grid.dx), dt, axes="tyx")
    return np.array([s.omega[np.argmin(np.abs(s.k - ki))] / oi - 1 for ki, oi in zip(kk, omega)])


def crest_parting(tolerance: float = 0.01, steepness=(0.1, 0.15, 0.2, 0.25, 0.3)) -> float:
    """The steepness kA (first harmonic of the Stokes wave) at which a Q = 1 Gerstner wave's
    crest elevation first differs from the exact Stokes wave's by ``tolerance`` (relative):
    scanned over ``steepness`` and interpolated in log–log between the bracketing values
    (the difference is third order, ∝ (kA)² relative); ``inf`` if it never does."""
    from wavephys.surfaces.gerstner import crest_comparison

    errors = [abs(crest_comparison(s)["crest_error"]) for s in steepness]
    for (s0, e0), (s1, e1) in zip(zip(steepness, errors), zip(steepness[1:], errors[1:])):
        if e0 < tolerance <= e1:
            return float(math.exp(math.log(s0) + (math.log(tolerance) - math.log(e0))
                                  * (math.log(s1) - math.log(s0)) / (math.log(e1) - math.log(e0))))
    return math.inf if errors[-1] < tolerance else float(steepness[0])


def check_gerstner() -> list[Check]:
    """Gerstner sums: ω(k) measured back, the mean level and crest against Stokes, the fold limit.

    Returns
    -------
    list of Check
        Seven rows: ω(k) measured back from a random Gerstner sum (Q = 0.8) in deep capillary-gravity
        and 0.5 m deep water (max relative error ≤ 0.003 each); the Q = 1 mean level at kA = 0.1
        against −kA²/2, m; the crest elevation against the Stokes wave's of the same height at
        kA = 0.1 (≤ 1e-3 relative) and up to kA = 0.3 (≤ 3 %); the order of that difference in kA
        (3); and the steepness where the crests part by 1 % (≥ 0.2).
    """
    from wavephys.surfaces.gerstner import crest_comparison

    rows = []
    for label, water in (("deep, capillary-gravity", Water()), ("0.5 m deep", Water(sigma=0.0, depth=0.5))):
        err = gerstner_dispersion(water)
        rows.append(bound(f"Gerstner sum ({label}, Q=0.8): max |omega_measured/omega(k) - 1|",
                          float(np.max(np.abs(err))), 0.003, note=f"{err.size} waves, harness ridge refinement"))
    c0, c1, c3 = crest_comparison(0.05), crest_comparison(0.1), crest_comparison(0.3)
    rows.append(compare("Gerstner Q=1 mean level on a fixed grid, kA=0.1", c1["gerstner_mean"],
                        -(c1["height"] / 2) ** 2 / 2, rtol=5e-5, unit="m", note="theory -kA^2/2 (k = 1)"))
    rows.append(bound("Gerstner vs Stokes crest elevation, same height, kA=0.1", abs(c1["crest_error"]), 1e-3,
                      note=f"trough {100 * c1['trough_error']:+.3f} %"))
    order = math.log2(c1["crest_error"] / c0["crest_error"])
    rows.append(compare("order of the Gerstner-Stokes crest difference in kA (relative)", order, 3.0, atol=0.05,
                        note="Stokes to third order: both crests a + ka^2/2 + 3k^2a^3/8 at equal height"))
    rows.append(bound("Gerstner vs Stokes crest elevation up to kA=0.3", abs(c3["crest_error"]), 0.03,
                      note=f"Gerstner crest {100 * c3['crest_error']:+.1f} %, trough {100 * c3['trough_error']:+.1f} %"))
    rows.append(bound("steepness kA where Gerstner's crest parts 1 % from Stokes", crest_parting(0.01), 0.2,
                      relation=">=", note="below it the trochoid's crest is within 1 % of the exact wave's"))
    return rows


def random_sea(n: int = 128, length: float = 64.0, seed: int = 0, wind_speed: float = 8.0, t: float = 1.0):
    """A seeded Phillips sea (m) on ``Grid(n, length)``, gravity waves, at time ``t``."""
    from wavephys.physics.wind import synthesize_height, wind_spectrum
    from wavephys.surfaces.choppy import sea_height

    grid = Grid(n, length)
    ky, kx = grid.wavenumbers()
    water = Water(sigma=0.0)
    spectrum = wind_spectrum(kx, ky, water, "phillips", wind_speed=wind_speed, amplitude=3e-3,
                             small_wave_length=length / n * 4)
    return sea_height(synthesize_height(spectrum, grid, jax.random.PRNGKey(seed)), grid, water, t), grid


def check_choppy() -> list[Check]:
    """Choppy displacement: Gerstner equivalence, the fold boundary, foam against Jacobian statistics,
    resampling error.

    Returns
    -------
    list of Check
        Seven rows: choppy displacement (λ = 1) of one wave against a Q = 1 Gerstner wave
        (max |ΔD| / A ≤ 1e-5); the fold choppiness of one wave against 1/(kA); on a seeded Phillips
        sea (U = 8 m/s), the fold λ against its first-order estimate (≥); the covered foam fraction
        (J < 0.7) against the first-order (λ up to 0.5 of the fold, ≤ 0.025) and second-order
        (0.5–0.9 of the fold, ≤ 0.04) Gaussian Jacobian estimates; and the resampled heights'
        error / height range at refine 1 (≤ 0.01) and 2 (≤ 0.003).
    """
    import jax.numpy as jnp

    from wavephys.surfaces import choppy
    from wavephys.surfaces.gerstner import GerstnerWaves
    from wavephys.surfaces.resample import resample_heights

    grid = Grid(64, 10.0)
    x, y = grid.mesh()
    k, a = 2 * np.pi * 3 / 10.0, 0.3
    x0 = float(grid.coordinates[0])  # a crest on a sample, where J is least
    h = a * jnp.cos(k * (x - x0))
    g = GerstnerWaves(np.array([[k, 0.0]]), np.array([a]), np.array([-k * x0]), steepness=1.0).displacement(x, y)
    rows = [bound("choppy (lambda=1) vs Gerstner Q=1, one wave: max |D - D_Gerstner| / A",
                  float(jnp.max(jnp.abs(choppy.displacement(h, grid) - g[:2]))) / a, 1e-5),
            compare("one wave folds at lambda = 1/(kA)", choppy.fold_choppiness(h, grid), 1 / (k * a), rtol=1e-3)]
    sea, grid = random_sea()
    fold = choppy.fold_choppiness(sea, grid)
    m = jnp.fft.irfft2(grid.wavenumber_magnitude(True) * jnp.fft.rfft2(sea), s=(grid.n, grid.n))
    rows.append(bound("Phillips sea (U=8 m/s): fold lambda / first-order estimate 1/max F^-1[|k|h]",
                      fold * float(jnp.max(m)), 1.0, relation=">=",
                      note=f"fold at lambda = {fold:.2f}; the lambda^2 term delays folding"))
    def foam_difference(frac, order):
        lam = frac * fold
        return (float((choppy.jacobian(sea, grid, lam) < 0.7).mean())
                - choppy.foam_fraction_estimate(sea, grid, lam, 0.7, order))

    first = max(abs(foam_difference(f, 1)) for f in (0.25, 0.4, 0.5))
    second = max(abs(foam_difference(f, 2)) for f in (0.5, 0.75, 0.9))
    rows.append(bound("foam fraction (J < 0.7) vs first-order Gaussian Jacobian, lambda = 0.25-0.5 of fold", first,
                      0.025, note="absolute difference in covered fraction"))
    rows.append(bound("foam fraction (J < 0.7) vs second-order Gaussian Jacobian, lambda = 0.5-0.9 of fold", second,
                      0.04, note="absolute; the lambda^2 term matters near the fold"))
    lam = 0.75 * fold
    d = choppy.displacement(sea, grid, lam)
    ref = resample_heights(d, sea, grid, refine=8, iterations=12)
    span = float(jnp.max(sea) - jnp.min(sea))
    for r, tol in ((1, 0.01), (2, 0.003)):
        err = float(jnp.max(jnp.abs(resample_heights(d, sea, grid, refine=r) - ref))) / span
        rows.append(bound(f"resampled heights, refine={r}, lambda = 0.75 of fold: max error / height range", err, tol))
    return rows
