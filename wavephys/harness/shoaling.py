"""A user's waves over a known floor measured against shoaling (docs/physics.md §1.12).

A steady wave train that runs across depth contours keeps its frequency ω and, where nothing is
reflected, its energy flux: its amplitude at depth h is A(h) = A_ref·√(c_g(h_ref)/c_g(h)) (Green's
law h^(−1/4) in shallow water). :func:`shoaling_check` takes a record of such a train travelling
along x over a floor whose depth varies along x (given per column), measures the amplitude in each
column (√2 × the rms of η over time and y), the dominant frequency (the peak of the time spectrum),
and compares the amplitude against the shoaling law, relative to the deepest columns.
"""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_scalar
from wavephys.core.water import Water

__all__ = ["shoaling_check"]


def shoaling_check(record, water: Water, depth, *, rtol: float = 0.02):
    """A :class:`~wavephys.harness.Check` that a wave train's amplitude follows the shoaling law across a floor.

    Parameters
    ----------
    record : Record
        Frames of a steady train travelling along x (n_t ≥ 8), covering a whole number of periods or many.
    water : Water
        g, ρ, σ (its depth is ignored: ``depth`` gives it per column).
    depth : array_like (n_x,)
        Still-water depth under each column, m, > 0.
    rtol : float, optional, keyword-only
        Largest relative amplitude error, > 0 (default 0.02).

    Returns
    -------
    Check
        A ``"~="`` row of the worst relative error of A(x)/A_ref against √(c_g,ref/c_g(x)), over the columns
        holding at least 10 % of the record's largest amplitude; on failure the note names the likely cause.

    References
    ----------
    G. Green (1838); R. G. Dean & R. A. Dalrymple (1991). *Water Wave Mechanics*, §4.
    """
    from wavephys.harness.checks import compare
    from wavephys.harness.record import Record
    from wavephys.physics.depth import shoaling_coefficient

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_instance("water", water, Water, "wavephys.Water")
    eta = np.asarray(record.eta, np.float64)
    nt, ny, nx = eta.shape
    check_array("depth", depth, ndim=1, shape_tail=(nx,), lo=0.0)
    check_scalar("rtol", rtol, lo=0.0, lo_open=True)
    h = np.asarray(depth, np.float64)
    if not np.all(h > 0):
        raise ValueError("depth must be > 0 in every column (shoaling is measured where there is water)")
    spectrum = np.abs(np.fft.rfft((eta - eta.mean(axis=0)).reshape(nt, -1), axis=0)) ** 2
    power = spectrum.sum(axis=1)
    power[0] = 0.0
    peak = int(np.argmax(power))
    omega = 2 * math.pi * peak / (nt * record.dt)
    quantity = "worst relative error of the amplitude across the floor against the shoaling law"
    if not omega > 0:
        return compare(quantity, math.nan, 0.0, atol=rtol, note="no oscillation in the record")
    amp = math.sqrt(2.0) * np.sqrt(np.mean((eta - eta.mean(axis=0)) ** 2, axis=(0, 1)))
    live = amp >= 0.1 * amp.max()
    deep = live & (h >= np.max(h[live]) * (1 - 1e-9))
    ref_amp, ref_h = float(np.mean(amp[deep])), float(np.max(h[live]))
    theory = np.where(live, shoaling_coefficient(omega, ref_h, h, water), math.nan)
    rel = amp[live] / (ref_amp * theory[live]) - 1.0
    worst = float(rel[np.argmax(np.abs(rel))])
    note = (f"omega {omega:.4g} rad/s from the time spectrum; {int(live.sum())} columns, depths "
            f"{float(h[live].min()):.4g}..{ref_h:.4g} m, shoaling law up to {float(np.nanmax(theory)):.4g}")
    row = compare(quantity, worst, 0.0, atol=rtol, note=note)
    if row.ok:
        return row
    shallow = live & (h <= np.min(h[live]) * (1 + 1e-9))
    measured = float(np.mean(amp[shallow])) / ref_amp
    expected = float(np.nanmean(theory[shallow]))
    if abs(measured - 1.0) < 0.25 * abs(expected - 1.0):
        cause = (f"the amplitude hardly changes with depth ({measured:.3g}x where theory says {expected:.3g}x): "
                 f"the floor is ignored, or the method keeps kinematics but not energy flux (spectral depth "
                 f"levels blended per place)")
    elif measured < 1.0 < expected or measured > 1.0 > expected:
        cause = (f"the amplitude moves the wrong way ({measured:.3g}x where theory says {expected:.3g}x): energy "
                 f"is lost or made over the slope")
    else:
        cause = (f"the amplitude changes by {measured:.3g}x where theory says {expected:.3g}x: a wrong group speed "
                 f"(a non-dispersive solver at kh > 0.3, or a coarse grid's dispersion), or reflection from the slope")
    return compare(quantity, worst, 0.0, atol=rtol, note=f"{note}; likely cause: {cause}")
