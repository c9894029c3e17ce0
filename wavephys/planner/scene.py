"""Scenes as data: what the output must show, from a TOML file or built in code.

A :class:`Scene` says what a viewer will see, not how to compute it: the square of water
(``extent``), the smallest feature the viewer can resolve (``pixel``: the output texel,
or a camera distance times the angle one pixel subtends), the water and its depth, the
sources (stones dropped at t = 0, ships on straight courses, a wind sea), how long and
how often frames are needed, the bit depths of the height texture and the image, and
the sun and view elevations. The planner (:func:`wavephys.planner.plan`) turns it into
the cheapest model that meets a tolerance.

TOML layout (every key optional except ``extent`` and one of ``pixel`` /
``camera_distance`` + ``pixel_angle``)::

    name = "pond"
    extent = 16.0            # m, side of the visible square
    pixel = 0.0625           # m per output texel (extent / pixel = texels per side, even)
    depth = 2.0              # m, or "inf" for deep water
    open_water = true        # waves leave the square (open-ocean cutoff) or wrap (a tank)
    walls = false            # the square is a walled tank (a pool): waves reflect at its edges
    duration = 2.0           # s of output
    fps = 30.0               # output frames per second
    height_bits = 8          # bit depth of the height texture
    height_range = 0.05      # m: the texture maps [-range, range] onto its codes
    image_bits = 8
    sun_elevation = 40.0     # degrees above the horizon
    view_elevation = 35.0    # degrees above the horizon of the camera's line of sight
    caustics = false         # the image shows the floor lit through the waves (periodic scenes with a floor)
    [water]                  # wavephys.Water fields (SI), depth comes from the top level
    sigma = 0.074
    [[stones]]               # dropped at t = 0: x, y (m), radius (m), depth (m)
    x = 0.0
    y = 1.0
    radius = 0.2
    depth = 0.02
    [[ships]]                # straight course from (x, y) at speed (m/s) along heading (deg)
    x = -4.0
    y = 0.0
    speed = 2.0
    heading = 0.0
    length = 2.0             # m, Gaussian hull of this length and width
    width = 0.8
    strength = 0.02          # m²/s
    [floor]                  # a plane floor: depth varies across the square (default: flat)
    slope = 0.02             # tan β, the rise per metre, in [0, 0.5]
    direction = 0.0          # degrees anticlockwise from +x: the way the water gets shallower
    [wind]                   # a Phillips sea added at t = 0
    speed = 5.0              # m/s
    direction = 0.0          # degrees
    amplitude = 1e-4         # Phillips constant (dimensionless scale)
    seed = 0

Units are SI throughout; every value is checked (named errors) when the scene is made.
"""

from __future__ import annotations

import math
from dataclasses import MISSING, dataclass, fields, replace
from pathlib import Path
from typing import Optional

from wavephys.core.inputs import check_bool, check_instance, check_int, check_scalar, describe
from wavephys.core.water import Water

__all__ = ["Scene", "StoneSpec", "ShipSpec", "WindSpec", "FloorSpec", "MIN_TEXELS", "MAX_TEXELS", "MIN_FLOOR_DEPTH"]

MIN_TEXELS, MAX_TEXELS = 32, 2048
"""Output texels per side the planner accepts (the range its error and cost models were measured on)."""
MAX_FRAMES = 4000
"""Most output frames of one scene (duration × fps)."""


def _float(table_name: str, key: str, value, **limits) -> float:
    check_scalar(f"{table_name}{key}", value, **limits)
    return float(value)


@dataclass(frozen=True)
class StoneSpec:
    """A stone dropped at t = 0: the crater of :class:`wavephys.Stones` in scene coordinates.

    Parameters
    ----------
    x, y : float
        Centre, m, from the centre of the visible square (inside it).
    radius : float
        Crater radius, m, > 0 (a scene refuses one below 2 pixels or above extent/4).
    depth : float
        Crater depth, m, ≥ 0.
    """

    x: float
    y: float
    radius: float
    depth: float

    def __post_init__(self):
        for k in ("x", "y"):
            object.__setattr__(self, k, _float("stones.", k, getattr(self, k)))
        object.__setattr__(self, "radius", _float("stones.", "radius", self.radius, lo=0.0, lo_open=True))
        object.__setattr__(self, "depth", _float("stones.", "depth", self.depth, lo=0.0))


@dataclass(frozen=True)
class ShipSpec:
    """A ship on a straight course with a Gaussian hull (:class:`wavephys.physics.ship_waves.Ship`).

    Parameters
    ----------
    x, y : float
        Start of the hull's centre at t = 0, m, from the centre of the visible square.
    speed : float
        m/s, in (0, 50].
    heading : float
        Direction of travel, degrees anticlockwise from +x.
    length, width : float
        Hull size, m, > 0 (the Gaussian's 4σ along and across the course).
    strength : float
        Source strength s of the hull's ∂(s f)/∂t, m²/s (Loviscach 2003, eq. 2).

    References
    ----------
    J. Loviscach, "Complex water effects at interactive frame rates", WSCG 2003.
    """

    x: float
    y: float
    speed: float
    heading: float = 0.0
    length: float = 2.0
    width: float = 0.8
    strength: float = 0.02

    def __post_init__(self):
        for k in ("x", "y", "heading", "strength"):
            object.__setattr__(self, k, _float("ships.", k, getattr(self, k)))
        object.__setattr__(self, "speed", _float("ships.", "speed", self.speed, lo=0.0, lo_open=True, hi=50.0))
        for k in ("length", "width"):
            object.__setattr__(self, k, _float("ships.", k, getattr(self, k), lo=0.0, lo_open=True))

    @property
    def velocity(self) -> tuple[float, float]:
        """(vx, vy), m/s."""
        a = math.radians(self.heading)
        return self.speed * math.cos(a), self.speed * math.sin(a)

    def position(self, t: float) -> tuple[float, float]:
        """Where the hull's centre is at time t (s), m."""
        check_scalar("t", t)
        vx, vy = self.velocity
        return self.x + vx * t, self.y + vy * t


MIN_FLOOR_DEPTH = 0.2
"""Shallowest water a sloping floor may leave anywhere on the simulated square, as a fraction of
the scene's ``depth`` (the planner's depth models were measured on submerged floors; a shoreline is
the ``shore`` render scene's)."""


@dataclass(frozen=True)
class FloorSpec:
    """A plane floor under the scene: the depth is the scene's ``depth`` at the centre of the
    visible square and changes by ``slope`` metres per metre, shallower along ``direction``:
    h(x, y) = depth − slope·(x cos θ + y sin θ).

    Parameters
    ----------
    slope : float
        tan β of the floor, in [0, 0.5].
    direction : float
        Degrees anticlockwise from +x: the way the water gets shallower.
    """

    slope: float
    direction: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "slope", _float("floor.", "slope", self.slope, lo=0.0, hi=0.5))
        object.__setattr__(self, "direction", _float("floor.", "direction", self.direction))

    def depth(self, depth: float, x, y):
        """h(x, y), m, for the centre depth ``depth`` (m, > 0, finite) at points x, y (m, finite,
        arrays that broadcast)."""
        import numpy as np

        from wavephys.core.inputs import check_array

        check_scalar("depth", depth, lo=0.0, lo_open=True)
        check_array("x", x)
        check_array("y", y)
        a = math.radians(self.direction)
        return depth - self.slope * (np.asarray(x) * math.cos(a) + np.asarray(y) * math.sin(a))


@dataclass(frozen=True)
class WindSpec:
    """A Phillips wind sea added at t = 0 (:func:`wavephys.physics.wind.phillips_spectrum`).

    Parameters
    ----------
    speed : float
        Wind speed, m/s, in [0.1, 40].
    direction : float
        Wind direction, degrees anticlockwise from +x (the sea runs downwind).
    amplitude : float
        The Phillips constant A, in (0, 1].
    seed : int
        Seed of the random phases, in [0, 2³¹ − 1].

    References
    ----------
    J. Tessendorf, "Simulating ocean water", SIGGRAPH course notes, 2001 (eq. 40).
    """

    speed: float
    direction: float = 0.0
    amplitude: float = 1e-4
    seed: int = 0

    def __post_init__(self):
        object.__setattr__(self, "speed", _float("wind.", "speed", self.speed, lo=0.1, hi=40.0))
        object.__setattr__(self, "direction", _float("wind.", "direction", self.direction))
        object.__setattr__(self, "amplitude", _float("wind.", "amplitude", self.amplitude, lo=0.0, lo_open=True,
                                                     hi=1.0))
        object.__setattr__(self, "seed", check_int("wind.seed", self.seed, lo=0, hi=2**31 - 1))


@dataclass(frozen=True)
class Scene:
    """What a scene's output must show (module doc). All lengths m, times s, angles degrees.

    Parameters
    ----------
    extent : float
        Side of the visible square of water, m.
    pixel : float
        Output texel, m: the smallest feature a viewer can see. ``extent / pixel`` must be
        an even integer in [MIN_TEXELS, MAX_TEXELS]. Give it, or (in TOML) a
        ``camera_distance`` (m) and ``pixel_angle`` (rad), whose product it is.
    depth : float
        Water depth, m (``math.inf``: deep water).
    open_water : bool, optional
        True: waves leave the square (an open-ocean cutoff margin of 1/8 of the side
        surrounds it); False: the square is periodic (a tank whose waves wrap). A scene
        with a wind sea is periodic either way (:attr:`margin`). Default: True, or False
        for a walled scene.
    duration, fps : float
        Seconds of output and output frames per second (frames at 1/fps, 2/fps, …,
        duration).
    height_bits, height_range : int, float
        The height texture's bit depth and the half-range it spans, m (±range).
    image_bits : int
        Bit depth of the rendered image.
    sun_elevation, view_elevation : float
        Degrees above the horizon (view: of the camera's line of sight to the water).
    water : Water
        Water properties; its ``depth`` is replaced by ``depth``.
    stones, ships, wind :
        The sources (:class:`StoneSpec`, :class:`ShipSpec`, :class:`WindSpec` or None).
    caustics : bool
        The image shows the floor lit through the waves (the sun's light focused by them,
        :mod:`wavephys.planner.caustics`). Needs a floor (finite ``depth``) and a periodic
        scene (a tank, or a wind sea: :attr:`margin` 0), because the light is traced
        through the visible square alone.
    floor : FloorSpec, optional
        A sloping plane floor (None: flat at ``depth``, which is then the depth at the centre).
        The full model steps the waves over it with the symmetric depth stepper
        (:func:`wavephys.simulation.depth.step_symmetric`, linear); the planner weighs that
        against the spectral step at the centre's depth (the ``depth_model`` term). Needs a
        finite depth, open water or walls (a periodic square would put a step in the floor
        at its seam), stones only, and water at least :data:`MIN_FLOOR_DEPTH` × ``depth``
        deep everywhere on the visible square and an n/8 margin around it.
    walls : bool
        The visible square is a tank closed by vertical walls at its four edges (a pool):
        waves reflect there (docs/physics.md §1.11). Its full model steps the tank's cosine
        modes exactly; the planner weighs that against a periodic square and an absorbing
        margin (the ``boundary`` term). Stones only (ships and a wind sea in a walled tank
        are not planned), no caustics, at most 1024 texels per side (its per-mode bounds
        are taken on the tank's even extension, twice the side: :meth:`even_extension`).
    """

    extent: float
    pixel: float
    depth: float = math.inf
    open_water: Optional[bool] = None
    duration: float = 2.0
    fps: float = 30.0
    height_bits: int = 8
    height_range: float = 0.05
    image_bits: int = 8
    sun_elevation: float = 45.0
    view_elevation: float = 35.0
    water: Water = Water()
    stones: tuple = ()
    ships: tuple = ()
    wind: Optional[WindSpec] = None
    caustics: bool = False
    walls: bool = False
    floor: Optional[FloorSpec] = None
    name: str = "scene"

    def __post_init__(self):
        set_ = lambda k, v: object.__setattr__(self, k, v)
        if not isinstance(self.name, str) or not self.name:
            raise TypeError(f"name must be a non-empty str, got {describe(self.name)}")
        set_("extent", _float("", "extent", self.extent, lo=0.01, hi=1e5))
        set_("pixel", _float("", "pixel", self.pixel, lo=0.0, lo_open=True))
        texels = self.extent / self.pixel
        n = round(texels)
        if abs(texels - n) > 1e-6 * texels or n % 2:
            raise ValueError(f"extent / pixel must be an even integer (texels per side), got "
                             f"{self.extent:g} / {self.pixel:g} = {texels:.6g}")
        if not MIN_TEXELS <= n <= MAX_TEXELS:
            raise ValueError(f"extent / pixel = {n} texels per side is outside [{MIN_TEXELS}, {MAX_TEXELS}], the "
                             f"range the planner's models were measured on")
        set_("depth", _float("", "depth", self.depth, lo=0.0, lo_open=True, allow_inf=True))
        set_("walls", check_bool("walls", self.walls))
        if self.open_water is None:
            set_("open_water", not self.walls)
        set_("open_water", check_bool("open_water", self.open_water))
        if self.walls and self.open_water:
            raise ValueError("walls = true closes the square with reflecting walls: open_water = true (waves leave "
                             "it) contradicts it; leave open_water out or set it false")
        set_("duration", _float("", "duration", self.duration, lo=0.0, lo_open=True, hi=3600.0))
        set_("fps", _float("", "fps", self.fps, lo=1.0, hi=1000.0))
        frames = round(self.duration * self.fps)
        if frames < 1 or frames > MAX_FRAMES:
            raise ValueError(f"duration × fps = {self.duration * self.fps:g} frames must lie in [1, {MAX_FRAMES}]")
        set_("height_bits", check_int("height_bits", self.height_bits, lo=1, hi=32))
        set_("height_range", _float("", "height_range", self.height_range, lo=0.0, lo_open=True))
        set_("image_bits", check_int("image_bits", self.image_bits, lo=1, hi=32))
        set_("sun_elevation", _float("", "sun_elevation", self.sun_elevation, lo=0.0, lo_open=True, hi=90.0))
        set_("view_elevation", _float("", "view_elevation", self.view_elevation, lo=0.0, lo_open=True, hi=90.0))
        check_instance("water", self.water, Water, "wavephys.Water")
        set_("water", replace(self.water, depth=self.depth))
        for key, cls in (("stones", StoneSpec), ("ships", ShipSpec)):
            items = getattr(self, key)
            if isinstance(items, (str, bytes, dict)) or not hasattr(items, "__iter__"):
                raise TypeError(f"{key} must be a sequence of {cls.__name__}, got {describe(items)}")
            items = tuple(items)
            for i, item in enumerate(items):
                check_instance(f"{key}[{i}]", item, cls, f"wavephys.planner.{cls.__name__}")
            set_(key, items)
        if self.wind is not None:
            check_instance("wind", self.wind, WindSpec, "wavephys.planner.WindSpec (or None)")
        if not (self.stones or self.ships or self.wind):
            raise ValueError("a scene needs at least one source: stones, ships or wind")
        self._check_sources()
        set_("caustics", check_bool("caustics", self.caustics))
        if self.caustics and math.isinf(self.depth):
            raise ValueError("caustics = true needs a floor: give a finite depth (m), not inf")
        if self.caustics and self.texels > 512:
            raise ValueError(f"caustics = true is planned up to 512 texels per side (the planner traces the floor "
                             f"light 4x finer), got {self.texels}")
        if self.caustics and self.margin:
            raise ValueError("caustics = true needs a periodic scene (open_water = false, or a wind sea): the light "
                             "is traced through the visible square alone, which an open-water cutoff margin surrounds")
        self._check_walls()
        self._check_floor()

    def _check_walls(self):
        if not self.walls:
            return
        if self.ships or self.wind is not None:
            raise ValueError(f"walls = true: a walled tank is planned with stones only (this scene has "
                             f"{len(self.ships)} ships{', a wind sea' if self.wind is not None else ''}): the pure step "
                             f"refuses ships in a tank, and a wind sea fills an open square")
        if self.caustics:
            raise ValueError("walls = true with caustics = true is not planned yet: the floor light is traced "
                             "through a periodic square, which a walled tank is not")
        if self.texels > MAX_TEXELS // 2:
            raise ValueError(f"walls = true is planned up to {MAX_TEXELS // 2} texels per side (its bounds are taken "
                             f"on the tank's even extension, twice the side), got {self.texels}")

    def _check_floor(self):
        if self.floor is None:
            return
        check_instance("floor", self.floor, FloorSpec, "wavephys.planner.FloorSpec (or None)")
        if math.isinf(self.depth):
            raise ValueError("floor: a sloping floor needs a finite depth (m) at the centre, not inf")
        if not (self.margin or self.walls):
            raise ValueError("floor: a sloping floor needs open water (a margin) or walls: a periodic square would "
                             "join its deep and shallow edges in a step")
        if self.ships:
            raise ValueError(f"floor: a sloping floor is planned with stones only (this scene has {len(self.ships)} "
                             f"ships): the depth stepper has no ship source")
        half = 0.625 * self.extent  # the simulated square with an n/8 margin (a walled scene's margin option too)
        a = math.radians(self.floor.direction)
        shallowest = self.depth - self.floor.slope * half * (abs(math.cos(a)) + abs(math.sin(a)))
        if shallowest < MIN_FLOOR_DEPTH * self.depth:
            raise ValueError(f"floor: slope {self.floor.slope:g} leaves {shallowest:.3g} m of water at the shallowest "
                             f"corner of the square and its n/8 margin, below {MIN_FLOOR_DEPTH:g} × depth = "
                             f"{MIN_FLOOR_DEPTH * self.depth:.3g} m (the planned range; a shoreline is the "
                             f"shore render scene's)")

    def depth_range(self) -> tuple[float, float]:
        """(shallowest, deepest) water on the visible square and an n/8 margin around it, m (both
        ``depth`` without a floor)."""
        if self.floor is None:
            return self.depth, self.depth
        half = 0.625 * self.extent
        a = math.radians(self.floor.direction)
        reach = self.floor.slope * half * (abs(math.cos(a)) + abs(math.sin(a)))
        return self.depth - reach, self.depth + reach

    def even_extension(self) -> "Scene":
        """The walled tank as a periodic scene twice its side: each stone with its three images
        in the walls (the method of images). The tank's cosine modes are exactly this scene's
        Fourier modes (docs/physics.md §1.11), so its heights on the quadrant [−extent, 0]²
        are the tank's, and its per-mode bounds are the tank's (a floor is left out: the
        per-mode bounds are the constant-depth model's). ValueError for a scene without walls."""
        if not self.walls:
            raise ValueError("even_extension: this scene has no walls")
        half = self.extent / 2
        stones = tuple(replace(s, x=sx * (s.x - half), y=sy * (s.y - half))
                       for s in self.stones for sx in (1, -1) for sy in (1, -1))
        return replace(self, extent=2 * self.extent, walls=False, open_water=False, stones=stones, floor=None,
                       name=f"{self.name} (even extension)")

    def _check_sources(self):
        half = self.extent / 2
        for i, s in enumerate(self.stones):
            if abs(s.x) > half or abs(s.y) > half:
                raise ValueError(f"stones[{i}] at ({s.x:g}, {s.y:g}) m lies outside the ±{half:g} m square")
            if s.radius < 2 * self.pixel:
                raise ValueError(f"stones[{i}].radius {s.radius:g} m must be ≥ 2 pixels ({2 * self.pixel:g} m): a "
                                 f"smaller crater is not seen")
            if 4 * s.radius > self.extent:
                raise ValueError(f"stones[{i}].radius {s.radius:g} m must be ≤ extent/4 = {self.extent / 4:g} m")
        for i, s in enumerate(self.ships):
            for t in (0.0, self.duration):
                x, y = s.position(t)
                reach = half - 0.75 * s.length - 0.5 * self.extent / 8
                if abs(x) > reach or abs(y) > reach:
                    raise ValueError(f"ships[{i}] is at ({x:.3g}, {y:.3g}) m at t = {t:g} s: its course must stay "
                                     f"{0.75 * s.length + self.extent / 16:.3g} m inside the square (±{reach:.3g} m)")
            if s.width < 4 * self.pixel:
                raise ValueError(f"ships[{i}].width {s.width:g} m must be ≥ 4 pixels ({4 * self.pixel:g} m)")

    # -- derived numbers ----------------------------------------------------------------
    @property
    def texels(self) -> int:
        """Output texels per side."""
        return round(self.extent / self.pixel)

    @property
    def frames(self) -> int:
        """Number of output frames (at 1/fps, …, duration)."""
        return round(self.duration * self.fps)

    @property
    def margin(self) -> int:
        """Cutoff margin, output texels per side: n/8 for open water, 0 for a periodic tank and
        for a scene with a wind sea (the sea fills the square, so it is simulated periodic, as
        FFT oceans are: a cutoff would damp it by an amount that depends on Δt, measured at
        4 % of its height after one step of 1/15 s against 1/30 s)."""
        return self.texels // 8 if self.open_water and self.wind is None else 0

    @property
    def height_quantum(self) -> float:
        """One code of the height texture, m: 2·range / (2^bits − 1)."""
        return 2.0 * self.height_range / (2.0 ** self.height_bits - 1.0)

    @property
    def image_quantum(self) -> float:
        """One code of the image on a [0, 1] scale: 1 / (2^bits − 1)."""
        return 1.0 / (2.0 ** self.image_bits - 1.0)

    # -- files ----------------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: dict, name: str = "scene") -> "Scene":
        """A scene from the TOML layout of the module doc (a dict). Unknown keys are refused
        by name, with the allowed ones."""
        if not isinstance(data, dict):
            raise TypeError(f"a scene must be a table (dict), got {describe(data)}")
        data = dict(data)
        allowed = {f.name for f in fields(cls)} | {"camera_distance", "pixel_angle"}
        _refuse_unknown("scene", data, allowed)
        if "camera_distance" in data or "pixel_angle" in data:
            if "pixel" in data:
                raise ValueError("give pixel, or camera_distance and pixel_angle, not both")
            if not ("camera_distance" in data and "pixel_angle" in data):
                raise ValueError("camera_distance and pixel_angle go together (pixel = distance × angle)")
            d = _float("", "camera_distance", data.pop("camera_distance"), lo=0.0, lo_open=True)
            a = _float("", "pixel_angle", data.pop("pixel_angle"), lo=0.0, lo_open=True, hi=0.1)
            data["pixel"] = d * a
        for key in ("extent", "pixel"):
            if key not in data:
                raise ValueError(f"a scene needs {key!r}" + (" (or camera_distance and pixel_angle)"
                                                             if key == "pixel" else ""))
        if isinstance(data.get("depth"), str):
            if data["depth"].strip().lower() not in ("inf", "infinity", "deep"):
                raise ValueError(f"depth must be a number of metres or \"inf\", got {data['depth']!r}")
            data["depth"] = math.inf
        if "water" in data:
            water = data["water"]
            if not isinstance(water, dict):
                raise TypeError(f"water must be a table of Water fields, got {describe(water)}")
            _refuse_unknown("water", water, {"g", "rho", "sigma"})
            for k, v in water.items():
                if isinstance(v, bool) or not isinstance(v, (int, float)):
                    raise TypeError(f"water.{k} must be a number, got {describe(v)}")
            data["water"] = Water(**{k: float(v) for k, v in water.items()})
        for key, spec in (("stones", StoneSpec), ("ships", ShipSpec)):
            if key in data:
                items = data[key]
                if not isinstance(items, list):
                    raise TypeError(f"{key} must be an array of tables ([[{key}]]), got {describe(items)}")
                built = []
                for i, item in enumerate(items):
                    if not isinstance(item, dict):
                        raise TypeError(f"{key}[{i}] must be a table, got {describe(item)}")
                    _refuse_unknown(f"{key}[{i}]", item, {f.name for f in fields(spec)})
                    try:
                        built.append(spec(**item))
                    except TypeError as exc:
                        if "required positional" in str(exc) or "missing" in str(exc):
                            need = [f.name for f in fields(spec) if f.default is MISSING and f.default_factory is MISSING]
                            raise ValueError(f"{key}[{i}] needs {', '.join(need)}; got {sorted(item)}") from None
                        raise
                data[key] = tuple(built)
        for key, spec, need in (("floor", FloorSpec, "slope (tan β)"), ("wind", WindSpec, "speed (m/s)")):
            if key in data:
                table = data[key]
                if not isinstance(table, dict):
                    raise TypeError(f"{key} must be a table, got {describe(table)}")
                _refuse_unknown(key, table, {f.name for f in fields(spec)})
                if need.split()[0] not in table:
                    raise ValueError(f"{key} needs {need}")
                data[key] = spec(**table)
        data.setdefault("name", name)
        return cls(**data)

    @classmethod
    def from_toml(cls, path) -> "Scene":
        """Read a scene from a TOML file (module doc). FileNotFoundError names the path."""
        import tomllib

        if not isinstance(path, (str, Path)):
            raise TypeError(f"path must be a str or pathlib.Path, got {describe(path)}")
        p = Path(path)
        if p.is_dir():
            raise ValueError(f"path: {str(p)!r} is a folder, not a scene file (.toml)")
        if not p.is_file():
            raise FileNotFoundError(f"scene file {str(p)!r} does not exist")
        try:
            data = tomllib.loads(p.read_text(encoding="utf-8"))
        except UnicodeDecodeError as exc:
            raise ValueError(f"path: {str(p)!r} is not a text file (UTF-8 TOML): {exc.reason} at byte {exc.start}") \
                from None
        except tomllib.TOMLDecodeError as exc:
            raise ValueError(f"path: {str(p)!r} is not valid TOML: {exc}") from None
        except RecursionError:
            raise ValueError(f"path: {str(p)!r} nests its arrays or tables too deeply to be a scene") from None
        try:
            return cls.from_dict(data, name=p.stem)
        except (TypeError, ValueError) as exc:
            raise type(exc)(f"path {str(p)!r}: {exc}") from None

    def as_dict(self) -> dict:
        """The scene as the TOML layout's dict (``from_dict(scene.as_dict())`` equals it)."""
        out = {f.name: getattr(self, f.name) for f in fields(self)
               if f.name not in ("water", "stones", "ships", "wind", "floor")}
        out["depth"] = "inf" if math.isinf(self.depth) else self.depth
        out["water"] = dict(g=self.water.g, rho=self.water.rho, sigma=self.water.sigma)
        out["stones"] = [vars(s).copy() for s in self.stones]
        out["ships"] = [vars(s).copy() for s in self.ships]
        if self.wind is not None:
            out["wind"] = vars(self.wind).copy()
        if self.floor is not None:
            out["floor"] = vars(self.floor).copy()
        return out


def _refuse_unknown(where: str, table: dict, allowed: set) -> None:
    unknown = sorted(set(table) - set(allowed))
    if unknown:
        raise ValueError(f"{where}: unknown key(s) {', '.join(map(repr, unknown))}; allowed: "
                         f"{', '.join(sorted(allowed))}")
