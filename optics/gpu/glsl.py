"""GLSL written once for every shader of the optics: texel sampling and the exact optics.

The float64 counterparts are :func:`wavephys.core.sampling.bilinear` (the cell-centred
convention: texel (i, j)'s centre at texel coordinate (i, j)),
:func:`optics.light.fresnel.reflectance_exact` and :func:`optics.light.directions.refract`;
``tests/shaders/test_shaders.py`` checks each GLSL function against them.
"""

from __future__ import annotations

__all__ = ["GLSL_SAMPLING", "GLSL_OPTICS", "GLSL_FRESNEL_FORMS"]

GLSL_SAMPLING = """
vec4 bilinear_texel(sampler2D t, ivec2 size, vec2 u, bvec2 wrap) {
    // u: texel coordinates (texel (i, j)'s centre at (i, j)); per axis periodic (wrap) or clamped
    vec2 f = floor(u);
    vec2 w = u - f;
    vec2 s = vec2(size);
    vec2 fw = f - s * floor(f / s);  // f mod size, >= 0 (GLSL's % is undefined for negative ints)
    ivec2 i = ivec2(f), iw = ivec2(fw);
    ivec2 i0 = ivec2(wrap.x ? iw.x : clamp(i.x, 0, size.x - 1), wrap.y ? iw.y : clamp(i.y, 0, size.y - 1));
    ivec2 i1 = ivec2(wrap.x ? (iw.x + 1) % size.x : clamp(i.x + 1, 0, size.x - 1),
                     wrap.y ? (iw.y + 1) % size.y : clamp(i.y + 1, 0, size.y - 1));
    vec4 a = texelFetch(t, ivec2(i0.x, i0.y), 0);
    vec4 b = texelFetch(t, ivec2(i1.x, i0.y), 0);
    vec4 c = texelFetch(t, ivec2(i0.x, i1.y), 0);
    vec4 d = texelFetch(t, ivec2(i1.x, i1.y), 0);
    return (a * (1.0 - w.x) + b * w.x) * (1.0 - w.y) + (c * (1.0 - w.x) + d * w.x) * w.y;
}
vec4 bilinear_at(sampler2D t, ivec2 size, vec2 xy, float extent, bool wrap) {
    // xy: metres on a square of side extent centred on the origin (the Grid convention)
    return bilinear_texel(t, size, (xy / extent + 0.5) * vec2(size) - 0.5, bvec2(wrap));
}
"""
"""GLSL: ``bilinear_texel(t, size, u, wrap)`` samples texture ``t`` bilinearly at texel
coordinates ``u`` (periodic or clamped per axis of ``wrap``) with ``texelFetch``;
``bilinear_at(t, size, xy, extent, wrap)`` at a point ``xy`` (m) of a square of side
``extent`` centred on the origin, the library's :class:`wavephys.core.grid.Grid` convention."""

GLSL_OPTICS = """
float fresnel_exact(float cos_i, float n1, float n2) {  // unpolarized dielectric reflectance
    float c = clamp(cos_i, 0.0, 1.0);
    float sin_t2 = (n1 / n2) * (n1 / n2) * (1.0 - c * c);
    if (sin_t2 >= 1.0) return 1.0;
    float ct = sqrt(max(1.0 - sin_t2, 0.0));
    float rs = (n1 * c - n2 * ct) / max(n1 * c + n2 * ct, 1e-30);
    float rp = (n1 * ct - n2 * c) / max(n1 * ct + n2 * c, 1e-30);
    return 0.5 * (rs * rs + rp * rp);
}
vec3 refract_dir(vec3 d, vec3 n, float eta) {  // Snell; n faces against d, eta = n1/n2; vec3(0) under TIR
    float c = -dot(d, n);
    float k = 1.0 - eta * eta * (1.0 - c * c);
    if (k < 0.0) return vec3(0.0);
    return normalize(eta * d + (eta * c - sqrt(k)) * n);
}
float fresnel_schlick(float cos_i, float n1, float n2) {  // cos(theta_t) from the denser side, 1 under TIR
    float c = clamp(cos_i, 0.0, 1.0);
    float f = (n1 - n2) / (n1 + n2);
    if (n1 > n2) {
        float sin_t2 = (n1 / n2) * (n1 / n2) * (1.0 - c * c);
        if (sin_t2 >= 1.0) return 1.0;
        c = sqrt(max(1.0 - sin_t2, 0.0));
    }
    return f * f + (1.0 - f * f) * pow(1.0 - c, 5.0);
}
float fresnel_jensen_golias(float cos_i) { return 1.0 / pow(1.0 + clamp(cos_i, 0.0, 1.0), 8.0); }
float fresnel_loviscach(float cos_i) { return clamp(1.0 - 2.5 * clamp(cos_i, 0.0, 1.0), 0.0, 1.0); }
float fresnel_lut(float cos_i, float n1, float n2) {  // the exact R at 64 nodes, linearly interpolated
    float u = clamp(cos_i, 0.0, 1.0) * 63.0;
    float i = clamp(floor(u), 0.0, 62.0);
    float a = fresnel_exact(i / 63.0, n1, n2), b = fresnel_exact((i + 1.0) / 63.0, n1, n2);
    return mix(a, b, u - i);
}
float fresnel_form(int form, float cos_i, float n1, float n2) {  // GLSL_FRESNEL_FORMS' order
    if (form == 1) return fresnel_schlick(cos_i, n1, n2);
    if (form == 2) return fresnel_jensen_golias(cos_i);
    if (form == 3) return fresnel_loviscach(cos_i);
    if (form == 4) return fresnel_lut(cos_i, n1, n2);
    return fresnel_exact(cos_i, n1, n2);
}
"""
"""GLSL: ``fresnel_exact(cos_i, n1, n2)``, each shader form of the Fresnel family
(``fresnel_schlick``, ``fresnel_jensen_golias``, ``fresnel_loviscach``, ``fresnel_lut``: the
float64 :data:`optics.light.fresnel.REFLECTANCE_METHODS`), ``fresnel_form(form, cos_i, n1, n2)``
choosing one by its index in :data:`GLSL_FRESNEL_FORMS`, and ``refract_dir(d, n, eta)`` (vec3(0)
under total internal reflection, as GLSL's ``refract``). Both pass their shader checks (``tests/shaders/test_shaders.py``)."""

GLSL_FRESNEL_FORMS = ("exact", "schlick", "jensen_golias", "loviscach", "lut")
"""The Fresnel forms the GLSL draws, in ``fresnel_form``'s order (names of
:data:`optics.light.fresnel.REFLECTANCE_METHODS`; the LUT at its default 64 entries)."""
