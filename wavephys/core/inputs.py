"""Input validation at the public boundary.

Every public entry point calls these helpers on its user-facing arguments so that bad
input fails before any work with an error that names the parameter, its value and the
allowed range:

* ``TypeError`` for the wrong kind of object (a string, ``None``, a bool where a number
  is meant, a complex number where a real one is, an object of another class);
* ``ValueError`` for the wrong value (NaN or inf, out of range, the wrong shape, empty).

Inside ``jit``/``vmap``/``grad`` the arguments are tracers whose values are unknown; the
helpers then check only what is static (kinds of objects and shapes) and leave values
alone, so traced code carries no Python checks and costs nothing extra. To check traced
values as well, wrap the function with :func:`jax.experimental.checkify.checkify`
(see ``docs/physics.md``, "Checking traced values").
"""

from __future__ import annotations

import math
import numbers
from typing import Any

import jax
import numpy as np

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["is_traced", "check_scalar", "check_array", "check_int", "check_choice", "check_bool",
           "check_instance", "describe"]


def is_traced(x: Any) -> bool:
    """True when ``x`` is (or contains) a JAX tracer, i.e. its value is not known yet.

    Parameters
    ----------
    x : object
        Any value or pytree.

    Returns
    -------
    bool
    """
    return any(isinstance(leaf, jax.core.Tracer) for leaf in jax.tree_util.tree_leaves(x))


def describe(value: Any) -> str:
    """A short description of a value for error messages: its type, and its repr when short.

    Parameters
    ----------
    value : object

    Returns
    -------
    str
        ``"<type> <repr>"``; past 60 characters of repr, the type and its shape (or the type alone).
    """
    text = repr(value)
    if len(text) > 60:
        shape = getattr(value, "shape", None)
        return f"{type(value).__name__} of shape {tuple(shape)}" if shape is not None else type(value).__name__
    return f"{type(value).__name__} {text}"


def _interval(lo, hi, lo_open, hi_open) -> str:
    left = "(" if lo_open else "["
    right = ")" if hi_open else "]"
    lo_s = "-inf" if lo is None else repr(lo)
    hi_s = "inf" if hi is None else repr(hi)
    return f"{left}{lo_s}, {hi_s}{right}"


def _check_range(name, vmin, vmax, lo, hi, lo_open, hi_open, shown):
    bad = False
    if lo is not None:
        bad |= vmin <= lo if lo_open else vmin < lo
    if hi is not None:
        bad |= vmax >= hi if hi_open else vmax > hi
    if bad:
        raise ValueError(f"{name} must lie in {_interval(lo, hi, lo_open, hi_open)}, got {shown}")


def _real_kind(name: str, value: Any, what: str = "a real number") -> None:
    """TypeError unless ``value`` is a real number or an array of them (not bool, str, None)."""
    if isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be {what}, got bool {value!r}")
    if isinstance(value, (str, bytes)) or value is None:
        raise TypeError(f"{name} must be {what}, got {describe(value)}")
    if isinstance(value, numbers.Number):
        if isinstance(value, numbers.Complex) and not isinstance(value, numbers.Real):
            raise TypeError(f"{name} must be {what}, got complex {value!r}")
        return
    if not hasattr(value, "dtype") and not isinstance(value, (list, tuple)):
        raise TypeError(f"{name} must be {what}, got {describe(value)}")


def check_scalar(name: str, value: Any, *, lo: float | None = None, hi: float | None = None,
                 lo_open: bool = False, hi_open: bool = False, allow_inf: bool = False) -> Any:
    """Check a real scalar parameter; return it unchanged.

    ``TypeError`` if ``value`` is not a real number (a string, ``None``, a bool, complex);
    ``ValueError`` if it is not a scalar, is NaN, is infinite (unless ``allow_inf``) or
    lies outside the interval given by ``lo``/``hi`` (closed unless ``lo_open``/``hi_open``).
    Tracers pass unchecked (their shape must still be a scalar).

    Parameters
    ----------
    name : str
        The parameter's name, in the messages.
    value : object
        What the caller passed.
    lo, hi : float, optional, keyword-only
        Bounds of the allowed interval, in the parameter's own unit (None: unbounded).
    lo_open, hi_open : bool, optional, keyword-only
        Exclude the bound itself.
    allow_inf : bool, optional, keyword-only
        Accept ±inf (within the bounds).

    Returns
    -------
    object
        ``value``, unchanged.
    """
    if is_traced(value):
        if np.ndim(value) != 0:
            raise ValueError(f"{name} must be a scalar, got shape {np.shape(value)}")
        return value
    _real_kind(name, value)
    arr = np.asarray(value)
    if not (np.issubdtype(arr.dtype, np.integer) or np.issubdtype(arr.dtype, np.floating)):
        raise TypeError(f"{name} must be a real number, got dtype {arr.dtype}")
    if arr.ndim != 0:
        raise ValueError(f"{name} must be a scalar, got shape {arr.shape}")
    v = float(arr)
    if math.isnan(v) or (math.isinf(v) and not allow_inf):
        raise ValueError(f"{name} must be finite, got {v!r}")
    _check_range(name, v, v, lo, hi, lo_open, hi_open, repr(v))
    return value


def check_array(name: str, value: Any, *, lo: float | None = None, hi: float | None = None,
                lo_open: bool = False, hi_open: bool = False, allow_inf: bool = False,
                complex_ok: bool = False, min_ndim: int = 0, ndim: int | None = None,
                shape_tail: tuple[int, ...] | None = None) -> Any:
    """Check an array argument (kind, shape and values); return it unchanged.

    ``TypeError`` for a non-numeric array (strings, objects, bools, ``None``) or complex
    values where real ones are needed; ``ValueError`` for the wrong number of dimensions,
    trailing shape ``shape_tail`` (e.g. ``(n, n)`` for a field on an ``n``-point grid),
    an empty array, NaN/inf, or values outside ``lo``/``hi``. Shapes are checked even
    under ``jit``; values only when concrete (large device arrays are summarized on the
    device, not copied).

    Parameters
    ----------
    name : str
        The parameter's name, in the messages.
    value : object
        What the caller passed.
    lo, hi, lo_open, hi_open, allow_inf : optional, keyword-only
        The values' allowed interval, as :func:`check_scalar`'s.
    complex_ok : bool, optional, keyword-only
        Accept complex values.
    min_ndim : int, optional, keyword-only
        Fewest dimensions.
    ndim : int, optional, keyword-only
        Exact number of dimensions.
    shape_tail : tuple of int, optional, keyword-only
        The trailing shape required.

    Returns
    -------
    object
        ``value``, unchanged.
    """
    _real_kind(name, value, "an array of numbers")
    shape = np.shape(value)
    if len(shape) < min_ndim:
        raise ValueError(f"{name} must have at least {min_ndim} dimensions, got shape {shape}")
    if ndim is not None and len(shape) != ndim:
        raise ValueError(f"{name} must have {ndim} dimensions, got shape {shape}")
    if shape_tail is not None and (len(shape) < len(shape_tail)
                                   or tuple(shape[len(shape) - len(shape_tail):]) != tuple(shape_tail)):
        raise ValueError(f"{name} must have trailing shape {tuple(shape_tail)}, got shape {shape}")
    if is_traced(value):
        return value
    if isinstance(value, jax.Array) and value.size > 4096 and not _host_checkable(value):
        _check_device_array(name, value, lo, hi, lo_open, hi_open, allow_inf, complex_ok)
        return value
    arr = np.asarray(value)
    _check_dtype(name, arr.dtype, complex_ok)
    if arr.size == 0:
        raise ValueError(f"{name} must not be empty, got shape {shape}")
    if not np.isfinite(arr).all() and (np.isnan(arr).any() or not allow_inf):
        bad = int((~np.isfinite(arr)).sum())
        raise ValueError(f"{name} must be finite everywhere; it contains NaN or inf ({bad} of {arr.size} values)")
    if lo is not None or hi is not None:
        vmin, vmax = arr.real.min().item(), arr.real.max().item()  # Python numbers: plain in the message
        _check_range(name, vmin, vmax, lo, hi, lo_open, hi_open, f"values in [{vmin!r}, {vmax!r}]")
    return value


def _check_dtype(name, dtype, complex_ok):
    if dtype == np.bool_ or not np.issubdtype(dtype, np.number):
        raise TypeError(f"{name} must be numeric, got dtype {dtype}")
    if np.issubdtype(dtype, np.complexfloating) and not complex_ok:
        raise TypeError(f"{name} must be real, got complex values (dtype {dtype})")


def _host_checkable(value) -> bool:
    """True for a JAX array held by the CPU and small enough (2^18 values) that NumPy checks it in
    well under a millisecond, cheaper than compiling the device summary for its shape (~0.1 s)."""
    try:
        return value.size <= 1 << 18 and value.is_fully_addressable and all(
            d.platform == "cpu" for d in value.devices())
    except Exception:  # a deleted or otherwise unreadable array: the device path reports it
        return False


@jax.jit
def _summary(x):
    """(all finite, any NaN, min, max) of the real part, in one pass on the device."""
    r = jax.numpy.real(x)
    return jax.numpy.isfinite(x).all(), jax.numpy.isnan(x).any(), r.min(), r.max()


def _check_device_array(name, value, lo, hi, lo_open, hi_open, allow_inf, complex_ok):
    """Value checks of a large JAX array without copying it to the host."""
    _check_dtype(name, np.dtype(value.dtype), complex_ok)
    with jax.ensure_compile_time_eval():  # a concrete array closed over by a user's jit stays concrete
        finite, has_nan, vmin, vmax = (v.item() for v in jax.device_get(_summary(value)))
    if not finite and (has_nan or not allow_inf):
        raise ValueError(f"{name} must be finite everywhere; it contains NaN or inf")
    if lo is not None or hi is not None:
        _check_range(name, vmin, vmax, lo, hi, lo_open, hi_open, f"values in [{vmin!r}, {vmax!r}]")


def check_int(name: str, value: Any, *, lo: int | None = None, hi: int | None = None,
              even: bool = False) -> int:
    """Check an integer parameter (a Python or numpy integer, not a bool); return it as int.

    Parameters
    ----------
    name : str
        The parameter's name, in the messages.
    value : object
        What the caller passed.
    lo, hi : int, optional, keyword-only
        Inclusive bounds.
    even : bool, optional, keyword-only
        Require an even number.

    Returns
    -------
    int
    """
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise TypeError(f"{name} must be an integer, got {describe(value)}")
    v = int(value)
    _check_range(name, v, v, lo, hi, False, False, repr(v))
    if even and v % 2:
        raise ValueError(f"{name} must be even, got {v}")
    return v


def check_bool(name: str, value: Any) -> bool:
    """Check a switch (a Python or numpy bool); return it as bool.

    Parameters
    ----------
    name : str
        The parameter's name, in the messages.
    value : object
        What the caller passed.

    Returns
    -------
    bool
    """
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False, got {describe(value)}")
    return bool(value)


def check_float_dtype(name: str, dtype: Any):
    """A float32 or float64 dtype (TypeError for what is not a dtype, ValueError for another one); returns it."""
    if dtype is None:
        raise TypeError(f"{name} must be float32 or float64, got None")
    try:
        kind = np.dtype(dtype)
    except TypeError:
        raise TypeError(f"{name} must be float32 or float64, got {describe(dtype)}") from None
    if kind not in (np.dtype(np.float32), np.dtype(np.float64)):
        raise ValueError(f"{name} must be float32 or float64, got {dtype}")
    return kind


def check_state_dtype(name: str, dtype: Any):
    """:func:`check_float_dtype`, and a ValueError for float64 while JAX is not set to keep it (arrays made
    with it would silently be float32); returns the dtype."""
    kind = check_float_dtype(name, dtype)
    if kind == np.dtype(np.float64) and not jax.config.jax_enable_x64:
        raise ValueError(f"{name} float64 needs jax_enable_x64: call jax.config.update('jax_enable_x64', True) "
                         f"(or work inside jax.enable_x64(True)) before making the state")
    return kind


def check_choice(name: str, value: Any, choices) -> Any:
    """Check that ``value`` is one of ``choices`` (TypeError for another kind of object).

    Parameters
    ----------
    name : str
        The parameter's name, in the messages.
    value : object
        What the caller passed.
    choices : iterable
        The allowed values (ValueError listing them otherwise).

    Returns
    -------
    object
        ``value``, unchanged.
    """
    kinds = {type(c) for c in choices}
    if kinds == {str} and not isinstance(value, str):
        raise TypeError(f"{name} must be one of {sorted(choices)}, got {describe(value)}")
    try:
        ok = value in choices
    except TypeError:  # unhashable
        ok = False
    if not ok:
        raise ValueError(f"{name} must be one of {sorted(map(str, choices))}, got {value!r}")
    return value


def check_key(name: str, value: Any) -> Any:
    """A ``jax.random`` key: ``jax.random.key(seed)`` or the legacy ``PRNGKey(seed)`` (uint32, shape (2,))."""
    dtype = getattr(value, "dtype", None)
    if dtype is not None and jax.dtypes.issubdtype(dtype, jax.dtypes.prng_key):
        return value
    if dtype is None or np.dtype(dtype) != np.uint32 or np.shape(value) != (2,):
        raise TypeError(f"{name} must be a jax.random key (jax.random.key(seed) or jax.random.PRNGKey(seed)), "
                        f"got {describe(value)}")
    return value


def check_instance(name: str, value: Any, cls, what: str | None = None) -> Any:
    """TypeError naming the expected class unless ``value`` is an instance of ``cls``.

    Parameters
    ----------
    name : str
        The parameter's name, in the messages.
    value : object
        What the caller passed.
    cls : type or tuple of type
        The accepted class(es).
    what : str, optional
        How the message names them (default: ``package.Class``).

    Returns
    -------
    object
        ``value``, unchanged.
    """
    if not isinstance(value, cls):
        label = what or (cls.__module__.split(".")[0] + "." + cls.__name__ if isinstance(cls, type)
                         else " or ".join(c.__name__ for c in cls))
        raise TypeError(f"{name} must be a {label}, got {describe(value)}")
    return value


# -- declarative checks ---------------------------------------------------------------------
class Spec:
    """A check of one argument: ``spec(name, value, arguments) -> value`` (possibly normalized)."""

    def __call__(self, name, value, arguments):
        raise NotImplementedError


class Real(Spec):
    """A real number in a range (:func:`check_scalar`)."""

    def __init__(self, lo=None, hi=None, lo_open=False, hi_open=False, allow_inf=False):
        self.kw = dict(lo=lo, hi=hi, lo_open=lo_open, hi_open=hi_open, allow_inf=allow_inf)

    def __call__(self, name, value, arguments):
        return check_scalar(name, value, **self.kw)


class Int(Spec):
    """An integer in a range (:func:`check_int`)."""

    def __init__(self, lo=None, hi=None, even=False):
        self.kw = dict(lo=lo, hi=hi, even=even)

    def __call__(self, name, value, arguments):
        return check_int(name, value, **self.kw)


class Bool(Spec):
    """A switch (:func:`check_bool`)."""

    def __call__(self, name, value, arguments):
        return check_bool(name, value)


class Choice(Spec):
    """One of a list of names (:func:`check_choice`)."""

    def __init__(self, choices):
        self.choices = tuple(choices)

    def __call__(self, name, value, arguments):
        return check_choice(name, value, self.choices)


class Instance(Spec):
    """An object of a class (:func:`check_instance`); ``cls`` may be a zero-argument callable
    returning the class, to avoid import cycles."""

    def __init__(self, cls, what=None):
        self.cls, self.what = cls, what

    def __call__(self, name, value, arguments):
        cls = self.cls if isinstance(self.cls, (type, tuple)) else self.cls()
        return check_instance(name, value, cls, self.what)


class Array(Spec):
    """An array of numbers (:func:`check_array`); ``shape`` is a trailing shape, or a callable
    of the other (already checked) arguments returning one."""

    def __init__(self, shape=None, **kw):
        self.shape, self.kw = shape, kw

    def __call__(self, name, value, arguments):
        tail = self.shape(arguments) if callable(self.shape) else self.shape
        return check_array(name, value, shape_tail=tail, **self.kw)


def field_of(grid_argument: str = "grid", **kw) -> Array:
    """A field on the grid passed as ``grid_argument``: trailing shape (n, n), finite."""
    return Array(shape=lambda a: (a[grid_argument].n, a[grid_argument].n), min_ndim=2, **kw)


class Vector(Array):
    """A 1-D array of ``size`` numbers (a direction, a point)."""

    def __init__(self, size, **kw):
        super().__init__(shape=(size,), ndim=1, **kw)


class Maybe(Spec):
    """None, or a value that passes ``spec``."""

    def __init__(self, spec):
        self.spec = spec

    def __call__(self, name, value, arguments):
        return None if value is None else self.spec(name, value, arguments)


class Function(Spec):
    """A callable."""

    def __call__(self, name, value, arguments):
        if not callable(value):
            raise TypeError(f"{name} must be a function, got {describe(value)}")
        return value


class Text(Spec):
    """A string (a title, a label, a name); ``empty`` allows ""."""

    def __init__(self, empty=True):
        self.empty = empty

    def __call__(self, name, value, arguments):
        if not isinstance(value, str):
            raise TypeError(f"{name} must be a string, got {describe(value)}")
        if not self.empty and not value.strip():
            raise ValueError(f"{name} must not be empty")
        return value


class Items(Spec):
    """A list or tuple (or any iterable but a string, with ``iterable``), each item passing
    ``item`` (named ``name[i]``); at least ``min_len`` items. Iterables are turned into lists."""

    def __init__(self, item=None, min_len=0, iterable=False, length=None):
        self.item, self.min_len, self.iterable, self.length = item, min_len, iterable, length

    def __call__(self, name, value, arguments):
        ok = isinstance(value, (list, tuple)) or (self.iterable and hasattr(value, "__iter__")
                                                   and not isinstance(value, (str, bytes, dict)))
        if not ok:
            raise TypeError(f"{name} must be a list or tuple, got {describe(value)}")
        items = list(value) if not isinstance(value, (list, tuple)) else value
        if len(items) < self.min_len:
            raise ValueError(f"{name} must hold at least {self.min_len} item(s), got {len(items)}")
        if self.length is not None and len(items) != self.length:
            raise ValueError(f"{name} must hold {self.length} items, got {len(items)}")
        if self.item is not None:
            for i, v in enumerate(items):
                self.item(f"{name}[{i}]", v, arguments)
        return items if not isinstance(value, (list, tuple)) else value


class Mapping(Spec):
    """A dict whose keys are strings and whose values pass ``value``."""

    def __init__(self, value=None):
        self.value = value

    def __call__(self, name, value, arguments):
        if not isinstance(value, dict):
            raise TypeError(f"{name} must be a dict, got {describe(value)}")
        for key, v in value.items():
            if not isinstance(key, str):
                raise TypeError(f"{name} keys must be strings, got {describe(key)}")
            if self.value is not None:
                self.value(f"{name}[{key!r}]", v, arguments)
        return value


class FilePath(Spec):
    """A file system path (str or os.PathLike, not empty)."""

    def __call__(self, name, value, arguments):
        import os

        if not isinstance(value, (str, os.PathLike)) or (isinstance(value, str) and not value.strip()):
            raise TypeError(f"{name} must be a file system path (str or pathlib.Path), got {describe(value)}")
        return value


def validate(**specs):
    """Decorator: check the named arguments at the boundary, in the order given, before the call.

    Each spec is a :class:`Spec` (``Real(lo=0, lo_open=True)``, ``Instance(Grid)``,
    ``field_of("grid")``, …). Missing arguments raise Python's own TypeError naming them.
    Checks on traced values (inside ``jit``) look at kinds and shapes only.
    """
    import functools
    import inspect

    def decorate(fn):
        sig = inspect.signature(fn)
        unknown = set(specs) - set(sig.parameters)
        if unknown:
            raise TypeError(f"validate: {fn.__qualname__} has no parameter(s) {sorted(unknown)}")

        @functools.wraps(fn)
        def wrapper(*args, **kwargs):
            bound = sig.bind(*args, **kwargs)
            bound.apply_defaults()
            arguments = bound.arguments
            for name, spec in specs.items():
                arguments[name] = spec(name, arguments[name], arguments)
            return fn(*bound.args, **bound.kwargs)

        wrapper.__signature__ = sig
        return wrapper

    return decorate
