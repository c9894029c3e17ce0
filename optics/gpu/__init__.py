"""The GPU foundation of the optics: the headless OpenGL context and the GLSL the shaders share.

Below both GPU users (:mod:`optics.caustics.gl`, :mod:`optics.rendering.renderer`) and the
shader checks (:mod:`optics.shaders`), so each primitive is written once:

* :func:`gl_context` — an OpenGL 3.3 core context through EGL without a display
  (:mod:`optics.gpu.context`);
* :data:`GLSL_SAMPLING` — bilinear texel sampling in the library's cell-centred convention,
  clamped or periodic per axis (the GPU twin of :func:`wavephys.core.sampling.bilinear`);
* :data:`GLSL_OPTICS` — the exact Fresnel reflectance and Snell refraction
  (:mod:`optics.gpu.glsl`).
"""

from optics.gpu.context import EGL_PACKAGES, RendererUnavailable, gl_context
from optics.gpu.glsl import GLSL_FRESNEL_FORMS, GLSL_OPTICS, GLSL_SAMPLING

__all__ = ["RendererUnavailable", "EGL_PACKAGES", "gl_context", "GLSL_OPTICS", "GLSL_SAMPLING", "GLSL_FRESNEL_FORMS"]
