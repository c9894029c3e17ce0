"""Headless moderngl renderer of water volumes from two height fields (Baboud & Décoret 2006).

A full-screen fragment shader ray-traces the ground and water height fields jointly
(equal steps through the volume's box, then bisection), refracts to the ground,
reflects to the ground or the environment (one level), weights them with the exact
Fresnel reflectance, applies Beer–Lambert absorption along the underwater paths and
lights the underwater ground with a caustics map; every effect is switchable
(:class:`optics.rendering.scene.Effects`). The model is written twice, here in GLSL and
in :mod:`optics.rendering.reference` in numpy float64, and the tests compare them pixel
by pixel; this module takes nothing from the reference (its Python side uses the
library's own Fresnel and texture sampling).

It runs on EGL without a display: Mesa llvmpipe on a CPU-only machine, the GPU driver
elsewhere, unchanged. Textures are float32 and sampled with ``texelFetch`` and explicit
bilinear weights, so that the GPU and the reference agree on the surfaces.

>>> from optics.rendering import Renderer                   # doctest: +SKIP
>>> from wavephys.app.builtin import builtin_scene          # doctest: +SKIP
>>> with Renderer(400, 300) as r:                           # doctest: +SKIP
...     image = r.render(builtin_scene("pool"))             # (300, 400, 3) float32, linear RGB
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

from optics.light.attenuation import TABLE_SCALE, transmittance_table

TABLE_ROW = 1024
"""Entries a row of the absorption texture holds (GL 3.3 guarantees textures 1024 texels a side)."""
from optics.light.fresnel import normal_reflectance, reflectance
from optics.gpu import EGL_PACKAGES, GLSL_FRESNEL_FORMS, GLSL_OPTICS, GLSL_SAMPLING, RendererUnavailable, gl_context
from optics.rendering.filtering import FACING, MAX_TAPS, VARIANCE_FLOOR, covariance_given_back, slope_moments
from optics.rendering.scene import FAR_TILES, NEAR_TILES, SURROUNDINGS, Scene, sun_in_water, texture_sample
from wavephys.core.files import atomic_path, output_file, output_folder
from wavephys.core.progress import Progress
from wavephys.core.inputs import check_array, check_bool, check_instance, check_int, describe

VIDEO_SUFFIXES = (".mp4", ".gif", ".webm", ".mov", ".mkv", ".avi")

__all__ = ["Renderer", "RendererUnavailable", "EGL_PACKAGES", "to_srgb8", "save_png", "render_sequence"]

def _sky_uniforms(scene) -> dict:
    """The Preetham sky's constants for the shader (computed once per frame in float64)."""
    from optics.light.sky import preetham_constants

    c = preetham_constants(scene.sun, scene.turbidity, scene.sky_brightness)
    return dict(perez_Y=tuple(c["coefficients"][0]), perez_x=tuple(c["coefficients"][1]),
                perez_y=tuple(c["coefficients"][2]), sky_scale=tuple(c["scale"]))


VERTEX = """
#version 330
in vec2 position;
void main() { gl_Position = vec4(position, 0.0, 1.0); }
"""

WATER_HEIGHT = """
vec4 bilerp(sampler2D t, ivec2 size, vec2 xy) { return bilinear_at(t, size, xy, extent, false); }
vec4 bilerp_wrap(sampler2D t, ivec2 size, vec2 xy) { return bilinear_at(t, size, xy, extent, true); }
float fade(vec2 xy) {  // distance filtering of tiled fields
    float r = length(xy - eye.xy) / extent;
    float t = clamp((r - near_tiles) / (far_tiles - near_tiles), 0.0, 1.0);
    return 1.0 - t * t * (3.0 - 2.0 * t);
}
float water_h(vec2 xy) {
    if (surroundings == 0) return bilerp(water_tex, water_size, xy).r;
    float h = surroundings == 2 ? bilerp_wrap(water_tex, water_size, xy).r : bilerp(water_tex, water_size, xy).r;
    return water_mean + (h - water_mean) * fade(xy);
}
"""
"""GLSL: the water's height as drawn, ``water_h(xy)`` (clamped, or tiled and faded with distance from
the eye), and the bilinear lookups ``bilerp``, ``bilerp_wrap`` it uses; shared by the fragment shaders
and the mesh path's vertex shader (:mod:`optics.rendering.meshes`). Needs ``water_tex``,
``water_size``, ``extent``, ``eye``, ``surroundings``, ``water_mean``, ``near_tiles``, ``far_tiles``
and :data:`optics.gpu.GLSL_SAMPLING`."""

FRAGMENT = """
#version 330
uniform sampler2D ground_tex;  uniform ivec2 ground_size;
uniform sampler2D water_tex;   uniform ivec2 water_size;
uniform sampler2D albedo_tex;  uniform ivec2 albedo_size;
uniform sampler2D caustic_tex; uniform ivec2 caustic_size;
uniform sampler2D foam_tex;    uniform ivec2 foam_size;
uniform sampler2D env_tex;     uniform ivec2 env_size;
uniform bool use_env, use_caustics, use_foam;
uniform float extent, zlo, zhi;
uniform vec3 eye, cam_f, cam_r, cam_u;
uniform float tan_half;
uniform vec2 resolution;
uniform vec3 sun, sun_w, sun_color, ambient, sky_zenith, sky_horizon, absorption, deep_color, foam_albedo;
uniform float sun_glow, n_air, n_water, sun_t;
uniform int steps, refine;
uniform bool e_refraction, e_reflection, e_fresnel, e_absorption, e_caustics, e_foam;
uniform int fresnel_id;  // the Fresnel form's index in GLSL_FRESNEL_FORMS
uniform bool absorption_table;  // the absorption form drawn from its table (u = s/(s + scale))
uniform sampler2D absorption_tex; uniform ivec2 absorption_size; uniform float absorption_scale;  // rows of TABLE_ROW
uniform bool under;
uniform int surroundings;  // 0 none, 1 extend, 2 tile
uniform bool sky_preetham;
uniform float water_mean, foam_mean, near_tiles, far_tiles;
uniform float perez_Y[5], perez_x[5], perez_y[5];  // Perez coefficients (host, float64: optics.light.sky)
uniform vec3 sky_scale;
uniform bool e_filtering;  // distance filtering of the normals (optics.rendering.filtering)
uniform sampler2D slope_tex; uniform ivec2 slope_size; uniform int slope_levels;  // mip k: (gx, gy, gx², gy²)
uniform sampler2D slope2_tex;  // mip k: gx·gy
uniform vec3 slope_cov_all;  // the whole square's slope covariance (cxx, cyy, cxy)
uniform float pixel_angle;  // rad per pixel
const int MAX_TAPS = %MAX_TAPS%;
const float VARIANCE_FLOOR = %VARIANCE_FLOOR%;
const float FACING = %FACING%;
out vec4 frag;
%OPTICS%
float eps;

%WATER_HEIGHT%
float ground_h(vec2 xy) { return bilerp(ground_tex, ground_size, xy).r; }
float foam_at(vec2 xy) {
    if (surroundings == 0) return bilerp(foam_tex, foam_size, xy).r;
    float f = surroundings == 2 ? bilerp_wrap(foam_tex, foam_size, xy).r : bilerp(foam_tex, foam_size, xy).r;
    return foam_mean + (f - foam_mean) * fade(xy);
}
vec2 water_slope(vec2 xy) {
    float hx = extent / float(water_size.x), hy = extent / float(water_size.y);
    float gx = (water_h(xy + vec2(hx, 0.0)) - water_h(xy - vec2(hx, 0.0))) / (2.0 * hx);
    float gy = (water_h(xy + vec2(0.0, hy)) - water_h(xy - vec2(0.0, hy))) / (2.0 * hy);
    return vec2(gx, gy);
}
vec3 water_normal(vec2 xy) {
    vec2 g = water_slope(xy);
    return normalize(vec3(-g.x, -g.y, 1.0));
}

// -- distance filtering: the slopes' distribution over a pixel's footprint (optics/rendering/filtering.py)
float fade_at(vec2 xy) { return surroundings == 0 ? 1.0 : fade(xy); }
void exact_moments(vec2 xy, out vec2 m, out vec3 s) {  // the point's own slope; the faded variance given back
    m = water_slope(xy);
    float f = fade_at(xy);
    s = vec3(m.x * m.x, m.y * m.y, m.x * m.y) + (1.0 - f * f) * slope_cov_all;
}
void level_moments(int k, vec2 xy, out vec2 m, out vec3 s) {  // pyramid level k >= 1, faded
    ivec2 size = max(ivec2(slope_size.x >> k, slope_size.y >> k), ivec2(1));
    vec2 u = (xy / extent + 0.5) * vec2(size) - 0.5;
    bvec2 wrap = bvec2(surroundings == 2);
    vec4 a = bilinear_texel_lod(slope_tex, size, u, wrap, k);
    float c = bilinear_texel_lod(slope2_tex, size, u, wrap, k).r;
    float f = fade_at(xy);
    m = f * a.xy;
    s = f * f * vec3(a.z, a.w, c) + (1.0 - f * f) * slope_cov_all;
}
void tap_moments(vec2 xy, float lod, out vec2 m, out vec3 s) {  // trilinear; below level 1 the exact slope
    int top = slope_levels - 1;
    if (lod <= 0.0 || top < 1) { exact_moments(xy, m, s); return; }
    if (lod >= float(top)) { level_moments(top, xy, m, s); return; }
    int k = int(floor(lod));
    float a = lod - float(k);
    vec2 m0, m1; vec3 s0, s1;
    if (k == 0) exact_moments(xy, m0, s0); else level_moments(k, xy, m0, s0);
    level_moments(k + 1, xy, m1, s1);
    m = mix(m0, m1, a);
    s = mix(s0, s1, a);
}
void filtered_slopes(vec3 p, vec3 d, float t, out vec2 m, out vec3 cov) {
    float width = t * pixel_angle;
    float texel = extent / float(min(slope_size.x, slope_size.y));
    float along = width / max(abs(d.z), 1.0 / float(MAX_TAPS));
    float hl = length(d.xy);
    int taps = hl > 0.0 ? clamp(int(ceil(along / max(width, texel) - 1e-6)), 1, MAX_TAPS) : 1;
    float lod = log2(max(width, 1e-30) / texel);
    vec2 axis = hl > 0.0 ? d.xy / hl : vec2(0.0);
    if (taps == 1 && lod <= 0.0) {  // the exact slope: its covariance is the faded variance alone, exactly
        m = water_slope(p.xy);
        float f = fade_at(p.xy);
        cov = (1.0 - f * f) * slope_cov_all;
        return;
    }
    vec3 s = vec3(0.0);
    m = vec2(0.0);
    for (int i = 0; i < taps; ++i) {
        vec2 mi; vec3 si;
        tap_moments(p.xy + ((float(i) + 0.5) / float(taps) - 0.5) * along * axis, lod, mi, si);
        m += mi; s += si;
    }
    m /= float(taps); s /= float(taps);
    cov = vec3(max(s.x - m.x * m.x, 0.0), max(s.y - m.y * m.y, 0.0), s.z - m.x * m.y);
}

vec3 normal_of(sampler2D t, ivec2 size, vec2 xy) {
    float hx = extent / float(size.x), hy = extent / float(size.y);
    float gx = (bilerp(t, size, xy + vec2(hx, 0.0)).r - bilerp(t, size, xy - vec2(hx, 0.0)).r) / (2.0 * hx);
    float gy = (bilerp(t, size, xy + vec2(0.0, hy)).r - bilerp(t, size, xy - vec2(0.0, hy)).r) / (2.0 * hy);
    return normalize(vec3(-gx, -gy, 1.0));
}

float reflectance(float cos_i, float n1, float n2) {
    if (e_fresnel) return fresnel_form(fresnel_id, cos_i, n1, n2);
    float c = clamp(cos_i, 0.0, 1.0);
    if ((n1 / n2) * (n1 / n2) * (1.0 - c * c) >= 1.0) return 1.0;
    float f = (n1 - n2) / (n1 + n2);
    return f * f;
}
vec3 transmittance(float len) {
    if (!e_absorption) return vec3(1.0);
    if (!absorption_table) return exp(-len * absorption);
    // u = s/(s + scale) written so that s = inf gives u = 1 (the last entry, 0); the table's rows
    // hold TABLE_ROW entries each (a texture GL 3.3 guarantees: 1024 texels a side)
    int last = absorption_size.x * absorption_size.y - 1;
    float u = (1.0 - absorption_scale / (max(len, 0.0) + absorption_scale)) * float(last);
    int i = clamp(int(floor(u)), 0, last - 1);
    int w = absorption_size.x;
    vec3 a = texelFetch(absorption_tex, ivec2(i % w, i / w), 0).rgb;
    vec3 b = texelFetch(absorption_tex, ivec2((i + 1) % w, (i + 1) / w), 0).rgb;
    return mix(a, b, clamp(u - float(i), 0.0, 1.0));
}

// Preetham, Shirley & Smits (1999) daylight; the CPU reference's copy is optics/light/sky.py
float perez(float cos_t, float g, float cos_g, float A, float B, float C, float D, float E) {
    return (1.0 + A * exp(B / cos_t)) * (1.0 + C * exp(D * g) + E * cos_g * cos_g);
}
vec3 preetham(vec3 d) {
    vec3 up = normalize(vec3(d.xy, max(d.z, 1e-3)));
    float cos_t = max(up.z, 1e-3);
    float cos_g = clamp(dot(up, sun), -1.0, 1.0);
    float g = atan(length(cross(up, sun)), dot(up, sun));
    float Y = sky_scale.x * perez(cos_t, g, cos_g, perez_Y[0], perez_Y[1], perez_Y[2], perez_Y[3], perez_Y[4]);
    float x = sky_scale.y * perez(cos_t, g, cos_g, perez_x[0], perez_x[1], perez_x[2], perez_x[3], perez_x[4]);
    float y = sky_scale.z * perez(cos_t, g, cos_g, perez_y[0], perez_y[1], perez_y[2], perez_y[3], perez_y[4]);
    vec3 XYZ = vec3(x / y * Y, Y, (1.0 - x - y) / y * Y);
    vec3 rgb = max(vec3(3.2406 * XYZ.x - 1.5372 * XYZ.y - 0.4986 * XYZ.z,
                        -0.9689 * XYZ.x + 1.8758 * XYZ.y + 0.0415 * XYZ.z,
                        0.0557 * XYZ.x - 0.2040 * XYZ.y + 1.0570 * XYZ.z), 0.0);
    return d.z < 0.0 ? 0.5 * rgb : rgb;
}

vec3 environment(vec3 d) {
    if (use_env) {  // equirectangular: periodic in azimuth, clamped at the poles
        const float PI = 3.14159265358979;
        vec2 u = vec2((atan(d.y, d.x) + PI) / (2.0 * PI) * float(env_size.x),
                      acos(clamp(d.z, -1.0, 1.0)) / PI * float(env_size.y)) - 0.5;
        return bilinear_texel(env_tex, env_size, u, bvec2(true, false)).rgb;
    }
    vec3 sky = sky_preetham ? preetham(d)
             : (d.z < 0.0 ? 0.5 * sky_horizon : sky_horizon + (sky_zenith - sky_horizon) * sqrt(max(d.z, 0.0)));
    return sky + sun_glow * exp(64.0 * (dot(d, sun) - 1.0)) * sun_color;
}

vec2 box(vec3 o, vec3 d) {
    vec3 lo = vec3(-0.5 * extent, -0.5 * extent, zlo), hi = vec3(0.5 * extent, 0.5 * extent, zhi);
    vec3 inv = 1.0 / vec3(d.x == 0.0 ? 1e-30 : d.x, d.y == 0.0 ? 1e-30 : d.y, d.z == 0.0 ? 1e-30 : d.z);
    vec3 a = (lo - o) * inv, b = (hi - o) * inv;
    vec3 mn = min(a, b), mx = max(a, b);
    return vec2(max(max(max(mn.x, mn.y), mn.z), 0.0), min(min(mx.x, mx.y), mx.z));
}

float far_distance(vec3 d) {
    float h = length(d.xy);
    return h > 0.0 ? far_tiles * extent / h : 1e30;
}
vec2 slab(vec3 o, vec3 d) {  // the layer of both surfaces, out to far_tiles sides from the eye
    float dz = d.z == 0.0 ? 1e-30 : d.z;
    float a = (zlo - o.z) / dz, b = (zhi - o.z) / dz;
    return vec2(max(min(a, b), 0.0), min(max(a, b), far_distance(d)));
}

// > 0 while in the ray's medium; mode 0 air, 1 water, 2 ground only. terms = (ground, water)
float gap(vec3 p, int mode, out vec2 terms) {
    float g = p.z - ground_h(p.xy);
    if (mode == 2) { terms = vec2(g, 1e30); return g; }
    float w = water_h(p.xy) - p.z;
    float wt = mode == 0 ? -w : w;
    terms = vec2(g, wt);
    return min(g, wt);
}

// first hit: returns t (< 0: none); which = 0 ground, 1 water
float march(vec3 o, vec3 d, int mode, out int which) {
    which = 0;
    bool wide = surroundings != 0;
    vec2 span = wide ? slab(o, d) : box(o, d);
    if (span.y <= span.x) return -1.0;
    float len = span.y - span.x;
    vec2 terms;
    float a = -1.0, b = -1.0;
    for (int i = 1; i <= steps; ++i) {
        float u = float(i) / float(steps), u0 = float(i - 1) / float(steps);
        if (wide) { u = u * u; u0 = u0 * u0; }  // fine near the eye, coarse far away
        float t = span.x + u * len;
        if (gap(o + t * d, mode, terms) < 0.0) { a = span.x + u0 * len; b = t; break; }
    }
    if (b < 0.0) return -1.0;
    for (int k = 0; k < refine; ++k) {
        float m = 0.5 * (a + b);
        if (gap(o + m * d, mode, terms) < 0.0) b = m; else a = m;
    }
    gap(o + b * d, mode, terms);
    which = terms.x <= terms.y ? 0 : 1;
    return 0.5 * (a + b);
}

vec3 shade_ground(vec3 p) {
    vec3 alb = bilerp(albedo_tex, albedo_size, p.xy).rgb;
    vec3 ng = normal_of(ground_tex, ground_size, p.xy);
    float depth = water_h(p.xy) - p.z;
    if (depth <= 0.0) return alb * (ambient + sun_color * max(dot(ng, sun), 0.0));
    float e = (e_caustics && use_caustics) ? bilerp(caustic_tex, caustic_size, p.xy).r : 1.0;
    vec3 wet = ambient * transmittance(depth)
             + sun_color * (sun_t * e * max(dot(ng, sun_w), 0.0)) * transmittance(depth / sun_w.z);
    return alb * wet;
}

vec3 secondary(vec3 p, vec3 d, bool in_water) {
    vec3 o = p + eps * d;
    int which;
    float t = march(o, d, 2, which);
    if (t < 0.0) return in_water ? deep_color : environment(d);
    vec3 c = shade_ground(o + t * d);
    return in_water ? c * transmittance(t + eps) : c;
}

// R·reflected + (1 − R)·trans averaged over the slopes (mean m, covariance cov) at four sigma points, each
// weighted by its facet's area seen from the eye; w = 0 when every facet faces away
vec4 over_slopes(vec3 p, vec3 d, vec2 m, vec3 cov, vec3 trans, bool traced) {
    float l11 = sqrt(max(cov.x, 0.0));
    float cxy = clamp(cov.z, -sqrt(max(cov.x * cov.y, 0.0)), sqrt(max(cov.x * cov.y, 0.0)));  // |cxy| ≤ √(cxx·cyy)
    float l21 = l11 > 0.0 ? cxy / l11 : 0.0;
    float l22 = sqrt(max(cov.y - l21 * l21, 0.0));
    vec2 c1 = 1.4142135623730951 * vec2(l11, l21), c2 = vec2(0.0, 1.4142135623730951 * l22);
    vec3 sum = vec3(0.0);
    float wsum = 0.0;
    for (int i = 0; i < 4; ++i) {
        vec2 g = m + (i == 0 ? c1 : (i == 1 ? -c1 : (i == 2 ? c2 : -c2)));
        vec3 n = normalize(vec3(-g.x, -g.y, 1.0));
        float w = max(-dot(d, n), 0.0) / n.z;
        if (w <= 0.0) continue;
        float r = reflectance(-dot(d, n), n_air, n_water);
        vec3 rdir = reflect(d, n);
        vec3 refl = traced ? secondary(p, rdir, false) : environment(rdir);
        sum += w * (r * refl + (1.0 - r) * trans);
        wsum += w;
    }
    return wsum > 0.0 ? vec4(sum / wsum, 1.0) : vec4(0.0);
}

vec3 far_field(vec3 o, vec3 d) {  // primary rays past the marched region: flat planes to the horizon
    float h = length(d.xy);
    if (d.z >= 0.0 || h == 0.0) return environment(d);
    vec3 q0 = o + far_distance(d) * d;
    if (q0.z < zlo) return environment(d);
    // land or water where the ray meets the water's level (a straight shore converges to the horizon, as
    // it does; decided at q0, a fixed distance from the eye, a shore crossing it drew a vertical edge)
    vec3 q = o + max((water_h(q0.xy) - o.z) / d.z, far_distance(d)) * d;
    float lw = water_h(q.xy), lg = ground_h(q.xy);
    vec3 alb = bilerp(albedo_tex, albedo_size, q.xy).rgb;
    if (lg >= lw) return alb * (ambient + sun_color * max(sun.z, 0.0));
    vec3 up = vec3(0.0, 0.0, 1.0);
    float r = reflectance(clamp(-d.z, 0.0, 1.0), n_air, n_water);
    vec3 refl = environment(reflect(d, up));
    vec3 tdir = e_refraction ? refract_dir(d, up, n_air / n_water) : d;
    float depth = max(lw - lg, 0.0);
    vec3 wet = alb * (ambient * transmittance(depth)
                      + sun_color * (sun_t * max(sun_w.z, 0.0)) * transmittance(depth / sun_w.z));
    vec3 trans = wet * transmittance(depth / max(-tdir.z, 1e-6));
    if (e_filtering && slope_cov_all.x + slope_cov_all.y > VARIANCE_FLOOR) {  // the waves' roughness, averaged
        vec4 o = over_slopes(q, d, vec2(0.0), slope_cov_all, trans, false);
        if (o.w > 0.0) return o.rgb;
    }
    return r * refl + (1.0 - r) * trans;
}

// the water's colour at p, seen from above along d at distance t (the ray-marcher's and the mesh path's)
vec3 shade_water(vec3 p, vec3 d, float t) {
    vec3 c;
    vec3 n = water_normal(p.xy);
    vec2 m = vec2(0.0);
    vec3 cov = vec3(0.0);
    if (e_filtering) {
        filtered_slopes(p, d, t, m, cov);
        n = normalize(vec3(-m.x, -m.y, 1.0));
        float tip = dot(d, n) + FACING;
        if (tip > 0.0) n = normalize(n - tip * d);  // a mean normal facing away: tipped
    }
    float r = reflectance(max(-dot(d, n), 0.0), n_air, n_water);
    vec3 tdir = e_refraction ? refract_dir(d, n, n_air / n_water) : d;
    vec3 trans = secondary(p, tdir, true);
    vec4 o = cov.x + cov.y > VARIANCE_FLOOR ? over_slopes(p, d, m, cov, trans, e_reflection) : vec4(0.0);
    if (o.w > 0.0) {
        c = o.rgb;
    } else {
        vec3 rdir = reflect(d, n);
        vec3 refl = e_reflection ? secondary(p, rdir, false) : environment(rdir);
        c = r * refl + (1.0 - r) * trans;
    }
    if (e_foam && use_foam) {
        float f = foam_at(p.xy);
        c = mix(c, foam_albedo * (ambient + sun_color * max(dot(n, sun), 0.0)), f);
    }
    return c;
}

vec3 view_ray() {  // the pixel's primary direction
    vec2 ndc = 2.0 * gl_FragCoord.xy / resolution - 1.0;
    return normalize(cam_f + ndc.x * tan_half * (resolution.x / resolution.y) * cam_r + ndc.y * tan_half * cam_u);
}

%MAIN%"""
MARCH_MAIN = """
void main() {
    eps = 1e-4 * extent;
    vec3 d = view_ray();
    int which;
    float t = march(eye, d, under ? 1 : 0, which);
    vec3 c;
    if (t < 0.0) {
        c = under ? deep_color : (surroundings != 0 ? far_field(eye, d) : environment(d));
    } else if (which == 0) {
        c = shade_ground(eye + t * d);
        if (under) c *= transmittance(t);
    } else {
        vec3 p = eye + t * d;
        if (!under) {
            c = shade_water(p, d, t);
        } else {
            vec3 n = water_normal(p.xy);
            float r = reflectance(max(dot(d, n), 0.0), n_water, n_air);
            vec3 rdir = reflect(d, n);
            vec3 refl = e_reflection ? secondary(p, rdir, true) : deep_color;
            vec3 trans = vec3(0.0);
            if (r < 1.0) {
                vec3 tdir = e_refraction ? refract_dir(d, -n, n_water / n_air) : d;
                trans = secondary(p, tdir, false);
            }
            c = (r * refl + (1.0 - r) * trans) * transmittance(t);
        }
    }
    frag = vec4(c, 1.0);
}
"""
SHADING = (FRAGMENT.replace("%OPTICS%", GLSL_SAMPLING + GLSL_OPTICS).replace("%WATER_HEIGHT%", WATER_HEIGHT)
           .replace("%MAX_TAPS%", str(MAX_TAPS))
           .replace("%VARIANCE_FLOOR%", repr(VARIANCE_FLOOR)).replace("%FACING%", repr(FACING)))
"""The fragment shaders' shared GLSL (the fields, the march, the shading of ground and water), with
``%MAIN%`` where a shader's ``main`` goes: the ray-marcher's (:data:`MARCH_MAIN`) or the mesh
path's (:mod:`optics.rendering.meshes`)."""
FRAGMENT = SHADING.replace("%MAIN%", MARCH_MAIN)
"""The ray-marcher's fragment shader."""


class Renderer:
    """Headless renderer: ``Renderer(width, height).render(scene)`` → (height, width, 3) float32 linear RGB.

    Parameters
    ----------
    width, height : int
        Image size, pixels (≥ 1, ≤ the context's largest framebuffer).
    steps, refine : int
        March steps through the volume and bisection steps of the joint search (the
        reference tracer takes the same).

    Raises
    ------
    RendererUnavailable
        If no OpenGL 3.3 context can be created; the message names the EGL packages.
    """

    def __init__(self, width: int = 800, height: int = 600, *, steps: int = 256, refine: int = 10):
        self.width = check_int("width", width, lo=1)
        self.height = check_int("height", height, lo=1)
        self.steps = check_int("steps", steps, lo=1)
        self.refine = check_int("refine", refine, lo=0)
        self.ctx = gl_context()
        self.max_texture_size = int(self.ctx.info["GL_MAX_TEXTURE_SIZE"])
        limit = int(self.ctx.info["GL_MAX_RENDERBUFFER_SIZE"])
        if max(self.width, self.height) > limit:
            self.ctx.release()
            raise ValueError(f"image size {self.width}×{self.height} exceeds the context's limit {limit}")
        self.program = self.ctx.program(vertex_shader=VERTEX, fragment_shader=FRAGMENT)
        quad = np.array([-1, -1, 1, -1, -1, 1, 1, 1], np.float32)
        self._vbo = self.ctx.buffer(quad.tobytes())
        self._vao = self.ctx.vertex_array(self.program, [(self._vbo, "2f", "position")])
        self._fbo = self.ctx.framebuffer(color_attachments=[self.ctx.renderbuffer((self.width, self.height), 4,
                                                                                  dtype="f4")])
        self._textures = {}

    # -- resources -------------------------------------------------------------------
    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.release()

    def release(self):
        """Free the GL context and everything on it."""
        if getattr(self, "ctx", None) is None:
            return
        with self.ctx:
            for tex in self._textures.values():
                tex.release()
        self._textures = {}
        self.ctx.release()
        self.ctx = None

    @property
    def renderer_name(self) -> str:
        """The OpenGL renderer string (e.g. ``llvmpipe (LLVM 15.0.6, 256 bits)``)."""
        return str(self.ctx.info["GL_RENDERER"])

    def texture(self, name: str, array) -> "object":
        """Upload a float32 array (ny, nx) or (ny, nx, c) as a moderngl texture (nearest,
        no mipmaps), reusing the slot ``name``; returns the moderngl.Texture."""
        if not isinstance(name, str) or not name.strip():
            raise TypeError(f"name must be a non-empty string, got {describe(name)}")
        check_array("array", array, min_ndim=2)
        with self.ctx:
            return self._upload(name, array)

    def _upload(self, name, array):
        """:meth:`texture` with this context already current (GL ``with`` blocks do not nest)."""
        a = np.ascontiguousarray(np.asarray(array, np.float32))
        if a.ndim == 2:
            a = a[..., None]
        if a.ndim != 3 or a.shape[2] not in (1, 2, 3, 4) or min(a.shape[:2]) < 1:
            raise ValueError(f"{name} texture must have shape (ny, nx[, 1–4]) with ny, nx ≥ 1, got {np.shape(array)}")
        ny, nx, c = a.shape
        if max(nx, ny) > self.max_texture_size:
            raise ValueError(f"{name} texture is {nx}×{ny}, larger than this context allows "
                             f"({self.max_texture_size}); downsample it")
        if not np.isfinite(a).all():
            raise ValueError(f"{name} texture contains NaN or inf")
        old = self._textures.get(name)
        if old is not None and old.size == (nx, ny) and old.components == c:
            old.write(a.tobytes())
            return old
        if old is not None:
            old.release()
        tex = self.ctx.texture((nx, ny), c, a.tobytes(), dtype="f4")
        tex.filter = (self.ctx.NEAREST, self.ctx.NEAREST)
        tex.repeat_x = tex.repeat_y = False
        self._textures[name] = tex
        return tex

    def _bind(self, scene: Scene, programs=None):
        programs = (self.program,) if programs is None else programs
        albedo = scene.albedo if scene.albedo is not None else scene.default_albedo
        caustics = scene.caustics if scene.caustics is not None else np.ones((2, 2), np.float32)
        foam = scene.foam if scene.foam is not None else np.zeros((2, 2), np.float32)
        env = scene.environment if scene.environment is not None else np.zeros((2, 2, 3), np.float32)
        form = scene.effects.absorption_form
        table = (transmittance_table(form).reshape(-1, TABLE_ROW, 3) if form != "rgb" else np.ones((1, 2, 3), np.float32))
        for unit, (name, arr) in enumerate((("ground", scene.ground), ("water", scene.water), ("albedo", albedo),
                                            ("caustic", caustics), ("env", env), ("foam", foam),
                                            ("absorption", table))):
            tex = self._upload(name, arr)
            tex.use(unit)
            for program in programs:
                if f"{name}_tex" in program:  # else optimized away by the compiler
                    program[f"{name}_tex"] = unit
                if f"{name}_size" in program:
                    program[f"{name}_size"] = tex.size
        levels = (slope_moments(scene.water, scene.length, wrap=scene.surroundings == "tile")
                  if scene.effects.filtering else [np.zeros((1, 1, 5), np.float32)])
        unit += 1
        for name, channels in (("slope", slice(0, 4)), ("slope2", slice(4, 5))):
            tex = self._upload_levels(name, [level[..., channels] for level in levels])
            tex.use(unit)
            for program in programs:
                if f"{name}_tex" in program:
                    program[f"{name}_tex"] = unit
            unit += 1
        for program in programs:
            if "slope_size" in program:
                program["slope_size"] = (levels[0].shape[1], levels[0].shape[0])
                program["slope_levels"] = len(levels)

    def _upload_levels(self, name, levels):
        """Upload a mip pyramid (level k: (ny >> k, nx >> k, c) float32), reusing the slot ``name``."""
        ny, nx, c = levels[0].shape
        old = self._textures.get(name)
        if old is not None and (old.size != (nx, ny) or old.components != c or old.extra != len(levels)):
            old.release()
            old = None
        if old is None:
            old = self.ctx.texture((nx, ny), c, np.ascontiguousarray(levels[0]).tobytes(), dtype="f4")
            old.filter = (self.ctx.NEAREST, self.ctx.NEAREST)
            old.repeat_x = old.repeat_y = False
            old.build_mipmaps(0, len(levels) - 1)  # allocates the levels; each is written below
            old.extra = len(levels)
            self._textures[name] = old
        for k, level in enumerate(levels):
            old.write(np.ascontiguousarray(level, np.float32).tobytes(), level=k)
        return old

    def _uniforms(self, scene: Scene, program=None, **extra):
        p, eff, cam = (self.program if program is None else program), scene.effects, scene.camera
        f, r, u = cam.basis()
        zlo, zhi = scene.bounds()
        eye = np.asarray(cam.eye, float)
        half = scene.length / 2
        under = bool(abs(eye[0]) <= half and abs(eye[1]) <= half
                     and eye[2] < float(texture_sample(scene.water, scene.length, eye[0], eye[1])))
        if scene.surroundings == "tile":  # the water is everywhere: wrap the eye into the square
            wx, wy = ((eye[:2] + half) % scene.length) - half
            under = bool(eye[2] < float(texture_sample(scene.water, scene.length, wx, wy)))
        if eff.fresnel:
            sun_t = 1.0 - float(reflectance(np.float64(scene.sun[2]), scene.n_air, scene.n_water,
                                            method=eff.fresnel_form))
        else:
            sun_t = 1.0 - normal_reflectance(scene.n_air, scene.n_water)
        values = dict(use_env=scene.environment is not None, use_caustics=scene.caustics is not None,
                      use_foam=scene.foam is not None, foam_albedo=scene.foam_albedo, e_foam=eff.foam,
                      surroundings=SURROUNDINGS.index(scene.surroundings), sky_preetham=scene.sky == "preetham",
                      **_sky_uniforms(scene),
                      water_mean=float(np.mean(scene.water, dtype=np.float64)),
                      foam_mean=float(np.mean(scene.foam, dtype=np.float64)) if scene.foam is not None else 0.0,
                      near_tiles=NEAR_TILES, far_tiles=FAR_TILES,
                      extent=scene.length, zlo=zlo, zhi=zhi, eye=eye, cam_f=f, cam_r=r, cam_u=u,
                      tan_half=math.tan(math.radians(cam.fov) / 2), resolution=(self.width, self.height),
                      sun=scene.sun, sun_w=sun_in_water(scene.sun, scene.n_air, scene.n_water),
                      sun_color=scene.sun_color, ambient=scene.ambient, sky_zenith=scene.sky_zenith,
                      sky_horizon=scene.sky_horizon, absorption=scene.absorption, deep_color=scene.deep_color,
                      sun_glow=scene.sun_glow, n_air=scene.n_air, n_water=scene.n_water, sun_t=sun_t,
                      steps=self.steps, refine=self.refine, e_refraction=eff.refraction,
                      e_reflection=eff.reflection, e_fresnel=eff.fresnel, e_absorption=eff.absorption,
                      e_caustics=eff.caustics, under=under, fresnel_id=GLSL_FRESNEL_FORMS.index(eff.fresnel_form),
                      absorption_table=eff.absorption_form != "rgb", absorption_scale=TABLE_SCALE,
                      e_filtering=eff.filtering, pixel_angle=2.0 * math.tan(math.radians(cam.fov) / 2) / self.height,
                      slope_cov_all=(covariance_given_back(scene.water, scene.length, scene.surroundings)
                                     if eff.filtering else (0.0, 0.0, 0.0)), **extra)
        for name, v in values.items():
            if name not in p:
                continue  # optimized away by the compiler
            if isinstance(v, (bool, np.bool_)):
                p[name] = bool(v)
            elif isinstance(v, (int, float)):
                p[name] = v
            else:
                p[name] = tuple(float(x) for x in np.asarray(v).ravel())

    # -- drawing ---------------------------------------------------------------------
    def render(self, scene: Scene) -> np.ndarray:
        """Draw ``scene``: (height, width, 3) float32, linear RGB, row 0 at the top."""
        check_instance("scene", scene, Scene, "optics.rendering.Scene")
        if self.ctx is None:
            raise RuntimeError("this Renderer has been released")
        with self.ctx:  # current again, whatever other contexts were made since
            self._bind(scene)
            self._uniforms(scene)
            self._fbo.use()
            self._vao.render(mode=self.ctx.TRIANGLE_STRIP)
            data = self._fbo.read(components=3, dtype="f4")
        img = np.frombuffer(data, np.float32).reshape(self.height, self.width, 3)
        return np.ascontiguousarray(img[::-1])

    def draw(self, scene: Scene) -> None:
        """Draw ``scene`` into the off-screen framebuffer and wait for it (no read-back): for timing."""
        check_instance("scene", scene, Scene, "optics.rendering.Scene")
        with self.ctx:
            self._bind(scene)
            self._uniforms(scene)
            self._fbo.use()
            self._vao.render(mode=self.ctx.TRIANGLE_STRIP)
            self.ctx.finish()

    def frame_seconds(self, scene: Scene, repeats: int = 5) -> float:
        """Median wall time of one frame (:meth:`draw`: upload, draw, finish), s, after one warm-up."""
        check_instance("scene", scene, Scene, "optics.rendering.Scene")
        times = []
        for _ in range(check_int("repeats", repeats, lo=1) + 1):
            t = time.perf_counter()
            self.draw(scene)
            times.append(time.perf_counter() - t)
        return float(np.median(times[1:]))


def to_srgb8(image) -> np.ndarray:
    """Linear RGB in [0, 1] (clipped; ±inf clip too, NaN is refused) → 8-bit sRGB (IEC 61966-2-1).

    Parameters
    ----------
    image : array_like
        Linear RGB values of any shape, dimensionless; clipped to [0, 1]; no NaN (±inf allowed).

    Returns
    -------
    numpy.ndarray
        sRGB-encoded values, uint8 in [0, 255], the shape of ``image``.
    """
    check_array("image", image, allow_inf=True)
    x = np.clip(np.asarray(image, np.float64), 0.0, 1.0)
    s = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    return np.round(s * 255).astype(np.uint8)


def save_png(image, path) -> Path:
    """Write a linear-RGB image as an 8-bit sRGB PNG, atomically; returns the path.

    Parameters
    ----------
    image : array_like (height, width, 3)
        Linear RGB, dimensionless, clipped to [0, 1]; no NaN (±inf allowed).
    path : str or os.PathLike
        Output file; must end in ``.png``.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    ValueError
        When ``image`` does not have shape (height, width, 3).
    """
    from PIL import Image

    check_array("image", image, ndim=3, allow_inf=True)
    a = np.asarray(image)
    if a.shape[2] != 3:
        raise ValueError(f"image must have shape (height, width, 3), got {a.shape}")
    path = output_file(path, "path", (".png",))
    with atomic_path(path) as tmp:
        Image.fromarray(to_srgb8(a)).save(tmp, format="PNG")
    return path


def render_sequence(renderer: Renderer, scenes, out_dir, *, count: int | None = None, video: str | None = None,
                    fps: int = 30, progress: bool = True) -> list[Path]:
    """Render an iterable of scenes to ``out_dir/frame_0000.png`` … with progress on stderr (a bar on a
    terminal, plain lines in a log: :mod:`wavephys.core.progress`).

    ``video`` (a file name in ``out_dir``, e.g. ``"water.mp4"``) also writes a video when
    imageio with imageio-ffmpeg is installed; otherwise a note says so and frames remain.
    Returns the frame paths.

    Parameters
    ----------
    renderer : Renderer
        The renderer that draws each scene.
    scenes : iterable of Scene
        The frames' scenes (a list, or any iterable when ``count`` is given; not a string).
    out_dir : str or os.PathLike
        Folder the frames (and the video) are written to.
    count : int, optional, keyword-only
        Number of frames to render, >= 1; at most this many scenes are taken from ``scenes`` (default: all,
        ``len(scenes)``).
    video : str, optional, keyword-only
        File name of a video in ``out_dir``, non-empty, ending in one of ``VIDEO_SUFFIXES`` (.mp4, .gif, .webm,
        .mov, .mkv, .avi) (default: no video).
    fps : int, optional, keyword-only
        Frames per second of the video, >= 1 (default 30).
    progress : bool, optional, keyword-only
        Whether to show progress on stderr (default True).

    Returns
    -------
    list of pathlib.Path
        The frame paths, ``out_dir/frame_0000.png`` …, in order.

    Raises
    ------
    TypeError
        When ``scenes`` is not an iterable, or ``video`` is not a non-empty file name.
    """
    check_instance("renderer", renderer, Renderer, "optics.rendering.Renderer")
    out = output_folder(out_dir, "out_dir")
    check_int("fps", fps, lo=1)
    check_bool("progress", progress)
    if not hasattr(scenes, "__iter__") or isinstance(scenes, (str, bytes)):
        raise TypeError(f"scenes must be an iterable of optics.rendering.Scene, got {describe(scenes)}")
    if video is not None:
        if not isinstance(video, str) or not video.strip():
            raise TypeError(f"video must be a file name such as 'water.mp4', got {describe(video)}")
        output_file(out / video, "video", VIDEO_SUFFIXES)
    scenes = list(scenes) if count is None else scenes
    total = len(scenes) if count is None else check_int("count", count, lo=1)
    paths = []
    writer = None
    if video:
        try:
            import imageio.v2 as imageio  # optional

            writer = imageio.get_writer(out / video, fps=fps)
        except Exception as exc:  # missing imageio or ffmpeg
            print(f"\nno video ({type(exc).__name__}: {exc}); install imageio imageio-ffmpeg. Frames are written.",
                  file=sys.stderr)
    try:
        with Progress(total, "frames", enabled=progress) as bar:
            for i, scene in enumerate(scenes):
                if i >= total:
                    break
                img = renderer.render(scene)
                paths.append(save_png(img, out / f"frame_{i:04d}.png"))
                if writer is not None:
                    writer.append_data(to_srgb8(img))
                bar.update()
    finally:
        if writer is not None:
            writer.close()
    return paths
