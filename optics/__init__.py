"""optics: light at and under the water surface.

Modules: ``directions`` (reflect, refract), ``fresnel`` (exact and shader approximations),
``attenuation`` (Beer–Lambert, spectral pure-water absorption via colour-science),
``caustics`` (floor irradiance: beam, photons, Blinn–Phong, reference), ``textures``
(height/normal/caustics/lookup export), ``scene`` and ``scenes`` (what is rendered, and
the built-in pool, shore and ship), ``render`` (the headless moderngl renderer),
``reference`` (the CPU tracer of the same model) and ``checks`` (validation rows).
Submodules are imported on use, so ``import optics`` stays light.
"""

__all__ = ["directions", "fresnel", "attenuation", "caustics", "textures", "scene", "scenes", "render", "reference",
           "checks"]
