"""Wave energy per unit area measured from any simulator's heights and vertical velocities
(linear theory, docs/physics.md §1.8)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from wavephys.core.inputs import check_array, check_bool, check_instance, check_scalar
from wavephys.core.spectral import angular_wavenumbers
from wavephys.core.water import Water

__all__ = ["Energy", "measure_energy", "Damping", "measure_damping", "energy_check"]


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


def _modes(fields, dx, tank: bool):
    """(coefficients, weights, k): fields on the modes of their domain, with ⟨f·g⟩ = Σ w·f̂·ĝ* / (n_x n_y)²
    (Parseval), and each mode's wavenumber, rad/m: Fourier modes of a periodic grid, or the cosine modes of
    a tank whose walls are half a sample outside the edges (docs/physics.md §1.11)."""
    ny, nx = fields.shape[-2:]
    if not tank:
        import scipy.fft

        from wavephys.harness.spectra import workers

        ky, kx = angular_wavenumbers((ny, nx), dx, xp=np)
        return scipy.fft.fft2(fields, workers=workers()), 1.0, np.sqrt(kx**2 + ky**2)
    from wavephys.core.spectral import cosine_transform2

    wy = np.where(np.arange(ny) == 0, 1.0, 2.0)[:, None]
    wx = np.where(np.arange(nx) == 0, 1.0, 2.0)[None, :]
    k = np.pi * np.hypot(np.arange(nx)[None, :] / (nx * dx), np.arange(ny)[:, None] / (ny * dx))
    return cosine_transform2(fields), wy * wx, k


def measure_energy(eta, eta_dot, dx: float, water: Water, tank: bool = False) -> Energy:
    """Energy per unit area from height η (m) and its rate η̇ (m/s) on a periodic grid, or in a tank.

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
    tank : bool
        The fields are water between four walls half a sample outside their edges: the operators act on the
        tank's cosine modes (k_mn = π√((m/Lx)² + (n/Ly)²)) instead of Fourier modes.

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
    check_bool("tank", tank)
    eta = np.asarray(eta, np.float64)
    eta_dot = np.asarray(eta_dot, np.float64)
    ny, nx = eta.shape[-2:]
    eh, w, k = _modes(eta, dx, bool(tank))
    dh = _modes(eta_dot, dx, bool(tank))[0]
    K = _surface_operator(k, water)
    n = nx * ny
    mean_sq = lambda f: np.sum(w * np.abs(f) ** 2, axis=(-2, -1)) / n**2  # Parseval: ⟨|f|²⟩
    pot = 0.5 * float(water.rho) * float(water.g) * np.mean(eta**2, axis=(-2, -1))
    cap = 0.5 * float(water.sigma) * mean_sq(k * eh)
    invK = np.where(K > 0, 1.0 / np.where(K > 0, K, 1.0), 0.0)
    kin = 0.5 * float(water.rho) * np.sum(w * np.abs(dh) ** 2 * invK, axis=(-2, -1)) / n**2
    return Energy(pot, cap, kin)


@dataclass(frozen=True)
class Damping:
    """How a record's wave energy changes, shell by shell.

    Attributes
    ----------
    k : numpy.ndarray
        Shell wavenumbers, rad/m (those holding at least 1e-3 of the energy).
    rate : numpy.ndarray
        Amplitude decay rate γ of each shell, 1/s (energy ∝ e^{−2γt}; negative: growing).
    share : numpy.ndarray
        Each shell's share of the mean energy.
    drift : float
        Relative change of the total energy over the record, from a fit of ln E(t): e^{βT} − 1.
    swing : float
        Largest |E(t)/Ē − 1| about that fit: energy sloshing between potential and kinetic.
    rate_error : float
        Estimated relative error of the η̇ used (0 when the record holds η̇).
    rate_method : str
        How η̇ was had: ``"given"``, ``"fd4"`` or ``"spectral"``.
    """

    k: np.ndarray
    rate: np.ndarray
    share: np.ndarray
    drift: float
    swing: float
    rate_error: float
    rate_method: str = "given"


def _shell_energy(eta, eta_dot, dx, water, tank=False):
    """Energy per shell of |k| (n_t, shells) and the shells' k: potential + capillary + kinetic per mode."""
    nt, ny, nx = eta.shape
    eh, w, k = _modes(eta, dx, tank)
    dh = _modes(eta_dot, dx, tank)[0]
    K = _surface_operator(k, water)
    invK = np.where(K > 0, 1.0 / np.where(K > 0, K, 1.0), 0.0)
    rho, g, sigma = float(water.rho), float(water.g), float(water.sigma)
    def power(z):
        p = np.abs(z)
        p *= p
        return p

    e = power(eh)
    e *= 0.5 * w * (rho * g + sigma * k**2) / (nx * ny) ** 2
    e += power(dh) * (0.5 * w * rho * invK / (nx * ny) ** 2)
    dk = (1.0 if tank else 2.0) * np.pi / (dx * max(nx, ny))
    shell = np.rint(k / dk).astype(np.int64).ravel()
    count = int(shell.max()) + 1
    index = (shell[None, :] + count * np.arange(nt)[:, None]).ravel()  # one bincount for every frame at once
    shells = np.bincount(index, weights=e.reshape(-1), minlength=count * nt).reshape(nt, count)
    k_shell = np.arange(shells.shape[1]) * dk
    return k_shell[1:], shells[:, 1:]


def measure_damping(record, water: Water, *, method: str = "auto", tank: bool = False) -> Damping:
    """Energy per shell of |k| over a record, and the decay rate of each shell.

    Parameters
    ----------
    record : Record
        The frames (:class:`wavephys.harness.Record`); its η̇, or η̇ from frames (:func:`time_derivative`).
    water : Water
        Density, gravity, surface tension and depth for the energy (docs/physics.md §1.8).
    method : {"auto", "fd4", "spectral"}, optional, keyword-only
        How η̇ is estimated from frames when the record does not hold it (default ``"auto"``).
    tank : bool, optional, keyword-only
        The record is water between four walls (its cosine modes, :func:`measure_energy`).

    Returns
    -------
    Damping
        Per-shell decay rates and shares, the total energy's drift and swing, and the η̇ error.
    """
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_instance("water", water, Water, "wavephys.Water")
    check_bool("tank", tank)
    rate = record.rate(method)
    eta = record.eta[rate.frames]
    k, shells = _shell_energy(eta, rate.eta_dot, record.dx, water, bool(tank))
    t = np.arange(eta.shape[0]) * record.dt
    total = shells.sum(axis=1)
    if not np.all(total > 0):
        return Damping(np.zeros(0), np.zeros(0), np.zeros(0), math.nan, math.nan, rate.error, rate.method)
    beta, c = np.polyfit(t, np.log(total), 1)
    drift = float(math.expm1(beta * (t[-1] - t[0])))
    swing = float(np.max(np.abs(total / np.exp(c + beta * t) - 1.0)))
    mean = shells.mean(axis=0)
    keep = mean >= 1e-3 * mean.sum()
    rates = np.array([-0.5 * np.polyfit(t, np.log(np.maximum(shells[:, j], 1e-300)), 1)[0]
                      for j in np.where(keep)[0]])
    return Damping(k[keep], rates, mean[keep] / mean.sum(), drift, swing, rate.error, rate.method)


def _damping_cause(d: Damping, dt: float, viscosity: float) -> str:
    """The damping's kind, in words: uniform, proportional to k², growth, or varying with k."""
    if d.k.size == 0:
        return ""
    w = d.share
    gamma = d.rate - 2.0 * viscosity * d.k**2  # beyond the claimed viscosity's 2 nu k^2
    mean = float(np.sum(w * gamma) / np.sum(w))
    if mean < 0:
        return (f"energy grows: amplitudes rise at {-mean:.3g} 1/s on average (an unstable scheme, or forcing "
                f"that keeps adding energy)")
    spread = float(np.sqrt(np.sum(w * (gamma - mean) ** 2) / np.sum(w)))
    b = float(np.sum(w * gamma * d.k**2) / np.sum(w * d.k**4))
    k2_spread = float(np.sqrt(np.sum(w * (gamma - b * d.k**2) ** 2) / np.sum(w)))
    if spread <= 0.2 * mean and d.k.size >= 1:
        return (f"uniform damping: every k loses amplitude at about gamma = {mean:.3g} 1/s (a factor "
                f"{math.exp(-mean * dt):.5f} per frame of {dt:.4g} s: a velocity or height multiplied by a "
                f"constant each step, e.g. velocity *= 0.995)")
    if k2_spread <= 0.25 * mean:
        return (f"damping proportional to k^2: gamma = nu k^2 with nu = {b:.3g} m^2/s ({b / 1e-6:.3g} x water's "
                f"kinematic viscosity 1e-6 m^2/s, which damps as 2 nu k^2): a Laplacian smoothing or an "
                f"artificial viscosity in the update")
    lo, hi = int(np.argmin(gamma)), int(np.argmax(gamma))
    return (f"damping that varies with k: gamma = {gamma[lo]:.3g} 1/s at k = {d.k[lo]:.4g} rad/m to "
            f"{gamma[hi]:.3g} 1/s at k = {d.k[hi]:.4g} rad/m")


def energy_check(record, water: Water, *, rtol: float = 0.01, viscosity: float = 0.0, method: str = "auto",
                 tank: bool = False):
    """A :class:`~wavephys.harness.Check` that a record's wave energy is conserved (or decays as claimed).

    The row is the total energy's relative drift over the record, e^{βT} − 1 from a fit of ln E(t) (the
    energy of linear theory, :func:`measure_energy`, with ``viscosity``'s decay e^{−4νk²t} per shell taken
    out), against ``rtol``. When it fails, the note gives the decay rate per k and names the damping:
    uniform (a constant multiplier each step), ∝ k² (a smoothing, an artificial viscosity), growing, or
    varying; and when the energy sloshes instead, that the simulator's ω is not theory's.

    Parameters
    ----------
    record : Record
        The frames (:class:`wavephys.harness.Record`); η̇ from frames unless it holds its own.
    water : Water
        The water whose linear theory gives the energy (ρ, g, σ, depth).
    rtol : float, optional, keyword-only
        Largest |relative drift| of the energy over the record, > 0 (default 0.01).
    viscosity : float, optional, keyword-only
        Kinematic viscosity ν the simulator claims to model, m²/s, >= 0 (default 0: inviscid).
    method : {"auto", "fd4", "spectral"}, optional, keyword-only
        How η̇ is estimated from frames (default ``"auto"``).
    tank : bool, optional, keyword-only
        The record is water between four walls (energy on its cosine modes).

    Returns
    -------
    Check
        A ``"~="`` row of the drift against 0 (absolute tolerance ``rtol``); its note names the shells, the
        η̇ method's error and, on failure, the likely cause.
    """
    from wavephys.harness.checks import compare

    check_scalar("rtol", rtol, lo=0.0, lo_open=True)
    check_scalar("viscosity", viscosity, lo=0.0)
    check_bool("tank", tank)
    d = measure_damping(record, water, method=method, tank=tank)
    drift = d.drift
    if viscosity > 0 and d.k.size:
        expected = float(np.sum(d.share * np.exp(-4 * viscosity * d.k**2 * record.duration)))
        if not expected > 1e-12:
            raise ValueError(f"viscosity {viscosity!r} m^2/s would decay the energy by more than 1e12 over the "
                             f"record ({record.duration:.4g} s): no wave energy would be left to check")
        drift = (1 + d.drift) / expected - 1
    how = ("eta_dot given" if d.rate_method == "given" else
           f"eta_dot from frames by {d.rate_method}, error {d.rate_error:.2g}")
    note = (f"{d.k.size} shells hold the energy ({d.k.min():.4g}..{d.k.max():.4g} rad/m); {how}; swing about the "
            f"trend {d.swing:.2g}" if d.k.size else f"no energy to measure; {how}")
    quantity = f"relative change of wave energy over {record.duration:.4g} s"
    row = compare(quantity, drift, 0.0, atol=rtol, note=note)
    if not row.ok and d.swing > abs(drift):
        row = compare(quantity, drift, 0.0, atol=rtol,
                      note=f"{note}; likely cause: the energy swings by {d.swing:.2g} about its trend, more than it "
                           f"drifts: kinetic and potential energy do not trade at theory's rate (the simulator's "
                           f"omega is not theory's, see the dispersion row), so no damping can be read from it")
    elif not row.ok:
        cause = _damping_cause(d, record.dt, viscosity)
        if cause:
            row = compare(quantity, drift, 0.0, atol=rtol, note=f"{note}; likely cause: {cause}")
    elif d.swing > 10 * rtol:
        row = compare(quantity, drift, 0.0, atol=rtol,
                      note=f"{note}; the energy swings by {d.swing:.2g} about its trend: kinetic and potential "
                           f"energy do not trade at theory's rate (the simulator's omega is not theory's, see the "
                           f"dispersion row)")
    return row
