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
    real FFT transforms both; ``time`` in s. Values are checked (finite) when a State is
    built by hand; states made by the step are not re-checked.
    """

    fields: jax.Array
    time: jax.Array

    def __post_init__(self):
        _check_fields(self.fields, self.time)

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
    """The water surface at one time: ``fields`` = (η in m, η̇ in m/s) stacked, ``time`` in s."""

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


register(State, ("fields", "time"))
register(Surface, ("fields", "time"))


def unchecked(cls, fields, time):
    """A State or Surface from trusted values (the step's own), skipping ``__post_init__``."""
    obj = object.__new__(cls)
    object.__setattr__(obj, "fields", fields)
    object.__setattr__(obj, "time", time)
    return obj
