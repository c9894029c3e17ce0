"""Check a user's GLSL function against the physics: :func:`check_glsl` and its :class:`ShaderReport`."""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from wavephys.core.inputs import check_instance, check_scalar, describe

from optics.shaders.checks import ROLES, SHADER_CHECKS, _finite_cause
from optics.shaders.glsl import GLSLError, evaluate, find_function

__all__ = ["ShaderReport", "check_glsl", "describe_check"]


@dataclass(frozen=True)
class ShaderReport:
    """The verdict on one GLSL function.

    Attributes
    ----------
    against : str
        The check (a name in :data:`~optics.shaders.SHADER_CHECKS`).
    function : str
        The checked declaration, as GLSL.
    takes : tuple of str
        The role of each parameter (:data:`~optics.shaders.ROLES`).
    error : float
        The worst error over the domain (NaN if the function returned NaN or inf); the
        quantity is ``quantity``.
    tolerance : float
        The largest error allowed.
    worst : dict
        The input at the worst error: each role's value and the domain's coordinates
        (angle, side, distance, …), with the value the function returned and the one expected.
    cause : str
        A one-line cause when the error matches a known mistake, else "".
    note : str
        What the domain covered.
    samples : int
        How many inputs were evaluated.
    seconds : float
        Wall time of the check (compile, evaluate, compare).
    renderer : str
        The OpenGL renderer that ran the function (``llvmpipe …`` or a GPU).
    """

    against: str
    function: str
    takes: tuple
    quantity: str
    error: float
    tolerance: float
    worst: dict
    cause: str
    note: str
    samples: int
    seconds: float
    renderer: str
    _errors: np.ndarray = field(repr=False, compare=False, default=None)
    _axis: tuple = field(repr=False, compare=False, default=None)
    _groups: np.ndarray = field(repr=False, compare=False, default=None)

    @property
    def ok(self) -> bool:
        """True when the worst error is finite and within the tolerance."""
        return math.isfinite(self.error) and self.error <= self.tolerance

    def as_check(self):
        """The verdict as a :class:`wavephys.harness.Check` row (worst error ≤ tolerance)."""
        from wavephys.harness.checks import bound

        note = self.note + (f"; likely cause: {self.cause}" if self.cause else "")
        return bound(f"{self.function} against {self.against}: worst {self.quantity}", self.error, self.tolerance,
                     note=note)

    def report(self) -> str:
        """A few lines: the verdict, the worst input, the cause."""
        where = ", ".join(f"{k} = {_show(v)}" for k, v in self.worst.items())
        lines = [f"{self.function} against {self.against}: {'ok' if self.ok else 'FAILED'}: worst {self.quantity} "
                 f"{self.error:.4g} (tolerance {self.tolerance:.3g}) over {self.samples} inputs",
                 f"  worst at {where}", f"  domain: {self.note}"]
        if self.cause and not self.ok:
            lines.append(f"  likely cause: {self.cause}")
        return "\n".join(lines)

    def as_dict(self) -> dict:
        """Plain data (JSON-ready)."""
        return dict(against=self.against, function=self.function, takes=list(self.takes), quantity=self.quantity,
                    ok=self.ok, error=self.error if math.isfinite(self.error) else None, tolerance=self.tolerance,
                    worst={k: _plain(v) for k, v in self.worst.items()}, cause=self.cause, note=self.note,
                    samples=self.samples, seconds=self.seconds, renderer=self.renderer)

    def chart(self, path):
        """Draw the error over the domain (one line per side or group, the tolerance dashed) to a PNG."""
        from matplotlib.figure import Figure  # no pyplot: the caller's backend is left alone

        from wavephys.core.files import atomic_path, output_file
        path = output_file(path, "chart", (".png",))
        label, x = self._axis
        fig = Figure(figsize=(6.0, 3.4), dpi=110)
        ax = fig.add_subplot()
        floor = max(self.tolerance * 1e-4, 1e-12)
        for g in dict.fromkeys(self._groups.tolist()):
            on = self._groups == g
            order = np.argsort(x[on], kind="stable")
            err = np.where(np.isfinite(self._errors[on]), self._errors[on], np.nan)[order]
            ax.plot(x[on][order], np.maximum(err, floor), ".", ms=2, label=str(g))
        ax.axhline(self.tolerance, color="k", ls="--", lw=1, label="tolerance")
        ax.set(yscale="log", xlabel=label, ylabel=self.quantity,
               title=f"{self.function}  ({'ok' if self.ok else 'FAILED'})")
        ax.title.set_fontsize(8)
        ax.legend(fontsize=7, markerscale=4)
        fig.tight_layout()
        with atomic_path(path) as tmp:
            fig.savefig(tmp, format="png")
        return path


def _plain(v):
    a = np.asarray(v)
    if a.dtype.kind in "US":
        return str(a)
    return float(a) if a.ndim == 0 else [float(x) for x in a.ravel()]


def _show(v):
    p = _plain(v)
    if isinstance(p, list):
        return "(" + ", ".join(f"{x:.5g}" for x in p) + ")"
    return f"{p:.5g}" if isinstance(p, float) else p


def _check_takes(check, takes, name="takes"):
    if takes is None:
        return check.takes
    if isinstance(takes, str):
        takes = tuple(t.strip() for t in takes.split(",") if t.strip())
    if not isinstance(takes, (tuple, list)) or not all(isinstance(t, str) for t in takes):
        raise TypeError(f"{name} must be a sequence of role names, got {describe(takes)}")
    unknown = [t for t in takes if t not in check.roles]
    if unknown:
        roles = "; ".join(f"{r} ({ROLES[r][0]}: {ROLES[r][1]})" for r in check.roles)
        raise ValueError(f"{name}: {unknown} are not roles the {check.name!r} check can feed; its roles: {roles}")
    return tuple(takes)


def _declaration(check, source, function, takes, returns):
    types = tuple(ROLES[t][0] for t in takes)
    try:
        decl = find_function(source, function, types)
    except GLSLError as exc:
        if "does not take" not in str(exc):
            raise
        raise GLSLError(f"{exc}: say what each parameter is with takes=(...), roles of {check.name!r}: "
                        + ", ".join(f"{r} ({ROLES[r][0]})" for r in check.roles)) from None
    if returns is not None and decl.returns != returns:
        raise GLSLError(f"returns: {decl.signature()} returns {decl.returns}, not {returns}")
    if decl.returns not in check.returns:
        raise GLSLError(f"function: {decl.signature()} returns {decl.returns}; the {check.name!r} check needs "
                        f"{' or '.join(check.returns)}")
    return decl


def _cause(check, values, domain, expected, errors, tolerance):
    """The first recognized cause: the check's early test, NaN, a matching alternative, the late test."""
    cause = check.early(values, domain, errors) or _finite_cause(values, domain)
    if cause:
        return cause
    worst = float(np.max(errors))
    for text, answer in domain.alternatives:
        alt = check.error(values, np.asarray(answer, np.float64)[:, :values.shape[1]], domain)
        if np.max(alt) <= max(2.0 * tolerance, 0.2 * worst) and np.max(alt) < 0.5 * worst:
            return text
    return check.late(values, domain, errors)


def check_glsl(source, function: str, against: str, *, takes=None, returns: str | None = None,
               uniforms: dict | None = None, tolerance: float | None = None, chart=None, **options) -> ShaderReport:
    """Run a GLSL function over its whole input domain and compare it with the physics.

    Parameters
    ----------
    source : str
        GLSL defining ``function`` (and anything it calls); a ``#version`` line is ignored,
        line numbers in driver messages are those of ``source``.
    function : str
        The function's name.
    against : str
        The check: a name in :data:`~optics.shaders.SHADER_CHECKS` ("fresnel", "refract",
        "reflect", "transmittance", "rgb_absorption", "normal_decode", "height_normal").
    takes : sequence of str, optional
        The role of each parameter, in order (:data:`~optics.shaders.ROLES`; default: the
        check's own, e.g. ``("cos_theta", "n1", "n2")`` for "fresnel").
    returns : str, optional
        The return type you expect ("float", "vec3"): refused if the declaration differs.
    uniforms : dict, optional
        Values for ``uniform`` variables the function reads (name → number or tuple).
    tolerance : float, optional
        The largest error allowed (default: the check's, see :mod:`optics.shaders.checks`).
    chart : path, optional
        Also draw the error over the domain to this PNG.
    **options
        The check's domain options (``form="schlick"``, ``sides=("above",)``, ``convention="directx"``, …).

    Returns
    -------
    ShaderReport

    Raises
    ------
    GLSLError
        The function is not defined, takes other types than ``takes`` say, returns a type the
        check cannot use, or the source does not compile (the driver's message).

    Examples
    --------
    >>> source = "float f(float c) { return 0.02 + 0.98 * pow(1.0 - c, 5.0); }"   # doctest: +SKIP
    >>> report = check_glsl(source, "f", "fresnel", form="schlick")              # doctest: +SKIP
    >>> report.ok, report.cause                                                  # doctest: +SKIP
    """
    start = time.perf_counter()
    check = _check_against(against)
    if not isinstance(source, str):
        raise TypeError(f"source must be GLSL text (str), got {describe(source)}")
    takes = _check_takes(check, takes)
    if uniforms is not None:
        check_instance("uniforms", uniforms, dict)
    if chart is not None:
        from wavephys.core.files import output_file

        output_file(chart, "chart", (".png",))
    decl = _declaration(check, source, function, takes, returns)
    if tolerance is not None:
        check_scalar("tolerance", tolerance, lo=0.0, lo_open=True)
        options["tolerance"] = tolerance
    domain = _domain(check, options)
    values = evaluate(source, decl, [domain.inputs[t] for t in takes], uniforms).astype(np.float64)
    expected = domain.expected[:, :values.shape[1]]
    errors = check.error(values, expected, domain)
    errors = np.where(np.isfinite(errors), errors, np.inf)
    i = int(np.argmax(errors))
    worst = {t: domain.inputs[t][i] for t in takes if not hasattr(domain.inputs[t], "wrap")}
    worst.update({k: v[i] for k, v in domain.context.items()})
    worst.update(returned=values[i], expected=expected[i])
    error = float(errors[i]) if math.isfinite(errors[i]) else math.nan
    ok = math.isfinite(error) and error <= domain.tolerance
    cause = "" if ok else _cause(check, values, domain, expected, errors, domain.tolerance)
    report = ShaderReport(check.name, decl.signature(), takes, check.quantity, error, domain.tolerance, worst, cause,
                          domain.note, len(values), time.perf_counter() - start, _renderer(), errors,
                          domain.axis, domain.groups)
    if chart is not None:
        report.chart(chart)
    return report


def _check_against(against):
    if not isinstance(against, str):
        raise TypeError(f"against must be one of {sorted(SHADER_CHECKS)}, got {describe(against)}")
    if against not in SHADER_CHECKS:
        raise ValueError(f"against must be one of {sorted(SHADER_CHECKS)}, got {against!r}")
    return SHADER_CHECKS[against]


def _domain(check, options):
    import inspect

    allowed = set(inspect.signature(check.domain).parameters)
    unknown = sorted(set(options) - allowed)
    if unknown:
        raise TypeError(f"{unknown} are not options of the {check.name!r} check; its options: {sorted(allowed)}")
    return check.domain(**options)


def _renderer() -> str:
    from optics.shaders.glsl import _context

    ctx = _context()
    with ctx:
        return str(ctx.info.get("GL_RENDERER", "unknown"))


def describe_check(against: str) -> str:
    """What a check feeds, returns and compares with, in words (for ``--help`` and errors).

    Parameters
    ----------
    against : str
        A name in :data:`~optics.shaders.SHADER_CHECKS`.

    Returns
    -------
    str
        Several lines: the summary, the default roles, each role's meaning, the options.
    """
    check = _check_against(against)
    import inspect

    roles = "\n".join(f"    {r:14s} {ROLES[r][0]:9s} {ROLES[r][1]}" for r in check.roles)
    params = ", ".join(p for p in inspect.signature(check.domain).parameters)
    doc = inspect.getdoc(check.domain) or ""
    return (f"{check.name}: {check.summary}; returns {' or '.join(check.returns)}; error {check.quantity}\n"
            f"  default takes: {', '.join(check.takes)}\n  roles:\n{roles}\n  options: {params}\n  {doc}")
