"""The suite's own footing: what tests/conftest.py relies on to keep a long-lived test worker alive.

A worker compiles thousands of XLA programs, each holding memory mappings while JAX keeps it, and Linux refuses
a process more than ``vm.max_map_count`` of them (past it jaxlib 0.10.2 crashed a slow-run worker with SIGSEGV).
The conftest releases JAX's compiled programs after a module once a worker holds half the limit; this checks
that releasing them gives the mappings back, so the guard guards.
"""

import jax
import jax.numpy as jnp
import pytest

import conftest

PROGRAMS = 40


@pytest.mark.skipif(conftest._memory_mappings() is None, reason="/proc/self/maps (Linux) is what the guard reads")
def test_releasing_compiled_programs_gives_their_memory_mappings_back():
    """40 small programs held by their jitted functions take mappings (3 each, measured); jax.clear_caches(),
    what the conftest calls, gives at least 2 of each back while the functions themselves are still held."""
    before, limit = conftest._memory_mappings()
    assert limit > 0
    held = [jax.jit(lambda x, i=i: x * i + 1.0) for i in range(PROGRAMS)]
    for f in held:
        f(jnp.ones(3, jnp.float32)).block_until_ready()
    compiled = conftest._memory_mappings()[0]
    jax.clear_caches()
    released = conftest._memory_mappings()[0]
    assert compiled - before >= 2 * PROGRAMS, (before, compiled)
    assert compiled - released >= 2 * PROGRAMS, (compiled, released)
    assert len(held) == PROGRAMS  # the functions outlive the release: it is the caches that held the programs
