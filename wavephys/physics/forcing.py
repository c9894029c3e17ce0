r"""Surface pressure forcing: a user's forcing function as a continuous simulation source.

Linearized Bernoulli with a surface pressure p(x, y, t) adds S = −p/ρ to the rate of the
velocity potential, so the complex wave field obeys ψ̂_t = −iωψ̂ + Ŝ
(docs/physics.md §1.2). Over one step with S held at its mid-step value the exact
(Duhamel) update is

.. math::

    \hat\psi(t + \Delta t) = e^{-i\omega\Delta t}\hat\psi(t)
        + \hat S\,\frac{1 - e^{-i\omega\Delta t}}{i\omega}
    = e^{-i\omega\Delta t}\hat\psi(t) + \hat S\left(\frac{\sin\omega\Delta t}{\omega}
        - i\,\frac{1 - \cos\omega\Delta t}{\omega}\right),

exact for pressure constant over the step and second order in Δt (midpoint rule) for
pressure that varies smoothly in time. With ``substeps`` = M the step is split into M
sub-intervals δ = Δt/M, each integrated this way at its own midpoint and propagated
exactly to the step's end.

Failure boundary (measured in the tests): a forcing that moves with a wave of frequency
ω — a moving source and its stationary Kelvin waves, ω = k·U — is under-applied by the
factor sinc = 2 sin(ωδ/2)/(ωδ), δ = Δt/M: 0.96 at ωδ = 1, 0.85 at ωδ = 2. Choose M so
that ωδ ≲ 0.3 (error < 0.4 %) for the fastest wave the forcing drives, e.g. the
transverse wake waves ω = g/U. A steady pressure moving at speed U then converges to
the steady wake of :func:`wavephys.physics.wake.steady_wake`, the same equation
(switch it on smoothly: a sudden start leaves transients that decay slowly).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache
from typing import Callable

import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_int
from wavephys.core.pytree import register

__all__ = ["Forcing"]


@dataclass(frozen=True)
class Forcing:
    """A surface pressure p = ``pressure(x, y, t)`` (Pa) acting on the water: a continuous source.

    ``pressure`` takes the grid's sample coordinates ``x``, ``y`` (m, arrays of shape
    (n, n)) and the time ``t`` (s, a scalar) and returns the pressure on the grid, Pa,
    written with ``jax.numpy`` (it is traced into the compiled step; positive pressure
    pushes the surface down). The simulation evaluates it at the midpoint of each of the
    ``substeps`` (≥ 1) sub-intervals of a step (module doc: the accuracy it buys).

    Parameters
    ----------
    pressure : callable
        ``pressure(x, y, t) -> p``: x, y in m (arrays (n, n)), t in s (scalar), p in Pa, an
        array (n, n), finite; positive pressure pushes the surface down.
    substeps : int
        M, sub-intervals of a step each integrated at its own midpoint, 1 … 64 (choose ωΔt/M ≲ 0.3
        for the fastest wave the forcing drives, module docstring).

    Examples
    --------
    >>> import jax.numpy as jnp
    >>> bump = Forcing(lambda x, y, t: 50.0 * jnp.exp(-((x - 0.5 * t) ** 2 + y ** 2) / 0.02))
    """

    pressure: Callable
    substeps: int = 1

    def __post_init__(self):
        if not callable(self.pressure):
            raise TypeError(f"pressure must be a callable (x, y, t) -> Pa, got {type(self.pressure).__name__}")
        object.__setattr__(self, "substeps", check_int("substeps", self.substeps, lo=1, hi=64))

    def check(self, model) -> None:
        """The pressure on the model's grid at t = 0 must be finite and of shape (n, n)
        (evaluated once per function and grid; later values are not re-checked)."""
        from wavephys.core.specs import model_grid

        model_grid(model)
        _check_pressure(self.pressure, model.grid.n, float(model.grid.length))

    def rate(self, model, ops, t):
        """Ŝ = −p̂/ρ at time ``t`` on the model's modes (m²/s² per sample, DFT convention).

        The pressure is evaluated on ``model.mesh_fields()`` and transformed by
        ``model.transform``: on a sharded model both stay split over its devices; on a walled
        one the cosine modes hold its mirror images."""
        x, y = model.mesh_fields()
        p = jnp.asarray(self.pressure(x.astype(ops.cos.dtype), y.astype(ops.cos.dtype), t), ops.cos.dtype)
        return -model.transform(p) / model.water.rho


@lru_cache(maxsize=64)
def _check_pressure(pressure, n, length):
    from wavephys.core.grid import Grid

    x, y = Grid(n, length).mesh()
    p = pressure(x, y, 0.0)
    if np.shape(p) != (n, n):
        raise ValueError(f"pressure(x, y, t) must return shape {(n, n)}, got {np.shape(p)}")
    if not bool(jnp.isfinite(jnp.asarray(p)).all()):
        raise ValueError("pressure(x, y, t) returned NaN or inf at t = 0")


register(Forcing, (), ("pressure", "substeps"))
