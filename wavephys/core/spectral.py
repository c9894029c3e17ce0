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

import math

from wavephys.core.sampling import array_module

__internal__ = True  # tooling for the library's own modules (users call the Grid's methods)
__all__ = ["angular_wavenumbers", "spectral_gradient", "central_gradient", "central_laplacian", "GRADIENT_METHODS",
           "gradient", "spectral_laplacian", "fourier_refine", "spectral_derivatives", "bspline_coefficients"]


def angular_wavenumbers(shape: tuple[int, int], spacing, real: bool = False, xp=None):
    """``(ky, kx)`` angular wavenumbers, rad/m, shaped ``(ny, 1)`` and ``(1, nx)`` (or
    ``(1, nx//2 + 1)`` with ``real``) to broadcast against a spectrum."""
    xp = xp or array_module(spacing)
    ny, nx = shape
    ky = 2.0 * math.pi * xp.fft.fftfreq(ny) / spacing
    kx = (xp.fft.rfftfreq(nx) if real else xp.fft.fftfreq(nx)) * (2.0 * math.pi) / spacing
    return ky[:, None], kx[None, :]


def spectral_gradient(field, spacing):
    """(∂f/∂x, ∂f/∂y) of a real periodic field by FFT: exact for band-limited fields, 1/m × f."""
    xp = array_module(field)
    f = xp.asarray(field)
    ny, nx = f.shape[-2:]
    ky, kx = angular_wavenumbers((ny, nx), spacing, real=True, xp=xp)
    spec = xp.fft.rfft2(f)
    both = xp.fft.irfft2(xp.stack([1j * kx * spec, 1j * ky * spec]), s=(ny, nx))
    return both[0], both[1]


def central_gradient(field, spacing):
    """(∂f/∂x, ∂f/∂y) by periodic central differences (second order, no transforms)."""
    xp = array_module(field)
    f = xp.asarray(field)
    gx = (xp.roll(f, -1, -1) - xp.roll(f, 1, -1)) / (2 * spacing)
    gy = (xp.roll(f, -1, -2) - xp.roll(f, 1, -2)) / (2 * spacing)
    return gx, gy


GRADIENT_METHODS = {"spectral": spectral_gradient, "central": central_gradient}
"""Gradient methods by name: exact spectral, or central differences (what a shader does)."""


def central_laplacian(field, spacing):
    """∇²f by the periodic 5-point stencil on the last two axes (second order, no transforms),
    1/spacing² × f. NumPy in → NumPy out, JAX in → JAX out."""
    xp = array_module(field)
    f = xp.asarray(field)
    return (xp.roll(f, 1, -1) + xp.roll(f, -1, -1) + xp.roll(f, 1, -2) + xp.roll(f, -1, -2) - 4.0 * f) / (
        spacing * spacing)


def gradient(field, spacing, method: str = "spectral"):
    """(∂f/∂x, ∂f/∂y) by ``method`` in :data:`GRADIENT_METHODS`."""
    from wavephys.core.methods import dispatch

    return dispatch(GRADIENT_METHODS, method, field, spacing, _family="gradient")


def spectral_laplacian(field, spacing):
    """∇²f of a real periodic field by FFT, 1/m² × f."""
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
    """
    if factor == 1:
        return field
    xp = array_module(field)
    f = xp.asarray(field)
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


def spectral_derivatives(field, spacing):
    """(∂f/∂x, ∂f/∂y, ∂²f/∂x², ∂²f/∂x∂y, ∂²f/∂y²) of a real periodic field by one FFT: exact for
    band-limited fields (1/m and 1/m² × f), stacked on a new first axis."""
    xp = array_module(field)
    f = xp.asarray(field)
    ny, nx = f.shape[-2:]
    ky, kx = angular_wavenumbers((ny, nx), spacing, real=True, xp=xp)
    spec = xp.fft.rfft2(f)
    planes = xp.stack([1j * kx * spec, 1j * ky * spec, -kx * kx * spec, -kx * ky * spec, -ky * ky * spec])
    return xp.fft.irfft2(planes, s=(ny, nx))


def bspline_coefficients(field):
    r"""Coefficients c of the periodic cubic B-spline that interpolates ``field`` (..., ny, nx) at its samples.

    The spline Σ c_ij β³(u − j) β³(v − i) equals the field at every sample; its transfer
    function per axis is (4 + 2 cos ω)/6 (ω = 2π·fftfreq), so c is the field's spectrum
    divided by it (one FFT each way; Unser 1999, "Splines: a perfect fit for signal and
    image processing"). Evaluate with :func:`wavephys.core.sampling.bspline`.
    """
    xp = array_module(field)
    f = xp.asarray(field)
    ny, nx = f.shape[-2:]
    wy = (4.0 + 2.0 * xp.cos(2.0 * math.pi * xp.fft.fftfreq(ny))) / 6.0
    wx = (4.0 + 2.0 * xp.cos(2.0 * math.pi * xp.fft.rfftfreq(nx))) / 6.0
    return xp.fft.irfft2(xp.fft.rfft2(f) / (wy[:, None] * wx[None, :]), s=(ny, nx)).astype(f.dtype)
