r"""Cubic Hermite frames between simulation steps (Loviscach 2003, §3; docs/physics.md §1.6).

.. math::

    \eta(t + s\Delta t) \approx h_{00}(s)\eta(t) + h_{01}(s)\eta(t + \Delta t)
        + \Delta t\,\big(h_{10}(s)\dot\eta(t) + h_{11}(s)\dot\eta(t + \Delta t)\big)

h00 = 2s³ − 3s² + 1, h01 = −2s³ + 3s², h10 = s³ − 2s² + s, h11 = s³ − s². At s = 1/3 the
weights are 20/27, 7/27, 4/27, −2/27. Correction to the source: the paper prints the η̇
terms without the factor Δt, which is dimensionally wrong (η̇ is m/s); we include it.
The error against exact propagation grows with ωΔt: :func:`hermite_error` gives it for
one Fourier mode, exactly.
"""

from __future__ import annotations

import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import Array, check_scalar, validate
from wavephys.core.specs import FRACTION, POSITIVE

__all__ = ["hermite_weights", "hermite_frame", "hermite_error"]


@validate(s=Array(lo=0.0, hi=1.0))
def hermite_weights(s):
    """Cubic Hermite basis (h00, h01, h10, h11) at s ∈ [0, 1] (dimensionless).

    Parameters
    ----------
    s : array_like
        Fraction of the step, dimensionless, in [0, 1], any shape.

    Returns
    -------
    (h00, h01, h10, h11) : tuple of jax.Array
        The four weights, dimensionless, each of the shape of ``s``.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (docs/physics.md
    §1.6).
    """
    s = jnp.asarray(s, dtype=jnp.result_type(float, s))
    s2, s3 = s * s, s * s * s
    return 2 * s3 - 3 * s2 + 1, -2 * s3 + 3 * s2, s3 - 2 * s2 + s, s3 - s2


@validate(eta0=Array(), eta1=Array(), eta_dot0=Array(), eta_dot1=Array(), dt=POSITIVE, s=FRACTION)
def hermite_frame(eta0, eta1, eta_dot0, eta_dot1, dt, s):
    """Interpolated height at t + sΔt from heights (m) and rates (m/s) at t and t + Δt.

    Parameters
    ----------
    eta0, eta1 : array_like
        η(t), η(t + Δt), m (same shape).
    eta_dot0, eta_dot1 : array_like
        η̇(t), η̇(t + Δt), m/s.
    dt : float
        Δt, s, > 0.
    s : float
        Fraction of the step, in [0, 1].

    Returns
    -------
    array_like
        η(t + sΔt), m, the shape of ``eta0``.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (printed without
    the factor Δt on the η̇ terms; corrected here, module docstring).
    """
    shapes = {jnp.shape(a) for a in (eta0, eta1, eta_dot0, eta_dot1)}
    if len(shapes) != 1:
        raise ValueError(f"eta0, eta1, eta_dot0, eta_dot1 must share one shape, got {shapes}")
    h00, h01, h10, h11 = hermite_weights(s)
    return h00 * eta0 + h01 * eta1 + dt * (h10 * eta_dot0 + h11 * eta_dot1)


def hermite_error(omega_dt: float, s: float = 1.0 / 3.0) -> float:
    """|error| / amplitude of the Hermite frame at t + sΔt for a wave of frequency ω.

    Exact for one Fourier mode e^{−iωt}: compares h00 + h01·e^{−ix} + (−ix)(h10 + h11·e^{−ix})
    with e^{−isx}, x = ωΔt. The worst case over a field is its largest ωΔt.

    Parameters
    ----------
    omega_dt : float
        ωΔt, rad, ≥ 0.
    s : float
        Fraction of the step, in [0, 1] (default 1/3).

    Returns
    -------
    float
        |error|/amplitude, dimensionless.

    References
    ----------
    J. Loviscach (2003). Complex water effects at interactive frame rates. *WSCG*, §3 (docs/physics.md
    §1.6).
    """
    check_scalar("omega_dt", omega_dt, lo=0.0)
    check_scalar("s", s, lo=0.0, hi=1.0)
    h00, h01, h10, h11 = (float(v) for v in hermite_weights(s))
    z = np.exp(-1j * omega_dt)
    approx = h00 + h01 * z - 1j * omega_dt * (h10 + h11 * z)
    return float(abs(approx - np.exp(-1j * s * omega_dt)))
