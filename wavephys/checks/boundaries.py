"""Validations of the methods' measured failure boundaries: the open-ocean cutoff, second-order
heights against exact Stokes waves, and the stability limit of the finite-difference peer."""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np

from wavephys.checks.common import working_dtype
from wavephys.core.grid import Grid
from wavephys.core.water import Water
from wavephys.harness.checks import Check, bound, compare
from wavephys.models.finite_difference import STABILITY_LIMIT, find_stability_limit
from wavephys.physics.boundary import cutoff_boundary, cutoff_reflection
from wavephys.physics.heights import monochromatic_wave, second_order_breakdown, second_order_error, \
    second_order_height

__all__ = ["check_cutoff", "check_second_order", "check_fd_stability"]


def check_cutoff() -> list[Check]:
    """The quadratic margin absorbs waves up to a longer λ/M than the linear one.

    Measured with :func:`~wavephys.physics.boundary.cutoff_reflection` (energy fraction reflected
    by a margin of M samples for a wavelength λ) and :func:`~wavephys.physics.boundary.cutoff_boundary`
    (largest λ/M that reflects less than 0.1 %).

    Returns
    -------
    list of Check
        Four rows: the quadratic margin's reflection at λ/M = 0.5 (≤ 1e-3); the linear/quadratic
        reflection ratio there (≥ 100); the quadratic margin's boundary λ/M against the linear one's
        (≥); the quadratic margin's visible reflection at λ/M = 1 (≥ 1 %, its failure boundary).
    """
    q = cutoff_reflection(0.5, "quadratic")
    lin = cutoff_reflection(0.5, "linear")
    bq, bl = cutoff_boundary("quadratic"), cutoff_boundary("linear")
    return [bound("cutoff reflection, quadratic, lambda/M = 0.5 (energy fraction)", q, 1e-3),
            bound("cutoff reflection, linear/quadratic at lambda/M = 0.5", lin / q, 100.0, relation=">="),
            bound("largest lambda/M reflecting < 0.1 %: quadratic vs linear", bq, bl, relation=">=",
                  note=f"quadratic {bq:.3f}, linear {bl:.3f}"),
            bound("quadratic cutoff reflects visibly (> 1 %) at lambda/M = 1 (failure boundary)",
                  cutoff_reflection(1.0, "quadratic"), 0.01, relation=">=")]


def check_second_order() -> list[Check]:
    """Second-order heights equal the Stokes expansion on one wave; error against exact Stokes waves.

    One deep gravity wave of steepness kA = 0.2 on a 10 m grid of 256 points, in the working
    precision (float64 with ``jax_enable_x64``, else float32).

    Returns
    -------
    list of Check
        Six rows: the second-order height against A cos θ + (kA²/2) cos 2θ (max error / A, 1e-5 in
        float32, 1e-12 in float64); the crest and trough offsets against ±kA²/2, m (rtol 1e-3); the
        error against an exact Stokes wave at kA = 0.1 (≤ 1 % of A) and its improvement over first
        order (≥ 5); the breakdown steepness where the error reaches 10 % of A (0.3 ± 0.02).
    """
    dtype = working_dtype()
    water = Water(sigma=0.0)
    grid = Grid(256, 10.0)
    psi, k, a = monochromatic_wave(grid, water, 0.2)
    psi = psi.astype(jnp.complex128 if dtype == jnp.float64 else jnp.complex64)
    eta = second_order_height(psi, grid, water)
    theta = k * (grid.coordinates + float(grid.length) / 2) + np.pi / 2  # first order: A cos θ
    stokes = a * jnp.cos(theta) + 0.5 * k * a**2 * jnp.cos(2 * theta)
    err = float(jnp.max(jnp.abs(eta[0] - stokes))) / a
    tol = 1e-5 if dtype == jnp.float32 else 1e-12
    small = second_order_error(0.1)
    fine = grid.refine(eta, 16)  # crests fall between samples: read them off the interpolated surface
    return [compare("2nd-order height vs Stokes A cos t + (kA^2/2) cos 2t (max err / A)", err, 0.0, atol=tol),
            compare("crest height - A (Stokes: +kA^2/2)", float(jnp.max(fine)) - a, 0.5 * k * a**2, rtol=1e-3,
                    unit="m"),
            compare("trough depth - A (Stokes: -kA^2/2)", -float(jnp.min(fine)) - a, -0.5 * k * a**2, rtol=1e-3,
                    unit="m"),
            bound("2nd-order error vs exact Stokes wave at kA = 0.1 (max |d eta|/A)", small["second"], 0.01),
            bound("improvement over 1st order at kA = 0.1 (error ratio 1st/2nd)", small["first"] / small["second"],
                  5.0, relation=">="),
            compare("breakdown steepness kA where the 2nd-order error reaches 10 % of A",
                    second_order_breakdown(0.1, (0.26, 0.28, 0.30, 0.32)), 0.3, atol=0.02)]


def check_fd_stability() -> list[Check]:
    """The explicit FD scheme's measured blow-up Courant number against 1/√2.

    Returns
    -------
    list of Check
        One row: the Courant number c Δt/Δx at which the finite-difference peer blows up, found by
        bisection to 1e-4 (:func:`~wavephys.models.finite_difference.find_stability_limit`), against
        :data:`~wavephys.models.finite_difference.STABILITY_LIMIT` (rtol 1e-3).
    """
    return [compare("FD stability boundary c dt/dx (measured by bisection to 1e-4)", find_stability_limit(),
                    STABILITY_LIMIT, rtol=1e-3)]
