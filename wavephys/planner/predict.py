r"""Predicted height errors of a configuration against the full model, from the scene's own numbers.

The scene's modes and their closed forms live in :mod:`wavephys.planner.spectrum`; this module
turns them into bounds.

The spectral step is exact per Fourier mode, so the linear surface of every scene the
planner takes is a closed form per mode k (docs/planner.md §2). With C_k(t) the DFT of the
complex height η_c (η = Re η_c) on the full grid:

* stones and the wind sea, given at t = 0 as heights: C_k(t) = A_k e^{−iω_k t};
* a ship on a straight course from x₀ at velocity U, source ∂(s f)/∂t:
  C_k(t) = s·m_k·(k·U)·f̂_k e^{−ik·x₀} e^{−iω_k t} · t·φ₁(i a_k t), a_k = ω_k − k·U,
  φ₁(z) = (eᶻ − 1)/z, m = K/ω.

A configuration changes ω and m (σ = 0, tanh kh → 1), drops the modes its coarser grid
cannot hold, and between steps replaces C by its cubic Hermite interpolant from C and the
simulation's η̇ = −iωC at the step ends. The difference X_k(t) = C_k^full(t) − C_k^cfg(t)
is evaluated per mode, and the height error of stones and ships bounded by the triangle
inequality,

.. math:: \max_x|\Delta\eta(x, t)| \le \frac1{n^2}\sum_k |\hat H_k|,\qquad
          \hat H_k = \tfrac12\left(X_k + \overline{X_{-k}}\right),

which is rigorous for the linear surface (the cutoff only removes waves); its RMS is exact
by Parseval. A wind sea has random phases, so its differences are Gaussian fields: their
maximum over the output's N points stays below z·RMS, z = sqrt(2 ln(2N/p)), except with
probability p = 10⁻³ (the union bound). The second-order term η₂ = ½ Re(η_c Λη_c) is bounded by
½ (Σ|C|/n²)(Σ|k||C|/n²) when dropped, and by the same bilinear bound on the differences when
kept; float32 rounding adds κ·Σ|C|/n² with κ measured by ``python -m bench calibrate``.
"""

from __future__ import annotations

__internal__ = True  # the planner's own models: used through plan(), not fuzzed as public API

import itertools
import math
from dataclasses import dataclass, replace
from functools import lru_cache

import numpy as np

from wavephys.planner.model import (BOUNDARIES, COARSEN, DEPTH_MODELS, MARGINS, SHIP_METHODS, STEPS_PER_FRAME, Choices, SceneModel,
                                   full_choices)
from wavephys.planner.scene import Scene
from wavephys.planner.spectrum import (CHOPPINESS, NOISE_HURST, NOISE_OCTAVES, SceneSpectrum, blended_mode_heights,
                                       dispersion_variants, evaluated_frames, gerstner_modes, mode_dispersion,
                                       mode_heights, noise_sea, pair_bound, scene_spectrum, variant_index)

__all__ = ["HeightBounds", "default_height_options", "height_bounds", "hermite_blend_error", "texture_error", "height_peak", "surface_bounds",
           "RESAMPLE_ERROR", "patch_bound", "margin_errors", "margin_step_errors", "margin_step_error", "boundary_errors", "depth_errors"]


def second_order_blend(spec: SceneSpectrum, dt: float) -> float:
    """Bound on the error of blending η₂ between steps without its rate: η₂ is a sum over pairs
    of modes at frequencies ω_p ± ω_q, each blended with error ≤ g((ω_p + ω_q)Δt)
    (:func:`hermite_blend_error`); binned by ω (:func:`pair_bound`)."""
    e = spec.omega_edges
    g = hermite_blend_error((e[:, None] + e[None, :]) * dt)
    return pair_bound(g, spec.omega_bins, spec.z)


@lru_cache(maxsize=1)
def _blend_weights():
    """h00, h01 of the cubic Hermite basis on 65 fractions s ∈ [0, 1] (column vectors)."""
    from wavephys.physics.interpolation import hermite_weights

    s = np.linspace(0.0, 1.0, 65)
    h00, h01, _, _ = (np.asarray(h, np.float64) for h in hermite_weights(s))
    return s[:, None], h00[:, None], h01[:, None]


def hermite_blend_error(theta) -> np.ndarray:
    """max over s ∈ [0, 1] and θ' ≤ θ of |h00 + h01·e^{−iθ'} − e^{−iθ's}|: the frame error of
    modes of phase step up to θ whose rate is not supplied (the second-order term's case);
    at most 2 (h00 + h01 = 1, both ≥ 0). Vectorized over θ (evaluated on a grid of 4096
    steps up to the largest θ, taking the grid value at or above each θ).

    Parameters
    ----------
    theta : array_like
        Phase steps ω·Δt, rad, ≥ 0.

    Returns
    -------
    numpy.ndarray
        The error bound per θ, relative to the mode's amplitude, shape of ``theta``.
    """
    theta = np.asarray(theta, np.float64)
    top = float(np.max(theta, initial=0.0))
    if top <= 0.0:
        return np.zeros_like(theta)
    s, h00, h01 = _blend_weights()
    grid = np.linspace(0.0, top, 4097)[None, :]
    raw = np.max(np.abs(h00 + h01 * np.exp(-1j * grid) - np.exp(-1j * grid * s)), axis=0)
    envelope = np.minimum(np.maximum.accumulate(raw), 2.0)
    at = np.minimum(np.searchsorted(grid[0], theta, side="left"), grid.size - 1)
    return envelope[at]


PATCH_SAMPLES = 3
"""Steps at which the ship patch's truncation is evaluated (the first, middle and last)."""
PATCH_MARGIN = 1.25
"""Safety factor on the evaluated patch term (the steps between the sampled ones)."""


def patch_bound(scene: Scene, coarsen: int, steps_per_frame: int, method: str) -> tuple:
    r"""What the single ship patch adds against the doubled one, evaluated: (max-norm bound on
    the heights, on |η_c|, on |Λη_c|), m, for the configuration's grid, Δt and ship method
    (the full model's water).

    Each step's new waves on the patch P and on the patch 2P differ by Δ (ψ units); their DFT
    on the simulation grid, |Δ̂_k|, is evaluated at :data:`PATCH_SAMPLES` steps and its
    largest value per mode taken. A ship on a straight course repeats the same Δ moved by
    U·Δt each step, so after N steps mode k holds Δ̂_k Σ_j e^{i a_k jΔt} (a = ω − k·U), of
    modulus ≤ |Δ̂_k|·min(N, 1/|sin(a_kΔt/2)|): only the modes near the Kelvin resonance add
    up. With η_c = i·m·ψ per mode, the bound is :data:`PATCH_MARGIN` ×
    (1/n²) Σ_k |m_k| |Δ̂_k| min(N, 1/|sin(a_kΔt/2)|), ×(1 + 0.3 ω_kΔt) where frames are
    blended between steps (the Hermite weights' rate terms). Evaluated, not bounded: the patch
    window's placement snaps to the grid, so Δ is a translate only up to a sub-texel shift.

    Parameters
    ----------
    scene : Scene
    coarsen : int
        The grid's coarsening.
    steps_per_frame : int
        Simulation steps a frame.
    method : str
        The ship method.

    Returns
    -------
    (float, float, float)
        m.
    """
    return _patch_bound(scene, coarsen, steps_per_frame, method)


@lru_cache(maxsize=256)
def _patch_bound(scene, coarsen, steps_per_frame, method):
    from wavephys.physics.ship_waves import ship_patch_waves

    base = Choices(coarsen=coarsen, steps_per_frame=steps_per_frame, ship_method=method)
    one = SceneModel(scene, replace(base, ship_patch=1))
    two = SceneModel(scene, replace(base, ship_patch=2))
    if one.ship_patch == two.ship_patch:
        return 0.0, 0.0, 0.0
    grid, water, dt, steps = one.grid, one.water, one.dt, one.steps
    n = grid.n
    k = np.asarray(grid.wavenumber_magnitude(), np.float64)
    ky, kx = (np.broadcast_to(np.asarray(a, np.float64), (n, n)) for a in grid.wavenumbers())
    omega, m = mode_dispersion(k, water)
    out = np.zeros(3)
    for spec, ship in zip(scene.ships, one.ships()):
        delta = np.zeros((n, n))
        for j in sorted({0, steps // 2, max(steps - 1, 0)}):
            field = np.zeros((n, n), np.complex128)
            for model, sign in ((one, 1.0), (two, -1.0)):
                waves, (r0, c0) = ship_patch_waves(ship, grid, water, j * dt, dt, model.ship_patch // 2, method)
                side = waves.shape[-1]
                rows, cols = (r0 + np.arange(side)) % n, (c0 + np.arange(side)) % n
                field[np.ix_(rows, cols)] += sign * np.asarray(waves, np.complex128)
            delta = np.maximum(delta, np.abs(np.fft.fft2(field)))
        ux, uy = spec.velocity
        a = omega - (kx * ux + ky * uy)
        sin = np.abs(np.sin(0.5 * a * dt))
        reach = np.minimum(steps, 1.0 / np.maximum(sin, 1e-300))
        if steps_per_frame > 1:
            reach = reach * (1.0 + 0.3 * omega * dt)
        weight = PATCH_MARGIN * m * delta * reach / n**2
        out += (float(weight.sum()), float(weight.sum()), float((k * weight).sum()))
    return tuple(out)


MARGIN_TEXELS = 512
"""Largest visible square (texels per side) whose margin is planned; larger keep n/8."""
MARGIN_SAFETY = 1.25
"""Factor on the measured margin difference (the other terms change it a little)."""


def margin_errors(scene: Scene) -> dict:
    """{margin choice: error}, m, for an open-water scene ({} for a periodic one): the largest
    difference on the visible square, over every frame, between the full model's linear heights
    with that cutoff margin and with n/8 (:data:`wavephys.planner.model.MARGINS`), × 1.25.

    Evaluated, not bounded: the planner runs the scene's linear model three times (why a bound
    does not serve: docs/planner.md §2, the margin). Scenes larger than :data:`MARGIN_TEXELS`
    keep n/8 (inf for the others).

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    dict
        Margin choice → error, m.
    """
    return dict(_margin_errors(scene))  # a copy: the cached result stays as measured


def margin_step_errors(scene: Scene) -> dict:
    """{(coarsen, steps per frame): error}, m, for an open-water scene ({} for a periodic one):
    how much the cutoff margin's own effect changes with the simulation grid and Δt, × 1.25.

    The cutoff damps once per step on the simulation grid's points (docs/physics.md, the
    open-ocean cutoff), so how much it absorbs, and reflects back into the square, depends on
    Δt and on the grid: a change the per-mode bounds (which see a periodic square) do not hold.
    Measured 1.1 mm at 4 steps per frame and 2.5 mm on a grid 2× coarser, on a 48-texel scene
    whose per-mode bounds for the same changes were 0.05 and 0.03 mm; a plan of it at 8 steps per
    frame, its η₂ (whose interpolation bound had hidden this) 100× smaller, missed its promise by
    33 %. Evaluated like the margin: the largest difference on the visible square over every
    frame between the full model's linear heights on a grid c× coarser (a step per frame) and
    on the texels, and likewise with s steps per frame; a pair's error is the sum of its two
    (each holds that term's own error again: a conservative double count). Scenes larger than
    :data:`MARGIN_TEXELS`: inf for all but the full model's (1, 1).

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    dict
        (coarsen, steps per frame) → error, m.
    """
    return dict(_margin_step_errors(scene))


@lru_cache(maxsize=16)
def _margin_step_errors(scene: Scene) -> dict:
    if not scene.margin:
        return {}
    spfs = tuple(s for s in STEPS_PER_FRAME if s <= scene.frames)
    return {(c, s): margin_step_error(scene, c, s) for c in COARSEN for s in spfs}


def margin_step_error(scene: Scene, coarsen: int, steps_per_frame: int) -> float:
    """One entry of :func:`margin_step_errors` (m; 0 for a periodic scene and for (1, 1)): the
    evaluated change of coarsening ``coarsen`` plus that of ``steps_per_frame``, each run once per
    scene (cached), so a plan runs only the ones its candidates within the tolerance need.

    Parameters
    ----------
    scene : Scene
    coarsen : int
        The grid's coarsening.
    steps_per_frame : int
        Simulation steps a frame.

    Returns
    -------
    float
        m.
    """
    if not scene.margin or (coarsen, steps_per_frame) == (1, 1):
        return 0.0
    if scene.texels > MARGIN_TEXELS:
        return math.inf
    return _margin_step_single(scene, "coarsen", coarsen) + _margin_step_single(scene, "steps_per_frame",
                                                                                steps_per_frame)


@lru_cache(maxsize=64)
def _margin_step_single(scene: Scene, name: str, value: int) -> float:
    from wavephys.planner.runner import simulated_heights

    if value == 1:
        return 0.0
    full = replace(full_choices(scene), second_order=False, depth_model="constant")

    def heights(**kw):
        model = SceneModel(scene, replace(full, **kw))
        if scene.ships:
            try:
                model.check_ships()
            except ValueError:  # the doubled patch leaves the square on this grid: the cutoff is the same
                model = SceneModel(scene, replace(full, ship_patch=1, **kw))
                model.check_ships()
        return simulated_heights(model).astype(np.float64)

    try:
        return MARGIN_SAFETY * float(np.abs(heights(**{name: value}) - _margin_step_reference(scene)).max())
    except ValueError:  # this grid cannot run the scene, or a ship's patch leaks at this Δt
        return math.inf


@lru_cache(maxsize=16)
def _margin_step_reference(scene: Scene) -> np.ndarray:
    from wavephys.planner.runner import simulated_heights

    full = replace(full_choices(scene), second_order=False, depth_model="constant")
    return simulated_heights(SceneModel(scene, full)).astype(np.float64)


@lru_cache(maxsize=16)
def _margin_errors(scene: Scene) -> dict:
    from wavephys.planner.model import MARGINS
    from wavephys.planner.runner import simulated_heights

    if not scene.margin:
        return {}
    if scene.texels > MARGIN_TEXELS:
        return {k: (0.0 if k == "n/8" else math.inf) for k in MARGINS}
    runs = {}
    for key in MARGINS:
        model = SceneModel(scene, Choices(second_order=False, margin=key, ship_patch=full_choices(scene).ship_patch,
                                          depth_model="constant"))
        try:
            if scene.ships:
                model.check_ships()
            runs[key] = simulated_heights(model).astype(np.float64)
        except ValueError:  # a ship's patch leaves the visible square at this margin
            runs[key] = None
    ref = runs["n/8"]
    return {k: (0.0 if k == "n/8" else math.inf if v is None else MARGIN_SAFETY * float(np.abs(v - ref).max()))
            for k, v in runs.items()}


def boundary_errors(scene: Scene) -> dict:
    """{boundary choice: error}, m, for a walled scene ({} for one without walls): the largest
    difference on the visible square, over every frame, between the full model's linear heights
    with that boundary (:data:`wavephys.planner.model.BOUNDARIES`) and with reflecting walls,
    × 1.25 (:data:`MARGIN_SAFETY`: the other terms change it a little).

    Evaluated, not bounded, as the margin is: the planner runs the scene's linear model three
    times. Scenes larger than :data:`MARGIN_TEXELS` keep the walls (inf for the others).

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    dict
        Boundary choice → error, m.
    """
    return dict(_boundary_errors(scene))  # a copy: the cached result stays as measured


@lru_cache(maxsize=16)
def _boundary_errors(scene: Scene) -> dict:
    from wavephys.planner.model import BOUNDARIES
    from wavephys.planner.runner import simulated_heights

    if not scene.walls:
        return {}
    if scene.texels > MARGIN_TEXELS:
        return {k: (0.0 if k == "walls" else math.inf) for k in BOUNDARIES}
    runs = {key: simulated_heights(SceneModel(scene, Choices(second_order=False, boundary=key,
                                                             depth_model="constant"))).astype(np.float64)
            for key in BOUNDARIES}
    ref = runs["walls"]
    return {k: (0.0 if k == "walls" else MARGIN_SAFETY * float(np.abs(v - ref).max())) for k, v in runs.items()}


def depth_errors(scene: Scene) -> dict:
    """{depth model: error}, m, for a scene with a sloping floor ({} for a flat one): the largest
    difference on the visible square, over every frame, between the spectral step's linear
    heights at the centre's depth (``"constant"``) and the waves stepped over the floor
    (``"varying"``, the full model), × 1.25 (:data:`MARGIN_SAFETY`).

    Evaluated, not bounded, as the margin is: the planner runs the scene's linear model over the
    floor and at constant depth (docs/planner.md, the depth model). Scenes larger than
    :data:`MARGIN_TEXELS` keep the floor (inf for constant depth).

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    dict
        Depth model → error, m.
    """
    return dict(_depth_errors(scene))  # a copy: the cached result stays as measured


@lru_cache(maxsize=16)
def _depth_errors(scene: Scene) -> dict:
    from wavephys.planner.runner import simulated_heights

    if scene.floor is None or scene.floor.slope == 0:
        return {}
    if scene.texels > MARGIN_TEXELS:
        return {"varying": 0.0, "constant": math.inf}
    full = full_choices(scene)
    runs = {key: simulated_heights(SceneModel(scene, replace(full, depth_model=key))).astype(np.float64)
            for key in DEPTH_MODELS}
    return {"varying": 0.0, "constant": MARGIN_SAFETY * float(np.abs(runs["constant"] - runs["varying"]).max())}


@dataclass(frozen=True)
class HeightBounds:
    """Predicted height errors (m) of one configuration against the full model.

    ``linear`` max-norm bound of the first-order surface, ``second_order`` of the η₂ term,
    ``rounding`` the float32 floor; ``total`` their sum (the triangle inequality: terms
    add in the max norm). ``rms``: a bound on the RMS over the visible square: the linear RMS
    over the simulated square (exact, by Parseval) times sqrt(simulated/visible area), plus
    the second-order and float32 max-norm bounds.

    Attributes
    ----------
    linear : float
        Max-norm bound of the first-order surface's error, m.
    second_order : float
        Of the η₂ term's, m.
    rounding : float
        The float32 floor, m.
    rms : float
        Bound on the RMS error over the visible square, m.
    total : float
        linear + second_order + rounding, m (a property).
    """

    linear: float
    second_order: float
    rounding: float
    rms: float

    @property
    def total(self) -> float:
        return self.linear + self.second_order + self.rounding


def _bound(spec, kappa, same, so, c, spf, e_lin, d0, d1, rms, blend) -> HeightBounds:
    """One configuration's bounds from its linear bound ``e_lin``, the bounds ``d0``, ``d1`` on
    its change of |η_c| and |Λη_c| and its linear ``rms`` (over the visible square)."""
    floor = float(kappa * spec.s0)
    if same and so:  # the full model itself (or one that computes the same numbers)
        return HeightBounds(0.0, 0.0, floor, floor)
    if same:  # only the second-order term differs
        return HeightBounds(0.0, 0.5 * spec.s0 * spec.s1, floor, 0.5 * spec.s0 * spec.s1 + floor)
    if so:
        e2 = 0.5 * (d0 * spec.s1 + spec.s0 * d1)
        if c > 1:  # products of modes the coarse grid folds back (aliasing)
            e2 += spec.alias[c]
        if spf > 1:  # η₂ is interpolated without its rate
            e2 += blend[spf]
    else:
        e2 = 0.5 * spec.s0 * spec.s1
    dropped = 2 * spec.dropped
    return HeightBounds(e_lin + dropped, float(e2), floor, rms + float(e2) + floor)


def default_height_options(scene: Scene) -> dict:
    """Every option of each of the spectral step's terms a scene can take (the one definition
    :mod:`wavephys.planner.terms` offers them from), {term: values}: both dispersion switches, every coarsening, the
    steps per frame up to the scene's frames, the second-order term on and off, the impulse
    method and the single patch only where there are ships (the latter where the full model
    takes the doubled patch), the narrower margins only for open water; over a sloping floor the
    linear model only (the depth stepper, the full model, is linear) and both depth models, the boundaries other than
    walls only for a walled scene.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    dict
        Term name → tuple of values, the full model's first.
    """
    full_patch = full_choices(scene).ship_patch
    return dict(surface_tension=(True, False), finite_depth=(True, False), coarsen=COARSEN,
                steps_per_frame=tuple(s for s in STEPS_PER_FRAME if s <= scene.frames),
                second_order=(False,) if _sloping(scene) else (True, False),
                ship_method=SHIP_METHODS if scene.ships else SHIP_METHODS[:1],
                ship_patch=(1, 2) if scene.ships and full_patch == 2 else (full_patch,),
                margin=MARGINS if scene.margin else MARGINS[:1],
                boundary=BOUNDARIES if scene.walls else BOUNDARIES[:1],
                depth_model=DEPTH_MODELS if _sloping(scene) else DEPTH_MODELS[:1])


def _sloping(scene: Scene) -> bool:
    return scene.floor is not None and scene.floor.slope > 0


@dataclass(frozen=True)
class _Linear:
    """What every configuration's linear bound is measured against: the full model's C_k and
    Ĥ_k at the evaluated frames, the modes each coarsening holds, and the η₂ blend bounds."""

    spec: SceneSpectrum
    t: np.ndarray
    waters: list
    disp: list
    kinds: tuple
    full: dict
    h_full: dict
    masks: dict
    blend: dict
    area: float


def _linear_context(scene: Scene, coarsens, spfs) -> _Linear:
    if scene.walls:  # the tank's cosine modes are its even extension's Fourier modes (exactly)
        scene = scene.even_extension()
    spec = scene_spectrum(scene)
    full_grid = SceneModel(scene).full_grid
    t = (evaluated_frames(scene.frames) / scene.fps)[:, None]
    waters = dispersion_variants(scene)
    disp = [mode_dispersion(spec.k, w) for w in waters]
    kinds = (False, True) if bool(np.any(spec.W)) else (False,)
    full = {w: mode_heights(spec, disp[0][0], disp[0][1], t, w) for w in kinds}
    h_full = {w: 0.5 * (c + np.conj(c[:, spec.mirror])) for w, c in full.items()}
    kmax_axis = np.maximum(np.abs(spec.kx), np.abs(spec.ky))
    masks = {}
    for c in coarsens:  # the modes a grid c times coarser holds (its Nyquist lines excluded)
        k_nyq = math.pi / (c * float(full_grid.dx))
        masks[c] = np.ones_like(kmax_axis, bool) if c == 1 else (kmax_axis < k_nyq - 1e-9 * k_nyq)
    blend = {spf: second_order_blend(spec, spf / scene.fps) for spf in spfs}
    area = full_grid.n / scene.texels  # an RMS over the visible square ≤ this × the RMS over the simulated one
    return _Linear(spec, t, waters, disp, kinds, full, h_full, masks, blend, area)


def _differences(lin: _Linear, vi: int, impulses: bool, spf: int, fps: float) -> dict:
    """Per kind of source (deterministic, wind): X = C_full − C_cfg and its real part's Ĥ."""
    spec, t = lin.spec, lin.t
    omega, m = lin.disp[vi]
    dt = spf / fps
    out = {}
    for w in lin.kinds:
        if spf == 1:
            cfg = mode_heights(spec, omega, m, t, w, dt if impulses and not w else None)
        else:
            cfg = blended_mode_heights(spec, omega, m, t, dt, w, impulses and not w)
        x = lin.full[w] - cfg
        out[w] = (x, 0.5 * (x + np.conj(x[:, spec.mirror])))
    return out


def _linear_sums(lin: _Linear, diffs: dict, c: int) -> tuple:
    """(e_lin, d0, d1, rms) of one configuration on a grid coarsened c times: the max-norm bound
    of the linear heights, the bounds on the change of |η_c| and |Λη_c|, the linear RMS."""
    spec = lin.spec
    n, z, root2, kk = spec.n, spec.z, math.sqrt(2.0), spec.k
    keep = lin.masks[c]
    lost = np.where(keep, 0.0, 2.0)  # a lost mode: its content, and at most as much misplaced
    e_lin = d0 = d1 = rms = 0.0
    for w, (x, h) in diffs.items():
        ah = np.where(keep, np.abs(h), lost * np.abs(lin.h_full[w]))
        ax = np.where(keep, np.abs(x), lost * np.abs(lin.full[w]))
        sq = np.sqrt(np.sum(ah**2, axis=1)) / n**2
        rms += float(np.max(sq))
        if w:  # the random sea: z × RMS (Parseval), √2 for the complex height
            e_lin += z * float(np.max(sq))
            d0 += root2 * z * float(np.max(np.sqrt(np.sum(ax**2, axis=1)))) / n**2
            d1 += root2 * z * float(np.max(np.sqrt(np.sum((kk * ax) ** 2, axis=1)))) / n**2
        else:
            e_lin += float(np.max(np.sum(ah, axis=1))) / n**2
            d0 += float(np.max(np.sum(ax, axis=1))) / n**2
            d1 += float(np.max(np.sum(kk * ax, axis=1))) / n**2
    return e_lin, d0, d1, rms


def height_bounds(scene: Scene, kappa: float, options=None, defer_steps: bool = False) -> dict:
    """:class:`HeightBounds` of every height configuration of ``scene``, a dict keyed by its
    :class:`~wavephys.planner.model.Choices` (the other terms full): the product of
    ``options`` ({term: values} for each of the spectral step's terms; default
    :func:`default_height_options`), less what cannot run. The single patch adds
    :func:`patch_bound` where the full model takes the doubled patch; the narrower margins add
    :func:`margin_errors` (a margin whose error is inf is left out), a walled scene's other
    boundaries :func:`boundary_errors`. A walled scene's per-mode bounds are its even
    extension's (:meth:`wavephys.planner.scene.Scene.even_extension`), whose Fourier modes are
    the tank's cosine modes: exact for the walls, and the boundary's evaluated change added
    for the others. The cutoff's change with the grid and Δt (:func:`margin_step_error`) is added
    too, unless ``defer_steps``: then it is left for the caller to add where it needs it (the plan
    adds it only to the candidates within its tolerance, :meth:`~wavephys.planner.terms.PlanContext.settle`).

    Stones and ships are bounded by the triangle inequality (rigorous for the linear
    surface); the wind sea by z × its RMS (:func:`wavephys.planner.spectrum.gaussian_factor`).
    ``kappa``: the float32 rounding coefficient (calibrated). The full configuration's own
    bound is the float32 floor alone.

    Parameters
    ----------
    scene : Scene
    kappa : float
        The calibrated factor of the second-order bound.
    options : dict, optional
        Term name → values (default :func:`default_height_options`).
    defer_steps : bool
        Leave the cutoff's change with the grid and Δt to later (:func:`margin_step_error`).

    Returns
    -------
    dict
        :class:`~wavephys.planner.model.Choices` → :class:`HeightBounds`.
    """
    opts = default_height_options(scene) if options is None else options
    spfs = tuple(s for s in opts["steps_per_frame"] if s <= scene.frames)
    lin = _linear_context(scene, opts["coarsen"], spfs)
    full_patch = full_choices(scene).ship_patch
    measured = margin_errors(scene) or {"n/8": 0.0}
    margins = {k: v for k, v in measured.items() if k in opts["margin"] and math.isfinite(v)} or {"n/8": 0.0}
    measured = boundary_errors(scene) or {"walls": 0.0}
    boundaries = {k: v for k, v in measured.items() if k in opts.get("boundary", ("walls",)) and math.isfinite(v)}
    margins = {(m, b): e + f for m, e in margins.items() for b, f in (boundaries or {"walls": 0.0}).items()}
    stepped = {} if defer_steps else margin_step_errors(scene)
    full = full_choices(scene)
    floor = _sloping(scene) and "constant" in opts.get("depth_model", ("varying",))
    e_depth = depth_errors(scene).get("constant", math.inf) if floor else math.inf
    out = {}
    for st, fd, method, spf in itertools.product(opts["surface_tension"], opts["finite_depth"], opts["ship_method"],
                                                  spfs):

        vi = variant_index(Choices(surface_tension=st, finite_depth=fd))
        impulses = method == "impulses"
        diffs = _differences(lin, vi, impulses, spf, scene.fps)
        for c in opts["coarsen"]:
            e_step = stepped.get((c, spf), 0.0)  # the cutoff's change with the grid and Δt (margin_step_errors)
            if defer_steps and scene.margin and scene.texels > MARGIN_TEXELS and (c, spf) != (1, 1):
                e_step = math.inf
            if not math.isfinite(e_step):
                continue
            e_lin, d0, d1, rms = _linear_sums(lin, diffs, c)
            same = lin.waters[vi] == lin.waters[0] and c == 1 and spf == 1 and not impulses  # e.g. no tanh, deep
            for so, patch in itertools.product(opts["second_order"], opts["ship_patch"]):
                if patch < full_patch:  # the single patch against the full model's doubled one
                    try:
                        p_lin, p0, p1 = patch_bound(scene, c, spf, method)
                    except ValueError:  # this coarsening cannot run the scene (SceneModel says why)
                        continue
                    b = _bound(lin.spec, kappa, False, so, c, spf, e_lin, d0 + p0, d1 + p1, rms * lin.area, lin.blend)
                    b = HeightBounds(b.linear + p_lin, b.second_order, b.rounding, b.rms + p_lin)
                else:
                    b = _bound(lin.spec, kappa, same, so, c, spf, e_lin, d0, d1, rms * lin.area, lin.blend)
                if _sloping(scene):  # the full model is linear (the depth stepper; so is every option): no η₂ to lose
                    b = HeightBounds(b.linear, 0.0, b.rounding, b.rms - b.second_order)
                for (margin, boundary), e_margin in margins.items():  # the margin's (boundary's) measured change adds
                    if boundary == "margin" and (c > 1 or spf > 1):  # its cutoff's change with grid and Δt: unmeasured
                        continue
                    key = Choices(st, fd, c, spf, so, ship_method=method, ship_patch=patch, margin=margin,
                                  boundary=boundary)
                    e_margin += e_step
                    bb = b if not e_margin else HeightBounds(b.linear + e_margin, b.second_order, b.rounding,
                                                            b.rms + e_margin)
                    if not _sloping(scene):
                        out[key] = bb
                        continue
                    if replace(key, caustics=full.caustics) == full:  # the floor stepped: the full model itself
                        out[key] = HeightBounds(0.0, 0.0, bb.rounding, bb.rounding)
                    if math.isfinite(e_depth):  # the spectral step at the centre's depth: its measured change adds
                        out[replace(key, depth_model="constant")] = HeightBounds(
                            bb.linear + e_depth, bb.second_order, bb.rounding, bb.rms + e_depth)
    return out


def height_peak(scene: Scene, bounds: HeightBounds) -> float:
    """A bound on max |η| of a configuration's heights, m: the full model's (|η_c| ≤ s0, |η₂| ≤
    ½·s0·s1) plus that configuration's error bound ``bounds``.

    Parameters
    ----------
    scene : Scene
    bounds : HeightBounds
        The configuration's error bounds.

    Returns
    -------
    float
        m.
    """
    spec = scene_spectrum(scene)
    return spec.s0 + 0.5 * spec.s0 * spec.s1 + bounds.total


HALF_RELATIVE, HALF_SUBNORMAL = 2.0**-11, 2.0**-25
"""Round to nearest half float: half an ulp, at most 2⁻¹¹ of the value for normal numbers and
2⁻²⁵ absolute (half the subnormal spacing 2⁻²⁴) below 2⁻¹⁴."""
HALF_MAX = 65504.0


def texture_error(fmt: str, peak: float) -> float:
    """Bound on what storing heights with |η| ≤ ``peak`` (m) in the height texture format ``fmt``
    (:data:`wavephys.planner.model.TEXTURES`) adds, m, in the max norm.

    * ``f32``: 0 (the frames are float32 already: the full model's own texture);
    * ``f16``: max(2⁻¹¹·peak, 2⁻²⁵) (round to nearest half float); inf past the largest
      half float, 65504;
    * ``u16`` / ``u8``: each frame is mapped from its own minimum to its maximum (a span of at
      most 2·peak) onto 2^b codes and rounded to the nearest: half a code, peak / (2^b − 1).

    Parameters
    ----------
    fmt : str
        A height texture format.
    peak : float
        The heights' largest magnitude, m.

    Returns
    -------
    float
        m (inf where the format cannot hold the heights).
    """
    from wavephys.core.inputs import check_choice, check_scalar
    from wavephys.planner.model import TEXTURES

    check_choice("fmt", fmt, TEXTURES)
    peak = check_scalar("peak", peak, lo=0.0)
    if fmt == "f32":
        return 0.0
    if fmt == "f16":
        return math.inf if peak > HALF_MAX else max(HALF_RELATIVE * peak, HALF_SUBNORMAL)
    levels = 2.0 ** (16 if fmt == "u16" else 8) - 1.0
    return peak / levels


RESAMPLE_ERROR = 0.01
"""Error of resampling displaced heights onto the texels, as a fraction of the height range:
:func:`wavephys.surfaces.resample.resample_heights` at refine 2 stays below 1 % of it for
choppiness up to 0.9 of the folding value (measured by its tests)."""
CHOPPY_REACH = 0.9
"""The choppy model is offered where 2λ·s1 (a bound on λ|∂D|) stays below this: the resampling's
1 % was measured up to 0.9 of the folding choppiness."""


def _phase_rounding(spec: SceneSpectrum, scene: Scene, sel, count: int) -> float:
    """Float32 rounding of summing modes ``sel`` directly: each phase k·x − ωt + φ rounded to
    within 4 ulps of its size Θ, each cosine to 1 ulp, and the sum of ``count`` terms to
    ``count`` ulps of Σ A: 2⁻²⁴ Σ A (4Θ + count + 1)."""
    amp = np.abs(spec.W[sel]) / spec.n**2
    omega = mode_dispersion(spec.k[sel], scene.water)[0]
    theta = spec.k[sel] * scene.extent / math.sqrt(2.0) + omega * scene.duration + math.pi
    return float(2.0**-24 * np.sum(amp * (4.0 * theta + count + 1)))


def surface_bounds(scene: Scene, kappa: float) -> dict:
    """:class:`HeightBounds` of each surface model other than the spectral step
    (:data:`wavephys.planner.model.SURFACES`) against the full model, for a scene whose only
    source is a wind sea ({} otherwise; an unavailable model is left out):

    * ``gerstner-K``: the other modes are missing, a Gaussian field bounded by z × their RMS
      (Parseval); η₂ is missing (½·s0·s1); float32 phases (:func:`_phase_rounding`);
    * ``choppy``: the same linear sea, each point moved by λD with |D| ≤ √2·s0, so a texel
      shows the height from up to λ√2·s0 away: ≤ λ√2·s0·s1; η₂ missing; resampling
      :data:`RESAMPLE_ERROR` × the range 2·s0. Unavailable from 2λ·s1 ≥ 0.9 (where it may fold,
      beyond the range the resampling error was measured on);
    * ``noise``: an unrelated field: |η_full| + |η_noise| ≤ s0 + ½·s0·s1 + a·Σ 2^{−Hi}.

    Parameters
    ----------
    scene : Scene
    kappa : float
        The calibrated factor of the second-order bound.

    Returns
    -------
    dict
        Surface model → :class:`HeightBounds`.
    """
    if scene.stones or scene.ships or scene.wind is None:
        return {}
    spec = scene_spectrum(scene)
    n, z = spec.n, spec.z
    floor = float(kappa * spec.s0)
    e2 = 0.5 * spec.s0 * spec.s1
    dropped = 2.0 * spec.dropped
    out = {}
    a = np.abs(spec.W)
    for name in ("gerstner-16", "gerstner-64", "gerstner-256"):
        count = int(name.split("-")[1])
        keep = np.zeros(a.size, bool)
        keep[gerstner_modes(scene, count)] = True
        x = np.where(keep, 0.0, a)
        h = 0.5 * (x + x[spec.mirror])
        rms = float(np.sqrt(np.sum(h * h))) / n**2
        lin = z * rms + dropped
        rounding = floor + _phase_rounding(spec, scene, keep, int(keep.sum()))
        out[name] = HeightBounds(lin, e2, rounding, rms + e2 + rounding)
    if 2.0 * CHOPPINESS * spec.s1 < CHOPPY_REACH:  # within the range its resampling error was measured on
        move = CHOPPINESS * math.sqrt(2.0) * spec.s0 * spec.s1 + RESAMPLE_ERROR * 2.0 * spec.s0
        rounding = floor + _phase_rounding(spec, scene, np.ones(a.size, bool), 1)
        out["choppy"] = HeightBounds(move + dropped, e2, rounding, move + dropped + e2 + rounding)
    try:
        amp = noise_sea(scene).amplitude * sum(2.0 ** (-NOISE_HURST * i) for i in range(NOISE_OCTAVES))
    except ValueError:  # the scene's square cannot hold the noise's lattice: left out
        return out
    out["noise"] = HeightBounds(spec.s0 + amp, e2, floor, spec.s0 + amp + e2 + floor)
    return out
