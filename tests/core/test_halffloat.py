"""to_float16 is numpy's float16 conversion bit for bit (round to nearest, ties to even, subnormals included),
without numpy's slow path for subnormal values (its speed is measured in bench, not here)."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from wavephys.core.halffloat import FLOAT16_TINY, to_float16


def _same(a):
    with np.errstate(all="ignore"):
        return np.array_equal(to_float16(a).view(np.uint16), np.asarray(a).astype(np.float16).view(np.uint16))


def test_every_float32_around_the_subnormal_range():
    """Every 61st float32 bit pattern below 2^-13 (15.7 million), both signs, and the edges of the range."""
    b = np.arange(0, 0x39000000, 61, dtype=np.uint32).view(np.float32)
    assert _same(b) and _same(-b)
    edges = np.array([FLOAT16_TINY, np.nextafter(np.float32(FLOAT16_TINY), 0), 2.0**-25, 3 * 2.0**-25, 2.0**-24,
                      65504.0, 0.0, -0.0, np.inf], np.float32)
    assert _same(edges[:-1])
    with pytest.raises(ValueError, match="values"):
        to_float16(edges)  # inf, and 65520 would round to inf


@settings(max_examples=200, deadline=None)
@given(st.floats(min_value=-1e-3, max_value=1e-3, allow_nan=False), st.integers(0, 3))
def test_float64_mixtures(scale, seed):
    """float64 arrays (converted by numpy and the subnormal counts) with few and many subnormal values."""
    rng = np.random.default_rng(seed)
    a = rng.standard_normal(4096) * scale
    assert _same(a) and _same(a.astype(np.float32))


@pytest.mark.parametrize("shape", [(3,), (4, 5), (2, 3, 4)])
def test_shapes_and_kinds(shape):
    a = np.random.default_rng(1).standard_normal(shape) * 1e-5
    assert to_float16(a).shape == shape and to_float16(a).dtype == np.float16
    assert _same(a) and _same(a.astype(np.float32))
    assert _same(np.arange(int(np.prod(shape))).reshape(shape))  # integers are converted as float64
