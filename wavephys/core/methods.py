"""Method families: several methods of one quantity, one dispatcher (colour-science style).

Each method is its own public, documented function (``reflectance_schlick``,
``floor_irradiance_beam``, …) listed in a :class:`Methods` mapping. The quantity's
dispatcher (``reflectance(..., method="schlick", **options)``) passes each method only
the keyword arguments its own signature declares, so options of other methods of the
family can travel in one bag (a planner's configuration) without piling up in every
signature. A keyword that no method of the family takes is a typo and raises
``TypeError``. Adding a method: write the function, add it to the family's mapping.
"""

from __future__ import annotations

import inspect
from collections.abc import Mapping
from typing import Callable

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["Methods", "dispatch"]


class Methods(Mapping):
    """An immutable name → function mapping for the methods of one ``quantity``.

    >>> family = Methods("doubling", twice=lambda x, *, scale=1: 2 * x * scale, plus=lambda x, *, offset=0: x + x + offset)
    >>> family("plus", 3, offset=1, scale=5)   # scale belongs to "twice": not passed to "plus"
    7
    >>> sorted(family)
    ['plus', 'twice']
    """

    def __init__(self, quantity: str, **methods: Callable):
        if not methods:
            raise ValueError("a method family needs at least one method")
        self.quantity = quantity
        self._methods = dict(methods)
        self._params = {k: _keywords(f) for k, f in methods.items()}
        self._all = set().union(*self._params.values())

    def __getitem__(self, name: str) -> Callable:
        return self._methods[name]

    def __iter__(self):
        return iter(self._methods)

    def __len__(self) -> int:
        return len(self._methods)

    def __repr__(self) -> str:
        return f"Methods({self.quantity!r}: {', '.join(self._methods)})"

    def check(self, method, name: str = "method") -> Callable:
        """The function for ``method``; TypeError/ValueError naming ``name`` otherwise."""
        if not isinstance(method, str):
            raise TypeError(f"{name} must be one of {list(self._methods)} for {self.quantity}, got "
                            f"{type(method).__name__} {method!r}")
        if method not in self._methods:
            raise ValueError(f"{name} must be one of {list(self._methods)} for {self.quantity}, got {method!r}")
        return self._methods[method]

    def options(self, method: str, kwargs: dict) -> dict:
        """The keyword arguments of ``kwargs`` that ``method`` takes (TypeError for unknown ones)."""
        unknown = set(kwargs) - self._all
        if unknown:
            raise TypeError(f"{self.quantity}: no method takes {sorted(unknown)}; the options are "
                            + "; ".join(f"{m}: {sorted(p) or 'none'}" for m, p in self._params.items()))
        mine = self._params[method]
        return {k: v for k, v in kwargs.items() if k in mine}

    def __call__(self, method: str, *args, **kwargs):
        """Call ``method`` with ``args`` and the keyword arguments its signature declares."""
        fn = self.check(method)
        return fn(*args, **self.options(method, kwargs))


def _keywords(fn: Callable) -> set[str]:
    params = inspect.signature(fn).parameters.values()
    return {p.name for p in params if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)}


def dispatch(methods: Mapping, method: str, *args, _family: str = "method", **kwargs):
    """Call ``methods[method](*args, **kwargs)`` for a plain mapping (see :class:`Methods`)."""
    if isinstance(methods, Methods):
        return methods(method, *args, **kwargs)
    return Methods(_family, **methods)(method, *args, **kwargs)
