"""Wavenumbers and derivatives of periodic fields: the one implementation the Grid and the
measurement code share.

Fields are ``(..., ny, nx)`` with spacing ``spacing`` (m) on both axes; angular
wavenumbers are k = 2π·fftfreq(n, spacing) (rad/m), ``real=True`` for the ``rfft``
half spectrum along x. NumPy in → NumPy out, JAX in → JAX out.

FFT-first programs (XLA on CPU). XLA runs an FFT on one thread when another operation
precedes it in the same compiled program (openxla/xla#46345, jax-ml/jax#39081); a
fully fused simulation step measured 1.4–2× slower than its bare FFTs here. Code on
the hot path (:func:`wavephys.simulation.step`, :mod:`optics.caustics`) is therefore
split into compiled programs that each *start* with their FFTs. Under a user's own
``jit`` the pieces fuse again, which is correct, only slower on CPU.
"""

from __future__ import annotations

import functools
import math

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.sampling import array_module

__internal__ = True  # tooling for the library's own modules (users call the Grid's methods)
__all__ = ["angular_wavenumbers", "jax_rounded_wavenumbers", "cosine_refine", "spectral_gradient", "central_gradient", "central_laplacian", "GRADIENT_METHODS",
           "cosine_transform", "inverse_cosine_transform", "cosine_transform2", "inverse_cosine_transform2",
           "mode_transform", "inverse_mode_transform", "mode_wavenumbers",
           "gradient", "spectral_laplacian", "fourier_refine", "spectral_derivatives", "bspline_coefficients"]


def angular_wavenumbers(shape: tuple[int, int], spacing, real: bool = False, xp=None):
    """``(ky, kx)`` angular wavenumbers, rad/m, shaped ``(ny, 1)`` and ``(1, nx)`` (or
    ``(1, nx//2 + 1)`` with ``real``) to broadcast against a spectrum.

    For ``jax.numpy`` with a concrete spacing they are made by NumPy in JAX's float dtype,
    operation for operation as ``jax.numpy`` rounds them, and then handed over: made eagerly by
    JAX, each operation would be compiled for every new shape.

    Parameters
    ----------
    shape : tuple of int
        (ny, nx) of the field.
    spacing : float
        Grid spacing, m.
    real : bool
        The half spectrum of ``rfft2`` along x.
    xp : module, optional
        ``numpy`` or ``jax.numpy`` (default ``jax.numpy``).

    Returns
    -------
    (array, array)
        ky (ny, 1) and kx (1, nx or nx//2 + 1), rad/m.
    """
    xp = xp or array_module(spacing)
    if xp is not np and isinstance(spacing, (int, float, np.number)):
        ky, kx = jax_rounded_wavenumbers(shape, spacing, real)
        return jax.device_put(ky), jax.device_put(kx)  # (jnp.asarray compiles a program per shape)
    return _wavenumbers(shape, spacing, real, xp)


def jax_rounded_wavenumbers(shape: tuple[int, int], spacing: float, real: bool = False):
    """:func:`angular_wavenumbers` as NumPy arrays in JAX's float dtype, rounded as ``jax.numpy`` rounds them.

    Parameters
    ----------
    shape : tuple of int
        (ny, nx) of the field.
    spacing : float
        Grid spacing, m (concrete).
    real : bool
        The half spectrum along x.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray)
        ky (ny, 1) and kx (1, …), rad/m.
    """
    dtype = np.dtype(jax.dtypes.canonicalize_dtype(np.float64))  # float32, or float64 with jax_enable_x64
    return _wavenumbers(shape, dtype.type(spacing), real, np, dtype)


def _wavenumbers(shape, spacing, real, xp, dtype=None):
    ny, nx = shape
    two_pi = 2.0 * math.pi if dtype is None else dtype.type(2.0 * math.pi)
    if dtype is None:
        fy = xp.fft.fftfreq(ny)
        fx = xp.fft.rfftfreq(nx) if real else xp.fft.fftfreq(nx)
    else:  # jax.numpy's fftfreq: integers divided by n in the float dtype
        fy = _divide(((np.arange(ny) + ny // 2) % ny - ny // 2).astype(dtype), dtype.type(ny))
        fx = _divide(np.arange(nx // 2 + 1).astype(dtype) if real
                     else ((np.arange(nx) + nx // 2) % nx - nx // 2).astype(dtype), dtype.type(nx))
    divide = (lambda a, b: a / b) if dtype is None else _divide
    ky = divide(two_pi * fy, spacing)
    kx = divide(fx * two_pi, spacing)
    return ky[:, None], kx[None, :]


def _divide(a, b):
    """a / b for a scalar b as XLA on a CPU computes it: a times the rounded reciprocal of b."""
    return a * (b.dtype.type(1) / b)


def spectral_gradient(field, spacing, wavenumbers=None):
    """(∂f/∂x, ∂f/∂y) of a real periodic field by FFT: exact for band-limited fields, 1/m × f.
    ``wavenumbers``: the half spectrum's ``(ky, kx)`` (:func:`angular_wavenumbers` with
    ``real=True``) when the caller has them (a compiled caller whose spacing is traced passes the
    ones formed outside, so that its slopes round exactly as an eager call's).

    Parameters
    ----------
    field : array_like (..., ny, nx)
        A real periodic field.
    spacing : float
        Grid spacing, m.
    wavenumbers : tuple of array, optional
        The half spectrum's (ky, kx), rad/m.

    Returns
    -------
    (array, array)
        ∂f/∂x and ∂f/∂y, shape of ``field``.
    """
    xp = array_module(field)
    f = xp.asarray(field)
    ny, nx = f.shape[-2:]
    ky, kx = wavenumbers if wavenumbers is not None else angular_wavenumbers((ny, nx), spacing, real=True, xp=xp)
    spec = xp.fft.rfft2(f)
    both = xp.fft.irfft2(xp.stack([1j * kx * spec, 1j * ky * spec]), s=(ny, nx))
    return both[0], both[1]


def central_gradient(field, spacing):
    """(∂f/∂x, ∂f/∂y) by periodic central differences (second order, no transforms).

    Parameters
    ----------
    field : array_like (..., ny, nx)
        A periodic field.
    spacing : float
        Grid spacing, m.

    Returns
    -------
    (array, array)
        ∂f/∂x and ∂f/∂y, shape of ``field``.
    """
    xp = array_module(field)
    f = xp.asarray(field)
    gx = (xp.roll(f, -1, -1) - xp.roll(f, 1, -1)) / (2 * spacing)
    gy = (xp.roll(f, -1, -2) - xp.roll(f, 1, -2)) / (2 * spacing)
    return gx, gy


GRADIENT_METHODS = {"spectral": spectral_gradient, "central": central_gradient}
"""Gradient methods by name: exact spectral, or central differences (what a shader does)."""


def central_laplacian(field, spacing):
    """∇²f by the periodic 5-point stencil on the last two axes (second order, no transforms),
    1/spacing² × f. NumPy in → NumPy out, JAX in → JAX out.

    Parameters
    ----------
    field : array_like (..., ny, nx)
        A periodic field.
    spacing : float
        Grid spacing, m.

    Returns
    -------
    array_like
        ∇²f, shape of ``field``.
    """
    xp = array_module(field)
    f = xp.asarray(field)
    return (xp.roll(f, 1, -1) + xp.roll(f, -1, -1) + xp.roll(f, 1, -2) + xp.roll(f, -1, -2) - 4.0 * f) / (
        spacing * spacing)


def gradient(field, spacing, method: str = "spectral"):
    """(∂f/∂x, ∂f/∂y) by ``method`` in :data:`GRADIENT_METHODS`.

    Parameters
    ----------
    field : array_like (..., ny, nx)
        A periodic field.
    spacing : float
        Grid spacing, m.
    method : str
        ``"spectral"`` or ``"central"``.

    Returns
    -------
    (array, array)
        ∂f/∂x and ∂f/∂y, shape of ``field``.
    """
    from wavephys.core.methods import dispatch

    return dispatch(GRADIENT_METHODS, method, field, spacing, _family="gradient")


def spectral_laplacian(field, spacing):
    """∇²f of a real periodic field by FFT, 1/m² × f.

    Parameters
    ----------
    field : array_like (..., ny, nx)
        A real periodic field.
    spacing : float
        Grid spacing, m.

    Returns
    -------
    array_like
        ∇²f, shape of ``field``.
    """
    xp = array_module(field)
    f = xp.asarray(field)
    ny, nx = f.shape[-2:]
    ky, kx = angular_wavenumbers((ny, nx), spacing, real=True, xp=xp)
    return xp.fft.irfft2(-(kx * kx + ky * ky) * xp.fft.rfft2(f), s=(ny, nx))


def fourier_refine(field, factor: int):
    """A periodic field (n, n) resampled ``factor`` times finer by Fourier interpolation.

    Exact for band-limited fields. The result holds the values at the finer grid's own
    cell centres (−L/2 + (j + ½)·L/(n·factor)), which are not a superset of the coarse
    ones: the spectrum is shifted by the half-cell difference before the inverse
    transform. The Nyquist row and column are split evenly between ±k_N.

    Parameters
    ----------
    field : array_like (n, n)
        A real periodic field at the cell centres.
    factor : int
        Refinement, ≥ 1.

    Returns
    -------
    jax.Array (n·factor, n·factor)
    """
    if factor == 1:
        return field
    if array_module(field) is jnp:
        return _fourier_refine_jax(jnp.asarray(field), int(factor))
    return _fourier_refine(np.asarray(field), factor, np)


def _fourier_refine(f, factor: int, xp):
    """:func:`fourier_refine` in the array module ``xp``."""
    n = f.shape[-1]
    m, h = n * factor, n // 2
    spec = xp.fft.rfft2(f)
    nyq = spec[h:h + 1] / 2
    zeros = xp.zeros((m - n - 1, h + 1), spec.dtype)
    rows = xp.concatenate([spec[:h], nyq, zeros, nyq, spec[h + 1:]], axis=0)
    pad = xp.zeros((m, m // 2 + 1 - h - 1), spec.dtype)
    full = xp.concatenate([rows[:, :h], rows[:, h:h + 1] / 2, pad], axis=1)
    ky, kx = angular_wavenumbers((m, m), 1.0 / m, real=True, xp=xp)  # on a unit square
    shift = 0.5 / m - 0.5 / n  # fine origin − coarse origin, in units of L
    return xp.fft.irfft2(full * xp.exp(1j * (kx + ky) * shift) * (factor * factor), s=(m, m)).astype(f.dtype)


_fourier_refine_jax = jax.jit(functools.partial(_fourier_refine, xp=jnp), static_argnums=1)


def cosine_refine(field, factor: int):
    """A field in a walled tank (n, n) resampled ``factor`` times finer by cosine interpolation.

    The tank's heights are even about its walls (no flux: ∂η/∂n = 0), so their cosine series
    is the Fourier series of the field's even extension, twice the side: the extension is
    refined by :func:`fourier_refine` and its first quadrant kept. Exact for fields band-limited
    in the tank's cosine modes (Fourier interpolation of the tank itself would ring at the
    walls, where its periodic copy jumps).

    Parameters
    ----------
    field : array_like (n, n)
        A real field in a walled tank, at the cell centres.
    factor : int
        Refinement, ≥ 1.

    Returns
    -------
    jax.Array (n·factor, n·factor)
    """
    if factor == 1:
        return field
    xp = array_module(field)
    f = xp.asarray(field)
    n = f.shape[-1]
    f = xp.concatenate([f, xp.flip(f, axis=-1)], axis=-1)
    f = xp.concatenate([f, xp.flip(f, axis=-2)], axis=-2)
    return fourier_refine(f, factor)[..., :n * factor, :n * factor]


def spectral_derivatives(field, spacing):
    """(∂f/∂x, ∂f/∂y, ∂²f/∂x², ∂²f/∂x∂y, ∂²f/∂y²) of a real periodic field by one FFT: exact for
    band-limited fields (1/m and 1/m² × f), stacked on a new first axis, in ``field``'s floating dtype.

    Parameters
    ----------
    field : array_like (..., ny, nx)
        A real periodic field.
    spacing : float
        Grid spacing, m.

    Returns
    -------
    jax.Array (5, ..., ny, nx)
    """
    xp = array_module(field)
    f = xp.asarray(field)
    ny, nx = f.shape[-2:]
    ky, kx = angular_wavenumbers((ny, nx), spacing, real=True, xp=xp)
    spec = xp.fft.rfft2(f)
    planes = xp.stack([1j * kx * spec, 1j * ky * spec, -kx * kx * spec, -kx * ky * spec, -ky * ky * spec])
    out = xp.fft.irfft2(planes, s=(ny, nx))
    return out.astype(f.dtype) if xp.issubdtype(f.dtype, xp.floating) else out  # float32 stays float32 (x64 mode too)


def bspline_coefficients(field):
    r"""Coefficients c of the periodic cubic B-spline that interpolates ``field`` (..., ny, nx) at its samples.

    The spline Σ c_ij β³(u − j) β³(v − i) equals the field at every sample; its transfer
    function per axis is (4 + 2 cos ω)/6 (ω = 2π·fftfreq), so c is the field's spectrum
    divided by it (one FFT each way; Unser 1999, "Splines: a perfect fit for signal and
    image processing"). Evaluate with :func:`wavephys.core.sampling.bspline`.

    Parameters
    ----------
    field : array_like (..., ny, nx)
        Samples of a periodic field.

    Returns
    -------
    jax.Array (..., ny, nx)
        The coefficients c, in the field's floating dtype.
    """
    xp = array_module(field)
    f = xp.asarray(field)
    ny, nx = f.shape[-2:]
    wy = (4.0 + 2.0 * xp.cos(2.0 * math.pi * xp.fft.fftfreq(ny))) / 6.0
    wx = (4.0 + 2.0 * xp.cos(2.0 * math.pi * xp.fft.rfftfreq(nx))) / 6.0
    return xp.fft.irfft2(xp.fft.rfft2(f) / (wy[:, None] * wx[None, :]), s=(ny, nx)).astype(f.dtype)


# -- reflecting walls: the type-II cosine transform ---------------------------------------
# Makhoul's reordering is a gather by precomputed index (strided reversed slices measured 5×
# slower under XLA on CPU); reversals are flips (gathers fused into complex arithmetic, 3×).
def _index(n: int, kind: str):
    """Makhoul's order of n samples (the even ones ascending, then the odd ones descending), or
    its inverse permutation."""
    import numpy

    order = numpy.concatenate([numpy.arange(0, n, 2), numpy.arange(n - 1, 0, -2)])
    return order if kind == "order" else numpy.argsort(order)


def _take(x, n, kind, axis):
    return array_module(x).take(x, _index(n, kind), axis=axis)


def _negate_rows(z):
    """z(−k₁ mod n, ·) along the second-last axis."""
    xp = array_module(z)
    return xp.roll(xp.flip(z, -2), 1, -2)


def _partners(c, axis, half=True):
    """c_{n−k} along ``axis`` for k = 0 … n/2 (all k unless ``half``), with c_n = 0."""
    xp = array_module(c)
    c = xp.moveaxis(c, axis, -1)
    n = c.shape[-1]
    out = xp.concatenate([xp.zeros_like(c[..., :1]), xp.flip(c[..., 1:], -1)], axis=-1)
    return xp.moveaxis(out[..., :n // 2 + 1] if half else out, -1, axis)


def _unfold(z, n):
    """X_0 … X_{n−1} from z_0 … z_{n/2} on the last axis: X_k = Re z_k, X_{n−k} = −Im z_k."""
    xp = array_module(z)
    return xp.concatenate([xp.real(z), -xp.flip(xp.imag(z[..., 1:n // 2]), -1)], axis=-1)


def _twiddle(n: int, xp, dtype, full: bool = False):
    """e^{−iπk/(2n)} for k = 0 … n/2 (or 0 … n − 1 with ``full``)."""
    k = xp.arange(n if full else n // 2 + 1)
    return xp.exp(-0.5j * math.pi * k / n).astype(dtype)


def _is_numpy(xp) -> bool:
    return getattr(xp, "__name__", "") == "numpy"


def _check_even(n: int):
    if n % 2:
        raise ValueError(f"the cosine transform needs an even number of samples, got {n}")


def cosine_transform(field, axis: int = -1):
    """Type-II cosine transform of a real field along ``axis``: X_k = Σ_j x_j cos(πk(2j + 1)/(2n)).

    The samples x_j sit at the cell centres (j + ½)L/n of [0, L], so X_k is the field's weight
    on the k-th cosine mode cos(kπx/L) of a tank with walls at both ends (half of SciPy's
    unnormalized ``dct(type=2)``). One real FFT of length n (Makhoul 1980: samples reordered,
    transformed, turned by e^{−iπk/(2n)}); n even. :func:`inverse_cosine_transform` undoes it
    exactly. NumPy in → NumPy out (any n, by SciPy's transform), JAX in → JAX out (n even).

    References
    ----------
    J. Makhoul (1980). A fast cosine transform in one and two dimensions. *IEEE Trans. ASSP*
    28(1), 27–34.

    Parameters
    ----------
    field : array_like
        Real samples at the cell centres.
    axis : int
        The axis transformed.

    Returns
    -------
    array_like
        X_k, shape of ``field``.
    """
    xp = array_module(field)
    x = xp.asarray(field)
    n = x.shape[axis]
    if _is_numpy(xp):
        import scipy.fft

        return 0.5 * scipy.fft.dct(x, type=2, axis=axis)
    _check_even(n)
    z = xp.moveaxis(xp.fft.rfft(_take(x, n, "order", axis), axis=axis), axis, -1)
    z = z * _twiddle(n, xp, xp.result_type(x.dtype, xp.complex64))
    return xp.moveaxis(_unfold(z, n), -1, axis).astype(x.dtype)


def inverse_cosine_transform(coefficients, axis: int = -1):
    """The inverse of :func:`cosine_transform` along ``axis`` (a type-III transform): the
    samples at cell centres of the cosine series with these coefficients. One inverse real
    FFT of length n (n even).

    Parameters
    ----------
    coefficients : array_like
        X_k along ``axis``.
    axis : int
        The axis transformed.

    Returns
    -------
    array_like
        The samples, shape of ``coefficients``.
    """
    xp = array_module(coefficients)
    if _is_numpy(xp):
        import scipy.fft

        return 2.0 * scipy.fft.idct(xp.asarray(coefficients), type=2, axis=axis)
    c = xp.moveaxis(xp.asarray(coefficients), axis, -1)
    n = c.shape[-1]
    _check_even(n)
    cdtype = xp.result_type(c.dtype, xp.complex64)
    spec = xp.conj(_twiddle(n, xp, cdtype)) * (c[..., :n // 2 + 1] - 1j * _partners(c, -1))
    x = _take(xp.fft.irfft(spec, n=n, axis=-1), n, "unorder", -1)
    return xp.moveaxis(x, -1, axis).astype(c.dtype)


def cosine_transform2(field):
    """The 2-D type-II cosine transform of a real field on its last two axes ``(..., ny, nx)``
    (both even): :func:`cosine_transform` along both, by one real 2-D FFT (Makhoul's 2-D form:
    Z = ½e^{−iπk₂/2n}[e^{−iπk₁/2n}V(k₁, k₂) + e^{iπk₁/2n}V(−k₁, k₂)], X(k₁, k₂) = Re Z,
    X(k₁, n − k₂) = −Im Z). Exact inverse: :func:`inverse_cosine_transform2`.

    Parameters
    ----------
    field : array_like (..., ny, nx)
        Real samples at the cell centres, ny and nx even.

    Returns
    -------
    array_like (..., ny, nx)
        X(k₁, k₂).
    """
    xp = array_module(field)
    x = xp.asarray(field)
    if _is_numpy(xp):
        return cosine_transform(cosine_transform(x, -1), -2)
    ny, nx = x.shape[-2:]
    _check_even(ny), _check_even(nx)
    cdtype = xp.result_type(x.dtype, xp.complex64)
    spec = xp.fft.rfft2(_take(_take(x, nx, "order", -1), ny, "order", -2))  # V(k₁, k₂), k₂ ≤ nx/2
    w1 = _twiddle(ny, xp, cdtype, full=True)[:, None]
    z = 0.5 * _twiddle(nx, xp, cdtype) * (w1 * spec + xp.conj(w1) * _negate_rows(spec))
    return _unfold(z, nx).astype(x.dtype)


def inverse_cosine_transform2(coefficients):
    """The inverse of :func:`cosine_transform2` (one inverse real 2-D FFT).

    Parameters
    ----------
    coefficients : array_like (..., ny, nx)
        X(k₁, k₂).

    Returns
    -------
    array_like (..., ny, nx)
        The samples.
    """
    xp = array_module(coefficients)
    c = xp.asarray(coefficients)
    if _is_numpy(xp):
        return inverse_cosine_transform(inverse_cosine_transform(c, -1), -2)
    ny, nx = c.shape[-2:]
    _check_even(ny), _check_even(nx)
    cdtype = xp.result_type(c.dtype, xp.complex64)
    z = c[..., :nx // 2 + 1] - 1j * _partners(c, -1)
    w1 = _twiddle(ny, xp, cdtype, full=True)[:, None]
    spec = xp.conj(w1) * xp.conj(_twiddle(nx, xp, cdtype)) * (z - 1j * _partners(z, -2, half=False))
    v = xp.fft.irfft2(spec, s=(ny, nx))
    return _take(_take(v, nx, "unorder", -1), ny, "unorder", -2).astype(c.dtype)


def _tank_block(n: int, extent):
    """The (rows, columns) slices of a centred tank of ``extent`` = (my, mx) cells in an n × n grid."""
    my, mx = extent
    return slice((n - my) // 2, (n - my) // 2 + my), slice((n - mx) // 2, (n - mx) // 2 + mx)


def _embed(xp, small, shape, where):
    """``small`` placed at ``where`` (a tuple of slices of the last two axes) in zeros of ``shape``."""
    index = (Ellipsis,) + tuple(where)
    if _is_numpy(xp):
        out = xp.zeros(shape, small.dtype)
        out[index] = small
        return out
    return xp.zeros(shape, small.dtype).at[index].set(small)


def mode_transform(field, walls=(False, False), extent=None):
    """A real field ``(..., n, n)`` on the modes of its domain: ``walls`` = (x walled, y walled).

    No walls: the ``rfft2`` half spectrum ``(n, n//2 + 1)``. Walls on both axes: the 2-D
    cosine transform ``(n, n)`` (real). Walls on x only: cosine along x, then ``rfft`` along y
    (``(n//2 + 1, n)``); on y only: cosine along y, then ``rfft`` along x (``(n, n//2 + 1)``).
    ``extent`` = (my, mx) (walls on both axes only): a tank of my × mx cells centred in the grid
    (even counts), the rest land: the cosine transform of that block, its (my, mx) coefficients
    first in an ``(n, n)`` array of zeros. :func:`mode_wavenumbers` gives (k_y, k_x) on the same
    layout, and :func:`inverse_mode_transform` undoes it exactly (land comes back as zeros).

    Parameters
    ----------
    field : array_like (..., n, n)
        A real field.
    walls : tuple of bool
        (x walled, y walled).
    extent : tuple of int, optional
        (my, mx) cells of a centred tank (walls on both axes only).

    Returns
    -------
    array_like
        The spectra, on the layout above.
    """
    xp = array_module(field)
    wx, wy = walls
    if extent is not None:
        x = xp.asarray(field)
        n = x.shape[-1]
        block = cosine_transform2(x[(Ellipsis,) + _tank_block(n, extent)])
        return _embed(xp, block, x.shape, (slice(0, extent[0]), slice(0, extent[1])))
    if not wx and not wy:
        return xp.fft.rfft2(field)
    if wx and wy:
        return cosine_transform2(field)
    if wx:
        return xp.fft.rfft(cosine_transform(field, -1), axis=-2)
    return xp.fft.rfft(cosine_transform(field, -2), axis=-1)


def inverse_mode_transform(spectra, n: int, walls=(False, False), extent=None):
    """The real fields ``(..., n, n)`` of :func:`mode_transform`'s spectra.

    Parameters
    ----------
    spectra : array_like
        :func:`mode_transform`'s output.
    n : int
        Grid points along a side.
    walls : tuple of bool
        (x walled, y walled), as given to :func:`mode_transform`.
    extent : tuple of int, optional
        As given to :func:`mode_transform`.

    Returns
    -------
    array_like (..., n, n)
    """
    xp = array_module(spectra)
    wx, wy = walls
    if extent is not None:
        c = xp.asarray(spectra)
        block = inverse_cosine_transform2(c[..., :extent[0], :extent[1]])
        return _embed(xp, block, c.shape[:-2] + (n, n), _tank_block(n, extent))
    if not wx and not wy:
        return xp.fft.irfft2(spectra, s=(n, n))
    if wx and wy:
        return inverse_cosine_transform2(spectra)
    if wx:
        return inverse_cosine_transform(xp.fft.irfft(spectra, n=n, axis=-2), -1)
    return inverse_cosine_transform(xp.fft.irfft(spectra, n=n, axis=-1), -2)


def mode_wavenumbers(n: int, spacing, walls=(False, False), xp=None, extent=None):
    """``(ky, kx)``, rad/m, of :func:`mode_transform`'s layout, shaped to broadcast against it:
    2π·fftfreq / 2π·rfftfreq along periodic axes, mπ/L (m = 0 … n − 1, L = n·spacing) along walled ones;
    with a tank ``extent`` = (my, mx), pπ/(my·spacing) and mπ/(mx·spacing) on its coefficients and 0 on
    the unused rest (their coefficients are always 0).

    Parameters
    ----------
    n : int
        Grid points along a side.
    spacing : float
        Grid spacing, m.
    walls : tuple of bool
        (x walled, y walled).
    xp : module, optional
        ``numpy`` or ``jax.numpy``.
    extent : tuple of int, optional
        (my, mx) cells of a centred tank.

    Returns
    -------
    (array, array)
        ky and kx, rad/m.
    """
    xp = xp or array_module(spacing)
    wx, wy = walls
    if extent is not None:
        index = xp.arange(n)
        ky = xp.where(index < extent[0], index * math.pi / (extent[0] * spacing), 0.0)
        kx = xp.where(index < extent[1], index * math.pi / (extent[1] * spacing), 0.0)
        return ky[:, None], kx[None, :]
    if not wx and not wy:
        return angular_wavenumbers((n, n), spacing, real=True, xp=xp)
    cosine = xp.arange(n) * math.pi / (n * spacing)
    if wx and wy:
        return cosine[:, None], cosine[None, :]
    half = xp.fft.rfftfreq(n) * (2.0 * math.pi) / spacing
    if wx:
        return half[:, None], cosine[None, :]
    return cosine[:, None], half[None, :]
