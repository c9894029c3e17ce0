"""The headless OpenGL context and the GLSL the shaders share.

One place for what the GPU code of :mod:`optics.rendering.renderer` and
:mod:`optics.caustics.gl` both need: an OpenGL 3.3 core context through EGL without a
display (Mesa llvmpipe on a CPU-only machine, the GPU driver elsewhere, unchanged) and the
exact Fresnel reflectance and Snell refraction written once in GLSL (their float64
counterparts are :func:`optics.light.fresnel.reflectance_exact` and
:func:`optics.light.directions.refract`).
"""

from __future__ import annotations

__all__ = ["RendererUnavailable", "EGL_PACKAGES", "gl_context", "GLSL_OPTICS"]

EGL_PACKAGES = "libegl1 libegl-mesa0 libgl1-mesa-dri"
"""Debian/Ubuntu packages that provide headless EGL with Mesa (llvmpipe on CPU-only machines)."""


class RendererUnavailable(RuntimeError):
    """No OpenGL 3.3 context could be created (headless EGL missing or broken)."""


def gl_context():
    """A standalone OpenGL 3.3 core context through EGL, or :class:`RendererUnavailable` saying
    which packages to install."""
    try:
        import moderngl
    except ImportError as exc:  # pragma: no cover - moderngl is a dependency
        raise RendererUnavailable(f"moderngl is not installed ({exc}); pip install moderngl") from exc
    try:
        return moderngl.create_context(standalone=True, backend="egl", require=330)
    except Exception as exc:
        raise RendererUnavailable(
            f"no headless OpenGL 3.3 context through EGL ({type(exc).__name__}: {exc}). "
            f"Install the EGL and Mesa packages: apt-get install {EGL_PACKAGES} "
            f"(or your GPU driver's EGL library)") from exc


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
"""
"""GLSL: ``fresnel_exact(cos_i, n1, n2)`` and ``refract_dir(d, n, eta)`` (vec3(0) under total internal
reflection, as GLSL's ``refract``). Both pass their shader checks (``tests/test_shaders.py``)."""
