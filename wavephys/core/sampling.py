"""Bilinear sampling and its adjoint, cloud-in-cell deposition: the one implementation.

Both work in *texel coordinates*: u = j is the centre of column j, v = i the centre of
row i, so a field of ``n`` samples over a square of side L with the library's convention
(sample centres at −L/2 + (j + ½)·L/n, ``docs/physics.md`` §0) has
u = (x + L/2)/(L/n) − ½ (:func:`texel_coordinates`). Edges either wrap (periodic fields:
the simulation, caustics) or clamp to the border texel (finite textures: the renderer's
ground). NumPy in → NumPy out (float64, for the reference tracer and measurements); JAX
in → JAX out (traceable).
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

__internal__ = True  # tooling for the library's own modules (users call the Grid's methods)
__all__ = ["texel_coordinates", "bilinear", "cloud_in_cell", "array_module"]

MODES = ("wrap", "clamp")


def array_module(*arrays):
    """``jax.numpy`` if any argument is a JAX array or tracer, else ``numpy``."""
    return jnp if any(isinstance(a, (jax.Array, jax.core.Tracer)) for a in arrays) else np


def texel_coordinates(x, length, n: int):
    """Continuous texel index of coordinate ``x`` (m) on ``n`` cell-centred samples over
    [−L/2, L/2): (x + L/2)/(L/n) − ½ (0 at the first sample's centre)."""
    return (x + 0.5 * length) * (n / length) - 0.5


def _corners(xp, u, v, shape, mode):
    rows, cols = shape
    i0f, j0f = xp.floor(v), xp.floor(u)
    fv, fu = v - i0f, u - j0f
    i0, j0 = i0f.astype(xp.int32), j0f.astype(xp.int32)
    if mode == "wrap":
        i0, j0 = i0 % rows, j0 % cols
        i1, j1 = (i0 + 1) % rows, (j0 + 1) % cols
    else:
        i1, j1 = xp.clip(i0 + 1, 0, rows - 1), xp.clip(j0 + 1, 0, cols - 1)
        i0, j0 = xp.clip(i0, 0, rows - 1), xp.clip(j0, 0, cols - 1)
    return (i0, i1, j0, j1), (fu, fv)


def bilinear(field, u, v, mode: str = "wrap"):
    """Bilinear interpolation of ``field`` (rows, cols[, channels]) at texel coordinates (u, v).

    ``u`` runs along columns (x), ``v`` along rows (y); any broadcastable shapes. Channels
    (a trailing axis) are interpolated together. ``mode`` "wrap" (periodic) or "clamp".
    """
    xp = array_module(field, u, v)
    f = xp.asarray(field)
    (i0, i1, j0, j1), (fu, fv) = _corners(xp, xp.asarray(u), xp.asarray(v), f.shape[:2], mode)
    if f.ndim == 3:
        fu, fv = fu[..., None], fv[..., None]
    return ((f[i0, j0] * (1 - fu) + f[i0, j1] * fu) * (1 - fv)
            + (f[i1, j0] * (1 - fu) + f[i1, j1] * fu) * fv)


def cloud_in_cell(u, v, values, shape: tuple[int, int], mode: str = "wrap"):
    """Deposit ``values`` at texel coordinates (u, v) onto a ``shape`` map (sums, not densities).

    The adjoint of :func:`bilinear`: each value is split over the four nearest texels with
    the bilinear weights, so the map's total equals the total of ``values`` exactly.
    """
    xp = array_module(u, v, values)
    u, v, w = (xp.ravel(xp.asarray(a)) for a in (u, v, values))
    (i0, i1, j0, j1), (fu, fv) = _corners(xp, u, v, shape, mode)
    cols = shape[1]
    index = xp.concatenate([i0 * cols + j0, i0 * cols + j1, i1 * cols + j0, i1 * cols + j1])
    weight = xp.concatenate([w * (1 - fu) * (1 - fv), w * fu * (1 - fv), w * (1 - fu) * fv, w * fu * fv])
    size = shape[0] * shape[1]
    if xp is np:
        return np.bincount(index, weights=weight, minlength=size).reshape(shape)
    total = jnp.zeros(size, weight.dtype).at[index].add(weight, mode="promise_in_bounds")  # wrapped or clamped above
    return total.reshape(shape)
