"""Beam tracing by exact rasterization (Watt 1990; Loviscach 2003): every surface cell is a beam.

The rays through the samples of the surface are refracted exactly and landed on the floor;
each cell between four samples is split into two triangles, and each triangle carries the
flux E0·T·A₀ of the sunlight that crosses z = 0 over its area A₀ there (T: the mean
Fresnel transmittance of its corners, 0 where the sun cannot reach). That flux is spread
uniformly over the triangle's landed footprint and every floor texel receives exactly the
share of the footprint that covers it (:func:`wavephys.core.sampling.deposit_triangles`:
coverage computed, not sampled at points). Irradiance = flux / texel area, so flux is
conserved exactly; where the map folds (past the first focus) the sheets of light simply
add, each triangle with its own area: the total stays exact, and texels at a fold collect
the tip of a very bright, very thin triangle. Where it does not fold, the error comes only
from replacing the curved map inside a cell by a linear one: second order in the cell size
(``refine`` Fourier-interpolates the surface that many times finer first).
"""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from optics.caustics.common import (CELL, blur_121, clip_cells, land, prepare, shadow_steps, sunlit, tank_cells, tank_clip,
                                    walled_tank)
from optics.light.fresnel import N_WATER
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_bool, check_choice, check_int
from wavephys.core.sampling import TriangleSpread, rasterize_triangles
from wavephys.core.spectral import central_gradient, spectral_gradient

__all__ = ["floor_irradiance_beam"]

_CELL = CELL  # (row = y, column = x) offsets of a cell's corners, counter-clockwise
_TRIANGLES = ((0, 1, 2), (0, 2, 3))


@jax.jit
def _slopes_spectral(eta, length):
    """First program: the FFT of η and its slopes (the XLA CPU note in wavephys.core.spectral)."""
    return jnp.stack(spectral_gradient(eta, length / eta.shape[-1]))


def _corners(field, a, b):
    """``field`` at the corner (row + a, column + b) of every cell (periodic)."""
    return jnp.roll(field, (-a, -b), (0, 1))


@partial(jax.jit, static_argnames=("m", "fresnel", "ground", "shadow", "coarse", "clip"))
def _vertices(eta, gx, gy, length, d, floor, n_water, m, fresnel, ground, shadow, coarse, clip=None):
    """Landed triangle vertices in floor texel units, ``(3, 2, n, n)`` (vertex, the two
    triangles of each cell) relative to each cell's integer texel ``origin``, and each
    triangle's flux E0·T·A₀ (m²), ``(2, n, n)``; ``eta``, ``gx``, ``gy`` on the (refined)
    tracing grid. ``clip`` (:func:`~optics.caustics.common.tank_clip`): a tank's extension, whose
    cells past its walls carry nothing and whose cells across a wall are cut at it."""
    n = eta.shape[-1]
    grid, floor_map = Grid(n, length), Grid(m, length)
    xv, yv = grid.mesh()
    floor_fn = (lambda x, y: Grid(coarse, length).sample(floor, x, y)) if ground else floor
    X, Y, T = land(xv, yv, eta, gx, gy, d, floor_fn, n_water, fresnel)
    T = T * sunlit(eta, grid, d, shadow)  # shadowed samples send nothing (0 steps: a high sun, no work)
    h = grid.dx
    # displacements keep a cell's corners adjacent across the periodic seam
    land_dx, land_dy = X - xv, Y - yv
    cross_dx, cross_dy = -eta * d[0] / d[2], -eta * d[1] / d[2]  # where each ray crossed z = 0
    p = floor_map.dx
    # each sample's floor texel coordinate ((2j + 1)m − n)/(2n), as an integer and a fraction
    # (float32 then keeps its digits for the coverage on any map size)
    num = (2 * jnp.arange(n, dtype=jnp.int32) + 1) * m - n
    base = num // (2 * n)
    frac = (num - base * 2 * n).astype(eta.dtype) / (2 * n)
    u0, v0 = frac[None, :], frac[:, None]
    origin = (jnp.broadcast_to(base[None, :], (n, n)), jnp.broadcast_to(base[:, None], (n, n)))
    u, v, cu, cv, t = [], [], [], [], []
    for a, b in _CELL:
        u.append(u0 + (b * h + _corners(land_dx, a, b)) / p)
        v.append(v0 + (a * h + _corners(land_dy, a, b)) / p)
        cu.append(b * h + _corners(cross_dx, a, b))
        cv.append(a * h + _corners(cross_dy, a, b))
        t.append(_corners(T, a, b))
    if clip is not None:
        u, v, cu, cv, t = (clip_cells(c, clip, n) for c in (u, v, cu, cv, t))
    tri_u, tri_v, flux = [], [], []
    for i, j, k in _TRIANGLES:
        tri_u.append(jnp.stack([u[i], u[j], u[k]]))
        tri_v.append(jnp.stack([v[i], v[j], v[k]]))
        source = 0.5 * jnp.abs((cu[j] - cu[i]) * (cv[k] - cv[i]) - (cu[k] - cu[i]) * (cv[j] - cv[i]))
        flux.append(source * (t[i] + t[j] + t[k]) / 3.0)
    finite = jnp.isfinite(eta).all()  # checked here, raised by the caller: no extra pass
    # the two triangles of a cell are one group (one window, one scatter)
    flux = jnp.stack(flux) * (tank_cells(clip, n) if clip is not None else 1.0)
    return jnp.stack(tri_u, 1), jnp.stack(tri_v, 1), flux, origin, finite


@partial(jax.jit, static_argnames=("blur",))
def _irradiance(deposited, texel, blur):
    out = deposited / (texel * texel)
    return blur_121(out) if blur else out


def floor_irradiance_beam(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                          n_water: float = N_WATER, fresnel: bool = True, refine: int = 3, blur: bool = False,
                          normals: str = "spectral", walls=None):
    """Floor irradiance E/E0 by exact beam rasterization (module doc), shape (m, m) on ``Grid(m, L)``.

    Parameters
    ----------
    eta, grid, depth, sun, resolution, n_water, fresnel
        As :func:`optics.caustics.floor_irradiance`.
    refine : int
        Trace the surface Fourier-interpolated ``refine`` times finer (1 to 32, n·refine at
        most 8192): smaller beams, error ∝ 1/refine² where the map does not fold. The
        default, 3, keeps the max-norm error within 0.67 % of the peak on random smooth
        surfaces whose shortest waves span ≥ 5 texels, down to 0.9 of the depth of the first
        fold (``python -m bench optics``; 1.17 % at 2.7 texels per wave, docs/physics.md §2.4);
        1 costs a ninth and errs up to 6.5 % there.
    blur : bool
        Apply Loviscach's 1-2-1 blur afterwards (not needed: the footprints are exact).
    normals : {"spectral", "central"}
        Surface slopes exact (FFT) or by central differences (second order, no transforms).
    walls : str or None
        The square is a tank with opaque vertical walls on these sides (``"all"``, ``"x"``, ``"y"``,
        or both side names of an axis; default None: periodic): the surface is even across a wall
        (the tank's cosine modes), light that reaches a wall is lost, and the floor by a wall lies
        in its shadow where the light arrives slanted (docs/physics.md §2.4). Traced on the even
        extension, 2n·refine at most 8192.

    Returns
    -------
    jax.Array (m, m)
        E/E0 at the cell centres of ``Grid(m, L)``.
    """
    light = prepare(eta, grid, depth, sun, resolution, n_water, fresnel, check_values=False)
    refine = check_int("refine", refine, lo=1, hi=32)
    if grid.n * refine > 8192:
        raise ValueError(f"refine {refine} traces {grid.n * refine}² cells: n·refine must be at most 8192")
    check_bool("blur", blur)
    check_choice("normals", normals, ("spectral", "central"))
    tank = walled_tank(light, walls)
    if tank is not None:
        if 2 * grid.n * refine > 8192:
            raise ValueError(f"refine {refine} traces the tank's even extension on {2 * grid.n * refine}² cells: "
                             f"2·n·refine must be at most 8192")
        return _tank_irradiance(tank, refine, fresnel, normals, blur)
    tri_u, tri_v, flux, origin = beam_triangles(light, refine, fresnel, normals)
    m = light.resolution
    return _irradiance(deposit_light(tri_u, tri_v, flux, (m, m), origin), float(grid.length) / m, blur)


def _tank_irradiance(tank, refine: int, fresnel: bool, normals: str, blur: bool):
    """The beam in a walled tank: the extension traced, only the tank's cells deposited, the tank's
    floor kept (the texel size is the tank's: the extension is twice as long with twice the texels)."""
    light = tank.light
    tri_u, tri_v, flux, origin = beam_triangles(light, refine, fresnel, normals, tank)
    big = light.resolution
    out = _irradiance(deposit_light(tri_u, tri_v, flux, (big, big), origin), float(light.grid.length) / big, False)
    out = out[:tank.m, :tank.m]
    return blur_121(out) if blur else out


def deposit_light(tri_u, tri_v, flux, shape, origin):
    """:func:`~wavephys.core.sampling.rasterize_triangles` of landed beams; light spread too wide to
    rasterize is refused naming the inputs that spread it."""
    try:
        return rasterize_triangles(tri_u, tri_v, flux, shape, origin)
    except TriangleSpread as exc:
        raise ValueError(f"eta, depth: the light of the surface's cells spreads too far on the floor to rasterize "
                         f"({exc}): the surface is too steep or too far above the floor for a map this fine; use "
                         "gentler or lower waves, a shallower floor, a coarser resolution, or a smaller refine") from exc


def beam_triangles(light, refine: int, fresnel: bool, normals: str = "spectral", tank=None):
    """The landed triangles of a checked :class:`~optics.caustics.common.Lighting` traced ``refine``
    times finer: ``(tri_u, tri_v, flux, origin)`` as :func:`wavephys.core.sampling.rasterize_triangles`
    takes them (vertices ``(3, 2, n', n')`` in floor texels relative to ``origin``, fluxes ``(2, n', n')``,
    m²). Refuses a non-finite surface by name. ``tank`` (:func:`~optics.caustics.common.walled_tank`,
    whose ``light`` this is): only the tank's cells carry light, cut at its walls."""
    grid = light.grid
    length = float(grid.length)
    fine = Grid(grid.n * refine, grid.length)
    if refine > 1 and not bool(jnp.isfinite(light.eta).all()):
        raise ValueError("eta must be finite everywhere; it contains NaN or inf")
    surface = grid.refine(light.eta, refine) if refine > 1 else light.eta
    gx, gy = (_slopes_spectral(surface, length) if normals == "spectral"
              else central_gradient(surface, float(fine.dx)))
    d = light.direction
    tri_u, tri_v, flux, origin, finite = _vertices(surface, gx, gy, length, jnp.asarray(d, jnp.float32), light.floor,
                                                   light.n_water, light.resolution, fresnel, light.ground,
                                                   shadow_steps(surface, fine, d), grid.n,
                                                   tank_clip(tank, grid.n * refine))
    if not bool(finite):
        raise ValueError("eta must be finite everywhere; it contains NaN or inf")
    return tri_u, tri_v, flux, origin
