"""The linear shallow-water depth stepper's shoreline on dry land: Lamb's standing wave on a plane beach with
the shoreline anywhere inside a cell converges at second order (issue 52, item 5; docs/physics.md §1.12).
Before the wet/dry faces took the bed's depth, ω was off by −5.4 % at 64 cells and −2.7 % at 128 (first
order), and the amplitude after three periods by 0.82 and 0.42."""

import numpy as np
import pytest

from wavephys.checks.depth import lamb_shoreline_errors


def _family(seed, count):
    """The issue's end slopes, 1:5 and 1:50, then slopes between them (log-uniform), with shoreline offsets
    anywhere in a cell: the first on a face, the rest drawn."""
    rng = np.random.default_rng(seed)
    slopes = np.concatenate([[1 / 5, 1 / 50], 10 ** rng.uniform(np.log10(1 / 50), np.log10(1 / 5), count - 2)])
    offsets = np.concatenate([[0.0], rng.uniform(0.0, 1.0, count - 1)])
    return list(zip(slopes, offsets))


def test_lambs_beach_with_dry_land_keeps_its_frequency_to_half_a_percent_at_64_cells():
    for slope, offset in _family(0, 6):
        r = lamb_shoreline_errors(64, slope, offset)
        assert abs(r["omega"]) < 0.005, (slope, offset, r)  # the bound
        assert abs(r["omega"]) < 6e-4, (slope, offset, r)   # measured: at most 3e-4
        assert abs(r["amplitude"]) < 0.005, (slope, offset, r)
        assert r["l2"] < 0.01 and r["max"] < 0.06, (slope, offset, r)


@pytest.mark.slow
def test_lambs_beach_with_dry_land_converges_at_second_order():
    for slope, offset in _family(1, 4):
        coarse, fine = (lamb_shoreline_errors(n, slope, offset) for n in (64, 128))
        if abs(coarse["omega"]) > 5e-5:  # above the fit's own noise
            assert abs(fine["omega"]) < abs(coarse["omega"]) / 3, (slope, offset, coarse, fine)
        assert fine["l2"] < coarse["l2"] / 1.8, (slope, offset, coarse, fine)
