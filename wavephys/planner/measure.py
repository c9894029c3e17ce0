"""Measure the planner's cost model on this machine: ``wavephys calibrate --out FILE``.

Every table :mod:`wavephys.planner.cost` reads is measured here, after compilation, as wall
seconds on the machine (and JAX device) this runs on: a step by grid size (linear and second
order; walled; one level of the symmetric depth stepper), a ship's patch per step, an output
frame (and the extra of a Hermite blend and of a Fourier refinement), each Fresnel form and
absorption method per million pixels, the floor light by beam and by Jacobian gather, each
height texture format, each cheap surface model, the shading's fixed part, a run's fixed
overhead, and κ (the float32 rounding of full runs against float64, in a subprocess with x64).

The result is a JSON file that ``wavephys plan --calibration FILE`` and
``plan(..., calibration=load_calibration(FILE))`` read; the shipped one
(``wavephys/planner/data/calibration.json``) is what ``python -m bench calibrate`` writes from
a checkout. A full calibration takes several minutes on a 2-core CPU (the step table up to
1024² dominates); ``only=`` re-measures some tables and keeps the rest from ``base``.
"""

from __future__ import annotations

import math
import os
import platform
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from wavephys.core.timing import interleaved, median_seconds
from wavephys.planner.cost import calibration as shipped
from wavephys.planner.cost import interpolate

__all__ = ["calibrate", "TABLES"]

STEP_SIZES = (16, 20, 32, 40, 64, 80, 128, 160, 256, 320, 512, 640, 1024)
KAPPA_SCENES = 6


def _package_root() -> str:
    """The folder holding the ``wavephys`` package (for the κ subprocess's import path)."""
    root = str(Path(__file__).resolve().parents[2])
    rest = os.environ.get("PYTHONPATH")
    return root + (os.pathsep + rest if rest else "")


def step_walls_seconds(progress=print, step: dict | None = None) -> dict:
    """Seconds per step in a walled tank by n: the ``step`` table (``step``, default the shipped
    one) times the ratio walled / periodic step measured here in interleaved rounds at the same n
    (a ratio from one run, not two tables measured on different days)."""
    import wavephys.simulation.stepping as st
    from wavephys import Grid, Stones, Water
    from wavephys.simulation.model import Model

    step = step or shipped()["step"]
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
    from wavephys import Grid, Stones, Water
    from wavephys.simulation.depth import Floor, depth_state, symmetric_work
    from wavephys.simulation.steppers import DepthStepper
    from wavephys.simulation.model import Model

    step = step or shipped()["step"]
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
                             "symmetric": lambda: DepthStepper(model, floor, "symmetric").trajectory(ds, steps)},
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
            out[key].append(median_seconds(lambda: st.run(model, state, steps), repeats=5) / steps)
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

        extra = median_seconds(with_ship, repeats=9, warmup=2) - median_seconds(without, repeats=9, warmup=2)
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
        ec = jnp.ones((steps, n // 2, n // 2), jnp.float32)
        times = interleaved({"base": lambda: np.asarray(_assemble(e, e, idx, zero, dt, 1)),
                             "blend": lambda: np.asarray(_assemble(e, e, idx, half, dt, 1)),
                             "refine": lambda: np.asarray(_assemble(ec, ec, idx, zero, dt, 2))},
                            repeats=5, warmup=1, block=3)  # the extras as differences within a round
        t0 = float(np.median(times["base"])) / FRAME_BLOCK
        t1 = t0 + float(np.median(np.subtract(times["blend"], times["base"]))) / FRAME_BLOCK
        t2 = t0 + float(np.median(np.subtract(times["refine"], times["base"]))) / FRAME_BLOCK
        for table, value in ((base, t0), (blend, max(t1 - t0, 1e-7)), (refine, max(t2 - t0, 1e-7))):
            table["n"].append(n)
            table["seconds"].append(value)
        progress(f"frame n={n}: base {t0 * 1e3:.3f} ms, blend +{(t1 - t0) * 1e3:.3f} ms, refine +{(t2 - t0) * 1e3:.3f} ms")
    return base, blend, refine


def overhead_seconds(progress=print, step: dict | None = None) -> float:
    """Fixed seconds of one run (state, sources, dispatch, host copies): a 32-texel periodic pool
    of one frame, run warm, less its one step."""
    from wavephys.planner.model import SceneModel
    from wavephys.planner.runner import run
    from wavephys.planner.scene import Scene, StoneSpec

    scene = Scene(1.0, 1.0 / 32, depth=0.5, open_water=False, duration=1 / 30, fps=30.0,
                  stones=(StoneSpec(0.0, 0.0, 0.1, 0.005),))
    model = SceneModel(scene)
    run(scene, model)
    t = statistics.median(run(scene, model).seconds for _ in range(15))
    step = interpolate(step or shipped()["step"], 32, "second")
    progress(f"run overhead {1e3 * (t - step):.2f} ms")
    return max(t - step, 0.0)


def optics_seconds(progress=print) -> tuple[dict, dict]:
    """Seconds per million pixels of each Fresnel form and absorption method, as the planner's
    one compiled shading program evaluates them (float32: the reflectance, and the interpolation
    of the method's transmittance table, :func:`wavephys.planner.runner.shading_table`)."""
    import jax
    import jax.numpy as jnp

    from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS
    from optics.light.fresnel import REFLECTANCE_METHODS, reflectance
    from wavephys.planner.runner import shading_table, uniform_interp
    from wavephys.planner.scene import Scene, StoneSpec

    cos = jnp.asarray(np.random.default_rng(0).uniform(0, 1, 1_000_000), jnp.float32)
    fresnel = {f: median_seconds(lambda g=jax.jit(lambda c, f=f: reflectance(c, method=f)): g(cos), repeats=7)
               for f in REFLECTANCE_METHODS}  # every entry of the family
    scene = Scene(8.0, 0.125, depth=2.0, stones=(StoneSpec(0.0, 0.0, 0.5, 0.02),))
    paths = jnp.asarray(np.random.default_rng(1).uniform(4.0, 5.0, 1_000_000), jnp.float32)

    @jax.jit
    def interpolate(path, table_d, table_rgb):
        return uniform_interp(path, table_d[0], table_d[-1], table_rgb)

    absorption = {}
    for m in WATER_TRANSMITTANCE_METHODS:  # every entry of the family
        table_d, table_rgb = (jnp.asarray(t, jnp.float32) for t in shading_table(scene, m))
        absorption[m] = median_seconds(lambda: interpolate(paths, table_d, table_rgb), repeats=7)
    progress("fresnel " + ", ".join(f"{k} {v * 1e3:.2f} ms" for k, v in fresnel.items()) + "; absorption "
             + ", ".join(f"{k} {v * 1e3:.2f} ms" for k, v in absorption.items()) + " per 1M pixels (compiled)")
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
        seconds = median_seconds(lambda: floor_irradiance_beam(eta, grid, 1.0, (-0.5, 0.0, 0.87), refine=r), repeats=3)
        table[n * r] = min(seconds, table.get(n * r, math.inf))
    cells = sorted(table)
    progress("caustics per frame: " + ", ".join(f"{c}² cells {table[c] * 1e3:.1f} ms" for c in cells))
    return dict(n=cells, seconds=[table[c] for c in cells])


def caustics_jacobian_seconds(progress=print) -> dict:
    """One frame's floor irradiance by the Jacobian gather (eager, as the planner's shading calls it),
    by the points it gathers a side (``"by": "points"``: a scene's texels × its supersampling, which
    the planner's screen records), on the beam table's surfaces with the floor at half their first
    fold (where the planner offers it), gathered at one point a texel on the surface's own samples
    (``supersample=1``, ``refine=1``; before, ``"auto"`` gathered 4 and 2 points a texel at 32² and
    64², so a smooth 64² scene was predicted at twice its cost); the median of 3 after one compiling
    call."""
    import jax.numpy as jnp

    from optics.caustics import first_fold_depth, floor_irradiance_jacobian
    from optics.caustics.surfaces import random_surface
    from wavephys.core.grid import Grid

    sizes = sorted({n for n, _ in CAUSTICS_CELLS} | {512, 1024})
    out = []
    for n in sizes:
        grid = Grid(n, 2.0)
        eta = jnp.asarray(random_surface(grid, "band", 0.08, 1), jnp.float32)
        sun = (-0.5, 0.0, 0.87)
        depth = 0.5 * first_fold_depth(eta, grid, sun)
        out.append(median_seconds(lambda: floor_irradiance_jacobian(eta, grid, depth, sun, fold="raise", supersample=1,
                                                                    refine=1), repeats=3))
    progress("jacobian caustics per frame: " + ", ".join(f"{n}² {t * 1e3:.1f} ms" for n, t in zip(sizes, out)))
    return dict(n=sizes, seconds=out, by="points")


TEXTURE_HEIGHTS = (1e-6, 1e-4, 1e-2, 1.0, 100.0)
"""RMS heights (m) the texture encodings are timed at: half floats of heights below 6e-5 m are
subnormal, which this CPU encodes about twice as slowly."""


def texture_seconds(progress=print, by_height: dict | None = None) -> dict:
    """Seconds per million texels of storing frames in each height texture format
    (:func:`wavephys.planner.runner.encode_texture`, as a run does), over 64 frames of 128²: the
    slowest over heights of every size (:data:`TEXTURE_HEIGHTS`), so that no scene's encoding is
    underestimated. ``by_height``: filled with each size's times, if given."""
    from wavephys.core.grid import Grid
    from wavephys.planner.model import TEXTURES
    from wavephys.planner.runner import encode_texture

    grid = Grid(128, 4.0)
    noise = np.random.default_rng(7).standard_normal((64, 128, 128))
    times = {}
    for rms in TEXTURE_HEIGHTS:
        frames = (rms * noise).astype(np.float32)
        times[rms] = {f: median_seconds(lambda: encode_texture(frames, f, grid), repeats=5) / (frames.size / 1e6)
                      for f in TEXTURES}
    out = {f: max(t[f] for t in times.values()) for f in TEXTURES}
    if by_height is not None:
        by_height.update({f"{rms:g}": t for rms, t in times.items()})
    progress("height texture per 1M texels (slowest over heights of 1e-6 to 100 m): "
             + ", ".join(f"{f} {t * 1e3:.2f} ms" for f, t in out.items()))
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
            out[name]["seconds"].append(median_seconds(lambda: surface_frames(model), repeats=3) / scene.frames)
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

    cal = cal or shipped()
    out = []
    for n in SHADE_SIZES:
        scene = Scene(4.0, 4.0 / n, depth=1.0, open_water=False, stones=(StoneSpec(0.0, 0.0, 0.5, 0.02),))
        model = SceneModel(scene)
        heights = 0.01 * np.random.default_rng(n).standard_normal((n, n))
        seconds = median_seconds(lambda: shade(scene, model, heights), repeats=5)
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

    from wavephys.planner.generate import generate_scenes
    from wavephys.planner.spectrum import scene_spectrum

    ratios = {}
    with tempfile.TemporaryDirectory() as tmp:
        files = {}
        for dtype in ("float32", "float64"):
            files[dtype] = Path(tmp) / f"{dtype}.npz"
            subprocess.run([sys.executable, "-c", _KAPPA_CHILD, str(count), str(seed), str(files[dtype]), dtype],
                           check=True, env={**os.environ, "PYTHONPATH": _package_root()})
        a, b = np.load(files["float32"]), np.load(files["float64"])
        for s in generate_scenes(count, seed=seed):
            ratios[s.name] = float(np.abs(a[s.name] - b[s.name]).max() / scene_spectrum(s).s0)
    worst = max(ratios.values())
    progress("kappa per scene: " + ", ".join(f"{k} {v:.2g}" for k, v in ratios.items()))
    return dict(kappa=4.0 * worst, measured=ratios)


TABLES = ("step", "step_walls", "step_symmetric", "ship", "ship_impulses", "frame", "optics", "run_overhead",
          "caustics", "caustics_jacobian", "shade", "texture", "surface", "kappa")
"""The names ``only=`` takes, in the order a full calibration measures them (``frame`` writes the
``frame``, ``blend`` and ``refine`` tables; ``optics`` the ``fresnel`` and ``absorption`` ones;
``kappa`` the ``kappa`` number and the ratios it came from)."""


def _measure(name: str, data: dict, progress) -> dict:
    """The entries of ``data`` table ``name`` replaces (later tables read earlier ones from ``data``)."""
    if name == "step":
        return {"step": step_seconds(progress)}
    if name == "step_walls":
        return {"step_walls": step_walls_seconds(progress, data["step"])}
    if name == "step_symmetric":
        return {"step_symmetric": step_symmetric_seconds(progress, data["step"])}
    if name in ("ship", "ship_impulses"):
        return {name: ship_seconds(progress, "kernels" if name == "ship" else "impulses")}
    if name == "frame":
        return dict(zip(("frame", "blend", "refine"), frame_seconds(progress)))
    if name == "optics":
        return dict(zip(("fresnel", "absorption"), optics_seconds(progress)))
    if name == "run_overhead":
        return {"run_overhead": overhead_seconds(progress, data["step"])}
    if name == "shade":
        return {"shade": shade_seconds(progress, data)}
    if name == "texture":
        by_height: dict = {}
        return dict(texture=texture_seconds(progress, by_height), texture_by_height=by_height)
    if name == "kappa":
        k = kappa(progress)
        return dict(kappa=k["kappa"], kappa_measured=k["measured"],
                    kappa_note="4 × the worst measured max|η32 − η64| / s0 over the scenes")
    return {name: globals()[f"{name}_seconds"](progress)}


def _device() -> str:
    import jax

    d = jax.devices()[0]
    kind = getattr(d, "device_kind", "")
    return d.platform if kind in ("", d.platform) else f"{d.platform} {kind}"


def calibrate(out, *, only=None, base=None, progress=None) -> dict:
    """Measure the planner's cost tables on this machine and write them to ``out`` (JSON, atomically).

    Parameters
    ----------
    out : str or os.PathLike
        The calibration file to write (``.json``; its folder must exist). Checked before any
        measurement starts.
    only : str or sequence of str, optional
        Measure these tables (:data:`TABLES`) alone and keep every other entry from ``base``
        (default: measure everything, several minutes on a 2-core CPU).
    base : dict or str or os.PathLike, optional
        With ``only``: the calibration the other tables come from (a dict as
        :func:`~wavephys.planner.cost.load_calibration` returns, or a file; default the shipped
        one). Tables derived from the step (``step_walls``, ``step_symmetric``,
        ``run_overhead``) scale ``base``'s step unless ``"step"`` is measured too.
    progress : callable, optional
        Called with one line of text per table measured (default: print to stderr).

    Returns
    -------
    dict
        The calibration written: every table, ``machine``, ``device``, ``date`` and, per
        table measured, ``<table>_date`` (with ``only``: the base's ``machine`` and ``date``
        stay, and ``<table>_machine`` says where each re-measured table was measured).

    Raises
    ------
    ValueError
        For an ``out`` that cannot be written, an unknown table, a ``base`` that is not a
        calibration, or a ``base`` without ``only`` (before measuring anything).

    Examples
    --------
    >>> from wavephys.planner import calibrate, load_calibration, plan, builtin_scene  # doctest: +SKIP
    >>> calibrate("here.json")                                                       # doctest: +SKIP
    >>> scene = builtin_scene("pond")                                                # doctest: +SKIP
    >>> plan(scene, scene.height_quantum, calibration=load_calibration("here.json"))  # doctest: +SKIP
    """
    from wavephys.core.files import atomic_path, output_file
    from wavephys.planner.cost import check_calibration, load_calibration

    path = output_file(out, "out", (".json",))
    if only is None and base is not None:
        raise ValueError("base: it is for only= (the tables not re-measured come from it); a full calibration "
                         "measures every table: drop base, or name the tables to measure with only=")
    if only is None:
        names = TABLES
        data: dict = {}
    else:
        if not isinstance(only, (str, list, tuple)):
            raise TypeError(f"only must be a table's name or a list of them (among {', '.join(TABLES)}), got "
                            f"{type(only).__name__}")
        names = (only,) if isinstance(only, str) else tuple(only)
        if not names or not all(isinstance(n, str) and n in TABLES for n in names):
            raise ValueError(f"only must name tables among {', '.join(TABLES)}, got {only!r}")
        names = tuple(n for n in TABLES if n in names)  # measured in dependency order
        if base is None:
            data = dict(shipped())
        elif isinstance(base, dict):
            data = dict(check_calibration(base, "base"))
        elif isinstance(base, (str, os.PathLike)) and str(base).strip():
            try:
                data = dict(load_calibration(base))
            except ValueError as exc:
                raise ValueError(f"base: {exc}") from None
        else:
            raise TypeError(f"base must be a calibration (a dict, or a file's path), got {type(base).__name__}")
        data.pop("source", None)
    if progress is None:
        def progress(line):
            print(line, file=sys.stderr, flush=True)
    elif not callable(progress):
        raise TypeError(f"progress must be callable (it is called with a line of text), got {type(progress).__name__}")
    today = time.strftime("%Y-%m-%d")
    for name in names:
        if name in ("step_walls", "step_symmetric", "run_overhead") and "step" not in data:
            raise ValueError(f"table {name!r} scales the step table, which base lacks: measure 'step' too")
        data.update(_measure(name, data, progress))
        data[f"{name}_date"] = today
    here = dict(machine=f"{platform.machine()} {os.cpu_count()} cores, Python {platform.python_version()}",
                device=_device())
    if only is None:
        data.update(here, date=today)
    else:  # the file stays the base's, with these tables from here
        data.update({f"{name}_machine": f"{here['machine']}, {here['device']}" for name in names})
    check_calibration(data, "the measured calibration")
    with atomic_path(path) as tmp:
        tmp.write_text(_dumps(data))
    return data


def _dumps(data: dict) -> str:
    """The calibration as the shipped file writes it (one-space indent)."""
    import json

    return json.dumps(data, indent=1)
