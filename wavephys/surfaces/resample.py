r"""Displaced surfaces back to heights on a grid: inverting the horizontal map.

A choppy or Gerstner surface is given in rest coordinates: the point that rests at grid
point x₀ sits at (x₀ + Δ(x₀), z(x₀)). Everything else in the library (caustics, textures,
the renderer, the harness) consumes heights η(x) over fixed grid points, so for each grid
point x we solve x₀ + Δ(x₀) = x and take η(x) = z(x₀) (docs/physics.md §1.9).

:func:`resample_heights` solves it by Newton's method on periodic bilinear interpolants of
Δ, its spectral derivatives and z, after an optional exact Fourier refinement of the fields
by ``refine`` (band-limited fields: no error added by the refinement). The interpolation is
the only approximation; its error against the converged fine solution (``refine=8``) is
measured in the tests and ``python -m bench surfaces`` and falls as refine⁻². A folded map
(J ≤ 0 somewhere) has no single-valued height and is refused.
"""

from __future__ import annotations

import functools

import jax
import jax.numpy as jnp

from wavephys.core import sampling, spectral
from wavephys.core.grid import Grid
from wavephys.core.inputs import Array, Instance, Int, validate
from wavephys.core.spectral import spectral_gradient

__all__ = ["resample_heights", "map_jacobian"]

_GRID = Instance(Grid, "wavephys.Grid")
_DISP = Array(shape=lambda a: (2, a["grid"].n, a["grid"].n), ndim=3)
_Z = Array(shape=lambda a: (a["grid"].n, a["grid"].n), ndim=2)


def _derivatives(disp, dx):
    (dxx, dxy), (dyx, dyy) = (spectral_gradient(disp[0], dx), spectral_gradient(disp[1], dx))
    return dxx, dxy, dyx, dyy


@validate(grid=_GRID, displacement=_DISP)
def map_jacobian(displacement, grid: Grid):
    """J = det ∂(x₀ + Δ)/∂x₀ (n, n) of a periodic horizontal displacement Δ (2, n, n), m, on ``grid``.

    Parameters
    ----------
    displacement : array_like (2, n, n)
        Δ = (Δx, Δy), m, of the surface point resting at each grid point; periodic.
    grid : Grid

    Returns
    -------
    jax.Array (n, n)
        J, dimensionless, from spectral derivatives (≤ 0 where the map folds).
    """
    dxx, dxy, dyx, dyy = _derivatives(jnp.asarray(displacement), grid.dx)
    return (1 + dxx) * (1 + dyy) - dxy * dyx


@validate(grid=_GRID, displacement=_DISP, heights=_Z, refine=Int(lo=1, hi=16), iterations=Int(lo=1, hi=100))
def resample_heights(displacement, heights, grid: Grid, *, refine: int = 2, iterations: int = 6):
    """Heights η (n, n), m, over ``grid``'s points of a surface displaced horizontally.

    Parameters
    ----------
    displacement : array_like (2, n, n)
        Δ = (Δx, Δy), m, of the surface point resting at each grid point
        (e.g. :func:`wavephys.choppy.displacement`); periodic.
    heights : array_like (n, n)
        z of the same points, m.
    grid : Grid
    refine : int
        Fourier refinement before interpolation (1–16): 2 (default) keeps the interpolation
        error under 1 % of the height range for fold choppiness up to 0.9 of the folding
        value (measured, tests), 1 is cheapest.
    iterations : int
        Newton steps, 1–100 (6 converges the map to float32 rounding unless J is near 0).

    Returns
    -------
    jax.Array (n, n)
        η at ``grid``'s points, m.

    Raises
    ------
    ValueError
        If the map folds (J ≤ 0 anywhere): lower the choppiness.
    """
    d = jnp.asarray(displacement)
    z = jnp.asarray(heights)
    dtype = jnp.result_type(d.dtype, z.dtype, jnp.float32)
    h, jmin = _resample(d.astype(dtype), z.astype(dtype), grid, refine, iterations)
    if float(jmin) <= 0:
        raise ValueError(f"displacement folds the surface (min Jacobian {float(jmin):.3g} ≤ 0): heights are "
                         "multi-valued; lower the choppiness or steepness")
    return h


@functools.partial(jax.jit, static_argnums=(3, 4))
def _resample(d, z, grid, refine, iterations):
    """(heights, min J): the compiled body of :func:`resample_heights`."""
    fine = Grid(grid.n * refine, grid.length)
    if refine > 1:
        d = jnp.stack([spectral.fourier_refine(d[0], refine), spectral.fourier_refine(d[1], refine)])
        z = spectral.fourier_refine(z, refine)
    dxx, dxy, dyx, dyy = _derivatives(d, fine.dx)
    jmin = jnp.min((1 + dxx) * (1 + dyy) - dxy * dyx)
    stack = jnp.stack([d[0], d[1], dxx, dxy, dyx, dyy, z], axis=-1)
    x, y = grid.mesh()
    x, y = x.astype(d.dtype), y.astype(d.dtype)
    u0 = lambda px, py: (sampling.texel_coordinates(px, fine.length, fine.n),
                         sampling.texel_coordinates(py, fine.length, fine.n))
    sample = lambda f, px, py: sampling.bilinear(f, *u0(px, py), "wrap")
    s = sample(stack, x, y)
    x0, y0 = x - s[..., 0], y - s[..., 1]
    def newton(_, p):
        x0, y0 = p
        s = sample(stack, x0, y0)
        rx, ry = x0 + s[..., 0] - x, y0 + s[..., 1] - y
        a, b, c, e = 1 + s[..., 2], s[..., 3], s[..., 4], 1 + s[..., 5]
        det = jnp.maximum(a * e - b * c, 1e-6)
        return x0 - (e * rx - b * ry) / det, y0 - (-c * rx + a * ry) / det

    x0, y0 = jax.lax.fori_loop(0, iterations, newton, (x0, y0))
    return sample(stack[..., 6], x0, y0), jmin
