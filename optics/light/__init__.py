"""Light at and in the water: ray directions (:mod:`~optics.light.directions`), Fresnel
reflectance exact and approximate (:mod:`~optics.light.fresnel`), and absorption,
Beer–Lambert and spectral (:mod:`~optics.light.attenuation`)."""
