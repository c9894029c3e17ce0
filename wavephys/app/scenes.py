"""Built-in scenes that need no input files: the default simulation scene, and the renderer's
``pool``, ``shore`` and ``ship``.

``pool``  an 8 m pool (tiled floor 1.5 m deep, walls out of the water) with ring waves of
          three stones from the spectral simulation, caustics by the beam method;
``shore`` a 16 m sandy beach rising out of the water under a three-component swell
          (deep-water dispersion), caustics on the sloping ground;
``ship``  a 40 m patch of 8 m deep water with the steady Kelvin wake of a hull at 2 m/s;
          ``ship=False`` gives the same frame without the ship (for comparisons).

Every field is made on a :class:`wavephys.Grid` of the scene's side and resolution, so the
simulated water, the ground, the caustics and the textures share one convention and
land texel for texel (docs/physics.md §0).
"""

from __future__ import annotations

from typing import Callable, Iterator, Optional

import numpy as np

from optics.rendering.scene import Camera, Scene, look_at
from wavephys.app import SCENES
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_bool, check_choice, check_instance, check_int, check_scalar
from wavephys.core.water import Water
from wavephys.physics.disturbances import Stones

__all__ = ["default_scene", "SCENES", "builtin_scene", "scene_frames", "scene_water", "scene_grid"]

SUN = (0.35, -0.45, 0.82)
MAX_TIME = 3600.0
"""Latest time of a built-in scene, s (the pool steps its simulation up to it)."""
MAX_N = 8192
"""Largest resolution of a built-in scene, texels per side."""
POOL_LENGTH, POOL_DEPTH = 8.0, 1.5
SHORE_LENGTH = 16.0
SWELL = ((4, 0, 0.05, 0.0), (5, 1, 0.03, 1.3), (3, -1, 0.035, 2.1))  # (m_x, m_y, amplitude m, phase)
SHIP_LENGTH, SHIP_SPEED, SHIP_DEPTH = 40.0, 2.0, 8.0
LENGTHS = {"pool": POOL_LENGTH, "shore": SHORE_LENGTH, "ship": SHIP_LENGTH}


def default_scene(n: int = 256, steps: int = 120, progress: Optional[Callable[[str], None]] = None):
    """A 16 m patch of open water: three stones, 30 steps per second, margin n/8.

    Returns a dict with the final ``eta`` (m), ``eta_dot`` (m/s), ``dx`` (m), ``time`` (s)
    and ``energy_ratio`` (energy after / before the steps with the cutoff off, as a
    sanity figure: 1 to rounding).
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
    """The grid every field of built-in scene ``name`` lives on."""
    return Grid(n, LENGTHS[check_choice("name", name, SCENES)])


def _mesh(name, n):
    return tuple(np.asarray(a, np.float64) for a in scene_grid(name, n).mesh())


def _smoothstep(e0, e1, x):
    t = np.clip((x - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3 - 2 * t)


def _caustics(eta, grid: Grid, ground):
    """Floor irradiance relative to flat water (beam method, ground height field below the water)."""
    from optics.caustics import floor_irradiance

    floor = np.minimum(ground, eta.min() - 0.05).astype(np.float32)
    wavy = np.asarray(floor_irradiance(eta.astype(np.float32), grid, floor, SUN))
    flat = np.asarray(floor_irradiance(np.zeros_like(eta, np.float32), grid, floor, SUN))
    return (wavy / np.maximum(flat, 1e-6)).astype(np.float32)


def _pool_ground(n):
    X, Y = _mesh("pool", n)
    r = np.maximum(np.abs(X), np.abs(Y))
    wall = _smoothstep(3.3, 3.6, r)
    ground = -POOL_DEPTH + (POOL_DEPTH + 0.3) * wall
    tile = 0.5  # m; soft grout lines
    grout = np.clip(np.cos(np.pi * X / tile) ** 40 + np.cos(np.pi * Y / tile) ** 40, 0, 1)
    albedo = np.array([0.55, 0.78, 0.86]) * (1 - 0.45 * grout[..., None])
    albedo = albedo * (1 - wall[..., None]) + np.array([0.85, 0.85, 0.82]) * wall[..., None]
    return ground.astype(np.float32), albedo.astype(np.float32)


def _pool_simulation(n, dt=1.0 / 30.0):
    from wavephys.simulation import Simulation

    sim = Simulation(scene_grid("pool", n), Water(), dt=dt, margin=max(1, n // 16))
    stones = Stones([-1.2, 1.0, 0.3], [0.8, -1.0, 1.5], [0.15, 0.13, 0.18], [0.04, 0.03, 0.05])  # R >= dx at n >= 64
    return sim, sim.drop(sim.initial_state(), stones)


def _shore_ground(n):
    X, Y = _mesh("shore", n)
    ground = -2.0 + 2.6 * (X + SHORE_LENGTH / 2) / SHORE_LENGTH + 0.04 * np.sin(2.3 * Y + 0.7 * X) * np.cos(1.7 * X)
    wet = _smoothstep(0.15, -0.3, ground)
    sand = np.array([0.80, 0.72, 0.52]) * (1 - 0.25 * wet[..., None])
    ripple = 1 + 0.08 * np.sin(9.0 * X + 2.0 * np.sin(1.3 * Y))
    return ground.astype(np.float32), (sand * ripple[..., None]).astype(np.float32)


def _swell(n, t):
    from wavephys.physics.dispersion import angular_frequency

    X, Y = _mesh("shore", n)
    eta = np.zeros((n, n))
    for mx, my, a, phase in SWELL:  # periodic on the square, so the caustics' FFTs see no seams
        kx, ky = 2 * np.pi * mx / SHORE_LENGTH, 2 * np.pi * my / SHORE_LENGTH
        w = float(angular_frequency(np.hypot(kx, ky), Water(sigma=0.0)))
        eta += a * np.cos(kx * X + ky * Y - w * t + phase)
    return eta.astype(np.float32)


def _ship_wake(n, t):
    from wavephys.physics.wake import GaussianPressure, steady_wake

    grid = scene_grid("ship", n)
    size = max(0.6, SHIP_LENGTH / n)  # resolved on coarse grids too
    eta = steady_wake(grid, Water(sigma=0.0), SHIP_SPEED, GaussianPressure(800.0, size), damping=0.08)  # fades over 25 m
    return np.asarray(grid.shift(eta, -5.0 + SHIP_SPEED * t), np.float32)


def _ship_ground(n):
    X, Y = _mesh("ship", n)
    ground = -SHIP_DEPTH + 0.3 * np.sin(0.4 * X) * np.cos(0.3 * Y)
    albedo = np.array([0.55, 0.6, 0.5]) * (1 + 0.15 * np.sin(1.1 * X + 0.8 * Y))[..., None]
    return ground.astype(np.float32), albedo.astype(np.float32)


def _cameras():
    return dict(pool=look_at((0.0, -6.5, 3.5), (0.0, 0.0, -1.0), 55.0),
                shore=look_at((-9.0, -7.0, 2.5), (1.0, 0.0, -0.5), 55.0),
                ship=look_at((8.0, -12.0, 9.0), (-6.0, 0.0, 0.0), 60.0))


def scene_water(name: str, n: int = 256, time: float = 0.0, ship: bool = True) -> np.ndarray:
    """The water height field (m) of a built-in scene at ``time`` (s), on :func:`scene_grid`."""
    check_choice("name", name, SCENES)
    n = check_int("n", n, lo=64, hi=MAX_N, even=True)
    check_scalar("time", time, lo=0.0, hi=MAX_TIME)
    check_bool("ship", ship)
    if name == "pool":
        sim, state = _pool_simulation(n)
        steps = int(round(time / sim.dt))
        if steps:
            state, _ = sim.run(state, steps)
        return np.asarray(sim.surface(state).eta, np.float32)
    if name == "shore":
        return _swell(n, time)
    return _ship_wake(n, time) if ship else np.zeros((n, n), np.float32)


def _assemble(name, n, water, caustics=True, camera=None):
    ground, albedo = {"pool": _pool_ground, "shore": _shore_ground, "ship": _ship_ground}[name](n)
    c = _caustics(water, scene_grid(name, n), ground) if caustics else None
    return Scene(ground, water, LENGTHS[name], camera or _cameras()[name], sun=SUN, albedo=albedo, caustics=c)


def builtin_scene(name: str, *, n: int = 256, time: float = 1.0, ship: bool = True, caustics: bool = True,
                  camera: Camera | None = None) -> Scene:
    """A built-in renderer scene by name (``"pool"``, ``"shore"``, ``"ship"``).

    Parameters
    ----------
    n : int
        Height-field resolution (texels per side), even, ≥ 64.
    time : float
        Seconds after the start (stones dropped at 0 in the pool; swell phase; ship position), ≥ 0.
    ship : bool
        ``"ship"`` only: False gives flat water, the same frame without the ship.
    caustics : bool
        Compute the caustics map (beam method); False leaves the flat-water light.
    camera : Camera, optional
        Replaces the scene's camera.
    """
    if camera is not None:
        check_instance("camera", camera, Camera, "optics.rendering.Camera")
    check_bool("caustics", caustics)
    return _assemble(name, n, scene_water(name, n, time, ship), caustics, camera)


def scene_frames(name: str, count: int, *, fps: float = 30.0, n: int = 256, start: float = 0.5,
                 caustics: bool = True) -> Iterator[Scene]:
    """``count`` successive scenes ``1/fps`` s apart from ``start`` (the pool steps its simulation once per frame).

    The arguments are checked when it is called, before the first frame is made."""
    check_choice("name", name, SCENES)
    count = check_int("count", count, lo=1)
    check_scalar("fps", fps, lo=0.0, hi=1000.0, lo_open=True)
    check_scalar("start", start, lo=0.0, hi=MAX_TIME)
    n = check_int("n", n, lo=64, hi=MAX_N, even=True)
    check_bool("caustics", caustics)
    if start + count / fps > MAX_TIME:
        raise ValueError(f"count: {count} frames at {fps} fps from {start} s end after MAX_TIME = {MAX_TIME} s")
    return _frames(name, count, fps, n, start, caustics)


def _frames(name, count, fps, n, start, caustics):
    if name != "pool":
        for i in range(count):
            yield _assemble(name, n, scene_water(name, n, start + i / fps), caustics)
        return
    sim, state = _pool_simulation(n, dt=1.0 / fps)
    skip = int(round(start * fps))
    if skip:
        state, _ = sim.run(state, skip)
    for _ in range(count):
        yield _assemble(name, n, np.asarray(sim.surface(state).eta, np.float32), caustics)
        state, _ = sim.step(state)
