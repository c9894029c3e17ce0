"""The spectral wave simulation: Loviscach (2003), §3, on real FFTs.

State: the complex wave field ψ = φ + iχ (m²/s) stored as its two real parts, stacked,
so each step needs only real transforms, batched. One step (``Simulation.step``) does,
in the paper's order:

1. one batched ``rfft2`` of (φ, χ);
2. sudden disturbances (stones) added in Fourier space (:mod:`wavephys.disturbances`);
3. the surface of this state: η = −F⁻¹[(K/ω)χ̂] (+ the second-order term if enabled)
   and η̇ = F⁻¹[Kφ̂] (:mod:`wavephys.heights`);
4. exact propagation by Δt, a rotation of (φ̂, χ̂) by ωΔt (:mod:`wavephys.ring_waves`);
5. two batched ``irfft2``: (φ', χ') → the next state, (η̂, η̇̂) → the surface
   [and (q̂, Λη̂, Λq̂) for the second-order term];
6. the open-ocean cutoff h(p)·h(q) on the next state (if ``margin`` > 0;
   :mod:`wavephys.boundary`).

It returns the state at t + Δt and the surface at t (of the state it was given, with
the stones of this step): 2 forward and 4 inverse real transforms per step (7 inverse
with second order).

CPU note: XLA runs an FFT on a single thread when another operation precedes it in the
same compiled program (openxla/xla#46345, jax-ml/jax#39081), which made a fully fused
step 1.4–2× slower than its bare FFTs here. ``step`` therefore dispatches two compiled
programs, each starting with its FFTs; ``run`` (a ``lax.scan``) stays one program.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import jax
import jax.numpy as jnp
import numpy as np

from wavephys._inputs import check_array, check_choice, check_int, check_scalar
from wavephys.boundary import CUTOFFS, cutoff_mask
from wavephys.dispersion import angular_frequency, surface_operator
from wavephys.disturbances import Stones, stone_height_spectrum
from wavephys.heights import height_multiplier, potential_from_height, second_order_correction
from wavephys.interpolation import hermite_frame
from wavephys.params import Grid, Water, _register
from wavephys.ring_waves import rotate_pair
from wavephys.ship_waves import Ship, add_ship_waves, patch_leak
from wavephys.wind import SPECTRA, synthesize_height

__all__ = ["State", "Surface", "Simulation"]


@dataclass(frozen=True)
class State:
    """Simulation state: ψ = φ + iχ on the grid at time t.

    ``fields`` holds (φ, χ) stacked, shape ``(..., 2, n, n)``, m²/s, so that one batched
    real FFT transforms both; ``time`` in s.
    """

    fields: jax.Array
    time: jax.Array

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

    @property
    def eta(self):
        """Height η, m, shape ``(..., n, n)``."""
        return self.fields[..., 0, :, :]

    @property
    def eta_dot(self):
        """Vertical surface velocity η̇, m/s."""
        return self.fields[..., 1, :, :]


_register(State, ("fields", "time"))
_register(Surface, ("fields", "time"))


def _check_dtype(dtype):
    dtype = jnp.dtype(dtype)
    if dtype not in (jnp.dtype(jnp.float32), jnp.dtype(jnp.float64)):
        raise ValueError(f"dtype must be float32 or float64, got {dtype}")
    if dtype == jnp.float64 and not jax.config.jax_enable_x64:
        raise ValueError("dtype float64 needs jax_enable_x64: "
                         "jax.config.update('jax_enable_x64', True) before creating arrays")
    return dtype


class Simulation:
    """Exact linear water waves on a periodic grid, stepped by Δt (any size).

    Parameters
    ----------
    grid : Grid
        The n × n periodic grid.
    water : Water
        Water properties (surface tension and finite depth switch off with σ = 0,
        depth = inf).
    dt : float
        Time step Δt, s, finite and > 0. The propagation is exact for any Δt; what limits
        Δt is what you do with the frames (Hermite interpolation error grows with ωΔt).
    margin : int
        Open-ocean cutoff margin M, points, 0 ≤ M < n/2 (0: periodic, no cutoff).
    cutoff : {"quadratic", "linear"}
        Cutoff shape (the paper's quadratic, or the earlier linear one).
    second_order : bool
        Add the second-order height term (SPEC §1.5) to η.
    dtype : float32 (default) or float64 (needs ``jax_enable_x64``).
    ship_patch : int
        Side 2M of the patch on which each ship's new waves are computed (even, ≤ n;
        default min(64, n)).
    leak_tolerance : float
        Largest fraction of a step's ship waves the patch may miss
        (:func:`wavephys.ship_waves.patch_leak`); a ship whose Δt exceeds it is refused.
    ship_method : {"kernels", "impulses"}
        Loviscach's Φ1/Φ2 kernels, or the naive row of dropped stones (for comparison).

    Examples
    --------
    >>> from wavephys import Grid, Water
    >>> from wavephys.disturbances import Stones
    >>> sim = Simulation(Grid(128, 4.0), Water(), dt=0.02, margin=16)
    >>> state = sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.05, 0.01))
    >>> state, surface = sim.step(state)
    >>> surface.eta.shape
    (128, 128)
    """

    def __init__(self, grid: Grid, water: Water = Water(), dt: float = 1.0 / 30.0,
                 margin: int = 0, cutoff: str = "quadratic", second_order: bool = False,
                 dtype=jnp.float32, ship_patch: int | None = None, leak_tolerance: float = 1e-3,
                 ship_method: str = "kernels"):
        if not isinstance(grid, Grid):
            raise TypeError(f"grid must be a wavephys.Grid, got {type(grid).__name__}")
        if not isinstance(water, Water):
            raise TypeError(f"water must be a wavephys.Water, got {type(water).__name__}")
        check_scalar("dt", dt, lo=0.0, lo_open=True)
        margin = check_int("margin", margin, lo=0)
        if 2 * margin >= grid.n:
            raise ValueError(f"margin must be < n/2 = {grid.n // 2}, got {margin}")
        check_choice("cutoff", cutoff, CUTOFFS)
        self.grid, self.water, self.dt = grid, water, float(dt)
        self.margin, self.cutoff, self.second_order = margin, cutoff, bool(second_order)
        self.dtype = _check_dtype(dtype)
        if ship_patch is None:
            ship_patch = min(64, grid.n)
        self.ship_patch = check_int("ship_patch", ship_patch, lo=4, hi=grid.n, even=True)
        check_scalar("leak_tolerance", leak_tolerance, lo=0.0, hi=1.0, lo_open=True)
        self.leak_tolerance = float(leak_tolerance)
        self.ship_method = check_choice("ship_method", ship_method, ("kernels", "impulses"))
        self._ships_checked: set = set()

        k = grid.wavenumber_magnitude(real=True).astype(self.dtype)
        phase = angular_frequency(k, water) * jnp.asarray(dt, self.dtype)
        hm = height_multiplier(k, water)
        self._ops = dict(
            cos=jnp.cos(phase), sin=jnp.sin(phase),
            height=hm,  # K/ω
            inverse_height=jnp.where(hm > 0, 1.0 / jnp.where(hm > 0, hm, 1.0), 0.0),  # ω/K
            K=surface_operator(k, water), lam=k,
            mask=cutoff_mask(grid.n, margin, cutoff, self.dtype) if margin else None,
        )
        self._forward_jit = jax.jit(self._forward)
        self._inverse_jit = jax.jit(self._inverse)
        self._surface = jax.jit(lambda state: self._step_impl(state, None)[1])
        self._run = jax.jit(self._run_impl, static_argnums=1)

    # -- states ---------------------------------------------------------------
    def initial_state(self, time: float = 0.0) -> State:
        """Still water at ``time`` (s)."""
        return State(jnp.zeros((2, self.grid.n, self.grid.n), self.dtype), jnp.asarray(time, self.dtype))

    def state_from_psi(self, psi, time: float = 0.0) -> State:
        """A state from a complex field ψ (m²/s, shape ``(n, n)``)."""
        n = self.grid.n
        check_array("psi", psi, complex_ok=True, min_ndim=2, shape_tail=(n, n))
        if jnp.ndim(psi) != 2:
            raise ValueError(f"psi must have shape ({n}, {n}), got {jnp.shape(psi)}")
        check_scalar("time", time)
        psi = jnp.asarray(psi)
        return State(jnp.stack([psi.real, psi.imag]).astype(self.dtype), jnp.asarray(time, self.dtype))

    def _add_psi(self, state: State, psi) -> State:
        return State(state.fields + jnp.stack([psi.real, psi.imag]).astype(self.dtype), state.time)

    def add_height(self, state: State, eta) -> State:
        """Add a height disturbance η (m, ``(n, n)``) with the fluid at rest (its mean drops)."""
        check_array("eta", eta, min_ndim=2, shape_tail=(self.grid.n, self.grid.n))
        return self._add_psi(state, potential_from_height(jnp.asarray(eta, self.dtype),
                                                          self.grid, self.water))

    def drop(self, state: State, stones: Stones) -> State:
        """Drop stones now: their craters are part of the returned state."""
        stones = self._check_stones(stones)
        eta = jnp.fft.irfft2(stone_height_spectrum(stones, self.grid), s=(self.grid.n,) * 2)
        return self._add_psi(state, potential_from_height(eta.astype(self.dtype),
                                                          self.grid, self.water))

    def add_wind(self, state: State, key, spectrum: str = "phillips", **params) -> State:
        """Add a random wind sea from a named spectrum (``"phillips"`` or ``"jonswap"``).

        ``params`` go to the spectrum function (:mod:`wavephys.wind`), e.g.
        ``wind_speed=5.0, direction=0.0`` (Phillips also ``amplitude``; JONSWAP
        ``fetch``). ``key`` is a ``jax.random`` key.
        """
        check_choice("spectrum", spectrum, SPECTRA)
        ky, kx = self.grid.wavenumbers()
        f = SPECTRA[spectrum](kx.astype(self.dtype), ky.astype(self.dtype), self.water, **params)
        h = synthesize_height(f, self.grid, key)
        return self._add_psi(state, potential_from_height(h, self.grid, self.water,
                                                          travelling=True))

    def _check_stones(self, stones):
        if not isinstance(stones, Stones):
            raise TypeError(f"stones must be wavephys.disturbances.Stones, got {type(stones).__name__}")
        return stones.check_on(self.grid)

    # -- stepping -------------------------------------------------------------
    def _forward(self, fields, stones: Optional[Stones]):
        """rfft2 of the state, stones, surface spectra and propagation (pure)."""
        ops = self._ops
        spec = jnp.fft.rfft2(fields)
        ph, ch = spec[0], spec[1]
        if stones is not None:
            eta_stone = stone_height_spectrum(stones, self.grid).astype(ch.dtype)
            ch = ch - ops["inverse_height"] * eta_stone
        eta_hat = -ops["height"] * ch
        surf = [eta_hat, ops["K"] * ph]
        if self.second_order:
            q_hat = ops["height"] * ph
            surf += [q_hat, ops["lam"] * eta_hat, ops["lam"] * q_hat]
        return jnp.stack(rotate_pair(ph, ch, ops["cos"], ops["sin"])), jnp.stack(surf)

    def _inverse(self, state_spec, surf_spec, time):
        """The two batched irfft2 (next state, surface) and the cutoff (pure)."""
        n, mask = self.grid.n, self._ops["mask"]
        new = jnp.fft.irfft2(state_spec, s=(n, n))
        if mask is not None:
            new = new * mask
        surf = jnp.fft.irfft2(surf_spec, s=(n, n))
        if self.second_order:
            eta = surf[0] + second_order_correction(surf[0], surf[2], surf[3], surf[4])
            surf = jnp.stack([eta, surf[1]])
        dt = jnp.asarray(self.dt, self.dtype)
        return State(new.astype(self.dtype), time + dt), Surface(surf.astype(self.dtype), time)

    def _step_impl(self, state: State, stones: Optional[Stones]):
        return self._inverse(*self._forward(state.fields, stones), state.time)

    def step(self, state: State, stones: Optional[Stones] = None, ships=()):
        """Advance by Δt: returns ``(state at t + Δt, surface at t)``.

        ``stones`` (optional) are dropped at t, before the surface is taken. The cutoff
        is applied to the returned state. ``ships`` (a sequence of
        :class:`~wavephys.ship_waves.Ship`) add the waves they make over [t, t + Δt]
        (Loviscach's eq. 2, on each ship's 2M × 2M patch) to the returned state, after
        the cutoff; a ship's patch must stay clear of the margin.
        """
        if stones is not None:
            stones = self._check_stones(stones)
        new, surf = self._inverse_jit(*self._forward_jit(state.fields, stones), state.time)
        if ships:
            new = State(self._add_ships(new.fields, ships, float(state.time)), new.time)
        return new, surf

    def _add_ships(self, fields, ships, t: float):
        half, n = self.ship_patch // 2, self.grid.n
        for ship in ships:
            if not isinstance(ship, Ship):
                raise TypeError(f"ships must hold wavephys.ship_waves.Ship, got {type(ship).__name__}")
            if id(ship) not in self._ships_checked:
                leak = patch_leak(ship, self.grid, self.water, self.dt, half, t)
                if leak > self.leak_tolerance:
                    raise ValueError(f"dt = {self.dt} s is too large for the ship patch of {2 * half} points: "
                                     f"{leak:.2g} of the new waves leak past it (tolerance "
                                     f"{self.leak_tolerance}); lower dt or raise ship_patch")
                self._ships_checked.add(id(ship))
            fields = add_ship_waves(fields, ship, self.grid, self.water, t, self.dt, half, self.ship_method,
                                    interior=(self.margin, n - self.margin))
        return fields


    def surface(self, state: State) -> Surface:
        """The surface (η, η̇) of ``state``, without stepping."""
        return self._surface(state)

    def _run_impl(self, state, steps):
        def body(s, _):
            s, surf = self._step_impl(s, None)
            return s, surf
        return jax.lax.scan(body, state, None, length=steps)

    def run(self, state: State, steps: int):
        """``steps`` steps in one compiled loop: ``(final state, Surface of stacked arrays)``.

        The surfaces are those at t, t + Δt, …, t + (steps − 1)Δt (shape ``(steps, n, n)``).
        """
        steps = check_int("steps", steps, lo=1)
        return self._run(state, steps)

    def frame(self, before: Surface, after: Surface, s: float):
        """Hermite-interpolated height at t + sΔt between two consecutive surfaces, m."""
        return hermite_frame(before.eta, after.eta, before.eta_dot, after.eta_dot, self.dt, s)

    def energy(self, state: State):
        """Wave energy per unit area of ``state`` (linear theory), J/m².

        E = ½ρ⟨φ·Kφ + χ·Kχ⟩, which equals potential + capillary + kinetic energy of the
        first-order surface (SPEC §1.8); conserved exactly by propagation.
        """
        K = self._ops["K"]
        n = self.grid.n
        kf = jnp.fft.irfft2(K * jnp.fft.rfft2(state.fields), s=(n, n))
        return 0.5 * self.water.rho * jnp.mean(state.fields * kf) * 2
