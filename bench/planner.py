"""The planner's calibration (``python -m bench calibrate``) and its proof (``python -m bench planner``).

``calibrate`` measures, on this machine and after compilation, what the planner's cost
model (:mod:`wavephys.planner.cost`) needs: a step by grid size (linear and second
order), a ship's patch per step, a Hermite frame, a Fourier refinement, each Fresnel form
and absorption method per million pixels, and κ, the float32 rounding of full runs against
float64 (in a subprocess with x64 enabled). It writes
``wavephys/planner/data/calibration.json`` atomically.

``planner`` is the proof over scenes nobody picked: for each generated scene
(:func:`wavephys.planner.generate_scenes`, 32–128 texels) it plans at a tolerance of one
height quantum, runs the full and the planned model, and records predicted against measured
error and predicted against measured cost (each run timed warm, after a first run). The
colour prediction covers the optics terms (Fresnel form, absorption), so it is measured on
the full model's surface (``measured_colour_optics``); ``measured_colour`` is the whole
image difference, heights included.
"""

from __future__ import annotations

import json
import math
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

CAL_PATH = Path(__file__).resolve().parents[1] / "wavephys" / "planner" / "data" / "calibration.json"
STEP_SIZES = (16, 20, 32, 40, 64, 80, 128, 160, 256, 320, 512, 640, 1024)
KAPPA_SCENES = 6


def _median(fn, repeats=5, warmup=1):
    import jax

    for _ in range(warmup):
        jax.block_until_ready(fn())
    ts = []
    for _ in range(repeats):
        t = time.perf_counter()
        jax.block_until_ready(fn())
        ts.append(time.perf_counter() - t)
    return statistics.median(ts)


def step_walls_seconds(progress=print, step: dict | None = None) -> dict:
    """Seconds per step in a walled tank by n: the ``step`` table (``step``, default the shipped
    one) times the ratio walled / periodic step measured here in interleaved rounds at the same n
    (a ratio from one run, not two tables measured on different days)."""
    import wavephys.simulation.stepping as st
    from bench.timing import interleaved
    from wavephys import Grid, Stones, Water
    from wavephys.simulation.model import Model

    step = step or json.loads(CAL_PATH.read_text())["step"]
    out = {"n": list(step["n"]), "first": [], "second": [], "ratio_first": [], "ratio_second": []}
    for i, n in enumerate(step["n"]):
        steps = max(4, min(50, 500_000 // (n * n)))
        for so, key in ((False, "first"), (True, "second")):
            fns = {}
            for name, kw in (("periodic", dict(margin=n // 8)), ("walls", dict(walls="all"))):
                model = Model(Grid(n, float(n)), Water(depth=5.0), 1 / 30, second_order=so, **kw)
                state = st.add_source(model, st.initial_state(model), Stones(0.0, 0.0, 3.0, 0.05))
                fns[name] = (lambda m=model, s=state: st.run(m, s, steps))
            times = interleaved(fns, repeats=7, warmup=1, block=3)
            ratio = float(np.median([w / p for w, p in zip(times["walls"], times["periodic"])]))
            out[f"ratio_{key}"].append(ratio)
            out[key].append(ratio * step[key][i])
        progress(f"step (walls) n={n}: ×{out['ratio_first'][-1]:.2f} the periodic step, second order "
                 f"×{out['ratio_second'][-1]:.2f}")
    return out


def step_symmetric_seconds(progress=print, step: dict | None = None) -> dict:
    """Seconds of one leapfrog sub-step of one wet level of the symmetric depth stepper, by n: the
    ``step`` table's linear step (``step``, default the shipped one) times the ratio measured here
    in interleaved rounds (a sloping floor 2.5–7.5 m deep, its levels and sub-steps from
    :func:`wavephys.simulation.depth.symmetric_work`, divided out)."""
    import wavephys.simulation.stepping as st
    from bench.timing import interleaved
    from wavephys import Grid, Stones, Water
    from wavephys.simulation.depth import Floor, depth_state, run_depth, symmetric_work
    from wavephys.simulation.model import Model

    step = step or json.loads(CAL_PATH.read_text())["step"]
    out = {"n": list(step["n"]), "seconds": [], "ratio": [], "work": []}
    for i, n in enumerate(step["n"]):
        steps = max(4, min(50, 500_000 // (n * n)))
        model = Model(Grid(n, float(n)), Water(depth=5.0), 1 / 30, margin=n // 8)
        state = st.add_source(model, st.initial_state(model), Stones(0.0, 0.0, 3.0, 0.05))
        x = np.asarray(model.grid.coordinates, np.float64)
        floor = Floor(np.broadcast_to(5.0 - 2.5 * x[None, :] / (0.5 * n), (n, n)))
        levels, substeps = symmetric_work(model, floor)
        ds = depth_state(model, st.surface(model, state).eta)
        times = interleaved({"spectral": lambda: st.run(model, state, steps),
                             "symmetric": lambda: run_depth(model, floor, ds, steps, method="symmetric")},
                            repeats=7, warmup=1, block=3)
        ratio = float(np.median([a / b for a, b in zip(times["symmetric"], times["spectral"])])) / (levels * substeps)
        out["ratio"].append(ratio)
        out["work"].append([levels, substeps])
        out["seconds"].append(ratio * step["first"][i])
        progress(f"symmetric depth step n={n}: {levels} levels × {substeps} sub-steps, ×{ratio:.2f} the spectral "
                 f"step per level and sub-step")
    return out


def step_seconds(progress=print) -> dict:
    """Seconds per step by n, linear and second order (a scan of steps, divided)."""
    import wavephys.simulation.stepping as st
    from wavephys import Grid, Stones, Water
    from wavephys.simulation.model import Model

    out = {"n": list(STEP_SIZES), "first": [], "second": []}
    for n in STEP_SIZES:
        steps = max(8, min(200, 2_000_000 // (n * n)))
        for so, key in ((False, "first"), (True, "second")):
            model = Model(Grid(n, float(n)), Water(depth=5.0), 1 / 30, margin=n // 8, second_order=so)
            state = st.add_source(model, st.initial_state(model), Stones(0.0, 0.0, 3.0, 0.05))
            out[key].append(_median(lambda: st.run(model, state, steps), repeats=5) / steps)
        progress(f"step n={n}: {out['first'][-1] * 1e3:.3f} ms, second order {out['second'][-1] * 1e3:.3f} ms")
    return out


def ship_seconds(progress=print, method: str = "kernels") -> dict:
    """Extra seconds per step of one ship, by patch side (step with ship − step without), its
    waves made by ``method`` (``"kernels"`` or ``"impulses"``)."""
    import wavephys.simulation.stepping as st
    from wavephys import Grid, Water
    from wavephys.physics.ship_waves import Hull, Ship, straight_path
    from wavephys.simulation.model import Model

    out = {"n": [], "seconds": []}
    for patch in (16, 32, 64, 128, 256):
        n = max(64, 2 * patch)
        model = Model(Grid(n, float(n)), Water(depth=5.0), 1 / 30, margin=n // 8, ship_patch=patch,
                      ship_method=method)
        ship = Ship(Hull("gaussian", 0.1 * patch, 0.04 * patch), straight_path((0.0, 0.0), (0.5, 0.0)), 0.01)
        state = st.initial_state(model)

        def with_ship(k=[0]):
            nonlocal state
            state, surf = st.step(model, state, [ship])
            return surf.eta

        def without():
            return st.step(model, state, [])[1].eta

        extra = _median(with_ship, repeats=9, warmup=2) - _median(without, repeats=9, warmup=2)
        out["n"].append(patch)
        out["seconds"].append(max(extra, 1e-6))
        progress(f"ship patch {patch} ({method}): +{extra * 1e3:.3f} ms per step")
    return out


def frame_seconds(progress=print) -> tuple[dict, dict, dict]:
    """Seconds per output frame, by size, of the runner's frame assembly (blocks of
    ``FRAME_BLOCK`` frames, brought to the host): the base (gathered at a step), the extra of a
    Hermite blend (by the simulated n), and the extra of a Fourier refinement by 2 (by the fine n)."""
    import jax.numpy as jnp

    from wavephys.planner.runner import FRAME_BLOCK, _assemble

    base, blend, refine = ({"n": [], "seconds": []} for _ in range(3))
    for n in (16, 32, 64, 128, 256, 512, 1024):
        steps = 9
        e = jnp.ones((steps, n, n), jnp.float32)
        idx = jnp.asarray(np.arange(FRAME_BLOCK) % (steps - 1), jnp.int32)
        zero, half = jnp.zeros(FRAME_BLOCK, jnp.float32), jnp.full(FRAME_BLOCK, 0.5, jnp.float32)
        dt = jnp.asarray(0.03, jnp.float32)
        t0 = _median(lambda: np.asarray(_assemble(e, e, idx, zero, dt, 1)), repeats=5) / FRAME_BLOCK
        t1 = _median(lambda: np.asarray(_assemble(e, e, idx, half, dt, 1)), repeats=5) / FRAME_BLOCK
        ec = jnp.ones((steps, n // 2, n // 2), jnp.float32)
        t2 = _median(lambda: np.asarray(_assemble(ec, ec, idx, zero, dt, 2)), repeats=5) / FRAME_BLOCK
        for table, value in ((base, t0), (blend, max(t1 - t0, 1e-7)), (refine, max(t2 - t0, 1e-7))):
            table["n"].append(n)
            table["seconds"].append(value)
        progress(f"frame n={n}: base {t0 * 1e3:.3f} ms, blend +{(t1 - t0) * 1e3:.3f} ms, refine +{(t2 - t0) * 1e3:.3f} ms")
    return base, blend, refine


def overhead_seconds(progress=print) -> float:
    """Fixed seconds of one run (state, sources, dispatch, host copies): a 32-texel periodic pool
    of one frame, run warm, less its one step."""
    from wavephys.planner import SceneModel, run
    from wavephys.planner.cost import interpolate
    from wavephys.planner.scene import Scene, StoneSpec

    scene = Scene(1.0, 1.0 / 32, depth=0.5, open_water=False, duration=1 / 30, fps=30.0,
                  stones=(StoneSpec(0.0, 0.0, 0.1, 0.005),))
    model = SceneModel(scene)
    run(scene, model)
    t = statistics.median(run(scene, model).seconds for _ in range(15))
    step = interpolate(json.loads(CAL_PATH.read_text())["step"], 32, "second")
    progress(f"run overhead {1e3 * (t - step):.2f} ms")
    return max(t - step, 0.0)


def optics_seconds(progress=print) -> tuple[dict, dict]:
    """Seconds per million pixels of each Fresnel form and absorption method, as the planner's
    shading evaluates them (eager, float32 reflectance; transmittance tables cached)."""
    import jax.numpy as jnp

    from optics.light.fresnel import REFLECTANCE_METHODS, reflectance
    from wavephys.planner.runner import transmittance
    from wavephys.planner.scene import Scene, StoneSpec

    cos = jnp.asarray(np.random.default_rng(0).uniform(0, 1, 1_000_000), jnp.float32)
    fresnel = {f: _median(lambda: reflectance(cos, method=f), repeats=5) for f in REFLECTANCE_METHODS}  # every entry of the family
    scene = Scene(8.0, 0.125, depth=2.0, stones=(StoneSpec(0.0, 0.0, 0.5, 0.02),))
    paths = np.random.default_rng(1).uniform(4.0, 9.0, 1_000_000)
    from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

    absorption = {m: _median(lambda: transmittance(scene, m, paths), repeats=3)
                  for m in WATER_TRANSMITTANCE_METHODS}  # every entry of the family
    progress("fresnel " + ", ".join(f"{k} {v * 1e3:.2f} ms" for k, v in fresnel.items()) + "; absorption "
             + ", ".join(f"{k} {v * 1e3:.1f} ms" for k, v in absorption.items()) + " per 1M pixels")
    return fresnel, absorption


CAUSTICS_CELLS = ((32, 1), (64, 1), (64, 2), (64, 3), (128, 2), (128, 3), (128, 4), (256, 4))
"""(texels, refinement) pairs timed for the caustics table (traced cells per side = their product)."""


def caustics_seconds(progress=print) -> dict:
    """One frame's floor irradiance by beam rasterization (eager, as the planner's shading calls
    it), by traced cells per side; the median of 3 after one compiling call."""
    import jax.numpy as jnp

    from optics.caustics import floor_irradiance_beam
    from optics.caustics.surfaces import random_surface
    from wavephys.core.grid import Grid

    table = {}
    for n, r in CAUSTICS_CELLS:
        grid = Grid(n, 2.0)
        eta = jnp.asarray(random_surface(grid, "band", 0.08, 1), jnp.float32)
        seconds = _median(lambda: floor_irradiance_beam(eta, grid, 1.0, (-0.5, 0.0, 0.87), refine=r), repeats=3)
        table[n * r] = min(seconds, table.get(n * r, math.inf))
    cells = sorted(table)
    progress("caustics per frame: " + ", ".join(f"{c}² cells {table[c] * 1e3:.1f} ms" for c in cells))
    return dict(n=cells, seconds=[table[c] for c in cells])


def caustics_jacobian_seconds(progress=print) -> dict:
    """One frame's floor irradiance by the Jacobian gather (eager, as the planner's shading calls it),
    by texels per side, on the beam table's surfaces with the floor at half their first fold (where
    the planner offers it); the median of 3 after one compiling call."""
    import jax.numpy as jnp

    from optics.caustics import first_fold_depth, floor_irradiance_jacobian
    from optics.caustics.surfaces import random_surface
    from wavephys.core.grid import Grid

    sizes = sorted({n for n, _ in CAUSTICS_CELLS} | {512})
    out = []
    for n in sizes:
        grid = Grid(n, 2.0)
        eta = jnp.asarray(random_surface(grid, "band", 0.08, 1), jnp.float32)
        sun = (-0.5, 0.0, 0.87)
        depth = 0.5 * first_fold_depth(eta, grid, sun)
        out.append(_median(lambda: floor_irradiance_jacobian(eta, grid, depth, sun, fold="raise"), repeats=3))
    progress("jacobian caustics per frame: " + ", ".join(f"{n}² {t * 1e3:.1f} ms" for n, t in zip(sizes, out)))
    return dict(n=sizes, seconds=out)


def texture_seconds(progress=print) -> dict:
    """Seconds per million texels of storing frames in each height texture format
    (:func:`wavephys.planner.runner.encode_texture`, as a run does), over 64 frames of 128²."""
    from wavephys.core.grid import Grid
    from wavephys.planner.model import TEXTURES
    from wavephys.planner.runner import encode_texture

    grid = Grid(128, 4.0)
    frames = (0.01 * np.random.default_rng(7).standard_normal((64, 128, 128))).astype(np.float32)
    out = {f: _median(lambda: encode_texture(frames, f, grid), repeats=7) / (frames.size / 1e6) for f in TEXTURES}
    progress("height texture per 1M texels: " + ", ".join(f"{f} {t * 1e3:.2f} ms" for f, t in out.items()))
    return out


SURFACE_SIZES = (32, 64, 128, 256)


def surface_seconds(progress=print) -> dict:
    """Seconds per output frame of each surface model other than the spectral step
    (:func:`wavephys.planner.runner.surface_frames`, host copy included), by texels per side:
    a wind sea of 8 frames, the median of 3 runs after one compiling run."""
    from wavephys.planner.model import SURFACES, Choices, SceneModel
    from wavephys.planner.runner import surface_frames
    from wavephys.planner.scene import Scene, WindSpec

    out = {name: {"n": list(SURFACE_SIZES), "seconds": []} for name in SURFACES[1:]}
    for n in SURFACE_SIZES:
        scene = Scene(float(n), 1.0, open_water=False, duration=8 / 30, fps=30.0, wind=WindSpec(6.0, seed=n))
        for name in SURFACES[1:]:
            model = SceneModel(scene, Choices(surface=name, second_order=False))
            out[name]["seconds"].append(_median(lambda: surface_frames(model), repeats=3) / scene.frames)
        progress(f"surface models per frame at {n}²: " + ", ".join(f"{k} {v['seconds'][-1] * 1e3:.2f} ms"
                                                                 for k, v in out.items()))
    return out


SHADE_SIZES = (32, 64, 128, 256)


def shade_seconds(progress=print, cal: dict | None = None) -> dict:
    """The planner's shading of one frame beyond its Fresnel and absorption per-pixel costs (the
    normals, angles and paths: :func:`wavephys.planner.runner.shade`), by texels per side."""
    from wavephys.planner.model import SceneModel
    from wavephys.planner.runner import shade
    from wavephys.planner.scene import Scene, StoneSpec

    cal = cal or json.loads(CAL_PATH.read_text())
    out = []
    for n in SHADE_SIZES:
        scene = Scene(4.0, 4.0 / n, depth=1.0, open_water=False, stones=(StoneSpec(0.0, 0.0, 0.5, 0.02),))
        model = SceneModel(scene)
        heights = 0.01 * np.random.default_rng(n).standard_normal((n, n))
        seconds = _median(lambda: shade(scene, model, heights), repeats=5)
        forms = n * n / 1e6 * (cal["fresnel"]["exact"] + cal["absorption"]["spectral"])
        out.append(max(seconds - forms, 0.0))
    progress("shading overhead per frame: " + ", ".join(f"{n}² {t * 1e3:.2f} ms" for n, t in zip(SHADE_SIZES, out)))
    return dict(n=list(SHADE_SIZES), seconds=out)


_KAPPA_CHILD = r"""
import json, sys
import jax
jax.config.update("jax_enable_x64", True)
import numpy as np
from wavephys.planner import generate_scenes, SceneModel, run
scenes = generate_scenes(int(sys.argv[1]), seed=int(sys.argv[2]))
out = {}
for s in scenes:
    o = run(s, SceneModel(s, dtype=sys.argv[4]))
    out[s.name] = o.heights.astype(np.float64)
np.savez(sys.argv[3], **out)
"""


def kappa(progress=print, count: int = KAPPA_SCENES, seed: int = 99) -> dict:
    """max over frames |η₃₂ − η₆₄| / s0 (the scene's amplitude bound) over generated scenes,
    each run in float32 and float64 (x64 in a subprocess: it changes JAX's global config)."""
    import tempfile

    from wavephys.planner import generate_scenes
    from wavephys.planner.spectrum import scene_spectrum

    ratios = {}
    with tempfile.TemporaryDirectory() as tmp:
        files = {}
        for dtype in ("float32", "float64"):
            files[dtype] = Path(tmp) / f"{dtype}.npz"
            subprocess.run([sys.executable, "-c", _KAPPA_CHILD, str(count), str(seed), str(files[dtype]), dtype],
                           check=True, env={**os.environ, "PYTHONPATH": str(CAL_PATH.parents[3])})
        a, b = np.load(files["float32"]), np.load(files["float64"])
        for s in generate_scenes(count, seed=seed):
            ratios[s.name] = float(np.abs(a[s.name] - b[s.name]).max() / scene_spectrum(s).s0)
    worst = max(ratios.values())
    progress("kappa per scene: " + ", ".join(f"{k} {v:.2g}" for k, v in ratios.items()))
    return dict(kappa=4.0 * worst, measured=ratios)


def calibrate(progress=print, only=None) -> dict:
    """Measure everything the cost model needs and write the calibration file (module doc).
    ``only="caustics"``, ``"caustics_jacobian"``, ``"step_walls"``, ``"step_symmetric"``, ``"shade"``, ``"texture"``, ``"surface"``, ``"ship"`` or ``"ship_impulses"``: measure that table alone and update the shipped file's entry."""
    import platform

    from wavephys.core.files import atomic_path

    if only is not None:
        parts = {"caustics": caustics_seconds, "caustics_jacobian": caustics_jacobian_seconds,
                 "shade": shade_seconds, "texture": texture_seconds,
                 "surface": surface_seconds, "ship": ship_seconds,
                 "step_walls": step_walls_seconds, "step_symmetric": step_symmetric_seconds,
                 "ship_impulses": lambda p: ship_seconds(p, "impulses")}
        if only not in parts:
            raise ValueError(f"only must be None or one of {sorted(parts)}, got {only!r}")
        data = json.loads(CAL_PATH.read_text())
        data[only] = parts[only](progress)
        data[f"{only}_date"] = time.strftime("%Y-%m-%d")
        with atomic_path(CAL_PATH) as tmp:
            tmp.write_text(json.dumps(data, indent=1))
        return data
    step = step_seconds(progress)
    step_walls = step_walls_seconds(progress, step)
    step_symmetric = step_symmetric_seconds(progress, step)
    ship = ship_seconds(progress)
    ship_impulses = ship_seconds(progress, "impulses")
    frame, blend, refine = frame_seconds(progress)
    fresnel, absorption = optics_seconds(progress)
    overhead = overhead_seconds(progress)
    caustics = caustics_seconds(progress)
    caustics_jacobian = caustics_jacobian_seconds(progress)
    shade = shade_seconds(progress, dict(fresnel=fresnel, absorption=absorption))
    texture = texture_seconds(progress)
    surface = surface_seconds(progress)
    k = kappa(progress)
    data = dict(machine=f"{platform.machine()} {os.cpu_count()} cores, {platform.python_version()}",
                date=time.strftime("%Y-%m-%d"), step=step, step_walls=step_walls, step_symmetric=step_symmetric, ship=ship, ship_impulses=ship_impulses, frame=frame, blend=blend, refine=refine,
                fresnel=fresnel, absorption=absorption, caustics=caustics, caustics_jacobian=caustics_jacobian, shade=shade, texture=texture, surface=surface, run_overhead=overhead, kappa=k["kappa"],
                kappa_measured=k["measured"],
                kappa_note="4 × the worst measured max|η32 − η64| / s0 over the scenes")
    with atomic_path(CAL_PATH) as tmp:
        tmp.write_text(json.dumps(data, indent=1))
    return data


def _total(output, frames: int = 1) -> float:
    """Wall seconds of one run: simulation and frames, and the shading of the image (measured on
    the last frame, counted ``frames`` times as the cost model counts it; the first run also
    compiles)."""
    return output.seconds + output.shade_seconds * frames


def proof_rows(count: int = 50, seed: int = 2026, quanta: float = 1.0, progress=print,
               texels=(32, 48, 64, 96, 128)) -> list:
    """Plan each of ``count`` generated scenes at ``quanta`` height quanta, run the full and the
    planned model (each five times; the fastest run timed), and record predicted and measured."""
    from wavephys.planner import Infeasible, compare, full_model, generate_scenes, plan, run
    from wavephys.planner.runner import shade

    rows = []
    for i, scene in enumerate(generate_scenes(count, seed=seed, texels=texels)):
        tol = quanta * scene.height_quantum
        t = time.perf_counter()
        try:
            p = plan(scene, tol)
        except Infeasible as exc:
            rows.append(dict(scene=scene.name, infeasible=str(exc)))
            progress(f"[{i + 1}/{count}] {scene.name}: infeasible: {exc}")
            continue
        planning = time.perf_counter() - t
        full_m = full_model(scene)
        cost = lambda o: _total(o, scene.frames)
        ref = min((run(scene, full_m) for _ in range(5)), key=cost)  # the first compiles
        out = min((run(scene, p.model) for _ in range(5)), key=cost)
        err = compare(out, ref)
        optics_only = float(np.abs(shade(scene, p.model, ref.heights[-1]) - ref.image).max())
        row = dict(scene=scene.name, kind=scene.name.split("-")[0], texels=scene.texels, frames=scene.frames,
                   tolerance=tol, predicted_error=p.predicted_error, measured_error=err["height_max"],
                   measured_rms=err["height_rms"], predicted_rms=p.predicted_rms,
                   predicted_colour=p.predicted_colour_error, measured_colour=err["colour_max"],
                   measured_colour_optics=optics_only,
                   colour_tolerance=p.colour_tolerance, predicted_cost=p.cost, predicted_full_cost=p.full_cost,
                   measured_cost=cost(out), measured_full_cost=cost(ref), caustics=scene.caustics,
                   planning_seconds=planning, choices=p.model.choices.as_dict())
        row["measured_saving"] = row["measured_full_cost"] / row["measured_cost"]
        row["predicted_saving"] = p.saving
        rows.append(row)
        progress(f"[{i + 1}/{count}] {scene.name}: {p.model.describe()}; error {err['height_max']:.3g} ≤ predicted "
                 f"{p.predicted_error:.3g} ≤ tol {tol:.3g}; colour of the optics terms {optics_only:.2g} ≤ "
                 f"{p.predicted_colour_error:.2g}, with the heights' {err['colour_max']:.2g}; saving ×{row['measured_saving']:.2f} (predicted "
                 f"×{p.saving:.2f})")
    return rows


def figures(rows) -> dict:
    """Predicted against measured error and cost over the proof's scenes."""
    import matplotlib.figure

    ok = [r for r in rows if "measured_error" in r]
    fig = matplotlib.figure.Figure(figsize=(16, 4.6))
    ax1, ax2, ax3 = fig.subplots(1, 3)
    kinds = sorted({r["kind"] for r in ok})
    for kind in kinds:
        sel = [r for r in ok if r["kind"] == kind]
        nz = [r for r in sel if r["measured_error"] > 0]
        pts = ax1.scatter([r["predicted_error"] / r["tolerance"] for r in nz],
                          [r["measured_error"] / r["tolerance"] for r in nz], label=kind, s=18)
        zero = [r for r in sel if r["measured_error"] == 0]
        if zero:  # the plan is the full model's heights: no error to draw on a log axis
            ax1.scatter([r["predicted_error"] / r["tolerance"] for r in zero], [1e-7] * len(zero), marker="v", s=18,
                        color=pts.get_facecolor()[0])
        ax2.scatter([r["predicted_saving"] for r in sel], [r["measured_saving"] for r in sel], label=kind, s=18)
    lo = 1e-6
    ax1.plot([lo, 1], [lo, 1], "k--", lw=0.8, label="measured = predicted")
    ax1.axhline(1.0, color="r", lw=0.8, label="tolerance")
    ax1.set(xscale="log", yscale="log", xlabel="predicted error / tolerance",
            ylabel="measured error / tolerance (▼: exactly 0)", title=f"height error, {len(ok)} generated scenes")
    ax1.legend(fontsize=7)
    top = max([r["measured_saving"] for r in ok] + [r["predicted_saving"] for r in ok] + [1.5])
    ax2.plot([0.8, top], [0.8, top], "k--", lw=0.8)
    ax2.set(xscale="log", yscale="log", xlabel="predicted saving (full cost / plan cost)",
            ylabel="measured saving", title="cost saving of the plan")
    ax2.legend(fontsize=7)
    floor = 1e-4
    for caustics, marker in ((False, "o"), (True, "s")):
        sel = [r for r in ok if r.get("caustics", False) == caustics]
        if not sel:
            continue
        ax3.scatter([max(r["predicted_colour"] / r["colour_tolerance"], floor) for r in sel],
                    [max(r["measured_colour_optics"] / r["colour_tolerance"], floor) for r in sel], marker=marker,
                    s=18, label=f"optics terms{' and caustics' if caustics else ''} ({len(sel)} scenes)")
        ax3.scatter([max(r["predicted_colour"] / r["colour_tolerance"], floor) for r in sel],
                    [max(r["measured_colour"] / r["colour_tolerance"], floor) for r in sel], marker=marker,
                    s=18, facecolors="none", edgecolors="grey", label="whole image (heights too)" if caustics else None)
    ax3.plot([floor, 1], [floor, 1], "k--", lw=0.8)
    ax3.axhline(1.0, color="r", lw=0.8, label="colour tolerance")
    ax3.set(xscale="log", yscale="log", xlabel="predicted colour error / tolerance (floored at 1e-4)",
            ylabel="measured / tolerance", title="colour (image quanta)")
    ax3.legend(fontsize=7)
    fig.tight_layout()
    return {"proof": fig}
