"""Exact results the caustics methods are checked against (docs/physics.md §2.4).

For η = a cos kx lit vertically with small slopes, the floor irradiance at depth z is
E(X) = E0/|1 − (z/z_f) cos kx| at X = x − (z/z_f) sin(kx)/k with the focal depth
z_f = n/((n − 1) a k²) (:func:`sinusoid_irradiance`, :func:`focal_depth`);
:func:`first_fold_depth` finds where the traced mesh of any surface first folds;
:func:`flat_irradiance` is the floor's light under flat water (the E₀ of every method's E/E₀).
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

from optics.caustics.common import land, surface_fields
from optics.light.fresnel import N_AIR, N_WATER, reflectance_exact
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_array, check_instance, check_scalar

__all__ = ["sinusoid_irradiance", "focal_depth", "first_fold_depth", "flat_irradiance"]


def flat_irradiance(sun_elevation: float, n_air: float = N_AIR, n_water: float = N_WATER) -> float:
    """E₀: the floor irradiance under flat water relative to the sun's irradiance on a horizontal
    plane above it, the Fresnel transmittance 1 − R at the sun's incidence 90° − elevation
    (the refracted beam's narrowing and the incidence's widening cancel on a horizontal floor).

    Parameters
    ----------
    sun_elevation : float
        Degrees above the horizon, in (0, 90].
    n_air, n_water : float
        Refractive indices.

    Returns
    -------
    float
        1 − R(cos θᵢ = sin e), in (0, 1).

    Examples
    --------
    >>> round(flat_irradiance(90.0), 5)
    0.97967
    """
    e = check_scalar("sun_elevation", sun_elevation, lo=0.0, hi=90.0, lo_open=True)
    check_scalar("n_air", n_air, lo=1.0, hi=10.0)
    check_scalar("n_water", n_water, lo=1.0, hi=10.0)
    return 1.0 - float(reflectance_exact(math.sin(math.radians(e)), n_air, n_water))


def focal_depth(amplitude, wavenumber, n_water=N_WATER):
    """z_f = n/((n − 1) a k²): the depth where the crests of η = a cos kx focus a vertical sun.

    Parameters
    ----------
    amplitude : float
        a, m, > 0.
    wavenumber : float
        k, rad/m, > 0.
    n_water : float
        Refractive index, > 1.

    Returns
    -------
    float
        z_f, m.

    References
    ----------
    J. Loviscach, "Complex water effects at interactive frame rates", WSCG 2003 (the focusing
    of a sinusoid's crests); docs/physics.md §2.4 derives the paraxial map.
    """
    check_scalar("amplitude", amplitude, lo=0.0, lo_open=True)
    check_scalar("wavenumber", wavenumber, lo=0.0, lo_open=True)
    check_scalar("n_water", n_water, lo=1.0, lo_open=True)
    return n_water / ((n_water - 1.0) * amplitude * wavenumber**2)


def sinusoid_irradiance(x, amplitude, wavenumber, depth, n_water=N_WATER):
    """Paraxial floor irradiance under η = a cos kx lit vertically (small slopes), E/E0.

    Parameters
    ----------
    x : array_like
        Surface positions, m.
    amplitude, wavenumber : float
        a (m) and k (rad/m), > 0.
    depth : float
        Floor depth z, m, ≥ 0.
    n_water : float
        Refractive index, > 1.

    Returns
    -------
    (X, E)
        The landing points X = x − (z/z_f) sin(kx)/k, m, and E = 1/|1 − (z/z_f) cos kx| there,
        with z_f = n/((n − 1) a k²) (:func:`focal_depth`).

    References
    ----------
    J. Loviscach, "Complex water effects at interactive frame rates", WSCG 2003 (the focusing
    of a sinusoid's crests); docs/physics.md §2.4 derives the paraxial map.
    """
    check_array("x", x)
    check_scalar("depth", depth, lo=0.0)
    zf = focal_depth(amplitude, wavenumber, n_water)
    r = depth / zf
    x = np.asarray(x, np.float64)
    return x - r * np.sin(wavenumber * x) / wavenumber, 1.0 / np.abs(1.0 - r * np.cos(wavenumber * x))


def first_fold_depth(eta, grid: Grid, sun=(0.0, 0.0, 1.0), n_water: float = N_WATER, max_depth: float = 1e4,
                     tolerance: float = 1e-4):
    """The shallowest floor depth (m) at which the traced surface mesh folds over.

    Above it every surface cell lands as a non-inverted quad (irradiance finite); at it
    the first caustic (a focus) forms. Bisection on the depth to relative ``tolerance``
    (in (0, 0.1]; a bounded number of steps). For η = a cos kx it measures the focal depth
    z_f. ``inf`` if no fold occurs above ``max_depth``.

    Parameters
    ----------
    eta : array_like (n, n)
        Surface heights on ``grid``, m, periodic.
    grid : Grid
    sun : array_like (3,)
        Direction towards the sun, pointing up.
    n_water : float
        Refractive index, > 1.
    max_depth : float
        Deepest floor searched, m, > 0.
    tolerance : float
        Relative tolerance of the bisection, in (0, 0.1].

    Returns
    -------
    float
        The depth, m (inf: no fold above ``max_depth``).
    """
    check_instance("grid", grid, Grid, "wavephys.Grid")
    n = grid.n
    check_array("eta", eta, ndim=2, shape_tail=(n, n))
    check_array("sun", sun, ndim=1, shape_tail=(3,))
    if not np.asarray(sun, float)[2] > 0:
        raise ValueError(f"sun must point up (z > 0), got {np.asarray(sun, float).tolist()}")
    check_scalar("n_water", n_water, lo=1.0, lo_open=True)
    check_scalar("max_depth", max_depth, lo=0.0, lo_open=True)
    check_scalar("tolerance", tolerance, lo=0.0, hi=0.1, lo_open=True)
    d = jnp.asarray(-np.asarray(sun, float) / np.linalg.norm(sun), jnp.float32)
    eta, gx, gy = surface_fields(jnp.asarray(eta, jnp.float32), grid)
    h = grid.dx
    xv, yv = grid.mesh()
    corner = lambda f, a, b: jnp.roll(f, (-a, -b), (0, 1))
    corners = ((0, 0), (0, 1), (1, 0), (1, 1))

    @jax.jit
    def min_area(depth):
        X, Y, _ = land(xv, yv, eta, gx, gy, d, depth, n_water, False)
        dx_, dy_ = X - xv, Y - yv
        cx = [xv + b * h + corner(dx_, a, b) for a, b in corners]
        cy = [yv + a * h + corner(dy_, a, b) for a, b in corners]
        # signed area of the quad (0,0) → (0,1) → (1,1) → (1,0) via its diagonals
        return jnp.min(0.5 * ((cx[3] - cx[0]) * (cy[2] - cy[1]) - (cx[2] - cx[1]) * (cy[3] - cy[0])))

    if float(min_area(max_depth)) > 0:
        return math.inf
    lo, hi = 0.0, float(max_depth)
    for _ in range(int(math.ceil(math.log2(1.0 / tolerance))) + 64):  # bisection halves hi - lo each step
        if hi - lo <= tolerance * hi:
            break
        mid = 0.5 * (lo + hi)
        lo, hi = (lo, mid) if float(min_area(mid)) <= 0 else (mid, hi)
    return 0.5 * (lo + hi)
