"""Module names that moved stay importable: ``wavephys.dispersion`` is ``wavephys.physics.dispersion``.

A package calls :func:`install` with a mapping of old submodule names to the module(s)
they now live in. ``import wavephys.dispersion`` and ``from wavephys import dispersion``
then give the very module object at the new place (nothing is copied, so monkeypatching
either name affects both). An old name that was split over several modules gets a
module of its own that re-exports their public names. Nothing is imported until the old
name is used. Every old name warns (``DeprecationWarning``, pointing at the importing line) when imported.
:func:`renamed_options` does the same for a keyword argument that was renamed.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import types
import warnings

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["install", "renamed_options", "deprecated_function"]


REMOVAL = "0.4"
"""The release in which the moved names of :func:`install` go."""


class _AliasFinder(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    def __init__(self, package: str, aliases: dict[str, tuple[str, ...]], deprecated=()):
        self.package = package
        self.aliases = {f"{package}.{old}": targets for old, targets in aliases.items()}
        self.deprecated = {f"{package}.{old}" for old in deprecated}

    def find_spec(self, fullname, path=None, target=None):
        if fullname in self.aliases:
            return importlib.util.spec_from_loader(fullname, self)
        return None

    def create_module(self, spec):
        return None  # a placeholder module; exec_module replaces or fills it

    def exec_module(self, module):
        if module.__name__ in self.deprecated:
            warnings.warn(f"{module.__name__} has moved to {', '.join(self.aliases[module.__name__])}; the old "
                          f"name will be removed in {REMOVAL}", DeprecationWarning, stacklevel=2)  # the importing line (the
            # warnings module skips the import machinery's frames)
        targets = [importlib.import_module(t) for t in self.aliases[module.__name__]]
        if len(targets) == 1:
            sys.modules[module.__name__] = targets[0]  # the import system returns this object
            return
        names = []
        for t in targets:
            public = getattr(t, "__all__", [n for n in vars(t) if not n.startswith("_")])
            names += [n for n in public if n not in names]
            module.__dict__.update({n: getattr(t, n) for n in public})
        module.__all__ = names
        module.__doc__ = "Re-exports " + ", ".join(t.__name__ for t in targets) + " (the old module name)."


def install(package: str, aliases: dict[str, str | tuple[str, ...]], deprecated=None):
    """Make ``package.<old>`` importable for each ``old → new`` (or ``old → (new, new2, …)``);
    the old names in ``deprecated`` (default: every one) warn when imported, naming the new place and the
    release that removes them (:data:`REMOVAL`).

    Returns a module ``__getattr__`` for the package, so ``package.<old>`` also works as an
    attribute after ``import package``.

    Parameters
    ----------
    package : str
        The package that keeps the old names (``"wavephys"``).
    aliases : dict of str to str or tuple of str
        Old module name → the new module's full name (or several, searched in order for attributes).
    deprecated : iterable of str, optional
        The old names that warn (default: all).

    Returns
    -------
    Callable
        The package's module ``__getattr__(name)``.
    """
    table = {old: (new,) if isinstance(new, str) else tuple(new) for old, new in aliases.items()}
    deprecated = tuple(table) if deprecated is None else tuple(deprecated)
    if not any(isinstance(f, _AliasFinder) and f.package == package for f in sys.meta_path):
        sys.meta_path.append(_AliasFinder(package, table, deprecated))

    def __getattr__(name: str) -> types.ModuleType:
        if name in table:
            full = f"{package}.{name}"
            if full in sys.modules or name not in deprecated:
                return importlib.import_module(full)
            with warnings.catch_warnings():  # the finder's warning would name this line: said below instead
                warnings.simplefilter("ignore", DeprecationWarning)
                module = importlib.import_module(full)
            level, frame = 2, sys._getframe(1)  # the caller's line: past the package's own __getattr__
            while frame is not None and frame.f_globals.get("__name__") == package:
                level, frame = level + 1, frame.f_back
            warnings.warn(f"{full} has moved to {', '.join(table[name])}; the old name will be removed in "
                          f"{REMOVAL}", DeprecationWarning, stacklevel=level)
            return module
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    return __getattr__


def renamed_options(function: str, options: dict, renames: dict, since: str = "0.3") -> dict:
    """``options`` with each old keyword of ``renames`` ({old: new}) replaced by its new name,
    warning (``DeprecationWarning``) that ``function`` renamed it in ``since``; TypeError when a
    call passes both names. The input is not modified.

    Parameters
    ----------
    function : str
        The renaming function's name, for the messages.
    options : dict
        The keyword arguments of a call.
    renames : dict of str to str
        Old keyword → new keyword.
    since : str
        The release that renamed them.

    Returns
    -------
    dict
        The keyword arguments under their new names.
    """
    out = dict(options)
    for old, new in renames.items():
        if old not in out:
            continue
        if new in out:
            raise TypeError(f"{function}: {old!r} is the old name of {new!r}; pass only {new!r}")
        warnings.warn(f"{function}: the option {old!r} was renamed {new!r} in {since}; the old name will be "
                      f"removed in a later release", DeprecationWarning, stacklevel=3)
        out[new] = out.pop(old)
    return out


def deprecated_function(function, name: str, replacement: str, since: str = "0.3", removal: str = "0.4"):
    """``function`` under its public ``name``, warning (``DeprecationWarning``) at each call that it is
    deprecated since ``since`` and goes in ``removal``, and what to use instead; its signature and
    documentation are the function's, with the notice first.

    Parameters
    ----------
    function : Callable
        What the old name calls.
    name : str
        The old public name.
    replacement : str
        What to use instead, as the message says it.
    since, removal : str
        The releases that deprecate it and remove it.

    Returns
    -------
    Callable
        The warning wrapper.
    """
    import functools

    message = f"{name} is deprecated since {since} and will be removed in {removal}: use {replacement}"

    @functools.wraps(function)
    def wrapper(*args, **kwargs):
        warnings.warn(message, DeprecationWarning, stacklevel=2)
        return function(*args, **kwargs)

    wrapper.__name__ = wrapper.__qualname__ = name
    wrapper.__doc__ = f".. deprecated:: {since}\n    {message}.\n\n" + (function.__doc__ or "")
    wrapper.__deprecated__ = message
    return wrapper
