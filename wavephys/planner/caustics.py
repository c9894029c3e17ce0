r"""The caustics term: how much each tracing refinement changes the floor's light, on the scene's own surface.

A scene with ``caustics = true`` shows its floor lit through the waves: the shading
(:func:`wavephys.planner.runner.shade`) multiplies the floor's colour by E/E₀, the floor
irradiance (:func:`optics.caustics.floor_irradiance_beam`, exact beam rasterization of the
surface refined r times, or :func:`optics.caustics.floor_irradiance_jacobian`) over E₀, the irradiance under flat water; with the term off
(r = 0) E/E₀ = 1.

This term is *evaluated*, not bounded. The full model's surface is known in closed form at
any frame (every Fourier mode of the linear surface, :mod:`wavephys.planner.predict`, and
η₂ = ½ Re(η_c Λη_c) computed from it on the grid, as the simulation does). A screen runs on
every frame: the beam at :data:`SCREEN_REFINE` against the Jacobian gather (on its folded
windows, the beam), whose largest difference rises and falls with the focusing that makes
the refinements differ. The frames it ranks highest (:data:`SAMPLED_FRAMES`, at least
:data:`SCREEN_SPACING` apart) and the frame of the brightest focus are traced at every
refinement and by the Jacobian gather (:data:`CAUSTICS_JACOBIAN`, ``fold="raise"``: any
frame of the screen past its first fold makes that choice unavailable). Each option's
difference from the full model's refinement, :data:`FULL_REFINE`, is the larger of the
traced differences and the screen's largest value times the largest ratio of difference to
screen on the traced frames, times :data:`MARGIN`. With five frames sampled evenly instead (as
this term did before), the largest difference of a frame reached 4.25 × the traced maximum on
the scenes that chose the screen and 9.7 × on others (docs/planner.md §3). Screening a frame
costs 5–9 % of tracing it at every option;
the plan saves the tracing on every frame it renders. Scenes with caustics are planned up
to :data:`MAX_CAUSTICS_TEXELS` texels per side (the planner traces 4× finer).
"""

from __future__ import annotations

__internal__ = True  # the planner's own models: used through plan(), not fuzzed as public API

import math
from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache
from types import MappingProxyType

import numpy as np

from wavephys.planner.model import CAUSTICS_JACOBIAN, CAUSTICS_OPTIONS, CAUSTICS_REFINE, FULL_REFINE, SceneModel

__all__ = ["full_surfaces", "CausticsErrors", "caustics_errors", "MARGIN",
           "SAMPLED_FRAMES", "SCREEN_SPACING", "SCREEN_REFINE", "MAX_CAUSTICS_TEXELS"]

MAX_CAUSTICS_TEXELS = 512
"""Largest texels per side of a scene that shows caustics (the full model traces 2048² cells)."""

MARGIN = 1.25
"""Factor on the evaluated differences, for the frames not traced: with every frame traced, the
largest difference of any frame came to at most 1.13 × the evaluated one (before this factor)
over the 20 generated pools and shores that chose the screen, and 1.17 × over 24 others
(docs/planner.md §3)."""
SAMPLED_FRAMES = 5
"""Frames traced at every option, chosen by the screen (:func:`_traced_frames`): the ones where
it finds the refinements differing most, at least :data:`SCREEN_SPACING` frames apart, and
the frame of the brightest focus (at most ``SAMPLED_FRAMES + 1`` frames)."""
SCREEN_SPACING = 2
"""Least distance (frames) between two frames the screen picks for tracing: focusing rises
and falls over several frames, and neighbours of a traced peak add little."""
SCREEN_REFINE = 1
"""The beam refinement traced on every frame by the screen (against the Jacobian gather)."""


def _surface_maker(scene):
    """A function frame ↦ the full model's heights (n, n) float64 m at that frame (1-based), from
    the closed form (linear modes at time t, then η + ½ Re(η_c Λη_c) on the grid)."""
    from wavephys.planner.spectrum import dispersion_variants, mode_dispersion, mode_heights, scene_spectrum

    spec = scene_spectrum(scene)
    n = spec.n
    omega, m = mode_dispersion(spec.k, dispersion_variants(scene)[0])
    rows, cols = spec.index
    k = np.zeros((n, n))
    k[rows, cols] = spec.k

    def surface(frame: int):
        t = np.asarray([[frame / scene.fps]], np.float64)
        c = mode_heights(spec, omega, m, t)
        if np.any(spec.W):
            c = c + mode_heights(spec, omega, m, t, wind=True)
        full = np.zeros((n, n), np.complex128)
        full[rows, cols] = c[0]
        eta_c = np.fft.ifft2(full)
        lam = np.fft.ifft2(k * full)
        return eta_c.real + 0.5 * (eta_c.real * lam.real - eta_c.imag * lam.imag)

    return surface


def full_surfaces(scene, frames=None) -> tuple:
    """(frame numbers, heights (F, n, n) float64 m): the full model's surface on the output
    texels at ``frames`` (1-based), from its closed form (linear modes at time t, then
    η + ½ Re(η_c Λη_c) on the grid). Needs a periodic scene (no margin). Without ``frames``:
    the first, the last and three evenly between, as the term traced them before its screen
    (deprecated: pass the frames).

    Parameters
    ----------
    scene : Scene
        A periodic scene.
    frames : sequence of int, optional
        1-based frame numbers.

    Returns
    -------
    (tuple of int, numpy.ndarray (F, n, n))
        The frames and their heights, m (float64).
    """
    if frames is None:
        import warnings

        warnings.warn("full_surfaces(scene) without frames is deprecated (the caustics term no longer traces five "
                      "evenly spaced frames); pass frames=", DeprecationWarning, stacklevel=2)
        frames = sorted({int(round(v)) for v in np.linspace(1, scene.frames, min(SAMPLED_FRAMES, scene.frames))})
    frames = tuple(int(f) for f in frames)
    surface = _surface_maker(scene)
    return frames, np.stack([surface(f) for f in frames])


def _traced_frames(screen, peak) -> tuple:
    """Indices (0-based) of the frames to trace at every option: the screen's largest values,
    each at least :data:`SCREEN_SPACING` from those taken before (a greedy suppression of their
    neighbours; in a short scene, then the next highest), :data:`SAMPLED_FRAMES` of them (every
    frame of a scene that has no more), and the frame of the
    largest ``peak``. A non-finite screen value ranks first."""
    value = np.where(np.isfinite(screen), screen, np.inf).astype(np.float64)
    rank, taken = value.copy(), []
    while len(taken) < SAMPLED_FRAMES and np.any(rank > -np.inf):
        i = int(np.argmax(rank))
        taken.append(i)
        rank[max(0, i - SCREEN_SPACING + 1):i + SCREEN_SPACING] = -np.inf
    value[taken] = -np.inf  # too few frames apart (a short scene): the next highest, neighbours or not
    while len(taken) < min(SAMPLED_FRAMES, value.size):
        i = int(np.argmax(value))
        taken.append(i)
        value[i] = -np.inf
    finite_peak = np.where(np.isfinite(peak), peak, np.inf)
    return tuple(sorted(set(taken) | {int(np.argmax(finite_peak))}))


@dataclass(frozen=True)
class CausticsErrors:
    """What the caustics term's choices do to one scene's floor light (module doc):
    ``delta`` r ↦ MARGIN × the evaluated max |E_r − E_full|/E₀ over the scene's frames (r = 0:
    the term off, E/E₀ = 1), ``e_max`` r ↦ MARGIN × the largest E_r/E₀ seen (read-only
    mappings), ``flat`` E₀, ``frames`` the frames traced at every option (1-based),
    ``screen`` the screen's value per frame (max |E₁ − E_J|/E₀, every frame), ``traced`` r ↦
    the largest |E_r − E_full|/E₀ on the traced frames alone, ``seconds`` the
    time the first evaluation took (later calls return the cached result), ``gather_points`` the
    most points a side the Jacobian gather took on a screened frame (texels × its supersampling;
    0 once a frame folds), what its cost is calibrated by. A trace that is not finite everywhere
    makes its entries ∞ (that choice is never taken); a frame past its first fold makes the
    Jacobian gather's ∞.

    Attributes
    ----------
    delta, e_max : Mapping
        Per tracing refinement r: MARGIN × the max relative change of the floor light, and of
        its largest value, E/E₀.
    flat : float
        E₀, the flat floor's irradiance, W/m².
    frames : tuple of int
        The frames traced at every option (1-based).
    seconds : float
        The first evaluation's time, s.
    screen : tuple of float
        The screen's value per frame.
    traced : Mapping
        Per r, the largest change on the traced frames alone.
    gather_points : int
        The most points a side the Jacobian gather took.
    """

    delta: Mapping
    e_max: Mapping
    flat: float
    frames: tuple
    seconds: float
    screen: tuple
    traced: Mapping
    gather_points: int = 0


def caustics_errors(scene) -> CausticsErrors | None:
    """:class:`CausticsErrors` of ``scene`` (None if it shows no caustics); cached per scene.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    CausticsErrors or None
    """
    if not scene.caustics:
        return None
    return _caustics_errors(scene)


def _evaluated(d, screen, traced) -> float:
    """One option's difference over every frame from its traced ones (module doc): the largest
    traced difference, and the screen's largest value times the largest ratio of difference to
    screen over the traced frames (the frames not traced differ as their screen says); ∞ where a
    frame not traced has no finite screen value."""
    worst = max(float(d[i]) for i in traced)
    untraced = np.ones(screen.size, bool)
    untraced[list(traced)] = False
    if not np.isfinite(screen[untraced]).all():  # a frame the screen could not measure and nobody traced
        return math.inf
    top = float(np.max(screen[np.isfinite(screen)], initial=0.0))
    ratios = [float(d[i]) / float(screen[i]) for i in traced if np.isfinite(screen[i]) and screen[i] > 0]
    return max(worst, top * max(ratios, default=0.0))


@lru_cache(maxsize=32)
def _caustics_errors(scene) -> CausticsErrors:
    import time

    import jax.numpy as jnp

    from optics.caustics import CausticsFold, flat_irradiance, floor_irradiance_beam, floor_irradiance_jacobian
    from optics.light.directions import sun_direction

    start = time.perf_counter()
    grid = SceneModel(scene).output_grid
    sun = sun_direction(scene.sun_elevation, 180.0)  # behind the viewer, who looks along +x
    e0 = flat_irradiance(scene.sun_elevation)
    surface = _surface_maker(scene)
    beam = lambda eta, r: np.asarray(floor_irradiance_beam(eta, grid, scene.depth, sun, refine=r), np.float64) / e0
    points = [0]  # the most points a side the gather took (texels × supersampling)

    def gather(eta, fold):
        out, info = floor_irradiance_jacobian(eta, grid, scene.depth, sun, fold=fold, explain=True)
        points[0] = max(points[0], grid.n * (info["supersample"] or 1))
        return np.asarray(out, np.float64) / e0

    # the screen, every frame: the coarsest beam against the gather (the beam on its folded windows)
    screen, peak, folds = np.zeros(scene.frames), np.zeros(scene.frames), False
    for i in range(scene.frames):
        eta = jnp.asarray(surface(i + 1), jnp.float32)
        if folds:  # the gather is out already: its answer with the beam on the folded windows
            light = gather(eta, "windows")
        else:
            try:  # offered only below the first fold, where the gather answers alone on every frame
                light = gather(eta, "raise")
            except CausticsFold:
                folds, light = True, gather(eta, "windows")
        coarse = beam(eta, SCREEN_REFINE)
        screen[i] = float(np.abs(coarse - light).max())
        peak[i] = float(light.max())
    traced = _traced_frames(screen, peak)
    d = {r: np.zeros(scene.frames) for r in CAUSTICS_OPTIONS}
    e_max = {r: 0.0 for r in CAUSTICS_OPTIONS}
    for i in traced:
        eta = jnp.asarray(surface(i + 1), jnp.float32)
        light = {r: beam(eta, r) for r in CAUSTICS_REFINE if r}
        light[0] = np.ones_like(light[FULL_REFINE])
        if folds:
            light[CAUSTICS_JACOBIAN] = np.full_like(light[0], np.inf)
        else:
            light[CAUSTICS_JACOBIAN] = gather(eta, "raise")
        ref = light[FULL_REFINE]
        for r in CAUSTICS_OPTIONS:
            finite = bool(np.isfinite(light[r]).all() and np.isfinite(ref).all())
            d[r][i] = float(np.abs(light[r] - ref).max()) if finite else math.inf
            e_max[r] = max(e_max[r], float(light[r].max()) if finite else math.inf)
    delta = {r: MARGIN * _evaluated(d[r], screen, traced) for r in CAUSTICS_OPTIONS}
    return CausticsErrors(MappingProxyType(delta), MappingProxyType({r: MARGIN * v for r, v in e_max.items()}), e0,
                          tuple(i + 1 for i in traced), time.perf_counter() - start, tuple(float(v) for v in screen),
                          MappingProxyType({r: max(float(d[r][i]) for i in traced) for r in CAUSTICS_OPTIONS}),
                          0 if folds else points[0])
