"""Explaining a shader function's output by fits: the forms a correct function may compute, and known mistakes.

A check does not compare a user's function with one library value. It holds *models* of what
the function may compute: the correct forms, each with the constants the physics allows left
free (water's index over the visible spectrum, 0–30 °C, fresh or sea, air as 1 or 1.000293),
and the mistakes real code makes, each with its own free constants. :func:`fit` finds a model's
constants from the function's output (the worst error over the inputs, minimized), so:

* the verdict is the best correct model fitted within the physical ranges: a function passes
  when some water the physics allows explains its output to within the tolerance;
* a cause is a model that explains the output when the correct ones do not: the fitted
  constants are part of the cause ("Schlick with F0 = 0.0400: the f0 of an index 1.50, not
  water's 0.0200–0.0224"), each from a fit, not a guess;
* :func:`explain` tries every model on the whole domain, then on each group of inputs (a side of
  the surface, a colour channel) alone, so a fault on one side, and a fault with a wrong
  constant, are both named.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable, Optional

import numpy as np

__internal__ = True  # the runner's pieces: users call optics.shaders.check_glsl
__all__ = ["Param", "Model", "Fit", "fit", "explain", "explain_rows", "best_correct", "errors_against"]


@dataclass(frozen=True)
class Param:
    """A model's free constant.

    Attributes
    ----------
    name : str
        Its name ("m", "f0", "p", "scale").
    wide : (float, float)
        The range searched when explaining an output.
    physical : (float, float) or None
        The range a correct function may hold (None: any value within ``wide`` is correct).
    log : bool
        Search in log space (positive ranges over decades).
    show : callable, optional
        value → words for a report ("F0 = 0.0200 (m = 1.330)"); default ``name = value``.
    physics : str
        The physical range in words, with where it comes from (for a cause).
    """

    name: str
    wide: tuple
    physical: Optional[tuple] = None
    log: bool = False
    show: Optional[Callable] = None
    physics: str = ""
    outside: Optional[Callable] = None

    def words(self, value: float) -> str:
        """The value in words."""
        return self.show(value) if self.show else f"{self.name} = {value:.4g}"

    def outside_words(self, value: float) -> str:
        """Why ``value`` is not physical, in words."""
        if self.outside is not None:
            return self.outside(value)
        return f"{self.words(value)}, outside {self.physics or 'its physical range'}"

    def is_physical(self, value: float) -> bool:
        """Whether a correct function may hold ``value``."""
        return self.physical is None or self.physical[0] * (1 - 1e-9) <= value <= self.physical[1] * (1 + 1e-9)


@dataclass(frozen=True)
class Model:
    """One thing a function may compute.

    Attributes
    ----------
    name : str
        Short name ("schlick", "no TIR from below").
    answer : callable
        ``answer(values)`` → (n, c) expected outputs over the domain for the constants ``values``
        (a tuple, one per ``params``); or a tuple of such arrays, any of which a row may match (NaN rows
        of an alternative are ignored).
    params : tuple of Param
        The free constants.
    correct : bool
        A form a correct function may compute (with its constants in their physical ranges).
    cause : str or callable
        For a mistake: the cause in words; a callable gets the fitted values.
    """

    name: str
    answer: Callable
    params: tuple = ()
    correct: bool = False
    cause: object = ""

    def text(self, values: tuple) -> str:
        """The cause for the fitted ``values``, with any constant outside its physical range named too."""
        odd = "; ".join(p.outside_words(v) for p, v in zip(self.params, values) if not p.is_physical(v))
        if self.correct:
            return f"{odd} (it computes {self.name} with that constant)"
        base = self.cause(values) if callable(self.cause) else str(self.cause)
        return f"{base}; and {odd}" if odd else base


@dataclass(frozen=True)
class Fit:
    """A model fitted to a function's output over some of its inputs.

    Attributes
    ----------
    model : Model
    values : tuple of float
        The fitted constants.
    error : float
        The worst error over the rows fitted (inf when the model gives NaN where the function does not).
    rows : numpy.ndarray of bool
        The rows fitted.
    errors : numpy.ndarray
        The error of every row of the domain under the fitted constants.
    """

    model: Model
    values: tuple
    error: float
    rows: np.ndarray = field(repr=False)
    errors: np.ndarray = field(repr=False)

    @property
    def physical(self) -> bool:
        """Whether every fitted constant lies in its physical range."""
        return all(p.is_physical(v) for p, v in zip(self.model.params, self.values))

    def constants(self) -> str:
        """The fitted constants in words ("" when the model has none)."""
        return ", ".join(p.words(v) for p, v in zip(self.model.params, self.values))


def errors_against(values: np.ndarray, answer, error: Callable) -> np.ndarray:
    """(n,) errors of ``values`` against an answer (an array, or a tuple of alternatives: the smallest).

    Parameters
    ----------
    values : numpy.ndarray (n, c)
        The function's outputs.
    answer : numpy.ndarray or tuple of numpy.ndarray
        The answer, or alternatives.
    error : Callable
        ``error(values, answer) -> (n,)``.

    Returns
    -------
    numpy.ndarray (n,)
    """
    options = answer if isinstance(answer, tuple) else (answer,)
    best = None
    if callable(answer):
        raise TypeError("errors_against takes the answer's values, not the model")
    for a in options:
        a = np.asarray(a, np.float64)
        with np.errstate(invalid="ignore"):
            e = error(values, a[:, :values.shape[1]] if a.shape[1] >= values.shape[1] else
                      np.broadcast_to(a, values.shape))
        e = np.where(np.isfinite(e), e, np.inf)
        if len(options) > 1:
            e = np.where(np.isnan(a).any(axis=1), np.inf, e)
        best = e if best is None else np.minimum(best, e)
    return best


def _objective(model, values, error, rows, kind="max"):
    def score(x):
        with np.errstate(all="ignore"):
            answer = model.answer(tuple(float(v) for v in x))
        e = errors_against(values, answer, error)[rows]
        if not e.size:
            return 0.0
        if kind == "max":
            return float(e.max())
        return float(np.mean(np.minimum(e, 1e3)))  # a row flipping branch (TIR) moves the mean a little
    return score


def _grid(lo, hi, log, points):
    return np.geomspace(lo, hi, points) if log else np.linspace(lo, hi, points)


def _search_1d(score, lo, hi, log, points=33, xatol=1e-9):
    from scipy.optimize import minimize_scalar

    grid = _grid(lo, hi, log, points if hi > lo else 1)
    scores = [score((g,)) for g in grid]
    i = int(np.argmin(scores))
    best, best_score = float(grid[i]), scores[i]
    a, b = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    if b > a:
        u = (math.log(a), math.log(b)) if log else (a, b)
        found = minimize_scalar(lambda t: score((math.exp(t) if log else t,)), bounds=u, method="bounded",
                                options=dict(xatol=xatol * max(1.0, abs(u[1]))))
        if found.fun <= best_score:
            best = float(math.exp(found.x) if log else found.x)
    return best


def fit(model: Model, values: np.ndarray, error: Callable, rows: np.ndarray, *, physical: bool = False) -> Fit:
    """The model's constants that minimize the worst error over ``rows``.

    The constants are found on the mean error (smooth where a row changes branch, a ray crossing the critical
    angle), then polished on the worst error near that.

    Parameters
    ----------
    model : Model
    values : numpy.ndarray (n, c)
        The function's output, float64.
    error : callable
        ``error(values, expected)`` → (n,) per-row errors.
    rows : numpy.ndarray (n,) of bool
        The rows that count.
    physical : bool, optional, keyword-only
        Search each constant within its physical range (the verdict) instead of its wide one (a cause).

    Returns
    -------
    Fit
    """
    from scipy.optimize import minimize

    bounds = [(p.physical if physical and p.physical is not None else p.wide) for p in model.params]
    worst = _objective(model, values, error, rows, "max")
    mean = _objective(model, values, error, rows, "mean")
    if not bounds:
        best = ()
    elif len(bounds) == 1:
        (lo, hi), log = bounds[0], model.params[0].log
        x = _search_1d(mean, lo, hi, log, points=25, xatol=1e-5)
        span = 1e-3 * (abs(x) if log or x else (hi - lo))
        near = (max(lo, x - span), min(hi, x + span)) if not log else (max(lo, x * (1 - 1e-3)), min(hi, x * (1 + 1e-3)))
        polished = _search_1d(worst, *near, log, points=7)
        best = (polished if worst((polished,)) <= worst((x,)) else x,)
    else:
        grids = [_grid(lo, hi, p.log, 9 if len(bounds) == 2 else 6) for (lo, hi), p in zip(bounds, model.params)]
        mesh = np.stack(np.meshgrid(*grids, indexing="ij"), -1).reshape(-1, len(bounds))
        start = min(mesh, key=lambda x: mean(x))
        lo = np.array([b[0] for b in bounds])
        hi = np.array([b[1] for b in bounds])
        logs = np.array([p.log for p in model.params])

        def to(x):
            return np.where(logs, np.log(np.maximum(x, 1e-300)), x)

        def back(u):
            return np.clip(np.where(logs, np.exp(u), u), lo, hi)

        found = minimize(lambda u: mean(back(u)), to(start), method="Nelder-Mead",
                         options=dict(xatol=1e-7, fatol=1e-12, maxiter=400))
        polish = minimize(lambda u: worst(back(u)), found.x, method="Nelder-Mead",
                          options=dict(xatol=1e-8, fatol=1e-12, maxiter=200))
        best = tuple(float(v) for v in back(polish.x if polish.fun <= worst(back(found.x)) else found.x))
    with np.errstate(all="ignore"):
        errors = errors_against(values, model.answer(best), error)
    on = errors[rows]
    return Fit(model, best, float(on.max()) if on.size else 0.0, rows, errors)


def best_correct(models, values, error, groups) -> tuple:
    """The verdict's fits: for each group, the correct model that fits best within the physical ranges.

    Returns (the fits by group, the per-row errors under them).

    Parameters
    ----------
    models : list of Model
        The correct models.
    values : numpy.ndarray (n, c)
        The function's outputs.
    error : Callable
        ``error(values, answer) -> (n,)``.
    groups : numpy.ndarray (n,)
        Each row's group.

    Returns
    -------
    (dict, numpy.ndarray)
    """
    fits, errors = {}, np.zeros(len(values))
    for g in dict.fromkeys(groups.tolist()):
        rows = groups == g
        found = min((fit(m, values, error, rows, physical=True) for m in models), key=lambda f: f.error)
        fits[g] = found
        errors[rows] = found.errors[rows]
    return fits, errors


def explain(correct, faults, values, error, groups, tolerance: float, worst: float) -> list:
    """The cause of a failure, from the models that explain the output: a list of (group or None, words),
    empty when none does.

    The whole domain first (every fault, and the correct forms with constants outside their physical
    ranges: one entry, group None); then each group alone, so that a fault on one side or in one channel is
    named with what the other groups compute ("right (…)" for those that are).

    Parameters
    ----------
    correct, faults : list of Model
        The correct and faulty models.
    values : numpy.ndarray (n, c)
        The function's outputs.
    error : Callable
        ``error(values, answer) -> (n,)``.
    groups : numpy.ndarray (n,)
        Each row's group.
    tolerance : float
        The largest error allowed.
    worst : float
        The largest error seen.

    Returns
    -------
    list of tuple
    """
    accept = max(2.0 * tolerance, min(0.1 * worst, 0.05))
    everywhere = np.ones(len(values), bool)
    found = _first_accepted(correct, faults, values, error, everywhere, tolerance, accept, worst)
    if found is not None:
        return [(None, found.model.text(found.values))]
    labels = list(dict.fromkeys(groups.tolist()))
    if len(labels) < 2:
        return []
    parts, faulty = [], 0
    for g in labels:
        rows = groups == g
        ok = min((fit(m, values, error, rows, physical=True) for m in correct), key=lambda f: f.error)
        if ok.error <= tolerance:
            parts.append((g, f"right ({ok.model.name}{', ' + ok.constants() if ok.constants() else ''})"))
            continue
        here = _first_accepted(correct, faults, values, error, rows, tolerance, accept, float(ok.errors[rows].max()))
        if here is None:
            return []
        faulty += 1
        parts.append((g, here.model.text(here.values)))
    return parts if faulty else []


def explain_rows(correct, faults, values, error, rows, tolerance: float) -> str:
    """The cause for some rows alone (a side or a channel), in words ("" when no model explains them).

    Parameters
    ----------
    correct, faults : list of Model
        The correct and faulty models.
    values : numpy.ndarray (n, c)
        The function's outputs.
    error : Callable
        ``error(values, answer) -> (n,)``.
    rows : numpy.ndarray
        The rows explained (a boolean mask or indices).
    tolerance : float
        The largest error allowed.

    Returns
    -------
    str
    """
    ok = min((fit(m, values, error, rows, physical=True) for m in correct), key=lambda f: f.error)
    worst = float(ok.errors[rows].max()) if rows.any() else 0.0
    accept = max(2.0 * tolerance, min(0.1 * worst, 0.05))
    found = _first_accepted(correct, faults, values, error, rows, tolerance, accept, worst)
    return found.model.text(found.values) if found is not None else ""


def _first_accepted(correct, faults, values, error, rows, tolerance, accept, worst):
    tried = []
    for order, m in enumerate(list(correct) + list(faults)):
        f = fit(m, values, error, rows)
        if m.correct and f.physical:
            continue  # a correct form with water's constants that does not fit is not a cause
        if f.error <= accept and f.error < 0.5 * worst:
            tried.append((f.error > tolerance, order if f.error <= tolerance else f.error, f))
            if f.error <= tolerance:
                break  # the models come in order of preference: the first that explains the output wins
    return min(tried, key=lambda t: (t[0], t[1]))[2] if tried else None
