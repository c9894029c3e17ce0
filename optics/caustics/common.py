"""What the caustics methods share: checked inputs, the exact surface, and refracting sunlight
onto the floor. Irradiance is relative to the sun's irradiance on a horizontal plane above
the water (E0 = 1); light is parametrized by where each ray would cross z = 0, so a patch
of rays carries exactly E0 × its area there whatever the sun's elevation."""

from __future__ import annotations

import math
from typing import NamedTuple

import jax
import jax.numpy as jnp
import numpy as np

from optics.light.directions import refract_components
from optics.light.fresnel import MAX_INDEX, N_AIR, N_WATER, reflectance_exact
from wavephys.core.grid import Grid
from wavephys.core.inputs import (Array, Int, Real, _real_kind, check_array, check_bool, check_instance, check_int, check_scalar,
                                  is_traced, validate)
from wavephys.core.spectral import central_gradient

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["Lighting", "prepare", "surface_fields", "land", "blur_121", "bilateral_filter", "Tank", "walled_tank", "tank_clip", "tank_cells", "clip_cells", "CELL"]


MAX_DEPTH = 1e4
"""Deepest floor, m: light lands within float32's digits of a floor texel below that."""

MAX_COLUMN = 2 * MAX_DEPTH
"""Farthest the surface may lie from the floor (above it, or below a flat floor that cuts the troughs),
m: the deepest floor and as much again for the waves (a crest over a floor at MAX_DEPTH is answered)."""


class Lighting(NamedTuple):
    """Checked inputs of a caustics method.

    Attributes
    ----------
    eta : jax.Array (n, n)
        Surface heights, float32, m.
    grid : Grid
        The surface's grid.
    floor : float or jax.Array (n, n)
        A flat floor's depth, m, or the ground's heights, m.
    ground : bool
        True for a ground height field.
    direction : numpy.ndarray (3,)
        Unit direction of travel of the sunlight, pointing down.
    resolution : int
        The floor map's side, texels.
    n_water : float
        Refractive index of the water.
    """

    eta: jnp.ndarray        # surface heights (n, n), float32, m
    grid: Grid              # the surface's grid
    floor: object           # depth of a flat floor (float, m) or ground heights (n, n), m
    ground: bool            # True for a ground height field
    direction: np.ndarray   # unit direction of travel of the sunlight (3,), pointing down
    resolution: int         # floor map side m
    n_water: float


def prepare(eta, grid: Grid, depth, sun, resolution, n_water, fresnel, check_values: bool = True) -> Lighting:
    """Check a caustics call's common arguments (before any work) and normalize them.

    Parameters
    ----------
    eta : array_like (n, n)
        Surface heights, m.
    grid : Grid
    depth : float or array_like (n, n)
        A flat floor's depth, m, or the ground's heights, m.
    sun : array_like (3,)
        Direction towards the sun.
    resolution : int or None
        The floor map's side (None: the grid's).
    n_water : float
        Refractive index of the water.
    fresnel : bool
        Weigh the light by the Fresnel transmittance.
    check_values : bool
        Check the heights' values too (not only their shape).

    Returns
    -------
    Lighting
    """
    check_instance("grid", grid, Grid, "wavephys.Grid")
    n = grid.n
    if check_values:
        check_array("eta", eta, ndim=2, shape_tail=(n, n))
    else:  # kinds and shapes only (values are checked on the device by the caller)
        _real_kind("eta", eta, "an array of numbers")
        if not np.issubdtype(np.asarray(eta).dtype if not hasattr(eta, "dtype") else eta.dtype, np.number):
            raise TypeError(f"eta must be numeric, got dtype {getattr(eta, 'dtype', np.asarray(eta).dtype)}")
    if np.shape(eta) != (n, n):
        raise ValueError(f"eta must have shape ({n}, {n}), got {np.shape(eta)}")
    ground = np.ndim(depth) == 2
    if ground:
        check_array("depth", depth, ndim=2, shape_tail=(n, n), lo=-MAX_DEPTH)
        floor = jnp.asarray(depth, jnp.float32)
    else:
        check_scalar("depth", depth, lo=0.0, hi=MAX_DEPTH, lo_open=True)
        floor = float(depth)
    if not is_traced((eta, floor)):  # values are checked where they are concrete (as check_array does)
        finite, shallowest, deepest = (float(v) for v in _water_column(jnp.asarray(eta, jnp.float32), floor))
        if not finite:
            raise ValueError("eta must be finite everywhere; it contains NaN or inf")
        if ground and shallowest <= 0:
            raise ValueError("depth (a ground height field) must lie below the water surface everywhere")
        if deepest <= 0:  # (a flat floor may cut the troughs, below)
            raise ValueError(f"eta lies below the floor everywhere (its highest sample {deepest - floor:.4g} m, the floor "
                             f"at -depth = {-floor:g} m): there is no water above the floor")
        if max(deepest, -shallowest) > MAX_COLUMN:  # (a flat floor may cut the troughs: the rays' lines still land)
            raise ValueError(f"eta: the surface lies {max(deepest, -shallowest):.4g} m from the floor at the farthest, "
                             f"at most {MAX_COLUMN:g} m (MAX_COLUMN: beyond it light lands outside float32's digits "
                             "of a texel)")
    check_array("sun", sun, ndim=1, shape_tail=(3,))
    sun = np.asarray(sun, float)
    if not sun[2] > 0:
        raise ValueError(f"sun must point up (z > 0), got {sun.tolist()}")
    check_scalar("n_water", n_water, lo=N_AIR, hi=MAX_INDEX, lo_open=True)  # denser than air: light bends in
    check_bool("fresnel", fresnel)
    m = n if resolution is None else check_int("resolution", resolution, lo=2)
    return Lighting(jnp.asarray(eta, jnp.float32), grid, floor, ground, -sun / np.linalg.norm(sun), m,
                    float(n_water))


@jax.jit
def _water_column(eta, floor):
    """Whether every sample is finite (1/0), and the shallowest and the deepest water between the
    surface and the floor (a depth or a ground height field) over the finite samples."""
    column = eta + floor if jnp.ndim(floor) == 0 else eta - floor
    finite = jnp.isfinite(column)
    return jnp.stack([jnp.all(finite).astype(column.dtype), jnp.min(jnp.where(finite, column, jnp.inf)),
                      jnp.max(jnp.where(finite, column, -jnp.inf))])


class Tank(NamedTuple):
    """A tank's caustics problem on its even extension (:func:`walled_tank`).

    The surface (and a ground) mirrored across each walled axis and repeated across each periodic one,
    on ``Grid(2n, 2L)``: periodic there, with the derivatives of the tank's cosine modes. The tank is the
    first n samples (and the first m floor texels) along each axis.

    Attributes
    ----------
    light : Lighting
        The extended problem (2n samples, a 2m floor map).
    walls : tuple of bool
        (x walled, y walled).
    n : int
        The tank's samples a side.
    m : int
        The tank's floor texels a side.
    """

    light: Lighting         # the extended problem (2n samples, a 2m floor map)
    walls: tuple            # (x walled, y walled)
    n: int                  # the tank's samples a side
    m: int                  # the tank's floor texels a side


def walled_tank(light: Lighting, walls) -> Tank | None:
    """The even extension of a checked caustics problem whose square is a tank with opaque walls on
    ``walls`` (``None``/``"none"``: no walls, returns None). An axis is walled on both ends or not at
    all (``"x"``, ``"y"``, ``"all"``, or both side names of an axis). Refused where the sun stands lower
    than the steepest slope (a crest's shadow across a wall is not modelled) and where 2·n·refine would
    pass 8192 (checked by the methods).

    Parameters
    ----------
    light : Lighting
        A checked problem.
    walls : str or None
        The walled sides.

    Returns
    -------
    Tank or None
    """
    if walls is None:
        return None
    from wavephys.physics.walls import check_walls, wall_axes

    sides = check_walls(walls)  # a lone wall needs an open side: refused by name (margin 0)
    if not sides:
        return None
    wx, wy = wall_axes(sides)
    n, m = light.grid.n, light.resolution
    if not bool(jnp.isfinite(light.eta).all()):
        raise ValueError("eta must be finite everywhere; it contains NaN or inf")

    def extend(field):
        field = jnp.concatenate([field, field[:, ::-1] if wx else field], axis=1)
        return jnp.concatenate([field, field[::-1, :] if wy else field], axis=0)

    eta, grid = extend(light.eta), Grid(2 * n, 2 * float(light.grid.length))
    if shadow_steps(eta, grid, light.direction) > 0:  # on the extension: the tank's surface is not periodic
        raise ValueError("walls: the sun stands lower than the surface's steepest slope, so crests shade the water; "
                         "a shadow cast across a tank's wall is not modelled (raise the sun or drop walls)")
    floor = extend(light.floor) if light.ground else light.floor
    return Tank(light._replace(eta=eta, grid=grid, floor=floor, resolution=2 * m), (wx, wy), n, m)


def tank_clip(tank: Tank | None, samples: int):
    """What the beam's :func:`_vertices` needs to trace a tank on its extension traced with ``samples``
    a side: ``(x walled, y walled, the tank's samples a side)`` (static), or None without a tank.

    Parameters
    ----------
    tank : Tank or None
    samples : int
        Samples a side traced on the extension.

    Returns
    -------
    tuple or None
    """
    if tank is None:
        return None
    return (bool(tank.walls[0]), bool(tank.walls[1]), samples // (2 * tank.n) * tank.n)


def tank_cells(clip, samples: int):
    """1 for the traced cells that carry the tank's light, 0 for its mirror image's, ``(samples,
    samples)``: along a walled axis the cells between the tank's samples and the two that straddle its
    walls (cut at the wall by :func:`clip_cells`); every cell along a periodic axis (its copy is real).

    Parameters
    ----------
    clip : tuple
        :func:`tank_clip`'s answer.
    samples : int
        Samples a side traced.

    Returns
    -------
    jax.Array (samples, samples)
        float32 weights, 0 or 1.
    """
    wx, wy, inside = clip
    line = np.zeros(samples)
    line[:inside] = 1.0
    line[samples - 1] = 1.0
    x = line if wx else np.ones(samples)
    y = line if wy else np.ones(samples)
    return jnp.asarray(y[:, None] * x[None, :], jnp.float32)


def clip_cells(corners, clip, samples: int):
    """Cut the cells that straddle a tank's walls at the wall: ``corners`` is a list over the cell's
    corners (:data:`CELL` order, (row offset a, column offset b)) of per-cell fields (landed positions,
    crossing points); the corner past the wall moves to the midpoint of the cell's edge, which is where
    the beam's linear map puts the wall. Returns the new list.

    Parameters
    ----------
    corners : list
        Per corner of a cell, per-cell fields.
    clip : tuple
        :func:`tank_clip`'s answer.
    samples : int
        Samples a side traced.

    Returns
    -------
    list
    """
    wx, wy, inside = clip
    out = list(corners)
    for walled, axis in ((wx, 1), (wy, 0)):
        if not walled:
            continue
        index = jnp.arange(samples)
        # the cell from sample inside−1 to inside: its far corner (offset 1) is the mirror's; the cell
        # from the last sample to sample 0 (across the periodic seam): its near corner (offset 0) is
        shape = (1, samples) if axis == 1 else (samples, 1)
        far = (index == inside - 1).reshape(shape)
        near = (index == samples - 1).reshape(shape)
        for k, (a, b) in enumerate(CELL):
            offset = b if axis == 1 else a
            partner = next(j for j, (a2, b2) in enumerate(CELL)
                           if (a2 == a if axis == 1 else b2 == b) and (b2 if axis == 1 else a2) != offset)
            mid = 0.5 * (corners[k] + corners[partner])
            out[k] = jnp.where(far if offset == 1 else near, mid, out[k])
        corners = list(out)
    return out


CELL = ((0, 0), (0, 1), (1, 1), (1, 0))
"""(row = y, column = x) offsets of a surface cell's corners, counter-clockwise."""


def surface_fields(eta, grid: Grid, oversample: int = 1):
    """η, ∂η/∂x, ∂η/∂y on ``Grid(n·oversample, L)`` (Fourier interpolation, exact for a
    band-limited periodic field): shapes (n·o, n·o); slopes dimensionless.

    Parameters
    ----------
    eta : array_like (n, n)
        Heights, m.
    grid : Grid
    oversample : int
        o, the refinement.

    Returns
    -------
    (jax.Array, jax.Array, jax.Array)
        η (m), ∂η/∂x and ∂η/∂y.
    """
    fine = Grid(grid.n * oversample, grid.length)
    eta = grid.refine(eta, oversample)
    return (eta, *fine.gradient(eta))


@jax.jit
def _slope_and_relief(eta, dx):
    """(steepest central-difference slope, max η − min η) in one pass on the device."""
    gx, gy = central_gradient(eta, dx)
    return jnp.max(jnp.hypot(gx, gy)), jnp.max(eta) - jnp.min(eta)


def shadow_steps(eta, grid: Grid, d) -> int:
    """How many half-cell steps toward the sun :func:`sunlit` must look (0: nothing can be in
    shadow, because the sun stands higher than the steepest slope). Host-side, concrete ``eta``."""
    horizontal = math.hypot(float(d[0]), float(d[1]))
    if horizontal == 0.0:
        return 0
    tan_elevation = -float(d[2]) / horizontal
    steepest, relief = (float(v) for v in _slope_and_relief(jnp.asarray(eta, jnp.float32), grid.dx))
    if steepest < tan_elevation:
        return 0
    return min(int(math.ceil(relief / tan_elevation / (0.5 * float(grid.dx)))) + 1, 4 * grid.n)


def sunlit(eta, grid: Grid, d, steps: int):
    """1 where the sun reaches the surface sample, 0 in shadow (a facet facing away from the
    sun, or one hidden behind a crest): the ray from each sample toward the sun, marched
    ``steps`` half cells (:func:`shadow_steps`), must stay above the periodic surface."""
    if steps == 0:
        return jnp.ones_like(eta)
    horizontal = jnp.hypot(d[0], d[1])
    ux, uy = -d[0] / horizontal, -d[1] / horizontal  # toward the sun
    rise = -d[2] / horizontal * 0.5 * grid.dx         # ray height gained per half cell
    x, y = grid.mesh()
    step = 0.5 * grid.dx

    def body(j, hidden):
        s = j * step
        above = grid.sample(eta, x + s * ux, y + s * uy) - (eta + j * rise)
        return hidden | (above > 1e-6 * (1.0 + jnp.abs(eta)))

    hidden = jax.lax.fori_loop(1, steps + 1, body, jnp.zeros(eta.shape, bool))
    return jnp.where(hidden, 0.0, 1.0).astype(eta.dtype)


def land(xs, ys, eta, gx, gy, d, floor, n_water, fresnel, iterations: int = 5):
    """Refract sunlight (direction of travel ``d``) at surface points and land it on the floor.

    ``xs, ys`` surface points (m), ``eta`` their heights, ``gx, gy`` slopes; ``floor`` a
    depth (m, flat floor at z = −depth) or a callable z_g(x, y) (ground height field,
    intersected by fixed-point iteration). Returns landing X, Y (m) and the Fresnel
    transmittance (1 with ``fresnel=False``).

    Parameters
    ----------
    xs, ys : jax.Array
        Surface points, m.
    eta, gx, gy : jax.Array
        Their heights (m) and slopes.
    d : array_like (3,)
        The sunlight's direction of travel.
    floor : float or Callable
        Depth (m) or z_g(x, y).
    n_water : float
        Refractive index of the water.
    fresnel : bool
        Weigh by the Fresnel transmittance.
    iterations : int
        Fixed-point iterations on a ground.

    Returns
    -------
    (jax.Array, jax.Array, jax.Array)
        X, Y (m) and the transmittance.
    """
    d = jnp.asarray(d, gx.dtype)
    if d.shape != (3,):
        raise ValueError(f"d must be one direction (3,), got shape {d.shape}")
    d = tuple(d)  # unit
    (tx, ty, tz), _, _ = refract_components(d, (-gx, -gy, jnp.ones_like(gx)), N_AIR,
                                            n_water)  # air into water: never total internal reflection
    # against the upward normal: a facet the sun reaches from below (cos ≤ 0) transmits nothing
    cos_i = jnp.clip((d[0] * gx + d[1] * gy - d[2]) / jnp.sqrt(1.0 + gx * gx + gy * gy), 0.0, 1.0)
    trans = 1.0 - reflectance_exact(cos_i, N_AIR, n_water) if fresnel else jnp.ones_like(cos_i)
    down = -tz
    if callable(floor):
        s = (eta - floor(xs, ys)) / down
        for _ in range(iterations):
            s = (eta - floor(xs + s * tx, ys + s * ty)) / down
    else:
        s = (eta + floor) / down
    return xs + s * tx, ys + s * ty, trans


_IMAGE = Array(ndim=2)


@validate(image=_IMAGE)
def blur_121(image):
    """The 3 × 3 1-2-1 blur (periodic) Loviscach uses to hide the beam triangles; ``image`` 2-D.

    Parameters
    ----------
    image : array_like (ny, nx)
        Any quantity per texel (irradiance, W/m² or relative).

    Returns
    -------
    jax.Array (ny, nx)
        Blurred, its sum kept (the kernel's weights add to 1).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*.
    """
    image = jnp.asarray(image)
    k = lambda a, ax: 0.25 * jnp.roll(a, 1, ax) + 0.5 * a + 0.25 * jnp.roll(a, -1, ax)
    return k(k(image, 0), 1)


@validate(image=_IMAGE, radius=Int(lo=1, hi=32), sigma_space=Real(lo=0.0, hi=1e3, lo_open=True),
          sigma_range=Real(lo=0.0, hi=1e3, lo_open=True))
def bilateral_filter(image, radius: int = 2, sigma_space: float = 1.0, sigma_range: float = 0.2):
    """Edge-preserving bilateral filter (periodic): weights exp(−r²/2σ_s²)·exp(−ΔE²/2σ_r²).

    ``sigma_space`` in pixels, ``sigma_range`` relative to the image mean (an all-zero
    image is returned unchanged); ``image`` 2-D, ``radius`` 1 to 32 pixels.

    Parameters
    ----------
    image : array_like (ny, nx)
        Any quantity per texel.
    radius : int
        Half-width of the window, pixels.
    sigma_space : float
        Spatial width, pixels.
    sigma_range : float
        Width in value, relative to the mean of |image|.

    Returns
    -------
    jax.Array (ny, nx)
    """
    image = jnp.asarray(image)
    scale = jnp.maximum(jnp.mean(jnp.abs(image)), jnp.finfo(jnp.float32).tiny)
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
