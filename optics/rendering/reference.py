"""CPU reference tracer of the two-height-field water model (numpy, float64).

The same model as the GPU renderer (:mod:`optics.rendering.renderer`), written in numpy
float64 from the library's own primitives (texture sampling of
:func:`optics.rendering.scene.texture_sample`, :mod:`optics.light.directions`,
:func:`optics.light.fresnel.reflectance_exact`), so that the shader — which shares no
code with it — can be checked pixel by pixel (PSNR). Per pixel (docs/physics.md §2.5):

1. the view ray is clipped to the volume's bounding box and marched in ``steps`` equal
   steps; the first sample inside the ground or across the water surface starts
   ``refine`` bisection steps (joint search of both height fields, then refinement);
2. a ground hit is shaded: albedo × (ambient + sun · n·l); under water the sun arrives
   refracted through a flat surface, weighted by its Fresnel transmittance, the
   caustics map and Beer–Lambert along its path, and the ambient light by Beer–Lambert
   over the depth;
3. a water hit splits into a reflected ray (traced to the ground, else the environment)
   and a refracted ray (traced to the ground under water, with Beer–Lambert along it,
   else the deep colour), combined by the exact Fresnel reflectance R:
   R·reflected + (1 − R)·refracted. One level: secondary rays see only the ground.
4. From under the water the surface is met from below: past the critical angle R = 1
   (total internal reflection); the refracted ray goes to the sky or the shore.

Height fields are sampled bilinearly with texel centres at −L/2 + (i + ½)·L/n and
clamped edges; normals are central differences of that bilinear surface one texel apart.

With ``scene.surroundings`` "extend" or "tile" the march runs over the slab between the
lowest and highest surface, out to ``FAR_TILES`` scene sides from the eye, with steps
growing quadratically from the eye; tiled water wraps and fades to its mean level between
``NEAR_TILES`` and ``FAR_TILES`` sides (distance filtering); a primary ray that reaches the
far distance going down meets flat water and ground planes at the levels where it crosses the
water's level (:func:`far_field`).
"""

from __future__ import annotations

import math

import numpy as np

from optics.light.directions import reflect, refract
from optics.light.fresnel import normal_reflectance, reflectance
from optics.light.sky import preetham_sky
from optics.rendering.filtering import (VARIANCE_FLOOR, covariance_given_back, covariance_of, facing_normal,
                                       fade_moments, footprint, sigma_slopes,
                                       slope_moments)
from optics.rendering.scene import FAR_TILES, NEAR_TILES, Camera, Scene, _texture_sample, sun_in_water, texture_sample
from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar
from wavephys.core.sampling import bilinear, texel_coordinates

# sample, environment, march, shade_ground: the tracer's own steps
__all__ = ["trace", "psnr", "psnr_against_reference", "ray_directions", "effect_change"]

GROUND, WATER = 0, 1
MAX_PIXELS = 16384
"""Largest image side the CPU reference draws, pixels."""


def sample(field, length: float, xy):
    """Bilinear sample of a (ny, nx[, c]) texture over [−L/2, L/2]² at points xy (..., 2), clamped edges."""
    return texture_sample(np.asarray(field), length, xy[..., 0], xy[..., 1])


def _sample(field, length: float, xy):
    """:func:`sample` without its checks, for the march's inner loop (the scene's textures were checked when it
    was made, and the points are the tracer's own): a trace samples them thousands of times, and the checks
    (each texture finite, every call) took 40 % of a sample's time (0.16 ms against 0.09 ms for 1500 points on
    a 256² texture)."""
    return _texture_sample(np.asarray(field, np.float64), length, xy[..., 0], xy[..., 1])


def water_level(scene: Scene, xy):
    """Water height (m) at points xy (..., 2): clamped, or tiled and faded with distance from the eye."""
    return _surface_sample(scene, scene.water, xy)


def _surface_sample(scene: Scene, field, xy):
    """A field on the water surface (heights, foam) at xy: clamped, or tiled; beyond the
    square (surroundings) it fades to its mean with distance from the eye."""
    if scene.surroundings == "none":
        return _sample(field, scene.length, xy)
    w = np.asarray(field, np.float64)
    if scene.surroundings == "extend":
        h = _sample(w, scene.length, xy)
    else:
        ny, nx = w.shape
        u = np.mod((xy[..., 0] / scene.length + 0.5) * nx - 0.5, nx)
        v = np.mod((xy[..., 1] / scene.length + 0.5) * ny - 0.5, ny)
        wrapped = np.concatenate([w, w[:1]], axis=0)
        wrapped = np.concatenate([wrapped, wrapped[:, :1]], axis=1)  # texel n = texel 0
        h = bilinear(wrapped, u, v, "clamp")
    mean = float(w.mean())
    r = np.hypot(xy[..., 0] - scene.camera.eye[0], xy[..., 1] - scene.camera.eye[1]) / scene.length
    return mean + (h - mean) * (1 - _smoothstep(NEAR_TILES, FAR_TILES, r))


def _smoothstep(e0, e1, x):
    t = np.clip((x - e0) / (e1 - e0), 0.0, 1.0)
    return t * t * (3 - 2 * t)


def _water_slope(scene: Scene, xy):
    """Slopes (gx, gy) (..., 2) of the water as drawn (clamped or tiled and faded), central differences one
    texel apart."""
    ny, nx = scene.water.shape
    hx, hy = scene.length / nx, scene.length / ny
    ex, ey = np.array([hx, 0.0]), np.array([0.0, hy])
    gx = (water_level(scene, xy + ex) - water_level(scene, xy - ex)) / (2 * hx)
    gy = (water_level(scene, xy + ey) - water_level(scene, xy - ey)) / (2 * hy)
    return np.stack([gx, gy], axis=-1)


def _unit_normal(g):
    """Unit normals (..., 3) of slopes g (..., 2)."""
    n = np.concatenate([-g, np.ones(g.shape[:-1] + (1,))], axis=-1)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def _water_normal(scene: Scene, xy):
    """Unit normal of the water as drawn (clamped or tiled and faded), central differences one texel apart."""
    return _unit_normal(_water_slope(scene, xy))


def _fade(scene: Scene, xy):
    """The waves' weight at xy: 1, fading to 0 between NEAR_TILES and FAR_TILES sides from the eye."""
    if scene.surroundings == "none":
        return np.ones(np.shape(xy)[:-1])
    r = np.hypot(xy[..., 0] - scene.camera.eye[0], xy[..., 1] - scene.camera.eye[1]) / scene.length
    return 1 - _smoothstep(NEAR_TILES, FAR_TILES, r)


class _Slopes:
    """The scene's slope pyramid and whole-square covariance (the distance filtering's data)."""

    def __init__(self, scene: Scene):
        wrap = scene.surroundings == "tile"
        self.levels = slope_moments(scene.water, scene.length, wrap)
        self.cov_all = covariance_given_back(scene.water, scene.length, scene.surroundings)
        self.mode = "wrap" if wrap else "clamp"
        self.texel = scene.length / min(scene.water.shape)

    def exact(self, scene, xy):
        """The point's own slope, with the variance the fade removed given back."""
        m = _water_slope(scene, xy)
        f = _fade(scene, xy)[..., None]
        second = np.stack([m[..., 0] ** 2, m[..., 1] ** 2, m[..., 0] * m[..., 1]], axis=-1)
        return m, second + (1 - f * f) * self.cov_all

    def level(self, scene, k, xy):
        """Faded moments of pyramid level k ≥ 1 at xy."""
        field = self.levels[k].astype(np.float64)
        ny, nx = field.shape[:2]
        v = bilinear(field, texel_coordinates(xy[..., 0], scene.length, nx),
                     texel_coordinates(xy[..., 1], scene.length, ny), self.mode)
        return fade_moments(v[..., :2], v[..., 2:], _fade(scene, xy), self.cov_all)

    def tap(self, scene, xy, lod):
        """Trilinear moments at xy (n, 2) and levels lod (n,); below level 1 the exact slope."""
        top = len(self.levels) - 1
        m, s = self.exact(scene, xy)
        if top < 1:
            return m, s
        lod = np.minimum(np.maximum(lod, 0.0), top)
        k = np.minimum(np.floor(lod).astype(np.int64), top - 1)
        a = np.where(lod >= top, 1.0, lod - k)[:, None]
        out_m, out_s = np.empty_like(m), np.empty_like(s)
        for level in np.unique(k):
            i = np.nonzero(k == level)[0]
            m0, s0 = (m[i], s[i]) if level == 0 else self.level(scene, level, xy[i])
            m1, s1 = self.level(scene, level + 1, xy[i])
            out_m[i] = m0 + (m1 - m0) * a[i]
            out_s[i] = s0 + (s1 - s0) * a[i]
        exact = lod <= 0
        out_m[exact], out_s[exact] = m[exact], s[exact]
        return out_m, out_s

    def filtered(self, scene, p, d, t, pixel_angle):
        """Mean slope (n, 2) and covariance (n, 3) over the footprints of pixels hitting p at distance t."""
        lod, along, taps = footprint(t, d, pixel_angle, self.texel)
        exact = (taps == 1) & (lod <= 0)  # the exact slope: its covariance is the faded variance alone
        h = np.hypot(d[:, 0], d[:, 1])
        axis = np.where(h[:, None] > 0, d[:, :2] / np.where(h > 0, h, 1.0)[:, None], 0.0)
        m, s = np.zeros((len(p), 2)), np.zeros((len(p), 3))
        for i in range(int(taps.max(initial=1))):
            live = np.nonzero(taps > i)[0]
            offset = ((i + 0.5) / taps[live] - 0.5) * along[live]
            mi, si = self.tap(scene, p[live, :2] + offset[:, None] * axis[live], lod[live])
            m[live] += mi
            s[live] += si
        m /= taps[:, None]
        s /= taps[:, None]
        cov = covariance_of(np.concatenate([m, s], axis=-1))
        f = _fade(scene, p[exact, :2])
        cov[exact] = (1 - f * f)[:, None] * self.cov_all
        return m, cov


def _over_slopes(scene, p, d, m, cov, trans, traced, steps, refine):
    """R·reflected + (1 − R)·trans averaged over the slopes at four sigma points, weighted by each facet's
    area seen from the eye; returns (colour (n, 3), whether any facet faces the eye (n,))."""
    g = sigma_slopes(m, cov)
    total, weight = np.zeros(p.shape), np.zeros(len(p))
    for gi in g:
        n = _unit_normal(gi)
        cos_i = -np.sum(d * n, axis=-1)
        w = np.maximum(cos_i, 0.0) / n[:, 2]
        live = np.nonzero(w > 0)[0]
        if live.size == 0:
            continue
        r = _reflectance(scene, cos_i[live], scene.n_air, scene.n_water)[:, None]
        rdir = reflect(d[live], n[live])
        refl = (_secondary(scene, p[live], rdir, "air", steps, refine) if traced
                else environment(scene, rdir))
        total[live] += w[live, None] * (r * refl + (1 - r) * trans[live])
        weight[live] += w[live]
    seen = weight > 0
    return np.where(seen[:, None], total / np.where(seen, weight, 1.0)[:, None], 0.0), seen


def _normal(field, length, xy):
    """Unit normal of the bilinear height field by central differences one texel apart."""
    ny, nx = field.shape
    hx, hy = length / nx, length / ny
    ex, ey = np.array([hx, 0.0]), np.array([0.0, hy])
    gx = (_sample(field, length, xy + ex) - _sample(field, length, xy - ex)) / (2 * hx)
    gy = (_sample(field, length, xy + ey) - _sample(field, length, xy - ey)) / (2 * hy)
    n = np.stack([-gx, -gy, np.ones_like(gx)], axis=-1)
    return n / np.linalg.norm(n, axis=-1, keepdims=True)


def _reflectance(scene: Scene, cos_i, n1, n2):
    """Fresnel R by the scene's form (effects.fresnel) or the normal-incidence value, 1 under TIR
    either way."""
    c = np.clip(np.asarray(cos_i, np.float64), 0.0, 1.0)
    if scene.effects.fresnel:
        return np.asarray(reflectance(c, n1, n2, method=scene.effects.fresnel_form), np.float64)
    sin_t2 = (n1 / n2) ** 2 * (1 - c * c)
    return np.where(sin_t2 >= 1, 1.0, normal_reflectance(n1, n2))


def environment(scene: Scene, d):
    """Radiance of the sky (or environment map) in directions d (..., 3)."""
    if scene.environment is not None:
        env = scene.environment.astype(np.float64)
        h, w = env.shape[:2]
        u = (np.arctan2(d[..., 1], d[..., 0]) + math.pi) / (2 * math.pi) * w - 0.5
        v = np.arccos(np.clip(d[..., 2], -1, 1)) / math.pi * h - 0.5
        # azimuth wraps, elevation clamps: sample a copy with the first column repeated past the last
        wrapped = np.concatenate([env, env[:, :1]], axis=1)
        return bilinear(wrapped, np.mod(u, w), v, "clamp")
    z = d[..., 2:3]
    if scene.sky == "preetham":
        sky = preetham_sky(d, scene.sun, scene.turbidity, scene.sky_brightness)
    else:
        sky = scene.sky_horizon + (scene.sky_zenith - scene.sky_horizon) * np.sqrt(np.maximum(z, 0.0))
        sky = np.where(z < 0, 0.5 * scene.sky_horizon, sky)
    glow = np.exp(64.0 * (np.sum(d * scene.sun, axis=-1, keepdims=True) - 1.0))
    return sky + scene.sun_glow * glow * scene.sun_color


def _box(scene: Scene, o, d):
    """Entry and exit distances of rays (o, d) through the volume's box."""
    half = scene.length / 2
    zlo, zhi = scene.bounds()
    lo = np.array([-half, -half, zlo])
    hi = np.array([half, half, zhi])
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / np.where(d == 0, 1e-30, d)
        a, b = (lo - o) * inv, (hi - o) * inv
    t0 = np.max(np.minimum(a, b), axis=-1)
    t1 = np.min(np.maximum(a, b), axis=-1)
    return np.maximum(t0, 0.0), t1


def _slab(scene: Scene, o, d):
    """Entry and exit distances of rays through the slab between the lowest and highest surface,
    out to FAR_TILES scene sides from the eye (horizontally)."""
    zlo, zhi = scene.bounds()
    with np.errstate(divide="ignore", invalid="ignore"):
        dz = np.where(d[:, 2] == 0, 1e-30, d[:, 2])
        a, b = (zlo - o[:, 2]) / dz, (zhi - o[:, 2]) / dz
        horizontal = np.hypot(d[:, 0], d[:, 1])
        far = np.where(horizontal > 0, FAR_TILES * scene.length / np.maximum(horizontal, 1e-30), np.inf)
    t0 = np.maximum(np.minimum(a, b), 0.0)
    t1 = np.minimum(np.maximum(a, b), far)
    return t0, t1


def far_field(scene: Scene, o, d):
    """Colour of primary rays (o, d) (n, 3) that left the marched region: beyond FAR_TILES sides
    the world is flat water and ground planes at the levels where the ray meets the water's level (that
    under its last marched point): land where the ground there is above the water; rays going up, or not
    reaching it, see the sky."""
    out = environment(scene, d)
    _, t1 = _slab(scene, o, d)
    zlo, zhi = scene.bounds()
    horizontal = np.hypot(d[:, 0], d[:, 1])
    with np.errstate(divide="ignore", invalid="ignore"):
        t_far = FAR_TILES * scene.length / np.maximum(horizontal, 1e-30)
    p1 = o + t_far[:, None] * d
    go = np.nonzero((d[:, 2] < 0) & (horizontal > 0) & (p1[:, 2] >= zlo))[0]
    if go.size == 0:
        return out
    dd = d[go]
    # land or water is decided where the ray meets the water's level (a straight shore extended to the horizon
    # converges there, as it does); decided at the far point itself, a fixed distance from the eye, a shore
    # crossing it drew a vertical edge down the frame (the beach scene showed one)
    with np.errstate(divide="ignore", invalid="ignore"):
        t_level = (water_level(scene, p1[go][:, :2]) - o[go][:, 2]) / dd[:, 2]
    q = o[go] + np.maximum(t_level, t_far[go])[:, None] * dd
    level_w = water_level(scene, q[:, :2])
    level_g = sample(scene.ground, scene.length, q[:, :2])
    albedo = scene.albedo if scene.albedo is not None else scene.default_albedo
    alb = sample(albedo, scene.length, q[:, :2])
    up = np.array([0.0, 0.0, 1.0])
    land = level_g >= level_w
    dry = alb * (scene.ambient + scene.sun_color * max(float(scene.sun[2]), 0.0))
    cos_i = np.clip(-dd[:, 2], 0.0, 1.0)
    r = _reflectance(scene, cos_i, scene.n_air, scene.n_water)[:, None]
    refl = environment(scene, reflect(dd, np.broadcast_to(up, dd.shape)))
    tdir = refract(dd, np.broadcast_to(up, dd.shape), scene.n_air, scene.n_water)[0] if scene.effects.refraction else dd
    depth = np.maximum(level_w - level_g, 0.0)
    lw = sun_in_water(scene.sun, scene.n_air, scene.n_water)
    sun_t = 1.0 - float(_reflectance(scene, np.array(scene.sun[2]), scene.n_air, scene.n_water))
    wet = alb * (scene.ambient * _transmittance(scene, depth)
                 + scene.sun_color * (sun_t * max(float(lw[2]), 0.0)) * _transmittance(scene, depth / lw[2]))
    trans = wet * _transmittance(scene, depth / np.maximum(-tdir[:, 2], 1e-6))
    water = r * refl + (1 - r) * trans
    if scene.effects.filtering:  # the waves' roughness, averaged (optics.rendering.filtering)
        cov = covariance_given_back(scene.water, scene.length, scene.surroundings)
        if cov[0] + cov[1] > VARIANCE_FLOOR:
            rough, seen = _over_slopes(scene, q, dd, np.zeros((len(dd), 2)), np.broadcast_to(cov, (len(dd), 3)),
                                       trans, False, 1, 0)
            water = np.where(seen[:, None], rough, water)
    out[go] = np.where(land[:, None], dry, water)
    return out


def _gap(scene: Scene, p, mode):
    """> 0 while the ray is in its medium: mode 0 air (ground, water from above), 1 water
    (ground, surface from below), 2 ground only. Returns (gap, ground term, water term)."""
    g = p[..., 2] - _sample(scene.ground, scene.length, p[..., :2])
    if mode == 2:
        return g, g, np.full_like(g, np.inf)
    w = water_level(scene, p[..., :2]) - p[..., 2]
    wt = -w if mode == 0 else w
    return np.minimum(g, wt), g, wt


def march(scene: Scene, o, d, mode: int, steps: int, refine: int):
    """First hit of rays (o, d) (n, 3): returns (t, hit mask, which surface: 0 ground, 1 water)."""
    wide = scene.surroundings != "none"
    t0, t1 = _slab(scene, o, d) if wide else _box(scene, o, d)
    n = o.shape[0]
    t_hit = np.full(n, np.inf)
    which = np.zeros(n, np.int64)
    live = np.nonzero(t1 > t0)[0]
    span = t1 - t0
    lo = np.zeros(n)
    for i in range(1, steps + 1):
        if live.size == 0:
            break
        u, u0 = i / steps, (i - 1) / steps
        if wide:  # quadratic schedule: fine near the eye, coarse far away
            u, u0 = u * u, u0 * u0
        t = t0[live] + u * span[live]
        gap, _, _ = _gap(scene, o[live] + t[:, None] * d[live], mode)
        crossed = gap < 0
        idx = live[crossed]
        lo[idx] = t0[idx] + u0 * span[idx]
        t_hit[idx] = t[crossed]
        live = live[~crossed]
    hit = np.isfinite(t_hit)
    idx = np.nonzero(hit)[0]
    a, b = lo[idx], t_hit[idx]
    for _ in range(refine):
        m = 0.5 * (a + b)
        gap, _, _ = _gap(scene, o[idx] + m[:, None] * d[idx], mode)
        inside = gap < 0
        b = np.where(inside, m, b)
        a = np.where(inside, a, m)
    _, g, w = _gap(scene, o[idx] + b[:, None] * d[idx], mode)
    which[idx] = np.where(g <= w, GROUND, WATER)
    t_hit[idx] = 0.5 * (a + b)
    return t_hit, hit, which


def _transmittance(scene: Scene, length):
    """The water's RGB transmittance over path lengths ``length`` (m): the scene's Beer–Lambert
    coefficients, or the method ``Effects.absorption_form`` names, evaluated directly (float64)."""
    if not scene.effects.absorption:
        return np.ones(np.shape(length) + (3,))
    form = scene.effects.absorption_form
    if form == "rgb":
        return np.exp(-np.asarray(length)[..., None] * scene.absorption)
    from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

    length = np.maximum(np.asarray(length, np.float64), 0.0)
    far = ~np.isfinite(length)  # a ray that never lands: no light comes back through water (as e^(-inf·a) = 0)
    out = np.asarray(WATER_TRANSMITTANCE_METHODS[form](np.where(far, 0.0, length)), np.float64)
    return np.where(far[..., None], 0.0, out)


def shade_ground(scene: Scene, p):
    """Radiance leaving the ground at points p (n, 3) toward any viewer (Lambertian)."""
    albedo = scene.albedo if scene.albedo is not None else scene.default_albedo
    alb = sample(albedo, scene.length, p[:, :2])
    ng = _normal(scene.ground, scene.length, p[:, :2])
    depth = water_level(scene, p[:, :2]) - p[:, 2]
    under = depth > 0
    dry = scene.ambient + scene.sun_color * np.maximum(ng @ scene.sun, 0.0)[:, None]
    lw = sun_in_water(scene.sun, scene.n_air, scene.n_water)
    d = np.maximum(depth, 0.0)
    sun_t = 1.0 - float(_reflectance(scene, np.array(scene.sun[2]), scene.n_air, scene.n_water))
    e = (sample(scene.caustics, scene.length, p[:, :2]) if scene.effects.caustics and scene.caustics is not None
         else np.ones(len(p)))
    wet = (scene.ambient * _transmittance(scene, d)
           + scene.sun_color * (sun_t * e * np.maximum(ng @ lw, 0.0))[:, None] * _transmittance(scene, d / lw[2]))
    return alb * np.where(under[:, None], wet, dry)


def _secondary(scene, p, d, medium, steps, refine):
    """Colour along one-level secondary rays from surface points p: ground only.
    ``medium`` "water" (Beer–Lambert, deep colour on a miss) or "air" (environment on a miss)."""
    eps = 1e-4 * scene.length
    o = p + eps * d
    t, hit, _ = march(scene, o, d, 2, steps, refine)
    out = np.empty(p.shape)
    if medium == "water":
        out[:] = scene.deep_color
    else:
        out[:] = environment(scene, d)
    idx = np.nonzero(hit)[0]
    if idx.size:
        q = o[idx] + t[idx, None] * d[idx]
        c = shade_ground(scene, q)
        if medium == "water":
            c = c * _transmittance(scene, t[idx] + eps)
        out[idx] = c
    return out


def ray_directions(camera, width: int, height: int, offset=(0.0, 0.0)):
    """Unit view directions (height, width, 3) through pixel centres, row 0 at the top.

    Parameters
    ----------
    camera : Camera
        The camera (eye, target, up and vertical field of view).
    width, height : int
        Image size, pixels, each in [1, ``MAX_PIXELS``] (16384).
    offset : (float, float), optional
        (right, down) shift of every ray from its pixel's centre, pixels, each in [−0.5, 0.5] (default none).

    Returns
    -------
    numpy.ndarray (height, width, 3)
        Unit direction vectors (world frame, dimensionless), float64.
    """
    check_instance("camera", camera, Camera, "optics.rendering.Camera")
    width, height = check_int("width", width, lo=1, hi=MAX_PIXELS), check_int("height", height, lo=1, hi=MAX_PIXELS)
    check_array("offset", offset, ndim=1, shape_tail=(2,), lo=-0.5, hi=0.5)
    right, down = (float(v) for v in offset)
    f, r, u = camera.basis()
    th = math.tan(math.radians(camera.fov) / 2)
    x = (2 * (np.arange(width) + 0.5 + right) / width - 1) * th * width / height
    y = (1 - 2 * (np.arange(height) + 0.5 + down) / height) * th
    d = f + x[None, :, None] * r + y[:, None, None] * u
    return d / np.linalg.norm(d, axis=-1, keepdims=True)


def trace(scene: Scene, width: int = 160, height: int = 120, *, steps: int = 256, refine: int = 10) -> np.ndarray:
    """Render ``scene`` on the CPU: linear RGB image (height, width, 3), float32.

    ``steps`` and ``refine`` are the march and bisection counts of the joint search (the
    renderer's defaults); raise ``steps`` for a converged image.

    Parameters
    ----------
    scene : Scene
        What is drawn: height fields, camera, lighting and effects.
    width, height : int, optional
        Image size, pixels, each in [1, ``MAX_PIXELS``] (16384) (defaults 160 × 120).
    steps : int, optional, keyword-only
        Equal march steps along each ray, >= 1 (default 256).
    refine : int, optional, keyword-only
        Bisection steps after the first crossing, >= 0 (default 10).

    Returns
    -------
    numpy.ndarray (height, width, 3)
        Linear RGB radiance, float32 (row 0 at the top).

    References
    ----------
    L. Baboud & X. Décoret (2006). Realistic water volumes in real-time. *Eurographics Workshop on Natural
    Phenomena* (the two-height-field model, docs/physics.md §2.5).
    """
    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    width, height = check_int("width", width, lo=1), check_int("height", height, lo=1)
    steps, refine = check_int("steps", steps, lo=1), check_int("refine", refine, lo=0)
    d = ray_directions(scene.camera, width, height).reshape(-1, 3)
    return _shade_rays(scene, d, height, steps, refine).reshape(height, width, 3).astype(np.float32)


def _shade_rays(scene: Scene, d, height: int, steps: int, refine: int) -> np.ndarray:
    """Linear RGB (n, 3), float64, of view rays ``d`` (n, 3) from the eye of an image ``height`` pixels tall (its
    pixels' footprint, for the distance filtering): :func:`trace`'s work, on any rays."""
    eff = scene.effects
    eye = np.asarray(scene.camera.eye, float)
    o = np.broadcast_to(eye, d.shape).copy()
    half = scene.length / 2
    inside = abs(eye[0]) <= half and abs(eye[1]) <= half
    under = (inside or scene.surroundings == "tile") and eye[2] < float(water_level(scene, eye[None, :2])[0])
    t, hit, which = march(scene, o, d, 1 if under else 0, steps, refine)
    out = np.empty(d.shape)
    if under:
        out[:] = scene.deep_color
    elif scene.surroundings != "none":
        miss = np.nonzero(~hit)[0]
        if miss.size:
            out[miss] = far_field(scene, o[miss], d[miss])
    else:
        out[:] = environment(scene, d)
    g = np.nonzero(hit & (which == GROUND))[0]
    if g.size:
        c = shade_ground(scene, o[g] + t[g, None] * d[g])
        out[g] = c * _transmittance(scene, t[g]) if under else c
    s = np.nonzero(hit & (which == WATER))[0]
    if s.size:
        p = o[s] + t[s, None] * d[s]
        n = _water_normal(scene, p[:, :2])
        ds = d[s]
        if not under:
            if eff.filtering:
                m, cov = _Slopes(scene).filtered(scene, p, ds, t[s], 2 * math.tan(math.radians(scene.camera.fov) / 2)
                                                 / height)
                n = facing_normal(_unit_normal(m), ds)
            cos_i = np.maximum(-np.sum(ds * n, axis=-1), 0.0)
            r = _reflectance(scene, cos_i, scene.n_air, scene.n_water)
            tdir = refract(ds, n, scene.n_air, scene.n_water)[0] if eff.refraction else ds
            trans = _secondary(scene, p, tdir, "water", steps, refine)
            rdir = reflect(ds, n)
            refl = _secondary(scene, p, rdir, "air", steps, refine) if eff.reflection else environment(scene, rdir)
            out[s] = r[:, None] * refl + (1 - r[:, None]) * trans
            if eff.filtering:
                rough = np.nonzero(cov[:, 0] + cov[:, 1] > VARIANCE_FLOOR)[0]
                if rough.size:
                    c, seen = _over_slopes(scene, p[rough], ds[rough], m[rough], cov[rough], trans[rough],
                                           eff.reflection, steps, refine)
                    out[s[rough[seen]]] = c[seen]
            if eff.foam and scene.foam is not None:
                f = _surface_sample(scene, scene.foam, p[:, :2])[:, None]
                white = scene.foam_albedo * (scene.ambient + scene.sun_color * np.maximum(n @ scene.sun, 0.0)[:, None])
                out[s] = out[s] * (1 - f) + white * f
        else:
            cos_i = np.maximum(np.sum(ds * n, axis=-1), 0.0)
            r = _reflectance(scene, cos_i, scene.n_water, scene.n_air)
            rdir = reflect(ds, n)
            refl = (_secondary(scene, p, rdir, "water", steps, refine) if eff.reflection
                    else np.broadcast_to(scene.deep_color, ds.shape))
            tdir = refract(ds, n, scene.n_water, scene.n_air)[0] if eff.refraction else ds
            trans = _secondary(scene, p, tdir, "air", steps, refine)
            out[s] = (r[:, None] * refl + (1 - r[:, None]) * trans) * _transmittance(scene, t[s])
    return out


def effect_change(scene: Scene, effect: str, width: int = 160, height: int = 120, *, steps: int = 256,
                  refine: int = 10) -> dict:
    """What switching ``effect`` off changes in ``scene``'s picture: the CPU reference drawn both ways.

    Parameters
    ----------
    scene : Scene
        The scene as it will be drawn (its effects as they are; an effect already off changes nothing).
    effect : str
        One of :attr:`optics.rendering.Effects.SWITCHES` (``"reflection"``, ``"caustics"``, …).
    width, height : int, optional
        Image size, pixels (defaults 160 × 120).
    steps, refine : int, optional, keyword-only
        As :func:`trace`.

    Returns
    -------
    dict
        ``change``: the largest difference of any pixel's channel, linear RGB clipped to the displayable
        [0, 1] (what an image quantum measures); ``psnr``: dB (inf: identical); ``seconds_on``,
        ``seconds_off``: the two frames' tracing times, s (this CPU; each once).
    """
    import time

    from optics.rendering.scene import Effects

    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    if not isinstance(effect, str):
        raise TypeError(f"effect must be a str, one of {list(Effects.SWITCHES)}, got {type(effect).__name__}")
    if effect not in Effects.SWITCHES:
        raise ValueError(f"effect must be one of {list(Effects.SWITCHES)}, got {effect!r}")
    width, height = check_int("width", width, lo=1, hi=MAX_PIXELS), check_int("height", height, lo=1, hi=MAX_PIXELS)
    images, seconds = [], []
    for drawn in (scene, scene.with_effects(**{effect: False})):
        start = time.perf_counter()
        images.append(np.clip(trace(drawn, width, height, steps=steps, refine=refine), 0.0, 1.0))
        seconds.append(time.perf_counter() - start)
    return dict(change=float(np.max(np.abs(images[0] - images[1]))), psnr=psnr(images[1], images[0]),
                seconds_on=seconds[0], seconds_off=seconds[1])


def psnr_against_reference(image, scene: Scene, *, shift: float = 0.01, steps: int = 256,
                           refine: int = 10) -> tuple[float, int]:
    """PSNR (dB) of a renderer's ``image`` of ``scene`` against the reference, a pixel at an edge compared with what
    the reference traces within ``shift`` pixels of its centre.

    Where a ray grazes an edge (a reflected ray skimming a ridge, a silhouette) the exact colour jumps, and a
    float32 renderer may land on either side of it: on the dam-break scene one sigma point's reflected ray of one
    pixel misses a ridge in float64 and meets it at 9.4 m if the slope moments move by 3 parts in 10⁵, and the
    pixel's colour moves by 1.6e-3 within a hundredth of a pixel (GPU 99.2 dB against :func:`trace`, 112 dB
    without the reflections). So the pixels more than 1e-4 off (ten times the RMS error 100 dB allows) — the
    worst 1 % of the image, at least 16 — are traced again at (±``shift``, 0) and (0, ±``shift``) pixels, and
    each channel counts only its distance to the range its five samples span (each channel on its own). Every
    other pixel counts its whole error. A renderer whose rays are misplaced by more than ``shift`` stays outside
    the ranges (half a pixel: 31.7 dB on that scene), and one off over more than 1 % of the image keeps the rest
    of its error (a two-hundredth of a pixel everywhere: 73 dB on a quay scene at 32 × 24; tested).

    Parameters
    ----------
    image : array_like (height, width, 3)
        The renderer's linear RGB, [0, 1] (values outside are clipped, as :func:`psnr` does).
    scene : Scene
        What it drew.
    shift : float, optional, keyword-only
        Pixels, in (0, 0.5] (default 0.01).
    steps, refine : int, optional, keyword-only
        As :func:`trace`'s.

    Returns
    -------
    psnr : float
        dB (inf where the image is within the ranges everywhere).
    edges : int
        How many pixels a shifted sample brought nearer.

    Raises
    ------
    ValueError
        For an ``image`` that is not (height, width, 3) or not finite, or a ``shift`` out of range.
    """
    check_array("image", image, ndim=3, shape_tail=(3,))
    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    check_scalar("shift", shift, lo=0.0, lo_open=True, hi=0.5)
    height, width = np.shape(image)[:2]
    image = np.clip(np.asarray(image, np.float64), 0.0, 1.0).reshape(-1, 3)
    reference = np.clip(trace(scene, width, height, steps=steps, refine=refine).astype(np.float64), 0.0, 1.0)
    reference = reference.reshape(-1, 3)
    error = np.abs(image - reference).max(axis=-1)
    far = np.flatnonzero(error > 1e-4)
    far = far[np.argsort(error[far])[::-1][:max(16, (width * height) // 100)]]
    edges = 0
    if far.size:
        lo, hi = reference[far].copy(), reference[far].copy()
        for offset in ((shift, 0.0), (-shift, 0.0), (0.0, shift), (0.0, -shift)):
            d = ray_directions(scene.camera, width, height, offset).reshape(-1, 3)[far]
            c = np.clip(_shade_rays(scene, d, height, steps, refine).astype(np.float32).astype(np.float64), 0.0, 1.0)
            lo, hi = np.minimum(lo, c), np.maximum(hi, c)
        within = np.clip(image[far], lo, hi)  # the nearest each range holds to the image
        edges = int(np.count_nonzero(np.abs(within - image[far]).max(-1) < error[far]))
        reference[far] = within
    return psnr(image, reference), edges


def psnr(image, reference, peak: float = 1.0) -> float:
    """Peak signal-to-noise ratio (dB) of ``image`` against ``reference``, both clipped to [0, peak]
    (``peak`` > 0, at most 1e6); inf for identical images.

    Parameters
    ----------
    image, reference : array_like
        Images of one shape (at least 1-D), in the same units as ``peak``.
    peak : float, optional
        Peak signal value, in (0, 1e6] (default 1.0).

    Returns
    -------
    float
        PSNR, dB (inf when the clipped images are identical).

    Raises
    ------
    ValueError
        When the shapes of ``image`` and ``reference`` differ.
    """
    check_array("image", image, min_ndim=1)
    check_array("reference", reference, min_ndim=1)
    check_scalar("peak", peak, lo=0.0, hi=1e6, lo_open=True)
    a = np.clip(np.asarray(image, np.float64), 0, peak)
    b = np.clip(np.asarray(reference, np.float64), 0, peak)
    if a.shape != b.shape:
        raise ValueError(f"image shape {a.shape} does not match reference shape {b.shape}")
    mse = float(np.mean((a - b) ** 2))
    return math.inf if mse == 0 else 10 * math.log10(peak * peak / mse)
