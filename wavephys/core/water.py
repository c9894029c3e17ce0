"""The water body's physical properties: one frozen pytree with SI defaults.

``Water``'s numbers are leaves, so ``jit``/``vmap``/``grad`` sweep them (a batch of depths,
the gradient with respect to surface tension); ``wavephys.core.pytree.stack`` makes a
batch. Constructors validate their arguments; values rebuilt inside JAX transformations
are not checked (they may be tracers).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

from wavephys.core.inputs import check_scalar, is_traced
from wavephys.core.pytree import register

__all__ = ["Water", "GRAVITY", "DENSITY", "SURFACE_TENSION"]

GRAVITY = 9.81
"""Standard gravitational acceleration used by default, m/s²."""
DENSITY = 1000.0
"""Density of fresh water used by default, kg/m³."""
SURFACE_TENSION = 0.0728
"""Surface tension of clean water against air at 20 °C, N/m."""


@dataclass(frozen=True)
class Water:
    """Physical properties of the water body.

    Parameters
    ----------
    g : float
        Gravitational acceleration, m/s², > 0. Default 9.81.
    rho : float
        Density, kg/m³, > 0. Default 1000.
    sigma : float
        Surface tension, N/m, ≥ 0. Default 0.0728 (clean water, 20 °C); 0 switches
        capillarity off (pure gravity waves).
    depth : float
        Still-water depth h, m, > 0; ``math.inf`` (the default) means deep water, where
        tanh(k h) is replaced by 1 exactly.

    Examples
    --------
    >>> Water()                       # deep, clean water
    Water(g=9.81, rho=1000.0, sigma=0.0728, depth=inf)
    >>> Water(sigma=0.0, depth=2.0)   # gravity waves on 2 m of water
    Water(g=9.81, rho=1000.0, sigma=0.0, depth=2.0)
    """

    g: float = GRAVITY
    rho: float = DENSITY
    sigma: float = SURFACE_TENSION
    depth: float = math.inf

    def __post_init__(self):
        check_scalar("g", self.g, lo=0.0, lo_open=True)
        check_scalar("rho", self.rho, lo=0.0, lo_open=True)
        check_scalar("sigma", self.sigma, lo=0.0)
        check_scalar("depth", self.depth, lo=0.0, lo_open=True, allow_inf=True)

    @property
    def kinematic_surface_tension(self):
        """σ/ρ, m³/s²."""
        return self.sigma / self.rho

    @property
    def is_deep(self) -> bool:
        """True when depth is infinite (requires a concrete depth)."""
        if is_traced(self.depth):
            raise TypeError("is_deep needs a concrete depth, not a traced one")
        return math.isinf(float(self.depth))

    def replace(self, **changes) -> "Water":
        """A copy with some fields changed (validated)."""
        values = {f.name: getattr(self, f.name) for f in fields(self)}
        values.update(changes)
        return Water(**values)


register(Water, ("g", "rho", "sigma", "depth"))
