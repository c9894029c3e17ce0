"""Checks of the textures an engine draws with: tiling seams, normal maps against heights,
the same sea at two resolutions, the flux of a caustics map, and quantized heights.

* :func:`tiling_check` — a periodic texture's wrap step (last column to first, last row to
  first) against its ordinary neighbour steps: about 1 for a tiling texture; far above for a
  seam (a crop of a larger surface), about 0 for a duplicated edge, and with zero slope at
  the border for edge-clamped (reflecting) boundaries.
* :func:`normals_check` — a normal map against the slopes of its height map (spectral or
  central differences, whichever the map matches), with the green convention (OpenGL
  green = +y, DirectX green = −y) and the packing (0.5 + 0.5 n or float) detected; the
  angle between the normals, degrees.
* :func:`resolution_check` — the spectrum of one sea exported at two resolutions, in octave
  bands both resolve, against the scatter a random sea has in a band of that many modes.
* :func:`caustics_flux_check` — the mean of a relative-irradiance map (1 = flat water's
  light): light is neither made nor lost by focusing, so the mean stays 1 up to the small
  change of Fresnel transmittance with slope.
* :func:`quantization_check` — heights that sit on a coarse lattice of values (float16,
  16-bit integers), as noise against the signal.
"""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.inputs import check_array, check_choice, check_scalar
from wavephys.core.spectral import angular_wavenumbers

__all__ = ["tiling_check", "normals_check", "resolution_check", "caustics_flux_check", "quantization_check",
           "NORMAL_CONVENTIONS", "STENCILS"]

NORMAL_CONVENTIONS = ("auto", "opengl", "directx")
"""Green conventions of a normal map: OpenGL (green = +y), DirectX (green = −y), or detected."""


def _frames(name, field):
    check_array(name, field, min_ndim=2)
    f = np.asarray(field, np.float64)
    if f.ndim > 3:
        raise ValueError(f"{name} must be one frame (n_y, n_x) or frames (n_t, n_y, n_x), got shape {f.shape}")
    f = f[None] if f.ndim == 2 else f
    if min(f.shape[1:]) < 4:
        raise ValueError(f"{name} must be at least 4 x 4, got shape {f.shape}")
    return f


def _rms(a) -> float:
    return float(np.sqrt(np.mean(np.square(a))))


def tiling_check(field, *, max_ratio: float = 2.0):
    """A :class:`~wavephys.harness.Check` that a texture tiles: its wrap steps are ordinary steps.

    Parameters
    ----------
    field : array_like (n_y, n_x) or (n_t, n_y, n_x)
        One texture or frames of one (any unit), finite, at least 4 x 4.
    max_ratio : float, optional, keyword-only
        Largest allowed wrap step / ordinary step, or its inverse, > 1 (default 2; a tiling random field gives
        1 within a few 1/√n).

    Returns
    -------
    Check
        A ``"<="`` row of the worse of the x and y ratios (each taken as max(r, 1/r)); its note gives both and,
        on failure, the likely cause: a seam, a duplicated edge, or (for frames, from the heights' variance at the
        edges against the interior's: about 2 beside a reflecting wall, about 0 at held edges) reflecting or
        held borders.
    """
    from wavephys.harness.checks import bound

    f = _frames("field", field)
    check_scalar("max_ratio", max_ratio, lo=1.0, lo_open=True)
    parts, worst, cause = [], 0.0, ""
    walls = None
    if f.shape[0] >= 8 and min(f.shape[1:]) >= 16:  # frames: the variance a reflecting wall doubles
        v = np.mean((f - f.mean(axis=0)) ** 2, axis=0)
        interior = float(v[4:-4, 4:-4].mean())
        if interior > 0:
            walls = float(np.mean(np.concatenate([v[0], v[-1], v[:, 0], v[:, -1]]))) / interior
    for axis, name in ((2, "x"), (1, "y")):
        g = np.moveaxis(f, axis, -1)
        inner = _rms(np.diff(g, axis=-1))
        wrap = _rms(g[..., 0] - g[..., -1])
        ratio = wrap / inner if inner > 0 else (1.0 if wrap == 0 else math.inf)
        score = max(ratio, 1.0 / ratio) if ratio > 0 else math.inf
        parts.append(f"{name}: wrap step {ratio:.3g} x an ordinary one")
        if score > worst:
            worst = score
            if walls is not None and walls <= 0.5:
                cause = (f"held borders: the heights' variance at the edges is {walls:.2f} x the interior's (edges "
                         f"fixed at 0, still water around a tank, or an absorbing margin); the surface is not "
                         f"periodic")
            elif ratio < 1.0 / max_ratio:
                cause = (f"the last {'column' if name == 'x' else 'row'} repeats the first (a grid of n + 1 points "
                         f"with both ends kept): drop one end so the texture tiles")
            elif walls is not None and walls >= 1.5:
                cause = (f"reflecting (edge-clamped) borders: the heights' variance in the edge rows and columns is "
                         f"{walls:.2f} x the interior's, the antinode a reflecting wall makes (a texture read with "
                         f"CLAMP_TO_EDGE, or walls); the surface is a closed tank, not periodic")
            else:
                cause = (f"a seam along {name}: the surface does not continue across the border (a crop of a larger "
                         f"surface, or a non-periodic simulation)")
    note = "; ".join(parts)
    row = bound("seam step / ordinary step (the larger of it and its inverse)", worst, max_ratio, note=note)
    if not row.ok:
        row = bound(row.quantity, worst, max_ratio, note=f"{note}; likely cause: {cause}")
    return row


STENCILS = ("spectral", "central", "forward", "backward", "sobel")
"""The derivatives a normal map may be made with: spectral (exact for a band-limited periodic map), central
differences (h₊ − h₋)/2Δx, one-sided forward (h₊ − h)/Δx and backward (h − h₋)/Δx, and a 3×3 Sobel filter."""


def _slopes(eta, dx, derivative):
    """(∂h/∂x, ∂h/∂y) of a periodic map by one of :data:`STENCILS`."""
    ny, nx = eta.shape
    if derivative == "spectral":
        ky, kx = angular_wavenumbers((ny, nx), dx, xp=np)
        spec = np.fft.fft2(eta)
        # the Nyquist modes' slopes are undefined on an even grid: left out
        kx = np.where(np.abs(kx) >= np.pi / dx * (1 - 1e-9), 0.0, kx)
        ky = np.where(np.abs(ky) >= np.pi / dx * (1 - 1e-9), 0.0, ky)
        return np.real(np.fft.ifft2(1j * kx * spec)), np.real(np.fft.ifft2(1j * ky * spec))
    if derivative == "forward":
        return (np.roll(eta, -1, 1) - eta) / dx, (np.roll(eta, -1, 0) - eta) / dx
    if derivative == "backward":
        return (eta - np.roll(eta, 1, 1)) / dx, (eta - np.roll(eta, 1, 0)) / dx
    central = ((np.roll(eta, -1, 1) - np.roll(eta, 1, 1)) / (2 * dx), (np.roll(eta, -1, 0) - np.roll(eta, 1, 0)) / (2 * dx))
    if derivative == "central":
        return central
    sx, sy = central  # Sobel: the central difference smoothed 1-2-1 across it
    return ((np.roll(sx, 1, 0) + 2 * sx + np.roll(sx, -1, 0)) / 4, (np.roll(sy, 1, 1) + 2 * sy + np.roll(sy, -1, 1)) / 4)


def _unit(v):
    return v / np.maximum(np.linalg.norm(v, axis=-1, keepdims=True), 1e-300)


def _angles(a, b):
    return np.degrees(np.arccos(np.clip(np.sum(a * b, axis=-1), -1.0, 1.0)))


def _map_slopes(m):
    """The slopes (s_x, s_y) a unit normal map stands for: −n_x/n_z, −n_y/n_z."""
    z = np.maximum(m[..., 2], 1e-9)
    return np.stack([-m[..., 0] / z, -m[..., 1] / z])


def _stencil_fit(slope, h, dx):
    """The stencil and scale whose slopes best explain the map's slopes: (relative residual, scale, stencil),
    the scale by least squares (slope ≈ s × stencil's slope)."""
    fits = []
    for derivative in STENCILS:
        ref = np.stack(_slopes(h, dx, derivative))
        c = float(np.sum(slope * ref) / max(np.sum(ref * ref), 1e-300))
        fits.append((_rms(slope - c * ref) / max(_rms(ref) * max(abs(c), 1e-300), 1e-300), c, derivative))
    return min(fits)


def normals_check(heights, normals, dx: float, *, convention: str = "auto", packed=None,
                  tolerance: float = 1.0):
    """A :class:`~wavephys.harness.Check` of a normal map against the slopes of its height map.

    Parameters
    ----------
    heights : array_like (n, n)
        The height map, m, periodic (a tiling texture), finite.
    normals : array_like (n, n, 3)
        The normal map: packed ``0.5 + 0.5 n`` (values 0–1; an 8-bit image divided by 255) or float n.
    dx : float
        Texel size, m, > 0 (as the engine takes it).
    convention : {"auto", "opengl", "directx"}, optional, keyword-only
        The green convention claimed (``"auto"``: detect it and only report it).
    packed : bool, optional, keyword-only
        Whether the map is packed 0.5 + 0.5 n (default: detected, packed when no component is below 0).
    tolerance : float, optional, keyword-only
        Largest allowed angle between the map's normals and the heights' normals, degrees, > 0 (default 1).

    Returns
    -------
    Check
        A ``"<="`` row of the largest angle (degrees); its note gives the rms angle, the convention and packing
        found, the derivative the map matches, and on failure the likely cause, fitted: the other green
        convention, the stencil the map was made with and the factor on its slopes (one-sided differences, a
        central difference not halved, a normal strength or dx taken otherwise, a flat map), or a map of other
        heights.
    """
    from wavephys.harness.checks import bound

    check_array("heights", heights, ndim=2)
    h = np.asarray(heights, np.float64)
    if np.shape(normals)[:2] != h.shape or np.ndim(normals) != 3:
        check_array("normals", normals, ndim=3)
        raise ValueError(f"normals must be (n_y, n_x, 3) over the texels of heights {h.shape}, got shape "
                         f"{np.shape(normals)}")
    check_array("normals", normals, ndim=3, shape_tail=h.shape + (3,))
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    check_choice("convention", convention, NORMAL_CONVENTIONS)
    check_scalar("tolerance", tolerance, lo=0.0, lo_open=True)
    v = np.asarray(normals, np.float64)
    if packed is None:
        packed = bool(v.min() >= 0.0)
    elif not isinstance(packed, bool):
        raise TypeError(f"packed must be True, False or None, got {packed!r}")
    n = _unit(2 * v - 1 if packed else v)
    fits = []
    for derivative in ("spectral", "central"):
        sx, sy = _slopes(h, dx, derivative)
        ref = _unit(np.stack([-sx, -sy, np.ones_like(sx)], -1))
        for green, sign in (("opengl", 1.0), ("directx", -1.0)):
            m = n * np.array([1.0, sign, 1.0])
            ang = _angles(m, ref)
            fits.append((float(ang.max()), float(np.sqrt(np.mean(ang**2))), derivative, green, m))
    found = min(fits, key=lambda f: f[1])
    wanted = found[3] if convention == "auto" else convention
    mine = min((f for f in fits if f[3] == wanted), key=lambda f: f[1])
    worst, rms, derivative, _, m = mine
    note = (f"rms {rms:.3g} deg; {'packed 0.5 + 0.5 n' if packed else 'float n'}; green convention found: "
            f"{found[3]}{'' if convention == 'auto' else f' (claimed {convention})'}; matches {derivative} "
            f"slopes of the heights")
    row = bound("largest angle between the map's normals and the heights' normals", worst, tolerance, unit="deg",
                note=note)
    if row.ok:
        return row
    cause = _normals_cause(found, wanted, tolerance, m, h, dx, v, packed)
    return bound(row.quantity, worst, tolerance, unit="deg", note=f"{note}; likely cause: {cause}")


def _normals_cause(found, wanted, tolerance, m, h, dx, v, packed) -> str:
    if found[3] != wanted and found[1] <= tolerance:
        return (f"the map uses the {found[3]} green convention (green = {'+y' if found[3] == 'opengl' else '-y'}), "
                f"not {wanted}: flip green (g' = 1 - g)")
    slope = _map_slopes(m)
    if _rms(slope) < 1e-6 * max(_rms(np.stack(_slopes(h, dx, "central"))), 1e-300):
        return "the map is flat (every normal (0, 0, 1)): it was not made from these heights, or its slopes are lost"
    resid, scale, stencil = _stencil_fit(slope, h, dx)
    swapped = _stencil_fit(slope[::-1], h, dx)
    if resid < 0.1:
        what = {"spectral": "spectral slopes", "central": "central differences (h₊ − h₋)/2Δx",
                "forward": "one-sided differences (h₊ − h)/Δx: each normal half a texel off",
                "backward": "one-sided differences (h − h₋)/Δx: each normal half a texel off",
                "sobel": "a 3×3 Sobel filter"}[stencil]
        parts = [f"the map's slopes are {what}"] if stencil in ("forward", "backward") else []
        if abs(scale - 2.0) < 0.04 and stencil == "central":
            parts.append("its slopes are 2 x the heights': the central difference is not divided by 2 ((h₊ − h₋)/Δx), "
                         "or a normal 'strength' of 2")
        elif abs(scale + 1.0) < 0.05:
            parts.append("the slopes have the wrong sign: the normals lean uphill")
        elif abs(scale - 1) > 0.05:
            parts.append(f"its slopes are {scale:.4g} x the heights' (a normal 'strength' factor, or dx taken as "
                         f"{dx / scale:.4g} m instead of {dx:.4g} m)")
        if parts:
            return f"{'; '.join(parts)} (fitted: {stencil} differences × {scale:.4g}, {resid:.2g} left)"
        return (f"the map matches {stencil} slopes of the heights × {scale:.4g} (residual {resid:.2g}): its error is "
                f"the stencil's own on this surface; a finer map or spectral slopes fix it")
    if swapped[0] < 0.1:
        return f"x and y are swapped (a transposed map): it matches {swapped[2]} slopes with x and y exchanged"
    if not packed and v.min() > -1e-3 and np.median(v[..., 2]) < 0.9:
        return "the map looks packed (0.5 + 0.5 n) but was read as float n: pass packed=True"
    return "the normals do not follow from these heights (another frame, another texel size, or flipped axes)"


def _band_variance(eta, dx, edges):
    """Variance of the heights in each band of |k| (octaves ``edges``), and the number of modes per band."""
    f = eta if eta.ndim == 3 else eta[None]
    ny, nx = f.shape[1:]
    ky, kx = angular_wavenumbers((ny, nx), dx, xp=np)
    k = np.sqrt(kx**2 + ky**2)
    power = np.mean(np.abs(np.fft.fft2(f - f.mean(axis=(1, 2), keepdims=True))) ** 2, axis=0) / (nx * ny) ** 2
    band = np.digitize(k, edges) - 1
    var = np.array([power[band == b].sum() for b in range(len(edges) - 1)])
    # independent modes a band's variance averages: (sum p)^2 / sum p^2, halved (k and -k are one wave)
    modes = np.array([0.5 * power[band == b].sum() ** 2 / max(np.sum(power[band == b] ** 2), 1e-300)
                      for b in range(len(edges) - 1)])
    return var, modes


def resolution_check(eta_a, dx_a: float, eta_b, dx_b: float, *, rtol: float = 0.2, min_modes: int = 16):
    """A :class:`~wavephys.harness.Check` that one sea has one spectrum at two resolutions.

    Parameters
    ----------
    eta_a, eta_b : array_like (n_y, n_x) or (n_t, n_y, n_x)
        The same sea exported at two resolutions (frames are averaged), m, finite.
    dx_a, dx_b : float
        Their texel sizes, m, > 0.
    rtol : float, optional, keyword-only
        Allowed relative difference of a band's variance, > 0 (default 0.2), or a random sea's own scatter where
        that is larger: e^{4√(1/N_a + 1/N_b)} − 1 for bands of N_a and N_b independent modes (N = ½(Σp)²/Σp² over
        the band's mode powers p).
    min_modes : int, optional, keyword-only
        Octave bands with fewer independent modes in either record are left out, >= 1 (default 16).

    Returns
    -------
    Check
        A ``"<="`` row of the worst band's |log(V_a/V_b)| / log(1 + allowed); its note gives each band's ratio,
        and on failure the likely cause (amplitudes that scale with the grid, a spectrum whose shape moves).
    """
    from wavephys.harness.checks import bound
    from wavephys.core.inputs import check_int

    a, b = _frames("eta_a", eta_a), _frames("eta_b", eta_b)
    check_scalar("dx_a", dx_a, lo=0.0, lo_open=True)
    check_scalar("dx_b", dx_b, lo=0.0, lo_open=True)
    check_scalar("rtol", rtol, lo=0.0, lo_open=True)
    min_modes = check_int("min_modes", min_modes, lo=1)
    length_a, length_b = a.shape[2] * dx_a, b.shape[2] * dx_b
    k_lo = 2 * math.pi / min(length_a, length_b)
    k_hi = 0.5 * math.pi / max(dx_a, dx_b)  # half the coarser Nyquist: both resolve it well
    if k_hi <= 2 * k_lo:
        raise ValueError(f"eta_a, eta_b (dx_a, dx_b): the two records share less than an octave of wavenumbers "
                         f"({k_lo:.4g}..{k_hi:.4g} rad/m)")
    edges = k_lo * 2.0 ** np.arange(0, math.floor(math.log2(k_hi / k_lo)) + 1)
    va, ma = _band_variance(a, dx_a, edges)
    vb, mb = _band_variance(b, dx_b, edges)
    use = (np.minimum(ma, mb) >= min_modes) & (va > 0) & (vb > 0)
    if not use.any():
        return bound("bands compared", 0, 1, relation=">=",
                     note=f"no octave band holds {min_modes} independent modes in both")
    ratio = va[use] / vb[use]
    # a random sea's band variance scatters by 1/sqrt(N) (N independent modes): 4 sigma of log(V_a/V_b) allowed
    allowed = np.maximum(rtol, np.expm1(4 * np.sqrt(1.0 / ma[use] + 1.0 / mb[use])))
    score = np.abs(np.log(ratio)) / np.log1p(allowed)
    bands = ", ".join(f"{lo:.3g}-{2 * lo:.3g} rad/m: {r:.3g}" for lo, r in zip(edges[:-1][use], ratio))
    note = f"variance ratio a/b per octave band: {bands}"
    quantity = "worst band |log(V_a/V_b)| / log(1 + allowed)"
    row = bound(quantity, float(score.max()), 1.0, note=note)
    if row.ok:
        return row
    logs = np.log(ratio)
    if np.std(logs) < 0.25 * abs(np.mean(logs)):
        c = float(np.exp(np.mean(logs)))
        na, nb = a.shape[2], b.shape[2]
        power = math.log(c) / math.log(na / nb) if na != nb else math.nan
        cause = (f"amplitudes scale with the grid: every band is {c:.3g} x at n = {na} against n = {nb} (about "
                 f"(n_a/n_b)^{power:.2g}); the spectrum's amplitudes miss a normalization by the grid (sqrt(S dk^2) "
                 f"per mode, with the FFT's 1/n^2)")
    else:
        cause = "the spectrum's shape changes with resolution (a cutoff or peak tied to texels, not to metres)"
    return bound(quantity, float(score.max()), 1.0, note=f"{note}; likely cause: {cause}")


def caustics_flux_check(irradiance, *, expected: float = 1.0, rtol: float = 0.02):
    """A :class:`~wavephys.harness.Check` that a caustics map conserves light: its mean is flat water's.

    Parameters
    ----------
    irradiance : array_like (n_y, n_x) or (n_t, n_y, n_x)
        Floor irradiance relative to flat water's (1 = the light under flat water), finite, from a periodic
        surface over a flat floor.
    expected : float, optional, keyword-only
        The mean light, > 0 (default 1).
    rtol : float, optional, keyword-only
        Allowed relative difference of the mean, > 0 (default 0.02: Fresnel transmittance changes with slope by
        about that much on steep seas).

    Returns
    -------
    Check
        A ``"~="`` row of the mean against ``expected``; on failure the note names the likely cause (clipped at a
        ceiling, normalized to the peak, negative light, another scale).
    """
    from wavephys.harness.checks import compare

    e = _frames("irradiance", irradiance)
    check_scalar("expected", expected, lo=0.0, lo_open=True)
    check_scalar("rtol", rtol, lo=0.0, lo_open=True)
    mean, top = float(e.mean()), float(e.max())
    at_top = float(np.mean(e >= top * (1 - 1e-6)))
    note = f"min {e.min():.4g}, max {top:.4g}, {100 * at_top:.2g} % of texels at the max"
    row = compare("mean floor irradiance / flat water's", mean, expected, rtol=rtol, note=note)
    if row.ok:
        return row
    if e.min() < 0:
        cause = "negative light: an interpolation overshoot or a signed encoding read as unsigned"
    elif at_top > 0.005:
        cause = f"clipped at {top:.4g}: the bright lines saturate (an 8-bit or tone-mapped map) and their light is lost"
    elif abs(top - 1.0) < 1e-6 and mean < expected:
        cause = "normalized to its peak (max = 1), not to flat water's light: multiply by the peak's value"
    else:
        cause = f"the light is scaled by {mean / expected:.4g}: the map is not relative to flat water's irradiance"
    return compare(row.quantity, mean, expected, rtol=rtol, note=f"{note}; likely cause: {cause}")


def quantization_check(eta, *, max_noise: float = 0.01):
    """A :class:`~wavephys.harness.Check` that heights are not dominated by the lattice they are stored on.

    Parameters
    ----------
    eta : array_like (n_y, n_x) or (n_t, n_y, n_x)
        Heights, m, finite.
    max_noise : float, optional, keyword-only
        Largest quantization noise (step/√12) relative to the rms height (about its mean), > 0 (default 0.01).

    Returns
    -------
    Check
        A ``"<="`` row of the noise/signal ratio; the note names the lattice (float16, float16's subnormals
        below 6.1e-5, a uniform step) and its step.
    """
    from wavephys.harness.checks import bound

    f = _frames("eta", eta)
    check_scalar("max_noise", max_noise, lo=0.0, lo_open=True)
    signal = _rms(f - f.mean())
    sample = f.ravel()[:: max(1, f.size // 1_000_000)]
    values = np.unique(sample)
    lattice, step, storage = "no coarse lattice", 0.0, "storage"
    if values.size == 1:  # a still surface: no lattice can be seen, and nothing is lost to one
        return bound("quantization noise / rms height", 0.0, max_noise,
                     note=f"the heights do not vary (all {float(values[0]):.6g} m): nothing to quantize")
    if np.array_equal(sample.astype(np.float16).astype(np.float64), sample):
        storage = "float16 storage"
        typical = np.float16(min(np.median(np.abs(sample)) + 1e-300, 65504.0))
        step = float(np.spacing(typical))
        lattice = (f"float16 (steps of {step:.3g} at |eta| ~ {float(typical):.3g} m"
                   f"{'; subnormal below 6.1e-5 m' if float(typical) < 6.1e-5 else ''})")
    elif values.size < 0.5 * sample.size and values.size > 1:
        step = float(np.min(np.diff(values)))
        lattice = f"{values.size} distinct values, steps of {step:.3g}"
        storage = f"storage (steps of {step:.3g})"
    noise = step / math.sqrt(12) / signal if signal > 0 else (math.inf if step > 0 else 0.0)
    row = bound("quantization noise / rms height", noise, max_noise, note=f"heights on {lattice}")
    if not row.ok:
        row = bound(row.quantity, noise, max_noise,
                    note=f"heights on {lattice}; likely cause: the heights are too small for their {storage}; scale "
                         f"them (store eta / amplitude) or store float32")
    return row
