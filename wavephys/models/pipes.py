r"""Virtual pipes: the height-field water of games (O'Brien & Hodgins 1995; the common 4-pipe form).

Each cell of side l holds a water depth d over a bed b and four *outflows* f (m³/s), one through
a pipe to each neighbour. A step of Δt (docs/physics.md §1.14):

1. every pipe's flow accelerates with the difference of the surfaces it joins,
   f ← max(0, f + Δt·A·g·(η − η_neighbour)/l), η = b + d;
2. a cell's four outflows are scaled by K = min(1, d·l² / (Δt·Σf)), so it cannot give more than it
   holds (depth stays ≥ 0);
3. d ← d + Δt·(Σ inflows − Σ outflows)/l².

Mass is conserved to rounding (each flow leaves one cell and enters another), depth stays ≥ 0 and a
lake at rest stays at rest. While the flow goes one way, one pipe of each face carries it and the
scheme is the wave equation with c² = g·A/l; once waves go back and forth both one-way pipes of a
face carry flow and the net flux accelerates twice as fast, c² = 2g·A/l (measured: a seiche at
1.414 √(gh) with A = l·h). The common form keeps A constant (``area`` a number, m²: its speed does not
follow the depth); ``area="depth"`` uses A = l·(d_i + d_j)/2 per pipe. Nothing carries momentum
(u·∇u), so a dam break is wrong at every resolution; the clamps damp waves more the larger they are;
the explicit update is stable to √(gh)·Δt/l = 0.7 in 1-D and 0.5 in 2-D (measured; the effective
Courant number is √2 larger). Measured against the finite-volume solver and the exact cases in
``python -m bench shallow`` and tests/models/test_pipes.py (docs/physics.md §1.14).

References
----------
J. F. O'Brien & J. K. Hodgins (1995). Dynamic simulation of splashing fluids. *Computer
Animation '95*, 198–205. X. Mei, P. Decaudin & B.-G. Hu (2007). Fast hydraulic erosion simulation
and visualization on GPU. *Pacific Graphics*, 47–56 (the 4-pipe form with the outflow scaling).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from typing import Any

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.aliases import deprecated_function
from wavephys.core.stepper import Stepper, _bed, _fixed_dt
from wavephys.core.inputs import (check_array, check_choice, check_instance, check_int, check_scalar, check_state_dtype,
                                  describe, is_traced)
from wavephys.physics.shallow_water import water_depth
from wavephys.core.pytree import register

__all__ = ["Pipes", "PipesStepper", "PipesState", "pipes_state", "pipes_step", "pipes_run", "pipes_courant", "COURANT_LIMITS"]


@dataclass(frozen=True)
class Pipes:
    """Virtual-pipe settings (a pytree: ``dx``, ``g`` and a constant area are leaves).

    Parameters
    ----------
    dx : float
        Cell size l, m, > 0.
    area : "depth" or float
        Pipe cross-section A: ``"depth"`` (A = l × the mean depth of the two cells) or a constant, m² (the
        common form). Waves run at √(2gA/l) once flows reverse (√2 × √(gh) with ``"depth"``).
    sides : {"wall", "periodic"}
        The domain's edges: closed, or joined to the opposite edge.
    g : float
        m/s².

    Examples
    --------
    >>> Pipes(0.1).area
    'depth'
    """

    dx: float
    area: Any = "depth"
    sides: str = "wall"
    g: float = 9.81

    def __post_init__(self):
        if isinstance(self.dx, jax.core.Tracer):
            return
        check_scalar("dx", self.dx, lo=0.0, lo_open=True)
        check_scalar("g", self.g, lo=0.0, lo_open=True)
        check_choice("sides", self.sides, ("wall", "periodic"))
        if isinstance(self.area, str):
            check_choice("area", self.area, ("depth",))
        elif isinstance(self.area, (bool, np.bool_)) or not isinstance(self.area, (int, float, np.number)):
            raise TypeError(f"area must be 'depth' or a cross-section in m², got {describe(self.area)}")
        else:
            check_scalar("area", self.area, lo=0.0, lo_open=True)

    @property
    def _constant(self):
        return not isinstance(self.area, str)


def _flatten(p):
    return ((p.dx, p.g, None if isinstance(p.area, str) else p.area),
            (p.sides, p.area if isinstance(p.area, str) else None))


def _unflatten(aux, children):
    obj = object.__new__(Pipes)
    dx, g, area = children
    object.__setattr__(obj, "dx", dx)
    object.__setattr__(obj, "g", g)
    object.__setattr__(obj, "sides", aux[0])
    object.__setattr__(obj, "area", aux[1] if aux[1] is not None else area)
    return obj


jax.tree_util.register_pytree_node(Pipes, _flatten, _unflatten)


@dataclass(frozen=True)
class PipesState:
    """Depth and the four outflows of every cell (make one with :func:`pipes_state`).

    Parameters
    ----------
    depth : array (ny, nx)
        m, ≥ 0.
    flows : array (4, ny, nx)
        Outflows to the left, right, bottom and top neighbours, m³/s, ≥ 0.
    time : float
        s.
    """

    depth: jax.Array
    flows: jax.Array
    time: jax.Array

    def __post_init__(self):
        if any(isinstance(v, jax.core.Tracer) for v in (self.depth, self.flows, self.time)):
            return
        check_array("depth", self.depth, ndim=2, lo=0.0)
        check_array("flows", self.flows, ndim=3, shape_tail=np.shape(self.depth), lo=0.0)
        if np.shape(self.flows)[0] != 4:
            raise ValueError(f"flows must hold 4 outflows per cell, shape (4, ny, nx), got {np.shape(self.flows)}")
        check_scalar("time", self.time)


register(PipesState, ("depth", "flows", "time"))


def pipes_state(bed, eta=None, *, depth=None, dtype=jnp.float32) -> PipesState:
    """Water at rest in the pipes: from the surface η (depth max(η − b, 0)) or the depth.

    Parameters
    ----------
    bed : array_like (ny, nx)
        Bed elevation, m.
    eta : float or array_like (ny, nx), optional
    depth : array_like (ny, nx), optional
    dtype : float32 or float64

    Returns
    -------
    PipesState
    """
    d = water_depth(bed, eta, depth)
    shape = d.shape
    dtype = check_state_dtype("dtype", dtype)
    return PipesState(jnp.asarray(d, dtype), jnp.zeros((4,) + shape, dtype), jnp.asarray(0.0, dtype))


_SHIFTS = ((-1, 1), (-1, -1), (-2, 1), (-2, -1))  # (axis, roll giving the neighbour) for left, right, bottom, top


def _neighbour(a, k, periodic):
    axis, shift = _SHIFTS[k]
    return jnp.roll(a, shift, axis)


def _edge_mask(shape, k):
    """1 where the pipe k of a cell leads inside the domain, 0 where it leads through the edge."""
    axis, shift = _SHIFTS[k]
    n = shape[axis]
    idx = jnp.arange(n)
    inside = (idx > 0) if shift == 1 else (idx < n - 1)
    return inside[None, :] if axis == -1 else inside[:, None]


def _advance(pipes, bed, depth, flows, dt):
    l = pipes.dx
    eta = bed + depth
    periodic = pipes.sides == "periodic"
    new = []
    for k in range(4):
        eta_n = _neighbour(eta, k, periodic)
        if pipes._constant:
            area = pipes.area
        else:
            area = l * 0.5 * (depth + _neighbour(depth, k, periodic))
        f = jnp.maximum(0.0, flows[k] + dt * area * pipes.g * (eta - eta_n) / l)
        if not periodic:
            f = f * _edge_mask(depth.shape, k)
        new.append(f)
    f = jnp.stack(new)
    total = jnp.sum(f, axis=0)
    cap = depth * l * l
    scale = jnp.where(total * dt > cap, cap / jnp.where(total > 0, total * dt, 1.0), 1.0)
    f = f * scale
    # what enters a cell: its left neighbour's right outflow, its right neighbour's left outflow, …
    inflow = (_neighbour(f[1], 0, periodic) + _neighbour(f[0], 1, periodic)
              + _neighbour(f[3], 2, periodic) + _neighbour(f[2], 3, periodic))
    depth = jnp.maximum(depth + dt * (inflow - jnp.sum(f, axis=0)) / (l * l), 0.0)
    return depth, f


@functools.partial(jax.jit, static_argnums=6)
def _run_program(pipes, bed, depth, flows, t, dt, steps):
    """``steps`` steps with no checks (for measuring where the pipes fail: wavephys.checks)."""
    def body(c, _):
        d, f = c
        return _advance(pipes, bed, d, f, dt), None

    (depth, flows), _ = jax.lax.scan(body, (depth, flows), None, length=steps)
    return depth, flows, t + steps * dt


def _stepper(pipes, bed, dt):
    """The pipes behind the one stepper interface (wavephys.core.stepper): its loop is the runs' loop."""
    return PipesStepper(pipes, bed, dt)


def _checked(pipes, bed, state, dt):
    check_instance("pipes", pipes, Pipes, "wavephys.models.pipes.Pipes")
    check_instance("state", state, PipesState, "wavephys.models.pipes.PipesState")
    shape = np.shape(state.depth)
    if len(shape) != 2 or np.shape(state.flows) != (4,) + shape:
        raise ValueError(f"state must hold depth (ny, nx) and flows (4, ny, nx), got {shape} and "
                         f"{np.shape(state.flows)}")
    check_array("bed", bed, ndim=2, shape_tail=shape)
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    if not any(is_traced(v) for v in (state.depth, state.flows, dt)):
        depth = np.asarray(state.depth)
        if not (np.all(np.isfinite(depth)) and np.all(np.isfinite(np.asarray(state.flows)))):
            raise ValueError("state holds NaN or inf values; a step needs a finite state")
        limit = COURANT_LIMITS[0 if min(shape) == 1 else 1]
        courant = pipes_courant(pipes, float(depth.max()), float(dt))
        if courant > limit:
            raise ValueError(f"dt = {float(dt):.4g} s is past the stable step: Courant number √(gh)·dt/dx = "
                             f"{courant:.3g} > {limit} (the measured limit {'in 1-D' if limit == 0.7 else 'in 2-D'}; "
                             f"stable to dt = {float(dt) * limit / courant:.4g} s here)")
    return jnp.asarray(bed, state.depth.dtype)


COURANT_LIMITS = (0.7, 0.5)
"""The virtual pipes' measured stable Courant numbers √(gh)·Δt/dx, in 1-D (a row or a column) and in 2-D:
steps past them are refused (the seiche grows ×10 within 6 periods at 0.72 and within 3 at 0.52)."""


def pipes_step(pipes: Pipes, bed, state: PipesState, dt: float) -> PipesState:
    """One step of the virtual pipes (module doc).

    Parameters
    ----------
    pipes : Pipes
    bed : array_like (ny, nx)
        m.
    state : PipesState
    dt : float
        s, > 0 (stable to :func:`pipes_courant` 0.7 in 1-D, 0.5 in 2-D, measured).

    Returns
    -------
    PipesState
    """
    b = _checked(pipes, bed, state, dt)
    return _stepper(pipes, b, dt).advance(state, 1)


def _pipes_run(pipes: Pipes, bed, state: PipesState, steps: int, dt: float) -> PipesState:
    """``steps`` steps of ``dt`` (one compiled scan).

    Parameters
    ----------
    pipes : Pipes
    bed : array_like (ny, nx)
    state : PipesState
    steps : int
        ≥ 1.
    dt : float
        s, > 0.

    Returns
    -------
    PipesState

    Examples
    --------
    >>> import numpy as np
    >>> bed = np.zeros((1, 32)); depth = np.where(np.arange(32) < 16, 1.0, 0.5)[None]
    >>> end = pipes_run(Pipes(0.1), bed, pipes_state(bed, depth=depth), 50, 0.005)
    >>> round(float(end.depth.sum()), 4)
    24.0
    """
    b = _checked(pipes, bed, state, dt)
    steps = check_int("steps", steps, lo=1)
    stepper = _stepper(pipes, b, dt)
    out = stepper.advance(state, steps)
    return out if is_traced(out.depth) else stepper._result(out)  # water deepened past the limit: refused


def pipes_courant(pipes: Pipes, depth_max: float, dt: float) -> float:
    """The nominal Courant number c·Δt/l of a step, c = √(g·A/l) (A at ``depth_max`` for ``area="depth"``).

    Nominal: waves that reverse run √2 faster (module doc); the measured limits are 0.7 (1-D) and 0.5 (2-D)
    of this number.

    Parameters
    ----------
    pipes : Pipes
    depth_max : float
        m, ≥ 0.
    dt : float
        s, > 0.

    Returns
    -------
    float
    """
    check_instance("pipes", pipes, Pipes, "wavephys.models.pipes.Pipes")
    check_scalar("depth_max", depth_max, lo=0.0)
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    area = pipes.dx * float(depth_max) if isinstance(pipes.area, str) else float(pipes.area)
    return float(np.sqrt(float(pipes.g) * area / float(pipes.dx)) * float(dt) / float(pipes.dx))


pipes_run = deprecated_function(
    _pipes_run, "pipes_run",
    "wavephys.steppers.PipesStepper(pipes, bed, dt).run(state, steps=...) (the pure form: .advance)")


class PipesStepper(Stepper):
    """The virtual pipes (:mod:`wavephys.models.pipes`) at a fixed ``dt``, refused past the measured Courant
    limit.

    Parameters
    ----------
    pipes : Pipes
    bed : array_like (ny, nx)
        m.
    dt : float
        s, > 0.
    """

    def __init__(self, pipes, bed, dt: float):

        check_instance("pipes", pipes, Pipes, "wavephys.models.pipes.Pipes")
        check_array("bed", bed, ndim=2)
        self.pipes, self.bed = pipes, _bed(bed)
        self.dt = dt if is_traced(dt) else check_scalar("dt", dt, lo=0.0, lo_open=True)
        self.state_type = PipesState

    def init(self, state):
        state = self._checked_state(state)
        _checked(self.pipes, self.bed, state, self.dt)  # shapes, finite, the Courant limit at this Δt
        return state

    def _parts(self):
        return None, (self.pipes, jnp.asarray(self.bed), self.dt)

    def _check_dt(self, state, dt):
        return _fixed_dt(self, self.dt, dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        """One step; past the measured Courant limit at this step's deepest water the state turns NaN (the pipes
        keep depths ≥ 0 whatever Δt, so a step past the limit would otherwise answer plausible depths: under a
        trace nothing can be refused, and a concrete run stops there and is refused by :meth:`_result`)."""
        pipes, bed, _ = dynamic
        depth, flows = _advance(pipes, bed.astype(state.depth.dtype), state.depth, state.flows, dt)
        area = pipes.area if pipes._constant else pipes.dx * jnp.max(state.depth)
        courant = jnp.sqrt(pipes.g * area / pipes.dx) * dt / pipes.dx
        limit = COURANT_LIMITS[0 if min(state.depth.shape) == 1 else 1] * (1 + 1e-5)  # as the checks: no rounding
        poison = jnp.where(courant > limit, jnp.asarray(np.nan, depth.dtype), 0.0)  # added: jax.grad sees NaN too
        return type(state)(depth + poison, flows + poison, state.time + dt)

    def _result(self, state):
        if not bool(self._finite(state)):
            raise ValueError(f"PipesStepper: the run became non-finite by t = {float(state.time):.6g} s: the water "
                             f"grew deep enough that dt = {float(self.dt):.4g} s passed the pipes' stable Courant "
                             f"number √(gh)·dt/dx (COURANT_LIMITS, {COURANT_LIMITS}); make the stepper with a "
                             f"shorter dt")
        return state

    @classmethod
    def _dt(cls, static, dynamic, state):
        return jnp.asarray(dynamic[2], state.depth.dtype)

    @classmethod
    def _height(cls, static, dynamic, state):
        return dynamic[1].astype(state.depth.dtype) + state.depth

    @property
    def sides(self):
        return (self.pipes.sides,) * 4
