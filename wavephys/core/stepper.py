"""The stepper interface every way of stepping water shares, and its one compiled loop (after diffrax's
solvers: one small class per method).

A method is one class deriving from :class:`Stepper`, beside its scheme, that gives the method's pieces as
class methods of (static settings, array settings, state): ``_parts``, ``_advance``, ``_dt``, ``_height``
(and ``sides``). From them every stepper gets

* :meth:`Stepper.init` — the state a run starts from, checked (and anything the method fixes from it: the
  sea outside an open side);
* :meth:`Stepper.step` — one step of the stepper's Δt (its fixed one, or the adaptive stable one), or of a
  given ``dt``, refused past the stable limit by name;
* :meth:`Stepper.run` — ``until=`` a time or ``steps=`` steps, keeping a frame (the surface η, m) every
  ``every`` steps or seconds and streaming each to a ``callback`` (nothing kept: memory stays flat) or
  returning the chosen frames stacked; never every step unless asked;
* the pure :meth:`Stepper.advance`, :meth:`Stepper.advance_to`, :meth:`Stepper.frames` (``jit``, ``vmap``;
  ``grad`` through a fixed number of steps), and :meth:`Stepper.trajectory`, every step's state for the
  measurements that need them;
* :attr:`Stepper.sides` — the four sides (``left``, ``right``, ``bottom``, ``top``) in one vocabulary,
  :data:`SIDE_KINDS`; one clock: each state carries its time, s.

The loop is written once here: one compiled ``while_loop`` (``_loop_program``) of the stepper's own step or a
given Δt, up to a time (the last step cut to land on it) or a number of steps, both arguments, so one program
serves every step and run of a stepper; ``_steps_program``, the ``fori_loop`` of a static count, is the form
``jax.grad`` differentiates (:meth:`Stepper.advance` under a trace). The steppers themselves and their
registry: :mod:`wavephys.steppers`.
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

__all__ = ["Stepper", "Run", "TwoLevelState", "SIDE_KINDS"]

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
    eta : array (..., ny, nx)
        η^n, m (leading axes: a batch of fields stepped together).
    eta_prev : array (..., ny, nx)
        η^{n−1}, m, the shape of ``eta``.
    time : float
        s.
    """

    eta: Any
    eta_prev: Any
    time: Any = 0.0

    def __post_init__(self):
        if any(is_traced(v) for v in (self.eta, self.eta_prev, self.time)):
            return
        check_array("eta", self.eta, min_ndim=2)
        check_array("eta_prev", self.eta_prev, min_ndim=2, shape_tail=np.shape(self.eta))
        if np.ndim(self.eta_prev) != np.ndim(self.eta):
            raise ValueError(f"eta_prev must have eta's shape {np.shape(self.eta)}, got {np.shape(self.eta_prev)}")
        check_scalar("time", self.time)
        object.__setattr__(self, "eta", jnp.asarray(self.eta))
        object.__setattr__(self, "eta_prev", jnp.asarray(self.eta_prev, jnp.asarray(self.eta).dtype))
        object.__setattr__(self, "time", jnp.asarray(self.time, jnp.asarray(self.eta).dtype))


register(TwoLevelState, ("eta", "eta_prev", "time"))


# -- the loop, written once ---------------------------------------------------------------------
@functools.partial(jax.jit, static_argnums=(0, 1, 4, 6))
def _steps_program(cls, static, dynamic, state, steps, dt, keep=False):
    """``steps`` steps (of ``dt``, or the stepper's own where it is NaN), the count static: the form
    ``jax.grad`` differentiates (:meth:`Stepper.advance`); with ``keep``, ``(state, the states at each step's
    start stacked)`` (:meth:`Stepper.trajectory`)."""
    def one(s):
        own = cls._dt(static, dynamic, s)
        return cls._advance(static, dynamic, s, jnp.where(jnp.isnan(dt), own, dt).astype(own.dtype))

    if keep:
        return jax.lax.scan(lambda s, _: (one(s), s), state, None, length=steps)
    return jax.lax.fori_loop(0, steps, lambda _, s: one(s), state)


@functools.partial(jax.jit, static_argnums=(0, 1))
def _loop_program(cls, static, dynamic, state, until, max_steps, dt):
    """Steps of ``dt`` (the stepper's own where it is NaN) up to ``until`` (the last one cut to land on it; +inf:
    no end time) or ``max_steps`` steps, stopping at a state that is not finite: ``(state, steps taken)``.

    One program per stepper and settings serves a step, a run of so many steps and a run to a time: the counts
    and times are arguments, not constants compiled in (each was a program of its own, compiled again for
    each count: these loops took 28 % of the test suite's XLA compile time, measured)."""
    def cond(c):
        s, n = c
        return (cls._time(s) < until) & (n < max_steps) & cls._finite(s)

    def body(c):
        s, n = c
        t = cls._time(s)
        own = cls._dt(static, dynamic, s)
        step = jnp.minimum(jnp.where(jnp.isnan(dt), own, dt).astype(own.dtype), until - t)
        s = cls._advance(static, dynamic, s, step)
        return cls._with_time(s, jnp.where(until - t <= step, until, t + step).astype(t.dtype)), n + 1

    return jax.lax.while_loop(cond, body, (state, jnp.asarray(0, jnp.int32)))


def _until_program(cls, static, dynamic, state, until, max_steps):
    """Stable steps up to ``until`` (the last one cut to land on it): ``(state, steps taken)``."""
    dtype = jnp.asarray(cls._time(state)).dtype
    return _loop_program(cls, static, dynamic, state, jnp.asarray(until, dtype), jnp.asarray(max_steps, jnp.int32),
                         jnp.asarray(np.nan, dtype))


def _count_program(cls, static, dynamic, state, steps, dt):
    """``steps`` steps (of ``dt``, or the stepper's own where it is NaN), the count an argument; it stops early
    at a state that is not finite."""
    dtype = jnp.asarray(cls._time(state)).dtype  # strong dtypes: one compiled program for every call
    return _loop_program(cls, static, dynamic, state, jnp.asarray(np.inf, dtype), jnp.asarray(steps, jnp.int32),
                         jnp.asarray(dt, dtype))[0]


@functools.partial(jax.jit, static_argnums=(0, 1))
def _frames_program(cls, static, dynamic, state, times, max_steps):
    """The states at each of ``times`` (stable steps between them), stacked."""
    def body(s, until):
        s, _ = _until_program(cls, static, dynamic, s, until, max_steps)
        return s, s

    return jax.lax.scan(body, state, times)[1]


@functools.partial(jax.jit, static_argnums=(0, 1))
def _height_program(cls, static, dynamic, state):
    return cls._height(static, dynamic, state)


@functools.partial(jax.jit, static_argnums=(0, 1))
def _dt_program(cls, static, dynamic, state):
    return cls._dt(static, dynamic, state)


class Stepper:
    """The interface every stepper shares (module doc). Subclasses give the method's pieces as class methods
    of (static settings, array settings, state), so one compiled loop serves them all.

    Attributes
    ----------
    adaptive : bool
        Whether Δt is chosen each step from the state (else the stepper's fixed ``dt``).
    state_type : type
        The kind of state the stepper steps.
    sides : tuple of str
        The four sides (left, right, bottom, top), each one of :data:`SIDE_KINDS`.
    """

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
        out = _count_program(type(self), static, dynamic, state, 1, jnp.asarray(np.nan if dt is None else dt))
        return self._result(out)

    def _check_dt(self, state, dt):
        check_scalar("dt", dt, lo=0.0, lo_open=True)
        limit = self._limit(state)
        if limit is not None and float(dt) > limit * (1 + 1e-5):
            raise ValueError(f"dt = {float(dt):.4g} s is past the stable step of {type(self).__name__} "
                             f"({limit:.4g} s here); take shorter steps, or leave dt out")
        return float(dt)

    # -- pure forms (jit, vmap; grad through a fixed number of steps) ---------------------------------
    def advance(self, state, steps: int, dt=None):
        """``steps`` steps of the stepper's own Δt, or of ``dt``: the state after them (pure: ``jax.jit``,
        ``jax.vmap`` and, with a fixed Δt, ``jax.grad`` apply; a concrete ``dt`` past the stable step is refused
        by name, and :meth:`init`'s checks apply, but the run is not checked as :meth:`step`'s is; called with
        concrete arrays it stops at the first state that is not finite, whose time then says how far it got).

        Parameters
        ----------
        state
            A state of this stepper's kind (:meth:`init` applied).
        steps : int
            ≥ 1 (static).
        dt : float, optional
            s.

        Returns
        -------
        The state.
        """
        steps = check_int("steps", steps, lo=1)
        state = self.init(state)
        if dt is not None and not (is_traced(dt) or is_traced(state)):
            dt = self._check_dt(state, dt)  # past the stable step: refused by name
        static, dynamic = self._parts()
        dt = jnp.asarray(np.nan) if dt is None else jnp.asarray(dt)
        if any(is_traced(v) for v in jax.tree_util.tree_leaves((state, dt, dynamic))):
            return _steps_program(type(self), static, dynamic, state, steps, dt)  # jax.grad needs a static count
        return _count_program(type(self), static, dynamic, state, steps, dt)

    def trajectory(self, state, steps: int):
        """``steps`` steps of the stepper's own Δt keeping every state: ``(state after them, the states at each
        step's start stacked on a leading axis)`` (pure, one compiled scan; it does not stop at a non-finite state,
        and checks no more than :meth:`init` does). Memory grows with ``steps``: for measurements that need every step (a gauge, a
        record); :meth:`run` with ``every`` or a ``callback`` keeps only what it is asked for.

        Parameters
        ----------
        state
            A state of this stepper's kind.
        steps : int
            ≥ 1 (static: one program per count).

        Returns
        -------
        (state, stacked states)
        """
        steps = check_int("steps", steps, lo=1)
        state = self.init(state)
        static, dynamic = self._parts()
        return _steps_program(type(self), static, dynamic, state, steps, jnp.asarray(np.nan), True)

    def _every_step(self, state, steps: int):
        """``steps`` of the stepper's own steps, all of them (no early stop at a non-finite state, nothing kept):
        what the deprecated run functions did."""
        state = self.init(state)
        static, dynamic = self._parts()
        return _steps_program(type(self), static, dynamic, state, steps, jnp.asarray(np.nan))

    def _whole_steps(self, state, time, name):
        """The number of the stepper's fixed steps from the state's time to ``time`` (ValueError naming
        ``name`` when it is not whole, or under a trace)."""
        if is_traced(time) or is_traced(self._time(state)):
            raise ValueError(f"{name}: a fixed-Δt stepper reaches a time by a whole number of steps, which a traced "
                             f"time cannot give: use advance(state, steps)")
        static, dynamic = self._parts()
        dt = float(type(self)._dt(static, dynamic, state))
        whole = (float(time) - float(self._time(state))) / dt
        if whole < -1e-9 or abs(whole - round(whole)) > 1e-6 * max(1.0, abs(whole)):
            raise ValueError(f"{name} must be the state's time plus a whole number of this stepper's Δt = {dt:g} s, "
                             f"got {float(time):g} s ({whole:.6g} steps)")
        return int(round(whole))

    def advance_to(self, state, until, max_steps: int = 1_000_000):
        """Stable steps up to ``until`` (s), the last one cut to land on it: ``(state, steps taken)`` (pure:
        ``jax.jit`` and ``jax.vmap`` apply; it stops early at ``max_steps`` or a non-finite state, which the
        caller reads from the state's time).

        Parameters
        ----------
        state
            A state of this stepper's kind.
        until : float
            s.
        max_steps : int
            ≥ 1.

        Returns
        -------
        (state, jax.Array)
        """
        if not is_traced(until):
            check_scalar("until", until)
        max_steps = check_int("max_steps", max_steps, lo=1)
        state = self.init(state)  # first: it may fix settings from the state (an open side's sea)
        static, dynamic = self._parts()
        if not (is_traced(until) or is_traced(self._time(state))) and float(until) < float(self._time(state)):
            raise ValueError(f"until must not be before the state's time {float(self._time(state))}, got {until}")
        if not self.adaptive:
            n = self._whole_steps(state, until, "until")
            return (self.advance(state, n) if n else state), jnp.asarray(n, jnp.int32)
        return _until_program(type(self), static, dynamic, state, jnp.asarray(until, self._time(state).dtype),
                              jnp.asarray(max_steps, jnp.int32))

    def frames(self, state, times, max_steps: int = 1_000_000):
        """The states at each of ``times`` (s, non-decreasing), stacked on a leading axis (pure).

        Parameters
        ----------
        state
            A state of this stepper's kind.
        times : array_like (T,)
            s.
        max_steps : int
            Stable steps allowed between two frames, ≥ 1.

        Returns
        -------
        The stacked states.
        """
        if not is_traced(times):
            check_array("times", times, ndim=1)
            if np.size(times) == 0 or np.any(np.diff(np.asarray(times, np.float64)) < 0):
                raise ValueError("times must hold at least one time, non-decreasing")
        max_steps = check_int("max_steps", max_steps, lo=1)
        state = self.init(state)  # first: it may fix settings from the state (an open side's sea)
        static, dynamic = self._parts()
        if not self.adaptive:
            out = []
            for t in np.asarray(times, np.float64):
                n = self._whole_steps(state, t, "times")  # from the last frame's state
                state = self.advance(state, n) if n else state
                out.append(state)
            return jax.tree_util.tree_map(lambda *leaves: jnp.stack(leaves), *out)
        times = jnp.asarray(times, self._time(state).dtype)
        max_steps = jnp.asarray(max_steps, jnp.int32)
        if any(is_traced(v) for v in jax.tree_util.tree_leaves((state, times, dynamic))):
            return _frames_program(type(self), static, dynamic, state, times, max_steps)
        out = []  # concrete: the run's own program from frame to frame (no program of its own to compile)
        for t in times:
            state, _ = _until_program(type(self), static, dynamic, state, t, max_steps)
            out.append(state)
        return jax.tree_util.tree_map(lambda *leaves: jnp.stack(leaves), *out)

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
                state = _count_program(cls, static, dynamic, state, value, nan)
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



def _bed(bed):
    """The bed as float64 NumPy (kept as it is under a trace)."""
    return bed if is_traced(bed) else np.asarray(bed, np.float64)


def _fixed_dt(stepper, own: float, dt) -> float:
    """A fixed-Δt stepper takes only its own Δt (ValueError naming ``dt`` otherwise)."""
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    if abs(float(dt) - own) > 1e-9 * own:
        raise ValueError(f"dt: {type(stepper).__name__} steps its own dt = {own:g} s (make the stepper with the Δt "
                         f"you want), got {dt}")
    return float(dt)


class _FixedEta(Stepper):
    """A stepper whose state holds the surface as ``eta`` and which steps its own fixed ``self.dt``."""

    @classmethod
    def _height(cls, static, dynamic, state):
        return state.eta

    def _check_dt(self, state, dt):
        return _fixed_dt(self, self.dt, dt)


class _TwoLevel(_FixedEta):
    state_type = TwoLevelState

    @classmethod
    def _dt(cls, static, dynamic, state):
        return jnp.asarray(dynamic[-1], state.eta.dtype)

    @property
    def sides(self):
        return ("periodic",) * 4


