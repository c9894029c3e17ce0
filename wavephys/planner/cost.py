"""Measured cost of a configuration: seconds on the machine a calibration was measured on.

A calibration (the shipped ``wavephys/planner/data/calibration.json``, which ``python -m bench
calibrate`` regenerates, or a file ``wavephys calibrate --out FILE`` writes on any machine:
:func:`load_calibration`) holds wall times of the pieces a scene's run is made of, each
measured after compilation (:mod:`wavephys.planner.measure`):

* ``step``: one simulation step by grid size n, linear and with the second-order term;
  ``step_walls``: the same in a walled tank (the cosine transforms of its modes);
  ``step_symmetric``: one leapfrog sub-step of one wet depth level of the symmetric depth
  stepper (a sloping floor), by n;
* ``ship``, ``ship_impulses``: one ship's patch per step, by patch side, its waves made by the
  Φ1/Φ2 kernels or by impulses;
* ``frame``: one output frame gathered and brought to the host, by the full grid's n;
* ``blend``: the extra of a Hermite frame between steps, by the simulated n;
* ``refine``: the extra of Fourier interpolation of a frame from a grid 2× coarser, by the fine n;
* ``fresnel``, ``absorption``: seconds per million pixels of each form, in the compiled shading;
* ``caustics``: one frame's floor irradiance by beam rasterization, by traced cells per side
  (texels × refinement); ``caustics_jacobian``: by the Jacobian gather, by the points it gathers a
  side (texels × its supersampling, ``"by": "points"``; older files: by texels);
* ``surface``: one output frame of each surface model other than the spectral step, by texels
  per side;
* ``texture``: encoding a frame into each height texture format, seconds per million texels;
* ``shade``: the rest of shading one frame (normals, angles, paths), by texels per side;
* ``run_overhead``: the fixed seconds of one run (state, sources, dispatch, host copies);
* ``kappa``: float32 rounding of a full run, max |η₃₂ − η₆₄| / (Σ|C|/n²).

Sizes between the measured ones are interpolated log-log; beyond them the cost is
extrapolated as n² log n from the nearest end (and said so in the model card).
"""

from __future__ import annotations

__internal__ = True  # the planner's own models: used through plan(), not fuzzed as public API

import json
import math
from functools import lru_cache
from importlib import resources

import numpy as np

from wavephys.planner.model import SceneModel

__all__ = ["calibration", "interpolate", "height_cost", "colour_cost", "caustics_cost", "texture_cost",
           "CALIBRATION_FILE", "CALIBRATION_KEYS", "load_calibration", "check_calibration", "describe_calibration"]

CALIBRATION_FILE = "calibration.json"

CALIBRATION_KEYS = frozenset({"step", "ship", "ship_impulses", "frame", "blend", "refine", "fresnel", "absorption",
                              "kappa", "caustics", "shade", "texture", "surface"})
"""The tables every calibration holds (``step_walls``, ``step_symmetric``, ``caustics_jacobian`` and
``run_overhead`` are read where a scene needs them, and refused by name where missing)."""

_SIZED = ("step", "step_walls", "step_symmetric", "ship", "ship_impulses", "frame", "blend", "refine", "caustics",
          "caustics_jacobian", "shade")
_PER_NAME = ("fresnel", "absorption", "texture")


@lru_cache(maxsize=1)
def calibration() -> dict:
    """The shipped calibration (see module doc).

    Returns
    -------
    dict
        The cost tables (seconds against size per operation) from the package's data, with
        ``"source": "shipped"``.
    """
    text = resources.files("wavephys.planner").joinpath("data", CALIBRATION_FILE).read_text()
    return {**json.loads(text), "source": "shipped"}


def _check_table(table, where: str) -> None:
    """A sized table: ``n`` ascending and > 0, each value list as long, finite and ≥ 0."""
    if not isinstance(table, dict) or "n" not in table:
        raise ValueError(f"{where} must be a table {{'n': [...], 'seconds': [...]}}, got {type(table).__name__}")
    ns = table["n"]
    if not isinstance(ns, list) or not ns or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                     for v in ns):
        raise ValueError(f"{where}['n'] must be a non-empty list of sizes, got {ns!r:.80}")
    if any(not (a > 0) for a in ns) or any(b <= a for a, b in zip(ns, ns[1:])):
        raise ValueError(f"{where}['n'] must be positive and ascending, got {ns}")
    values = [k for k in table if k != "n" and isinstance(table[k], list) and not k.startswith(("ratio", "work"))]
    if not values:
        raise ValueError(f"{where} has sizes but no seconds")
    for k in values:
        v = table[k]
        if len(v) != len(ns):
            raise ValueError(f"{where}[{k!r}] has {len(v)} values for {len(ns)} sizes")
        for i, x in enumerate(v):
            if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x) or x < 0:
                raise ValueError(f"{where}[{k!r}][{i}] must be seconds (finite, >= 0), got {x!r}")


def _check_seconds(x, where: str) -> None:
    if isinstance(x, bool) or not isinstance(x, (int, float)) or not math.isfinite(x) or x < 0:
        raise ValueError(f"{where} must be seconds (finite, >= 0), got {x!r}")


def check_calibration(cal, name: str = "calibration") -> dict:
    """Check that ``cal`` has the shape the cost model reads (module doc) and return it.

    Parameters
    ----------
    cal : dict
        A calibration, as :func:`load_calibration` returns.
    name : str
        What the error messages call it.

    Returns
    -------
    dict
        ``cal`` itself.

    Raises
    ------
    TypeError
        ``cal`` is not a dict.
    ValueError
        A table is missing, or a value is not finite seconds (the message names it).
    """
    if not isinstance(cal, dict):
        raise TypeError(f"{name} must be a dict (the shape of planner/data/calibration.json; "
                        f"load_calibration(FILE) reads one), got {type(cal).__name__}")
    missing = sorted(CALIBRATION_KEYS - set(cal))
    if missing:
        raise ValueError(f"{name} lacks {missing} (wavephys calibrate --out FILE measures every table)")
    for key in _SIZED:
        if key in cal:
            _check_table(cal[key], f"{name}[{key!r}]")
    for key in _PER_NAME:
        if not isinstance(cal[key], dict) or not cal[key]:
            raise ValueError(f"{name}[{key!r}] must map each form to seconds per million pixels")
        for form, x in cal[key].items():
            _check_seconds(x, f"{name}[{key!r}][{form!r}]")
    if not isinstance(cal["surface"], dict):
        raise ValueError(f"{name}['surface'] must map each surface model to a table")
    for model, table in cal["surface"].items():
        _check_table(table, f"{name}['surface'][{model!r}]")
    if "caustics_jacobian" in cal and cal["caustics_jacobian"].get("by", "texels") not in ("points", "texels"):
        raise ValueError(f"{name}['caustics_jacobian']['by'] must be 'points' or 'texels' (what its sizes count), "
                         f"got {cal['caustics_jacobian']['by']!r}")
    if "run_overhead" in cal:
        _check_seconds(cal["run_overhead"], f"{name}['run_overhead']")
    _check_seconds(cal["kappa"], f"{name}['kappa']")
    return cal


def load_calibration(path) -> dict:
    """Read a calibration file (what ``wavephys calibrate --out FILE`` writes) and check it.

    Parameters
    ----------
    path : str or os.PathLike
        The JSON file.

    Returns
    -------
    dict
        The calibration, with ``source`` set to the file's path (the model card names it).

    Raises
    ------
    TypeError
        ``path`` is not a path.
    ValueError
        The file is missing, is not JSON, or lacks a table (the message names the file and the
        table).
    """
    import os
    from pathlib import Path

    if not isinstance(path, (str, os.PathLike)) or (isinstance(path, str) and not path.strip()):
        raise TypeError(f"path must be a file system path (str or pathlib.Path), got {type(path).__name__}")
    p = Path(path)
    if not p.is_file():
        raise ValueError(f"calibration file {str(p)!r} does not exist (wavephys calibrate --out {p} writes one)")
    try:
        data = json.loads(p.read_text())
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise ValueError(f"calibration file {str(p)!r} is not JSON: {exc}") from None
    if not isinstance(data, dict):
        raise ValueError(f"calibration file {str(p)!r} holds a {type(data).__name__}, not a calibration")
    check_calibration(data, f"calibration file {str(p)!r}")
    return {**data, "source": str(Path(p))}


def describe_calibration(cal: dict) -> str:
    """One line for the model card: where the costs were measured, and which file holds them.

    Parameters
    ----------
    cal : dict
        A calibration (:func:`calibration` or a file of ``wavephys calibrate``).

    Returns
    -------
    str
    """
    where = ", ".join(str(cal[k]) for k in ("machine", "device") if cal.get(k)) or "an unnamed machine"
    date = f" on {cal['date']}" if cal.get("date") else ""
    return f"{cal.get('source', 'a calibration given as a dict')} ({where}{date})"


def interpolate(table: dict, n: float, key: str = "seconds") -> float:
    """Seconds at size ``n`` from a table ``{"n": [...], key: [...]}``: log-log between the
    measured sizes, n² log₂ n scaling beyond them.

    Parameters
    ----------
    table : dict
        ``{"n": sizes, key: values}``.
    n : float
        The size asked for.
    key : str
        The column read.

    Returns
    -------
    float
        Seconds.
    """
    ns, ts = np.asarray(table["n"], float), np.asarray(table[key], float)
    if n <= ns[0] or n >= ns[-1]:
        ref_n, ref_t = (ns[0], ts[0]) if n <= ns[0] else (ns[-1], ts[-1])
        return float(ref_t * (n * n * math.log2(max(n, 2))) / (ref_n * ref_n * math.log2(ref_n)))
    return float(np.exp(np.interp(math.log(n), np.log(ns), np.log(ts))))


def height_cost(model: SceneModel, cal: dict | None = None) -> dict:
    """Predicted seconds of the height output of ``model``: steps, ships, output frames, blends
    between steps, refinement onto the output texels, and their sum ``total`` (a surface model
    other than the spectral step: its frames alone).

    Parameters
    ----------
    model : SceneModel
        A scene and the height model's choices.
    cal : dict, optional
        A calibration (default: :func:`calibration`).

    Returns
    -------
    dict of str to float
        Seconds per part, and ``total``.
    """
    cal = cal or calibration()
    scene, c = model.scene, model.choices
    if c.surface != "spectral":  # evaluated at every frame on the output texels
        frames = interpolate(cal["surface"][c.surface], scene.texels) * scene.frames
        parts = dict(overhead=cal.get("run_overhead", 0.0), steps=0.0, ships=0.0, frames=frames, blend=0.0,
                     refine=0.0)
        parts["total"] = sum(parts.values())
        return parts
    n = model.grid.n
    steps = model.steps
    if model.walls and "step_walls" not in cal:
        raise ValueError("a walled tank's cost needs the calibration's step_walls table "
                         "(python -m bench calibrate --only step_walls)")
    step = interpolate(cal["step_walls" if model.walls else "step"], n, "second" if c.second_order else "first")
    if model.varying:  # the symmetric depth stepper: levels × sub-steps of its own unit
        if "step_symmetric" not in cal:
            raise ValueError("a sloping floor's cost needs the calibration's step_symmetric table "
                             "(python -m bench calibrate --only step_symmetric)")
        from wavephys.simulation.depth import symmetric_work

        levels, substeps = symmetric_work(model.simulation, model.floor())
        step = interpolate(cal["step_symmetric"], n) * levels * substeps
    table = cal["ship_impulses"] if c.ship_method == "impulses" else cal["ship"]
    ships = sum(interpolate(table, model.ship_patch) for _ in scene.ships)
    from wavephys.planner.runner import assembled_frames

    between = scene.frames - scene.frames // c.steps_per_frame
    assembled = assembled_frames(scene.frames)  # the last block's padding is computed too
    frames = interpolate(cal["frame"], model.full_grid.n) * assembled
    blend = interpolate(cal["blend"], n) * between
    refine = interpolate(cal["refine"], model.full_grid.n) * assembled if c.coarsen > 1 else 0.0
    parts = dict(overhead=cal.get("run_overhead", 0.0), steps=steps * step, ships=steps * ships, frames=frames,
                 blend=blend, refine=refine)
    parts["total"] = sum(parts.values())
    return parts


def colour_cost(scene, fresnel: str, absorption: str, cal: dict | None = None) -> float:
    """Predicted seconds of shading every output frame with these optics forms (the caustics
    apart: :func:`caustics_cost`).

    Parameters
    ----------
    scene : Scene
    fresnel : str
        A Fresnel form (:data:`optics.light.fresnel.REFLECTANCE_METHODS`).
    absorption : str
        An absorption method (:data:`optics.light.attenuation.WATER_TRANSMITTANCE_METHODS`).
    cal : dict, optional
        A calibration (default: :func:`calibration`).

    Returns
    -------
    float
        Seconds for the whole clip.
    """
    cal = cal or calibration()
    pixels = scene.texels**2 / 1e6
    per_frame = interpolate(cal["shade"], scene.texels) + pixels * (cal["fresnel"][fresnel] + cal["absorption"][absorption])
    return per_frame * scene.frames


def caustics_cost(scene, refine, cal: dict | None = None, gather_points: int | None = None) -> float:
    """Predicted seconds of the floor irradiance of every output frame at tracing refinement
    ``refine`` (0: off, free; ``"jacobian"``: the Jacobian gather; scenes without caustics: 0).
    ``gather_points``: the points a side the gather takes on the scene's frames (texels × its
    supersampling; :class:`~wavephys.planner.caustics.CausticsErrors`), which a table measured
    ``by`` points is read at; without it, or with a table by texels (a calibration written before
    2026-12-05), the scene's texels.

    Parameters
    ----------
    scene : Scene
    refine : int or str
        0 (off), a tracing refinement ≥ 1, or ``"jacobian"``.
    cal : dict, optional
        A calibration (default: :func:`calibration`).
    gather_points : int, optional
        Points a side of the Jacobian gather.

    Returns
    -------
    float
        Seconds for the whole clip.
    """
    if not refine or not scene.caustics:
        return 0.0
    cal = cal or calibration()
    if refine == "jacobian":
        if "caustics_jacobian" not in cal:
            raise ValueError("refine 'jacobian' needs the calibration's caustics_jacobian table "
                             "(python -m bench calibrate --only caustics_jacobian)")
        table = cal["caustics_jacobian"]
        side = gather_points if table.get("by") == "points" and gather_points else scene.texels
        return interpolate(table, side) * scene.frames
    return interpolate(cal["caustics"], scene.texels * refine) * scene.frames


def texture_cost(scene, fmt: str, cal: dict | None = None) -> float:
    """Predicted seconds of encoding every output frame into the height texture format ``fmt``
    (:data:`wavephys.planner.model.TEXTURES`; the renderer decodes on the GPU, for free).

    Parameters
    ----------
    scene : Scene
    fmt : str
        A height texture format.
    cal : dict, optional
        A calibration (default: :func:`calibration`).

    Returns
    -------
    float
        Seconds for the whole clip.
    """
    from wavephys.core.inputs import check_choice
    from wavephys.planner.model import TEXTURES

    check_choice("fmt", fmt, TEXTURES)
    cal = cal or calibration()
    return cal["texture"][fmt] * scene.texels**2 / 1e6 * scene.frames
