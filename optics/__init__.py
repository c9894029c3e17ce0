"""optics: light at and under the water surface (reflection, refraction, Fresnel,
absorption, caustics, textures, rendering).

Empty for now: the optics issue fills it. The package exists so that the project layout
and install are fixed from the start.
"""

__all__: list[str] = []
