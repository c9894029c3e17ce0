"""The planner as a registry of terms: one class per term, candidates from their options, the
model card from their rows, the Fresnel options from optics' family; plans on the built-in scenes
as recorded before the registry (tests/data/builtin_plans.json)."""

import json
import math
from dataclasses import fields
from pathlib import Path

import numpy as np
import pytest

from wavephys.planner import BUILTIN_SCENES, Choices, Scene, StoneSpec, builtin_scene, plan
from wavephys.planner.model import TERMS as TERM_NAMES
from wavephys.planner.model import full_choices
from wavephys.planner.terms import COLOUR_TERMS, HEIGHT_TERMS, TERMS, PlanTerm, fresnel_forms

DATA = Path(__file__).resolve().parents[1] / "data" / "builtin_plans.json"
RECORDED_CALIBRATION = DATA.with_name("builtin_plans_calibration.json")


def _pond(n=32, frames=6):
    return Scene(2.0, 2.0 / n, depth=0.5, open_water=False, duration=frames / 30.0, fps=30.0, height_range=0.02,
                 stones=(StoneSpec(0.1, -0.2, 0.25, 0.01),), name=f"registry-pond-{n}")


def test_one_term_per_choice_in_card_order():
    assert tuple(TERMS) == TERM_NAMES
    assert set(TERMS) == {f.name for f in fields(Choices)} - {"added"}
    assert all(isinstance(t, PlanTerm) and t.kind in ("height", "texture", "colour") for t in TERMS.values())
    assert set(HEIGHT_TERMS) | set(COLOUR_TERMS) | {"surface", "texture"} == set(TERMS)


@pytest.mark.parametrize("name", BUILTIN_SCENES)
def test_every_term_offers_the_full_model(name):
    """Each term's options hold the full model's value, and a term applies (has a choice) only
    where its options differ: no ships, no ship choices; a periodic tank, no margin."""
    scene = builtin_scene(name)
    full = full_choices(scene)
    for term in TERMS.values():
        assert term.full(scene) in term.options(scene), (term.name, term.options(scene))
        assert term.apply(full, term.full(scene)) == full
    assert TERMS["ship_method"].applies(scene) == bool(scene.ships)
    assert TERMS["margin"].applies(scene) == bool(scene.margin)
    assert TERMS["boundary"].applies(scene) == scene.walls
    assert TERMS["depth_model"].applies(scene) == (scene.floor is not None and scene.floor.slope > 0)
    assert TERMS["caustics"].applies(scene) == scene.caustics


def test_the_card_is_the_terms_rows():
    p = plan(_pond(), 0.5 * _pond().height_quantum)
    assert [t.term for t in p.terms] == list(TERMS)
    for row in p.terms:
        assert row.unit == TERMS[row.term].unit and row.choice == getattr(p.model.choices, row.term)
        assert isinstance(row.reason, str) and row.reason


@pytest.mark.slow
def test_plans_on_the_builtin_scenes_are_the_recorded_ones():
    """The registry changed how plans are made, not what they are: every built-in scene at 0.5, 1
    and 4 height quanta gets the choices, predicted errors and costs recorded before it. One
    deliberate change since: water_srgb caps blue at 1 (it reached 1.001 on 0–2.6 m paths), which
    moves the ripples tank's colour bound from 6.1e-6 to 1.2e-4 (a thirtieth of an image quantum;
    no choice changes). And another: the cutoff margin's Δt-dependence is now evaluated
    (:func:`wavephys.planner.predict.margin_step_errors`: a plan at 8 steps per frame of a faint
    open scene had missed its promise by 33 %), which raises the predicted error of the open
    scenes planned with several steps per frame by 0.3–2 % (harbour, lake, pond at 4 quanta); no
    choice changes. The terms added since (boundary, depth_model) take their full values here.
    And on 2026-12-05 the cost model began counting the frames the assembly pads its last block
    with (runner.assembled_frames): recorded costs changed by at most 0.11 %, no choice or error
    changed. And on 2026-12-06 the grid's wavenumbers became NumPy constants rounded as eager
    ``jax.numpy`` rounds them, inside compiled programs too (where XLA had divided exactly): harbour's
    predicted errors moved by 2e-5 to 7.7e-5 of themselves (float32 rounding in the error they
    measure), every other number by under 1e-9; no choice changed. The plans are made with the calibration they were recorded with
    (tests/data/builtin_plans_calibration.json, the shipped one until 2026-12-05), so that a new
    measurement of the costs does not count as a change of the planner."""
    recorded = json.loads(DATA.read_text())
    for key, want in recorded.items():
        name, factor = key.split("@")
        scene = builtin_scene(name)
        p = plan(scene, float(factor) * scene.height_quantum, calibration=RECORDED_CALIBRATION)
        got = p.as_dict()
        new = {k: v for k, v in got["choices"].items() if k not in want["choices"]}
        assert new == {"boundary": "walls", "depth_model": "varying"}, key  # terms added since: these scenes ignore them
        assert {k: got["choices"][k] for k in want["choices"]} == want["choices"], key
        for k in ("predicted_error", "predicted_colour_error", "cost", "full_cost"):
            assert math.isclose(got[k], want[k], rel_tol=1e-6, abs_tol=1e-15), (key, k, got[k], want[k])


def _family_with(extra_name, extra):
    from optics.light import fresnel
    from wavephys.core.methods import Methods

    methods = {k: fresnel.REFLECTANCE_METHODS[k] for k in fresnel.REFLECTANCE_METHODS}
    return Methods("Fresnel reflectance", **methods, **{extra_name: extra})


def test_a_new_fresnel_form_is_planned_by_registering_it(monkeypatch):
    """Families drive the planner: a form registered in optics' family is bounded by
    colour_errors and offered by the planner once the calibration has its cost; without a cost
    it is not offered and the card says so (no KeyError)."""
    import wavephys.planner.cost as cost
    from optics.light import fresnel

    def reflectance_copy(cos_theta, n1=fresnel.N_AIR, n2=fresnel.N_WATER):  # the exact form, renamed
        return fresnel.reflectance_exact(cos_theta, n1, n2)

    monkeypatch.setattr(fresnel, "REFLECTANCE_METHODS", _family_with("copy", reflectance_copy))
    scene = _pond(n=32, frames=4)
    shipped = cost.calibration()
    assert "copy" not in fresnel_forms(shipped)
    p = plan(scene, 0.5 * scene.height_quantum, calibration=dict(shipped))
    row = next(t for t in p.terms if t.term == "fresnel")
    assert "not calibrated, so not offered: copy" in row.reason
    cal = dict(shipped, fresnel=dict(shipped["fresnel"], copy=1e-9))  # as exact, and nearly free
    p = plan(scene, 0.5 * scene.height_quantum, calibration=cal)
    assert p.model.choices.fresnel == "copy", p.card()
    row = next(t for t in p.terms if t.term == "fresnel")
    assert row.error == pytest.approx(0.0, abs=1e-7) and "copy: |ΔR|" in row.reason


def test_a_family_entry_the_planner_lacks_is_refused_by_name():
    with pytest.raises(ValueError, match="fresnel must be one of"):
        Choices(fresnel="no-such-form")


def test_the_explicit_calibration_is_checked():
    with pytest.raises(TypeError, match="calibration must be a dict or a calibration file's path"):
        plan(_pond(), 1e-3, calibration=1.5)
    with pytest.raises(ValueError, match="calibration file 'fast' does not exist"):
        plan(_pond(), 1e-3, calibration="fast")


def test_the_old_fresnel_forms_name_warns():
    import wavephys.planner.model as model

    with pytest.warns(DeprecationWarning, match="REFLECTANCE_METHODS"):
        forms = model.FRESNEL_FORMS
    assert set(forms) >= {"exact", "schlick", "lut"}


def test_shipped_calibration_covers_every_fresnel_form():
    """The calibration covers every entry of the family (bench calibrate measures them all)."""
    from optics.light.fresnel import REFLECTANCE_METHODS
    from wavephys.planner.cost import calibration

    assert set(fresnel_forms(calibration())) == set(REFLECTANCE_METHODS)
    assert np.all(np.isfinite(list(calibration()["fresnel"].values())))


def test_an_incomplete_calibration_is_refused_by_name():
    from wavephys.planner.cost import calibration

    cal = {k: v for k, v in calibration().items() if k != "shade"}
    with pytest.raises(ValueError, match=r"calibration lacks \['shade'\]"):
        plan(_pond(), 1e-3, calibration=cal)


def test_a_new_absorption_method_is_planned_by_registering_it(monkeypatch):
    """The absorption term's options are the family's entries the calibration covers: a method
    registered in optics (here the spectral answer itself, renamed) is bounded (by the spectral
    table's interpolation alone) and, once calibrated as nearly free, chosen."""
    import wavephys.planner.cost as cost
    from optics.light import attenuation
    from wavephys.core.methods import Methods

    methods = {k: attenuation.WATER_TRANSMITTANCE_METHODS[k] for k in attenuation.WATER_TRANSMITTANCE_METHODS}
    monkeypatch.setattr(attenuation, "WATER_TRANSMITTANCE_METHODS",
                        Methods("water transmittance", **methods, copy=attenuation.water_transmittance_spectral))
    scene = _pond(n=32, frames=4)
    shipped = cost.calibration()
    p = plan(scene, 0.5 * scene.height_quantum, calibration=dict(shipped))
    row = next(t for t in p.terms if t.term == "absorption")
    assert "not calibrated, so not offered: copy" in row.reason
    cal = dict(shipped, absorption=dict(shipped["absorption"], copy=1e-9))
    p = plan(scene, 0.5 * scene.height_quantum, calibration=cal)
    assert p.model.choices.absorption == "copy", p.card()
    # the spectral integral itself, against the planner's spectral table (64 paths, interpolated): 1.9e-6
    assert next(t for t in p.terms if t.term == "absorption").error <= 1e-5


def test_the_old_absorption_methods_name_warns():
    import wavephys.planner.model as model

    with pytest.warns(DeprecationWarning, match="WATER_TRANSMITTANCE_METHODS"):
        assert set(model.ABSORPTION_METHODS) == {"spectral", "rgb"}


def test_every_caustics_method_of_the_family_is_offered_or_declined_with_a_reason():
    """The caustics term is driven by optics' family: each method is offered (the beam's refinements, the
    Jacobian gather) or declined with its measured reason on the card; a new method is a decision."""
    from optics.caustics import FLOOR_IRRADIANCE_METHODS
    from wavephys.planner.model import CAUSTICS_JACOBIAN, CAUSTICS_OPTIONS
    from wavephys.planner.terms import CAUSTICS_METHODS_NOTE, CAUSTICS_NOT_PLANNED, CAUSTICS_PLANNED

    assert set(CAUSTICS_PLANNED) | set(CAUSTICS_NOT_PLANNED) == set(FLOOR_IRRADIANCE_METHODS)
    assert not set(CAUSTICS_PLANNED) & set(CAUSTICS_NOT_PLANNED)
    assert CAUSTICS_JACOBIAN in CAUSTICS_PLANNED and CAUSTICS_JACOBIAN in CAUSTICS_OPTIONS
    for name, why in CAUSTICS_NOT_PLANNED.items():
        assert name == "reference" or why in CAUSTICS_METHODS_NOTE


def test_every_sea_model_of_the_surfaces_package_is_offered_or_declined():
    """The surface term is driven by wavephys.surfaces: each sea model it ships is offered (its options
    in SURFACES, after the spectral step) or declined with a reason; a new model is a decision."""
    from wavephys.planner.model import SURFACE_OPTIONS, SURFACES, SURFACES_NOT_PLANNED
    from wavephys.surfaces import SEA_MODELS

    assert set(SURFACE_OPTIONS) | set(SURFACES_NOT_PLANNED) == set(SEA_MODELS)
    assert not set(SURFACE_OPTIONS) & set(SURFACES_NOT_PLANNED)
    assert SURFACES[0] == "spectral"
    assert list(SURFACES[1:]) == [o for options in SURFACE_OPTIONS.values() for o in options]
    assert all(o.split("-")[0] in SEA_MODELS for o in SURFACES[1:])
