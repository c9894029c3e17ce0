"""Dispersion measured from any simulator's output: the ω–k ridge of a space–time height field.

:func:`measure_dispersion` takes heights ``(n_t, n_y, n_x)`` sampled every Δt on a grid
of spacing Δx (any simulator: ours, a shader, a finite-difference toy) and returns one
measured (k, ω) per shell of equal |k|; :func:`dispersion_error` compares them with
linear theory for given :class:`~wavephys.Water`. Host-side float64 numpy: measurement
code, not the hot path.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar
from wavephys.core.spectral import angular_wavenumbers
from wavephys.core.water import Water

__all__ = ["DispersionSamples", "measure_dispersion", "dispersion_error", "dispersion_check"]


@dataclass(frozen=True)
class DispersionSamples:
    """Measured points of the dispersion relation, one per wavenumber shell.

    Attributes
    ----------
    k : ndarray
        Shell wavenumber |k|, rad/m (ascending).
    omega : ndarray
        Measured angular frequency of the spectral ridge, rad/s.
    power : ndarray
        Ridge power (arbitrary units, relative to each other).
    resolution : float
        Frequency bin width 2π/(n_t Δt), rad/s.
    spectra : ndarray or None
        Each shell's power over the frequency bins 0 … π/Δt (shells × bins, ±ω summed), as
        :func:`measure_dispersion` found its ridge in; None for samples made another way. The check
        reads it to tell a ridge that is not the shell's free wave (:func:`dispersion_check`).
    """

    k: np.ndarray
    omega: np.ndarray
    power: np.ndarray
    resolution: float
    spectra: np.ndarray | None = None

    def __post_init__(self):
        if self.spectra is not None:
            spectra = np.asarray(self.spectra, dtype=np.float64)
            if spectra.ndim != 2 or spectra.shape[0] != np.size(self.k):
                raise ValueError(f"spectra must have one row per shell, shape ({np.size(self.k)}, bins), got "
                                 f"{spectra.shape}")
            object.__setattr__(self, "spectra", spectra)

    def select(self, k_min: float = 0.0, k_max: float = math.inf) -> "DispersionSamples":
        """The samples with k_min ≤ k ≤ k_max."""
        return self.select_mask((self.k >= k_min) & (self.k <= k_max))

    def select_mask(self, mask) -> "DispersionSamples":
        """The samples where ``mask`` (one boolean per shell) is true."""
        m = np.asarray(mask, bool)
        return DispersionSamples(self.k[m], self.omega[m], self.power[m], self.resolution,
                                 None if self.spectra is None else self.spectra[m])


def _shells(power, dx):
    """Sum the space–time power (n_t, n_y, n_x) over shells of equal |k|: (k of each shell, (n_t, shells))."""
    nt, ny, nx = power.shape
    mx = np.fft.fftfreq(nx) * nx
    my = np.fft.fftfreq(ny) * ny
    if nx == ny:  # exact shells: integer m² = mx² + my²
        shell_key = (my[:, None] ** 2 + mx[None, :] ** 2).astype(np.int64)
    else:
        shell_key = np.round(np.sqrt((my[:, None] / ny) ** 2 + (mx[None, :] / nx) ** 2) * 1e9).astype(np.int64)
    ky, kx = angular_wavenumbers((ny, nx), dx, xp=np)
    kmag = np.sqrt(kx * kx + ky * ky)
    keys, inverse = np.unique(shell_key.ravel(), return_inverse=True)
    flat = power.reshape(nt, -1)
    shells = np.stack([np.bincount(inverse, weights=flat[t], minlength=keys.size) for t in range(nt)])
    k_shell = np.zeros(keys.size)
    np.maximum.at(k_shell, inverse, kmag.ravel())
    return k_shell, shells


def measure_dispersion(eta, dx: float, dt: float, *, min_relative_power: float = 1e-6,
                       min_bins: float = 4.0, axes=None, spectrum=None) -> DispersionSamples:
    """Measure ω(k) from a space–time height field.

    The field is Hann-windowed in time and Fourier transformed in x, y and t. For each
    shell of equal |k| the power is summed over the shell and over ±ω (a wave and its
    mirror image); the ridge is the peak in ω, refined by a parabola through the
    log-power of the peak bin and its neighbours (error ≲ 0.05 bins for a clean ridge).

    Parameters
    ----------
    eta : array_like
        Heights, m, shape ``(n_t, n_y, n_x)``, uniformly sampled in time; n_t ≥ 8.
    dx : float
        Grid spacing, m, > 0 (the same along x and y).
    dt : float
        Time between frames, s, > 0. Frequencies above π/Δt alias: sample fast enough.
    min_relative_power : float, optional, keyword-only
        Shells whose ridge power is below this fraction of the record's strongest shell (measured or not) are
        dropped; in [0, 1] (default 1e-6).
    min_bins : float, optional, keyword-only
        In [0, n_t/4] (default 4). Ridges closer than this many frequency bins to ω = 0 or to π/Δt are dropped
        (they cannot be located reliably).
    axes : str, optional, keyword-only
        The layout of ``eta`` (``"tyx"``, ``"yxt"``, … :data:`wavephys.harness.record.AXES`). Needed when the shape
        could be read more than one way: ``(n, n, m)`` (time last?) or a cube ``(n, n, n)``, which are refused
        without it. Default: infer, for ``(n_t, n, n)`` with n_t ≠ n and for a rectangular grid whose sides both
        differ from n_t.
    spectrum : numpy.ndarray, optional, keyword-only
        The frames' windowed space–time spectrum when already computed
        (:func:`wavephys.harness.spectra.spacetime_spectrum`, ``Record.spectrum()``), in the ``"tyx"`` layout.

    Returns
    -------
    DispersionSamples
        One measured (k, ω, power) per shell of equal |k| (k ascending, rad/m; ω in rad/s), with the frequency
        resolution 2π/(n_t Δt), rad/s.

    Raises
    ------
    ValueError
        When ``eta`` has fewer than 8 time samples on its first axis, or an argument is out of range.

    Examples
    --------
    A record of frames from any simulator (docs/harness.md has the whole guide):

    >>> from wavephys.harness import dispersion_check                     # doctest: +SKIP
    >>> samples = measure_dispersion(frames, dx=0.01, dt=1 / 60)           # doctest: +SKIP
    >>> print(dispersion_check(samples, Water(depth=0.5)))                # doctest: +SKIP
    """
    from wavephys.core.frames import resolve_axes

    check_array("eta", eta, ndim=3)
    eta = np.asarray(eta, dtype=np.float64)
    if axes is None and eta.shape[1] != eta.shape[2] and eta.shape[0] not in eta.shape[1:]:
        axes = "tyx"  # a rectangular grid and a time axis of another length: one reading only
    try:
        axes = resolve_axes(eta.shape, axes)
    except ValueError as exc:
        raise ValueError(f"eta: {exc}") from None
    eta = np.transpose(eta, [axes.index(c) for c in "tyx"])
    nt, ny, nx = eta.shape
    if nt < 8:
        raise ValueError(f"eta must have at least 8 time samples on its time axis, got shape {eta.shape} "
                         f"(axes {axes!r})")
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    check_scalar("min_relative_power", min_relative_power, lo=0.0, hi=1.0)
    check_scalar("min_bins", min_bins, lo=0.0, hi=nt / 4)

    from wavephys.harness.spectra import spacetime_spectrum

    if spectrum is None:
        spectrum = spacetime_spectrum(eta)
    elif not isinstance(spectrum, np.ndarray) or spectrum.shape != eta.shape:
        raise ValueError(f"spectrum must be the frames' (n_t, n_y, n_x) = {eta.shape} spectrum, got shape "
                         f"{np.shape(spectrum)}")
    power = (spectrum.real.astype(np.float64) ** 2 + spectrum.imag.astype(np.float64) ** 2)  # (ω, ky, kx)
    k_shell, shells = _shells(power, dx)
    half = nt // 2
    folded = shells[: half + 1].copy()
    folded[1:half] += shells[nt - 1: nt - half: -1]
    dw = 2 * np.pi / (nt * dt)

    ks, ws, ps, cols = [], [], [], []
    for j in range(k_shell.size):
        if k_shell[j] == 0:
            continue
        col = folded[:, j]
        i = int(np.argmax(col))
        if i < 1 or i >= half or col[i] <= 0:
            continue
        a, b, c = np.log(np.maximum(col[i - 1: i + 2], 1e-300))
        denom = a - 2 * b + c
        offset = min(max(0.5 * (a - c) / denom, -0.5), 0.5) if denom < 0 else 0.0  # within its own bin
        w = (i + offset) * dw
        if w < min_bins * dw or w > (half - min_bins) * dw:
            continue
        ks.append(k_shell[j])
        ws.append(w)
        ps.append(col[i])
        cols.append(col)
    ks, ws, ps = map(np.asarray, (ks, ws, ps))
    cols = np.asarray(cols).reshape(len(cols), half + 1)
    if ks.size:
        # relative to the record's strongest shell, measured or not: when the strong waves cannot be measured
        # (too few periods), the rounding noise left in the other shells must not stand in for them
        strongest = float(folded[:, k_shell > 0].max(initial=0.0))
        keep = ps >= min_relative_power * strongest
        ks, ws, ps, cols = ks[keep], ws[keep], ps[keep], cols[keep]
    order = np.argsort(ks)
    return DispersionSamples(ks[order], ws[order], ps[order], dw, cols[order])


def dispersion_error(samples: DispersionSamples, water: Water) -> np.ndarray:
    """Relative error of measured ω against ω(k) of linear theory for ``water`` (signed).

    Parameters
    ----------
    samples : DispersionSamples
        Measured (k, ω) points, e.g. from :func:`measure_dispersion`.
    water : Water
        The water whose linear dispersion relation ω(k) is the theory.

    Returns
    -------
    numpy.ndarray (n,)
        ω_measured/ω_theory − 1 per sample, dimensionless, float64 (positive: measured too fast).
    """
    from wavephys.physics.dispersion import angular_frequency

    check_instance("samples", samples, DispersionSamples, "wavephys.harness.DispersionSamples")
    check_instance("water", water, Water, "wavephys.Water")

    theory = np.asarray(angular_frequency(np.asarray(samples.k, np.float32), water), np.float64)
    return samples.omega / theory - 1.0


def _worst(samples: DispersionSamples, water: Water, scale_k: float = 1.0, scale_w: float = 1.0) -> float:
    """Worst |ω/ω_theory − 1| with k and ω rescaled (a trial explanation of the data)."""
    from wavephys.physics.dispersion import angular_frequency

    if not samples.k.size:
        return math.inf
    theory = np.asarray(angular_frequency(np.asarray(samples.k * scale_k, np.float32), water), np.float64)
    return float(np.max(np.abs(samples.omega * scale_w / theory - 1.0)))


def _refine(error, lo: float, hi: float, points: int = 49) -> tuple[float, float]:  # noqa: D401
    """(smallest error, its argument) over [lo, hi]: a log-spaced scan, then a bounded search around its best."""
    from scipy.optimize import minimize_scalar

    grid = np.geomspace(lo, hi, points)
    values = [error(float(v)) for v in grid]
    i = int(np.argmin(values))
    a, b = math.log(grid[max(i - 1, 0)]), math.log(grid[min(i + 1, points - 1)])
    if b > a:
        found = minimize_scalar(lambda u: error(math.exp(u)), bounds=(a, b), method="bounded",
                                options=dict(xatol=1e-4))
        if found.fun < values[i]:
            return float(found.fun), float(math.exp(found.x))
    return float(values[i]), float(grid[i])


def _aliasing(samples, dt, theory) -> str:
    nyquist = math.pi / dt
    if np.any(theory > nyquist):
        k_alias = float(samples.k[np.argmax(theory > nyquist)])
        return (f"aliased sampling: theory puts omega above the Nyquist frequency pi/dt = {nyquist:.4g} "
                f"rad/s from k = {k_alias:.4g} rad/m on; record frames closer together or limit k_range")
    w = samples.omega
    if w.size >= 6:  # the simulator's own waves fold: its measured omega turns down while theory rises
        top = int(np.argmax(w))
        if w[top] > 0.7 * nyquist and top < w.size - 2 and w[-1] < 0.9 * w[top] and theory[-1] > theory[top]:
            return (f"aliased sampling of the simulator's own waves: measured omega rises to {w[top]:.4g} rad/s "
                    f"(pi/dt = {nyquist:.4g}) at k = {samples.k[top]:.4g} rad/m and then folds back down; its "
                    f"waves are faster than the frames can follow: record frames closer together")
    return ""


def _non_dispersive(samples, theory) -> str:
    from scipy.stats import theilslopes

    # the whole band, then its lower half and quarter: shells swamped by the leakage of a non-periodic record
    # (at high k, where the heights' own power is small) must not hide a band that is clearly non-dispersive
    for top in (1.0, 0.5, 0.25):
        band = samples.k <= samples.k.min() + top * (samples.k.max() - samples.k.min())
        k = samples.k[band]
        if k.size < 8 or k.max() <= 2.5 * k.min():
            continue
        step = max(1, k.size // 400)  # at most ~400 shells: the robust fit is quadratic in them
        k, c, c_theory = k[::step], samples.omega[band][::step] / k[::step], theory[band][::step] / k[::step]
        # log-log slope of phase speed against k: -1/2 for deep gravity waves, 0 for no dispersion; robust (the
        # median of pairwise slopes)
        slope = theilslopes(np.log(c), np.log(k))[0]
        slope_theory = theilslopes(np.log(c_theory), np.log(k))[0]
        if abs(slope) < 0.2 and abs(slope_theory) > 0.3:
            return (f"non-dispersive: every k moves at about one speed c = {np.median(c):.4g} m/s (d log c / "
                    f"d log k = {slope:.2f} over k = {k.min():.4g}..{k.max():.4g} rad/m; water waves there have "
                    f"{slope_theory:.2f}, c from {c_theory.min():.4g} to {c_theory.max():.4g} m/s): a wave "
                    f"equation, not water waves")
    return ""


BOUND_SHARE = 0.01
"""A failing shell whose ridge lies more than 2 frequency bins from theory's ω(k) has its free wave there too when
the spectrum has a local peak within a bin of ω(k) holding at least this share of the shell's strongest power and
standing :data:`BOUND_PROMINENCE` times above the shell's median."""

BOUND_PROMINENCE = 50.0
"""How far above its shell's median power a peak at theory's ω(k) must stand to count as a free wave (measured:
78–1.5e3 on choppy seas; the wave equation's broadband shells reach local peaks 4.6–29× their median)."""

ENERGETIC_SHELLS = 0.1
"""Shells whose ridge holds at least this share of the strongest shell's power are the record's energetic waves:
the bound-wave cause is named only when all of them obey the relation (a wrong simulator fails there too)."""


def _free_peak(samples, j, at) -> float:
    """The share of shell ``j``'s strongest power in a local peak within a bin of frequency bin ``at`` (the caller
    takes shells whose ridge lies more than 2 bins away, so the ridge's own bin is outside that window): 0 when
    there is none, or it is weak or not prominent."""
    col = samples.spectra[j]
    bins = col.size
    centre = int(round(at))
    if not 2 <= centre <= bins - 3:
        return 0.0
    i = centre - 1 + int(np.argmax(col[centre - 1:centre + 2]))
    peak = col[i] >= col[i - 1] and col[i] >= col[i + 1]
    if peak and col[i] >= BOUND_SHARE * col.max() and col[i] >= BOUND_PROMINENCE * np.median(col):
        return float(col[i] / col.max())
    return 0.0


def _bound_components(samples, theory, err, rtol) -> str:
    """The record's energetic waves obey the relation, and the worst shell's strongest component is far from ω(k)
    while a prominent peak sits at ω(k): free waves under components that do not obey it (bound waves of nonlinear
    heights)."""
    if samples.spectra is None:
        return ""
    energetic = samples.power >= ENERGETIC_SHELLS * samples.power.max()
    if np.any(np.abs(err[energetic]) > rtol):
        return ""
    failing = np.flatnonzero(np.abs(err) > rtol)
    shares = {j: _free_peak(samples, j, theory[j] / samples.resolution) for j in failing
              if abs(samples.omega[j] - theory[j]) > 2.0 * samples.resolution}
    found = {j: v for j, v in shares.items() if v > 0}
    worst = int(np.argmax(np.abs(err)))
    if worst not in found:
        return ""
    below = samples.k[failing].min()
    passing = samples.k[samples.k < below]
    band = (f"; the {passing.size} shells below k = {below:.6g} rad/m all pass "
            f"(k_range=(0, {0.5 * (passing.max() + below):.6g}))" if passing.size >= 3 else "")
    return (f"components that do not obey the linear dispersion relation, in weak shells: the energetic waves obey "
            f"it, and at k = {samples.k[worst]:.4g} rad/m the strongest component is at omega = "
            f"{samples.omega[worst]:.4g} rad/s while a peak sits at theory's {theory[worst]:.4g} rad/s "
            f"({10 * math.log10(found[worst]):.0f} dB below it), and so in {len(found)} of the {failing.size} failing "
            f"shells: free waves under bound waves, as nonlinear heights carry (a choppy displacement, Stokes "
            f"harmonics, short waves riding on long ones). This check measures linear heights (before any "
            f"displacement){band}")


def _frequency_floor(samples, theory) -> str:
    n = max(3, samples.k.size // 4)
    if samples.k.size < 6:
        return ""
    k, w, t = samples.k[:n], samples.omega[:n], theory[:n]
    slope = np.polyfit(np.log(k), np.log(w), 1)[0]
    slope_theory = np.polyfit(np.log(k), np.log(t), 1)[0]
    if w[0] > 1.5 * t[0] and slope < 0.5 * slope_theory:
        floor = float(np.sqrt(max(np.median(w ** 2 - t ** 2), 0.0)))
        return (f"a low-k frequency floor: omega does not go to 0 as k -> 0 (at k = {k[0]:.4g} rad/m measured "
                f"{w[0]:.4g}, theory {t[0]:.4g} rad/s; d log omega / d log k = {slope:.2f} there, theory "
                f"{slope_theory:.2f}; floor about {floor:.3g} rad/s): a restoring term at k = 0, such as a "
                f"truncated convolution kernel whose sum is not 0 (iWave's normalized kernel) or a damping term "
                f"folded into the update")
    return ""


def _depth_fit(samples, water, tolerance) -> str:
    from dataclasses import replace

    deep = _worst(samples, replace(water, depth=math.inf))
    best, h = _refine(lambda h: _worst(samples, replace(water, depth=h)), 0.3 / samples.k.max(),
                      10.0 / samples.k.min())
    claimed = "deep water" if not math.isfinite(water.depth) else f"h = {float(water.depth):.4g} m"
    if math.isfinite(water.depth) and deep < tolerance and deep <= best:
        return f"wrong depth: the data match deep water (worst error {deep:.2g}), not the claimed {claimed}"
    if best < tolerance and (not math.isfinite(water.depth) or abs(math.log(h / float(water.depth))) > 0.1):
        return (f"wrong depth: the data match depth h = {h:.3g} m (worst error {best:.2g}), not the claimed "
                f"{claimed}")
    return ""


def _sigma_fit(samples, water, tolerance) -> str:
    from dataclasses import replace

    best, sg = min((_worst(samples, replace(water, sigma=0.0)), 0.0),
                   _refine(lambda sg: _worst(samples, replace(water, sigma=sg)), 1e-5, 10.0))
    claimed = float(water.sigma)
    if best >= tolerance or (claimed > 0 and sg > 0 and abs(math.log(sg / claimed)) < 0.15):
        return ""
    if sg == 0.0 or (claimed > 0 and sg < 0.02 * claimed):
        return (f"surface tension missing: the data match sigma = {sg:.3g} N/m, about 0 (claimed {claimed:.4g} "
                f"N/m)")
    ratio = f", {sg / claimed:.3g} x the claimed {claimed:.4g} N/m" if claimed > 0 else " (claimed 0)"
    return (f"surface tension at another scale: the data match sigma = {sg:.3g} N/m{ratio} (worst error "
            f"{best:.2g}); clean water has 0.0728 N/m = 72.8 dyn/cm = 72.8 mN/m, and sigma/rho = 7.28e-5 m^3/s^2 "
            f"is not sigma")


def _scale_fit(samples, water, err, tolerance) -> str:
    ratio = float(np.median(1.0 + err))
    if not (np.std(1.0 + err) < 0.02 * ratio and abs(ratio - 1.0) > 0.02):
        return ""
    from dataclasses import replace

    tried = []
    if _worst(samples, water, scale_w=1 / ratio) < tolerance:
        tried.append(f"the frames are {ratio:.4g} x further apart than dt says (dt x {ratio:.4g})")
    best, s = _refine(lambda s: _worst(samples, water, scale_k=s), 0.05, 20.0)
    if best < tolerance and abs(s - 1) > 0.01:
        tried.append(f"dx x {1 / s:.4g} (a texel of {1 / s:.4g} x the size said)")
    best, f = _refine(lambda f: _worst(samples, replace(water, g=float(water.g) * f)), 0.01, 100.0)
    if best < tolerance and abs(f - 1) > 0.01:
        tried.append(f"g = {float(water.g) * f:.4g} m/s^2 (x {f:.4g})")
    which = "; or ".join(tried) if tried else "no single scaling of dt, dx or g fits exactly"
    trade = (" In deep gravity water omega = sqrt(g k), so dt, dx and g trade: one record cannot tell which "
             "is off." if len(tried) > 1 else "")
    return f"omega off by a constant factor {ratio:.4g}: {which}.{trade}"


def _lattice(w, lo, hi, power=None) -> float:
    """The base frequency ω₀ in [lo, hi] whose multiples the frequencies ``w`` sit on best (the phase coherence of
    w/ω₀ modulo 1 over a fine grid of ω₀, on the 128 strongest shells; then ω₀ refined by least squares on the
    multiples of every shell)."""
    strong = w if power is None or w.size <= 128 else w[np.argsort(power)[-128:]]
    grid = np.geomspace(lo, hi, 6000)
    coherence = np.abs(np.exp(2j * np.pi * strong[None, :] / grid[:, None]).mean(axis=1))
    # ω₀/2, ω₀/3 … fit as well as ω₀ itself: the largest base that fits is the lattice's
    w0 = float(grid[np.flatnonzero(coherence >= 0.98 * coherence.max())[-1]])
    n = np.maximum(np.round(w / w0), 1.0)
    return float(np.sum(n * w) / np.sum(n * n))


def _quantized(samples, theory, rtol) -> str:
    """Frequencies on a lattice ω₀·n (a looping ocean: ω(k) rounded to multiples of one base frequency so that
    the sea repeats every 2π/ω₀): ω₀ fitted, and how the rounding goes (down, to the nearest, up)."""
    w = samples.omega
    if w.size < 8:
        return ""
    lo, hi = 0.5 * samples.resolution, 0.7 * float(np.min(theory[theory > 0]))
    if not hi > lo:
        return ""
    w0 = _lattice(w, lo, hi, samples.power)
    fits = [(float(np.max(np.abs(w - w0 * np.maximum(f(theory / w0), 1.0)))), kind)
            for kind, f in (("down", np.floor), ("to the nearest", np.round), ("up", np.ceil))]
    found, kind = min(fits)
    typical = float(np.max(np.abs(w - theory)))
    if not (found <= 0.25 * samples.resolution and found < 0.25 * typical):
        return ""
    worst = int(np.argmax(np.abs(w / theory - 1)))
    period = 2 * math.pi / w0
    need = 2 * math.pi / (rtol * float(theory.min()))
    return (f"frequencies on a lattice: omega(k) rounded {kind} to multiples of omega0 = {w0:.4g} rad/s, as a looping "
            f"ocean does to repeat every T = 2 pi/omega0 = {period:.4g} s (fitted within {found:.2g} rad/s over "
            f"{w.size} shells). The error, up to omega0/omega(k), is largest for the longest waves "
            f"({100 * abs(w[worst] / theory[worst] - 1):.3g} % at k = {samples.k[worst]:.4g} rad/m): a loop of "
            f"T >= {need:.4g} s keeps every shell within rtol, or check the band where omega >> omega0 (k_range)")


def _likely_cause(samples: DispersionSamples, water: Water, dt: float, err: np.ndarray, rtol: float = 0.005) -> str:
    """A guess, in words, at why measured ω(k) departs from theory (empty when none fits).

    Where some shells' theory lies above the frames' Nyquist frequency, the shells the frames do sample are
    explained first: when they fail on their own, aliasing is not the cause (ω = g k read at 15 fps fails by
    6.6 × theory below the aliased band already)."""
    theory = samples.omega / (1.0 + err)
    nyquist = math.pi / dt
    clean = (theory < 0.8 * nyquist) & (samples.omega < 0.8 * nyquist)
    if (~clean).any() and clean.sum() >= 6 and np.max(np.abs(err[clean])) > rtol:
        sub = samples.select_mask(clean)
        found = _causes(sub, water, dt, err[clean], rtol, aliasing=False)
        if found:
            alias = _aliasing(samples, dt, theory)
            return (f"{found} (from the {int(clean.sum())} shells the frames sample without aliasing, which fail on "
                    f"their own)" + (f"; and above them, {alias}" if alias else ""))
    return _causes(samples, water, dt, err, rtol)


def _one_speed(samples) -> float:
    """The worst relative misfit of ω = c k with one speed c (the median of ω/k) over the shells."""
    c = float(np.median(samples.omega / samples.k))
    return float(np.max(np.abs(samples.omega / (c * samples.k) - 1.0)))


def _causes(samples, water, dt, err, rtol, aliasing=True) -> str:
    theory = samples.omega / (1.0 + err)
    tolerance = 0.25 * float(np.max(np.abs(err)))
    exact_speed = samples.k.size >= 8 and _one_speed(samples) <= rtol  # one speed explains every shell exactly
    for cause in ((lambda: _aliasing(samples, dt, theory)) if aliasing else (lambda: ""),
                  lambda: _frequency_floor(samples, theory), lambda: _quantized(samples, theory, rtol),
                  (lambda: _non_dispersive(samples, theory)) if exact_speed else (lambda: ""),
                  lambda: _scale_fit(samples, water, err, tolerance), lambda: _depth_fit(samples, water, tolerance),
                  lambda: _sigma_fit(samples, water, tolerance), lambda: _bound_components(samples, theory, err, rtol),
                  lambda: _non_dispersive(samples, theory)):
        found = cause()
        if found:
            return found
    return ""


def dispersion_check(samples: DispersionSamples, water: Water, dt: float, *, rtol: float = 0.005,
                     k_range=(0.0, math.inf), min_samples: int = 3):
    """A :class:`~wavephys.harness.Check` of measured ω(k) against ``water``'s theory that explains itself.

    The row is max |ω_measured/ω_theory − 1| over the shells with k in ``k_range`` (rad/m)
    against ``rtol``; its note names the band covered (k range and number of shells), the
    worst k with its measured and expected ω, and when the row fails the likely cause if
    one is recognizable (aliased sampling, no dispersion, wrong depth, surface tension,
    a constant factor). Fewer than ``min_samples`` shells in the band fail the row too.
    ``dt`` (s) is the time between frames of the record.

    Parameters
    ----------
    samples : DispersionSamples
        Measured (k, ω) points, e.g. from :func:`measure_dispersion`.
    water : Water
        The water whose linear dispersion relation ω(k) is the theory.
    dt : float
        Time between frames of the record, s, > 0 (used to recognize aliased sampling).
    rtol : float, optional, keyword-only
        Allowed max relative error |ω_measured/ω_theory − 1|, dimensionless, >= 0 (default 0.005).
    k_range : (float, float), optional, keyword-only
        Band (k_min, k_max) of shells checked, rad/m, both >= 0 (k_max may be inf), k_min < k_max
        (default: all shells).
    min_samples : int, optional, keyword-only
        Fewest shells in the band for the row to pass, >= 1 (default 3).

    Returns
    -------
    Check
        A ``"~="`` row of the worst relative error against 0 with ``atol=rtol`` (its note names the band, the
        worst k and, on failure, the likely cause), or, when fewer than ``min_samples`` shells lie in the band,
        a failed ``">="`` bound row on their number.

    Raises
    ------
    ValueError
        When ``k_range`` does not have k_min < k_max, or an argument is out of range.
    """
    from wavephys.harness.checks import bound, compare

    check_instance("samples", samples, DispersionSamples, "wavephys.harness.DispersionSamples")
    check_instance("water", water, Water, "wavephys.Water")
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    check_scalar("rtol", rtol, lo=0.0)
    check_int("min_samples", min_samples, lo=1)
    check_array("k_range", k_range, ndim=1, shape_tail=(2,), lo=0.0, allow_inf=True)
    if not k_range[0] < k_range[1]:
        raise ValueError(f"k_range must be (k_min, k_max) with k_min < k_max, got {np.asarray(k_range, float).tolist()}")
    k_range = (float(k_range[0]), float(k_range[1]))
    all_k = samples.k
    samples = samples.select(*k_range)
    quantity = "max |omega_measured/omega_theory - 1|"
    if samples.k.size < min_samples:
        span = f"{all_k.min():.4g}..{all_k.max():.4g} rad/m" if all_k.size else "none"
        return bound("dispersion shells measured in k_range", samples.k.size, min_samples, relation=">=",
                     note=f"k_range {k_range[0]:.4g}..{k_range[1]:.4g} rad/m; shells measured anywhere: "
                          f"{all_k.size} ({span}); a longer record or more frames per period measures more")
    err = dispersion_error(samples, water)
    i = int(np.argmax(np.abs(err)))
    theory = samples.omega[i] / (1.0 + err[i])
    note = (f"band k = {samples.k.min():.4g}..{samples.k.max():.4g} rad/m, {samples.k.size} shells; worst at "
            f"k = {samples.k[i]:.4g} rad/m: omega measured {samples.omega[i]:.4g}, expected {theory:.4g} rad/s")
    row = compare(quantity, float(np.abs(err[i])), 0.0, atol=rtol, note=note)
    if not row.ok:
        cause = _likely_cause(samples, water, dt, err, rtol)
        if cause:
            row = compare(quantity, float(np.abs(err[i])), 0.0, atol=rtol, note=f"{note}; likely cause: {cause}")
    return row
