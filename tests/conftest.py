import atexit
import os
import shutil
import tempfile

# One JAX compilation cache for this test session, shared by the xdist workers and every
# subprocess they start (notebook kernels, the command, the multi-device checks): the same
# programs are otherwise compiled again in each process. Made fresh per session (by the
# first process to import this file; the workers and subprocesses inherit it), so a run
# never reuses programs compiled by an earlier one.
if "JAX_COMPILATION_CACHE_DIR" not in os.environ:
    _cache = tempfile.mkdtemp(prefix="wavephys-tests-jax-cache-")
    os.environ["JAX_COMPILATION_CACHE_DIR"] = _cache
    os.environ.setdefault("JAX_PERSISTENT_CACHE_MIN_COMPILE_TIME_SECS", "0")
    atexit.register(shutil.rmtree, _cache, ignore_errors=True)

import jax  # noqa: E402  (after the cache settings, which JAX reads when imported)
import pytest  # noqa: E402

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
