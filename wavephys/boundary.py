r"""Open-ocean boundary: the margin cutoff of Loviscach (2003), §3.

Each step the field is multiplied by h(p)·h(q) (p along x, q along y) with margin M:

.. math::

    h(p) = \begin{cases}
        1 - (p/M - 1)^2 & p < M \\
        1 & M \le p < N - M \\
        1 - ((N - 1 - p)/M - 1)^2 & p \ge N - M
    \end{cases}

(quadratic, the paper's choice), or h(p) = p/M on the same margins (linear, the earlier
choice of Loviscach 2002). Only the inner (N − 2M)² points are meant to be shown. How
much of a wave the margin reflects, as a function of λ/M, is measured by
:func:`wavephys.checks.cutoff_reflection`.
"""

from __future__ import annotations

import jax.numpy as jnp

from wavephys._inputs import check_choice, check_int

__all__ = ["CUTOFFS", "cutoff_profile", "cutoff_mask", "interior"]


def _quadratic(s):
    return 1.0 - (s - 1.0) ** 2


def _linear(s):
    return s


CUTOFFS = {"quadratic": _quadratic, "linear": _linear}
"""Cutoff shapes by name: s = p/M in [0, 1) ↦ weight."""


def cutoff_profile(n: int, margin: int, kind: str = "quadratic", dtype=jnp.float32):
    """The 1-D cutoff weights h(p), p = 0 … n − 1 (dimensionless, in [0, 1]).

    Parameters
    ----------
    n : int
        Grid points per side, ≥ 2.
    margin : int
        M, points, 0 ≤ M < n/2 (0: no cutoff, all weights 1).
    kind : {"quadratic", "linear"}
    dtype : dtype of the result.
    """
    n = check_int("n", n, lo=2)
    margin = check_int("margin", margin, lo=0)
    if 2 * margin >= n:
        raise ValueError(f"margin must be < n/2 = {n / 2}, got {margin}")
    check_choice("kind", kind, CUTOFFS)
    p = jnp.arange(n, dtype=dtype)
    if margin == 0:
        return jnp.ones(n, dtype)
    dist = jnp.minimum(p, n - 1 - p)  # distance to the nearer edge
    return jnp.where(dist < margin, CUTOFFS[kind](dist / margin), 1.0).astype(dtype)


def cutoff_mask(n: int, margin: int, kind: str = "quadratic", dtype=jnp.float32):
    """The 2-D weights h(q)·h(p) of shape ``(n, n)`` (rows q = y, columns p = x)."""
    h = cutoff_profile(n, margin, kind, dtype)
    return h[:, None] * h[None, :]


def interior(field, margin: int):
    """The visible inner ``(n − 2M)²`` part of ``field`` (last two axes)."""
    margin = check_int("margin", margin, lo=0)
    n = field.shape[-1]
    if 2 * margin >= n:
        raise ValueError(f"margin must be < n/2 = {n / 2}, got {margin}")
    return field[..., margin:n - margin, margin:n - margin]
