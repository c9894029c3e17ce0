"""Check rows: what was measured, what was expected, the tolerance, and the verdict.

Every validation in the library (``wavephys validate``, the test suite, a user's own
pytest checks through the plugin) reports :class:`Check` rows, so that a failure shows
expected against measured with its tolerance. Relations are ASCII: ``"~="`` (agreement
within a tolerance), ``"<="`` and ``">="`` (bounds).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Optional

from wavephys.core.inputs import Real, Text, _real_kind, check_bool, check_choice, check_instance, check_scalar, validate

_QUANTITY = Text(empty=False)
_TEXT = Text()


def _measured(name, value):
    """A measured value: a real scalar; NaN and inf are allowed (the row then fails)."""
    _real_kind(name, value)
    try:
        return float(value)
    except (TypeError, ValueError):
        raise TypeError(f"{name} must be a real number, got {type(value).__name__}") from None

__all__ = ["Check", "compare", "bound", "assert_check", "RELATIONS"]

RELATIONS = ("~=", "<=", ">=")


@dataclass(frozen=True)
class Check:
    """One validated quantity, with the same argument order as :func:`compare`.

    Parameters
    ----------
    quantity : str
        What is measured (a sentence fragment, with its conditions).
    measured : float
        The measured value (NaN or inf make a failed row: a measurement that did not work).
    expected : float
        The expected value (``"~="``) or the limit (``"<="``, ``">="``).
    tolerance : float
        Allowed |error| for ``"~="`` (relative to ``expected`` when ``relative``).
    relation : {"~=", "<=", ">="}
    relative : bool
        Whether the tolerance of a ``"~="`` row is relative.
    unit : str
        Unit of ``measured`` and ``expected``.
    note : str
        What the row covered or why it failed, in words (optional).
    """

    quantity: str
    measured: float
    expected: float
    tolerance: float = 0.0
    relation: str = "~="
    relative: bool = True
    unit: str = ""
    note: str = ""

    def __post_init__(self):
        _QUANTITY("quantity", self.quantity, {})
        object.__setattr__(self, "measured", _measured("measured", self.measured))
        check_scalar("expected", self.expected, allow_inf=True)
        check_scalar("tolerance", self.tolerance, lo=0.0)
        check_choice("relation", self.relation, RELATIONS)
        check_bool("relative", self.relative)
        _TEXT("unit", self.unit, {})
        _TEXT("note", self.note, {})

    @property
    def error(self) -> Optional[float]:
        """measured − expected (relative to expected for relative rows); None for bounds."""
        if self.relation != "~=":
            return None
        diff = self.measured - self.expected
        return diff / self.expected if self.relative and self.expected != 0 else diff

    @property
    def margin(self) -> float:
        """How much room the row has before it fails: tolerance − |error| for ``"~="``, the
        distance from the limit (positive inside) for bounds; negative when failed."""
        if self.relation == "~=":
            return self.tolerance - abs(self.error)
        return self.expected - self.measured if self.relation == "<=" else self.measured - self.expected

    @property
    def ok(self) -> bool:
        """True when the measured value is finite and meets the relation."""
        return math.isfinite(self.measured) and self.margin >= 0

    def as_dict(self) -> dict:
        """The row as plain data (JSON-ready), with ``error``, ``margin`` and ``ok``."""
        return {**asdict(self), "error": self.error, "margin": self.margin, "ok": self.ok}

    def report(self) -> str:
        """One line: quantity, expected, measured, the rule and the verdict (and the note)."""
        unit = f" {self.unit}" if self.unit else ""
        if self.relation == "~=":
            rule = (f"error {self.error:.3g}, tolerance +-{self.tolerance:.3g}{' relative' if self.relative else ''}")
            expect = f"expected {self.expected:.6g}{unit}"
        else:
            rule = f"bound {self.relation} {self.expected:.6g}{unit}"
            expect = f"expected {self.relation} {self.expected:.6g}{unit}"
        note = f" ({self.note})" if self.note else ""
        return (f"{self.quantity}: {expect}, measured {self.measured:.6g}{unit}, {rule}: "
                f"{'ok' if self.ok else 'FAILED'}{note}")


@validate(quantity=_QUANTITY, unit=_TEXT, note=_TEXT)
def compare(quantity: str, measured, expected, *, rtol: Optional[float] = None, atol: Optional[float] = None,
            unit: str = "", note: str = "") -> Check:
    """A ``"~="`` row: ``measured`` agrees with ``expected`` within ``rtol`` (relative) or ``atol``.

    Parameters
    ----------
    quantity : str
        What is measured (non-empty; a sentence fragment, with its conditions).
    measured : float
        The measured value, a real scalar in ``unit``; NaN or inf are accepted and make a failed row.
    expected : float
        The expected value in ``unit``, real (±inf allowed).
    rtol : float, optional, keyword-only
        Relative tolerance, >= 0 (dimensionless). Give exactly one of ``rtol`` and ``atol``.
    atol : float, optional, keyword-only
        Absolute tolerance, >= 0, in ``unit``. Give exactly one of ``rtol`` and ``atol``.
    unit : str, optional, keyword-only
        Unit of ``measured`` and ``expected`` (default ``""``).
    note : str, optional, keyword-only
        What the row covered, in words (default ``""``).

    Returns
    -------
    Check
        The row, with ``relation="~="`` and ``relative`` true when ``rtol`` was given.

    Raises
    ------
    ValueError
        When neither or both of ``rtol`` and ``atol`` are given, or a tolerance is negative.
    TypeError
        When ``measured`` is not a real number.
    """
    if (rtol is None) == (atol is None):
        raise ValueError("give exactly one of rtol, atol")
    tol = rtol if rtol is not None else atol
    check_scalar("rtol" if rtol is not None else "atol", tol, lo=0.0)
    check_scalar("expected", expected, allow_inf=True)
    return Check(quantity, _measured("measured", measured), float(expected), float(tol), "~=", rtol is not None,
                 unit, note)


@validate(quantity=_QUANTITY, limit=Real(allow_inf=True), unit=_TEXT, note=_TEXT)
def bound(quantity: str, measured, limit, *, relation: str = "<=", unit: str = "", note: str = "") -> Check:
    """A bound row: ``measured`` <= ``limit`` (or >= with ``relation=">="``).

    Parameters
    ----------
    quantity : str
        What is measured (non-empty; a sentence fragment, with its conditions).
    measured : float
        The measured value, a real scalar in ``unit``; NaN or inf are accepted and make a failed row.
    limit : float
        The bound in ``unit``, real (±inf allowed).
    relation : {"<=", ">="}, optional, keyword-only
        Direction of the bound (default ``"<="``).
    unit : str, optional, keyword-only
        Unit of ``measured`` and ``limit`` (default ``""``).
    note : str, optional, keyword-only
        What the row covered, in words (default ``""``).

    Returns
    -------
    Check
        The row, with ``expected=limit``, ``tolerance=0`` and ``relative=False``.

    Raises
    ------
    ValueError
        When ``relation`` is not ``"<="`` or ``">="``.
    """
    check_choice("relation", relation, ("<=", ">="))
    return Check(quantity, _measured("measured", measured), float(limit), 0.0, relation, False, unit, note)


def assert_check(check: Check) -> Check:
    """Raise ``AssertionError`` with the row's report unless it is ok; return it.

    Parameters
    ----------
    check : Check
        The row to assert.

    Returns
    -------
    Check
        ``check`` itself, when it is ok.

    Raises
    ------
    AssertionError
        When ``check.ok`` is false; the message is :meth:`Check.report`.
    """
    check_instance("check", check, Check, "wavephys.harness.Check")
    if not check.ok:
        raise AssertionError(check.report())
    return check
