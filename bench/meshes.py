"""The mesh path's techniques against the ray-marcher, per distance band, with their cost
(``python -m bench meshes``): each built-in scene drawn by a uniform grid, clipmap rings and a
projected grid at several densities (:mod:`optics.rendering.meshes`), its image against the march's
(PSNR, the 99th percentile of the pixel error, bare pixels) and its surface against the texture's
(max height error), per band of distance from the eye in eye heights; the cost in vertices,
triangles and draw time on this machine. ``docs/meshes.md`` is written from the rows: which
technique, at the fewest vertices, keeps a band within each PSNR budget on every scene measured.
"""

from __future__ import annotations

import math
import platform
import time

import numpy as np

SCENES = ("storm", "shore", "beach", "harbour")
"""The built-in scenes measured (open sea, tiled shore, beach, harbour with its quay)."""

SETTINGS = (("uniform", "spacing ×1", dict(spacing=1)), ("uniform", "spacing ×2", dict(spacing=2)),
            ("uniform", "spacing ×4", dict(spacing=4)),
            ("clipmap", "16 cells", dict(cells=16)), ("clipmap", "32 cells", dict(cells=32)),
            ("clipmap", "64 cells", dict(cells=64)),
            ("projected", "80×60", dict(columns=80, rows=60)), ("projected", "160×120", dict(columns=160, rows=120)),
            ("projected", "320×240", dict(columns=320, rows=240)),
            ("projected", "160×120 margin 0.5", dict(columns=160, rows=120, margin=0.5)))
"""Each technique at three densities: spacings in texels (uniform; the clipmap's finest level is one
texel), rings of 2·cells cells a side, projected grids of columns × rows cells (margin 0.1)."""

CHOPPY = (("uniform", "spacing ×1 choppy", dict(spacing=1)), ("clipmap", "64 cells choppy", dict(cells=64)))
"""Settings drawn on scenes with a choppy displacement (the storm) with their vertices moved by it, as
engines move them (:func:`optics.rendering.meshes.displaced_mesh`); reported, never recommended (they
need the displacement, which the other scenes lack)."""
TIME = 1.0
"""The second of each scene drawn (its heights and its displacement alike)."""

BUDGETS = (40.0, 50.0, 60.0)
"""The PSNR budgets (dB, per band, against the march) the docs table answers."""


def _mesh(scene, technique, options, width, height):
    from optics.rendering.meshes import water_mesh
    from optics.rendering.meshes import _texel

    opts = dict(options)
    if technique == "uniform":
        opts["spacing"] = opts["spacing"] * _texel(scene)
    if technique == "projected":
        opts["aspect"] = width / height
    return water_mesh(scene, technique, **opts)


def mesh_rows(names=SCENES, n: int = 128, width: int = 320, height: int = 240, settings=SETTINGS, repeats: int = 3,
              progress=None) -> list:
    """One row per scene, setting and distance band (keys in the module doc and
    :func:`optics.rendering.meshes.mesh_errors`); the march's time is measured in the same run."""
    from optics.rendering import Renderer
    from optics.rendering.meshes import displaced_mesh, mesh_errors
    from wavephys.app.scenes import builtin_scene, scene_displacement

    rows = []
    with Renderer(width, height) as r:
        for name in names:
            scene = builtin_scene(name, n=n, time=TIME)
            eye_h = float(scene.camera.eye[2]) - float(np.mean(scene.water, dtype=np.float64))
            disp = scene_displacement(name, n=n, time=TIME)
            runs = [(s, False) for s in settings] + [(s, True) for s in (CHOPPY if disp is not None else ())]
            for (technique, label, options), choppy in runs:
                t0 = time.perf_counter()
                mesh = _mesh(scene, technique, options, width, height)
                if choppy:
                    mesh = displaced_mesh(scene, mesh, disp)
                res = mesh_errors(scene, mesh, width, height, renderer=r, repeats=repeats)
                for b in res["bands"]:
                    rows.append(dict(scene=name, technique=technique, setting=label, choppy=choppy, n=n, width=width,
                                 height=height,
                                     vertices=res["vertices"], triangles=res["triangles"],
                                     texel_reads=res["texel_reads"], passes=res["passes"],
                                     mesh_seconds=res["mesh_seconds"], march_seconds=res["march_seconds"],
                                     image_psnr=res["psnr"], image_bare=res["bare"], eye_height=eye_h,
                                     band=(b["lo"] / eye_h, b["hi"] / eye_h), **{k: b[k] for k in (
                                         "pixels", "water", "psnr", "max", "p99", "bare", "height_max", "height_rms")}))
                if progress:
                    progress(f"{name} {technique} {label}: {res['vertices']} vertices, {res['psnr']:.1f} dB, "
                             f"{res['bare']} bare, {res['mesh_seconds'] * 1e3:.0f} ms (march "
                             f"{res['march_seconds'] * 1e3:.0f} ms), {time.perf_counter() - t0:.1f} s")
    return rows


def recommendations(rows, budgets=BUDGETS) -> list:
    """For each distance band and PSNR budget, the setting with the fewest vertices whose band PSNR is
    at least the budget on every scene measured that has pixels there, and no bare pixels in it
    (None when no setting measured does)."""
    bands = sorted({tuple(r["band"]) for r in rows})
    settings = list(dict.fromkeys((r["technique"], r["setting"]) for r in rows
                                  if not r.get("choppy", r["setting"].endswith("choppy"))))
    out = []
    for band in bands:
        here = [r for r in rows if tuple(r["band"]) == band and r["water"] > 0]
        if not here:
            continue
        for budget in budgets:
            best = None
            for tech, label in settings:
                mine = [r for r in here if (r["technique"], r["setting"]) == (tech, label)]
                if {r["scene"] for r in mine} != {r["scene"] for r in here}:
                    continue  # not measured on every scene with water here (the choppy settings: the storm alone)
                if any(not (r["psnr"] >= budget) or r["bare"] for r in mine):
                    continue
                verts = max(r["vertices"] for r in mine)
                if best is None or verts < best[2]:
                    best = (tech, label, verts, min(r["psnr"] for r in mine), sorted({r["scene"] for r in mine}))
            out.append(dict(band=band, budget=budget, technique=best[0] if best else None,
                            setting=best[1] if best else None, vertices=best[2] if best else None,
                            worst_psnr=best[3] if best else None, scenes=best[4] if best else
                            sorted({r["scene"] for r in here})))
    return out


def _band(band) -> str:
    lo, hi = band
    return f"{lo:g}–{hi:g} H" if math.isfinite(hi) else f"> {lo:g} H"


def markdown(rows, command: str) -> str:
    """docs/meshes.md from the rows (module doc)."""
    recs = recommendations(rows)
    scenes = sorted({r["scene"] for r in rows})
    lines = ["# Drawing the water as a mesh: which technique for which distance and budget",
             "",
             f"Generated by `{command}` on {time.strftime('%Y-%m-%d')} ({platform.machine()}, "
             f"{rows[0]['width']}×{rows[0]['height']} pixels, {rows[0]['n']}² textures, Mesa llvmpipe); do not edit by "
             "hand. The techniques are `optics.rendering.meshes` (docs/guide.md, \"The mesh path\"): each "
             "built-in scene below is drawn by the mesh and by the ray-marcher with the same shading, so the "
             "difference is where the surface is. A distance band is where a pixel's view ray meets the mean "
             "water level, in eye heights H above it (r/H). PSNR is over the band's pixels against the march; "
             "*bare* pixels are water the march sees and the mesh does not cover.",
             "",
             f"Scenes: {', '.join(scenes)}. A setting is recommended for a band and budget only if it met the "
             "budget, with no bare pixel, on every scene with water in the band (bands where no scene shows water are "
             "left out); \"none measured\" means no "
             "setting did, not that none could. The storm's *choppy* rows move the vertices by its choppy "
             "displacement as engines do (`displaced_mesh`); they are reported, not recommended (the other scenes "
             "have no displacement).",
             "",
             "The chart (`bench/figures/meshes_chart.png`, written beside the rows' JSON) shows each setting's "
             "worst band PSNR against distance, and its image PSNR against its vertices.",
             "",
             "## Fewest vertices within a budget, per distance band",
             "",
             "| band | " + " | ".join(f"≥ {b:g} dB" for b in BUDGETS) + " |",
             "| --- | " + " | ".join("---" for _ in BUDGETS) + " |"]
    for band in sorted({tuple(r["band"]) for r in recs}):
        cells = []
        for budget in BUDGETS:
            rec = next(r for r in recs if tuple(r["band"]) == band and r["budget"] == budget)
            cells.append(f"{rec['technique']} {rec['setting']} ({rec['vertices']:,} vertices; worst "
                         f"{rec['worst_psnr']:.1f} dB)" if rec["technique"] else "none measured")
        lines.append(f"| {_band(band)} | " + " | ".join(cells) + " |")
    lines += ["", "## Every measurement", "",
              "| scene | technique | setting | vertices | texel reads | mesh ms | march ms | band | water px | PSNR dB "
              "| p99 | bare | height max m |",
              "| --- | --- | --- | ---: | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: |"]
    for r in rows:
        if not r["water"]:
            continue
        hm = f"{r['height_max']:.3g}" if r["height_max"] == r["height_max"] else "–"
        reads = f"{r['texel_reads']:,}" if "texel_reads" in r else "–"
        lines.append(f"| {r['scene']} | {r['technique']} | {r['setting']} | {r['vertices']:,} | {reads} | "
                     f"{r['mesh_seconds'] * 1e3:.0f} | {r['march_seconds'] * 1e3:.0f} | {_band(r['band'])} | "
                     f"{r['water']} | {r['psnr']:.1f} | {r['p99']:.2g} | {r['bare']} | {hm} |")
    lines += ["", "Times are llvmpipe's on this machine (a CPU rasterizer: the shading, the same in both paths, "
              "dominates); vertices and triangles are what carries over to a GPU. The uniform grid's spacing is in "
              "texels; the clipmap's finest level is one texel; projected grids have a margin of 0.1 of the screen unless "
              "the setting says otherwise.",
              ""]
    return "\n".join(lines)


def figures(rows) -> dict:
    """Error against distance (band PSNR, worst scene) and against cost (vertices), per technique."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (a, b) = plt.subplots(1, 2, figsize=(11, 4))
    settings = list(dict.fromkeys((r["technique"], r["setting"]) for r in rows))
    colours = {"uniform": "tab:blue", "clipmap": "tab:orange", "projected": "tab:green"}
    all_bands = sorted({tuple(r["band"]) for r in rows if r["water"]})
    for tech, label in settings:
        mine = [r for r in rows if (r["technique"], r["setting"]) == (tech, label) and r["water"]]
        bands = sorted({tuple(r["band"]) for r in mine})
        x = [all_bands.index(bd) for bd in bands]
        y = [min(min(r["psnr"], 120.0) for r in mine if tuple(r["band"]) == bd) for bd in bands]
        mine_labels = [lab for t, lab in settings if t == tech]
        k = mine_labels.index(label)
        a.plot(x, y, "o-", color=colours[tech], alpha=0.35 + 0.65 * k / max(len(mine_labels) - 1, 1),
               label=f"{tech} {label}")
        verts = max(r["vertices"] for r in mine)
        b.scatter([verts], [min(min(r["image_psnr"], 120.0) for r in mine)], color=colours[tech])
        b.annotate(label, (verts, min(min(r["image_psnr"], 120.0) for r in mine)), fontsize=7)
    a.set_xticks(range(len(all_bands)), [_band(bd) for bd in all_bands])
    a.set_xlabel("distance band, eye heights H above the water")
    a.set_ylabel("PSNR against the march, worst scene (dB)")
    a.legend(fontsize=6)
    b.set_xscale("log")
    b.set_xlabel("vertices")
    b.set_ylabel("image PSNR, worst scene (dB)")
    fig.tight_layout()
    return {"chart": fig}
