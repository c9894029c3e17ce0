"""The wavephys command: validate the physics, simulate the default scene, render, export textures.

Its subcommands, their one-line help, descriptions and exit codes are one table, :data:`COMMANDS`; each
``--help`` is generated from it (``wavephys --help`` lists them).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

from wavephys.app.commands import COMMANDS, INTERRUPTED, NO_OPENGL, USAGE_ERROR, Command  # noqa: F401


def _overview() -> str:
    """``wavephys --help``'s description: each subcommand in a line."""
    width = max(len(c.usage) for c in COMMANDS.values())
    return (__doc__.splitlines()[0] + "\n\n" +
            "\n".join(f"  {c.usage:<{width}}  {c.help}" for c in COMMANDS.values()))


EXIT_CODES = """exit status: each command's --help gives its own (wavephys COMMAND --help); 2 is always a usage
error (a bad option or output path, said before any work starts)."""
"""``wavephys --help``'s exit-status line (each subcommand's own: :attr:`Command.epilog`)."""


def _subcommand(sub, name: str, fmt, description: str | None = None):
    """The subparser of :data:`COMMANDS`' ``name``: its help, description and exit codes from the table."""
    import textwrap

    c = COMMANDS[name]
    return sub.add_parser(name, help=c.help, description=textwrap.fill(description or c.description, 100),
                          epilog=c.epilog(), formatter_class=fmt)


EFFECTS = ("refraction", "reflection", "fresnel", "absorption", "caustics", "filtering")
from wavephys.app import SCENES  # light: --help answers at once


class _Parser(argparse.ArgumentParser):
    """Usage errors on one line, exit status 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message} (see '{self.prog} --help')\n")


def _int(lo: int, even: bool = False, hi: int | None = None):
    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None
        if value < lo or (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(f"must be ≥ {lo}" + (f" and ≤ {hi}" if hi is not None else "") +
                                             f", got {value}")
        if even and value % 2:
            raise argparse.ArgumentTypeError(f"must be even, got {value}")
        return value

    parse.limits = (lo, hi, False)  # for the tests: the documented range (lo, hi, lo excluded)
    return parse


def _float(lo: float, open_lo: bool = False, hi: float | None = None):
    def parse(text: str) -> float:
        from wavephys.harness.claims import parse_number

        try:
            value = parse_number(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number (0.05, 2/256), got {text!r}") from None
        if not math.isfinite(value) or value < lo or (open_lo and value == lo) or (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(f"must be a finite number {'>' if open_lo else '≥'} {lo}"
                                             + (f" and ≤ {hi:g}" if hi is not None else "") + f", got {text}")
        return value

    parse.limits = (lo, hi, open_lo)

    return parse


def _real(text: str) -> float:
    """Any finite number (a signed angle, a time offset); fractions accepted."""
    from wavephys.harness.claims import parse_number

    try:
        value = parse_number(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(f"must be a finite number, got {text}")
    return value


MAX_N, MAX_TIME, MAX_FPS, MAX_STEPS = 8192, 3600.0, 1000.0, 10**6  # wavephys.app.scenes' limits (light: --help)


def _checked(parser, check, *args):
    """Run a path check; a bad path is a usage error (one line, exit 2)."""
    try:
        return check(*args)
    except (TypeError, ValueError) as exc:
        parser.error(str(exc))


def _progress(i: int, total: int, name: str, start: float) -> None:
    print(f"[{i + 1}/{total}] {name} ... ({time.perf_counter() - start:.1f} s elapsed)", file=sys.stderr, flush=True)


def _rule(r) -> str:
    """What the row asks, in one cell: "~= 0.2312 +-5e-05" or "<= 0.001"."""
    if r.relation == "~=":
        return f"~= {r.expected:.6g} +-{r.tolerance:.2g}{' rel' if r.relative else ''}"
    return f"{r.relation} {r.expected:.6g}"


def _table(rows, width: int | None = None) -> str:
    """The rows as a table that fits ``width`` columns (default: the terminal, at most 100):
    quantity (wrapped), the rule it must meet, the measured value, the margin left before it
    fails (the same meaning for agreements and bounds: negative when failed) and the verdict."""
    import shutil
    import textwrap

    width = width or min(shutil.get_terminal_size((100, 24)).columns, 100)
    head = ("quantity", "rule", "measured", "margin", "ok")
    cells = [(r.quantity + (f" [{r.unit}]" if r.unit else ""), _rule(r), f"{r.measured:.6g}", f"{r.margin:.2g}",
              "ok" if r.ok else "FAIL") for r in rows]
    fixed = [max(len(h), *(len(c[i]) for c in cells)) for i, h in enumerate(head)]
    fixed[0] = max(20, width - sum(fixed[1:]) - 2 * (len(head) - 1))
    fmt = "  ".join(f"{{:<{w}}}" for w in fixed)
    out = [fmt.format(*head).rstrip(), fmt.format(*("-" * w for w in fixed)).rstrip()]
    for c in cells:
        lines = textwrap.wrap(c[0], fixed[0]) or [""]
        out.append(fmt.format(lines[0], *c[1:]).rstrip())
        out += [lines[k] for k in range(1, len(lines))]
    return "\n".join(out)


def cmd_validate(args, parser) -> int:
    from wavephys.core.files import atomic_path, output_file

    json_path = _checked(parser, output_file, args.json, "--json", (".json",)) if args.json else None
    import jax

    if args.x64:
        jax.config.update("jax_enable_x64", True)
    from wavephys.app.registry import LONG_CHECKS, registry as get_registry

    registry = get_registry()
    if args.list:
        for name, fn in registry.items():
            print(f"{name:24s} {'long  ' if name in LONG_CHECKS else '      '}"
                  f"{((fn.__doc__ or '').strip().splitlines() or [''])[0]}")
        return 0
    if args.only and args.all:
        parser.error("--all and --only: name the checks with --only, or run every one with --all")
    names = args.only or [n for n in registry if args.all or n not in LONG_CHECKS]
    unknown = [n for n in names if n not in registry]
    if unknown:
        parser.error(f"unknown check(s) {', '.join(unknown)}; 'wavephys validate --list' names them")
    start = time.perf_counter()
    rows, done = [], 0
    try:
        for i, name in enumerate(names):
            _progress(i, len(names), name, start)
            got = registry[name]()
            rows.extend(got)
            done += 1
            for r in got:  # each row as it finishes (the table follows at the end)
                print(f"  {'ok  ' if r.ok else 'FAIL'}  {r.quantity}: {r.measured:.6g} ({_rule(r)})", file=sys.stderr,
                      flush=True)
    except KeyboardInterrupt:
        done = -done - 1  # interrupted after `done` checks
    if rows:
        print(_table(rows))
    failed = [r for r in rows if not r.ok]
    print(f"\n{len(rows) - len(failed)} passed, {len(failed)} failed ({time.perf_counter() - start:.1f} s)")
    if json_path is not None and rows:
        with atomic_path(json_path) as tmp:
            tmp.write_text(json.dumps([r.as_dict() for r in rows], indent=2))
        print(f"wrote {json_path}")
    if done < 0:
        finished = -done - 1
        print(f"wavephys validate: interrupted (Ctrl-C) after {finished} of {len(names)} checks; their {len(rows)} "
              f"rows are above" + (f" and in {json_path}" if json_path is not None and rows else ""),
              file=sys.stderr)
        return INTERRUPTED[0]
    return 1 if failed else 0


def cmd_run(args, parser) -> int:
    from wavephys.core.files import atomic_path, output_folder

    out = _checked(parser, output_folder, args.out, "--out")
    import numpy as np

    from wavephys.app.scenes import default_scene
    from wavephys.plot import plot_surface

    start = time.perf_counter()
    result = default_scene(n=args.n, steps=args.steps, progress=lambda m: print(m, file=sys.stderr, flush=True))
    with atomic_path(out / "surface.npz") as tmp, open(tmp, "wb") as f:
        np.savez_compressed(f, eta=result["eta"], eta_dot=result["eta_dot"], dx=result["dx"], time=result["time"],
                            units="m, m/s, m, s")
    fig = plot_surface(result["eta"], result["dx"], title=f"default scene at t = {result['time']:.2f} s")
    with atomic_path(out / "surface.png") as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    print(f"simulated {args.steps} steps on {args.n}x{args.n} in {time.perf_counter() - start:.1f} s; "
          f"energy drift without the cutoff {result['energy_ratio'] - 1:.2e}; wrote {out}/surface.npz, "
          f"{out}/surface.png")
    return 0


def cmd_render(args, parser) -> int:
    from wavephys.core.files import output_file, output_folder

    if args.frames == 1:
        out = _checked(parser, output_file, args.out, "--out", (".png",))
    else:
        out = _checked(parser, output_folder, args.out, "--out")
    from optics.rendering.renderer import Renderer, RendererUnavailable, render_sequence, save_png
    from wavephys.app.scenes import builtin_scene, scene_frames

    off = {e: False for e in args.off or []}
    last = args.time + (args.frames - 1) / args.fps
    if last > MAX_TIME:  # checked before any work: the frames must end by the scenes' last time
        parser.error(f"--frames: {args.frames} frames at {args.fps:g} fps from {args.time:g} s end at {last:.6g} s, "
                     f"after the scenes' last time {MAX_TIME:g} s")
    start = time.perf_counter()
    try:
        renderer = Renderer(args.width, args.height, steps=args.steps)
    except RendererUnavailable as exc:
        print(f"wavephys render: {exc}", file=sys.stderr)
        return 3
    except ValueError as exc:  # e.g. an image larger than the context allows
        parser.error(str(exc))
    with renderer:
        if args.frames == 1:  # two phases, each said as it starts and timed (docs/performance.md: each scene's)
            print(f"rendering {args.scene} ({args.width}x{args.height}): building its water, ground and caustics ...",
                  file=sys.stderr, flush=True)
            scene = builtin_scene(args.scene, n=args.n, time=args.time, caustics="caustics" not in off,
                                  progress=True).with_effects(**off)  # caustics off: the map is not computed
            built = time.perf_counter()
            print(f"built in {built - start:.1f} s; drawing ...", file=sys.stderr, flush=True)
            path = save_png(renderer.render(scene), out)
            print(f"rendered {args.scene} ({args.width}x{args.height}, {renderer.renderer_name}) in "
                  f"{time.perf_counter() - start:.1f} s (built {built - start:.1f} s, drawn "
                  f"{time.perf_counter() - built:.1f} s); wrote {path}")
            return 0
        scenes = (s.with_effects(**off) for s in scene_frames(args.scene, args.frames, fps=args.fps, n=args.n,
                                                                  start=args.time, caustics="caustics" not in off))
        paths = render_sequence(renderer, scenes, out, count=args.frames, video=args.video, fps=round(args.fps))
        print(f"rendered {len(paths)} frames of {args.scene} in {time.perf_counter() - start:.1f} s; wrote {out}/")
    return 0


def cmd_textures(args, parser) -> int:
    from wavephys.core.files import output_folder

    out = _checked(parser, output_folder, args.out, "--out")
    from optics.rendering.textures import export_scene
    from wavephys.app.scenes import builtin_scene

    scenes = None
    if args.frames:  # checked before any work: the frames must end by the scenes' last time
        from wavephys.app.scenes import scene_frames

        try:
            scenes = scene_frames(args.scene, args.frames, fps=args.fps, n=args.n, start=args.time, caustics=False)
        except ValueError as exc:
            parser.error(f"--frames: {exc}")

    paths = export_scene(builtin_scene(args.scene, n=args.n, time=args.time), out)
    from wavephys.app.scenes import scene_displacement

    displacement = scene_displacement(args.scene, n=args.n, time=args.time)
    if displacement is not None:  # a displaced surface: also the form engines draw it in
        from optics.rendering.textures import save_vector_displacement
        from wavephys.app.scenes import scene_grid

        paths["water_displacement_exr"] = save_vector_displacement(out / "water_displacement.exr", displacement,
                                                                   scene_grid(args.scene, args.n))
    for name, p in paths.items():
        print(f"{name:15s} {p}")
    if scenes is not None:
        import numpy as np

        from optics.rendering.textures import export_height_frames
        from wavephys.app.scenes import scene_height_frames

        start = time.perf_counter()
        series, length, said = scene_height_frames(args.scene, args.frames, fps=args.fps, n=args.n, start=args.time)
        written = export_height_frames(series, length, 1.0 / args.fps, out / "frames", start=args.time,
                                       attributes=said)
        print(f"frames          {out / 'frames'}/ ({len(written)} EXR height frames at {args.fps:g} fps, "
              f"{time.perf_counter() - start:.1f} s; check them with: wavephys check {out / 'frames'})")
    return 0


def _tolerance(text: str):
    """A tolerance: metres ("0.001") or height-texture quanta ("0.5q")."""
    quanta = text.strip().lower().endswith("q")
    try:
        value = float(text.strip()[:-1] if quanta else text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected metres (0.001) or quanta (0.5q), got {text!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"must be > 0, got {text}")
    return ("q" if quanta else "m", value)


PLAN_SCENES = ("ripples", "ocean", "pond", "lake", "harbour", "pool", "shelf")
"""wavephys.planner.BUILTIN_SCENES, written out so that --help imports nothing heavy (a test keeps them equal)."""

CALIBRATION_TABLES = ("step", "step_walls", "step_symmetric", "ship", "ship_impulses", "frame", "optics",
                      "run_overhead", "caustics", "caustics_jacobian", "shade", "texture", "surface", "kappa")
"""wavephys.planner.measure.TABLES, written out for the same reason (a test keeps them equal)."""


def cmd_plan(args, parser) -> int:
    from wavephys.core.files import output_file

    json_path = _checked(parser, output_file, args.json, "--json", (".json",)) if args.json else None
    chart_path = _checked(parser, output_file, args.chart, "--chart", (".png",)) if args.chart else None
    from wavephys.planner import BUILTIN_SCENES, Infeasible, Scene, builtin_scene, plan

    if args.scene in SCENES and args.scene not in BUILTIN_SCENES and not Path(args.scene).exists():
        parser.error(f"{args.scene!r} is a scene of 'wavephys render', not one the planner can plan: the two "
                     f"commands' built-in scenes are two sets today (plan: {', '.join(BUILTIN_SCENES)}; render: "
                     f"{', '.join(SCENES)}); describe it as a scene file (docs/planner.md) to plan it")
    try:
        scene = builtin_scene(args.scene) if args.scene in BUILTIN_SCENES else Scene.from_toml(Path(args.scene))
    except FileNotFoundError as exc:
        parser.error(f"{exc} (or name a built-in scene: {', '.join(BUILTIN_SCENES)})")
    except (TypeError, ValueError) as exc:
        parser.error(str(exc) if args.scene in str(exc) else f"{args.scene}: {exc}")
    cal = None
    if args.calibration is not None:
        from wavephys.planner import load_calibration

        cal = _checked(parser, load_calibration, args.calibration)
    unit, value = args.tolerance
    tolerance = value * scene.height_quantum if unit == "q" else value
    colour = None if args.colour_tolerance is None else args.colour_tolerance * scene.image_quantum
    try:
        p = plan(scene, tolerance, colour, args.budget, calibration=cal)
    except Infeasible as exc:
        print(f"wavephys plan: {exc}", file=sys.stderr)
        return 1
    print(p.card())
    if json_path is not None:
        p.to_json(json_path)
        print(f"wrote {json_path}")
    if chart_path is not None:
        from wavephys.core.files import atomic_path
        from wavephys.planner.charts import plot_plan

        with atomic_path(chart_path) as tmp:
            plot_plan(p).savefig(tmp, dpi=110, format="png")
        print(f"wrote {chart_path}")
    return 0


def cmd_calibrate(args, parser) -> int:
    from wavephys.core.files import output_file

    out = _checked(parser, output_file, args.out, "--out", (".json",))
    from wavephys.planner import calibrate, load_calibration

    base = _checked(parser, load_calibration, args.base) if args.base else None
    if base is not None and not args.only:
        parser.error("--base is for --only (a full calibration measures every table)")
    start = time.perf_counter()
    data = calibrate(out, only=args.only, base=base)
    kind = f"{', '.join(args.only)}" if args.only else "every table"
    where = data[f"{args.only[0]}_machine"] if args.only else f"{data['machine']}, {data['device']}"
    print(f"wrote {out}: {kind} measured on {where} in {time.perf_counter() - start:.0f} s; "
          f"kappa {data['kappa']:.3g}. Use it: wavephys plan SCENE --calibration {out}")
    return 0


def cmd_report(args, parser) -> int:
    from wavephys.core.files import output_folder

    out = _checked(parser, output_folder, args.out, "--out")
    if args.validation is not None:
        from wavephys.app.report import read_validation

        try:
            read_validation(args.validation)
        except (TypeError, ValueError) as exc:
            parser.error(f"--validation{str(exc)[len('path'):]}")
    from wavephys.app.registry import registry

    if args.checks:
        unknown = [c for c in args.checks if c not in registry()]
        if unknown:
            parser.error(f"unknown check(s) {', '.join(unknown)}; 'wavephys validate --list' names them")
    from wavephys.app.report import build_report

    from wavephys.app.report import ReportInterrupted

    start = time.perf_counter()
    try:
        path = build_report(out, args.checks, args.validation, args.figures, args.quick,
                            progress=lambda m: print(m if m.startswith("  ") else
                                                     f"{m} ({time.perf_counter() - start:.1f} s elapsed)",
                                                     file=sys.stderr, flush=True))
    except ReportInterrupted as stop:
        print(f"wavephys report: interrupted (Ctrl-C) while building {stop.section}; the page so far, with what is "
              f"missing said at its top: {stop.path}", file=sys.stderr)
        return INTERRUPTED[0]
    print(f"wrote {path} in {time.perf_counter() - start:.0f} s")
    return 0


def _setting(text: str):
    """``KEY=VALUE`` with VALUE a number, true/false/none, a comma list (a tuple; ``a,`` has one item) or text."""
    key, sep, value = text.partition("=")
    if not sep or not key.strip().isidentifier():
        raise argparse.ArgumentTypeError(f"expected KEY=VALUE, got {text!r}")

    def one(v: str):
        v = v.strip()
        low = v.lower()
        if low in ("true", "false"):
            return low == "true"
        if low == "none":
            return None
        for kind in (int, float):
            try:
                return kind(v)
            except ValueError:
                pass
        return v

    parts = [one(v) for v in value.split(",") if v.strip()] if "," in value else None  # "above," is a 1-tuple
    return key.strip(), tuple(parts) if parts is not None else one(value)


def _version() -> str:
    from wavephys import __version__

    return f"wavephys {__version__}"


HELPERS = {"setting": _setting, "checked": _checked}
"""The command's shared argument types, for the subcommands defined in their own modules."""


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (no heavy imports: ``--help`` answers at once)."""
    fmt = argparse.RawDescriptionHelpFormatter
    parser = _Parser(prog="wavephys", description=_overview(), epilog=EXIT_CODES, formatter_class=fmt)
    parser.add_argument("--version", action="version", version=_version())
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)
    v = _subcommand(sub, "validate", fmt)
    v.add_argument("--json", metavar="PATH", help="also write the table as JSON (a .json file in an existing folder)")
    v.add_argument("--only", nargs="+", metavar="NAME", help="run only these checks (names from --list)")
    v.add_argument("--list", action="store_true", help="list the checks and exit")
    v.add_argument("--all", action="store_true", help="also run the long checks (marked 'long' by --list; about 4 "
                                                     "minutes more on a 2-core CPU)")
    v.add_argument("--x64", action="store_true", help="run in float64")
    v.set_defaults(func=cmd_validate)
    r = _subcommand(sub, "run", fmt)
    r.add_argument("--n", type=_int(128, even=True, hi=MAX_N), default=256,
                   help=f"grid points per side (even, 128 to {MAX_N})")
    r.add_argument("--steps", type=_int(1, hi=MAX_STEPS), default=120, help=f"steps of 1/30 s (1 to {MAX_STEPS})")
    r.add_argument("--out", default="wavephys-out", help="output folder (created if its parent exists)")
    r.set_defaults(func=cmd_run)
    g = _subcommand(sub, "render", fmt)
    g.add_argument("--scene", choices=SCENES, default="pool")
    g.add_argument("--out", default="frame.png", help="a .png file (one frame) or a folder (--frames > 1)")
    g.add_argument("--frames", type=_int(1), default=1, help="number of frames (an animation when > 1)")
    g.add_argument("--fps", type=_float(0.0, open_lo=True, hi=MAX_FPS), default=30.0,
                   help=f"frames per second of the animation (up to {MAX_FPS:g})")
    g.add_argument("--time", type=_float(0.0, hi=MAX_TIME), default=1.0,
                   help=f"scene time of the (first) frame, s (0 to {MAX_TIME:g})")
    g.add_argument("--width", type=_int(1), default=800, help="image width, pixels")
    g.add_argument("--height", type=_int(1), default=600, help="image height, pixels")
    g.add_argument("--n", type=_int(64, even=True, hi=MAX_N), default=256,
                   help=f"height-field texels per side (even, 64 to {MAX_N})")
    g.add_argument("--steps", type=_int(1, hi=4096), default=256, help="ray-march steps (1 to 4096)")
    g.add_argument("--off", nargs="+", choices=EFFECTS, metavar="EFFECT", help=f"switch effects off: {', '.join(EFFECTS)}")
    g.add_argument("--video", metavar="NAME", help="also write a video in the folder (needs imageio-ffmpeg)")
    g.set_defaults(func=cmd_render)
    t = _subcommand(sub, "textures", fmt)
    t.add_argument("--scene", choices=SCENES, default="pool")
    t.add_argument("--out", default="textures", help="output folder (created if its parent exists)")
    t.add_argument("--n", type=_int(64, even=True, hi=MAX_N), default=256, help=f"texels per side (even, 64 to {MAX_N})")
    t.add_argument("--time", type=_float(0.0, hi=MAX_TIME), default=1.0,
                   help=f"scene time, s, 0 to {MAX_TIME:g} (of the first frame with --frames)")
    t.add_argument("--frames", type=_int(8), default=0, metavar="N",
                   help="also write N >= 8 numbered EXR height frames to OUT/frames/ (a record for wavephys check)")
    t.add_argument("--fps", type=_float(0.0, open_lo=True, hi=MAX_FPS), default=30.0,
                   help=f"frames per second of --frames (up to {MAX_FPS:g})")
    t.set_defaults(func=cmd_textures)
    pl = _subcommand(sub, "plan", fmt, "Plan a scene (a TOML file, or a built-in: " + ", ".join(PLAN_SCENES)
                     + "): print its model card.")
    pl.add_argument("scene", help="a scene TOML file or a built-in scene's name")
    pl.add_argument("--tolerance", type=_tolerance, default=("q", 0.5),
                    help="largest height error: metres (0.001) or height-texture quanta (0.5q, the default)")
    pl.add_argument("--colour-tolerance", type=_float(0.0, open_lo=True), default=None, metavar="QUANTA",
                    help="largest colour error in image quanta (default 1)")
    pl.add_argument("--budget", type=_float(0.0, open_lo=True), default=None, metavar="SECONDS",
                    help="refuse plans whose predicted cost exceeds this")
    pl.add_argument("--calibration", metavar="FILE",
                    help="costs measured by 'wavephys calibrate --out FILE' (default: the shipped ones, a 2-core CPU)")
    pl.add_argument("--json", metavar="PATH", help="also write the model card as JSON")
    pl.add_argument("--chart", metavar="PATH", help="draw the Pareto front and error budget (a .png)")
    pl.set_defaults(func=cmd_plan)
    _add_calibrate_parser(sub, fmt)
    rp = _subcommand(sub, "report", fmt)
    rp.add_argument("--out", default="wavephys-report", help="output folder (created if its parent exists)")
    rp.add_argument("--checks", nargs="+", metavar="NAME", help="run only these validations (default: all)")
    rp.add_argument("--validation", metavar="JSON", help="show this 'wavephys validate --json' table instead")
    rp.add_argument("--figures", metavar="DIR", help="the bench charts' folder (default: the checkout's bench/figures)")
    rp.add_argument("--quick", action="store_true", help="smaller grids, one model card, one frame, and the "
                                                          "validations but the long ones (validate --all has them)")
    rp.set_defaults(func=cmd_report)
    from wavephys.app.check_command import add_check_parser

    add_check_parser(sub, fmt, _Parser, HELPERS)
    return parser


def _add_calibrate_parser(sub, fmt) -> None:
    ca = _subcommand(sub, "calibrate", fmt)
    ca.add_argument("--out", required=True, metavar="FILE", help="the calibration file to write (.json)")
    ca.add_argument("--only", nargs="+", choices=CALIBRATION_TABLES, metavar="TABLE",
                    help="measure these tables alone, the rest from --base: " + ", ".join(CALIBRATION_TABLES))
    ca.add_argument("--base", metavar="FILE", help="with --only: the calibration the other tables come from "
                                                   "(default: the shipped one)")
    ca.set_defaults(func=cmd_calibrate)


def main(argv=None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 2
    try:
        code = args.func(args, parser)
        sys.stdout.flush()  # here, so that a reader gone away is seen here
        return code
    except BrokenPipeError:  # the reader went away (wavephys validate --list | head): nothing more to say
        import os

        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no second error when Python flushes
        return 0


if __name__ == "__main__":
    sys.exit(main())
