"""Beam tracing with area ratios (Loviscach 2003; Watt 1990): every surface cell is a beam.

The four corner rays of each cell (between four adjacent samples) are refracted exactly
and landed on the floor; the cell's flux E0·T·A₀ (A₀: the area where its rays cross
z = 0) is spread over its bilinear floor footprint by ``samples``² sub-beams deposited
cloud-in-cell. Flux is conserved exactly; irradiance = source area / projected area;
second order in the mesh spacing where the map has no fold. With ``samples=1`` each
sample's ray carries the flux of its dual cell.
"""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp

from optics.caustics.common import blur_121, land, prepare, shadow_steps, sunlit
from optics.light.fresnel import N_WATER
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_bool, check_choice, check_int
from wavephys.core.spectral import central_gradient

__all__ = ["floor_irradiance_beam"]

_CORNERS = ((0, 0), (0, 1), (1, 0), (1, 1))  # (row = y, column = x) offsets


def _cell_corners(field, a, b):
    """``field`` at the corner (row + a, col + b) of every cell (periodic)."""
    return jnp.roll(field, (-a, -b), (0, 1))


@jax.jit
def _slope_spectra(eta, length):
    """First program: the FFT of η and its slope spectra (the XLA CPU note in wavephys.core.spectral)."""
    n = eta.shape[-1]
    ky, kx = Grid(n, length).wavenumbers(real=True)
    spec = jnp.fft.rfft2(eta)
    return jnp.stack([1j * kx * spec, 1j * ky * spec])


def _sub_beams(grid, xv, yv, eta, X, Y, T, d, samples, vertical):
    """Sub-beam positions on the floor and their flux, ``samples``² per cell."""
    h = grid.dx
    # work with displacements so that corners across the periodic seam stay adjacent
    disp = [X - xv, Y - yv, -eta * d[0] / d[2], -eta * d[1] / d[2]]  # floor, and z = 0 crossing
    q = (jnp.arange(samples) + 0.5) / samples
    su, sv = (g.ravel()[:, None, None] for g in jnp.meshgrid(q, q))
    weights = [(1 - su) * (1 - sv), su * (1 - sv), (1 - su) * sv, su * sv]
    bilinear = lambda F: sum(w * _cell_corners(F, a, b) for w, (a, b) in zip(weights, _CORNERS))
    px, py = xv + su * h + bilinear(disp[0]), yv + sv * h + bilinear(disp[1])
    # flux of a cell: E0 × the area of its four rays' z = 0 crossings × transmittance
    if vertical:  # the crossings are the samples themselves: area h² exactly
        area = h * h
    else:
        cx = [xv + b * h + _cell_corners(disp[2], a, b) for a, b in _CORNERS]
        cy = [yv + a * h + _cell_corners(disp[3], a, b) for a, b in _CORNERS]
        area = 0.5 * jnp.abs((cx[3] - cx[0]) * (cy[2] - cy[1]) - (cx[2] - cx[1]) * (cy[3] - cy[0]))
    t_cell = 0.25 * sum(_cell_corners(T, a, b) for a, b in _CORNERS)
    return px, py, jnp.broadcast_to(area * t_cell / (samples * samples), px.shape)


@partial(jax.jit, static_argnames=("m", "samples", "blur", "fresnel", "ground", "vertical", "shadow"))
def _beam(slope_spectra, eta, length, d, floor, n_water, m, samples, blur, fresnel, ground, vertical, shadow):
    n = eta.shape[-1]
    grid, floor_map = Grid(n, length), Grid(m, length)
    h = grid.dx
    if slope_spectra is None:
        gx, gy = central_gradient(eta, h)
    else:
        gx, gy = jnp.fft.irfft2(slope_spectra, s=(n, n))
    xv, yv = grid.mesh()
    floor_fn = (lambda x, y: grid.sample(floor, x, y)) if ground else floor
    X, Y, T = land(xv, yv, eta, gx, gy, d, floor_fn, n_water, fresnel)
    T = T * sunlit(eta, grid, d, shadow)  # shadowed samples send nothing (0 steps: high sun, no work)
    finite = jnp.isfinite(eta).all()  # checked here, raised by the caller: no extra pass
    if samples == 1:
        # one ray per sample carrying the flux of its dual cell: E0·T·(x0-area), with the
        # x0-area h²·det(∂x0/∂x) = h²·(1 − gx·dx/dz − gy·dy/dz)
        area = h * h if vertical else h * h * jnp.abs(1.0 - (gx * d[0] + gy * d[1]) / d[2])
        px, py, flux = X, Y, area * T
    else:
        px, py, flux = _sub_beams(grid, xv, yv, eta, X, Y, T, d, samples, vertical)
    out = floor_map.deposit(px, py, flux) / (floor_map.dx * floor_map.dx)
    return (blur_121(out) if blur else out), finite


def floor_irradiance_beam(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                          n_water: float = N_WATER, fresnel: bool = True, samples: int = 2, blur: bool = False,
                          normals: str = "spectral"):
    """Floor irradiance E/E0 by beam tracing (module doc), shape (m, m) on ``Grid(m, L)``.

    Parameters
    ----------
    eta, grid, depth, sun, resolution, n_water, fresnel
        As :func:`optics.caustics.floor_irradiance`.
    samples : int
        Sub-beams per cell edge (samples² per cell), ≥ 1.
    blur : bool
        Apply the 1-2-1 blur.
    normals : {"spectral", "central"}
        Surface slopes exact (FFT) or by central differences (second order, no transforms).
    """
    light = prepare(eta, grid, depth, sun, resolution, n_water, fresnel, check_values=False)
    samples = check_int("samples", samples, lo=1)
    check_bool("blur", blur)
    check_choice("normals", normals, ("spectral", "central"))
    d = light.direction
    vertical = bool(d[0] == 0 and d[1] == 0)
    length = float(grid.length)
    spectra = None if normals == "central" else _slope_spectra(light.eta, length)
    shadow = shadow_steps(light.eta, grid, d)
    out, finite = _beam(spectra, light.eta, length, jnp.asarray(d, jnp.float32), light.floor, light.n_water,
                        light.resolution, samples, blur, fresnel, light.ground, vertical, shadow)
    if not bool(finite):
        raise ValueError("eta must be finite everywhere; it contains NaN or inf")
    return out
