"""``wavephys check``: a record's frames, or a shader function, against the physics.

The options for a record are generated from the claims (:class:`wavephys.harness.Claims`, and any
claim a registered check brings): each claim's flag, value, help and the check that needs it come
from its one declaration, so a new check with a new claim is on the command line with no edit here.
This module imports nothing heavy until a command runs: ``--help`` answers at once.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

__internal__ = True  # the command's `check` subcommand: used through `wavephys check`, not fuzzed as public API
__all__ = ["add_check_parser", "cmd_check"]

_WAKE_FIELDS = (("at", "source", "X,Y", "where that source is in the first frame, m (default 0,0: the centre)"),
                ("heading", "direction", "DEG", "its heading, degrees, 0 = +x (default 0)"),
                ("size", "size", "M", "its size as a Gaussian pressure, m (wake_max check)"))


def _number(claim=None, lo=None, hi=None, lo_open=False, inf_ok=False):
    """An argparse type: a number or a fraction (1/60, 2/256) within the claim's range; finite (a deep-water depth
    is the default, not ``--depth inf``)."""
    if claim is not None:
        lo, hi, lo_open = claim.lo, claim.hi, claim.lo_open

    def parse(text: str) -> float:
        from wavephys.harness.claims import parse_number

        try:
            value = parse_number(text)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
        if not math.isfinite(value) and not (value == math.inf and inf_ok):
            raise argparse.ArgumentTypeError(f"must be a finite number, got {text}")
        if (lo is not None and (value < lo or (lo_open and value == lo))) or (hi is not None and value > hi):
            raise argparse.ArgumentTypeError(f"must be {'>' if lo_open else '≥'} {lo:g}" if lo is not None else
                                             f"must be ≤ {hi:g}" + f", got {text}")
        return value

    if lo is not None:
        parse.limits = (lo, hi, lo_open)  # for the tests: the documented range (lo, hi, lo excluded)
    return parse


def _pair(kind="pair"):
    def parse(text: str):
        """``X,Y``: two numbers (fractions accepted)."""
        from wavephys.harness.claims import parse_number

        parts = text.split(",")
        try:
            values = tuple(parse_number(p) for p in parts)
        except ValueError:
            values = ()
        if len(values) != 2 or not all(math.isfinite(v) or (kind == "range" and v == math.inf) for v in values):
            raise argparse.ArgumentTypeError(f"expected {'LO,HI (rad/m)' if kind == 'range' else 'X,Y (m)'}, "
                                             f"got {text!r}")
        return values
    return parse


def _dest(name: str) -> str:
    return "claim_" + name


def add_claim_options(ck) -> None:
    """One option per claim (fields of Claims, then registered checks' own), from the claims' declarations."""
    from wavephys.harness.claims import claim_fields

    for c in claim_fields().values():
        kw = dict(dest=_dest(c.name), help=c.help)
        if c.metavar:
            kw["metavar"] = c.metavar
        if c.kind == "flag":
            ck.add_argument(c.option, action="store_true", dest=_dest(c.name), help=c.help)
        elif c.kind == "number":
            ck.add_argument(c.option, type=_number(c), **kw)
        elif c.kind in ("pair", "range"):
            ck.add_argument(c.option, type=_pair(c.kind), **kw)
        elif c.kind == "choice":
            ck.add_argument(c.option, choices=c.choices, **{k: v for k, v in kw.items() if k != "metavar"})
        elif c.kind in ("map", "array"):
            ck.add_argument(c.option, **kw)
        elif c.kind == "frames":
            ck.add_argument(c.option, nargs="+", **kw)
        elif c.kind == "dam":
            ck.add_argument(c.option, nargs="+", type=_number(), **kw)
        elif c.kind == "wake":
            ck.add_argument(c.option, type=_number(lo=0.0, lo_open=True), **kw)
            for suffix, _, metavar, help_ in _WAKE_FIELDS:
                parse = _pair() if suffix == "at" else _number(lo=0.0, lo_open=True) if suffix == "size" else \
                    _number(lo=-360.0, hi=360.0)
                ck.add_argument(f"{c.option}-{suffix}", type=parse, metavar=metavar, help=help_,
                                dest=_dest(f"{c.name}_{suffix}"))


def _checks_help() -> str:
    from wavephys.harness.claims import claim_fields
    from wavephys.harness.suite import RECORD_CHECKS

    fields = claim_fields()
    lines = []
    for name, row in RECORD_CHECKS.items():
        needs = ", ".join(fields[n].option for n in row.needs) if row.needs else ""
        lines.append(f"  {name:15s} {row.measures}" + (f" (needs {needs})" if needs else ""))
    return "\n".join(lines)


def add_check_parser(sub, fmt, parser_class, helpers) -> None:
    """The ``check`` subcommand (exported frames, or a shader function, against the physics).

    Parameters
    ----------
    sub : argparse subparsers
        Where the subcommand goes.
    fmt : type
        The help formatter.
    parser_class : type
        The command's parser class (usage errors on one line).
    helpers : dict
        The command's shared argument types: ``setting`` (KEY=VALUE) and ``checked`` (an output path check).
    """
    from wavephys.app.commands import COMMANDS

    ck = sub.add_parser("check", help=COMMANDS["check"].help, epilog=COMMANDS["check"].epilog(), formatter_class=fmt,
                        description="Frames: read a folder, glob or list of EXR / 16-bit PNG / npy / npz height "
                                    "frames (dx, dt and units from the files' headers where they say, else from "
                                    "--dx and --dt) and print each check's verdict and, on failure, its likely "
                                    "cause.\n\n  wavephys check out/frames --sea --direction 0\n  wavephys check "
                                    "'export/h_*.exr' --dx 0.05 --dt 1/60 --depth 0.5 --junit checks.xml\n\nChecks "
                                    "on a record (and the claims each needs):\n" + _checks_help() +
                                    "\n\nShaders: compile a function (GLSL, GLSL ES, WebGL, Shadertoy, Godot, or HLSL "
                                    "through glslang and SPIRV-Cross) on the headless OpenGL context, evaluate it "
                                    "over its whole input domain and compare it with the physics; its constants (F0, "
                                    "the index ratio) are found from its output and judged against water's range."
                                    "\n\n  wavephys check --glsl water.glsl --function fresnel --against fresnel\n"
                                    "  wavephys check --hlsl Water.hlsl --function FresnelSchlick --against fresnel")
    ck.add_argument("frames", nargs="*", metavar="FRAMES", help="a folder, glob pattern or files of height frames")
    frames = ck.add_argument_group("frames", "how to read them")
    frames.add_argument("--dx", type=_number(lo=0.0, lo_open=True), help="grid spacing, m: 0.05 or 2/256 (when the "
                                                                         "files do not say)")
    frames.add_argument("--dt", type=_number(lo=0.0, lo_open=True), help="time between frames, s: 0.0167 or 1/60 "
                                                                         "(when the files do not say)")
    frames.add_argument("--axes", choices=("tyx", "yxt", "txy", "xyt", "ytx", "xty"),
                        help="the layout of one .npy/.npz array of frames (yxt: time last); needed when its shape "
                             "could be read more than one way")
    frames.add_argument("--channel", metavar="NAME", help="the EXR channel holding the heights (default Y or the "
                                                          "only one)")
    frames.add_argument("--png-range", type=_pair(), metavar="OFFSET,AMPLITUDE",
                        help="16-bit PNGs without a JSON sidecar: heights = OFFSET + AMPLITUDE × level/65535, m "
                             "(without it such PNGs are refused: their levels do not say metres); write "
                             "--png-range=-0.5,1 when OFFSET is negative")
    frames.add_argument("--only", nargs="+", metavar="CHECK", help="run only these checks (names above)")
    frames.add_argument("--junit", metavar="PATH", help="also write JUnit XML for a CI server")
    add_claim_options(ck.add_argument_group("claims", "what the frames are (each check's needs above)"))
    sh = ck.add_argument_group("shaders")
    sh.add_argument("--glsl", metavar="FILE", help="the GLSL source that defines the function (GLSL ES, WebGL, "
                                                   "Shadertoy and Godot shader files are read as written)")
    sh.add_argument("--hlsl", metavar="FILE", help="the HLSL source that defines the function (Unity, Unreal, Crest): "
                                                   "translated by glslang and SPIRV-Cross (apt-get install "
                                                   "glslang-tools spirv-cross)")
    sh.add_argument("--shader", metavar="FILE", help="a shader source in any of those languages (--language)")
    sh.add_argument("--language", default="auto", choices=("auto", "glsl", "glsl_es", "webgl", "shadertoy", "godot",
                                                           "hlsl"), help="the source's language (default: told from "
                                                                         "the text)")
    sh.add_argument("--define", action="append", metavar="NAME=VALUE", help="a macro the source relies on, e.g. "
                                                                            "UNITY_PI=3.14159265 (repeatable)")
    sh.add_argument("--include", action="append", metavar="DIR", help="a folder for the source's #include lines "
                                                                      "(repeatable)")
    sh.add_argument("--function", metavar="NAME", help="the function to check")
    sh.add_argument("--result", metavar="NAME", help="the out parameter that holds the result (default: the return "
                                                     "value, or a void function's only out parameter)")
    sh.add_argument("--against", metavar="CHECK", help="what it computes: fresnel, refract, reflect, transmittance, "
                                                        "rgb_absorption, normal_decode, height_normal (see --list)")
    sh.add_argument("--takes", metavar="ROLE,...", help="what each parameter is, in order (roles from --list, or a "
                                                        "number to hold one fixed; default: the check's own, else "
                                                        "read from the names)")
    sh.add_argument("--returns", metavar="TYPE", help="the return type you expect (float, vec3)")
    sh.add_argument("--option", type=helpers["setting"], action="append", metavar="KEY=VALUE",
                    help="an option of the check, e.g. form=schlick, sides=above, convention=directx, bits=10 "
                         "(repeatable)")
    sh.add_argument("--uniform", type=helpers["setting"], action="append", metavar="NAME=VALUE",
                    help="a value for a uniform the function reads, e.g. uF0=0.02 or uTint=0.1,0.2,0.3 (repeatable)")
    sh.add_argument("--tolerance", type=_number(lo=0.0, lo_open=True), default=None,
                    help="largest error allowed (default: the check's, from physics and the display)")
    sh.add_argument("--chart", metavar="PATH", help="also draw the error over the domain (a .png)")
    sh.add_argument("--list", action="store_true", help="list the shader checks, their roles and options, and exit")
    ck.add_argument("--json", metavar="PATH", help="also write the report as JSON")
    ck.set_defaults(func=lambda args, parser: cmd_check(args, parser, helpers))


def _option_words(text: str) -> str:
    """A message of the harness in the command's words: each claim's Python name at the start of a clause
    becomes its option (``bed must …`` → ``--bed must …``), ``only:`` becomes ``--only:``."""
    import re

    from wavephys.harness.claims import claim_fields

    text = re.sub(r"^only:", "--only:", text)
    for c in claim_fields().values():  # "direction= (--direction DEG)" → "--direction DEG"
        text = text.replace(c.words(), c.option + (f" {c.metavar}" if c.metavar and c.kind != "flag" else ""))
    text = re.sub(r"[\w']+(?:\[[^\]]*\])?=(?:dict\([^)]*\))? \((--[\w-]+(?: [^)]*)?)\)", r"\1", text)
    for name, c in sorted(claim_fields().items(), key=lambda kv: -len(kv[0])):
        text = re.sub(rf"(^|; |\()({name})(\[|\b(?=[ :]))", lambda m: m.group(1) + c.option + (
            m.group(3) if m.group(3) == "[" else ""), text)
    return text


def _given(args) -> dict:
    """The claims the command line makes, by name, as the options gave them (files not read yet)."""
    from wavephys.harness.claims import claim_fields

    made = {}
    for name, c in claim_fields().items():
        value = getattr(args, _dest(name), None)
        if c.kind == "wake":
            extra = {f: getattr(args, _dest(f"{name}_{s}"), None) for s, f, _, _ in _WAKE_FIELDS}
            if value is None:
                if any(v is not None for v in extra.values()):
                    raise ValueError(f"{c.option}-at, {c.option}-heading and {c.option}-size describe a moving "
                                     f"source: give its speed with {c.option} U")
                continue
            value = dict(speed=value, **{k: v for k, v in extra.items() if v is not None})
        elif c.kind == "dam" and value is not None:
            if len(value) not in (2, 3):
                raise ValueError(f"{c.option} takes X H0 [HR] (m), got {len(value)} values")
            value = dict(zip(("x", "h0", "hr"), value))
        if c.given(value):
            made[name] = value
    return made


def _read(c, value, channel):
    """A file claim read: a map (EXR/PNG/npy), an array (.npy), or frames (another record)."""
    import numpy as np

    from wavephys.core.frames import read_map
    from wavephys.harness import Record

    if c.kind == "map":
        return read_map(value, name=c.option, channels=3 if c.name == "normals" else 1)
    if c.kind == "array":
        try:
            return np.load(value, allow_pickle=False)
        except (OSError, ValueError, EOFError) as exc:
            raise ValueError(f"{c.option}: cannot read {value} as a .npy array: {exc}") from None
    if c.kind == "frames":
        return Record.from_files(value[0] if len(value) == 1 else list(value), channel=channel)
    return value


def _refuse_early(parser, args, made) -> None:
    """What can be said before any frame is read: unknown or impossible --only checks, claims without the claims
    they require."""
    from wavephys.harness.claims import claim_fields
    from wavephys.harness.suite import RECORD_CHECKS

    fields = claim_fields()
    if args.only:
        unknown = [n for n in args.only if n not in RECORD_CHECKS]
        if unknown:
            parser.error(f"--only: unknown check(s) {', '.join(unknown)}; the checks are {', '.join(RECORD_CHECKS)}")
        from types import SimpleNamespace

        view = SimpleNamespace(**{name: made.get(name, fields[name].default) for name in fields})
        for n in args.only:
            row = RECORD_CHECKS[n]
            missing = [fields[x].option for x in row.needs if x not in made]
            if not missing and row.also is not None and row.also(view):
                import re

                said = re.search(r"\((--[\w-]+)[^)]*\)", row.also(view))
                missing = [said.group(1) if said else row.also(view)]
            if missing:
                parser.error(f"--only: the {n} check needs {', '.join(missing)}")
    for name in made:
        missing = [fields[r].option for r in fields[name].requires if r not in made]
        if missing:
            parser.error(f"{fields[name].option} describes {', '.join(missing)}: give {', '.join(missing)} too")


def cmd_check_frames(args, parser, helpers) -> int:
    """``wavephys check FRAMES...``: the record's checks, their verdicts and causes."""
    from wavephys.core.files import atomic_path, output_file

    json_path = helpers["checked"](parser, output_file, args.json, "--json", (".json",)) if args.json else None
    junit_path = helpers["checked"](parser, output_file, args.junit, "--junit", (".xml",)) if args.junit else None
    try:
        made = _given(args)
    except ValueError as exc:
        parser.error(str(exc))
    _refuse_early(parser, args, made)
    from wavephys import Water
    from wavephys.harness import Record, check_record
    from wavephys.harness.claims import claim_fields

    fields = claim_fields()
    source = args.frames[0] if len(args.frames) == 1 else list(args.frames)
    try:
        record = Record.from_files(source, dx=args.dx, dt=args.dt, channel=args.channel, axes=args.axes,
                                   png_range=args.png_range)
        made = {n: _read(fields[n], v, args.channel) for n, v in made.items()}
    except (TypeError, ValueError) as exc:
        print(f"wavephys check: {_frames_words(exc)}", file=sys.stderr)
        return 2
    nt, ny, nx = record.shape
    print(f"{record.source}: {nt} frames of {nx} x {ny}, dx = {record.dx:.6g} m, dt = {record.dt:.6g} s", flush=True)
    try:
        report = check_record(record, Water(), only=args.only, progress=lambda m: print(m, file=sys.stderr,
                                                                                        flush=True), **made)
    except (TypeError, ValueError) as exc:  # the claims against the frames: the options' names, not Python's
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


def _frames_words(exc) -> str:
    """An error about the frames in the command's words: the frames are FRAMES, a saved record's path too."""
    import re

    return re.sub(r"^(source|path)(\[\d+\])?:", lambda m: "FRAMES" + (m.group(2) or "") + ":", str(exc))


def cmd_check(args, parser, helpers) -> int:
    """``wavephys check``: frames (a record) or a shader function.

    Parameters
    ----------
    args : argparse.Namespace
        The parsed options.
    parser : argparse.ArgumentParser
        For usage errors (exit 2).
    helpers : dict
        The command's shared argument types (``setting``, ``checked``).

    Returns
    -------
    int
        The exit status: 0 ok, 1 a check failed, 2 a usage error, 3 no OpenGL context or translator.
    """
    if args.frames:
        if args.glsl is not None or args.hlsl is not None or args.shader is not None or args.list:
            parser.error("give either FRAMES (a record) or --glsl/--hlsl/--shader FILE (a shader), not both")
        return cmd_check_frames(args, parser, helpers)
    if args.list:
        from optics.shaders import SHADER_CHECKS, describe_check

        print("\n\n".join(describe_check(name) for name in SHADER_CHECKS))
        return 0
    return _cmd_check_shader(args, parser, helpers)


def _read_source(parser, path: str, flag: str) -> str:
    p = Path(path)
    if not p.is_file():
        parser.error(f"{flag}: no file at {path}" if not p.exists() else f"{flag}: {path} is not a file")
    try:
        return p.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        parser.error(f"{flag}: {path} is not a UTF-8 text file (shader source expected)")
    except OSError as exc:
        parser.error(f"{flag}: cannot read {path} ({exc.strerror})")


def _cmd_check_shader(args, parser, helpers) -> int:
    from wavephys.core.files import atomic_path, output_file

    shader = [(flag, path) for flag, path in (("--glsl", args.glsl), ("--hlsl", args.hlsl), ("--shader", args.shader))
              if path is not None]
    if len(shader) > 1:
        parser.error(f"give one of --glsl, --hlsl and --shader, not {' and '.join(f for f, _ in shader)}")
    if not shader or args.function is None or args.against is None:
        parser.error("give FRAMES... (exported frames), or --glsl FILE (or --hlsl, --shader), --function NAME and "
                     "--against CHECK (names from --list)")
    flag, path = shader[0]
    source = _read_source(parser, path, flag)
    language = "hlsl" if flag == "--hlsl" else args.language
    json_path = helpers["checked"](parser, output_file, args.json, "--json", (".json",)) if args.json else None
    chart = helpers["checked"](parser, output_file, args.chart, "--chart", (".png",)) if args.chart else None
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
