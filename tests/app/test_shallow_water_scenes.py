"""The shallow-water render scenes (``beach``, ``dambreak``): what the renderer is given is the solver's water —
the ground shows where it is dry, the water is conserved in the walled yard, frames and single scenes agree,
and time wraps with the scene's cycle."""

import numpy as np
import pytest

from wavephys.app.scenes import (SHALLOW_WATER_CYCLES, _ground, _shallow_water_setup, builtin_scene, scene_caustics,
                                 scene_frames, scene_water)


_SLOW_SCENES = {"wakebeach"}  # the split: 5–15 s a run at n = 64; its tests here are in the slow run
SCENE_PARAMS = [pytest.param(name, marks=pytest.mark.slow) if name in _SLOW_SCENES else name
                for name in sorted(SHALLOW_WATER_CYCLES)]


@pytest.mark.parametrize("name", SCENE_PARAMS)
def test_dry_land_shows_the_ground_and_the_water_moves(name):
    n = 64
    ground = _ground(name, n)[0]
    a, b = scene_water(name, n, 0.5), scene_water(name, n, 2.5)
    for w in (a, b):
        dry = w < ground
        assert dry.any() and (~dry).any()  # both wet and dry texels
        assert np.all(ground[dry] - w[dry] == pytest.approx(0.02, abs=1e-5))  # 2 cm under the ground where dry
    assert np.abs(a - b).max() > 0.05  # the wave / the flood has moved


@pytest.mark.parametrize("name", SCENE_PARAMS)
def test_frames_agree_with_single_frames_and_time_wraps(name):
    n = 64
    frames = list(scene_frames(name, 2, fps=2.0, n=n, start=1.0, caustics=False))
    ground = _ground(name, n)[0]
    for i, s in enumerate(frames):  # one run to both frames, or a run to each: the same steps but the last
        a, b = np.asarray(s.water), scene_water(name, n, 1.0 + i / 2.0)
        wet = (a > ground) & (b > ground)
        # measured 3e-4 m at the beach's bore; 3.9 mm in the wake scene, whose split is first order in time (the
        # shortened last step of a run moves the waves by O(Δt)) at 8 cells per wavelength (n = 64)
        assert np.abs(a - b)[wet].max() < (5e-3 if name == "wakebeach" else 2e-3)
        assert np.mean((a > ground) != (b > ground)) < 0.01  # a film at the swash front may be wet in one only
    cycle = SHALLOW_WATER_CYCLES[name]
    assert np.array_equal(scene_water(name, n, 1.0), scene_water(name, n, 1.0 + cycle))


def test_the_dam_break_conserves_its_water():
    from wavephys.simulation.shallow_water import sw_frames, sw_mass

    solver, bed, state = _shallow_water_setup("dambreak", 64)
    out = sw_frames(solver, bed, state, np.linspace(0.5, 6.0, 6))
    mass = np.asarray(sw_mass(out, float(solver.dx)))
    assert np.abs(mass / float(sw_mass(state, float(solver.dx))) - 1).max() < 1e-5  # float32, walls
    assert np.asarray(out.h).min() >= 0


@pytest.mark.slow
def test_caustics_are_flat_light_on_dry_land_and_bores_focus_light():
    n = 64
    water = scene_water("beach", n, 1.0)
    ground = _ground("beach", n)[0]
    c = scene_caustics("beach", water)
    dry = water < ground
    assert np.all(np.isfinite(c))
    assert np.all(c[dry] == 1.0)  # no water: the flat light
    assert np.abs(c[~dry] - 1.0).max() > 0.03  # the long, smooth wave: weak caustics (measured ±5–9 %)
    scene = builtin_scene("dambreak", n=n, time=2.0)
    assert np.asarray(scene.caustics).max() > 1.5  # the flood's bores focus light (measured 2.2)


@pytest.mark.slow
def test_the_boat_wake_reaches_the_beach_and_the_water_is_conserved():
    """``wakebeach``: the split model under a boat at 2.5 m/s; its wake (4 m waves over 2 m) has crossed to the
    shallows by the scene's t = 5 s, and the water is conserved over the run (float32, walls and periodic)."""
    from wavephys.app.scenes import WAKE_WARMUP
    from wavephys.simulation.shallow_water import sw_mass
    from wavephys.simulation.split import split_frames

    n = 64
    model, bed, state = _shallow_water_setup("wakebeach", n)
    out = split_frames(model, bed, state, WAKE_WARMUP + np.array([0.0, 5.0]))
    h = np.asarray(out.h)
    assert h.min() >= 0
    mass = np.asarray(sw_mass(out, float(model.solver.dx)))
    assert np.abs(mass / float(sw_mass(state, float(model.solver.dx))) - 1).max() < 1e-5
    shallows = (bed > -0.8) & (bed < -0.2)
    eta = h[1] + bed
    assert np.abs(eta[shallows]).max() > 0.01  # the wake on the beach (measured 3–6 cm)


@pytest.mark.slow
def test_harbour_wake_reaches_the_quay_and_frames_match_single_times(monkeypatch):
    """``harbour``: the boat's wake has reached the quay by t = 8 s (the rows along it move 10× more than at 1 s,
    before it arrives) and is reflected there (1.5× more than with the quay's side open), the band under the quay
    holds still water, and the frames of one run equal the heights made for each time alone."""
    from wavephys.app.scenes import _harbour_simulation, scene_frames, scene_water

    n = 64
    _, band, _ = _harbour_simulation(n)
    water = scene_water("harbour", n, 8.0)
    assert np.abs(water[n - band:]).max() == 0.0
    early = scene_water("harbour", n, 1.0)
    assert np.abs(water[n - band - 3:n - band]).max() > 10 * np.abs(early[n - band - 3:n - band]).max()
    frames = [np.asarray(s.water) for s in scene_frames("harbour", 2, fps=2.0, n=n, start=7.5, caustics=False)]
    assert np.array_equal(frames[1], water)
    # the quay reflects: with its side open instead (the margin there), the rows along it move far less
    import wavephys.simulation

    walled = wavephys.simulation.Simulation

    def open_quay(*args, **kwargs):
        kwargs["walls"] = ()
        return walled(*args, **kwargs)

    monkeypatch.setattr(wavephys.simulation, "Simulation", open_quay)
    opened = scene_water("harbour", n, 8.0)
    quay = slice(n - band - 3, n - band)
    assert np.abs(water[quay]).max() > 1.5 * np.abs(opened[quay]).max()


def test_shore_swell_feels_the_beach():
    """``shore``: the swell runs over the beach's floor (the symmetric depth blend) — none under the sand (the old
    swell passed under it), waves up to the surf zone, damped within it; one run's frames equal the heights made
    for each time alone."""
    from wavephys.app.scenes import _shore_setup, scene_frames, scene_water

    n = 64
    _, floor, _, _, _ = _shore_setup(n)
    depth = floor.depth
    water = scene_water("shore", n, 3.0)
    assert np.abs(water[depth == 0]).max() == 0.0
    rms = lambda band: float(np.sqrt(np.mean(water[band] ** 2)))
    assert rms((depth > 0.4) & (depth < 1.0)) > 0.02
    assert rms((depth > 0) & (depth < 0.05)) < 0.2 * rms((depth > 0.4) & (depth < 1.0))
    frames = [np.asarray(s.water) for s in scene_frames("shore", 2, fps=1.0, n=n, start=2.0, caustics=False)]
    assert np.array_equal(frames[1], water)


def test_the_slow_scenes_say_their_simulated_seconds_as_they_step(capsys):
    """progress=True (what `wavephys render` passes) says each simulated second on stderr and steps the
    frame landing on each: the same water to the scheme's truncation (measured 5.1e-4 m under a 0.15 m
    wave at 64², 2.5 s), not another scene."""
    from wavephys.app.scenes import scene_water

    quiet = scene_water("beach", 64, 2.5)
    assert capsys.readouterr().err == ""
    said = scene_water("beach", 64, 2.5, progress=True)
    assert "3/3 s simulated" in capsys.readouterr().err
    assert float(np.abs(said - quiet).max()) < 2e-3
    with pytest.raises(TypeError, match="progress"):
        scene_water("beach", 64, 2.5, progress="yes")
