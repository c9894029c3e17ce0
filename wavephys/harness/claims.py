"""What a user claims about a record, as data: :class:`Claims`, each field one :class:`Claim`.

A record's frames say nothing of what they are meant to be: a sea that travels, toward some
direction, over some depth, in a walled tank, a shallow-water run over a bed. Those are
*claims*, and each check of :data:`~wavephys.harness.RECORD_CHECKS` needs some of them. Every
claim is declared once, here (or by the registry row of a check that brings a new one): its
name, what it means with its unit, how it is checked, and how the command reads it. From that
one declaration come :class:`Claims` (``check_record(record, **claims)`` and the pytest fixture
take the same words), the flags and help of ``wavephys check FRAMES``, and the messages that
name a missing claim in both the Python and the command's words.

This module imports nothing heavy (``wavephys check --help`` reads it); values are checked on
first use.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import Any, Callable, Optional

__all__ = ["Claim", "Claims", "CLAIM_KINDS", "claim_fields", "parse_number", "add_claims", "extra_claims"]

CLAIM_KINDS = ("number", "flag", "pair", "range", "choice", "map", "array", "frames", "wake", "dam")
"""How a claim's value is given: a number (fractions such as 1/60 accepted on the command line), a flag (true
when given), a pair X,Y, a range LO,HI, a choice, a map file (an EXR/PNG/npy texture), an array file (.npy), other
frames (another record), and the two compound claims (a moving source; a dam break)."""


def parse_number(text: str) -> float:
    """A number as the command reads it: ``0.0167``, ``1/60``, ``2/256``, ``1e-3``, ``inf``.

    Parameters
    ----------
    text : str
        A number or a fraction of two numbers.

    Returns
    -------
    float
        Its value (inf allowed, NaN refused).

    Raises
    ------
    ValueError
        When it is not a number, names what was read.
    """
    if not isinstance(text, str):
        raise TypeError(f"text must be a number as text (str: '0.05', '1/60'), got {type(text).__name__}")
    num, sep, den = str(text).strip().partition("/")
    try:
        value = float(num) / float(den) if sep else float(num)
    except (ValueError, ZeroDivisionError):
        raise ValueError(f"expected a number (0.0167, 1/60, 2e-3), got {text!r}") from None
    if math.isnan(value):
        raise ValueError(f"expected a number, got {text!r}")
    return value


@dataclass(frozen=True)
class Claim:
    """One thing a user may claim about a record.

    Attributes
    ----------
    name : str
        Its keyword in Python (``check_record(..., direction=30.0)``).
    kind : str
        How its value is given, one of :data:`CLAIM_KINDS`.
    help : str
        What it means, with its unit (the command's ``--help`` and the docs show it).
    flag : str, optional
        Its option on the command line (default ``--`` + the name with ``-`` for ``_``).
    metavar : str
        What the option's value is called in ``--help``.
    lo, hi : float, optional
        The range of a number (``lo_open``: strictly above ``lo``).
    choices : tuple
        The values of a choice.
    default : object
        The value when not claimed.
    requires : tuple of str
        Claims that must be made with this one (``at_rest`` requires ``bed``).
    inf_ok : bool
        A number that may be infinite (a depth: deep water).
    check : callable, optional
        ``check(value, record)`` → the value, validated and converted (arrays against the record's shape);
        raises TypeError/ValueError naming the claim.
    """

    name: str
    kind: str
    help: str
    flag: Optional[str] = None
    metavar: str = ""
    lo: Optional[float] = None
    hi: Optional[float] = None
    lo_open: bool = False
    choices: tuple = ()
    default: Any = None
    requires: tuple = ()
    check: Optional[Callable] = None
    inf_ok: bool = False

    def __post_init__(self):
        if self.kind not in CLAIM_KINDS:
            raise ValueError(f"kind must be one of {CLAIM_KINDS}, got {self.kind!r}")
        if not self.name.isidentifier():
            raise ValueError(f"name must be a Python identifier, got {self.name!r}")

    @property
    def option(self) -> str:
        """The command-line option."""
        return self.flag or "--" + self.name.replace("_", "-")

    def words(self) -> str:
        """How to make the claim, in Python's and the command's words: ``direction= (--direction DEG)``."""
        if self.kind == "flag":
            return f"{self.name}=True ({self.option})"
        return f"{self.name}= ({self.option}{' ' + self.metavar if self.metavar else ''})"

    def given(self, value) -> bool:
        """Whether ``value`` makes the claim: a flag that is true, anything else that is not None and not the
        claim's default."""
        if self.kind == "flag":
            return bool(value)
        if value is None:
            return False
        try:
            return bool(value != self.default) if self.default is not None else True
        except (TypeError, ValueError):  # an array compared with a default
            return True

    def validate(self, value, record=None):
        """The value checked and converted (``record``: the frames, for arrays of their shape)."""
        from wavephys.core.inputs import check_bool, check_choice, check_scalar

        if value is None:
            if self.default is not None:
                raise TypeError(f"{self.name} must be given as {self.kind} (default {self.default!r}), got None")
            return value
        if self.kind == "number":
            value = check_scalar(self.name, value, lo=self.lo, hi=self.hi, lo_open=self.lo_open,
                                 allow_inf=self.inf_ok)
        elif self.kind == "flag":
            value = check_bool(self.name, value)
        elif self.kind == "choice":
            value = check_choice(self.name, value, self.choices)
        elif self.kind in ("pair", "range"):
            value = _pair(self.name, value, self.kind)
        if self.check is not None:
            value = self.check(value, record)
        return value


def _pair(name, value, kind):
    from wavephys.core.inputs import check_array

    check_array(name, value, ndim=1, shape_tail=(2,), lo=0.0 if kind == "range" else None,
                allow_inf=kind == "range")
    a, b = (float(v) for v in value)
    if kind == "range" and not a < b:
        raise ValueError(f"{name} must be (low, high) with low < high, got {[a, b]}")
    return (a, b)


def _array(name, ndim, tail=None, lo=None):
    """A check of an array claim: ``ndim`` dimensions, ``tail(record)`` its shape against the frames."""
    def check(value, record):
        import numpy as np

        from wavephys.core.inputs import check_array

        shape = None if record is None or tail is None else tail(record)
        check_array(name, value, ndim=ndim, lo=lo, shape_tail=shape)
        return np.asarray(value, np.float64)
    return check


def _caustics(value, record):
    import numpy as np

    from wavephys.core.inputs import check_array

    check_array("caustics", value, lo=0.0)
    if np.ndim(value) not in (2, 3):
        raise ValueError(f"caustics must be a map (n_y, n_x) or maps (n_t, n_y, n_x), got shape {np.shape(value)}")
    return np.asarray(value, np.float64)


def _other(value, record):
    from wavephys.core.inputs import check_instance
    from wavephys.harness.record import Record

    return check_instance("other", value, Record, "wavephys.harness.Record")


def _wake(value, record):
    from wavephys.core.inputs import check_scalar, describe

    if not isinstance(value, dict):
        raise TypeError(f"wake must be a dict (speed=, source=, direction=, size=), got {describe(value)}")
    unknown = set(value) - {"speed", "source", "direction", "size"}
    if unknown or "speed" not in value:
        raise ValueError(f"wake must hold speed (m/s) and optionally source, direction, size; got keys "
                         f"{sorted(value)}")
    check_scalar("wake['speed']", value["speed"], lo=0.0, lo_open=True)
    if value.get("size") is not None:
        check_scalar("wake['size']", value["size"], lo=0.0, lo_open=True)
    check_scalar("wake['direction']", value.get("direction", 0.0), lo=-360.0, hi=360.0)
    if value.get("source") is not None:
        _pair("wake['source']", value["source"], "pair")
    return dict(value)


def _dam(value, record):
    from wavephys.core.inputs import check_scalar, describe

    if not isinstance(value, dict):
        raise TypeError(f"dam must be a dict (x=, h0=, hr=, t0=), got {describe(value)}")
    if set(value) - {"x", "h0", "hr", "t0"} or not {"x", "h0"} <= set(value):
        raise ValueError(f"dam must hold x (m) and h0 (m), and optionally hr and t0; got keys {sorted(value)}")
    check_scalar("dam['x']", value["x"])
    check_scalar("dam['h0']", value["h0"], lo=0.0, lo_open=True)
    check_scalar("dam['hr']", value.get("hr", 0.0), lo=0.0)
    check_scalar("dam['t0']", value.get("t0", 0.0), lo=0.0)
    return dict(value)


def _claim(c: Claim, default=None):
    return field(default=c.default if default is None else default, metadata={"claim": c})


@dataclass(frozen=True)
class Claims:
    """What a record is claimed to be, and the tolerances it is held to (module doc).

    Every field is optional; a check runs when the claims it needs are made. The command's options are
    these fields' ``Claim.option`` (``direction`` → ``--direction``).

    Parameters
    ----------
    depth : float, optional
        The still-water depth, m, > 0 (inf: deep water; default: the record's own, else deep).
    sigma : float, optional
        The surface tension, N/m, >= 0 (default: the record's own, else clean water's 0.0728).
    direction : float, optional
        The direction of travel, degrees (0 = +x, 90 = +y).
    sea : bool
        The record is a sea meant to travel (the standing-wave check).
    packet : bool
        The record is one wave packet (the group-velocity check).
    source : (float, float), optional
        Where one disturbance was, m, in the grid convention (the ring-arrival check), with ``t0`` and ``radius``.
    t0 : float
        When it happened, s from the first frame (default 0).
    radius : float
        Its radius, m, >= 0 (default 0).
    viscosity : float
        The kinematic viscosity the simulator models, m²/s, >= 0 (default 0).
    rtol : float
        The dispersion check's tolerance, relative, > 0 (default 0.02).
    energy_rtol : float
        The energy drift allowed over the record, > 0 (default 0.01).
    k_range : (float, float)
        The dispersion check's band, rad/m (default all).
    wake : dict, optional
        A moving source in the first frame: ``speed`` (m/s), ``source`` (x, y) m, ``direction`` (degrees),
        ``size`` (σ of a Gaussian pressure, m; the angle of maximum amplitude needs it).
    normals : array (n_y, n_x, 3), optional
        The normal map exported with the first frame (packed 0.5 + 0.5 n, or float n).
    convention : {"auto", "opengl", "directx"}
        The normal map's green convention (default "auto": detected and reported).
    caustics : array (n_y, n_x) or (n_t, n_y, n_x), optional
        A caustics map relative to flat water's irradiance.
    other : Record, optional
        The same sea exported at another resolution.
    tank : bool
        The water lies between four reflecting walls half a sample outside the frames' edges.
    floor : array (n_x,), optional
        The still-water depth under each column, m, of a wave train travelling along x.
    bed : array (n_y, n_x), optional
        The frames are shallow water over this bed elevation, m (dry where below it).
    at_rest : bool
        With ``bed``: the water was started flat and at rest.
    dam : dict, optional
        With ``bed``: a dam break on a flat bed released at rest: ``x`` (m from the left edge), ``h0`` (m),
        optionally ``hr`` (m, ahead of the dam) and ``t0`` (s after release of the first frame).
    extra : dict
        Claims brought by checks registered beyond these (each row's ``claims``), by name.
    """

    depth: Optional[float] = _claim(Claim("depth", "number", "the water's depth, m (default: deep)", lo=0.0,
                                          lo_open=True, metavar="M", inf_ok=True))
    sigma: Optional[float] = _claim(Claim("sigma", "number", "surface tension, N/m (default 0.0728; 0 for gravity "
                                          "waves)", lo=0.0, metavar="N/M"))
    direction: Optional[float] = _claim(Claim("direction", "number", "claimed direction of travel, degrees, 0 = +x",
                                              metavar="DEG"))
    sea: bool = _claim(Claim("sea", "flag", "the frames are a sea meant to travel (standing-wave check)", default=False))
    packet: bool = _claim(Claim("packet", "flag", "the frames are one wave packet (group-velocity check)",
                                default=False))
    source: Optional[tuple] = _claim(Claim("source", "pair", "where one disturbance was, m (ring-arrival check)",
                                           metavar="X,Y"))
    t0: float = _claim(Claim("t0", "number", "when it happened, s from the first frame (default 0)", default=0.0,
                             metavar="S"))
    radius: float = _claim(Claim("radius", "number", "its radius, m (default 0)", lo=0.0, default=0.0, metavar="M"))
    viscosity: float = _claim(Claim("viscosity", "number", "kinematic viscosity modelled, m^2/s (default 0)", lo=0.0,
                                    default=0.0, metavar="M2/S"))
    rtol: float = _claim(Claim("rtol", "number", "dispersion tolerance, relative (default 0.02)", lo=0.0, lo_open=True,
                               default=0.02, metavar="R"))
    energy_rtol: float = _claim(Claim("energy_rtol", "number", "energy drift allowed over the record (default 0.01)",
                                      lo=0.0, lo_open=True, default=0.01, metavar="R"))
    k_range: tuple = _claim(Claim("k_range", "range", "the dispersion check's band, rad/m (default all)",
                                  default=(0.0, math.inf), metavar="LO,HI"))
    wake: Optional[dict] = _claim(Claim("wake", "wake", "a source moving at U m/s (wake checks on the first frame)",
                                        metavar="U", check=_wake))
    normals: Any = _claim(Claim("normals", "map", "the normal map exported with the first frame (EXR RGB, PNG, npy)",
                                metavar="FILE", check=_array("normals", 3)))
    convention: str = _claim(Claim("convention", "choice", "the normal map's green convention (default: detected)",
                                   choices=("auto", "opengl", "directx"), default="auto"))
    caustics: Any = _claim(Claim("caustics", "map", "a caustics map, relative to flat water (EXR Y, PNG, npy)",
                                 metavar="FILE", check=_caustics))
    other: Any = _claim(Claim("other", "frames", "the same sea exported at another resolution (resolution check)",
                              metavar="FRAMES", check=_other))
    tank: bool = _claim(Claim("tank", "flag", "the frames are water between four reflecting walls half a sample "
                                              "outside the edges (seiche and wall-reflection checks)", default=False))
    floor: Any = _claim(Claim("floor", "array", "a .npy of the still-water depth under each column, m, of a wave "
                                                "train travelling along x (shoaling check)", metavar="FILE",
                              check=_array("floor", 1, lambda r: (r.shape[2],), lo=0.0)))
    bed: Any = _claim(Claim("bed", "array", "a .npy of the bed elevation under each cell, m: the frames are shallow "
                                            "water over it (mass check; linear-wave checks skipped)", metavar="FILE",
                            check=_array("bed", 2, lambda r: tuple(r.shape[1:]))))
    at_rest: bool = _claim(Claim("at_rest", "flag", "with --bed: the water was started flat and at rest "
                                                    "(lake-at-rest check)", default=False, requires=("bed",)))
    dam: Optional[dict] = _claim(Claim("dam", "dam", "with --bed: a dam at X m from the left edge, H0 m deep behind "
                                                     "it, HR ahead (default 0: dry) (dam-break check)",
                                       metavar="X H0 [HR]", requires=("bed",), check=_dam))
    extra: dict = field(default_factory=dict)

    def __post_init__(self):
        from wavephys.core.inputs import describe

        if not isinstance(self.extra, dict):
            raise TypeError(f"extra must be a dict of claims by name, got {describe(self.extra)}")
        known = extra_claims()
        unknown = sorted(set(self.extra) - set(known))
        if unknown:
            raise TypeError(f"{unknown} are not claims; the claims are {', '.join(n for n in claim_fields())}")
        for c in claim_fields(extra=False).values():
            object.__setattr__(self, c.name, c.validate(getattr(self, c.name)))
        object.__setattr__(self, "extra", {k: known[k].validate(v) for k, v in self.extra.items()})
        for c in self.made().values():
            missing = [r for r in c.requires if not self.given(r)]
            if missing:
                raise ValueError(f"{c.name} describes {', '.join(missing)}: give " + ", ".join(
                    claim_fields()[m].words() for m in missing) + " too")

    @classmethod
    def from_kwargs(cls, **claims) -> "Claims":
        """Claims from keywords: the fields by name, and any registered check's own claims into ``extra``.

        Raises TypeError naming a keyword that is no claim."""
        names = {f.name for f in dataclasses.fields(cls)} - {"extra"}
        extra_names = extra_claims()
        direct = {k: v for k, v in claims.items() if k in names}
        extra = {k: v for k, v in claims.items() if k in extra_names}
        unknown = sorted(set(claims) - set(direct) - set(extra))
        if unknown:
            raise TypeError(f"{unknown} are not claims; the claims are {', '.join(claim_fields())}")
        return cls(**direct, extra=extra)

    def get(self, name: str):
        """A claim's value by name (a field or a registered check's own claim; its default when not made).

        Parameters
        ----------
        name : str
            A claim's name.

        Returns
        -------
        object
            Its value.

        Raises
        ------
        ValueError
            When no claim has that name.
        """
        if not isinstance(name, str):
            raise TypeError(f"name must be a claim's name (str), got {type(name).__name__}")
        if name in self.extra:
            return self.extra[name]
        if name in claim_fields(extra=False):
            return getattr(self, name)
        extra = extra_claims()
        if name in extra:
            return extra[name].default
        raise ValueError(f"name: {name!r} is not a claim; the claims are {', '.join(claim_fields())}")

    def given(self, name: str) -> bool:
        """Whether the claim ``name`` is made.

        Parameters
        ----------
        name : str
            A claim's name.

        Returns
        -------
        bool
            True when its value makes the claim (a flag that is true, a value that is not its default).
        """
        value = self.get(name)
        return claim_fields()[name].given(value)

    def made(self) -> dict:
        """The claims that are made, by name."""
        return {n: c for n, c in claim_fields().items() if c.given(self.get(n))}

    def with_record(self, record) -> "Claims":
        """The claims checked against the record's shape (maps and arrays of its size).

        Parameters
        ----------
        record : Record
            The frames the claims are about.

        Returns
        -------
        Claims
            These claims, their arrays checked against the record.
        """
        from wavephys.core.inputs import check_instance
        from wavephys.harness.record import Record

        check_instance("record", record, Record, "wavephys.harness.Record")
        for c in claim_fields(extra=False).values():
            if c.check is not None and c.given(getattr(self, c.name)):
                object.__setattr__(self, c.name, c.validate(getattr(self, c.name), record))
        return self


_EXTRA: dict = {}  # check name -> the claims its row brings (filled by wavephys.harness.suite.register)


def add_claims(check: str, claims: tuple) -> None:
    """Declare the claims a registered check brings (:func:`wavephys.harness.suite.register` calls it).

    Parameters
    ----------
    check : str
        The check's name.
    claims : tuple of Claim
        Its own claims (an empty tuple forgets the check's).
    """
    if not isinstance(check, str):
        raise TypeError(f"check must be a check's name (str), got {type(check).__name__}")
    if not isinstance(claims, tuple) or not all(isinstance(c, Claim) for c in claims):
        raise TypeError(f"claims must be a tuple of Claim, got {type(claims).__name__}")
    if claims:
        _EXTRA[check] = claims
    else:
        _EXTRA.pop(check, None)


def extra_claims() -> dict:
    """The claims that registered checks bring beyond the fields of :class:`Claims`, by name.

    Returns
    -------
    dict of str to Claim
        Each claim a registered check declares, first declaration first.
    """
    found = {}
    for claims in _EXTRA.values():
        for c in claims:
            found.setdefault(c.name, c)
    return found


def claim_fields(extra: bool = True) -> dict:
    """Every claim by name: the fields of :class:`Claims`, and the registered checks' own.

    Parameters
    ----------
    extra : bool, optional
        Include the claims registered checks bring (default True).

    Returns
    -------
    dict of str to Claim
        The claims, fields first in their order.
    """
    if not isinstance(extra, bool):
        raise TypeError(f"extra must be True or False, got {type(extra).__name__}")
    out = {f.name: f.metadata["claim"] for f in dataclasses.fields(Claims) if "claim" in f.metadata}
    if extra:
        out.update(extra_claims())
    return out
