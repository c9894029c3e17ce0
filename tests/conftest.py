import jax
import pytest

pytest_plugins = ["pytester"]


@pytest.fixture
def x64():
    """Run the test body with float64 enabled (jax.enable_x64 context)."""
    with jax.enable_x64(True):
        yield


def pytest_terminal_summary(terminalreporter):
    """The fuzz suite's counts per outcome (tests/test_fuzz.py), when it ran."""
    import sys

    fuzz = sys.modules.get("test_fuzz")
    if fuzz is None or not fuzz.OUTCOMES:
        return
    counts, failures = fuzz.pytest_fuzz_summary()
    total = sum(counts.values())
    line = ", ".join(f"{k} {v}" for k, v in sorted(counts.items()))
    terminalreporter.write_line(f"fuzz: {total} bad inputs tried: {line}")
