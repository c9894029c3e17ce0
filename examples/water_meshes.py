"""The water as engines draw it: a displaced mesh laid three ways, against the exact ray-marched surface.

    python examples/water_meshes.py --scene storm --out meshes.png

The scene is drawn four times with the same shading: by the ray-marcher (the exact bilinear surface) and as a
mesh laid by a uniform grid (one vertex a texel), clipmap rings (32 cells a level) and Johanson's projected grid
(one cell per 2 × 2 pixels). The picture puts them side by side with each one's error, ×10, below it; the script
prints each technique's cost (vertices, draw time on this machine) and its error per distance band in eye heights
(PSNR against the march, bare pixels where the mesh leaves water uncovered, the surface's height error). On the
storm the projected grid's nearest rows, lifted by the crests, leave the bottom of the screen bare: the failure
its margin (``projected_grid(margin=)``) exists for.
"""

from __future__ import annotations

import argparse

import numpy as np


def main(argv=None) -> None:
    from PIL import Image

    from optics.rendering import Renderer
    from optics.rendering.meshes import mesh_errors, water_mesh
    from optics.rendering.renderer import to_srgb8
    from wavephys.app.scenes import SCENES, builtin_scene

    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("--scene", default="storm", choices=SCENES)
    p.add_argument("--out", default="meshes.png")
    p.add_argument("--width", type=int, default=320)
    p.add_argument("--height", type=int, default=240)
    p.add_argument("--texels", type=int, default=128, help="the scene's texture size")
    args = p.parse_args(argv)
    scene = builtin_scene(args.scene, n=args.texels)
    w, h = args.width, args.height
    eye_h = scene.camera.eye[2] - float(np.mean(scene.water))  # distances are counted in eye heights
    tiles, errors = [], []
    with Renderer(w, h) as r:
        for technique, options in (("uniform", {}), ("clipmap", dict(cells=32)),
                                   ("projected", dict(columns=w // 2, rows=h // 2, aspect=w / h))):
            mesh = water_mesh(scene, technique, **options)
            res = mesh_errors(scene, mesh, w, h, renderer=r)
            print(f"{technique}: {mesh.vertices:,} vertices, {res['mesh_seconds'] * 1e3:.0f} ms a frame (the march "
                  f"{res['march_seconds'] * 1e3:.0f} ms), {res['psnr']:.1f} dB, {res['bare']} bare pixels")
            for b in res["bands"]:
                if b["pixels"]:
                    lo, hi = b["lo"] / eye_h, b["hi"] / eye_h
                    heights = (f"height error ≤ {b['height_max']:.3g} m" if b["height_max"] == b["height_max"]
                               else "beyond the mesh: the far field, drawn alike")
                    print(f"    r/H {lo:5.0f}–{hi:<5.0f} {b['pixels']:6d} px  {b['psnr']:6.1f} dB  bare {b['bare']:5d}  "
                          f"{heights}")
            tiles.append(to_srgb8(res["image"]))
            errors.append(to_srgb8(np.clip(10 * np.abs(res["image"] - res["reference"]), 0, 1)))
        tiles.insert(0, to_srgb8(res["reference"]))
        errors.insert(0, np.zeros_like(errors[0]))
    strip = np.concatenate([np.concatenate(tiles, axis=1), np.concatenate(errors, axis=1)], axis=0)
    Image.fromarray(strip).save(args.out)
    print(f"wrote {args.out}: the march, uniform, clipmap, projected; their errors ×10 below")


if __name__ == "__main__":
    main()
