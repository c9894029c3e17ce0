"""The periodic square grid: it owns every coordinate, wavenumber and sampling rule.

One convention for the simulation, the optics, the textures and the renderer
(``docs/physics.md`` §0): a ``Grid(n, length)`` splits the square [−L/2, L/2)² into
n × n cells of side dx = L/n, and sample (i, j) — row i (y), column j (x) — sits at the
centre of its cell, x_j = −L/2 + (j + ½)·dx, y_i likewise. A texture of the same n texels
over the same square has its texel centres at exactly these points, so a field computed
here lands on the texel of the same index. Cell corners are at −L/2 + j·dx
(:attr:`Grid.edges`).
"""

from __future__ import annotations

from dataclasses import dataclass

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core import sampling, spectral
from wavephys.core.inputs import Array, Bool, Int, Real, check_array, check_int, check_scalar, validate
from wavephys.core.pytree import register

__all__ = ["Grid"]


_POINTS = Array()  # coordinates, m: finite numbers of any shape
_COORD = Real()
_FIELD = Array(shape=lambda a: (a["self"].n, a["self"].n), min_ndim=2)


class _FieldWithChannels(Array):
    """(n, n) or (n, n, c) on this grid."""

    def __call__(self, name, value, arguments):
        n = arguments["self"].n
        shape = np.shape(value)
        check_array(name, value, min_ndim=2, complex_ok=True)
        if shape[:2] != (n, n) or len(shape) > 3:
            raise ValueError(f"{name} must have shape ({n}, {n}) or ({n}, {n}, channels), got {shape}")
        return value


_FIELD_CHANNELS = _FieldWithChannels()


@dataclass(frozen=True)
class Grid:
    """A square, periodic grid of ``n × n`` cell-centred samples over ``length × length`` m.

    Arrays on the grid have shape ``(..., n, n)`` ordered ``(y, x)``; spacing
    ``dx = length / n``; sample centres at −L/2 + (i + ½)·dx (module doc); angular
    wavenumbers ``k = 2π·fftfreq(n, dx)`` (rad/m).

    Parameters
    ----------
    n : int
        Samples per side, even, ≥ 2 (static: it fixes array shapes).
    length : float
        Side length L, m, finite and > 0 (a pytree leaf).

    Examples
    --------
    >>> grid = Grid(4, 2.0)
    >>> [float(c) for c in grid.coordinates]
    [-0.75, -0.25, 0.25, 0.75]
    >>> grid.nearest(0.3, -0.8)      # (row, column) of the sample nearest (x, y)
    (0, 2)
    """

    n: int
    length: float

    def __post_init__(self):
        object.__setattr__(self, "n", check_int("n", self.n, lo=2, even=True))
        check_scalar("length", self.length, lo=0.0, lo_open=True)

    # -- coordinates ----------------------------------------------------------------
    @property
    def dx(self):
        """Grid spacing, m."""
        return self.length / self.n

    @property
    def origin(self):
        """Coordinate of the first sample, −L/2 + dx/2, m (on both axes)."""
        return -0.5 * self.length + 0.5 * self.dx

    @property
    def coordinates(self):
        """1-D sample coordinates (cell centres), m, shape ``(n,)``."""
        return _line(self.n, self.origin, self.dx)

    @property
    def edges(self):
        """1-D cell boundaries, m, shape ``(n + 1,)``: −L/2, −L/2 + dx, …, L/2."""
        return _line(self.n + 1, -0.5 * self.length, self.dx)

    def mesh(self):
        """``(x, y)`` sample coordinates, each shape ``(n, n)``, m."""
        return _mesh(self.n, self.origin, self.dx)

    @validate(x=_POINTS, y=_POINTS)
    def texel(self, x, y):
        """Continuous (u, v) texel coordinates of points (x, y) in m: u = 0 at column 0's centre."""
        return (sampling.texel_coordinates(x, self.length, self.n),
                sampling.texel_coordinates(y, self.length, self.n))

    @validate(x=_COORD, y=_COORD)
    def nearest(self, x: float, y: float) -> tuple[int, int]:
        """(row, column) of the sample nearest the point (x, y), wrapped periodically."""
        u, v = self.texel(float(x), float(y))
        return int(round(float(v))) % self.n, int(round(float(u))) % self.n

    @validate(x=_COORD, y=_COORD, half=Int(lo=1))
    def window(self, x: float, y: float, half: int):
        """The 2·``half`` × 2·``half`` block of samples centred as near (x, y) as the samples allow.

        Returns ``(row0, col0, (cx, cy))``: the grid index of its first row and column
        (not wrapped) and the world coordinates of the block's centre (a cell corner), m.
        A ``Grid(2·half, 2·half·dx)`` centred at (cx, cy) has its samples on the block's.
        """
        dx, edge = float(self.dx), -0.5 * float(self.length)
        c0 = int(round((float(x) - edge) / dx)) - half
        r0 = int(round((float(y) - edge) / dx)) - half
        return r0, c0, (edge + (c0 + half) * dx, edge + (r0 + half) * dx)

    # -- spectra --------------------------------------------------------------------
    @validate(real=Bool())
    def wavenumbers(self, real: bool = False):
        """``(ky, kx)`` angular wavenumbers, rad/m, shaped to broadcast to the spectrum.

        ``real=True`` gives the half spectrum of ``rfft2`` (``kx`` has ``n//2 + 1`` entries).
        """
        return spectral.angular_wavenumbers((self.n, self.n), self.dx, real, xp=jnp)

    @validate(real=Bool())
    def wavenumber_magnitude(self, real: bool = False):
        """|k| on the spectrum, rad/m, shape ``(n, n)`` or ``(n, n//2 + 1)``."""
        return _magnitude(self.n, self.dx, bool(real))

    @property
    def nyquist(self):
        """Largest resolved angular wavenumber along an axis, π/dx, rad/m."""
        return jnp.pi / self.dx

    @property
    def dk(self):
        """Wavenumber spacing 2π/L, rad/m."""
        return 2.0 * jnp.pi / self.length

    @validate(x=_POINTS, y=_POINTS, real=Bool())
    def source_phase(self, x, y, real: bool = False):
        """DFT phase factor e^{−i(kx(x − x₀) + ky(y − y₀))} of a feature centred at (x, y), m.

        A field g(x − x_s) sampled on the grid has the DFT (1/dx²)·ĝ(k)·``source_phase``
        (x₀ = y₀ = :attr:`origin`, the first sample). ``x``, ``y`` may carry a leading
        batch axis (one phase per feature).
        """
        ky, kx = self.wavenumbers(real)
        x = jnp.asarray(x)[..., None, None] - self.origin
        y = jnp.asarray(y)[..., None, None] - self.origin
        return jnp.exp(-1j * (kx * x + ky * y))

    @validate(field=_FIELD)
    def gradient(self, field, method: str = "spectral"):
        """(∂f/∂x, ∂f/∂y) of a periodic field ``(..., n, n)``: ``"spectral"`` (exact) or
        ``"central"`` differences (:data:`wavephys.core.spectral.GRADIENT_METHODS`)."""
        from wavephys.core.inputs import check_choice

        check_choice("method", method, spectral.GRADIENT_METHODS)
        return spectral.gradient(field, self.dx, method)

    @validate(field=_FIELD)
    def laplacian(self, field):
        """∇²f of a periodic field by FFT, 1/m² × f."""
        return spectral.spectral_laplacian(field, self.dx)

    @validate(field=_FIELD, factor=Int(lo=1, hi=64))
    def refine(self, field, factor: int):
        """``field`` on ``Grid(n·factor, length)`` by Fourier interpolation (band-limited fields)."""
        return spectral.fourier_refine(field, factor)

    @validate(field=_FIELD, x=Real(), y=Real())
    def shift(self, field, x, y=0.0):
        """The periodic ``field`` (..., n, n) translated by (x, y) m: f(x' − x, y' − y).

        Spectral (exact for band-limited fields, any fraction of a cell)."""
        ky, kx = self.wavenumbers(real=True)
        spec = jnp.fft.rfft2(jnp.asarray(field))
        return jnp.fft.irfft2(spec * jnp.exp(-1j * (kx * x + ky * y)), s=(self.n, self.n))

    # -- sampling -------------------------------------------------------------------
    @validate(field=_FIELD_CHANNELS, x=_POINTS, y=_POINTS)
    def sample(self, field, x, y):
        """Periodic bilinear interpolation of ``field`` (n, n[, c]) at points (x, y), m."""
        try:
            np.broadcast_shapes(np.shape(x), np.shape(y))
        except ValueError:
            raise ValueError(f"x and y must broadcast to one shape, got {np.shape(x)} and {np.shape(y)}") from None
        u, v = self.texel(x, y)
        return sampling.bilinear(field, u, v, "wrap")

    @validate(x=_POINTS, y=_POINTS, values=Array(allow_inf=False))
    def deposit(self, x, y, values):
        """Cloud-in-cell sums of ``values`` at points (x, y) on this grid's cells (periodic).

        Divide by ``dx²`` for a density per square metre. The total is conserved exactly.
        """
        if not (np.shape(x) == np.shape(y) == np.shape(values)):
            raise ValueError(f"x, y and values must have one shape, got {np.shape(x)}, {np.shape(y)}, {np.shape(values)}")
        u, v = self.texel(x, y)
        return sampling.cloud_in_cell(u, v, values, (self.n, self.n), "wrap")


register(Grid, ("length",), ("n",))


# The Grid's arrays for concrete numbers are made by NumPy in JAX's float dtype, operation for
# operation as jax.numpy rounds them, then handed over with device_put (jnp.asarray compiles a
# program per shape): made eagerly by JAX, each operation
# would be compiled by itself for every new n. Traced numbers (a Grid inside jit) use jax.numpy.
def _concrete(*values) -> bool:
    return all(isinstance(v, (int, float, np.number)) for v in values)


def _float_dtype():
    return np.dtype(jax.dtypes.canonicalize_dtype(np.float64))  # float32, or float64 with jax_enable_x64


def _line(count, start, step):
    if not _concrete(start, step):
        return start + jnp.arange(count) * step
    return jax.device_put(_host_line(count, start, step))


def _host_line(count, start, step):
    dtype = _float_dtype()
    return dtype.type(start) + np.arange(count).astype(dtype) * dtype.type(step)


def _mesh(n, origin, dx):
    if not _concrete(origin, dx):
        c = _line(n, origin, dx)
        return jnp.broadcast_to(c[None, :], (n, n)), jnp.broadcast_to(c[:, None], (n, n))
    c = _host_line(n, origin, dx)
    return (jax.device_put(np.ascontiguousarray(np.broadcast_to(c[None, :], (n, n)))),
            jax.device_put(np.ascontiguousarray(np.broadcast_to(c[:, None], (n, n)))))


def _magnitude(n, dx, real):
    if not _concrete(dx):
        ky, kx = spectral.angular_wavenumbers((n, n), dx, real, xp=jnp)
        return jnp.sqrt(kx * kx + ky * ky)
    ky, kx = spectral.jax_rounded_wavenumbers((n, n), dx, real)
    return jax.device_put(np.sqrt(kx * kx + ky * ky))
