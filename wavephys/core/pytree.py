"""Frozen dataclasses as JAX pytrees: numeric fields are leaves, sizes and switches are static.

``jit``/``vmap``/``grad`` then sweep the numeric fields (a batch of depths, the gradient
with respect to surface tension) while the static ones fix array shapes and compiled
programs. Rebuilding a pytree inside a JAX transformation bypasses ``__post_init__``
checks: the values may be tracers there.
"""

from __future__ import annotations

import jax
import jax.numpy as jnp

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["register", "stack"]


def register(cls, data: tuple[str, ...], static: tuple[str, ...] = ()):
    """Register frozen dataclass ``cls`` as a pytree with leaves ``data`` and static ``static``.

    Unflattening sets the fields directly (no validation), as JAX transformations need.

    Parameters
    ----------
    cls : type
        A frozen dataclass.
    data : tuple of str
        The fields that are leaves (arrays or numbers: traced under ``jit``, mapped by ``vmap``).
    static : tuple of str
        The fields kept as auxiliary data (hashable; a change compiles a new program).

    Returns
    -------
    type
        ``cls`` itself (usable as a class decorator's result).
    """

    def flatten(obj):
        return tuple(getattr(obj, f) for f in data), tuple(getattr(obj, f) for f in static)

    def unflatten(aux, children):
        obj = object.__new__(cls)
        for name, value in zip(data, children):
            object.__setattr__(obj, name, value)
        for name, value in zip(static, aux):
            object.__setattr__(obj, name, value)
        return obj

    jax.tree_util.register_pytree_node(cls, flatten, unflatten)
    return cls


def stack(items):
    """Stack pytrees of one structure into one pytree of arrays with a leading batch axis.

    Parameters
    ----------
    items : sequence of pytree
        At least one, all of one structure (ValueError naming the first that differs).

    Returns
    -------
    pytree
        Of that structure, each leaf the leaves of ``items`` stacked along a new axis 0.

    >>> from wavephys import Water
    >>> batch = stack([Water(depth=d) for d in (1.0, 2.0, 4.0)])
    >>> batch.depth.shape
    (3,)
    """
    if isinstance(items, (str, bytes, dict)) or not hasattr(items, "__iter__"):
        raise TypeError(f"items must be a list of pytrees of one structure, got {type(items).__name__}")
    items = list(items)
    if not items:
        raise ValueError("items must hold at least one pytree, got none")
    structure = jax.tree_util.tree_structure(items[0])
    for i, item in enumerate(items[1:], 1):
        if jax.tree_util.tree_structure(item) != structure:
            raise ValueError(f"items[{i}] has another structure than items[0]: {structure} vs "
                             f"{jax.tree_util.tree_structure(item)}")
    return jax.tree_util.tree_map(lambda *leaves: jnp.stack([jnp.asarray(v) for v in leaves]), *items)
