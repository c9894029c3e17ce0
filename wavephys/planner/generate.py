"""A seeded generator of varied scenes nobody picked: the planner's proof runs on them.

Kinds (drawn in turn, parameters drawn at random within each kind's range):

``pool``      a periodic tank 2–12 m, 0.3–2 m deep, 1–4 stones, its floor's caustics shown;
``shore``     open shallow water 8–40 m, 0.3–3 m deep, a light wind sea, sometimes a stone,
              its floor's caustics shown;
``open_sea``  open deep water 32–400 m at coarse pixels (0.25–2 m), a wind sea;
``ship``      open water with a ship at 0.2–10 m/s (hull 4–6 pixels wide), 1–20 m deep or deep;
``ripples``   a small tank 0.2–0.8 m at fine pixels (1–4 mm): capillary waves resolved;
``tank``      a walled pool 1–12 m (waves reflect at its edges), 0.2–2 m deep, 1–3 stones;
``slope``     water 2–16 m over a plane floor (slope 0.003 up to the steepest the scene allows,
              any direction), 0.3–2 m deep at the centre, open or walled, 1–2 stones.

Texels per side are 32–128 (ship scenes 64–128), 12–60 frames at 24–60 fps, height
textures of 8 or 16 bits. Ship scenes whose full model cannot run (the patch leaves the
visible square) are drawn again.
"""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.inputs import check_choice, check_int
from wavephys.core.water import Water
from wavephys.planner.model import Choices, SceneModel
from wavephys.planner.scene import MIN_FLOOR_DEPTH, MIN_TEXELS, FloorSpec, Scene, ShipSpec, StoneSpec, WindSpec

__all__ = ["generate_scenes", "KINDS"]

KINDS = ("pool", "shore", "open_sea", "ship", "ripples", "tank", "slope")


def generate_scenes(count: int, seed: int = 0, kinds=KINDS, texels=(32, 48, 64, 96, 128)) -> list:
    """Seeded scenes nobody picked: the planner's proof runs on them (docs/planner.md §6).

    Parameters
    ----------
    count : int
        How many, in [1, 10000].
    seed : int
        Seed of ``numpy.random.default_rng``, ≥ 0.
    kinds : sequence of str
        Kinds of scene to cycle through (names in :data:`KINDS`).
    texels : sequence of int
        Visible texels per side to draw from.

    Returns
    -------
    list of Scene
    """
    count = check_int("count", count, lo=1, hi=10000)
    seed = check_int("seed", seed, lo=0)
    for name, items in (("kinds", kinds), ("texels", texels)):
        if isinstance(items, (str, bytes)) or not hasattr(items, "__iter__") or not len(items):
            raise TypeError(f"{name} must be a non-empty sequence, got {type(items).__name__}")
    kinds, texels = tuple(kinds), tuple(texels)
    for k in kinds:
        check_choice("kinds", k, KINDS)
    for t in texels:
        check_int("texels", t, lo=MIN_TEXELS, hi=512)
        if t % 16:
            raise ValueError(f"texels must be multiples of 16, got {t}")
    rng = np.random.default_rng(seed)
    out, attempts = [], 0
    while len(out) < count:
        attempts += 1
        if attempts > 50 * count:
            raise ValueError(f"could not draw {count} runnable scenes of kinds {kinds} with texels {texels} "
                             f"(ship scenes need 64 texels or more)")
        kind = kinds[len(out) % len(kinds)]
        try:
            n = int(rng.choice([t for t in texels if t >= 64] or texels)) if kind == "ship" else int(rng.choice(texels))
            scene = _draw(kind, rng, n, f"{kind}-{len(out)}")
            if scene is not None and scene.ships:
                SceneModel(scene, Choices(ship_patch=1)).check_ships()  # the full model must run it
        except ValueError:  # a draw the scene refuses (a course that leaves the square): draw again
            continue
        if scene is not None:
            out.append(scene)
    return out


def _common(rng, n):
    fps = float(rng.choice([24.0, 30.0, 60.0]))
    frames = int(rng.integers(12, 61))
    return dict(fps=fps, duration=frames / fps, height_bits=int(rng.choice([8, 16])),
                sun_elevation=float(rng.uniform(10, 80)), view_elevation=float(rng.uniform(10, 80)))


def _stones(rng, extent, pixel, count, depth_scale):
    out = []
    for _ in range(count):
        r = float(rng.uniform(2.5 * pixel, max(3 * pixel, extent / 12)))
        out.append(StoneSpec(float(rng.uniform(-0.35, 0.35) * extent), float(rng.uniform(-0.35, 0.35) * extent), r,
                             float(rng.uniform(0.02, 0.15) * r * depth_scale)))
    return tuple(out)


def _draw(kind, rng, n, name):
    c = _common(rng, n)
    if kind == "pool":
        extent = float(rng.uniform(2, 12))
        pixel = extent / n
        stones = _stones(rng, extent, pixel, int(rng.integers(1, 5)), 1.0)
        peak = max(s.depth for s in stones)
        return Scene(extent, pixel, depth=float(rng.uniform(0.3, 2.0)), open_water=False, stones=stones,
                     height_range=2 * peak, caustics=True, name=name, **c)
    if kind == "shore":
        extent = float(rng.uniform(8, 40))
        pixel = extent / n
        wind = WindSpec(float(rng.uniform(1.5, 4)), float(rng.uniform(0, 360)), float(10 ** rng.uniform(-5, -3.5)),
                        int(rng.integers(0, 1000)))
        stones = _stones(rng, extent, pixel, int(rng.integers(0, 2)), 0.5)
        return Scene(extent, pixel, depth=float(rng.uniform(0.3, 3.0)), open_water=True, wind=wind, stones=stones,
                     height_range=0.05, caustics=True, name=name, **c)
    if kind == "open_sea":
        pixel = float(rng.choice([0.25, 0.5, 1.0, 2.0]))
        extent = pixel * n
        wind = WindSpec(float(rng.uniform(3, 12)), float(rng.uniform(0, 360)), float(10 ** rng.uniform(-5, -3)),
                        int(rng.integers(0, 1000)))
        return Scene(extent, pixel, depth=math.inf, open_water=True, wind=wind, height_range=1.0, name=name, **c)
    if kind == "ship":
        speed = float(10 ** rng.uniform(math.log10(0.2), 1.0))
        width_px = float(rng.uniform(4, 6))
        frames = round(c["duration"] * c["fps"])
        # the domain holds the course plus the hull and the margin on both sides
        pixel = float(rng.uniform(0.02, 0.2)) * max(1.0, speed / 2)
        width = width_px * pixel
        length = width * float(rng.uniform(2, 3))
        travel = speed * c["duration"]
        extent = pixel * n
        need = travel + 2 * (0.75 * length + extent / 16) + 64 * pixel
        if need > extent:  # a larger pixel keeps the course inside
            pixel = need / n * 1.05
            extent = pixel * n
            width, length = width_px * pixel, width_px * pixel * 2.5
        depth = math.inf if rng.random() < 0.3 else float(rng.uniform(1, 20))
        heading = float(rng.choice([0.0, 30.0, 90.0, 180.0, 225.0]))
        a = math.radians(heading)
        x0, y0 = -0.5 * travel * math.cos(a), -0.5 * travel * math.sin(a)
        ship = ShipSpec(x0, y0, speed, heading, length, width, float(0.01 * speed * width))
        return Scene(extent, pixel, depth=depth, open_water=True, ships=(ship,), height_range=0.05, name=name, **c)
    if kind == "ripples":
        extent = float(rng.uniform(0.2, 0.8))
        pixel = extent / n
        stones = _stones(rng, extent, pixel, int(rng.integers(1, 3)), 1.0)
        stones = tuple(StoneSpec(s.x, s.y, s.radius, min(s.depth, 0.002)) for s in stones)
        return Scene(extent, pixel, depth=float(rng.uniform(0.02, 0.3)), open_water=False, stones=stones,
                     water=Water(), height_range=2 * max(s.depth for s in stones), name=name, **c)
    if kind == "tank":
        extent = float(rng.uniform(1, 12))
        pixel = extent / n
        stones = _stones(rng, extent, pixel, int(rng.integers(1, 4)), 1.0)
        return Scene(extent, pixel, depth=float(rng.uniform(0.2, 2.0)), walls=True, stones=stones,
                     height_range=2 * max(s.depth for s in stones), name=name, **c)
    if kind == "slope":
        extent = float(rng.uniform(2, 16))
        pixel = extent / n
        stones = _stones(rng, extent, pixel, int(rng.integers(1, 3)), 1.0)
        depth = float(rng.uniform(0.3, 2.0))
        direction = float(rng.uniform(0, 360))
        a = math.radians(direction)
        steepest = (1 - MIN_FLOOR_DEPTH) * depth / (0.625 * extent * (abs(math.cos(a)) + abs(math.sin(a))))
        slope = float(np.exp(rng.uniform(math.log(0.003), math.log(0.999 * min(0.5, steepest)))))
        return Scene(extent, pixel, depth=depth, walls=bool(rng.random() < 0.5), stones=stones,
                     floor=FloorSpec(slope, direction), height_range=2 * max(s.depth for s in stones), name=name, **c)
    raise ValueError(kind)
