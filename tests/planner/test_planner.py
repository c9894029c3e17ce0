"""The scene planner: scenes as data, predicted errors that bound the measured ones, named
choices on scenes built for them, and the proof on generated scenes nobody picked."""

from __future__ import annotations

import functools
import json
import math
import subprocess
import sys
from dataclasses import replace

import numpy as np
import pytest

from wavephys.planner import (BUILTIN_SCENES, Choices, Infeasible, KINDS, Scene, SceneModel, ShipSpec, StoneSpec,
                              WindSpec, builtin_scene, compare, full_model, generate_scenes, plan, run)
from wavephys.planner.model import TERMS
from wavephys.planner.predict import height_bounds
from wavephys.planner.caustics import MARGIN


def _pool(n=32, frames=12, depth=0.5, fps=30.0, **kw):
    stones = (StoneSpec(0.3, -0.2, 0.15, 0.01), StoneSpec(-0.6, 0.5, 0.25, 0.02))
    return Scene(2.0, 2.0 / n, depth=depth, open_water=False, duration=frames / fps, fps=fps, stones=stones,
                 height_range=0.02, name="test-pool", **kw)


# -- scenes as data -------------------------------------------------------------------------
@pytest.mark.parametrize("name", BUILTIN_SCENES)
def test_builtin_scenes_load_and_round_trip(name):
    scene = builtin_scene(name)
    assert Scene.from_dict(scene.as_dict(), name=scene.name) == scene
    assert scene.texels == round(scene.extent / scene.pixel)


def test_scene_from_toml_with_camera_pixel(tmp_path):
    path = tmp_path / "cam.toml"
    path.write_text('extent = 8.0\ncamera_distance = 20.0\npixel_angle = 0.003125\ndepth = "inf"\n'
                    '[[stones]]\nx = 0.0\ny = 0.0\nradius = 0.5\ndepth = 0.02\n')
    scene = Scene.from_toml(path)
    assert scene.pixel == pytest.approx(0.0625) and scene.texels == 128 and math.isinf(scene.depth)
    assert scene.name == "cam"


@pytest.mark.parametrize("text,error,words", [
    ("extent = 8.0\npixel = 0.125\nbogus = 1\n[[stones]]\nx=0\ny=0\nradius=0.5\ndepth=0.01\n", ValueError,
     ["'bogus'", "allowed", "extent"]),
    ("extent = 8.0\npixel = 0.125\n[[stones]]\nx=0\ny=0\nradius=0.5\ndepth=0.01\nsize=3\n", ValueError,
     ["stones[0]", "'size'"]),
    ("extent = 8.0\npixel = 0.125\n[water]\nsigma=0.07\ndepth=3\n[[stones]]\nx=0\ny=0\nradius=0.5\ndepth=0.01\n",
     ValueError, ["water", "'depth'"]),
    ("extent = 8.0\npixel = 0.3\n[[stones]]\nx=0\ny=0\nradius=0.9\ndepth=0.01\n", ValueError, ["even integer"]),
    ("extent = 8.0\npixel = -0.125\n[[stones]]\nx=0\ny=0\nradius=0.5\ndepth=0.01\n", ValueError, ["pixel"]),
    ('extent = 8.0\npixel = 0.125\ndepth = "shallow"\n[[stones]]\nx=0\ny=0\nradius=0.5\ndepth=0.01\n', ValueError,
     ["depth", "inf"]),
    ("extent = 8.0\npixel = 0.125\n", ValueError, ["at least one source"]),
    ("extent = 8.0\npixel = 0.125\n[[stones]]\nx=0\ny=0\nradius=0.5\n", ValueError, ["stones[0] needs", "depth"]),
    ("extent = 8.0\npixel = 0.125\nfps = 0.5\n[[stones]]\nx=0\ny=0\nradius=0.5\ndepth=0.01\n", ValueError, ["fps"]),
    ("extent = 8.0\npixel = 0.125\n[[ships]]\nx=0\ny=0\nspeed=-1\n", ValueError, ["ships.speed"]),
    ("extent = 8.0\npixel = 0.125\n[wind]\ndirection = 3\n", ValueError, ["wind needs speed"]),
    ('extent = "big"\npixel = 0.125\n[[stones]]\nx=0\ny=0\nradius=0.5\ndepth=0.01\n', TypeError, ["extent"]),
    ("extent = 8.0\npixel = [0.125\n", ValueError, ["not valid TOML"]),
])
def test_bad_scene_files_are_refused_by_name(tmp_path, text, error, words):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(error) as info:
        Scene.from_toml(path)
    for w in words:
        assert w in str(info.value), str(info.value)


def test_missing_scene_file_names_the_path(tmp_path):
    with pytest.raises(FileNotFoundError, match="nowhere.toml"):
        Scene.from_toml(tmp_path / "nowhere.toml")


# -- predictions bound measurements ----------------------------------------------------------
VARIANTS = [Choices(surface_tension=False), Choices(finite_depth=False), Choices(coarsen=2),
            Choices(steps_per_frame=2), Choices(steps_per_frame=4), Choices(second_order=False),
            Choices(surface_tension=False, finite_depth=False, coarsen=2, steps_per_frame=2, second_order=False)]
SHIP_VARIANTS = [Choices(ship_method="impulses"), Choices(ship_method="impulses", steps_per_frame=4, second_order=False),
                 Choices(ship_patch=1), Choices(ship_patch=1, coarsen=2, steps_per_frame=2)]
"""Variants that only change a scene with ships (run on the ship scene alone)."""


def _measured_scenes():
    shore = Scene(16.0, 0.25, depth=0.8, open_water=True, duration=0.3, fps=30.0, height_range=0.05,
                  wind=WindSpec(3.0, 20.0, 1e-4, 3), stones=(StoneSpec(1.0, -2.0, 0.75, 0.01),), name="test-shore")
    ship = Scene(24.0, 0.375, depth=4.0, open_water=True, duration=0.3, fps=30.0, height_range=0.05,
                 ships=(ShipSpec(-1.0, 0.5, 2.0, 10.0, 2.0, 1.5, 0.03),), name="test-ship")
    return {s.name: s for s in (_pool(), shore, ship)}


@pytest.fixture(scope="module")
def measured_pool():
    """A pool, a shallow shore with wind and a ship: the full model and each variant, run (per scene,
    when a test first asks for it)."""
    scenes, out = _measured_scenes(), {}

    def measured(name, choices):
        if (name, choices) not in out:
            scene = scenes[name]
            bounds = height_bounds(scene, 0.0)
            ref = run(scene, full_model(scene))
            for variant in VARIANTS + (SHIP_VARIANTS if scene.ships else []):
                model = SceneModel(scene, variant)
                if scene.ships:
                    try:
                        model.check_ships()
                    except ValueError:  # the doubled patch leaves the visible square on the coarse grid
                        model = SceneModel(scene, replace(variant, ship_patch=1))
                got = run(scene, model)
                c = model.choices
                key = replace(Choices(), surface_tension=c.surface_tension, finite_depth=c.finite_depth,
                              coarsen=c.coarsen, steps_per_frame=c.steps_per_frame, second_order=c.second_order,
                              ship_method=c.ship_method if scene.ships else "kernels",  # no ships: changes nothing
                              ship_patch=c.ship_patch if scene.ships else 2, margin=c.margin)
                out[(scene.name, variant)] = (compare(got, ref), bounds[key])
        return out[(name, choices)]

    return measured


def _ids(c):
    return c if isinstance(c, str) else ",".join(f"{k}={v}" for k, v in c.as_dict().items() if v != getattr(Choices(), k))


@pytest.mark.parametrize("scene,choices",
                         [("test-pool", c) for c in VARIANTS]
                         + [pytest.param("test-shore", c, marks=pytest.mark.slow) for c in VARIANTS]
                         + [pytest.param("test-ship", c, marks=pytest.mark.slow) for c in VARIANTS + SHIP_VARIANTS],
                         ids=_ids)
def test_predicted_height_error_bounds_the_measured_one(measured_pool, scene, choices):
    """Every variant's measured max-norm error (over all frames and texels) stays below its
    predicted bound, and the bound is not vacuous (within 60× of the measurement). The
    float32 floor is left out of the bound here (κ = 0), so the linear and second-order
    models must hold on their own; measurements below 1e-6 of the amplitude are rounding."""
    err, bound = measured_pool(scene, choices)
    floor = 2e-6 * 0.02
    assert err["height_max"] <= bound.total + floor, (err, bound)
    assert bound.total <= 60 * max(err["height_max"], floor), (err, bound)
    assert err["height_rms"] <= 2 * bound.rms + floor, (err, bound)


def test_plan_meets_its_tolerance_on_a_scene_and_runs_on_the_pure_step():
    scene = _pool(n=32, frames=12)
    tol = 0.5 * scene.height_quantum
    p = plan(scene, tol)
    assert p.predicted_error <= tol and p.cost <= p.full_cost
    assert [t.term for t in p.terms] == list(TERMS)
    got, ref = run(scene, p.model), run(scene, full_model(scene))
    err = compare(got, ref)
    assert err["height_max"] <= p.predicted_error + 1e-9
    from wavephys.planner.runner import shade

    optics_only = np.abs(shade(scene, p.model, ref.heights[-1]) - ref.image).max()
    assert optics_only <= p.predicted_colour_error + 1e-6 and err["colour_max"] <= p.colour_tolerance
    json.dumps(p.as_dict(), default=str)  # the model card serializes
    import wavephys.simulation.stepping as stepping

    sim = p.model.simulation
    state, surface = stepping.step(sim, stepping.initial_state(sim), [p.model.stones()])
    assert surface.eta.shape == (p.model.grid.n, p.model.grid.n)


def test_pareto_front_is_monotone():
    p = plan(_pool(), 1.0 * _pool().height_quantum)
    costs = [c.cost for c in p.front]
    errs = [c.bounds.total for c in p.front]
    assert costs == sorted(costs) and errs == sorted(errs, reverse=True) and len(p.front) >= 2


# -- named cases ----------------------------------------------------------------------------
def _choices(name, quanta=0.5, **changes):
    return _plan(name, quanta, tuple(sorted(changes.items()))).model.choices


@functools.lru_cache(maxsize=8)
def _plan(name, quanta, changes):
    """A built-in scene's plan (cached: several tests ask for the same one)."""
    scene = builtin_scene(name)
    if changes:
        scene = replace(scene, **dict(changes))
    return plan(scene, quanta * scene.height_quantum)


def test_capillary_scene_keeps_surface_tension():
    assert _choices("ripples").surface_tension


def test_metre_per_pixel_ocean_drops_surface_tension():
    assert not _choices("ocean").surface_tension


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_deep_lake_drops_finite_depth_and_shallow_pond_keeps_it():
    assert not _choices("lake").finite_depth
    assert _choices("pond").finite_depth


def test_eight_bit_image_picks_a_cheap_fresnel_form():
    """Seen from above (incidence ≤ 35°), the cheap forms stay within one 8-bit quantum."""
    assert _choices("lake", view_elevation=75.0).fresnel not in ("exact", "lut")


@pytest.mark.slow
def test_sixteen_bits_and_a_grazing_view_need_the_exact_fresnel_form():
    """A 16-bit image needs the exact form; at a grazing view (60–70°) even 8 bits need it."""
    assert _choices("lake", view_elevation=75.0, image_bits=16).fresnel == "exact"
    assert _choices("lake", view_elevation=25.0).fresnel == "exact"


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_a_plan_is_drawn_with_its_shading_choices():
    """Plan.drawn gives the renderer the plan's Fresnel form and absorption (RGB: the coefficients fitted
    over the scene's paths, as the plan's shading has them); the picture differs from the full model's."""
    from optics.light.attenuation import fit_rgb_coefficients
    from optics.rendering.reference import psnr, trace
    from wavephys.app.scenes import builtin_scene as render_scene
    from wavephys.planner.runner import path_range

    scene = replace(builtin_scene("lake"), view_elevation=75.0)
    p = _plan("lake", 0.5, (("view_elevation", 75.0),))
    full = render_scene("storm", n=64)
    drawn = p.drawn(full)
    assert drawn.effects.fresnel_form == p.model.choices.fresnel not in ("exact", "lut")
    assert drawn.effects.absorption_form == p.model.choices.absorption
    rgb = replace(p, model=SceneModel(scene, replace(p.model.choices, absorption="rgb"))).drawn(full)
    assert rgb.effects.absorption_form == "rgb"
    assert np.allclose(rgb.absorption, fit_rgb_coefficients(path_range(scene)[1]), rtol=1e-12)
    assert psnr(trace(drawn, 24, 16), trace(full, 24, 16)) < 100.0
    with pytest.raises(TypeError, match="render_scene"):
        p.drawn(scene)


def test_the_reflected_rays_are_dropped_only_where_they_show_nothing():
    """Plan.reflection draws each frame with and without the renderer's reflected rays: over open water
    (the pool's waves with its walls sunk to a deep flat floor) they meet only sky and the frames are
    identical, so they go; in the pool they show the walls, many quanta, so they stay; drawn(reflection=
    "measure") applies the decision, and two frames are measured together (the pool in one keeps them)."""
    from wavephys.app.scenes import builtin_scene as render_scene

    p = _plan("lake", 0.5, (("view_elevation", 75.0),))
    pool = render_scene("pool", n=64, caustics=False)  # the floor's light is not what the reflected rays show
    sea = replace(pool, ground=np.full_like(pool.ground, float(pool.water.min()) - 5.0))
    off = p.reflection(sea, width=48, height=36)
    assert off.choice is False and off.error == 0.0 and off.unit == "colour"
    assert "no pixel" in off.reason and "48×36" in off.reason
    kept = p.reflection(pool, width=48, height=36)
    assert kept.choice is True and kept.error == 0.0
    change = float(kept.reason.split("up to ")[1].split(" image")[0])
    assert change > 5.0  # quanta: the walls' reflection
    assert p.drawn(sea, reflection="measure", width=48, height=36).effects.reflection is False
    assert p.drawn(pool, reflection="measure", width=48, height=36).effects.reflection is True
    assert p.drawn(sea).effects.reflection is True  # "keep": the render scene's own switch
    assert p.reflection([sea, pool], width=48, height=36).choice is True
    already = p.reflection(sea.with_effects(reflection=False), width=8, height=6)
    assert already.choice is False and "has the reflected rays off" in already.reason
    with pytest.raises(ValueError, match="reflection"):
        p.drawn(sea, reflection="off")
    with pytest.raises(TypeError, match="render_scenes"):
        p.reflection(p.scene)
    with pytest.raises(ValueError, match="render_scenes"):
        p.reflection([])
    with pytest.raises(ValueError, match="width"):
        p.reflection(sea, width=0)


def test_effect_change_measures_what_an_effect_shows():
    """The CPU reference drawn with and without an effect: caustics change the pool's floor, an effect
    already off changes nothing, and an unknown effect is refused by name."""
    from optics.rendering.reference import effect_change
    from wavephys.app.scenes import builtin_scene as render_scene

    pool = render_scene("pool", n=64)
    out = effect_change(pool, "caustics", 32, 24)
    assert out["change"] > 0.01 and math.isfinite(out["psnr"]) and out["seconds_on"] > 0
    same = effect_change(pool.with_effects(caustics=False), "caustics", 16, 12)
    assert same["change"] == 0.0 and same["psnr"] == math.inf
    with pytest.raises(ValueError, match="effect"):
        effect_change(pool, "bloom", 8, 6)
    with pytest.raises(TypeError, match="effect"):
        effect_change(pool, 3, 8, 6)


# -- caustics ---------------------------------------------------------------------------------
@pytest.mark.slow
def test_caustics_term_on_pools_with_and_without_light_to_show():
    """A clear pool with ripples (stones, 8-bit image, 64 texels) keeps the caustics (below its
    first fold the Jacobian gather, cheaper than the beam at refine 2 or more on this size: at
    32 texels the gather's supersampling makes it dearer than the beam at refine 3, and the
    planner takes the beam there) and, traced by each option, stays within the error the planner
    evaluated; the same pool with waves a hundred times lower drops them (E/E₀ within a quantum
    of 1); a 16-bit image keeps them too."""
    from wavephys.planner.caustics import caustics_errors
    from wavephys.planner.cost import caustics_cost
    from wavephys.planner.runner import floor_light

    scene = _pool(n=64, depth=0.4, caustics=True)
    assert caustics_cost(scene, "jacobian") < caustics_cost(scene, 2)
    p = plan(scene, scene.height_quantum)
    assert p.model.choices.caustics == "jacobian", p.card()
    row = {t.term: t for t in p.terms}["caustics"]
    assert row.error <= p.colour_tolerance and "Jacobian" in row.reason
    errors = caustics_errors(scene)
    ref = run(scene, full_model(scene))
    beams = {r: SceneModel(scene, replace(full_model(scene).choices, caustics=r)) for r in (0, 1, 2, 3, 4)}
    worst = dict.fromkeys((0, 1, 2, 3), 0.0)
    for h in ref.heights:  # every frame of the run against the evaluation on the closed-form surface
        light = {r: floor_light(scene, model, h) for r, model in beams.items()}
        for r in worst:
            worst[r] = max(worst[r], float(np.abs(light[r] - light[4]).max()))
    for r, measured in worst.items():
        assert measured <= errors.delta[r], (r, measured, errors.delta[r])
        assert measured >= 0.3 * errors.delta[r] or r == 0, (r, measured, errors.delta[r])  # a close estimate
    # the gather at the frames the planner traced (frame k is the run's frame k - 1): the run agrees
    models = {r: SceneModel(scene, replace(full_model(scene).choices, caustics=r)) for r in (4, "jacobian")}
    measured = max(float(np.abs(floor_light(scene, models["jacobian"], ref.heights[k - 1])
                                - floor_light(scene, models[4], ref.heights[k - 1])).max()) for k in errors.frames)
    assert 0.7 * errors.traced["jacobian"] <= measured <= 1.01 * errors.traced["jacobian"], (measured, errors.traced)
    assert errors.delta[1] > errors.delta[2] > errors.delta[3] > 0  # finer traces err less
    assert errors.delta["jacobian"] < errors.delta[2]  # the gather: closer than a beam refined twice
    err = compare(run(scene, p.model), ref)
    assert err["colour_max"] <= p.colour_tolerance, (err, p.card())

    calm = replace(scene, stones=tuple(replace(s, depth=s.depth / 100) for s in scene.stones), height_range=0.0002)
    assert plan(calm, calm.height_quantum).model.choices.caustics == 0
    fine = replace(scene, image_bits=16)
    assert plan(fine, fine.height_quantum).model.choices.caustics != 0


def test_the_gathers_cost_is_read_at_the_points_it_gathers():
    """The Jacobian gather's calibration counts points gathered a side (texels × the supersampling the
    gather chose): 4 points a texel cost what that many points cost, more than one. A calibration
    from before (by texels) is read at the texels, as it was measured."""
    from wavephys.planner.cost import calibration, caustics_cost, interpolate

    scene = _pool(n=32, frames=6, depth=0.4, caustics=True)
    cal = calibration()
    assert cal["caustics_jacobian"]["by"] == "points"
    at = lambda side: scene.frames * interpolate(cal["caustics_jacobian"], side)
    assert caustics_cost(scene, "jacobian", cal, 4 * scene.texels) == pytest.approx(at(4 * scene.texels))
    assert caustics_cost(scene, "jacobian", cal, 4 * scene.texels) > 1.5 * caustics_cost(scene, "jacobian", cal, scene.texels)
    assert caustics_cost(scene, "jacobian", cal) == pytest.approx(at(scene.texels))  # not screened: one a texel
    old = dict(cal, caustics_jacobian={k: v for k, v in cal["caustics_jacobian"].items() if k != "by"})
    assert caustics_cost(scene, "jacobian", old, 4 * scene.texels) == pytest.approx(at(scene.texels))


@pytest.mark.slow  # a plan with its caustics screen: 18 s
def test_the_plan_reads_the_gathers_cost_where_its_screen_gathered():
    """The screen records the points a side the gather took on the scene's frames, and the plan's
    caustics cost is read there."""
    from wavephys.planner.caustics import caustics_errors
    from wavephys.planner.cost import calibration, caustics_cost

    scene = _pool(n=32, frames=6, depth=1.6, caustics=True)  # sharp light: the gather takes 4 points a texel
    points = caustics_errors(scene).gather_points
    assert points in {scene.texels * s for s in (2, 4, 8)}, points
    from wavephys.planner.plan import _context, cost_parts
    from wavephys.planner.terms import TERMS as REGISTRY  # (model.TERMS is the names alone)

    ctx = _context(scene, calibration())
    expected = caustics_cost(scene, "jacobian", calibration(), points)
    assert expected > 1.5 * caustics_cost(scene, "jacobian", calibration(), scene.texels)
    assert REGISTRY["caustics"].cost(ctx, "jacobian") == pytest.approx(expected)
    assert cost_parts(ctx, replace(ctx.full.choices, caustics="jacobian"))["caustics"] == pytest.approx(expected)


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
@pytest.mark.parametrize("seed, index", [(5, 2), (808, 0), (808, 1), (909, 2), (909, 3)])
def test_the_caustics_bound_holds_over_every_frame_of_a_run(seed, index):
    """Every frame of the full model's run, traced at every option, stays within the evaluated
    difference: generated pools and shores (pool-2 of seed 5 is the case where five evenly
    sampled frames missed its focusing peak by 2.3 ×; the other seeds were not used to choose
    the screen)."""
    from wavephys.planner import generate_scenes
    from wavephys.planner.caustics import caustics_errors
    from wavephys.planner.runner import floor_light

    scene = generate_scenes(index + 1, seed=seed, kinds=("pool", "shore"), texels=(32, 48, 64))[index]
    errors = caustics_errors(scene)
    full = full_model(scene)
    frames = run(scene, full).heights
    options = [r for r in (1, 2, 3, "jacobian") if math.isfinite(errors.delta[r])]
    models = {r: SceneModel(scene, replace(full.choices, caustics=r)) for r in (*options, 4)}
    worst = dict.fromkeys(options, 0.0)
    for h in frames:
        ref = floor_light(scene, models[4], h)
        for r in options:
            worst[r] = max(worst[r], float(np.abs(floor_light(scene, models[r], h) - ref).max()))
    for r in options:
        assert worst[r] <= errors.delta[r], (scene.name, r, worst[r], errors.delta[r], errors.frames)
    assert len(errors.screen) == scene.frames and 1 <= len(errors.frames) <= 6


def test_full_surfaces_takes_its_frames_and_the_old_call_warns():
    import warnings

    from wavephys.planner.caustics import full_surfaces

    scene = _pool(caustics=True)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        frames, heights = full_surfaces(scene, frames=(1, 3))
    assert frames == (1, 3) and heights.shape[0] == 2
    with pytest.warns(DeprecationWarning, match="frames"):
        frames, old = full_surfaces(scene)
    assert frames[0] == 1 and frames[-1] == scene.frames and len(frames) == min(5, scene.frames)
    np.testing.assert_array_equal(old[0], heights[0])


def test_the_screen_picks_separate_peaks_and_the_brightest_focus():
    from wavephys.planner.caustics import SAMPLED_FRAMES, SCREEN_SPACING, _evaluated, _traced_frames

    screen = np.array([0.1, 0.9, 1.0, 0.95, 0.2, 0.1, 0.6, 0.7, 0.1, 0.05, 0.3, 0.1])
    peak = np.ones(12)
    peak[9] = 3.0
    picked = _traced_frames(screen, peak)
    assert 2 in picked and 9 in picked  # the screen's top and the brightest focus
    taken = [i for i in picked if i != 9]
    assert len(taken) == SAMPLED_FRAMES and all(b - a >= SCREEN_SPACING for a, b in zip(taken, taken[1:]))
    assert 7 in picked and 10 in picked  # a second and third event, not the first one's neighbours
    screen[5] = np.nan  # a frame the screen could not measure is traced first
    assert 5 in _traced_frames(screen, peak)
    assert _traced_frames(np.array([0.5, 0.1]), np.array([1.0, 1.0])) == (0, 1)  # short scenes: every frame
    # an option twice the screen on a traced frame: the untraced maximum of the screen, twice
    d = np.zeros(12)
    d[[2, 7]] = [1.0, 1.4]
    assert _evaluated(d, np.array([0.1] * 2 + [1.0] + [0.1] * 4 + [0.7] + [1.2] + [0.1] * 3), (2, 7)) == pytest.approx(2.4)
    assert _evaluated(np.zeros(3), np.zeros(3), (0, 1, 2)) == 0.0  # flat water: nothing to scale
    # short scenes: too few frames two apart, so the next highest fill in, every frame up to five
    for frames in (3, 4, 5, 6):
        screen = np.linspace(1.0, 2.0, frames)
        picked = _traced_frames(screen, screen)  # the brightest focus where the screen peaks
        assert len(picked) == min(frames, SAMPLED_FRAMES) and frames - 1 in picked, (frames, picked)
    assert _traced_frames(np.zeros(12), np.ones(12)) == (0, 2, 4, 6, 8)  # a flat screen: spread over the start
    # a frame the screen could not measure: traced if it ranks among the first; if not, the option is unknown
    screen = np.full(12, np.nan)
    picked = _traced_frames(screen, np.ones(12))
    assert _evaluated(np.ones(12), screen, picked) == math.inf
    screen = np.ones(12)
    screen[[3, 9]] = np.nan
    picked = _traced_frames(screen, np.ones(12))
    assert {3, 9} <= set(picked) and _evaluated(np.ones(12), screen, picked) == 1.0  # both traced: known


@pytest.mark.slow  # 20 s: the README's pytest must stay under 10 min on 2 cores (CI runs the slow ones)
def test_a_fold_on_a_frame_the_planner_does_not_trace_rules_the_gather_out(monkeypatch):
    """The gather is offered only where no frame of the screen folds: one frame that folds (here the
    gather refuses it, CausticsFold) and is not among the traced frames still makes the choice
    unavailable; from that frame on the screen takes the gather with its folded windows directly."""
    import optics.caustics as caustics
    from wavephys.planner.caustics import _caustics_errors

    scene = _pool(caustics=True)
    before = _caustics_errors.__wrapped__(scene)
    assert math.isfinite(before.delta["jacobian"])
    untraced = [f for f in range(2, scene.frames + 1) if f not in before.frames]  # 1-based
    assert untraced, before.frames  # 12 frames, at most 6 traced
    folded = untraced[0]
    real, calls = caustics.floor_irradiance_jacobian, []

    def gather(eta, grid, depth, sun, *, fold="windows", **kw):
        calls.append(fold)
        if fold == "raise" and len(calls) == folded:
            raise caustics.CausticsFold("the test's fold")
        return real(eta, grid, depth, sun, fold=fold, **kw)

    monkeypatch.setattr(caustics, "floor_irradiance_jacobian", gather)
    after = _caustics_errors.__wrapped__(scene)
    assert after.frames == before.frames and folded not in after.frames  # the same screen, so the same traces
    assert math.isinf(after.delta["jacobian"])
    assert calls == ["raise"] * folded + ["windows"] * (scene.frames - folded + 1)
    assert all(after.delta[r] == before.delta[r] for r in (0, 1, 2, 3))


@pytest.mark.slow  # moved to the slow run (CI runs it): the README's pytest must stay under 10 min on 2 cores
def test_past_the_first_fold_the_jacobian_is_not_offered():
    """A pool 20 times deeper folds its light: the gather refuses (CausticsFold) on the traced
    frames, so the choice is the beam, and the card says why."""
    from wavephys.planner.caustics import caustics_errors

    scene = _pool(depth=8.0, caustics=True)
    errors = caustics_errors(scene)
    assert math.isinf(errors.delta["jacobian"])
    p = plan(scene, scene.height_quantum)
    assert p.model.choices.caustics in (1, 2, 3, 4), p.card()
    assert "screened frames fold" in {t.term: t for t in p.terms}["caustics"].reason


def test_an_old_calibration_without_the_gather_offers_only_the_beam():
    from wavephys.planner.cost import calibration
    from wavephys.planner.terms import TERMS

    scene = _pool(depth=0.4, caustics=True)
    old = {k: v for k, v in calibration().items() if k != "caustics_jacobian"}
    assert "jacobian" not in TERMS["caustics"].options(scene, old)
    assert "jacobian" in TERMS["caustics"].options(scene, calibration())


@pytest.mark.slow
def test_an_old_calibration_plans_the_beam():
    from wavephys.planner.cost import calibration

    scene = _pool(depth=0.4, caustics=True)
    old = {k: v for k, v in calibration().items() if k != "caustics_jacobian"}
    assert plan(scene, scene.height_quantum, calibration=old).model.choices.caustics in (1, 2, 3, 4)


def test_caustics_need_a_floor_and_a_periodic_scene():
    with pytest.raises(ValueError, match="caustics.*finite depth"):
        _pool(depth=math.inf, caustics=True)
    stones = (StoneSpec(0.0, 0.0, 0.2, 0.01),)
    with pytest.raises(ValueError, match="caustics.*periodic"):
        Scene(4.0, 0.0625, depth=1.0, open_water=True, stones=stones, caustics=True)
    with pytest.raises(ValueError, match="caustics.*512 texels"):
        Scene(10.24, 0.01, depth=1.0, open_water=False, stones=(StoneSpec(0.0, 0.0, 0.05, 0.001),), caustics=True)
    with pytest.raises(TypeError, match="caustics"):
        _pool(caustics="yes")
    with pytest.raises(ValueError, match="caustics"):
        Choices(caustics=5)


# -- bad input -------------------------------------------------------------------------------
def test_tolerance_is_checked_and_an_unreachable_one_says_so():
    scene = _pool()
    with pytest.raises(ValueError, match="tolerance"):
        plan(scene, 0.0)
    with pytest.raises(TypeError, match="tolerance"):
        plan(scene, "1 mm")
    with pytest.raises(Infeasible, match="float32 floor"):
        plan(scene, 1e-15)
    with pytest.raises(Infeasible, match="budget"):
        plan(scene, scene.height_quantum, budget=1e-9)
    with pytest.raises(TypeError, match="scene"):
        plan({"extent": 1.0}, 1e-3)


def test_run_refuses_a_model_of_another_scene():
    with pytest.raises(ValueError, match="another scene"):
        run(_pool(), full_model(_pool(n=64)))


# -- proof over generated scenes (the full sweep is `python -m bench planner`) --------------
def test_generated_scenes_are_seeded_and_cover_every_kind():
    a, b = generate_scenes(10, seed=5), generate_scenes(10, seed=5)
    assert a == b and {s.name.split("-")[0] for s in a} == set(KINDS)
    assert generate_scenes(10, seed=6) != a


@pytest.mark.slow
def test_plans_stay_within_tolerance_on_generated_scenes():
    """Five generated scenes (one per kind, small sizes): planned at half a height quantum,
    each plan's measured error against the full model is within its tolerance."""
    scenes = generate_scenes(5, seed=11, texels=(32, 64))
    for scene in scenes:
        tol = 0.5 * scene.height_quantum
        p = plan(scene, tol)
        err = compare(run(scene, p.model), run(scene, full_model(scene)))
        assert err["height_max"] <= tol, (scene.name, err, p.model.describe())
        assert err["colour_max"] <= p.colour_tolerance, (scene.name, err)


# -- the command ------------------------------------------------------------------------------
def test_cli_plan_prints_the_card_and_writes_json_and_chart(tmp_path):
    """The command on a small deep tank (a TOML file): the card, the JSON (deep water: tanh kh
    dropped, it changes nothing) and the chart."""
    out, chart, toml = tmp_path / "plan.json", tmp_path / "front.png", tmp_path / "tank.toml"
    toml.write_text('extent = 2.0\npixel = 0.0625\ndepth = "inf"\nopen_water = false\nduration = 0.2\n'
                    '[[stones]]\nx = 0.2\ny = -0.1\nradius = 0.15\ndepth = 0.01\n')
    r = subprocess.run([sys.executable, "-m", "wavephys", "plan", str(toml), "--tolerance", "0.5q", "--json", str(out),
                        "--chart", str(chart)], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    assert "surface_tension" in r.stdout and "predicted error" in r.stdout
    data = json.loads(out.read_text())
    assert data["choices"]["finite_depth"] is False and data["predicted_error"] <= data["tolerance"]
    from PIL import Image

    assert Image.open(chart).size[0] > 500


@pytest.mark.parametrize("args,words,status", [
    (["nowhere.toml"], ["nowhere.toml", "does not exist"], 2),
    (["shore"], ["'shore' is a scene of 'wavephys render'", "plan: ripples", "scene file"], 2),
    (["wakebeach"], ["'wakebeach' is a scene of 'wavephys render'"], 2),
    (["lake", "--tolerance", "-1"], ["--tolerance"], 2),
    (["lake", "--tolerance", "1e-15"], ["float32 floor"], 1),
    (["lake", "--json", "/no/such/folder/card.json"], ["--json", "does not exist"], 2),
])
def test_cli_plan_bad_input(capsys, args, words, status):
    from wavephys.app.cli import main

    try:
        code = main(["plan", *args])
    except SystemExit as exc:
        code = exc.code
    assert code == status
    err = capsys.readouterr().err
    for w in words:
        assert w in err, err
