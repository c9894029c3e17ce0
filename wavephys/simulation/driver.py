"""``Simulation``: a thin convenience wrapper around the pure step, holding one :class:`Model`."""

from __future__ import annotations

import jax.numpy as jnp

from wavephys.core.grid import Grid
from wavephys.core.water import Water
import wavephys.simulation.stepping as _step
from wavephys.simulation.model import Model
from wavephys.simulation.state import State, Surface

__all__ = ["Simulation"]


class Simulation:
    """Exact linear water waves on a periodic grid, stepped by Δt (any size).

    Every method calls the pure functions of :mod:`wavephys.simulation.step` with
    :attr:`model`; ``step(sim.model, state)`` equals ``sim.step(state)``.

    Parameters
    ----------
    grid, water, dt, margin, cutoff, second_order, ship_patch, leak_tolerance, ship_method
        As :class:`~wavephys.simulation.Model` (grid; water; Δt in s, > 0; margin in samples,
        0 ≤ M < n/2; …).
    dtype : numpy/JAX dtype or its name
        float32 (default) or float64 (needs ``jax_enable_x64``).
    devices : sequence of jax devices, optional
        Shard the grid's rows over them (a one-axis mesh named ``mesh_axis``;
        :mod:`wavephys.parallel`).
    mesh : jax.sharding.Mesh, optional
        Or give the mesh directly.
    mesh_axis : str
        The mesh axis the rows are split over (default ``"rows"``).
    walls : str or sequence of str
        Reflecting walls, as :class:`~wavephys.simulation.Model` (``"all"`` for a tank).
    tank : (float, float), optional
        (width, height), m: a rectangular tank smaller than the grid, centred, with ``walls="all"``
        (:class:`~wavephys.simulation.Model`).

    Examples
    --------
    >>> from wavephys import Grid, Water, Stones
    >>> sim = Simulation(Grid(128, 4.0), Water(), dt=0.02, margin=16)
    >>> state = sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.05, 0.01))
    >>> state, surface = sim.step(state)
    >>> surface.eta.shape
    (128, 128)
    """

    def __init__(self, grid: Grid, water: Water = Water(), dt: float = 1.0 / 30.0, margin: int = 0,
                 cutoff: str = "quadratic", second_order: bool = False, dtype=jnp.float32,
                 ship_patch: int | None = None, leak_tolerance: float = 1e-3, ship_method: str = "kernels",
                 devices=None, mesh=None, mesh_axis: str = "rows", walls=(), tank=None):
        if not isinstance(mesh_axis, str) or not mesh_axis:
            raise TypeError(f"mesh_axis must be a non-empty str, got {type(mesh_axis).__name__}")
        if devices is not None:
            if mesh is not None:
                raise ValueError("give devices or mesh, not both")
            from wavephys.parallel.layout import row_mesh

            mesh = row_mesh(devices, mesh_axis)
        self.model = Model(grid, water, dt, margin, cutoff, second_order, dtype, ship_patch, leak_tolerance,
                           ship_method, mesh, mesh_axis, walls, tank)

    def __repr__(self) -> str:
        return f"Simulation({self.model})"

    # the model's fields, read-only
    grid = property(lambda self: self.model.grid, doc="The grid.")
    water = property(lambda self: self.model.water, doc="The water.")
    dt = property(lambda self: float(self.model.dt), doc="Δt, s.")
    margin = property(lambda self: self.model.margin, doc="Cutoff margin, samples.")
    walls = property(lambda self: self.model.walls, doc="The walled sides.")
    tank = property(lambda self: self.model.tank, doc="(width, height) of a tank smaller than the grid, m, or None.")
    dtype = property(lambda self: jnp.dtype(self.model.dtype), doc="Floating dtype.")

    # -- states ---------------------------------------------------------------------
    def initial_state(self, time: float = 0.0) -> State:
        """Still water at ``time`` (s)."""
        return _step.initial_state(self.model, time)

    def state_from_psi(self, psi, time: float = 0.0) -> State:
        """A state from a complex field ψ (m²/s, shape ``(n, n)``)."""
        return _step.state_from_psi(self.model, psi, time)

    def add_height(self, state: State, eta) -> State:
        """Add a height disturbance η (m, ``(n, n)``) with the fluid at rest (its mean drops)."""
        return _step.add_height(self.model, state, eta)

    def drop(self, state: State, stones) -> State:
        """Drop stones now: their craters are part of the returned state."""
        from wavephys.physics.disturbances import Stones
        from wavephys.core.inputs import check_instance

        check_instance("stones", stones, Stones, "wavephys.Stones")
        return _step.add_source(self.model, state, stones)

    def add_wind(self, state: State, key, spectrum: str = "phillips", **params) -> State:
        """Add a random wind sea from a named spectrum (``"phillips"`` or ``"jonswap"``).

        ``params`` go to the spectrum (:mod:`wavephys.physics.wind`), e.g. ``wind_speed=5.0,
        direction=0.0`` (Phillips also ``amplitude``; JONSWAP ``fetch``). ``key`` is a
        ``jax.random`` key.
        """
        from wavephys.core.inputs import check_key
        from wavephys.physics.wind import WindSea

        check_key("key", key)
        return _step.add_source(self.model, state, WindSea(key, spectrum, params))

    # -- stepping -------------------------------------------------------------------
    def step(self, state: State, stones=None, ships=(), sources=()):
        """Advance by Δt: ``(state at t + Δt, surface at t)`` (:func:`wavephys.simulation.step`).

        ``stones`` are dropped at t, before the surface is taken; ``ships`` add the waves
        they make over [t, t + Δt] after the cutoff; ``sources`` are any other sources.
        """
        for name, value in (("ships", ships), ("sources", sources)):
            if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
                raise TypeError(f"{name} must be a sequence of sources, got {type(value).__name__}")
        if stones is not None and not hasattr(stones, "impulse"):
            raise TypeError(f"stones must be wavephys.Stones (or None), got {type(stones).__name__}")
        everything = ([] if stones is None else [stones]) + list(ships) + list(sources)
        return _step.step(self.model, state, everything)

    def surface(self, state: State) -> Surface:
        """The surface (η, η̇) of ``state``, without stepping."""
        return _step.surface(self.model, state)

    def run(self, state: State, steps: int, sources=()):
        """``steps`` steps in one compiled loop: ``(final state, Surface of stacked arrays)``."""
        return _step.run(self.model, state, steps, sources)

    def frame(self, before: Surface, after: Surface, s: float):
        """Hermite-interpolated height at t + sΔt between two consecutive surfaces, m."""
        return _step.frame(self.model, before, after, s)

    def energy(self, state: State):
        """Wave energy per unit area of ``state`` (linear theory), J/m²."""
        return _step.energy(self.model, state)
