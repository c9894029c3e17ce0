r"""Caustics: irradiance on the floor under a wavy surface lit by the sun (SPEC §2.4).

All methods trace parallel sunlight through the height field η (periodic, on a
:class:`wavephys.Grid`), refract it by Snell's law at the exact surface normal (spectral
gradient of η) and land it on a flat floor at a given depth or on a ground height
field. Irradiance is relative to the sun's irradiance on a horizontal plane above the
water (E0 = 1): flat water without Fresnel loss gives 1 everywhere. Light is
parametrized by where each ray would cross z = 0 (x₀), so a patch of rays carries
exactly E0 × its x₀-area whatever the sun's elevation.

Methods (``floor_irradiance(..., method=)``):

* ``"beam"`` — beam tracing with area ratios (Loviscach 2003; Watt 1990): every surface
  cell is a beam whose corners are traced exactly; its flux E0·T·A₀ is spread over its
  bilinear floor footprint by ``samples``² sub-beams deposited cloud-in-cell. Flux is
  conserved exactly; irradiance = source area / projected area; an optional 1-2-1 blur
  hides the cells. Second order in the mesh spacing where there is no fold. With
  ``samples=1`` (the fast setting) each vertex's ray carries the flux of its dual cell.
* ``"photon"`` — photon splatting (Baboud & Décoret 2006): one photon per jittered texel
  of an ``m × m`` light-view texture, a 2-D histogram on the floor, then an
  edge-preserving (bilateral) filter. Noise falls as 1/sqrt(photons per texel).
* ``"blinn_phong"`` — Schneider & Westermann's (2001) transmissive Blinn–Phong term
  ⟨H_t, N⟩^tr, H_t = normalize(L − V/n), V pointing down to the floor, normalized to 1
  for flat water: a shading trick, not a flux (it cannot focus light).
* ``"reference"`` — brute force: the surface is Fourier-interpolated ``oversample`` times
  finer and one exact ray per fine cell lands cloud-in-cell. Used to measure the others.

Exact facts the tests check: flux conservation (floor total = transmitted total, on the
periodic domain, no absorption); uniform light under flat water; for η = a cos kx lit
vertically with small slopes, E(X) = E0/|1 − (z/z_f) cos kx| at X = x − (z/z_f) sin(kx)/k
with focal depth z_f = n/((n − 1) a k²) (:func:`sinusoid_irradiance`).
"""

from __future__ import annotations

import math
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from optics.directions import normalize
from optics.fresnel import N_AIR, N_WATER, _exact as _fresnel_exact
from wavephys._inputs import check_array, check_choice, check_int, check_scalar
from wavephys.params import Grid

__all__ = ["METHODS", "floor_irradiance", "first_fold_depth", "central_slopes", "surface_fields", "surface_slopes", "sinusoid_irradiance", "focal_depth",
           "bilateral_filter", "blur_121"]

METHODS = ("beam", "photon", "blinn_phong", "reference")


# -- the exact surface ------------------------------------------------------------------
def _slope_spectra(height, length):
    m = height.shape[-1]
    spec = jnp.fft.rfft2(height)
    ky = 2 * jnp.pi * jnp.fft.fftfreq(m, length / m)[:, None]
    kx = 2 * jnp.pi * jnp.fft.rfftfreq(m, length / m)[None, :]
    return jnp.stack([1j * kx * spec, 1j * ky * spec])


def surface_slopes(height, length):
    """∂η/∂x, ∂η/∂y of a periodic height field on its own grid (spectral, exact), 1."""
    m = height.shape[-1]
    out = jnp.fft.irfft2(_slope_spectra(height, length), s=(m, m))
    return out[0], out[1]


def surface_fields(height, length, oversample: int = 1):
    """η, ∂η/∂x, ∂η/∂y on a grid ``oversample`` times finer (Fourier interpolation, exact for
    a band-limited periodic field). Shapes ``(n·o, n·o)``; slopes dimensionless."""
    n = height.shape[-1]
    m = n * oversample
    if oversample == 1:
        return (height, *surface_slopes(height, length))
    spec = jnp.fft.rfft2(height)
    h = n // 2
    big = jnp.zeros((m, m // 2 + 1), spec.dtype)
    big = big.at[:h, :h + 1].set(spec[:h, :h + 1]).at[m - h:, :h + 1].set(spec[n - h:, :h + 1])
    fine = jnp.fft.irfft2(big * (oversample * oversample), s=(m, m))
    return (fine, *surface_slopes(fine, length))


def _land(xs, ys, eta, gx, gy, d, floor, n_water, fresnel, iterations=5):
    """Refract sunlight (direction of travel ``d``) at surface points and land it on the floor.

    ``xs, ys`` surface points (m), ``eta`` their heights, ``gx, gy`` slopes; ``floor`` a
    depth (m, flat floor at z = −depth) or a callable z_g(x, y) (ground height field,
    intersected by fixed-point iteration). Returns landing X, Y (m) and the Fresnel
    transmittance (1 with ``fresnel=False``).
    """
    normal = normalize(jnp.stack([-gx, -gy, jnp.ones_like(gx)], axis=-1))
    cos_i = -jnp.sum(d * normal, axis=-1)
    eta_r = N_AIR / n_water
    k = 1.0 - eta_r**2 * (1.0 - cos_i**2)  # > 0 always: light goes from air into water
    t = eta_r * d + (eta_r * cos_i - jnp.sqrt(k))[..., None] * normal
    trans = 1.0 - _fresnel_exact(cos_i, N_AIR, n_water) if fresnel else jnp.ones_like(cos_i)
    down = -t[..., 2]
    if callable(floor):
        s = (eta - floor(xs, ys)) / down
        for _ in range(iterations):
            s = (eta - floor(xs + s * t[..., 0], ys + s * t[..., 1])) / down
    else:
        s = (eta + floor) / down
    return xs + s * t[..., 0], ys + s * t[..., 1], trans


def _bilinear(field, length):
    """Periodic bilinear interpolation of a (m, m) field whose point i sits at x = (i − m/2)·h."""
    m = field.shape[-1]
    h = length / m

    def f(x, y):
        u = x / h + m / 2
        v = y / h + m / 2
        i0, j0 = jnp.floor(u), jnp.floor(v)
        fu, fv = u - i0, v - j0
        i0 = i0.astype(jnp.int32) % m
        j0 = j0.astype(jnp.int32) % m
        i1, j1 = (i0 + 1) % m, (j0 + 1) % m
        return ((1 - fu) * (1 - fv) * field[j0, i0] + fu * (1 - fv) * field[j0, i1]
                + (1 - fu) * fv * field[j1, i0] + fu * fv * field[j1, i1])
    return f


def _deposit(x, y, flux, m, length):
    """Cloud-in-cell deposit of flux on the periodic floor map (one scatter); irradiance."""
    h = length / m
    u = x.ravel() / h + m / 2
    v = y.ravel() / h + m / 2
    i0, j0 = jnp.floor(u), jnp.floor(v)
    fu, fv = u - i0, v - j0
    i0 = i0.astype(jnp.int32) % m
    j0 = j0.astype(jnp.int32) % m
    i1, j1 = (i0 + 1) % m, (j0 + 1) % m
    w = flux.ravel()
    index = jnp.concatenate([j0 * m + i0, j0 * m + i1, j1 * m + i0, j1 * m + i1])
    value = jnp.concatenate([w * (1 - fu) * (1 - fv), w * fu * (1 - fv), w * (1 - fu) * fv, w * fu * fv])
    total = jnp.zeros(m * m, w.dtype).at[index].add(value, mode="promise_in_bounds")  # indices wrapped above
    return total.reshape(m, m) / (h * h)


def blur_121(image):
    """The 3 × 3 1-2-1 blur (periodic) Loviscach uses to hide the beam triangles."""
    k = lambda a, ax: 0.25 * jnp.roll(a, 1, ax) + 0.5 * a + 0.25 * jnp.roll(a, -1, ax)
    return k(k(image, 0), 1)


def bilateral_filter(image, radius: int = 2, sigma_space: float = 1.0, sigma_range: float = 0.2):
    """Edge-preserving bilateral filter (periodic): weights exp(−r²/2σ_s²)·exp(−ΔE²/2σ_r²).

    ``sigma_space`` in pixels, ``sigma_range`` relative to the image mean.
    """
    scale = jnp.mean(image)
    num = jnp.zeros_like(image)
    den = jnp.zeros_like(image)
    for dy in range(-radius, radius + 1):
        for dx in range(-radius, radius + 1):
            shifted = jnp.roll(image, (dy, dx), (0, 1))
            w = math.exp(-(dx * dx + dy * dy) / (2 * sigma_space**2)) * jnp.exp(
                -((shifted - image) / (sigma_range * scale)) ** 2 / 2)
            num = num + w * shifted
            den = den + w
    return num / den


# -- methods ----------------------------------------------------------------------------
def _cell_corners(field, a, b):
    """``field`` at the corner (row + a, col + b) of every cell (periodic)."""
    return jnp.roll(field, (-a, -b), (0, 1))


_CORNERS = ((0, 0), (0, 1), (1, 0), (1, 1))  # (row = y, column = x) offsets


_slope_spectra_jit = jax.jit(_slope_spectra)


def central_slopes(height, length):
    """∂η/∂x, ∂η/∂y by periodic central differences (second order), dimensionless."""
    h = length / height.shape[-1]
    gx = (jnp.roll(height, -1, 1) - jnp.roll(height, 1, 1)) / (2 * h)
    gy = (jnp.roll(height, -1, 0) - jnp.roll(height, 1, 0)) / (2 * h)
    return gx, gy


def _beam(height, length, d, floor, n_water, m, samples, blur, fresnel, ground, normals):
    vertical = bool(d[0] == 0 and d[1] == 0)
    d = jnp.asarray(d, jnp.float32)
    if normals == "central":
        return _beam_core(None, height, length, d, floor, n_water, m, samples, blur, fresnel, ground, vertical)
    # two compiled programs, the second starting with its FFT: on CPU, XLA runs an FFT
    # single-threaded when another operation precedes it in the same program
    # (openxla/xla#46345); see wavephys.simulation
    return _beam_core(_slope_spectra_jit(height, length), height, length, d, floor, n_water, m, samples, blur,
                      fresnel, ground, vertical)


@partial(jax.jit, static_argnames=("m", "samples", "blur", "fresnel", "ground", "vertical"))
def _beam_core(slope_spectra, eta, length, d, floor, n_water, m, samples, blur, fresnel, ground, vertical):
    n = eta.shape[-1]
    h = length / n
    if slope_spectra is None:
        gx, gy = central_slopes(eta, length)
    else:
        gx, gy = jnp.fft.irfft2(slope_spectra, s=(n, n))
    c = (jnp.arange(n) - n // 2) * h
    xv, yv = jnp.meshgrid(c, c)
    floor_fn = _bilinear(floor, length) if ground else floor
    X, Y, T = _land(xv, yv, eta, gx, gy, d, floor_fn, n_water, fresnel)
    finite = jnp.isfinite(eta).all()  # checked here, raised by the caller: no extra pass
    if samples == 1:
        # one ray per vertex carrying the flux of its dual cell: E0·T·(x0-area), with the
        # x0-area h²·det(∂x0/∂x) = h²·(1 − gx·dx/dz − gy·dy/dz)
        area = h * h if vertical else h * h * jnp.abs(1.0 - (gx * d[0] + gy * d[1]) / d[2])
        out = _deposit(X, Y, area * T, m, length)
        return (blur_121(out) if blur else out), finite
    # work with displacements so that corners across the periodic seam stay adjacent
    disp = [X - xv, Y - yv, -eta * d[0] / d[2], -eta * d[1] / d[2]]  # floor, and z = 0 crossing
    q = (jnp.arange(samples) + 0.5) / samples
    su, sv = (g.ravel()[:, None, None] for g in jnp.meshgrid(q, q))
    weights = [(1 - su) * (1 - sv), su * (1 - sv), (1 - su) * sv, su * sv]

    def bilinear(F):
        return sum(w * _cell_corners(F, a, b) for w, (a, b) in zip(weights, _CORNERS))

    px, py = xv + su * h + bilinear(disp[0]), yv + sv * h + bilinear(disp[1])
    # flux of a cell: E0 × the area of its four rays' z = 0 crossings × transmittance
    if vertical:  # the crossings are the vertices themselves: area h² exactly
        area = h * h
    else:
        cx = [xv + b * h + _cell_corners(disp[2], a, b) for a, b in _CORNERS]
        cy = [yv + a * h + _cell_corners(disp[3], a, b) for a, b in _CORNERS]
        area = 0.5 * jnp.abs((cx[3] - cx[0]) * (cy[2] - cy[1]) - (cx[2] - cx[1]) * (cy[3] - cy[0]))
    t_cell = 0.25 * sum(_cell_corners(T, a, b) for a, b in _CORNERS)
    flux = jnp.broadcast_to(area * t_cell / (samples * samples), px.shape)
    out = _deposit(px, py, flux, m, length)
    return (blur_121(out) if blur else out), finite


@partial(jax.jit, static_argnames=("m", "oversample", "fresnel", "ground"))
def _rays(height, length, d, floor, n_water, x0, y0, m, oversample, fresnel, ground):
    """Rays crossing z = 0 at (x0, y0), each with flux E0·(L²/count), through the exact
    (Fourier-interpolated) surface; deposited cloud-in-cell on an m × m floor map."""
    eta, gx, gy = (_bilinear(f, length) for f in surface_fields(height, length, oversample))
    xs, ys = x0, y0
    for _ in range(4):  # surface hit: the ray through (x0, y0, 0) meets z = η(x, y)
        e = eta(xs, ys)
        xs, ys = x0 + e * d[0] / d[2], y0 + e * d[1] / d[2]
    floor_fn = _bilinear(floor, length) if ground else floor
    X, Y, T = _land(xs, ys, eta(xs, ys), gx(xs, ys), gy(xs, ys), d, floor_fn, n_water, fresnel)
    flux = T * (length * length / x0.size)
    return _deposit(X, Y, flux, m, length)


def _blinn_phong(height, length, d, n_water, m, exponent):
    eta, gx, gy = surface_fields(height, length, max(1, m // height.shape[-1]))
    normal = normalize(jnp.stack([-gx, -gy, jnp.ones_like(gx)], axis=-1))
    light = -d
    view = jnp.array([0.0, 0.0, -1.0])  # towards the floor point below
    ht = normalize(light - view / n_water)
    flat = ht[2] ** exponent
    return jnp.maximum(jnp.sum(ht * normal, axis=-1), 0.0) ** exponent / flat


# -- public -----------------------------------------------------------------------------
def floor_irradiance(height, grid: Grid, depth, sun=(0.0, 0.0, 1.0), method: str = "beam", *,
                     resolution: int | None = None, n_water: float = N_WATER, fresnel: bool = True,
                     samples: int = 2, blur: bool = False, normals: str = "spectral", photons_per_texel: int = 1,
                     filter_radius: int = 2, oversample: int = 4, exponent: float = 20.0, seed: int = 0):
    """Irradiance on the floor, relative to the sun's horizontal irradiance above water.

    Parameters
    ----------
    height : array_like (n, n)
        Surface height η on ``grid``, m (periodic).
    grid : Grid
    depth : float or array_like (n, n)
        Depth of a flat floor below the still surface, m, > 0; or a ground height field
        z_g (m, negative below the surface, every point below the water) on the same grid.
    sun : array_like (3,)
        Direction towards the sun (any length), pointing up (z > 0).
    method : {"beam", "photon", "blinn_phong", "reference"}
    resolution : int
        Floor map size m (default n): the map covers the same periodic square.
    n_water : float
        Refractive index of water, ≥ 1.
    fresnel : bool
        Multiply by the exact Fresnel transmittance (False: every ray carries full flux).
    samples : int
        ``"beam"``: sub-beams per cell edge (samples² per cell).
    blur : bool
        ``"beam"``: apply the 1-2-1 blur.
    normals : {"spectral", "central"}
        ``"beam"``: surface slopes exact (FFT) or by central differences (second order,
        no transforms: the fast setting).
    photons_per_texel : int
        ``"photon"``: photons per floor texel (the light-view texture is m·sqrt(p) square).
    filter_radius : int
        ``"photon"``: bilateral filter radius in texels (0: raw histogram).
    oversample : int
        ``"reference"``: Fourier interpolation factor of the surface (rays per cell = o²).
    exponent : float
        ``"blinn_phong"``: transmissive exponent tr.
    seed : int
        ``"photon"``: jitter seed.

    Returns
    -------
    jax.Array (m, m)
        Floor irradiance / E0 (dimensionless), on points at the grid's coordinates.
    """
    check_choice("method", method, METHODS)
    n = grid.n
    if jnp.shape(height) != (n, n):
        raise ValueError(f"height must have shape ({n}, {n}), got {jnp.shape(height)}")
    if method != "beam":  # the beam method checks finiteness inside its own program
        check_array("height", height)
    ground = jnp.ndim(depth) == 2
    if ground:
        check_array("depth", depth, shape_tail=(n, n))
        if float(jnp.max(jnp.asarray(depth) - jnp.asarray(height))) >= 0:
            raise ValueError("depth (a ground height field) must lie below the water surface everywhere")
        floor = jnp.asarray(depth, jnp.float32)
    else:
        check_scalar("depth", depth, lo=0.0, lo_open=True)
        floor = float(depth)
    check_array("sun", sun, min_ndim=1, shape_tail=(3,))
    sun = np.asarray(sun, float)
    if not sun[2] > 0:
        raise ValueError(f"sun must point up (z > 0), got {tuple(sun)}")
    check_scalar("n_water", n_water, lo=1.0)
    m = n if resolution is None else check_int("resolution", resolution, lo=2)
    d = -sun / np.linalg.norm(sun)  # numpy: the beam method branches on a vertical sun
    height = jnp.asarray(height, jnp.float32)
    length = float(grid.length)
    if method == "beam":
        check_choice("normals", normals, ("spectral", "central"))
        out, finite = _beam(height, length, d, floor, n_water, m, check_int("samples", samples, lo=1), bool(blur),
                            bool(fresnel), ground, normals)
        if not bool(finite):
            raise ValueError("height must be finite everywhere; it contains NaN or inf")
        return out
    if method == "blinn_phong":
        if ground:
            raise ValueError("blinn_phong takes a flat floor depth (it ignores geometry)")
        if m % n:
            raise ValueError(f"blinn_phong needs resolution a multiple of n={n}, got {m}")
        return _blinn_phong(height, length, jnp.asarray(d, jnp.float32), n_water, m, float(exponent))
    if method == "photon":
        p = check_int("photons_per_texel", photons_per_texel, lo=1)
        side = int(round(m * math.sqrt(p)))
        c = (jnp.arange(side) - side / 2 + 0.5) * (length / side)
        x0, y0 = jnp.meshgrid(c, c)
        jitter = jax.random.uniform(jax.random.PRNGKey(seed), (2, side, side), minval=-0.5, maxval=0.5)
        x0, y0 = x0 + jitter[0] * length / side, y0 + jitter[1] * length / side
        out = _rays(height, length, jnp.asarray(d, jnp.float32), floor, n_water, x0, y0, m, 2, bool(fresnel), ground)
        r = check_int("filter_radius", filter_radius, lo=0)
        return bilateral_filter(out, r) if r else out
    o = check_int("oversample", oversample, lo=1)
    side = n * o
    c = (jnp.arange(side) - side / 2 + 0.5) * (length / side)
    x0, y0 = jnp.meshgrid(c, c)
    return _rays(height, length, jnp.asarray(d, jnp.float32), floor, n_water, x0, y0, m, o, bool(fresnel), ground)


def sinusoid_irradiance(x, amplitude, wavenumber, depth, n_water=N_WATER):
    """Paraxial floor irradiance under η = a cos kx lit vertically (small slopes), E/E0.

    Returns (X, E): the landing point X = x − (z/z_f) sin(kx)/k and E = 1/|1 − (z/z_f) cos kx|
    with z_f = n/((n − 1) a k²) (SPEC §2.4).
    """
    zf = focal_depth(amplitude, wavenumber, n_water)
    r = depth / zf
    return x - r * np.sin(wavenumber * x) / wavenumber, 1.0 / np.abs(1.0 - r * np.cos(wavenumber * x))


def focal_depth(amplitude, wavenumber, n_water=N_WATER):
    """z_f = n/((n − 1) a k²), m: the depth where the crests of η = a cos kx focus the sun."""
    check_scalar("amplitude", amplitude, lo=0.0, lo_open=True)
    check_scalar("wavenumber", wavenumber, lo=0.0, lo_open=True)
    return n_water / ((n_water - 1.0) * amplitude * wavenumber**2)


def first_fold_depth(height, grid: Grid, sun=(0.0, 0.0, 1.0), n_water: float = N_WATER,
                     max_depth: float = 1e4, tolerance: float = 1e-4):
    """The shallowest floor depth (m) at which the traced surface mesh folds over.

    Above it every surface cell lands as a non-inverted quad (irradiance finite); at it
    the first caustic (a focus) forms. Bisection on the depth, relative ``tolerance``.
    For η = a cos kx it measures the focal depth z_f (SPEC §2.4). ``inf`` if no fold
    occurs above ``max_depth``.
    """
    n = grid.n
    check_array("height", height, min_ndim=2, shape_tail=(n, n))
    check_array("sun", sun, min_ndim=1, shape_tail=(3,))
    check_scalar("max_depth", max_depth, lo=0.0, lo_open=True)
    length = float(grid.length)
    height = jnp.asarray(height, jnp.float32)
    d = jnp.asarray(-np.asarray(sun, float) / np.linalg.norm(sun), jnp.float32)
    eta, gx, gy = surface_fields(height, length)
    h = length / n
    c = (jnp.arange(n) - n // 2) * h
    xv, yv = jnp.meshgrid(c, c)

    @jax.jit
    def min_area(depth):
        X, Y, _ = _land(xv, yv, eta, gx, gy, d, depth, n_water, False)
        dx_, dy_ = X - xv, Y - yv
        cx = [xv + b * h + _cell_corners(dx_, a, b) for a, b in _CORNERS]
        cy = [yv + a * h + _cell_corners(dy_, a, b) for a, b in _CORNERS]
        # signed area of the quad (0,0) → (0,1) → (1,1) → (1,0) via its diagonals
        return jnp.min(0.5 * ((cx[3] - cx[0]) * (cy[2] - cy[1]) - (cx[2] - cx[1]) * (cy[3] - cy[0])))

    if float(min_area(max_depth)) > 0:
        return math.inf
    lo, hi = 0.0, float(max_depth)
    while hi - lo > tolerance * hi:
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if float(min_area(mid)) <= 0 else (mid, hi)
    return 0.5 * (lo + hi)
