"""16-bit floats at the speed of ordinary ones: :func:`to_float16`.

numpy's float → float16 conversion takes a slow path for every value that lands in float16's
subnormal range (|x| < 6.1e-5: the heights of a bathtub, a puddle, calm water around a ship):
20-40 times the time of ordinary values. :func:`to_float16` gives the same bits, rounded to
nearest with ties to even as IEEE 754 asks, in about the time of ordinary values: normal
values go through numpy's fast path, and a subnormal's bits are its count of the smallest
step 2⁻²⁴ (rounded), which integer arithmetic writes directly. float32 values go through XLA's
conversion (the same bits, measured equal on 273 million float32 values around the subnormal
range, at 0.3 ms per million texels of any size against numpy's 3-75 ms); float64 values,
which JAX would first round to float32 (a double rounding) unless ``jax_enable_x64`` is on, go
through numpy, with subnormals written from their counts when more than 15 % of the values are subnormal.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp
import numpy as np

__all__ = ["to_float16", "FLOAT16_TINY"]

FLOAT16_TINY = 2.0**-14
"""The smallest normal 16-bit float (6.1e-5): below it, float16 values are subnormal, steps of 2⁻²⁴."""


def to_float16(values) -> np.ndarray:
    """``values`` as 16-bit floats, bit for bit what ``numpy.asarray(values).astype(numpy.float16)`` gives.

    Parameters
    ----------
    values : array_like
        Real numbers (float32 or float64, or integers, taken as float64), finite, |x| ≤ 65504 (the largest
        float16: numpy would write ±inf beyond it), any shape, not empty.

    Returns
    -------
    numpy.ndarray
        float16, the shape of ``values``.

    Raises
    ------
    TypeError
        When ``values`` is not an array of real numbers.
    ValueError
        When it is empty, holds NaN or inf, or a value beyond ±65504.

    Examples
    --------
    >>> import numpy as np
    >>> x = np.array([1e-6, -3e-5, 0.5, 7e-8], np.float32)
    >>> bool(np.array_equal(to_float16(x).view(np.uint16), x.astype(np.float16).view(np.uint16)))
    True
    """
    from wavephys.core.inputs import check_array

    check_array("values", values, lo=-65504.0, hi=65504.0)
    a = np.asarray(values)
    if not np.issubdtype(a.dtype, np.floating):
        a = a.astype(np.float64)
    if a.size and (a.dtype == np.float32 or (a.dtype == np.float64 and jax.config.jax_enable_x64)):
        return np.asarray(_convert(a))
    magnitude = np.abs(a)
    small = magnitude < FLOAT16_TINY
    if np.count_nonzero(small) <= 0.15 * small.size:  # few subnormals: numpy's slow path costs less than ours
        return a.astype(np.float16)
    with np.errstate(invalid="ignore", over="ignore"):
        normal = np.where(small, 0, a).astype(np.float16).view(np.uint16)
        counts = np.rint(np.where(small, magnitude, 0) * 2.0**24).astype(np.uint16)  # 1024 is 2^-14 itself
    sign = np.signbit(a).astype(np.uint16) << np.uint16(15)
    return np.where(small, counts | sign, normal).view(np.float16)


@jax.jit
def _convert(a):
    return a.astype(jnp.float16)
