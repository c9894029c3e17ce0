"""Caustics by photon splatting (Baboud & Décoret 2006): rays through the exact surface.

Photons cross z = 0 at jittered points of a light-view texture (each carrying E0 × its
share of the area), meet the Fourier-interpolated surface at their first hit, are
refracted exactly and deposited cloud-in-cell on the floor map; an edge-preserving
(bilateral) filter then smooths the histogram. Noise falls as 1/sqrt(photons per texel).

The first hit: while the sun stands higher than the steepest slope, the fixed point
x = x0 + η(x)·d_h/d_z has one solution and four iterations find it; below that angle a
ray can meet the surface several times, and each photon marches down its ray from above
the highest crest in half-cell steps to the first crossing, then bisects it (a photon that
would land on a facet hidden from the sun lands on the crest that hides it instead).
"""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp

from optics.caustics.common import bilateral_filter, land, prepare, shadow_steps, surface_fields
from optics.light.fresnel import N_WATER
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_int

__all__ = ["floor_irradiance_photon"]


@partial(jax.jit, static_argnames=("m", "oversample", "fresnel", "ground", "march"))
def _rays(eta, length, d, floor, n_water, x0, y0, m, oversample, fresnel, ground, march):
    """Rays crossing z = 0 at (x0, y0), each with flux E0·(L²/count), through the exact
    (Fourier-interpolated) surface; deposited cloud-in-cell on an m × m floor map."""
    n = eta.shape[-1]
    grid, fine, floor_map = Grid(n, length), Grid(n * oversample, length), Grid(m, length)
    fields = surface_fields(eta, grid, oversample)
    surf = [lambda x, y, f=f: fine.sample(f, x, y) for f in fields]
    xs, ys = _first_hit(surf[0], fields[0], x0, y0, d, fine, march)
    floor_fn = (lambda x, y: grid.sample(floor, x, y)) if ground else floor
    X, Y, T = land(xs, ys, *(f(xs, ys) for f in surf), d, floor_fn, n_water, fresnel)
    flux = T * (length * length / x0.size)
    return floor_map.deposit(X, Y, flux) / (floor_map.dx * floor_map.dx)


def _first_hit(height, eta, x0, y0, d, fine: Grid, march: int):
    """Where each ray through (x0, y0, 0) along ``d`` first meets the surface (module doc)."""
    ax, ay = d[0] / d[2], d[1] / d[2]  # horizontal travel per metre of height
    if march == 0:  # the sun above every slope: one crossing, the fixed point finds it
        xs, ys = x0, y0
        for _ in range(4):
            e = height(xs, ys)
            xs, ys = x0 + e * ax, y0 + e * ay
        return xs, ys
    top = jnp.max(eta)
    ds = 0.5 * fine.dx / jnp.hypot(ax, ay)  # height step of a half-cell horizontal step
    above = lambda z: z - height(x0 + z * ax, y0 + z * ay)  # ray height over the surface at ray height z

    def step(i, state):
        lo, hi, found = state
        z = top - i * ds
        hit = (~found) & (above(z) <= 0)
        return jnp.where(hit, z, lo), jnp.where(hit, z + ds, hi), found | hit

    lo, hi, found = jax.lax.fori_loop(0, march, step, (jnp.full_like(x0, top), jnp.full_like(x0, top + ds),
                                                      jnp.zeros(x0.shape, bool)))
    for _ in range(12):  # bisect the first crossing between z = lo (below) and hi (above)
        mid = 0.5 * (lo + hi)
        below = above(mid) <= 0
        lo, hi = jnp.where(below, mid, lo), jnp.where(below, hi, mid)
    z = jnp.where(found, 0.5 * (lo + hi), height(x0, y0))
    return x0 + z * ax, y0 + z * ay


def floor_irradiance_photon(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                            n_water: float = N_WATER, fresnel: bool = True, photons_per_texel: int = 1,
                            filter_radius: int = 2, seed: int = 0):
    """Floor irradiance E/E0 by photon splatting (shot noise per texel).

    Parameters
    ----------
    eta, grid, depth, sun, resolution, n_water, fresnel
        As :func:`optics.caustics.floor_irradiance` (heights in m on ``grid``; a floor depth
        in m or a ground height field; the direction towards the sun; the map's side).
    photons_per_texel : int
        ≥ 1: photons per floor texel (the light-view texture is m·sqrt(p) square).
    filter_radius : int
        ≥ 0: bilateral filter radius in texels (0: the raw histogram).
    seed : int
        Jitter seed, ≥ 0.

    Returns
    -------
    jax.Array (m, m)
    """
    light = prepare(eta, grid, depth, sun, resolution, n_water, fresnel)
    p = check_int("photons_per_texel", photons_per_texel, lo=1)
    r = check_int("filter_radius", filter_radius, lo=0)
    seed = check_int("seed", seed, lo=0)
    length = float(grid.length)
    side = int(round(light.resolution * p ** 0.5))
    x0, y0 = Grid(side, length).mesh()
    jitter = jax.random.uniform(jax.random.PRNGKey(seed), (2, side, side), minval=-0.5, maxval=0.5)
    x0, y0 = x0 + jitter[0] * length / side, y0 + jitter[1] * length / side
    march = 2 * shadow_steps(light.eta, grid, light.direction)  # half-cell steps of the 2× refined surface
    out = _rays(light.eta, length, jnp.asarray(light.direction, jnp.float32), light.floor, light.n_water, x0, y0,
                light.resolution, 2, fresnel, light.ground, march)
    return bilateral_filter(out, r) if r else out
