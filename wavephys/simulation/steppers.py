r"""One interface for every way of stepping water in time (after diffrax's solvers: one small class per method).

Each stepper is a class holding its settings (and the bed or floor it runs over). All of them share

* :meth:`Stepper.init` — the state a run starts from, checked (and anything the method fixes from it: the
  sea outside an open side);
* :meth:`Stepper.step` — one step of the stepper's Δt (its fixed one, or the adaptive stable one), or of a
  given ``dt``, refused past the stable limit by name;
* :meth:`Stepper.run` — ``until=`` a time or ``steps=`` steps, keeping a frame (the surface η, m) every
  ``every`` steps or seconds and streaming each to a ``callback`` (nothing kept: memory stays flat) or
  returning the chosen frames stacked; never every step unless asked;
* :attr:`Stepper.sides` — the four sides (``left``, ``right``, ``bottom``, ``top``) in one vocabulary:
  ``"wall"``, ``"open"``, ``"periodic"``, ``"inflow"``;
* one clock: each state carries its time, s.

The loop is written once (:func:`_steps_program`, :func:`_until_program`): a compiled ``fori_loop`` of the
stepper's own step for a frame's steps, or a ``while_loop`` of stable steps with the last one cut to land on
the frame's time.

==================  =====================================  ========================  ==========================
class               method                                 state                     Δt
==================  =====================================  ========================  ==========================
``Spectral``        exact linear waves (:func:`step`)       :class:`State`            ``model.dt`` (any size)
``Depth``           a varying floor (levels, symmetric,     :class:`DepthState`       ``model.dt``
                    linear shallow water)
``ShallowWater``    nonlinear shallow water, wet/dry        :class:`SWState`          adaptive (``cfl``)
``SplitWater``      shallow water + dispersive waves        :class:`SWState`          adaptive
``VirtualPipes``    virtual pipes                           :class:`PipesState`       fixed ``dt``
``FiniteDiff``      the explicit wave equation              :class:`TwoLevelState`    fixed ``dt``
``Kernel``          truncated kernels (leapfrog)            :class:`TwoLevelState`    fixed ``dt``
==================  =====================================  ========================  ==========================

A stepper that cannot pose a problem refuses it by name (tests/simulation/test_steppers.py records each).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any, Callable, NamedTuple, Optional

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar, describe, is_traced
from wavephys.core.pytree import register

__all__ = ["Stepper", "Run", "TwoLevelState", "Spectral", "Depth", "ShallowWater", "SplitWater", "VirtualPipes",
           "FiniteDiff", "Kernel", "STEPPERS", "SIDE_KINDS"]

SIDE_KINDS = ("wall", "open", "periodic", "inflow")
"""The one vocabulary of sides: a reflecting wall, an open side (waves leave), periodic, or a given inflow."""


class Run(NamedTuple):
    """What :meth:`Stepper.run` returns.

    Attributes
    ----------
    state : Any
        The state at the end.
    times : numpy.ndarray (F,)
        s, the kept frames' times.
    frames : numpy.ndarray (F, ny, nx) or None
        The surface η at those times, m (None when a callback took them).
    """

    state: Any
    times: np.ndarray
    frames: Optional[np.ndarray]


@dataclass(frozen=True)
class TwoLevelState:
    """The heights at the last two steps (for the two-level schemes) and the time.

    Parameters
    ----------
    eta : array (ny, nx)
        η^n, m.
    eta_prev : array (ny, nx)
        η^{n−1}, m.
    time : float
        s.
    """

    eta: Any
    eta_prev: Any
    time: Any = 0.0

    def __post_init__(self):
        if any(is_traced(v) for v in (self.eta, self.eta_prev, self.time)):
            return
        check_array("eta", self.eta, ndim=2)
        check_array("eta_prev", self.eta_prev, ndim=2, shape_tail=np.shape(self.eta))
        check_scalar("time", self.time)
        object.__setattr__(self, "eta", jnp.asarray(self.eta))
        object.__setattr__(self, "eta_prev", jnp.asarray(self.eta_prev, jnp.asarray(self.eta).dtype))
        object.__setattr__(self, "time", jnp.asarray(self.time, jnp.asarray(self.eta).dtype))


register(TwoLevelState, ("eta", "eta_prev", "time"))


# -- the loop, written once ---------------------------------------------------------------------
@functools.partial(jax.jit, static_argnums=(0, 1, 4))
def _steps_program(cls, static, dynamic, state, steps, dt):
    """``steps`` steps (of ``dt``, or the stepper's own where it is NaN)."""
    def body(_, s):
        own = cls._dt(static, dynamic, s)
        return cls._advance(static, dynamic, s, jnp.where(jnp.isnan(dt), own, dt).astype(own.dtype))

    return jax.lax.fori_loop(0, steps, body, state)


@functools.partial(jax.jit, static_argnums=(0, 1))
def _until_program(cls, static, dynamic, state, until, max_steps):
    """Stable steps up to ``until`` (the last one cut to land on it)."""
    def cond(c):
        s, n = c
        return (cls._time(s) < until) & (n < max_steps) & cls._finite(s)

    def body(c):
        s, n = c
        t = cls._time(s)
        dt = jnp.minimum(cls._dt(static, dynamic, s), until - t)
        s = cls._advance(static, dynamic, s, dt)
        return cls._with_time(s, jnp.where(until - t <= dt, until, t + dt).astype(t.dtype)), n + 1

    return jax.lax.while_loop(cond, body, (state, jnp.asarray(0, jnp.int32)))


@functools.partial(jax.jit, static_argnums=(0, 1))
def _height_program(cls, static, dynamic, state):
    return cls._height(static, dynamic, state)


@functools.partial(jax.jit, static_argnums=(0, 1))
def _dt_program(cls, static, dynamic, state):
    return cls._dt(static, dynamic, state)


class Stepper:
    """The interface every stepper shares (module doc). Subclasses give the method's pieces as class methods
    of (static settings, array settings, state), so one compiled loop serves them all."""

    adaptive: bool = False
    """Whether Δt is chosen each step from the state (else the stepper's fixed ``dt``)."""
    state_type: type = object

    # -- what a method supplies ----------------------------------------------------------------
    def _parts(self):
        """(hashable static settings, pytree of arrays) handed to the class methods below."""
        raise NotImplementedError

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        raise NotImplementedError

    @classmethod
    def _dt(cls, static, dynamic, state):
        """The fixed step, or the adaptive stable one, s (traced)."""
        raise NotImplementedError

    @classmethod
    def _height(cls, static, dynamic, state):
        raise NotImplementedError

    @staticmethod
    def _time(state):
        return state.time

    @staticmethod
    def _with_time(state, t):
        return state

    @staticmethod
    def _finite(state):
        return jnp.all(jnp.asarray([jnp.all(jnp.isfinite(leaf)) for leaf in jax.tree_util.tree_leaves(state)]))

    def _limit(self, state):
        """The largest step this stepper takes stably from ``state``, s (concrete), or None when any Δt is."""
        return None

    def _checked_state(self, state):
        check_instance("state", state, self.state_type, f"{self.state_type.__module__}.{self.state_type.__name__}")
        return state

    def _result(self, state):
        """A ValueError for a run that went wrong (non-finite, negative depth); the state otherwise."""
        if not bool(self._finite(state)):
            raise ValueError(f"{type(self).__name__}: the run became non-finite by t = {float(self._time(state)):.6g} s")
        return state

    @property
    def sides(self) -> tuple:
        """The four sides (left, right, bottom, top), each one of :data:`SIDE_KINDS`."""
        raise NotImplementedError

    # -- the interface --------------------------------------------------------------------------
    def init(self, state):
        """The state a run starts from, checked (the stepper fixes anything it takes from it).

        Parameters
        ----------
        state
            A state of this stepper's kind (:attr:`state_type`).

        Returns
        -------
        The same state.
        """
        return self._checked_state(state)

    def step(self, state, dt: Optional[float] = None):
        """One step: of the stepper's own Δt (fixed, or adaptive), or of ``dt``.

        Parameters
        ----------
        state
            A state of this stepper's kind.
        dt : float, optional
            s, > 0: refused (ValueError naming ``dt``) past the stable step.

        Returns
        -------
        The state one step later.
        """
        state = self._checked_state(state)
        if dt is not None:
            dt = self._check_dt(state, dt)
        static, dynamic = self._parts()
        out = _steps_program(type(self), static, dynamic, state, 1, jnp.asarray(np.nan if dt is None else dt))
        return self._result(out)

    def _check_dt(self, state, dt):
        check_scalar("dt", dt, lo=0.0, lo_open=True)
        limit = self._limit(state)
        if limit is not None and float(dt) > limit * (1 + 1e-5):
            raise ValueError(f"dt = {float(dt):.4g} s is past the stable step of {type(self).__name__} "
                             f"({limit:.4g} s here); take shorter steps, or leave dt out")
        return float(dt)

    def run(self, state, until: Optional[float] = None, *, steps: Optional[int] = None, every=None,
            callback: Optional[Callable] = None, max_steps: int = 1_000_000) -> Run:
        """Advance to ``until`` (s) or by ``steps`` steps, keeping a frame every ``every``.

        Parameters
        ----------
        state
            Where the run starts (:meth:`init` is applied).
        until : float, optional
            s, ≥ the state's time. A fixed-Δt stepper needs a whole number of its steps.
        steps : int, optional
            ≥ 1, instead of ``until``.
        every : int or float, optional
            With ``steps``: a frame every this many steps (int ≥ 1); with ``until``: every this many
            seconds (> 0). Default: only the last frame.
        callback : callable, optional
            ``callback(index, time, eta)`` for each frame, on the host (η a NumPy array, m): nothing is kept,
            so memory stays flat over any run.
        max_steps : int
            Adaptive steps allowed between two frames, ≥ 1.

        Returns
        -------
        Run
            The end state, the frames' times, and the frames (None with a callback).

        Raises
        ------
        ValueError
            For a run that goes non-finite (or past the stable range), or a bad ``until``/``steps``/``every``.
        """
        state = self.init(state)
        if (until is None) == (steps is None):
            raise ValueError("give either until (s) or steps")
        if callback is not None and not callable(callback):
            raise TypeError(f"callback must be callable, got {describe(callback)}")
        max_steps = check_int("max_steps", max_steps, lo=1)
        static, dynamic = self._parts()
        cls = type(self)
        t0 = float(self._time(state))
        if steps is not None:
            steps = check_int("steps", steps, lo=1)
            every = steps if every is None else check_int("every", every, lo=1)
            counts = [every] * (steps // every) + ([steps % every] if steps % every else [])
            plan = [("steps", c) for c in counts]
        else:
            check_scalar("until", until)
            if float(until) < t0:
                raise ValueError(f"until must not be before the state's time {t0}, got {until}")
            span = float(until) - t0
            if every is None:
                marks = [float(until)]
            else:
                check_scalar("every", every, lo=0.0, lo_open=True)
                count = int(math.floor(span / float(every) + 1e-9))
                marks = [t0 + (i + 1) * float(every) for i in range(count)]
                if not marks or marks[-1] < float(until) - 1e-9 * max(1.0, abs(float(until))):
                    marks.append(float(until))
            if self.adaptive:
                plan = [("until", m) for m in marks]
            else:
                dt = float(cls._dt(static, dynamic, state))
                plan, done = [], 0
                for m in marks:
                    whole = (m - t0) / dt
                    if abs(whole - round(whole)) > 1e-6 * max(1.0, whole):
                        raise ValueError(f"until and every must be whole numbers of this stepper's Δt = {dt:g} s "
                                         f"(time {m:g} s is {whole:.6g} steps)")
                    if round(whole) > done:
                        plan.append(("steps", int(round(whole)) - done))
                        done = int(round(whole))
        times, frames = [], []
        nan = jnp.asarray(np.nan)
        for index, (kind, value) in enumerate(plan):
            if kind == "steps":
                state = _steps_program(cls, static, dynamic, state, value, nan)
            else:
                state, n = _until_program(cls, static, dynamic, state, jnp.asarray(value, self._time(state).dtype),
                                          jnp.asarray(max_steps, jnp.int32))
                if bool(self._finite(state)) and float(self._time(state)) < value * (1 - 1e-6) - 1e-12:
                    raise ValueError(f"max_steps = {max_steps} steps reached t = {float(self._time(state)):.6g} s, "
                                     f"not {value:g} s")
            state = self._result(state)
            t = float(self._time(state))
            eta = np.asarray(_height_program(cls, static, dynamic, state))
            if callback is not None:
                callback(index, t, eta)
            else:
                frames.append(eta)
            times.append(t)
        return Run(state, np.asarray(times), None if callback is not None else np.stack(frames))


# -- the steppers -------------------------------------------------------------------------------
def _fixed_dt(stepper, own: float, dt) -> float:
    """A fixed-Δt stepper takes only its own Δt (ValueError naming ``dt`` otherwise)."""
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    if abs(float(dt) - own) > 1e-9 * own:
        raise ValueError(f"dt: {type(stepper).__name__} steps its own dt = {own:g} s (make the stepper with the Δt "
                         f"you want), got {dt}")
    return float(dt)


class Spectral(Stepper):
    """Exact linear waves on the model's grid (:func:`wavephys.simulation.step`): any Δt, walls and tanks as
    the :class:`~wavephys.simulation.Model` has them; continuous sources (forcing) act in the loop.

    Parameters
    ----------
    model : Model
    sources : sequence, optional
        Continuous sources (a ``rate`` hook); impulses go in with :func:`~wavephys.simulation.add_source`.
    """

    def __init__(self, model, sources=()):
        from wavephys.simulation.model import Model
        from wavephys.simulation.sources import sort_sources

        check_instance("model", model, Model, "wavephys.simulation.Model")
        impulses, rates, adders = sort_sources(model, sources)
        if impulses or adders:
            raise ValueError("sources: the Spectral stepper takes continuous sources (forcing) only; add impulses "
                             "with add_source first, and step ships with wavephys.simulation.step")
        self.model, self.rates = model, tuple(rates)
        from wavephys.simulation.state import State
        self.state_type = State

    def _parts(self):
        from wavephys.simulation.model import operators
        return None, (self.model, operators(self.model), self.rates)

    def _checked_state(self, state):
        from wavephys.simulation.stepping import _check_state, _laid
        super()._checked_state(state)
        _check_state(self.model, state)
        return _laid(self.model, state)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        from wavephys.simulation.stepping import _dt_error, _pure_step
        model, ops, rates = dynamic
        return _pure_step(model, ops, state, (), rates, _dt_error(model))[0]

    @classmethod
    def _dt(cls, static, dynamic, state):
        return jnp.asarray(dynamic[0].dt, state.time.dtype)

    @classmethod
    def _height(cls, static, dynamic, state):
        from wavephys.simulation.stepping import _surface
        model, ops, _ = dynamic
        return _surface(model, ops, state.fields, state.time).eta

    def _check_dt(self, state, dt):
        return _fixed_dt(self, float(self.model.dt), dt)

    @property
    def sides(self):
        wx, wy = self.model.wall_axes
        x = "wall" if wx else ("open" if self.model.margin else "periodic")
        y = "wall" if wy else ("open" if self.model.margin else "periodic")
        return (x, x, y, y)


class Depth(Stepper):
    """Linear waves over a varying floor (:mod:`wavephys.simulation.depth`): ``method`` one of ``"levels"``,
    ``"symmetric"``, ``"shallow"``; Δt is the model's.

    Parameters
    ----------
    model : Model
    floor : Floor
    method : str
    """

    def __init__(self, model, floor, method: str = "levels"):
        from wavephys.simulation.depth import DEPTH_METHODS, DepthState, Floor
        from wavephys.simulation.model import Model

        check_instance("model", model, Model, "wavephys.simulation.Model")
        check_instance("floor", floor, Floor, "wavephys.simulation.depth.Floor")
        DEPTH_METHODS.check(method, "method")
        floor.check(model)
        self.model, self.floor, self.method, self.state_type = model, floor, method, DepthState

    def _parts(self):
        from wavephys.simulation import depth as d
        from wavephys.simulation.model import operators

        model, floor, method = self.model, self.floor, self.method
        mask = operators(model).mask
        if method == "symmetric" and d._is_one_level(floor):
            method = "levels"
        if method == "levels":
            if not float(floor.depth.min()) > 0:
                raise ValueError("floor: the levels method needs depth > 0 everywhere (dry land: method='shallow' "
                                 "or 'symmetric')")
            tables, weights, _ = d._level_tables(model, floor)
            return ("levels", 0), (model, (tables, weights, mask))
        if method == "symmetric":
            big_k, restoring, roots, substeps = d._symmetric_tables(model, floor)
            return ("symmetric", substeps), (model, (big_k, restoring, roots, mask))
        hx, hy, inv = (a.astype(model.dtype) for a in d._shore_geometry(floor.depth, model.wall_axes))
        return ("shallow", d.shallow_substeps(model, floor)), (model, (hx, hy, inv, mask))

    def _checked_state(self, state):
        from wavephys.simulation.depth import _check
        _check(self.model, self.floor, state)
        return state

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        from wavephys.simulation import depth as d
        kind, substeps = static
        model, args = dynamic
        if kind == "levels":
            new = d._levels_program(model.transform, model.inverse_transform, *args, state.fields)[0]
        elif kind == "symmetric":
            new = d._symmetric_program(model, *args, state.fields, substeps)[0]
        else:
            new = d._shallow_program(model, *args, state.fields, substeps)[0]
        return type(state)(new.astype(state.fields.dtype), state.time + model.dt)

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


class ShallowWater(Stepper):
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
        from wavephys.simulation import shallow_water as sw

        check_instance("solver", solver, sw.ShallowWater, "wavephys.simulation.shallow_water.ShallowWater")
        check_array("bed", bed, ndim=2)
        self.solver, self.bed, self.state_type = solver, np.asarray(bed, np.float64), sw.SWState

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
        from wavephys.simulation.shallow_water import _limit_program
        return float(_limit_program(self.solver, state.fields, jnp.asarray(self.bed, state.fields.dtype), state.time))

    def step(self, state, dt=None):
        self.init(state)
        return super().step(state, dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        from wavephys.simulation.shallow_water import _advance
        solver, bed = dynamic
        fields = _advance(solver, bed.astype(state.fields.dtype), state.fields, state.time, dt)
        return type(state)(fields, state.time + dt)

    @classmethod
    def _dt(cls, static, dynamic, state):
        from wavephys.simulation.shallow_water import _stable_dt
        solver, bed = dynamic
        return _stable_dt(solver, state.fields, bed.astype(state.fields.dtype), state.time)

    @staticmethod
    def _with_time(state, t):
        return type(state)(state.fields, t)

    @classmethod
    def _height(cls, static, dynamic, state):
        return dynamic[1].astype(state.fields.dtype) + state.fields[0]

    def _result(self, state):
        from wavephys.simulation.shallow_water import _check_result
        _check_result(self.solver, state.fields, state.time)
        return state

    @property
    def sides(self):
        return tuple(self.solver.sides)


class SplitWater(ShallowWater):
    """Shallow water with dispersive surface waves (:mod:`wavephys.simulation.split`), adaptive steps.

    Parameters
    ----------
    split : Split
    bed : array_like (ny, nx)
        m.
    """

    def __init__(self, split, bed):
        from wavephys.simulation.shallow_water import SWState
        from wavephys.simulation.split import Split

        check_instance("split", split, Split, "wavephys.simulation.split.Split")
        check_array("bed", bed, ndim=2)
        self.split, self.solver, self.bed, self.state_type = split, split.solver, np.asarray(bed, np.float64), SWState

    def init(self, state):
        state = self._checked_state(state)
        if np.shape(state.fields)[1:] != self.bed.shape or np.ndim(state.fields) != 3:
            raise ValueError(f"state.fields must have shape (3,) + the bed's {self.bed.shape}, got "
                             f"{np.shape(state.fields)}")
        return state

    def _parts(self):
        return self.split, jnp.asarray(self.bed)

    def _limit(self, state):
        from wavephys.simulation.split import _limit_program
        return float(_limit_program(self.split, state.fields))

    def step(self, state, dt=None):
        return Stepper.step(self, state, dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        from wavephys.simulation.split import _split_advance
        fields = _split_advance(static, dynamic.astype(state.fields.dtype), state.fields, state.time, dt)
        return type(state)(fields, state.time + dt)

    @classmethod
    def _dt(cls, static, dynamic, state):
        from wavephys.simulation.split import _split_dt
        return _split_dt(static, state.fields)

    @classmethod
    def _height(cls, static, dynamic, state):
        return dynamic.astype(state.fields.dtype) + state.fields[0]


class VirtualPipes(Stepper):
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
        from wavephys.models.pipes import Pipes, PipesState

        check_instance("pipes", pipes, Pipes, "wavephys.models.pipes.Pipes")
        check_array("bed", bed, ndim=2)
        self.pipes, self.bed, self.dt = pipes, np.asarray(bed, np.float64), check_scalar("dt", dt, lo=0.0,
                                                                                          lo_open=True)
        self.state_type = PipesState

    def init(self, state):
        from wavephys.models.pipes import _checked
        state = self._checked_state(state)
        _checked(self.pipes, self.bed, state, self.dt)  # shapes, finite, the Courant limit at this Δt
        return state

    def _parts(self):
        return None, (self.pipes, jnp.asarray(self.bed), self.dt)

    def _check_dt(self, state, dt):
        return _fixed_dt(self, self.dt, dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        from wavephys.models.pipes import _advance
        pipes, bed, _ = dynamic
        depth, flows = _advance(pipes, bed.astype(state.depth.dtype), state.depth, state.flows, dt)
        return type(state)(depth, flows, state.time + dt)

    @classmethod
    def _dt(cls, static, dynamic, state):
        return jnp.asarray(dynamic[2], state.depth.dtype)

    @classmethod
    def _height(cls, static, dynamic, state):
        return dynamic[1].astype(state.depth.dtype) + state.depth

    @property
    def sides(self):
        return (self.pipes.sides,) * 4


class _TwoLevel(Stepper):
    state_type = TwoLevelState

    @classmethod
    def _dt(cls, static, dynamic, state):
        return jnp.asarray(dynamic[-1], state.eta.dtype)

    @classmethod
    def _height(cls, static, dynamic, state):
        return state.eta

    def _check_dt(self, state, dt):
        return _fixed_dt(self, self.dt, dt)

    @property
    def sides(self):
        return ("periodic",) * 4


class FiniteDiff(_TwoLevel):
    """The explicit wave equation (:mod:`wavephys.models.finite_difference`): Courant number C = cΔt/Δx ≤ 1/√2,
    damping d, on a periodic grid.

    Parameters
    ----------
    courant : float
        C in (0, 1/√2].
    dt : float
        s, > 0 (the clock; the scheme itself sees only C).
    damping : float
        d in [0, 1).
    """

    def __init__(self, courant: float, dt: float, damping: float = 0.0):
        from wavephys.models.finite_difference import STABILITY_LIMIT
        check_scalar("courant", courant, lo=0.0, hi=STABILITY_LIMIT, lo_open=True)
        check_scalar("damping", damping, lo=0.0, hi=1.0, hi_open=True)
        self.courant, self.damping, self.dt = float(courant), float(damping), check_scalar("dt", dt, lo=0.0,
                                                                                         lo_open=True)

    def _parts(self):
        return None, (self.courant, self.damping, self.dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        from wavephys.models.finite_difference import fd_step
        courant, damping, _ = dynamic
        new = fd_step(state.eta, state.eta_prev, courant, damping)
        return TwoLevelState(new, state.eta, state.time + dt)


class Kernel(_TwoLevel):
    """Truncated kernels stepped by leapfrog (:mod:`wavephys.models.truncated_kernel`).

    Parameters
    ----------
    stencil : array_like (m, m)
        The kernel, 1/s² (from :func:`~wavephys.models.truncated_kernel.kernel_stencil`).
    dt : float
        s, > 0 (stable below the stencil's limit: :func:`~wavephys.models.truncated_kernel.kernel_stable_dt`).
    """

    def __init__(self, stencil, dt: float):
        check_array("stencil", stencil, ndim=2)
        self.stencil, self.dt = np.asarray(stencil), check_scalar("dt", dt, lo=0.0, lo_open=True)

    def _parts(self):
        return None, (jnp.asarray(self.stencil), self.dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        from wavephys.models.truncated_kernel import kernel_step
        stencil, _ = dynamic
        new = kernel_step(state.eta, state.eta_prev, stencil.astype(state.eta.dtype), dt)
        return TwoLevelState(new, state.eta, state.time + dt)


STEPPERS = {cls.__name__: cls for cls in (Spectral, Depth, ShallowWater, SplitWater, VirtualPipes, FiniteDiff,
                                          Kernel)}
"""Every stepper class by name (a new stepper is one class here plus its problems in the set)."""
