"""Parameters that travel together: the water's properties and the periodic grid.

Both are immutable pytrees. ``Water``'s numbers are leaves, so ``jit``/``vmap``/``grad``
sweep them; ``Grid``'s point count ``n`` is static (it fixes array shapes) and its side
length is a leaf. Constructors validate their arguments; rebuilding a pytree inside JAX
transformations bypasses the checks (the values may be tracers there).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import jax
import jax.numpy as jnp
import numpy as np

from wavephys._inputs import check_int, check_scalar, is_traced

__all__ = ["Water", "Grid", "GRAVITY", "DENSITY", "SURFACE_TENSION"]

GRAVITY = 9.81
"""Standard gravitational acceleration used by default, m/s²."""
DENSITY = 1000.0
"""Density of fresh water used by default, kg/m³."""
SURFACE_TENSION = 0.0728
"""Surface tension of clean water against air at 20 °C, N/m."""


def _register(cls, data: tuple[str, ...], meta: tuple[str, ...] = ()):
    """Register a frozen dataclass as a pytree whose unflatten skips validation."""

    def flatten(obj):
        return tuple(getattr(obj, f) for f in data), tuple(getattr(obj, f) for f in meta)

    def unflatten(aux, children):
        obj = object.__new__(cls)
        for name, value in zip(data, children):
            object.__setattr__(obj, name, value)
        for name, value in zip(meta, aux):
            object.__setattr__(obj, name, value)
        return obj

    jax.tree_util.register_pytree_node(cls, flatten, unflatten)
    return cls


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


_register(Water, ("g", "rho", "sigma", "depth"))


@dataclass(frozen=True)
class Grid:
    """A square, periodic grid of ``n × n`` points covering ``length × length`` metres.

    Arrays on the grid have shape ``(..., n, n)`` ordered ``(y, x)``; spacing
    ``dx = length / n``; angular wavenumbers ``k = 2π·fftfreq(n, dx)`` (rad/m). Physical
    coordinates put x = y = 0 at index ``n // 2`` (the grid's centre).

    Parameters
    ----------
    n : int
        Points per side, even, ≥ 2 (static: it fixes array shapes).
    length : float
        Side length, m, finite and > 0.

    Examples
    --------
    >>> grid = Grid(256, 10.0)
    >>> float(grid.dx)
    0.0390625
    """

    n: int
    length: float

    def __post_init__(self):
        object.__setattr__(self, "n", check_int("n", self.n, lo=2, even=True))
        check_scalar("length", self.length, lo=0.0, lo_open=True)

    @property
    def dx(self):
        """Grid spacing, m."""
        return self.length / self.n

    @property
    def coordinates(self):
        """1-D point coordinates, m, shape ``(n,)``: ``(i − n//2)·dx``."""
        return (jnp.arange(self.n) - self.n // 2) * self.dx

    def mesh(self):
        """``(x, y)`` coordinate arrays of shape ``(n, n)``, m."""
        c = self.coordinates
        return c[None, :] * jnp.ones((self.n, 1), c.dtype), c[:, None] * jnp.ones((1, self.n), c.dtype)

    def wavenumbers(self, real: bool = False):
        """``(ky, kx)`` angular wavenumbers, rad/m, shaped to broadcast to the spectrum.

        ``real=True`` gives the half spectrum of ``rfft2`` (``kx`` has ``n//2 + 1``
        entries), for real fields.
        """
        ky = 2.0 * jnp.pi * jnp.fft.fftfreq(self.n) * (self.n / self.length)
        if real:
            kx = 2.0 * jnp.pi * jnp.fft.rfftfreq(self.n) * (self.n / self.length)
        else:
            kx = ky
        return ky[:, None], kx[None, :]

    def wavenumber_magnitude(self, real: bool = False):
        """|k| on the spectrum, rad/m, shape ``(n, n)`` or ``(n, n//2 + 1)``."""
        ky, kx = self.wavenumbers(real)
        return jnp.sqrt(kx * kx + ky * ky)

    @property
    def nyquist(self):
        """Largest resolved angular wavenumber along an axis, π/dx, rad/m."""
        return jnp.pi / self.dx


_register(Grid, ("length",), ("n",))
