"""Every law the harness measures, as one registry of checks on a :class:`~wavephys.harness.Record`.

:data:`RECORD_CHECKS` names each check, says what it measures and which claims it needs
(:class:`~wavephys.harness.Claims`: a direction of travel, a source, "this is a sea"), and how
many frames it needs at least; :func:`check_record` runs the ones asked for (by default every one
whose claims are made) and returns a :class:`RecordReport`: one :class:`~wavephys.harness.Check`
row per check, with its verdict and, on failure, the likely cause. ``wavephys check FRAMES...``
and the pytest fixture are built on it, their options generated from the claims.

A new check is one function and one row here; a check that needs a claim :class:`Claims` does not
hold brings it in its row (``claims=(Claim(...),)``), and ``check_record``, the fixture and the
command take it by name (``tests/harness/test_claims.py`` shows one). This module imports nothing
heavy: ``wavephys check --help`` lists the rows.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Optional

from wavephys.harness.claims import Claim, Claims, add_claims, claim_fields

__all__ = ["RecordCheck", "RECORD_CHECKS", "RecordReport", "check_record", "CLAIMS", "register", "unregister",
           "Claim", "Claims"]


@dataclass(frozen=True)
class RecordCheck:
    """One law checked on a record.

    Attributes
    ----------
    name : str
        Its name (``wavephys check --only NAME``).
    measures : str
        What it measures, in words.
    needs : tuple of str
        The claims it needs (names of :class:`~wavephys.harness.Claims` fields or of its own ``claims``); none:
        it runs on every record.
    run : callable
        ``run(record, water, claims) -> Check`` (``claims`` a :class:`~wavephys.harness.Claims`).
    min_frames : int
        The fewest frames it can measure on (a shorter record is refused by name before any work).
    claims : tuple of Claim
        Claims it brings that :class:`~wavephys.harness.Claims` does not hold (taken by name everywhere).
    periodic : bool
        It assumes a periodic domain: not run on a tank (``instead`` names the check that is).
    instead : str
        For a periodic check, the tank's check that takes its place.
    linear : bool
        A check of linear waves on a periodic sea: not run on shallow water over a bed.
    also : callable, optional
        ``also(claims)`` → "" when it can run, else the further claim it needs, in words.
    square : bool
        It measures on square frames only (n_y = n_x): not run on a strip, with why.
    flat : bool
        Its theory is a flat floor's (a tank's cosine modes): not run over an uneven ``bed``; over a flat one
        the water's depth is the bed's.
    still : bool
        It measures a lake at rest: the only kind of row run when the record claims ``at_rest`` (the others
        measure waves, and a lake at rest has none).
    """

    name: str
    measures: str
    needs: tuple
    run: Callable
    min_frames: int = 8
    claims: tuple = ()
    periodic: bool = False
    instead: str = ""
    linear: bool = False
    also: Optional[Callable] = None
    square: bool = False
    flat: bool = False
    still: bool = False


def _dispersion(record, water, c):
    from wavephys.harness.dispersion import dispersion_check, measure_dispersion

    samples = measure_dispersion(record.eta, record.dx, record.dt, axes="tyx", spectrum=record.spectrum())
    return dispersion_check(samples, water, record.dt, rtol=c.rtol, k_range=c.k_range)


def _energy(record, water, c):
    from wavephys.harness.energy import energy_check

    return energy_check(record, water, rtol=c.energy_rtol, viscosity=c.viscosity, tank=c.tank)


def _standing(record, water, c):
    from wavephys.harness.travel import standing_check

    return standing_check(record)


def _direction(record, water, c):
    from wavephys.harness.travel import direction_check

    return direction_check(record, c.direction)


def _tiling(record, water, c):
    from wavephys.harness.maps import tiling_check

    return tiling_check(record.eta)


def _quantization(record, water, c):
    from wavephys.harness.maps import quantization_check

    return quantization_check(record.eta)


def _group(record, water, c):
    from wavephys.harness.packets import group_velocity_check

    return group_velocity_check(record, water, direction=c.direction)


def _ring(record, water, c):
    from wavephys.harness.packets import ring_arrival_check

    return ring_arrival_check(record, water, source=c.source, t0=c.t0, radius=c.radius)


def _wake(angle):
    def run(record, water, c):
        from wavephys.harness.steady import wake_check

        w = dict(c.wake)
        return wake_check(record.eta[0], record.dx, water=water, angle=angle, speed=w["speed"],
                          source=w.get("source", (0.0, 0.0)), direction=w.get("direction", 0.0), size=w.get("size"))
    return run


def _normals(record, water, c):
    from wavephys.harness.maps import normals_check

    return normals_check(record.eta[0], c.normals, record.dx, convention=c.convention)


def _caustics(record, water, c):
    from wavephys.harness.maps import caustics_flux_check

    return caustics_flux_check(c.caustics)


def _flat_water(record, water, c):
    """``water``, over a flat ``bed`` claim (frames: the surface's elevation) as deep as the mean surface is
    above that bed."""
    from dataclasses import replace

    import numpy as np

    if not c.given("bed"):
        return water
    return replace(water, depth=float(np.mean(record.eta[0]) - np.mean(np.asarray(c.bed, np.float64))))


def _uneven(c) -> str:
    """How uneven the claimed bed is, in words ("" when there is no bed or it is flat)."""
    import numpy as np

    if not c.given("bed"):
        return ""
    bed = np.asarray(c.bed, np.float64)
    lo, hi = float(bed.min()), float(bed.max())
    return "" if hi - lo <= 1e-9 * max(abs(lo), abs(hi), 1e-300) else f"{lo:.4g} .. {hi:.4g} m"


def _seiche(record, water, c):
    from wavephys.harness.tank import seiche_check

    return seiche_check(record, _flat_water(record, water, c), rtol=c.rtol / 2)


def _reflection(record, water, c):
    from wavephys.harness.tank import wall_reflection_check

    return wall_reflection_check(record, _flat_water(record, water, c), tolerance=c.energy_rtol)


def _shoaling(record, water, c):
    from wavephys.harness.shoaling import shoaling_check

    return shoaling_check(record, water, c.floor)


def _depth(record, c):
    """Depth frames of a shallow-water record: its heights over the claimed bed, 0 where below it (dry)."""
    import numpy as np

    return np.maximum(np.asarray(record.eta, np.float64) - np.asarray(c.bed, np.float64)[None], 0.0)


def _mass(record, water, c):
    from wavephys.harness.shallow_water import mass_check

    return mass_check(_depth(record, c), record.dx)


def _lake(record, water, c):
    from wavephys.harness.shallow_water import lake_at_rest_check

    return lake_at_rest_check(_depth(record, c), c.bed, record.dx)


def _dam(record, water, c):
    from wavephys.harness.shallow_water import dam_break_check

    d = c.dam
    return dam_break_check(_depth(record, c), record.dx, record.dt, d["h0"], dam=d["x"], hr=d.get("hr", 0.0),
                           t0=d.get("t0", 0.0), g=float(water.g), rtol=max(c.rtol, 0.05))


def _resolution(record, water, c):
    from wavephys.harness.maps import resolution_check

    other = c.other
    return resolution_check(record.eta, record.dx, other.eta, other.dx)


def _wake_size(c) -> str:
    return "" if (c.wake or {}).get("size") is not None else \
        "the source's size, wake=dict(size=...) (--wake-size SIGMA)"


RECORD_CHECKS = {c.name: c for c in (
    RecordCheck("dispersion", "omega(k) of every shell of |k| against linear theory (worst relative error)", (),
                _dispersion, min_frames=16, periodic=True, instead="seiche", linear=True),
    RecordCheck("energy", "drift of the wave energy over the record, with the damping rate per k and its kind", (),
                _energy, linear=True),
    RecordCheck("tiling", "the wrap step of the frames against an ordinary step (seams, clamped edges)", (), _tiling,
                periodic=True, linear=True),
    RecordCheck("quantization", "noise of the lattice the heights are stored on, against the rms height", (),
                _quantization),
    RecordCheck("standing", "phase locking of every mode's +omega and -omega parts (a sea that does not travel)",
                ("sea",), _standing),
    RecordCheck("direction", "the power-weighted mean direction of travel against the claimed one, degrees",
                ("direction",), _direction),
    RecordCheck("group_velocity", "speed of a packet's energy centroid against the mean group velocity",
                ("packet",), _group),
    RecordCheck("ring_arrival", "share of eta^2 inside the calm disc r < c_g,min (t - t0) behind the first ring",
                ("source",), _ring),
    RecordCheck("wake_edge", "outer edge of a moving source's wake in the first frame against the cusp line, degrees",
                ("wake",), _wake("edge"), min_frames=1, square=True),
    RecordCheck("wake_max", "angle of maximum amplitude on arcs behind the source (Darmon et al.; its size given), degrees",
                ("wake",), _wake("max"), min_frames=1, also=_wake_size, square=True),
    RecordCheck("normals", "the normal map against the slopes of the first frame's heights (largest angle, degrees)",
                ("normals",), _normals, min_frames=1),
    RecordCheck("caustics_flux", "mean of a caustics map against flat water's irradiance (light conserved)",
                ("caustics",), _caustics, min_frames=1),
    RecordCheck("resolution", "variance per octave of |k| against the same sea exported at another resolution",
                ("other",), _resolution, min_frames=1),
    RecordCheck("seiche", "frequencies of a tank's strongest cosine modes against omega(k_mn) (walls at the edges)",
                ("tank",), _seiche, min_frames=16, flat=True),
    RecordCheck("shoaling", "a wave train's amplitude across a floor against sqrt(c_g,ref/c_g(h)) (Green's law)",
                ("floor",), _shoaling),
    RecordCheck("wall_reflection", "amplitude kept per reflection at a tank's walls, from its modes' decay",
                ("tank",), _reflection, min_frames=16, flat=True),
    RecordCheck("mass", "the water's volume over a shallow-water record's frames (heights over a bed, closed domain)",
                ("bed",), _mass, min_frames=2, still=True),
    RecordCheck("lake_at_rest", "largest movement of a lake at rest's surface over an uneven bed, m",
                ("bed", "at_rest"), _lake, min_frames=2, still=True),
    RecordCheck("dam_break", "speed of a dam break's front (Ritter) or bore (Stoker) against the exact one, m/s",
                ("bed", "dam"), _dam, min_frames=3),
)}
"""The registry of checks on a record, by name. A new check is one function and one row (:func:`register`)."""

CLAIMS = tuple(claim_fields(extra=False))
"""The names of the claims :class:`~wavephys.harness.Claims` holds (a check may bring its own)."""


def register(row: RecordCheck) -> RecordCheck:
    """Add a check to :data:`RECORD_CHECKS` (and any claim it brings to every place claims are taken).

    Parameters
    ----------
    row : RecordCheck
        The check; its name must be new, its ``needs`` claims known or its own.

    Returns
    -------
    RecordCheck
        The row, registered.

    Raises
    ------
    ValueError
        When a check of that name exists, or it needs a claim nobody declares.
    """
    if not isinstance(row, RecordCheck):
        raise TypeError(f"row must be a RecordCheck, got {type(row).__name__}")
    if row.name in RECORD_CHECKS:
        raise ValueError(f"row: a check named {row.name!r} is registered already")
    known = set(claim_fields()) | {c.name for c in row.claims}
    unknown = [n for n in row.needs if n not in known]
    if unknown:
        raise ValueError(f"row: {row.name!r} needs claims nobody declares: {', '.join(unknown)} (declare them in its "
                         f"claims=(Claim(...),))")
    RECORD_CHECKS[row.name] = row
    add_claims(row.name, tuple(row.claims))
    return row


def unregister(name: str) -> RecordCheck:
    """Take a check out of :data:`RECORD_CHECKS`, and the claims it brought.

    Parameters
    ----------
    name : str
        The check's name.

    Returns
    -------
    RecordCheck
        The row taken out.

    Raises
    ------
    ValueError
        When no check has that name.
    """
    if not isinstance(name, str) or name not in RECORD_CHECKS:
        raise ValueError(f"name: {name!r} is not a registered check; they are {', '.join(RECORD_CHECKS)}")
    add_claims(name, ())
    return RECORD_CHECKS.pop(name)


@dataclass(frozen=True)
class RecordReport:
    """The rows of :func:`check_record`.

    Attributes
    ----------
    rows : dict of str to Check
        One row per check run, by name.
    skipped : dict of str to str
        Checks not run, with why (a claim they need was not given).
    seconds : dict of str to float
        Run time of each check, s.
    source : str
        The record's source.
    """

    rows: dict
    skipped: dict = field(default_factory=dict)
    seconds: dict = field(default_factory=dict)
    source: str = ""

    @property
    def ok(self) -> bool:
        """True when every row is ok."""
        return all(r.ok for r in self.rows.values())

    def report(self) -> str:
        """The rows' reports, one per line, then the checks skipped and why."""
        lines = [f"{name}: {row.report()}" for name, row in self.rows.items()]
        lines += [f"{name}: not run ({why})" for name, why in self.skipped.items()]
        return "\n".join(lines)

    def table(self) -> str:
        """The rows as a short table, one line per check: the verdict, what was measured against what it must
        be, then each failure's likely cause on its own line (what a failing pytest shows)."""
        lines = [f"{self.source or 'record'}: {sum(r.ok for r in self.rows.values())} of {len(self.rows)} checks "
                 f"ok"]
        width = max((len(n) for n in self.rows), default=0)
        for name, row in self.rows.items():
            rule = {"~=": "=", "<=": "<=", ">=": ">="}[row.relation]
            unit = f" {row.unit}" if row.unit else ""
            limit = (f"{row.expected:.4g}{unit} ± {row.tolerance:.3g}{'' if not row.relative else ' (relative)'}"
                     if row.relation == "~=" else f"{row.expected:.4g}{unit}")
            lines.append(f"  {'ok    ' if row.ok else 'FAILED'} {name:{width}s}  {row.measured:.4g}{unit} {rule} "
                         f"{limit}")
        for name, row in self.rows.items():
            if not row.ok:
                cause = row.note.split("likely cause: ", 1)[1] if "likely cause: " in row.note else row.note
                lines.append(f"  {name}: {cause}")
        lines += [f"  not run: {name} ({why})" for name, why in self.skipped.items()]
        return "\n".join(lines)

    def as_dict(self) -> dict:
        """JSON-ready: source, ok, rows (each :meth:`Check.as_dict` with its seconds), skipped."""
        return dict(source=self.source, ok=self.ok,
                    rows={n: dict(r.as_dict(), seconds=self.seconds.get(n)) for n, r in self.rows.items()},
                    skipped=dict(self.skipped))


def _why_not(row, claims, record) -> str:
    """Why ``row`` cannot run on this record with these claims ("" when it can)."""
    fields = claim_fields()
    missing = [fields[n].words() for n in row.needs if not claims.given(n)]
    if missing:
        return "needs " + ", ".join(missing)
    if row.also is not None and row.also(claims):
        return "needs " + row.also(claims)
    if row.periodic and claims.tank:
        return "the record is a tank: it does not wrap" + (f" (its modes: the {row.instead} row)" if row.instead
                                                           else "")
    if row.linear and claims.given("bed"):
        return "the record is shallow water over a bed: a check of linear waves on a periodic sea"
    if row.square and record is not None and record.shape[1] != record.shape[2]:
        return (f"measures on square frames (n_y = n_x), the record's are {record.shape[1]} x {record.shape[2]}: "
                f"export a square around the source")
    if claims.at_rest and not row.still:
        return "the record is a lake at rest (at_rest): it has no waves to measure"
    if row.flat and _uneven(claims):
        return (f"its theory is a flat floor's (a tank's cosine modes), and the bed is uneven ({_uneven(claims)}): "
                f"check the mass, or a lake at rest")
    if record is not None and record.shape[0] < row.min_frames:
        return (f"needs at least {row.min_frames} frames (the record has {record.shape[0]}): record "
                f"{row.min_frames - record.shape[0]} more")
    return ""


def _wanted(only, claims, record) -> tuple:
    """(the checks to run, the others with why not); a named check that cannot run is refused."""
    from wavephys.core.inputs import describe

    if only is None:
        names, skipped = [], {}
        for name, row in RECORD_CHECKS.items():
            why = _why_not(row, claims, record)
            (skipped.__setitem__(name, why) if why else names.append(name))
        if not names:
            raise ValueError(f"record: no check can run on it: {'; '.join(f'{n} {w}' for n, w in skipped.items())}")
        return names, skipped
    if not isinstance(only, (list, tuple)) or not all(isinstance(n, str) for n in only):
        raise TypeError(f"only must be a list of check names, got {describe(only)}")
    if not only:
        raise ValueError(f"only: an empty list selects no check; name some of {', '.join(RECORD_CHECKS)}, or leave "
                         f"only out to run every check the claims allow")
    unknown = [n for n in only if n not in RECORD_CHECKS]
    if unknown:
        raise ValueError(f"only: unknown check(s) {', '.join(unknown)}; the checks are {', '.join(RECORD_CHECKS)}")
    for n in only:
        row = RECORD_CHECKS[n]
        why = _why_not(row, claims, record)
        if why.startswith("needs"):
            raise ValueError(f"only: the {n} check {why}")
        if why and row.periodic and claims.tank:
            raise ValueError(f"only: the {n} check assumes a periodic domain, and the record is a tank (tank=True)"
                             + (f": its modes are checked by {row.instead}" if row.instead else ""))
        if why:
            raise ValueError(f"only: the {n} check cannot run: {why}")
    return list(dict.fromkeys(only)), {}


def check_record(record, water=None, *, only=None, claims: Optional[Claims] = None,
                 progress: Optional[Callable[[str], None]] = None, **kwargs) -> "RecordReport":
    """Run the checks of :data:`RECORD_CHECKS` on a record.

    Parameters
    ----------
    record : Record
        The frames (:class:`wavephys.harness.Record`).
    water : Water, optional
        The water of the theory (default ``Water()``), with the record's own depth and σ applied, then the
        claimed ones.
    only : list of str, optional, keyword-only
        The checks to run (default: every one whose claims are made and that the record is long enough for);
        a named check that cannot run is refused before any work, naming what it needs.
    claims : Claims, optional, keyword-only
        What the record is claimed to be (:class:`~wavephys.harness.Claims`), as one object.
    progress : callable, optional, keyword-only
        Called with a line of text before each check.
    **kwargs
        The claims by name instead (``direction=30.0, sea=True, tank=True, bed=..., rtol=0.01`` …): every field of
        :class:`~wavephys.harness.Claims` and any claim a registered check brings.

    Returns
    -------
    RecordReport
        The rows, the checks skipped and why, the run time of each.

    Raises
    ------
    TypeError
        When a keyword is no claim, or a value is of the wrong kind.
    ValueError
        When ``only`` is empty, names an unknown check or one that cannot run (a claim missing, too few frames),
        when no check can run at all, or a value is out of range.

    Examples
    --------
    >>> report = check_record(Record.from_files("frames/"), Water(sigma=0.0), sea=True)   # doctest: +SKIP
    >>> print(report.report())                                                            # doctest: +SKIP
    """
    from wavephys.core.inputs import check_instance, describe
    from wavephys.core.water import Water
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    if water is not None:
        check_instance("water", water, Water, "wavephys.Water")
    if claims is not None and kwargs:
        raise TypeError(f"give the claims as claims=Claims(...) or as keywords, not both (got {sorted(kwargs)})")
    if claims is None:
        claims = Claims.from_kwargs(**kwargs)
    check_instance("claims", claims, Claims, "wavephys.harness.Claims")
    claims.with_record(record)
    if record.tank and not claims.tank:  # the files say so: a tank is a tank whoever forgets to claim it
        from dataclasses import replace

        claims = replace(claims, tank=True)
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable or None, got {describe(progress)}")
    water = _water(record.water(water), claims)
    names, skipped = _wanted(only, claims, record)
    rows, seconds = {}, {}
    for i, name in enumerate(names):
        if progress is not None:
            progress(f"[{i + 1}/{len(names)}] {name}")
        start = time.perf_counter()
        rows[name] = RECORD_CHECKS[name].run(record, water, claims)
        seconds[name] = time.perf_counter() - start
    if not claims.tank and any(not rows[n].ok for n in rows if RECORD_CHECKS[n].periodic or n == "energy"):
        _hint_tank(record, water, rows)
    return RecordReport(rows, skipped, seconds, record.source)


def _water(water, claims):
    from dataclasses import replace

    changes = {k: getattr(claims, k) for k in ("depth", "sigma") if getattr(claims, k) is not None}
    return replace(water, **changes) if changes else water


def _hint_tank(record, water, rows):
    """Failing periodic rows of a record that looks like a tank get a note saying so (verdicts unchanged)."""
    from dataclasses import replace

    from wavephys.harness.tank import looks_like_tank

    why = looks_like_tank(record, water)
    if not why:
        return
    for n in [n for n in rows if RECORD_CHECKS[n].periodic] + ["energy"]:
        if n in rows and not rows[n].ok:
            rows[n] = replace(rows[n], note=f"{rows[n].note}; the record looks like a closed tank ({why}): if it "
                                            f"is, check it with tank=True (--tank)")
