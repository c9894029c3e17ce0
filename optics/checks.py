"""Built-in optics validations (rows of ``wavephys validate``), docs/physics.md §2.

Each ``check_*`` returns :class:`wavephys.harness.Check` rows; :data:`CHECKS` lists them by
name (the application's registry, :mod:`wavephys.app.registry`, runs them after the wave
checks). The scenes with known answers are public so that tests and ``python -m bench
optics`` reuse them.
"""

from __future__ import annotations

import math
from importlib import resources

import colour
import jax
import jax.numpy as jnp
import numpy as np

from optics.caustics import converged_floor_irradiance, first_fold_depth, floor_irradiance, focal_depth, random_surface
from optics.light.attenuation import cutoff_distance, pure_water_absorption, transmittance, water_srgb
from optics.light.fresnel import (N_AIR, N_WATER, approximation_errors, normal_reflectance, reflectance,
                                  reflectance_sp)
from wavephys.core.grid import Grid
from wavephys.harness.checks import Check, bound, compare

# the scenes and helpers below the checks (flat_pool, sinusoid_scene, ...) are the checks' own
__all__ = ["CHECKS", "check_fresnel", "check_absorption", "check_caustics", "check_renderer"]


def check_fresnel() -> list[Check]:
    """Exact Fresnel against its landmarks and colour-science; Schlick's errors above and below.

    Returns
    -------
    list of Check
        Eleven rows: R(0) from air against the normal-incidence formula and against 0.0204 (n 1 → 1.333);
        Brewster's angle (53.1°) and R_p there (≤ 1e-10); the critical angle from below (48.6°) and
        R = 1 just past it (total internal reflection); R_s, R_p against colour-science over 0–89°
        (atol 1e-6); Schlick's worst error from above (0.059); Schlick with cos θᵢ from below (its
        failure, −0.97); and Schlick with cos θₜ from below (|worst| ≤ 0.07).
    """
    rows = [compare("Fresnel R(0), air -> water", float(reflectance(1.0)), normal_reflectance(N_AIR, N_WATER), rtol=1e-6),
            compare("Fresnel R(0) = 0.0204 for water (n 1 -> 1.333)", float(reflectance(1.0, 1.0, 1.333)), 0.0204, atol=5e-5)]
    brewster = math.atan(N_WATER / N_AIR)
    rows.append(compare("Brewster angle from air", math.degrees(brewster), 53.1, atol=0.05, unit="deg"))
    rows.append(bound("R_p at Brewster", float(reflectance_sp(math.cos(brewster), N_AIR, N_WATER)[1]), 1e-10))
    crit = math.asin(N_AIR / N_WATER)
    rows.append(compare("critical angle from below", math.degrees(crit), 48.6, atol=0.05, unit="deg"))
    rows.append(compare("R just past the critical angle (TIR)", float(reflectance(math.cos(crit + 1e-3), N_WATER, N_AIR)), 1.0, atol=0.0))
    th = np.linspace(0.0, 89.0, 90)
    tt = np.degrees(np.arcsin(N_AIR / N_WATER * np.sin(np.radians(th))))
    ref = np.real(colour.phenomena.polarised_light_reflection_coefficient(N_AIR, N_WATER, th, tt))
    rs, rp = reflectance_sp(jnp.cos(jnp.radians(jnp.asarray(th, jnp.float32))), N_AIR, N_WATER)
    diff = max(np.max(np.abs(np.asarray(rs) - ref[:, 0])), np.max(np.abs(np.asarray(rp) - ref[:, 1])))
    rows.append(compare("R_s, R_p vs colour-science (max |diff|)", diff, 0.0, atol=1e-6))
    s = approximation_errors("schlick", N_AIR, N_WATER)
    rows.append(compare(f"Schlick worst error from above (at {s['angle']:.1f} deg)", s["worst"], 0.059, atol=0.002))
    c = jnp.asarray(np.cos(np.radians(np.linspace(0, 89.9, 20000))), jnp.float32)
    f0 = normal_reflectance(N_WATER, N_AIR)
    naive = np.asarray(f0 + (1 - f0) * (1 - c) ** 5) - np.asarray(reflectance(c, N_WATER, N_AIR))
    rows.append(compare("Schlick with cos thetai from below: worst error (failure)", naive[np.argmax(np.abs(naive))],
                        -0.97, atol=0.01))
    below = approximation_errors("schlick", N_WATER, N_AIR)
    rows.append(bound("Schlick with cos thetat from below: worst |error|", abs(below["worst"]), 0.07))
    return rows


def plain_numpy_water_srgb(distance: float) -> np.ndarray:
    """Independent path for :func:`optics.attenuation.water_srgb`: the same tables read and
    integrated with plain numpy at 5 nm (CIE 1931 2° at its native 1 nm samples, D65 at
    its native 5 nm samples, water a(λ) linearly interpolated, IEC 61966-2-1 matrix)."""
    with resources.files("optics").joinpath("data/purewater_absorption_wopp_v3.dat").open("rb") as f:
        table = np.loadtxt(f, comments="%")
    wl = np.arange(380.0, 781.0, 5.0)
    a = np.interp(wl, table[:, 0], table[:, 1])
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    xyz_bar = np.array([cmfs[w] for w in wl])
    s = np.array([colour.SDS_ILLUMINANTS["D65"][w] for w in wl])
    m = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])
    rgb = lambda t: m @ (np.sum((s * t)[:, None] * xyz_bar, axis=0) / np.sum(s * xyz_bar[:, 1]))
    return rgb(np.exp(-a * distance)) / rgb(np.ones_like(a))


def check_absorption() -> list[Check]:
    """Beer–Lambert identities, the shipped a(λ), the cut-off distance, spectral sRGB vs plain numpy.

    Returns
    -------
    list of Check
        Eight rows: the shipped pure-water absorption a(550 nm) against 0.0581 1/m (WOPP v3); the
        transmittance of 3 m against e^{−ad}; transmittances of layers multiplying; the cut-off
        distance −ln ε / min a (ε = 1e-3) being positive, m, and the transmittance there being ε;
        and the spectral sRGB of 1, 5 and 10 m of water against the plain-numpy path
        :func:`plain_numpy_water_srgb` (atol 1e-4).

    References
    ----------
    Röttgers, R., Doerffer, R., McKee, D. & Schönfeld, W. (2011/2016). Pure water spectral absorption,
    scattering, and real part of refractive index model (WOPP).
    """
    a = float(pure_water_absorption(550.0))
    rows = [compare("pure water a(550 nm) (WOPP v3)", a, 0.0581, rtol=1e-9, unit="1/m"),
            compare("Beer-Lambert e^{-ad}, 3 m at 550 nm", float(transmittance(3.0, a)), math.exp(-3 * a), rtol=1e-6),
            compare("layers multiply: T(1 m)*T(2 m) / T(3 m)",
                    float(transmittance(1.0, a) * transmittance(2.0, a) / transmittance(3.0, a)), 1.0, rtol=1e-6)]
    d_max = cutoff_distance(1e-3, pure_water_absorption(np.arange(380.0, 781.0, 2.0)))
    rows.append(bound("cut-off distance -ln eps / min a (eps = 1e-3) is positive", d_max, 0.0, relation=">=", unit="m"))
    rows.append(compare("transmittance at the cut-off distance", float(transmittance(d_max, pure_water_absorption(np.arange(380.0, 781.0, 2.0)).min())),
                        1e-3, rtol=1e-5))
    for d in (1.0, 5.0, 10.0):
        diff = float(np.max(np.abs(water_srgb(d, gamut="none") - plain_numpy_water_srgb(d))))
        rows.append(compare(f"spectral sRGB of {d:g} m: colour-science vs plain numpy", diff, 0.0, atol=1e-4))
    return rows


def sinusoid_scene(n: int = 128, diagonal: bool = False):
    """η = a cos(k·(x − x_c)) on a 1 m periodic grid: a = 2 mm, |k| = 4π (or 4π√2 at 45°),
    with a crest through the first sample x_c (so that the floor map has a texel at the focus)."""
    grid = Grid(n, 1.0)
    x, y = grid.mesh()
    x, y = x - grid.origin, y - grid.origin
    if diagonal:
        return grid, 0.002 * jnp.cos(4 * math.pi * (x + y)), 4 * math.pi * math.sqrt(2)
    return grid, 0.002 * jnp.cos(4 * math.pi * x), 4 * math.pi


def check_caustics() -> list[Check]:
    """Flux conservation, flat water, and the sinusoid's peak, trough and focal depth (0° and 45°).

    Returns
    -------
    list of Check
        The mean floor irradiance E/E0 under a rough surface and an oblique sun against 1 (flux
        conserved); the spread under flat water against 0; for the sinusoid of :func:`sinusoid_scene`
        at 0° and 45°, the peak (2) and trough (2/3) of E/E0 at half the focal depth by the beam and
        the reference methods, and the first fold depth against the focal depth, m (rtol 0.01); then,
        on a generated 2-D sea, the converged reference's bound, the beam and jacobian methods against
        it, the jacobian's refusal, hand-over to the beam and folded windows past the first fold, and the GPU drawing
        against the reference (or a failing "GPU drawing available" row without OpenGL).
    """
    rows = []
    grid = Grid(64, 2.0)
    x, y = grid.mesh()
    rough = 0.01 * jnp.cos(3 * math.pi * x) * jnp.sin(2 * math.pi * y) + 0.005 * jnp.sin(5 * math.pi * (x + y))
    e = floor_irradiance(rough, grid, 1.0, sun=(0.3, 0.2, 1.0), fresnel=False)
    rows.append(compare("caustics flux conserved (beam, oblique sun, mean E/E0)", float(jnp.mean(e)), 1.0, atol=1e-5))
    flat = floor_irradiance(jnp.zeros((64, 64)), grid, 1.0, sun=(0.3, 0.2, 1.0))
    rows.append(compare("flat water: floor irradiance spread (max - min)", float(flat.max() - flat.min()), 0.0, atol=1e-5))
    for diagonal in (False, True):
        g, eta, k = sinusoid_scene(diagonal=diagonal)
        zf = focal_depth(0.002, k)
        label = "45 deg" if diagonal else "0 deg"
        for method, kw in (("beam", {}), ("reference", {})):
            e = floor_irradiance(eta, g, zf / 2, method=method, fresnel=False, **kw)
            rows.append(compare(f"sinusoid {label}, z_f/2, {method}: peak E/E0", float(e.max()), 2.0, rtol=0.01))
            rows.append(compare(f"sinusoid {label}, z_f/2, {method}: trough E/E0", float(e.min()), 2 / 3, rtol=0.01))
        rows.append(compare(f"sinusoid {label}: focal depth (first fold of the beam mesh)", first_fold_depth(eta, g), zf,
                            rtol=0.01, unit="m"))
    return rows + _generated_surface_rows()


def _generated_surface_rows() -> list[Check]:
    """A random 2-D sea (a band of directions, steepest slope 0.1, sun at 55 deg), floor at 0.6
    of the first fold: the default beam, the jacobian and the GPU drawing against the converged
    reference; past the fold (1.5 ×) the jacobian's refusal and hand-over, and at 1.1 × its
    folded windows against the beam's own error."""
    from optics.gpu import RendererUnavailable

    grid = Grid(64, 2.0)
    eta = random_surface(grid, "band", 0.1, 7)
    sun = (0.4 * math.cos(0.9), 0.4 * math.sin(0.9), math.sin(math.radians(55)))
    depth = 0.6 * first_fold_depth(eta, grid, sun)
    ref = converged_floor_irradiance(eta, grid, depth, sun, tolerance=2e-3)
    peak = float(ref.irradiance.max())
    beam = np.asarray(floor_irradiance(eta, grid, depth, sun), np.float64)
    jac = np.asarray(floor_irradiance(eta, grid, depth, sun, method="jacobian", fold="raise"), np.float64)
    rows = [bound("converged reference on a generated 2-D sea: bound (max |E_2r - E_r| / peak)", ref.bound, 2e-3),
            bound("default beam (refine 3) vs the reference, generated 2-D sea: max |error| / peak",
                  float(np.max(np.abs(beam - ref.irradiance))) / peak, 0.01),
            bound("jacobian gather vs the reference, same sea (0.6 of the first fold): max |error| / peak",
                  float(np.max(np.abs(jac - ref.irradiance))) / peak, 0.01)]
    import warnings

    from optics.caustics import CausticsFold

    deep = 1.5 * first_fold_depth(eta, grid, sun)
    try:
        floor_irradiance(eta, grid, deep, sun, method="jacobian", fold="raise")
        refused = 0.0
    except CausticsFold:
        refused = 1.0
    rows.append(bound("jacobian at 1.5 x the first fold: refused by name (1 = CausticsFold)", refused, 1.0,
                      relation=">="))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        handed = np.asarray(floor_irradiance(eta, grid, deep, sun, method="jacobian", fold="beam"), np.float64)
    rows.append(bound("jacobian at 1.5 x the first fold, fold='beam': max |E - beam| (the beam answers)",
                      float(np.max(np.abs(handed - np.asarray(floor_irradiance(eta, grid, deep, sun))))), 0.0))
    past = 1.1 * first_fold_depth(eta, grid, sun)
    ref_past = converged_floor_irradiance(eta, grid, past, sun, tolerance=2e-3)
    peak_past = float(ref_past.irradiance.max())
    windows = np.asarray(floor_irradiance(eta, grid, past, sun, method="jacobian"), np.float64)
    beam_past = np.asarray(floor_irradiance(eta, grid, past, sun), np.float64)
    rows.append(bound("jacobian at 1.1 x the first fold (the beam on its folded windows, or everywhere past half "
                      "the floor): max |error| / peak, minus the default beam's",
                      float(np.max(np.abs(windows - ref_past.irradiance)) - np.max(np.abs(beam_past - ref_past.irradiance)))
                      / peak_past, 0.005))
    try:
        gl = floor_irradiance(eta, grid, depth, sun, method="gl", refine=3, supersample=8)
        rows.append(bound("GPU drawing (refine 3, supersample 8) vs the reference, same sea: max |error| / peak",
                          float(np.max(np.abs(gl - ref.irradiance))) / peak, 0.02))
    except RendererUnavailable as exc:
        rows.append(bound("GPU drawing available", 0.0, 1.0, relation=">=", note=str(exc)[:120]))
    return rows


def flat_pool(depth: float = 1.5, **kw):
    """Still water over a flat floor ``depth`` m down, seen straight down, sun overhead, uniform sky."""
    from optics.rendering.scene import Scene, look_at

    n = 32
    args = dict(camera=look_at((0.0, 0.0, 3.0), (0.0, 0.0, -depth), 20.0), sun=(0.0, 0.0, 1.0),
                sky_zenith=(0.3, 0.5, 0.9), sky_horizon=(0.3, 0.5, 0.9), sun_glow=0.0,
                albedo=np.full((n, n, 3), (0.8, 0.7, 0.5)), ambient=(0.1, 0.1, 0.1), sun_color=(1.0, 1.0, 1.0))
    args.update(kw)
    return Scene(np.full((n, n), -depth), 0.0, 8.0, **args)


def flat_pool_colour(scene, depth: float = 1.5) -> np.ndarray:
    """Analytic colour at the centre of :func:`flat_pool`: R0·sky + (1 − R0)·ground·T, the
    ground lit by ambient·T + sun·(1 − R0)·T, T = e^{−a·depth} (R0: exact normal-incidence Fresnel)."""
    r0 = normal_reflectance(scene.n_air, scene.n_water)
    t = np.exp(-depth * np.asarray(scene.absorption))
    alb = np.asarray(scene.albedo)[0, 0]
    ground = alb * (scene.ambient * t + scene.sun_color * (1 - r0) * t)
    return r0 * scene.sky_zenith + (1 - r0) * ground * t


def underwater_view(angle_deg: float):
    """Camera 0.75 m under still water (floor at 1.5 m, 40 m wide) looking up ``angle_deg`` from
    the vertical, under a pure red sky over a green-blue floor, clear water."""
    from optics.rendering.scene import Camera, Effects, Scene

    n, a = 32, math.radians(angle_deg)
    up = (1.0, 0.0, 0.0) if angle_deg == 0 else (0.0, 0.0, 1.0)
    cam = Camera((0.0, 0.0, -0.75), (math.sin(a), 0.0, -0.75 + math.cos(a)), up, 2.0)
    return Scene(np.full((n, n), -1.5), 0.0, 40.0, camera=cam, sky_zenith=(2.0, 0.0, 0.0),
                 sky_horizon=(2.0, 0.0, 0.0), sun_glow=0.0, albedo=np.full((n, n, 3), (0.0, 0.6, 0.6)),
                 effects=Effects(absorption=False))


def check_renderer() -> list[Check]:
    """The GPU renderer and the CPU reference against the analytic flat pool and TIR; 16-bit heights.

    Returns
    -------
    list of Check
        The CPU reference's centre colour of :func:`flat_pool` against :func:`flat_pool_colour`
        (max relative error, atol 1e-5) and the red of the sky seen from below 5° past the critical
        angle (:func:`underwater_view`; ≤ 0, total internal reflection hides the sky); the same two
        for the GPU renderer (or a failing "GPU renderer available" row without OpenGL); and the RMS
        curvature error of 16-bit heights of a swell of 16 texels per wavelength (≤ 1e-3).
    """
    from optics.rendering.reference import trace
    from optics.rendering.renderer import Renderer, RendererUnavailable
    from optics.rendering.textures import height_precision

    w, h = 160, 120
    pool = flat_pool()
    expected = flat_pool_colour(pool)
    ref = trace(pool, w, h)[h // 2, w // 2]
    critical = math.degrees(math.asin(N_AIR / N_WATER))
    tir = underwater_view(critical + 5.0)
    rows = [compare("flat pool, normal view: reference vs analytic colour (max rel.)",
                    float(np.max(np.abs(ref - expected) / expected)), 0.0, atol=1e-5),
            bound(f"from below at {critical + 5:.1f} deg (past critical): sky red seen, reference",
                  float(trace(tir, w, h)[h // 2, w // 2, 0]), 0.0)]
    try:
        with Renderer(w, h) as renderer:
            gpu = renderer.render(pool)[h // 2, w // 2]
            rows += [compare("flat pool, normal view: GPU vs analytic colour (max rel.)",
                             float(np.max(np.abs(gpu - expected) / expected)), 0.0, atol=1e-5),
                     bound("past critical: sky red seen, GPU", float(renderer.render(tir)[h // 2, w // 2, 0]), 0.0)]
    except RendererUnavailable as exc:
        rows.append(bound("GPU renderer available", 0.0, 1.0, relation=">=", note=str(exc)[:120]))
    grid = Grid(256, 64.0)
    x, y = (np.asarray(a) for a in grid.mesh())
    swell = 0.05 * np.cos(2 * np.pi * 16 * x / 64) + 0.03 * np.sin(2 * np.pi * 16 * (x + y) / 64)
    rows.append(bound("16-bit heights, swell of 16 texels per wavelength: curvature error (RMS)",
                      height_precision(swell, grid, 16, norm="rms")["curvature"], 1e-3))
    return rows


CHECKS = {"fresnel": check_fresnel, "absorption": check_absorption, "caustics": check_caustics,
          "renderer": check_renderer}
"""Optics validations, in the order ``wavephys validate`` runs them (after the wave ones)."""
