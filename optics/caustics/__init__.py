r"""Caustics: irradiance on the floor under a wavy surface lit by the sun (docs/physics.md §2.4).

Every method traces parallel sunlight through the height field η (periodic, on a
:class:`wavephys.Grid`), refracts it by Snell's law at the surface normal and lands it on
a flat floor at a given depth or on a ground height field. Irradiance is relative to the
sun's irradiance on a horizontal plane above the water (E0 = 1): flat water without
Fresnel loss gives 1 everywhere. The floor map is an m × m field on ``Grid(m, L)`` (the
grid convention of docs/physics.md §0).

The methods (:data:`FLOOR_IRRADIANCE_METHODS`), one module each:

* ``"beam"`` — :func:`floor_irradiance_beam`, beam tracing by exact rasterization: every
  surface cell's two triangles spread their flux over their exact landed footprints;
* ``"jacobian"`` — :func:`floor_irradiance_jacobian`, the area ratio of the landing map from
  spectral curvatures, gathered per floor texel by Newton's method where one smooth sheet
  lights the floor, with the exact beam on the texels folded sheets reach (or, by option,
  the beam everywhere or a refusal by name);
* ``"gl"`` — :func:`floor_irradiance_gl`, the same beams drawn by OpenGL (moderngl) into a
  float target with additive blending, the way Loviscach and WebGL Water do it in hardware;
* ``"photon"`` — :func:`floor_irradiance_photon`, photon splatting with a bilateral filter;
* ``"reference"`` — :func:`floor_irradiance_reference`, the beam refined until two levels
  agree, with its error bound (:func:`converged_floor_irradiance`);
* ``"blinn_phong"`` — :func:`floor_irradiance_blinn_phong`, a shading trick, not a flux.

Exact facts the tests check (:mod:`optics.caustics.analytic`): flux conservation (floor
total = transmitted total, on the periodic domain, no absorption); uniform light under
flat water; the sinusoid's irradiance profile and focal depth. Adding a method: one
module with a ``floor_irradiance_<name>`` function, and its entry in the mapping below.
"""

from optics.caustics.analytic import first_fold_depth, flat_irradiance, focal_depth, sinusoid_irradiance
from optics.caustics.beam import floor_irradiance_beam
from optics.caustics.blinn_phong import floor_irradiance_blinn_phong
from optics.caustics.common import bilateral_filter, blur_121, surface_fields
from optics.caustics.gl import floor_irradiance_gl
from optics.caustics.jacobian import CausticsFold, floor_irradiance_jacobian
from optics.caustics.rays import floor_irradiance_photon
from optics.caustics.surfaces import SURFACE_SPECTRA, random_surface
from optics.caustics.reference import ConvergedIrradiance, converged_floor_irradiance, floor_irradiance_reference
from optics.light.fresnel import N_WATER
from wavephys.core.methods import Methods

__all__ = ["FLOOR_IRRADIANCE_METHODS", "floor_irradiance", "floor_irradiance_beam", "floor_irradiance_gl",
           "floor_irradiance_jacobian", "CausticsFold",
           "floor_irradiance_photon", "floor_irradiance_reference", "converged_floor_irradiance", "ConvergedIrradiance",
           "floor_irradiance_blinn_phong", "random_surface", "SURFACE_SPECTRA", "first_fold_depth", "flat_irradiance", "focal_depth",
           "sinusoid_irradiance", "bilateral_filter", "blur_121"]

FLOOR_IRRADIANCE_METHODS = Methods("floor irradiance", beam=floor_irradiance_beam, jacobian=floor_irradiance_jacobian,
                                   gl=floor_irradiance_gl,
                                   photon=floor_irradiance_photon, reference=floor_irradiance_reference,
                                   blinn_phong=floor_irradiance_blinn_phong)
"""Caustics methods by name."""


def floor_irradiance(eta, grid, depth, sun=(0.0, 0.0, 1.0), method: str = "beam", *, resolution=None,
                     n_water: float = N_WATER, walls=None, **options):
    """Irradiance on the floor, relative to the sun's horizontal irradiance above water.

    Parameters
    ----------
    eta : array_like (n, n)
        Surface height η on ``grid``, m (periodic).
    grid : Grid
    depth : float or array_like (n, n)
        Depth of a flat floor below the still surface, m, > 0; or a ground height field
        z_g (m, negative below the surface, every point below the water) on the same grid.
    sun : array_like (3,)
        Direction towards the sun (any length), pointing up (z > 0).
    method : str
        A name in :data:`FLOOR_IRRADIANCE_METHODS`.
    resolution : int
        Floor map side m (default n): the map covers the same periodic square.
    n_water : float
        Refractive index of water, ≥ 1.
    walls : str or None
        The square is a tank with opaque vertical walls on these sides (``"all"``, ``"x"``,
        ``"y"``, or both side names of an axis; default None: periodic): ``beam``, ``jacobian``
        and ``reference`` trace the surface's even extension (the tank's cosine modes), lose the
        light that reaches a wall and leave the floor in a wall's shadow dark; the other methods
        refuse walls by name.
    options
        The method's own options (each method takes only its own): ``fresnel``;
        ``refine``, ``blur``, ``normals`` (beam); ``refine``, ``supersample``, ``iterations``, ``fold``, ``explain``
        (jacobian); ``refine``, ``supersample`` (gl);
        ``photons_per_texel``, ``filter_radius``, ``seed`` (photon); ``tolerance``,
        ``max_refine`` (reference); ``exponent`` (blinn_phong).

    Returns
    -------
    jax.Array (m, m)
        Floor irradiance / E0 (dimensionless), at the cell centres of ``Grid(m, L)``.

    Examples
    --------
    >>> import math, jax.numpy as jnp
    >>> from wavephys import Grid
    >>> grid = Grid(32, 1.0)
    >>> x, _ = grid.mesh()
    >>> light = floor_irradiance(0.002 * jnp.cos(2 * math.pi * x / 0.5), grid, depth=1.0)
    >>> light.shape, round(float(light.mean()), 3)   # the flux of flat water, 1 − R(0°)
    ((32, 32), 0.98)
    """
    from wavephys.core.aliases import renamed_options

    options = renamed_options("floor_irradiance", options, {"samples": "refine"}, since="0.2")
    if walls is not None:
        import inspect

        if "walls" not in inspect.signature(FLOOR_IRRADIANCE_METHODS.check(method)).parameters:
            takes = [k for k, f in FLOOR_IRRADIANCE_METHODS.items() if "walls" in inspect.signature(f).parameters]
            raise ValueError(f"walls: the {method!r} caustics method traces a periodic square only; "
                             f"{', '.join(takes)} trace a walled tank")
        options["walls"] = walls
    return FLOOR_IRRADIANCE_METHODS(method, eta, grid, depth, sun, resolution=resolution, n_water=n_water, **options)
