r"""Exact steady Stokes waves on deep water: the reference for second-order heights.

Solved from Babenko's (1987) equation in conformal variables (nondimensional, g = k = 1):

.. math::

    c^2\,\hat K y - y - \tfrac12\hat K(y^2) - y\,\hat K y = 0,
    \qquad \hat K e^{i j u} = |j|\,e^{i j u},

for the surface elevation y(u), u ∈ [0, 2π), with the physical abscissa
x(u) = u + Ĥ... written here as x'(u) = 1 + K̂y (Dyachenko, Lushnikov & Korotkevich 2016,
eq. 12 ff.). The mean level ∫η dx = 0 follows from the mean mode of the equation. y is a
cosine series; its first coefficient is fixed and Newton's method finds
the rest and c² (Newton's method); an outer secant iteration matches the requested first-harmonic
amplitude of η(x). Solved for kA ≤ 0.33 (kH/2 ≤ 0.36; the limiting wave has
kH/2 ≈ 0.443). Verified by the tests against Stokes' expansion:
c² = 1 + (kA)² + O((kA)⁴) and η = A cos θ + ½kA² cos 2θ + ⅜k²A³ cos 3θ + O(A⁴).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from wavephys.core.inputs import check_int, check_scalar

__all__ = ["StokesWave", "stokes_wave"]


def _solve_babenko(b1: float, modes: int, guess=None):
    m = 4 * modes
    j = np.arange(m // 2 + 1)

    def K(f):
        return np.fft.irfft(np.fft.rfft(f) * j, m)

    def unpack(v):
        b = np.zeros(m // 2 + 1)
        b[0] = v[0]
        b[1] = b1
        b[2:modes + 1] = v[1:modes]
        return b, v[modes]

    def residual(v):
        b, c2 = unpack(v)
        y = np.fft.irfft(b * m / 2 * np.where(j == 0, 2, 1), m)  # y = b0 + Σ b_j cos(ju)
        ky = K(y)
        r = c2 * ky - y - 0.5 * K(y * y) - y * ky
        rc = np.fft.rfft(r).real / (m / 2)
        rc[0] /= 2
        return rc[: modes + 1]

    if guess is None:
        guess = np.zeros(modes + 1)
        guess[1] = 0.5 * b1 * b1
        guess[modes] = 1.0 + b1 * b1
    v = np.asarray(guess, np.float64).copy()
    step = 1e-7
    for _ in range(30):
        r = residual(v)
        if np.abs(r).max() < 1e-14:
            break
        jac = np.empty((v.size, v.size))
        for i in range(v.size):  # forward-difference Jacobian (the residual is quadratic)
            dv = v.copy()
            dv[i] += step
            jac[:, i] = (residual(dv) - r) / step
        v = v - np.linalg.solve(jac, r)
    if np.abs(residual(v)).max() > 1e-12:
        raise RuntimeError(f"Stokes wave solver did not converge for b1={b1}")
    return unpack(v), v


@dataclass(frozen=True)
class StokesWave:
    """A solved Stokes wave: evaluate η(x) (m) with ``wave(x)``; crest at x = 0.

    Made by :func:`stokes_wave`; calling it with positions x (m, array_like) returns η(x), m,
    interpolated periodically on the solved profile.

    Parameters
    ----------
    amplitude : float
        First-harmonic amplitude A of η(x), m.
    wavenumber : float
        k, rad/m.
    speed_factor : float
        c/sqrt(g/k), dimensionless.
    height : float
        Crest-to-trough height, m.
    _x, _y : numpy.ndarray
        The solved profile, nondimensional (g = k = 1): abscissae x(u) in increasing order and
        elevations y there.

    References
    ----------
    K. I. Babenko (1987). Some remarks on the theory of surface waves of finite amplitude.
    *Soviet Math. Dokl.* 35; with Dyachenko, Lushnikov & Korotkevich (2016), *Stud. Appl. Math.*
    137, for the conformal form used to solve Stokes waves (docs/physics.md).
    """

    amplitude: float
    wavenumber: float
    speed_factor: float
    height: float
    _x: np.ndarray
    _y: np.ndarray

    def __call__(self, x):
        period = 2 * np.pi
        u = np.mod(np.asarray(x, np.float64) * self.wavenumber, period)
        return np.interp(u, self._x, self._y, period=period) / self.wavenumber


def _profile(b, c2, fine=1 << 14):
    m = fine
    j = np.arange(m // 2 + 1)
    bb = np.zeros(m // 2 + 1)
    bb[: b.size] = b[: min(b.size, bb.size)]
    y = np.fft.irfft(bb * m / 2 * np.where(j == 0, 2, 1), m)
    ky = np.fft.irfft(np.fft.rfft(y) * j, m)
    u = 2 * np.pi * np.arange(m) / m
    # x(u) = u + ∫(K y) du: integrate the cosine series of K y term by term
    khat = np.fft.rfft(ky)
    integ = np.zeros_like(khat)
    integ[1:] = khat[1:] / (1j * j[1:])
    x = u + np.fft.irfft(integ, m)
    return x, y


def _first_harmonic(x, y):
    # η(x) sampled at x(u): A = (1/π)∫ η cos x dx = (1/π)∫ y cos(x(u)) x'(u) du
    dxdu = np.gradient(np.unwrap(x), 2 * np.pi / x.size)
    return np.mean(y * np.cos(x) * dxdu) * 2


@functools.lru_cache(maxsize=64)
def stokes_wave(steepness: float, wavenumber: float = 1.0, modes: int = 128) -> StokesWave:
    """The exact deep-water Stokes wave whose η(x) has first harmonic A = steepness/k.

    Parameters
    ----------
    steepness : float
        kA, in (0, 0.33] (the solver's parametrization by the first conformal
        harmonic stops converging near kA ≈ 0.35, about 85 % of the limiting wave height).
    wavenumber : float
        k, rad/m, > 0.
    modes : int
        Cosine modes of y(u) (≥ 16; more for steeper waves).

    Returns
    -------
    StokesWave
        The solved wave (crest at x = 0); cached by arguments.

    Raises
    ------
    RuntimeError
        If the solver or the amplitude iteration does not converge.

    References
    ----------
    K. I. Babenko (1987). Some remarks on the theory of surface waves of finite amplitude.
    *Soviet Math. Dokl.* 35; with Dyachenko, Lushnikov & Korotkevich (2016), *Stud. Appl. Math.*
    137, for the conformal form used to solve Stokes waves.
    """
    check_scalar("steepness", steepness, lo=0.0, hi=0.33, lo_open=True)
    check_scalar("wavenumber", wavenumber, lo=0.0, lo_open=True)
    modes = check_int("modes", modes, lo=16)
    guess = None

    def amplitude_of(b1):
        nonlocal guess
        (b, c2), guess = _solve_babenko(b1, modes, guess)
        x, y = _profile(b, c2)
        return _first_harmonic(x, y), b, c2, x, y

    b1 = 0.0
    # continuation in the physical amplitude: each solved wave seeds the next, steeper one
    for target in np.linspace(0.0, steepness, int(np.ceil(steepness / 0.025)) + 1)[1:]:
        b1 = b1 + (target - (b1 and amplitude_of(b1)[0]))  # first-order predictor
        for _ in range(50):
            a, b, c2, x, y = amplitude_of(b1)
            if abs(a - target) < 1e-13:
                break
            a2, *_ = amplitude_of(b1 * (1 + 1e-6))
            b1 = b1 - (a - target) / ((a2 - a) / (b1 * 1e-6))
        else:
            raise RuntimeError(f"Stokes wave amplitude iteration did not converge for kA={steepness}")
    order = np.argsort(x)
    xs, ys = x[order], y[order]
    return StokesWave(steepness / wavenumber, wavenumber, float(np.sqrt(c2)),
                      float((y.max() - y.min()) / wavenumber), xs, ys)
