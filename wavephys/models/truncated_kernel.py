r"""Peer method: a truncated convolution kernel stepped in time (iWave, Tessendorf 2004).

The linear wave equation η_tt = −Ω η, with Ω the operator whose Fourier symbol is ω(k)²
(docs/physics.md §1.1), is stepped with leapfrog,

.. math::

    \eta^{n+1} = 2\eta^n - \eta^{n-1} - \Delta t^2\, (G_P \ast \eta^n),

where G_P is the exact discrete kernel F⁻¹[ω²] cut to a P × P stencil (P odd) and
applied by direct periodic convolution, so the cost grows as P² per point instead of an
FFT's log N. As in iWave, the centre weight is corrected so the stencil sums to zero
(a uniform height stays still: symbol 0 at k = 0). What truncation costs is in the
stencil's own symbol Ĝ_P(k) (:func:`stencil_symbol`): the scheme's dispersion is
cos(ωΔt) = 1 − Δt²Ĝ_P/2, long waves are the worst (the ω² kernel decays only as r⁻³),
and it is stable only for Δt ≤ 2/sqrt(max Ĝ_P) (:func:`max_stable_dt`).
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import Array, Real, Spec, check_array, check_bool, check_int, check_scalar, validate
from wavephys.core.specs import GRID, WATER
from wavephys.core.stepper import TwoLevelState, _TwoLevel
from wavephys.core.aliases import deprecated_function
from wavephys.models.two_level import check_levels
from wavephys.physics.dispersion import angular_frequency
from wavephys.core.grid import Grid
from wavephys.core.water import Water

__all__ = ["KernelStepper", "truncated_kernel", "stencil_symbol", "max_stable_dt", "convolve_periodic",
           "kernel_step", "kernel_run"]


class _Stencil(Spec):
    """A square stencil (P, P), P odd, smaller than the grid of ``grid`` (or of the field ``eta``)."""

    def __call__(self, name, value, arguments):
        check_array(name, value, ndim=2)
        p, q = np.shape(value)
        if p != q or p % 2 == 0:
            raise ValueError(f"{name} must be square with an odd side (P, P), got shape {np.shape(value)}")
        if "grid" in arguments and isinstance(arguments["grid"], Grid):
            n = arguments["grid"].n
        elif "eta" in arguments:
            n = min(np.shape(arguments["eta"])[-2:])
        else:
            n = None
        if n is not None and p >= n:
            raise ValueError(f"{name} must be smaller than the grid ({n} samples), got side {p}")
        return value


_STENCIL = _Stencil()
_DT = Real(lo=0.0, hi=1e6, lo_open=True)


@validate(grid=GRID, water=WATER)
def truncated_kernel(grid: Grid, water: Water, size: int):
    """The P × P stencil of the ω² operator, 1/s² per point, centre at ``[P//2, P//2]``.

    Parameters
    ----------
    grid, water
    size : int
        P, odd, 1 ≤ P < n. P = n − 1 keeps nearly the whole kernel.

    Returns
    -------
    jax.Array (P, P)
        The stencil, 1/s² per point, summing to zero.

    References
    ----------
    J. Tessendorf (2004). Interactive water surfaces (iWave) (docs/physics.md §1.7).
    """
    size = check_int("size", size, lo=1, hi=grid.n - 1)
    if size % 2 == 0:
        raise ValueError(f"size must be odd, got {size}")
    omega2 = angular_frequency(grid.wavenumber_magnitude(), water) ** 2
    full = jnp.fft.fftshift(jnp.fft.ifft2(omega2).real)
    c, h = grid.n // 2, size // 2
    stencil = full[c - h:c + h + 1, c - h:c + h + 1]
    return stencil.at[h, h].add(-jnp.sum(stencil))


@validate(grid=GRID, stencil=_STENCIL)
def stencil_symbol(stencil, grid: Grid):
    """Fourier symbol Ĝ_P(k) of a centred stencil on the grid, 1/s², shape ``(n, n)``.

    Parameters
    ----------
    stencil : array_like (P, P)
        A centred stencil (:func:`truncated_kernel`), 1/s² per point, square, P odd, P < n.
    grid : Grid

    Returns
    -------
    jax.Array (n, n)
        Ĝ_P, 1/s² (real part of the DFT of the stencil embedded at the origin).

    References
    ----------
    J. Tessendorf (2004). Interactive water surfaces (iWave) (docs/physics.md §1.7).
    """
    stencil = jnp.asarray(stencil)
    p = stencil.shape[-1]
    h = p // 2
    emb = jnp.zeros((grid.n, grid.n), stencil.dtype).at[:p, :p].set(stencil)
    emb = jnp.roll(emb, (-h, -h), axis=(0, 1))
    return jnp.fft.fft2(emb).real


@validate(grid=GRID, stencil=_STENCIL)
def max_stable_dt(stencil, grid: Grid):
    """Largest stable leapfrog step for the stencil, s: 2/sqrt(max Ĝ_P).

    Parameters
    ----------
    stencil : array_like (P, P)
        A centred stencil (:func:`truncated_kernel`), 1/s² per point, square, P odd, P < n.
    grid : Grid

    Returns
    -------
    float
        Δt, s.

    Raises
    ------
    ValueError
        If the stencil has no positive Fourier symbol.

    References
    ----------
    J. Tessendorf (2004). Interactive water surfaces (iWave) (docs/physics.md §1.7).
    """
    top = float(jnp.max(stencil_symbol(stencil, grid)))
    if not top > 0:
        raise ValueError(f"stencil has no positive Fourier symbol (max {top:.3g} 1/s^2): it is not an omega^2 "
                         f"operator, so no step is stable")
    return 2.0 / math.sqrt(top)


@validate(eta=Array(min_ndim=2), stencil=_STENCIL)
def convolve_periodic(eta, stencil):
    """Periodic 2-D convolution of ``eta`` (..., n, n) with a centred odd stencil (P, P).

    Parameters
    ----------
    eta : array_like (..., n, n)
        The field (any unit).
    stencil : array_like (P, P)
        Square, P odd, smaller than the field.

    Returns
    -------
    jax.Array (..., n, n)
        G ∗ η, in the units of ``eta`` times those of ``stencil``.
    """
    eta, stencil = jnp.asarray(eta), jnp.asarray(stencil)
    h = stencil.shape[-1] // 2
    lead = eta.shape[:-2]
    x = eta.reshape((-1, 1) + eta.shape[-2:])
    x = jnp.pad(x, ((0, 0), (0, 0), (h, h), (h, h)), mode="wrap")
    w = stencil[::-1, ::-1][None, None].astype(eta.dtype)  # convolution, not correlation
    out = jax.lax.conv_general_dilated(x, w, (1, 1), "VALID")
    return out.reshape(lead + eta.shape[-2:])


@validate(eta=Array(min_ndim=2), eta_prev=Array(shape=lambda a: np.shape(a["eta"]), min_ndim=2),
          stencil=_STENCIL, dt=_DT)
def kernel_step(eta, eta_prev, stencil, dt):
    """One leapfrog step η^{n+1} = 2η^n − η^{n−1} − Δt²·(G_P ∗ η^n), m (Δt in (0, 1e6] s).

    Parameters
    ----------
    eta : array_like (..., n, n)
        η^n, m.
    eta_prev : array_like (..., n, n)
        η^{n−1}, m, the shape of ``eta``.
    stencil : array_like (P, P)
        A centred stencil (:func:`truncated_kernel`), 1/s² per point, square, P odd, P < n.
    dt : float
        Δt, s, in (0, 1e6] (stable up to :func:`max_stable_dt`).

    Returns
    -------
    jax.Array (..., n, n)
        η^{n+1}, m.

    References
    ----------
    J. Tessendorf (2004). Interactive water surfaces (iWave) (docs/physics.md §1.7).
    """
    return 2.0 * eta - eta_prev - dt * dt * convolve_periodic(eta, stencil)


def _kernel_steps(eta, eta_prev, stencil, dt, steps: int, check_stability: bool = True):
    """``steps`` leapfrog steps; returns (η^N, η^{N−1}), m.

    Parameters
    ----------
    eta, eta_prev : array_like
        Heights at the last two times, m, same shape ``(..., n, n)``.
    stencil : array_like
        From :func:`truncated_kernel`.
    dt : float
        Step, s, > 0; with ``check_stability`` (default) at most :func:`max_stable_dt` on the
        field's grid. Pass ``check_stability=False`` to explore the unstable side (it blows up).
    steps : int
        ≥ 1.
    check_stability : bool
        Reject Δt above :func:`max_stable_dt`, default True.

    Returns
    -------
    (eta, eta_prev)
        η^N and η^{N−1}, m, shape of ``eta``.

    References
    ----------
    J. Tessendorf (2004). Interactive water surfaces (iWave) (docs/physics.md §1.7).
    """
    eta, eta_prev = check_levels(eta, eta_prev)
    check_bool("check_stability", check_stability)
    _STENCIL("stencil", stencil, {"eta": eta})
    _DT("dt", dt, {})
    steps = check_int("steps", steps, lo=1)
    end = KernelStepper(stencil, dt, check_stability)._every_step(TwoLevelState(eta, eta_prev), steps)
    return end.eta, end.eta_prev


kernel_run = deprecated_function(_kernel_steps, "kernel_run", "KernelStepper(stencil, dt).run / .advance")


class KernelStepper(_TwoLevel):
    """Truncated kernels stepped by leapfrog (:mod:`wavephys.models.truncated_kernel`).

    Parameters
    ----------
    stencil : array_like (m, m)
        The kernel, 1/s² (from :func:`~wavephys.models.truncated_kernel.kernel_stencil`).
    dt : float
        s, > 0, at most the stencil's limit on the state's grid (:func:`max_stable_dt`).
    check_stability : bool
        Refuse a state whose grid makes ``dt`` unstable (default); False lets it run, to watch it blow up (its
        failure boundary).
    """

    def __init__(self, stencil, dt: float, check_stability: bool = True):
        check_array("stencil", stencil, ndim=2)
        shape = np.shape(stencil)
        if shape[0] != shape[1] or shape[0] % 2 == 0:
            raise ValueError(f"stencil must be square with an odd side (its centre a sample), got shape {shape}")
        self.stencil, self.dt = np.asarray(stencil), check_scalar("dt", dt, lo=0.0, lo_open=True)
        self.check_stability, self._limits = check_bool("check_stability", check_stability), {}

    def _checked_state(self, state):
        state = super()._checked_state(state)
        if self.check_stability:  # the grid's size is static, even under a trace
            n = state.eta.shape[-1]
            limit = self._stable_dt(n)
            if self.dt > limit:
                raise ValueError(f"dt must be <= {limit:.4g} s, the stability limit of this stencil (max_stable_dt) "
                                 f"on a {n}-sample grid, got {self.dt!r}; pass check_stability=False to watch it "
                                 f"blow up")
        return state

    def _stable_dt(self, n):
        if n not in self._limits:  # the symbol depends on the samples only; the stencil is concrete, even under jit
            with jax.ensure_compile_time_eval():
                self._limits[n] = float(max_stable_dt(self.stencil, Grid(n, float(n))))
        return self._limits[n]

    def _parts(self):
        return None, (jnp.asarray(self.stencil), self.dt)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        stencil, _ = dynamic
        new = kernel_step(state.eta, state.eta_prev, stencil.astype(state.eta.dtype), dt)
        return TwoLevelState(new, state.eta, state.time + dt)
