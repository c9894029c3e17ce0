"""Built-in scenes for the renderer, made by wavephys (no input files).

``pool``  an 8 m pool (tiled floor 1.5 m deep, walls out of the water) with ring waves of
          three stones from the spectral simulation, caustics by the beam method;
``shore`` a 16 m sandy beach rising out of the water under a three-component swell
          (deep-water dispersion), caustics on the sloping ground;
``ship``  a 40 m patch of 8 m deep water with the steady Kelvin wake of a hull at 2 m/s;
          ``ship=False`` gives the same frame without the ship (for comparisons).

:func:`builtin_scene` returns one :class:`optics.scene.Scene`; :func:`scene_frames`
yields an animation. Simulation fields are laid on the scene's texels one to one.
"""

from __future__ import annotations

import math
from typing import Iterator

import numpy as np

from optics.scene import Camera, Scene, look_at
from wavephys._inputs import check_choice, check_int, check_scalar

__all__ = ["SCENES", "builtin_scene", "scene_frames", "scene_water"]

SCENES = ("pool", "shore", "ship")
SUN = (0.35, -0.45, 0.82)


def _axis(n, extent):
    return (np.arange(n) + 0.5) * (extent / n) - extent / 2


def _smoothstep(e0, e1, x):
    t = np.clip((x - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3 - 2 * t)


def _caustics(eta, extent, ground, sun=SUN):
    """Floor irradiance relative to flat water (beam method, ground height field below the water)."""
    from optics.caustics import floor_irradiance
    from wavephys.params import Grid

    n = eta.shape[0]
    grid = Grid(n, extent)
    floor = np.minimum(ground, eta.min() - 0.05)
    wavy = np.asarray(floor_irradiance(eta.astype(np.float32), grid, floor.astype(np.float32), sun))
    flat = np.asarray(floor_irradiance(np.zeros_like(eta, np.float32), grid, floor.astype(np.float32), sun))
    return (wavy / np.maximum(flat, 1e-6)).astype(np.float32)


# -- pool -----------------------------------------------------------------------------
POOL_EXTENT, POOL_DEPTH = 8.0, 1.5


def _pool_ground(n):
    x = _axis(n, POOL_EXTENT)
    X, Y = np.meshgrid(x, x)
    r = np.maximum(np.abs(X), np.abs(Y))
    wall = _smoothstep(3.3, 3.6, r)
    ground = -POOL_DEPTH + (POOL_DEPTH + 0.3) * wall
    tile = 0.5  # m; soft grout lines
    gx = np.cos(np.pi * X / tile) ** 40
    gy = np.cos(np.pi * Y / tile) ** 40
    grout = np.clip(gx + gy, 0, 1)
    base = np.array([0.55, 0.78, 0.86])
    albedo = base * (1 - 0.45 * grout[..., None])
    albedo = albedo * (1 - wall[..., None]) + np.array([0.85, 0.85, 0.82]) * wall[..., None]
    return ground.astype(np.float32), albedo.astype(np.float32)


def _pool_simulation(n):
    from wavephys.disturbances import Stones
    from wavephys.params import Grid, Water
    from wavephys.simulation import Simulation

    sim = Simulation(Grid(n, POOL_EXTENT), Water(), dt=1.0 / 30.0, margin=max(1, n // 16))
    stones = Stones([-1.2, 1.0, 0.3], [0.8, -1.0, 1.5], [0.15, 0.13, 0.18], [0.04, 0.03, 0.05])  # R ≥ dx at n ≥ 64
    return sim, sim.drop(sim.initial_state(), stones)


# -- shore ----------------------------------------------------------------------------
SHORE_EXTENT = 16.0
SWELL = ((4, 0, 0.05, 0.0), (5, 1, 0.03, 1.3), (3, -1, 0.035, 2.1))  # (m_x, m_y, amplitude m, phase)


def _shore_ground(n):
    x = _axis(n, SHORE_EXTENT)
    X, Y = np.meshgrid(x, x)
    ground = -2.0 + 2.6 * (X + SHORE_EXTENT / 2) / SHORE_EXTENT + 0.04 * np.sin(2.3 * Y + 0.7 * X) * np.cos(1.7 * X)
    wet = _smoothstep(0.15, -0.3, ground)
    sand = np.array([0.80, 0.72, 0.52]) * (1 - 0.25 * wet[..., None])
    ripple = 1 + 0.08 * np.sin(9.0 * X + 2.0 * np.sin(1.3 * Y))
    return ground.astype(np.float32), (sand * ripple[..., None]).astype(np.float32)


def _swell(n, t):
    from wavephys.dispersion import angular_frequency
    from wavephys.params import Water

    x = _axis(n, SHORE_EXTENT)
    X, Y = np.meshgrid(x, x)
    eta = np.zeros((n, n))
    for mx, my, a, phase in SWELL:  # periodic on the square, so the caustics' FFTs see no seams
        kx, ky = 2 * np.pi * mx / SHORE_EXTENT, 2 * np.pi * my / SHORE_EXTENT
        w = float(angular_frequency(math.hypot(kx, ky), Water(sigma=0.0)))
        eta += a * np.cos(kx * X + ky * Y - w * t + phase)
    return eta.astype(np.float32)


# -- ship -----------------------------------------------------------------------------
SHIP_EXTENT, SHIP_SPEED, SHIP_DEPTH = 40.0, 2.0, 8.0


def _ship_wake(n):
    from wavephys.params import Grid, Water
    from wavephys.wake import GaussianPressure, steady_wake

    size = max(0.6, SHIP_EXTENT / n)  # resolved on coarse grids too
    eta = np.asarray(steady_wake(Grid(n, SHIP_EXTENT), Water(sigma=0.0), SHIP_SPEED, GaussianPressure(800.0, size),
                                 damping=0.08), np.float64)  # fades over U/ε = 25 m
    return eta


def _ship_ground(n):
    x = _axis(n, SHIP_EXTENT)
    X, Y = np.meshgrid(x, x)
    ground = -SHIP_DEPTH + 0.3 * np.sin(0.4 * X) * np.cos(0.3 * Y)
    albedo = np.array([0.55, 0.6, 0.5]) * (1 + 0.15 * np.sin(1.1 * X + 0.8 * Y))[..., None]
    return ground.astype(np.float32), albedo.astype(np.float32)


def _shift(eta, dx_m, extent):
    n = eta.shape[1]
    k = 2 * np.pi * np.fft.fftfreq(n, extent / n)
    return np.fft.ifft(np.fft.fft(eta, axis=1) * np.exp(-1j * k * dx_m)[None, :], axis=1).real


def _cameras():
    return dict(pool=look_at((0.0, -6.5, 3.5), (0.0, 0.0, -1.0), 55.0),
                shore=look_at((-9.0, -7.0, 2.5), (1.0, 0.0, -0.5), 55.0),
                ship=look_at((8.0, -12.0, 9.0), (-6.0, 0.0, 0.0), 60.0))


def scene_water(name: str, n: int = 256, time: float = 0.0, ship: bool = True) -> np.ndarray:
    """The water height field (m) of a built-in scene at ``time`` (s)."""
    check_choice("name", name, SCENES)
    n = check_int("n", n, lo=64)
    check_scalar("time", time, lo=0.0)
    if name == "pool":
        sim, state = _pool_simulation(n)
        for _ in range(int(round(time / sim.dt))):
            state, _ = sim.step(state)
        return np.asarray(sim.surface(state).eta, np.float32)
    if name == "shore":
        return _swell(n, time)
    if not ship:
        return np.zeros((n, n), np.float32)
    return _shift(_ship_wake(n), -5.0 + SHIP_SPEED * time, SHIP_EXTENT).astype(np.float32)


def _assemble(name, n, water, caustics=True, camera=None):
    ground, albedo = {"pool": _pool_ground, "shore": _shore_ground, "ship": _ship_ground}[name](n)
    extent = {"pool": POOL_EXTENT, "shore": SHORE_EXTENT, "ship": SHIP_EXTENT}[name]
    c = _caustics(water, extent, ground) if caustics else None
    return Scene(ground, water, extent, camera or _cameras()[name], sun=SUN, albedo=albedo, caustics=c)


def builtin_scene(name: str, *, n: int = 256, time: float = 1.0, ship: bool = True, caustics: bool = True,
                  camera: Camera | None = None) -> Scene:
    """A built-in scene by name (``"pool"``, ``"shore"``, ``"ship"``).

    Parameters
    ----------
    n : int
        Height-field resolution (texels per side), ≥ 64.
    time : float
        Seconds after the start (stones dropped at 0 in the pool; swell phase; ship position).
    ship : bool
        ``"ship"`` only: False gives flat water, the same frame without the ship.
    caustics : bool
        Compute the caustics map (beam method); False leaves the flat-water light.
    camera : Camera, optional
        Replaces the scene's camera.
    """
    water = scene_water(name, n, time, ship)
    return _assemble(name, n, water, caustics, camera)


def scene_frames(name: str, count: int, *, fps: float = 30.0, n: int = 256, start: float = 0.5,
                 caustics: bool = True) -> Iterator[Scene]:
    """``count`` successive scenes ``1/fps`` s apart from ``start`` (the pool steps its simulation once per frame)."""
    check_choice("name", name, SCENES)
    count = check_int("count", count, lo=1)
    check_scalar("fps", fps, lo=0.0, lo_open=True)
    n = check_int("n", n, lo=64)
    if name == "pool":
        from wavephys.params import Grid, Water
        from wavephys.simulation import Simulation

        _, state = _pool_simulation(n)
        sim = Simulation(Grid(n, POOL_EXTENT), Water(), dt=1.0 / fps, margin=max(1, n // 16))
        for _ in range(int(round(start * fps))):
            state, _ = sim.step(state)
        for _ in range(count):
            yield _assemble(name, n, np.asarray(sim.surface(state).eta, np.float32), caustics)
            state, _ = sim.step(state)
        return
    for i in range(count):
        yield _assemble(name, n, scene_water(name, n, start + i / fps), caustics)
