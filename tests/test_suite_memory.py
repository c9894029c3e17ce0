"""The suite's own footing: what tests/conftest.py relies on to keep a long-lived test worker alive.

A worker compiles thousands of XLA programs, each holding memory mappings while JAX keeps it, and Linux refuses
a process more than ``vm.max_map_count`` of them (past it jaxlib 0.10.2 crashed a slow-run worker with SIGSEGV).
The conftest releases JAX's compiled programs after a module once a worker holds half the limit; this checks
that releasing them gives the mappings back, so the guard guards.
"""

import os
import subprocess
import sys

import pytest

import conftest

PROGRAMS = 20
CHILD = f"""
import jax, jax.numpy as jnp
maps = lambda: open("/proc/self/maps", "rb").read().count(b"\\n")
jnp.ones(3).block_until_ready()
before = maps()
held = [jax.jit(lambda x, i=i: x * i + 1.0) for i in range({PROGRAMS})]
for f in held:
    f(jnp.ones(3, jnp.float32)).block_until_ready()
compiled = maps()
jax.clear_caches()
print(before, compiled, maps(), len(held))
"""


@pytest.mark.skipif(conftest._memory_mappings() is None, reason="/proc/self/maps (Linux) is what the guard reads")
def test_releasing_compiled_programs_gives_their_memory_mappings_back():
    """20 small programs held by their jitted functions take mappings (3 each, measured); jax.clear_caches(),
    what the conftest calls, gives at least 2 of each back while the functions themselves are still held. Run in
    a child process, so that this worker keeps its own compiled programs."""
    env = {"JAX_PLATFORMS": "cpu", "JAX_ENABLE_COMPILATION_CACHE": "false"}
    out = subprocess.run([sys.executable, "-c", CHILD], capture_output=True, text=True, timeout=120,
                         env={**os.environ, **env})
    assert out.returncode == 0, out.stderr[-2000:]
    before, compiled, released, held = map(int, out.stdout.split())
    assert compiled - before >= 2 * PROGRAMS, (before, compiled)
    assert compiled - released >= 2 * PROGRAMS, (compiled, released)
    assert held == PROGRAMS  # the functions outlive the release: it is the caches that held the programs
