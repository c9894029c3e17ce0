"""Run a scene with a configuration: the height frames its output shows, and the colour image.

:func:`run` simulates with the pure step (:mod:`wavephys.simulation`), blends frames
between steps, Fourier-interpolates a coarse grid back onto the output texels and keeps the
visible square; :func:`shade` turns a frame into the image the planner's colour terms are
judged on. :func:`compare` measures one output against another (max norm and RMS).
"""

from __future__ import annotations

import functools
import math
import time as _time
from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.inputs import check_array, check_instance, check_scalar
from wavephys.planner.model import SceneModel, interior, texel_shift_phase
from wavephys.planner.scene import Scene

__all__ = ["Output", "run", "shade", "floor_light", "compare", "surface_frames", "encode_texture", "decode_texture", "FLOOR_ALBEDO"]

FLOOR_ALBEDO = 0.6
"""Reflectance of the floor seen through the water in :func:`shade` (pale sand)."""


@dataclass(frozen=True)
class Output:
    """What a scene shows, as :func:`run` returns it.

    Parameters
    ----------
    heights : numpy.ndarray (F, n, n)
        Heights on the output texels at 1/fps … duration, m.
    image : numpy.ndarray (n, n, 3)
        The last frame shaded (:func:`shade`), [0, 1].
    seconds : float
        Wall seconds the simulation and frames took, finite, ≥ 0.
    shade_seconds : float
        Wall seconds of the image, finite, ≥ 0.
    """

    heights: np.ndarray
    image: np.ndarray
    seconds: float
    shade_seconds: float

    def __post_init__(self):
        # a run whose heights or image went non-finite (a blown-up model) is refused here, never compared
        check_array("heights", self.heights, ndim=3)
        check_array("image", self.image, ndim=3, lo=0.0, hi=1.0)
        if np.shape(self.image)[-1] != 3:
            raise ValueError(f"image must be RGB (n, n, 3), got shape {np.shape(self.image)}")
        check_scalar("seconds", self.seconds, lo=0.0)
        check_scalar("shade_seconds", self.shade_seconds, lo=0.0)


def _initial_state(model: SceneModel):
    import wavephys.simulation.stepping as stepping

    sim = model.simulation
    state = stepping.initial_state(sim)
    if model.scene.wind is not None:
        state = stepping.state_from_psi(sim, _wind_psi(model))
    stones = model.stones()
    if stones is not None:
        state = stepping.add_source(sim, state, stones)
    return state


def _wind_psi(model: SceneModel):
    """The wind sea on the simulation grid: the full grid's ĥ restricted to the modes this grid
    holds (its Nyquist row and column left out) and referred to its first sample, as a
    travelling field ψ̂ = −i(ω/K)ĥ of the configuration's own dispersion."""
    from wavephys.planner.spectrum import mode_dispersion, wind_heights

    full, grid = model.full_grid, model.grid
    h_full = wind_heights(model.scene, full)
    nf, nc = full.n, grid.n
    f = np.fft.fftfreq(nc, 1.0 / nc).astype(int)
    h = h_full[np.ix_(f % nf, f % nf)] * (nc / nf) ** 2 * texel_shift_phase(full, grid)
    nyq = np.abs(f) == nc // 2
    h[nyq, :] = 0.0
    h[:, nyq] = 0.0
    k = np.asarray(grid.wavenumber_magnitude(), np.float64)
    omega, m = mode_dispersion(k, model.water)
    inverse = np.where(m > 0, 1.0 / np.where(m > 0, m, 1.0), 0.0)
    return np.fft.ifft2(-1j * inverse * h)


def run(scene: Scene, model: SceneModel) -> Output:
    """Simulate ``scene`` with ``model``: heights on the output texels at every frame, and the
    shaded last frame.

    Parameters
    ----------
    scene : Scene
    model : SceneModel
        A configuration of that same scene (``plan(...).model``, :func:`full_model`).

    Returns
    -------
    Output
        Heights stored in and read back from the configuration's texture format.

    Examples
    --------
    >>> from wavephys.planner import builtin_scene, full_model, plan   # doctest: +SKIP
    >>> scene = builtin_scene("pond")                                  # doctest: +SKIP
    >>> out = run(scene, plan(scene, scene.height_quantum).model)      # doctest: +SKIP
    """
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    check_instance("model", model, SceneModel, "wavephys.planner.SceneModel")
    if model.scene != scene:
        raise ValueError("model was made for another scene: SceneModel(scene, choices)")
    if scene.ships:
        model.check_ships()
    start = _time.perf_counter()
    frames = simulated_heights(model) if model.choices.surface == "spectral" else surface_frames(model)
    for term, option in model.choices.added:  # terms registered beside the built-ins (planner.terms.AddedTerm)
        frames = _hooked("heights", term, frames, term.change_heights(model, frames, option))
    stored = encode_texture(frames, model.choices.texture, model.output_grid)
    seconds = _time.perf_counter() - start
    heights = decode_texture(stored)  # what the renderer reads (decoded in its shader, not timed here)
    t0 = _time.perf_counter()
    image = shade(scene, model, heights[-1])
    return Output(heights, image, seconds, _time.perf_counter() - t0)


def simulated_heights(model: SceneModel) -> np.ndarray:
    """The spectral step's frames (F, n, n), m, on the output texels: the pure step over the
    scene, frames blended between steps and refined onto the texels."""
    import wavephys.simulation.stepping as stepping

    if model.varying:
        return _floor_heights(model)
    sim = model.simulation
    state = _initial_state(model)
    if model.scene.ships:
        ships, etas, rates = model.ships(), [], []
        for _ in range(model.steps):
            state, surf = stepping.step(sim, state, ships)
            etas.append(surf.eta)
            rates.append(surf.eta_dot)
        last = stepping.surface(sim, state)
        eta = jnp.stack(etas + [last.eta])
        eta_dot = jnp.stack(rates + [last.eta_dot])
    else:
        state, surfs = stepping.run(sim, state, model.steps)
        last = stepping.surface(sim, state)
        eta = jnp.concatenate([surfs.eta, last.eta[None]])
        eta_dot = jnp.concatenate([surfs.eta_dot, last.eta_dot[None]])
    return _frames(model, eta, eta_dot)


def _floor_heights(model: SceneModel) -> np.ndarray:
    """Frames (F, n, n), m, on the output texels, of the waves stepped over the scene's sloping
    floor by the symmetric depth stepper, from the stones' craters at rest."""
    import wavephys.simulation.stepping as stepping
    from wavephys.simulation.depth import depth_state
    from wavephys.simulation.steppers import DepthStepper

    sim = model.simulation
    eta0 = stepping.surface(sim, _initial_state(model)).eta  # the craters, exactly as the spectral step's
    state, states = DepthStepper(sim, model.floor(), "symmetric").trajectory(depth_state(sim, eta0), model.steps)
    eta = jnp.concatenate([states.fields[1:, 0], state.eta[None]])
    return np.asarray(interior(model, eta))


@jax.jit
def _blend(e0, e1, d0, d1, dt, s):
    """Hermite frames at fractions ``s`` (shape (F, 1, 1)) between surfaces e0, e1 with rates d0, d1."""
    from wavephys.physics.interpolation import hermite_weights

    h00, h01, h10, h11 = hermite_weights(s)
    return h00 * e0 + h01 * e1 + dt * (h10 * d0 + h11 * d1)


@functools.partial(jax.jit, static_argnames=("factor", "walls"))
def _assemble(eta, eta_dot, index, s, dt, factor, walls=False):
    """One block of frames: gathered from the step surfaces, blended where s > 0, refined by
    ``factor`` (Fourier interpolation; cosine interpolation in a walled tank) — one compiled
    program per block."""
    from wavephys.core.spectral import cosine_refine, fourier_refine

    last = eta.shape[0] - 1
    nxt = jnp.minimum(index + 1, last)
    w = s[:, None, None]
    blend = _blend(eta[index], eta[nxt], eta_dot[index], eta_dot[nxt], dt, w)
    frames = jnp.where(w > 0, blend, eta[index])
    refine = cosine_refine if walls else fourier_refine
    return jax.vmap(lambda f: refine(f, factor))(frames) if factor > 1 else frames


def surface_frames(model: SceneModel) -> np.ndarray:
    """Frames of a wind scene by a surface model other than the spectral step.

    Each frame is evaluated at t = j/fps on the output texels: the strongest waves summed
    directly, the sea in closed form displaced by Tessendorf's λD and resampled, or the
    procedural fBm (:data:`wavephys.planner.model.SURFACES`).

    Parameters
    ----------
    model : SceneModel
        A wind-only scene's configuration whose ``choices.surface`` is not ``"spectral"``.

    Returns
    -------
    numpy.ndarray (F, n, n)
        Heights, m, float32.
    """
    check_instance("model", model, SceneModel, "wavephys.planner.SceneModel")
    name = model.choices.surface
    if name == "spectral":
        raise ValueError("surface_frames is for the surface models other than 'spectral' (run() steps that one)")
    from wavephys.planner.spectrum import CHOPPINESS, gerstner_modes, mode_dispersion, noise_sea, scene_spectrum, wind_heights

    scene, grid = model.scene, model.output_grid
    times = np.arange(1, scene.frames + 1) / scene.fps
    if name.startswith("gerstner"):
        from wavephys.surfaces.gerstner import GerstnerWaves

        spec = scene_spectrum(scene)
        sel = gerstner_modes(scene, int(name.split("-")[1]))
        x, y = (np.asarray(a, np.float64) for a in grid.mesh())
        kx, ky = spec.kx[sel], spec.ky[sel]
        phase = np.angle(spec.W[sel]) - kx * x[0, 0] - ky * y[0, 0]  # the DFT refers to the first sample
        waves = GerstnerWaves(np.stack([kx, ky], 1), np.abs(spec.W[sel]) / spec.n**2, np.angle(np.exp(1j * phase)),
                              0.0, model.water)
        return np.stack([np.asarray(waves.heights(grid, float(t), iterations=1)) for t in times])
    if name == "choppy":
        from wavephys.surfaces.choppy import displacement
        from wavephys.surfaces.resample import resample_heights

        k = np.asarray(grid.wavenumber_magnitude(), np.float64)
        omega = jnp.asarray(mode_dispersion(k, model.water)[0], jnp.float32)
        w = jnp.asarray(wind_heights(scene, grid), jnp.complex64)
        out = []
        for t in times:
            eta = _sea_at(w, omega, jnp.float32(t))
            out.append(np.asarray(resample_heights(displacement(eta, grid, CHOPPINESS), eta, grid)))
        return np.stack(out)
    sea = noise_sea(scene)
    return np.stack([np.asarray(sea.heights(grid, float(t))) for t in times])


@jax.jit
def _sea_at(w, omega, t):
    """The linear sea's heights at time t from its DFT at t = 0: Re F⁻¹[ĥ e^{−iωt}]."""
    return jnp.real(jnp.fft.ifft2(w * jnp.exp(-1j * omega * t)))


def encode_texture(heights, fmt: str, grid):
    """Frames stored in a height texture format (:func:`decode_texture` reads them back).

    Parameters
    ----------
    heights : array_like (F, n, n)
        Heights, m, finite.
    fmt : {"f32", "f16", "u16", "u8"}
        :data:`wavephys.planner.model.TEXTURES`.
    grid : Grid
        The texels' grid (the extent goes with integer codes).

    Returns
    -------
    numpy.ndarray or list of EncodedHeight
        A float32 or float16 array, or for ``u16`` / ``u8`` one
        :class:`optics.rendering.textures.EncodedHeight` per frame (its own minimum to maximum
        onto the codes).
    """
    from optics.rendering.textures import encode_height
    from wavephys.core.inputs import check_array, check_choice
    from wavephys.planner.model import TEXTURES

    check_choice("fmt", fmt, TEXTURES)
    check_instance("grid", grid, Grid, "wavephys.Grid")
    check_array("heights", heights, ndim=3, shape_tail=(grid.n, grid.n))
    if fmt == "f32":
        return np.asarray(heights, np.float32)
    if fmt == "f16":
        from wavephys.core.halffloat import to_float16

        return to_float16(np.asarray(heights, np.float32))  # numpy's own conversion is 20x slower on subnormals
    bits = 16 if fmt == "u16" else 8
    return [encode_height(f, grid, bits) for f in np.asarray(heights)]


def decode_texture(stored) -> np.ndarray:
    """Heights from :func:`encode_texture`'s result.

    Parameters
    ----------
    stored : numpy.ndarray or list of EncodedHeight
        What :func:`encode_texture` returned.

    Returns
    -------
    numpy.ndarray (F, n, n)
        Heights, m: float32 for the float formats, float64 for the integer ones (their exact
        decoded values).
    """
    from optics.rendering.textures import EncodedHeight, decode_height

    if isinstance(stored, np.ndarray) and stored.dtype in (np.float32, np.float16):
        return stored.astype(np.float32)
    if isinstance(stored, list) and stored and all(isinstance(t, EncodedHeight) for t in stored):
        return np.stack([decode_height(t) for t in stored])
    raise TypeError(f"stored must be what encode_texture returns (a float32/float16 array or a list of "
                    f"EncodedHeight), got {type(stored).__name__}")


FRAME_BLOCK = 64
"""Most frames assembled per compiled call (bounds the memory of a long scene's frames); a scene's
frames are split into blocks of one size from :data:`FRAME_BLOCK_SIZES`, at most this (a 13-frame
scene once assembled 64, five times the work its cost predicted)."""


FRAME_BLOCK_SIZES = (1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64)
"""The block sizes frames are assembled in: few, so that scenes of different lengths share
compiled programs, and each at most 1.5× the one below, so that padding wastes less than half
a block."""


def frame_block(frames: int) -> int:
    """Frames per compiled assembly call for a scene of ``frames`` frames: the smallest size of
    :data:`FRAME_BLOCK_SIZES` that holds the frames in as few blocks as :data:`FRAME_BLOCK` allows
    (every block that size, the last padded)."""
    blocks = -(-frames // FRAME_BLOCK)
    need = -(-frames // blocks)
    return next(size for size in FRAME_BLOCK_SIZES if size >= need)


def assembled_frames(frames: int) -> int:
    """Frames the assembly computes for a scene of ``frames`` frames, padding included (what
    the cost model counts)."""
    size = frame_block(frames)
    return -(-frames // size) * size


def _frames(model: SceneModel, eta, eta_dot):
    """Frames 1…F from the surfaces at the steps (Hermite between them), on the output texels."""
    spf, frames = model.choices.steps_per_frame, model.scene.frames
    j = np.arange(1, frames + 1)
    index, rest = j // spf, (j % spf) / spf
    dtype = eta.dtype
    size = frame_block(frames)
    out = []
    for b in range(0, frames, size):
        sl = slice(b, b + size)
        idx = np.zeros(size, np.int32)
        fr = np.zeros(size, dtype)
        count = len(index[sl])
        idx[:count], fr[:count] = index[sl], rest[sl]  # the last block padded to the same shape
        block = _assemble(eta, eta_dot, jnp.asarray(idx), jnp.asarray(fr), jnp.asarray(model.dt, dtype),
                          model.choices.coarsen, model.walls)
        out.append(np.asarray(interior(model, block))[:count])
    return np.concatenate(out)


def shade(scene: Scene, model: SceneModel, heights):
    """The colour the planner's optics terms are judged on: C = R + (1 − R)·T(d)·albedo·E/E₀ per
    channel, clipped to [0, 1], seen along the scene's view elevation (from −x), with R the
    configuration's Fresnel form at the facet's incidence angle, T the absorption over the path
    d down to the floor and straight back up (0 in deep water), and E/E₀ the floor's
    irradiance relative to flat water's (:func:`floor_light`; 1 where the scene shows no
    caustics).

    Parameters
    ----------
    scene : Scene
    model : SceneModel
        A configuration of ``scene`` (its Fresnel form, absorption and caustics).
    heights : array_like (n, n)
        One frame on the output texels, m.

    Returns
    -------
    numpy.ndarray (n, n, 3)
        Linear colour, [0, 1].
    """
    from optics.light.directions import sun_direction
    from wavephys.core.inputs import check_array

    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    check_instance("model", model, SceneModel, "wavephys.planner.SceneModel")
    n = scene.texels
    check_array("heights", heights, ndim=2, shape_tail=(n, n))
    if model.scene != scene:
        raise ValueError("model was made for another scene: SceneModel(scene, choices)")

    to_eye = tuple(float(c) for c in sun_direction(scene.view_elevation, 180.0))  # the viewer looks along +x
    deep = math.isinf(scene.depth)
    if deep:
        table_d, table_rgb, light = np.zeros(2), np.zeros((2, 3)), np.ones((n, n))
    else:
        table_d, table_rgb = shading_table(scene, model.choices.absorption)
        light = floor_light(scene, model, heights)
    f32 = np.float32  # host arrays go to the program as they are: one dispatch, no eager conversions
    colour = _shade_program(np.asarray(heights, f32), np.asarray(light, f32), np.asarray(table_d, f32),
                            np.asarray(table_rgb, f32), _half_wavenumbers(model.output_grid), np.asarray(to_eye, f32),
                            0.0 if deep else float(scene.depth), model.choices.fresnel, deep)
    colour = np.asarray(colour, np.float64)
    for term, option in model.choices.added:  # terms registered beside the built-ins (planner.terms.AddedTerm)
        colour = _hooked("colour", term, colour, term.change_colour(model, colour, option))
    return colour


def _hooked(what: str, term, before: np.ndarray, after) -> np.ndarray:
    """An added term's changed heights or colour, checked: same shape, finite."""
    try:
        out = np.asarray(after, before.dtype)
    except (TypeError, ValueError):
        raise TypeError(f"term {term.name!r} changed the {what} to {type(after).__name__}, not an array of "
                        f"numbers") from None
    if out.shape != before.shape or not np.all(np.isfinite(out)):
        raise ValueError(f"term {term.name!r} changed the {what} to an array of shape {out.shape}"
                         f"{'' if out.shape != before.shape else ' holding non-finite values'}; expected "
                         f"{before.shape}, finite")
    return out


@functools.lru_cache(maxsize=64)
def _half_wavenumbers(grid: Grid):
    """The grid's half-spectrum (ky, kx), formed once (eagerly, as the grid's own gradient forms them)."""
    return grid.wavenumbers(real=True)


@functools.partial(jax.jit, static_argnames=("fresnel", "deep"))
def _shade_program(heights, light, table_d, table_rgb, wavenumbers, to_eye, depth, fresnel: str, deep: bool):
    """:func:`shade` as one compiled program: the facet normals from the spectral slopes, the
    reflectance R by the Fresnel form ``fresnel`` at the incidence angle towards the eye, the
    water path down (refracted) and straight back up, the transmittance interpolated in
    :func:`shading_table`'s table, and C = R + (1 − R)·T·albedo·E/E₀ clipped to [0, 1]. Compiled
    once per texel count, Fresnel form and deep or not (the grid's wavenumbers, the view and the
    depth are arguments)."""
    from optics.light.fresnel import N_WATER, reflectance
    from wavephys.core.spectral import spectral_gradient

    gx, gy = spectral_gradient(heights, None, wavenumbers)
    norm = jnp.sqrt(gx * gx + gy * gy + 1.0)
    cos_i = jnp.clip((-gx * to_eye[0] - gy * to_eye[1] + to_eye[2]) / norm, 0.0, 1.0)
    r = reflectance(cos_i, method=fresnel)[..., None]
    if deep:
        return jnp.broadcast_to(r, r.shape[:2] + (3,))
    sin_t = jnp.sqrt(1.0 - cos_i * cos_i) / N_WATER
    path = depth * (1.0 / jnp.sqrt(1.0 - sin_t * sin_t) + 1.0)
    trans = uniform_interp(path, table_d[0], table_d[-1], table_rgb)
    return jnp.clip(r + (1.0 - r) * trans * FLOOR_ALBEDO * light[..., None], 0.0, 1.0)


def uniform_interp(x, x0, x1, values):
    """Linear interpolation of a table on evenly spaced nodes x0 … x1 (``values`` (P, C)), held
    at its ends beyond them (:func:`numpy.interp` per column), by index arithmetic instead of a
    search: traceable, and on a CPU about 20× faster than ``jnp.interp``."""
    last = values.shape[0] - 1
    u = jnp.clip((x - x0) / (x1 - x0) * last, 0.0, last)
    i = jnp.minimum(jnp.floor(u).astype(jnp.int32), last - 1)
    f = (u - i)[..., None]
    return values[i] * (1.0 - f) + values[i + 1] * f


SHADING_TABLE_PATHS = 256
"""Path lengths the shading tabulates an absorption method on (other than ``"spectral"``, whose
own table :func:`transmittance` interpolates), evenly over the scene's :func:`path_range`:
linear interpolation of e^(−a·d) there errs by at most (a·Δd)²/8, under 1e-6 of T for
a ≤ 0.5 /m and depths to 10 m."""


def shading_table(scene: Scene, method: str) -> tuple[np.ndarray, np.ndarray]:
    """The table (evenly spaced paths, m; linear-sRGB transmittance (P, 3)) the compiled shading
    interpolates (:func:`uniform_interp`) for
    absorption ``method``: :func:`transmittance`'s own 64-path table for ``"spectral"`` (so the
    shading equals it), the method evaluated on :data:`SHADING_TABLE_PATHS` paths over the scene's
    :func:`path_range` for the others."""
    lo, hi = path_range(scene)
    if method == "spectral":
        return _srgb_table(hi)
    return _method_table(method, lo, hi)


@functools.lru_cache(maxsize=64)
def _method_table(method: str, lo: float, hi: float):
    from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

    d = np.linspace(lo, hi, SHADING_TABLE_PATHS)
    return d, np.asarray(WATER_TRANSMITTANCE_METHODS(method, d, max_distance=hi), np.float64)


def floor_light(scene: Scene, model: SceneModel, heights) -> np.ndarray:
    """E/E₀ on the output texels: the floor irradiance under ``heights`` relative to flat water's
    (:func:`optics.caustics.floor_irradiance_beam` at the configuration's ``caustics`` refinement,
    or :func:`optics.caustics.floor_irradiance_jacobian` where it says ``"jacobian"``; the sun at
    the scene's elevation behind the viewer); 1 where the scene shows no caustics or the term is off.

    Parameters
    ----------
    scene : Scene
    model : SceneModel
        A configuration of ``scene``.
    heights : array_like (n, n)
        One frame on the output texels, m.

    Returns
    -------
    numpy.ndarray (n, n)
        E/E₀, ≥ 0, float64.
    """
    from wavephys.core.inputs import check_array

    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    check_instance("model", model, SceneModel, "wavephys.planner.SceneModel")
    check_array("heights", heights, ndim=2, shape_tail=(scene.texels, scene.texels))
    if model.scene != scene:
        raise ValueError("model was made for another scene: SceneModel(scene, choices)")
    refine = model.choices.caustics
    if not scene.caustics or not refine:
        return np.ones((scene.texels, scene.texels))
    from optics.caustics import flat_irradiance, floor_irradiance_beam, floor_irradiance_jacobian
    from optics.light.directions import sun_direction

    sun = sun_direction(scene.sun_elevation, 180.0)
    if refine == "jacobian":  # a frame the planner did not trace may fold: the beam answers its folded windows
        e = floor_irradiance_jacobian(jnp.asarray(heights, jnp.float32), model.output_grid, scene.depth, sun)
    else:
        e = floor_irradiance_beam(jnp.asarray(heights, jnp.float32), model.output_grid, scene.depth, sun,
                                  refine=refine)
    return np.asarray(e, np.float64) / flat_irradiance(scene.sun_elevation)


def transmittance(scene: Scene, method: str, path):
    """Linear-sRGB transmittance over path lengths ``path`` (m) by ``method``, a name in
    :data:`optics.light.attenuation.WATER_TRANSMITTANCE_METHODS` called with the scene's longest
    path: ``"spectral"`` tabulated on 64 path lengths and interpolated (the integral per texel
    would cost seconds a frame), the others evaluated directly (``"rgb"``: three coefficients
    fitted over the scene's own range of paths)."""
    from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

    path = np.asarray(path, np.float64)
    hi = path_range(scene)[1]
    if method != "spectral":
        return WATER_TRANSMITTANCE_METHODS(method, path, max_distance=hi)
    table, rgb = _srgb_table(hi)
    return np.stack([np.interp(path, table, rgb[:, c]) for c in range(3)], -1)


@functools.lru_cache(maxsize=64)
def _srgb_table(hi: float):
    from optics.light.attenuation import water_transmittance_spectral

    table = np.linspace(0.0, hi, 64)
    return table, water_transmittance_spectral(table, max_distance=hi)


def path_range(scene: Scene) -> tuple[float, float]:
    """Shortest and longest water path (m) of :func:`shade` over incidence 0…90° (down at the
    refracted angle, back up vertically)."""
    from optics.light.fresnel import N_WATER

    cos_t_min = math.sqrt(1.0 - 1.0 / N_WATER**2)
    return 2.0 * scene.depth, scene.depth * (1.0 / cos_t_min + 1.0)


def compare(output, reference) -> dict:
    """Errors of one run against another of the same scene.

    Parameters
    ----------
    output, reference : Output
        Two :func:`run` results of the same scene (the reference usually :func:`full_model`'s).

    Returns
    -------
    dict
        ``height_max`` (max norm over every frame and texel, m), ``height_rms`` (m) and
        ``colour_max`` (max over texels and channels of the last frame's image, [0, 1]).
    """
    check_instance("output", output, Output, "wavephys.planner.Output")
    check_instance("reference", reference, Output, "wavephys.planner.Output")
    if output.heights.shape != reference.heights.shape:
        raise ValueError(f"outputs of different scenes: heights {output.heights.shape} vs {reference.heights.shape}")
    d = output.heights.astype(np.float64) - reference.heights.astype(np.float64)
    return dict(height_max=float(np.abs(d).max()), height_rms=float(np.sqrt(np.mean(d * d))),
                colour_max=float(np.abs(output.image - reference.image).max()))
