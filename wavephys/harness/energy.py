"""Wave energy per unit area measured from any simulator's heights and vertical velocities
(linear theory, docs/physics.md §1.8)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_scalar
from wavephys.core.spectral import angular_wavenumbers
from wavephys.core.water import Water

__all__ = ["Energy", "measure_energy"]


@dataclass(frozen=True)
class Energy:
    """Mean wave energy per unit area, J/m² (linear theory).

    Each field is a float, or an array of the leading shape of the heights given to :func:`measure_energy`.

    Attributes
    ----------
    potential : float or numpy.ndarray
        Potential energy ½ρg⟨η²⟩, J/m², >= 0.
    capillary : float or numpy.ndarray
        Capillary (surface tension) energy ½σ⟨|∇η|²⟩, J/m², >= 0.
    kinetic : float or numpy.ndarray
        Kinetic energy ½ρ⟨φ·Kφ⟩, J/m², >= 0.
    total : float or numpy.ndarray
        potential + capillary + kinetic, J/m² (a property).
    """

    potential: float
    capillary: float
    kinetic: float

    @property
    def total(self) -> float:
        return self.potential + self.capillary + self.kinetic


def _surface_operator(k, water: Water) -> np.ndarray:
    """K = k tanh kh in float64 (:func:`wavephys.physics.dispersion.surface_operator`, the one
    definition), for numpy wavenumbers."""
    import jax
    import jax.numpy as jnp

    from wavephys.physics.dispersion import surface_operator

    with jax.enable_x64(True):
        return np.asarray(surface_operator(jnp.asarray(k, jnp.float64), water), np.float64)


def measure_energy(eta, eta_dot, dx: float, water: Water) -> Energy:
    """Energy per unit area from height η (m) and its rate η̇ (m/s) on a periodic grid.

    potential ½ρg⟨η²⟩; capillary ½σ⟨|∇η|²⟩ (spectral gradient); kinetic ½ρ⟨φ·Kφ⟩ with the
    surface potential recovered from the kinematic condition, φ̂ = η̇̂ / K,
    K = |k| tanh(|k| h) (docs/physics.md §1.8). For free waves kinetic ≈ potential + capillary
    (equipartition); a monochromatic wave of amplitude A has total ½ρgA² (σ = 0).

    Parameters
    ----------
    eta, eta_dot : array_like
        Height η, m, and its rate η̇, m/s; same shape ``(..., n_y, n_x)`` (at least 2-D, finite); leading axes
        give one Energy of arrays each.
    dx : float
        Grid spacing, m, > 0.
    water : Water
        Density ρ, gravity g, surface tension σ and depth h of the water.

    Returns
    -------
    Energy
        Potential, capillary and kinetic energy per unit area, J/m², float64 (arrays of the leading shape when
        the inputs have leading axes).

    Raises
    ------
    ValueError
        When ``eta`` and ``eta_dot`` differ in shape, or ``dx`` is not > 0.

    Examples
    --------
    >>> import math, numpy as np
    >>> from wavephys import Grid, Water
    >>> from wavephys.physics.dispersion import angular_frequency
    >>> grid, water, a, k = Grid(32, 1.0), Water(sigma=0.0), 0.01, 2 * math.pi / 0.5
    >>> x = np.asarray(grid.mesh()[0])
    >>> omega = float(angular_frequency(k, water))
    >>> e = measure_energy(a * np.cos(k * x), a * omega * np.sin(k * x), float(grid.dx), water)
    >>> round(float(e.total), 4), round(0.5 * water.rho * water.g * a * a, 4)   # ½ρgA²
    (0.4905, 0.4905)
    """
    check_array("eta", eta, min_ndim=2)
    check_array("eta_dot", eta_dot, min_ndim=2)
    if np.shape(eta) != np.shape(eta_dot):
        raise ValueError(f"eta and eta_dot must have one shape, got {np.shape(eta)} and {np.shape(eta_dot)}")
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    check_instance("water", water, Water, "wavephys.Water")
    eta = np.asarray(eta, np.float64)
    eta_dot = np.asarray(eta_dot, np.float64)
    ny, nx = eta.shape[-2:]
    ky, kx = angular_wavenumbers((ny, nx), dx, xp=np)
    k = np.sqrt(kx**2 + ky**2)
    K = _surface_operator(k, water)
    n = nx * ny
    eh = np.fft.fft2(eta)
    dh = np.fft.fft2(eta_dot)
    mean_sq = lambda f: np.sum(np.abs(f) ** 2, axis=(-2, -1)) / n**2  # Parseval: ⟨|f|²⟩
    pot = 0.5 * float(water.rho) * float(water.g) * np.mean(eta**2, axis=(-2, -1))
    cap = 0.5 * float(water.sigma) * mean_sq(k * eh)
    invK = np.where(K > 0, 1.0 / np.where(K > 0, K, 1.0), 0.0)
    kin = 0.5 * float(water.rho) * np.sum(np.abs(dh) ** 2 * invK, axis=(-2, -1)) / n**2
    return Energy(pot, cap, kin)
