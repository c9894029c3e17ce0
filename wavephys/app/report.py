"""``wavephys report``: one self-contained HTML page a person can read.

The page holds, with every image embedded (no network or other file needed to view it):
the validation table with pass/fail, a steady wake with its measured angles, ring waves
from the default scene, the speed/accuracy charts and failure boundaries of the bench
(``bench/figures`` of a checkout, when there is one), the planner's model cards for the
built-in scenes with one Pareto chart, and frames rendered by the headless renderer.

A script at the end of the page counts the images that decoded and the script errors, and
writes them on ``<body>`` (``data-images``, ``data-images-loaded``, ``data-errors``), so a
headless browser can check the page (``tests/app/test_report.py`` does, with Chromium).
"""

from __future__ import annotations

import base64
import html
import io
import json
import time
from pathlib import Path
from typing import Callable, Optional

__all__ = ["build_report", "read_validation", "FIGURES", "ReportInterrupted"]

FIGURES = Path(__file__).resolve().parents[2] / "bench" / "figures"
"""The bench's charts in a checkout (absent from an installed package: the report says so)."""

_CSS = """
body { font: 15px/1.45 system-ui, sans-serif; max-width: 1100px; margin: 2em auto; padding: 0 1em; color: #1b1f24; }
h1 { font-size: 1.6em; } h2 { margin-top: 2em; border-bottom: 1px solid #ccd; padding-bottom: .2em; }
table { border-collapse: collapse; font-size: 13px; width: 100%; }
td, th { border-bottom: 1px solid #e3e6ea; padding: 3px 6px; text-align: left; vertical-align: top; }
td.ok { color: #116329; font-weight: 600; } td.fail { color: #b3261e; font-weight: 700; }
img { max-width: 100%; border: 1px solid #e3e6ea; margin: .4em 0; }
pre { background: #f6f8fa; padding: .8em; overflow-x: auto; font-size: 12px; }
figure { margin: 1em 0; } figcaption { font-size: 13px; color: #57606a; }
.summary { font-size: 1.1em; }
"""

_CHECK_SCRIPT = """
<script>
window.__errors = 0;
window.addEventListener('error', function () { window.__errors += 1; document.body.dataset.errors = window.__errors; }, true);
window.addEventListener('load', function () {
  var imgs = Array.prototype.slice.call(document.images);
  var ok = imgs.filter(function (i) { return i.complete && i.naturalWidth > 0; }).length;
  document.body.dataset.images = imgs.length;
  document.body.dataset.imagesLoaded = ok;
  document.body.dataset.errors = window.__errors;
});
</script>
"""


def _png(fig_or_path) -> str:
    """An <img> of a matplotlib figure or a PNG file, as a data URI."""
    if isinstance(fig_or_path, (str, Path)):
        data = Path(fig_or_path).read_bytes()
    else:
        buf = io.BytesIO()
        fig_or_path.savefig(buf, format="png", dpi=100)
        data = buf.getvalue()
    return f'<img alt="" src="data:image/png;base64,{base64.b64encode(data).decode()}">'


def _figure(img: str, caption: str) -> str:
    return f"<figure>{img}<figcaption>{html.escape(caption)}</figcaption></figure>"


_ROW_KEYS = ("quantity", "expected", "measured", "relation", "margin", "ok")


def read_validation(path) -> list:
    """The rows of a ``wavephys validate --json`` file, checked: a JSON list of rows with their keys.

    Parameters
    ----------
    path : str or os.PathLike
        The file.

    Returns
    -------
    list of dict
        The rows.

    Raises
    ------
    ValueError
        When the file is missing, not UTF-8 JSON, or not a list of validation rows (the message names ``path``
        and the file).
    """
    from wavephys.core.files import _as_path

    p = _as_path("path", path)
    if not p.is_file():
        raise ValueError(f"path: {str(p)!r} is not a file (write one with wavephys validate --json)")
    try:
        rows = json.loads(p.read_text(encoding="utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError) as exc:
        raise ValueError(f"path: {str(p)!r} is not a JSON file of validation rows ({type(exc).__name__}: "
                         f"{str(exc)[:120]})") from None
    if not isinstance(rows, list) or not all(isinstance(r, dict) and all(k in r for k in _ROW_KEYS) for r in rows):
        raise ValueError(f"path: {str(p)!r} must hold a list of rows with {', '.join(_ROW_KEYS)} "
                         f"(what wavephys validate --json writes)")
    for r in rows:
        if not isinstance(r["quantity"], str) or not all(
                isinstance(r[k], (int, float)) and not isinstance(r[k], bool) for k in ("expected", "measured", "margin")):
            raise ValueError(f"path: {str(p)!r} has a row whose quantity is not text or whose numbers are not "
                             f"numbers: {str(r)[:120]}")
    return rows


def _validation(names, validation: Optional[Path], say) -> str:
    if validation is not None:
        rows = read_validation(validation)
        source = f"from {html.escape(str(validation))}"
    else:
        from wavephys.app.registry import registry

        reg = registry()
        names = list(reg) if names is None else names
        rows = []
        for i, name in enumerate(names):
            say(f"[validate {i + 1}/{len(names)}] {name}")
            got = reg[name]()
            for r in got:  # each row as it finishes
                say(f"  {'ok  ' if r.ok else 'FAIL'}  {r.quantity}: {r.measured:.6g}")
            rows += [r.as_dict() for r in got]
        source = f"measured now ({', '.join(names)})"
    failed = [r for r in rows if not r["ok"]]
    head = "<tr><th>quantity</th><th>expected</th><th>measured</th><th>margin</th><th>verdict</th></tr>"
    body = "".join(
        f"<tr><td>{html.escape(r['quantity'])}{(' [' + html.escape(r['unit']) + ']') if r.get('unit') else ''}</td>"
        f"<td>{html.escape(str(r['relation']))} {r['expected']:.6g}</td><td>{r['measured']:.6g}</td>"
        f"<td>{r['margin']:.2g}</td><td class=\"{'ok' if r['ok'] else 'fail'}\">{'pass' if r['ok'] else 'FAIL'}</td></tr>"
        for r in rows)
    return (f"<p class=\"summary\">{len(rows) - len(failed)} of {len(rows)} rows pass ({source}).</p>"
            f"<table>{head}{body}</table>")


def _wake(quick: bool, say) -> str:
    from wavephys import Grid, Water
    from wavephys.harness import wake_angle
    from wavephys.physics.wake import KELVIN_ANGLE, GaussianPressure, steady_wake
    from wavephys.plot import plot_wake

    say("steady wake ...")
    grid, water, speed = Grid(384 if quick else 1024, 40.0), Water(sigma=0.0), 1.0
    eta = steady_wake(grid, water, speed, GaussianPressure(100.0, 0.125))
    largest = wake_angle(eta, grid, near=2.0, far=16.0)
    edge = wake_angle(eta, grid, method="cusp", speed=speed, near=3.0, far=14.0)
    fig = plot_wake(eta, float(grid.dx), angle=[largest, edge], window=(-16, 2, -8, 8),
                    title="steady wake, U = 1 m/s, σ = 0.125 m")
    return (f"<p>Angle of the largest waves {largest.angle:.2f}° ± {largest.uncertainty:.2f}°; outer edge "
            f"{edge.angle:.2f}° ± {edge.uncertainty:.2f}° (Kelvin {KELVIN_ANGLE:.2f}°), on {grid.n}² × "
            f"{float(grid.length):g} m.</p>" + _figure(_png(fig), "solid: maximum; dotted: outer edge"))


def _rings(quick: bool, say) -> str:
    from wavephys.app.scenes import default_scene
    from wavephys.plot import plot_surface

    say("ring waves ...")
    result = default_scene(n=128 if quick else 256, steps=60)
    fig = plot_surface(result["eta"], result["dx"], title=f"three stones after {result['time']:.1f} s")
    return (f"<p>The default scene (<code>wavephys run</code>): energy after / before without the cutoff "
            f"{result['energy_ratio']:.7f}.</p>" + _figure(_png(fig), "heights, m"))


def _bench(figures: Path) -> str:
    if not figures.is_dir():
        return ("<p>No bench charts here: run the report from a checkout (they are in "
                "<code>bench/figures</code>), or regenerate them with <code>python -m bench …</code>.</p>")
    pngs = sorted(figures.glob("*.png"))
    speed = [p for p in pngs if not p.stem.startswith("boundaries")]
    bounds = [p for p in pngs if p.stem.startswith("boundaries")]
    out = "<h3>Speed against accuracy</h3>" + "".join(_figure(_png(p), p.stem.replace("_", " ")) for p in speed)
    out += "<h3>Failure boundaries</h3>" + "".join(_figure(_png(p), p.stem.replace("_", " ")) for p in bounds)
    return out


def _planner(quick: bool, say) -> str:
    from wavephys.planner import BUILTIN_SCENES, Infeasible, builtin_scene, plan
    from wavephys.planner.charts import plot_plan

    names = BUILTIN_SCENES[2:3] if quick else BUILTIN_SCENES
    out = ""
    for i, name in enumerate(names):
        say(f"[plan {i + 1}/{len(names)}] {name}")
        scene = builtin_scene(name)
        try:
            p = plan(scene, scene.height_quantum)
        except Infeasible as exc:
            out += f"<h3>{name}</h3><p>{html.escape(str(exc))}</p>"
            continue
        out += f"<h3>{name}</h3><pre>{html.escape(p.card())}</pre>"
        if i == 0:
            out += _figure(_png(plot_plan(p)), f"{name}: candidate models and the error budget of the chosen one")
    return out


def _frames(quick: bool, say) -> str:
    from optics.rendering.renderer import Renderer, RendererUnavailable, to_srgb8
    from wavephys.app.scenes import builtin_scene

    say("rendering ...")
    try:
        renderer = Renderer(320, 240) if quick else Renderer(640, 480)
    except RendererUnavailable as exc:
        return f"<p>No OpenGL context here: {html.escape(str(exc))}</p>"
    import numpy as np
    from PIL import Image

    out = ""
    with renderer:
        for name in (("calm",) if quick else ("pool", "shore", "ship", "storm")):  # quick: the cheapest to build
            image = renderer.render(builtin_scene(name, n=128 if quick else 256))
            buf = io.BytesIO()
            Image.fromarray(to_srgb8(np.asarray(image))).save(buf, format="PNG")
            img = f'<img alt="{name}" src="data:image/png;base64,{base64.b64encode(buf.getvalue()).decode()}">'
            out += _figure(img, f"{name} ({renderer.renderer_name})")
    return out


def build_report(out_dir, checks=None, validation=None, figures=None, quick: bool = False,
                 progress: Optional[Callable[[str], None]] = None) -> Path:
    """Write ``out_dir/report.html`` (module doc) and return its path.

    The page holds the validation table, a steady wake, ring waves from the default scene,
    the bench charts, the planner's model cards and rendered frames, every image embedded.
    It is written atomically (a partial page never replaces a complete one).

    Parameters
    ----------
    out_dir : str or os.PathLike
        Folder to write ``report.html`` into; created (one level) if missing. Its parent must
        exist and be writable.
    checks : list of str, optional
        Names of the validations to run (keys of :func:`wavephys.app.registry.registry`);
        default: all.
    validation : str or os.PathLike, optional
        A JSON file from ``wavephys validate --json`` to show instead of running the validations
        (``checks`` is then still checked against the registry, but nothing is run). Must be an existing file.
    figures : str or os.PathLike, optional
        The bench charts' folder (default: the checkout's ``bench/figures``, :data:`FIGURES`); when
        it is not a folder the page says so.
    quick : bool
        Smaller grids, one planner scene and one frame, and (unless ``checks`` or ``validation`` says) every
        validation group but the long ones (:data:`~wavephys.app.registry.LONG_CHECKS`).
    progress : callable, optional
        Called with one message (str) as each part of the page starts.

    Returns
    -------
    pathlib.Path
        The path of the written page, ``out_dir/report.html``.

    Raises
    ------
    ValueError
        When ``out_dir`` is not a usable folder, ``validation`` is not a file, or a name in
        ``checks`` is unknown.
    ReportInterrupted
        On Ctrl-C (a ``KeyboardInterrupt``), after writing the page with the sections finished and a line
        naming those missing.
    TypeError
        When ``quick`` is not a bool.
    """
    from wavephys.core.files import atomic_path, output_folder
    from wavephys.core.inputs import check_bool

    out = output_folder(out_dir, "out_dir")
    check_bool("quick", quick)
    if validation is not None and not Path(validation).is_file():
        raise ValueError(f"validation: {str(validation)!r} is not a file (write one with wavephys validate --json)")
    if checks is not None:
        from wavephys.app.registry import registry

        known = registry()
        unknown = [c for c in checks if c not in known]
        if unknown:
            raise ValueError(f"checks: unknown {unknown}; 'wavephys validate --list' names them")
    say = progress or (lambda _m: None)
    start = time.perf_counter()
    if checks is None and validation is None and quick:  # --quick: the long groups are left to validate --all
        from wavephys.app.registry import LONG_CHECKS, registry

        checks = [n for n in registry() if n not in LONG_CHECKS]
    parts = [("Validation", lambda: _validation(checks, validation, say)), ("Wake pattern", lambda: _wake(quick, say)),
             ("Ring waves", lambda: _rings(quick, say)),
             ("Bench", lambda: _bench(Path(figures) if figures else FIGURES)),
             ("Model cards of the built-in scenes", lambda: _planner(quick, say)),
             ("Rendered frames", lambda: _frames(quick, say))]
    sections, stopped = [], None
    for title, make in parts:
        try:
            sections.append((title, make()))
        except KeyboardInterrupt:  # Ctrl-C: the page keeps the sections finished, and says what is missing
            stopped = title
            break
    from wavephys import __version__

    body = "".join(f"<h2>{html.escape(t)}</h2>{s}" for t, s in sections)
    if stopped is not None:
        missing = ", ".join(t for t, _ in parts[len(sections):])
        body = (f"<p class=\"summary fail\">Interrupted (Ctrl-C) while building {html.escape(stopped)}: "
                f"missing {html.escape(missing)}.</p>") + body
    page = (f"<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>wavephys report</title>"
            f"<style>{_CSS}</style></head><body><h1>wavephys {__version__}: what is measured</h1>"
            f"<p>Generated {time.strftime('%Y-%m-%d %H:%M')} in {time.perf_counter() - start:.0f} s. Every figure is "
            f"measured by the code that ships; see docs/physics.md and docs/planner.md.</p>{body}{_CHECK_SCRIPT}"
            f"</body></html>")
    path = out / "report.html"
    with atomic_path(path) as tmp:
        tmp.write_text(page, encoding="utf-8")
    if stopped is not None:
        raise ReportInterrupted(path, stopped)
    return path


class ReportInterrupted(KeyboardInterrupt):
    """Ctrl-C stopped :func:`build_report`: the page was written with the sections finished before it.

    Attributes
    ----------
    path : pathlib.Path
        The page written.
    section : str
        The section being built when it was stopped (it and those after it are missing).
    """

    def __init__(self, path, section):
        super().__init__(f"interrupted while building {section}; the page so far: {path}")
        self.path, self.section = path, section
