"""Method families: several methods of one quantity, one dispatcher (colour-science style).

Each method is its own public, documented function (``reflectance_schlick``,
``floor_irradiance_beam``, …) listed in a :class:`Methods` mapping. The quantity's
dispatcher (``reflectance(..., method="schlick", **options)``) passes each method only
the keyword arguments its own signature declares, so options of other methods of the
family can travel in one bag (a planner's configuration) without piling up in every
signature. A keyword that no method of the family takes is a typo and raises
``TypeError``. Adding a method: write the function, add it to the family's mapping.

A method a shader can draw carries its GLSL beside its Python function (:func:`shader_form`);
:func:`glsl_family` writes every form of a family and the switch that picks one by its index,
so the GLSL a renderer compiles is generated from the registry, not kept by hand beside it.
"""

from __future__ import annotations

import inspect
from collections.abc import Mapping
from typing import Callable

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["Methods", "dispatch", "shader_form", "glsl_family"]


class Methods(Mapping):
    """An immutable name → function mapping for the methods of one ``quantity``.

    Parameters
    ----------
    quantity : str
        What the methods compute, for messages (``"Fresnel reflectance"``).
    **methods : Callable
        Each method by name, in the family's order (at least one).

    Attributes
    ----------
    quantity : str
        As given.
    glsl_forms : dict
        The methods with a GLSL form (:func:`shader_form`).

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

    @property
    def glsl_forms(self) -> dict:
        """``{method: (GLSL function name, GLSL source)}`` for the methods with a shader form
        (:func:`shader_form`), in the family's order."""
        return {k: (f.glsl_name, f.glsl) for k, f in self._methods.items() if getattr(f, "glsl", None)}


def shader_form(name: str, source: str) -> Callable:
    """Decorator: the GLSL form of a method, registered beside its Python function.

    Parameters
    ----------
    name : str
        The GLSL function's name (it must be defined by ``source``).
    source : str
        GLSL source defining ``name`` (and nothing a sibling form defines); it may call the forms
        registered before it in its family.

    Returns
    -------
    Callable
        A decorator that sets ``fn.glsl_name`` and ``fn.glsl`` and returns ``fn`` itself.

    >>> @shader_form("twice", "float twice(float x) { return 2.0 * x; }")
    ... def twice(x):
    ...     return 2 * x
    >>> twice.glsl_name, twice(2)
    ('twice', 4)
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str (a GLSL function's name), got {type(name).__name__}")
    if not name.isidentifier():
        raise ValueError(f"name must be a GLSL identifier, got {name!r}")
    if not isinstance(source, str):
        raise TypeError(f"source must be a str (GLSL), got {type(source).__name__}")
    if f"{name}(" not in source:
        raise ValueError(f"source must define {name}(...), got {source[:60]!r}")

    def register(fn: Callable) -> Callable:
        fn.glsl_name, fn.glsl = name, source.strip() + "\n"
        return fn

    return register


def glsl_family(methods: "Methods", switch: str, params: str, args: str, returns: str = "float") -> str:
    """GLSL: every shader form of ``methods`` (in the family's order) and ``switch``, the function that
    calls form ``i`` (its index in :attr:`Methods.glsl_forms`; an unknown index: form 0).

    Parameters
    ----------
    methods : Methods
        A family with at least one shader form; every form takes ``params``.
    switch : str
        The switch's GLSL name; it takes ``int form`` and then ``params``.
    params, args : str
        The forms' parameter list (``"float cos_i, float n1, float n2"``) and the arguments passed on
        (``"cos_i, n1, n2"``).
    returns : str
        The GLSL type every form returns.

    Returns
    -------
    str
        GLSL source.
    """
    forms = list(methods.glsl_forms.values())
    if not forms:
        raise ValueError(f"{methods.quantity}: no method has a shader form")
    calls = "".join(f"    if (form == {i}) return {name}({args});\n" for i, (name, _) in enumerate(forms) if i)
    return ("".join(src for _, src in forms) + f"{returns} {switch}(int form, {params}) {{  // "
            f"{methods.quantity}: the forms in their family's order\n{calls}    return {forms[0][0]}({args});\n}}\n")


def _keywords(fn: Callable) -> set[str]:
    params = inspect.signature(fn).parameters.values()
    return {p.name for p in params if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)}


def dispatch(methods: Mapping, method: str, *args, _family: str = "method", **kwargs):
    """Call ``methods[method](*args, **kwargs)`` for a plain mapping (see :class:`Methods`).

    Parameters
    ----------
    methods : Mapping
        Name → function (a :class:`Methods` or a plain mapping, made one for the call).
    method : str
        The method's name; ValueError naming ``method`` when it is not one of them.
    *args, **kwargs
        Passed on; each method gets only the keyword arguments its signature declares.
    _family : str
        The quantity's name in messages, for a plain mapping.

    Returns
    -------
    object
        What the method returns.
    """
    if isinstance(methods, Methods):
        return methods(method, *args, **kwargs)
    return Methods(_family, **methods)(method, *args, **kwargs)
