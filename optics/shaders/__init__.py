"""Check a user's shader function against the physics: Fresnel, refraction and reflection, absorption, normals.

:func:`check_glsl` reads the user's function as shipped (GLSL, GLSL ES, WebGL, Shadertoy, Godot,
or HLSL through glslang and SPIRV-Cross), compiles it into a small fragment program on the shared
headless context (llvmpipe on a CPU-only machine, the GPU elsewhere), evaluates it over its
whole input domain (every angle from above and below the surface, path lengths, normals,
height textures) and explains its output by fitted models (:mod:`optics.shaders.models`): the
correct forms with the constants water allows (its index over the visible spectrum, 0–30 °C,
fresh or sea), and the mistakes real code makes, each with its own constants. It returns a
:class:`ShaderReport`: the worst error and the input where it occurs, what the function computes
(the fitted form and constants) and, on failure, the cause with its numbers, per side (no total
internal reflection from below, the index ratio inverted, F0 from the wrong indices, an
artistic curve by its fitted shape, the wrong ray's cos θ, a green channel flipped, …).

>>> from optics.shaders import check_glsl
>>> src = '''
... float schlick(float c, float n1, float n2) {
...     float f0 = pow((n1 - n2) / (n1 + n2), 2.0);
...     return f0 + (1.0 - f0) * pow(1.0 - c, 5.0);
... }'''
>>> r = check_glsl(src, "schlick", "fresnel")
>>> r.ok
False
>>> [part.split(":")[0] for part in r.cause.split("; ")][:2]
['above', 'below']
>>> "below: no total internal reflection from below" in r.cause
True

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
