"""One validation truth: every row of the check registry (``wavephys validate``) holds.

Each check group runs once here, parametrized over the registry, so a new validation is
tested by adding it to the registry. The float64 variants of the dtype-sensitive groups
run with x64 enabled. The other test files check what the rows cannot: bad input,
shapes, that a check can fail, and properties over families of inputs.
"""

import pytest

from wavephys.app.registry import registry

GROUPS = list(registry())
DTYPE_SENSITIVE = ["dispersion-limits", "inverse-dispersion", "energy-conservation", "step-composition",
                   "second-order-heights"]


FLOOR = 1e-6  # errors at float32 rounding are not made tighter than this


@pytest.mark.slow
@pytest.mark.parametrize("name", GROUPS)
def test_registry_rows_hold(name):
    rows = registry()[name]()
    assert rows, f"check group {name} returned no rows"
    assert all(r.quantity.isascii() for r in rows), [r.quantity for r in rows if not r.quantity.isascii()]
    failed = [r.report() for r in rows if not r.ok]
    assert not failed, "\n".join(failed)
    # a tolerance that dwarfs the measured error cannot catch a bug: at most 100 times it
    loose = [r.report() for r in rows if r.relation == "~=" and r.tolerance > 100 * max(abs(r.error), FLOOR)]
    assert not loose, "tolerance more than 100x the measured error:\n" + "\n".join(loose)


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.slow) if n == "second-order-heights" else n
                                  for n in DTYPE_SENSITIVE])
def test_registry_rows_hold_in_float64(name, x64):
    rows = registry()[name]()
    failed = [r.report() for r in rows if not r.ok]
    assert not failed, "\n".join(failed)


def test_row_names_are_unquoted_words():
    """Check names work unquoted on the command line: lower-case words joined by hyphens."""
    import re

    assert all(re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", n) for n in GROUPS), GROUPS
