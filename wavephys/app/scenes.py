"""Built-in scenes that need no input files: the default simulation scene, and the renderer's
``pool``, ``shore`` and ``ship``.

``pool``  an 8 m square holding a 6.9 m pool (tiled floor 1.5 m deep, walls out of the water)
          with ring waves of three stones from the spectral simulation of a tank whose
          walls reflect them (docs/physics.md §1.11), caustics by the Jacobian gather
          (:data:`CAUSTICS_METHODS`);
``shore`` a 16 m sandy beach rising out of the water under a three-component swell that feels the
          floor: it slows, shortens, turns towards the beach and grows as the water shoals (the
          symmetric depth blend, docs/physics.md §1.12), then is damped in the surf zone; made along
          the offshore side by a relaxation zone; caustics on the sloping ground;
``ship``  a 40 m patch of 8 m deep water with the steady Kelvin wake of a hull at 2 m/s;
          ``ship=False`` gives the same frame without the ship (for comparisons).
``storm`` a 64 m patch of open sea under a 9 m/s wind: a Phillips sea with choppy
          displacement (λ = 1, crests sharpened; resampled onto the grid) and foam where
          the surface is compressed below 35 % of its rest area, built up over the last
          1.5 s and fading with a 1 s time constant, broken into streaks by a fixed
          gradient-noise texture;
``calm``  a 16 m pond in the style of Schneider & Westermann: a B-spline base surface from
          an 8 × 8 control grid plus two octaves of animated gradient-noise fBm.
``beach`` a 16 m sandy beach with a bar and cusps, where a 0.15 m solitary wave from the open
          sea steepens into a bore and runs up the sand and back (nonlinear shallow water with
          wetting and drying, docs/physics.md §1.13; a new wave every 8 s);
``dambreak`` a 16 m walled yard: a reservoir 1 m deep bursts through a 3 m breach in its wall and
          floods the dry ground around four blocks (the same solver; the dam breaks again every 12 s).
``harbour`` a 32 m basin 4 m deep along a stone quay: a boat at 2.5 m/s runs parallel to the quay 6 m
          off it, and its Kelvin wake reflects from the quay wall (the spectral step with one reflecting
          side, docs/physics.md §1.11, and an open-sea margin on the others; the boat passes every 12 s).
``wakebeach`` a 32 m strip of coast: a boat at 2.5 m/s runs along the shore over 2 m of water, and
          its Kelvin wake (4 m waves, kh ≈ 3) crosses to a sandy beach and runs up it (the split
          model, docs/physics.md §1.15: shallow water alone would give no wake at all at this
          depth Froude number of 0.56; the boat passes again every 12.8 s).

Every field is made on a :class:`wavephys.Grid` of the scene's side and resolution, so the
simulated water, the ground, the caustics and the textures share one convention and
land texel for texel (docs/physics.md §0). Every scene is lit by Preetham's analytic sky
and continues beyond its square to the horizon (:data:`SURROUNDINGS`).
"""

from __future__ import annotations

import functools
import math
from typing import Callable, Iterator, Optional

import numpy as np

from optics.rendering.scene import Camera, Scene, look_at
from wavephys.app import SCENES
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_array, check_bool, check_choice, check_instance, check_int, check_scalar
from wavephys.core.water import Water
from wavephys.physics.disturbances import Stones

__all__ = ["default_scene", "SCENES", "builtin_scene", "scene_frames", "scene_water", "scene_grid",
           "scene_displacement", "scene_caustics", "CAUSTICS_METHODS"]

SUN = (0.35, -0.45, 0.82)
MAX_TIME = 3600.0
"""Latest time of a built-in scene, s (the pool steps its simulation up to it)."""
MAX_N = 8192
"""Largest resolution of a built-in scene, texels per side."""
POOL_LENGTH, POOL_DEPTH, POOL_TANK = 8.0, 1.5, 6.9  # scene side, water depth, side between the walls (m)
SHORE_LENGTH = 16.0
SHORE_WARMUP, SHORE_CYCLE = 16.0, 16.0  # s: the swell has crossed to the beach; frames repeat after a cycle
SHORE_RELAX, SHORE_SURF = (-8.0, -5.5), (0.35, 0.05, 3.0)  # relaxation zone x (m); surf damping depths (m), rate 1/s
SWELL = ((4, 0, 0.05, 0.0), (5, 1, 0.03, 1.3), (3, -1, 0.035, 2.1))  # (m_x, m_y, amplitude m, phase)
SHIP_LENGTH, SHIP_SPEED, SHIP_DEPTH = 40.0, 2.0, 8.0
STORM_LENGTH, STORM_WIND, STORM_CHOPPINESS, STORM_DEPTH = 64.0, 9.0, 1.0, 20.0
STORM_FOAM = dict(threshold=0.35, softness=0.12, decay_time=1.0, history=1.5, fps=15.0)
CALM_LENGTH = 16.0
BEACH_LENGTH, BEACH_DEPTH, BEACH_WAVE, BEACH_CYCLE = 16.0, 1.2, 0.15, 8.0  # side, offshore depth, wave height (m), s
DAM_LENGTH, DAM_RESERVOIR, DAM_CYCLE = 16.0, 1.0, 12.0  # side, reservoir depth (m), s
WAKE_LENGTH, WAKE_DEPTH, WAKE_SPEED, WAKE_TRACK = 32.0, 2.0, 2.5, -5.0  # side, offshore depth (m), boat m/s, x (m)
WAKE_CYCLE, WAKE_WARMUP = WAKE_LENGTH / WAKE_SPEED, 10.0  # s: a boat passage; the scene's t = 0 is 10 s into one
HARBOUR_LENGTH, HARBOUR_DEPTH, HARBOUR_SPEED, HARBOUR_TRACK = 32.0, 4.0, 2.5, 6.0  # side, depth (m), boat m/s, y (m)
HARBOUR_QUAY, HARBOUR_RUN, HARBOUR_CYCLE = 1.0, 6.4, 12.0  # quay band (m); the boat runs 6.4 s of every 12 s
LENGTHS = {"pool": POOL_LENGTH, "shore": SHORE_LENGTH, "ship": SHIP_LENGTH, "storm": STORM_LENGTH,
           "calm": CALM_LENGTH, "beach": BEACH_LENGTH, "dambreak": DAM_LENGTH, "wakebeach": WAKE_LENGTH,
           "harbour": HARBOUR_LENGTH}
SHALLOW_WATER_CYCLES = {"beach": BEACH_CYCLE, "dambreak": DAM_CYCLE, "wakebeach": WAKE_CYCLE}
"""The scenes run by nonlinear shallow water, and the period (s) after which each starts again
from rest (time is taken modulo it, so a frame at any time costs at most one cycle of steps)."""

CAUSTICS_METHODS = {"pool": "jacobian", "shore": "beam", "ship": "jacobian", "storm": "beam", "calm": "beam",
                    "beach": "beam", "dambreak": "beam", "wakebeach": "beam", "harbour": "jacobian"}
"""Each built-in scene's caustics method (:data:`optics.caustics.FLOOR_IRRADIANCE_METHODS`): the
Jacobian gather (with the exact beam on its folded windows) where it is as close to the converged
reference as the beam on the scene's own surface, else the beam (the bores of the shallow-water
scenes are steep fronts that fold: the beam); measured by
``python -m bench jacobian`` (docs/physics.md §2.4): the storm folds over more than half its
floor (the gather would save nothing) and the calm pond's noise has waves of 2–3 samples, where
the gather erred 1.4 % of the peak at refine 1 against the beam's 0.4 % (and would hand it to
the beam: such a surface needs finer fields than a ground on its grid allows)."""


def default_scene(n: int = 256, steps: int = 120, progress: Optional[Callable[[str], None]] = None):
    """A 16 m patch of open water: three stones, 30 steps per second, margin n/8.

    Returns a dict with the final ``eta`` (m), ``eta_dot`` (m/s), ``dx`` (m), ``time`` (s)
    and ``energy_ratio`` (energy after / before the steps with the cutoff off, as a
    sanity figure: 1 to rounding).

    Parameters
    ----------
    n : int
        Grid points per side, even, 128 to 8192 (:data:`MAX_N`).
    steps : int
        Time steps of 1/30 s to run, 1 to 10⁶.
    progress : callable, optional
        Called with one message (str) before the steps run.

    Returns
    -------
    dict
        ``eta`` (numpy.ndarray, (n, n), m) and ``eta_dot`` (numpy.ndarray, (n, n), m/s): the final
        surface; ``dx`` (float, m): the grid spacing; ``time`` (float, s): the final time;
        ``energy_ratio`` (float): energy after / before the same steps without the cutoff margin.

    Raises
    ------
    TypeError
        When ``progress`` is neither callable nor None, or ``n`` or ``steps`` is not an integer.
    ValueError
        When ``n`` or ``steps`` is out of range or ``n`` is odd.
    """
    from wavephys.simulation import Simulation

    n = check_int("n", n, lo=128, hi=MAX_N, even=True)
    steps = check_int("steps", steps, lo=1, hi=10**6)
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be a function of one message (or None), got {type(progress).__name__}")
    grid = Grid(n, 16.0)
    sim = Simulation(grid, Water(), dt=1.0 / 30.0, margin=max(1, n // 8))
    state = sim.drop(sim.initial_state(), Stones([-3.0, 2.0, 0.5], [1.0, -2.5, 3.0], [0.25, 0.15, 0.3],
                                                 [0.05, 0.03, 0.06]))
    free = Simulation(grid, Water(), dt=sim.dt)
    e0 = float(free.energy(state))
    (progress or (lambda _m: None))(f"running {steps} steps on {n}x{n} ...")
    final_free, _ = free.run(state, steps)
    state, _ = sim.run(state, steps)
    last = sim.surface(state)
    return dict(eta=np.asarray(last.eta), eta_dot=np.asarray(last.eta_dot), dx=float(grid.dx),
                time=float(last.time), energy_ratio=float(free.energy(final_free)) / e0)


def scene_grid(name: str, n: int) -> Grid:
    """The grid every field of built-in scene ``name`` lives on.

    Parameters
    ----------
    name : str
        A built-in scene, one of :data:`SCENES` (``"pool"``, ``"shore"``, ``"ship"``, ``"storm"``,
        ``"calm"``).
    n : int
        Grid points per side, even, ≥ 2 (checked by :class:`wavephys.Grid`).

    Returns
    -------
    Grid
        ``Grid(n, length)`` with the scene's side length, m (8 pool, 16 shore, 40 ship, 64 storm,
        16 calm, 16 beach, 16 dambreak, 32 wakebeach, 32 harbour).

    Raises
    ------
    ValueError
        When ``name`` is not a built-in scene.
    """
    return Grid(n, LENGTHS[check_choice("name", name, SCENES)])


def _mesh(name, n):
    return tuple(np.asarray(a, np.float64) for a in scene_grid(name, n).mesh())


def _smoothstep(e0, e1, x):
    t = np.clip((x - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3 - 2 * t)


def _caustics(eta, grid: Grid, ground, method: str = "beam", **options):
    """Floor irradiance relative to flat water (ground height field below the water) by ``method``."""
    from optics.caustics import floor_irradiance

    floor = np.minimum(ground, eta.min() - 0.05).astype(np.float32)
    wavy = np.asarray(floor_irradiance(eta.astype(np.float32), grid, floor, SUN, method=method, **options))
    flat = np.asarray(floor_irradiance(np.zeros_like(eta, np.float32), grid, floor, SUN, method=method, **options))
    return (wavy / np.maximum(flat, 1e-6)).astype(np.float32)


def _pool_tank(n):
    """(samples per side, side, m) of the pool's water: the tank inside its walls, a whole even number of
    the scene's texels, centred (so that its samples are texels of the scene's grid)."""
    dx = POOL_LENGTH / n
    inner = 2 * int(round(POOL_TANK / dx / 2))
    return inner, inner * dx


def _pool_ground(n):
    X, Y = _mesh("pool", n)
    r = np.maximum(np.abs(X), np.abs(Y))
    edge = 0.5 * _pool_tank(n)[1]
    wall = _smoothstep(edge - 0.04, edge + 0.12, r)  # the tank's walls rise where the simulation reflects
    ground = -POOL_DEPTH + (POOL_DEPTH + 0.3) * wall
    tile = 0.5  # m; soft grout lines
    grout = np.clip(np.cos(np.pi * X / tile) ** 40 + np.cos(np.pi * Y / tile) ** 40, 0, 1)
    albedo = np.array([0.55, 0.78, 0.86]) * (1 - 0.45 * grout[..., None])
    albedo = albedo * (1 - wall[..., None]) + np.array([0.85, 0.85, 0.82]) * wall[..., None]
    return ground.astype(np.float32), albedo.astype(np.float32)


def _pool_simulation(n, dt=1.0 / 30.0):
    """The pool's water: a tank with reflecting walls (docs/physics.md §1.11) inside the scene's square."""
    from wavephys.simulation import Simulation

    inner, side = _pool_tank(n)
    sim = Simulation(Grid(inner, side), Water(depth=POOL_DEPTH), dt=dt, walls="all")
    stones = Stones([-1.2, 1.0, 0.3], [0.8, -1.0, 1.5], [0.15, 0.13, 0.18], [0.04, 0.03, 0.05])  # R >= dx at n >= 64
    return sim, sim.drop(sim.initial_state(), stones)


def _pool_heights(sim, state, n):
    """The tank's heights on the scene's grid (still water on the rim outside the walls), float32."""
    eta = np.asarray(sim.surface(state).eta, np.float32)
    pad = (n - eta.shape[0]) // 2
    return np.pad(eta, pad)


def _harbour_simulation(n):
    """(simulation, the quay band in texels, the boat): the basin's water is the scene's square less a band along
    its top, whose lower edge is the quay wall (a reflecting side); the other three sides are open sea."""
    from wavephys.physics.ship_waves import Hull, Ship, straight_path
    from wavephys.simulation import Simulation

    dx = HARBOUR_LENGTH / n
    band = 2 * int(math.ceil(HARBOUR_QUAY / dx / 2))
    inner = n - band
    sim = Simulation(Grid(inner, inner * dx), Water(depth=HARBOUR_DEPTH), dt=1.0 / 30.0, walls=("top",),
                     margin=max(2, inner // 16), ship_patch=min(inner, 2 * int(round(4.0 / dx))))  # an 8 m patch
    track = HARBOUR_TRACK + band * dx / 2  # the basin's grid is centred below the band
    boat = Ship(Hull("gaussian", 3.0, 1.2), straight_path((-8.0, track), (HARBOUR_SPEED, 0.0)), 0.3)
    return sim, band, boat


def _harbour_heights(n, times):
    """The basin's heights on the scene's grid at each of ``times`` (s, modulo :data:`HARBOUR_CYCLE`), float32
    (len(times), n, n); still water under the quay band (the ground is above it there)."""
    sim, band, boat = _harbour_simulation(n)
    phases = np.mod(np.asarray(times, np.float64), HARBOUR_CYCLE)
    order = np.argsort(phases, kind="stable")
    out = np.zeros((len(phases), n, n), np.float32)
    state, step = sim.initial_state(), 0
    for i in order:
        target = int(round(phases[i] / sim.dt))
        while step < target:
            state, _ = sim.step(state, ships=[boat] if step * sim.dt < HARBOUR_RUN else [])
            step += 1
        out[i, :n - band, band // 2:n - band // 2] = np.asarray(sim.surface(state).eta, np.float32)
    return out


def _harbour_ground(n):
    X, Y = _mesh("harbour", n)
    band = 2 * int(math.ceil(HARBOUR_QUAY / (HARBOUR_LENGTH / n) / 2))
    quay = (np.arange(n) >= n - band)[:, None] * np.ones((1, n))  # the band's rows: the quay, 1.2 m above the water
    relief = 0.3 * np.sin(0.4 * X + 0.3 * Y) * np.cos(0.25 * Y - 0.2 * X)  # a muddy, uneven basin floor
    ground = np.where(quay > 0, 1.2, -HARBOUR_DEPTH + relief)
    face = np.arange(n)[:, None] < n - band // 2  # the quay's face and coping: one course of blocks; the top
    blocks = 1 + 0.12 * face * np.sign(np.sin(np.pi * X / 1.5))  # beyond is plain (extended past the square)
    stone = np.array([0.62, 0.6, 0.56]) * blocks[..., None]
    mud = np.array([0.36, 0.34, 0.26]) * (1 + 0.1 * np.sin(1.3 * X) * np.cos(1.1 * Y))[..., None]
    albedo = np.where(quay[..., None] > 0, stone, mud)
    return ground.astype(np.float32), albedo.astype(np.float32)


def _shore_ground(n):
    X, Y = _mesh("shore", n)
    fade = _border_window("shore", n, 0.7)  # relief and ripples fade out at the border: the sand extended
    # beyond the square (surroundings) continues plain, with no stripes drawn out of the border texels
    ground = (-2.0 + 2.6 * (X + SHORE_LENGTH / 2) / SHORE_LENGTH
              + 0.04 * fade * np.sin(2.3 * Y + 0.7 * X) * np.cos(1.7 * X))
    wet = _smoothstep(0.15, -0.3, ground)
    sand = np.array([0.80, 0.72, 0.52]) * (1 - 0.25 * wet[..., None])
    ripple = 1 + 0.08 * fade * np.sin(9.0 * X + 2.0 * np.sin(1.3 * Y))
    return ground.astype(np.float32), (sand * ripple[..., None]).astype(np.float32)


@functools.lru_cache(maxsize=4)
def _shore_setup(n):
    """(model, floor, relaxation weights, surf damping per step, swell components (kx, ky, ω, a, phase)) of the
    shore: linear waves over the beach's floor by the symmetric depth blend (docs/physics.md §1.12)."""
    from wavephys.physics.dispersion import angular_frequency
    from wavephys.simulation import Model
    from wavephys.simulation.depth import Floor

    X = _mesh("shore", n)[0]
    ground = _shore_ground(n)[0].astype(np.float64)
    depth = np.maximum(-ground, 0.0)
    model = Model(scene_grid("shore", n), Water(sigma=0.0), dt=1.0 / 30.0)
    deep = Water(sigma=0.0, depth=float(depth[:, 0].mean()))
    components = []
    for mx, my, a, phase in SWELL:  # periodic along the shore, so the swell and its caustics have no seams
        kx, ky = 2 * np.pi * mx / SHORE_LENGTH, 2 * np.pi * my / SHORE_LENGTH
        components.append((kx, ky, float(angular_frequency(np.hypot(kx, ky), deep)), a, phase))
    relax = np.where(X < SHORE_RELAX[1], _smoothstep(SHORE_RELAX[1], SHORE_RELAX[0], X), 0.0)
    surf = np.exp(-SHORE_SURF[2] * _smoothstep(SHORE_SURF[0], SHORE_SURF[1], depth) * model.dt) * (depth > 0)
    return model, Floor(depth, levels=4), relax, surf, tuple(components)


def _shore_swell(n, t):
    """The incoming swell's (η, φ) at time t, m and m²/s (deep-water components at the offshore depth)."""
    X, Y = _mesh("shore", n)
    eta, phi = np.zeros((n, n)), np.zeros((n, n))
    for kx, ky, w, a, phase in _shore_setup(n)[4]:
        theta = kx * X + ky * Y - w * t + phase
        eta += a * np.cos(theta)
        phi += 9.81 * a / w * np.sin(theta)
    return eta, phi


def _shore_heights(n, times):
    """The shore's heights at each of ``times`` (s, modulo :data:`SHORE_CYCLE`, after :data:`SHORE_WARMUP`),
    float32 (len(times), n, n). Each step of the symmetric depth blend is followed by the relaxation zone along
    the offshore side (the water there is pulled to the incoming swell: it makes the swell and takes what the
    beach sends back) and by a surf-zone damping where the water is shallower than 35 cm (a crude stand-in for
    breaking: linear waves would steepen without limit at the shoreline)."""
    from wavephys.simulation.depth import depth_state
    from wavephys.simulation.steppers import DepthStepper

    model, floor, relax, surf, _ = _shore_setup(n)
    stepper = DepthStepper(model, floor, "symmetric")
    phases = SHORE_WARMUP + np.mod(np.asarray(times, np.float64), SHORE_CYCLE)
    order = np.argsort(phases, kind="stable")
    out = np.zeros((len(phases), n, n), np.float32)
    state = depth_state(model, *(f * relax for f in _shore_swell(n, 0.0)))
    step = 0
    for i in order:
        target = int(round(phases[i] / model.dt))
        while step < target:
            state = stepper.advance(state, 1)
            step += 1
            want_eta, want_phi = _shore_swell(n, step * model.dt)
            eta, phi = np.asarray(state.eta, np.float64), np.asarray(state.phi, np.float64)
            state = depth_state(model, (eta + relax * (want_eta - eta)) * surf,
                                (phi + relax * (want_phi - phi)) * surf, step * model.dt)
        out[i] = np.asarray(state.eta, np.float32)
    return out


def _ship_wake(n, t):
    from wavephys.physics.wake import GaussianPressure, steady_wake

    grid = scene_grid("ship", n)
    size = max(0.6, SHIP_LENGTH / n)  # resolved on coarse grids too
    eta = steady_wake(grid, Water(sigma=0.0), SHIP_SPEED, GaussianPressure(800.0, size), damping=0.08)  # fades over 25 m
    eta = np.asarray(grid.shift(eta, -5.0 + SHIP_SPEED * t), np.float64)
    return (eta * _border_window("ship", n, 0.8)).astype(np.float32)  # calm at the border, and beyond


def _border_window(name, n, inner=0.75):
    """1 inside ``inner`` of the half-side, 0 at the border: relief that fades out there, so the
    ground extended beyond the square (surroundings) shows no stripes."""
    X, Y = _mesh(name, n)
    edge = LENGTHS[name] / 2
    return _smoothstep(edge, inner * edge, np.abs(X)) * _smoothstep(edge, inner * edge, np.abs(Y))


def _ship_ground(n):
    X, Y = _mesh("ship", n)
    w = _border_window("ship", n)
    ground = -SHIP_DEPTH + 0.3 * np.sin(0.4 * X) * np.cos(0.3 * Y) * w
    albedo = np.array([0.55, 0.6, 0.5]) * (1 + 0.15 * w * np.sin(1.1 * X + 0.8 * Y))[..., None]
    return ground.astype(np.float32), albedo.astype(np.float32)


def _storm_sea(n):
    """The storm's complex travelling sea (seeded) on its grid."""
    import jax

    from wavephys.physics.wind import synthesize_height, wind_spectrum

    grid = scene_grid("storm", n)
    ky, kx = grid.wavenumbers()
    spectrum = wind_spectrum(kx, ky, Water(sigma=0.0), "phillips", wind_speed=STORM_WIND, amplitude=2.2e-2,
                             direction=0.4, small_wave_length=max(0.3, 2 * STORM_LENGTH / n))
    return synthesize_height(spectrum, grid, jax.random.PRNGKey(11)), grid


def _storm_fields(sea, grid, t):
    """(heights, Jacobian) over the grid points at time t: the choppy sea resampled."""
    from wavephys.surfaces import choppy
    from wavephys.surfaces.resample import resample_heights

    h = choppy.sea_height(sea, grid, Water(sigma=0.0), t)
    d = choppy.displacement(h, grid, STORM_CHOPPINESS)
    jac = choppy.jacobian(h, grid, STORM_CHOPPINESS)
    both = resample_heights(d, h, grid, refine=2), resample_heights(d, jac, grid, refine=2)
    return np.asarray(both[0], np.float32), np.asarray(both[1], np.float32)


def scene_displacement(name: str, n: int = 256, time: float = 0.0):
    """The vector displacement (3, n, n) (Δx, Δy, z), m, of a built-in scene whose surface is
    displaced (``"storm"``: the choppy sea in its rest coordinates), else None.

    Parameters
    ----------
    name : str
        A built-in scene, one of :data:`SCENES`.
    n : int
        Grid points per side, even, 64 to 8192 (:data:`MAX_N`).
    time : float
        Seconds after the start, s, 0 to 3600 (:data:`MAX_TIME`).

    Returns
    -------
    numpy.ndarray or None
        float32 array of shape (3, n, n): the horizontal displacement (Δx, Δy) and the height z, m,
        at each rest grid point of :func:`scene_grid`; None for scenes without displacement (all but
        ``"storm"``).
    """
    check_choice("name", name, SCENES)
    n = check_int("n", n, lo=64, hi=MAX_N, even=True)
    check_scalar("time", time, lo=0.0, hi=MAX_TIME)
    if name != "storm":
        return None
    from wavephys.surfaces import choppy

    sea, grid = _storm_sea(n)
    h = choppy.sea_height(sea, grid, Water(sigma=0.0), float(time))
    d = choppy.displacement(h, grid, STORM_CHOPPINESS)
    return np.concatenate([np.asarray(d, np.float32), np.asarray(h, np.float32)[None]])


def _storm_frames(n, times):
    """(heights, foam) at each of the increasing ``times``: foam built up frame by frame."""
    from wavephys.surfaces import choppy

    sea, grid = _storm_sea(n)
    cfg = STORM_FOAM
    start = max(0.0, times[0] - cfg["history"])
    warm = list(np.arange(start, times[0], 1.0 / cfg["fps"]))
    foam, last, out = None, None, []
    for t in warm + list(times):
        h, jac = _storm_fields(sea, grid, t)
        cover = np.asarray(choppy.foam(jac, cfg["threshold"], cfg["softness"]), np.float32)
        foam = cover if foam is None else np.asarray(
            choppy.accumulate_foam(foam, cover, t - last, cfg["decay_time"]), np.float32)
        last = t
        if t in times:
            out.append((h, np.clip(foam * _foam_texture(n), 0.0, 1.0)))
    return out


def _foam_texture(n):
    """A fixed streaky modulation in [0, 1.6] (gradient-noise fBm, 4 octaves, stretched along the wind)."""
    from wavephys.surfaces.noise import fbm

    X, Y = _mesh("storm", n)
    u, v = X * np.cos(0.4) + Y * np.sin(0.4), -X * np.sin(0.4) + Y * np.cos(0.4)
    tex = np.asarray(fbm(u * 0.35, v, None, octaves=4, frequency=1.0, seed=5), np.float64)
    return np.clip(0.8 + 2.0 * tex, 0.0, 1.6).astype(np.float32)


def _storm_ground(n):
    X, Y = _mesh("storm", n)
    ground = -STORM_DEPTH + 1.5 * np.sin(0.11 * X + 0.3) * np.cos(0.09 * Y)
    albedo = np.array([0.3, 0.34, 0.3]) * (1 + 0.2 * np.sin(0.5 * X + 0.7 * Y))[..., None]
    return ground.astype(np.float32), albedo.astype(np.float32)


def _calm_sea(n: int = 256):
    """The pond's noise: two octaves, or one on a grid too coarse for the second (the finest octave's lattice
    cell must span 2 texels, or it aliases: one octave at n = 64)."""
    import math

    from wavephys.surfaces.noise import NoiseSea

    frequency, dx = 1.5, CALM_LENGTH / n
    fits = int(math.floor(math.log2(1.0 / (frequency * 2 * dx)))) + 1  # octaves whose cell spans >= 2 texels
    return NoiseSea(length=CALM_LENGTH, amplitude=0.01, frequency=frequency, octaves=max(1, min(2, fits)),
                    hurst=1.0, seed=3, evolution=0.35, time_exponent=0.5, base_amplitude=0.03)


def _calm_ground(n):
    X, Y = _mesh("calm", n)
    r = np.hypot(X / 7.2, Y / 7.2)
    w = _border_window("calm", n)
    ground = -1.6 + 1.9 * _smoothstep(0.75, 1.05, r) + 0.05 * np.sin(1.7 * X) * np.sin(1.3 * Y) * w
    pebbles = 1 + 0.12 * w * np.sin(5.0 * X + 1.5 * np.sin(2.1 * Y)) * np.sin(4.3 * Y)
    albedo = np.array([0.62, 0.58, 0.45]) * pebbles[..., None]
    grass = _smoothstep(-0.05, 0.2, ground)[..., None]
    albedo = albedo * (1 - grass) + np.array([0.25, 0.4, 0.18]) * grass
    return ground.astype(np.float32), albedo.astype(np.float32)


def _beach_bed(n):
    X, Y = _mesh("beach", n)
    bed = -BEACH_DEPTH + 1.6 * (X + BEACH_LENGTH / 2) / BEACH_LENGTH  # the still shoreline at x = 4 m
    bed += 0.18 * np.exp(-((X + 1.0) / 1.3) ** 2) * (1 + 0.6 * np.cos(2 * np.pi * Y / 8.0))  # a bar, rip gaps
    bed += 0.05 * _smoothstep(2.0, 4.0, X) * _smoothstep(8.0, 6.0, X) * np.cos(2 * np.pi * Y / 4.0)  # beach
    # cusps, gone by the square's dry edge (the sand extended past it would draw them out as ridges)
    bed += 0.25 * _smoothstep(4.0, 8.0, X)  # the dry beach steepens: the run-up stays on the sand
    return bed


def _dam_bed(n):
    X, Y = _mesh("dambreak", n)
    wall = _smoothstep(0.35, 0.2, np.abs(X + 4.0)) * _smoothstep(1.3, 1.6, np.abs(Y))  # breach |y| < 1.5 m
    bed = 1.5 * wall + 0.1 * _smoothstep(-4.0, 8.0, X) * np.sin(0.5 * Y)
    for cx, cy in ((0.5, 2.0), (1.0, -1.5), (4.0, 0.3), (5.5, 3.5)):  # blocks 1.2 m square, 0.8 m high
        bed += 0.8 * _smoothstep(0.7, 0.55, np.abs(X - cx)) * _smoothstep(0.7, 0.55, np.abs(Y - cy))
    rim = _smoothstep(0.93, 0.97, np.maximum(np.abs(X), np.abs(Y)) / (DAM_LENGTH / 2))
    return np.maximum(bed, 1.6 * rim)  # the yard's own walls, above the reservoir: nothing spills past the square


def _wake_bed(n):
    X, Y = _mesh("wakebeach", n)
    bed = -WAKE_DEPTH + (WAKE_DEPTH + 0.6) * _smoothstep(0.0, 15.0, X)  # the still shoreline near x = 8.6 m
    bed += 0.06 * _smoothstep(6.0, 10.0, X) * np.cos(2 * np.pi * Y / 8.0)  # beach cusps
    return bed


@functools.lru_cache(maxsize=4)
def _shallow_water_setup(name, n):
    """(model, bed, state at rest at t = 0) of a shallow-water scene on its grid (float32); the model is a
    ShallowWater solver, or a Split for ``wakebeach``."""
    from wavephys.physics.shallow_water import solitary_wave
    from wavephys.simulation.shallow_water import ShallowWater, sw_state

    dx = LENGTHS[name] / n
    if name == "wakebeach":
        from wavephys.simulation.split import MovingPressure, Split

        bed = _wake_bed(n)
        solver = ShallowWater(dx, sides={"left": "wall", "right": "wall", "bottom": "periodic", "top": "periodic"})
        boat = MovingPressure(start=(WAKE_TRACK + WAKE_LENGTH / 2, 0.0), velocity=(0.0, WAKE_SPEED), head=0.08,
                              length=1.6, beam=0.6)
        model = Split(solver, levels=(0.5, WAKE_DEPTH), pressure=boat)
        return model, bed.astype(np.float32), sw_state(bed, np.zeros_like(bed))
    if name == "beach":
        bed = _beach_bed(n)
        X = _mesh("beach", n)[0]
        eta, u = solitary_wave(X, BEACH_WAVE, BEACH_DEPTH, -3.5)  # travelling towards −x: turn it round
        taper = _smoothstep(-7.5, -5.5, X)  # its tail ends inside the square (an open side would feed it)
        state = sw_state(bed, eta * taper, u=-u * taper)
        solver = ShallowWater(dx, sides={"left": "open", "right": "wall", "bottom": "periodic", "top": "periodic"})
    else:
        bed = _dam_bed(n)
        X = _mesh("dambreak", n)[0]
        state = sw_state(bed, depth=np.where(X < -4.3, np.maximum(DAM_RESERVOIR - bed, 0.0), 0.0))
        solver = ShallowWater(dx)
    return solver, bed.astype(np.float32), state


def _shallow_water_heights(name, n, times, progress=False):
    """Water heights at each of ``times`` (s, taken modulo the scene's cycle), float32 (len(times), n, n):
    the surface where wet, 2 cm below the ground where dry (so the renderer shows the ground there)."""
    from wavephys.simulation.shallow_water import _sw_frames
    from wavephys.simulation.split import Split, _split_frames

    model, bed, state = _shallow_water_setup(name, n)
    phases = np.mod(np.asarray(times, np.float64), SHALLOW_WATER_CYCLES[name])
    if name == "wakebeach":
        phases = phases + WAKE_WARMUP
    order = np.argsort(phases, kind="stable")
    if progress and len(phases) == 1:
        h = np.asarray(_stepped_with_progress(model, bed, state, float(phases[0])).h, np.float32)[None]
    else:
        run = _split_frames if isinstance(model, Split) else _sw_frames
        h = np.asarray(run(model, bed, state, phases[order]).h, np.float32)
    water = np.where(h > 1e-3, bed + h, bed - 0.02).astype(np.float32)
    result = np.empty_like(water)
    result[order] = water
    return result


def _stepped_with_progress(model, bed, state, until):
    """The state at ``until`` (s), stepped by the model's stepper landing on each whole second, each said on
    stderr (:class:`wavephys.core.progress.Progress`)."""
    from wavephys.core.progress import Progress
    from wavephys.simulation.shallow_water import ShallowWaterStepper
    from wavephys.simulation.split import Split, SplitStepper

    stepper = SplitStepper(model, bed) if isinstance(model, Split) else ShallowWaterStepper(model, bed)
    span = until - float(state.time)
    total = max(1, int(math.floor(span + 1e-9)) + (span - math.floor(span + 1e-9) > 1e-9))
    with Progress(total, "s simulated") as bar:
        return stepper.run(state, until=until, every=1.0, callback=lambda index, t, eta: bar.update()).state


def _beach_ground(n):
    bed = _beach_bed(n)
    wet = _smoothstep(0.3, -0.2, bed)
    X, Y = _mesh("beach", n)
    sand = np.array([0.82, 0.74, 0.55]) * (1 - 0.3 * wet[..., None])
    fade = _border_window("beach", n, 0.7)  # the sand extended past the square (surroundings) continues plain:
    # ripples at the border, drawn out of the border texels, made stripes to the horizon
    ripple = 1 + 0.05 * fade * (1 - wet) * np.sin(8.0 * X + 2.0 * np.sin(1.1 * Y))  # wind ripples on the dry sand
    return bed.astype(np.float32), (sand * ripple[..., None]).astype(np.float32)


def _wake_ground(n):
    bed = _wake_bed(n)
    wet = _smoothstep(0.3, -0.2, bed)
    X, Y = _mesh("wakebeach", n)
    sand = np.array([0.8, 0.73, 0.55]) * (1 - 0.3 * wet[..., None])
    ripple = 1 + 0.05 * (1 - wet) * np.sin(6.0 * X + 2.0 * np.sin(0.9 * Y))
    deep = _smoothstep(-0.6, -1.8, bed)[..., None]  # sea grass offshore
    albedo = sand * ripple[..., None] * (1 - deep) + np.array([0.3, 0.38, 0.22]) * deep
    return bed.astype(np.float32), albedo.astype(np.float32)


def _dam_ground(n):
    bed = _dam_bed(n)
    X, Y = _mesh("dambreak", n)
    built = np.clip(bed / 0.8, 0.0, 1.0)  # the walls and the blocks
    grass = np.array([0.36, 0.5, 0.25]) * (1 + 0.1 * np.sin(3.1 * X) * np.cos(2.3 * Y))[..., None]
    basin = np.array([0.5, 0.45, 0.36])  # the reservoir's muddy floor
    ground = np.where((X < -4.3)[..., None], basin, grass)
    albedo = ground * (1 - built[..., None]) + np.array([0.7, 0.68, 0.64]) * built[..., None]
    return bed.astype(np.float32), albedo.astype(np.float32)


def _cameras():
    return dict(pool=look_at((0.0, -6.5, 3.5), (0.0, 0.0, -1.0), 55.0),
                shore=look_at((-9.0, -7.0, 2.5), (1.0, 0.0, -0.5), 55.0),
                ship=look_at((8.0, -12.0, 9.0), (-6.0, 0.0, 0.0), 60.0),
                storm=look_at((-4.0, -30.0, 11.0), (4.0, 4.0, -2.0), 60.0),
                calm=look_at((0.0, -9.5, 2.6), (0.0, 0.5, -0.8), 55.0),
                beach=look_at((-3.0, -7.5, 2.2), (3.5, 2.0, -0.2), 60.0),
                dambreak=look_at((8.0, -9.5, 6.5), (-1.0, 0.5, 0.0), 55.0),
                wakebeach=look_at((13.0, -12.0, 4.0), (-6.0, 2.0, -0.5), 60.0),
                harbour=look_at((0.0, -5.0, 4.5), (0.0, 8.0, -0.5), 60.0))  # the quay in view is the square's
    # own (its blocks are drawn there; extended past it the quay is plain: seen from the side, they stopped)


def scene_water(name: str, n: int = 256, time: float = 0.0, ship: bool = True, *, progress: bool = False) -> np.ndarray:
    """The water height field (m) of a built-in scene at ``time`` (s), on :func:`scene_grid`.

    Parameters
    ----------
    name : str
        A built-in scene, one of :data:`SCENES`.
    n : int
        Grid points per side, even, 64 to 8192 (:data:`MAX_N`).
    time : float
        Seconds after the start, s, 0 to 3600 (:data:`MAX_TIME`): the pool's simulation is stepped
        up to it (at 1/30 s), the shore's swell too (16 s of warm-up, then modulo 16 s), the ship's position, the
        harbour's boat (modulo 12 s), the storm's sea, the pond's noise.
    ship : bool
        ``"ship"`` only: False gives flat water, the same frame without the ship.
    progress : bool, keyword-only
        Show the simulated seconds on stderr as they are stepped (the shallow-water scenes, whose
        simulation takes the longest: ``wakebeach`` about 95 s on 2 cores); the frame is then stepped
        landing on each whole second, the same water to the scheme's truncation error.

    Returns
    -------
    numpy.ndarray
        float32 heights, m, shape (n, n).
    """
    check_choice("name", name, SCENES)
    n = check_int("n", n, lo=64, hi=MAX_N, even=True)
    check_scalar("time", time, lo=0.0, hi=MAX_TIME)
    check_bool("ship", ship)
    check_bool("progress", progress)
    if name == "pool":
        sim, state = _pool_simulation(n)
        steps = int(round(time / sim.dt))
        if steps:
            state, _ = sim.run(state, steps)
        return _pool_heights(sim, state, n)
    if name == "shore":
        return _shore_heights(n, [float(time)])[0]
    if name == "storm":
        return _storm_frames(n, [float(time)])[0][0]
    if name == "calm":
        return np.asarray(_calm_sea(n).heights(scene_grid("calm", n), float(time)), np.float32)
    if name in SHALLOW_WATER_CYCLES:
        return _shallow_water_heights(name, n, [float(time)], progress)[0]
    if name == "harbour":
        return _harbour_heights(n, [float(time)])[0]
    return _ship_wake(n, time) if ship else np.zeros((n, n), np.float32)


SEA_WATER = dict(absorption=(0.42, 0.095, 0.075), deep_color=(0.0, 0.015, 0.03))
"""Coastal sea water for the storm: pure water's absorption plus an effective loss to
scattering and particles (Jerlov type II-like, 1/m), so the 20 m floor fades out."""


def _ground(name, n):
    return {"pool": _pool_ground, "shore": _shore_ground, "ship": _ship_ground, "storm": _storm_ground,
            "calm": _calm_ground, "beach": _beach_ground, "dambreak": _dam_ground,
            "wakebeach": _wake_ground, "harbour": _harbour_ground}[name](n)


def scene_caustics(name: str, water, method: str | None = None, **options) -> np.ndarray:
    """The caustics map of built-in scene ``name`` over ``water``, relative to flat water's light.

    Parameters
    ----------
    name : str
        A built-in scene, one of :data:`SCENES`.
    water : array_like (n, n)
        Water heights on :func:`scene_grid` (e.g. :func:`scene_water`), m; n even, 64 to 8192.
    method : str, optional
        A caustics method of :data:`optics.caustics.FLOOR_IRRADIANCE_METHODS` (default: the
        scene's own, :data:`CAUSTICS_METHODS`).
    options
        The method's own options (e.g. ``method="beam", refine=4``; on these grounds the
        jacobian takes ``refine=1`` only).

    Returns
    -------
    numpy.ndarray
        float32 (n, n): the floor's irradiance under ``water`` over its irradiance under flat
        water, on the scene's ground (the ground kept 5 cm below the lowest water).
    """
    check_choice("name", name, SCENES)
    check_array("water", water, ndim=2)
    n = np.shape(water)[0]
    if np.shape(water) != (n, n) or n % 2 or not 64 <= n <= MAX_N:
        raise ValueError(f"water must be (n, n) with n even, 64 to {MAX_N}, got shape {np.shape(water)}")
    if method is not None:
        check_instance("method", method, str, "a caustics method's name")
    if name in SHALLOW_WATER_CYCLES and method is None and not options:
        return _shallow_water_caustics(name, n, np.asarray(water, np.float32), _ground(name, n)[0])
    return _caustics(np.asarray(water, np.float32), scene_grid(name, n), _ground(name, n)[0],
                     CAUSTICS_METHODS[name] if method is None else method, **options)


def _shallow_water_caustics(name, n, water, ground):
    """Caustics of a shallow-water scene: the water as it is where wet and a 1 mm film on the ground where
    dry (so the floor is the real ground everywhere and dry land gets the flat light), traced by the beam
    on the samples themselves with central-difference slopes (the scene is not periodic and its shorelines
    are kinks: Fourier slopes and refinement would ring there), over the light under flat water. The fields
    are extended by 8 texels of their own border first and cropped after, so no slope wraps round."""
    from optics.caustics import floor_irradiance

    pad = 8
    film = np.pad(np.maximum(water, ground + 1e-3), pad, mode="edge").astype(np.float32)
    floor = np.pad(ground, pad, mode="edge").astype(np.float32)
    grid = Grid(n + 2 * pad, LENGTHS[name] * (n + 2 * pad) / n)
    wavy = np.asarray(floor_irradiance(film, grid, floor, SUN, method="beam", refine=1, normals="central"))
    flat = np.asarray(floor_irradiance(np.zeros_like(film), grid, np.full_like(film, -1.0), SUN, method="beam",
                                       refine=1, normals="central"))
    light = (wavy / float(np.median(flat)))[pad:-pad, pad:-pad]
    return np.where(water < ground, 1.0, light).astype(np.float32)  # dry land: no water, no caustics


def _assemble(name, n, water, caustics=True, camera=None, foam=None):
    ground, albedo = _ground(name, n)
    if not caustics:
        c = None
    elif name in SHALLOW_WATER_CYCLES or name == "shore":
        c = _shallow_water_caustics(name, n, water, ground)
    else:
        c = _caustics(water, scene_grid(name, n), ground, CAUSTICS_METHODS[name])
    extra = SEA_WATER if name in ("storm", "beach", "wakebeach", "harbour") else {}
    return Scene(ground, water, LENGTHS[name], camera or _cameras()[name], sun=SUN, albedo=albedo, caustics=c,
                 foam=foam, sky="preetham", surroundings=SURROUNDINGS[name], **extra)


SURROUNDINGS = {"pool": "extend", "shore": "tile", "ship": "extend", "storm": "tile", "calm": "extend",
                "beach": "tile", "dambreak": "extend", "wakebeach": "tile", "harbour": "extend"}
"""What each built-in scene shows beyond its square: the pool's deck, the lake's meadow, the
ship's calm sea and the yard extended from their borders; the swell, the storm and the two beaches
(periodic along their shores) tiled to the horizon."""


def builtin_scene(name: str, *, n: int = 256, time: float = 1.0, ship: bool = True, caustics: bool = True,
                  camera: Camera | None = None, progress: bool = False) -> Scene:
    """A built-in renderer scene by name (``"pool"``, ``"shore"``, ``"ship"``, ``"storm"``, ``"calm"``).

    Parameters
    ----------
    name : str
        A built-in scene, one of :data:`SCENES`.
    n : int
        Height-field resolution (texels per side), even, 64 to 8192 (:data:`MAX_N`).
    time : float
        Seconds after the start (stones dropped at 0 in the pool; swell phase; ship position;
        the storm's sea and its foam; the calm pond's noise), 0 to 3600 (:data:`MAX_TIME`).
    ship : bool
        ``"ship"`` only: False gives flat water, the same frame without the ship.
    caustics : bool
        Compute the caustics map (:data:`CAUSTICS_METHODS`); False leaves the flat-water light.
    progress : bool, keyword-only
        Show the simulated seconds on stderr as they are stepped (:func:`scene_water`).
    camera : Camera, optional
        Replaces the scene's camera.

    Returns
    -------
    Scene
        The :class:`optics.rendering.scene.Scene`: ground and albedo, water heights, the caustics
        map (or None), foam (storm), Preetham's sky and the scene's :data:`SURROUNDINGS`.

    Raises
    ------
    ValueError
        When ``name`` is not a built-in scene or an argument is out of range.
    TypeError
        When ``camera`` is not a Camera or a switch is not a bool.

    References
    ----------
    Preetham, A. J., Shirley, P. & Smits, B. (1999). A practical analytic model for daylight. *SIGGRAPH*.

    Schneider, J. & Westermann, R. (2001). Towards real-time visual simulation of water surfaces. *VMV*.
    """
    if camera is not None:
        check_instance("camera", camera, Camera, "optics.rendering.Camera")
    check_bool("caustics", caustics)
    if name == "storm":
        check_scalar("time", time, lo=0.0, hi=MAX_TIME)
        n = check_int("n", n, lo=64, hi=MAX_N, even=True)
        water, foam = _storm_frames(n, [float(time)])[0]
        return _assemble(name, n, water, caustics, camera, foam)
    return _assemble(name, n, scene_water(name, n, time, ship, progress=progress), caustics, camera)


def scene_frames(name: str, count: int, *, fps: float = 30.0, n: int = 256, start: float = 0.5,
                 caustics: bool = True) -> Iterator[Scene]:
    """``count`` successive scenes ``1/fps`` s apart from ``start`` (the pool steps its simulation once per frame).

    The arguments are checked when it is called, before the first frame is made.

    Parameters
    ----------
    name : str
        A built-in scene, one of :data:`SCENES`.
    count : int
        Number of frames, ≥ 1.
    fps : float, keyword-only
        Frames per second, 1/s, in (0, 1000].
    n : int, keyword-only
        Height-field resolution (texels per side), even, 64 to 8192 (:data:`MAX_N`).
    start : float, keyword-only
        Time of the first frame, s, 0 to 3600 (:data:`MAX_TIME`); the last frame must end by
        :data:`MAX_TIME` too (``start + count / fps <= MAX_TIME``).
    caustics : bool, keyword-only
        Compute the caustics map of each frame (:data:`CAUSTICS_METHODS`).

    Returns
    -------
    Iterator of Scene
        The ``count`` scenes at ``start + i / fps``, made one by one as they are drawn.

    Raises
    ------
    ValueError
        When an argument is out of range or the frames would end after :data:`MAX_TIME`.
    """
    check_choice("name", name, SCENES)
    count = check_int("count", count, lo=1)
    check_scalar("fps", fps, lo=0.0, hi=1000.0, lo_open=True)
    check_scalar("start", start, lo=0.0, hi=MAX_TIME)
    n = check_int("n", n, lo=64, hi=MAX_N, even=True)
    check_bool("caustics", caustics)
    if start + count / fps > MAX_TIME:
        raise ValueError(f"count: {count} frames at {fps} fps from {start} s end after MAX_TIME = {MAX_TIME} s")
    return _frames(name, count, fps, n, start, caustics)


def scene_height_frames(name: str, count: int, *, fps: float = 30.0, n: int = 256, start: float = 0.5):
    """The water of ``count`` frames of a built-in scene as a record to check, with what it is.

    The pool's frames are its tank alone (the water between its reflecting walls, the walls half a sample
    outside the first and last samples: the texel convention ``check_record(..., tank=True)`` reads), not the
    scene's square with its still rim; the other scenes' frames are their water on :func:`scene_grid`.

    Parameters
    ----------
    name : str
        A built-in scene, one of :data:`SCENES`.
    count : int
        Number of frames, ≥ 1.
    fps : float, keyword-only
        Frames per second, 1/s, in (0, 1000].
    n : int, keyword-only
        The scene's resolution (texels per side), even, 64 to 8192.
    start : float, keyword-only
        Time of the first frame, s, 0 to 3600; the frames must end by then too.

    Returns
    -------
    (Iterator of numpy.ndarray, float, dict)
        The frames (m) made one by one, the side of the square they cover (m), and the header entries that say
        what they are: ``boundary`` ("walls" for a tank, "periodic" for a sea that wraps, "open" otherwise), and
        ``depth`` (m) and ``sigma`` (N/m) where the scene's water has them.
    """
    frames = scene_frames(name, count, fps=fps, n=n, start=start, caustics=False)  # checks the arguments
    if name != "pool":
        boundary = "periodic" if name in ("calm", "storm") else "open"
        return (np.asarray(s.water) for s in frames), float(scene_grid(name, n).length), dict(boundary=boundary)
    sim, state = _pool_simulation(n, dt=1.0 / fps)

    def tank():
        nonlocal state
        skip = int(round(start * fps))
        if skip:
            state, _ = sim.run(state, skip)
        for _ in range(count):
            yield np.asarray(sim.surface(state).eta, np.float32)
            state, _ = sim.step(state)
    water = sim.model.water
    return tank(), float(sim.model.grid.length), dict(boundary="walls", depth=float(water.depth),
                                                      sigma=float(water.sigma))


def _frames(name, count, fps, n, start, caustics):
    if name == "storm":
        for water, foam in _storm_frames(n, [start + i / fps for i in range(count)]):
            yield _assemble(name, n, water, caustics, foam=foam)
        return
    if name in SHALLOW_WATER_CYCLES or name in ("harbour", "shore"):  # one run of the simulation for all the frames
        run = {"harbour": _harbour_heights, "shore": _shore_heights}.get(name)
        run = run or functools.partial(_shallow_water_heights, name)
        for water in run(n, [start + i / fps for i in range(count)]):
            yield _assemble(name, n, water, caustics)
        return
    if name != "pool":
        for i in range(count):
            yield _assemble(name, n, scene_water(name, n, start + i / fps), caustics)
        return
    sim, state = _pool_simulation(n, dt=1.0 / fps)
    skip = int(round(start * fps))
    if skip:
        state, _ = sim.run(state, skip)
    for _ in range(count):
        yield _assemble(name, n, _pool_heights(sim, state, n), caustics)
        state, _ = sim.step(state)
