"""The registry of checks: every validation the project runs, by name, in one place.

``wavephys validate`` prints its rows, the test suite asserts them (parametrized over
:data:`REGISTRY`), and the report shows them. It joins the wave physics validations
(:data:`wavephys.checks.CHECKS`), the optics ones (:data:`optics.checks.CHECKS`) and the
renderer on the built-in scenes (here, because those scenes are the application's).
"""

from __future__ import annotations

from typing import Callable


from wavephys.harness.checks import Check, bound

__all__ = ["REGISTRY", "registry", "run", "check_builtin_scenes", "LONG_CHECKS", "EDGE_PIXELS"]

LONG_CHECKS = ("reflecting-walls", "varying-depth", "shallow-water", "second-order-heights", "steady-wakes",
               "gerstner-waves", "choppy-waves", "caustics", "builtin-scenes")
"""The check groups ``wavephys validate`` (and ``wavephys report --quick``) leave to ``--all`` (or ``--only``):
each 7.5 s or more on a 2-core CPU (measured, s: reflecting-walls 8, varying-depth 9, shallow-water 20,
second-order-heights 10, steady-wakes 21, gerstner-waves 9, choppy-waves 8, caustics 35, builtin-scenes 123 of a
264 s full run); the others run by default. The test suite and the full report run every group."""


EDGE_PIXELS = 8
"""Most pixels of a built-in scene's frame that :func:`check_builtin_scenes` compares with the reference within a
hundredth of a pixel (where a ray grazes an edge): 0–2 measured on each scene at 160 × 120."""


def check_builtin_scenes(width: int = 160, height: int = 120, n: int = 128) -> list[Check]:
    """The GPU renderer against the CPU reference on each built-in scene, every effect on (PSNR).

    Each scene of :data:`wavephys.app.SCENES` is made by :func:`wavephys.app.scenes.builtin_scene`,
    rendered by :class:`optics.rendering.renderer.Renderer` and traced by the CPU reference
    (:func:`optics.rendering.reference.trace`); the two images must agree to a PSNR of at least 100 dB,
    a pixel's reference being what the reference traces within a hundredth of a pixel of its centre
    (:func:`optics.rendering.reference.psnr_against_reference`: where a ray grazes an edge, float32 and
    float64 may land on either side of it).

    Parameters
    ----------
    width : int
        Image width, pixels, ≥ 1 (checked by the renderer).
    height : int
        Image height, pixels, ≥ 1 (checked by the renderer).
    n : int
        Height-field resolution of each scene, texels per side, even, 64 to 8192 (checked by
        :func:`~wavephys.app.scenes.builtin_scene`).

    Returns
    -------
    list of Check
        Two rows per built-in scene: the PSNR of the GPU image against the CPU reference, dB, ``">="``
        100 dB; the pixels compared at an edge (those a shifted sample brought nearer), ``"<="``
        :data:`EDGE_PIXELS`. Where no OpenGL context can be made, a single failing row "GPU renderer
        available" (0 ≥ 1) whose note gives the reason.
    """
    from optics.rendering.reference import psnr_against_reference
    from optics.rendering.renderer import Renderer, RendererUnavailable
    from wavephys.app.scenes import SCENES, builtin_scene

    try:
        renderer = Renderer(width, height)
    except RendererUnavailable as exc:
        return [bound("GPU renderer available", 0.0, 1.0, relation=">=", note=str(exc)[:120])]
    rows = []
    with renderer:
        for name in SCENES:
            scene = builtin_scene(name, n=n)
            value, edges = psnr_against_reference(renderer.render(scene), scene)
            rows.append(bound(f"{name}: GPU vs CPU reference PSNR, all effects ({width}x{height})", value, 100.0,
                              relation=">=", unit="dB"))
            # the edges' allowance is for a few pixels where a ray grazes an edge (0-2 a scene, measured)
            rows.append(bound(f"{name}: pixels compared at an edge ({width}x{height})", edges, EDGE_PIXELS,
                              unit="pixels"))
    return rows


def registry() -> dict[str, Callable[[], list[Check]]]:
    """Every check group by name: wave physics, optics, then the renderer on the built-in scenes.

    Returns
    -------
    dict of str to callable
        ``name -> check()``, each a function of no arguments returning a list of
        :class:`~wavephys.harness.Check` rows: :data:`wavephys.checks.CHECKS`, then
        :data:`optics.checks.CHECKS`, then ``"builtin-scenes"`` (:func:`check_builtin_scenes`), in the
        order ``wavephys validate`` runs them. A new dict on every call.
    """
    import optics.checks
    import wavephys.checks

    return {**wavephys.checks.CHECKS, **optics.checks.CHECKS, "builtin-scenes": check_builtin_scenes}


def __getattr__(name):
    if name == "REGISTRY":
        return registry()
    raise AttributeError(f"module 'wavephys.app.registry' has no attribute {name!r}")


def run(names=None, progress: Callable[[int, int, str], None] | None = None) -> list[Check]:
    """Run the named check groups (default: all); ``progress(i, total, name)`` before each.

    Parameters
    ----------
    names : list of str, optional
        Names of check groups (keys of :func:`registry`), run in the order given; None runs all of
        them in the registry's order. Any iterable of names but a string.
    progress : callable, optional
        Called as ``progress(i, total, name)`` before group ``i`` (from 0) of ``total`` runs.

    Returns
    -------
    list of Check
        The rows of every group run, group after group.

    Raises
    ------
    TypeError
        If ``names`` is a string or not iterable, or ``progress`` is not callable.
    ValueError
        If a name is not in the registry (the message lists the known ones).
    """
    checks = registry()
    if names is not None and (isinstance(names, (str, bytes)) or not hasattr(names, "__iter__")):
        raise TypeError(f"names must be a list of check names (see registry()), got {type(names).__name__}")
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be a function (i, total, name), or None, got {type(progress).__name__}")
    names = list(checks) if names is None else list(names)
    unknown = [n for n in names if n not in checks]
    if unknown:
        raise ValueError(f"unknown check(s) {unknown}; choose from {list(checks)}")
    rows: list[Check] = []
    for i, name in enumerate(names):
        if progress:
            progress(i, len(names), name)
        rows.extend(checks[name]())
    return rows
