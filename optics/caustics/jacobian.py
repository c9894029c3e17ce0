r"""Caustics from the Jacobian of the landing map, gathered on the floor (docs/physics.md §2.4).

Below its first fold every floor point X is lit by exactly one surface point x, so the floor
irradiance is the flux that crosses z = 0 over a small patch divided by the area that patch
lands on:

.. math::

    E(X) = E_0\,T(x)\,s(x)\,\frac{\det \partial c/\partial x}{\det \partial X/\partial x},
    \qquad X(x) = x + D(x),\quad D = \frac{\eta + d}{-t_z}\,\mathbf t_h,\quad
    c(x) = x - \eta\,\frac{\mathbf s_h}{s_z}

(t the refracted direction, d the depth of the flat floor, s the sunlight's direction of travel, T the Fresnel
transmittance, s(x) = 1 where the sun reaches the surface and 0 in shadow, c where the ray
crossed z = 0: det ∂c/∂x = 1 − s_h·∇η/s_z). The slopes and curvatures of η are spectral
(exact for a band-limited surface); D, its Jacobian and the numerator are exact functions
of them (forward-mode derivatives through the refraction). The inverse map is found per
floor texel by Newton's method on the periodic cubic B-spline of D (interpolating, third
order, its derivative consistent with the values so Newton converges quadratically),
started from X − D(X).

A texel of the reference holds the average of E over the texel; the gathered E is a point
value, which differs by Δx²∇²E/24 to leading order. The map is corrected by the texel's
box filter in Fourier space (sinc(k_xΔx/2)·sinc(k_yΔx/2)), exact for its band-limited part;
towards the first fold E has peaks narrower than a texel, so the gather is made on a floor
grid ``supersample`` times finer and averaged down (``"auto"`` chooses from how fast log E
changes across a floor texel, :data:`SHARPNESS_LIMIT`, measured over surface families).

Folds (det ∂X/∂x below :data:`MIN_AREA_RATIO` somewhere on the surface, light that even an
8-fold supersampling cannot resolve, or Newton not converging) are never answered silently: ``fold="beam"`` (default) returns the
exact beam rasterization instead, ``fold="raise"`` refuses by name.
"""

from __future__ import annotations

import math
import warnings
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from optics.caustics.common import land, prepare, shadow_steps, sunlit
from optics.light.fresnel import N_WATER
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_choice, check_int
from wavephys.core.sampling import bspline
from wavephys.core.spectral import bspline_coefficients, central_gradient, spectral_derivatives

__all__ = ["floor_irradiance_jacobian", "CausticsFold", "SHARPNESS_LIMIT", "MIN_AREA_RATIO"]

SHARPNESS_LIMIT = 0.4
"""``supersample="auto"`` gathers s = 1, 2, 4 or 8 points per floor texel side, the fewest with
β/s ≤ this, β = Δx·max|∇_X log E| (how much log E changes across one floor texel, from the
surface's own fields). Measured over the surface families (docs/physics.md §2.4): at
β/s ≤ 0.4 the map stays within 0.5 % of the peak; past s = 8 the map counts as folded."""

MIN_AREA_RATIO = 0.02
"""Smallest det ∂X/∂x (E up to 50 E0) the method answers; below it the map counts as folded."""

NEWTON_TOLERANCE = 1e-3
"""Largest Newton residual |X(x) − X| accepted, in floor texels (converged ones reach 1e-5–1e-4)."""


class CausticsFold(ValueError):
    """The surface's landing map folds (or comes too close to folding) for the Jacobian method."""


@jax.jit
def _derivatives(eta, dx):
    """First program (FFT first, the CPU note in wavephys.core.spectral): slopes and curvatures."""
    return spectral_derivatives(eta, dx)


@partial(jax.jit, static_argnames=("fresnel", "shadow"))
def _fields(eta, derivs, d, depth, n_water, fresnel, shadow, length):
    """D = X − x (2 planes), the numerator T·s·det ∂c/∂x, det ∂X/∂x and how fast E changes on
    the floor (max |J⁻ᵀ∇ log E|, 1/m), on the surface grid."""
    gx, gy, hxx, hxy, hyy = derivs
    zero = jnp.zeros_like(eta)

    def landing(e, sx, sy):
        return land(zero, zero, e, sx, sy, d, depth, n_water, fresnel)

    (dxx, dyx, trans), (dxx_x, dyx_x, _) = jax.jvp(landing, (eta, gx, gy), (gx, hxx, hxy))
    _, (dxx_y, dyx_y, _) = jax.jvp(landing, (eta, gx, gy), (gy, hxy, hyy))
    a, b, c, e = 1.0 + dxx_x, dxx_y, dyx_x, 1.0 + dyx_y
    det = a * e - b * c
    grid = Grid(eta.shape[-1], length)
    lit = sunlit(eta, grid, d, shadow)
    numerator = trans * lit * (1.0 - (d[0] * gx + d[1] * gy) / d[2])
    # how fast E changes on the floor: |J⁻ᵀ ∇ log E| (1/m), E at the surface samples (lit ones)
    log_e = jnp.log(jnp.maximum(trans * (1.0 - (d[0] * gx + d[1] * gy) / d[2]), 1e-6) / jnp.maximum(det, 1e-6))
    lx, ly = central_gradient(log_e, grid.dx)
    sharpness = jnp.max(jnp.hypot(e * lx - c * ly, -b * lx + a * ly) / jnp.maximum(det, 1e-6))
    return jnp.stack([dxx, dyx, numerator]), jnp.min(det), sharpness, jnp.isfinite(eta).all()


@jax.jit
def _coefficients(planes):
    """Third program (FFT first): B-spline coefficients of D and the numerator, channels last."""
    return jnp.moveaxis(bspline_coefficients(planes), 0, -1)


@partial(jax.jit, static_argnames=("m", "iterations"))
def _gather(coefficients, length, m, iterations):
    """Newton per floor point of Grid(m, L): E at the preimage, and the largest residual (texels of the floor)."""
    n = coefficients.shape[0]
    h = length / n
    X, Y = Grid(m, length).mesh()
    X, Y = X.ravel(), Y.ravel()

    def tex(x):
        return (x + 0.5 * length) / h - 0.5

    disp = coefficients[..., :2]
    first = bspline(disp, tex(X), tex(Y))
    x, y = X - first[:, 0], Y - first[:, 1]
    for _ in range(iterations):
        value, du, dv = bspline(disp, tex(x), tex(y), derivatives=True)
        a, b, c, e = 1.0 + du[:, 0] / h, dv[:, 0] / h, du[:, 1] / h, 1.0 + dv[:, 1] / h
        rx, ry = x + value[:, 0] - X, y + value[:, 1] - Y
        det = a * e - b * c
        x, y = x - (e * rx - b * ry) / det, y - (a * ry - c * rx) / det
    value, du, dv = bspline(coefficients, tex(x), tex(y), derivatives=True)
    det = (1.0 + du[:, 0] / h) * (1.0 + dv[:, 1] / h) - (dv[:, 0] / h) * (du[:, 1] / h)
    residual = jnp.max(jnp.hypot(x + value[:, 0] - X, y + value[:, 1] - Y)) / (length / m)
    irradiance = jnp.maximum(value[:, 2], 0.0) / det  # a spline of a shadow edge may undershoot 0
    return irradiance.reshape(m, m), residual, jnp.min(det)


@partial(jax.jit, static_argnames=("s",))
def _texel_average(point, length, s):
    """Fourth program (FFT first): the box filter of one fine texel in Fourier space, then the
    average of s × s fine texels per floor texel."""
    fine = point.shape[-1]
    ky, kx = Grid(fine, length).wavenumbers(real=True)
    p = length / fine
    box = jnp.sinc(kx * p / (2 * math.pi)) * jnp.sinc(ky * p / (2 * math.pi))
    averaged = jnp.fft.irfft2(jnp.fft.rfft2(point) * box, s=(fine, fine))
    m = fine // s
    return averaged.reshape(m, s, m, s).mean(axis=(1, 3))


def _supersampling(sharpness: float, texel: float, supersample):
    """The floor supersampling that resolves E (1, 2, 4 or 8), or None when even 8 does not."""
    if supersample != "auto":
        return supersample
    for s in (1, 2, 4, 8):
        if sharpness * texel <= SHARPNESS_LIMIT * s:
            return s
    return None


def floor_irradiance_jacobian(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                              n_water: float = N_WATER, fresnel: bool = True, refine: int = 1, supersample="auto",
                              iterations: int = 4, fold: str = "beam"):
    """Floor irradiance E/E0 from the Jacobian of the landing map (module doc), shape (m, m).

    Parameters
    ----------
    eta, grid, sun, resolution, n_water, fresnel
        As :func:`optics.caustics.floor_irradiance`.
    depth : float
        Depth of a flat floor, m, > 0 (a ground height field is refused by name: use "beam").
    refine : int
        Fourier-refine the surface this many times (1 to 8) before the fields are built
        (the default 1 suffices down to 4 samples per shortest wave: the error measured is the
        floor sampling's, which ``supersample`` controls).
    supersample : "auto" or int
        Gather on a floor grid this many times finer (1 to 8) and average down; ``"auto"``
        takes the fewest of 1, 2, 4, 8 that resolve E (:data:`SHARPNESS_LIMIT`).
    iterations : int
        Newton steps per floor point (1 to 16); a residual above 1e-3 texel counts as a fold.
    fold : {"beam", "raise"}
        What a folded map gets: the exact beam rasterization (its default refinement), or
        :class:`CausticsFold` (a ValueError) naming the smallest area ratio.

    Returns
    -------
    jax.Array (m, m)
        Floor irradiance / E0 at the cell centres of ``Grid(m, L)``.
    """
    light = prepare(eta, grid, depth, sun, resolution, n_water, fresnel, check_values=False)
    if light.ground:
        raise ValueError("depth must be a number (a flat floor) for the jacobian method; on a ground height field "
                         "use method='beam' (the gather's inverse map needs the floor's own smooth slopes)")
    if supersample != "auto":
        supersample = check_int("supersample", supersample, lo=1, hi=8)
    iterations = check_int("iterations", iterations, lo=1, hi=16)
    check_choice("fold", fold, ("beam", "raise"))
    length, m, d = float(grid.length), light.resolution, jnp.asarray(light.direction, jnp.float32)
    r = check_int("refine", refine, lo=1, hi=8)
    if grid.n * r > 8192:
        raise ValueError(f"refine {r} traces {grid.n * r}² samples: n·refine must be at most 8192")
    fine = Grid(grid.n * r, grid.length)
    surface = grid.refine(light.eta, r) if r > 1 else light.eta
    planes, min_det, sharpness, finite = _fields(surface, _derivatives(surface, fine.dx), d, light.floor,
                                                 light.n_water, fresnel, shadow_steps(surface, fine, light.direction),
                                                 length)
    if not bool(finite):
        raise ValueError("eta must be finite everywhere; it contains NaN or inf")
    min_det = float(min_det)
    s = _supersampling(float(sharpness), length / m, supersample) if min_det > MIN_AREA_RATIO else None
    if s is not None and m * s > 8192:
        raise ValueError(f"resolution × supersample = {m * s} must be at most 8192")
    if s is not None:
        point, residual, _ = _gather(_coefficients(planes), length, m * s, iterations)
        if float(residual) <= NEWTON_TOLERANCE:
            return _texel_average(point, length, s)
        reason = f"Newton did not converge (residual {float(residual):.2g} texel)"
    elif min_det <= MIN_AREA_RATIO:
        reason = (f"the smallest area ratio det ∂X/∂x on the surface is {min_det:.3g} (the map folds at 0; the "
                  f"method answers down to {MIN_AREA_RATIO})")
    else:
        reason = (f"the light varies too fast on the floor (log E changes by {float(sharpness) * length / m:.3g} "
                  f"per texel; 8-fold supersampling resolves {8 * SHARPNESS_LIMIT})")
    if fold == "raise":
        raise CausticsFold(f"depth: the landing map folds or nearly folds on this floor: {reason}; "
                           "use fold='beam' or method='beam'")
    from optics.caustics.beam import floor_irradiance_beam

    warnings.warn(f"jacobian caustics: {reason}; the exact beam rasterization is used instead", stacklevel=2)
    return floor_irradiance_beam(eta, grid, depth, sun, resolution=resolution, n_water=n_water, fresnel=fresnel)
