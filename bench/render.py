"""Renderer benchmark: frame times by screen coverage and effect (Baboud & Décoret's Table 1
layout), texture-generation cost per frame, and each effect's cost and effect on the image.

On this machine the GPU is Mesa llvmpipe (the CPU); the absolute rates are not a GPU's,
but the ratios between effects and coverages are comparable with the paper's
(26/20/15 Hz at 100 % coverage on a GeForce 7800: +reflection ×0.77, +caustics ×0.58).
"""

from __future__ import annotations

import math
import time

import numpy as np

from bench.timing import interleaved, median_seconds, paired_ratio
from optics.rendering.reference import _box, psnr, ray_directions, trace
from optics.rendering.renderer import Renderer
from optics.rendering.scene import Effects, look_at
from wavephys.app.scenes import SCENES, builtin_scene

MODES = {"refraction": Effects(reflection=False, caustics=False),
         "+ reflection": Effects(caustics=False),
         "+ caustics": Effects()}
PAPER_HZ = {100: (26, 20, 15), 50: (45, 36, 23), 25: (87, 69, 34)}


def coverage(scene, width: int, height: int) -> float:
    """Fraction of pixels whose view ray enters the water volume's box."""
    d = ray_directions(scene.camera, width, height).reshape(-1, 3)
    o = np.broadcast_to(np.asarray(scene.camera.eye, float), d.shape)
    t0, t1 = _box(scene, o, d)
    return float(np.mean(t1 > t0))


def camera_for_coverage(scene, target: float, width: int, height: int):
    """An oblique (45°) camera whose view of the volume covers ``target`` of the screen."""
    def cam(dist):
        return look_at((0.0, -dist / math.sqrt(2), dist / math.sqrt(2)), (0.0, 0.0, 0.0), 50.0)

    lo, hi = 0.05 * scene.length, 20.0 * scene.length  # coverage falls with distance
    if target >= 1.0:
        target = 0.9999
    for _ in range(40):
        mid = math.sqrt(lo * hi)
        if coverage(scene.with_camera(cam(mid)), width, height) >= target:
            lo = mid
        else:
            hi = mid
    return cam(lo)


def frame_rows(width: int = 800, height: int = 600, repeats: int = 7, progress=print) -> list[dict]:
    from dataclasses import replace

    full = builtin_scene("ship", n=256)
    scene = replace(full, surroundings="none")  # a water volume in a box, as in the paper's table
    rows = []
    with Renderer(width, height) as r:
        progress(f"frames {width}×{height}: to the horizon against the box alone, interleaved …")
        times = interleaved({"box": lambda: r.draw(scene), "horizon": lambda: r.draw(full)}, repeats=repeats,
                            warmup=1, block=1)
        ratio = paired_ratio(times, "horizon", ["box"])
        rows.append(dict(family="horizon cost", scene="ship", surroundings=full.surroundings,
                         seconds=float(np.median(times["horizon"])), baseline_seconds=float(np.median(times["box"])),
                         ratio=ratio[0], ratio_quartiles=ratio[1:], width=width, height=height))
        for pct in (100, 50, 25):
            cam = camera_for_coverage(scene, pct / 100, width, height)
            s = scene.with_camera(cam)
            measured = coverage(s, width, height)
            progress(f"frames {width}×{height}, {pct} % coverage, the three modes interleaved …")
            scenes = {mode: s.with_effects(**eff.__dict__) for mode, eff in MODES.items()}
            times = interleaved({m: (lambda sc=sc: r.draw(sc)) for m, sc in scenes.items()}, repeats=repeats,
                                warmup=1, block=1)
            for i, mode in enumerate(MODES):
                sec = float(np.median(times[mode]))
                ratio = paired_ratio(times, "refraction", [mode]) if i else (1.0, 1.0, 1.0)
                rows.append(dict(family="frame", coverage=pct, measured_coverage=measured, mode=mode, seconds=sec,
                                 hz=1 / sec, ratio_to_refraction=ratio[0], ratio_quartiles=ratio[1:],
                                 renderer=r.renderer_name, paper_hz=PAPER_HZ[pct][i],
                                 paper_ratio=PAPER_HZ[pct][i] / PAPER_HZ[pct][0], width=width, height=height))
    return rows


def texture_rows(sizes=(512, 1024), progress=print) -> list[dict]:
    """Per-frame texture work at N: simulation step, normals, caustics, 16-bit encode, upload."""
    import jax

    from optics.caustics import floor_irradiance
    from optics.rendering.textures import encode_height, normal_map
    from wavephys import Grid, Simulation, Stones, Water

    rows = []
    with Renderer(8, 8) as r:
        for n in sizes:
            progress(f"texture generation at N = {n} …")
            grid = Grid(n, 16.0)
            sim = Simulation(grid, Water(), dt=1 / 30, margin=n // 8)
            state = sim.drop(sim.initial_state(), Stones([0.0], [0.0], [0.3], [0.05]))
            state, _ = sim.step(state)
            eta = sim.surface(state).eta
            eta_np = np.asarray(eta)
            work = {
                "simulation step": lambda: sim.step(state)[0].fields,
                "normals (spectral)": lambda: normal_map(eta_np, grid),
                "caustics (beam, refine=1)": lambda: floor_irradiance(eta, grid, 2.0, (0.3, -0.4, 0.87), refine=1),
                "caustics (beam, default refine=3)": lambda: floor_irradiance(eta, grid, 2.0, (0.3, -0.4, 0.87)),
                "16-bit encode": lambda: encode_height(eta_np, grid, 16).data,
                "upload (float32)": lambda: r.texture("water", eta_np) and r.ctx.finish(),
            }
            step = None
            for name, fn in work.items():
                sec = median_seconds(fn, repeats=5)
                step = step or sec
                rows.append(dict(family="textures", n=n, work=name, seconds=sec, ratio_to_step=sec / step))
            jax.clear_caches()
    return rows


def half_float_rows(sizes=(512, 1024), repeats: int = 7, progress=print) -> list[dict]:
    """16-bit float encoding per frame: numpy's ``astype(float16)`` (what a user writes) against
    :func:`wavephys.core.halffloat.to_float16`, for heights of every size: a swell (0.5 m), a ripple tank
    (1 mm), calm water (20 µm: float16 subnormals) and float32 and float64 input."""
    from wavephys.core.halffloat import to_float16

    rows = []
    rng = np.random.default_rng(0)
    for n in sizes:
        for label, scale in (("swell, 0.5 m", 0.5), ("ripples, 1 mm", 1e-3), ("calm, 20 um (subnormal)", 2e-5)):
            for dtype in (np.float32, np.float64):
                h = (scale * rng.standard_normal((n, n))).astype(dtype)
                base = median_seconds(lambda: h.astype(np.float16), repeats=repeats)
                ours = median_seconds(lambda: to_float16(h), repeats=repeats)
                same = bool(np.array_equal(to_float16(h).view(np.uint16), h.astype(np.float16).view(np.uint16)))
                rows.append(dict(family="half float", n=n, heights=label, dtype=np.dtype(dtype).name,
                                 numpy_seconds=base, seconds=ours, ratio=ours / base, identical=same))
                progress(f"N = {n} {label} {np.dtype(dtype).name}: numpy {base * 1e3:.2f} ms, to_float16 "
                         f"{ours * 1e3:.2f} ms, identical bits: {same}")
    return rows


def agreement_rows(width: int = 320, height: int = 240, repeats: int = 5, progress=print) -> list[dict]:
    """PSNR of the GPU image against the CPU reference, per scene and effect; and each
    effect's effect (PSNR of the frame with it off against all on) and its cost (frame
    time with it off / all on, the six frames timed interleaved)."""
    rows = []
    offs = (None, "refraction", "reflection", "fresnel", "absorption", "caustics")
    with Renderer(width, height) as r:
        for name in SCENES:
            scene = builtin_scene(name, n=256)
            variants = {off or "none": scene if off is None else scene.with_effects(**{off: False}) for off in offs}
            progress(f"agreement {name}: timing the six variants interleaved …")
            times = interleaved({k: (lambda s=s: r.draw(s)) for k, s in variants.items()}, repeats=repeats,
                                warmup=1, block=1)
            full = r.render(scene)
            for off, s in variants.items():
                progress(f"agreement {name}, off = {off} …")
                gpu = r.render(s)
                t = time.perf_counter()
                ref = trace(s, width, height)
                ref_s = time.perf_counter() - t
                converged = trace(s, width, height, steps=1024) if off == "none" else None
                cost = paired_ratio(times, off, ["none"])
                rows.append(dict(family="agreement", scene=name, off=off, psnr=psnr(gpu, ref),
                                 psnr_vs_converged=None if converged is None else psnr(gpu, converged),
                                 effect_psnr=None if off == "none" else psnr(gpu, full),
                                 frame_seconds=float(np.median(times[off])),
                                 full_frame_seconds=float(np.median(times["none"])),
                                 cost_ratio=cost[0], cost_quartiles=cost[1:],
                                 reference_seconds=ref_s, width=width, height=height))
    return rows


def figures(rows) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figs = {}
    frames = [r for r in rows if r["family"] == "frame"]
    if frames:
        fig, ax = plt.subplots(figsize=(6, 4))
        for mode in MODES:
            rs = [r for r in frames if r["mode"] == mode]
            ax.plot([r["coverage"] for r in rs], [r["hz"] for r in rs], "o-", label=f"{mode} (llvmpipe)")
        ax.set_xlabel("screen coverage (%)")
        ax.set_ylabel("frames per second")
        ax.set_title(f"{frames[0]['width']}×{frames[0]['height']} on {frames[0]['renderer'].split(' (')[0]}")
        ax.legend(fontsize=8)
        figs["frames"] = fig
    agree = [r for r in rows if r["family"] == "agreement" and r["off"] != "none"]
    if agree:
        fig, ax = plt.subplots(figsize=(6, 4))
        for name in SCENES:
            rs = [r for r in agree if r["scene"] == name]
            ax.plot([r["cost_ratio"] for r in rs], [min(r["effect_psnr"], 80) for r in rs], "o", label=name)
            for r in rs:
                ax.annotate(r["off"], (r["cost_ratio"], min(r["effect_psnr"], 80)), fontsize=6)
        ax.set_xlabel("frame time with the effect off / all effects on")
        ax.set_ylabel("PSNR against all effects on (dB; 80 = no change)")
        ax.set_title("what each effect costs and changes")
        ax.legend(fontsize=8)
        figs["effects"] = fig
    return figs
