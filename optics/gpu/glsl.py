"""GLSL written once for every shader of the optics: texel sampling and the exact optics.

The float64 counterparts are :func:`wavephys.core.sampling.bilinear` (the cell-centred
convention: texel (i, j)'s centre at texel coordinate (i, j)), the Fresnel family
(:data:`optics.light.fresnel.REFLECTANCE_METHODS`, whose GLSL forms live beside their Python
functions and are generated in here) and :func:`optics.light.directions.refract`;
``tests/shaders/test_shaders.py`` checks each GLSL function against them.
"""

from __future__ import annotations

from optics.light.fresnel import REFLECTANCE_METHODS
from wavephys.core.methods import glsl_family

__all__ = ["GLSL_SAMPLING", "GLSL_OPTICS", "GLSL_FRESNEL_FORMS"]

GLSL_SAMPLING = """
vec4 bilinear_texel_lod(sampler2D t, ivec2 size, vec2 u, bvec2 wrap, int lod) {
    // u: texel coordinates (texel (i, j)'s centre at (i, j)) of mip level lod, whose size is size;
    // per axis periodic (wrap) or clamped
    vec2 f = floor(u);
    vec2 w = u - f;
    vec2 s = vec2(size);
    vec2 fw = f - s * floor(f / s);  // f mod size, >= 0 (GLSL's % is undefined for negative ints)
    ivec2 i = ivec2(f), iw = ivec2(fw);
    ivec2 i0 = ivec2(wrap.x ? iw.x : clamp(i.x, 0, size.x - 1), wrap.y ? iw.y : clamp(i.y, 0, size.y - 1));
    ivec2 i1 = ivec2(wrap.x ? (iw.x + 1) % size.x : clamp(i.x + 1, 0, size.x - 1),
                     wrap.y ? (iw.y + 1) % size.y : clamp(i.y + 1, 0, size.y - 1));
    vec4 a = texelFetch(t, ivec2(i0.x, i0.y), lod);
    vec4 b = texelFetch(t, ivec2(i1.x, i0.y), lod);
    vec4 c = texelFetch(t, ivec2(i0.x, i1.y), lod);
    vec4 d = texelFetch(t, ivec2(i1.x, i1.y), lod);
    return (a * (1.0 - w.x) + b * w.x) * (1.0 - w.y) + (c * (1.0 - w.x) + d * w.x) * w.y;
}
vec4 bilinear_texel(sampler2D t, ivec2 size, vec2 u, bvec2 wrap) { return bilinear_texel_lod(t, size, u, wrap, 0); }
vec4 bilinear_at(sampler2D t, ivec2 size, vec2 xy, float extent, bool wrap) {
    // xy: metres on a square of side extent centred on the origin (the Grid convention)
    return bilinear_texel(t, size, (xy / extent + 0.5) * vec2(size) - 0.5, bvec2(wrap));
}
"""
"""GLSL: ``bilinear_texel(t, size, u, wrap)`` samples texture ``t`` bilinearly at texel
coordinates ``u`` (periodic or clamped per axis of ``wrap``) with ``texelFetch``
(``bilinear_texel_lod(t, size, u, wrap, lod)`` at a mip level, ``size`` that level's);
``bilinear_at(t, size, xy, extent, wrap)`` at a point ``xy`` (m) of a square of side
``extent`` centred on the origin, the library's :class:`wavephys.core.grid.Grid` convention."""

_REFRACT = """
vec3 refract_dir(vec3 d, vec3 n, float eta) {  // Snell; n faces against d, eta = n1/n2; vec3(0) under TIR
    float c = -dot(d, n);
    float k = 1.0 - eta * eta * (1.0 - c * c);
    if (k < 0.0) return vec3(0.0);
    return normalize(eta * d + (eta * c - sqrt(k)) * n);
}
"""

GLSL_FRESNEL_FORMS = tuple(REFLECTANCE_METHODS.glsl_forms)
"""The Fresnel forms the GLSL draws, in ``fresnel_form``'s order: the methods of
:data:`optics.light.fresnel.REFLECTANCE_METHODS` with a shader form (each registered beside its Python
function by :func:`wavephys.core.methods.shader_form`; the LUT at its default 64 entries)."""

GLSL_OPTICS = glsl_family(REFLECTANCE_METHODS, "fresnel_form", "float cos_i, float n1, float n2", "cos_i, n1, n2") \
    + _REFRACT
"""GLSL, generated from the Fresnel family's registry: each shader form of
:data:`optics.light.fresnel.REFLECTANCE_METHODS` (``fresnel_exact``, ``fresnel_schlick``,
``fresnel_jensen_golias``, ``fresnel_loviscach``, ``fresnel_lut``, each ``(cos_i, n1, n2)``),
``fresnel_form(form, cos_i, n1, n2)`` choosing one by its index in :data:`GLSL_FRESNEL_FORMS`, and
``refract_dir(d, n, eta)`` (vec3(0) under total internal reflection, as GLSL's ``refract``). Each passes
its shader check against its float64 form (``tests/shaders/test_shaders.py``)."""
