"""The Grid's wavenumbers, coordinates and mesh: the same numbers jax.numpy makes, without compiling.

They are made by NumPy, operation for operation as jax.numpy rounds them (XLA on a CPU divides
by a scalar as a multiplication by its rounded reciprocal), so every caller sees bit-identical
arrays to the eager jax.numpy formulas; and making them compiles no XLA program, where the eager
formulas compiled five to ten per new size (about 40 ms each on a 2-core CPU).
"""

import math

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys.core.grid import Grid
from wavephys.core.spectral import angular_wavenumbers

RNG = np.random.default_rng(7)
SIZES = [62, int(2 * RNG.integers(1, 600))]  # each new size compiles the eager references (~1 s)
LENGTHS = [1.0, 0.37, 1e-3, 5e3] + [float(v) for v in 10 ** RNG.uniform(-2, 3, 4)]


@pytest.mark.parametrize("x64", [False, True])
def test_grid_arrays_are_the_eager_jax_numpy_formulas_bit_for_bit(x64):
    with jax.enable_x64(x64):
        for n in SIZES[x64:]:
            for length in LENGTHS:
                s = length / n
                for real in (False, True):
                    ky, kx = angular_wavenumbers((n, n + 2 * x64), s, real, xp=jnp)
                    ry = 2.0 * math.pi * jnp.fft.fftfreq(n) / s
                    rx = (jnp.fft.rfftfreq(n + 2 * x64) if real else jnp.fft.fftfreq(n + 2 * x64)) * (2.0 * math.pi) / s
                    assert ky.dtype == ry.dtype and ky.shape == (n, 1) and kx.shape == (1, rx.size)
                    assert np.array_equal(ky[:, 0], ry) and np.array_equal(kx[0], rx), (n, length, real)
                    grid = Grid(n, length)
                    gy, gx = grid.wavenumbers(real)
                    assert np.array_equal(grid.wavenumber_magnitude(real), jnp.sqrt(gx * gx + gy * gy))
                line = grid.origin + jnp.arange(n) * grid.dx
                x, y = grid.mesh()
                assert np.array_equal(grid.coordinates, line), (n, length)
                assert np.array_equal(grid.edges, -0.5 * grid.length + jnp.arange(n + 1) * grid.dx)
                assert np.array_equal(x, jnp.broadcast_to(line[None, :], (n, n)))
                assert np.array_equal(y, jnp.broadcast_to(line[:, None], (n, n)))
                assert x.dtype == line.dtype


def test_grid_arrays_compile_nothing_and_still_trace():
    compiles = []

    def listen(event, duration, **kw):
        if "backend_compile" in event:
            compiles.append(kw.get("fun_name", event))

    grid = Grid(2 * int(RNG.integers(300, 400)), 2.5)  # a size no other test uses
    jax.monitoring.register_event_duration_secs_listener(listen)
    try:
        arrays = (grid.wavenumbers(), grid.wavenumbers(True), grid.wavenumber_magnitude(True), grid.mesh(),
                  grid.coordinates, grid.edges)
        jax.block_until_ready(arrays)
    finally:
        jax.monitoring.unregister_event_duration_listener(listen)
    assert compiles == [], compiles
    # a Grid whose length is traced (inside jit) makes the same arrays with jax.numpy
    traced = jax.jit(lambda length: Grid(grid.n, length).wavenumber_magnitude(True))(grid.length)
    np.testing.assert_allclose(traced, grid.wavenumber_magnitude(True), rtol=1e-6)
    mesh = jax.jit(lambda length: Grid(grid.n, length).mesh()[0])(grid.length)
    np.testing.assert_allclose(mesh, grid.mesh()[0], rtol=1e-6, atol=1e-6)
