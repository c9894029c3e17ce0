"""What the validation groups share."""

from __future__ import annotations

import jax
import jax.numpy as jnp

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["working_dtype"]


def working_dtype():
    """float64 when ``jax_enable_x64`` is on (``wavephys validate --x64``), else float32.

    Returns
    -------
    numpy.dtype
        ``jnp.float64`` or ``jnp.float32``.
    """
    return jnp.float64 if jax.config.jax_enable_x64 else jnp.float32
