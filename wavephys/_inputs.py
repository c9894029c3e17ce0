"""Input validation at the public boundary.

Every public entry point calls these helpers on its user-facing arguments so that bad
input fails with a ``ValueError`` naming the parameter, its value and the allowed range,
instead of a silent NaN field or an error deep inside XLA. Inside ``jit`` the arguments
are tracers whose values are unknown; the helpers then check only what is static
(shapes) and leave the values alone, so traced inner code carries no Python checks.
"""

from __future__ import annotations

import math
from typing import Any

import jax
import numpy as np

__all__ = ["is_traced", "check_scalar", "check_array", "check_int", "check_choice"]


def is_traced(x: Any) -> bool:
    """True when ``x`` is (or contains) a JAX tracer, i.e. its value is not known yet."""
    return any(isinstance(leaf, jax.core.Tracer) for leaf in jax.tree_util.tree_leaves(x))


def _describe(lo, hi, lo_open, hi_open) -> str:
    left = "(" if lo_open else "["
    right = ")" if hi_open else "]"
    lo_s = "-inf" if lo is None else repr(lo)
    hi_s = "inf" if hi is None else repr(hi)
    return f"{left}{lo_s}, {hi_s}{right}"


def check_scalar(
    name: str,
    value: Any,
    *,
    lo: float | None = None,
    hi: float | None = None,
    lo_open: bool = False,
    hi_open: bool = False,
    allow_inf: bool = False,
) -> Any:
    """Check a real scalar parameter; return it unchanged.

    Raises ``ValueError`` if ``value`` is not a real scalar, is NaN, is infinite (unless
    ``allow_inf``) or lies outside the interval given by ``lo``/``hi`` (closed unless
    ``lo_open``/``hi_open``). Tracers pass unchecked.
    """
    if is_traced(value):
        return value
    arr = np.asarray(value)
    if arr.ndim != 0 or not np.issubdtype(arr.dtype, np.number) or np.iscomplexobj(arr):
        raise ValueError(f"{name} must be a real scalar, got {value!r}")
    v = float(arr)
    if math.isnan(v) or (math.isinf(v) and not allow_inf):
        raise ValueError(f"{name} must be finite, got {v!r}")
    _check_range(name, v, v, lo, hi, lo_open, hi_open, repr(v))
    return value


def _check_range(name, vmin, vmax, lo, hi, lo_open, hi_open, shown):
    bad = False
    if lo is not None:
        bad |= vmin <= lo if lo_open else vmin < lo
    if hi is not None:
        bad |= vmax >= hi if hi_open else vmax > hi
    if bad:
        raise ValueError(
            f"{name} must lie in {_describe(lo, hi, lo_open, hi_open)}, got {shown}"
        )


def check_array(
    name: str,
    value: Any,
    *,
    lo: float | None = None,
    hi: float | None = None,
    lo_open: bool = False,
    hi_open: bool = False,
    allow_inf: bool = False,
    complex_ok: bool = False,
    min_ndim: int = 0,
    shape_tail: tuple[int, ...] | None = None,
) -> Any:
    """Check an array argument (values and shape); return it unchanged.

    ``shape_tail`` requires the trailing axes to equal the given sizes (e.g. ``(n, n)``
    for a field on an ``n``-point grid). Shapes are checked even under ``jit``; values
    only when concrete.
    """
    shape = np.shape(value)
    if len(shape) < min_ndim:
        raise ValueError(f"{name} must have at least {min_ndim} dimensions, got shape {shape}")
    if shape_tail is not None and (
        len(shape) < len(shape_tail) or tuple(shape[len(shape) - len(shape_tail):]) != tuple(shape_tail)
    ):
        raise ValueError(
            f"{name} must have trailing shape {tuple(shape_tail)}, got shape {shape}"
        )
    if is_traced(value):
        return value
    if isinstance(value, jax.Array) and value.size > 4096:
        _check_device_array(name, value, lo, hi, lo_open, hi_open, allow_inf, complex_ok)
        return value
    arr = np.asarray(value)
    if not np.issubdtype(arr.dtype, np.number):
        raise ValueError(f"{name} must be numeric, got dtype {arr.dtype}")
    if np.iscomplexobj(arr) and not complex_ok:
        raise ValueError(f"{name} must be real, got complex values")
    if arr.size == 0:
        raise ValueError(f"{name} must not be empty, got shape {shape}")
    finite = np.isfinite(arr)
    if not finite.all():
        if np.isnan(arr).any() or not allow_inf:
            raise ValueError(f"{name} must be finite everywhere; it contains NaN or inf")
    if lo is not None or hi is not None:
        real = arr.real
        _check_range(name, real.min(), real.max(), lo, hi, lo_open, hi_open,
                     f"values in [{real.min()!r}, {real.max()!r}]")
    return value


@jax.jit
def _summary(x):
    """(all finite, any NaN, min, max) of the real part, in one pass on the device."""
    r = jax.numpy.real(x)
    return jax.numpy.isfinite(x).all(), jax.numpy.isnan(x).any(), r.min(), r.max()


def _check_device_array(name, value, lo, hi, lo_open, hi_open, allow_inf, complex_ok):
    """Value checks of a large JAX array without copying it to the host."""
    if jax.numpy.iscomplexobj(value) and not complex_ok:
        raise ValueError(f"{name} must be real, got complex values")
    finite, has_nan, vmin, vmax = (v.item() for v in jax.device_get(_summary(value)))
    if not finite and (has_nan or not allow_inf):
        raise ValueError(f"{name} must be finite everywhere; it contains NaN or inf")
    if lo is not None or hi is not None:
        _check_range(name, vmin, vmax, lo, hi, lo_open, hi_open, f"values in [{vmin!r}, {vmax!r}]")


def check_int(name: str, value: Any, *, lo: int | None = None, hi: int | None = None,
              even: bool = False) -> int:
    """Check an integer parameter (a Python or numpy integer, not a bool); return int."""
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{name} must be an integer, got {value!r}")
    v = int(value)
    _check_range(name, v, v, lo, hi, False, False, repr(v))
    if even and v % 2:
        raise ValueError(f"{name} must be even, got {v}")
    return v


def check_choice(name: str, value: Any, choices) -> Any:
    """Check that ``value`` is one of ``choices``."""
    if value not in choices:
        raise ValueError(f"{name} must be one of {sorted(choices)}, got {value!r}")
    return value
