"""The planner: the cheapest configuration whose predicted error stays within the tolerance.

Heights and colour have their own tolerances and error models (in different units); the
choice is made jointly over both, cheapest first:

* heights (m, max norm over every frame and texel): every combination of σ, tanh kh,
  grid coarsening, steps per frame and the second-order term is bounded jointly by
  :func:`wavephys.planner.predict.height_bounds` (one per-mode bound for all linear terms;
  the second-order and float32 terms added by the triangle inequality); a wind sea's other
  surface models by :func:`wavephys.planner.predict.surface_bounds`; the height texture's
  rounding (:func:`wavephys.planner.predict.texture_error`) adds to each;
* colour ([0, 1] image scale, compared with the image's quantum): each Fresnel form
  and absorption method, bounded over the scene's own incidence angles and water paths,
  and for scenes that show caustics the floor light E/E₀ at each tracing refinement
  (traced on the full model's own surface, :mod:`wavephys.planner.caustics`; such scenes
  keep the full model's heights, since a height change moves the light by amounts no term
  bounds):
  ΔC ≤ ΔR·max(1, T·albedo·E_max) + albedo·ΔT·E_max + T·albedo·ΔE (the shading of
  :func:`wavephys.planner.runner.shade`).

Among the combinations within both tolerances the cheapest by the calibrated cost
(:mod:`wavephys.planner.cost`) wins; at equal cost, the one with fewer terms.
"""

from __future__ import annotations

import itertools
import json
import math
import os
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Optional

from wavephys.core.inputs import check_instance, check_scalar
from wavephys.planner.caustics import caustics_errors
from wavephys.planner.colour import colour_errors
from wavephys.planner.cost import calibration as shipped_calibration
from wavephys.planner.cost import (CALIBRATION_KEYS, caustics_cost, check_calibration, colour_cost,  # noqa: F401
                                   describe_calibration, height_cost, load_calibration, texture_cost)
from wavephys.planner.model import FULL_REFINE, TEXTURE_BYTES, Choices, SceneModel, full_choices
from wavephys.planner.predict import HeightBounds, height_bounds, surface_bounds
from wavephys.planner.scene import Scene
from wavephys.planner.terms import HEIGHT_TERMS, TERMS, Candidate, PlanContext, Term, caustics_delta, colour_total

__all__ = ["plan", "Plan", "Term", "Candidate", "Infeasible", "full_model", "candidates", "colour_errors",
           "plan_context"]

REFLECTION_CHOICES = ("keep", "measure")
"""What :meth:`Plan.drawn` does with the render scene's reflected rays (``reflection``)."""


class Infeasible(ValueError):
    """No configuration meets the tolerance (the message says why and what the full model reaches)."""


@dataclass(frozen=True)
class Plan:
    """The planner's answer (module doc), as :func:`plan` returns it.

    Parameters
    ----------
    scene : Scene
    tolerance, colour_tolerance : float
        The tolerances planned for: m, and the image's [0, 1] scale.
    model : SceneModel
        The configuration to run (``model.simulation`` is the pure step's model).
    bounds : HeightBounds
        The height configuration's error bounds, m.
    predicted_colour_error : float
        The colour bound, [0, 1].
    cost, full_cost : float
        Predicted seconds of the plan and of the full model.
    terms : tuple of Term
        The model card, one row per term.
    height_cost : float
        The heights' share of ``cost``, s.
    front : tuple of Candidate
        The Pareto front of the height candidates (computed when first read: it evaluates the
        cutoff's change for every coarsening and steps per frame, which the plan itself needs only
        for the candidates within its tolerance).
    texture_error : float
        The height texture's rounding, m (added to ``bounds.total`` in :attr:`predicted_error`).
    calibration : str
        Where the costs were measured (:func:`wavephys.planner.cost.describe_calibration`).
    cost_parts : dict
        Where ``cost`` goes, s: the run's fixed overhead, steps, ships, frames, blends,
        refinement (or a cheap surface model's frames), shading, caustics, texture encoding, and
        each registered term's cost under ``"added <name>"``.
    added_error : float
        What the registered terms with ``unit = "m"`` add to the height bound, m (their colour
        errors are in ``predicted_colour_error``).
    """

    scene: Scene
    tolerance: float
    colour_tolerance: float
    model: SceneModel
    bounds: HeightBounds
    predicted_colour_error: float
    cost: float
    full_cost: float
    terms: tuple
    height_cost: float = 0.0
    front: tuple = field(repr=False, default=(), compare=False)
    texture_error: float = 0.0
    calibration: str = ""
    cost_parts: dict = field(default_factory=dict, compare=False)
    added_error: float = 0.0

    def __getattribute__(self, name):
        value = object.__getattribute__(self, name)
        if name == "front" and callable(value):  # made on first read (class doc)
            value = value()
            object.__setattr__(self, "front", value)
        return value

    @property
    def predicted_error(self) -> float:
        """The height bound, m: the configuration's (``bounds.total``) plus the texture's rounding and
        the registered terms' (``added_error``)."""
        return self.bounds.total + self.texture_error + self.added_error

    @property
    def predicted_rms(self) -> float:
        """A bound on the RMS height error over the visible square, m (``bounds.rms`` plus the
        texture's rounding, a max-norm bound)."""
        return self.bounds.rms + self.texture_error + self.added_error

    @property
    def saving(self) -> float:
        """Predicted cost of the full model over the plan's."""
        return self.full_cost / self.cost

    def drawn(self, render_scene, *, reflection: str = "keep", width: int = 160, height: int = 120):
        """``render_scene`` (an :class:`optics.rendering.Scene`) with this plan's shading choices, so the
        renderer draws what the plan modelled: its Fresnel form, its absorption method (``"rgb"``: three
        coefficients fitted over the scene's own paths, as the plan's shading has them; any other method
        through its table) and caustics switched off where the plan leaves them off. The caustics map
        itself, the surface and the camera are the render scene's.

        Parameters
        ----------
        render_scene : optics.rendering.Scene
            The scene to draw.
        reflection : {"keep", "measure"}, keyword-only
            ``"keep"`` (default): the render scene's own reflection switch. ``"measure"``: the reflected
            rays are switched off where :meth:`reflection` measures that they change no pixel beyond
            the plan's colour tolerance (two CPU-reference traces of the frame: about a second at
            160 × 120).
        width, height : int, keyword-only
            The image size ``"measure"`` draws at, pixels (defaults 160 × 120).

        Returns
        -------
        optics.rendering.Scene
        """
        from dataclasses import replace

        from optics.light.attenuation import fit_rgb_coefficients
        from optics.rendering.scene import Scene as RenderScene
        from wavephys.core.inputs import check_choice, check_instance
        from wavephys.planner.runner import path_range

        check_instance("render_scene", render_scene, RenderScene, "optics.rendering.Scene")
        check_choice("reflection", reflection, REFLECTION_CHOICES)
        choices = self.model.choices
        out = render_scene.with_effects(fresnel_form=choices.fresnel, absorption_form=choices.absorption,
                                        caustics=render_scene.effects.caustics and bool(choices.caustics))
        if choices.absorption == "rgb":
            out = replace(out, absorption=tuple(float(a) for a in fit_rgb_coefficients(path_range(self.scene)[1])))
        if reflection == "measure" and not self.reflection(out, width=width, height=height).choice:
            out = out.with_effects(reflection=False)
        return out

    def reflection(self, render_scenes, *, width: int = 160, height: int = 120) -> Term:
        """Whether the renderer's reflected rays show anything in this scene: measured, not modelled.

        The planner's own shading (:func:`wavephys.planner.runner.shade`) reflects a uniform sky and has
        no geometry above the water, so it cannot tell; the renderer traces each reflected ray to the
        ground (walls, quays, a shore) or else takes the environment. So each frame is drawn (the plan's
        shading choices applied, :meth:`drawn`) by the CPU reference with and without the reflected
        rays, and they are dropped where no pixel changes by more than what the plan's colour bound
        leaves of its tolerance (``colour_tolerance − predicted_colour_error``). On the open sea the
        reflected rays meet only sky: the frames are identical, and the renderer saves their march
        (×0.72–0.84 of a GPU frame on llvmpipe, ``python -m bench render``).

        The frames and the image size are the caller's sample: a reflection seen only in other frames, or
        in features smaller than a pixel at ``width`` × ``height``, is not measured.

        Parameters
        ----------
        render_scenes : optics.rendering.Scene or sequence of them
            The frames to measure (at least one).
        width, height : int, keyword-only
            Image size the frames are drawn at, pixels (defaults 160 × 120).

        Returns
        -------
        Term
            ``choice`` True (keep the reflected rays) or False; ``error`` the largest change measured
            with them off (linear colour, [0, 1]; 0 when kept); ``saving`` the CPU reference's seconds
            saved over the frames, timed once each (0 when kept; the GPU renderer's saving is its own:
            ×0.72–0.84 of a frame on llvmpipe); ``reason`` the measurement.
        """
        from optics.rendering.reference import effect_change
        from optics.rendering.scene import Scene as RenderScene
        from wavephys.core.inputs import check_instance, check_int

        frames = [render_scenes] if isinstance(render_scenes, RenderScene) else render_scenes
        if isinstance(frames, (str, bytes)) or not hasattr(frames, "__iter__"):
            raise TypeError(f"render_scenes must be an optics.rendering.Scene or a sequence of them, got "
                            f"{type(render_scenes).__name__}")
        frames = list(frames)
        if not frames:
            raise ValueError("render_scenes must hold at least one optics.rendering.Scene")
        for i, frame in enumerate(frames):
            check_instance(f"render_scenes[{i}]", frame, RenderScene, "optics.rendering.Scene")
        from optics.rendering.reference import MAX_PIXELS

        width = check_int("width", width, lo=1, hi=MAX_PIXELS)
        height = check_int("height", height, lo=1, hi=MAX_PIXELS)
        q = self.scene.image_quantum
        budget = max(self.colour_tolerance - self.predicted_colour_error, 0.0)
        drawn = [self.drawn(f) for f in frames]
        if not any(f.effects.reflection for f in drawn):
            return Term("reflection", False, 0.0, 0.0, "off: the render scene has the reflected rays off", "colour")
        runs = [effect_change(f, "reflection", width, height) for f in drawn if f.effects.reflection]
        change = max(r["change"] for r in runs)
        size = f"{len(runs)} frame{'s' if len(runs) > 1 else ''} at {width}×{height}, CPU reference"
        if change <= budget:
            saved = max(sum(r["seconds_on"] - r["seconds_off"] for r in runs), 0.0)  # one timing each: noisy
            return Term("reflection", False, change, saved,
                        f"off: the reflected rays change no pixel by more than {change / q:.2g} image quanta "
                        f"(the colour bound leaves {budget / q:.2g}; {size}); the renderer skips their march", "colour")
        worst = min(r["psnr"] for r in runs)
        return Term("reflection", True, 0.0, 0.0,
                    f"kept: without the reflected rays pixels change by up to {change / q:.3g} image quanta "
                    f"(PSNR {worst:.1f} dB; the colour bound leaves {budget / q:.2g}; {size})", "colour")

    def card(self) -> str:
        """The model card as a text table."""
        s = self.scene
        q = s.height_quantum
        lines = [f"scene {s.name}: {s.texels}² texels of {s.pixel:.4g} m, {s.frames} frames at {s.fps:g} fps, "
                 f"depth {s.depth:g} m",
                 f"tolerance {self.tolerance:.3g} m ({_quanta(self.tolerance / q)} of the height texture), colour "
                 f"{_quanta(self.colour_tolerance / s.image_quantum)} of the image",
                 f"model: {self.model.describe()}",
                 f"predicted error {self.predicted_error:.3g} m ({self.predicted_error / q:.3g} quanta; linear "
                 f"{self.bounds.linear:.2g}, second order {self.bounds.second_order:.2g}, float32 "
                 f"{self.bounds.rounding:.2g}, texture {self.texture_error:.2g}"
                 f"{f', added terms {self.added_error:.2g}' if self.added_error else ''}), colour {self.predicted_colour_error / s.image_quantum:.3g} quanta",
                 f"predicted cost {self.cost:.3g} s against {self.full_cost:.3g} s for the full model "
                 f"(×{self.saving:.3g} cheaper)"]
        if self.cost_parts:
            parts = [(k, v) for k, v in self.cost_parts.items() if v > 0.005 * self.cost]
            lines.append("time goes to " + ", ".join(f"{k} {v:.2g} s ({100 * v / self.cost:.0f} %)"
                                                       for k, v in sorted(parts, key=lambda kv: -kv[1])))
        if self.calibration:
            lines.append(f"costs measured by calibration {self.calibration}")
        lines.append("")
        head = ("term", "choice", "error alone", "saves [s]", "reason")
        rows = [(t.term, str(t.choice), f"{t.error:.2g} {t.unit}", f"{t.saving:.2g}", t.reason) for t in self.terms]
        widths = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(head[:-1])]
        fmt = "  ".join(f"{{:<{w}}}" for w in widths) + "  {}"
        lines += [fmt.format(*head), fmt.format(*("-" * w for w in widths), "------")]
        lines += [fmt.format(*r) for r in rows]
        return "\n".join(lines)

    def as_dict(self) -> dict:
        return dict(scene=self.scene.as_dict(), tolerance=self.tolerance, colour_tolerance=self.colour_tolerance,
                    choices=self.model.choices.as_dict(), simulation=dict(n=self.model.grid.n,
                                                                          dx=self.model.grid.dx, dt=self.model.dt,
                                                                          steps=self.model.steps),
                    predicted_error=self.predicted_error,
                    bounds=dict(linear=self.bounds.linear, second_order=self.bounds.second_order,
                                rounding=self.bounds.rounding, rms=self.bounds.rms, texture=self.texture_error,
                                added=self.added_error),
                    predicted_colour_error=self.predicted_colour_error, cost=self.cost, full_cost=self.full_cost,
                    height_cost=self.height_cost, calibration=self.calibration, cost_parts=self.cost_parts,
                    terms=[dict(term=t.term, choice=t.choice, error=t.error, unit=t.unit, saving=t.saving,
                                reason=t.reason) for t in self.terms],
                    front=[dict(choices=c.choices.as_dict(), predicted_error=c.bounds.total, cost=c.cost)
                           for c in self.front])

    def to_json(self, path) -> None:
        """Write :meth:`as_dict` as JSON (atomically)."""
        from wavephys.core.files import atomic_path, output_file

        p = output_file(path, "path", (".json",))
        with atomic_path(p) as tmp:
            tmp.write_text(json.dumps(self.as_dict(), indent=2, default=str))


def _quanta(x: float) -> str:
    return f"{x:.3g} quantum" if abs(x - 1.0) < 5e-4 else f"{x:.3g} quanta"


def full_model(scene: Scene) -> SceneModel:
    """The most complete configuration of a scene: the reference every plan is measured against.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    SceneModel
        With :func:`wavephys.planner.model.full_choices` of the scene.
    """
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    return SceneModel(scene, replace(full_choices(scene), added=tuple((t, t.exact) for t in TERMS.added())))


def candidates(scene: Scene, calibration: Optional[dict] = None) -> list:
    """Every height configuration the scene can run, with predicted bounds and cost.

    The product of the height terms' options (:mod:`wavephys.planner.terms`), less what cannot
    run; the colour choices are the full model's.

    Parameters
    ----------
    scene : Scene
    calibration : dict or str or os.PathLike, optional
        The cost calibration: a dict (:func:`wavephys.planner.load_calibration`) or a file that
        ``wavephys calibrate`` wrote (default the shipped one, measured on a 2-core CPU).

    Returns
    -------
    list of Candidate
    """
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    ctx = plan_context(scene, calibration)
    return [ctx.settle(c) for c in ctx.candidates]


def plan_context(scene: Scene, calibration: Optional[dict] = None) -> PlanContext:
    """The one per-scene context every term reads.

    Parameters
    ----------
    scene : Scene
    calibration : dict or str or os.PathLike, optional
        The cost calibration: a dict (:func:`wavephys.planner.load_calibration`) or a file that
        ``wavephys calibrate`` wrote (default the shipped one). Contexts of the shipped
        calibration are kept, so planning a scene at several tolerances computes its bounds once.

    Returns
    -------
    wavephys.planner.terms.PlanContext
        The candidates, the full model's, the colour and caustics errors.
    """
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    if calibration is None:
        return _shipped_context(scene)
    if isinstance(calibration, (str, os.PathLike)):
        stat = os.stat(calibration) if os.path.isfile(calibration) else None
        if stat is None:
            load_calibration(calibration)  # raises, naming the file
        return _file_context(scene, os.path.abspath(calibration), stat.st_mtime_ns, stat.st_size)
    if not isinstance(calibration, dict):
        raise TypeError(f"calibration must be a dict or a calibration file's path (wavephys calibrate --out FILE "
                        f"writes one), got {type(calibration).__name__}")
    check_calibration(calibration)
    return _context(scene, calibration)


@lru_cache(maxsize=32)
def _file_context(scene: Scene, path: str, mtime_ns: int, size: int) -> PlanContext:
    """A context of a calibration file, kept while the file is unchanged (planning one scene at
    several tolerances computes its bounds once, as with the shipped calibration)."""
    return _context(scene, load_calibration(path))


@lru_cache(maxsize=32)
def _shipped_context(scene: Scene) -> PlanContext:
    return _context(scene, shipped_calibration())


def _context(scene: Scene, cal: dict) -> PlanContext:
    options = {name: TERMS[name].options(scene) for name in HEIGHT_TERMS}
    out = []
    for choices, b in height_bounds(scene, cal["kappa"], options, defer_steps=True).items():
        try:
            model = SceneModel(scene, choices)
            if scene.ships:
                model.check_ships()
        except ValueError:
            continue
        pending = bool(scene.margin) and (choices.coarsen, choices.steps_per_frame) != (1, 1)
        out.append(Candidate(model.choices, b, height_cost(model, cal)["total"], pending))
    for name, b in surface_bounds(scene, cal["kappa"]).items():  # wind seas: the other surface models
        if name in TERMS["surface"].options(scene):
            model = SceneModel(scene, Choices(second_order=False, surface=name))
            out.append(Candidate(model.choices, b, height_cost(model, cal)["total"]))
    fc = full_choices(scene)
    full_key = replace(Choices(), ship_patch=fc.ship_patch, second_order=fc.second_order)
    full = next((c for c in out if c.choices == full_key), None)
    if full is None:
        raise Infeasible(f"scene {scene.name!r}: the full model cannot run it (a ship's patch leaks or leaves "
                         f"the visible square at Δt = 1/fps)")
    return PlanContext(scene, cal, tuple(out), full, colour_errors(scene), caustics_errors(scene))


TEXTURE_SLACK = 0.05
"""A smaller height texture is taken when its model costs at most this much more (relative)
than the cheapest model with any format: a texture half the bytes is worth 5 % more compute."""


def plan(scene: Scene, tolerance: float, colour_tolerance: Optional[float] = None,
         budget: Optional[float] = None, texture_slack: float = TEXTURE_SLACK,
         calibration: Optional[dict] = None) -> Plan:
    """The cheapest configuration of ``scene`` whose predicted height error is ≤ ``tolerance``
    (m, max norm over all frames and texels) and colour error ≤ ``colour_tolerance`` (on the
    image's [0, 1] scale, so at most 1; default one image quantum).

    Candidates are the product of the terms' options (:data:`wavephys.planner.terms.TERMS`).
    The height texture format (``f32``, ``f16``, ``u16``, ``u8``) is the one of fewest bytes
    per texel whose cheapest model costs at most ``texture_slack`` (relative) more than the
    cheapest model with any format; its rounding adds to the height bound.

    Parameters
    ----------
    scene : Scene
    tolerance : float
        Largest height error, m, > 0 (max norm over every frame and texel; the scene's
        ``height_quantum`` is one texture quantum).
    colour_tolerance : float, optional
        Largest colour error on the image's [0, 1] scale, in (0, 1] (default one image quantum).
    budget : float, optional
        Largest acceptable predicted cost, s, > 0 (None: any).
    texture_slack : float
        In [0, 10]: how much more (relative) a smaller texture's model may cost.
    calibration : dict or str or os.PathLike, optional
        The cost calibration: a dict (:func:`wavephys.planner.load_calibration`) or a file that
        ``wavephys calibrate`` wrote (default the shipped one, measured on a 2-core CPU).

    Returns
    -------
    Plan
        The model to run (``.model``), its predicted errors and cost, the model card.

    Raises
    ------
    Infeasible
        (a ValueError) when nothing meets the tolerance, saying what the full model reaches.

    References
    ----------
    docs/planner.md: how each term's error is bounded and its cost calibrated.

    Examples
    --------
    >>> from wavephys.planner import builtin_scene                     # doctest: +SKIP
    >>> scene = builtin_scene("pond")                                  # doctest: +SKIP
    >>> print(plan(scene, scene.height_quantum).card())                # doctest: +SKIP
    """
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    check_scalar("tolerance", tolerance, lo=0.0, lo_open=True)
    if colour_tolerance is None:
        colour_tolerance = scene.image_quantum
    check_scalar("colour_tolerance", colour_tolerance, lo=0.0, lo_open=True, hi=1.0)
    if budget is not None:
        check_scalar("budget", budget, lo=0.0, lo_open=True)
    texture_slack = check_scalar("texture_slack", texture_slack, lo=0.0, hi=10.0)
    tolerance, colour_tolerance = float(tolerance), float(colour_tolerance)
    ctx = plan_context(scene, calibration)
    cands, full = ctx.candidates, ctx.full
    # a deferred term only adds: the candidates within the tolerance without it are the only ones it can keep
    ok = [c for c in (ctx.settle(c) for c in cands if c.bounds.total <= tolerance) if c.bounds.total <= tolerance]
    if not ok:
        raise Infeasible(f"no model meets {tolerance:.3g} m: the full model's own float32 floor is "
                         f"{full.bounds.total:.3g} m (run in float64 for less), and the best candidate reaches "
                         f"{min(c.bounds.total for c in cands):.3g} m")
    if scene.caustics:  # the light moves with the heights, which no term bounds: keep the full model's heights
        ok = [c for c in ok if _same_heights(c)]
    best = {}
    for added in _added_options(ctx):  # terms registered beside the built-ins: each combination of their options
        h_add = sum(e for term, _, e, _ in added if term.unit == "m")
        c_add = sum(e for term, _, e, _ in added if term.unit == "colour")
        for fmt, (cand, tex_err, choices, colour_err, cost) in _best_by_format(ctx, ok, tolerance - h_add,
                                                                               colour_tolerance - c_add).items():
            choices = replace(choices, added=tuple((term, option) for term, option, _, _ in added))
            found = (cand, tex_err, choices, colour_err + c_add, cost + sum(c for *_, c in added), h_add)
            key = (round(found[4], 12), -choices.simpler())
            if fmt not in best or key < (round(best[fmt][4], 12), -best[fmt][2].simpler()):
                best[fmt] = found
    if not best:
        raise Infeasible(f"no optics form{' or caustics refinement' if scene.caustics else ''} meets the colour "
                         f"tolerance {colour_tolerance:.3g}")
    if budget is not None:
        over = min(b[4] for b in best.values())
        best = {f: b for f, b in best.items() if b[4] <= budget}
        if not best:
            raise Infeasible(f"the cheapest model within {tolerance:.3g} m costs {over:.3g} s, over the budget "
                             f"{budget:.3g} s")
    cheapest = min(b[4] for b in best.values())
    full = full_cost(ctx)
    # a smaller texture may cost up to the slack more, but never more than the full model
    limit = max(min((1.0 + texture_slack) * cheapest, full), cheapest)
    fmt = min((f for f in best if best[f][4] <= limit), key=lambda f: (TEXTURE_BYTES[f], best[f][4]))
    cand, tex_err, choices, colour_err, cost, added_err = best[fmt]
    terms = tuple(term.row(ctx, choices) for term in TERMS.values())
    return Plan(scene, tolerance, colour_tolerance, SceneModel(scene, choices), cand.bounds, colour_err, cost,
                full, terms, cand.cost, lambda: tuple(_pareto([ctx.settle(c) for c in cands])), tex_err,
                describe_calibration(ctx.calibration), cost_parts(ctx, choices), added_err)


def _best_by_format(ctx: PlanContext, ok: list, tolerance: float, colour_tolerance: float) -> dict:
    """Texture format → the cheapest (candidate, texture error, choices, colour error, cost) among the
    height candidates ``ok`` within ``tolerance`` (m) and ``colour_tolerance``."""
    texture, best = TERMS["texture"], {}
    if tolerance < 0 or colour_tolerance < 0:
        return best
    for fmt in texture.options(ctx.scene):  # the cheapest model for each texture format
        fits = [(c, e) for c in ok for e in (texture.error(ctx.scene, fmt, c.bounds),) if c.bounds.total + e <= tolerance]
        found = _search(ctx, fits, fmt, colour_tolerance)
        if found is not None:
            best[fmt] = found
    return best


def _added_options(ctx: PlanContext) -> list:
    """Every combination of the registered terms' options (:meth:`Terms.register
    <wavephys.planner.terms.Terms.register>`), as tuples of (term, option, error, cost); one empty
    combination when none is registered. A scene that shows caustics keeps every height term at its
    exact option, as it keeps the built-in ones: the light moves with the heights, which no term
    bounds."""
    per_term = []
    for term in TERMS.added():
        options = term.checked_options(ctx.scene, ctx.calibration)
        if ctx.scene.caustics and term.unit == "m":
            options = options[:1]
        per_term.append([(term, o, term.checked("error", ctx, o), term.checked("cost", ctx, o)) for o in options])
    return list(itertools.product(*per_term))


def cost_parts(ctx: PlanContext, choices: Choices) -> dict:
    """Where a configuration's predicted seconds go (:class:`Plan` ``cost_parts``); they sum to
    its cost."""
    scene, cal = ctx.scene, ctx.calibration
    heights = height_cost(SceneModel(scene, choices), cal)
    heights.pop("total")
    heights["overhead"] = heights.pop("overhead")  # listed after the work
    return dict(heights, shading=colour_cost(scene, choices.fresnel, choices.absorption, cal),
                caustics=caustics_cost(scene, choices.caustics, cal, ctx.gather_points),
                texture=texture_cost(scene, choices.texture, cal),
                **{f"added {term.name}": term.checked("cost", ctx, option) for term, option in choices.added})


def full_cost(ctx: PlanContext) -> float:
    """Predicted seconds of the full model: its heights, shading, caustics and float32 texture."""
    scene, cal = ctx.scene, ctx.calibration
    refine = FULL_REFINE if scene.caustics else 0
    return (ctx.full.cost + colour_cost(scene, "exact", "spectral", cal) + caustics_cost(scene, refine, cal)
            + texture_cost(scene, "f32", cal) + sum(term.checked("cost", ctx, term.exact) for term in TERMS.added()))


def _search(ctx: PlanContext, fits, fmt, colour_tolerance):
    """The cheapest (candidate, texture error, choices, colour error, cost) among height
    candidates ``fits`` ((candidate, texture error) pairs within the tolerance) with the texture
    format ``fmt`` and every combination of the colour terms' options within the colour
    tolerance; None if there is none."""
    scene, cal = ctx.scene, ctx.calibration
    refines = TERMS["caustics"].options(scene, cal)
    forms = TERMS["fresnel"].options(scene, cal)
    methods = TERMS["absorption"].options(scene, cal)
    best, best_key = None, None
    for cand, tex_err in fits:
        for r in refines:
            delta, e_max = caustics_delta(ctx.caustics, r)
            if not math.isfinite(delta):
                continue
            for f, a in itertools.product(forms, methods):
                err = colour_total(ctx.colour, f, a, delta, e_max)
                if not err <= colour_tolerance:
                    continue
                cost = (cand.cost + colour_cost(scene, f, a, cal) + caustics_cost(scene, r, cal, ctx.gather_points)
                        + texture_cost(scene, fmt, cal))
                choices = replace(cand.choices, fresnel=f, absorption=a, caustics=r, texture=fmt)
                key = (round(cost, 12), -choices.simpler())
                if best_key is None or key < best_key:
                    best, best_key = (cand, tex_err, choices, err, cost), key
    return best


def _same_heights(cand: Candidate) -> bool:
    """The candidate computes the full model's heights (e.g. σ off in a scene whose water has
    σ = 0 already)."""
    return cand.bounds.linear == 0.0 and cand.bounds.second_order == 0.0


def _pareto(cands) -> list:
    """Candidates no other beats on both cost and predicted error, cheapest first."""
    pts = sorted(cands, key=lambda c: (c.cost, c.bounds.total))
    front, best = [], math.inf
    for c in pts:
        if c.bounds.total < best:
            front.append(c)
            best = c.bounds.total
    return front
