"""Cheap surface models that engines ship, measured against the wave physics.

* :mod:`~wavephys.surfaces.noise` — gradient and value noise, fBm, the Schneider &
  Westermann base surface, normals three ways (``wavephys.noise``);
* :mod:`~wavephys.surfaces.gerstner` — sums of Gerstner (trochoidal) waves with exact
  normals and Jacobian (``wavephys.gerstner``);
* :mod:`~wavephys.surfaces.choppy` — Tessendorf's choppy horizontal displacement of a
  spectral sea, its Jacobian and foam (``wavephys.choppy``);
* :mod:`~wavephys.surfaces.resample` — displaced surfaces back to heights on a
  :class:`~wavephys.Grid`, the form the rest of the library consumes.
"""

from wavephys.surfaces.choppy import accumulate_foam, displacement, foam, jacobian
from wavephys.surfaces.gerstner import GerstnerWaves, crest_comparison
from wavephys.surfaces.noise import NoiseSea, fbm, gradient_noise, value_noise
from wavephys.surfaces.resample import map_jacobian, resample_heights

__all__ = ["SEA_MODELS", "GerstnerWaves", "NoiseSea", "accumulate_foam", "crest_comparison", "displacement", "fbm", "foam",
           "gradient_noise", "jacobian", "map_jacobian", "resample_heights", "value_noise"]

SEA_MODELS = {"gerstner": GerstnerWaves, "choppy": displacement, "noise": NoiseSea}
"""The cheap sea models this package ships, by name (a sum of Gerstner waves, Tessendorf's choppy
displacement of a spectral sea, procedural fBm): what consumers offer or decline. The planner's
surface term offers each (:data:`wavephys.planner.model.SURFACE_OPTIONS`) or names why not
(:data:`wavephys.planner.model.SURFACES_NOT_PLANNED`); a test keeps every model in one of them."""
