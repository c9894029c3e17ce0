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

from wavephys.core.inputs import check_array, check_choice, check_instance, check_int, check_scalar
from wavephys.core.water import Water
from wavephys.core.methods import Methods
from wavephys.core.aliases import deprecated_function
from wavephys.core.pytree import register
from wavephys.core.stepper import Stepper, _FixedEta, _fixed_dt
from wavephys.physics.depth import depth_levels, depth_weights
from wavephys.physics.dispersion import angular_frequency, surface_operator
from wavephys.physics.ring_waves import rotate_pair
from wavephys.simulation.model import Model, operators

__all__ = ["Floor", "DepthState", "depth_state", "step_levels", "step_shallow", "step_symmetric", "DEPTH_METHODS",
           "run_depth", "run_profile", "DepthStepper", "ProfileState", "ProfileStepper", "PROFILE_ENDS", "shallow_substeps", "symmetric_levels", "symmetric_work", "SYMMETRIC_COURANT",
           "MAX_SUBSTEPS"]


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
        Height, m. In a tank smaller than the grid (``Model(tank=...)``) only its centred block is water: the
        land around it is set to 0, as the spectral model's :func:`~wavephys.simulation.add_height` does.
    phi : array_like (n, n), optional
        Surface potential, m²/s (default 0); on land, 0 likewise.
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
    fields = jnp.stack([jnp.asarray(eta, model.dtype), jnp.asarray(phi, model.dtype)])
    if model.tank_cells is not None:
        from wavephys.core.spectral import _tank_block

        water = np.zeros((n, n), bool)
        water[_tank_block(n, model.tank_cells)] = True
        fields = jnp.where(jnp.asarray(water), fields, 0)
    return DepthState(fields, jnp.asarray(time, model.dtype))


# -- levels: the spectral step at a few depths, blended -----------------------------------------
def _level_operators(k, water, dt, levels):
    """Per level, on the wavenumbers ``k`` (rad/m, any shape): (cos ωΔt, sin ωΔt, ω/K, K/ω, K), (J, 5, *k.shape),
    float64 (inside ``jax.enable_x64``)."""
    k = jnp.asarray(k, jnp.float64)
    rows = []
    for h in levels:
        lw = replace(water, depth=float(h))
        w = angular_frequency(k, lw)
        big_k = surface_operator(k, lw)
        pos = k > 0
        rows.append(jnp.stack(jnp.broadcast_arrays(
            jnp.cos(w * dt), jnp.sin(w * dt),
            jnp.where(pos, w / jnp.where(pos, big_k, 1.0), 0.0),
            jnp.where(pos, big_k / jnp.where(pos, w, 1.0), 0.0), big_k)))
    return jnp.stack(rows)


def _model_k(model: Model):
    ky, kx = model.mode_wavenumbers()
    return jnp.sqrt(ky * ky + kx * kx)


@functools.lru_cache(maxsize=8)
def _level_tables(model: Model, floor: Floor):
    """Per level: (cos ωΔt, sin ωΔt, ω/K, K/ω, K) on the model's layout, float64 → model dtype; and the
    per-place weights (J, n, n)."""
    levels = depth_levels(floor.depth, floor.levels)
    with jax.enable_x64(True):
        tables = _level_operators(_model_k(model), model.water, float(model.dt), levels).astype(model.dtype)
        weights = depth_weights(floor.depth, levels).astype(model.dtype)
    return tables, weights, levels


def _levels_program(forward, inverse, tables, weights, mask, fields):
    """One levels step of ``fields`` (η, φ) with the mode transform ``forward`` and its ``inverse``."""
    spec = forward(fields)
    eta_h, phi_h = spec[0], spec[1]
    zero_k = tables[0, 4] == 0  # k = 0: the mean height stays
    planes = []
    for j in range(tables.shape[0]):
        c, s, w_over_k, k_over_w, big_k = (tables[j, i] for i in range(5))
        chi = -w_over_k * eta_h
        ph, ch = rotate_pair(phi_h, chi, c, s)
        planes.append(jnp.stack([jnp.where(zero_k, eta_h, -k_over_w * ch), ph, big_k * phi_h]))
    out = inverse(jnp.stack(planes))  # (J, 3, n, n)
    blended = jnp.sum(weights[:, None] * out, axis=0)
    new = blended[:2] if mask is None else blended[:2] * mask
    return new, jnp.stack([fields[0], blended[2]])


@functools.partial(jax.jit, static_argnums=0)
def _levels_jit(model, tables, weights, mask, fields):
    return _levels_program(model.transform, model.inverse_transform, tables, weights, mask, fields)


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
    floor = _check(model, floor, state)
    if not float(floor.depth.min()) > 0:
        raise ValueError("floor: the levels method needs depth > 0 everywhere (dry land: method='shallow' "
                         "or 'symmetric')")
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


def _axis_shore(h, axis, walled):
    """Along one axis of the sampled depth h (≥ 0, 0 dry): the depth at each face between sample i and i + 1,
    and the wet length of each cell (a fraction of dx) as seen along this axis.

    Where a wet sample meets a dry one, the shoreline is placed by extending the bed's slope from the wet side
    (the depth drop between the wet sample and its wet neighbour further in): it lies d = h/drop cells past
    the wet sample. The face then has the bed's depth there, drop·(d − ½) ≥ 0 (0 when the shoreline falls
    before the face), a wet cell is wet over ½ + min(d, ½) of its length, and a dry cell past a wet face over
    d − ½ of it, which stores water. With no slope to extend (a vertical shore, a lone wet sample) the
    shoreline is the face. A wall end (``walled``) is a face of depth 0 with the wall at the cell's edge."""
    def shift(a, k):  # a at i + k, nan past a wall end
        out = np.roll(a, -k, axis)
        if walled and k:
            index = [slice(None)] * a.ndim
            index[axis] = slice(-k, None) if k > 0 else slice(None, -k)
            out[tuple(index)] = np.nan
        return out

    wet = h > 0
    h1, hm1 = shift(h, 1), shift(h, -1)
    dry1, drym1 = h1 == 0, hm1 == 0  # a dry neighbour (not a wall end: nan there)
    with np.errstate(invalid="ignore", divide="ignore"):
        # the shoreline past wet sample i towards +1 (drop from i − 1 to i) and towards −1 (drop from i + 1 to i)
        drop_up, drop_down = hm1 - h, h1 - h
        d_up = np.where(wet & (hm1 > 0) & (drop_up > 0), h / drop_up, np.nan)
        d_down = np.where(wet & (h1 > 0) & (drop_down > 0), h / drop_down, np.nan)
        face = np.where(wet & (h1 > 0), 0.5 * (h + h1), 0.0)
        past = wet & dry1 & np.isfinite(d_up)  # wet i, dry i + 1: the face from i's side
        face = np.where(past, np.maximum(h - 0.5 * drop_up, 0.0), face)
        before = ~wet & (h1 > 0) & np.isfinite(shift(d_down, 1))  # dry i, wet i + 1: from i + 1's side
        face = np.where(before, np.maximum(h1 - 0.5 * shift(drop_down, 1), 0.0), face)
        face = np.nan_to_num(face)
        upper = np.where(wet & dry1 & np.isfinite(d_up), np.minimum(d_up, 0.5), 0.5)
        lower = np.where(wet & drym1 & np.isfinite(d_down), np.minimum(d_down, 0.5), 0.5)
        length_wet = upper + lower
        from_below = np.nan_to_num(np.maximum(shift(d_up, -1) - 0.5, 0.0))
        from_above = np.nan_to_num(np.maximum(shift(d_down, 1) - 0.5, 0.0))
        length_dry = np.minimum(from_below + from_above, 1.0)
    length = np.where(wet, length_wet, length_dry)
    if walled:
        index = [slice(None)] * h.ndim
        index[axis] = slice(-1, None)
        face[tuple(index)] = 0.0
    return face, length


def _shore_geometry(depth, walls):
    """The linear shallow-water stepper's geometry on a sampled floor: face depths along x and y, and the
    inverse of each cell's wet area fraction (0 where a cell holds no water) — wet cells take the smaller
    of their two axes' wet lengths, dry cells the larger (a straight shoreline along either axis is exact).
    ``walls`` = (x walled, y walled)."""
    h = np.asarray(depth, np.float64)
    hx, lx = _axis_shore(h, -1, walls[0])
    hy, ly = _axis_shore(h, -2, walls[1])
    wet = h > 0
    area = np.where(wet, np.minimum(lx, ly), np.maximum(lx, ly))
    inv = np.where(area > 0, 1.0 / np.where(area > 0, area, 1.0), 0.0)
    return hx, hy, inv


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
    return _substeps(c * float(model.dt) / (0.5 * float(model.grid.dx)), float(model.dt), "shallow")


def _shallow_steps(dx, g, dt, hx, hy, mask, fields, substeps, inv_area=None):
    """``substeps`` symplectic-Euler sub-steps of the linear shallow-water equations over Δt on any (ny, nx);
    ``inv_area``: 1 / each cell's wet fraction (0 for a cell that holds no water; None: every cell whole)."""
    d = dt / substeps

    def divergence(phi):
        fx = hx * (jnp.roll(phi, -1, -1) - phi) / dx
        fy = hy * (jnp.roll(phi, -1, -2) - phi) / dx
        div = (fx - jnp.roll(fx, 1, -1) + fy - jnp.roll(fy, 1, -2)) / dx
        return div if inv_area is None else div * inv_area

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


def _shallow_program(model: Model, hx, hy, inv_area, mask, fields, substeps):
    return _shallow_steps(model.grid.dx, model.water.g, model.dt, hx, hy, mask, fields, substeps, inv_area)


_shallow_jit = jax.jit(_shallow_program, static_argnums=(0, 6))


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
    floor = _check(model, floor, state)
    hx, hy, inv = _geometry(model, floor)
    new, surf = _shallow_jit(model, hx, hy, inv, operators(model).mask, state.fields, shallow_substeps(model, floor))
    return DepthState(new.astype(model.dtype), state.time + model.dt), surf


# -- symmetric: the levels' operators blended so that energy is conserved ------------------------
MAX_SUBSTEPS = 100_000
"""Sub-steps per Δt beyond which a stepper refuses the Δt (by name) rather than run for hours."""

SYMMETRIC_COURANT = 1.0
"""The symmetric method's sub-step δ keeps ω_max·δ ≤ this (leapfrog is stable to 2): the highest frequency
on the grid turns by at most 1 rad a sub-step, a resolved wave's by far less (its phase error is (ωδ)²/24)."""


def symmetric_levels(depth, count: int = 4) -> np.ndarray:
    """The symmetric method's depth levels for a floor: :func:`~wavephys.physics.depth.depth_levels` over its
    wet part, with 0 in front when it has dry land (h = 0), m, increasing.

    Between the dry level and the shallowest wet one the operator is linear in h, which is the shallow-water
    limit K = k²h: near a shoreline the blend is exact for long waves.

    Parameters
    ----------
    depth : array_like
        h(x), m, ≥ 0, with some water (h > 0).
    count : int
        Wet levels, 1 … 16.

    Returns
    -------
    numpy.ndarray
    """
    check_array("depth", depth, lo=0.0)
    h = np.asarray(depth, np.float64)
    wet = h[h > 0]
    if wet.size == 0:
        raise ValueError("depth: the floor is dry everywhere (no water to step)")
    levels = depth_levels(wet, count)
    return np.concatenate([[0.0], levels]) if wet.size < h.size else levels


def _substeps(count: float, dt: float, what: str) -> int:
    """``ceil(count)`` sub-steps, at least 1; ValueError naming ``dt`` above :data:`MAX_SUBSTEPS`."""
    if not count <= MAX_SUBSTEPS:
        raise ValueError(f"dt = {dt:g} s needs {count:.3g} sub-steps of the {what} stepper (stability), more than "
                         f"{MAX_SUBSTEPS}: give a smaller dt")
    return max(1, int(math.ceil(count)))


def _symmetric_operators(k, water, levels, dt):
    """(K̃ at each wet level (J, *k.shape), the restoring multiplier R = g + σk²/ρ or None without surface
    tension, sub-steps), float64 (inside ``jax.enable_x64``).

    The sub-steps δ = Δt/s keep ω_max·δ ≤ :data:`SYMMETRIC_COURANT` (ω_max = max √(R·K) at the deepest level).
    Each level's K = |k| tanh(|k|h_j) is replaced by K̃ = 4 sin²(ωδ/2) / (R δ²), ω = √(R·K): leapfrog's own
    frequency for a mode is 2 arcsin(√(R·K̃)·δ/2)/δ, which with K̃ is ω exactly. So a floor at any one level
    is stepped with no phase error at all (plain leapfrog lags by ≈ (ωδ)²/24 of a radian per radian: 1.6 % of
    a stone's crater height after 1 s at ω_max·δ = 1, measured), and K̃ > 0 keeps the blend self-adjoint."""
    k = jnp.asarray(k, jnp.float64)
    big_k = jnp.stack([surface_operator(k, replace(water, depth=float(h))) for h in levels if h > 0])
    restoring = water.g + water.sigma * k * k / water.rho
    omega = jnp.sqrt(restoring * big_k)
    substeps = _substeps(float(jnp.max(omega[-1])) * dt / SYMMETRIC_COURANT, dt, "symmetric")
    d = dt / substeps
    tuned = 4.0 * jnp.sin(0.5 * omega * d) ** 2 / (restoring * d * d)
    return tuned, (restoring if water.sigma > 0 else None), substeps


def _symmetric_steps(forward, inverse, big_k, roots, restoring, g, dt, mask, fields, substeps):
    """``substeps`` leapfrog sub-steps over Δt of η_t = Σ_j S_j G_j S_j φ, φ_t = −Rη (module doc)."""
    d = dt / substeps

    def apply_g(phi):
        return jnp.sum(roots * inverse(big_k * forward(roots * phi)), axis=0)

    def restore(eta):
        return g * eta if restoring is None else inverse(restoring * forward(eta))

    def body(_, f):
        eta, phi = f[0], f[1]
        phi = phi - 0.5 * d * restore(eta)
        eta = eta + d * apply_g(phi)
        phi = phi - 0.5 * d * restore(eta)
        return jnp.stack([eta, phi])

    eta_dot = apply_g(fields[1])
    new = jax.lax.fori_loop(0, substeps, body, fields)
    if mask is not None:
        new = new * mask
    return new, jnp.stack([fields[0], eta_dot])


@functools.lru_cache(maxsize=8)
def _symmetric_tables(model: Model, floor: Floor):
    """(K per wet level, restoring or None, √w per wet level (J, n, n), sub-steps), in the model's dtype."""
    levels = symmetric_levels(floor.depth, floor.levels)
    with jax.enable_x64(True):
        big_k, restoring, substeps = _symmetric_operators(_model_k(model), model.water, levels, float(model.dt))
        weights = depth_weights(floor.depth, levels)[int(levels[0] == 0):]  # the dry level carries no flux
        roots = jnp.sqrt(weights)
        cast = lambda a: None if a is None else a.astype(model.dtype)
        return cast(big_k), cast(restoring), cast(roots), substeps


def symmetric_work(model: Model, floor: Floor) -> tuple[int, int]:
    """(wet depth levels, leapfrog sub-steps per Δt) of :func:`step_symmetric` on this floor: a step
    costs about levels × sub-steps forward and inverse transforms (the planner's cost model).

    Parameters
    ----------
    model : Model
    floor : Floor

    Returns
    -------
    (int, int)
    """
    check_instance("model", model, Model, "wavephys.simulation.Model")
    check_instance("floor", floor, Floor, "wavephys.simulation.depth.Floor")
    floor.check(model)
    if not float(floor.depth.max()) > 0:
        raise ValueError("floor: no water (depth 0 everywhere)")
    big_k, _, _, substeps = _symmetric_tables(model, floor)
    return int(big_k.shape[0]), int(substeps)


def _symmetric_program(model: Model, big_k, restoring, roots, mask, fields, substeps):
    return _symmetric_steps(model.transform, model.inverse_transform, big_k, roots, restoring, model.water.g,
                            model.dt, mask, fields, substeps)


_symmetric_jit = jax.jit(_symmetric_program, static_argnums=(0, 6))


def _is_one_level(floor: Floor) -> bool:
    """A floor the symmetric method steps exactly by the spectral step: one depth, no dry land."""
    return len(symmetric_levels(floor.depth, floor.levels)) == 1


def step_symmetric(model: Model, floor: Floor, state: DepthState):
    """One step over the floor by the depth levels blended symmetrically: η_t = Σ_j S_j G_j S_j φ, φ_t = −gη.

    G_j is the exact linear operator (Dirichlet-to-Neumann, K_j = |k| tanh(|k|h_j) on the model's modes) at
    depth level h_j and S_j multiplies by √w_j(x), the square root of the level's weight at each place (linear
    in h between the two levels around h(x)). The blend is self-adjoint, so the scheme is Hamiltonian: energy
    ½∫(gη² + φ·Σ S_j G_j S_j φ) is conserved, and over a slowly varying floor a wave's energy flux is too —
    it shoals right at every kh, where the levels method (which blends the levels' outputs) does not. Time:
    Störmer–Verlet (leapfrog) with ω_max·δ ≤ :data:`SYMMETRIC_COURANT` sub-steps. A floor at one depth with
    no dry land is stepped exactly, by the spectral step. Dry land (h = 0) is a level with no flux: between it
    and the shallowest wet level the operator is k²h, the shallow-water limit, so waves run to a shoreline
    and reflect from it.

    Parameters
    ----------
    model : Model
        Grid, water (g, ρ, σ; its depth is ignored: the floor's is used), Δt, walls and margin.
    floor : Floor
        h(x) ≥ 0, with water somewhere.
    state : DepthState

    Returns
    -------
    (DepthState, jax.Array (2, n, n))
        The state at t + Δt, and (η, η̇) at t, m and m/s.

    References
    ----------
    S. Jeschke & C. Wojtan (2023). Generalizing shallow water simulations with dispersive surface waves.
    *ACM TOG* 42(4), 83 (depth levels blended per place); V. E. Zakharov (1968). Stability of periodic
    waves of finite amplitude on the surface of a deep fluid. *J. Appl. Mech. Tech. Phys.* 9, 190–194
    (water waves as a Hamiltonian system in η and the surface potential).
    """
    floor = _check(model, floor, state)
    if _is_one_level(floor):
        return step_levels(model, floor, state)
    big_k, restoring, roots, substeps = _symmetric_tables(model, floor)
    new, surf = _symmetric_jit(model, big_k, restoring, roots, operators(model).mask, state.fields, substeps)
    return DepthState(new.astype(model.dtype), state.time + model.dt), surf


def _check(model, floor, state) -> "Floor":
    """Refuse bad input by name; the floor the steppers use (:func:`_tank_floor`)."""
    check_instance("model", model, Model, "wavephys.simulation.Model")
    check_instance("floor", floor, Floor, "wavephys.simulation.depth.Floor")
    check_instance("state", state, DepthState, "wavephys.simulation.depth.DepthState")
    floor.check(model)
    if model.mesh is not None:
        raise ValueError("a varying floor with a mesh (sharded model) is not supported yet")
    n = model.grid.n
    if tuple(np.shape(state.fields)) != (2, n, n):
        raise ValueError(f"state.fields must have shape (2, {n}, {n}), got {np.shape(state.fields)}")
    return _tank_floor(model, floor)


def _tank_floor(model: Model, floor: Floor) -> Floor:
    """The floor as the steppers read it. In a tank smaller than the grid (``Model(tank=...)``) only the tank's
    centred block of cells is water; the land around it is given the depths of the tank's edge (any depth
    would do: the walls hold the waves in, and the land's fields stay 0), so that the depth levels, the
    wet test and the sub-steps are the tank's own."""
    if model.tank_cells is None:
        return floor
    from wavephys.core.spectral import _tank_block

    n = model.grid.n
    rows, cols = _tank_block(n, model.tank_cells)
    pad = ((rows.start, n - rows.stop), (cols.start, n - cols.stop))
    return Floor(np.pad(floor.depth[rows, cols], pad, mode="edge"), floor.levels)


def _geometry(model: Model, floor: Floor):
    """The ``shallow`` method's face depths along x and y and inverse wet areas, in the model's dtype: walls at
    the grid's walled edges, or around a tank smaller than the grid (faces of depth 0 on its edges and
    outside it)."""
    if model.tank_cells is None:
        hx, hy, inv = _shore_geometry(floor.depth, model.wall_axes)
    else:
        from wavephys.core.spectral import _tank_block

        block = _tank_block(model.grid.n, model.tank_cells)
        hx, hy, inv = (np.zeros(floor.depth.shape) for _ in range(3))
        for whole, part in zip((hx, hy, inv), _shore_geometry(floor.depth[block], (True, True))):
            whole[block] = part
    return tuple(jnp.asarray(a, model.dtype) for a in (hx, hy, inv))


DEPTH_METHODS = Methods("varying depth", levels=step_levels, shallow=step_shallow, symmetric=step_symmetric)
"""Steppers over a varying floor by name (module doc)."""


@functools.partial(jax.jit, static_argnums=(0, 1))
def _surfaces_program(cls, static, dynamic, fields):
    # one state at a time (lax.map, not vmap: a vmapped step over every state held 3.6× run_depth's memory)
    return jax.lax.map(lambda f: cls._program(static, dynamic, f)[1].astype(f.dtype), fields)


class DepthStepper(Stepper):
    """Linear waves over a varying floor (:mod:`wavephys.simulation.depth`): ``method`` one of ``"levels"``,
    ``"symmetric"``, ``"shallow"``; Δt is the model's.

    Parameters
    ----------
    model : Model
    floor : Floor
    method : str
    """

    def __init__(self, model, floor, method: str = "levels"):
        check_instance("model", model, Model, "wavephys.simulation.Model")
        check_instance("floor", floor, Floor, "wavephys.simulation.depth.Floor")
        DEPTH_METHODS.check(method, "method")
        floor.check(model)
        self.model, self.floor, self.method, self.state_type = model, floor, method, DepthState

    def _parts(self):
        model, method = self.model, self.method
        floor = _tank_floor(model, self.floor)
        mask = operators(model).mask
        if method == "symmetric" and _is_one_level(floor):
            method = "levels"
        if method == "levels":
            if not float(floor.depth.min()) > 0:
                raise ValueError("floor: the levels method needs depth > 0 everywhere (dry land: method='shallow' "
                                 "or 'symmetric')")
            tables, weights, _ = _level_tables(model, floor)
            return ("levels", 0), (model, (tables, weights, mask))
        if method == "symmetric":
            big_k, restoring, roots, substeps = _symmetric_tables(model, floor)
            return ("symmetric", substeps), (model, (big_k, restoring, roots, mask))
        hx, hy, inv = _geometry(model, floor)
        return ("shallow", shallow_substeps(model, floor)), (model, (hx, hy, inv, mask))

    def _checked_state(self, state):
        _check(self.model, self.floor, state)
        return state

    @classmethod
    def _program(cls, static, dynamic, fields):
        """One step of (η, φ): ``(the fields after it, (η, η̇) at its start)``."""
        kind, substeps = static
        model, args = dynamic
        if kind == "levels":
            return _levels_program(model.transform, model.inverse_transform, *args, fields)
        if kind == "symmetric":
            return _symmetric_program(model, *args, fields, substeps)
        return _shallow_program(model, *args, fields, substeps)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        new = cls._program(static, dynamic, state.fields)[0]
        return type(state)(new.astype(state.fields.dtype), state.time + dynamic[0].dt)

    def surfaces(self, states):
        """The surfaces (η, m; η̇, m/s) of stacked states (:meth:`trajectory`'s), stacked: (T, 2, n, n).

        Parameters
        ----------
        states : DepthState
            States stacked on a leading axis.

        Returns
        -------
        jax.Array (T, 2, n, n)
        """
        static, dynamic = self._parts()
        return _surfaces_program(type(self), static, dynamic, states.fields)

    @classmethod
    def _dt(cls, static, dynamic, state):
        return jnp.asarray(dynamic[0].dt, state.time.dtype)

    @classmethod
    def _height(cls, static, dynamic, state):
        return state.fields[0]

    def _check_dt(self, state, dt):
        return _fixed_dt(self, float(self.model.dt), dt)

    @property
    def sides(self):
        wx, wy = self.model.wall_axes
        return ("wall" if wx else "periodic",) * 2 + ("wall" if wy else "periodic",) * 2


def _run_depth(model: Model, floor: Floor, state: DepthState, steps: int, method: str = "levels"):
    """``steps`` steps over the floor: ``(final state, (steps, 2, n, n) stacked (η, η̇) at each step's start)``
    (``DepthStepper``'s ``trajectory`` and ``surfaces``).

    Parameters
    ----------
    model : Model
    floor : Floor
    state : DepthState
    steps : int
        ≥ 1.
    method : {"levels", "shallow", "symmetric"}
        A name in :data:`DEPTH_METHODS`.

    Returns
    -------
    (DepthState, jax.Array)
    """
    steps = check_int("steps", steps, lo=1)
    stepper = DepthStepper(model, floor, method)
    end, states = stepper.trajectory(state, steps)
    return end, stepper.surfaces(states)


run_depth = deprecated_function(_run_depth, "run_depth", "DepthStepper(model, floor, method).run / .advance, or "
                                                         ".trajectory and .surfaces for every step")


PROFILE_ENDS = ("periodic", "walls")
""":class:`ProfileStepper`'s ends: the profile wraps, or reflecting walls half a sample past its first and last
samples (the texel convention of a walled tank)."""


@dataclass(frozen=True)
class ProfileState:
    """Plane waves along x over a depth profile (:class:`ProfileStepper`): η and φ at the profile's samples.

    Parameters
    ----------
    eta : array (n,)
        Height η, m, finite.
    phi : array (n,)
        Surface potential φ, m²/s, the shape of ``eta``.
    time : float
        s.
    """

    eta: jax.Array
    phi: jax.Array
    time: jax.Array = 0.0

    def __post_init__(self):
        if any(isinstance(v, jax.core.Tracer) for v in (self.eta, self.phi, self.time)):
            return
        check_array("eta", self.eta, ndim=1)
        check_array("phi", self.phi, ndim=1)
        if np.shape(self.eta) != np.shape(self.phi):
            raise ValueError(f"eta and phi must have one shape, got {np.shape(self.eta)} and {np.shape(self.phi)}")
        check_scalar("time", self.time)
        dtype = jnp.float64 if jax.config.jax_enable_x64 else jnp.float32
        for name in ("eta", "phi", "time"):
            object.__setattr__(self, name, jnp.asarray(getattr(self, name), dtype))


register(ProfileState, ("eta", "phi", "time"))


class ProfileStepper(_FixedEta):
    """Plane waves along x over a depth profile h(x): the methods of :data:`DEPTH_METHODS` on one row (what a
    square grid gives for waves uniform in y, at 1/n of the cost), periodic or between walls; Δt fixed.

    Parameters
    ----------
    depth : array_like (n,)
        h(x), m, ≥ 0 (> 0 for ``"levels"``), n even ≥ 4.
    dx : float
        Spacing, m, > 0.
    water : Water
        g, ρ, σ (its depth is ignored).
    dt : float
        Step, s, > 0.
    method : {"levels", "shallow", "symmetric"}
    levels : int
        Depth levels, 1 … 16 (as :class:`Floor`).
    ends : {"periodic", "walls"}
        ``"periodic"`` (default): the profile wraps (a ramp up must come back down); ``"walls"``: a reflecting
        wall half a sample past each end (cosine modes cos(mπx/L), L = n·dx), so a beach or a ramp can end
        where it ends.

    Examples
    --------
    >>> import numpy as np
    >>> from wavephys import Water
    >>> x = (np.arange(64) + 0.5) * 0.05
    >>> stepper = ProfileStepper(0.1 + 0.2 * x / x[-1], 0.05, Water(sigma=0.0), 1 / 64, ends="walls")
    >>> run = stepper.run(ProfileState(0.001 * np.cos(np.pi * x / 3.2), np.zeros(64)), steps=64, every=32)
    >>> run.frames.shape, run.times.tolist()
    ((2, 64), [0.5, 1.0])
    """

    def __init__(self, depth, dx: float, water: Water, dt: float, method: str = "symmetric", levels: int = 4,
                 ends: str = "periodic"):
        check_array("depth", depth, ndim=1, lo=0.0)
        self.n = check_int("depth.shape[0]", np.shape(depth)[0], lo=4, even=True)
        self.dx = check_scalar("dx", dx, lo=0.0, lo_open=True)
        check_instance("water", water, Water, "wavephys.Water")
        self.dt = check_scalar("dt", dt, lo=0.0, lo_open=True)
        DEPTH_METHODS.check(method, "method")
        self.levels = check_int("levels", levels, lo=1, hi=16)
        self.ends = check_choice("ends", ends, PROFILE_ENDS)
        self.depth, self.water, self.method = np.asarray(depth, np.float64), water, method
        if method == "levels" and not float(self.depth.min()) > 0:
            raise ValueError("depth: the levels method needs depth > 0 everywhere (dry land: method='shallow' "
                             "or 'symmetric')")
        self.state_type, self._made = ProfileState, {}

    def _parts(self):
        dtype = jnp.float64 if jax.config.jax_enable_x64 else jnp.float32
        if dtype not in self._made:
            self._made[dtype] = self._operators(dtype)
        return self._made[dtype]

    def _operators(self, dtype):
        """(static (method, walled, sub-steps), dynamic ((dx, g, Δt), operators)) in ``dtype``."""
        n, dx, dt, water, walled = self.n, self.dx, self.dt, self.water, self.ends == "walls"
        h = np.broadcast_to(self.depth, (2, n))
        if walled:
            kx = np.pi * np.arange(n)[None, :] / (n * dx)
            ky = 2 * np.pi * np.fft.rfftfreq(2, dx)[:, None]
        else:
            ky = 2 * np.pi * np.fft.fftfreq(2, dx)[:, None]
            kx = 2 * np.pi * np.fft.rfftfreq(n, dx)[None, :]
        k = np.sqrt(kx * kx + ky * ky)
        method = self.method
        if method == "symmetric" and len(symmetric_levels(h, self.levels)) == 1:
            method = "levels"
        with jax.enable_x64(True):
            if method == "levels":
                lv = depth_levels(h, self.levels)
                args, sub = (np.asarray(_level_operators(k, water, dt, lv)), np.asarray(depth_weights(h, lv))), 0
            elif method == "symmetric":
                lv = symmetric_levels(h, self.levels)
                big_k, restoring, sub = _symmetric_operators(k, water, lv, dt)
                roots = np.sqrt(np.asarray(depth_weights(h, lv))[int(lv[0] == 0):])
                args = (np.asarray(big_k), roots, None if restoring is None else np.asarray(restoring))
            else:
                hx, _, inv = _shore_geometry(h, (walled, False))
                c = math.sqrt(float(water.g) * float(h.max()))
                sub = _substeps(c * dt / (0.5 * dx), dt, "shallow")
                args = (hx, np.zeros((2, n)), inv)
        args = tuple(None if a is None else jnp.asarray(a, dtype) for a in args)
        scalars = tuple(jnp.asarray(v, dtype) for v in (dx, water.g, dt))
        return (method, walled, sub), (scalars, args)

    def _checked_state(self, state):
        state = super()._checked_state(state)
        if not isinstance(state.eta, jax.core.Tracer) and np.shape(state.eta) != (self.n,):
            raise ValueError(f"state: eta must have the profile's {self.n} samples, got shape {np.shape(state.eta)}")
        return state

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        method, walled, substeps = static
        (dx, g, own), args = dynamic
        n = state.eta.shape[-1]
        if walled:  # cosine modes along x, the two rows (uniform in y) by rfft
            from wavephys.core.spectral import cosine_transform, inverse_cosine_transform

            forward = lambda f: jnp.fft.rfft(cosine_transform(f, -1), axis=-2)
            inverse = lambda spec: inverse_cosine_transform(jnp.fft.irfft(spec, n=2, axis=-2), -1)
        else:
            forward = jnp.fft.rfft2
            inverse = lambda spec: jnp.fft.irfft2(spec, s=(2, n))
        fields = jnp.stack([jnp.broadcast_to(state.eta, (2, n)), jnp.broadcast_to(state.phi, (2, n))])
        if method == "levels":
            out = _levels_program(forward, inverse, *args, None, fields)[0]
        elif method == "symmetric":
            out = _symmetric_steps(forward, inverse, args[0], args[1], args[2], g, own, None, fields, substeps)[0]
        else:
            out = _shallow_steps(dx, g, own, args[0], args[1], None, fields, substeps, args[2])[0]
        out = out.astype(state.eta.dtype)
        return ProfileState(out[0, 0], out[1, 0], state.time + own.astype(state.time.dtype))

    @classmethod
    def _dt(cls, static, dynamic, state):
        return jnp.asarray(dynamic[0][2], state.time.dtype)

    @property
    def sides(self):
        return ("wall" if self.ends == "walls" else "periodic",) * 2 + ("periodic",) * 2


def _run_profile(depth, dx: float, water: Water, dt: float, eta, phi, steps: int, method: str = "symmetric",
                 levels: int = 4, ends: str = "periodic", every: Optional[int] = None):
    """``steps`` steps of a :class:`ProfileStepper` from (η, φ), optionally keeping η every ``every`` steps.

    Parameters
    ----------
    depth, dx, water, dt, method, levels, ends
        As :class:`ProfileStepper`.
    eta, phi : array_like (n,)
        Height (m) and surface potential (m²/s) at the start.
    steps : int
        ≥ 1.
    every : int, optional
        Also return η every ``every`` steps (≥ 1, dividing ``steps``): frames at steps 0, every, …, steps.

    Returns
    -------
    (jax.Array, jax.Array) or (jax.Array, jax.Array, jax.Array)
        η and φ after ``steps`` steps, (n,), float64 when x64 is on, else float32; with ``every``, the frames
        (steps // every + 1, n) too.
    """
    stepper = ProfileStepper(depth, dx, water, dt, method, levels, ends)
    check_array("eta", eta, ndim=1, shape_tail=(stepper.n,))
    check_array("phi", phi, ndim=1, shape_tail=(stepper.n,))
    steps = check_int("steps", steps, lo=1)
    if every is not None:
        every = check_int("every", every, lo=1)
        if steps % every:
            raise ValueError(f"every: {every} does not divide steps = {steps} (frames are taken every `every` steps "
                             f"up to the last)")
    state = ProfileState(eta, phi)
    if every is None:
        end = stepper._every_step(state, steps)
        return end.eta, end.phi
    end, states = stepper.trajectory(state, steps)  # one compiled scan (a profile's states are small)
    return end.eta, end.phi, jnp.concatenate([states.eta[::every], end.eta[None]])


run_profile = deprecated_function(_run_profile, "run_profile",
                                  "ProfileStepper(depth, dx, water, dt, method, levels, ends).run / .advance")
