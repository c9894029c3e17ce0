"""Which way the waves go: standing waves and the direction of travel, measured from frames.

Each spatial Fourier mode k of a record holds two waves: one travelling along +k (its
complex amplitude turns as e^{−iωt}) and one along −k (e^{+iωt}). The windowed Fourier
transform in time separates them: a mode's power at negative temporal frequencies belongs to
the wave along +k (numpy's sign conventions), at positive ones to the wave along −k.

* :func:`standing_check` — in a *standing* wave the two parts have equal power **and
  locked phases**: a_+/a_− = e^{−2iω(t₀ − t_c)} for one release time t₀ shared by every
  mode (t_c the record's centre), so every mode's power oscillates at 2ω, all in step. The
  check measures the balance 2√(P₊P₋)/(P₊ + P₋) of each mode and the coherence of the phase
  ratios across modes at the best t₀ (0: random, 1: locked). Equal power at ±ω alone is no
  fault: a random sea with symmetric spreading has it, with unlocked phases, and passes. A
  wave field released from rest (a dropped stone, a displaced surface let go) is locked
  too, correctly: run this check on seas that are meant to travel.
* :func:`direction_check` — the power-weighted mean direction of travel against a claimed
  one (degrees, 0 = +x, 90 = +y), with the spread of directions.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from wavephys.core.inputs import check_instance, check_scalar
from wavephys.core.spectral import angular_wavenumbers

__all__ = ["Travel", "measure_travel", "standing_check", "direction_check"]


@dataclass(frozen=True)
class Travel:
    """How a record's waves travel.

    Attributes
    ----------
    direction : float
        Power-weighted mean direction of travel, degrees in (−180, 180] (0 = +x, 90 = +y).
    concentration : float
        Length of the mean unit direction vector, 0 (no preferred direction) to 1 (all one way).
    balance : float
        Power-weighted mean over modes of 2√(P₊P₋)/(P₊ + P₋): 0 all travelling one way, 1 equal both ways.
    coherence : float
        Weighted coherence of the ± phase ratios across modes at the best release time, 0 (random) to 1 (locked).
    release : float
        The best release time t₀, s from the first frame (meaningful when ``coherence`` is high).
    modes : int
        Number of modes that hold the record's power (those above 1e-4 of the strongest).
    headings, powers : numpy.ndarray
        Each mode's direction of travel (radians) and power (its wave along +k), for :meth:`share_against`.
    effective_modes : float
        ½(Σw)²/Σw² over the (up to 2048) strongest modes, w their amplitude √power (k and −k are one pair): how many
        independent pairs the coherence averages; a random sea's coherence is about 1/√(effective_modes), and
        stays below 5/√(effective_modes).
    direction_error : float
        The sampling error (one standard deviation) of ``direction``, degrees: each mode's power of a random sea
        scatters about its mean as much as the mean (an exponential), so the mean direction of a few strong
        modes scatters too; √(Σ p²(u·e⊥)²)/|Σ p u| with e⊥ across the mean direction.
    """

    direction: float
    concentration: float
    balance: float
    coherence: float
    release: float
    modes: int
    effective_modes: float
    direction_error: float = math.nan
    headings: np.ndarray = None
    powers: np.ndarray = None

    def share_against(self, direction: float) -> float:
        """The share of the travelling power that runs against ``direction`` (degrees): modes whose direction of
        travel has a negative component along it (NaN when nothing travels)."""
        if self.powers is None or not self.powers.size:
            return math.nan
        d = math.radians(direction)
        along = np.cos(self.headings - d)
        return float(np.sum(self.powers[along < 0]) / max(np.sum(self.powers), 1e-300))


def _peaks(spec, nt, min_bins):
    """Per mode: the peak bin among negative and among positive temporal frequencies, and their powers."""
    power = np.abs(spec) ** 2
    f = np.fft.fftfreq(nt) * nt
    neg = np.where(f < -min_bins)[0]
    pos = np.where(f > min_bins)[0]
    p_neg, p_pos = power[neg].sum(axis=0), power[pos].sum(axis=0)
    i_neg = neg[np.argmax(power[neg], axis=0)]
    i_pos = pos[np.argmax(power[pos], axis=0)]
    return p_neg, p_pos, i_neg, i_pos, power


def _refined(power, i, nt):
    """Parabolic refinement of a peak bin in log power (bins), per mode, within ±½ bin of the peak (a parabola
    through a flat or noisy top is no guide beyond its own bin)."""
    cols = np.arange(i.size)
    a = np.log(np.maximum(power[(i - 1) % nt, cols], 1e-300))
    b = np.log(np.maximum(power[i, cols], 1e-300))
    c = np.log(np.maximum(power[(i + 1) % nt, cols], 1e-300))
    denom = a - 2 * b + c
    return np.clip(np.where(denom < 0, 0.5 * (a - c) / np.where(denom < 0, denom, -1.0), 0.0), -0.5, 0.5)


def measure_travel(eta, dx: float, dt: float, *, min_bins: float = 2.0, locking: bool = True,
                   spectrum=None) -> Travel:
    """Direction, balance and phase locking of the waves in frames ``(n_t, n_y, n_x)``.

    Parameters
    ----------
    eta : array_like (n_t, n_y, n_x)
        Heights, m, finite, n_t ≥ 8 (a :class:`~wavephys.harness.Record`'s ``eta``).
    dx : float
        Grid spacing, m, > 0.
    dt : float
        Time between frames, s, > 0.
    min_bins : float, optional, keyword-only
        Temporal frequencies within this many bins of 0 are left out (steady patterns), >= 0 (default 2).
    locking : bool, optional, keyword-only
        Measure the phase locking of the ± parts (``coherence``, ``release``, ``effective_modes``; default True);
        without it they are NaN and the measurement is cheaper (the direction needs none of them).
    spectrum : numpy.ndarray, optional, keyword-only
        The frames' windowed space–time spectrum when already computed (``Record.spectrum()``).

    Returns
    -------
    Travel
        Mean direction (degrees), concentration, ± balance, phase coherence and release time, modes used.
    """
    from wavephys.core.inputs import check_array

    check_array("eta", eta, ndim=3)
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    eta = np.asarray(eta, np.float64)
    nt, ny, nx = eta.shape
    check_scalar("min_bins", min_bins, lo=0.0, hi=nt / 4)
    from wavephys.core.inputs import check_bool
    from wavephys.harness.spectra import spacetime_spectrum

    check_bool("locking", locking)
    if spectrum is not None and (not isinstance(spectrum, np.ndarray) or spectrum.shape != eta.shape):
        raise ValueError(f"spectrum must be the frames' {eta.shape} space-time spectrum (Record.spectrum()), got "
                         f"{type(spectrum).__name__} of shape {np.shape(spectrum)}")
    spec = (spacetime_spectrum(eta) if spectrum is None else spectrum).reshape(nt, -1)
    p_neg, p_pos, i_neg, i_pos, power = _peaks(spec, nt, min_bins)
    ky, kx = angular_wavenumbers((ny, nx), dx, xp=np)
    kx, ky = np.broadcast_to(kx, (ny, nx)).ravel(), np.broadcast_to(ky, (ny, nx)).ravel()
    kmag = np.hypot(kx, ky)
    total = p_neg + p_pos
    keep = (kmag > 0) & (total > 1e-4 * total.max()) if total.max() > 0 else np.zeros_like(kmag, bool)
    if not keep.any():
        return Travel(math.nan, 0.0, math.nan, math.nan, math.nan, 0, 0.0)
    # direction: the wave along +k holds p_neg (and its twin at -k, the same wave, holds p_pos there)
    ux, uy = kx[keep] / kmag[keep], ky[keep] / kmag[keep]
    d = np.array([np.sum(p_neg[keep] * ux), np.sum(p_neg[keep] * uy)]) / np.sum(p_neg[keep] + 1e-300)
    across = (-ux * d[1] + uy * d[0]) / max(float(np.hypot(*d)), 1e-300)  # u·e⊥ of each mode
    spread = math.sqrt(float(np.sum((p_neg[keep] * across) ** 2))) / max(float(np.sum(p_neg[keep])), 1e-300)
    direction_error = math.degrees(spread / max(float(np.hypot(*d)), 1e-300))
    balance = 2 * np.sqrt(p_neg * p_pos) / np.maximum(total, 1e-300)
    w = total[keep]
    mean_balance = float(np.sum(w * balance[keep]) / np.sum(w))
    # amplitude weights: a sea's power is held by a few long waves; its phases are in every mode
    # (modes down to 1e-8 of the strongest's power take part: their phases are as clean as the strong ones')
    faint = (kmag > 0) & (total > 1e-8 * total.max())
    coherence, release, n_eff = (_locking(spec, power, i_neg, i_pos, faint, np.sqrt(total[faint]), nt, dt) if locking
                                 else (math.nan, math.nan, math.nan))
    return Travel(float(math.degrees(math.atan2(d[1], d[0]))), float(np.hypot(*d)), mean_balance, coherence,
                  release, int(keep.sum()), n_eff, min(direction_error, 180.0), np.arctan2(uy, ux), p_neg[keep])


def _locking(spec, power, i_neg, i_pos, keep, w, nt, dt):
    """Coherence of a₊/a₋ = e^{−2iω(t₀ − t_c)} across modes, at the best t₀ (searched over ± 4 records)."""
    cols = np.where(keep)[0]
    strongest = np.argsort(w)[::-1][:2048]  # the modes that hold the power decide; the search stays cheap
    cols, w = cols[strongest], w[strongest]
    f = np.fft.fftfreq(nt) * nt
    pos_bin = f[i_pos[cols]] + _refined(power, i_pos, nt)[cols]
    neg_bin = -(f[i_neg[cols]] + _refined(power, i_neg, nt)[cols])
    omega = 2 * math.pi * 0.5 * (pos_bin + neg_bin) / (nt * dt)
    t_c = 0.5 * (nt - 1) * dt
    a_pos, a_neg = spec[i_pos[cols], cols], spec[i_neg[cols], cols]
    # undo the bins' own phase at the window's centre: each bin f carries e^{-2 pi i f t_c / (nt dt)}
    ratio = a_pos / np.where(np.abs(a_neg) > 0, a_neg, 1.0)
    bins_phase = 2 * math.pi * (f[i_pos[cols]] - f[i_neg[cols]]) * t_c / (nt * dt)
    phase = np.exp(1j * (np.angle(ratio) + bins_phase))
    weight = w * np.minimum(1.0, 2 * np.sqrt(np.abs(a_pos) ** 2 * np.abs(a_neg) ** 2) /
                            np.maximum(np.abs(a_pos) ** 2 + np.abs(a_neg) ** 2, 1e-300))
    span = 4 * nt * dt
    step = math.pi / (8 * max(float(omega.max()), 2 * math.pi / (nt * dt)))  # at least one bin's frequency
    weighted = (weight * phase)[None, :]

    def best_of(taus):
        best, best_tau = 0.0, 0.0
        for chunk in np.array_split(taus, max(1, taus.size * cols.size // 2_000_000)):
            c = np.abs(weighted @ np.exp(2j * omega[:, None] * chunk[None, :]))[0] / np.sum(w)
            j = int(np.argmax(c))
            if c[j] > best:
                best, best_tau = float(c[j]), float(chunk[j])
        return best, best_tau

    # a bounded search whatever the record: at most 1025 release times on a coarse grid (each within a quarter
    # of the fastest mode's half period of the finest grid), then the finest step around the best few
    coarse = max(step, 2 * span / 1024)
    best, best_tau = best_of(np.arange(-span, span + coarse, coarse))
    if coarse > step:
        found = best_of(np.arange(best_tau - 2 * coarse, best_tau + 2 * coarse + step, step))
        best, best_tau = max((best, best_tau), found)
    # modes k and -k are one pair of waves with the same phase ratio: count pairs
    return best, t_c + best_tau, 0.5 * float(np.sum(w) ** 2 / np.sum(w ** 2))


def standing_check(record, *, max_coherence: float = 0.5):
    """A :class:`~wavephys.harness.Check` that a sea travels: its modes' ± parts are not phase-locked.

    Parameters
    ----------
    record : Record
        The frames (:class:`wavephys.harness.Record`) of a sea that is meant to travel.
    max_coherence : float, optional, keyword-only
        Largest phase coherence of the ± parts across modes that passes, in (0, 1] (default 0.5; a random sea
        of N independent pairs of modes gives about 1/√N, a standing one about 1). The limit is raised to
        5/√N where that is larger, so that chance never fails a random sea; where it reaches 0.9 the record
        cannot tell and the row passes, saying so.

    Returns
    -------
    Check
        A ``"<="`` row of the coherence; its note gives the ± balance, and on failure the cause (standing waves,
        with the release time they share) and the fix.
    """
    from wavephys.harness.checks import bound
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_scalar("max_coherence", max_coherence, lo=0.0, hi=1.0, lo_open=True)
    t = measure_travel(record.eta, record.dx, record.dt, spectrum=record.spectrum())
    chance = 5.0 / math.sqrt(max(t.effective_modes, 1e-12))  # a random sea stays below it
    limit = max(max_coherence, chance)
    note = (f"{t.modes} modes, {t.effective_modes:.0f} effective pairs; +-omega power balance {t.balance:.2f} "
            f"(0: one way, 1: equal both ways); phase coherence {t.coherence:.2f} at t0 = {t.release:.3g} s")
    quantity = "phase coherence of the +omega and -omega parts across modes"
    if limit >= 0.9:
        return bound(quantity, t.coherence, 1.0, note=f"{note}; inconclusive: too few independent modes for "
                                                          f"chance to stay below {chance:.2f}; a longer or wider "
                                                          f"record (a broader spectrum) can tell")
    row = bound(quantity, t.coherence, limit, note=note)
    if not row.ok:
        row = bound(quantity, t.coherence, limit,
                    note=f"{note}; likely cause: standing waves: every mode's +omega and -omega parts are locked, as "
                         f"if the whole surface were released from rest at t = {t.release:.3g} s (the sea does not "
                         f"travel). In an FFT ocean, h(k, t) = h0(k) exp(i w t) + conj(h0(-k)) exp(-i w t); "
                         f"using one sign for both halves, or (h0(k) + conj(h0(-k))) cos(w t), makes this. A field "
                         f"released from rest (a dropped stone) does it correctly: check seas only")
    return row


def direction_check(record, direction: float, *, tolerance: float = 15.0, min_concentration: float = 0.2):
    """A :class:`~wavephys.harness.Check` of the mean direction of travel against a claim, in degrees.

    Parameters
    ----------
    record : Record
        The frames (:class:`wavephys.harness.Record`).
    direction : float
        The claimed direction of travel (downwind for a wind sea), degrees, 0 = +x, 90 = +y (counter-clockwise
        in the grid convention, row 0 = lowest y).
    tolerance : float, optional, keyword-only
        Allowed difference, degrees, in (0, 180] (default 15). The row's tolerance is the larger of this and 4 ×
        the measured direction's own sampling error (``Travel.direction_error``): a small random sea's mean
        direction scatters (a correct 32² sea: up to 21° over 12 draws, 1.7 of its sampling error).
    min_concentration : float, optional, keyword-only
        Below this concentration of directions (0–1) the record has no direction to check and the row fails
        (default 0.2).

    Returns
    -------
    Check
        A ``"~="`` row of the measured direction against the claim (degrees, absolute tolerance); on failure
        its note names the likely cause (a flipped sign of ωt, a flipped y axis, swapped axes).
    """
    from wavephys.harness.checks import compare
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_scalar("direction", direction)
    check_scalar("tolerance", tolerance, lo=0.0, hi=180.0, lo_open=True)
    check_scalar("min_concentration", min_concentration, lo=0.0, hi=1.0)
    t = measure_travel(record.eta, record.dx, record.dt, locking=False, spectrum=record.spectrum())
    claimed = (float(direction) + 180.0) % 360.0 - 180.0
    diff = (t.direction - claimed + 180.0) % 360.0 - 180.0 if math.isfinite(t.direction) else math.nan
    tolerance = max(float(tolerance), 4.0 * t.direction_error) if math.isfinite(t.direction_error) else tolerance
    note = (f"{t.modes} modes; concentration {t.concentration:.2f}; claimed {claimed:.1f} deg; sampling error "
            f"{t.direction_error:.2g} deg (tolerance the larger of the given and 4 x it)")
    measured = claimed + diff
    if not (t.concentration >= min_concentration):
        return compare("mean direction of travel", math.nan, claimed, atol=tolerance, unit="deg",
                       note=f"{note}; no preferred direction (concentration below {min_concentration}): the waves "
                            f"go every way equally, or stand")
    row = compare("mean direction of travel", measured, claimed, atol=tolerance, unit="deg", note=note)
    if not row.ok:
        mirrored = (-claimed + 180.0) % 360.0 - 180.0
        against = t.share_against(claimed)
        if abs(abs(diff) - 180.0) <= tolerance:
            cause = (f"the waves travel opposite to the claim ({100 * against:.0f} % of the power runs against it): "
                     f"the sign of omega t is flipped (exp(+i w t) for exp(-i w t)), or the wind vector is, or the "
                     f"spectrum keeps its upwind half (a directional mask or suppression factor that keeps k.wind < 0 "
                     f"where k.wind > 0 is due); the frames cannot tell these apart")
        elif abs((t.direction - mirrored + 180.0) % 360.0 - 180.0) <= tolerance:
            cause = "the y axis is flipped (rows stored top-down, or a DirectX-style texture origin)"
        elif abs((t.direction - (90.0 - claimed) + 180.0) % 360.0 - 180.0) <= tolerance:
            cause = "x and y are swapped (a transposed texture)"
        elif t.share_against(t.direction) >= 0.25:
            cause = (f"the power runs both ways ({100 * t.share_against(t.direction):.0f} % against its own mean "
                     f"direction {t.direction:.1f} deg, {100 * against:.0f} % against the claim): the spectrum's "
                     f"directional factor keeps both halves (|k.wind|^2 without the one-way mask)")
        else:
            cause = (f"the waves travel toward {t.direction:.1f} deg ({100 * against:.0f} % of the power against the "
                     f"claim; concentration {t.concentration:.2f}): the claimed direction, or the wind vector's "
                     f"angle, is not the sea's")
        row = compare(row.quantity, measured, claimed, atol=tolerance, unit="deg", note=f"{note}; likely cause: {cause}")
    return row
