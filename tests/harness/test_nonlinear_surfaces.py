"""The dispersion check on nonlinear heights: Tessendorf's choppy seas, generated here (two wind spectra, two
seeds, choppiness at a quarter and half of each sea's own fold). The check measures the linear relation, so the
displaced heights fail it while the same seas' linear heights pass; the harness never names a wrong cause for
them (no "wave equation", no depth, no surface tension), and where it can tell (the energetic waves obey the
relation, a prominent peak sits at theory's ω in the worst shell) it names the bound components."""

import jax
import numpy as np
import pytest

from wavephys import Grid, Water
from wavephys.harness import dispersion_check, measure_dispersion
from wavephys.physics.wind import jonswap_spectrum, phillips_spectrum, synthesize_height
from wavephys.surfaces.choppy import displacement, fold_choppiness, sea_height
from wavephys.surfaces.resample import resample_heights

WATER = Water()
WRONG_CAUSES = ("non-dispersive", "wave equation", "depth", "surface tension", "sigma", "constant factor",
                "frequency floor", "aliased")


def _sea(spectrum, seed, fraction, n=64, length=32.0, frames=96, dt=0.1):
    grid = Grid(n, length)
    ky, kx = grid.wavenumbers()
    spec = (phillips_spectrum(kx, ky, WATER, 6.0, small_wave_length=0.3) if spectrum == "phillips"
            else jonswap_spectrum(kx, ky, WATER, 6.0, 10000.0))
    sea = synthesize_height(spec, grid, jax.random.PRNGKey(seed))
    lam = fraction * fold_choppiness(sea_height(sea, grid, WATER, 0.0), grid)
    heights = [sea_height(sea, grid, WATER, i * dt) for i in range(frames)]
    linear = np.stack([np.asarray(h) for h in heights])
    choppy = np.stack([np.asarray(resample_heights(displacement(h, grid, lam), h, grid)) for h in heights])
    check = lambda eta: dispersion_check(measure_dispersion(eta, grid.dx, dt, axes="tyx"), WATER, dt)
    return check(linear), check(choppy)


CASES = [(s, seed, f) for s in ("phillips", "jonswap") for seed in (0, 1) for f in (0.25, 0.5)]


@pytest.mark.parametrize("case", [pytest.param(c, marks=() if c == ("jonswap", 0, 0.25) else pytest.mark.slow)
                                  for c in CASES], ids=lambda c: f"{c[0]}-{c[1]}-{c[2]}")
def test_choppy_seas_fail_for_what_they_are_and_never_for_a_wrong_cause(case):
    linear, choppy = _sea(*case)
    assert linear.ok, linear
    assert not choppy.ok  # bound components do not obey the linear relation (measured 24-84 % off)
    assert not any(w in choppy.note for w in WRONG_CAUSES), choppy.note
    if case == ("jonswap", 0, 0.25):
        assert "do not obey the linear dispersion relation, in weak shells" in choppy.note


def test_the_bound_cause_needs_a_prominent_free_peak_and_obedient_energetic_waves():
    """Made-up samples: the energetic shells on theory, the weakest shell's ridge 6 bins off. A peak at theory's
    ω standing 500× over the shell's floor names bound components; a bump on a flat shell, or a peak under 1 % of
    the shell's strongest, does not; nor does a prominent peak when an energetic shell is off too."""
    from wavephys.harness.dispersion import DispersionSamples
    from wavephys.physics.dispersion import angular_frequency

    k = np.linspace(1.0, 4.0, 12)
    theory = np.asarray(angular_frequency(k, WATER), float)
    dw = 0.1
    bins = int(theory.max() / dw) + 20
    spectra = np.full((k.size, bins), 1e-3)
    omega = theory.copy()
    omega[-1] = theory[-1] + 6 * dw  # the weakest shell's ridge: something else
    power = np.geomspace(1.0, 1e-4, k.size)
    at = int(round(theory[-1] / dw))
    spectra[-1, at + 6] = 1.0

    def cause(peak, floor=1e-3, om=omega):
        s = spectra.copy()
        s[-1, :] = floor
        s[-1, at + 6] = 1.0
        s[-1, at] = peak
        return dispersion_check(DispersionSamples(k, om, power, dw, s), WATER, 0.01).note

    named = cause(0.5)
    assert "do not obey the linear dispersion relation" in named
    assert "the 11 shells below" in named and "k_range=(0, " in named  # the band that passes, between shells
    band = float(named.split("k_range=(0, ")[1].split(")")[0])
    assert k[-2] < band < k[-1]
    assert "do not obey" not in cause(0.5, floor=0.4)  # a bump on a flat shell: not prominent
    assert "do not obey" not in cause(0.005, floor=1e-6)  # prominent, but under 1 % of the shell's strongest
    off = omega.copy()
    off[0] = theory[0] * 1.05  # the strongest shell off too: a wrong simulator, not bound waves
    assert "do not obey" not in cause(0.5, om=off)
    # a lone ridge 2.3 bins off with nothing at theory: its own bin is within reach of theory's ±1, but it is
    # the ridge, not a second peak
    near = omega.copy()
    near[-1] = theory[-1] + 2.3 * dw
    lone = np.full_like(spectra, 1e-3)
    lone[-1, int(round(near[-1] / dw))] = 1.0
    assert "do not obey" not in dispersion_check(DispersionSamples(k, near, power, dw, lone), WATER, 0.01).note
    with pytest.raises(ValueError, match="spectra"):
        DispersionSamples(k, omega, power, dw, spectra[:-1])
