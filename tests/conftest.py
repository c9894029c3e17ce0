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
    # Only programs that take 0.1 s or more to compile are written: a write costs 2.5 ms (compressing and storing
    # the executable), which for the thousands of small programs (mostly single operations run eagerly, 20-60 ms
    # each) cost more than reading them back saves (profiled over tests/caustics, planner, rendering, surfaces:
    # 6.0 s of 291 s writing 2335 programs).
    os.environ.setdefault("JAX_PERSISTENT_CACHE_MIN_COMPILE_TIME_SECS", "0.1")
    atexit.register(shutil.rmtree, _cache, ignore_errors=True)

# XLA's CPU code generator: its older per-operation emitters compile each program about twice as fast as
# the default MLIR fusion emitters (measured with jaxlib 0.10.2: a new shape of a two-operation formula
# 52 ms against 89; tests/caustics/test_caustics.py and tests/surfaces/test_surfaces.py 92 s against 123
# on 2 cores), and most of this suite's time is compiling. The programs compute the same formulas (their
# summation order may differ, within rounding). Set once for the session, and inherited like the cache,
# where this jaxlib knows the flag (an unknown XLA flag aborts the process, so a child probes it first);
# WAVEPHYS_TESTS_XLA_DEFAULTS=1 keeps XLA's defaults (.ci/run's slow runs use them). The child probes on the
# CPU (the flag is the CPU generator's; a GPU plugin is released with its jaxlib and parses the same flags).
# With it, LLVM's optimization level 1 (XLA's default is 2): it compiles the largest programs in about half the
# time (the split's step at 32², 11 000 StableHLO lines: 4.0 s against 7.4), though most programs here are small
# (XLA compile over tests/simulation/test_steppers.py and tests/caustics/test_caustics_jacobian.py: 89.3 s against
# 95.0). Whole README runs on 2 cores: 378, 435 and 439 s at level 1 (the last a fresh clone) against 423 and 487 s
# at level 2 (the last a fresh clone): about 9 %, in a run-to-run spread of 30-50 s; an interleaved A/B of three
# compile-heavy files gave 3 %. Level 0 runs 3-4 times slower and moved a float32 coverage test's texels by 1.4 %
# (the wide window in tests/caustics/test_caustics.py): not used.
_EMITTERS = "--xla_cpu_use_fusion_emitters=false --xla_backend_optimization_level=1"
if (os.environ.get("WAVEPHYS_TESTS_XLA_DEFAULTS", "") in ("", "0")
        and "xla_cpu_use_fusion_emitters" not in os.environ.get("XLA_FLAGS", "")):
    import subprocess
    import sys

    _flags = (os.environ.get("XLA_FLAGS", "") + " " + _EMITTERS).strip()
    try:
        _probe = subprocess.run([sys.executable, "-c", "import jax.numpy as j; j.ones(1).block_until_ready()"],
                                env=dict(os.environ, XLA_FLAGS=_flags, JAX_PLATFORMS="cpu"),
                                capture_output=True, timeout=120)
        if _probe.returncode == 0:
            os.environ["XLA_FLAGS"] = _flags
        else:
            os.environ["WAVEPHYS_TESTS_XLA_DEFAULTS"] = "1"  # the workers need not try again
    except (OSError, subprocess.TimeoutExpired):
        os.environ["WAVEPHYS_TESTS_XLA_DEFAULTS"] = "1"

import sys  # noqa: E402
from pathlib import Path  # noqa: E402

# bench/ is a top-level folder, not an installed package: the tests that read its measurements import it from
# the checkout. (A whole run had it on sys.path only because collecting wavephys/'s doctests puts the checkout
# there; a test file run by itself could not import it.)
_ROOT = str(Path(__file__).resolve().parent.parent)
if _ROOT not in sys.path:
    sys.path.append(_ROOT)

import jax  # noqa: E402  (after the cache settings, which JAX reads when imported)
import pytest  # noqa: E402

pytest_plugins = ["pytester"]


def _memory_mappings():
    """(mappings this process holds, the most Linux allows one: ``vm.max_map_count``), or None off Linux."""
    try:
        with open("/proc/self/maps", "rb") as maps, open("/proc/sys/vm/max_map_count") as limit:
            return maps.read().count(b"\n"), int(limit.read())
    except (OSError, ValueError):
        return None


@pytest.fixture(autouse=True, scope="module")
def _compiled_programs_released():
    """Release JAX's compiled programs after a test module once the worker holds half the mappings it may.

    Every compiled XLA:CPU program that JAX keeps holds memory mappings (3 for a small one, measured), never given
    back while its jitted function lives, and Linux refuses a process more than ``vm.max_map_count`` (65530 by
    default). A test worker compiles thousands of programs: in the README's run each worker ended holding about
    30 000 mappings, and in the slow run one went past the limit, where LLVM cannot map a new program's code
    ("Cannot allocate memory") and jaxlib 0.10.2 crashed the worker (SIGSEGV, while compiling or while writing the
    program to the persistent cache; reproduced by filling the mappings by hand). ``jax.clear_caches()`` frees
    them (1500 small programs: 5000 mappings back to 534); later modules recompile what they share, or read it
    back from the persistent cache."""
    yield
    held = _memory_mappings()
    if held is not None and held[0] > held[1] // 2:
        jax.clear_caches()


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
