r"""Shallow water with dispersive surface waves: the split model (docs/physics.md §1.15).

Nonlinear shallow water (:mod:`wavephys.simulation.shallow_water`) runs every wave at √(gh): right
for kh ≲ 0.3, too fast for anything shorter than the depth. The spectral step has the exact ω(k)
but no run-up and no dry land. After Jeschke & Wojtan (2023), each step of :func:`split_step`
separates the water into a smooth *bulk*, advanced by the finite-volume shallow-water solver (run-up,
wetting and drying, bores), and *surface waves*, advanced exactly in Fourier space with the linear
dispersion of the local depth, then adds the two back together. The state is the shallow-water
solver's own :class:`~wavephys.simulation.shallow_water.SWState` (h, hu, hv): everything that reads
one (``sw_mass``, ``sw_surface``, the harness) reads the split's output.

One step of Δt, with x = (η − η_ref, q_x, q_y) (surface and discharge) and w(h) ∈ [0, 1] a taper that
is 1 in water deeper than ``taper[1]`` and 0 below ``taper[0]`` (surface waves live only where w > 0):

1. **Separate.** x̄ = G∗(w x) / G∗w, a normalized Gaussian smoothing over the water (σ = ``bulk_length``;
   a constant over the wet region is kept exactly, so a lake at rest has no surface waves); the surface
   waves are x̃ = w (x − x̄) and the bulk is x − x̃.
2. **Advance.** The bulk by one shallow-water step, SW(x − x̃); the surface waves by B, one Störmer–Verlet step
   of η_t = −∇·q, q_t = −g R ∇η with R = Σ_j √R_j W_j √R_j: R_j(k) = (ω_j/k)² sinc²(ω_jΔt/2)/g in Fourier space
   is depth level j's operator (for one level the step turns each wave by exactly ω_j(k)Δt, the exact
   dispersion at every kh), and the weights W_j are linear in the bulk's depth h between the levels (a dry level
   of depth 0 below the shallowest), so Σ_j W_j h_j = h. R is symmetric and positive for any weights, so B keeps
   an energy over any bed; R → h for long waves, so the long-wave limit is linear shallow water, slope terms
   and all. Derivatives are spectral, and B moves water only where the bulk is deeper than ``taper[0]``.
3. **Recombine**, with a correction that makes the sum exact: new = SW(x − x̃) + B(w x) − L(w x̄), where L is
   the bulk solver's own step linearized about still water of the bulk's depth (its slopes unlimited: the
   linear scheme its minmod limits; by ``jax.jvp``). Since x − x̃ = (1 − w) x + w x̄ and SW ≈ L for small
   waves, new ≈ L((1 − w) x) + B(w x): where the taper is 1 the exact ω(k) of the local depth at every kh,
   whatever the split, and shallow water where it is 0. What is left is the limited solver's difference from
   its linear scheme on the smooth x̄ (and the nonlinear terms). Earlier blends of each level's exact
   exponential grew noise over stepped beds and smooth ramps into a grid-scale mode (docs/physics.md §1.15).
   The bulk length σ (≥ 8 cells by default; below 2 cells the split is unstable) sets what the nonlinear
   bulk holds.

Water is conserved exactly: the shallow-water step conserves it, and the surface increment is made to
hold the surface waves' water: L keeps the water it is given, but B's divergence cut to the surface-wave
region and the part that lands on dry cells do not, and their difference is put back evenly over the
surface-wave region. A surface wave running into shallow water is handed to
the bulk by the taper, where it shoals, breaks as a bore and runs up the beach as shallow water.

Sides are walls (mirror images: the surface waves see a cosine series) or periodic (Fourier series);
open and inflow sides are not supported. Neglected: the bulk current's transport and refraction of the
surface waves (Jeschke & Wojtan advect them), the surface waves' own nonlinearity (Stokes drift,
steepening; they are linear), and their effect on the bulk beyond adding to it.

References
----------
S. Jeschke & C. Wojtan (2023). Generalizing shallow water simulations with dispersive surface waves.
*ACM Transactions on Graphics* 42(4), 83. H. Lamb (1932). *Hydrodynamics*, §§169, 228.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Optional

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.aliases import deprecated_function
from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar, is_traced
from wavephys.core.pytree import register
from wavephys.core.water import Water
from wavephys.physics.depth import depth_weights
from wavephys.physics.dispersion import angular_frequency
from wavephys.core.stepper import Stepper, _bed
from wavephys.simulation.shallow_water import (ShallowWater, ShallowWaterStepper, SWState, advance_fields, check_run,
                                               stable_dt_fields, _linear_advance)

__all__ = ["Split", "MovingPressure", "split_step", "split_run", "split_frames", "split_parts"]


@dataclass(frozen=True)
class MovingPressure:
    """A pressure patch moving in a straight line: a boat's hull, as a Gaussian head of water.

    The pressure p = ρ g ``head`` exp(−(ξ/``length``)² − (ζ/``beam``)²) in the hull's frame (ξ along its
    course, ζ across) pushes the water by −h ∇p/ρ.

    Parameters
    ----------
    start : (float, float)
        Centre (x, y) at t = 0, m, measured from the outer corner of cell (0, 0) (cell (i, j) is centred at
        ((j + ½)·dx, (i + ½)·dx)).
    velocity : (float, float)
        (u, v), m/s; the hull points along it (a patch at rest points along x).
    head : float
        Peak pressure over ρg, m, ≥ 0 (a hull drawing 0.2 m: about 0.2).
    length, beam : float
        Gaussian half-widths along and across the course, m, > 0.
    """

    start: tuple
    velocity: tuple
    head: float
    length: float
    beam: float

    def __post_init__(self):
        for name in ("start", "velocity"):
            check_array(name, getattr(self, name), ndim=1, shape_tail=(2,))
            object.__setattr__(self, name, tuple(float(v) for v in getattr(self, name)))
        check_scalar("head", self.head, lo=0.0)
        check_scalar("length", self.length, lo=0.0, lo_open=True)
        check_scalar("beam", self.beam, lo=0.0, lo_open=True)
        for name in ("head", "length", "beam"):
            object.__setattr__(self, name, float(getattr(self, name)))

    def head_at(self, x, y, t, period=(None, None)):
        """The pressure head p/(ρg), m, at (x, y) (arrays, m) and time t (s); ``period`` (m, or None per axis):
        the patch wraps round a periodic axis of that length."""
        check_array("x", x)
        check_array("y", y)
        check_scalar("t", t)
        if not isinstance(period, (tuple, list)) or len(period) != 2:
            raise TypeError(f"period must be a pair (x, y) of lengths or None, got {period!r}")
        for p in period:
            if p is not None:
                check_scalar("period", p, lo=0.0, lo_open=True)
        u, v = self.velocity
        if is_traced((u, v)):  # the patch's settings traced (a compiled split: one program for every boat)
            speed = jnp.hypot(u, v)
            moving = speed > 0
            cx = jnp.where(moving, u / jnp.where(moving, speed, 1.0), 1.0)
            cy = jnp.where(moving, v / jnp.where(moving, speed, 1.0), 0.0)
        else:
            speed = math.hypot(u, v)
            cx, cy = (u / speed, v / speed) if speed > 0 else (1.0, 0.0)
        dx = x - (self.start[0] + u * t)
        dy = y - (self.start[1] + v * t)
        if period[0] is not None:
            dx = jnp.mod(dx + 0.5 * period[0], period[0]) - 0.5 * period[0]
        if period[1] is not None:
            dy = jnp.mod(dy + 0.5 * period[1], period[1]) - 0.5 * period[1]
        along = dx * cx + dy * cy
        across = -dx * cy + dy * cx
        return self.head * jnp.exp(-(along / self.length) ** 2 - (across / self.beam) ** 2)


@dataclass(frozen=True)
class Split:
    """The split model's settings (a pytree: its numbers are leaves, traced under ``jit``, so one compiled
    program serves every split of one grid shape, side kinds, order and number of levels).

    Parameters
    ----------
    solver : ShallowWater
        The bulk's solver: its cell size, g and sides (each ``"wall"`` or ``"periodic"``), Courant number
        and order.
    levels : sequence of float
        Depths at which the surface waves' exact operator is made, m, increasing, > 0; each place blends
        the two around its bulk depth (one level: a constant-depth floor, exact).
    bulk_length : float, optional
        σ of the Gaussian that separates the bulk, m, ≥ 2 cells (default: the deepest level, at least 8
        cells). The bulk holds waves with kσ ≲ 1, and the shallow-water solver's error on them is what is
        left in ω(k): measured 0.05 % / 0.15 % / 0.4 % / 1 % at 16 / 8 / 4 / 2 cells for 32–128 cells per
        wavelength, and below 2 cells the run blows up (docs/physics.md §1.15).
    taper : (float, float), optional
        Depths (m) between which surface waves fade into the bulk: none below ``taper[0]``, all above
        ``taper[1]``, which must be at least the shallowest level (default: a quarter of the shallowest level
        and the shallowest level). Shallower, waves are the bulk's: shallow water's speed, √(gh).
    sigma : float
        Surface tension, N/m (≥ 0; default 0: the bulk has none, so only the surface waves would feel it).
    rho : float
        Density, kg/m³, > 0.
    pressure : MovingPressure, optional
        A moving pressure patch (a boat) pushing the water.
    """

    solver: ShallowWater
    levels: tuple
    bulk_length: Optional[float] = None
    taper: Optional[tuple] = None
    sigma: float = 0.0
    rho: float = 1000.0
    pressure: Optional[MovingPressure] = None

    def __post_init__(self):
        check_instance("solver", self.solver, ShallowWater, "wavephys.simulation.shallow_water.ShallowWater")
        bad = [k for k in self.solver.sides if k not in ("wall", "periodic")]
        if bad:
            raise ValueError(f"solver.sides: the split model takes 'wall' or 'periodic' sides, got {bad[0]!r} "
                             f"(open and inflow sides would reflect its surface waves)")
        check_array("levels", self.levels, ndim=1, lo=0.0, lo_open=True)
        levels = tuple(float(v) for v in np.atleast_1d(np.asarray(self.levels, np.float64)))
        if len(levels) < 1 or len(levels) > 16:
            raise ValueError(f"levels must hold 1 to 16 depths, got {len(levels)}")
        if any(b <= a for a, b in zip(levels, levels[1:])):
            raise ValueError(f"levels must increase, got {levels}")
        object.__setattr__(self, "levels", levels)
        dx = self.solver.dx
        if self.bulk_length is None:
            object.__setattr__(self, "bulk_length", max(levels[-1], 8 * dx))
        check_scalar("bulk_length", self.bulk_length, lo=0.0, lo_open=True)
        if self.bulk_length < 2 * dx:
            raise ValueError(f"bulk_length must be at least 2 cells ({2 * dx:g} m; below, the split is unstable: "
                             f"docs/physics.md §1.15), got {self.bulk_length:g} m")
        object.__setattr__(self, "bulk_length", float(self.bulk_length))
        if self.taper is None:
            object.__setattr__(self, "taper", (0.25 * levels[0], levels[0]))
        check_array("taper", self.taper, ndim=1, shape_tail=(2,), lo=0.0)
        lo, hi = (float(v) for v in self.taper)
        if not hi > lo:
            raise ValueError(f"taper must be (shallow, deep) with deep > shallow, got {self.taper}")
        if hi < levels[0] * (1 - 1e-9):
            raise ValueError(f"taper[1] ({hi:g} m) must be at least the shallowest level ({levels[0]:g} m): surface "
                             f"waves shallower than every level would run at a deeper level's speed (and blow up)")
        object.__setattr__(self, "taper", (lo, hi))
        check_scalar("sigma", self.sigma, lo=0.0)
        check_scalar("rho", self.rho, lo=0.0, lo_open=True)
        object.__setattr__(self, "sigma", float(self.sigma))
        object.__setattr__(self, "rho", float(self.rho))
        if self.pressure is not None:
            check_instance("pressure", self.pressure, MovingPressure, "wavephys.simulation.split.MovingPressure")

    @property
    def water(self) -> Water:
        """The water of the surface waves (depth: the deepest level)."""
        return Water(g=self.solver.g, rho=self.rho, sigma=self.sigma, depth=self.levels[-1])


register(MovingPressure, ("start", "velocity", "head", "length", "beam"))
register(Split, ("solver", "levels", "bulk_length", "taper", "sigma", "rho", "pressure"))


# -- the spectral side: mirror images for walls, Fourier series for periodic axes --------------
def _extend(f, axis, odd):
    """f and its mirror image across the wall after the last cell (odd: with the sign flipped)."""
    mirror = jnp.flip(f, axis)
    return jnp.concatenate([f, -mirror if odd else mirror], axis=axis)


def _to_spectrum(split, f, odd_x=False, odd_y=False):
    wall_x = split.solver.sides[0] == "wall"
    wall_y = split.solver.sides[2] == "wall"
    if wall_x:
        f = _extend(f, -1, odd_x)
    if wall_y:
        f = _extend(f, -2, odd_y)
    return jnp.fft.rfft2(f)


def _from_spectrum(split, spec, shape):
    ny, nx = shape
    wall_x = split.solver.sides[0] == "wall"
    wall_y = split.solver.sides[2] == "wall"
    full = (2 * ny if wall_y else ny, 2 * nx if wall_x else nx)
    return jnp.fft.irfft2(spec, s=full)[..., :ny, :nx]


def _tables(split: Split, shape):
    """On the (extended) grid's half spectrum: |k|, the signed wavenumbers k_x and k_y of its derivatives (0 on
    the Nyquist rows, which a real derivative cannot hold), the bulk's Gaussian and the exact ω at each level,
    (J, my, mx//2 + 1); then the levels after a dry one, (J + 1,): all numpy float64, made on the host from a
    concrete ``split`` and handed to the compiled step as arrays (:class:`SplitStepper`)."""
    if is_traced(split):
        raise TypeError("split: the split's spectral tables are made from its concrete numbers, so a Split cannot "
                        "be traced (an argument of jax.jit or jax.vmap); close over it instead (the step is "
                        "compiled with its numbers traced all the same: one program serves every split)")
    # scalars held as arrays (a Split returned by a compiled function) hash as their numbers
    split = jax.tree_util.tree_map(lambda v: float(v) if np.ndim(v) == 0 else v, split)
    return _host_tables(split, tuple(shape))


@functools.lru_cache(maxsize=16)
def _host_tables(split: Split, shape):
    ny, nx = shape
    dx = split.solver.dx
    my = 2 * ny if split.solver.sides[2] == "wall" else ny
    mx = 2 * nx if split.solver.sides[0] == "wall" else nx
    ky = 2 * np.pi * np.fft.fftfreq(my, dx)[:, None]
    kx = 2 * np.pi * np.fft.rfftfreq(mx, dx)[None, :]
    k = np.sqrt(kx * kx + ky * ky)
    gauss = np.exp(-0.5 * (k * split.bulk_length) ** 2)
    omegas = []
    with jax.ensure_compile_time_eval(), jax.enable_x64(True):
        for h in split.levels:
            water = Water(g=split.solver.g, rho=split.rho, sigma=split.sigma, depth=h)
            omegas.append(np.asarray(angular_frequency(jnp.asarray(k, jnp.float64), water)))
    # the Nyquist rows and columns: a real derivative cannot hold them (the grid's 2-cell waves do not move)
    resolved = np.broadcast_to((np.arange(kx.shape[1]) * 2 != mx)[None, :] & (np.arange(my)[:, None] * 2 != my),
                               k.shape).astype(np.float64)
    dkx, dky = np.broadcast_to(kx, k.shape) * resolved, np.broadcast_to(ky, k.shape) * resolved
    levels = np.concatenate([[0.0], split.levels])
    return k, dkx, dky, gauss, np.stack(omegas), levels, resolved


def _taper(split, h):
    lo, hi = split.taper
    t = jnp.clip((h - lo) / (hi - lo), 0.0, 1.0)
    return t * t * (3 - 2 * t)


def _separate(split, bed, fields, tables):
    """Step 1: the surface waves x̃ = w (x − x̄), the smoothed x̄ (over the water; x itself where there is none),
    the taper w and η_ref (``tables``: :func:`_tables`)."""
    h = fields[0]
    shape = h.shape
    gauss = tables[3]
    gauss = jnp.asarray(gauss, h.dtype)
    w = _taper(split, h)
    eta = h + bed
    total = jnp.sum(w)
    ref = jnp.where(total > 0, jnp.sum(w * eta) / jnp.where(total > 0, total, 1.0), 0.0)
    x = jnp.stack([eta - ref, fields[1], fields[2]])
    den = _from_spectrum(split, gauss * _to_spectrum(split, w), shape)
    odd = ((False, False), (True, False), (False, True))
    nums = [_from_spectrum(split, gauss * _to_spectrum(split, w * x[i], *odd[i]), shape) for i in range(3)]
    inside = den > 1e-4
    bar = jnp.stack([jnp.where(inside, n / jnp.where(inside, den, 1.0), xi) for n, xi in zip(nums, x)])
    surf = w * (x - bar)
    # a crest may not take more than the water there: the bulk keeps h ≥ 0 (the solver would add water to a
    # negative depth: measured 5e-5 of a wake scene's water in 15 s before this)
    surf = surf.at[0].set(jnp.minimum(surf[0], h))
    return surf, bar, w, ref


def _advance_surface(split, waves, depth, dt, tables):
    """B x: one step of Δt of the surface waves x = (η, q_x, q_y) (3, ny, nx) over the bulk's ``depth`` (m).

    The waves obey η_t = −E ∇·q, q_t = −g E R ∇(E η), with R = Σⱼ √Rⱼ Wⱼ √Rⱼ: the weights Wⱼ linear in h between
    the levels (a dry level of depth 0 and R = 0 below the shallowest, so Σⱼ Wⱼ hⱼ = h), Rⱼ(k) level j's operator
    in Fourier space on both sides of its weight, and E the cells deeper than ``taper[0]`` (1 there, else 0:
    the waves move no water where they do not live; without it, a spectral derivative's ringing put water on the
    shoreline's nearly dry cells and made a depth of −4e-7 m in a run-up). R is symmetric and positive, so the
    waves keep the energy g η² + q·(E R E)⁻¹q for any weights, over any bed. Rⱼ → hⱼ for long waves, so the
    long-wave limit is linear shallow water, q_t = −g h ∇η, slope terms and all. Stepped by Störmer–Verlet (a
    half drift of η, a kick of q, a half drift), which keeps a nearby energy exactly, with
    Rⱼ = (ωⱼ/k)² sinc²(ωⱼΔt/2)/g: for one level the step then turns each wave by exactly ωⱼ(k)Δt, the exact
    dispersion at every kh. √Wⱼ on both sides of Rⱼ (which also keeps R symmetric) slowed a beach's standing
    wave by 1.6 % with two levels and 3.5 % with eight: √Wⱼ has a √ kink where a weight reaches 0. Derivatives
    are spectral (mirror images across walls); the 2-cell waves on the Nyquist rows have none and are taken
    out."""
    shape = waves.shape[1:]
    dtype = waves.dtype
    k, dkx, dky, _, omegas, levels, resolved = tables
    k = jnp.asarray(k, dtype)
    dkx, dky, resolved = jnp.asarray(dkx, dtype), jnp.asarray(dky, dtype), jnp.asarray(resolved, dtype)
    omegas = jnp.asarray(omegas, dtype)
    levels = jnp.asarray(levels, dtype)
    g = split.solver.g
    pos = k > 0
    half = 0.5 * dt
    # √Rⱼ(k), with its long-wave limit √hⱼ at k = 0 (jnp.sinc(x) = sin(πx)/(πx)); 0 on the Nyquist rows
    ratio = jnp.where(pos, omegas / jnp.where(pos, k, 1.0), 0.0)
    roots = resolved * jnp.where(pos, ratio * jnp.abs(jnp.sinc(omegas * half / jnp.pi)) / jnp.sqrt(g),
                                 _root(levels[1:, None, None]))
    weights = depth_weights(jnp.clip(depth, 0.0, split.levels[-1]), levels).astype(dtype)[1:]
    # where surface waves may live (the bulk deeper than the taper's start): the step moves no water elsewhere
    live = (depth > split.taper[0]).astype(dtype)
    odd = ((True, False), (False, True))

    def flux(q):
        return [_to_spectrum(split, q[i], *odd[i]) for i in range(2)]

    def divergence(spec):
        return 1j * (dkx * spec[0] + dky * spec[1])

    # half a drift of η, a kick of q, half a drift (9 + 4J real FFTs of the extended grid, J levels); the 2-cell
    # waves (no derivative, so no motion) are taken out in the same transforms: kept, rounding drove them to
    # 9e-5 m over a float32 lake at rest in 1200 s, where every other wave stayed at the 1e-6 m it was given
    eta, q = waves[0], waves[1:]
    unresolved = 1.0 - resolved
    before = flux(q)
    eta = eta - half * live * _from_spectrum(split, divergence(before), shape)
    spec = _to_spectrum(split, live * eta)
    out = [unresolved * before[0], unresolved * before[1]]
    for j in range(len(split.levels)):
        for i, d in enumerate((dkx, dky)):
            part = weights[j] * _from_spectrum(split, 1j * d * roots[j] * spec, shape)
            out[i] = out[i] + (dt * g) * roots[j] * _to_spectrum(split, part, *odd[i])
    q = q - live * jnp.stack([_from_spectrum(split, s, shape) for s in out])
    eta = eta - live * _from_spectrum(split, half * divergence(flux(q)) + unresolved * spec, shape)
    return jnp.concatenate([eta[None], q])


def _root(x):
    """√x for x ≥ 0, with a finite derivative at 0 (for jax.grad and jacfwd through a step)."""
    some = x > 0
    return jnp.where(some, jnp.sqrt(jnp.where(some, x, 1.0)), 0.0)


def _bulk_linear(solver, bed, depth, perturbation, t, dt):
    """L y: the bulk solver's step linearized about still water of ``depth`` (m), with its slopes unlimited (the
    linear scheme its minmod limits, so L is second order like the solver on smooth fields), applied to
    ``perturbation`` (3, ny, nx)."""
    rest = jnp.stack([depth, jnp.zeros_like(depth), jnp.zeros_like(depth)])
    return jax.jvp(lambda f: _linear_advance(solver, bed, f, t, dt), (rest,), (perturbation,))[1]


def _central(f, axis, periodic):
    """The derivative along ``axis`` times the spacing, by central differences (wrapping round a periodic axis;
    one-sided at a wall)."""
    if periodic:
        return 0.5 * (jnp.roll(f, -1, axis) - jnp.roll(f, 1, axis))
    return jnp.gradient(f, axis=axis)


def _force(split, bed, fields, t, dt):
    """The moving pressure's push on the discharges, −h ∇(p/ρ) Δt (central differences)."""
    p = split.pressure
    if p is None:
        return fields
    ny, nx = fields.shape[1:]
    dx = split.solver.dx
    y, x = jnp.meshgrid((jnp.arange(ny) + 0.5) * dx, (jnp.arange(nx) + 0.5) * dx, indexing="ij")
    sides = split.solver.sides
    period = (nx * dx if sides[0] == "periodic" else None, ny * dx if sides[2] == "periodic" else None)
    head = p.head_at(x.astype(fields.dtype), y.astype(fields.dtype), t, period)
    gx = _central(head, -1, sides[0] == "periodic") / dx
    gy = _central(head, -2, sides[2] == "periodic") / dx
    g = split.solver.g
    h = fields[0]
    return jnp.stack([h, fields[1] - dt * g * h * gx, fields[2] - dt * g * h * gy])


def _split_advance(split, bed, fields, t, dt, tables):
    """One step of the split (module doc, steps 1–3), ``split`` an argument of the compiled program (traced: the
    bulk solver's constants folded into the program make its step ×27 slower, and every split of one structure
    shares the program); ``tables``: :func:`_tables`."""
    solver = split.solver
    fields = _force(split, bed, fields, t, dt)
    surf, bar, w, ref = _separate(split, bed, fields, tables)
    bulk = fields - surf
    bulk_new = advance_fields(solver, bed, bulk, t, dt)
    bulk_depth = jnp.maximum(bar[0] + ref - bed, 0.0)
    inc = _advance_surface(split, surf + w * bar, bulk_depth, dt, tables) - _bulk_linear(solver, bed, bulk_depth, w * bar, t, dt)
    # the increment lands whole on every wet cell: the taper already chose the surface waves in step 1, and
    # weighting the increment by it again took w(1 − w)(x − x̄) from the water each step where it fades, which
    # destroyed Lamb's standing wave on a beach within a period (measured: amplitude left 5e-4 after three;
    # now −47 %, shallow water's own −44 %). The surface waves keep their water: what the blend of levels with
    # weights varying in space adds or takes (each level alone keeps it), and what −L would put on a dry cell,
    # goes back evenly over the surface-wave region
    inc = jnp.where(bulk_new[0] > split.solver.dry, inc, 0.0)
    w_new = _taper(split, bulk_new[0])
    lost = jnp.sum(surf[0] - inc[0])
    total = jnp.sum(w_new)
    spread = jnp.where(total > 0, lost / jnp.where(total > 0, total, 1.0), 0.0)
    new = bulk_new + inc.at[0].add(spread * w_new)
    dry = split.solver.dry
    wet = new[0] > dry
    return jnp.stack([new[0], jnp.where(wet, new[1], 0.0), jnp.where(wet, new[2], 0.0)])


def _check_split_run(split, fields, t, dt=None):
    try:
        check_run(split.solver, fields, t, dt)
    except ValueError as error:
        raise ValueError(_split_hint(split, error)) from None


def _split_hint(split, error):
    return (f"{error}; in the split model, a bulk_length of {split.bulk_length / split.solver.dx:.3g} cells (at "
            f"least 8 advised), surface waves steep near the taper's depths {split.taper} m, and waves as high as "
            f"the depth (a dam break, a bore: shallow water's alone, docs/physics.md §1.15) can do this too")


def _checked(split, bed, state):
    check_instance("split", split, Split, "wavephys.simulation.split.Split")
    check_instance("state", state, SWState, "wavephys.simulation.shallow_water.SWState")
    shape = np.shape(state.fields)
    if len(shape) != 3:
        raise ValueError(f"state.fields must have shape (3, ny, nx) (use jax.vmap for a batch), got {shape}")
    check_array("bed", bed, ndim=2, shape_tail=shape[1:])
    return jnp.asarray(bed, state.fields.dtype)


def split_parts(split: Split, bed, state: SWState):
    """The separation of step 1: (bulk, surface waves), each (3, ny, nx).

    The surface waves' planes are (η̃, q̃_x, q̃_y), m and m²/s; the bulk's are (h − η̃, q_x − q̃_x, q_y − q̃_y), so
    the two add up to the state's fields.

    Parameters
    ----------
    split : Split
    bed : array_like (ny, nx)
        Bed elevation, m.
    state : SWState

    Returns
    -------
    (jax.Array, jax.Array)
    """
    b = _checked(split, bed, state)
    surf = _separate(split, b, state.fields, _tables(split, tuple(np.shape(b))))[0]
    return state.fields - surf, surf


def _split_dt(split, fields):
    """The bulk solver's adaptive step, capped by the still-water waves' own Courant limit (and the boat's speed),
    so water at rest under a moving pressure is not stepped by an unbounded Δt."""
    solver = split.solver
    c = 2 * jnp.sqrt(solver.g * jnp.max(fields[0]))
    if split.pressure is not None:
        c = c + jnp.hypot(*split.pressure.velocity)
    cap = jnp.where(c > 0, solver.cfl * solver.dx / jnp.where(c > 0, c, 1.0), jnp.inf)
    return jnp.minimum(stable_dt_fields(solver, fields), cap)


@jax.jit
def _limit_program(split, fields):
    return _split_dt(split, fields) / split.solver.cfl


def _check_step(split, fields, dt):
    """ValueError naming ``dt`` for a concrete step past Courant number 1 of the bulk (or of the still-water
    waves and the boat); nothing under a trace."""
    if is_traced(fields) or is_traced(dt):
        return
    if not np.all(np.isfinite(np.asarray(fields))):
        raise ValueError("state: the fields hold NaN or inf values; a step needs a finite state")
    limit = float(_limit_program(split, jnp.asarray(fields)))
    if float(dt) > limit * (1 + 1e-5):
        raise ValueError(f"dt = {float(dt):.4g} s is past the stable step of the split: Courant number "
                         f"{float(dt) / limit:.3g} > 1 (the largest stable step here is {limit:.4g} s); take shorter "
                         f"steps, or leave dt out for the bulk's adaptive ones")


def split_step(split: Split, bed, state: SWState, dt: Optional[float] = None) -> SWState:
    """One step of the split model: Δt = ``dt`` when given, else the bulk solver's adaptive step.

    Parameters
    ----------
    split : Split
    bed : array_like (ny, nx)
        Bed elevation, m.
    state : SWState
        Depth and discharges (:func:`~wavephys.simulation.shallow_water.sw_state`).
    dt : float, optional
        s, > 0; a step past Courant number 1 of the bulk (the adaptive step over ``cfl``) is refused.

    Returns
    -------
    SWState
        At t + Δt. Pure: ``jax.jit`` and ``jax.vmap`` apply.
    """
    b = _checked(split, bed, state)
    if dt is None:
        _check_step(split, state.fields, 0.0)
    else:
        check_scalar("dt", dt, lo=0.0, lo_open=True)
        _check_step(split, state.fields, dt)
    out = _stepper(split, b).advance(state, 1, None if dt is None else jnp.asarray(dt, state.fields.dtype))
    fields, t = out.fields, out.time
    dt = jnp.inf if dt is None else dt
    if not is_traced(fields):
        _check_split_run(split, fields, t, dt if np.isfinite(float(dt)) else None)
    return SWState(fields, t)


def _stepper(split, bed):
    """The split behind the one stepper interface (wavephys.core.stepper): its loop is the runs' loop."""
    return SplitStepper(split, bed)


def _split_run(split: Split, bed, state: SWState, until: Optional[float] = None, *, steps: Optional[int] = None,
              dt: Optional[float] = None, max_steps: int = 1_000_000):
    """Advance to ``until`` with the bulk's adaptive steps, or ``steps`` steps of ``dt``.

    Parameters
    ----------
    split : Split
    bed : array_like (ny, nx)
        Bed elevation, m.
    state : SWState
    until : float, optional
        s, ≥ state.time.
    steps : int, optional
        Fixed steps of ``dt`` instead.
    dt : float, optional
        s, with ``steps``.
    max_steps : int
        Adaptive steps allowed, ≥ 1.

    Returns
    -------
    (SWState, int)
        The state at the end and the number of steps.

    Raises
    ------
    ValueError
        When the run makes a negative depth or a non-finite value (naming ``cfl`` or ``dt``), or runs out
        of ``max_steps``.
    """
    b = _checked(split, bed, state)
    if (until is None) == (steps is None):
        raise ValueError("give either until (adaptive steps) or steps and dt (fixed steps)")
    if steps is not None:
        steps = check_int("steps", steps, lo=1)
        if dt is None:
            raise ValueError("steps needs dt (s)")
        check_scalar("dt", dt, lo=0.0, lo_open=True)
        _check_step(split, state.fields, dt)
        end = _stepper(split, b).advance(state, steps, jnp.asarray(dt, state.fields.dtype))
        fields, t = end.fields, end.time
        if not is_traced(fields):
            _check_split_run(split, fields, t, dt)
        return SWState(fields, t), steps
    if dt is not None:
        raise ValueError("dt is for fixed steps (with steps); adaptive steps (until) choose their own")
    check_scalar("until", until)
    max_steps = check_int("max_steps", max_steps, lo=1)
    if not (is_traced(state.time) or is_traced(until)) and float(until) < float(state.time):
        raise ValueError(f"until must not be before the state's time {float(state.time)}, got {until}")
    end, n = _stepper(split, b).advance_to(state, jnp.asarray(until, state.fields.dtype), max_steps)
    fields, t = end.fields, end.time
    if not is_traced(fields):
        _check_split_run(split, fields, t)
        if float(t) < float(np.asarray(until, np.asarray(t).dtype)):  # in the state's precision
            raise ValueError(f"max_steps = {max_steps} steps reached t = {float(t):.6g} s, not until = {until} s")
        n = int(n)
    return SWState(fields, t), n


def _split_frames(split: Split, bed, state: SWState, times, max_steps: int = 1_000_000) -> SWState:
    """The states at each of ``times`` (s, non-decreasing, ≥ state.time), stacked: fields (T, 3, ny, nx).

    Parameters
    ----------
    split : Split
    bed : array_like (ny, nx)
    state : SWState
    times : array_like (T,)
    max_steps : int
        Steps allowed between two frames, ≥ 1.

    Returns
    -------
    SWState
    """
    b = _checked(split, bed, state)
    check_array("times", times, ndim=1)
    ts = np.asarray(times, np.float64)
    if np.any(np.diff(ts) < 0) or ts[0] < float(state.time) - 1e-12:
        raise ValueError("times must be non-decreasing and not before the state's time")
    max_steps = check_int("max_steps", max_steps, lo=1)
    out = _stepper(split, b).frames(state, ts, max_steps)
    fields, t = out.fields, out.time
    _check_split_run(split, fields, t)
    if bool(jnp.any(t < jnp.asarray(ts, t.dtype))):
        raise ValueError(f"max_steps = {max_steps} steps were not enough between two frames")
    return SWState(fields, t)


split_run = deprecated_function(
    _split_run, "split_run",
    "wavephys.steppers.SplitStepper(split, bed).run(state, until=...) (the pure forms: .advance, .advance_to)")


split_frames = deprecated_function(
    _split_frames, "split_frames",
    "wavephys.steppers.SplitStepper(split, bed).run(state, until=..., every=...) (the pure form: .frames)")


class SplitStepper(ShallowWaterStepper):
    """Shallow water with dispersive surface waves (:mod:`wavephys.simulation.split`), adaptive steps.

    Parameters
    ----------
    split : Split
    bed : array_like (ny, nx)
        m.
    """

    def __init__(self, split, bed):

        check_instance("split", split, Split, "wavephys.simulation.split.Split")
        check_array("bed", bed, ndim=2)
        self.split, self.solver, self.bed, self.state_type = split, split.solver, _bed(bed), SWState
        self._device_tables = {}

    def init(self, state):
        state = self._checked_state(state)
        if np.shape(state.fields)[1:] != self.bed.shape or np.ndim(state.fields) != 3:
            raise ValueError(f"state.fields must have shape (3,) + the bed's {self.bed.shape}, got "
                             f"{np.shape(state.fields)}")
        return state

    def _parts(self):
        # the tables on the device once per precision (a float64 table is float32 with x64 off), not per call
        precision = jax.dtypes.canonicalize_dtype(np.float64)
        if precision not in self._device_tables:
            # concrete arrays even when first asked for inside a trace (a tracer kept here leaked into the next
            # call: jit, then grad, of one stepper failed)
            with jax.ensure_compile_time_eval():
                self._device_tables[precision] = jax.device_put(_tables(self.split, self.bed.shape))
        return None, (self.split, jnp.asarray(self.bed), self._device_tables[precision])

    def _limit(self, state):
        return float(_limit_program(self.split, state.fields))

    def step(self, state, dt=None):
        return Stepper.step(self, state, dt)

    @staticmethod
    def _finite(state):
        """Finite, and no depth below −rounding: a run stops there (a split that blows up, as on a dam break, would
        otherwise go on with ever shorter steps)."""
        h = state.fields[0]
        rounding = 1e3 * jnp.finfo(h.dtype).eps * jnp.max(jnp.abs(jnp.where(jnp.isfinite(h), h, 0.0)))
        return Stepper._finite(state) & (jnp.min(h) >= -rounding)

    def _result(self, state):
        try:
            return super()._result(state)
        except ValueError as error:
            raise ValueError(_split_hint(self.split, error)) from None

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        split, bed, tables = dynamic
        fields = _split_advance(split, bed.astype(state.fields.dtype), state.fields, state.time, dt, tables)
        return type(state)(fields, state.time + dt)

    @classmethod
    def _dt(cls, static, dynamic, state):
        return _split_dt(dynamic[0], state.fields)

    @classmethod
    def _height(cls, static, dynamic, state):
        return dynamic[1].astype(state.fields.dtype) + state.fields[0]
