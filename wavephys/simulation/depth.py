"""Linear waves over a varying floor: two steppers, one family (docs/physics.md §1.12).

``"levels"`` (:func:`step_levels`): the spectral step run at a few depths h_j and blended per
place by the local depth, as Jeschke & Wojtan (2023) blend their surface waves. Exact where the
floor is at a level (a constant-depth floor at one level is today's step), dispersive at every
kh, fast (one forward and J inverse transforms). It neglects what a depth *change* does beyond
the local dispersion: nothing is reflected by a slope, and its amplitude follows no energy flux
(measured: docs/physics.md §1.12).

``"shallow"`` (:func:`step_shallow`): the linear shallow-water equations η_t = −∇·(h∇φ),
φ_t = −gη on the grid (fluxes at cell faces, symplectic Euler, as many sub-steps as stability
needs). It conserves energy flux across slopes (Green's law), reflects from them and from the
shoreline (Lamb's beach), and takes dry floors (h = 0: no flux) — but it is not dispersive:
ω = k√(gh) (plus the grid's own error), right only for kh ≲ 0.3.

Both step a :class:`DepthState` (η and the surface potential φ, m and m²/s) on a model's grid,
walls and margin (:class:`~wavephys.simulation.Model`); the floor is a :class:`Floor`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, replace
from typing import Optional

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar
from wavephys.core.methods import Methods
from wavephys.core.pytree import register
from wavephys.physics.depth import depth_levels, depth_weights
from wavephys.physics.dispersion import angular_frequency, surface_operator
from wavephys.physics.ring_waves import rotate_pair
from wavephys.simulation.model import Model, operators

__all__ = ["Floor", "DepthState", "depth_state", "step_levels", "step_shallow", "DEPTH_METHODS", "run_depth",
           "shallow_substeps"]


@dataclass(frozen=True)
class Floor:
    """A floor of varying depth under a model's grid.

    Parameters
    ----------
    depth : array_like (n, n)
        Still-water depth h(x) at each sample, m, finite, ≥ 0 (0: dry, ``"shallow"`` only).
    levels : int
        Depth levels of the ``"levels"`` method, 1 … 16 (default 4; geometric between min and max h).

    Examples
    --------
    >>> import numpy as np
    >>> floor = Floor(np.full((32, 32), 0.5))
    """

    depth: np.ndarray
    levels: int = 4

    def __post_init__(self):
        check_array("depth", self.depth, ndim=2, lo=0.0)
        object.__setattr__(self, "depth", np.asarray(self.depth, np.float64))
        object.__setattr__(self, "levels", check_int("levels", self.levels, lo=1, hi=16))

    def check(self, model: Model) -> None:
        """The floor fits the model's grid (ValueError otherwise).

        Parameters
        ----------
        model : Model
        """
        check_instance("model", model, Model, "wavephys.simulation.Model")
        n = model.grid.n
        if self.depth.shape != (n, n):
            raise ValueError(f"floor depth must have the grid's shape {(n, n)}, got {self.depth.shape}")

    def __hash__(self):
        return hash((self.depth.tobytes(), self.depth.shape, self.levels))

    def __eq__(self, other):
        return (isinstance(other, Floor) and self.levels == other.levels and self.depth.shape == other.depth.shape
                and np.array_equal(self.depth, other.depth))


@dataclass(frozen=True)
class DepthState:
    """The wave field over a varying floor (make one with :func:`depth_state`).

    Parameters
    ----------
    fields : array (2, n, n)
        Height η, m, and surface potential φ, m²/s, stacked, finite.
    time : float
        s, finite.
    """

    fields: jax.Array
    time: jax.Array

    def __post_init__(self):
        if isinstance(self.fields, jax.core.Tracer) or isinstance(self.time, jax.core.Tracer):
            return
        check_array("fields", self.fields, ndim=3)
        shape = np.shape(self.fields)
        if shape[0] != 2 or shape[1] != shape[2]:
            raise ValueError(f"fields must stack (eta, phi) of a square grid, shape (2, n, n), got {shape}")
        check_scalar("time", self.time)

    @property
    def eta(self):
        """Height η, m."""
        return self.fields[0]

    @property
    def phi(self):
        """Surface potential φ, m²/s."""
        return self.fields[1]


register(DepthState, ("fields", "time"))


def depth_state(model: Model, eta, phi=None, time: float = 0.0) -> DepthState:
    """A :class:`DepthState` from a height (and potential; default the fluid at rest).

    Parameters
    ----------
    model : Model
    eta : array_like (n, n)
        Height, m.
    phi : array_like (n, n), optional
        Surface potential, m²/s (default 0).
    time : float
        s.

    Returns
    -------
    DepthState
    """
    check_instance("model", model, Model, "wavephys.simulation.Model")
    n = model.grid.n
    check_array("eta", eta, ndim=2, shape_tail=(n, n))
    phi = np.zeros((n, n)) if phi is None else phi
    check_array("phi", phi, ndim=2, shape_tail=(n, n))
    check_scalar("time", time)
    return DepthState(jnp.stack([jnp.asarray(eta, model.dtype), jnp.asarray(phi, model.dtype)]),
                      jnp.asarray(time, model.dtype))


# -- levels: the spectral step at a few depths, blended -----------------------------------------
@functools.lru_cache(maxsize=8)
def _level_tables(model: Model, floor: Floor):
    """Per level: (cos ωΔt, sin ωΔt, ω/K, K/ω, K) on the model's layout, float64 → model dtype; and the
    per-place weights (J, n, n)."""
    levels = depth_levels(floor.depth, floor.levels)
    with jax.enable_x64(True):
        ky, kx = model.mode_wavenumbers()
        k = jnp.sqrt(ky * ky + kx * kx).astype(jnp.float64)
        rows = []
        for h in levels:
            water = replace(model.water, depth=float(h))
            w = angular_frequency(k, water)
            big_k = surface_operator(k, water)
            pos = k > 0
            rows.append(jnp.stack(jnp.broadcast_arrays(
                jnp.cos(w * model.dt), jnp.sin(w * model.dt),
                jnp.where(pos, w / jnp.where(pos, big_k, 1.0), 0.0),
                jnp.where(pos, big_k / jnp.where(pos, w, 1.0), 0.0), big_k)))
        tables = jnp.stack(rows).astype(model.dtype)
        weights = depth_weights(floor.depth, levels).astype(model.dtype)
    return tables, weights, levels


def _levels_program(model: Model, tables, weights, mask, fields):
    spec = model.transform(fields)
    eta_h, phi_h = spec[0], spec[1]
    zero_k = tables[0, 4] == 0  # k = 0: the mean height stays
    planes = []
    for j in range(tables.shape[0]):
        c, s, w_over_k, k_over_w, big_k = (tables[j, i] for i in range(5))
        chi = -w_over_k * eta_h
        ph, ch = rotate_pair(phi_h, chi, c, s)
        planes.append(jnp.stack([jnp.where(zero_k, eta_h, -k_over_w * ch), ph, big_k * phi_h]))
    out = model.inverse_transform(jnp.stack(planes))  # (J, 3, n, n)
    blended = jnp.sum(weights[:, None] * out, axis=0)
    new = blended[:2] if mask is None else blended[:2] * mask
    return new, jnp.stack([fields[0], blended[2]])


_levels_jit = jax.jit(_levels_program, static_argnums=0)


def step_levels(model: Model, floor: Floor, state: DepthState):
    """One step over the floor by the spectral step at ``floor.levels`` depths, blended per place.

    Parameters
    ----------
    model : Model
        Grid, water (its depth is ignored: the floor's is used), Δt, walls and margin.
    floor : Floor
        h(x) > 0 everywhere.
    state : DepthState
        η and φ at t.

    Returns
    -------
    (DepthState, jax.Array (2, n, n))
        The state at t + Δt, and (η, η̇) at t, m and m/s.

    References
    ----------
    S. Jeschke & C. Wojtan (2023). Generalizing shallow water simulations with dispersive surface
    waves. *ACM TOG* 42(4), 83 (depth levels blended per place).
    """
    _check(model, floor, state)
    if not float(floor.depth.min()) > 0:
        raise ValueError("floor: the levels method needs depth > 0 everywhere (dry land: method='shallow')")
    tables, weights, _ = _level_tables(model, floor)
    new, surf = _levels_jit(model, tables, weights, operators(model).mask, state.fields)
    return DepthState(new.astype(model.dtype), state.time + model.dt), surf


# -- shallow: the linear shallow-water equations on the grid ------------------------------------
def _faces(depth, axis, walled):
    """Depth at the faces between sample i and i + 1 along ``axis`` (mean of the two); the face past
    the last sample is the wall (0) when walled, the periodic neighbour's otherwise."""
    h = jnp.asarray(depth)
    faces = 0.5 * (h + jnp.roll(h, -1, axis))
    if walled:
        index = [slice(None)] * h.ndim
        index[axis] = slice(-1, None)
        faces = faces.at[tuple(index)].set(0.0)
    return faces


def shallow_substeps(model: Model, floor: Floor) -> int:
    """Sub-steps per Δt that keep the shallow-water update stable: c_max·δ/dx ≤ 0.5 (the 2-D limit is 1/√2).

    Parameters
    ----------
    model : Model
    floor : Floor

    Returns
    -------
    int
        ≥ 1.
    """
    check_instance("model", model, Model, "wavephys.simulation.Model")
    check_instance("floor", floor, Floor, "wavephys.simulation.depth.Floor")
    c = math.sqrt(float(model.water.g) * float(floor.depth.max()))
    return max(1, int(math.ceil(c * float(model.dt) / (0.5 * float(model.grid.dx)))))


@functools.partial(jax.jit, static_argnums=(0, 5))
def _shallow_program(model: Model, hx, hy, mask, fields, substeps):
    dx = model.grid.dx
    g = model.water.g
    d = model.dt / substeps

    def divergence(phi):
        fx = hx * (jnp.roll(phi, -1, -1) - phi) / dx
        fy = hy * (jnp.roll(phi, -1, -2) - phi) / dx
        return (fx - jnp.roll(fx, 1, -1) + fy - jnp.roll(fy, 1, -2)) / dx

    def body(_, f):
        eta, phi = f[0], f[1]
        phi = phi - g * d * eta
        eta = eta - d * divergence(phi)
        return jnp.stack([eta, phi])

    eta_dot = -divergence(fields[1])
    new = jax.lax.fori_loop(0, substeps, body, fields)
    if mask is not None:
        new = new * mask
    return new, jnp.stack([fields[0], eta_dot])


def step_shallow(model: Model, floor: Floor, state: DepthState):
    """One step over the floor by the linear shallow-water equations (η_t = −∇·(h∇φ), φ_t = −gη).

    Fluxes h_face·∂φ/∂n at cell faces (a wall's face carries none; a dry face, h = 0, none either),
    symplectic Euler with :func:`shallow_substeps` sub-steps. Energy-conserving, reflecting at walls,
    slopes and shorelines; non-dispersive (σ ignored).

    Parameters
    ----------
    model : Model
        Grid, water (g), Δt, walls and margin.
    floor : Floor
        h(x) ≥ 0.
    state : DepthState

    Returns
    -------
    (DepthState, jax.Array (2, n, n))
        The state at t + Δt, and (η, η̇) at t.

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, §§169, 186 (long waves over a varying depth).
    """
    _check(model, floor, state)
    wx, wy = model.wall_axes
    hx = _faces(floor.depth, -1, wx).astype(model.dtype)
    hy = _faces(floor.depth, -2, wy).astype(model.dtype)
    new, surf = _shallow_program(model, hx, hy, operators(model).mask, state.fields, shallow_substeps(model, floor))
    return DepthState(new.astype(model.dtype), state.time + model.dt), surf


def _check(model, floor, state):
    check_instance("model", model, Model, "wavephys.simulation.Model")
    check_instance("floor", floor, Floor, "wavephys.simulation.depth.Floor")
    check_instance("state", state, DepthState, "wavephys.simulation.depth.DepthState")
    floor.check(model)
    if model.mesh is not None:
        raise ValueError("a varying floor with a mesh (sharded model) is not supported yet")
    n = model.grid.n
    if tuple(np.shape(state.fields)) != (2, n, n):
        raise ValueError(f"state.fields must have shape (2, {n}, {n}), got {np.shape(state.fields)}")


DEPTH_METHODS = Methods("varying depth", levels=step_levels, shallow=step_shallow)
"""Steppers over a varying floor by name (module doc)."""


def run_depth(model: Model, floor: Floor, state: DepthState, steps: int, method: str = "levels"):
    """``steps`` steps over the floor: ``(final state, (steps, 2, n, n) stacked (η, η̇) at each step's start)``.

    Parameters
    ----------
    model : Model
    floor : Floor
    state : DepthState
    steps : int
        ≥ 1.
    method : {"levels", "shallow"}
        A name in :data:`DEPTH_METHODS`.

    Returns
    -------
    (DepthState, jax.Array)
    """
    steps = check_int("steps", steps, lo=1)
    DEPTH_METHODS.check(method, "method")
    _check(model, floor, state)
    mask = operators(model).mask
    if method == "levels":
        if not float(floor.depth.min()) > 0:
            raise ValueError("floor: the levels method needs depth > 0 everywhere (dry land: method='shallow')")
        tables, weights, _ = _level_tables(model, floor)
        fields, surfaces = _scan(model, "levels", (tables, weights, mask), state.fields, steps, 0)
    else:
        wx, wy = model.wall_axes
        hx = _faces(floor.depth, -1, wx).astype(model.dtype)
        hy = _faces(floor.depth, -2, wy).astype(model.dtype)
        fields, surfaces = _scan(model, "shallow", (hx, hy, mask), state.fields, steps, shallow_substeps(model, floor))
    return DepthState(fields.astype(model.dtype), state.time + steps * model.dt), surfaces


@functools.partial(jax.jit, static_argnums=(0, 1, 4, 5))
def _scan(model, kind, args, fields, steps, substeps):
    """``steps`` steps of one method, compiled once per (model, method, steps, sub-steps)."""
    if kind == "levels":
        def body(f, _):
            return _levels_program(model, *args, f)
    else:
        def body(f, _):
            return _shallow_program.__wrapped__(model, *args, f, substeps)
    return jax.lax.scan(body, fields, None, length=steps)
