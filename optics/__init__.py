"""optics: light at and under the water surface, built on wavephys.

* :mod:`optics.gpu` — the headless OpenGL context and the GLSL every shader shares;
* :mod:`optics.light` — reflection and refraction directions, Fresnel (exact and the
  shader approximations), Beer–Lambert and spectral absorption (colour-science);
* :mod:`optics.caustics` — irradiance on the floor (beam, photons, reference, Blinn–Phong);
* :mod:`optics.rendering` — scenes, the headless moderngl renderer, its CPU reference
  tracer, and texture export;
* :mod:`optics.shaders` — a user's GLSL checked against the physics;
* :mod:`optics.checks` — the optics validations (rows of ``wavephys validate``).

Submodules load on first use, so ``import optics`` stays light; ``optics.fresnel`` and
the other old module names still work.
"""

import importlib

from wavephys.core.aliases import install as _install

_SUBPACKAGES = ("gpu", "light", "caustics", "rendering", "shaders", "checks")
__all__ = list(_SUBPACKAGES)

_legacy = _install(__name__, {
    "directions": "optics.light.directions",
    "fresnel": "optics.light.fresnel",
    "attenuation": "optics.light.attenuation",
    "scene": "optics.rendering.scene",
    "render": "optics.rendering.renderer",
    "reference": "optics.rendering.reference",
    "textures": "optics.rendering.textures",
    "scenes": "wavephys.app.scenes",  # the built-in scenes moved to the application layer in 0.2
})  # every old name warns when imported (removed in 0.4)


def __getattr__(name):
    if name in _SUBPACKAGES:
        return importlib.import_module(f"optics.{name}")
    return _legacy(name)


def __dir__():
    return sorted(set(globals()) | set(_SUBPACKAGES))
