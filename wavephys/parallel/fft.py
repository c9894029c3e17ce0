"""Slab-decomposed 2-D real FFTs inside ``shard_map``: one huge grid over many devices.

Plain ``jnp.fft.rfft2`` of an array sharded by rows gathers the whole array on every
device (jax-ml/jax#15680). The slab decomposition instead transforms the local axis,
transposes with one ``all_to_all`` and transforms the other:

* :func:`rfft2` — rows-sharded real ``(..., n, n)`` → ``rfft`` along x (local) → pad the
  n/2 + 1 columns to W (:func:`~wavephys.parallel.layout.spectrum_width`) → ``all_to_all``
  (each device sends a (n/P) × (W/P) block to every other) → ``fft`` along y (now
  local). The result is the padded half spectrum ``(..., n, W)``, sharded by kx columns.
* :func:`irfft2` — the same in reverse: ``ifft`` along y, ``all_to_all`` back, drop the
  padding, ``irfft`` along x.

With ``mesh=None`` both are ``jnp.fft.rfft2``/``irfft2`` (the natural ``n//2 + 1`` columns).
Each transform moves (P − 1)/P of a device's complex block: :func:`exchanged_bytes`
gives the count, and :func:`collective_bytes` reads it back from a compiled program.
"""

from __future__ import annotations

import re

import jax
import jax.numpy as jnp
import numpy as np
from jax import shard_map

from wavephys.core.inputs import check_array, check_int, describe
from wavephys.parallel.layout import AXIS, _spec, check_mesh, device_count, spectrum_width

__all__ = ["rfft2", "irfft2", "exchanged_bytes", "collective_bytes"]


def _check_axis(axis):
    if not isinstance(axis, str) or not axis:
        raise TypeError(f"axis must be the name of a mesh axis (a non-empty str), got {describe(axis)}")


def rfft2(x, mesh=None, axis: str = AXIS):
    """2-D real FFT of ``x`` (..., n, n), sharded by rows over ``mesh``'s axis ``axis``.

    Parameters
    ----------
    x : array_like (..., n, n)
        Real fields, square on their last two axes.
    mesh : jax.sharding.Mesh, optional
        Split the rows over its axis ``axis`` (n divisible by its size); None: one device.
    axis : str
        The mesh axis.

    Returns
    -------
    jax.Array
        The half spectrum: ``(..., n, n//2 + 1)`` without a mesh, the padded ``(..., n, W)``
        sharded by columns with one (module doc).
    """
    _check_axis(axis)
    check_array("x", x, min_ndim=2)
    if np.shape(x)[-1] != np.shape(x)[-2]:
        raise ValueError(f"x must be square on its last two axes (n, n), got shape {np.shape(x)}")
    if mesh is None:
        return jnp.fft.rfft2(x)
    check_mesh(mesh, axis, np.shape(x)[-1])
    x = jnp.asarray(x)
    n, ndim = x.shape[-1], x.ndim
    width = spectrum_width(n, device_count(mesh, axis))

    def local(block):  # (..., n/P, n) real
        s = jnp.fft.rfft(block, axis=-1)
        s = jnp.pad(s, [(0, 0)] * (ndim - 1) + [(0, width - s.shape[-1])])
        s = jax.lax.all_to_all(s, axis, ndim - 1, ndim - 2, tiled=True)  # → (..., n, W/P)
        return jnp.fft.fft(s, axis=-2)

    return shard_map(local, mesh=mesh, in_specs=_spec(ndim, ndim - 2, axis), out_specs=_spec(ndim, ndim - 1, axis),
                     check_vma=False)(x)


def irfft2(spectrum, n: int, mesh=None, axis: str = AXIS):
    """Inverse of :func:`rfft2`.

    Parameters
    ----------
    spectrum : array_like (..., n, W), complex
        A half spectrum as :func:`rfft2` returns it (W = n//2 + 1, padded with a mesh).
    n : int
        The grid's side, ≥ 2.
    mesh : jax.sharding.Mesh, optional
    axis : str
        The mesh axis.

    Returns
    -------
    jax.Array (..., n, n)
        Real fields (sharded by rows with a mesh).
    """
    n = check_int("n", n, lo=2)
    _check_axis(axis)
    check_array("spectrum", spectrum, complex_ok=True, min_ndim=2)
    width = n // 2 + 1 if mesh is None else spectrum_width(n, check_mesh(mesh, axis, n))
    if np.shape(spectrum)[-2:] != (n, width):
        raise ValueError(f"spectrum must end in shape ({n}, {width}) (the {'padded ' if mesh else ''}half spectrum of "
                         f"an n = {n} grid), got {np.shape(spectrum)}")
    if mesh is None:
        return jnp.fft.irfft2(spectrum, s=(n, n))
    spectrum = jnp.asarray(spectrum)
    ndim = spectrum.ndim

    def local(block):  # (..., n, W/P) complex
        s = jnp.fft.ifft(block, axis=-2)
        s = jax.lax.all_to_all(s, axis, ndim - 2, ndim - 1, tiled=True)  # → (..., n/P, W)
        return jnp.fft.irfft(s[..., : n // 2 + 1], n=n, axis=-1)

    return shard_map(local, mesh=mesh, in_specs=_spec(ndim, ndim - 1, axis), out_specs=_spec(ndim, ndim - 2, axis),
                     check_vma=False)(spectrum)


def exchanged_bytes(n: int, shards: int, planes: int, itemsize: int = 8) -> int:
    """Bytes one device sends in one slab transform of ``planes`` stacked n × n fields split
    over ``shards`` devices: its (n/P) × W complex block less the part it keeps, (P − 1)/P
    of it.

    Parameters
    ----------
    n : int
        Grid side, ≥ 2, divisible by ``shards``.
    shards : int
        Devices P, ≥ 1.
    planes : int
        Fields transformed together, ≥ 1.
    itemsize : int
        Bytes per complex value: 8 for complex64 (float32 fields), 16 for complex128.

    Returns
    -------
    int
        Bytes sent by each device.
    """
    n, shards, planes = check_int("n", n, lo=2), check_int("shards", shards, lo=1), check_int("planes", planes, lo=1)
    itemsize = check_int("itemsize", itemsize, lo=1)
    if n % shards:
        raise ValueError(f"n = {n} must be divisible by shards = {shards}")
    if shards == 1:
        return 0
    width = spectrum_width(n, shards)
    block = planes * (n // shards) * width * itemsize
    return block * (shards - 1) // shards


_SHAPE = re.compile(r"(c64|c128|f32|f64)\[([0-9,]*)\]")
_ITEM = {"c64": 8, "c128": 16, "f32": 4, "f64": 8}


def collective_bytes(compiled_text: str) -> dict[str, int]:
    """Bytes each device sends per run of a compiled SPMD program, by collective kind.

    Reads the optimized HLO text (``jax.jit(f).lower(...).compile().as_text()``): for every
    ``all-to-all`` the operand blocks it exchanges, counting the ones a device sends away
    ((P − 1) of its P blocks); other collectives (``all-gather``, ``all-reduce``,
    ``collective-permute``) are counted by their result size, so that an unexpected one shows.

    Parameters
    ----------
    compiled_text : str
        The optimized HLO text.

    Returns
    -------
    dict
        {collective kind: bytes per device per run}.
    """
    if not isinstance(compiled_text, str):
        raise TypeError(f"compiled_text must be the str of compiled.as_text(), got {describe(compiled_text)}")
    totals: dict[str, int] = {}
    for line in compiled_text.splitlines():
        line = line.strip()
        match = re.match(r"%?[\w.\-]+ = (.*?) (all-to-all|all-gather|all-reduce|collective-permute|reduce-scatter)"
                         r"(-start)?\(", line)
        if not match:
            continue
        result, kind = match.group(1), match.group(2)
        sizes = [_ITEM[t] * int(np.prod([int(d) for d in dims.split(",") if d] or [1]))
                 for t, dims in _SHAPE.findall(result)]
        if kind == "all-to-all":
            blocks = len(sizes)
            if blocks == 1:  # the array form: one operand split over the replica group
                group = re.search(r"replica_groups=\{\{([0-9,]*)\}", line)
                iota = re.search(r"replica_groups=\[\d+,(\d+)\]<=", line)  # [groups,size]<=[n]
                blocks = len(group.group(1).split(",")) if group else (int(iota.group(1)) if iota else 1)
            sent = sum(sizes) * (blocks - 1) // blocks if blocks > 1 else 0
        else:
            sent = sum(sizes)
        totals[kind] = totals.get(kind, 0) + sent
    return totals
