r"""Sudden disturbances: stones dropped into the water (Loviscach 2003, §3).

A stone leaves a crater of depth D and radius R whose displaced water stands in a rim,
so the disturbance has zero net volume (a Ricker / "Mexican hat" profile):

.. math::

    \eta_0(r) = -D\left(1 - \frac{r^2}{2R^2}\right)e^{-r^2/(2R^2)},\qquad
    \hat\eta_0(k) = -D\,\pi R^4 k^2 e^{-k^2R^2/2}

(continuous Fourier transform). The fluid starts at rest (φ = 0): the Cauchy–Poisson
problem. Stones are added in Fourier space inside the simulation step, so they cost no
transform; the closed-form spectrum keeps them band-limited (R ≥ dx is required).
:class:`Stones` is a source of the simulation (``wavephys.simulation.Source``): an
*impulse*, added to the wave field at the instant of the step it is given to.
"""

from __future__ import annotations

from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_array, validate
from wavephys.core.specs import BOOL, GRID, Instance, model_grid
from wavephys.core.grid import Grid
from wavephys.core.pytree import register

__all__ = ["Stones", "stone_height", "stone_height_spectrum"]


@dataclass(frozen=True)
class Stones:
    """A batch of m stones dropped at the same instant (all fields shape ``(m,)``): a simulation source.

    Parameters
    ----------
    x, y : array_like
        Impact points, m, in grid coordinates (0 at the grid centre, |x|, |y| ≤ L/2).
    radius : array_like
        Crater radius R, m, ≥ the grid spacing of the grid it is dropped on.
    depth : array_like
        Crater depth D, m, ≥ 0 (the rim is highest at r = 2R, by D·e⁻² ≈ 0.135·D).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3.
    """

    x: jax.Array
    y: jax.Array
    radius: jax.Array
    depth: jax.Array

    def __init__(self, x, y, radius, depth):
        names = ("x", "y", "radius", "depth")
        limits = (dict(), dict(), dict(lo=0.0, lo_open=True), dict(lo=0.0))
        for name, v, lim in zip(names, (x, y, radius, depth), limits):
            check_array(name, v, **lim)
        vals = [np.atleast_1d(np.asarray(v, dtype=float)) if not _traced(v) else v
                for v in (x, y, radius, depth)]
        shapes = {np.shape(v) for v in vals}
        if len(shapes) != 1 or len(next(iter(shapes))) != 1:
            raise ValueError(f"x, y, radius, depth must be 1-D of one length, got shapes "
                             f"{dict(zip(names, (np.shape(v) for v in vals)))}")
        for name, v in zip(names, vals):
            object.__setattr__(self, name, jnp.asarray(v))

    @validate(grid=GRID)
    def check_on(self, grid: Grid) -> "Stones":
        """Raise ValueError if a stone lies outside ``grid``, is not resolved by it, or its
        crater (out to the rim at 2R) does not fit in the domain."""
        half = float(grid.length) / 2
        for name in ("x", "y"):
            v = np.asarray(getattr(self, name))
            if np.any(np.abs(v) > half):
                raise ValueError(f"stone {name} must lie in [-{half}, {half}] m (the grid), got {v}")
        r = np.asarray(self.radius)
        if np.any(r < float(grid.dx)):
            raise ValueError(f"stone radius must be ≥ the grid spacing {float(grid.dx):.4g} m (else the crater is "
                             f"not resolved), got {r}")
        if np.any(4 * r > 2 * half):
            raise ValueError(f"stone radius must be ≤ L/4 = {half / 2:.4g} m: the crater and its rim (out to 2R) "
                             f"must fit in the {2 * half:.4g} m domain, got {r}")
        return self

    # -- the simulation's source protocol -------------------------------------------
    def check(self, model) -> None:
        """Host-side check against a simulation model (before any work): with a ``tank``, every stone
        inside it."""
        self.check_on(model_grid(model))
        tank = getattr(model, "tank", None)
        if tank is not None and not _traced(self.x) and not _traced(self.y):
            outside = (np.abs(np.asarray(self.x)) > tank[0] / 2) | (np.abs(np.asarray(self.y)) > tank[1] / 2)
            if np.any(outside):
                raise ValueError(f"stones at x = {np.asarray(self.x)[outside]}, y = {np.asarray(self.y)[outside]} m "
                                 f"fall outside the tank ({tank[0]:g} × {tank[1]:g} m, centred): they would hit land")

    def impulse(self, model, ops, t):
        """(Δφ̂, Δχ̂) half spectra the stones add at ``t``: fluid at rest, χ̂ −= (ω/K)·η̂_stone.

        In a walled model the craters are evaluated in space (with their periodic images along
        axes without walls) and put on the model's cosine modes, which holds their mirror
        images in the walls (docs/physics.md §1.11)."""
        if getattr(model, "walls", ()):
            eta = stone_height(self, model.grid, walls=model.walls, lengths=getattr(model, "tank", None))
            eta = eta.astype(ops.inverse_height.dtype)
            return None, -ops.inverse_height * model.transform(eta)
        complex_dtype = jnp.result_type(ops.inverse_height.dtype, jnp.complex64)
        eta_hat = stone_height_spectrum(self, model.grid).astype(complex_dtype)
        return None, -ops.inverse_height * eta_hat


def _traced(v):
    return isinstance(v, jax.core.Tracer)


register(Stones, ("x", "y", "radius", "depth"))


@validate(stones=Instance(Stones, "wavephys.Stones"), grid=GRID, real=BOOL)
def stone_height_spectrum(stones: Stones, grid: Grid, real: bool = True):
    """DFT of the stones' summed crater heights, m (DFT convention: sum over points).

    ``real=True`` gives the ``rfft2`` half spectrum ``(n, n//2 + 1)``.

    Parameters
    ----------
    stones : Stones
        The craters (positions, radii R and depths D, m); R ≥ the grid spacing is needed for a
        band-limited spectrum.
    grid : Grid
    real : bool
        True: the ``rfft2`` half spectrum; False: the full ``fft2`` spectrum ``(n, n)``.

    Returns
    -------
    jax.Array (n, n//2 + 1) or (n, n), complex
        η̂₀ = −D πR⁴k² e^{−k²R²/2}/dx² per stone, shifted to its impact point and summed, m
        (DFT convention).

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3.
    """
    k2 = grid.wavenumber_magnitude(real) ** 2
    r = stones.radius[:, None, None]
    amp = -stones.depth[:, None, None] * jnp.pi * r**4 * k2 * jnp.exp(-0.5 * k2 * r * r) / (grid.dx * grid.dx)
    return jnp.sum(amp * grid.source_phase(stones.x, stones.y, real), axis=0)


@validate(stones=Instance(Stones, "wavephys.Stones"), grid=GRID)
def stone_height(stones: Stones, grid: Grid, walls=None, lengths=None):
    """The stones' crater heights in space, m, shape ``(n, n)``.

    Parameters
    ----------
    stones : Stones
        The craters (positions, radii R and depths D, m); R ≥ the grid spacing is needed for a
        band-limited spectrum.
    grid : Grid
    walls : None or str or sequence of str
        None: images ignored. Otherwise the walled sides of the domain
        (:func:`wavephys.physics.walls.check_walls`): each crater's mirror images in the walls
        of walled axes (x → ±L − x; the part of a crater beyond a wall folds back in) and its
        periodic images (±L) along axes without walls are added.
    lengths : (float, float), optional
        (Lx, Ly), m: the sides of the walled domain, centred on the grid (a model's ``tank``); default
        the grid's side on both axes.

    Returns
    -------
    jax.Array (n, n)
        η₀ = −D(1 − r²/(2R²))e^{−r²/(2R²)} summed over the stones, m.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3.
    """
    if lengths is not None:
        from wavephys.core.inputs import check_array

        check_array("lengths", lengths, ndim=1, shape_tail=(2,), lo=0.0, lo_open=True)
        lengths = tuple(float(v) for v in np.asarray(lengths, np.float64))
    x, y = grid.mesh()
    copies_x, copies_y = [(1.0, 0.0)], [(1.0, 0.0)]  # (sign, offset): the copy sits at sign·x + offset
    if walls is not None:
        from wavephys.physics.walls import wall_axes

        sides = (grid.length, grid.length) if lengths is None else lengths
        for axis_walled, copies, length in zip(wall_axes(walls), (copies_x, copies_y), sides):
            copies += [(-1.0, -length), (-1.0, length)] if axis_walled else [(1.0, -length), (1.0, length)]
    total = 0.0
    for ax, bx in copies_x:
        for ay, by in copies_y:
            px, py = ax * stones.x + bx, ay * stones.y + by
            rr = (x[None] - px[:, None, None]) ** 2 + (y[None] - py[:, None, None]) ** 2
            q = rr / (2.0 * stones.radius[:, None, None] ** 2)
            total = total + jnp.sum(-stones.depth[:, None, None] * (1.0 - q) * jnp.exp(-q), axis=0)
    return total
