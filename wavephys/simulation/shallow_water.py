r"""Nonlinear shallow water with wetting and drying: a well-balanced, positive finite-volume solver.

The equations (docs/physics.md §1.13), with b the bed elevation (m, z up), h ≥ 0 the depth and
η = b + h the surface:

    h_t + ∇·(h u) = 0,      (h u)_t + ∇·(h u ⊗ u + ½ g h² I) = −g h ∇b.

Cells of side ``dx`` hold averages of (h, h u, h v). Each face gets a flux from the HLL
approximate Riemann solver applied to the *hydrostatic reconstruction* of Audusse et al. (2004):
the two sides' depths are cut to the higher of their two beds, h* = max(0, h + b − max(b_L, b_R)),
and the pressure difference that cut removes is put back as a source on each side. Three
properties follow and are tested (tests/simulation/test_shallow_water.py):

* **well balanced** — a lake at rest (η constant, u = 0) over any bed, dry islands included,
  stays at rest to rounding;
* **positive** — h ≥ 0 when Δt ≤ C·dx / max(|u| + √(gh) + |v| + √(gh)) with C ≤ ½ (each step's
  stages are forward-Euler steps of a positive scheme);
* **conservative** — the water changes only by what crosses an open or inflow side.

``order=2`` reconstructs h, η and the velocities linearly in each wet cell, the shoreline's too
(minmod slopes; a lake at rest has η's slope 0, so a shoreline at rest stays at rest) with a
cell-centred bed source that keeps the balance (Audusse et al. 2004, §4), and steps with Heun's
method (SSP RK2); ``order=1`` is piecewise constant with forward Euler.

What it neglects: dispersion (every wave runs at √(gh): right for kh ≲ 0.3), vertical
accelerations, friction, viscosity, and breaking (a bore is a shock that conserves mass and
momentum; real breaking starts near H/h ≈ 0.78 and is out of this model).

References
----------
E. Audusse, F. Bouchut, M.-O. Bristeau, R. Klein & B. Perthame (2004). A fast and stable
well-balanced scheme with hydrostatic reconstruction for shallow water flows. *SIAM J. Sci.
Comput.* 25(6), 2050–2065. A. Harten, P. D. Lax & B. van Leer (1983). On upstream differencing
and Godunov-type schemes for hyperbolic conservation laws. *SIAM Review* 25(1), 35–61.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Optional

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.aliases import deprecated_function
from wavephys.core.stepper import Stepper, _bed
from wavephys.core.inputs import (check_array, check_state_dtype, check_instance, check_int, check_scalar, describe,
                                  is_traced)
from wavephys.core.pytree import register
from wavephys.physics.shallow_water import water_depth
from wavephys.physics.walls import SIDES

__all__ = ["ShallowWater", "ShallowWaterStepper", "Inflow", "Open", "SWState", "sw_state", "stable_dt", "sw_step", "sw_run", "sw_frames",
           "sw_mass", "sw_surface", "SIDE_KINDS", "advance_fields", "stable_dt_fields", "check_run"]

SIDE_KINDS = ("wall", "open", "periodic", "inflow")
"""What a side of the domain can be: a reflecting wall, an open side (:class:`Open`: a sea at rest
outside, which outgoing waves leave into), periodic (with the opposite side), or an :class:`Inflow` (a
given surface and velocity outside)."""


@dataclass(frozen=True)
class Open:
    """An open side: the water outside is a sea at rest at ``level``; waves leave through the side.

    The ghost cells take the outgoing Riemann invariant u·n + 2√(gh) from the edge cell and the incoming
    one from the sea at rest outside, −2√(g h_sea) (a characteristic, absorbing condition: a long wave at
    normal incidence leaves without reflection in the linear limit; docs/physics.md §1.13). Flow leaving
    faster than √(gh) takes the edge cell's state. A lake at rest at the sea's level stays at rest to
    rounding over any bed.

    Parameters
    ----------
    level : float or array_like, optional
        The sea's surface outside, m (same datum as the bed): one value, or one per cell along the side
        (rows for ``left``/``right``, columns for ``bottom``/``top``). ``None`` (the default, and the
        plain string ``"open"``): the surface on the side's edge cells when a run starts
        (:meth:`ShallowWater.settle`).

    Examples
    --------
    >>> solver = ShallowWater(0.05, sides={"left": Open(level=0.0)})
    >>> solver.sides
    ('open', 'wall', 'wall', 'wall')
    """

    level: Any = None
    depth: Any = field(default=None, repr=False)
    """The sea's depth over each edge cell's bed, m (set by :meth:`ShallowWater.settle`)."""

    def __post_init__(self):
        if self.level is not None and not is_traced(self.level):
            if np.ndim(self.level) == 0:
                check_scalar("level", self.level)
            else:
                check_array("level", self.level, ndim=1)
        if self.depth is not None and not is_traced(self.depth):
            check_array("depth", self.depth, ndim=1, lo=0.0)


register(Open, ("level", "depth"))


@dataclass(frozen=True)
class Inflow:
    """A side where the water outside is given: its surface η(t) and its velocity into the domain u(t).

    Between the listed times the values are interpolated linearly; before the first and after
    the last they are held. The same values hold along the whole side.

    Parameters
    ----------
    times : array_like (T,)
        s, increasing, T ≥ 2.
    eta : array_like (T,)
        Surface elevation outside the side, m (same datum as the bed).
    u : array_like (T,), optional
        Velocity into the domain, m/s (default 0).

    Examples
    --------
    >>> import numpy as np
    >>> t = np.linspace(0.0, 10.0, 101)
    >>> tide = Inflow(t, 0.1 * np.sin(t))
    """

    times: Any
    eta: Any
    u: Any = None

    def __post_init__(self):
        if any(isinstance(v, jax.core.Tracer) for v in (self.times, self.eta, self.u)):
            return
        check_array("times", self.times, ndim=1)
        t = np.asarray(self.times, np.float64)
        if t.size < 2 or not np.all(np.diff(t) > 0):
            raise ValueError(f"times must increase and hold at least 2 values, got {t.size} values")
        check_array("eta", self.eta, ndim=1, shape_tail=t.shape)
        u = np.zeros_like(t) if self.u is None else self.u
        check_array("u", u, ndim=1, shape_tail=t.shape)
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "eta", np.asarray(self.eta, np.float64))
        object.__setattr__(self, "u", np.asarray(u, np.float64))

    def at(self, t):
        """(η, u) at time t (linear interpolation; held outside the table).

        Parameters
        ----------
        t : float
            s (a tracer inside the solver's step).

        Returns
        -------
        (jax.Array, jax.Array)
            m and m/s.
        """
        check_scalar("t", t)
        return jnp.interp(t, self.times, self.eta), jnp.interp(t, self.times, self.u)


register(Inflow, ("times", "eta", "u"))


@dataclass(frozen=True)
class ShallowWater:
    """The finite-volume shallow-water solver's settings (a pytree: ``dx``, ``g``, ``cfl``, ``dry``
    and the inflow tables are leaves; the side kinds and the order are static).

    Parameters
    ----------
    dx : float
        Cell size, m, > 0 (square cells; a field is (ny, nx) with x along the last axis).
    sides : str, or mapping side → kind, or 4-tuple
        Each of ``left`` (x min), ``right`` (x max), ``bottom`` (row 0), ``top`` (last row):
        ``"wall"``, ``"open"`` (an :class:`Open` side whose sea is at the level the run starts with there),
        an :class:`Open` with its level, ``"periodic"`` (both sides of the axis) or an :class:`Inflow`.
        A single value sets all four; a mapping leaves the sides it omits as walls.
    g : float
        Gravity, m/s², > 0.
    cfl : float
        Courant number C of the adaptive step, Δt = C·dx / max(|u| + c + |v| + c), in (0, 1]: h ≥ 0 is
        guaranteed for C ≤ 0.5 in 1-D and measured to C = 1 on dam breaks and Thacker's bowl; past 1 order 1
        makes negative depths (1.2) and order 2 blows up (1.5), so larger values are refused (default 0.45).
    dry : float
        Depth below which a cell counts as dry (no velocity), m, ≥ 0 (default 1e-6).
    order : {1, 2}
        Spatial order of the reconstruction (and Euler / Heun in time).

    Examples
    --------
    >>> solver = ShallowWater(0.05, sides={"left": "open"})
    >>> solver.sides
    ('open', 'wall', 'wall', 'wall')
    """

    dx: float
    sides: Any = "wall"
    g: float = 9.81
    cfl: float = 0.45
    dry: float = 1e-6
    order: int = 2
    inflows: tuple = field(default=(None, None, None, None), init=False, repr=False)

    def __post_init__(self):
        if isinstance(self.dx, jax.core.Tracer):
            return
        check_scalar("dx", self.dx, lo=0.0, lo_open=True)
        check_scalar("g", self.g, lo=0.0, lo_open=True)
        check_scalar("cfl", self.cfl, lo=0.0, hi=1.0, lo_open=True)
        check_scalar("dry", self.dry, lo=0.0)
        order = check_int("order", self.order, lo=1, hi=2)
        for name in ("dx", "g", "cfl", "dry"):  # Python floats: weakly typed under jit, so a float32 state stays so
            object.__setattr__(self, name, float(getattr(self, name)))
        kinds, inflows = _normalize_sides(self.sides)
        object.__setattr__(self, "sides", kinds)
        object.__setattr__(self, "inflows", inflows)
        object.__setattr__(self, "order", order)

    @property
    def settled(self) -> bool:
        """Whether every open side knows its sea's depth (:meth:`settle`)."""
        return all(not isinstance(o, Open) or o.depth is not None for o in self.inflows)

    def settle(self, bed, state) -> "ShallowWater":
        """This solver with each open side's sea fixed: from its ``level``, or, for ``level=None``, from
        the surface on the side's edge cells in ``state`` (the runs call it on their starting state; call
        it once yourself before a loop of :func:`sw_step`).

        Parameters
        ----------
        bed : array_like (ny, nx)
            Bed elevation, m.
        state : SWState
            The state the run starts from.

        Returns
        -------
        ShallowWater
            The same settings, every open side settled (unchanged when there is none).
        """
        if all(not isinstance(o, Open) for o in self.inflows):
            return self
        b = _checked(self, bed, state)
        h = state.fields[0]
        edges = ((h[:, 0], b[:, 0]), (h[:, -1], b[:, -1]), (h[0], b[0]), (h[-1], b[-1]))
        outside = []
        for side, o, (he, be) in zip(SIDES, self.inflows, edges):
            if isinstance(o, Open) and o.depth is None:
                if o.level is None:
                    depth = he
                else:
                    level = jnp.asarray(o.level, h.dtype)
                    if level.ndim and level.shape != he.shape:
                        raise ValueError(f"sides[{side!r}]: an Open level along the side needs {he.shape[0]} "
                                         f"values (one per edge cell), got {level.shape[0]}")
                    depth = jnp.maximum(level - be, 0.0)
                o = Open(o.level, depth)
            outside.append(o)
        settled = object.__new__(ShallowWater)
        for name in ("dx", "g", "cfl", "dry", "order", "sides"):
            object.__setattr__(settled, name, getattr(self, name))
        object.__setattr__(settled, "inflows", tuple(outside))
        return settled


register(ShallowWater, ("dx", "g", "cfl", "dry", "inflows"), ("sides", "order"))


def _past_limit(solver: ShallowWater, cfl: float) -> ShallowWater:
    """``solver`` with a Courant number past the stable range (≤ 2) that the settings refuse: only for
    measuring where the scheme fails (wavephys.checks.shallow_water)."""
    check_scalar("cfl", cfl, lo=0.0, hi=2.0, lo_open=True)
    copy = object.__new__(ShallowWater)
    for name in ("dx", "g", "dry", "order", "sides", "inflows"):
        object.__setattr__(copy, name, getattr(solver, name))
    object.__setattr__(copy, "cfl", float(cfl))
    return copy


def _normalize_sides(sides):
    if isinstance(sides, (str, Inflow, Open)):
        values = [sides] * 4
    elif isinstance(sides, dict):
        unknown = set(sides) - set(SIDES)
        if unknown:
            raise ValueError(f"sides: unknown side {sorted(unknown)[0]!r}; the sides are {list(SIDES)}")
        values = [sides.get(s, "wall") for s in SIDES]
    elif isinstance(sides, (tuple, list)):
        if len(sides) != 4:
            raise ValueError(f"sides must give 4 sides {SIDES}, got {len(sides)}")
        values = list(sides)
    else:
        raise TypeError(f"sides must be a string, a mapping side → kind or a 4-tuple, got {describe(sides)}")
    kinds, inflows = [], []
    for side, v in zip(SIDES, values):
        if isinstance(v, Inflow):
            kinds.append("inflow")
            inflows.append(v)
        elif isinstance(v, Open) or (isinstance(v, str) and v == "open"):
            kinds.append("open")
            inflows.append(v if isinstance(v, Open) else Open())
        elif isinstance(v, str) and v in SIDE_KINDS and v != "inflow":
            kinds.append(v)
            inflows.append(None)
        elif isinstance(v, str):
            raise ValueError(f"sides[{side!r}] must be 'wall', 'open', 'periodic', an Open or an Inflow, got {v!r}")
        else:
            raise TypeError(f"sides[{side!r}] must be 'wall', 'open', 'periodic', an Open or an Inflow, got "
                            f"{describe(v)}")
    for a, b in ((0, 1), (2, 3)):
        if (kinds[a] == "periodic") != (kinds[b] == "periodic"):
            raise ValueError(f"sides: {SIDES[a]} and {SIDES[b]} must both be periodic or neither, got "
                             f"{kinds[a]!r} and {kinds[b]!r}")
    return tuple(kinds), tuple(inflows)


@dataclass(frozen=True)
class SWState:
    """Depth and discharges on the cells (make one with :func:`sw_state`).

    Parameters
    ----------
    fields : array (3, ny, nx), or (..., 3, ny, nx) for a stack of states
        Depth h (m, ≥ 0), discharges h·u and h·v (m²/s), stacked.
    time : float, or array of the fields' leading shape
        s.
    """

    fields: jax.Array
    time: jax.Array

    def __post_init__(self):
        if isinstance(self.fields, jax.core.Tracer) or isinstance(self.time, jax.core.Tracer):
            return
        check_array("fields", self.fields, min_ndim=3)
        shape = np.shape(self.fields)
        if shape[-3] != 3:
            raise ValueError(f"fields must stack (h, hu, hv), shape (..., 3, ny, nx), got {shape}")
        values = np.asarray(self.fields)
        if not np.all(np.isfinite(values)):
            raise ValueError("fields hold NaN or inf values: a state must be finite (a run that went non-finite "
                             "is refused where it happens)")
        if float(np.min(values[..., 0, :, :])) < 0:
            raise ValueError("fields: the depth h (fields[..., 0, :, :]) must be >= 0 everywhere")
        check_array("time", self.time)
        if np.shape(self.time) != shape[:-3]:
            raise ValueError(f"time must have the shape of the fields' leading axes {shape[:-3]}, got "
                             f"{np.shape(self.time)}")

    @property
    def h(self):
        """Depth, m."""
        return self.fields[..., 0, :, :]

    @property
    def hu(self):
        """Discharge along x, m²/s."""
        return self.fields[..., 1, :, :]

    @property
    def hv(self):
        """Discharge along y, m²/s."""
        return self.fields[..., 2, :, :]


register(SWState, ("fields", "time"))


def sw_state(bed, eta=None, *, depth=None, u=None, v=None, time: float = 0.0, dtype=jnp.float32) -> SWState:
    """A :class:`SWState` from the bed and either the surface η or the depth h.

    Parameters
    ----------
    bed : array_like (ny, nx)
        Bed elevation b, m.
    eta : float or array_like (ny, nx), optional
        Surface elevation; the depth is max(η − b, 0) (land above η stays dry).
    depth : array_like (ny, nx), optional
        Depth h ≥ 0 instead of ``eta``.
    u, v : array_like (ny, nx), optional
        Velocities, m/s (default 0; zero where dry).
    time : float
        s.
    dtype : float32 or float64

    Returns
    -------
    SWState

    Examples
    --------
    >>> import numpy as np
    >>> x = np.linspace(-1, 1, 8)
    >>> state = sw_state(np.tile(0.3 * x, (2, 1)), 0.0)
    >>> float(state.h.max()) > 0 and float(state.h.min()) == 0
    True
    """
    h = water_depth(bed, eta, depth)
    shape = h.shape
    fields = [h]
    for name, vel in (("u", u), ("v", v)):
        vel = np.zeros(shape) if vel is None else np.asarray(check_array(name, vel, ndim=2, shape_tail=shape),
                                                             np.float64)
        fields.append(h * vel)
    check_scalar("time", time)
    dtype = check_state_dtype("dtype", dtype)
    return SWState(jnp.asarray(np.stack(fields), dtype), jnp.asarray(time, dtype))


def sw_mass(state: SWState, dx: float):
    """Water volume Σ h·dx², m³ (per batch member).

    Parameters
    ----------
    state : SWState
        One state, or a stack of them (fields (..., 3, ny, nx)).
    dx : float
        Cell size, m, > 0.

    Returns
    -------
    array
        m³: a scalar, or one per stacked state.
    """
    check_instance("state", state, SWState, "wavephys.simulation.shallow_water.SWState")
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    if isinstance(state.fields, jax.core.Tracer):
        return jnp.sum(state.h, axis=(-2, -1)) * dx * dx
    return np.sum(np.asarray(state.h, np.float64), axis=(-2, -1)) * float(dx) ** 2  # float64: no overflow


def sw_surface(state: SWState, bed):
    """The surface η = b + h where wet; the bed where dry (the height field a renderer draws).

    Parameters
    ----------
    state : SWState
        One state, or a stack of them.
    bed : array_like (ny, nx)
        m.

    Returns
    -------
    jax.Array
        m, the state's shape without its field axis.
    """
    check_instance("state", state, SWState, "wavephys.simulation.shallow_water.SWState")
    check_array("bed", bed, ndim=2, shape_tail=np.shape(state.fields)[-2:])
    return jnp.asarray(bed, state.fields.dtype) + state.h


# -- the scheme ------------------------------------------------------------------------------
def _safe_div(a, h, dry):
    wet = h > dry
    return jnp.where(wet, a / jnp.where(wet, h, 1.0), 0.0)


def _sqrt_gh(g, h):
    pos = h > 0
    return jnp.where(pos, jnp.sqrt(g * jnp.where(pos, h, 1.0)), 0.0)


def _ghost_index(n, kind, lo):
    """Indices of the 2 ghost cells on one side of an axis of n cells (left to right), and the
    sign of the normal discharge there."""
    if kind == "periodic":
        idx = [n - 2, n - 1] if lo else [0, 1]
        return [i % n for i in idx], 1.0
    if kind == "wall":
        idx = [1, 0] if lo else [n - 1, n - 2]
        return [min(max(i, 0), n - 1) for i in idx], -1.0
    idx = [0, 0] if lo else [n - 1, n - 1]  # open, inflow: the edge cell repeated
    return idx, 1.0


def _open_ghost(ghost, lo, axis, sea, g, dry):
    """The ghost cells (4, …) of an open side, from the edge cell repeated (``ghost``) and the sea's depth
    over each edge cell (``sea``, along the side): the outgoing invariant u·n + 2c from the edge, the
    incoming −2c_sea from the sea at rest; the edge's own state where the flow leaves supercritically.
    Written as c_g = c + (u·n − 2(c − c_sea))/4 so that at rest over the sea's depth the ghost is the edge
    cell bit for bit (a lake at rest stays so to rounding)."""
    h, hn, ht, b = ghost[0], ghost[1], ghost[2], ghost[3]
    sea = jnp.expand_dims(jnp.asarray(sea, h.dtype), axis)
    out = -1.0 if lo else 1.0  # the outward normal along the axis
    un = out * _safe_div(hn, h, dry)
    c, c_sea = _sqrt_gh(g, h), _sqrt_gh(g, sea)
    leaving = (un >= c) & (h > dry)
    cg = jnp.maximum(c + 0.25 * (un - 2.0 * (c - c_sea)), 0.0)
    ug = 0.5 * un + (c - c_sea)
    hg = jnp.maximum(h + (cg - c) * (cg + c) / g, 0.0)
    ug = jnp.where(leaving, un, jnp.where(hg > 0, ug, 0.0))
    hg = jnp.where(leaving, h, hg)
    vt = jnp.where(ug >= 0, _safe_div(ht, h, dry), 0.0)  # the tangential velocity leaves with the water
    return jnp.stack([hg, out * hg * ug, hg * vt, b])


def _pad_axis(q, axis, axis_sides, inflows, t, g=9.81, dry=0.0):
    """q: (4, ny, nx) = (h, normal discharge, tangential discharge, bed) for the faces across ``axis`` (−1: x,
    −2: y); returns q with two ghost cells at each end of that axis."""
    n = q.shape[axis]
    parts = []
    for lo, kind, inflow in ((True, axis_sides[0], inflows[0]), (False, axis_sides[1], inflows[1])):
        idx, sign = _ghost_index(n, kind, lo)
        ghost = jnp.take(q, jnp.asarray(idx), axis=axis)
        ghost = ghost.at[1].multiply(sign)
        if kind == "open":
            sea = inflow.depth
            if sea is None:  # a level given, not settled: the sea's depth over the edge's bed
                level = jnp.asarray(inflow.level, q.dtype)
                edge = jnp.take(q[3], 0 if lo else n - 1, axis=axis)
                sea = jnp.maximum(level - edge, 0.0)
            ghost = _open_ghost(ghost, lo, axis, sea, g, dry)
        if kind == "inflow":
            eta, u = (v.astype(q.dtype) for v in inflow.at(t))
            b = ghost[3]
            h = jnp.maximum(eta - b, 0.0)
            un = u if lo else -u
            ghost = jnp.stack([h, h * un, jnp.zeros_like(h), b])
        parts.append(ghost)
    return jnp.concatenate([parts[0], q, parts[1]], axis=axis)


def _minmod(a, b):
    return jnp.where(a * b > 0, jnp.sign(a) * jnp.minimum(jnp.abs(a), jnp.abs(b)), 0.0)


def _mean(a, b):
    """The unlimited (central) slope: the linear scheme that minmod limits."""
    return 0.5 * (a + b)


def _face_value(a, b, c, side, order, dry, limited=True):
    """The value at one face (``side`` = +1: the face towards c, −1: towards a) of the middle cell b of three
    consecutive cells a, b, c, each a tuple (h, normal discharge, tangential discharge, bed) of arrays:
    (h, bed, u, v) there. Written as a function of the three cells alone, so XLA fuses all of it into one
    loop over the faces (slicing intermediate arrays instead splits it into many kernels: ×4 slower)."""
    def prim(q):
        h, hn, ht, bed = q
        return h, h + bed, _safe_div(hn, h, dry), _safe_div(ht, h, dry)

    hb, eb, ub, vb = prim(b)
    if order == 1:
        return hb, eb - hb, ub, vb
    ha, ea, ua, va = prim(a)
    hc, ec, uc, vc = prim(c)
    # linear in every wet cell, the shoreline's included (η's slope is 0 in a lake at rest, so it stays at rest);
    # first order there let a backwash's sheet hold the run-up and drop at once (docs/physics.md §1.13)
    keep = hb > dry
    half = 0.5 * side * jnp.where(keep, 1.0, 0.0)
    slope = _minmod if limited else _mean
    h = hb + half * slope(hb - ha, hc - hb)
    eta = eb + half * slope(eb - ea, ec - eb)
    return h, eta - h, ub + half * slope(ub - ua, uc - ub), vb + half * slope(vb - va, vc - vb)


def _hll(g, hl, ul, vl, hr, ur, vr):
    """HLL fluxes (mass, normal momentum, tangential momentum) between two states, each an array."""
    cl, cr = _sqrt_gh(g, hl), _sqrt_gh(g, hr)
    sl = jnp.minimum(ul - cl, ur - cr)
    sr = jnp.maximum(ul + cl, ur + cr)
    ql, qr = hl * ul, hr * ur
    span = sr - sl
    ok = span > 0
    inv = 1.0 / jnp.where(ok, span, 1.0)
    upl, upr = sl >= 0, sr <= 0

    def pick(fl, fr, jump):
        mid = (sr * fl - sl * fr + sl * sr * jump) * inv
        return jnp.where(upl, fl, jnp.where(upr, fr, jnp.where(ok, mid, 0.0)))

    mass = pick(ql, qr, hr - hl)
    normal = pick(ql * ul + 0.5 * g * hl * hl, qr * ur + 0.5 * g * hr * hr, qr - ql)
    along = pick(ql * vl, qr * vr, hr * vr - hl * vl)
    return mass, normal, along


def _axis_rate(p, axis, g, dx, order, dry, walls, limited=True):
    """Rate of change (h, normal, tangential), each (ny, nx), from the fluxes across ``axis`` of a padded
    (4, …) array (two ghost cells each end of that axis); ``walls`` = (lo, hi) set the wall faces' mass flux
    to exactly 0."""
    n = p.shape[axis] - 4

    def cut(a, k, count):
        index = [slice(None)] * a.ndim
        index[axis] = slice(k, k + count)
        return a[tuple(index)]

    def face_fluxes(p):  # faces j = 0 … n between padded cells j+1 and j+2
        def cells(k, count):
            return tuple(cut(p[i], k, count) for i in range(4))

        lh, lb, lu, lv = _face_value(cells(0, n + 1), cells(1, n + 1), cells(2, n + 1), 1.0, order, dry, limited)
        rh, rb, ru, rv = _face_value(cells(1, n + 1), cells(2, n + 1), cells(3, n + 1), -1.0, order, dry, limited)
        top = jnp.maximum(lb, rb)
        hl = jnp.maximum(0.0, lh + lb - top)
        hr = jnp.maximum(0.0, rh + rb - top)
        return _hll(g, hl, lu, lv, hr, ru, rv) + (lh, hl, rh, hr)

    # a conditional is a boundary XLA does not fuse across: the face fluxes are computed once, in their own
    # loop, then differenced (fused into the difference, each face was recomputed per use: ×30 slower on CPU, measured at 256²).
    # g must be traced for it (the solver an argument of the compiled program, not a constant in it): XLA folds a
    # constant predicate away with the boundary (measured: 27 ms a step at 128² instead of 1)
    def nothing(p):  # never taken (g > 0): a branch as cheap as possible
        return (jnp.zeros_like(cut(p[0], 0, n + 1)),) * 7

    out = jax.lax.cond(g > 0, face_fluxes, nothing, p)
    mass, normal, along, lh, hl, rh, hr = out
    if walls[0] or walls[1]:
        shape = [1] * mass.ndim
        shape[axis] = n + 1
        open_face = jnp.ones((n + 1,), mass.dtype)
        if walls[0]:
            open_face = open_face.at[0].set(0.0)
        if walls[1]:
            open_face = open_face.at[-1].set(0.0)
        open_face = open_face.reshape(shape)
        mass, along = mass * open_face, along * open_face
    seen_left = normal + 0.5 * g * (lh * lh - hl * hl)  # what the cell on the low side of a face sees
    seen_right = normal + 0.5 * g * (rh * rh - hr * hr)  # … and the cell on its high side
    r_mass = -(cut(mass, 1, n) - cut(mass, 0, n)) / dx
    r_normal = -(cut(seen_left, 1, n) - cut(seen_right, 0, n)) / dx
    r_along = -(cut(along, 1, n) - cut(along, 0, n)) / dx
    if order == 2:  # the cell-centred bed source that keeps the second-order scheme balanced
        a, b, c = (tuple(cut(p[i], k, n) for i in range(4)) for k in (1, 2, 3))
        hm, bm, _, _ = _face_value(a, b, c, -1.0, order, dry, limited)
        hp, bp, _, _ = _face_value(a, b, c, 1.0, order, dry, limited)
        r_normal = r_normal + 0.5 * g * (hm + hp) * (bm - bp) / dx
    return r_mass, r_normal, r_along


def _rate(solver: ShallowWater, bed, fields, t, limited=True):
    """d/dt of (h, hu, hv): the fluxes across x and across y, both on the fields' own layout (no transposes:
    XLA on CPU fuses each axis's stencil into the sum; transposed, it recomputed the faces, ×15 slower)."""
    h, hu, hv = fields[0], fields[1], fields[2]
    ny, nx = h.shape
    out = jnp.zeros_like(fields)
    if nx > 1 or "inflow" in solver.sides[:2]:  # an axis one cell long: a 1-D problem along the other one
        p = _pad_axis(jnp.stack([h, hu, hv, bed]), -1, solver.sides[:2], solver.inflows[:2], t, solver.g,
                      solver.dry)
        r = _axis_rate(p, -1, solver.g, solver.dx, solver.order, solver.dry,
                       (solver.sides[0] == "wall", solver.sides[1] == "wall"), limited)
        out = out + jnp.stack([r[0], r[1], r[2]])
    if ny > 1 or "inflow" in solver.sides[2:]:
        p = _pad_axis(jnp.stack([h, hv, hu, bed]), -2, solver.sides[2:], solver.inflows[2:], t, solver.g,
                      solver.dry)
        r = _axis_rate(p, -2, solver.g, solver.dx, solver.order, solver.dry,
                       (solver.sides[2] == "wall", solver.sides[3] == "wall"), limited)
        out = out + jnp.stack([r[0], r[2], r[1]])
    return out


def _dry_out(fields, dry):
    h = fields[0]
    wet = h > dry
    return jnp.stack([h, jnp.where(wet, fields[1], 0.0), jnp.where(wet, fields[2], 0.0)])


def _advance(solver, bed, fields, t, dt, limited=True):
    """One step: forward Euler (order 1) or Heun's method, the strong-stability-preserving RK2 (order 2):
    u₁ = u + Δt L(u, t), u' = ½u + ½(u₁ + Δt L(u₁, t + Δt)), dry cells' discharges zeroed after each stage.

    The two stages are one loop of two turns, not two copies of the rate in the program: a stepper's compiled
    loop is about half as long (2 020 StableHLO lines against 3 760 at 32²; the split's, which also holds the
    step's linearization, 6 080 against 10 940) and compiles in 1.25 s against 1.74 (the split's 4.4 s against
    5.5; ``python -m bench shallow``, XLA's defaults, 2 cores), with the same arithmetic (the same results to
    the bit, measured) and the same speed (0.8 ms a step at 128², 2.8–3.0 ms at 256², either way)."""
    # the loop's state keeps the fields' dtype: a float64 Δt or bed with float32 fields (x64 on) is taken at the
    # fields' precision (written out, the step answered float64 fields)
    dt, bed = jnp.asarray(dt, fields.dtype), jnp.asarray(bed).astype(fields.dtype)
    if solver.order == 1:
        return _dry_out(fields + dt * _rate(solver, bed, fields, t, limited), solver.dry)

    def stage(i, u):
        first = i == 0
        moved = u + dt * _rate(solver, bed, u, jnp.where(first, t, t + dt), limited)
        return _dry_out(jnp.where(first, moved, 0.5 * fields + 0.5 * moved), solver.dry)

    return jax.lax.fori_loop(0, 2, stage, fields)


def _stable_dt(solver, fields, bed=None, t=None):
    """C·dx over the largest signal speed: the cells' |u| + c (+ |v| + c), and the water coming in at an inflow
    side (its |u| + 2c: a front running onto a dry bed), so a dry basin filled from a side is stepped safely."""
    h = fields[0]
    c = _sqrt_gh(solver.g, h)
    u = jnp.abs(_safe_div(fields[1], h, solver.dry))
    v = jnp.abs(_safe_div(fields[2], h, solver.dry))
    ny, nx = h.shape
    speed = (u + c) * (nx > 1) + (v + c) * (ny > 1)
    top = jnp.max(speed)
    if bed is not None:
        edges = (bed[:, 0], bed[:, -1], bed[0], bed[-1])
        for kind, inflow, edge in zip(solver.sides, solver.inflows, edges):
            if kind == "inflow":
                eta, u_in = inflow.at(t)
                depth = jnp.maximum(eta.astype(h.dtype) - edge, 0.0)
                top = jnp.maximum(top, jnp.max(jnp.abs(u_in.astype(h.dtype)) + 2 * _sqrt_gh(solver.g, depth)))
    return jnp.where(top > 0, solver.cfl * solver.dx / jnp.where(top > 0, top, 1.0), jnp.inf)


def _linear_advance(solver: ShallowWater, bed, fields, t, dt):
    """One step of Δt (s) of the solver's scheme with its slopes unlimited (central, no minmod) on raw fields
    (3, ny, nx): the linear scheme the second-order solver limits (order 1: the solver's own step), traced,
    without checks. Its Jacobian about still water is the solver's linearization for small waves, which the
    split's correction needs (:mod:`wavephys.simulation.split`): minmod's own derivative at still water is 0,
    the first-order scheme's, more diffusive than the solver on smooth waves."""
    return _advance(solver, bed, fields, t, dt, limited=False)


def advance_fields(solver: ShallowWater, bed, fields, t, dt):
    """One step of Δt on raw fields (3, ny, nx): the traced kernel under :func:`sw_step`, without its checks
    (for models built on the solver, such as :mod:`wavephys.simulation.split`). Under your own ``jax.jit``, pass
    the solver as an argument (it is a pytree), not as a constant closed over: with g a constant XLA folds away
    the boundary that keeps the face fluxes computed once, and the step is ×27 slower (measured at 128²).

    Parameters
    ----------
    solver : ShallowWater
    bed : jax.Array (ny, nx)
        Bed elevation, m, in the fields' dtype.
    fields : jax.Array (3, ny, nx)
        (h, hu, hv).
    t, dt : float or jax.Array
        Time and step, s: with concrete inputs a step past Courant number 1 (:func:`stable_dt_fields` over
        ``cfl``) is refused (ValueError naming ``dt``); under a trace only shapes are checked, and a step too
        long gives non-finite or negative depths.

    Returns
    -------
    jax.Array (3, ny, nx)
    """
    check_instance("solver", solver, ShallowWater, "wavephys.simulation.shallow_water.ShallowWater")
    check_array("bed", bed, ndim=2)
    check_array("fields", fields, ndim=3, shape_tail=(3,) + tuple(np.shape(bed)))
    check_scalar("t", t)
    check_scalar("dt", dt, lo=0.0, hi=1e6, lo_open=True)
    _check_settled(solver)
    _check_step(solver, bed, fields, t, dt)
    return _advance(solver, jnp.asarray(bed), jnp.asarray(fields), t, dt)


def stable_dt_fields(solver: ShallowWater, fields, bed=None, t=None):
    """:func:`stable_dt` on raw fields (3, ny, nx) (jit-able: under a trace only shapes are checked), s.

    Parameters
    ----------
    solver : ShallowWater
    fields : array_like (3, ny, nx)
        (h, hu, hv).
    bed : array_like (ny, nx), optional
        With it (and ``t``), the inflow sides count, as in :func:`stable_dt`.
    t : float, optional
        s.

    Returns
    -------
    jax.Array
    """
    check_instance("solver", solver, ShallowWater, "wavephys.simulation.shallow_water.ShallowWater")
    check_array("fields", fields, ndim=3)
    if np.shape(fields)[0] != 3:
        raise ValueError(f"fields must stack (h, hu, hv), shape (3, ny, nx), got {np.shape(fields)}")
    if bed is not None:
        check_array("bed", bed, ndim=2, shape_tail=np.shape(fields)[1:])
        bed = jnp.asarray(bed)
    if not is_traced(fields) and not np.all(np.isfinite(np.asarray(fields))):
        raise ValueError("fields hold NaN or inf values; no step is stable for them")
    if not is_traced(fields) and float(np.min(np.asarray(fields)[0])) < 0:
        raise ValueError("fields: the depth h (fields[0]) must be >= 0 everywhere")
    if t is not None:
        check_scalar("t", t)
    return _stable_dt(solver, jnp.asarray(fields), bed, t)


def _check_settled(solver):
    for side, o in zip(SIDES, solver.inflows):
        if isinstance(o, Open) and o.level is None and o.depth is None:
            raise ValueError(f"solver: the open side {side!r} takes its sea's level from the state a run starts "
                             f"with; call solver = solver.settle(bed, state) once before stepping, or give "
                             f"Open(level=...)")


def _checked(solver, bed, state):
    check_instance("solver", solver, ShallowWater, "wavephys.simulation.shallow_water.ShallowWater")
    check_instance("state", state, SWState, "wavephys.simulation.shallow_water.SWState")
    shape = np.shape(state.fields)
    if len(shape) != 3:
        raise ValueError(f"state.fields must have shape (3, ny, nx) (use jax.vmap for a batch), got {shape}")
    check_array("bed", bed, ndim=2, shape_tail=shape[1:])
    return jnp.asarray(bed, state.fields.dtype)


def stable_dt(solver: ShallowWater, state: SWState, bed=None):
    """The adaptive time step C·dx / max(|u| + √(gh) + |v| + √(gh)), s (inf for water at rest with no depth).

    Parameters
    ----------
    solver : ShallowWater
    state : SWState
    bed : array_like (ny, nx), optional
        Bed elevation, m: with it, the water coming in at inflow sides counts too (|u| + 2√(gh) there), as in
        the solver's own steps.

    Returns
    -------
    jax.Array
        s.
    """
    check_instance("solver", solver, ShallowWater, "wavephys.simulation.shallow_water.ShallowWater")
    check_instance("state", state, SWState, "wavephys.simulation.shallow_water.SWState")
    if np.ndim(state.fields) != 3:
        raise ValueError(f"state.fields must have shape (3, ny, nx) (use jax.vmap for a batch), got "
                         f"{np.shape(state.fields)}")
    if not is_traced(state.fields) and not np.all(np.isfinite(np.asarray(state.fields))):
        raise ValueError("state: the fields hold NaN or inf values; no step is stable for them")
    if bed is None:
        return _stable_dt(solver, state.fields)
    return _stable_dt(solver, state.fields, _checked(solver, bed, state), state.time)


@jax.jit
def _limit_program(solver, fields, bed, t):
    return _stable_dt(solver, fields, bed, t) / solver.cfl


def _check_step(solver, bed, fields, t, dt, name="dt"):
    """ValueError naming ``dt`` for a concrete step past Courant number 1 (the measured stable range: past it
    order 1 makes negative depths and order 2 blows up), or for fields that are not finite; nothing under a
    trace (there a step too long gives NaN or negative depths, refused when the run's result is read)."""
    if any(is_traced(v) for v in (fields, t, dt)):
        return
    if not np.all(np.isfinite(np.asarray(fields))):
        raise ValueError("state: the fields hold NaN or inf values; a step needs a finite state")
    limit = float(_limit_program(solver, jnp.asarray(fields), jnp.asarray(bed, fields.dtype), t))
    if float(dt) > limit * (1 + 1e-5):
        raise ValueError(f"{name} = {float(dt):.4g} s is past the stable step: Courant number {float(dt) / limit:.3g} "
                         f"> 1 (the largest stable step here is {limit:.4g} s; stable_dt gives {limit * solver.cfl:.4g} "
                         f"s at cfl = {solver.cfl:g}); take shorter steps, or leave dt out for adaptive ones")


def sw_step(solver: ShallowWater, bed, state: SWState, dt: Optional[float] = None) -> SWState:
    """One step: Δt = ``dt`` when given (no check of stability: see :func:`stable_dt`), else the adaptive one.

    Parameters
    ----------
    solver : ShallowWater
    bed : array_like (ny, nx)
        Bed elevation, m.
    state : SWState
    dt : float, optional
        s, > 0.

    Returns
    -------
    SWState
        At t + Δt. Pure: ``jax.jit``, ``jax.vmap`` and (with a fixed ``dt``) ``jax.grad`` apply.
    """
    b = _checked(solver, bed, state)
    _check_settled(solver)
    if dt is None:
        _check_step(solver, b, state.fields, state.time, 0.0)
    else:
        check_scalar("dt", dt, lo=0.0, lo_open=True)
        _check_step(solver, b, state.fields, state.time, dt)
    out = _stepper(solver, b).advance(state, 1, None if dt is None else jnp.asarray(dt, state.fields.dtype))
    fields, t = out.fields, out.time
    if not isinstance(fields, jax.core.Tracer):
        _check_result(solver, fields, t, dt)
    return SWState(fields, t)


def _stepper(solver, bed):
    """The solver behind the one stepper interface (wavephys.core.stepper): its loop is the runs' loop."""
    return ShallowWaterStepper(solver, bed)


def _run_to(solver, bed, fields, t, until, max_steps):
    """(fields, time, steps) after stable steps up to ``until`` (pure; the one loop of the steppers)."""
    end, n = _stepper(solver, bed).advance_to(SWState(fields, t), until, max_steps)
    return end.fields, end.time, n


def _sw_run(solver: ShallowWater, bed, state: SWState, until: Optional[float] = None, *, steps: Optional[int] = None,
           dt: Optional[float] = None, max_steps: int = 1_000_000):
    """Advance to time ``until`` with adaptive steps (the last one cut to land on it), or ``steps`` steps of ``dt``.

    Parameters
    ----------
    solver : ShallowWater
    bed : array_like (ny, nx)
        Bed elevation, m.
    state : SWState
    until : float, optional
        s, ≥ state.time. With adaptive steps (``jit``/``vmap`` apply; not ``grad``: use ``steps``).
    steps : int, optional
        Number of fixed steps of ``dt`` instead (``grad`` applies).
    dt : float, optional
        s, with ``steps``.
    max_steps : int
        Adaptive steps allowed before giving up (ValueError), ≥ 1.

    Returns
    -------
    (SWState, int)
        The state at the end, and the number of steps taken.

    Raises
    ------
    ValueError
        When the solution becomes non-finite (a Courant number above the stable range, ``cfl``) or
        ``max_steps`` is not enough.

    Examples
    --------
    >>> import numpy as np
    >>> bed = np.zeros((1, 64)); depth = np.where(np.arange(64) < 32, 1.0, 0.0)[None]
    >>> solver = ShallowWater(0.1)
    >>> end, n = sw_run(solver, bed, sw_state(bed, depth=depth), until=0.5)
    >>> round(float(end.time), 6), n > 10
    (0.5, True)
    """
    b = _checked(solver, bed, state)
    solver = solver.settle(b, state)
    if (until is None) == (steps is None):
        raise ValueError("give either until (adaptive steps) or steps and dt (fixed steps)")
    if steps is not None:
        steps = check_int("steps", steps, lo=1)
        if dt is None:
            raise ValueError("steps needs dt (s)")
        check_scalar("dt", dt, lo=0.0, lo_open=True)
        _check_step(solver, b, state.fields, state.time, dt)
        end = _stepper(solver, b).advance(state, steps, jnp.asarray(dt, state.fields.dtype))
        fields, t = end.fields, end.time
        if not isinstance(fields, jax.core.Tracer):
            _check_result(solver, fields, t, dt)
        return SWState(fields, t), steps
    if dt is not None:
        raise ValueError("dt is for fixed steps (with steps); adaptive steps (until) choose their own")
    check_scalar("until", until)
    max_steps = check_int("max_steps", max_steps, lo=1)
    if not (is_traced(state.time) or is_traced(until)) and float(until) < float(state.time):
        raise ValueError(f"until must not be before the state's time {float(state.time)}, got {until}")
    fields, t, n = _run_to(solver, b, state.fields, state.time, jnp.asarray(until, state.fields.dtype), max_steps)
    if not isinstance(fields, jax.core.Tracer):
        _check_result(solver, fields, t)
        if float(t) < float(np.asarray(until, np.asarray(t).dtype)):  # in the state's precision
            raise ValueError(f"max_steps = {max_steps} steps reached t = {float(t):.6g} s, not until = {until} s")
        n = int(n)
    return SWState(fields, t), n


def _sw_frames(solver: ShallowWater, bed, state: SWState, times, max_steps: int = 1_000_000) -> SWState:
    """The states at each of ``times`` (s, non-decreasing, ≥ state.time), stacked: fields (T, 3, ny, nx).

    Parameters
    ----------
    solver : ShallowWater
    bed : array_like (ny, nx)
    state : SWState
    times : array_like (T,)
    max_steps : int
        Adaptive steps allowed between two frames, ≥ 1.

    Returns
    -------
    SWState
        ``fields`` (T, 3, ny, nx), ``time`` (T,).
    """
    b = _checked(solver, bed, state)
    solver = solver.settle(b, state)
    check_array("times", times, ndim=1)
    ts = np.asarray(times, np.float64)
    if np.any(np.diff(ts) < 0) or ts[0] < float(state.time) - 1e-12:
        raise ValueError("times must be non-decreasing and not before the state's time")
    max_steps = check_int("max_steps", max_steps, lo=1)
    out = _stepper(solver, b).frames(state, ts, max_steps)
    fields, t = out.fields, out.time
    _check_result(solver, fields, t)
    if bool(jnp.any(t < jnp.asarray(ts, t.dtype))):
        raise ValueError(f"max_steps = {max_steps} steps were not enough between two frames")
    return SWState(fields, t)


def check_run(solver: ShallowWater, fields, t, dt=None) -> None:
    """ValueError naming ``cfl`` (or ``dt`` when given) for fields (..., 3, ny, nx) that went non-finite or
    negative in depth beyond rounding by time(s) ``t``.

    Parameters
    ----------
    solver : ShallowWater
    fields : array_like (..., 3, ny, nx)
    t : float or array_like
        s.
    dt : float, optional
        The fixed step of the run, s.
    """
    check_instance("solver", solver, ShallowWater, "wavephys.simulation.shallow_water.ShallowWater")
    if isinstance(fields, (str, bytes)) or fields is None or not np.issubdtype(np.asarray(fields).dtype, np.number):
        raise TypeError(f"fields must be an array of numbers, got {describe(fields)}")
    if np.ndim(fields) < 3 or np.shape(fields)[-3] != 3 or np.size(fields) == 0 or np.iscomplexobj(fields):
        raise ValueError(f"fields must stack (h, hu, hv), shape (..., 3, ny, nx), got {np.shape(fields)}")
    check_array("t", t)
    if dt is not None:
        check_scalar("dt", dt, lo=0.0, lo_open=True)
    try:
        _check_result(solver, fields, t, dt)
    except ValueError as error:
        raise ValueError(f"fields: {error}") from None


def _check_result(solver, fields, t, dt=None):
    """ValueError for a run that failed: non-finite values, or depths below −(rounding) (h ≥ 0 is
    guaranteed for cfl ≤ 0.5; beyond, a negative depth means the step was unstable)."""
    fields = np.asarray(fields)
    when = float(np.max(np.asarray(t)))
    depth = np.abs(fields[..., 0, :, :])
    scale = float(np.max(depth, where=np.isfinite(depth), initial=0.0))
    rounding = -1e3 * np.finfo(fields.dtype).eps * max(scale, 1e-30)
    if dt is not None and not (np.all(np.isfinite(fields)) and fields[..., 0, :, :].min() >= rounding):
        raise ValueError(f"dt = {float(dt):.4g} s is past the stable step (the depth went negative or non-finite "
                         f"by t = {when:.6g} s); stable_dt gives a safe one")
    if not np.all(np.isfinite(fields)):
        raise ValueError(f"the shallow-water solution became non-finite by t = {when:.6g} s "
                         f"(cfl = {float(solver.cfl):g}: stable to 1 measured, try a smaller one)")
    h = fields[..., 0, :, :]
    low = float(h.min())
    if low < rounding:
        cfl = float(solver.cfl)
        why = (f"cfl = {cfl:g}: h >= 0 is guaranteed for cfl <= 0.5, try a smaller one" if cfl > 0.5 else
               f"cfl = {cfl:g} keeps h >= 0 in the solver's own step, so the water was taken by something else: a "
               f"source, or a model around the solver")
        raise ValueError(f"the shallow-water solution made a negative depth ({low:.3g} m) by t = {when:.6g} s ({why})")


sw_run = deprecated_function(
    _sw_run, "sw_run",
    "wavephys.steppers.ShallowWaterStepper(solver, bed).run(state, until=...) (the pure forms: .advance, .advance_to)")


sw_frames = deprecated_function(
    _sw_frames, "sw_frames",
    "wavephys.steppers.ShallowWaterStepper(solver, bed).run(state, until=..., every=...) (the pure form: .frames)")


class ShallowWaterStepper(Stepper):
    """Nonlinear shallow water with wetting and drying (:mod:`wavephys.simulation.shallow_water`), adaptive
    steps at the solver's ``cfl``.

    Parameters
    ----------
    solver : wavephys.simulation.shallow_water.ShallowWater
    bed : array_like (ny, nx)
        Bed elevation, m (any ny, nx: rectangles are native).
    """

    adaptive = True

    def __init__(self, solver, bed):
        
        check_instance("solver", solver, ShallowWater, "wavephys.simulation.shallow_water.ShallowWater")
        check_array("bed", bed, ndim=2)
        self.solver, self.bed, self.state_type = solver, _bed(bed), SWState

    def init(self, state):
        state = self._checked_state(state)
        if np.shape(state.fields)[1:] != self.bed.shape or np.ndim(state.fields) != 3:
            raise ValueError(f"state.fields must have shape (3,) + the bed's {self.bed.shape}, got "
                             f"{np.shape(state.fields)}")
        # an open side's sea: from the first state this stepper starts from (then fixed)
        self.solver = self.solver.settle(self.bed, state)
        return state

    def _parts(self):
        return None, (self.solver, jnp.asarray(self.bed))

    def _limit(self, state):
        return float(_limit_program(self.solver, state.fields, jnp.asarray(self.bed, state.fields.dtype), state.time))

    def step(self, state, dt=None):
        self.init(state)
        return super().step(state, dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        solver, bed = dynamic
        fields = _advance(solver, bed.astype(state.fields.dtype), state.fields, state.time, dt)
        return type(state)(fields, state.time + dt)

    @classmethod
    def _dt(cls, static, dynamic, state):
        solver, bed = dynamic
        return _stable_dt(solver, state.fields, bed.astype(state.fields.dtype), state.time)

    @staticmethod
    def _with_time(state, t):
        return type(state)(state.fields, t)

    @classmethod
    def _height(cls, static, dynamic, state):
        return dynamic[1].astype(state.fields.dtype) + state.fields[0]

    def _result(self, state):
        _check_result(self.solver, state.fields, state.time)
        return state

    @property
    def sides(self):
        return tuple(self.solver.sides)
