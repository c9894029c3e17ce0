"""Schneider & Westermann's (2001) transmissive Blinn–Phong caustics: a shading trick.

⟨H_t, N⟩^tr with H_t = normalize(L − V/n), V pointing down to the floor point below,
normalized to 1 for flat water. It is not a flux: it cannot focus light (measured in
``python -m bench optics``).
"""

from __future__ import annotations

import jax.numpy as jnp

from optics.caustics.common import prepare, surface_fields
from optics.light.directions import normalize
from optics.light.fresnel import N_WATER
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_scalar

__all__ = ["floor_irradiance_blinn_phong"]


def floor_irradiance_blinn_phong(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                                 n_water: float = N_WATER, exponent: float = 20.0):
    """The transmissive Blinn–Phong term k_t⟨H_t, N⟩^tr, normalized to 1 under flat water.

    A shading trick, not a flux: it cannot focus light. Takes a flat floor ``depth`` only (it
    ignores geometry) and a ``resolution`` that is a multiple of n (the surface is
    Fourier-refined to it).

    Parameters
    ----------
    eta, grid, depth, sun, resolution, n_water
        As :func:`optics.caustics.floor_irradiance`.
    exponent : float
        tr, > 0.

    Returns
    -------
    jax.Array (m, m)

    References
    ----------
    J. Schneider and R. Westermann, "Towards real-time visual simulation of water surfaces",
    VMV 2001.
    """
    light = prepare(eta, grid, depth, sun, resolution, n_water, True)
    check_scalar("exponent", exponent, lo=0.0, lo_open=True)
    if light.ground:
        raise ValueError("blinn_phong takes a flat floor depth (it ignores geometry), not a ground height field")
    m, n = light.resolution, grid.n
    if m % n:
        raise ValueError(f"blinn_phong needs resolution a multiple of n={n}, got {m}")
    _, gx, gy = surface_fields(light.eta, grid, m // n)
    normal = normalize(jnp.stack([-gx, -gy, jnp.ones_like(gx)], axis=-1))
    view = jnp.array([0.0, 0.0, -1.0])  # towards the floor point below
    ht = normalize(jnp.asarray(-light.direction, jnp.float32) - view / light.n_water)
    flat = ht[2] ** exponent
    return jnp.maximum(jnp.sum(ht * normal, axis=-1), 0.0) ** exponent / flat
