"""The planner's sloping floors and its depth-model term: the waves stepped over the floor (the
symmetric depth stepper, the full model) or the spectral step at the centre's depth, the
difference measured, the plan's promise kept on sloping scenes nobody picked; and the cutoff
margin's change with the grid and Δt, which the per-mode bounds do not hold."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
from pathlib import Path

import pytest

from wavephys.planner import (FloorSpec, Scene, SceneModel, StoneSpec, compare, full_model, generate_scenes, plan,
                              run)
from wavephys.planner.predict import depth_errors, margin_step_errors


def _beach(slope, frames=20, n=48, walls=False, **kw):
    return Scene(4.0, 4.0 / n, depth=0.5, walls=walls, duration=frames / 30.0, fps=30.0, height_range=0.02,
                 stones=(StoneSpec(0.3, -0.2, 0.2, 0.01),), floor=FloorSpec(slope, 30.0), name="test-beach", **kw)


@pytest.mark.slow
def test_a_flat_floor_is_the_spectral_step_and_has_no_depth_choice():
    """slope 0: the depth model does not apply, the full model is the spectral step with η₂, and
    the plan is the one of the same scene without a floor."""
    flat, none = _beach(0.0), replace(_beach(0.0), floor=None)
    assert depth_errors(flat) == {} and full_model(flat).choices.second_order and not full_model(flat).varying
    tol = flat.height_quantum
    assert plan(flat, tol).model.choices == plan(none, tol).model.choices


@pytest.mark.slow
def test_the_constant_depth_error_is_the_steppers_floor_then_the_slopes():
    """The evaluated difference between the spectral step at the centre's depth and the waves over
    the floor, on one scene (a 0.01 m crater): 1.34e-5, 1.31e-5, 9.7e-6 m at slopes 0.0003, 0.003,
    0.03 (measured) — the depth stepper's own error (its √w blend), the same for any gentle slope,
    which the planner counts against constant depth — then 2.8e-5 at 0.06 and 2.2e-4 at 0.1: the
    floor itself, 1.4 height quanta."""
    errs = [depth_errors(_beach(s))["constant"] for s in (0.0003, 0.003, 0.03, 0.1)]
    assert max(errs[:3]) < 1.5 * min(errs[:3])
    assert errs[3] > 10 * max(errs[:3]) and errs[3] > _beach(0.1).height_quantum


@pytest.mark.slow
def test_depth_errors_match_runs_on_generated_slopes():
    """For sloping scenes nobody picked (open or walled), the evaluated depth term (1.25× the
    linear model's change) covers the change of the full model's run, and is within 1.6× of it."""
    for scene in generate_scenes(2, seed=8, kinds=("slope",), texels=(32, 48)):
        bound = depth_errors(scene)["constant"]
        ref = run(scene, full_model(scene))
        got = run(scene, SceneModel(scene, replace(full_model(scene).choices, depth_model="constant")))
        measured = compare(got, ref)["height_max"]
        assert bound / 1.6 <= measured <= bound, (scene.name, measured, bound)


@pytest.mark.slow
def test_a_gentle_floor_is_planned_at_constant_depth_and_a_steep_one_over_the_floor():
    """At 8 quanta a 0.003 slope is not worth stepping (constant depth, within its promise); at
    ½ quantum a 0.1 slope is (the symmetric depth stepper, the full model itself)."""
    gentle, steep = _beach(0.003, frames=12, n=40, walls=True), _beach(0.1, frames=12, n=40, walls=True)
    p = plan(gentle, 8 * gentle.height_quantum)
    assert p.model.choices.depth_model == "constant" and not p.model.varying
    err = compare(run(gentle, p.model), run(gentle, full_model(gentle)))["height_max"]
    assert err <= p.predicted_error <= p.tolerance
    # at ½ quantum constant depth also fits this slope (predicted 7.5e-5 m of 7.8e-5, measured 4.2e-5 on
    # 2026-12-05), so the choice is the costs': with the calibration this test was written for the
    # symmetric stepper wins; with the compiled shading's calibration constant depth does (and keeps its promise)
    recorded = Path(__file__).resolve().parents[1] / "data" / "builtin_plans_calibration.json"
    q = plan(steep, 0.5 * steep.height_quantum, calibration=recorded)
    assert q.model.choices.depth_model == "varying" and q.model.varying
    row = next(t for t in q.terms if t.term == "depth_model")
    assert "symmetric depth stepper" in row.reason and "0.1" in row.reason


@pytest.mark.slow
@pytest.mark.parametrize("seed", [5, 6])
def test_plans_of_generated_slopes_keep_their_promise(seed):
    """Planned at ½, 2 and 8 height quanta, every generated sloping scene's planned heights stay
    within the predicted error of the full model (the waves stepped over the floor)."""
    for scene in generate_scenes(3, seed=seed, kinds=("slope",), texels=(32, 48, 64)):
        ref = run(scene, full_model(scene))
        for quanta in (0.5, 2.0, 8.0):
            p = plan(scene, quanta * scene.height_quantum)
            err = compare(run(scene, p.model), ref)["height_max"]
            assert err <= p.predicted_error <= p.tolerance, (scene.name, quanta, p.model.describe(), err)


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_the_cutoffs_change_with_grid_and_step_is_in_the_bound():
    """A faint open scene (η₂ 10⁴× below its heights' quanta) planned with several steps per frame
    or a coarser grid: the cutoff margin absorbs differently (it damps once per step, on the grid's
    points), a change of 5e-5 m here that the per-mode bounds put at 5e-6; the plans keep their
    promise because margin_step_errors measures it. Without it, the plan at 1 quantum (8 steps per
    frame) missed by 33 %."""
    scene = Scene(8.712, 0.1815, depth=0.856, duration=46 / 30, fps=30.0, height_range=1.6e-5,
                  stones=(StoneSpec(-1.114, -0.597, 0.715, 1.44e-4), StoneSpec(0.802, 2.653, 0.568, 7.96e-4)),
                  name="test-faint")
    steps = margin_step_errors(scene)
    assert steps[(1, 1)] == 0.0 and steps[(1, 8)] > 2 * scene.height_quantum and steps[(2, 1)] > 0
    ref = run(scene, full_model(scene))
    for quanta in (1.0, 4.0):
        p = plan(scene, quanta * scene.height_quantum)
        err = compare(run(scene, p.model), ref)["height_max"]
        assert err <= p.predicted_error <= p.tolerance, (quanta, p.model.describe(), err)
    assert margin_step_errors(replace(scene, open_water=False)) == {}


def test_the_varying_model_runs_only_with_the_full_models_other_terms():
    scene = _beach(0.05)
    model = SceneModel(scene, replace(full_model(scene).choices, steps_per_frame=2))
    with pytest.raises(ValueError, match="depth_model = 'varying'.*steps_per_frame 1"):
        run(scene, model)
    assert full_model(scene).choices.second_order is False


def test_sloping_scenes_are_checked_by_name(tmp_path):
    from wavephys.planner import ShipSpec

    with pytest.raises(ValueError, match="floor.*finite depth"):
        replace(_beach(0.05), depth=math.inf)
    with pytest.raises(ValueError, match="floor.*periodic"):
        _beach(0.05, open_water=False)
    with pytest.raises(ValueError, match="floor.*ships"):
        Scene(20.0, 0.125, depth=2.0, floor=FloorSpec(0.01), ships=(ShipSpec(-2.0, 0.0, 1.0),))
    with pytest.raises(ValueError, match="floor: slope 0.2 leaves"):
        _beach(0.2)
    with pytest.raises(ValueError, match="floor.slope"):
        FloorSpec(-0.1)
    with pytest.raises(ValueError, match="floor.slope"):
        FloorSpec(math.nan)
    with pytest.raises(TypeError, match="floor"):
        Scene(4.0, 0.125, depth=0.5, stones=(StoneSpec(0.0, 0.0, 0.3, 0.01),), floor=0.05)
    toml = tmp_path / "beach.toml"
    toml.write_text('extent = 4.0\npixel = 0.125\ndepth = 0.5\nduration = 0.2\n[floor]\nslope = 0.05\n'
                    'direction = 90.0\n[[stones]]\nx = 0.0\ny = 0.0\nradius = 0.3\ndepth = 0.01\n')
    scene = Scene.from_toml(toml)
    assert scene.floor == FloorSpec(0.05, 90.0) and Scene.from_dict(scene.as_dict()) == scene
    lo, hi = scene.depth_range()
    assert math.isclose(lo, 0.5 - 0.05 * 2.5) and math.isclose(hi, 0.5 + 0.05 * 2.5)
    toml.write_text('extent = 4.0\npixel = 0.125\n[floor]\nangle = 3\n[[stones]]\nx = 0.0\ny = 0.0\n'
                    'radius = 0.3\ndepth = 0.01\n')
    with pytest.raises(ValueError, match="floor: unknown key.*angle"):
        Scene.from_toml(toml)


def test_the_floor_on_the_grid_is_the_plane():
    """SceneModel.floor samples h = depth − slope·(x cos θ + y sin θ) at the grid's cell centres
    (rows y, columns x): shallower along θ."""
    scene = Scene(4.0, 0.125, depth=0.5, stones=(StoneSpec(0.0, 0.0, 0.3, 0.01),), floor=FloorSpec(0.05, 90.0))
    floor = full_model(scene).floor()
    h = floor.depth
    assert h.shape == (40, 40)  # 32 texels and a 4-texel margin a side
    assert np.allclose(h[:, 0], h[:, -1]) and h[0, 0] > h[-1, 0]  # rises along +y
    x = (np.arange(40) + 0.5) * 0.125 - 2.5
    assert np.allclose(h[:, 7], 0.5 - 0.05 * x)


@pytest.mark.slow
def test_the_cutoffs_change_is_evaluated_only_where_a_plan_needs_it():
    """The plan adds the cutoff's change only to candidates already within its tolerance (it only
    adds): a tight plan of a short open scene runs none of the five extra runs, its Pareto front
    (made when first read) runs them all, and every candidate's bound equals the eager one."""
    from wavephys.planner import candidates
    from wavephys.planner.plan import plan_context
    from wavephys.planner.predict import _margin_step_single, height_bounds

    scene = Scene(2.0, 2.0 / 32, depth=0.5, duration=6 / 30, fps=30.0, height_range=0.02,
                  stones=(StoneSpec(0.0, 0.0, 0.15, 0.01),), name="test-lazy")
    _margin_step_single.cache_clear()
    p = plan(scene, 0.05 * scene.height_quantum)
    assert _margin_step_single.cache_info().currsize <= 1  # (1, 1): nothing to run
    assert len(p.front) >= 2 and _margin_step_single.cache_info().currsize >= 4
    eager = height_bounds(scene, plan_context(scene).calibration["kappa"])
    for c in candidates(scene):
        assert math.isclose(c.bounds.total, eager[c.choices].total, rel_tol=1e-12), c.choices
