"""The planner's walled scenes (a pool whose waves reflect) and its boundary term: walls, a
periodic square or an absorbing margin, each error measured, the plan's promise kept on walled
scenes nobody picked."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from wavephys.planner import Choices, Scene, SceneModel, StoneSpec, compare, full_model, generate_scenes, plan, run
from wavephys.planner.model import BOUNDARIES
from wavephys.planner.predict import boundary_errors
from wavephys.planner.runner import simulated_heights


def _pool(frames, x=0.0, y=0.0, n=32, **kw):
    return Scene(2.0, 2.0 / n, depth=0.5, walls=True, duration=frames / 30.0, fps=30.0, height_range=0.02,
                 stones=(StoneSpec(x, y, 0.15, 0.01),), name="test-pool", **kw)


@pytest.mark.parametrize("second_order", [False, True])
def test_walled_heights_are_the_even_extensions_quadrant(second_order):
    """The tank's cosine modes are its even extension's Fourier modes: the walled model's frames
    equal the periodic scene twice the side, with every stone's images in the walls, on its
    quadrant [−extent, 0]² (float32 rounding), for stones drawn anywhere, the corner too."""
    rng = np.random.default_rng(7)
    for x, y in [(0.9, 0.9), *rng.uniform(-0.9, 0.9, (2, 2))]:
        scene = _pool(12, float(x), float(y))
        ext = scene.even_extension()
        assert ext.extent == 4.0 and len(ext.stones) == 4 and not ext.walls and not ext.margin
        choices = Choices(second_order=second_order)
        walled = simulated_heights(SceneModel(scene, choices))
        mirror = simulated_heights(SceneModel(ext, choices))[:, :scene.texels, :scene.texels]
        peak = float(np.abs(mirror).max())
        assert np.abs(walled - mirror).max() <= 1e-5 * peak, (x, y)
        # the walls reflect: the periodic square differs once the rings reach them
        periodic = simulated_heights(SceneModel(scene, replace(choices, boundary="periodic")))
        assert np.abs(walled - periodic).max() > 0.01 * peak


def test_coarse_walled_frames_are_refined_by_cosine_interpolation():
    """A walled tank simulated on every 2nd point and refined onto the texels keeps the walls'
    evenness: a stone near a corner, its waves resolved on the coarse grid, comes back to 1.2e-6 of
    the full model's peak (measured); Fourier interpolation (the periodic seam) rang at the walls,
    0.25 of the peak — the defect a generated tank found (its plan measured 1.8e-4 m against a
    3.4e-5 m bound)."""
    from wavephys.core.spectral import cosine_refine, fourier_refine

    scene = _pool(16, 0.8, 0.7, n=64)
    full = simulated_heights(SceneModel(scene, Choices(second_order=False)))
    coarse = simulated_heights(SceneModel(scene, Choices(second_order=False, coarsen=2)))
    assert np.abs(coarse - full).max() <= 1e-4 * np.abs(full).max()
    # a cosine series (even about the walls) is refined exactly; Fourier interpolation is not
    n = 16
    x = (np.arange(n) + 0.5) / n
    f = np.cos(3 * np.pi * x)[None, :] * np.cos(2 * np.pi * x)[:, None]
    xf = (np.arange(2 * n) + 0.5) / (2 * n)
    exact = np.cos(3 * np.pi * xf)[None, :] * np.cos(2 * np.pi * xf)[:, None]
    assert np.abs(np.asarray(cosine_refine(f, 2)) - exact).max() < 1e-12
    assert np.abs(np.asarray(fourier_refine(f, 2)) - exact).max() > 0.1


@pytest.mark.slow
def test_short_pool_drops_the_walls_and_a_long_one_keeps_them():
    """Three frames after a stone lands in the middle of a pool nothing has reached a wall: the
    periodic square (cheaper: no cosine transforms) changes nothing and the plan takes it, its
    measured error within the prediction. A second after a stone lands near a wall its rings
    have reflected: periodic and margin each change the pool by many quanta, and the plan keeps
    the walls."""
    short, long_ = _pool(3), _pool(30, x=0.6)
    p = plan(short, 0.5 * short.height_quantum)
    assert p.model.choices.boundary == "periodic" and not p.model.walls
    err = compare(run(short, p.model), run(short, full_model(short)))["height_max"]
    assert err <= p.predicted_error <= p.tolerance
    errs = boundary_errors(long_)
    assert errs["walls"] == 0.0 and min(errs["periodic"], errs["margin"]) > 10 * long_.height_quantum
    q = plan(long_, 0.5 * long_.height_quantum)
    assert q.model.choices.boundary == "walls" and q.model.walls
    row = next(t for t in q.terms if t.term == "boundary")
    assert "reflecting" in row.reason


@pytest.mark.slow
def test_boundary_errors_match_runs_on_generated_pools():
    """For walled pools nobody picked, the evaluated boundary term (1.25× the linear model's
    change) covers the full model's own change, η₂ included, and is within 1.6× of it."""
    for scene in generate_scenes(2, seed=13, kinds=("tank",), texels=(32, 48)):
        errs = boundary_errors(scene)
        ref = run(scene, full_model(scene))
        for boundary in BOUNDARIES[1:]:
            got = run(scene, SceneModel(scene, replace(full_model(scene).choices, boundary=boundary)))
            measured = compare(got, ref)["height_max"]
            assert errs[boundary] / 1.6 <= measured <= errs[boundary], (scene.name, boundary, measured, errs)


@pytest.mark.slow
@pytest.mark.parametrize("seed", [41, 43])
def test_plans_of_generated_pools_keep_their_promise(seed):
    """Planned at ½, 2 and 8 height quanta, every generated pool's planned heights stay within
    the predicted error of the full (walled) model: the per-mode bounds taken on the even
    extension hold for the tank."""
    for scene in generate_scenes(3, seed=seed, kinds=("tank",), texels=(32, 48, 64)):
        ref = run(scene, full_model(scene))
        for quanta in (0.5, 2.0, 8.0):
            p = plan(scene, quanta * scene.height_quantum)
            err = compare(run(scene, p.model), ref)["height_max"]
            assert err <= p.predicted_error <= p.tolerance, (scene.name, quanta, p.model.describe(), err)


def test_walled_scenes_are_checked_by_name(tmp_path):
    from wavephys.planner import ShipSpec, WindSpec

    with pytest.raises(ValueError, match="walls.*open_water"):
        _pool(3, open_water=True)
    with pytest.raises(ValueError, match="walls.*ships"):
        Scene(20.0, 0.125, depth=2.0, walls=True, ships=(ShipSpec(-2.0, 0.0, 1.0),))
    with pytest.raises(ValueError, match="walls.*wind"):
        Scene(20.0, 0.25, depth=2.0, walls=True, wind=WindSpec(5.0))
    with pytest.raises(ValueError, match="walls.*caustics"):
        _pool(3, caustics=True)
    with pytest.raises(ValueError, match="walls.*1024"):
        Scene(2048 * 0.01, 0.01, depth=2.0, walls=True, stones=(StoneSpec(0.0, 0.0, 0.1, 0.01),))
    with pytest.raises(TypeError, match="walls"):
        Scene(2.0, 2.0 / 32, walls="yes", stones=(StoneSpec(0.0, 0.0, 0.15, 0.01),))
    with pytest.raises(ValueError, match="no walls"):
        replace(_pool(3), walls=False).even_extension()
    with pytest.raises(ValueError, match="boundary"):
        Choices(boundary="mirror")
    toml = tmp_path / "pool.toml"
    toml.write_text('extent = 2.0\npixel = 0.0625\ndepth = 0.5\nwalls = true\nduration = 0.1\n'
                    '[[stones]]\nx = 0.0\ny = 0.0\nradius = 0.15\ndepth = 0.01\n')
    scene = Scene.from_toml(toml)
    assert scene.walls and not scene.open_water and Scene.from_dict(scene.as_dict()) == scene
    assert boundary_errors(replace(_pool(3), walls=False)) == {}
