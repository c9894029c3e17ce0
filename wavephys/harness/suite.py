"""Every law the harness measures, as one registry of checks on a :class:`~wavephys.harness.Record`.

:data:`RECORD_CHECKS` names each check, says what it measures and which claims it needs
(a direction of travel, a source, "this is a sea"); :func:`check_record` runs the ones asked
for (by default every one whose claims are given) and returns a :class:`RecordReport`: one
:class:`~wavephys.harness.Check` row per check, with its verdict and, on failure, the
likely cause. ``wavephys check FRAMES...`` and the pytest fixture are built on it.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

from wavephys.core.inputs import check_array, check_bool, check_choice, check_instance, check_scalar, describe
from wavephys.core.water import Water

__all__ = ["RecordCheck", "RECORD_CHECKS", "RecordReport", "check_record", "CLAIMS"]

CLAIMS = ("direction", "sea", "packet", "source", "wake", "normals", "caustics", "other", "tank", "floor")
"""Claims a check may need: a direction of travel (degrees), that the record is a travelling sea, that it is
one wave packet, where a single disturbance was, a moving source (its speed, where it is in the first frame, its
heading and size), the normal map or caustics map exported with the first frame, the same sea exported at
another resolution, that the record is water between four reflecting walls (a tank), the depth under each
column of a wave train crossing a floor."""


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
        The claims it needs (from :data:`CLAIMS`); none: it runs on every record.
    run : callable
        ``run(record, water, options) -> Check``.
    """

    name: str
    measures: str
    needs: tuple
    run: Callable


def _dispersion(record, water, o):
    from wavephys.harness.dispersion import dispersion_check, measure_dispersion

    samples = measure_dispersion(record.eta, record.dx, record.dt, axes="tyx")
    return dispersion_check(samples, water, record.dt, rtol=o.get("rtol", 0.02), k_range=o.get("k_range", (0, math.inf)))


def _energy(record, water, o):
    from wavephys.harness.energy import energy_check

    return energy_check(record, water, rtol=o.get("energy_rtol", 0.01), viscosity=o.get("viscosity", 0.0),
                        tank=bool(o.get("tank")))


def _standing(record, water, o):
    from wavephys.harness.travel import standing_check

    return standing_check(record)


def _direction(record, water, o):
    from wavephys.harness.travel import direction_check

    return direction_check(record, o["direction"])


def _tiling(record, water, o):
    from wavephys.harness.maps import tiling_check

    return tiling_check(record.eta)


def _quantization(record, water, o):
    from wavephys.harness.maps import quantization_check

    return quantization_check(record.eta)


def _group(record, water, o):
    from wavephys.harness.packets import group_velocity_check

    return group_velocity_check(record, water, direction=o.get("direction"))


def _ring(record, water, o):
    from wavephys.harness.packets import ring_arrival_check

    return ring_arrival_check(record, water, source=o["source"], t0=o.get("t0", 0.0), radius=o.get("radius", 0.0))


def _wake(angle):
    def run(record, water, o):
        from wavephys.harness.steady import wake_check

        w = dict(o["wake"])
        return wake_check(record.eta[0], record.dx, water=water, angle=angle, speed=w["speed"],
                          source=w.get("source", (0.0, 0.0)), direction=w.get("direction", 0.0), size=w.get("size"))
    return run


def _normals(record, water, o):
    from wavephys.harness.maps import normals_check

    return normals_check(record.eta[0], o["normals"], record.dx, convention=o.get("convention", "auto"))


def _caustics(record, water, o):
    from wavephys.harness.maps import caustics_flux_check

    return caustics_flux_check(o["caustics"])


def _seiche(record, water, o):
    from wavephys.harness.tank import seiche_check

    return seiche_check(record, water, rtol=o.get("rtol", 0.02) / 2)


def _reflection(record, water, o):
    from wavephys.harness.tank import wall_reflection_check

    return wall_reflection_check(record, water, tolerance=o.get("energy_rtol", 0.01))


def _shoaling(record, water, o):
    from wavephys.harness.shoaling import shoaling_check

    return shoaling_check(record, water, o["floor"])


def _depth(record, o):
    """Depth frames of a shallow-water record: its heights over the claimed bed, 0 where below it (dry)."""
    return np.maximum(np.asarray(record.eta, np.float64) - np.asarray(o["bed"], np.float64)[None], 0.0)


def _mass(record, water, o):
    from wavephys.harness.shallow_water import mass_check

    return mass_check(_depth(record, o), record.dx)


def _lake(record, water, o):
    from wavephys.harness.shallow_water import lake_at_rest_check

    return lake_at_rest_check(_depth(record, o), o["bed"], record.dx)


def _dam(record, water, o):
    from wavephys.harness.shallow_water import dam_break_check

    d = o["dam"]
    return dam_break_check(_depth(record, o), record.dx, record.dt, d["h0"], dam=d["x"], hr=d.get("hr", 0.0),
                           t0=d.get("t0", 0.0), g=float(water.g), rtol=max(o.get("rtol", 0.02), 0.05))


def _resolution(record, water, o):
    from wavephys.harness.maps import resolution_check

    other = o["other"]
    return resolution_check(record.eta, record.dx, other.eta, other.dx)


RECORD_CHECKS = {c.name: c for c in (
    RecordCheck("dispersion", "omega(k) of every shell of |k| against linear theory (worst relative error)", (),
                _dispersion),
    RecordCheck("energy", "drift of the wave energy over the record, with the damping rate per k and its kind", (),
                _energy),
    RecordCheck("tiling", "the wrap step of the frames against an ordinary step (seams, clamped edges)", (), _tiling),
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
                ("wake",), _wake("edge")),
    RecordCheck("wake_max", "angle of maximum amplitude on arcs behind the source (Darmon et al.), degrees",
                ("wake",), _wake("max")),
    RecordCheck("normals", "the normal map against the slopes of the first frame's heights (largest angle, degrees)",
                ("normals",), _normals),
    RecordCheck("caustics_flux", "mean of a caustics map against flat water's irradiance (light conserved)",
                ("caustics",), _caustics),
    RecordCheck("resolution", "variance per octave of |k| against the same sea exported at another resolution",
                ("other",), _resolution),
    RecordCheck("seiche", "frequencies of a tank's strongest cosine modes against omega(k_mn) (walls at the edges)",
                ("tank",), _seiche),
    RecordCheck("shoaling", "a wave train's amplitude across a floor against sqrt(c_g,ref/c_g(h)) (Green's law)",
                ("floor",), _shoaling),
    RecordCheck("wall_reflection", "amplitude kept per reflection at a tank's walls, from its modes' decay",
                ("tank",), _reflection),
    RecordCheck("mass", "the water's volume over a shallow-water record's frames (heights over a bed, closed domain)",
                ("bed",), _mass),
    RecordCheck("lake_at_rest", "largest movement of a lake at rest's surface over an uneven bed, m",
                ("bed", "at_rest"), _lake),
    RecordCheck("dam_break", "speed of a dam break's front (Ritter) or bore (Stoker) against the exact one, m/s",
                ("bed", "dam"), _dam),
)}
LINEAR_ONLY = ("dispersion", "energy", "tiling")
"""Checks of linear waves on a periodic sea, skipped for a shallow-water record (a bed claimed)."""
PERIODIC_ONLY = {"dispersion": "seiche", "tiling": None}
"""Checks that assume a periodic domain, skipped for a tank (and the check that takes their place)."""
"""The registry of checks on a record, by name."""


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

    def as_dict(self) -> dict:
        """JSON-ready: source, ok, rows (each :meth:`Check.as_dict` with its seconds), skipped."""
        return dict(source=self.source, ok=self.ok,
                    rows={n: dict(r.as_dict(), seconds=self.seconds.get(n)) for n, r in self.rows.items()},
                    skipped=dict(self.skipped))


def _wanted(only, options) -> tuple[list, dict]:
    have = {"direction": options.get("direction") is not None, "sea": bool(options.get("sea")),
            "source": options.get("source") is not None, "packet": bool(options.get("packet")),
            "wake": options.get("wake") is not None, "normals": options.get("normals") is not None,
            "caustics": options.get("caustics") is not None, "other": options.get("other") is not None,
            "tank": bool(options.get("tank")), "floor": options.get("floor") is not None,
            "bed": options.get("bed") is not None, "at_rest": bool(options.get("at_rest")),
            "dam": options.get("dam") is not None}
    flags = {"direction": "direction= (--direction DEG)", "sea": "sea=True (--sea)",
             "source": "source= (--source X,Y)", "packet": "packet=True (--packet)",
             "wake": "wake=dict(speed=...) (--wake U)", "normals": "normals= (--normals FILE)",
             "caustics": "caustics= (--caustics FILE)", "other": "other= (--other FRAMES)",
             "tank": "tank=True (--tank)", "floor": "floor= (--floor FILE)", "bed": "bed= (--bed FILE)",
             "at_rest": "at_rest=True (--at-rest)", "dam": "dam=dict(x=, h0=) (--dam X H0)"}
    wake = options.get("wake") or {}
    if only is None:
        names = [n for n, c in RECORD_CHECKS.items() if all(have[x] for x in c.needs)
                 and (n != "wake_max" or wake.get("size") is not None)]
        skipped = {n: "needs " + ", ".join(flags[x] for x in c.needs) for n, c in RECORD_CHECKS.items()
                   if n not in names}
        if have["tank"]:
            for n, instead in PERIODIC_ONLY.items():
                if n in names:
                    names.remove(n)
                    skipped[n] = "the record is a tank: it does not wrap" + (f" (its modes: the {instead} row)"
                                                                            if instead else "")
        if have["bed"]:
            for n in LINEAR_ONLY:
                if n in names:
                    names.remove(n)
                    skipped[n] = "the record is shallow water over a bed: a check of linear waves on a periodic sea"
        return names, skipped
    if not isinstance(only, (list, tuple)) or not all(isinstance(n, str) for n in only):
        raise TypeError(f"only must be a list of check names, got {describe(only)}")
    unknown = [n for n in only if n not in RECORD_CHECKS]
    if unknown:
        raise ValueError(f"only: unknown check(s) {', '.join(unknown)}; the checks are {', '.join(RECORD_CHECKS)}")
    for n in only:
        if have["tank"] and n in PERIODIC_ONLY:
            raise ValueError(f"only: the {n} check assumes a periodic domain, and the record is a tank (tank=True)"
                             + (f": its modes are checked by {PERIODIC_ONLY[n]}" if PERIODIC_ONLY[n] else ""))
        missing = [flags[x] for x in RECORD_CHECKS[n].needs if not have[x]]
        if n == "wake_max" and have["wake"] and wake.get("size") is None:
            missing.append("the source's size, wake=dict(size=...) (--wake-size SIGMA)")
        if missing:
            raise ValueError(f"only: the {n} check needs {', '.join(missing)}")
    return list(dict.fromkeys(only)), {}


def check_record(record, water: Optional[Water] = None, *, only=None, direction: Optional[float] = None,
                 sea: bool = False, packet: bool = False, source=None, t0: float = 0.0, radius: float = 0.0,
                 viscosity: float = 0.0, rtol: float = 0.02, energy_rtol: float = 0.01, k_range=(0.0, math.inf),
                 wake: Optional[dict] = None, normals=None, convention: str = "auto", caustics=None, other=None,
                 tank: bool = False, floor=None, bed=None, at_rest: bool = False, dam: Optional[dict] = None,
                 progress: Optional[Callable[[str], None]] = None) -> RecordReport:
    """Run the checks of :data:`RECORD_CHECKS` on a record.

    Parameters
    ----------
    record : Record
        The frames (:class:`wavephys.harness.Record`).
    water : Water, optional
        The water of the theory (default ``Water()``), with the record's claimed depth and σ applied.
    only : list of str, optional, keyword-only
        The checks to run (default: every one whose claims are given); a named check whose claim is missing is
        refused before any work.
    direction : float, optional, keyword-only
        The claimed direction of travel, degrees (0 = +x, 90 = +y).
    sea : bool, optional, keyword-only
        The record is a sea meant to travel (runs the standing-wave check).
    packet : bool, optional, keyword-only
        The record is one wave packet (runs the group-velocity check).
    source : (float, float), optional, keyword-only
        Where a single disturbance was, m (runs the ring-arrival check), with ``t0`` (s from the first frame)
        and ``radius`` (m).
    t0, radius : float, optional, keyword-only
        See ``source``.
    viscosity : float, optional, keyword-only
        Kinematic viscosity the simulator claims to model, m²/s, >= 0 (default 0).
    rtol : float, optional, keyword-only
        Dispersion tolerance, relative, > 0 (default 0.02).
    energy_rtol : float, optional, keyword-only
        Energy drift tolerance over the record, > 0 (default 0.01).
    k_range : (float, float), optional, keyword-only
        Band of the dispersion check, rad/m (default all).
    wake : dict, optional, keyword-only
        A moving source in the first frame (runs the wake checks): ``speed`` (m/s, required), ``source`` (x, y)
        where it is, m, in the grid convention (default the centre), ``direction`` its heading, degrees (default
        0 = +x), ``size`` σ of a Gaussian pressure source, m (needed by ``wake_max``).
    normals : array_like (n_y, n_x, 3), optional, keyword-only
        The normal map exported with the first frame, packed 0.5 + 0.5 n or float n (runs ``normals``), with
        ``convention`` ``"auto"`` (detect and report), ``"opengl"`` or ``"directx"``.
    convention : {"auto", "opengl", "directx"}, optional, keyword-only
        See ``normals``.
    caustics : array_like (n_y, n_x) or (n_t, n_y, n_x), optional, keyword-only
        A caustics map relative to flat water's irradiance (runs ``caustics_flux``).
    other : Record, optional, keyword-only
        The same sea exported at another resolution (runs ``resolution``).
    tank : bool, optional, keyword-only
        The record is water between four reflecting walls half a sample outside its edges (runs ``seiche`` and
        ``wall_reflection``, measures the energy on the tank's modes, skips the periodic-only ``dispersion`` and
        ``tiling``). A record that fails those without the claim and looks like a tank gets a note saying so.
    floor : array_like (n_x,), optional, keyword-only
        The still-water depth under each column, m, of a wave train travelling along x (runs ``shoaling``).
    bed : array_like (n_y, n_x), optional, keyword-only
        The record is shallow water: its frames are the surface over this bed elevation, m (dry where below it).
        Runs ``mass`` (a closed domain's volume) and skips the linear-wave checks ``dispersion``, ``energy``
        and ``tiling``.
    at_rest : bool, optional, keyword-only
        With ``bed``: the water was started at rest with a flat surface (runs ``lake_at_rest``).
    dam : dict, optional, keyword-only
        With ``bed``: a dam break on a flat bed, released at rest — ``x`` (the dam's position, m from the frames'
        left edge), ``h0`` (depth behind it, m), optionally ``hr`` (ahead, default 0: dry) and ``t0`` (the first
        frame's time after release, s). Runs ``dam_break`` (its tolerance: ``rtol`` or 5 %, whichever is
        larger: the thin front of a consistent solver lags a few per cent on coarse cells).
    progress : callable, optional, keyword-only
        Called with a line of text before each check.

    Returns
    -------
    RecordReport
        The rows, the checks skipped and why, the run time of each.

    Raises
    ------
    ValueError
        When ``only`` names an unknown check or one whose claim is missing, or a value is out of range.

    Examples
    --------
    >>> report = check_record(Record.from_files("frames/"), Water(sigma=0.0), sea=True)   # doctest: +SKIP
    >>> print(report.report())                                                            # doctest: +SKIP
    """
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    if water is not None:
        check_instance("water", water, Water, "wavephys.Water")
    water = record.water(water)
    check_bool("sea", sea)
    check_bool("packet", packet)
    check_bool("tank", tank)
    if direction is not None:
        check_scalar("direction", direction)
    check_scalar("t0", t0)
    check_scalar("radius", radius, lo=0.0)
    check_scalar("viscosity", viscosity, lo=0.0)
    check_scalar("rtol", rtol, lo=0.0, lo_open=True)
    check_scalar("energy_rtol", energy_rtol, lo=0.0, lo_open=True)
    if progress is not None and not callable(progress):
        raise TypeError(f"progress must be callable or None, got {describe(progress)}")
    if wake is not None:
        if not isinstance(wake, dict):
            raise TypeError(f"wake must be a dict (speed=, source=, direction=, size=), got {describe(wake)}")
        unknown = set(wake) - {"speed", "source", "direction", "size"}
        if unknown or "speed" not in wake:
            raise ValueError(f"wake must hold speed (m/s) and optionally source, direction, size; got keys "
                             f"{sorted(wake)}")
        check_scalar("wake['speed']", wake["speed"], lo=0.0, lo_open=True)
        if wake.get("size") is not None:
            check_scalar("wake['size']", wake["size"], lo=0.0, lo_open=True)
        check_scalar("wake['direction']", wake.get("direction", 0.0), lo=-360.0, hi=360.0)
    if other is not None:
        check_instance("other", other, Record, "wavephys.harness.Record")
    check_choice("convention", convention, ("auto", "opengl", "directx"))
    if caustics is not None:
        check_array("caustics", caustics, lo=0.0)
        if np.ndim(caustics) not in (2, 3):
            raise ValueError(f"caustics must be a map (n_y, n_x) or maps (n_t, n_y, n_x), got shape "
                             f"{np.shape(caustics)}")
    if normals is not None:
        check_array("normals", normals, ndim=3)
    options = dict(direction=direction, sea=sea, packet=packet, source=source, t0=t0, radius=radius,
                   viscosity=viscosity, rtol=rtol, energy_rtol=energy_rtol, k_range=k_range, wake=wake,
                   normals=normals, convention=convention, caustics=caustics, other=other, tank=tank, floor=floor)
    if floor is not None:
        check_array("floor", floor, ndim=1, shape_tail=(record.shape[2],), lo=0.0)
    check_bool("at_rest", at_rest)
    if bed is not None:
        check_array("bed", bed, ndim=2, shape_tail=tuple(record.shape[1:]))
    elif at_rest or dam is not None:
        raise ValueError("at_rest and dam describe shallow water: give its bed elevation too, bed= (--bed FILE)")
    if dam is not None:
        if not isinstance(dam, dict):
            raise TypeError(f"dam must be a dict (x=, h0=, hr=, t0=), got {describe(dam)}")
        if set(dam) - {"x", "h0", "hr", "t0"} or not {"x", "h0"} <= set(dam):
            raise ValueError(f"dam must hold x (m) and h0 (m), and optionally hr and t0; got keys {sorted(dam)}")
        check_scalar("dam['x']", dam["x"])
        check_scalar("dam['h0']", dam["h0"], lo=0.0, lo_open=True)
        check_scalar("dam['hr']", dam.get("hr", 0.0), lo=0.0)
        check_scalar("dam['t0']", dam.get("t0", 0.0), lo=0.0)
    options.update(bed=bed, at_rest=at_rest, dam=dam)
    if source is not None:
        check_array("source", source, ndim=1, shape_tail=(2,))
    names, skipped = _wanted(only, options)
    rows, seconds = {}, {}
    for i, name in enumerate(names):
        if progress is not None:
            progress(f"[{i + 1}/{len(names)}] {name}")
        start = time.perf_counter()
        rows[name] = RECORD_CHECKS[name].run(record, water, options)
        seconds[name] = time.perf_counter() - start
    if not tank and any(not rows[n].ok for n in PERIODIC_ONLY.keys() | {"energy"} if n in rows):
        _hint_tank(record, water, rows)
    return RecordReport(rows, skipped, seconds, record.source)


def _hint_tank(record, water, rows):
    """Failing periodic rows of a record that looks like a tank get a note saying so (verdicts unchanged)."""
    from dataclasses import replace

    from wavephys.harness.tank import looks_like_tank

    why = looks_like_tank(record, water)
    if not why:
        return
    for n in list(PERIODIC_ONLY) + ["energy"]:
        if n in rows and not rows[n].ok:
            rows[n] = replace(rows[n], note=f"{rows[n].note}; the record looks like a closed tank ({why}): if it "
                                            f"is, check it with tank=True (--tank)")
