"""The planner's configuration: what each switchable term is set to, and the model it makes.

:class:`Choices` holds one setting per term (:data:`TERMS`); :class:`SceneModel` is a
scene plus choices, and builds what the rest of the library runs: the pure step's
:class:`wavephys.simulation.Model` (:attr:`SceneModel.simulation`), the sources, the
output grid, and the optics settings (Fresnel form and absorption method, names in
:data:`optics.light.fresnel.REFLECTANCE_METHODS` and
:data:`optics.light.attenuation.WATER_TRANSMITTANCE_METHODS`).

The grid of a scene: the output texels (``extent / pixel`` per side), surrounded for
open water by a cutoff margin of n/8 texels on every side (so the simulated square is
1.25 × the visible one); ``coarsen`` = c simulates on every c-th point of it and
Fourier-interpolates each frame back onto the output texels.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields, replace
from functools import cached_property, lru_cache

import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.inputs import check_bool, check_choice, check_instance, check_int, describe
from wavephys.core.water import Water
from wavephys.planner.scene import Scene

__all__ = ["Choices", "SceneModel", "TERMS", "COARSEN", "STEPS_PER_FRAME",
           "CAUSTICS_REFINE", "CAUSTICS_JACOBIAN", "CAUSTICS_OPTIONS", "FULL_REFINE", "TEXTURES", "TEXTURE_BYTES", "SURFACES", "SURFACE_OPTIONS", "SURFACES_NOT_PLANNED", "SHIP_METHODS", "SHIP_PATCHES", "MARGINS", "BOUNDARIES", "DEPTH_MODELS", "full_choices"]

COARSEN = (1, 2, 4)
"""Simulation grid spacings the planner considers, in output texels."""
STEPS_PER_FRAME = (1, 2, 4, 8)
"""Output frames per simulation step the planner considers (frames between steps by Hermite)."""
CAUSTICS_REFINE = (0, 1, 2, 3, 4)
"""Caustics tracing refinements the planner considers (0: off, the floor lit as under flat water;
r: beam rasterization of the surface refined r times, :func:`optics.caustics.floor_irradiance_beam`)."""
CAUSTICS_JACOBIAN = "jacobian"
"""The caustics choice by the Jacobian of the landing map (:func:`optics.caustics.floor_irradiance_jacobian`),
offered where every frame stays below its first fold and the calibration has its cost."""
CAUSTICS_OPTIONS = CAUSTICS_REFINE + (CAUSTICS_JACOBIAN,)
"""Every value of :attr:`Choices.caustics`."""
FULL_REFINE = 4
"""The full model's caustics refinement."""
SURFACE_OPTIONS = {"gerstner": ("gerstner-16", "gerstner-64", "gerstner-256"), "choppy": ("choppy",),
                   "noise": ("noise",)}
"""The planner's options for each sea model of :data:`wavephys.surfaces.SEA_MODELS` it offers (a
Gerstner sum of the K strongest waves for K = 16, 64, 256)."""
SURFACES_NOT_PLANNED: dict = {}
"""Sea models of :data:`wavephys.surfaces.SEA_MODELS` the planner does not offer, with the reason
(none: every model is offered)."""
SURFACES = ("spectral",) + tuple(o for options in SURFACE_OPTIONS.values() for o in options)
"""Surface models the planner considers for a wind sea (a scene whose only source is the wind):
the spectral step (the full model); the K strongest of the sea's own waves summed directly at
every frame (:class:`wavephys.surfaces.gerstner.GerstnerWaves`, steepness 0: no horizontal
motion); the sea in closed form with Tessendorf's horizontal displacement (choppiness 1,
resampled onto the texels: :mod:`wavephys.surfaces.choppy`); a procedural fBm of the sea's
RMS height (:class:`wavephys.surfaces.noise.NoiseSea`). The alternatives have no second-order
term and are evaluated on the output texels at every frame."""
SHIP_METHODS = ("kernels", "impulses")
"""How a ship makes its waves each step (:data:`wavephys.physics.ship_waves.SHIP_METHODS`): the
Φ1/Φ2 kernels (exact for straight motion within a step; the full model) or the naive row of
impulses (the hull's change added at once)."""
MARGINS = ("n/8", "n/16", "none")
"""Open-water cutoff margins the planner considers, per side: an eighth of the visible texels
(the full model), a sixteenth, or none (the visible square simulated periodic, right only while
nothing that matters reaches its edges). Periodic scenes have none either way."""
BOUNDARIES = ("walls", "periodic", "margin")
"""How a walled scene's edges are modelled (``Scene(walls=True)``, a pool): reflecting walls,
the tank's cosine modes stepped exactly (the full model); the square periodic (a wave that
reaches a wall comes back through the opposite one: right until the first wave reaches a wall);
or an open-water cutoff margin of n/8 texels around it (the wave leaves: no reflection).
Scenes without walls ignore it."""
DEPTH_MODELS = ("varying", "constant")
"""How a scene with a sloping floor (``Scene(floor=...)``) is stepped: over the floor by the
symmetric depth stepper (:func:`wavephys.simulation.depth.step_symmetric`, linear, a step per
frame on the full grid: the full model), or by the spectral step at the centre's depth (every
other term open). Scenes with a flat floor ignore it."""
SHIP_PATCHES = (1, 2)
"""Ship patch sides the planner considers, in multiples of the smallest power-of-two patch that
holds the hull and its motion over a step (:attr:`SceneModel.ship_patch`); the full model takes
2 where that patch stays inside the visible square, else 1."""
TEXTURES = ("f32", "f16", "u16", "u8")
"""Height texture formats the planner considers: float32 (the full model), half float, and
16- or 8-bit normalized integers spanning each frame's own minimum to maximum
(:func:`optics.rendering.textures.encode_height`)."""
TEXTURE_BYTES = {"f32": 4, "f16": 2, "u16": 2, "u8": 1}
"""Bytes per texel of each height texture format."""
TERMS = ("surface", "depth_model", "margin", "boundary", "surface_tension", "finite_depth", "coarsen", "steps_per_frame", "second_order", "ship_method",
         "ship_patch", "texture", "fresnel",
         "absorption", "caustics")
"""The switchable terms' names, in the order model cards list them (the terms themselves, one
class each: :data:`wavephys.planner.terms.TERMS`; a test keeps the two equal)."""


def __getattr__(name):
    if name == "FRESNEL_FORMS":  # 0.3: the forms come from optics' family
        import warnings

        from optics.light.fresnel import REFLECTANCE_METHODS

        warnings.warn("wavephys.planner.model.FRESNEL_FORMS is deprecated: the planner offers every entry of "
                      "optics.light.fresnel.REFLECTANCE_METHODS its calibration covers "
                      "(wavephys.planner.terms.fresnel_forms)", DeprecationWarning, stacklevel=2)
        return tuple(REFLECTANCE_METHODS)
    if name == "ABSORPTION_METHODS":  # 0.3: the methods come from optics' family
        import warnings

        from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

        warnings.warn("wavephys.planner.model.ABSORPTION_METHODS is deprecated: the planner offers every entry of "
                      "optics.light.attenuation.WATER_TRANSMITTANCE_METHODS its calibration covers "
                      "(wavephys.planner.terms.absorption_methods)", DeprecationWarning, stacklevel=2)
        return tuple(WATER_TRANSMITTANCE_METHODS)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


@dataclass(frozen=True)
class Choices:
    """One setting per switchable term; the defaults are the full model.

    Parameters
    ----------
    surface_tension : bool
        Keep σ (capillary waves) in the dispersion; False sets σ = 0.
    finite_depth : bool
        Keep tanh(kh); False treats the water as deep.
    coarsen : int
        Simulation grid spacing in output texels (:data:`COARSEN`).
    steps_per_frame : int
        Δt = steps_per_frame / fps; frames between steps are Hermite-interpolated
        (:data:`STEPS_PER_FRAME`). 1: every frame is a step.
    second_order : bool
        Add the second-order height term.
    fresnel : str
        Fresnel reflectance form: a name in :data:`optics.light.fresnel.REFLECTANCE_METHODS`
        (the planner offers the ones its calibration has a cost for).
    absorption : str
        A name in :data:`optics.light.attenuation.WATER_TRANSMITTANCE_METHODS` (``"spectral"``,
        ``"rgb"``; the planner offers the ones its calibration has a cost for).
    caustics : int or str
        Caustics tracing refinement (:data:`CAUSTICS_REFINE`; 0 off), or ``"jacobian"``
        (:data:`CAUSTICS_JACOBIAN`). Only scenes with ``caustics = true`` show them; the others
        run with 0.
    margin : str
        The open-water cutoff margin (:data:`MARGINS`); periodic scenes ignore it.
    boundary : str
        A walled scene's edges (:data:`BOUNDARIES`); scenes without walls ignore it.
    depth_model : str
        A sloping floor's model (:data:`DEPTH_MODELS`); scenes with a flat floor ignore it.
        ``"varying"`` runs with ``coarsen`` 1, ``steps_per_frame`` 1, ``second_order`` False,
        σ and tanh kh kept, and the full margin.
    ship_method : str
        How ships make waves (:data:`SHIP_METHODS`); scenes without ships ignore it.
    ship_patch : int
        Ship patch side in multiples of the smallest that holds the hull (:data:`SHIP_PATCHES`).
    surface : str
        The surface model (:data:`SURFACES`); other than ``"spectral"`` only for scenes
        whose one source is a wind sea, with ``coarsen`` 1, ``steps_per_frame`` 1 and
        ``second_order`` False (they are evaluated at every frame and have no η₂).
    texture : str
        Format of the height texture handed to the renderer (:data:`TEXTURES`): the frames
        are stored in it and read back, so its rounding is part of the output.
    added : tuple of (term, option) pairs
        The settings of terms registered beside the built-in ones
        (:meth:`wavephys.planner.terms.Terms.register`, an
        :class:`~wavephys.planner.terms.AddedTerm` each), sorted by name: a term added to the
        registry needs no field here. Read one with :meth:`get`, set one with :meth:`set`.
    """

    surface_tension: bool = True
    finite_depth: bool = True
    coarsen: int = 1
    steps_per_frame: int = 1
    second_order: bool = True
    fresnel: str = "exact"
    absorption: str = "spectral"
    caustics: int | str = FULL_REFINE
    texture: str = "f32"
    surface: str = "spectral"
    ship_method: str = "kernels"
    ship_patch: int = 2
    margin: str = "n/8"
    boundary: str = "walls"
    depth_model: str = "varying"
    added: tuple = ()

    def __post_init__(self):
        object.__setattr__(self, "added", _check_added(self.added))
        for k in ("surface_tension", "finite_depth", "second_order"):
            object.__setattr__(self, k, check_bool(k, getattr(self, k)))
        object.__setattr__(self, "coarsen", check_int("coarsen", self.coarsen, lo=1))
        check_choice("coarsen", self.coarsen, COARSEN)
        object.__setattr__(self, "steps_per_frame", check_int("steps_per_frame", self.steps_per_frame, lo=1))
        check_choice("steps_per_frame", self.steps_per_frame, STEPS_PER_FRAME)
        from optics.light.fresnel import REFLECTANCE_METHODS

        REFLECTANCE_METHODS.check(self.fresnel, "fresnel")
        from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

        WATER_TRANSMITTANCE_METHODS.check(self.absorption, "absorption")
        if not isinstance(self.caustics, str):
            object.__setattr__(self, "caustics", check_int("caustics", self.caustics, lo=0))
        check_choice("caustics", self.caustics, CAUSTICS_OPTIONS)
        check_choice("texture", self.texture, TEXTURES)
        check_choice("surface", self.surface, SURFACES)
        check_choice("ship_method", self.ship_method, SHIP_METHODS)
        object.__setattr__(self, "ship_patch", check_int("ship_patch", self.ship_patch, lo=1))
        check_choice("ship_patch", self.ship_patch, SHIP_PATCHES)
        check_choice("margin", self.margin, MARGINS)
        check_choice("boundary", self.boundary, BOUNDARIES)
        check_choice("depth_model", self.depth_model, DEPTH_MODELS)
        if self.surface != "spectral" and (self.coarsen != 1 or self.steps_per_frame != 1 or self.second_order):
            raise ValueError(f"surface = {self.surface!r} is evaluated on the output texels at every frame and has no "
                             f"second-order term: it needs coarsen = 1, steps_per_frame = 1 and second_order = False, "
                             f"got {self.coarsen}, {self.steps_per_frame}, {self.second_order}")

    def simpler(self) -> int:
        """How many terms are dropped or cheapened against the full model (tie-breaker: with equal
        cost the planner takes the simpler model)."""
        full = Choices()
        return (sum(getattr(self, f.name) != getattr(full, f.name) for f in fields(self) if f.name != "added")
                + sum(option != term.exact for term, option in self.added))

    def get(self, name: str):
        """The setting of term ``name``: a field, or an added term's option."""
        if not isinstance(name, str):
            raise TypeError(f"name must be a term's name (str), got {describe(name)}")
        if name in _FIELDS:
            return getattr(self, name)
        for term, option in self.added:
            if term.name == name:
                return option
        raise ValueError(f"name {name!r} is no term of these choices: fields {', '.join(_FIELDS)}; added "
                         f"{', '.join(t.name for t, _ in self.added) or 'none'}")

    def set(self, name: str, value, term=None) -> "Choices":
        """A copy with term ``name`` set to ``value``: a field, or an added term's option (``term``,
        the :class:`~wavephys.planner.terms.AddedTerm` itself, when the choices do not hold it
        yet; it is ignored for a field)."""
        if not isinstance(name, str):
            raise TypeError(f"name must be a term's name (str), got {describe(name)}")
        if term is not None and not _is_term(term):
            raise TypeError(f"term must be an AddedTerm (wavephys.planner.terms), got {describe(term)}")
        if term is not None and name not in _FIELDS and term.name != name:
            raise ValueError(f"term is named {term.name!r}, not name {name!r}")
        held = {t.name: t for t, _ in self.added}
        if name not in _FIELDS and term is None and name not in held:
            raise ValueError(f"name {name!r} is no term of these choices: pass term= to add it")
        try:
            if name in _FIELDS:
                return replace(self, **{name: value})
            term = term if term is not None else held[name]
            return replace(self, added=tuple((t, o) for t, o in self.added if t.name != name) + ((term, value),))
        except (TypeError, ValueError) as e:
            raise type(e)(f"value for {name!r}: {e}") from None

    def as_dict(self) -> dict:
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "added"}
        out.update((term.name, option) for term, option in self.added)
        return out


_FIELDS = tuple(f.name for f in fields(Choices) if f.name != "added")
"""The built-in terms' fields of :class:`Choices`."""


def _is_term(term) -> bool:
    """``term`` looks like an :class:`~wavephys.planner.terms.AddedTerm` (this module sits below it)."""
    return (isinstance(getattr(term, "name", None), str) and hasattr(term, "exact")
            and callable(getattr(term, "change_heights", None)) and callable(getattr(term, "change_colour", None)))


def _check_added(added) -> tuple:
    """``Choices.added`` checked: (term, option) pairs, one per name, no name a field; sorted by name."""
    if not isinstance(added, tuple):
        raise TypeError(f"added must be a tuple of (term, option) pairs, got {describe(added)}")
    names = set()
    for item in added:
        if not (isinstance(item, tuple) and len(item) == 2 and _is_term(item[0])):
            raise TypeError(f"added must hold (term, option) pairs with an AddedTerm first, got {describe(item)}")
        name = item[0].name
        if name in _FIELDS:
            raise ValueError(f"added: term {name!r} is a field of Choices; set it there")
        if name in names:
            raise ValueError(f"added: term {name!r} is named twice")
        names.add(name)
        try:
            hash(item[1])
        except TypeError:
            raise TypeError(f"added: the option of {name!r} must be hashable, got {describe(item[1])}") from None
    return tuple(sorted(added, key=lambda item: item[0].name))


def full_choices(scene: Scene | None = None) -> Choices:
    """The most complete configuration: the reference every plan is measured against.

    Parameters
    ----------
    scene : Scene, optional
        For a scene that shows no caustics the caustics term is 0 (nothing to trace); where a
        ship's doubled patch would leave the visible square, the single patch.

    Returns
    -------
    Choices
        ``Choices()`` without a scene.
    """
    if scene is None:
        return Choices()
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    return _full_choices(scene)


@lru_cache(maxsize=64)
def _full_choices(scene: Scene) -> Choices:
    out = Choices() if scene.caustics else Choices(caustics=0)
    if scene.floor is not None and scene.floor.slope > 0:  # the depth stepper is linear
        out = replace(out, second_order=False)
    if scene.ships:
        try:
            SceneModel(scene, out).check_ships()
        except ValueError:
            out = replace(out, ship_patch=1)
    return out


@dataclass(frozen=True)
class SceneModel:
    """A scene and its choices: the configuration the pure step, the optics and the renderer use.

    Attributes are derived on use: :attr:`simulation` (a :class:`wavephys.simulation.Model`),
    :attr:`grid` (the simulated square), :attr:`output_grid`, :attr:`dt`, :attr:`steps`.

    Parameters
    ----------
    scene : Scene
    choices : Choices, optional
        One setting per term (default the full model's, :func:`full_choices` of the scene).
    dtype : {"float32", "float64"}
        The simulation's (float64 needs ``jax_enable_x64``; the planner plans float32).
    """

    scene: Scene
    choices: Choices = None
    dtype: str = "float32"

    def __post_init__(self):
        check_instance("scene", self.scene, Scene, "wavephys.planner.Scene")
        if self.choices is None:
            object.__setattr__(self, "choices", full_choices(self.scene))
        check_instance("choices", self.choices, Choices, "wavephys.planner.Choices")
        check_choice("dtype", self.dtype, ("float32", "float64"))
        if self.choices.surface != "spectral" and (self.scene.stones or self.scene.ships or self.scene.wind is None):
            raise ValueError(f"surface = {self.choices.surface!r} models a wind sea: it needs a scene whose only source "
                             f"is the wind (this one has {len(self.scene.stones)} stones, {len(self.scene.ships)} ships"
                             f"{'' if self.scene.wind is not None else ', no wind'})")
        n_total = self.scene.texels + 2 * self.margin
        c = self.choices.coarsen
        if n_total % (2 * c) or self.margin % c or n_total // c < 16:
            raise ValueError(f"coarsen = {c} does not divide this scene's grid ({n_total} points with a "
                             f"{self.margin}-point margin) into an even grid of ≥ 16 points")
        for i, s in enumerate(self.scene.stones):
            if s.radius < self.grid.dx:
                raise ValueError(f"coarsen = {c}: stones[{i}].radius {s.radius:g} m is below the simulation grid "
                                 f"spacing {self.grid.dx:g} m")

    # -- grids and times --------------------------------------------------------------
    @property
    def margin(self) -> int:
        """The cutoff margin, output texels per side: the scene's (n/8 for open water, 0 for a
        periodic scene) with ``choices.margin`` n/16 or none instead of n/8; a walled scene's
        n/8 with ``choices.boundary`` ``"margin"``, else 0."""
        if self.scene.walls:
            return self.scene.texels // 8 if self.choices.boundary == "margin" else 0
        if not self.scene.margin:
            return 0
        return {"n/8": self.scene.margin, "n/16": self.scene.texels // 16, "none": 0}[self.choices.margin]

    @property
    def full_grid(self) -> Grid:
        """The simulated square at output resolution (visible texels plus margin)."""
        n = self.scene.texels + 2 * self.margin
        return Grid(n, n * self.scene.pixel)

    @property
    def grid(self) -> Grid:
        """The simulation grid (every ``coarsen``-th point of :attr:`full_grid`)."""
        full = self.full_grid
        return Grid(full.n // self.choices.coarsen, full.length)

    @property
    def output_grid(self) -> Grid:
        """The visible texels."""
        return Grid(self.scene.texels, self.scene.extent)

    @property
    def dt(self) -> float:
        """Simulation step, s."""
        return self.choices.steps_per_frame / self.scene.fps

    @property
    def steps(self) -> int:
        """Simulation steps to cover the scene's frames."""
        return -(-self.scene.frames // self.choices.steps_per_frame)

    @property
    def water(self) -> Water:
        """The simulated water (σ = 0 without surface tension, deep without finite depth)."""
        w = self.scene.water
        if not self.choices.surface_tension:
            w = replace(w, sigma=0.0)
        if not self.choices.finite_depth:
            w = replace(w, depth=math.inf)
        return w

    @cached_property
    def ship_patch(self) -> int:
        """Ship patch side, points: ``choices.ship_patch`` × the smallest power of two (≥ 16) that
        holds the hull and its motion over Δt with a quarter to spare, at most the grid."""
        if not self.scene.ships:
            return min(64, self.grid.n)
        return min(self.choices.ship_patch * self.smallest_ship_patch, self.grid.n)

    @cached_property
    def smallest_ship_patch(self) -> int:
        """The smallest power-of-two patch side (≥ 16 points, at most the grid) that holds the
        hull and its motion over Δt with a quarter to spare."""
        dx = self.grid.dx
        need = max(1.5 * 0.5 * math.hypot(s.length, s.width) + 0.5 * s.speed * self.dt for s in self.scene.ships)
        side = 16
        while side * dx / 2 < 1.25 * need and side < self.grid.n:
            side *= 2
        return min(side, self.grid.n)

    @property
    def varying(self) -> bool:
        """Whether the waves are stepped over a sloping floor (``depth_model`` ``"varying"``)."""
        floor = self.scene.floor
        return floor is not None and floor.slope > 0 and self.choices.depth_model == "varying"

    def floor(self):
        """The sloping floor on the simulation grid (:class:`wavephys.simulation.depth.Floor`, 4
        levels), or None where the depth is constant."""
        if not self.varying:
            return None
        self.check_varying()
        from wavephys.simulation.depth import Floor

        x = np.asarray(self.grid.coordinates, np.float64)
        return Floor(self.scene.floor.depth(self.scene.depth, x[None, :], x[:, None]))

    def check_varying(self) -> None:
        """ValueError unless a sloping floor's other height terms are the full model's (the depth
        stepper runs on the full grid, a step per frame, linear, with σ, tanh kh and the full
        margin)."""
        if self.varying:
            c = self.choices
            if (c.coarsen, c.steps_per_frame, c.second_order, c.surface_tension, c.finite_depth, c.margin) != (
                    1, 1, False, True, True, "n/8"):
                raise ValueError(f"depth_model = 'varying' steps the floor on the full grid, a step per frame, linear, "
                                 f"with σ, tanh kh and the full margin: it needs coarsen 1, steps_per_frame 1, "
                                 f"second_order False, surface_tension and finite_depth True, margin 'n/8'; got "
                                 f"{c.coarsen}, {c.steps_per_frame}, {c.second_order}, {c.surface_tension}, "
                                 f"{c.finite_depth}, {c.margin!r}")

    @property
    def walls(self) -> bool:
        """Whether the simulation has reflecting walls (a walled scene, ``boundary`` ``"walls"``)."""
        return self.scene.walls and self.choices.boundary == "walls"

    @property
    def simulation(self):
        """The :class:`wavephys.simulation.Model` of this configuration (pure step, ``run``)."""
        from wavephys.simulation.model import Model

        return Model(self.grid, self.water, self.dt, margin=self.margin // self.choices.coarsen,
                     second_order=self.choices.second_order, dtype=self.dtype, ship_patch=self.ship_patch,
                     ship_method=self.choices.ship_method, walls="all" if self.walls else ())

    # -- sources ----------------------------------------------------------------------
    def stones(self):
        """The scene's stones as :class:`wavephys.Stones` (or None)."""
        if not self.scene.stones:
            return None
        from wavephys.physics.disturbances import Stones

        s = self.scene.stones
        return Stones([v.x for v in s], [v.y for v in s], [v.radius for v in s], [v.depth for v in s])

    def ships(self) -> list:
        """The scene's ships as :class:`wavephys.physics.ship_waves.Ship` sources."""
        from wavephys.physics.ship_waves import Hull, Ship, straight_path

        return [Ship(Hull("gaussian", s.length, s.width), straight_path((s.x, s.y), s.velocity), s.strength)
                for s in self.scene.ships]

    def check_ships(self) -> None:
        """ValueError if a ship's patch leaves the visible square or leaks past ``leak_tolerance``
        at this Δt (checked before any stepping; the leak is measured once per water, grid
        spacing, Δt and patch, on the full model's grid, and shared by every margin)."""
        model = self.simulation
        half, grid = model.ship_patch // 2, model.grid
        lo, hi = model.margin, grid.n - model.margin
        for i, spec in enumerate(self.scene.ships):
            for t in (0.0, self.scene.duration):
                r0, c0, _ = grid.window(*spec.position(t), half)
                if not (lo <= r0 and r0 + 2 * half <= hi and lo <= c0 and c0 + 2 * half <= hi):
                    raise ValueError(f"ships[{i}]: its {2 * half}-point patch leaves the visible square at t = {t:g} s")
        for i, leak in enumerate(_patch_leaks(self.scene, self.choices.coarsen, model.dt, half)):
            if leak > model.leak_tolerance:
                raise ValueError(f"ships[{i}]: {leak:.2g} of the waves leak past the {2 * half}-point patch at "
                                 f"Δt = {model.dt:.3g} s")

    def describe(self) -> str:
        c = self.choices
        if c.surface != "spectral":
            parts = [f"surface {c.surface} on {self.scene.texels}² texels", "σ" if c.surface_tension else "no σ",
                     "tanh kh" if c.finite_depth else "deep", f"texture {c.texture}", f"Fresnel {c.fresnel}",
                     f"absorption {c.absorption}"] + [f"{term.name} {option}" for term, option in c.added]
            return ", ".join(parts)
        parts = [f"grid {self.grid.n}² (dx {self.grid.dx:.3g} m)" + (
                     f", margin {self.margin}" if self.scene.margin or self.margin else "") + (
                     f", {c.boundary}" + (" (reflecting)" if self.walls else "") if self.scene.walls else "") + (
                     (", over the sloping floor (symmetric depth stepper)" if self.varying else
                      f", constant depth {self.scene.depth:g} m") if self.scene.floor is not None else ""),
                 f"Δt {self.dt:.4g} s",
                 "σ" if c.surface_tension else "no σ", "tanh kh" if c.finite_depth else "deep",
                 "2nd order" if c.second_order else "linear"] + (
                    [f"ship {c.ship_method}, patch {self.ship_patch}²"] if self.scene.ships else []) + [
                    f"texture {c.texture}", f"Fresnel {c.fresnel}",
                 f"absorption {c.absorption}"]
        if self.scene.caustics:
            parts.append("caustics by the Jacobian gather" if c.caustics == CAUSTICS_JACOBIAN else
                         f"caustics refine {c.caustics}" if c.caustics else "caustics off (flat-water light)")
        parts += [f"{term.name} {option}" for term, option in c.added]
        return ", ".join(parts)


@lru_cache(maxsize=4096)
def _patch_leaks(scene: Scene, coarsen: int, dt: float, half: int) -> tuple:
    """:func:`wavephys.physics.ship_waves.patch_leak` of each of the scene's ships for a patch of
    half-side ``half`` at Δt ``dt`` on the full model's grid coarsened ``coarsen`` times, with
    the scene's own water (σ and tanh kh change the leak by far less than its tolerance, and one
    compiled patch serves every dispersion variant)."""
    from wavephys.physics.ship_waves import patch_leak

    n = scene.texels + 2 * scene.margin
    grid = Grid(n // coarsen, n * scene.pixel)
    return tuple(patch_leak(ship, grid, scene.water, 0.0, dt, half) for ship in SceneModel(scene, Choices()).ships())


def interior(model: SceneModel, field):
    """The visible texels of a field on :attr:`SceneModel.full_grid` (last two axes)."""
    m = model.margin
    return field[..., m:field.shape[-2] - m, m:field.shape[-1] - m] if m else field


def texel_shift_phase(full: Grid, coarse: Grid):
    """e^{ik·(x₀_coarse − x₀_full)} on the coarse grid's full spectrum: turns a DFT coefficient
    referred to the full grid's first sample into one referred to the coarse grid's."""
    ky, kx = (np.asarray(a) for a in coarse.wavenumbers())
    shift = float(coarse.origin) - float(full.origin)
    return np.exp(1j * (kx + ky) * shift)
