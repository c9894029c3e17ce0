r"""The per-scene context the planner's error models share: the scene's modes and their heights.

The spectral step is exact per Fourier mode, so the linear surface of every scene the
planner takes is a closed form per mode k (docs/planner.md §2). With C_k(t) the DFT of the
complex height η_c (η = Re η_c) on the full grid:

* stones and the wind sea, given at t = 0 as heights: C_k(t) = A_k e^{−iω_k t};
* a ship on a straight course from x₀ at velocity U, source ∂(s f)/∂t:
  C_k(t) = s·m_k·(k·U)·f̂_k e^{−ik·x₀} e^{−iω_k t} · t·φ₁(i a_k t), a_k = ω_k − k·U,
  φ₁(z) = (eᶻ − 1)/z, m = K/ω.

:func:`scene_spectrum` gathers the modes once per scene (:class:`SceneSpectrum`);
:func:`mode_heights` and :func:`blended_mode_heights` evaluate C_k(t) for a configuration's
dispersion (:func:`mode_dispersion`, :func:`dispersion_variants`), step and ship method; the
wind sea's cheap surface models (:func:`gerstner_modes`, :func:`noise_sea`) are defined on the
same modes. Used by the error models (:mod:`wavephys.planner.predict`,
:mod:`wavephys.planner.caustics`) and the runner, below both.
"""

from __future__ import annotations

__internal__ = True  # the planner's own models: used through plan(), not fuzzed as public API

import math
from dataclasses import dataclass
from functools import lru_cache

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.water import Water
from wavephys.planner.model import COARSEN, STEPS_PER_FRAME, Choices, SceneModel
from wavephys.planner.scene import Scene

__all__ = ["SceneSpectrum", "scene_spectrum", "mode_dispersion", "dispersion_variants", "variant_index",
           "mode_heights", "blended_mode_heights", "evaluated_frames", "pair_bound", "gaussian_factor",
           "wind_heights", "gerstner_modes", "sea_rms", "noise_sea", "CHOPPINESS", "CONFIDENCE"]


SUPPORT_FRACTION = 1e-6
"""Modes are dropped from the per-mode sums in ascending order of their largest possible
|C| while the dropped total stays below this fraction of Σ|C|; the dropped total, doubled,
is added to every bound."""


MAX_EVALUATED_FRAMES = 24


def mode_dispersion(k, water: Water):
    """(ω, m = K/ω) in float64 on a numpy wavenumber array: the library's own formulas
    (:func:`wavephys.physics.dispersion.angular_frequency`,
    :func:`wavephys.physics.heights.height_multiplier`).

    Parameters
    ----------
    k : numpy.ndarray
        Wavenumbers, rad/m.
    water : Water

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        ω (rad/s) and m = K/ω (s/m), shape of ``k``.
    """
    from wavephys.physics.dispersion import angular_frequency
    from wavephys.physics.heights import height_multiplier

    with jax.enable_x64(True):
        kj = jnp.asarray(k, jnp.float64)
        omega = np.asarray(angular_frequency(kj, water), np.float64)
        m = np.asarray(height_multiplier(kj, water), np.float64)
    return omega, m


def _phi1(z):
    """(eᶻ − 1)/z for complex z, 1 at z = 0 (accurate near 0 by expm1)."""
    small = np.abs(z) < 1e-12
    zz = np.where(small, 1.0, z)
    return np.where(small, 1.0 + 0.5 * z, np.expm1(zz) / zz)


@dataclass(frozen=True)
class SceneSpectrum:
    """The scene's modes on the full grid, restricted to where they matter.

    Attributes
    ----------
    n : int
        The full grid's points a side.
    k, kx, ky : numpy.ndarray (M,)
        The support's wavenumbers, rad/m.
    mirror : numpy.ndarray (M,)
        Index in the support of −k.
    index : tuple
        (rows, cols) of the support in the full spectrum.
    A, W : numpy.ndarray (M,)
        Complex heights at t = 0 of the impulses (stones) and of the wind sea.
    ships : tuple
        Per ship: its spectrum B (M,) and velocity (Ux, Uy), m/s.
    dropped : float
        What the dropped modes carry at most, m.
    z : float
        The Gaussian union-bound factor of the wind sea's maxima.
    s0, s1 : float
        Bounds on max |η_c| (m) and on max |Λη_c| (also on |∇η|).
    s0_hi, s1_hi : dict
        Per coarsening, the same for the modes past half its Nyquist wavenumber.
    omega_top : float
        The largest ω of the support, rad/s.
    omega_edges : numpy.ndarray
        Upper edges of the ω bins, rad/s.
    omega_bins : tuple
        Per bin, the amplitude sums and variances its bounds use.
    alias : dict
        Per coarsening, the bound on the η₂ products the coarse grid folds back, m.
    """

    n: int
    k: np.ndarray            # |k| on the support (M,)
    kx: np.ndarray
    ky: np.ndarray
    mirror: np.ndarray       # index in the support of −k
    index: tuple             # (rows, cols) of the support in the full spectrum
    A: np.ndarray            # deterministic impulse heights at t = 0 (stones) (M,) complex
    W: np.ndarray            # the wind sea's heights at t = 0 (M,) complex (random phases)
    ships: tuple             # ((B (M,) complex, (Ux, Uy)), ...): B = s (k·U) f̂ e^{-ik·x0}
    dropped: float           # Σ of the dropped modes' largest |C|, / n²
    z: float                 # Gaussian union-bound factor of the wind sea's maxima
    s0: float                # bound on max|η_c| (triangle for stones and ships, z·RMS for the sea)
    s1: float                # bound on max|Λη_c| (the same with |k| weights); also bounds |∇η|
    s0_hi: dict              # per coarsen c: s0 of the modes with a component > k_N(c)/2
    s1_hi: dict
    omega_top: float         # the largest ω of the support, over the four dispersion variants
    omega_edges: np.ndarray  # upper edges of the ω bins (rad/s)
    omega_bins: tuple        # (d0, d1, v0, v1) per ω bin (_bins)
    alias: dict              # per coarsen c: the bound on η₂ products the coarse grid folds back

    @property
    def max_slope(self) -> float:
        """A bound on |∇η| over the scene (s1)."""
        return self.s1


def scene_spectrum(scene: Scene) -> SceneSpectrum:
    """The scene's per-mode amplitudes on its full grid (cached per scene); a walled scene's are
    its even extension's (:meth:`wavephys.planner.scene.Scene.even_extension`: the tank's cosine
    modes).

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    SceneSpectrum
    """
    return _scene_spectrum(scene.even_extension() if scene.walls else scene)


@lru_cache(maxsize=16)
def _scene_spectrum(scene: Scene) -> SceneSpectrum:
    model = SceneModel(scene)
    grid = model.full_grid
    n = grid.n
    ky, kx = (np.broadcast_to(np.asarray(a, np.float64), (n, n)) for a in grid.wavenumbers())
    k = np.hypot(kx, ky)
    A = np.zeros((n, n), np.complex128)
    W = np.zeros((n, n), np.complex128)
    if scene.stones:
        from wavephys.physics.disturbances import stone_height_spectrum

        with jax.enable_x64(True):
            A += np.asarray(stone_height_spectrum(model.stones(), grid, real=False), np.complex128)
    if scene.wind is not None:
        W += wind_heights(scene, grid)
    variants = [mode_dispersion(k, v) for v in dispersion_variants(scene)]
    m_max = np.max([m for _, m in variants], axis=0)
    sup = np.abs(A)
    reach_all = np.abs(A)  # with the ships' impulse method too (for the support alone)
    ships = []
    T = scene.duration
    for spec, ship in zip(scene.ships, model.ships()):
        f_hat = hull_dft(ship, grid, spec)
        ux, uy = spec.velocity
        kv = kx * ux + ky * uy
        B = spec.strength * kv * f_hat
        ships.append((B, (ux, uy)))
        a_min = np.min([np.abs(om - kv) for om, _ in variants], axis=0)
        reach = np.minimum(T, 2.0 / np.maximum(a_min, 1e-300))  # |t·φ₁(iat)| of the kernels
        sup = sup + m_max * np.abs(B) * reach
        for om, _ in variants:  # the impulse method: |Δt·φ₁·Σ e^{iajΔt}| ≤ Δt·min(N, 1/|sin(aΔt/2)|)
            for spf in STEPS_PER_FRAME:
                dt = spf / scene.fps
                sin = np.abs(np.sin(0.5 * (om - kv) * dt))
                reach = np.maximum(reach, dt * np.minimum(math.ceil(T / dt), 1.0 / np.maximum(sin, 1e-300)))
        reach_all = reach_all + m_max * np.abs(B) * reach
    sup[0, 0] = 0.0
    reach_all[0, 0] = 0.0
    det = sup.copy()  # the deterministic sources' largest |C| per mode (the full model's)
    sup = np.maximum(sup, reach_all) + np.abs(W)  # what any configuration can put in a mode
    total = float(sup.sum())
    if total == 0.0:
        raise ValueError(f"scene {scene.name!r}: its sources make no waves on a {n}² grid")
    # the support: drop the smallest modes while their total stays below SUPPORT_FRACTION
    sym = np.maximum(sup, np.roll(np.flip(sup, (0, 1)), 1, (0, 1)))  # a mode and its mirror together
    order = np.argsort(sym, axis=None)
    csum = np.cumsum(sup.ravel()[order])
    cut = int(np.searchsorted(csum, SUPPORT_FRACTION * total, side="right"))
    keep = np.zeros(n * n, bool)
    keep[order[cut:]] = True
    keep = keep.reshape(n, n)
    keep |= np.roll(np.flip(keep, (0, 1)), 1, (0, 1))
    keep[0, 0] = False
    dropped = float(sup[~keep].sum()) / n**2
    rows, cols = np.nonzero(keep)
    pos = -np.ones((n, n), np.int64)
    pos[rows, cols] = np.arange(rows.size)
    mirror = pos[(-rows) % n, (-cols) % n]
    z = gaussian_factor(scene)
    w2 = np.abs(W) ** 2
    bound = lambda sel, weight: (float((weight * det)[sel].sum()) / n**2
                                 + math.sqrt(2.0) * z * math.sqrt(float((weight**2 * w2)[sel].sum())) / n**2)
    everywhere = np.ones((n, n), bool)
    s0, s1 = bound(everywhere, 1.0), bound(everywhere, k)
    s0_hi, s1_hi, alias = {}, {}, {}
    kmax = np.maximum(np.abs(kx), np.abs(ky))
    for c in COARSEN:
        k_nyq = math.pi / (c * float(grid.dx))
        hi = kmax > 0.5 * k_nyq
        s0_hi[c], s1_hi[c] = bound(hi, 1.0), bound(hi, k)
        # products of two kept modes fold back only if their components sum past k_N: bin the
        # modes by max(|kx|, |ky|) / k_N and add the pairs of bins whose upper edges can
        edges = np.linspace(0.0, 1.0, ALIAS_BINS + 1)[1:]
        b = np.where(kmax < k_nyq, np.minimum((kmax / k_nyq * ALIAS_BINS).astype(int), ALIAS_BINS - 1), -1)
        folds = (edges[:, None] + edges[None, :] > 1.0 + 1e-12).astype(float)
        alias[c] = pair_bound(folds, _bins(b, ALIAS_BINS, det, w2, k, n), z)
    omega_all = np.max([om for om, _ in variants], axis=0)
    omega_top = float(omega_all[keep].max())
    omega_edges = np.linspace(0.0, omega_top, OMEGA_BINS + 1)[1:]
    ob = np.minimum((omega_all / omega_top * OMEGA_BINS).astype(int), OMEGA_BINS - 1)
    omega_bins = _bins(ob, OMEGA_BINS, det, w2, k, n)
    return SceneSpectrum(n, k[rows, cols], kx[rows, cols], ky[rows, cols], mirror, (rows, cols), A[rows, cols],
                     W[rows, cols], tuple((B[rows, cols], u) for B, u in ships), dropped, z, s0, s1, s0_hi, s1_hi,
                     omega_top, omega_edges, omega_bins, alias)


ALIAS_BINS = 16


OMEGA_BINS = 24


def _bins(index, count, det, w2, k, n):
    """Per bin (index −1: none): the deterministic sums Σ|C|, Σ|k||C| (/n²) and the wind sea's
    variances Σ|W|², Σ k²|W|² (/n⁴)."""
    out = np.zeros((4, count))
    for i in range(count):
        sel = index == i
        out[:, i] = ((det[sel]).sum() / n**2, (k * det)[sel].sum() / n**2, w2[sel].sum() / n**4,
                     (k * k * w2)[sel].sum() / n**4)
    return tuple(out)


def pair_bound(G, bins, z) -> float:
    """Bound on ½|Σ_ab G_ab η_c,a Λη_c,b| (η₂'s pairs of bins a, b weighted by G ≥ 0).

    Stones and ships (deterministic): ½ Σ G_ab d0_a d1_b (the triangle inequality). The wind
    sea (random phases): each sum over one bin's partner, Σ_b G_ab Λη_c,b, is a Gaussian field
    of variance Σ_b G_ab² v1_b, bounded by √2·z·RMS; sea–sea pairs use ½(√2z)² sqrt(Σ G² v0 v1)
    (for a constant G this is the product of the two fields' bounds).

    Parameters
    ----------
    G : numpy.ndarray (B, B)
        The pair weights, ≥ 0.
    bins : tuple
        (d0, d1, v0, v1) per bin (:attr:`SceneSpectrum.omega_bins`).
    z : float
        The Gaussian factor.

    Returns
    -------
    float
        m.
    """
    d0, d1, v0, v1 = bins
    r = math.sqrt(2.0) * z
    dd = float(np.sum(G * d0[:, None] * d1[None, :]))
    ww = r * r * math.sqrt(float(np.sum(G * G * v0[:, None] * v1[None, :])))
    cross = r * (float(np.sum(d0 * np.sqrt(np.sum(G * G * v1[None, :], axis=1))))
                 + float(np.sum(d1 * np.sqrt(np.sum(G * G * v0[:, None], axis=0)))))
    return 0.5 * (dd + ww + cross)


CONFIDENCE = 1e-3
"""Probability the wind sea's bound may be exceeded (:func:`gaussian_factor`)."""


def gaussian_factor(scene: Scene) -> float:
    """z = sqrt(2 ln(2N/p)): a Gaussian field of RMS σ exceeds z·σ somewhere among N points with
    probability below p (the union bound), N = texels² × frames, p = :data:`CONFIDENCE`. The
    wind sea's heights, and every linear change of them, are such fields (random phases).

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    float
        z.
    """
    points = scene.texels**2 * scene.frames
    return math.sqrt(2.0 * math.log(2.0 * points / CONFIDENCE))


def dispersion_variants(scene: Scene):
    """The four dispersion variants, full first: (σ, tanh) on/off.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    list of Water
        The waters of the four variants.
    """
    return [SceneModel(scene, Choices(surface_tension=s, finite_depth=d)).water
            for s, d in ((True, True), (False, True), (True, False), (False, False))]


def variant_index(choices: Choices) -> int:
    """The index in :func:`dispersion_variants` of a configuration's dispersion (σ, tanh) switches.

    Parameters
    ----------
    choices : Choices

    Returns
    -------
    int
        0 … 3.
    """
    return {(True, True): 0, (False, True): 1, (True, False): 2, (False, False): 3}[
        (choices.surface_tension, choices.finite_depth)]


def wind_heights(scene: Scene, grid) -> np.ndarray:
    """The wind sea's complex-height DFT ĥ at t = 0 on ``grid`` (full spectrum, m per sample sum;
    cached per scene and grid: a read-only array).

    Parameters
    ----------
    scene : Scene
    grid : Grid

    Returns
    -------
    numpy.ndarray (n, n)
        Complex.
    """
    return _wind_heights(scene, grid)


@lru_cache(maxsize=8)
def _wind_heights(scene: Scene, grid) -> np.ndarray:
    from wavephys.physics.wind import phillips_spectrum, synthesize_height

    w = scene.wind
    ky, kx = grid.wavenumbers()
    with jax.enable_x64(True):
        f = phillips_spectrum(jnp.asarray(kx, jnp.float64), jnp.asarray(ky, jnp.float64), scene.water, w.speed,
                              math.radians(w.direction), w.amplitude)
        f = jnp.broadcast_to(f, (grid.n, grid.n))
        eta_c = synthesize_height(f, grid, jax.random.PRNGKey(w.seed))
        out = np.fft.fft2(np.asarray(eta_c, np.complex128))
    out.setflags(write=False)
    return out


def hull_dft(ship, grid, spec) -> np.ndarray:
    """DFT (sum over samples) of the ship's footprint at t = 0 on ``grid``."""
    x, y = (np.asarray(a, np.float64) for a in grid.mesh())
    a = math.radians(spec.heading)
    c, s = math.cos(a), math.sin(a)
    u = c * (x - spec.x) + s * (y - spec.y)
    v = -s * (x - spec.x) + c * (y - spec.y)
    f = np.exp(-0.5 * ((u / (spec.length / 4)) ** 2 + (v / (spec.width / 4)) ** 2))
    return np.fft.fft2(f)


def evaluated_frames(frames: int) -> np.ndarray:
    """Frame numbers (1…F) at which errors are evaluated: all of short scenes; else the last
    16 (where dispersion errors are largest and every Hermite phase occurs) and 8 spread.

    Parameters
    ----------
    frames : int
        F, the scene's frames.

    Returns
    -------
    numpy.ndarray of int
    """
    if frames <= MAX_EVALUATED_FRAMES:
        return np.arange(1, frames + 1)
    last = np.arange(frames - 15, frames + 1)
    spread = np.unique(np.linspace(1, frames - 16, MAX_EVALUATED_FRAMES - 16).round().astype(int))
    return np.concatenate([spread, last])


def mode_heights(spec: SceneSpectrum, omega, m, t, wind: bool = False, impulse_dt=None):
    """C_k(t) on the support for times t (shape (T, 1)): the deterministic sources (stones and
    ships), or with ``wind`` the wind sea alone. ``impulse_dt``: the ships make their waves by
    impulses with this step (s), and t are step times (:func:`impulse_factor`).

    Parameters
    ----------
    spec : SceneSpectrum
    omega, m : numpy.ndarray (M,)
        ω (rad/s) and K/ω (s/m) of the support's modes.
    t : numpy.ndarray (T, 1)
        Times, s.
    wind : bool
        The wind sea instead of the deterministic sources.
    impulse_dt : float, optional
        The ships' impulse step, s.

    Returns
    -------
    numpy.ndarray (T, M)
        Complex heights, m.
    """
    phase = np.exp(-1j * omega[None, :] * t)
    if wind:
        return spec.W[None, :] * phase
    out = spec.A[None, :] * phase
    for B, (ux, uy) in spec.ships:
        b = spec.kx * ux + spec.ky * uy
        a = omega - b
        if impulse_dt is None:
            out = out + (m * B)[None, :] * phase * t * _phi1(1j * a[None, :] * t)
        else:
            out = out + (m * B)[None, :] * phase * impulse_factor(a, b, t, impulse_dt, omega)
    return out


def impulse_factor(a, b, t, dt, omega):
    r"""The ships' impulse method against the exact source, per mode: where the kernels give
    t·φ₁(iat), the hull's change f̂(t_{j+1}) − f̂(t_j) added at each step's end gives, after
    N = t/Δt steps,

    .. math:: Δt\,φ₁(−ibΔt)\,e^{iωΔt}\sum_{j<N} e^{iajΔt}
              = Δt\,φ₁(−ibΔt)\,e^{iωΔt}\,e^{ia(N−1)Δt/2}\,\frac{\sin(NaΔt/2)}{\sin(aΔt/2)}

    (b = k·U, a = ω − b; the same limit t·φ₁(iat) as Δt → 0)."""
    steps = np.rint(t / dt)
    theta = 0.5 * a[None, :] * dt
    sin = np.sin(theta)
    tiny = np.abs(sin) < 1e-12
    dirichlet = np.where(tiny, steps * np.cos(steps * theta) / np.where(tiny, np.cos(theta), 1.0),
                         np.sin(steps * theta) / np.where(tiny, 1.0, sin))
    return (dt * _phi1(-1j * b[None, :] * dt) * np.exp(1j * omega[None, :] * dt)
            * np.exp(1j * theta * (steps - 1)) * dirichlet)


def blended_mode_heights(spec, omega, m, t_frames, dt, wind: bool = False, impulses: bool = False):
    """The simulation's frames: C at the steps around each frame, Hermite-blended with η̇ = −iωC
    (``impulses``: ships by the impulse method at step Δt).

    Parameters
    ----------
    spec : SceneSpectrum
    omega, m : numpy.ndarray (M,)
        ω (rad/s) and K/ω (s/m) of the support's modes.
    t_frames : numpy.ndarray
        The frames' times, s.
    dt : float
        The simulation's step, s.
    wind : bool
        The wind sea instead of the deterministic sources.
    impulses : bool
        Ships by the impulse method.

    Returns
    -------
    numpy.ndarray (T, M)
        Complex heights at the frames, m.
    """
    from wavephys.physics.interpolation import hermite_weights

    step = np.floor(t_frames / dt + 1e-9)
    s = t_frames / dt - step
    t0, t1 = step * dt, (step + 1) * dt
    imp = dt if impulses else None
    c0, c1 = mode_heights(spec, omega, m, t0, wind, imp), mode_heights(spec, omega, m, t1, wind, imp)
    h00, h01, h10, h11 = (np.asarray(h, np.float64) for h in hermite_weights(np.clip(s, 0.0, 1.0)))
    d0, d1 = -1j * omega[None, :] * c0, -1j * omega[None, :] * c1
    blend = h00 * c0 + h01 * c1 + dt * (h10 * d0 + h11 * d1)
    on_step = s < 1e-9
    return np.where(on_step, c0, blend)


CHOPPINESS = 1.0
"""λ of the ``choppy`` surface model: the linear (Airy) particle orbit, as Gerstner's Q = 1."""


NOISE_OCTAVES, NOISE_HURST = 2, 1.0
"""The ``noise`` surface model's fBm: two octaves (Schneider & Westermann), H = 1 (a k⁻⁴ tail)."""


def gerstner_modes(scene: Scene, count: int) -> np.ndarray:
    """Indices into the scene's support (:func:`scene_spectrum`) of the ``count`` strongest modes
    of its wind sea (largest |ĥ_k|; each wavevector one wave) among those the texels resolve
    (both components below the Nyquist wavenumber).

    Parameters
    ----------
    scene : Scene
    count : int
        How many.

    Returns
    -------
    numpy.ndarray of int
    """
    spec = scene_spectrum(scene)
    k_nyq = math.pi / scene.pixel
    held = np.maximum(np.abs(spec.kx), np.abs(spec.ky)) < k_nyq * (1 - 1e-9)  # a wave the texels resolve
    order = np.argsort(-np.where(held, np.abs(spec.W), -1.0), kind="stable")
    return order[:min(count, int(held.sum()))]


def sea_rms(scene: Scene) -> float:
    """RMS height of the scene's wind sea over its square, m (Parseval; constant in time up to
    the interference of opposed modes, taken at its largest).

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    float
        m.
    """
    spec = scene_spectrum(scene)
    a = np.abs(spec.W)
    h = 0.5 * (a + a[spec.mirror])
    return float(np.sqrt(np.sum(h * h))) / spec.n**2


def noise_sea(scene: Scene):
    """The ``noise`` surface model of a wind scene: :class:`wavephys.surfaces.noise.NoiseSea` of
    the sea's RMS amplitude, its first octave at the sea's strongest wavelength (at most a
    quarter of the texel rate, so the finest octave spans ≥ 2 texels), tiling the square.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    wavephys.surfaces.noise.NoiseSea
    """
    from wavephys.surfaces.noise import NoiseSea

    spec = scene_spectrum(scene)
    k_peak = float(spec.k[np.argmax(np.abs(spec.W))])
    from wavephys.surfaces.noise import TABLE_SIZE

    top = min(scene.texels // 4, TABLE_SIZE // 2 ** (NOISE_OCTAVES - 1))  # finest octave ≥ 2 texels, ≤ the table
    cells = max(1, min(round(k_peak * scene.extent / (2 * math.pi)), top))
    return NoiseSea(length=scene.extent, amplitude=max(sea_rms(scene), 1e-12), frequency=cells / scene.extent, octaves=NOISE_OCTAVES,
                    hurst=NOISE_HURST, seed=scene.wind.seed, base_amplitude=0.0)
