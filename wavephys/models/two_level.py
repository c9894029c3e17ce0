"""Shared driver for the two-level (leapfrog-type) peer schemes: η^{n+1} = step(η^n, η^{n−1})."""

from __future__ import annotations

from functools import partial

import jax
import jax.numpy as jnp

from wavephys.core.inputs import check_array

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["check_levels", "run_two_level"]


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


@partial(jax.jit, static_argnames=("step", "steps", "history"))
def run_two_level(step, eta, eta_prev, args, steps: int, history: bool):
    """Apply ``step(η^n, η^{n−1}, *args)`` ``steps`` times in one compiled loop.

    Parameters
    ----------
    step : Callable
        ``step(eta, eta_prev, *args) -> eta_next``, traceable.
    eta, eta_prev : jax.Array
        η^0 and η^{−1}, m.
    args : tuple
        Passed to every step.
    steps : int
        N, static.
    history : bool
        Also return every step's η.

    Returns
    -------
    tuple
        (η^N, η^{N−1}) and, with ``history``, the stacked η^1 … η^N.
    """
    def body(carry, _):
        a, b = carry
        c = step(a, b, *args)
        return (c, a), (c if history else None)

    (a, b), hist = jax.lax.scan(body, (eta, eta_prev), None, length=steps)
    return (a, b, hist) if history else (a, b)
