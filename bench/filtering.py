"""Distance filtering of the normals against a supersampled reference, per distance band.

For each scene whose water is tiled to the horizon, two frames at one sample per pixel — the normals
unfiltered (as drawn before filtering) and filtered (:mod:`optics.rendering.filtering`) — are compared
with the *truth*: the same world drawn unfiltered at ``ss × ss`` samples per pixel and averaged,
its waves never faded (the water tiled into a square ``TILES`` scene sides wide, so the fade and the
flat far field start beyond the bands measured) and marched with ``TRUTH_STEPS`` steps. Errors are
taken per band of the distance at which each pixel's ray meets the mean water level, in scene
sides, in the max norm and RMS (linear RGB clipped to [0, 1]) and as PSNR. Caustics and foam are off
in every frame (their maps fade differently from the waves). Frame costs are interleaved medians.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np

from bench.timing import interleaved, paired_ratio
from optics.rendering.reference import psnr, ray_directions
from optics.rendering.renderer import Renderer
from optics.rendering.scene import FAR_TILES, NEAR_TILES, texture_sample
from wavephys.app.scenes import builtin_scene
from wavephys.core.grid import Grid

TILES = 9
"""The truth's square, in scene sides (odd: its texel centres fall on the scene's)."""
TRUTH_STEPS = 1024
BANDS = ((0.0, 0.5), (0.5, 1.0), (1.0, NEAR_TILES), (NEAR_TILES, 2.5), (2.5, FAR_TILES), (FAR_TILES, 8.0))
"""Distance bands, scene sides from the eye (horizontal) to where the ray meets the mean water level; the
waves fade between NEAR_TILES and FAR_TILES in the frames measured; the last band is their flat far field."""
SCENES = ("storm", "shore", "wakebeach")


def truth_scene(scene, tiles: int = TILES):
    """The scene's world with its waves never faded out to ``tiles``·NEAR_TILES/2 sides: the water tiled
    ``tiles`` × ``tiles`` times, the ground and albedo resampled (clamped, as drawn) on the same texels."""
    ny, nx = scene.water.shape
    big = tiles * scene.length
    X, Y = (np.asarray(a, np.float64) for a in Grid(tiles * nx, big).mesh())
    water = np.tile(np.asarray(scene.water, np.float32), (tiles, tiles))

    def resample(field):
        return texture_sample(np.asarray(field, np.float64), scene.length, X, Y).astype(np.float32)

    albedo = scene.albedo if scene.albedo is not None else scene.default_albedo
    albedo = np.stack([resample(np.asarray(albedo)[..., c]) for c in range(3)], axis=-1) \
        if np.ndim(albedo) == 3 else albedo
    return replace(scene, water=water, ground=resample(scene.ground), albedo=albedo, length=big)


def _downsample(image, ss):
    h, w = image.shape[0] // ss, image.shape[1] // ss
    return image.reshape(h, ss, w, ss, 3).mean(axis=(1, 3))


def band_errors(image, truth, distance) -> list[dict]:
    """Max, RMS and PSNR of ``image`` against ``truth`` per band of ``distance`` (scene sides)."""
    rows = []
    a, b = np.clip(image, 0, 1), np.clip(truth, 0, 1)
    for lo, hi in BANDS:
        mask = (distance >= lo) & (distance < hi)
        if mask.sum() < 20:
            continue
        e = np.abs(a[mask] - b[mask])
        rows.append(dict(band=(lo, hi), pixels=int(mask.sum()), max=float(e.max()),
                         rms=float(np.sqrt(np.mean(e ** 2))), psnr=psnr(a[mask], b[mask])))
    return rows


def filtering_rows(width: int = 240, height: int = 180, ss: int = 4, names=SCENES, repeats: int = 5,
                   progress=print) -> list[dict]:
    """Per scene and band: the unfiltered and filtered frames' error against the supersampled truth,
    and the filtered frame's cost against the unfiltered one (interleaved)."""
    rows = []
    for name in names:
        progress(f"{name}: building the scene …")
        base = builtin_scene(name, progress=name == "wakebeach")
        if base.surroundings != "tile":
            continue
        base = base.with_effects(caustics=False, foam=False)
        off = base.with_effects(filtering=False)
        d = ray_directions(base.camera, width, height)
        eye = np.asarray(base.camera.eye, float)
        level = float(np.mean(base.water, dtype=np.float64))
        with np.errstate(divide="ignore"):
            t = np.where(d[..., 2] < 0, (level - eye[2]) / d[..., 2], np.inf)
        distance = t * np.hypot(d[..., 0], d[..., 1]) / base.length
        texels = t * 2 * math.tan(math.radians(base.camera.fov) / 2) / height / (base.length / min(base.water.shape))
        progress(f"{name}: the truth, {ss}×{ss} samples per pixel, {TRUTH_STEPS} steps …")
        truth_world = truth_scene(off)
        with Renderer(width * ss, height * ss, steps=TRUTH_STEPS) as r:
            truth = _downsample(r.render(truth_world), ss)
        with Renderer(width, height) as r:
            frames = {"unfiltered": r.render(off), "filtered": r.render(base)}
            progress(f"{name}: frame times, interleaved …")
            times = interleaved({"unfiltered": lambda: r.draw(off), "filtered": lambda: r.draw(base)},
                                repeats=repeats, warmup=1, block=1)
        ratio = paired_ratio(times, "filtered", ["unfiltered"])
        for method, image in frames.items():
            for b in band_errors(image, truth, distance):
                inside = (distance >= b["band"][0]) & (distance < b["band"][1])
                rows.append(dict(family="filtering", scene=name, method=method, width=width, height=height, ss=ss,
                                 footprint_texels=float(np.median(texels[inside])),
                                 seconds=float(np.median(times[method])),
                                 cost_ratio=ratio[0] if method == "filtered" else 1.0, **b))
    return rows


def figures(rows) -> dict:
    """Error against distance band per scene, unfiltered and filtered (max and RMS)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = sorted({r["scene"] for r in rows})
    if not names:
        return {}
    fig, axes = plt.subplots(1, len(names), figsize=(4.2 * len(names), 3.4), squeeze=False)
    for ax, name in zip(axes[0], names):
        for method, colour in (("unfiltered", "tab:red"), ("filtered", "tab:blue")):
            sel = [r for r in rows if r["scene"] == name and r["method"] == method]
            x = [0.5 * (r["band"][0] + r["band"][1]) for r in sel]
            ax.plot(x, [r["max"] for r in sel], "o-", color=colour, label=f"{method}, max")
            ax.plot(x, [r["rms"] for r in sel], "s--", color=colour, label=f"{method}, RMS")
        ax.axvspan(NEAR_TILES, FAR_TILES, color="0.9", zorder=0)
        ax.set_yscale("log")
        ax.set_xlabel("distance, scene sides (grey: waves fading)")
        ax.set_ylabel("error against the supersampled truth")
        ax.set_title(name)
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    return {"error_vs_distance": fig}
