"""The ``wavephys`` command.

``wavephys validate [--json PATH] [--only NAME ...] [--x64]`` runs the built-in validations
(:mod:`wavephys.app.registry`) and prints quantity, expected, measured, error,
tolerance and verdict; exit status 1 if any fails. Progress goes to stderr.
``wavephys run`` simulates the built-in default scene (stones dropped into a pool with
an open-ocean margin) and writes the height field as ``.npz`` and a PNG figure.
``wavephys render --scene pool --out frame.png [--frames N]`` draws a built-in scene
with the headless moderngl renderer (frames go to a folder when N > 1).
``wavephys textures --scene pool --out DIR`` writes the scene's textures (heights,
normals, caustics, Fresnel and absorption lookups) as PNG, .npy and .npz.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path


def _progress(i: int, total: int, name: str, start: list) -> None:
    elapsed = time.perf_counter() - start[0]
    print(f"[{i + 1}/{total}] {name} … ({elapsed:.1f} s elapsed)", file=sys.stderr, flush=True)


def _table(rows) -> str:
    head = ("quantity", "expected", "measured", "error", "tolerance", "ok")
    lines = []
    for r in rows:
        tol = (f"+-{r.tolerance:.3g}{' rel' if r.relative else ''}" if r.relation == "~="
               else f"{r.relation} expected")
        err = "-" if r.error is None else f"{r.error:.3g}"
        lines.append((r.quantity + (f" [{r.unit}]" if r.unit else ""), f"{r.expected:.6g}",
                      f"{r.measured:.6g}", err, tol, "ok" if r.ok else "FAIL"))
    widths = [max(len(h), *(len(l[i]) for l in lines)) for i, h in enumerate(head)]
    fmt = "  ".join(f"{{:<{w}}}" for w in widths)
    out = [fmt.format(*head), fmt.format(*("-" * w for w in widths))]
    out += [fmt.format(*l) for l in lines]
    return "\n".join(out)


def cmd_validate(args) -> int:
    import jax

    if args.x64:
        jax.config.update("jax_enable_x64", True)
    from wavephys.app.registry import registry as get_registry

    registry = get_registry()
    if args.list:
        for name, fn in registry.items():
            print(f"{name:24s} {((fn.__doc__ or '').strip().splitlines() or [''])[0]}")
        return 0
    names = args.only or list(registry)
    unknown = [n for n in names if n not in registry]
    if unknown:
        print(f"unknown check(s) {unknown}; choose from {list(registry)}", file=sys.stderr)
        return 2
    start = [time.perf_counter()]
    rows = []
    for i, name in enumerate(names):
        _progress(i, len(names), name, start)
        rows.extend(registry[name]())
    print(_table(rows))
    failed = [r for r in rows if not r.ok]
    print(f"\n{len(rows) - len(failed)} passed, {len(failed)} failed "
          f"({time.perf_counter() - start[0]:.1f} s)")
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        Path(args.json).write_text(json.dumps([r.as_dict() for r in rows], indent=2))
        print(f"wrote {args.json}")
    return 1 if failed else 0


def cmd_run(args) -> int:
    import numpy as np

    from wavephys.app.scenes import default_scene

    start = time.perf_counter()
    result = default_scene(n=args.n, steps=args.steps, progress=lambda m: print(m, file=sys.stderr, flush=True))
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    np.savez_compressed(out / "surface.npz", eta=result["eta"], eta_dot=result["eta_dot"],
                        dx=result["dx"], time=result["time"], units="m, m/s, m, s")
    from wavephys.plot import plot_surface

    fig = plot_surface(result["eta"], result["dx"], title=f"default scene at t = {result['time']:.2f} s")
    fig.savefig(out / "surface.png", dpi=120)
    print(f"simulated {args.steps} steps on {args.n}² in {time.perf_counter() - start:.1f} s; "
          f"energy drift without the cutoff {result['energy_ratio'] - 1:.2e}; wrote {out}/surface.npz, "
          f"{out}/surface.png")
    return 0


EFFECTS = ("refraction", "reflection", "fresnel", "absorption", "caustics")


def cmd_render(args) -> int:
    from optics.rendering.renderer import Renderer, RendererUnavailable, render_sequence, save_png
    from wavephys.app.scenes import builtin_scene, scene_frames

    off = {e: False for e in args.off or []}
    start = time.perf_counter()
    try:
        renderer = Renderer(args.width, args.height, steps=args.steps)
    except RendererUnavailable as exc:
        print(f"wavephys render: {exc}", file=sys.stderr)
        return 3
    with renderer:
        if args.frames == 1:
            scene = builtin_scene(args.scene, n=args.n, time=args.time).with_effects(**off)
            path = save_png(renderer.render(scene), args.out)
            print(f"rendered {args.scene} ({args.width}×{args.height}, {renderer.renderer_name}) in "
                  f"{time.perf_counter() - start:.1f} s; wrote {path}")
            return 0
        out = Path(args.out)
        folder = out.with_suffix("") if out.suffix else out
        scenes = (s.with_effects(**off) for s in scene_frames(args.scene, args.frames, fps=args.fps, n=args.n,
                                                                  start=args.time))
        paths = render_sequence(renderer, scenes, folder, count=args.frames, video=args.video, fps=int(args.fps))
        print(f"rendered {len(paths)} frames of {args.scene} in {time.perf_counter() - start:.1f} s; wrote {folder}/")
    return 0


def cmd_textures(args) -> int:
    from optics.rendering.textures import export_scene
    from wavephys.app.scenes import builtin_scene

    paths = export_scene(builtin_scene(args.scene, n=args.n, time=args.time), args.out)
    for name, p in paths.items():
        print(f"{name:15s} {p}")
    return 0


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="wavephys", description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command")
    v = sub.add_parser("validate", help="run the built-in physics validations")
    v.add_argument("--json", metavar="PATH", help="also write the table as JSON")
    v.add_argument("--only", nargs="+", metavar="NAME", help="run only these checks (names from --list)")
    v.add_argument("--list", action="store_true", help="list the checks and exit")
    v.add_argument("--x64", action="store_true", help="run in float64")
    v.set_defaults(func=cmd_validate)
    r = sub.add_parser("run", help="simulate the built-in default scene")
    r.add_argument("--n", type=int, default=256, help="grid points per side (even)")
    r.add_argument("--steps", type=int, default=120, help="steps of 1/30 s")
    r.add_argument("--out", default="wavephys-out", help="output folder")
    r.set_defaults(func=cmd_run)
    from wavephys.app.scenes import SCENES

    g = sub.add_parser("render", help="render a built-in scene with the headless moderngl renderer")
    g.add_argument("--scene", choices=SCENES, default="pool")
    g.add_argument("--out", default="frame.png", help="PNG file (one frame) or folder (--frames > 1)")
    g.add_argument("--frames", type=int, default=1, help="number of frames (an animation when > 1)")
    g.add_argument("--fps", type=float, default=30.0, help="frames per second of the animation")
    g.add_argument("--time", type=float, default=1.0, help="scene time of the (first) frame, s")
    g.add_argument("--width", type=int, default=800)
    g.add_argument("--height", type=int, default=600)
    g.add_argument("--n", type=int, default=256, help="height-field texels per side")
    g.add_argument("--steps", type=int, default=256, help="ray-march steps")
    g.add_argument("--off", nargs="+", choices=EFFECTS, metavar="EFFECT",
                   help=f"switch effects off ({', '.join(EFFECTS)})")
    g.add_argument("--video", metavar="NAME", help="also write a video (needs imageio-ffmpeg), e.g. water.mp4")
    g.set_defaults(func=cmd_render)
    t = sub.add_parser("textures", help="export a built-in scene's textures")
    t.add_argument("--scene", choices=SCENES, default="pool")
    t.add_argument("--out", default="textures", help="output folder")
    t.add_argument("--n", type=int, default=256)
    t.add_argument("--time", type=float, default=1.0)
    t.set_defaults(func=cmd_textures)
    args = parser.parse_args(argv)
    if getattr(args, "frames", 1) < 1:
        parser.error(f"--frames must be ≥ 1, got {args.frames}")
    if args.command is None:
        parser.print_help()
        return 2
    return args.func(args)


if __name__ == "__main__":
    sys.exit(main())
