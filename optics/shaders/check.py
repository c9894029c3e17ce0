"""Check a user's shader function against the physics: :func:`check_glsl` and its :class:`ShaderReport`."""

from __future__ import annotations

import inspect
import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from wavephys.core.inputs import check_instance, check_scalar, describe

from optics.shaders.checks import ROLES, SHADER_CHECKS, SIDE_ROLES, finite_cause
from optics.shaders.glsl import GLSLError, declarations, evaluate
from optics.shaders.models import best_correct, explain
from optics.shaders.roles import infer_takes, is_constant, role_type
from optics.shaders.source import LANGUAGES, detect_language, prepare

__all__ = ["ShaderReport", "check_glsl", "describe_check"]


@dataclass(frozen=True)
class ShaderReport:
    """The verdict on one shader function.

    Attributes
    ----------
    against : str
        The check (a name in :data:`~optics.shaders.SHADER_CHECKS`).
    function : str
        The checked declaration, as written (HLSL parameters with GLSL types).
    takes : tuple of str
        The role of each value-taking parameter (:data:`~optics.shaders.ROLES`).
    quantity : str
        What ``error`` measures.
    error : float
        The worst error over the domain of the best correct form with constants the physics allows (NaN if the
        function returned NaN or inf).
    tolerance : float
        The largest error allowed.
    worst : dict
        The input at the worst error: each role's value and the domain's coordinates (angle, side, distance, …),
        with the value the function returned and the one expected.
    cause : str
        On failure, the cause in words when a model explains the output, else "".
    note : str
        What the domain covered.
    samples : int
        How many inputs were evaluated.
    seconds : float
        Wall time of the check (translate, compile, evaluate, fit).
    renderer : str
        The OpenGL renderer that ran the function (``llvmpipe …`` or a GPU).
    fitted : str
        What the function computes, as fitted: the form and its constants per side or channel
        ("above: Schlick's approximation, F0 = 0.0200 (m = 1.3300)").
    tolerance_note : str
        How the tolerance was set.
    notes : tuple of str
        How the function was read: the language, roles read from names, the side it is checked from.
    language : str
        The language it was read as (:data:`~optics.shaders.source.LANGUAGES`).
    result : str
        Where the result came from: ``"return"`` or an out parameter's name.
    unphysical : str
        When the function's output is explained, within the tolerance, only by a constant outside its physical
        range (an F0 of 0.0233, a hair above water's 0.0224), what that constant is; the verdict is then a
        failure whatever the error. "" otherwise.
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
    fitted: str = ""
    tolerance_note: str = ""
    notes: tuple = ()
    language: str = "glsl"
    result: str = "return"
    unphysical: str = ""
    _errors: np.ndarray = field(repr=False, compare=False, default=None)
    _axis: tuple = field(repr=False, compare=False, default=None)
    _groups: np.ndarray = field(repr=False, compare=False, default=None)

    @property
    def ok(self) -> bool:
        """True when the worst error is finite and within the tolerance, and no constant of the function is
        measured outside its physical range (``unphysical``)."""
        return math.isfinite(self.error) and self.error <= self.tolerance and not self.unphysical

    def as_check(self):
        """The verdict as a :class:`wavephys.harness.Check` row (worst error ≤ tolerance)."""
        from wavephys.harness.checks import bound

        note = "; ".join(x for x in (self.note, self.fitted, self.tolerance_note) if x)
        note += f"; likely cause: {self.cause}" if self.cause else ""
        if self.unphysical:  # within the tolerance only with a constant the physics does not allow: no measurement
            note = f"worst error {self.error:.4g} with {self.unphysical}; {note}"
            return bound(f"{self.function} against {self.against}: worst {self.quantity} with physical constants",
                         math.nan, self.tolerance, note=note)
        return bound(f"{self.function} against {self.against}: worst {self.quantity}", self.error, self.tolerance,
                     note=note)

    def report(self) -> str:
        """A few lines: the verdict, the worst input, what the function computes, the cause."""
        where = ", ".join(f"{k} = {_show(v)}" for k, v in self.worst.items())
        lines = [f"{self.function} against {self.against}: {'ok' if self.ok else 'FAILED'}: worst {self.quantity} "
                 f"{self.error:.4g} (tolerance {self.tolerance:.3g}) over {self.samples} inputs"
                 + (" with a constant outside its physical range" if self.unphysical else ""),
                 f"  worst at {where}", f"  domain: {self.note}"]
        if self.fitted:
            lines.append(f"  fitted: {self.fitted}")
        if self.tolerance_note:
            lines.append(f"  {self.tolerance_note}")
        lines += [f"  read: {n}" for n in self.notes]
        if self.cause and not self.ok:
            lines.append(f"  likely cause: {self.cause}")
        return "\n".join(lines)

    def as_dict(self) -> dict:
        """Plain data (JSON-ready)."""
        return dict(against=self.against, function=self.function, takes=list(self.takes), quantity=self.quantity,
                    ok=self.ok, error=self.error if math.isfinite(self.error) else None, tolerance=self.tolerance,
                    worst={k: _plain(v) for k, v in self.worst.items()}, cause=self.cause, note=self.note,
                    fitted=self.fitted, tolerance_note=self.tolerance_note, notes=list(self.notes),
                    language=self.language, result=self.result, unphysical=self.unphysical, samples=self.samples,
                    seconds=self.seconds,
                    renderer=self.renderer)

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


def _number(t):
    if isinstance(t, str):
        try:
            value = float(t)
        except ValueError:
            return t
        return value if math.isfinite(value) else t
    return float(t) if is_constant(t) else t


def _check_takes(check, takes, name="takes"):
    if isinstance(takes, str):
        takes = tuple(t.strip() for t in takes.split(",") if t.strip())
    if not isinstance(takes, (tuple, list)) or not all(isinstance(t, str) or is_constant(t) for t in takes):
        raise TypeError(f"{name} must be a sequence of role names (or numbers for parameters held fixed), got "
                        f"{describe(takes)}")
    takes = tuple(_number(t) for t in takes)
    unknown = [t for t in takes if not is_constant(t) and t not in check.roles]
    if unknown:
        roles = "; ".join(f"{r} ({ROLES[r][0]}: {ROLES[r][1]})" for r in check.roles)
        raise ValueError(f"{name}: {unknown} are not roles the {check.name!r} check can feed; its roles: {roles}")
    return tuple(takes)


def _declaration(check, code, function, takes):
    """The overload of ``function`` to check and its roles: the one whose types ``takes`` gives, or whose
    parameter names say their roles."""
    named = [d for d in declarations(code) if d.name == function]
    if not named:
        from optics.shaders.glsl import find_function

        find_function(code, function)  # raises, listing what is defined
    if takes is not None:
        types = tuple(role_type(t) for t in takes)
        for d in named:
            if d.types == types:
                return d, takes, ""
        have = "; ".join(d.signature() for d in named)
        raise GLSLError(f"function: {have} does not take ({', '.join(types)}) as takes says: roles of "
                        f"{check.name!r}: " + ", ".join(f"{r} ({ROLES[r][0]})" for r in check.roles))
    problem = None
    for d in named:
        try:
            found, how = infer_takes(check, d)
            return d, found, how
        except GLSLError as exc:
            problem = exc
    raise problem


def _result(check, decl, result, returns):
    result = decl.default_result() if result is None else result
    if not isinstance(result, str) or result not in decl.outputs:
        raise GLSLError(f"result: {decl.signature()} has no result {result!r}; its results: "
                        f"{', '.join(decl.outputs) or 'none'}")
    kind = decl.result_type(result)
    if returns is not None and kind != returns:
        raise GLSLError(f"returns: {decl.signature()} gives {kind} ({result}), not {returns}")
    if kind not in check.returns:
        raise GLSLError(f"function: {decl.signature()} gives {kind} ({result}); the {check.name!r} check needs "
                        f"{' or '.join(check.returns)}")
    return result


def _side_options(check, takes, front_facing, options, notes):
    """A Fresnel or refraction function that takes nothing telling the side is checked from the air; one that
    takes no normal assumes flat water."""
    if not check.sided:
        return
    vectors = {"incident", "view"} & set(takes)
    knows = bool({"n1", "n2", "eta", "front_facing"} & set(takes)) or front_facing or (
        "normal" in takes and vectors)
    if "sides" not in options and not knows and check.name != "reflect":
        options["sides"] = ("above",)
        notes.append("checked from the air only: the function takes nothing that tells the side the ray comes from "
                     f"({', '.join(r for r in SIDE_ROLES if r != 'cos_theta_t')} or gl_FrontFacing); pass "
                     "sides=('above', 'below') to check it from the water too")
    if vectors and not {"normal", "facing_normal"} & set(takes) and "tilt" not in options:
        options["tilt"] = 0.0
        notes.append("flat water: the function takes no normal, so the surface's normal is up")


def _read(source, function, language, defines, include_dirs):
    """(prepared GLSL, the user's declarations' source text, the translation or None)."""
    if not isinstance(language, str) or language not in LANGUAGES:
        raise ValueError(f"language must be one of {LANGUAGES}, got {language!r}")
    read_as = detect_language(source) if language == "auto" else language
    if read_as == "hlsl":
        from optics.shaders.hlsl import translate

        tr = translate(source, function, defines=defines, include_dirs=include_dirs)
        return tr.prepared, tr, read_as
    prepared = prepare(source, read_as, defines=defines, include_dirs=include_dirs)
    return prepared, None, read_as


def check_glsl(source, function: str, against: str, *, takes=None, result=None, returns: str | None = None,
               uniforms: dict | None = None, tolerance: float | None = None, language: str = "auto", defines=None,
               include_dirs=(), chart=None, **options) -> ShaderReport:
    """Run a shader function over its whole input domain and compare it with the physics.

    Parameters
    ----------
    source : str
        The shader source defining ``function`` (and anything it calls), as shipped: GLSL, GLSL ES, WebGL,
        Shadertoy, a Godot shader file or HLSL (``language``). A ``#version`` line is ignored; line numbers in
        messages are those of ``source``.
    function : str
        The function's name.
    against : str
        The check: a name in :data:`~optics.shaders.SHADER_CHECKS` ("fresnel", "refract", "reflect",
        "transmittance", "rgb_absorption", "normal_decode", "height_normal").
    takes : sequence of str, optional
        The role of each value-taking parameter (in, inout), in order (:data:`~optics.shaders.ROLES`). Default:
        the check's own when the types match, else read from the parameters' names (``cosTheta``, ``F0``,
        ``I``, ``N``, ``eta`` …); a name it cannot place is refused by name.
    result : str, optional
        Where the result is: ``"return"`` or an out/inout parameter (default: the return value, or a void
        function's only out parameter).
    returns : str, optional
        The result type you expect ("float", "vec3"): refused if the declaration differs.
    uniforms : dict, optional
        Values for uniforms the function reads (name → number or tuple; HLSL globals by their names).
    tolerance : float, optional
        The largest error allowed (default: the check's, from physics and the display; see the report's
        ``tolerance_note``).
    language : str, optional
        "auto" (default: told from the text), "glsl", "glsl_es", "webgl", "shadertoy", "godot" or "hlsl".
    defines : dict or list of str, optional
        Macros the source relies on (an engine's), defined before it.
    include_dirs : sequence of path, optional
        Folders for ``#include``.
    chart : path, optional
        Also draw the error over the domain to this PNG.
    **options
        The check's domain options (``form="schlick"``, ``sides=("above",)``, ``convention="directx"``,
        ``bits=10``, ``radiance=4``, ``up="y"`` …; :func:`describe_check` lists them).

    Returns
    -------
    ShaderReport

    Raises
    ------
    GLSLError
        The function is not defined, takes other types than ``takes`` say, has parameters whose roles cannot
        be read, gives a type the check cannot use, or the source does not compile (the driver's or glslang's
        message with your line numbers, and a missing macro or include named).
    TranslatorMissing
        HLSL was given and glslangValidator or spirv-cross is not installed.

    Examples
    --------
    >>> source = "float f(float cosTheta) { return 0.02 + 0.98 * pow(1.0 - cosTheta, 5.0); }"   # doctest: +SKIP
    >>> check_glsl(source, "f", "fresnel").ok                                                   # doctest: +SKIP
    True
    """
    start = time.perf_counter()
    check = _check_against(against)
    if not isinstance(source, str):
        raise TypeError(f"source must be shader text (str), got {describe(source)}")
    if not isinstance(function, str):
        raise TypeError(f"function must be the name of a function (str), got {describe(function)}")
    takes = None if takes is None else _check_takes(check, takes)
    if uniforms is not None:
        check_instance("uniforms", uniforms, dict)
    if chart is not None:
        from wavephys.core.files import output_file

        output_file(chart, "chart", (".png",))
    if tolerance is not None:
        check_scalar("tolerance", tolerance, lo=0.0, lo_open=True)
        options["tolerance"] = tolerance
    _check_options(check, options)
    from optics.shaders.source import check_defines, check_include_dirs

    include_dirs = check_include_dirs(include_dirs)
    check_defines(defines)
    prepared, translated, language = _read(source, function, language, defines, include_dirs)
    user_code = source if translated is not None else prepared.text
    decl, takes, how = _declaration(check, user_code, function, takes) if translated is None else \
        _translated_declaration(check, translated, takes)
    result = _result(check, decl, result, returns)
    notes = [n for n in (*prepared.notes, how) if n]
    _side_options(check, takes, prepared.front_facing, options, notes)
    domain = _domain(check, options, takes)
    inputs = [np.full((domain.size, 1), t) if is_constant(t) else domain.inputs[t] for t in takes]
    glsl_decl = decl if translated is None else translated.glsl
    if translated is not None:
        inputs = [inputs[i] for i in translated.order]
        uniforms = {translated.uniforms.get(k, k): v for k, v in (uniforms or {}).items()}
    values = evaluate(prepared, glsl_decl, inputs, uniforms, result=result,
                      front_facing=domain.front_facing if prepared.front_facing else None).astype(np.float64)
    return _judge(check, domain, values, decl, takes, result, language, notes, start, chart)


def _translated_declaration(check, translated, takes):
    decl = translated.declaration
    if takes is not None:
        types = tuple(role_type(t) for t in takes)
        if decl.types != types:
            raise GLSLError(f"function: {decl.signature()} does not take ({', '.join(types)}) as takes says")
        return decl, takes, ""
    found, how = infer_takes(check, decl)
    return decl, found, how


def _per_channel(domain, values):
    """A colour result of a scalar check: each channel its own group of rows (fitted alone)."""
    c = values.shape[1]
    names = "RGBA"[:c]

    def tile(answer):
        if isinstance(answer, tuple):
            return tuple(np.tile(np.asarray(a)[:, :1], (c, 1)) for a in answer)
        return np.tile(np.asarray(answer)[:, :1], (c, 1))

    def wrap(models):
        return [replace(m, answer=lambda v, a=m.answer: tile(a(v))) for m in models]

    groups = np.concatenate([np.char.add(domain.groups.astype(str), f" {ch}") for ch in names])
    context = {k: np.tile(np.asarray(v), c) for k, v in domain.context.items()}
    context["channel"] = np.repeat(np.array(list(names)), len(values))
    extra = {k: (np.tile(v, c) if isinstance(v, np.ndarray) and v.shape[:1] == (len(values),) else v)
             for k, v in domain.extra.items()}
    axis = (domain.axis[0], np.tile(domain.axis[1], c))
    flat = values.T.reshape(-1, 1)
    return replace(domain, groups=groups, context=context, correct=wrap(domain.correct), faults=wrap(domain.faults),
                   extra=extra, axis=axis), flat


def _judge(check, domain, values, decl, takes, result, language, notes, start, chart):
    """The verdict: the best correct model within the physical ranges; on failure, the cause."""
    rows = len(values)
    if check.per_channel and values.shape[1] > 1:
        if np.array_equal(values, np.repeat(values[:, :1], values.shape[1], axis=1), equal_nan=True):
            values = values[:, :1]
            notes.append("its colour result has equal channels: checked as one")
        else:
            domain, values = _per_channel(domain, values)
    fits, errors = best_correct(domain.correct, values, check.error, domain.groups)
    unphysical = _unphysical(domain, values, check.error, fits)
    i = int(np.argmax(errors))
    error = float(errors[i]) if math.isfinite(errors[i]) else math.nan
    fit = fits[domain.groups[i]]
    expected = _expected_row(fit, values, check.error, i)
    worst = {t: domain.inputs[t][i % rows] for t in takes if not is_constant(t) and not hasattr(domain.inputs[t],
                                                                                                   "wrap")}
    worst.update({k: v[i] for k, v in domain.context.items()})
    worst.update(returned=values[i], expected=expected)
    ok = math.isfinite(error) and error <= domain.tolerance and not unphysical
    extra = dict(domain.extra, expected=_expected_all(fits, domain, values, check.error))
    judged = replace(domain, extra=extra)
    cause = "" if ok else (unphysical if error <= domain.tolerance else _cause(check, judged, values, errors, error,
                                                                                   fits))
    report = ShaderReport(check.name, decl.signature(), tuple(takes), check.quantity, error, domain.tolerance, worst,
                          cause, domain.note, rows, time.perf_counter() - start, _renderer(), _fitted(fits, domain.tolerance),
                          domain.tolerance_note, tuple(notes), language, result, unphysical, errors, domain.axis,
                          domain.groups)
    if chart is not None:
        report.chart(chart)
    return report


def _unphysical(domain, values, error, fits) -> str:
    """A constant measured outside its physical range: in a group that passes, a correct model fitted with its
    constants free explains the output much better than within their ranges (the constant is measurable, not
    noise), and those constants are not physical."""
    from optics.shaders.models import fit

    said = []
    for g, inside in fits.items():
        if inside.error > domain.tolerance or not inside.model.params:
            continue
        rows = domain.groups == g
        free = min((fit(m, values, error, rows) for m in domain.correct if m.params), key=lambda f: f.error)
        if not free.physical and free.error <= domain.tolerance and inside.error > 2 * free.error + \
                0.05 * domain.tolerance:
            said.append((g, free.model.text(free.values)))
    if len(said) == 1 and len(fits) == 1:
        return said[0][1]
    return _join(said) if said else ""


def _expected_row(fit, values, error, i):
    answer = fit.model.answer(fit.values)
    options = answer if isinstance(answer, tuple) else (answer,)
    rows = [np.asarray(a, np.float64)[i, :values.shape[1]] for a in options]
    return min(rows, key=lambda r: float(np.nan_to_num(error(values[i:i + 1], r[None]), nan=np.inf)[0]))


def _expected_all(fits, domain, values, error):
    out = np.full(values.shape, np.nan)
    for g, f in fits.items():
        on = domain.groups == g
        answer = f.model.answer(f.values)
        answer = answer[0] if isinstance(answer, tuple) else answer
        out[on] = np.asarray(answer, np.float64)[on, :values.shape[1]]
    return out


def _fitted(fits, tolerance) -> str:
    parts = []
    for g, f in fits.items():
        constants = f.constants()
        parts.append((g, f"{f.model.name}{', ' + constants if constants else ''}" if f.error <= tolerance else
                      "no correct form with water's constants fits"))
    if len(fits) > 1 and len({w for _, w in parts}) == 1:
        return parts[0][1]
    return _join(parts)


def _subset(domain, rows):
    """The domain restricted to some rows (arrays over the rows sliced, the rest kept)."""
    n = len(rows)

    def cut(v):
        return v[rows] if isinstance(v, np.ndarray) and v.shape[:1] == (n,) else v

    return replace(domain, inputs={k: cut(v) for k, v in domain.inputs.items()}, groups=domain.groups[rows],
                   context={k: cut(v) for k, v in domain.context.items()}, extra={k: cut(v) for k, v in
                                                                                  domain.extra.items()},
                   axis=(domain.axis[0], cut(domain.axis[1])), front_facing=cut(domain.front_facing))


def _right(f) -> str:
    return f"right ({f.model.name}{', ' + f.constants() if f.constants() else ''})"


def _cause(check, domain, values, errors, error, fits):
    """The cause of a failure: the check's early test, NaN, a model that explains the whole output; else each
    group (side, channel) alone: right, a model that explains it, or the late test on its rows."""
    from optics.shaders.models import explain_rows

    early = check.early(values, domain, errors)
    flagged = early if isinstance(early, tuple) else None
    whole = early if isinstance(early, str) and early else finite_cause(values, domain)
    if not whole and flagged is None:
        worst = float(np.nanmax(np.where(np.isfinite(errors), errors, np.nan))) if np.isfinite(errors).any() else 1.0
        parts = explain(domain.correct, domain.faults, values, check.error, domain.groups, domain.tolerance, worst)
        whole = parts[0][1] if len(parts) == 1 and parts[0][0] is None else ""
    right = {g: f for g, f in fits.items() if f.error <= domain.tolerance}
    if whole:
        if right and len(right) < len(fits):
            wrong = ", ".join(g for g in fits if g not in right)
            return _join([(g, _right(f)) for g, f in right.items()] + [(wrong, whole)])
        return whole
    parts, found = [], False
    for g, f in fits.items():
        if g in right:
            parts.append((g, _right(f)))
            continue
        rows = domain.groups == g
        if flagged is not None and g == flagged[0]:
            text = flagged[1]
        else:
            text = (explain_rows(domain.correct, domain.faults, values, check.error, rows, domain.tolerance)
                    or check.late(values[rows], _subset(domain, rows), errors[rows]))
        found = found or bool(text)
        parts.append((g, text or "wrong, for no cause the checker knows"))
    if found and len(fits) > 1:
        return _join(parts)
    return check.late(values, domain, errors)


def _join(parts) -> str:
    """(group, words) pairs as one line, groups with the same words merged ('above R, above G: …')."""
    if len(parts) == 1 and parts[0][0] is None:
        return parts[0][1]
    merged = {}
    for label, words in parts:
        merged.setdefault(words, []).append(label)
    return "; ".join(f"{', '.join(labels)}: {words}" for words, labels in merged.items())


def _check_against(against):
    if not isinstance(against, str):
        raise TypeError(f"against must be one of {sorted(SHADER_CHECKS)}, got {describe(against)}")
    if against not in SHADER_CHECKS:
        raise ValueError(f"against must be one of {sorted(SHADER_CHECKS)}, got {against!r}")
    return SHADER_CHECKS[against]


def _check_options(check, options):
    allowed = set(inspect.signature(check.domain).parameters) - {"roles"}
    unknown = sorted(set(options) - allowed)
    if unknown:
        raise TypeError(f"{unknown} are not options of the {check.name!r} check; its options: {sorted(allowed)}")


def _domain(check, options, takes):
    if "roles" in inspect.signature(check.domain).parameters:
        return check.domain(**options, roles=tuple(takes))
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
    roles = "\n".join(f"    {r:16s} {ROLES[r][0]:9s} {ROLES[r][1]}" for r in check.roles)
    params = ", ".join(p for p in inspect.signature(check.domain).parameters if p != "roles")
    doc = inspect.getdoc(check.domain) or ""
    return (f"{check.name}: {check.summary}; returns {' or '.join(check.returns)}; error {check.quantity}\n"
            f"  default takes: {', '.join(check.takes)} (else read from the parameter names)\n  roles:\n{roles}\n"
            f"  options: {params}\n  {doc}")

