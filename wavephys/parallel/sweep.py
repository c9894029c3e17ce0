"""Sweeps: one function over many scenes or models, ``vmap`` inside a device and the batch
axis sharded across devices (docs/architecture.md, "Scale-out")."""

from __future__ import annotations

from typing import Callable, Sequence

import jax
import jax.numpy as jnp
import numpy as np
from jax.sharding import NamedSharding, PartitionSpec

from wavephys.core.inputs import check_int, describe
from wavephys.parallel.hosts import _gather
from wavephys.parallel.layout import place, row_mesh

__all__ = ["sweep"]

BATCH = "batch"


def sweep(fn: Callable, items: Sequence, *, devices=None, per_device: int = 1) -> list:
    """``[fn(item) for item in items]``, evaluated in batches: ``jax.vmap(fn)`` over
    ``per_device`` items on each device, the batch split over ``devices``.

    Parameters
    ----------
    fn : callable
        A pure JAX function of one item, returning a pytree of arrays (e.g. a measure of a
        simulation run from a :class:`~wavephys.simulation.Model`).
    items : sequence of pytrees
        Scenes or models. Items of one structure (equal static parts: grid size, options)
        are stacked and batched together; each structure is its own compiled program.
    devices : sequence of jax devices, optional
        Default: ``jax.devices()`` (every device of every process under ``jax.distributed``).
    per_device : int
        Items each device evaluates at once (≥ 1): memory against fewer dispatches. More than the items
        need (``ceil(len(items) / devices)``) is the same as that many.

    Returns
    -------
    list
        ``fn(item)`` for every item, in order, as numpy pytrees. An output holding NaN or inf is returned with
        a ``RuntimeWarning`` that names the items.

    Raises
    ------
    TypeError
        When ``fn`` is not callable, ``items`` is not a sequence, or an item holds a leaf that is not an array of
        real or complex numbers.
    ValueError
        When an item holds NaN, or ``per_device`` < 1.
    """
    if not callable(fn):
        raise TypeError(f"fn must be a function of one item, got {describe(fn)}")
    if isinstance(items, (str, bytes)) or not hasattr(items, "__len__"):
        raise TypeError(f"items must be a sequence of pytrees (models, scenes), got {describe(items)}")
    items = list(items)
    per_device = check_int("per_device", per_device, lo=1)
    if not items:
        return []
    mesh = row_mesh(jax.devices() if devices is None else devices, BATCH)
    chunk = mesh.size * min(per_device, -(-len(items) // mesh.size))  # no batch larger than the items need
    groups: dict = {}  # one program per structure and leaf shapes
    for i, item in enumerate(items):
        leaves, tree = jax.tree_util.tree_flatten(item)
        for leaf in leaves:
            kind = np.result_type(leaf) if isinstance(leaf, (int, float, complex, np.generic, np.ndarray, jax.Array)) \
                else None
            if kind is None or not (np.issubdtype(kind, np.number) or kind == np.bool_):
                raise TypeError(f"items[{i}] holds a leaf that is not an array of numbers: {describe(leaf)}")
            if np.issubdtype(kind, np.inexact) and np.any(np.isnan(np.asarray(leaf))):
                raise ValueError(f"items[{i}] holds NaN")  # inf is a value (deep water's depth)
        shapes = tuple((np.shape(a), np.result_type(a).str) for a in leaves)
        groups.setdefault((tree, shapes), []).append((i, leaves))
    out: list = [None] * len(items)
    for (tree, _), members in groups.items():
        batched = _compiled(fn, tree, mesh)
        for start in range(0, len(members), chunk):
            part = members[start:start + chunk]
            rows = [leaves for _, leaves in part] + [part[-1][1]] * (chunk - len(part))  # pad with the last
            stacked = [np.stack([np.asarray(r[j]) for r in rows]) for j in range(len(rows[0]))]
            sharded = [place(a, NamedSharding(mesh, PartitionSpec(BATCH))) for a in stacked]
            result = jax.tree_util.tree_map(_gather, batched(*sharded))
            for k, (index, _) in enumerate(part):
                out[index] = jax.tree_util.tree_map(lambda a: a[k], result)
    bad = [i for i, r in enumerate(out) if not all(np.all(np.isfinite(a)) for a in jax.tree_util.tree_leaves(r)
                                                   if np.issubdtype(np.asarray(a).dtype, np.inexact))]
    if bad:
        import warnings

        warnings.warn(f"sweep: fn returned NaN or inf for items {bad[:10]}{' ...' if len(bad) > 10 else ''} "
                      f"(from items without NaN)", RuntimeWarning, stacklevel=2)
    return out


def _compiled(fn, tree, mesh):
    sharding = NamedSharding(mesh, PartitionSpec(BATCH))

    def one(*leaves):
        return fn(jax.tree_util.tree_unflatten(tree, leaves))

    return jax.jit(jax.vmap(one), in_shardings=sharding, out_shardings=sharding)
