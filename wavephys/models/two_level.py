"""The two-level (leapfrog-type) peer schemes' shared input check (their loop is the steppers' one:
:mod:`wavephys.core.stepper`)."""

from __future__ import annotations

import jax.numpy as jnp

from wavephys.core.inputs import check_array

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["check_levels"]


def check_levels(eta, eta_prev):
    """Validate the two starting levels (finite, ≥ 2-D, one shape); return them as arrays.

    Parameters
    ----------
    eta, eta_prev : array_like (..., ny, nx)
        η^n and η^{n−1}, m.

    Returns
    -------
    (jax.Array, jax.Array)
        Both, ``eta_prev`` in ``eta``'s dtype.
    """
    check_array("eta", eta, min_ndim=2)
    check_array("eta_prev", eta_prev, min_ndim=2)
    if jnp.shape(eta) != jnp.shape(eta_prev):
        raise ValueError(f"eta and eta_prev must have one shape, got {jnp.shape(eta)} and {jnp.shape(eta_prev)}")
    eta = jnp.asarray(eta)
    return eta, jnp.asarray(eta_prev, eta.dtype)
