"""The wavephys command: validate the physics, simulate the default scene, render, export textures.

  wavephys run                 simulate the built-in default scene (the main job)
  wavephys validate            run the built-in validations, expected against measured
  wavephys render              render a built-in scene with the headless renderer
  wavephys textures            export a built-in scene's textures
  wavephys plan SCENE          the cheapest model that meets a tolerance (the scene planner)
  wavephys calibrate --out F   measure the planner's costs on this machine (for plan --calibration F)
  wavephys report --out DIR    one self-contained HTML page of what is measured
  wavephys check FRAMES...     check exported frames against the physics (dispersion, energy, …)
  wavephys check --glsl FILE   check a GLSL function against the physics (Fresnel, refraction, …)
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from pathlib import Path

EXIT_CODES = """exit status:
  0  done (every validation row ok)
  1  a validation row failed
  2  usage error: a bad option or output path (checked before any work starts)
  3  no OpenGL context (headless EGL missing: apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri)"""

CHECK_EXIT_CODES = """exit status:
  0  every check ok (frames), or the function meets the physics (a shader)
  1  a check failed, or the function does not meet the physics
  2  usage error: a bad option or output path, unreadable frames, or a shader that does not compile or whose
     function cannot be called as asked (said before any check runs)
  3  no OpenGL context (apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri), or for HLSL no translator
     (apt-get install glslang-tools spirv-cross)"""

RECORD_CHECK_HELP = (  # wavephys.harness.RECORD_CHECKS, written out so that --help imports nothing heavy
    ("dispersion", "omega(k) of every shell of |k| against linear theory (worst relative error)", ()),
    ("energy", "drift of the wave energy over the record, with the damping rate per k and its kind", ()),
    ("tiling", "the wrap step of the frames against an ordinary step (seams, clamped edges)", ()),
    ("quantization", "noise of the lattice the heights are stored on, against the rms height", ()),
    ("standing", "phase locking of every mode's +omega and -omega parts (a sea that does not travel)", ("sea",)),
    ("direction", "the power-weighted mean direction of travel against the claimed one, degrees", ("direction",)),
    ("group_velocity", "speed of a packet's energy centroid against the mean group velocity", ("packet",)),
    ("ring_arrival", "share of eta^2 inside the calm disc r < c_g,min (t - t0) behind the first ring", ("source",)),
    ("wake_edge", "outer edge of a moving source's wake in the first frame against the cusp line, degrees", ("wake",)),
    ("wake_max", "angle of maximum amplitude on arcs behind the source (Darmon et al.), degrees",
     ("wake", "wake-size")),
    ("normals", "the normal map against the slopes of the first frame's heights (largest angle, degrees)",
     ("normals",)),
    ("caustics_flux", "mean of a caustics map against flat water's irradiance (light conserved)", ("caustics",)),
    ("resolution", "variance per octave of |k| against the same sea exported at another resolution", ("other",)),
    ("seiche", "frequencies of a tank's strongest cosine modes against omega(k_mn) (walls at the edges)", ("tank",)),
    ("shoaling", "a wave train's amplitude across a floor against sqrt(c_g,ref/c_g(h)) (Green's law)", ("floor",)),
    ("wall_reflection", "amplitude kept per reflection at a tank's walls, from its modes' decay", ("tank",)),
    ("mass", "the water's volume over a shallow-water record's frames (heights over a bed, closed domain)",
     ("bed",)),
    ("lake_at_rest", "largest movement of a lake at rest's surface over an uneven bed, m", ("bed", "at-rest")),
    ("dam_break", "speed of a dam break's front (Ritter) or bore (Stoker) against the exact one, m/s", ("bed", "dam")),
)

EFFECTS = ("refraction", "reflection", "fresnel", "absorption", "caustics")
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
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
        if not math.isfinite(value) or value < lo or (open_lo and value == lo) or (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(f"must be a finite number {'>' if open_lo else '≥'} {lo}"
                                             + (f" and ≤ {hi:g}" if hi is not None else "") + f", got {text}")
        return value

    parse.limits = (lo, hi, open_lo)

    return parse


def _real(text: str) -> float:
    """Any finite number (a signed angle, a time offset)."""
    try:
        value = float(text)
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
    from wavephys.app.registry import registry as get_registry

    registry = get_registry()
    if args.list:
        for name, fn in registry.items():
            print(f"{name:24s} {((fn.__doc__ or '').strip().splitlines() or [''])[0]}")
        return 0
    names = args.only or list(registry)
    unknown = [n for n in names if n not in registry]
    if unknown:
        parser.error(f"unknown check(s) {', '.join(unknown)}; 'wavephys validate --list' names them")
    start = time.perf_counter()
    rows = []
    for i, name in enumerate(names):
        _progress(i, len(names), name, start)
        rows.extend(registry[name]())
    print(_table(rows))
    failed = [r for r in rows if not r.ok]
    print(f"\n{len(rows) - len(failed)} passed, {len(failed)} failed ({time.perf_counter() - start:.1f} s)")
    if json_path is not None:
        with atomic_path(json_path) as tmp:
            tmp.write_text(json.dumps([r.as_dict() for r in rows], indent=2))
        print(f"wrote {json_path}")
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
        if args.frames == 1:
            print(f"rendering {args.scene} ({args.width}x{args.height}) ...", file=sys.stderr, flush=True)
            scene = builtin_scene(args.scene, n=args.n, time=args.time).with_effects(**off)
            path = save_png(renderer.render(scene), out)
            print(f"rendered {args.scene} ({args.width}x{args.height}, {renderer.renderer_name}) in "
                  f"{time.perf_counter() - start:.1f} s; wrote {path}")
            return 0
        scenes = (s.with_effects(**off) for s in scene_frames(args.scene, args.frames, fps=args.fps, n=args.n,
                                                                  start=args.time))
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
        from wavephys.app.scenes import scene_grid

        start = time.perf_counter()
        series = (np.asarray(s.water) for s in scenes)
        written = export_height_frames(series, float(scene_grid(args.scene, args.n).length), 1.0 / args.fps,
                                       out / "frames", start=args.time)
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

    start = time.perf_counter()
    path = build_report(out, args.checks, args.validation, args.figures, args.quick,
                        progress=lambda m: print(m, file=sys.stderr, flush=True))
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


def _read_glsl(parser, path: str, flag: str = "--glsl") -> str:
    p = Path(path)
    if not p.is_file():
        parser.error(f"{flag}: no file at {path}" if not p.exists() else f"{flag}: {path} is not a file")
    try:
        return p.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        parser.error(f"{flag}: {path} is not a UTF-8 text file (shader source expected)")
    except OSError as exc:
        parser.error(f"{flag}: cannot read {path} ({exc.strerror})")


def _pair(text: str):
    """``X,Y``: two finite numbers."""
    parts = text.split(",")
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        values = ()
    if len(values) != 2 or not all(math.isfinite(v) for v in values):
        raise argparse.ArgumentTypeError(f"expected X,Y (two numbers, m), got {text!r}")
    return values


def _seconds(text: str) -> float:
    """Seconds: a number or a fraction such as 1/60."""
    num, sep, den = text.partition("/")
    try:
        value = float(num) / float(den) if sep else float(num)
    except (ValueError, ZeroDivisionError):
        raise argparse.ArgumentTypeError(f"expected seconds (0.0167 or 1/60), got {text!r}") from None
    if not math.isfinite(value) or value <= 0:
        raise argparse.ArgumentTypeError(f"must be > 0, got {text}")
    return value


_CLAIM_OPTIONS = (("only:", "--only:"), ("direction= (--direction DEG)", "--direction DEG"),
                  ("sea=True (--sea)", "--sea"), ("source= (--source X,Y)", "--source X,Y"),
                  ("packet=True (--packet)", "--packet"), ("wake=dict(speed=...) (--wake U)", "--wake U"),
                  ("the source's size, wake=dict(size=...) (--wake-size SIGMA)", "--wake-size M"),
                  ("normals= (--normals FILE)", "--normals FILE"), ("caustics= (--caustics FILE)", "--caustics FILE"),
                  ("other= (--other FRAMES)", "--other FRAMES"), ("tank=True (--tank)", "--tank"),
                  ("floor= (--floor FILE)", "--floor FILE"),
                  ("(tank=True)", "(--tank)"))


def _option_words(text: str) -> str:
    """A message of :func:`wavephys.harness.check_record` in the command's words (its options, not Python's)."""
    for python, option in _CLAIM_OPTIONS:
        text = text.replace(python, option)
    return text


def _wake_claim(args):
    """The ``wake=`` claim of :func:`wavephys.harness.check_record` from ``--wake`` and its companions."""
    if args.wake is None:
        return None
    claim = dict(speed=args.wake, source=tuple(args.wake_at) if args.wake_at else (0.0, 0.0),
                 direction=args.wake_heading)
    if args.wake_size is not None:
        claim["size"] = args.wake_size
    return claim


def _claim_maps(args) -> dict:
    """The maps and arrays the record's claims name (--normals, --caustics, --floor, --bed, --other), read."""
    import numpy as np

    from wavephys.core.frames import read_map
    from wavephys.harness import Record

    maps = {}
    if args.normals:
        maps["normals"] = read_map(args.normals, name="--normals", channels=3)
    if args.caustics:
        maps["caustics"] = read_map(args.caustics, name="--caustics", channels=1)
    if args.floor:
        try:
            maps["floor"] = np.load(args.floor, allow_pickle=False)
        except (OSError, ValueError) as exc:
            raise ValueError(f"--floor: cannot read {args.floor} as a .npy array of depths per column: {exc}")
    if args.bed:
        try:
            maps["bed"] = np.load(args.bed, allow_pickle=False)
        except (OSError, ValueError) as exc:
            raise ValueError(f"--bed: cannot read {args.bed} as a .npy array of bed elevations, m: {exc}")
    if args.other:
        other = args.other[0] if len(args.other) == 1 else list(args.other)
        maps["other"] = Record.from_files(other, channel=args.channel)
    return maps


def _dam_claim(parser, args):
    if args.dam is None:
        return None
    if len(args.dam) not in (2, 3):
        parser.error(f"--dam takes X H0 [HR] (m), got {len(args.dam)} values")
    return dict(zip(("x", "h0", "hr"), args.dam))


def cmd_check_frames(args, parser) -> int:
    """``wavephys check FRAMES...``: the record's checks, their verdicts and causes."""
    from wavephys.core.files import atomic_path, output_file

    json_path = _checked(parser, output_file, args.json, "--json", (".json",)) if args.json else None
    junit_path = _checked(parser, output_file, args.junit, "--junit", (".xml",)) if args.junit else None
    names = [n for n, _, _ in RECORD_CHECK_HELP]
    if args.only:  # checked before the frames are read
        unknown = [n for n in args.only if n not in names]
        if unknown:
            parser.error(f"--only: unknown check(s) {', '.join(unknown)}; the checks are {', '.join(names)}")
    given = {"direction": args.direction is not None, "sea": args.sea, "packet": args.packet,
             "source": args.source is not None, "wake": args.wake is not None, "wake-size": args.wake_size is not None,
             "normals": bool(args.normals), "caustics": bool(args.caustics), "other": bool(args.other),
             "tank": args.tank, "floor": bool(args.floor), "bed": bool(args.bed), "at-rest": args.at_rest,
             "dam": args.dam is not None}
    for name, _, needs in RECORD_CHECK_HELP:
        missing = [f"--{x}" for x in needs if not given[x]]
        if args.only and name in args.only and missing:
            parser.error(f"--only: the {name} check needs {', '.join(missing)}")
    if args.wake is None and (args.wake_at is not None or args.wake_size is not None or args.wake_heading != 0.0):
        parser.error("--wake-at, --wake-heading and --wake-size describe a moving source: give its speed with "
                     "--wake U")
    from wavephys import Water
    from wavephys.harness import Record, check_record

    source = args.frames[0] if len(args.frames) == 1 else list(args.frames)
    try:
        record = Record.from_files(source, dx=args.dx, dt=args.dt, channel=args.channel, depth=args.depth,
                                   sigma=args.sigma, axes=args.axes)
    except (TypeError, ValueError) as exc:
        print(f"wavephys check: {exc}", file=sys.stderr)
        return 2
    try:
        maps = _claim_maps(args)
    except (TypeError, ValueError) as exc:
        print(f"wavephys check: {exc}", file=sys.stderr)
        return 2
    nt, ny, nx = record.shape
    print(f"{record.source}: {nt} frames of {nx} x {ny}, dx = {record.dx:.6g} m, dt = {record.dt:.6g} s", flush=True)
    try:
        report = check_record(record, Water(), only=args.only, direction=args.direction, sea=args.sea,
                              packet=args.packet, source=args.source, t0=args.t0, radius=args.radius,
                              viscosity=args.viscosity, rtol=args.rtol, wake=_wake_claim(args),
                              convention=args.convention, tank=args.tank, at_rest=args.at_rest,
                              dam=_dam_claim(parser, args), **maps,
                              progress=lambda m: print(m, file=sys.stderr, flush=True))
    except (TypeError, ValueError) as exc:  # a claim a named check needs: the option's name, not Python's
        parser.error(_option_words(str(exc)))
    for name, row in report.rows.items():
        print(f"{'ok    ' if row.ok else 'FAILED'} {name}: {row.report()}")
    for name, why in report.skipped.items():
        print(f"skip   {name}: {_option_words(why)}")
    if json_path is not None:
        with atomic_path(json_path) as tmp:
            tmp.write_text(json.dumps(report.as_dict(), indent=2))
        print(f"wrote {json_path}")
    if junit_path is not None:
        from wavephys.app.junit import junit_xml

        with atomic_path(junit_path) as tmp:
            tmp.write_text(junit_xml(record.source, report.rows, report.seconds, report.skipped), encoding="utf-8")
        print(f"wrote {junit_path}")
    return 0 if report.ok else 1


def cmd_check(args, parser) -> int:
    from wavephys.core.files import atomic_path, output_file

    if args.frames:
        if args.glsl is not None or args.hlsl is not None or args.shader is not None or args.list:
            parser.error("give either FRAMES (a record) or --glsl/--hlsl/--shader FILE (a shader), not both")
        return cmd_check_frames(args, parser)
    if args.list:
        from optics.shaders import SHADER_CHECKS, describe_check

        print("\n\n".join(describe_check(name) for name in SHADER_CHECKS))
        return 0
    shader = [(flag, path) for flag, path in (("--glsl", args.glsl), ("--hlsl", args.hlsl), ("--shader", args.shader))
              if path is not None]
    if len(shader) > 1:
        parser.error(f"give one of --glsl, --hlsl and --shader, not {' and '.join(f for f, _ in shader)}")
    if not shader or args.function is None or args.against is None:
        parser.error("give FRAMES... (exported frames), or --glsl FILE (or --hlsl, --shader), --function NAME and "
                     "--against CHECK (names from --list)")
    flag, path = shader[0]
    source = _read_glsl(parser, path, flag)
    language = "hlsl" if flag == "--hlsl" else args.language if flag == "--shader" or args.language != "auto" else \
        "auto"
    json_path = _checked(parser, output_file, args.json, "--json", (".json",)) if args.json else None
    chart = _checked(parser, output_file, args.chart, "--chart", (".png",)) if args.chart else None
    for folder in args.include or []:
        if not Path(folder).is_dir():
            parser.error(f"--include: {folder} is not a folder")
    from optics.gpu import RendererUnavailable
    from optics.shaders import GLSLError, TranslatorMissing, check_glsl

    options = dict(args.option or [])
    takes = tuple(t.strip() for t in args.takes.split(",")) if args.takes else None
    try:
        report = check_glsl(source, args.function, args.against, takes=takes, result=args.result,
                            returns=args.returns, uniforms=dict(args.uniform or []) or None, tolerance=args.tolerance,
                            language=language, defines=args.define, include_dirs=tuple(args.include or ()),
                            chart=chart, **options)
    except (RendererUnavailable, TranslatorMissing) as exc:
        print(f"wavephys check: {exc}", file=sys.stderr)
        return 3
    except GLSLError as exc:
        print(f"wavephys check: {path}: {exc}", file=sys.stderr)
        return 2
    except (TypeError, ValueError) as exc:
        parser.error(str(exc))
    print(report.report())
    if json_path is not None:
        with atomic_path(json_path) as tmp:
            tmp.write_text(json.dumps(report.as_dict(), indent=2))
        print(f"wrote {json_path}")
    if chart is not None:
        print(f"wrote {chart}")
    return 0 if report.ok else 1


def _version() -> str:
    from wavephys import __version__

    return f"wavephys {__version__}"


def _add_check_parser(sub, fmt) -> None:
    """The ``check`` subcommand's options (exported frames, or a user's GLSL, against the physics)."""
    checks = "\n".join(f"  {name:15s} {measures}" + (f" (needs {', '.join('--' + x for x in needs)})" if needs else "")
                       for name, measures, needs in RECORD_CHECK_HELP)
    ck = sub.add_parser("check", help="check exported frames, or a GLSL function, against the physics",
                        epilog=CHECK_EXIT_CODES,
                        formatter_class=fmt,
                        description="Frames: read a folder, glob or list of EXR / 16-bit PNG / npy / npz height "
                                    "frames (dx, dt and units from the files' headers where they say, else from "
                                    "--dx and --dt) and print each check's verdict and, on failure, its likely "
                                    "cause.\n\n  wavephys check out/frames --sea --direction 0\n  wavephys check "
                                    "'export/h_*.exr' --dx 0.05 --dt 1/60 --depth 0.5 --junit checks.xml\n\nChecks "
                                    "on a record:\n" + checks + "\n\nShaders: compile a function (GLSL, GLSL ES, WebGL, "
                                    "Shadertoy, Godot, or HLSL through glslang and SPIRV-Cross) on the headless "
                                    "OpenGL context, evaluate it over its whole input domain and compare it with the "
                                    "physics; its constants (F0, the index ratio) are found from its output and "
                                    "judged against water's range.\n\n  wavephys check --glsl water.glsl --function "
                                    "fresnel --against fresnel\n  wavephys check --hlsl Water.hlsl --function "
                                    "FresnelSchlick --against fresnel")
    ck.add_argument("frames", nargs="*", metavar="FRAMES", help="a folder, glob pattern or files of height frames")
    ck.add_argument("--dx", type=_float(0.0, open_lo=True), help="grid spacing, m (when the files do not say)")
    ck.add_argument("--dt", type=_seconds, help="time between frames, s: 0.0167 or 1/60 (when the files do not say)")
    ck.add_argument("--depth", type=_float(0.0, open_lo=True), help="the water's depth, m (default: deep)")
    ck.add_argument("--sigma", type=_float(0.0), help="surface tension, N/m (default 0.0728; 0 for gravity waves)")
    ck.add_argument("--axes", choices=("tyx", "yxt", "txy", "xyt", "ytx", "xty"),
                    help="the layout of one .npy/.npz array of frames (yxt: time last); needed when its shape could "
                         "be read more than one way")
    ck.add_argument("--channel", metavar="NAME", help="the EXR channel holding the heights (default Y or the only one)")
    ck.add_argument("--only", nargs="+", metavar="CHECK", help="run only these checks (names above)")
    ck.add_argument("--sea", action="store_true", help="the frames are a sea meant to travel (standing-wave check)")
    ck.add_argument("--direction", type=_real, metavar="DEG", help="claimed direction of travel, degrees, 0 = +x")
    ck.add_argument("--packet", action="store_true", help="the frames are one wave packet (group-velocity check)")
    ck.add_argument("--floor", metavar="FILE", help="a .npy of the still-water depth under each column, m, of a "
                                                    "wave train travelling along x (shoaling check)")
    ck.add_argument("--bed", metavar="FILE", help="a .npy of the bed elevation under each cell, m: the frames are "
                                                  "shallow water over it (mass check; linear-wave checks skipped)")
    ck.add_argument("--at-rest", action="store_true", help="with --bed: the water was started flat and at rest "
                                                           "(lake-at-rest check)")
    ck.add_argument("--dam", nargs="+", type=_real, metavar="X H0 [HR]", help="with --bed: a dam at X m from the "
                    "left edge, H0 m deep behind it (HR ahead, default dry), released at the first frame")
    ck.add_argument("--tank", action="store_true", help="the frames are water between four reflecting walls half a "
                                                        "sample outside the edges (seiche and wall-reflection checks)")
    ck.add_argument("--source", type=_pair, metavar="X,Y", help="where one disturbance was, m (ring-arrival check)")
    ck.add_argument("--t0", type=_real, default=0.0, help="when it happened, s from the first frame (default 0)")
    ck.add_argument("--radius", type=_float(0.0), default=0.0, help="its radius, m (default 0)")
    ck.add_argument("--viscosity", type=_float(0.0), default=0.0, help="kinematic viscosity modelled, m^2/s")
    ck.add_argument("--normals", metavar="FILE", help="the normal map exported with the first frame (EXR RGB or PNG)")
    ck.add_argument("--convention", choices=("auto", "opengl", "directx"), default="auto",
                    help="the normal map's green convention claimed (default: detect and report)")
    ck.add_argument("--caustics", metavar="FILE", help="a caustics map, relative to flat water (EXR Y or PNG)")
    ck.add_argument("--other", nargs="+", metavar="FRAMES", help="the same sea exported at another resolution "
                                                                 "(files with dx in their headers)")
    ck.add_argument("--wake", type=_float(0.0, open_lo=True), metavar="U", help="a source moving at U m/s (wake "
                                                                                "checks on the first frame)")
    ck.add_argument("--wake-at", type=_pair, metavar="X,Y", help="where that source is in the first frame, m "
                                                                 "(default 0,0: the centre)")
    ck.add_argument("--wake-heading", type=_real, default=0.0, metavar="DEG", help="its heading, degrees, 0 = +x")
    ck.add_argument("--wake-size", type=_float(0.0, open_lo=True), metavar="M",
                    help="its size as a Gaussian pressure, m (wake_max check)")
    ck.add_argument("--rtol", type=_float(0.0, open_lo=True), default=0.02, help="dispersion tolerance (default "
                                                                                   "0.02)")
    ck.add_argument("--junit", metavar="PATH", help="also write JUnit XML for a CI server (frames)")
    ck.add_argument("--glsl", metavar="FILE", help="the GLSL source that defines the function (GLSL ES, WebGL, "
                                                   "Shadertoy and Godot shader files are read as written)")
    ck.add_argument("--hlsl", metavar="FILE", help="the HLSL source that defines the function (Unity, Unreal, Crest): "
                                                   "translated by glslang and SPIRV-Cross (apt-get install "
                                                   "glslang-tools spirv-cross)")
    ck.add_argument("--shader", metavar="FILE", help="a shader source in any of those languages (--language)")
    ck.add_argument("--language", default="auto", choices=("auto", "glsl", "glsl_es", "webgl", "shadertoy", "godot",
                                                           "hlsl"), help="the source's language (default: told from "
                                                                         "the text)")
    ck.add_argument("--define", action="append", metavar="NAME=VALUE", help="a macro the source relies on, e.g. "
                                                                            "UNITY_PI=3.14159265 (repeatable)")
    ck.add_argument("--include", action="append", metavar="DIR", help="a folder for the source's #include lines "
                                                                      "(repeatable)")
    ck.add_argument("--function", metavar="NAME", help="the function to check")
    ck.add_argument("--result", metavar="NAME", help="the out parameter that holds the result (default: the return "
                                                     "value, or a void function's only out parameter)")
    ck.add_argument("--against", metavar="CHECK", help="what it computes: fresnel, refract, reflect, transmittance, "
                                                        "rgb_absorption, normal_decode, height_normal (see --list)")
    ck.add_argument("--takes", metavar="ROLE,...", help="what each parameter is, in order (roles from --list; "
                                                        "default: the check's own, else read from the names)")
    ck.add_argument("--returns", metavar="TYPE", help="the return type you expect (float, vec3)")
    ck.add_argument("--option", type=_setting, action="append", metavar="KEY=VALUE",
                    help="an option of the check, e.g. form=schlick, sides=above, convention=directx (repeatable)")
    ck.add_argument("--uniform", type=_setting, action="append", metavar="NAME=VALUE",
                    help="a value for a uniform the function reads, e.g. uF0=0.02 or uTint=0.1,0.2,0.3 (repeatable)")
    ck.add_argument("--tolerance", type=_float(0.0, open_lo=True), default=None, help="largest error allowed "
                                                                                      "(default: the check's)")
    ck.add_argument("--json", metavar="PATH", help="also write the report as JSON")
    ck.add_argument("--chart", metavar="PATH", help="also draw the error over the domain (a .png)")
    ck.add_argument("--list", action="store_true", help="list the checks, their roles and options, and exit")
    ck.set_defaults(func=cmd_check)


def build_parser() -> argparse.ArgumentParser:
    """The argument parser (no heavy imports: ``--help`` answers at once)."""
    fmt = argparse.RawDescriptionHelpFormatter
    parser = _Parser(prog="wavephys", description=__doc__, epilog=EXIT_CODES, formatter_class=fmt)
    parser.add_argument("--version", action="version", version=_version())
    sub = parser.add_subparsers(dest="command", parser_class=_Parser)
    v = sub.add_parser("validate", help="run the built-in physics validations", epilog=EXIT_CODES, formatter_class=fmt,
                       description="Run the built-in validations and print expected against measured.")
    v.add_argument("--json", metavar="PATH", help="also write the table as JSON (a .json file in an existing folder)")
    v.add_argument("--only", nargs="+", metavar="NAME", help="run only these checks (names from --list)")
    v.add_argument("--list", action="store_true", help="list the checks and exit")
    v.add_argument("--x64", action="store_true", help="run in float64")
    v.set_defaults(func=cmd_validate)
    r = sub.add_parser("run", help="simulate the built-in default scene (the main job)", epilog=EXIT_CODES,
                       formatter_class=fmt, description="Three stones in 16 m of open water; writes surface.npz "
                                                        "(heights, m) and surface.png.")
    r.add_argument("--n", type=_int(128, even=True, hi=MAX_N), default=256,
                   help=f"grid points per side (even, 128 to {MAX_N})")
    r.add_argument("--steps", type=_int(1, hi=MAX_STEPS), default=120, help=f"steps of 1/30 s (1 to {MAX_STEPS})")
    r.add_argument("--out", default="wavephys-out", help="output folder (created if its parent exists)")
    r.set_defaults(func=cmd_run)
    g = sub.add_parser("render", help="render a built-in scene with the headless moderngl renderer",
                       epilog=EXIT_CODES, formatter_class=fmt)
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
    t = sub.add_parser("textures", help="export a built-in scene's textures", epilog=EXIT_CODES, formatter_class=fmt)
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
    pl = sub.add_parser("plan", help="the cheapest model that meets a tolerance (the scene planner)",
                        epilog=EXIT_CODES + "\n  1  (plan) no model meets the tolerance", formatter_class=fmt,
                        description="Plan a scene (a TOML file, or a built-in: " + ", ".join(PLAN_SCENES) + "): "
                                    "print its model card.")
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
    rp = sub.add_parser("report", help="one self-contained HTML page of what is measured", epilog=EXIT_CODES,
                        formatter_class=fmt, description="Validation table, wake pattern and angles, ring waves, bench "
                                                         "charts, model cards, rendered frames: DIR/report.html.")
    rp.add_argument("--out", default="wavephys-report", help="output folder (created if its parent exists)")
    rp.add_argument("--checks", nargs="+", metavar="NAME", help="run only these validations (default: all)")
    rp.add_argument("--validation", metavar="JSON", help="show this 'wavephys validate --json' table instead")
    rp.add_argument("--figures", metavar="DIR", help="the bench charts' folder (default: the checkout's bench/figures)")
    rp.add_argument("--quick", action="store_true", help="smaller grids, one model card, one frame")
    rp.set_defaults(func=cmd_report)
    _add_check_parser(sub, fmt)
    return parser


def _add_calibrate_parser(sub, fmt) -> None:
    ca = sub.add_parser("calibrate", help="measure the planner's costs on this machine", epilog=EXIT_CODES,
                        formatter_class=fmt,
                        description="Time every piece the planner's cost model reads (steps, frames, shading, caustics, "
                                    "textures, float32 rounding) on this machine and its JAX device, and write them "
                                    "to a JSON file for 'wavephys plan --calibration FILE'. All tables took 7 minutes "
                                    "on a 2-core CPU; --only measures some.")
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
    return args.func(args, parser)


if __name__ == "__main__":
    sys.exit(main())
