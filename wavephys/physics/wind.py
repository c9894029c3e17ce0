r"""Wind seas: random wave spectra synthesized in Fourier space (docs/physics.md §1.7).

Two spectra, both as height variance density F(k) per unit wavenumber area, m⁴
(Var η = ∫F d²k):

* Phillips (as used for graphics by Tessendorf 2001):
  F(k) = A·exp(−1/(kL)²)/k⁴·cos²(θ − θ_w)·exp(−(k ℓ)²), L = U²/g, waves travelling
  against the wind removed.
* JONSWAP (Hasselmann et al. 1973), a frequency spectrum S(ω) (m²·s)

  .. math::

      S(\omega) = \frac{\alpha g^2}{\omega^5}\exp\!\Big[-\tfrac54\big(\tfrac{\omega_p}{\omega}\big)^4\Big]
      \gamma^{\exp[-(\omega - \omega_p)^2/(2\sigma^2\omega_p^2)]}

  with α = 0.076 (U²/(F g))^0.22, ω_p = 22 (g²/(U F))^{1/3}, γ = 3.3, σ = 0.07 (ω ≤ ω_p)
  or 0.09, spread over directions with D(θ) = (2/π)cos²(θ − θ_w) on |θ − θ_w| < π/2 and
  mapped to wavenumbers with F(k, θ) = S(ω(k))·c_g(k)·D(θ)/k.

The synthesized sea is a complex field whose every component travels along its own k
(Gaussian random amplitudes), turned into the wave field ψ with
:func:`wavephys.physics.heights.potential_from_height` (``travelling=True``).
:class:`WindSea` is the simulation source that adds such a sea (an impulse).
"""

from __future__ import annotations

from dataclasses import dataclass

import jax
import jax.numpy as jnp

import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_key, check_scalar
from wavephys.core.specs import model_grid
from wavephys.core.methods import Methods
from wavephys.core.pytree import register
from wavephys.physics.dispersion import angular_frequency, group_speed
from wavephys.core.grid import Grid
from wavephys.core.water import Water

__all__ = [
    "phillips_spectrum",
    "jonswap_frequency_spectrum",
    "jonswap_spectrum",
    "synthesize_height",
    "SPECTRA",
    "wind_spectrum",
    "WindSea",
]


def _check_k(kx, ky, water):
    """Wavenumber components (rad/m) that broadcast together, and the water."""
    check_array("kx", kx)
    check_array("ky", ky)
    try:
        np.broadcast_shapes(np.shape(kx), np.shape(ky))
    except ValueError:
        raise ValueError(f"kx and ky must broadcast together, got shapes {np.shape(kx)} and {np.shape(ky)}") from None
    check_instance("water", water, Water, "wavephys.Water")


def _direction_cos(kx, ky, direction):
    k = jnp.sqrt(kx * kx + ky * ky)
    ks = jnp.where(k > 0, k, 1.0)
    return (kx * jnp.cos(direction) + ky * jnp.sin(direction)) / ks


def phillips_spectrum(kx, ky, water: Water, wind_speed, direction=0.0, amplitude=1e-3,
                      small_wave_length=0.0):
    """Phillips spectrum F(k), m⁴ (Tessendorf 2001, eq. 40), travelling with the wind.

    Parameters
    ----------
    kx, ky : array_like
        Wavenumber components, rad/m (broadcastable).
    water : Water
        Uses g.
    wind_speed : float
        U, m/s, > 0. Largest waves L = U²/g.
    direction : float
        Wind direction θ_w, rad (0 = +x).
    amplitude : float
        Dimensionless constant A, > 0.
    small_wave_length : float
        ℓ, m, ≥ 0: suppresses waves shorter than ℓ by exp(−k²ℓ²).

    Returns
    -------
    jax.Array
        F, m⁴, of the broadcast shape of ``kx`` and ``ky``; 0 at k = 0 and against the wind.

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water, eq. 40 (docs/physics.md §1.7).
    """
    _check_k(kx, ky, water)
    check_scalar("wind_speed", wind_speed, lo=0.0, lo_open=True)
    check_scalar("amplitude", amplitude, lo=0.0, lo_open=True)
    check_scalar("small_wave_length", small_wave_length, lo=0.0)
    check_scalar("direction", direction)
    k2 = kx * kx + ky * ky
    pos = k2 > 0
    k2s = jnp.where(pos, k2, 1.0)
    big = wind_speed**2 / water.g
    cosd = _direction_cos(kx, ky, direction)
    f = amplitude * jnp.exp(-1.0 / (k2s * big * big)) / (k2s * k2s) * cosd**2
    f = f * jnp.exp(-k2s * small_wave_length**2)
    return jnp.where(pos & (cosd > 0), f, 0.0)


def jonswap_frequency_spectrum(omega, water: Water, wind_speed, fetch, gamma=3.3):
    """JONSWAP frequency spectrum S(ω), m²·s (Hasselmann et al. 1973).

    Parameters
    ----------
    omega : array_like
        Angular frequency, rad/s, ≥ 0 (S(0) = 0).
    water : Water
        Uses g.
    wind_speed : float
        U₁₀, m/s, > 0.
    fetch : float
        Fetch F, m, > 0.
    gamma : float
        Peak enhancement γ ≥ 1 (3.3; 1 gives Pierson–Moskowitz's shape).

    Returns
    -------
    jax.Array
        S(ω), m²·s, shape of ``omega``.

    References
    ----------
    K. Hasselmann et al. (1973). Measurements of wind-wave growth and swell decay (JONSWAP)
    (docs/physics.md §1.7).
    """
    check_array("omega", omega, lo=0.0)
    check_instance("water", water, Water, "wavephys.Water")
    check_scalar("wind_speed", wind_speed, lo=0.0, lo_open=True)
    check_scalar("fetch", fetch, lo=0.0, lo_open=True)
    check_scalar("gamma", gamma, lo=1.0)
    g = water.g
    alpha = 0.076 * (wind_speed**2 / (fetch * g)) ** 0.22
    wp = 22.0 * (g * g / (wind_speed * fetch)) ** (1.0 / 3.0)
    pos = omega > 0
    w = jnp.where(pos, omega, 1.0)
    sig = jnp.where(w <= wp, 0.07, 0.09)
    r = jnp.exp(-((w - wp) ** 2) / (2.0 * sig * sig * wp * wp))
    s = alpha * g * g / w**5 * jnp.exp(-1.25 * (wp / w) ** 4) * gamma**r
    return jnp.where(pos, s, 0.0)


def jonswap_spectrum(kx, ky, water: Water, wind_speed, fetch, direction=0.0, gamma=3.3):
    """JONSWAP as a wavenumber spectrum F(k), m⁴, with cos² spreading (module doc).

    F(k, θ) = S(ω(k))·c_g(k)·D(θ)/k, D(θ) = (2/π)cos²(θ − θ_w) on |θ − θ_w| < π/2 (0 against
    the wind), S from :func:`jonswap_frequency_spectrum`.

    Parameters
    ----------
    kx, ky : array_like
        Wavenumber components, rad/m (broadcastable).
    water : Water
        g (m/s²) and the dispersion relation ω(k), c_g(k) (any depth and surface tension).
    wind_speed : float
        U₁₀, m/s, > 0.
    fetch : float
        Fetch F, m, > 0.
    direction : float
        Wind direction θ_w, rad (0 = +x).
    gamma : float
        Peak enhancement γ ≥ 1 (3.3; 1 gives Pierson–Moskowitz's shape).

    Returns
    -------
    jax.Array
        F, m⁴, of the broadcast shape of ``kx`` and ``ky``; 0 at k = 0.

    References
    ----------
    K. Hasselmann et al. (1973). Measurements of wind-wave growth and swell decay (JONSWAP)
    (docs/physics.md §1.7).
    """
    _check_k(kx, ky, water)
    check_scalar("direction", direction)
    k = jnp.sqrt(kx * kx + ky * ky)
    pos = k > 0
    ks = jnp.where(pos, k, 1.0)
    s = jonswap_frequency_spectrum(angular_frequency(ks, water), water, wind_speed, fetch, gamma)
    cosd = _direction_cos(kx, ky, direction)
    spread = jnp.where(cosd > 0, (2.0 / jnp.pi) * cosd**2, 0.0)
    return jnp.where(pos, s * group_speed(ks, water) * spread / ks, 0.0)


SPECTRA = Methods("wind spectrum", phillips=phillips_spectrum, jonswap=jonswap_spectrum)
"""Wind spectra by name (``Simulation.add_wind(..., spectrum=name)``)."""


def wind_spectrum(kx, ky, water: Water, method: str = "phillips", **params):
    """F(k) (m⁴) of the wind spectrum ``method`` in :data:`SPECTRA` with its own ``params``.

    Parameters
    ----------
    kx, ky : array_like
        Wavenumber components, rad/m (broadcastable).
    water : Water
    method : {"phillips", "jonswap"}
        A name in :data:`SPECTRA`: :func:`phillips_spectrum` or :func:`jonswap_spectrum`.
    **params
        That spectrum's own parameters (``wind_speed``, ``fetch``, ``direction``, …).

    Returns
    -------
    jax.Array
        F, m⁴, of the broadcast shape of ``kx`` and ``ky``.

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water (Phillips spectrum); K. Hasselmann et al. (1973).
    Measurements of wind-wave growth and swell decay (JONSWAP) (docs/physics.md §1.7).
    """
    return SPECTRA(method, kx, ky, water, **params)


def synthesize_height(spectrum, grid: Grid, key):
    """A random travelling sea with variance density ``spectrum``: complex height, m.

    ``spectrum`` is F on the full ``fft2`` grid ``(n, n)``, m⁴. Amplitudes are complex
    Gaussian, ĥ = n²·sqrt(F Δk²)·(ξ₁ + iξ₂), so that E[Var Re η] = Σ F Δk².

    Parameters
    ----------
    spectrum : array_like (n, n)
        F on the full ``fft2`` grid, m⁴, ≥ 0.
    grid : Grid
    key : jax.random key
        Seed of the random amplitudes.

    Returns
    -------
    jax.Array (n, n), complex
        F⁻¹[ĥ], m (its real part is the height; pass it to
        ``potential_from_height(..., travelling=True)``).

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water (docs/physics.md §1.7).
    """
    check_instance("grid", grid, Grid, "wavephys.Grid")
    check_array("spectrum", spectrum, ndim=2, shape_tail=(grid.n, grid.n), lo=0.0)
    check_key("key", key)
    return jnp.fft.ifft2(_random_amplitudes(jnp.asarray(spectrum), grid, key))


@dataclass(frozen=True)
class WindSea:
    """A random wind sea added to the simulation at the step it is given to (a source).

    Parameters
    ----------
    key : jax.random key
        Seed of the random amplitudes.
    spectrum : {"phillips", "jonswap"}
        A name in :data:`SPECTRA`.
    params : dict
        The spectrum's own parameters, e.g. ``dict(wind_speed=5.0, fetch=2e3)`` (numbers:
        they are static parameters of the compiled step; stored as sorted pairs).

    References
    ----------
    J. Tessendorf (2001). Simulating ocean water (Phillips spectrum); K. Hasselmann et al. (1973).
    Measurements of wind-wave growth and swell decay (JONSWAP) (docs/physics.md §1.7).
    """

    key: jax.Array
    spectrum: str = "phillips"
    params: tuple = ()

    def __post_init__(self):
        check_key("key", self.key)
        SPECTRA.check(self.spectrum, "spectrum")
        params = dict(self.params) if isinstance(self.params, (dict, tuple)) else None
        if params is None:
            raise TypeError(f"params must be a dict of the spectrum's parameters, got {type(self.params).__name__}")
        SPECTRA.options(self.spectrum, params)  # unknown names fail here, before any work
        object.__setattr__(self, "params", tuple(sorted((k, float(v)) for k, v in params.items())))

    def check(self, model) -> None:
        """Host-side checks against a simulation model: evaluates the spectrum once."""
        model_grid(model)
        ky, kx = model.grid.wavenumbers()
        f = wind_spectrum(kx, ky, model.water, self.spectrum, **dict(self.params))
        if not bool(jnp.isfinite(f).all()):
            raise ValueError(f"the {self.spectrum} spectrum with {self.params} is not finite on this grid")

    def impulse(self, model, ops, t):
        """(Δφ̂, Δχ̂) half spectra of the sea: ψ̂ += −i(ω/K)·ĥ, split into its two real fields.

        In a walled model the periodic sea of the same grid is put on the tank's cosine modes:
        the same heights and potential at t, which the walls then reflect."""
        from wavephys.physics.heights import height_multiplier

        grid = model.grid
        dtype = ops.inverse_height.dtype
        ky, kx = grid.wavenumbers()
        f = wind_spectrum(kx.astype(dtype), ky.astype(dtype), model.water, self.spectrum, **dict(self.params))
        m = height_multiplier(grid.wavenumber_magnitude().astype(dtype), model.water)  # K/ω, full spectrum
        inverse = jnp.where(m > 0, 1.0 / jnp.where(m > 0, m, 1.0), 0.0)
        psi_hat = -1j * inverse * _random_amplitudes(f, grid, self.key)
        mirror = jnp.conj(jnp.roll(jnp.flip(psi_hat, (0, 1)), 1, (0, 1)))  # ψ̂(−k)*
        half = grid.n // 2 + 1
        d_phi, d_chi = (0.5 * (psi_hat + mirror))[:, :half], (-0.5j * (psi_hat - mirror))[:, :half]
        if getattr(model, "walls", ()):  # the sea's fields in space, put on the tank's cosine modes
            fields = jnp.fft.irfft2(jnp.stack([d_phi, d_chi]), s=(grid.n, grid.n)).astype(dtype)
            spectra = model.transform(fields)
            return spectra[0], spectra[1]
        return d_phi, d_chi


def _random_amplitudes(spectrum, grid, key):
    """ĥ = n²·sqrt(F Δk²)·(ξ₁ + iξ₂): the DFT of a random travelling sea (full spectrum)."""
    n = grid.n
    k1, k2 = jax.random.split(key)
    dtype = jnp.result_type(spectrum.dtype, jnp.float32)
    xi = jax.random.normal(k1, (n, n), dtype) + 1j * jax.random.normal(k2, (n, n), dtype)
    return n * n * jnp.sqrt(jnp.maximum(spectrum, 0.0)) * grid.dk * xi


register(WindSea, ("key",), ("spectrum", "params"))
