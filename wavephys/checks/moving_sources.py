"""Validations of moving sources: the ship kernels' exact identities and float32 stability,
Kelvin wakes of steady pressure sources, and the capillary-gravity threshold c_min."""

from __future__ import annotations

import math

import jax.numpy as jnp
import numpy as np

from wavephys.core.grid import Grid
from wavephys.core.water import Water
from wavephys.harness.checks import Check, bound, compare
from wavephys.harness.wake import max_amplitude_angle_theory, track_wavelength, wake_angle
from wavephys.physics.ship_waves import (resonance_quotients, resonance_quotients_exact, ship_multipliers,
                                         ship_multipliers_naive)
from wavephys.physics.wake import (KELVIN_ANGLE, GaussianPressure, cusp_line, gaussian_size, mach_like_angle,
                                   steady_wake, transverse_wavelength)

__all__ = ["check_ship_kernels", "check_steady_wakes", "check_capillary_wake"]


def check_ship_kernels() -> list[Check]:
    """M1 + M2 = 0 at rest; the series quotients against exact arithmetic; the naive form's failure.

    Returns
    -------
    list of Check
        Three rows: max |M1 + M2| of the ship multipliers for a source at rest (atol 1e-6); the float32
        resonance quotient Q1(α) against exact arithmetic over 1e-6 ≤ |α| ≤ 2 (max relative error,
        atol 1e-6); and the error of the naive float32 multipliers, which must be large (≥ 0.1, a
        documented failure).
    """
    grid, deep = Grid(128, 8.0), Water(sigma=0.0)
    m1, m2 = ship_multipliers(grid, Water(), (0.0, 0.0), 0.1)
    alpha = np.concatenate([np.geomspace(1e-6, 2.0, 40), -np.geomspace(1e-6, 2.0, 40)])
    q1, _ = resonance_quotients(jnp.asarray(alpha, jnp.float32))
    r1, _ = resonance_quotients_exact(alpha)
    n1, _ = ship_multipliers_naive(grid, deep, (1.0, 0.0), 0.05)
    s1, _ = ship_multipliers(grid, deep, (1.0, 0.0), 0.05)
    err = np.abs(np.asarray(n1) - np.asarray(s1))
    err[0, 0] = 0.0  # 0/0 there
    return [compare("ship at rest: max |M1 + M2|", float(jnp.max(jnp.abs(m1 + m2))), 0.0, atol=1e-6),
            compare("float32 Q1(alpha) vs exact, |alpha| in [1e-6, 2] (max rel. error)",
                    float(np.max(np.abs(np.asarray(q1) - r1) / np.abs(r1))), 0.0, atol=1e-6),
            bound("naive quotients in float32: max |M1 error| (documented failure)", float(err.max()), 0.1,
                  relation=">=")]


def check_steady_wakes() -> list[Check]:
    """Kelvin's angle, the transverse wavelength and the outer edge of steady deep-water wakes;
    the angle of maximum amplitude against linear theory across Froude numbers.

    Gaussian pressure sources at 1 m/s on a 40 m grid of 2048 points, then at Froude numbers 0.5,
    1.5 and 4 on grids of 100 source lengths.

    Returns
    -------
    list of Check
        The angle of maximum amplitude of a 5 cm source against linear theory (≤ 0.2°); the
        transverse wavelength on the track against 2πU²/g, m; the cusp line from the dispersion
        relation against Kelvin's 19.47°; the outer edge for two source sizes against Kelvin's angle
        (± 0.3°); the broad source's maximum on the track (≤ 1°); then the angle of maximum amplitude
        at Fr = 0.5, 1.5, 4 against theory (within max(1°, 10 %)), theory at Fr = 0.5 against Kelvin
        and theory at Fr = 4 against Rabaud & Moisy's Fr·α = 1/(2√(2π)) (rtol 0.2).

    References
    ----------
    Rabaud, M. & Moisy, F. (2013). Ship wakes: Kelvin or Mach angle? *Phys. Rev. Lett.* 110.
    """
    grid, deep = Grid(2048, 40.0), Water(sigma=0.0)
    small = GaussianPressure(100.0, 0.05)
    eta = steady_wake(grid, deep, 1.0, small)
    angle = wake_angle(eta, grid, near=2.0, far=16.0, exclude=0.3)
    theory = max_amplitude_angle_theory(1.0, small, near=2.0, far=16.0, exclude=0.3, spacing=float(grid.dx),
                                        damping=8.0 / 40.0)
    rows = [bound("sigma = 5 cm at 1 m/s: angle of max amplitude, |measured - linear theory| (same sections)",
                  abs(angle.angle - theory.angle), 0.2, unit="deg",
                  note=f"{angle.angle:.2f} +- {angle.uncertainty:.2f} vs {theory.angle:.2f} deg; Kelvin 19.47"),
            compare("transverse wavelength on the track vs 2 pi U^2/g",
                    track_wavelength(eta, grid, near=4.0, far=16.0), transverse_wavelength(1.0), rtol=0.01, unit="m"),
            compare("cusp line from the dispersion relation (deep, gravity)", cusp_line(1.0).angle, KELVIN_ANGLE,
                    atol=5e-5, unit="deg")]
    for size in (0.05, 0.3):
        e = eta if size == 0.05 else steady_wake(grid, deep, 1.0, GaussianPressure(100.0, size))
        edge = wake_angle(e, grid, method="cusp", speed=1.0, near=3.0, far=14.0)
        rows.append(compare(f"steady wake, source sigma/lambda = {size / transverse_wavelength(1.0):.2f}: outer edge",
                            edge.angle, KELVIN_ANGLE, atol=0.3, unit="deg", note=f"+- {edge.uncertainty:.2f} deg"))
    largest = wake_angle(e, grid, near=2.0, far=16.0)
    rows.append(bound("sigma/lambda = 0.47 (Fr 0.28): angle of maximum amplitude, on the track (transverse waves)",
                      abs(largest.angle), 1.0, unit="deg", note=f"{largest.angle:.2f} +- {largest.uncertainty:.2f}"))
    return rows + _froude_rows()


def _froude_rows() -> list[Check]:
    """Gaussian sources at Fr = 0.5, 1.5 and 4 (1024² grids of 100 source lengths, ε = 2U/L):
    the measured angle of maximum amplitude against linear theory; theory's published shape."""
    worst, angles = 0.0, {}
    for froude in (0.5, 1.5, 4.0):
        size = gaussian_size(froude, 1.0)
        b = math.pi * math.sqrt(2) * size
        grid, source = Grid(1024, 100 * b), GaussianPressure(100.0, size)
        e = steady_wake(grid, Water(sigma=0.0), 1.0, source, damping=2.0 / float(grid.length))
        m = wake_angle(e, grid, near=10 * b, far=40 * b)
        t = max_amplitude_angle_theory(1.0, source, near=10 * b, far=40 * b, spacing=float(grid.dx))
        worst = max(worst, abs(m.angle - t.angle) / max(1.0, 0.1 * t.angle))
        angles[froude] = t.angle
    return [bound("angle of max amplitude at Fr = 0.5, 1.5, 4: |measured - theory| / max(1 deg, 10 %)", worst, 1.0),
            compare("linear theory at Fr = 0.5: angle of max amplitude vs Kelvin", angles[0.5], KELVIN_ANGLE, atol=1.0,
                    unit="deg"),
            compare("linear theory at Fr = 4: Fr x angle vs Rabaud-Moisy 1/(2 sqrt(2 pi))", 4.0 * angles[4.0],
                    mach_like_angle(1.0), rtol=0.2, unit="deg")]


def check_capillary_wake() -> list[Check]:
    """Below c_min = 0.2312 m/s a capillary-gravity source leaves (almost) no wake behind it.

    Returns
    -------
    list of Check
        One row: the ratio of the wake amplitude behind a 5 mm source (0.1 to 0.4 m behind, relative
        to the field's peak) at U = 0.26 m/s to that at U = 0.22 m/s, ≥ 100.
    """
    grid, cap = Grid(1024, 1.0), Water()
    x, _ = (np.asarray(a) for a in grid.mesh())
    behind_band = (x[0] > -0.4) & (x[0] < -0.1)

    def behind(u):
        e = np.asarray(steady_wake(grid, cap, u, GaussianPressure(10.0, 0.005)))
        return np.abs(e[:, behind_band]).max() / np.abs(e).max()

    return [bound("capillary-gravity wake amplitude ratio U=0.26 / U=0.22 (c_min = 0.2312)",
                  behind(0.26) / behind(0.22), 100.0, relation=">=")]
