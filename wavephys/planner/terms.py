"""The planner's terms: one class each, in one registry (:data:`TERMS`).

A term is one switch of the model a scene runs with: what it may be set to
(:meth:`PlanTerm.options`), what the full model uses (:meth:`PlanTerm.full`), whether the
scene has anything for it to change (:meth:`PlanTerm.applies`), what an option alone adds to
the error and saves against the full model (:meth:`PlanTerm.bound`, :meth:`PlanTerm.saving`),
how it changes a configuration (:meth:`PlanTerm.apply`) and why the plan chose it
(:meth:`PlanTerm.reason`). :func:`wavephys.planner.plan.plan` takes its candidates from the
product of the terms' options and writes the model card from :meth:`PlanTerm.row`.

Three kinds, by how their errors combine (docs/planner.md):

* ``"height"``: the spectral step's terms (σ, depth factor, coarsening, steps per frame,
  second order, margin, ship method and patch) change every Fourier mode together, so they
  are bounded *jointly* per mode (:func:`wavephys.planner.predict.height_bounds`, over the
  product of their options); the error a term adds alone is read off that joint bound with
  the other terms full. The surface model is a height term bounded by
  :func:`wavephys.planner.predict.surface_bounds`.
* ``"texture"``: the height texture's rounding adds to the height bound.
* ``"colour"``: Fresnel, absorption and caustics bound the image's error
  (:func:`wavephys.planner.plan.colour_errors`); their costs add.

Everything a term reads about a scene is in one :class:`PlanContext`, built once per plan
(the spectrum, the calibration, the candidates and their bounds, the colour errors).

* ``"added"``: terms registered beside the built-in ones (:meth:`Terms.register`), each one
  :class:`AddedTerm`: their errors add to the heights' or the colour's bound, their costs to
  the plan's, and their options change the run through their own hooks.

Adding a term whose error adds: one :class:`AddedTerm` subclass anywhere, registered with
``TERMS.register(term)`` (docs/planner.md §5). Adding a term of the spectral step: one
subclass here with its registry entry, its field in :class:`wavephys.planner.model.Choices`,
what it changes in :class:`~wavephys.planner.model.SceneModel`, its bound in
:func:`wavephys.planner.predict.height_bounds`, its cost and its test.
"""

from __future__ import annotations

__internal__ = True  # the planner's own models: used through plan(), not fuzzed as public API

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from functools import cached_property
from typing import ClassVar, Optional

import numpy as np

from wavephys.planner.caustics import MARGIN
from wavephys.planner.colour import incidence_range
from wavephys.planner.cost import caustics_cost, colour_cost, texture_cost
from wavephys.planner.model import CAUSTICS_JACOBIAN, CAUSTICS_OPTIONS, CAUSTICS_REFINE, FULL_REFINE, SURFACES, TEXTURE_BYTES, TEXTURES, Choices, full_choices
from wavephys.planner.predict import MARGIN_TEXELS, HeightBounds, default_height_options, height_peak, texture_error
from wavephys.planner.scene import Scene
from wavephys.planner.spectrum import scene_spectrum

__all__ = ["PlanTerm", "AddedTerm", "PlanContext", "Candidate", "Term", "TERMS", "HEIGHT_TERMS", "COLOUR_TERMS",
           "fresnel_forms", "absorption_methods", "colour_total", "caustics_delta", "CAUSTICS_METHODS_NOTE",
           "CAUSTICS_PLANNED", "CAUSTICS_NOT_PLANNED"]


@dataclass(frozen=True)
class Candidate:
    """One height configuration: its choices, predicted error bounds and predicted cost (s).

    Attributes
    ----------
    choices : Choices
        The height model's settings.
    bounds : HeightBounds
        Its predicted error bounds, m.
    cost : float
        Its predicted cost, s over the whole run (every frame; as every cost of the plan).
    pending : bool
        Whether its bounds still lack the cutoff's change with the grid and Δt.
    """

    choices: Choices
    bounds: HeightBounds
    cost: float
    pending: bool = False
    """True while its bounds lack the cutoff's change with the grid and Δt
    (:func:`wavephys.planner.predict.margin_step_error`): :meth:`PlanContext.settle` adds it."""


@dataclass(frozen=True)
class Term:
    """One row of a model card: the term, its choice, what that choice alone adds to the error
    (m for heights, [0, 1] for colour), what it saves (s), and why.

    Attributes
    ----------
    term : str
        The term's name.
    choice : object
        What the plan chose for it.
    error : float
        What that choice alone adds to the error, in ``unit``.
    saving : float
        What it saves against the term's most exact choice, s over the whole run.
    reason : str
        Why, in words.
    unit : str
        ``"m"`` for heights, ``"colour"`` for the [0, 1] colour scale.
    """

    term: str
    choice: object
    error: float
    saving: float
    reason: str
    unit: str = "m"


@dataclass(frozen=True)
class PlanContext:
    """One scene's numbers, computed once per plan and read by every term.

    ``calibration`` the cost calibration (:func:`wavephys.planner.cost.calibration` unless a
    caller passes its own), ``candidates`` every height configuration with its bounds and cost,
    ``full`` the full model's candidate, ``colour`` the colour error bounds of each optics
    option (:func:`wavephys.planner.plan.colour_errors`), ``caustics`` the traced caustics
    errors (None: the scene shows none).

    Attributes
    ----------
    scene : Scene
    calibration : dict
        The cost calibration.
    candidates : tuple of Candidate
        Every height configuration.
    full : Candidate
        The full model's.
    colour : dict
        The colour error bounds of each optics option.
    caustics : CausticsErrors or None
        The traced caustics errors.
    """

    scene: Scene
    calibration: dict
    candidates: tuple
    full: Candidate
    colour: dict
    caustics: object = None

    @cached_property
    def spectrum(self):
        """The scene's modes (:func:`wavephys.planner.spectrum.scene_spectrum`)."""
        return scene_spectrum(self.scene)

    @property
    def gather_points(self) -> Optional[int]:
        """The points a side the Jacobian gather takes on the scene's screened frames (what its cost
        is read at; None without caustics)."""
        return self.caustics.gather_points if self.caustics is not None else None

    @cached_property
    def by_choices(self) -> dict:
        return {c.choices: c for c in self.candidates}

    @cached_property
    def _settled(self) -> dict:
        return {}

    def settle(self, cand: Optional[Candidate]) -> Optional[Candidate]:
        """``cand`` with the cutoff's change with the grid and Δt added to its bounds (run once per
        coarsening and steps per frame, on the first candidate that needs it)."""
        if cand is None or not cand.pending:
            return cand
        if cand.choices not in self._settled:
            from wavephys.planner.predict import margin_step_error

            e = margin_step_error(self.scene, cand.choices.coarsen, cand.choices.steps_per_frame)
            b = cand.bounds
            self._settled[cand.choices] = Candidate(cand.choices, HeightBounds(b.linear + e, b.second_order, b.rounding,
                                                                               b.rms + e), cand.cost)
        return self._settled[cand.choices]

    def base(self, choices: Choices) -> Candidate:
        """The full model's candidate with ``choices``' depth model (over a sloping floor the
        constant-depth model's other terms are measured from the constant-depth full model)."""
        return self.settle(self.by_choices.get(replace(self.full.choices, depth_model=choices.depth_model), self.full))

    def alone(self, name: str, value) -> Optional[Candidate]:
        """The height candidate with ``name`` set to ``value`` and every other term full (None
        if that configuration cannot run)."""
        return self.settle(self.by_choices.get(replace(self.full.choices, **{name: value})))


class PlanTerm:
    """One switchable term of the planner (module doc). Subclasses set :attr:`name` (the
    :class:`~wavephys.planner.model.Choices` field), :attr:`kind` and :attr:`unit`, and
    implement :meth:`options` and :meth:`reason`; the defaults suit a height term.

    Attributes
    ----------
    name : str
        The :class:`~wavephys.planner.model.Choices` field the term sets (class attribute).
    kind : str
        ``"height"`` or ``"colour"`` (class attribute).
    unit : str
        The unit of its error: ``"m"`` or ``"colour"`` (class attribute).
    """

    name: ClassVar[str]
    kind: ClassVar[str] = "height"
    unit: ClassVar[str] = "m"

    def options(self, scene: Scene) -> tuple:
        """The values the planner considers for ``scene``, the full model's first (a height
        term's: :func:`wavephys.planner.predict.default_height_options`, the joint bound's own)."""
        return default_height_options(scene)[self.name]

    def full(self, scene: Scene):
        """The full model's value for ``scene``."""
        return getattr(full_choices(scene), self.name)

    def applies(self, scene: Scene) -> bool:
        """Whether the scene has a choice to make here (more than one option)."""
        return len(self.options(scene)) > 1

    def apply(self, choices: Choices, option) -> Choices:
        """``choices`` with this term set to ``option``."""
        return replace(choices, **{self.name: option})

    def bound(self, ctx: PlanContext, option) -> float:
        """What ``option`` alone adds to the error against the full model (inf: cannot run alone)."""
        alone = ctx.alone(self.name, option)
        return (alone.bounds.total - ctx.full.bounds.total) if alone else math.nan

    def saving(self, ctx: PlanContext, option) -> float:
        """Seconds ``option`` alone saves against the full model."""
        alone = ctx.alone(self.name, option)
        return (ctx.full.cost - alone.cost) if alone else math.nan

    def reason(self, ctx: PlanContext, option, error: float) -> str:
        raise NotImplementedError

    def row(self, ctx: PlanContext, choices: Choices) -> Term:
        """The model card's row for the plan's ``choices``."""
        value = getattr(choices, self.name)
        base = ctx.base(choices) if self.kind == "height" and self.name != "depth_model" else ctx.full
        if base is ctx.full:
            err, saving = self.bound(ctx, value), self.saving(ctx, value)
        else:  # constant depth under a sloping floor: this term's share from that model's full configuration
            alone = ctx.settle(ctx.by_choices.get(replace(base.choices, **{self.name: value})))
            err = (alone.bounds.total - base.bounds.total) if alone else math.nan
            saving = (base.cost - alone.cost) if alone else math.nan
        reason = self.reason(ctx, value, err)
        if ctx.scene.caustics and self.kind == "height":
            reason += "; heights kept as the full model's: the image shows caustics, which a height change moves"
        return Term(self.name, value, max(err, 0.0), saving, reason, self.unit)


def _effect(ctx: PlanContext, err: float) -> str:
    q = ctx.scene.height_quantum
    return f"adds ≤ {err:.2g} m ({err / q:.2g} quanta)" if math.isfinite(err) else "not runnable alone"


# -- the spectral step's terms (bounded jointly, predict.height_bounds) ----------------------------

class SurfaceTension(PlanTerm):
    """σ in ω² = (gk + σk³/ρ) tanh kh, or σ = 0."""

    name = "surface_tension"

    def reason(self, ctx, option, error):
        water = ctx.scene.water
        lam_c = 2 * math.pi * math.sqrt(water.sigma / (water.rho * water.g)) if water.sigma > 0 else 0.0
        seen = f"shortest wave shown {2 * ctx.scene.pixel:.3g} m, capillary length 2π√(σ/ρg) = {lam_c:.3g} m"
        return f"kept: {seen}" if option else f"dropped: {seen}; {_effect(ctx, error)}"


class FiniteDepth(PlanTerm):
    """tanh kh, or deep water (tanh = 1)."""

    name = "finite_depth"

    def reason(self, ctx, option, error):
        if math.isinf(ctx.scene.depth):
            return "deep water: tanh kh = 1 exactly"
        k_min = float(ctx.spectrum.k.min())
        return (f"{'kept' if option else 'dropped'}: smallest kh = {k_min * ctx.scene.depth:.3g}"
                + ("" if option else f"; {_effect(ctx, error)}"))


class Coarsen(PlanTerm):
    """The grid = the texels, or every 2nd or 4th point (frames Fourier-interpolated)."""

    name = "coarsen"

    def reason(self, ctx, option, error):
        return "output resolution" if option == 1 else f"grid {option}× coarser than the texels: {_effect(ctx, error)}"


class StepsPerFrame(PlanTerm):
    """Δt = 1/fps, or 2, 4 or 8 frames per step (Hermite frames between)."""

    name = "steps_per_frame"

    def reason(self, ctx, option, error):
        dt = option / ctx.scene.fps
        return ("a step per frame" if option == 1 else
                f"Δt = {dt:.3g} s, ω_top·Δt = {ctx.spectrum.omega_top * dt:.2g}: Hermite frames {_effect(ctx, error)}")


class SecondOrder(PlanTerm):
    """η + η₂, or η."""

    name = "second_order"

    def reason(self, ctx, option, error):
        spec = ctx.spectrum
        if ctx.scene.floor is not None and ctx.scene.floor.slope > 0:
            return "linear: over a sloping floor the full model (the depth stepper) is linear"
        return f"kept: η₂ up to {spec.s0 * spec.s1 / 2:.2g} m" if option else f"dropped: {_effect(ctx, error)}"


class Margin(PlanTerm):
    """n/8 texels of cutoff around the visible square, n/16, or none (periodic)."""

    name = "margin"

    def reason(self, ctx, option, error):
        scene = ctx.scene
        if scene.walls:
            return "a walled scene: its edges are the boundary term's"
        if not scene.margin:
            return "a periodic scene: no margin"
        if scene.texels > MARGIN_TEXELS:
            return f"n/8: margins are planned up to {MARGIN_TEXELS} texels"
        size = {"n/8": scene.texels // 8, "n/16": scene.texels // 16, "none": 0}[option]
        if option == "n/8":
            return f"the full model's {size} texels a side"
        return f"{size} texels a side (measured against n/8 on the linear model, ×1.25): {_effect(ctx, error)}"


class DepthModel(PlanTerm):
    """A sloping floor: the waves stepped over it (the symmetric depth stepper), or the spectral
    step at the centre's depth (:data:`wavephys.planner.model.DEPTH_MODELS`); evaluated like the
    margin (:func:`wavephys.planner.predict.depth_errors`)."""

    name = "depth_model"

    def reason(self, ctx, option, error):
        scene = ctx.scene
        if scene.floor is None or scene.floor.slope == 0:
            return "a flat floor: the spectral step is exact"
        lo, hi = scene.depth_range()
        span = f"the floor slopes {scene.floor.slope:g} (depth {lo:.3g}–{hi:.3g} m over the visible square and its n/8 margin)"
        if option == "varying":
            return f"stepped over the floor (symmetric depth stepper, linear): {span}"
        return (f"constant depth {scene.depth:g} m (the spectral step, every other term open): {span}; measured "
                f"against the floor on the linear model, ×1.25: {_effect(ctx, error)}")


class Boundary(PlanTerm):
    """A walled scene's edges: reflecting walls (exact), a periodic square, or an absorbing margin
    (:data:`wavephys.planner.model.BOUNDARIES`); evaluated like the margin
    (:func:`wavephys.planner.predict.boundary_errors`)."""

    name = "boundary"

    def reason(self, ctx, option, error):
        scene = ctx.scene
        if not scene.walls:
            return "no walls"
        if option == "walls":
            return "reflecting walls: the tank's cosine modes stepped exactly"
        what = ("periodic: a wave reaching a wall comes back through the opposite one" if option == "periodic" else
                f"an absorbing margin of {scene.texels // 8} texels: the waves leave instead of reflecting")
        return f"{what} (measured against the walls on the linear model, ×1.25): {_effect(ctx, error)}"


class ShipMethod(PlanTerm):
    """Φ1/Φ2 kernels, or impulses (the hull's change added at once)."""

    name = "ship_method"

    def reason(self, ctx, option, error):
        if not ctx.scene.ships:
            return "no ships"
        if option == "kernels":
            return "Φ1/Φ2 kernels: exact for straight motion within a step"
        return f"impulses (the hull's change added at each step's end): {_effect(ctx, error)}"


class ShipPatch(PlanTerm):
    """Twice the smallest patch that holds the hull, or the smallest."""

    name = "ship_patch"

    def reason(self, ctx, option, error):
        if not ctx.scene.ships:
            return "no ships"
        if self.full(ctx.scene) == 1:
            return "the single patch: the doubled one would leave the visible square"
        return ("the doubled patch (the full model's)" if option == 2 else
                f"the single patch (its truncation evaluated per mode at three steps, ×1.25): {_effect(ctx, error)}")


class Surface(PlanTerm):
    """The spectral step, or for a wind sea alone a cheap surface model (Gerstner sums,
    choppy displacement, fBm noise: :data:`wavephys.planner.model.SURFACES`)."""

    name = "surface"

    def options(self, scene):
        wind_only = scene.wind is not None and not scene.stones and not scene.ships
        return SURFACES if wind_only else SURFACES[:1]

    def _others(self, ctx):
        return sorted((c for c in ctx.candidates if c.choices.surface != "spectral"), key=lambda c: c.bounds.total)

    def bound(self, ctx, option):
        mine = next((c for c in self._others(ctx) if c.choices.surface == option), None)
        return 0.0 if mine is None else mine.bounds.total - ctx.full.bounds.total

    def saving(self, ctx, option):
        mine = next((c for c in self._others(ctx) if c.choices.surface == option), None)
        return 0.0 if mine is None else ctx.full.cost - mine.cost

    def reason(self, ctx, option, error):
        others = self._others(ctx)
        if not others:
            return "spectral step: the scene has stones or ships (the other surface models stand for a wind sea alone)"
        q = ctx.scene.height_quantum
        listing = "; ".join(f"{c.choices.surface} ≤ {c.bounds.total / q:.3g} quanta at {c.cost / ctx.full.cost:.3g}× "
                            f"the step's cost" for c in others)
        return f"spectral step: {listing}" if option == "spectral" else \
            f"{option} within the tolerance and cheaper; {listing}"

    def row(self, ctx, choices):
        value = choices.surface
        return Term(self.name, value, self.bound(ctx, value), self.saving(ctx, value), self.reason(ctx, value, 0.0))


# -- the height texture -----------------------------------------------------------------------------

class Texture(PlanTerm):
    """float32 heights, or half float, 16- or 8-bit codes over each frame's span."""

    name = "texture"
    kind = "texture"

    def options(self, scene):
        return ("f32",) if scene.caustics else TEXTURES  # caustics scenes keep the full model's heights

    def error(self, scene: Scene, option, bounds: HeightBounds) -> float:
        """The rounding the format adds to a configuration of height ``bounds``, m."""
        return texture_error(option, height_peak(scene, bounds))

    def cost(self, ctx: PlanContext, option) -> float:
        return texture_cost(ctx.scene, option, ctx.calibration)

    def bound(self, ctx, option):
        return self.error(ctx.scene, option, ctx.full.bounds)

    def saving(self, ctx, option):
        return self.cost(ctx, "f32") - self.cost(ctx, option)

    def reason(self, ctx, option, error):
        scene = ctx.scene
        kib = scene.texels**2 * TEXTURE_BYTES[option] / 1024
        size = f"{kib:.3g} KiB a frame (float32: {scene.texels**2 * 4 / 1024:.3g} KiB)"
        if option == "f32":
            why = ("the image shows caustics: heights kept" if scene.caustics else
                   "no smaller format fits the tolerance at a cost within the slack")
            return f"float32: {size}; {why}"
        q = scene.height_quantum
        what = {"f16": "half float", "u16": "16-bit codes over each frame's span",
                "u8": "8-bit codes over each frame's span"}
        return f"{what[option]}: {size}; rounding ≤ {error:.2g} m ({error / q:.2g} quanta)"


# -- the colour terms ---------------------------------------------------------------------------------

def caustics_delta(caustics, refine: int) -> tuple:
    """(|E_plan − E_full|/E₀, largest E/E₀) of tracing at ``refine`` (evaluated on the full
    model's surface, :mod:`wavephys.planner.caustics`); (0, 1) for a scene without caustics.
    Scenes with caustics keep the full model's heights, so this is the whole change.

    Parameters
    ----------
    caustics : CausticsErrors or None
    refine : int
        The tracing refinement (0: off).

    Returns
    -------
    (float, float)
    """
    if caustics is None:
        return 0.0, 1.0
    return caustics.delta[refine], max(caustics.e_max[FULL_REFINE], caustics.e_max[refine])


def colour_total(colour: dict, fresnel: str, absorption: str, delta: float, e_max: float) -> float:
    """ΔC ≤ ΔR·max(1, T·albedo·E_max) + albedo·ΔT·E_max + T·albedo·ΔE: the colour error of a
    Fresnel form, an absorption method and a caustics change together (the shading of
    :func:`wavephys.planner.runner.shade`).

    Parameters
    ----------
    colour : dict
        The colour error bounds (:func:`wavephys.planner.colour.colour_errors`).
    fresnel, absorption : str
        The optics forms.
    delta : float
        The caustics change, relative to E₀.
    e_max : float
        The largest E/E₀.

    Returns
    -------
    float
        ΔC on the [0, 1] colour scale.
    """
    dr, dt = colour["fresnel"][fresnel], colour["absorption"][absorption]
    floor = colour["floor"]  # the largest T·albedo
    out = dr * max(1.0, floor * e_max) if dr else 0.0
    out += dt * e_max if dt else 0.0
    return out + (floor * delta if delta else 0.0)


def fresnel_forms(calibration: dict) -> tuple:
    """The Fresnel forms the planner offers: every entry of the family
    (:data:`optics.light.fresnel.REFLECTANCE_METHODS`) that the calibration has a cost for,
    exact first. The others are listed by :func:`uncalibrated_fresnel_forms`.

    Parameters
    ----------
    calibration : dict

    Returns
    -------
    tuple of str
    """
    from optics.light.fresnel import REFLECTANCE_METHODS

    forms = [f for f in REFLECTANCE_METHODS if f in calibration.get("fresnel", {})]
    return tuple(sorted(forms, key=lambda f: f != "exact"))


def uncalibrated_fresnel_forms(calibration: dict) -> tuple:
    """Entries of the Fresnel family the calibration lacks (``python -m bench calibrate`` adds them)."""
    from optics.light.fresnel import REFLECTANCE_METHODS

    return tuple(f for f in REFLECTANCE_METHODS if f not in calibration.get("fresnel", {}))


def absorption_methods(calibration: dict) -> tuple:
    """The absorption methods the planner offers: every entry of the family
    (:data:`optics.light.attenuation.WATER_TRANSMITTANCE_METHODS`) the calibration has a cost
    for, spectral first.

    Parameters
    ----------
    calibration : dict

    Returns
    -------
    tuple of str
    """
    from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

    methods = [m for m in WATER_TRANSMITTANCE_METHODS if m in calibration.get("absorption", {})]
    return tuple(sorted(methods, key=lambda m: m != "spectral"))


class Fresnel(PlanTerm):
    """The exact Fresnel reflectance, or a shader form (Schlick, a LUT, …) from the family."""

    name = "fresnel"
    kind = "colour"
    unit = "colour"

    def options(self, scene, calibration=None):
        from wavephys.planner.cost import calibration as shipped

        return fresnel_forms(calibration if calibration is not None else shipped())

    def bound(self, ctx, option, refine: int = 0):
        """ΔR alone, × the floor light at caustics refinement ``refine`` where caustics show."""
        _, e_max = caustics_delta(ctx.caustics, refine)
        return colour_total(ctx.colour, option, "spectral", 0.0, e_max)

    def row(self, ctx, choices):
        value = choices.fresnel
        err = self.bound(ctx, value, choices.caustics)
        return Term(self.name, value, err, self.saving(ctx, value), self.reason(ctx, value, err), self.unit)

    def saving(self, ctx, option):
        cal = ctx.calibration
        return colour_cost(ctx.scene, "exact", "spectral", cal) - colour_cost(ctx.scene, option, "spectral", cal)

    def reason(self, ctx, option, error):
        lo, hi = incidence_range(ctx.scene)
        q = ctx.scene.image_quantum
        out = f"{option}: |ΔR| ≤ {error:.2g} over incidence {lo:.0f}–{hi:.0f}° = {error / q:.2g} image quanta"
        missing = uncalibrated_fresnel_forms(ctx.calibration)
        return out + (f"; not calibrated, so not offered: {', '.join(missing)}" if missing else "")


class Absorption(PlanTerm):
    """Beer–Lambert integrated over the spectrum, or three fitted RGB coefficients."""

    name = "absorption"
    kind = "colour"
    unit = "colour"

    def options(self, scene, calibration=None):
        from wavephys.planner.cost import calibration as shipped

        return absorption_methods(calibration if calibration is not None else shipped())

    def bound(self, ctx, option, refine: int = 0):
        """albedo·ΔT alone, × the floor light at caustics refinement ``refine``."""
        _, e_max = caustics_delta(ctx.caustics, refine)
        return colour_total(ctx.colour, "exact", option, 0.0, e_max)

    def row(self, ctx, choices):
        value = choices.absorption
        err = self.bound(ctx, value, choices.caustics)
        return Term(self.name, value, err, self.saving(ctx, value), self.reason(ctx, value, err), self.unit)

    def saving(self, ctx, option):
        cal = ctx.calibration
        return colour_cost(ctx.scene, "exact", "spectral", cal) - colour_cost(ctx.scene, "exact", option, cal)

    def reason(self, ctx, option, error):
        from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

        missing = [m for m in WATER_TRANSMITTANCE_METHODS if m not in ctx.calibration.get("absorption", {})]
        note = f"; not calibrated, so not offered: {', '.join(missing)}" if missing else ""
        if math.isinf(ctx.scene.depth):
            return f"{option}: deep water, no floor seen{note}"
        return (f"{option}: ≤ {error / ctx.scene.image_quantum:.2g} image quanta over paths "
                f"{ctx.scene.depth * 2:.3g} m and longer{note}")


CAUSTICS_PLANNED = {"beam": "refine 1–4", "jacobian": "where every frame stays below its first fold"}
"""The methods of :data:`optics.caustics.FLOOR_IRRADIANCE_METHODS` the caustics term offers."""

CAUSTICS_NOT_PLANNED = {
    "photon": "photons: 3–17 % of the peak at 37× a step",
    "gl": "GL beams: 53× a step on llvmpipe",
    "blinn_phong": "Blinn–Phong: 34–95 % of the peak (a shading trick, not a flux)",
    "reference": "the reference: the beam refined until converged, the planner's yardstick",
}
"""Why the other methods of the caustics family are not choices: measured by the optics bench on 9
generated surfaces at 128² and at 512² against a step (docs/planner.md §3). Every method of the family
is in this mapping or in :data:`CAUSTICS_PLANNED` (a test keeps it so: a new method is a decision)."""

CAUSTICS_METHODS_NOTE = ("not offered, dominated by the beam (python -m bench optics): "
                         + "; ".join(v for k, v in CAUSTICS_NOT_PLANNED.items() if k != "reference"))
"""The card's note on the caustics methods it does not offer (from :data:`CAUSTICS_NOT_PLANNED`)."""


class Caustics(PlanTerm):
    """The floor's caustics by beam rasterization refined r times, by the Jacobian gather (where
    every frame stays below its first fold and the calibration has its cost), or off
    (flat-water light)."""

    name = "caustics"
    kind = "colour"
    unit = "colour"

    def options(self, scene, calibration=None):
        if not scene.caustics:
            return (0,)
        from wavephys.planner.cost import calibration as shipped

        cal = calibration if calibration is not None else shipped()
        return CAUSTICS_OPTIONS if "caustics_jacobian" in cal else CAUSTICS_REFINE

    def cost(self, ctx, option) -> float:
        return caustics_cost(ctx.scene, option, ctx.calibration, ctx.gather_points)

    def bound(self, ctx, option):
        if ctx.caustics is None:
            return 0.0
        delta, e_max = caustics_delta(ctx.caustics, option)
        return colour_total(ctx.colour, "exact", "spectral", delta, e_max)

    def saving(self, ctx, option):
        return 0.0 if ctx.caustics is None else self.cost(ctx, FULL_REFINE) - self.cost(ctx, option)

    def reason(self, ctx, option, error):
        caustics = ctx.caustics
        if caustics is None:
            return "the scene shows no caustics"
        q = ctx.scene.image_quantum
        light = (f"E/E₀ up to {caustics.e_max[FULL_REFINE] / MARGIN:.3g} at the traced frames "
                 f"{', '.join(map(str, caustics.frames))} (of {len(caustics.screen)} screened)")
        if option == 0:
            return f"off: {light}; ≤ {error / q:.2g} image quanta"
        jacobian = caustics.delta.get(CAUSTICS_JACOBIAN, math.inf)
        if option == CAUSTICS_JACOBIAN:
            return (f"the Jacobian gather: {light}; ≤ {error / q:.2g} image quanta against the beam refined "
                    f"{FULL_REFINE}; {CAUSTICS_METHODS_NOTE}")
        why = ("the Jacobian gather: the screened frames fold (past the first fold it is not offered)"
               if not math.isfinite(jacobian) else "")
        return (f"beam, refine {option}: {light}; tracing ≤ {error / q:.2g} image quanta; {CAUSTICS_METHODS_NOTE}"
                + (f"; {why}" if why else ""))


# -- terms added to the registry -------------------------------------------------------------------

class AddedTerm(PlanTerm):
    """A term registered beside the built-in ones (:meth:`Terms.register`): everything about it is
    in its one class. Its error adds to the heights' bound (``unit = "m"``) or the colour's
    (``unit = "colour"``) by the triangle inequality, its cost adds to the plan's, and its
    option changes the run through :meth:`change_heights` and :meth:`change_colour` (the terms'
    hooks run in the order of their names), checked when run
    (:func:`wavephys.planner.runner.run`, :func:`~wavephys.planner.runner.shade`). Its setting
    travels in :attr:`Choices.added <wavephys.planner.model.Choices>`, so
    :class:`~wavephys.planner.model.Choices` needs no field for it.

    Subclasses set :attr:`name`, :attr:`unit` and :attr:`exact` and implement :meth:`options`,
    :meth:`error` and :meth:`cost`; :meth:`reason`, :meth:`change_heights` and
    :meth:`change_colour` have defaults.

    Attributes
    ----------
    name : str
        A Python identifier, not a built-in term's (class attribute).
    unit : str
        ``"m"`` (its error adds to the heights') or ``"colour"`` (to the colour's).
    exact : object
        The full model's option: the first of :meth:`options`, with error 0.
    """

    kind: ClassVar[str] = "added"
    exact: ClassVar[object]

    def options(self, scene: Scene, calibration: Optional[dict] = None) -> tuple:
        """The options the planner considers for ``scene``, :attr:`exact` first."""
        raise NotImplementedError

    def full(self, scene: Scene):
        return self.exact

    def error(self, ctx: PlanContext, option) -> float:
        """What ``option`` adds to the heights' (m) or the colour's ([0, 1]) max-norm bound, ≥ 0."""
        raise NotImplementedError

    def cost(self, ctx: PlanContext, option) -> float:
        """Seconds ``option`` adds to the plan's run (over all its frames, as every cost of the
        plan is counted), ≥ 0."""
        raise NotImplementedError

    def change_heights(self, model, frames: np.ndarray, option) -> np.ndarray:
        """The height frames (frames, n, n), m, as ``option`` changes them (default: unchanged)."""
        return frames

    def change_colour(self, model, colour: np.ndarray, option) -> np.ndarray:
        """The shaded colour (n, n, 3), [0, 1], as ``option`` changes it (default: unchanged)."""
        return colour

    def bound(self, ctx, option):
        return self.error(ctx, option)

    def saving(self, ctx, option):
        return self.cost(ctx, self.exact) - self.cost(ctx, option)

    def reason(self, ctx, option, error):
        unit = "m" if self.unit == "m" else "of the colour scale"
        return f"{option}: adds ≤ {error:.2g} {unit}" if option != self.exact else f"{option}: the full model's"

    def row(self, ctx, choices):
        value = choices.get(self.name)
        err = self.bound(ctx, value)
        return Term(self.name, value, err, self.saving(ctx, value), self.reason(ctx, value, err), self.unit)

    def checked_options(self, scene: Scene, calibration: dict) -> tuple:
        """:meth:`options`, checked: a non-empty tuple starting with :attr:`exact`."""
        opts = self.options(scene, calibration)
        if not isinstance(opts, tuple) or not opts or opts[0] != self.exact:
            raise ValueError(f"term {self.name!r}: options(scene) must be a non-empty tuple starting with its exact "
                             f"option {self.exact!r}, got {opts!r}")
        return opts

    def checked(self, what: str, ctx: PlanContext, option) -> float:
        """:meth:`error` or :meth:`cost` of ``option``, checked finite and ≥ 0 (the exact error 0)."""
        value = float(getattr(self, what)(ctx, option))
        if not (math.isfinite(value) and value >= 0.0) or (what == "error" and option == self.exact and value):
            raise ValueError(f"term {self.name!r}: {what}({option!r}) must be finite and ≥ 0"
                             f"{' (0 for the exact option)' if what == 'error' else ''}, got {value!r}")
        return value


class Terms(Mapping):
    """The registry: term name → :class:`PlanTerm`, in the order model cards list them.

    The built-in terms are fixed; :meth:`register` adds an :class:`AddedTerm` (listed last) and
    :meth:`unregister` takes it out again.
    """

    def __init__(self, *terms: PlanTerm):
        self._terms = {t.name: t for t in terms}
        fields = set(Choices.__dataclass_fields__)
        missing = [t.name for t in terms if t.name not in fields]
        if missing:
            raise ValueError(f"terms {missing} have no field in Choices")
        self._builtin = frozenset(self._terms)

    def register(self, term: AddedTerm) -> AddedTerm:
        """Add ``term`` to every plan from now on (returned, so this can decorate an instance's
        creation).

        Parameters
        ----------
        term : AddedTerm
            An instance; its ``name`` a Python identifier no term has, its ``unit`` ``"m"`` or
            ``"colour"``.

        Returns
        -------
        AddedTerm

        Raises
        ------
        TypeError
            ``term`` is not an :class:`AddedTerm` instance, or lacks ``exact``.
        ValueError
            A name taken or not an identifier, or another unit.
        """
        if not isinstance(term, AddedTerm):
            raise TypeError(f"term must be an AddedTerm instance (wavephys.planner.terms.AddedTerm), got "
                            f"{type(term).__name__}")
        name = getattr(term, "name", None)
        if not isinstance(name, str) or not name.isidentifier():
            raise ValueError(f"term.name must be a Python identifier, got {name!r}")
        if name in self._terms or name in Choices.__dataclass_fields__:
            raise ValueError(f"term.name {name!r} is taken: terms {', '.join(self._terms)}")
        if term.unit not in ("m", "colour"):
            raise ValueError(f"term.unit must be 'm' or 'colour', got {term.unit!r}")
        if not hasattr(term, "exact"):
            raise TypeError(f"term {name!r} must set exact, the full model's option")
        self._terms[name] = term
        return term

    def unregister(self, name: str) -> None:
        """Take the added term ``name`` out (a built-in term cannot be)."""
        if name in self._builtin:
            raise ValueError(f"{name!r} is a built-in term: only registered terms can be unregistered")
        if name not in self._terms:
            raise KeyError(f"no registered term {name!r}")
        del self._terms[name]

    def added(self) -> tuple:
        """The registered :class:`AddedTerm` instances, in registration order."""
        return tuple(t for n, t in self._terms.items() if n not in self._builtin)

    def __getitem__(self, name):
        return self._terms[name]

    def __iter__(self):
        return iter(self._terms)

    def __len__(self):
        return len(self._terms)

    def of_kind(self, kind: str) -> tuple:
        return tuple(t for t in self._terms.values() if t.kind == kind)


TERMS = Terms(Surface(), DepthModel(), Margin(), Boundary(), SurfaceTension(), FiniteDepth(), Coarsen(), StepsPerFrame(), SecondOrder(),
              ShipMethod(), ShipPatch(), Texture(), Fresnel(), Absorption(), Caustics())
"""Every switchable term, in model-card order."""
HEIGHT_TERMS = tuple(t.name for t in TERMS.of_kind("height") if t.name != "surface")
"""The spectral step's terms, bounded jointly (:func:`wavephys.planner.predict.height_bounds`)."""
COLOUR_TERMS = tuple(t.name for t in TERMS.of_kind("colour"))
