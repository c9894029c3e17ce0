"""``python -m bench wake``: the angle of maximum amplitude and the outer edge of the steady
wakes of Gaussian pressure sources against Froude number, measured and from linear theory,
with Rabaud & Moisy's large-Fr law and Kelvin's angle (docs/physics.md §1.3).

Rows (JSON): froude, measured and theory angles with their uncertainties (max), the cusp
estimate where the grid can hold its waves, and the grid used.
"""

from __future__ import annotations

import math

import numpy as np

from wavephys import Grid, Water
from wavephys.harness.wake import max_amplitude_angle_theory, wake_angle_cusp, wake_angle_max
from wavephys.physics.wake import (KELVIN_ANGLE, GaussianPressure, cusp_line, gaussian_size, mach_like_angle,
                                   steady_wake)

DEEP = Water(sigma=0.0)
SPEED = 1.0


def _wake(froude: float, n: int, lengths: float):
    """Steady wake of the Gaussian of ``froude`` on a grid ``lengths`` source lengths b wide,
    lightly damped (ε = 2U/L: the angle moves < 0.3° against ε → 0)."""
    size = gaussian_size(froude, SPEED)
    b = math.pi * math.sqrt(2) * size
    grid = Grid(n, lengths * b)
    source = GaussianPressure(100.0, size)
    eta = np.asarray(steady_wake(grid, DEEP, SPEED, source, damping=2 * SPEED / float(grid.length)))
    return grid, eta, source, b


def angle_rows(froudes=None, progress=print) -> list[dict]:
    """Max-amplitude angle (sections 10 b to 40 b behind, 1024² grid of 100 b) and its linear
    theory; the cusp line (:func:`_cusp`)."""
    froudes = np.geomspace(0.25, 4.0, 17) if froudes is None else froudes
    rows = []
    for fr in froudes:
        fr = float(fr)
        progress(f"wake at Fr = {fr:.3g}")
        grid, eta, source, b = _wake(fr, 1024, 100.0)
        row = dict(froude=fr, size=source.size, length_b=b, rabaud_moisy=mach_like_angle(fr), kelvin=KELVIN_ANGLE)
        near, far = 10 * b, 40 * b
        try:
            m = wake_angle_max(eta, grid, near=near, far=far)
            row.update(measured=m.angle, measured_uncertainty=m.uncertainty)
        except ValueError as exc:
            row.update(measured=None, measured_note=str(exc))
        t = max_amplitude_angle_theory(SPEED, source, near=near, far=far, spacing=float(grid.dx))
        row.update(theory=t.angle, theory_uncertainty=t.uncertainty)
        row.update(_cusp(fr, source))
        rows.append(row)
    return rows


def _cusp(froude: float, source: GaussianPressure) -> dict:
    """The outer edge on a grid of 60 cusp wavelengths, sections 6-28 of them behind (the cusp
    waves of a slow, broad source are e^-7 weaker than its transverse waves: nearer, or on 30
    wavelengths, the estimate fails at Fr <= 0.3), at 2048² or 4096² where the source stays
    resolved (σ ≥ dx)."""
    lam_c = 2 * math.pi / cusp_line(SPEED, DEEP).wavenumber
    length = 60 * lam_c
    n = next((m for m in (2048, 4096) if source.size >= length / m), None)
    if n is None:
        return dict(cusp=None, cusp_note=f"a grid of 60 cusp wavelengths ({length:.3g} m) cannot resolve the "
                                         f"source (sigma {source.size:.3g} m) at 4096^2")
    grid = Grid(n, length)
    eta = steady_wake(grid, DEEP, SPEED, source)
    c = wake_angle_cusp(eta, grid, speed=SPEED, near=6 * lam_c, far=28 * lam_c, water=DEEP)
    return dict(cusp=c.angle, cusp_uncertainty=c.uncertainty, cusp_grid=n)


def figures(rows) -> dict:
    import matplotlib.pyplot as plt  # figures only; the bench's rows need no plotting

    fig, ax = plt.subplots(figsize=(7.0, 4.6), layout="constrained")
    fr = np.array([r["froude"] for r in rows])
    ax.plot(fr, [r["theory"] for r in rows], "-", color="C0", label="linear theory, same sections")
    got = [r for r in rows if r.get("measured") is not None]
    ax.errorbar([r["froude"] for r in got], [r["measured"] for r in got],
                yerr=[r["measured_uncertainty"] for r in got], fmt="o", color="C0", ms=4, capsize=2,
                label="measured: wake_angle(method='max') on the steady wake")
    cu = [r for r in rows if r.get("cusp") is not None]
    ax.errorbar([r["froude"] for r in cu], [r["cusp"] for r in cu], yerr=[r["cusp_uncertainty"] for r in cu],
                fmt="s", color="C3", ms=4, capsize=2, label="measured: outer edge (method='cusp')")
    fine = np.geomspace(0.55, fr.max(), 50)
    ax.plot(fine, [mach_like_angle(f) for f in fine], "--", color="0.4", label="Rabaud & Moisy: 1/(2 sqrt(2 pi) Fr)")
    ax.axhline(KELVIN_ANGLE, color="C3", lw=0.8, ls=":", label="Kelvin 19.47°")
    ax.set_xscale("log")
    from matplotlib.ticker import FormatStrFormatter
    ax.xaxis.set_major_formatter(FormatStrFormatter("%g"))
    ax.xaxis.set_minor_formatter(FormatStrFormatter("%g"))
    ax.set_xlabel("Froude number U/sqrt(g b)  (Gaussian p0 exp(-pi^2 r^2/b^2))")
    ax.set_ylabel("half-angle (degrees)")
    ax.set_title("Wake angles of Gaussian pressure sources, deep water")
    ax.set_ylim(-1.0, 24.0)
    ax.legend(fontsize=8)
    return {"angles": fig}
