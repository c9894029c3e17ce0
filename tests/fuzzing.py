"""The fuzz harness behind ``tests/test_fuzz.py``: discover the public API, build valid calls,
and classify what each bad input does.

Discovery walks every module of ``wavephys`` and ``optics`` and takes the callables named in
its ``__all__`` (modules that declare ``__internal__ = True`` are the library's own
tooling and are skipped); classes contribute their constructor and their public methods.
A valid call is built from :mod:`fuzz_examples` (valid values by parameter name, with
overrides per callable), so a new public function is covered as soon as its parameters
have names the table knows — and ``test_every_public_callable_has_a_valid_call`` fails
until they do.

For one parameter at a time, a bad value replaces the valid one; the outcome is one of:

``named``     TypeError or ValueError whose message names the parameter (what we want);
``unnamed``   TypeError or ValueError that does not name it;
``crash``     any other exception (from numpy, JAX, XLA, ZeroDivisionError, …);
``hang``      no answer within the time limit;
``nan``       returned, but the result holds NaN or inf (a silent failure);
``accepted``  returned a finite result (a failure for values no parameter accepts —
              ``None`` where None is not the default, strings, NaN, empty or misshaped
              arrays — and for negative or zero values of parameters that must be positive).
"""

from __future__ import annotations

import dataclasses
import importlib
import inspect
import math
import os
import pkgutil
import signal
from dataclasses import dataclass
from typing import Any, Callable

import numpy as np

import fuzz_examples as ex

TIME_LIMIT = 30  # seconds per call


@dataclass(frozen=True)
class Target:
    name: str                 # qualified name, e.g. "wavephys.physics.dispersion.angular_frequency"
    make: Callable            # () -> the callable (a function, a class, or a bound method)
    params: tuple             # inspect.Parameter objects that can be fuzzed


def _walk():
    import optics
    import wavephys

    for pkg in (wavephys, optics):
        yield pkg.__name__
        for info in pkgutil.walk_packages(pkg.__path__, pkg.__name__ + "."):
            if not info.name.endswith("__main__"):
                yield info.name


def _fuzzable(sig: inspect.Signature):
    return tuple(p for p in sig.parameters.values()
                 if p.kind not in (p.VAR_POSITIONAL, p.VAR_KEYWORD) and p.name != "self")


def discover() -> list[Target]:
    """Every public callable and public method, once (re-exports are the same object)."""
    seen, targets = set(), []
    for modname in _walk():
        mod = importlib.import_module(modname)
        if getattr(mod, "__internal__", False):
            continue
        for attr in getattr(mod, "__all__", []):
            obj = getattr(mod, attr)
            if not callable(obj) or id(obj) in seen or isinstance(obj, dict) or hasattr(obj, "__getitem__"):
                continue
            seen.add(id(obj))
            name = f"{obj.__module__}.{obj.__qualname__}" if hasattr(obj, "__qualname__") else f"{modname}.{attr}"
            if name in ex.SKIP:
                continue
            if inspect.isclass(obj):
                if issubclass(obj, BaseException):
                    continue
                targets += _class_targets(obj, name)
            else:
                params = _fuzzable(inspect.signature(obj))
                if params:
                    targets.append(Target(name, (lambda o=obj: o), params))
    return targets


def _class_targets(cls, name):
    out = []
    try:
        params = _fuzzable(inspect.signature(cls))
    except (TypeError, ValueError):
        params = ()
    if params and name not in ex.SKIP:
        out.append(Target(name, (lambda c=cls: c), params))
    for meth, fn in inspect.getmembers(cls, inspect.isfunction):
        qual = f"{name}.{meth}"
        if meth.startswith("_") or qual in ex.SKIP:
            continue
        params = _fuzzable(inspect.signature(fn))
        if params:
            out.append(Target(qual, (lambda c=cls, m=meth: getattr(ex.instance(c), m)), params))
    return out


# -- valid calls ------------------------------------------------------------------------
def example_of(target: Target, param: inspect.Parameter):
    """The valid value of ``param`` in a call (for an optional parameter: the table's, else its default)."""
    kwargs = valid_kwargs(target)
    if param.name in kwargs:
        return kwargs[param.name]
    if param.default is None and param.name in ex.EXAMPLES:
        return ex.EXAMPLES[param.name]()
    return param.default


def valid_kwargs(target: Target) -> dict:
    """Valid values for the required parameters (and overridden optional ones)."""
    over = ex.OVERRIDES.get(target.name, {})
    kwargs = {name: make() for name, make in over.items()}  # may name **options too
    for p in target.params:
        if p.name in kwargs:
            continue
        if p.default is inspect.Parameter.empty:
            if p.name not in ex.EXAMPLES:
                raise KeyError(f"{target.name}: no valid example for parameter {p.name!r}")
            kwargs[p.name] = ex.EXAMPLES[p.name]()
    return kwargs


def call(target: Target, kwargs: dict):
    fn = target.make()
    positional = [p for p in target.params if p.kind == p.POSITIONAL_ONLY]
    args = [kwargs.pop(p.name) for p in positional if p.name in kwargs]
    return fn(*args, **kwargs)


# -- bad values ---------------------------------------------------------------------------
class _Alien:
    """An object of no kind any parameter accepts."""

    def __repr__(self):
        return "<alien>"


UNIVERSAL = "universal"  # must be refused by every parameter
RANGE = "range"          # must be refused by positive (non-negative) parameters


def bad_values(target: Target, param: inspect.Parameter, example) -> list[tuple[Any, str]]:
    """(value, category) pairs that are wrong for ``param`` whose valid value is ``example``."""
    out = [(_Alien(), UNIVERSAL)]
    if param.default is not None and param.name not in ex.NONE_OK:
        out.append((None, UNIVERSAL))
    name = param.name
    ranged = (target.name, name) not in ex.RANGE_FREE
    if isinstance(example, (bool, np.bool_)):
        return out + [("yes", UNIVERSAL), (2, UNIVERSAL)]
    if isinstance(example, str):
        return out + [(3, UNIVERSAL)] + ([("no-such-choice", UNIVERSAL)] if name in ex.CHOICES and (target.name, name) not in ex.FREE_TEXT else [])
    if isinstance(example, (int, np.integer)):
        out += [(2.5, UNIVERSAL), ("3", UNIVERSAL), (True, UNIVERSAL)]
        if ranged and name in ex.POSITIVE:
            out += [(0, RANGE), (-1, RANGE)]
        elif ranged and name in ex.NON_NEGATIVE:
            out += [(-1, RANGE)]
        return out
    if isinstance(example, (float, np.floating)) or (hasattr(example, "shape") and np.ndim(example) == 0
                                                     and np.issubdtype(np.asarray(example).dtype, np.floating)):
        out += [("x", UNIVERSAL), (True, UNIVERSAL), (1j, UNIVERSAL), (1e30, "huge")]
        if name not in ex.NAN_OK:
            out.append((math.nan, UNIVERSAL))
        if name not in ex.INF_OK:
            out += [(math.inf, UNIVERSAL), (-math.inf, UNIVERSAL)]
        if ranged and name in ex.POSITIVE:
            out += [(0.0, RANGE), (-1.0, RANGE)]
        elif ranged and name in ex.NON_NEGATIVE:
            out += [(-1.0, RANGE)]
        return out
    if isinstance(example, (np.ndarray, tuple, list)) or _is_jax_array(example):
        arr = np.asarray(example)
        if arr.dtype == object or arr.size == 0:
            return out
        if np.issubdtype(arr.dtype, np.number):
            nan = arr.astype(np.complex128 if np.iscomplexobj(arr) else np.float64).copy()
            nan.flat[nan.size // 2] = np.nan
            out += [("x", UNIVERSAL), (nan, UNIVERSAL), (np.zeros((0,) * max(arr.ndim, 1)), UNIVERSAL),
                    (np.full(arr.shape, "a"), UNIVERSAL)]
            if name in ex.SHAPED and (target.name, name) not in ex.SHAPE_FREE:  # a shape is part of the contract
                out.append((arr[..., None] if arr.ndim else arr[None], UNIVERSAL))
                if arr.ndim >= 1:
                    out.append((np.resize(arr, arr.shape[:-1] + (arr.shape[-1] + 1,)), UNIVERSAL))
            if ranged and name in ex.NON_NEGATIVE:  # arrays of non-negative quantities (k, ω, distances, …)
                out.append((-np.abs(arr.astype(float)) - 1.0, RANGE))
        return out
    if isinstance(example, os.PathLike):  # a file or folder: any string names one, so only kinds are wrong
        return out + [(3, UNIVERSAL), ("", UNIVERSAL)]
    if inspect.isfunction(example) or inspect.ismethod(example):
        return out + [(3, UNIVERSAL), ("x", UNIVERSAL)]
    # an object of a library class (Grid, Water, Scene, …)
    return out + [("x", UNIVERSAL), (3.0, UNIVERSAL)]


def _is_jax_array(x):
    import jax

    return isinstance(x, jax.Array)


def short(value) -> str:
    """A one-line description of a bad value for reports (arrays by shape and dtype)."""
    if hasattr(value, "shape") and np.ndim(value) > 0:
        return f"array{tuple(np.shape(value))} {np.asarray(value).dtype}"
    return repr(value)


# -- outcomes ---------------------------------------------------------------------------
def _nonfinite(obj, depth=0) -> tuple[bool, bool]:
    """(holds NaN, holds ±inf) anywhere in a result (arrays, numbers, tuples, dataclasses)."""
    if depth > 6 or obj is None or isinstance(obj, (str, bytes, bool, np.bool_)):
        return False, False
    if isinstance(obj, (int, float, complex, np.number)) or _is_jax_array(obj) or isinstance(obj, np.ndarray):
        arr = np.asarray(obj)
        if not np.issubdtype(arr.dtype, np.inexact):
            return False, False
        return bool(np.isnan(arr).any()), bool(np.isinf(arr).any())
    if isinstance(obj, dict):
        obj = list(obj.values())
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        obj = [getattr(obj, f.name) for f in dataclasses.fields(obj)]
    if isinstance(obj, (tuple, list)):
        parts = [_nonfinite(o, depth + 1) for o in obj]
        return any(p[0] for p in parts), any(p[1] for p in parts)
    return False, False


_BASELINE: dict = {}


def _baseline_inf(target: Target) -> bool:
    """Whether the valid call's own result holds inf (e.g. a Water of infinite depth): then
    inf in a bad call's result is not a new failure, NaN still is."""
    if target.name not in _BASELINE:
        try:
            _BASELINE[target.name] = _nonfinite(call(target, valid_kwargs(target)))[1]
        except Exception:  # noqa: BLE001 - reported by test_every_public_callable_has_a_valid_call
            _BASELINE[target.name] = False
    return _BASELINE[target.name]


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout()


def classify(target: Target, param: str, value, category: str) -> tuple[str, str]:
    """(outcome, detail) of calling ``target`` with ``param`` = ``value`` and valid others."""
    kwargs = valid_kwargs(target)
    kwargs[param] = value
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(TIME_LIMIT)
    try:
        result = call(target, kwargs)
    except _Timeout:
        return "hang", f"no answer in {TIME_LIMIT} s"
    except (TypeError, ValueError) as exc:
        msg = str(exc)
        return ("named" if param in msg else "unnamed"), f"{type(exc).__name__}: {msg[:200]}"
    except AssertionError as exc:
        # the pytest plugin's job is to fail a test with expected against measured: for a huge
        # but valid value (data that do not match the physics) that is the right answer
        if ".pytest_plugin.Checker." in target.name and category == "huge":
            return "fine", f"asserted: {str(exc)[:120]}"
        return "crash", f"AssertionError: {str(exc)[:200]}"
    except Exception as exc:  # noqa: BLE001 - the point is to catch anything
        return "crash", f"{type(exc).__name__}: {str(exc)[:200]}"
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    has_nan, has_inf = _nonfinite(result)
    if category == "huge" and target.name in ex.NAN_RESULT_OK:
        return "fine", "NaN by design (documented)"
    if has_nan or (has_inf and not _baseline_inf(target)):
        return "nan", "the result holds NaN" if has_nan else "the result holds inf"
    if category in (UNIVERSAL, RANGE):  # RANGE values are only made for parameters that must refuse them
        return "accepted", f"returned {type(result).__name__}"
    return "fine", "a huge but finite value, handled finitely"


FAILURES = ("unnamed", "crash", "hang", "nan", "accepted")
