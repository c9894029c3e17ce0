"""The reference caustics map: exact beam rasterization refined until two levels agree.

Where the map does not fold, :func:`~optics.caustics.beam.floor_irradiance_beam` converges
at second order in the cell size (its only error is the straight-edged footprint of a
curved map). The reference traces the surface Fourier-interpolated r and 2r times finer and
doubles r until the two maps agree to ``tolerance`` of the peak in the max norm; it returns
the finer map with the bound |E_2r − E_r|. That bounds the finer map's own error as long as
each doubling at least halves it (second order would quarter it; measured ratios are 3 to
4.6, and the fourfold extrapolation is not used because the refined grids' samples shift
and the ratio is not steady enough for it). Past a fold the irradiance is unbounded at the
caustic lines and no refinement converges pointwise: the bound says so.
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from optics.caustics.beam import floor_irradiance_beam
from optics.caustics.common import prepare, walled_tank
from optics.light.fresnel import N_WATER
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_int, check_scalar

__all__ = ["ConvergedIrradiance", "converged_floor_irradiance", "floor_irradiance_reference"]


class ConvergedIrradiance(NamedTuple):
    """A reference map and how far it can be trusted.

    Parameters
    ----------
    irradiance : numpy.ndarray (m, m)
        Floor irradiance E/E0, the finer level's.
    bound : float
        max |E_2r − E_r| / peak: the finer level's error bound.
    refine : int
        The finer level's refinement 2r.
    converged : bool
        ``bound <= tolerance``.
    """

    irradiance: np.ndarray  # (m, m) floor irradiance E/E0, the finer level's
    bound: float            # max |E_2r − E_r| / peak: the finer level's error bound
    refine: int             # the finer level's refinement 2r
    converged: bool         # bound <= tolerance


def converged_floor_irradiance(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                               n_water: float = N_WATER, fresnel: bool = True, tolerance: float = 1e-3,
                               start: int = 4, max_refine: int = 16, walls=None) -> ConvergedIrradiance:
    """The reference map with its error bound (module doc).

    Parameters
    ----------
    eta, grid, depth, sun, resolution, n_water, fresnel
        As :func:`optics.caustics.floor_irradiance` (heights in m on ``grid``; a floor depth
        in m or a ground height field; the direction towards the sun; the map's side).
    tolerance : float
        The bound to reach, relative to the peak, in (0, 0.1].
    start : int
        The first level r, 1 to 8.
    max_refine : int
        The finest level 2r allowed, 2 to 32 (each doubling costs four times the last).
    walls : str or None
        A tank with opaque walls on these sides, as :func:`~optics.caustics.floor_irradiance_beam`
        (default None: periodic).

    Returns
    -------
    ConvergedIrradiance
        The last level reached, with ``converged`` False when the bound stayed above
        ``tolerance`` (e.g. past a fold).
    """
    walled_tank(prepare(eta, grid, depth, sun, resolution, n_water, fresnel), walls)  # every argument checked first
    check_scalar("tolerance", tolerance, lo=0.0, hi=0.1, lo_open=True)
    start = check_int("start", start, lo=1, hi=8)
    max_refine = check_int("max_refine", max_refine, lo=2, hi=32)
    if max_refine < 2 * start:
        raise ValueError(f"max_refine must be at least 2 × start = {2 * start}, got {max_refine}")
    trace = lambda r: np.asarray(floor_irradiance_beam(eta, grid, depth, sun, resolution=resolution, n_water=n_water,
                                                        fresnel=fresnel, refine=r, walls=walls), np.float64)
    r, coarse = start, trace(start)
    while True:
        fine = trace(2 * r)
        peak = float(np.max(fine)) or 1.0
        bound = float(np.max(np.abs(fine - coarse))) / peak
        if bound <= tolerance or 4 * r > max_refine:
            return ConvergedIrradiance(fine, bound, 2 * r, bound <= tolerance)
        r, coarse = 2 * r, fine


def floor_irradiance_reference(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                               n_water: float = N_WATER, fresnel: bool = True, tolerance: float = 1e-3,
                               max_refine: int = 16, walls=None):
    """Floor irradiance E/E0 converged to ``tolerance`` of the peak.

    Parameters
    ----------
    eta, grid, depth, sun, resolution, n_water, fresnel
        As :func:`optics.caustics.floor_irradiance` (heights in m on ``grid``; a floor depth
        in m or a ground height field; the direction towards the sun; the map's side).
    tolerance : float
        The bound to reach, relative to the peak, in (0, 0.1].
    max_refine : int
        The finest refinement allowed, 2 to 32.
    walls : str or None
        A tank with opaque walls on these sides (default None: periodic).

    Returns
    -------
    numpy.ndarray (m, m)
        The map of :func:`converged_floor_irradiance` (which also returns its bound).
    """
    return converged_floor_irradiance(eta, grid, depth, sun, resolution=resolution, n_water=n_water, fresnel=fresnel,
                                      tolerance=tolerance, max_refine=max_refine, walls=walls).irradiance
