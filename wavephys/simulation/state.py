"""What the step carries (the wave field) and what it returns (the surface), as pytrees."""

from __future__ import annotations

from dataclasses import dataclass

import jax
import numpy as np

from wavephys.core.inputs import check_array, check_scalar
from wavephys.core.pytree import register

__all__ = ["State", "Surface"]


def _check_fields(fields, time):
    check_array("fields", fields, min_ndim=3)
    if np.shape(fields)[-3] != 2:
        raise ValueError(f"fields must stack two fields on axis −3, shape (..., 2, n, n), got {np.shape(fields)}")
    if np.shape(fields)[-1] != np.shape(fields)[-2]:
        raise ValueError(f"fields must be square on the last two axes (a Grid is n x n), got {np.shape(fields)}")
    if np.ndim(time) == 0:
        check_scalar("time", time)
    else:
        check_array("time", time)


@dataclass(frozen=True)
class State:
    """Simulation state: the complex wave field ψ = φ + iχ on the grid at time t.

    ``fields`` holds (φ, χ) stacked, shape ``(..., 2, n, n)``, m²/s, so that one batched
    real FFT transforms both; ``time`` in s, in the model's dtype. ``time_error`` (s) is
    what ``time`` leaves out: the clock is the compensated sum ``time + time_error``
    (Kahan/Møller two-sum on every step), so float32 time does not drift over long runs
    (:attr:`exact_time`; docs/physics.md §1.2). Values are checked (finite) when a State is
    built by hand; states made by the step are not re-checked.

    Parameters
    ----------
    fields : jax.Array (..., 2, n, n)
        (φ, χ), m²/s, finite.
    time : jax.Array
        t, s (a scalar, or one per batch entry).
    time_error : jax.Array
        The part of t that ``time`` leaves out, s (default 0).
    """

    fields: jax.Array
    time: jax.Array
    time_error: jax.Array = 0.0

    def __post_init__(self):
        _check_fields(self.fields, self.time)
        if np.ndim(self.time_error) == 0:
            check_scalar("time_error", self.time_error)
        else:
            check_array("time_error", self.time_error)

    @property
    def exact_time(self) -> float:
        """The simulation clock ``time + time_error`` as a Python float (float64), s."""
        return float(self.time) + float(self.time_error)

    @property
    def phi(self):
        """Real part φ of ψ (the surface velocity potential), m²/s."""
        return self.fields[..., 0, :, :]

    @property
    def chi(self):
        """Imaginary part χ of ψ, m²/s."""
        return self.fields[..., 1, :, :]

    @property
    def psi(self):
        """The complex wave field ψ = φ + iχ, m²/s."""
        return self.phi + 1j * self.chi


@dataclass(frozen=True)
class Surface:
    """The water surface at one time.

    Parameters
    ----------
    fields : jax.Array (..., 2, n, n)
        (η in m, η̇ in m/s) stacked, finite.
    time : jax.Array
        t, s.
    """

    fields: jax.Array
    time: jax.Array

    def __post_init__(self):
        _check_fields(self.fields, self.time)

    @property
    def eta(self):
        """Height η, m, shape ``(..., n, n)``."""
        return self.fields[..., 0, :, :]

    @property
    def eta_dot(self):
        """Vertical surface velocity η̇, m/s."""
        return self.fields[..., 1, :, :]


register(State, ("fields", "time", "time_error"))
register(Surface, ("fields", "time"))


def unchecked(cls, fields, time, time_error=None):
    """A State or Surface from trusted values (the step's own), skipping ``__post_init__``."""
    obj = object.__new__(cls)
    object.__setattr__(obj, "fields", fields)
    object.__setattr__(obj, "time", time)
    if cls is State:
        object.__setattr__(obj, "time_error", jax.numpy.zeros_like(time) if time_error is None else time_error)
    return obj


def advance_clock(time, time_error, dt):
    """(time, time_error) + Δt, compensated: error-free two-sum of time and Δt, the rounding
    error carried in ``time_error`` (so float32 time stays exact to float32 rounding of the
    true clock over any number of steps). Pure; works under jit."""
    s = time + dt
    bb = s - time
    err = (time - (s - bb)) + (dt - bb)
    lo = time_error + err
    hi = s + lo
    return hi, lo - (hi - s)


def split_time(time: float, dtype):
    """A host time (Python float, s) as (time, time_error) in ``dtype``: time_error = the rest."""
    import jax.numpy as jnp

    if isinstance(time, jax.core.Tracer):
        return jnp.asarray(time, dtype), jnp.zeros((), dtype)
    hi = np.asarray(time, dtype)
    return jnp.asarray(hi), jnp.asarray(np.asarray(float(time) - float(hi), dtype))
