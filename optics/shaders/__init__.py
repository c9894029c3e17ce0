"""Check a user's GLSL against the physics: Fresnel, refraction and reflection, absorption, normals.

:func:`check_glsl` compiles the user's function into a small fragment program on the shared
headless context (llvmpipe on a CPU-only machine, the GPU elsewhere), evaluates it over its
whole input domain (every angle from above and below the surface, path lengths, normals,
height textures), compares the results with the library's float64 physics and returns a
:class:`ShaderReport`: the worst error and the input where it occurs, and a one-line cause
when the error matches a known mistake (no total internal reflection from below, the index
ratio inverted, F0 from the wrong indices, the wrong ray's cos θ, a clamp hiding a negative
cosine, an unnormalized vector, the green channel of a normal map flipped, …).

>>> from optics.shaders import check_glsl
>>> src = '''
... float schlick(float c, float n1, float n2) {
...     float f0 = pow((n1 - n2) / (n1 + n2), 2.0);
...     return f0 + (1.0 - f0) * pow(1.0 - c, 5.0);
... }'''
>>> r = check_glsl(src, "schlick", "fresnel", form="schlick")
>>> r.ok
False
>>> r.cause.split(":")[0]
'no total internal reflection from below'

The checks are entries of :data:`SHADER_CHECKS` (:mod:`optics.shaders.checks`); the same
check runs from pytest (``wavephys_check.glsl``) and from ``wavephys check --glsl``.
"""

from optics.shaders.check import ShaderReport, check_glsl, describe_check
from optics.shaders.checks import ROLES, SHADER_CHECKS
from optics.shaders.glsl import GLSLError
from optics.shaders.hlsl import TRANSLATOR_PACKAGES, TranslatorMissing
from optics.shaders.source import LANGUAGES

__all__ = ["check_glsl", "ShaderReport", "SHADER_CHECKS", "ROLES", "GLSLError", "describe_check", "TranslatorMissing",
           "TRANSLATOR_PACKAGES", "LANGUAGES"]
