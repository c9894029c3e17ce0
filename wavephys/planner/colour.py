"""The colour terms' error bounds: each optics option over the scene's own angles and water paths.

The shading (:func:`wavephys.planner.runner.shade`) is C = R + (1 − R)·T·albedo·E/E₀; a Fresnel
form changes R, an absorption method T. :func:`colour_errors` bounds each change over the
incidence angles the view meets (:func:`incidence_range`) and the water paths it sees.
"""

from __future__ import annotations

__internal__ = True  # the planner's own models: used through plan(), not fuzzed as public API

import math

import numpy as np

from wavephys.core.inputs import check_instance
from wavephys.planner.scene import Scene
from wavephys.planner.spectrum import scene_spectrum

__all__ = ["incidence_range", "colour_errors"]


def incidence_range(scene: Scene) -> tuple[float, float]:
    """Incidence angles (degrees) the view meets: the view's own ± the steepest facet tilt.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    (float, float)
        The lowest and highest incidence angle, degrees from the normal, within [0, 90].
    """
    slope = scene_spectrum(scene).max_slope
    tilt = math.degrees(math.atan(min(slope, 50.0)))
    theta = 90.0 - scene.view_elevation
    return max(0.0, theta - tilt), min(90.0, theta + tilt)


def colour_errors(scene: Scene) -> dict:
    """Bounds on the colour error ([0, 1] scale) of each Fresnel form and absorption method:
    {"fresnel": {form: max ΔR}, "absorption": {method: albedo · max ΔT}, "floor": the largest
    albedo · T} over the scene's incidence range and water paths. Every form of the Fresnel
    family (:data:`optics.light.fresnel.REFLECTANCE_METHODS`) and every absorption method
    (:data:`optics.light.attenuation.WATER_TRANSMITTANCE_METHODS`) is bounded.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    dict
        ``{"fresnel": {form: float}, "absorption": {method: float}, "floor": float}``, on the [0, 1]
        colour scale.
    """
    check_instance("scene", scene, Scene, "wavephys.planner.Scene")
    import jax.numpy as jnp

    from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS
    from optics.light.fresnel import REFLECTANCE_METHODS, reflectance
    from wavephys.planner.runner import FLOOR_ALBEDO, path_range, transmittance

    lo, hi = incidence_range(scene)
    cos = jnp.asarray(np.cos(np.radians(np.linspace(lo, hi, 4001))), jnp.float32)
    floor = 0.0
    exact = np.asarray(reflectance(cos, method="exact"), np.float64)
    fresnel = {f: float(np.abs(np.asarray(reflectance(cos, method=f), np.float64) - exact).max())
               for f in REFLECTANCE_METHODS}
    absorption = {m: 0.0 for m in WATER_TRANSMITTANCE_METHODS}
    if not math.isinf(scene.depth):
        d = np.linspace(*path_range(scene), 512)
        spectral = transmittance(scene, "spectral", d)
        for m in WATER_TRANSMITTANCE_METHODS:
            if m != "spectral":
                absorption[m] = float(FLOOR_ALBEDO * np.abs(transmittance(scene, m, d) - spectral).max())
        floor = FLOOR_ALBEDO * float(max(transmittance(scene, m, d[:1]).max() for m in WATER_TRANSMITTANCE_METHODS))
    return dict(fresnel=fresnel, absorption=absorption, floor=floor)
