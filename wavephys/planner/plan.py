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

import json
import math
from dataclasses import dataclass, field, replace
from functools import lru_cache
from typing import Optional

import numpy as np

from wavephys.core.inputs import check_instance, check_scalar
from wavephys.planner.caustics import MARGIN, caustics_errors
from wavephys.planner.cost import calibration, caustics_cost, colour_cost, height_cost, texture_cost
from wavephys.planner.model import (ABSORPTION_METHODS, CAUSTICS_REFINE, FRESNEL_FORMS, FULL_REFINE,
                                    TERMS, TEXTURE_BYTES, TEXTURES, Choices, SceneModel, full_choices)
from wavephys.planner.predict import (MARGIN_TEXELS, HeightBounds, height_bounds, height_peak, surface_bounds,
                                      texture_error)
from wavephys.planner.scene import Scene
from wavephys.planner.spectrum import scene_spectrum

__all__ = ["plan", "Plan", "Term", "Candidate", "Infeasible", "full_model", "candidates", "colour_errors"]

class Infeasible(ValueError):
    """No configuration meets the tolerance (the message says why and what the full model reaches)."""


@dataclass(frozen=True)
class Candidate:
    """One height configuration: its choices, predicted error bounds and predicted cost (s)."""

    choices: Choices
    bounds: HeightBounds
    cost: float


@dataclass(frozen=True)
class Term:
    """One row of a model card: the term, its choice, what that choice alone adds to the error
    (m for heights, [0, 1] for colour), what it saves (s), and why."""

    term: str
    choice: object
    error: float
    saving: float
    reason: str
    unit: str = "m"


@dataclass(frozen=True)
class Plan:
    """The planner's answer (module doc). ``model`` is the configuration to run
    (:class:`SceneModel`; ``model.simulation`` is the pure step's model), ``predicted_error``
    the height bound (m), ``predicted_colour_error`` the colour bound ([0, 1]), ``cost`` the
    predicted seconds (``height_cost`` of it for the heights), ``full_cost`` those of the full
    model, ``terms`` the model card, ``front`` the Pareto front of the height candidates."""

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
    front: tuple = field(repr=False, default=())
    texture_error: float = 0.0

    @property
    def predicted_error(self) -> float:
        """The height bound, m: the configuration's (``bounds.total``) plus the texture's rounding."""
        return self.bounds.total + self.texture_error

    @property
    def predicted_rms(self) -> float:
        """A bound on the RMS height error over the visible square, m (``bounds.rms`` plus the
        texture's rounding, a max-norm bound)."""
        return self.bounds.rms + self.texture_error

    @property
    def saving(self) -> float:
        """Predicted cost of the full model over the plan's."""
        return self.full_cost / self.cost

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
                 f"{self.bounds.rounding:.2g}, texture {self.texture_error:.2g}), colour {self.predicted_colour_error / s.image_quantum:.3g} quanta",
                 f"predicted cost {self.cost:.3g} s against {self.full_cost:.3g} s for the full model "
                 f"(×{self.saving:.3g} cheaper)", ""]
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
                                rounding=self.bounds.rounding, rms=self.bounds.rms, texture=self.texture_error),
                    predicted_colour_error=self.predicted_colour_error, cost=self.cost, full_cost=self.full_cost,
                    height_cost=self.height_cost,
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
    """The most complete configuration of ``scene``: the reference every plan is measured against."""
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    return SceneModel(scene, full_choices(scene))


def candidates(scene: Scene) -> list:
    """Every height configuration the scene can run, with predicted bounds and cost (the
    colour choices set to the full model's)."""
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    return list(_candidates(scene))


@lru_cache(maxsize=32)
def _candidates(scene: Scene) -> tuple:
    cal = calibration()
    bounds = height_bounds(scene, cal["kappa"])
    out = []
    for (st, fd, c, spf, so, method, patch, margin), b in bounds.items():
        try:
            model = SceneModel(scene, Choices(st, fd, c, spf, so, ship_method=method, ship_patch=patch,
                                              margin=margin))
            if scene.ships:
                model.check_ships()
        except ValueError:
            continue
        out.append(Candidate(model.choices, b, height_cost(model, cal)["total"]))
    for name, b in surface_bounds(scene, cal["kappa"]).items():  # wind seas: the other surface models
        model = SceneModel(scene, Choices(second_order=False, surface=name))
        out.append(Candidate(model.choices, b, height_cost(model, cal)["total"]))
    return tuple(out)


def _incidence_range(scene: Scene) -> tuple[float, float]:
    """Incidence angles (degrees) the view meets: the view's own ± the steepest facet tilt."""
    slope = scene_spectrum(scene).max_slope
    tilt = math.degrees(math.atan(min(slope, 50.0)))
    theta = 90.0 - scene.view_elevation
    return max(0.0, theta - tilt), min(90.0, theta + tilt)


def colour_errors(scene: Scene) -> dict:
    """Bounds on the colour error ([0, 1] scale) of each Fresnel form and absorption method:
    {"fresnel": {form: max ΔR}, "absorption": {method: albedo · max ΔT}, "floor": the largest
    albedo · T} over the scene's incidence range and water paths."""
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    import jax.numpy as jnp

    from optics.light.fresnel import reflectance
    from wavephys.planner.runner import FLOOR_ALBEDO, path_range, transmittance

    lo, hi = _incidence_range(scene)
    cos = jnp.asarray(np.cos(np.radians(np.linspace(lo, hi, 4001))), jnp.float32)
    floor = 0.0
    exact = np.asarray(reflectance(cos, method="exact"), np.float64)
    fresnel = {f: float(np.abs(np.asarray(reflectance(cos, method=f), np.float64) - exact).max())
               for f in FRESNEL_FORMS}
    absorption = {"spectral": 0.0, "rgb": 0.0}
    if not math.isinf(scene.depth):
        d = np.linspace(*path_range(scene), 512)
        delta = np.abs(transmittance(scene, "rgb", d) - transmittance(scene, "spectral", d)).max()
        absorption["rgb"] = float(FLOOR_ALBEDO * delta)
        floor = FLOOR_ALBEDO * float(max(transmittance(scene, m, d[:1]).max() for m in ABSORPTION_METHODS))
    return dict(fresnel=fresnel, absorption=absorption, floor=floor)


def _pick(items, key_cost, key_simpler):
    return min(items, key=lambda it: (round(key_cost(it), 12), -key_simpler(it)))


TEXTURE_SLACK = 0.05
"""A smaller height texture is taken when its model costs at most this much more (relative)
than the cheapest model with any format: a texture half the bytes is worth 5 % more compute."""


def plan(scene: Scene, tolerance: float, colour_tolerance: Optional[float] = None,
         budget: Optional[float] = None, texture_slack: float = TEXTURE_SLACK) -> Plan:
    """The cheapest configuration of ``scene`` whose predicted height error is ≤ ``tolerance``
    (m, max norm over all frames and texels) and colour error ≤ ``colour_tolerance`` (on the
    image's [0, 1] scale, so at most 1; default one image quantum).

    The height texture format (``f32``, ``f16``, ``u16``, ``u8``) is the one of fewest bytes
    per texel whose cheapest model costs at most ``texture_slack`` (relative) more than the
    cheapest model with any format; its rounding adds to the height bound.

    ``budget``: largest acceptable predicted cost, s (None: any). Raises :class:`Infeasible`
    (a ValueError) when nothing meets the tolerance, saying what the full model reaches.
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
    cands = candidates(scene)
    full = next((c for c in cands if c.choices == replace(Choices(), ship_patch=full_choices(scene).ship_patch)),
                None)
    if full is None:
        raise Infeasible(f"scene {scene.name!r}: the full model cannot run it (a ship's patch leaks or leaves "
                         f"the visible square at Δt = 1/fps)")
    ok = [c for c in cands if c.bounds.total <= tolerance]
    if not ok:
        raise Infeasible(f"no model meets {tolerance:.3g} m: the full model's own float32 floor is "
                         f"{full.bounds.total:.3g} m (run in float64 for less), and the best candidate reaches "
                         f"{min(c.bounds.total for c in cands):.3g} m")
    if scene.caustics:  # the light moves with the heights, which no term bounds: keep the full model's heights
        ok = [c for c in ok if _same_heights(c)]
    colour = colour_errors(scene)
    caustics = caustics_errors(scene)  # traced on the scene's own surface (None: no caustics shown)
    best = {}
    # caustics scenes keep the full model's heights, the texture's among them (§3 of docs/planner.md)
    for fmt in (("f32",) if scene.caustics else TEXTURES):  # the cheapest model for each texture format
        fits = [(c, e) for c in ok for e in (texture_error(fmt, height_peak(scene, c.bounds)),)
                if c.bounds.total + e <= tolerance]
        found = _search(scene, fits, fmt, colour, caustics, colour_tolerance)
        if found is not None:
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
    fmt = min((f for f in best if best[f][4] <= (1.0 + texture_slack) * cheapest),
              key=lambda f: (TEXTURE_BYTES[f], best[f][4]))
    cand, tex_err, choices, colour_err, cost = best[fmt]
    full_refine = FULL_REFINE if scene.caustics else 0
    full_cost = (full.cost + colour_cost(scene, "exact", "spectral") + caustics_cost(scene, full_refine)
                 + texture_cost(scene, "f32"))
    terms = _card(scene, cands, full, choices, colour, caustics, cand)
    front = _pareto(cands)
    return Plan(scene, tolerance, colour_tolerance, SceneModel(scene, choices), cand.bounds, colour_err, cost,
                full_cost, tuple(terms), cand.cost, tuple(front), tex_err)


def _search(scene, fits, fmt, colour, caustics, colour_tolerance):
    """The cheapest (candidate, texture error, choices, colour error, cost) among height
    candidates ``fits`` ((candidate, texture error) pairs within the tolerance) with the texture
    format ``fmt`` and every optics form and caustics refinement within the colour tolerance;
    None if there is none."""
    refines = CAUSTICS_REFINE if scene.caustics else (0,)
    best, best_key = None, None
    for cand, tex_err in fits:
        for r in refines:
            delta, e_max = _caustics_delta(caustics, r)
            if not math.isfinite(delta):
                continue
            for f in FRESNEL_FORMS:
                for a in ABSORPTION_METHODS:
                    err = _colour_total(colour, f, a, delta, e_max)
                    if not err <= colour_tolerance:
                        continue
                    cost = (cand.cost + colour_cost(scene, f, a) + caustics_cost(scene, r)
                            + texture_cost(scene, fmt))
                    choices = replace(cand.choices, fresnel=f, absorption=a, caustics=r, texture=fmt)
                    key = (round(cost, 12), -choices.simpler())
                    if best_key is None or key < best_key:
                        best, best_key = (cand, tex_err, choices, err, cost), key
    return best


def _same_heights(cand: Candidate) -> bool:
    """The candidate computes the full model's heights (e.g. σ off in a scene whose water has
    σ = 0 already)."""
    return cand.bounds.linear == 0.0 and cand.bounds.second_order == 0.0


def _caustics_delta(caustics, refine: int) -> tuple:
    """(|E_plan − E_full|/E₀, largest E/E₀) of tracing at ``refine`` (evaluated on the full
    model's surface, :mod:`wavephys.planner.caustics`); (0, 1) for a scene without caustics.
    Scenes with caustics keep the full model's heights, so this is the whole change."""
    if caustics is None:
        return 0.0, 1.0
    return caustics.delta[refine], max(caustics.e_max[FULL_REFINE], caustics.e_max[refine])


def _colour_total(colour: dict, fresnel: str, absorption: str, delta: float, e_max: float) -> float:
    """ΔC ≤ ΔR·max(1, T·albedo·E_max) + albedo·ΔT·E_max + T·albedo·ΔE (module doc)."""
    dr, dt = colour["fresnel"][fresnel], colour["absorption"][absorption]
    floor = colour["floor"]  # the largest T·albedo
    out = dr * max(1.0, floor * e_max) if dr else 0.0
    out += dt * e_max if dt else 0.0
    return out + (floor * delta if delta else 0.0)


def _pareto(cands) -> list:
    """Candidates no other beats on both cost and predicted error, cheapest first."""
    pts = sorted(cands, key=lambda c: (c.cost, c.bounds.total))
    front, best = [], math.inf
    for c in pts:
        if c.bounds.total < best:
            front.append(c)
            best = c.bounds.total
    return front


def _card(scene: Scene, cands, full: Candidate, choices: Choices, colour: dict, caustics, cand: Candidate) -> list:
    """One row per term: the effect of the plan's choice for that term alone (all others full)."""
    by = {c.choices: c for c in cands}
    spectrum = scene_spectrum(scene)
    rows = []
    rows.append(_surface_row(scene, cands, full, choices))
    for term in HEIGHT_TERMS:
        value = getattr(choices, term)
        alone = by.get(replace(full.choices, **{term: value}))
        err = (alone.bounds.total - full.bounds.total) if alone else math.nan
        saving = (full.cost - alone.cost) if alone else math.nan
        reason = _reason(scene, spectrum, term, value, err)
        if scene.caustics:
            reason += "; heights kept as the full model's: the image shows caustics, which a height change moves"
        rows.append(Term(term, value, max(err, 0.0), saving, reason))
    fmt = choices.texture
    err = texture_error(fmt, height_peak(scene, full.bounds))
    saving = texture_cost(scene, "f32") - texture_cost(scene, fmt)
    rows.append(Term("texture", fmt, err, saving, _texture_reason(scene, fmt, err, cand)))
    _, e_max = _caustics_delta(caustics, choices.caustics)
    for term, table in (("fresnel", "fresnel"), ("absorption", "absorption")):
        value = getattr(choices, term)
        err = (_colour_total(colour, value, "spectral", 0.0, e_max) if term == "fresnel"
               else _colour_total(colour, "exact", value, 0.0, e_max))  # × the floor light where caustics show
        ref = "exact" if term == "fresnel" else "spectral"
        saving = (colour_cost(scene, ref, "spectral") - colour_cost(scene, value, "spectral")) if term == "fresnel" \
            else (colour_cost(scene, "exact", ref) - colour_cost(scene, "exact", value))
        rows.append(Term(term, value, err, saving, _colour_reason(scene, term, value, err), unit="colour"))
    value = choices.caustics
    if caustics is None:
        rows.append(Term("caustics", value, 0.0, 0.0, "the scene shows no caustics", unit="colour"))
    else:
        delta, e_max = _caustics_delta(caustics, value)
        err = _colour_total(colour, "exact", "spectral", delta, e_max)
        saving = caustics_cost(scene, FULL_REFINE) - caustics_cost(scene, value)
        rows.append(Term("caustics", value, err, saving, _caustics_reason(scene, caustics, value, err), unit="colour"))
    return rows


HEIGHT_TERMS = ("margin", "surface_tension", "finite_depth", "coarsen", "steps_per_frame", "second_order",
                "ship_method", "ship_patch")
"""The terms of the spectral step's configuration (card rows, each alone against the full model)."""


def _surface_row(scene, cands, full, choices) -> Term:
    """The surface model's card row: the plan's model, and why not the others."""
    others = sorted((c for c in cands if c.choices.surface != "spectral"), key=lambda c: c.bounds.total)
    value = choices.surface
    if not others:
        return Term("surface", value, 0.0, 0.0, "spectral step: the scene has stones or ships (the other surface "
                    "models stand for a wind sea alone)")
    q = scene.height_quantum
    listing = "; ".join(f"{c.choices.surface} ≤ {c.bounds.total / q:.3g} quanta at {c.cost / full.cost:.3g}× the "
                        f"step's cost" for c in others)
    if value == "spectral":
        return Term("surface", value, 0.0, 0.0, f"spectral step: {listing}")
    mine = next(c for c in others if c.choices.surface == value)
    return Term("surface", value, mine.bounds.total - full.bounds.total, full.cost - mine.cost,
                f"{value} within the tolerance and cheaper; {listing}")


def _texture_reason(scene, fmt, err, cand) -> str:
    kib = scene.texels**2 * TEXTURE_BYTES[fmt] / 1024
    size = f"{kib:.3g} KiB a frame (float32: {scene.texels**2 * 4 / 1024:.3g} KiB)"
    if fmt == "f32":
        why = ("the image shows caustics: heights kept" if scene.caustics else
               "no smaller format fits the tolerance at a cost within the slack")
        return f"float32: {size}; {why}"
    q = scene.height_quantum
    what = {"f16": "half float", "u16": "16-bit codes over each frame's span", "u8": "8-bit codes over each frame's span"}
    return f"{what[fmt]}: {size}; rounding ≤ {err:.2g} m ({err / q:.2g} quanta)"


def _caustics_reason(scene, caustics, value, err) -> str:
    q = scene.image_quantum
    light = (f"E/E₀ up to {caustics.e_max[FULL_REFINE] / MARGIN:.3g} at the traced frames "
             f"{', '.join(map(str, caustics.frames))}")
    if value == 0:
        return f"off: {light}; ≤ {err / q:.2g} image quanta"
    return f"beam, refine {value}: {light}; tracing ≤ {err / q:.2g} image quanta; {CAUSTICS_METHODS_NOTE}"


CAUSTICS_METHODS_NOTE = ("photons (3–17 % of the peak at 37× a step), GL beams (53× on llvmpipe) and Blinn–Phong "
                         "(34–95 %) are dominated by the beam (python -m bench optics)")
"""Why the other caustics methods are not choices: measured by the optics bench on 9 generated
surfaces at 128² and at 512² against a step (docs/planner.md §3)."""


def _reason(scene, spectrum, term, value, err) -> str:
    q = scene.height_quantum
    water = scene.water
    effect = f"adds ≤ {err:.2g} m ({err / q:.2g} quanta)" if math.isfinite(err) else "not runnable alone"
    if term == "surface_tension":
        lam_c = 2 * math.pi * math.sqrt(water.sigma / (water.rho * water.g)) if water.sigma > 0 else 0.0
        shortest = 2 * scene.pixel
        seen = f"shortest wave shown {shortest:.3g} m, capillary length 2π√(σ/ρg) = {lam_c:.3g} m"
        return (f"kept: {seen}" if value else f"dropped: {seen}; {effect}")
    if term == "finite_depth":
        if math.isinf(scene.depth):
            return "deep water: tanh kh = 1 exactly"
        k_min = float(spectrum.k.min())
        return (f"{'kept' if value else 'dropped'}: smallest kh = {k_min * scene.depth:.3g}"
                + ("" if value else f"; {effect}"))
    if term == "coarsen":
        return "output resolution" if value == 1 else f"grid {value}× coarser than the texels: {effect}"
    if term == "steps_per_frame":
        dt = value / scene.fps
        return ("a step per frame" if value == 1 else
                f"Δt = {dt:.3g} s, ω_top·Δt = {spectrum.omega_top * dt:.2g}: Hermite frames {effect}")
    if term == "second_order":
        return (f"kept: η₂ up to {spectrum.s0 * spectrum.s1 / 2:.2g} m" if value else f"dropped: {effect}")
    if term == "ship_method":
        if not scene.ships:
            return "no ships"
        if value == "kernels":
            return "Φ1/Φ2 kernels: exact for straight motion within a step"
        return f"impulses (the hull's change added at each step's end): {effect}"
    if term == "margin":
        if not scene.margin:
            return "a periodic scene: no margin"
        if scene.texels > MARGIN_TEXELS:
            return f"n/8: margins are planned up to {MARGIN_TEXELS} texels"
        size = {"n/8": scene.texels // 8, "n/16": scene.texels // 16, "none": 0}[value]
        if value == "n/8":
            return f"the full model's {size} texels a side"
        return f"{size} texels a side (measured against n/8 on the linear model, ×1.25): {effect}"
    if term == "ship_patch":
        if not scene.ships:
            return "no ships"
        full = full_choices(scene).ship_patch
        if full == 1:
            return "the single patch: the doubled one would leave the visible square"
        return ("the doubled patch (the full model's)" if value == 2 else
                f"the single patch (its truncation evaluated per mode at three steps, ×1.25): {effect}")
    return ""


def _colour_reason(scene, term, value, err) -> str:
    q = scene.image_quantum
    if term == "fresnel":
        lo, hi = _incidence_range(scene)
        return f"{value}: |ΔR| ≤ {err:.2g} over incidence {lo:.0f}–{hi:.0f}° = {err / q:.2g} image quanta"
    if math.isinf(scene.depth):
        return f"{value}: deep water, no floor seen"
    return f"{value}: ≤ {err / q:.2g} image quanta over paths {scene.depth * 2:.3g} m and longer"
