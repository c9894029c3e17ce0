"""Caustics by rays through the exact surface: photon splatting (Baboud & Décoret 2006) and the
brute-force reference.

Both shoot rays that cross z = 0 at given points (each carrying E0 × its share of the
area), find where they meet the Fourier-interpolated surface, refract them exactly and
deposit them cloud-in-cell on the floor map.

* :func:`floor_irradiance_photon` — one photon per jittered texel of a light-view
  texture, a 2-D histogram on the floor, then an edge-preserving (bilateral) filter.
  Noise falls as 1/sqrt(photons per texel).
* :func:`floor_irradiance_reference` — one ray per cell of a surface ``oversample`` times
  finer: used to measure the others.
"""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp

from optics.caustics.common import bilateral_filter, land, prepare, surface_fields
from optics.light.fresnel import N_WATER
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_int

__all__ = ["floor_irradiance_photon", "floor_irradiance_reference"]


@partial(jax.jit, static_argnames=("m", "oversample", "fresnel", "ground"))
def _rays(eta, length, d, floor, n_water, x0, y0, m, oversample, fresnel, ground):
    """Rays crossing z = 0 at (x0, y0), each with flux E0·(L²/count), through the exact
    (Fourier-interpolated) surface; deposited cloud-in-cell on an m × m floor map."""
    n = eta.shape[-1]
    grid, fine, floor_map = Grid(n, length), Grid(n * oversample, length), Grid(m, length)
    surf = [lambda x, y, f=f: fine.sample(f, x, y) for f in surface_fields(eta, grid, oversample)]
    xs, ys = x0, y0
    for _ in range(4):  # surface hit: the ray through (x0, y0, 0) meets z = η(x, y)
        e = surf[0](xs, ys)
        xs, ys = x0 + e * d[0] / d[2], y0 + e * d[1] / d[2]
    floor_fn = (lambda x, y: grid.sample(floor, x, y)) if ground else floor
    X, Y, T = land(xs, ys, *(f(xs, ys) for f in surf), d, floor_fn, n_water, fresnel)
    flux = T * (length * length / x0.size)
    return floor_map.deposit(X, Y, flux) / (floor_map.dx * floor_map.dx)


def floor_irradiance_photon(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                            n_water: float = N_WATER, fresnel: bool = True, photons_per_texel: int = 1,
                            filter_radius: int = 2, seed: int = 0):
    """Floor irradiance E/E0 by photon splatting, shape (m, m).

    ``photons_per_texel`` (≥ 1): photons per floor texel (the light-view texture is
    m·sqrt(p) square); ``filter_radius`` (≥ 0): bilateral filter radius in texels (0: the
    raw histogram); ``seed``: jitter seed. Other parameters as
    :func:`optics.caustics.floor_irradiance`.
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
    out = _rays(light.eta, length, jnp.asarray(light.direction, jnp.float32), light.floor, light.n_water, x0, y0,
                light.resolution, 2, fresnel, light.ground)
    return bilateral_filter(out, r) if r else out


def floor_irradiance_reference(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                               n_water: float = N_WATER, fresnel: bool = True, oversample: int = 4):
    """Floor irradiance E/E0 by brute force: one exact ray per cell of the surface refined
    ``oversample`` times (≥ 1; rays per cell = oversample²), shape (m, m)."""
    light = prepare(eta, grid, depth, sun, resolution, n_water, fresnel)
    o = check_int("oversample", oversample, lo=1)
    length = float(grid.length)
    x0, y0 = Grid(grid.n * o, length).mesh()
    return _rays(light.eta, length, jnp.asarray(light.direction, jnp.float32), light.floor, light.n_water, x0, y0,
                 light.resolution, o, fresnel, light.ground)
