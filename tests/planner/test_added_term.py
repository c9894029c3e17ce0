"""A planner term added in this one file (issue 53, item 1's proof): registered beside the
built-in terms, it carries its own options, error bound, cost and effect on the run; it changes a
plan, is costed in the plan's cost and its parts, is shown on the model card, and the plan that
uses it keeps its promise when run. Nothing outside this file knows it."""

import math

import numpy as np
import pytest

from wavephys.planner import Scene, StoneSpec, plan
from wavephys.planner.model import Choices, SceneModel
from wavephys.planner.plan import full_model
from wavephys.planner.runner import compare, run, shade
from wavephys.planner.terms import TERMS, AddedTerm


def _pond(n=32, frames=6):
    return Scene(2.0, 2.0 / n, depth=0.5, open_water=False, duration=frames / 30.0, fps=30.0, height_range=0.02,
                 stones=(StoneSpec(0.1, -0.2, 0.25, 0.01),), name=f"added-term-pond-{n}")


class HeightSnap(AddedTerm):
    """Heights snapped to multiples of ``step`` quanta after the run (a throwaway post-process):
    the snap moves a height by at most half a step, and skipping the full model's exact option
    saves ``seconds`` a frame (a cost the term declares for itself)."""

    name = "height_snap"
    unit = "m"
    exact = "exact"

    def __init__(self, step=0.5, seconds=2e-3):
        self.step, self.seconds = step, seconds

    def options(self, scene, calibration=None):
        return ("exact", "snapped")

    def error(self, ctx, option):
        return 0.0 if option == "exact" else 0.5 * self.step * ctx.scene.height_quantum

    def cost(self, ctx, option):
        return self.seconds * ctx.scene.frames if option == "exact" else 0.0

    def change_heights(self, model, frames, option):
        if option == "exact":
            return frames
        s = self.step * model.scene.height_quantum
        return np.round(frames / s) * s


class ColourSnap(AddedTerm):
    """The shaded colour snapped to 1/``levels``: at most half a level off; the exact option costs
    1 ms a frame."""

    name = "colour_snap"
    unit = "colour"
    exact = "exact"
    levels = 4096

    def options(self, scene, calibration=None):
        return ("exact", "snapped")

    def error(self, ctx, option):
        return 0.0 if option == "exact" else 0.5 / self.levels

    def cost(self, ctx, option):
        return 1e-3 * ctx.scene.frames if option == "exact" else 0.0

    def change_colour(self, model, colour, option):
        return colour if option == "exact" else np.round(colour * self.levels) / self.levels


@pytest.fixture
def registered(request):
    """Register the given terms for one test, and always take them out again."""
    terms = request.param if isinstance(request.param, tuple) else (request.param,)
    for term in terms:
        TERMS.register(term)
    try:
        yield terms
    finally:
        for term in terms:
            TERMS.unregister(term.name)


@pytest.mark.parametrize("registered", [HeightSnap()], indirect=True)
def test_an_added_term_changes_the_plan_is_costed_and_shown_and_the_run_keeps_the_promise(registered):
    (term,) = registered
    scene = _pond()
    q = scene.height_quantum
    p = plan(scene, 4 * q)
    assert p.model.choices.get("height_snap") == "snapped"
    assert p.added_error == pytest.approx(0.25 * q) and p.predicted_error >= p.bounds.total + 0.25 * q
    # costed: its share of the plan is its own, the parts sum to the plan's cost, the full model pays the exact option
    assert p.cost_parts["added height_snap"] == 0.0
    assert sum(p.cost_parts.values()) == pytest.approx(p.cost, rel=1e-9)
    TERMS.unregister("height_snap")
    try:
        without = plan(scene, 4 * q)
    finally:
        TERMS.register(term)
    assert p.full_cost == pytest.approx(without.full_cost + term.seconds * scene.frames, rel=1e-12)
    # shown on the card: its row last, with its error, saving and reason
    row = p.terms[-1]
    assert (row.term, row.choice, row.unit) == ("height_snap", "snapped", "m")
    assert row.error == pytest.approx(0.25 * q) and row.saving == pytest.approx(term.seconds * scene.frames)
    card = p.card()
    assert "height_snap" in card and "added terms" in card and "height_snap snapped" in p.model.describe()
    assert p.as_dict()["choices"]["height_snap"] == "snapped"
    # the run: snapped heights, within the promise against the full model (which the term leaves as it is)
    ref = run(scene, full_model(scene))
    assert full_model(scene).choices.get("height_snap") == "exact"
    got = run(scene, p.model)
    unsnapped = run(scene, SceneModel(scene, p.model.choices.set("height_snap", "exact")))
    moved = np.abs(got.heights - unsnapped.heights).max()  # the snap, read back through the plan's texture
    assert 0.0 < moved <= 0.25 * q + 2 * p.texture_error + 1e-12
    err = compare(got, ref)
    assert 0.0 < err["height_max"] <= p.predicted_error


@pytest.mark.parametrize("registered", [HeightSnap(step=4.0)], indirect=True)
def test_an_added_term_too_coarse_for_the_tolerance_keeps_its_exact_option_and_pays_for_it(registered):
    (term,) = registered
    scene = _pond()
    p = plan(scene, scene.height_quantum)  # snapping to 4 quanta adds 2 quanta: over the tolerance
    assert p.model.choices.get("height_snap") == "exact" and p.added_error == 0.0
    assert p.cost_parts["added height_snap"] == pytest.approx(term.seconds * scene.frames)
    assert sum(p.cost_parts.values()) == pytest.approx(p.cost, rel=1e-9)
    assert p.terms[-1].choice == "exact" and p.terms[-1].reason == "exact: the full model's"


@pytest.mark.parametrize("registered", [(HeightSnap(), ColourSnap())], indirect=True)
def test_a_colour_term_adds_to_the_colour_bound_and_changes_the_shading(registered):
    scene = _pond()
    p = plan(scene, 4 * scene.height_quantum)
    assert [t.term for t in p.terms[-2:]] == ["height_snap", "colour_snap"]
    assert p.model.choices.get("colour_snap") == "snapped" and p.terms[-1].unit == "colour"
    assert p.predicted_colour_error >= 0.5 / ColourSnap.levels
    ref, got = run(scene, full_model(scene)), run(scene, p.model)
    assert np.allclose(got.image * ColourSnap.levels, np.round(got.image * ColourSnap.levels), atol=1e-6)
    # the colour bound is the optics' own (at the full model's heights, as the planner's colour terms are judged)
    optics_only = np.abs(shade(scene, p.model, ref.heights[-1]) - ref.image).max()
    assert 0.0 < optics_only <= p.predicted_colour_error + 1e-6
    assert compare(got, ref)["colour_max"] <= p.colour_tolerance
    # a colour tolerance below the snap's half level keeps the colour exact
    tight = plan(scene, 4 * scene.height_quantum, colour_tolerance=0.4 / ColourSnap.levels)
    assert tight.model.choices.get("colour_snap") == "exact"


class _NoExact(HeightSnap):
    name = "no_exact"

    def options(self, scene, calibration=None):
        return ("snapped", "exact")


class _NegativeCost(HeightSnap):
    name = "negative_cost"

    def cost(self, ctx, option):
        return -1.0


class _NanError(HeightSnap):
    name = "nan_error"

    def error(self, ctx, option):
        return math.nan


@pytest.mark.parametrize("term, words", [(_NoExact(), "starting with its exact option"),
                                         (_NegativeCost(), "cost('exact') must be finite and ≥ 0"),
                                         (_NanError(), "error('exact') must be finite")])
def test_a_term_that_breaks_its_contract_is_refused_by_name(term, words):
    TERMS.register(term)
    try:
        with pytest.raises(ValueError, match=term.name) as info:
            plan(_pond(), 4 * _pond().height_quantum)
        assert words in str(info.value)
    finally:
        TERMS.unregister(term.name)


def test_registering_bad_terms_is_refused_by_name():
    with pytest.raises(TypeError, match="AddedTerm"):
        TERMS.register(object())
    for attrs, words in (({"name": "fresnel"}, "'fresnel' is taken"), ({"name": "kilos", "unit": "kg"}, "term.unit"),
                         ({"name": "two words"}, "identifier")):
        with pytest.raises(ValueError, match=words):
            TERMS.register(type("Bad", (HeightSnap,), attrs)())
    with pytest.raises(ValueError, match="built-in"):
        TERMS.unregister("caustics")
    with pytest.raises(KeyError, match="no registered term"):
        TERMS.unregister("height_snap")
    assert not TERMS.added()


def test_choices_hold_added_terms_by_name():
    term = HeightSnap()
    c = Choices().set("height_snap", "snapped", term=term)
    assert c.get("height_snap") == "snapped" and c.get("fresnel") == "exact"
    assert c.set("height_snap", "exact").get("height_snap") == "exact"
    assert c.simpler() == 1 and Choices().set("height_snap", "exact", term=term).simpler() == 0
    assert c.as_dict()["height_snap"] == "snapped"
    with pytest.raises(ValueError, match="name 'height_snap'"):
        Choices().get("height_snap")
    with pytest.raises(ValueError, match="value for 'coarsen'"):
        c.set("coarsen", 3)
    with pytest.raises(ValueError, match="term is named 'height_snap'"):
        Choices().set("other", "exact", term=term)
    with pytest.raises(TypeError, match="term must be an AddedTerm"):
        Choices().set("height_snap", "exact", term=object())
    with pytest.raises(ValueError, match="field of Choices"):
        Choices(added=((type("T", (HeightSnap,), {"name": "coarsen"})(), "exact"),))
    with pytest.raises(ValueError, match="named twice"):
        Choices(added=((term, "exact"), (term, "snapped")))
    with pytest.raises(TypeError, match="pairs"):
        Choices(added=("height_snap",))


@pytest.mark.parametrize("registered", [HeightSnap()], indirect=True)
def test_a_scene_with_caustics_keeps_added_height_terms_exact(registered):
    """The light on the floor moves with the heights, which no term bounds: a caustics scene keeps the
    full model's heights, an added height term's included (snapped heights broke the colour promise:
    0.032 against a tolerance of 0.02)."""
    scene = Scene(2.0, 2.0 / 32, depth=0.4, open_water=False, duration=6 / 30.0, fps=30.0, height_range=0.02,
                  stones=(StoneSpec(0.3, -0.2, 0.15, 0.01), StoneSpec(-0.6, 0.5, 0.25, 0.02)), caustics=True,
                  name="added-term-caustics-pool")
    p = plan(scene, 4 * scene.height_quantum, colour_tolerance=0.02)
    assert p.model.choices.get("height_snap") == "exact"
    assert compare(run(scene, p.model), run(scene, full_model(scene)))["colour_max"] <= 0.02


class _BadHook(HeightSnap):
    name = "bad_hook"

    def __init__(self, make):
        super().__init__()
        self.make = make

    def change_heights(self, model, frames, option):
        return self.make(frames) if option != "exact" else frames


@pytest.mark.parametrize("make, error, words", [(lambda f: f[:, :-1], ValueError, "shape"),
                                                (lambda f: f * np.nan, ValueError, "non-finite"),
                                                (lambda f: "heights", TypeError, "not an array of numbers")])
def test_a_hook_that_returns_garbage_is_refused_by_name_when_run(make, error, words):
    term = TERMS.register(_BadHook(make))
    try:
        scene = _pond()
        p = plan(scene, 4 * scene.height_quantum)
        assert p.model.choices.get("bad_hook") == "snapped"
        with pytest.raises(error, match="bad_hook") as info:
            run(scene, p.model)
        assert words in str(info.value)
    finally:
        TERMS.unregister(term.name)
