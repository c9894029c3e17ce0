"""Rendering water volumes from two height fields (Baboud & Décoret 2006; docs/physics.md §2.5):

* :mod:`~optics.rendering.scene` — what is drawn (:class:`Scene`, :class:`Camera`,
  :class:`Effects`) and the texture convention;
* :mod:`~optics.rendering.renderer` — the headless moderngl renderer (GLSL);
* :mod:`~optics.rendering.reference` — the CPU tracer of the same model (numpy float64),
  the renderer's test oracle;
* :mod:`~optics.rendering.meshes` — the water as a displaced mesh, laid as engines lay it
  (uniform grid, clipmap rings, projected grid), and its error against the march per distance;
* :mod:`~optics.rendering.textures` — textures for other renderers (heights, normals,
  caustics, lookups) and their files.
"""

from wavephys.core.aliases import install

from optics.rendering.meshes import mesh_errors, render_mesh, water_mesh
from optics.rendering.reference import psnr, trace
from optics.rendering.renderer import Renderer, RendererUnavailable, render_sequence, save_png, to_srgb8
from optics.rendering.scene import Camera, Effects, Scene, look_at

__all__ = ["Scene", "Camera", "Effects", "look_at", "Renderer", "RendererUnavailable", "render_sequence",
           "save_png", "to_srgb8", "trace", "psnr", "water_mesh", "render_mesh", "mesh_errors"]

__getattr__ = install("optics.rendering", {"gl": "optics.gpu"}, deprecated=("gl",))  # moved in 0.3
