r"""The caustics term: how much each tracing refinement changes the floor's light, on the scene's own surface.

A scene with ``caustics = true`` shows its floor lit through the waves: the shading
(:func:`wavephys.planner.runner.shade`) multiplies the floor's colour by E/E₀, the floor
irradiance (:func:`optics.caustics.floor_irradiance_beam`, exact beam rasterization of the
surface refined r times, or :func:`optics.caustics.floor_irradiance_jacobian`) over E₀, the irradiance under flat water; with the term off
(r = 0) E/E₀ = 1.

This term is *evaluated*, not bounded. The full model's surface is known in closed form at
any frame (every Fourier mode of the linear surface, :mod:`wavephys.planner.predict`, and
η₂ = ½ Re(η_c Λη_c) computed from it on the grid, as the simulation does), so the planner
traces it at a few frames (:data:`SAMPLED_FRAMES`: the first, the last and three between)
at every refinement, and by the Jacobian gather (:data:`CAUSTICS_JACOBIAN`, with ``fold="raise"``:
a traced frame past its first fold makes that choice unavailable), and takes the largest
difference from the full model's refinement, :data:`FULL_REFINE`, times :data:`MARGIN` for the
frames it did not trace. Tracing one frame
at all refinements costs about 30 traces of the plain surface, once per plan; the plan
saves it on every frame it renders. Scenes with caustics are planned up to
:data:`MAX_CAUSTICS_TEXELS` texels per side (the planner traces 4× finer).
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
           "SAMPLED_FRAMES", "MAX_CAUSTICS_TEXELS"]

MAX_CAUSTICS_TEXELS = 512
"""Largest texels per side of a scene that shows caustics (the full model traces 2048² cells)."""

MARGIN = 1.25
"""Factor on the largest difference traced at the sampled frames (for the frames between them)."""
SAMPLED_FRAMES = 5
"""Frames traced per scene: the first, the last and three evenly between (fewer for shorter
scenes). A sampled estimate: focusing can peak between them (hence :data:`MARGIN`)."""


def _sampled_frames(frames: int) -> tuple:
    return tuple(sorted({int(round(v)) for v in np.linspace(1, frames, min(SAMPLED_FRAMES, frames))}))


def full_surfaces(scene) -> tuple:
    """(frame numbers, heights (F, n, n) float64 m): the full model's surface at the sampled
    frames on the output texels, from its closed form (linear modes at time t, then
    η + ½ Re(η_c Λη_c) on the grid). Needs a periodic scene (no margin)."""
    from wavephys.planner.spectrum import dispersion_variants, mode_dispersion, mode_heights, scene_spectrum

    spec = scene_spectrum(scene)
    n = spec.n
    omega, m = mode_dispersion(spec.k, dispersion_variants(scene)[0])
    frames = _sampled_frames(scene.frames)
    t = (np.asarray(frames, np.float64) / scene.fps)[:, None]
    c = mode_heights(spec, omega, m, t)
    if np.any(spec.W):
        c = c + mode_heights(spec, omega, m, t, wind=True)
    rows, cols = spec.index
    k = np.zeros((n, n))
    k[rows, cols] = spec.k
    out = []
    for row in c:
        full = np.zeros((n, n), np.complex128)
        full[rows, cols] = row
        eta_c = np.fft.ifft2(full)
        lam = np.fft.ifft2(k * full)
        out.append(eta_c.real + 0.5 * (eta_c.real * lam.real - eta_c.imag * lam.imag))
    return frames, np.stack(out)


@dataclass(frozen=True)
class CausticsErrors:
    """What the caustics term's choices do to one scene's floor light (module doc):
    ``delta`` r ↦ MARGIN × max |E_r − E_full|/E₀ over the sampled frames (r = 0: the term off,
    E/E₀ = 1), ``e_max`` r ↦ MARGIN × the largest E_r/E₀ seen (read-only mappings), ``flat``
    E₀, ``frames`` the frames traced, ``seconds`` the time the first evaluation took (later
    calls return the cached result). A trace that is not finite everywhere makes its
    entries ∞ (that choice is never taken)."""

    delta: Mapping
    e_max: Mapping
    flat: float
    frames: tuple
    seconds: float


def caustics_errors(scene) -> CausticsErrors | None:
    """:class:`CausticsErrors` of ``scene`` (None if it shows no caustics); cached per scene."""
    if not scene.caustics:
        return None
    return _caustics_errors(scene)


@lru_cache(maxsize=32)
def _caustics_errors(scene) -> CausticsErrors:
    import time

    import jax.numpy as jnp

    from optics.caustics import CausticsFold, floor_irradiance_beam, floor_irradiance_jacobian

    start = time.perf_counter()
    grid = SceneModel(scene).output_grid
    from optics.caustics import flat_irradiance
    from optics.light.directions import sun_direction

    sun = sun_direction(scene.sun_elevation, 180.0)  # behind the viewer, who looks along +x
    e0 = flat_irradiance(scene.sun_elevation)
    frames, heights = full_surfaces(scene)
    delta = {r: 0.0 for r in CAUSTICS_OPTIONS}
    e_max = {r: 0.0 for r in CAUSTICS_OPTIONS}
    for eta in heights:
        eta = jnp.asarray(eta, jnp.float32)
        light = {r: np.asarray(floor_irradiance_beam(eta, grid, scene.depth, sun, refine=r), np.float64) / e0
                 for r in CAUSTICS_REFINE if r}
        light[0] = np.ones_like(light[FULL_REFINE])
        try:  # offered only below the first fold, where the gather answers alone
            light[CAUSTICS_JACOBIAN] = np.asarray(floor_irradiance_jacobian(eta, grid, scene.depth, sun, fold="raise"),
                                                  np.float64) / e0
        except CausticsFold:
            light[CAUSTICS_JACOBIAN] = np.full_like(light[0], np.inf)
        ref = light[FULL_REFINE]
        for r in CAUSTICS_OPTIONS:
            finite = bool(np.isfinite(light[r]).all() and np.isfinite(ref).all())
            delta[r] = max(delta[r], float(np.abs(light[r] - ref).max()) if finite else math.inf)
            e_max[r] = max(e_max[r], float(light[r].max()) if finite else math.inf)
    return CausticsErrors(MappingProxyType({r: MARGIN * v for r, v in delta.items()}),
                          MappingProxyType({r: MARGIN * v for r, v in e_max.items()}), e0, frames,
                          time.perf_counter() - start)
