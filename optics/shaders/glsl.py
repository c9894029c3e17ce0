"""A user's GLSL function, found in its source, compiled and run over arrays of inputs.

The function is called once per texel of a float32 render target from a fragment shader
on the shared headless context (:func:`optics.gpu.gl_context`: Mesa llvmpipe on
a CPU-only machine, the GPU's driver elsewhere). Each argument is read from a float32
texture with ``texelFetch`` (so values reach the function exactly as float32) or, for a
``sampler2D`` parameter, is a texture the function samples itself. The result is written
to an RGBA32F target and read back, so NaN and inf come back as they were computed.

The user's source is compiled after a ``#line 1`` directive, so the driver's messages
carry the line numbers of the user's own file.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

import numpy as np

from wavephys.core.inputs import check_choice, check_instance, describe

from optics.shaders.source import FRONT_FACING, GLSLError, Prepared, prepare, strip_comments

__internal__ = True  # the registry's and the runner's pieces: users call optics.shaders.check_glsl
__all__ = ["GLSL_TYPES", "Parameter", "Declaration", "Sampler", "GLSLError", "declarations", "find_function",
           "evaluate"]

GLSL_TYPES = {"float": 1, "vec2": 2, "vec3": 3, "vec4": 4, "bool": 1, "sampler2D": 0}
"""The parameter and return types a checked function may use, with their component counts."""

_QUALIFIERS = {"in", "const", "highp", "mediump", "lowp", "precise"}
_WIDTH = 1024  # texels per row of the input and output textures
_WRAPPER_LINE = 1_000_000  # the #line of the generated main(): a message there is about the call, not the user


@dataclass(frozen=True)
class Parameter:
    """One declared parameter: its GLSL type, name and direction ("in", "out" or "inout").

    Attributes
    ----------
    type : str
        GLSL type.
    name : str
    direction : str
        ``"in"``, ``"out"`` or ``"inout"``.
    """

    type: str
    name: str
    direction: str = "in"

    @property
    def takes_input(self) -> bool:
        """Whether the caller gives it a value (``in`` and ``inout``)."""
        return self.direction != "out"


@dataclass(frozen=True)
class Declaration:
    """A function defined in a GLSL source: return type, name, parameters, and the line it starts on.

    Attributes
    ----------
    returns : str
        The return type.
    name : str
    parameters : tuple of Parameter
    line : int
        Where the definition starts (1-based).
    """

    returns: str
    name: str
    parameters: tuple
    line: int

    @property
    def types(self) -> tuple:
        """The types of the parameters that take a value (``in`` and ``inout``), in order."""
        return tuple(p.type for p in self.parameters if p.takes_input)

    @property
    def inputs(self) -> tuple:
        """The parameters that take a value (``in`` and ``inout``), in order."""
        return tuple(p for p in self.parameters if p.takes_input)

    @property
    def outputs(self) -> tuple:
        """The names a result can come from: ``"return"`` (non-void) and each out/inout parameter."""
        return (("return",) if self.returns != "void" else ()) + tuple(
            p.name for p in self.parameters if p.direction != "in")

    def result_type(self, result: str) -> str:
        """The GLSL type of ``result`` (``"return"`` or an out/inout parameter's name)."""
        if result == "return":
            return self.returns
        return next(p.type for p in self.parameters if p.name == result)

    def default_result(self) -> str:
        """The result a check reads when none is named: the return value, else the only out parameter.

        Raises GLSLError when a void function has no out/inout parameter or several of them."""
        if self.returns != "void":
            return "return"
        outs = [p.name for p in self.parameters if p.direction != "in"]
        if len(outs) == 1:
            return outs[0]
        if not outs:
            raise GLSLError(f"function: {self.signature()} returns nothing and has no out parameter: there is no "
                            "result to check")
        raise GLSLError(f"function: {self.signature()} returns nothing and has out parameters {', '.join(outs)}: "
                        f"say which holds the result with result='{outs[0]}' (--result {outs[0]})")

    def signature(self) -> str:
        """The declaration as GLSL: ``float fresnel(float cos_theta, float n1, float n2)``."""
        def one(p):
            return f"{p.direction + ' ' if p.direction != 'in' else ''}{p.type} {p.name}"

        return f"{self.returns} {self.name}({', '.join(one(p) for p in self.parameters)})"


@dataclass(frozen=True)
class Sampler:
    """A texture argument: ``data`` (h, w) or (h, w, c ≤ 4) float values, row 0 at v = 0;
    ``wrap`` "repeat" or "clamp"; ``filter`` "linear" or "nearest".

    Attributes
    ----------
    data : numpy.ndarray (h, w) or (h, w, c)
        The texels.
    wrap : str
        ``"repeat"`` or ``"clamp"``.
    filter : str
        ``"linear"`` or ``"nearest"``.
    """

    data: np.ndarray
    wrap: str = "repeat"
    filter: str = "linear"

    def __post_init__(self):
        data = np.asarray(self.data, np.float32)
        if data.ndim == 2:
            data = data[..., None]
        if data.ndim != 3 or not 1 <= data.shape[2] <= 4:
            raise ValueError(f"Sampler.data must have shape (h, w) or (h, w, c) with c from 1 to 4, got {data.shape}")
        object.__setattr__(self, "data", np.ascontiguousarray(data))
        check_choice("wrap", self.wrap, ("repeat", "clamp"))
        check_choice("filter", self.filter, ("linear", "nearest"))


_DEFINITION = re.compile(r"(?m)(?:^|[;}\s])(\w+)\s+(\w+)\s*\(([^()]*)\)\s*\{")


def _parameter(text: str) -> Parameter | None:
    words = [w for w in re.split(r"\s+", text.strip()) if w]
    if not words or words == ["void"]:
        return None
    direction = "inout" if "inout" in words else "out" if "out" in words else "in"
    words = [w for w in words if w not in _QUALIFIERS | {"out", "inout"}]
    if len(words) == 1:  # a prototype-style parameter without a name
        words.append("_")
    return Parameter(words[0], re.sub(r"\[.*", "", words[1]), direction)


def declarations(source: str) -> list:
    """Every function *defined* (with a body) in ``source``, in order (comments ignored).

    Parameters
    ----------
    source : str
        GLSL source.

    Returns
    -------
    list of Declaration
    """
    if not isinstance(source, str):
        raise TypeError(f"source must be GLSL text (str), got {describe(source)}")
    code = strip_comments(source)
    found = []
    for m in _DEFINITION.finditer(code):
        returns, name, params = m.group(1), m.group(2), m.group(3)
        if returns in {"return", "else", "if", "while", "for", "switch"} or name in {"if", "while", "for", "switch"}:
            continue
        parameters = tuple(p for p in (_parameter(t) for t in params.split(",")) if p is not None)
        found.append(Declaration(returns, name, parameters, code.count("\n", 0, m.start(2)) + 1))
    return found


def find_function(source: str, function: str, types: tuple | None = None) -> Declaration:
    """The definition of ``function`` in ``source`` whose value-taking parameters (in, inout) have ``types``
    (any overload, if None; the first).

    GLSLError when the function is not defined, or no overload takes ``types``, or a parameter's
    type cannot be fed.

    Parameters
    ----------
    source : str
        GLSL source.
    function : str
        The function's name.
    types : tuple of str, optional
        The types of its value-taking parameters.

    Returns
    -------
    Declaration
    """
    if not isinstance(function, str):
        raise TypeError(f"function must be the name of a GLSL function (str), got {describe(function)}")
    if not re.fullmatch(r"[A-Za-z_]\w*", function):
        raise ValueError(f"function must be a GLSL identifier, got {function!r}")
    found = declarations(source)
    named = [d for d in found if d.name == function]
    if not named:
        defined = ", ".join(sorted({d.name for d in found})) or "none"
        raise GLSLError(f"function: {function!r} is not defined in the source (functions defined there: {defined})")
    for d in named if types is None else [d for d in named if d.types == tuple(types)]:
        odd = [f"{p.type} {p.name}" for p in d.parameters if p.type not in GLSL_TYPES]
        if odd:
            raise GLSLError(f"function: {d.signature()} has parameters of types the checker cannot feed "
                            f"({', '.join(odd)}); it feeds {', '.join(GLSL_TYPES)}: wrap it in a function of those")
        if d.returns not in GLSL_TYPES and d.returns != "void" or d.returns == "sampler2D":
            raise GLSLError(f"function: {d.signature()} returns {d.returns}; a checked function returns a "
                            "float, a vector or a bool, or writes one to an out parameter")
        return d
    have = "; ".join(d.signature() for d in named)
    raise GLSLError(f"function: {have} does not take ({', '.join(types)}) as the check asks")


def _context():
    from optics.gpu import gl_context

    if "ctx" not in _STATE:
        _STATE["ctx"] = gl_context()
    return _STATE["ctx"]


_STATE: dict = {}

_VERTEX = """#version 330
void main() {
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
"""

_SWIZZLE = {1: ".x", 2: ".xy", 3: ".xyz", 4: ""}
_PACK = {"float": "vec4({}, 0.0, 0.0, 0.0)", "vec2": "vec4({}, 0.0, 0.0)", "vec3": "vec4({}, 0.0)", "vec4": "{}",
         "bool": "vec4(float({}), 0.0, 0.0, 0.0)"}


def _fetch(i: int, kind: str) -> str:
    value = f"texelFetch(wp_in{i}, wp_p, 0)"
    return f"({value}.x > 0.5)" if kind == "bool" else value + _SWIZZLE[GLSL_TYPES[kind]]


def _fragment(prepared: Prepared, decl: Declaration, result: str) -> str:
    """The user's source inside a fragment program whose main() calls ``decl`` once per texel, each input
    parameter read from its own texture, and writes ``result`` (the return value or an out parameter)."""
    head = ["#version 330", prepared.header]
    if prepared.front_facing:
        head += ["uniform sampler2D wp_in_ff;", f"bool {FRONT_FACING};"]
    lines, args, k = [], [], 0
    for i, p in enumerate(decl.parameters):
        if p.direction == "out":
            lines.append(f"    {p.type} wp_a{i};")
            args.append(f"wp_a{i}")
            continue
        head.append(f"uniform sampler2D wp_in{k};")
        if p.type == "sampler2D":
            args.append(f"wp_in{k}")
        elif p.direction == "inout":
            lines.append(f"    {p.type} wp_a{i} = {_fetch(k, p.type)};")
            args.append(f"wp_a{i}")
        else:
            args.append(_fetch(k, p.type))
        k += 1
    head.append("out vec4 wp_result;")
    call = f"{decl.name}({', '.join(args)})"
    if result == "return":
        lines.append(f"    wp_result = {_PACK[decl.returns].format(call)};")
    else:
        index = next(i for i, p in enumerate(decl.parameters) if p.name == result)
        lines += [f"    {call};", f"    wp_result = {_PACK[decl.parameters[index].type].format(f'wp_a{index}')};"]
    if prepared.front_facing:
        lines.insert(0, f"    {FRONT_FACING} = texelFetch(wp_in_ff, wp_p, 0).x > 0.5;")
    main = (f"#line {_WRAPPER_LINE}\nvoid main() {{\n    ivec2 wp_p = ivec2(gl_FragCoord.xy);\n"
            + "\n".join(lines) + "\n}\n")
    return "\n".join(head) + "\n#line 1\n" + prepared.text + "\n" + main


def _compile(ctx, prepared: Prepared, decl: Declaration, result: str):
    import moderngl

    try:
        return ctx.program(vertex_shader=_VERTEX, fragment_shader=_fragment(prepared, decl, result))
    except moderngl.Error as exc:
        message = str(exc).strip()
        where = (f" (the error is in the call {decl.signature()} that the check makes)"
                 if re.search(rf"\b{_WRAPPER_LINE}\b", message) else "")
        raise GLSLError(f"source: the {_LANGUAGE_NAMES.get(prepared.language, prepared.language)} does not "
                        f"compile; the driver says, with your line numbers:\n{message}{where}{_hint(message, prepared)}"
                        ) from None


_LANGUAGE_NAMES = {"glsl": "GLSL", "glsl_es": "GLSL ES", "webgl": "WebGL GLSL", "godot": "Godot shader",
                   "shadertoy": "Shadertoy GLSL", "hlsl": "HLSL (translated to GLSL)"}


def _hint(message: str, prepared: Prepared) -> str:
    """A line on what to do when the driver names an identifier the source does not define."""
    names = re.findall(r"`(\w+)' undeclared|'(\w+)' : undeclared|undeclared identifier[^`']*[`'](\w+)", message)
    names = [n for group in names for n in group if n]
    if not names:
        return ""
    name = names[0]
    if prepared.language == "godot" or re.fullmatch(r"[A-Z][A-Z0-9_]+", name):
        return (f"\n{name} is not defined in the source: an engine's built-in or macro? Define it with "
                f"defines={{'{name}': ...}} (--define {name}=VALUE), or give it as a uniform (uniforms=)")
    return f"\n{name} is not defined in the source: paste its definition, or define it (defines=, --define)"


def _texture(ctx, values: np.ndarray, rows: int):
    """Pack (n, c) values into a (rows × _WIDTH) RGBA32F texture, texel k = value k."""
    n, c = values.shape
    data = np.zeros((rows * _WIDTH, 4), np.float32)
    data[:n, :c] = values
    tex = ctx.texture((_WIDTH, rows), 4, data.tobytes(), dtype="f4")
    return tex


def _sampler(ctx, s: Sampler):
    import moderngl

    h, w, c = s.data.shape
    tex = ctx.texture((w, h), c, s.data.tobytes(), dtype="f4")
    f = moderngl.LINEAR if s.filter == "linear" else moderngl.NEAREST
    tex.filter = (f, f)
    tex.repeat_x = tex.repeat_y = s.wrap == "repeat"
    return tex


def evaluate(source, decl: Declaration, arguments: list, uniforms: dict | None = None, *, result: str | None = None,
             front_facing=None) -> np.ndarray:
    """Call ``decl`` from ``source`` once per row of the arguments; returns (n, components) float32.

    ``source``: GLSL text or a :class:`~optics.shaders.source.Prepared` source. ``arguments``: one per
    value-taking parameter (in, inout), in order: an (n, c) array for a float/vecN/bool parameter (c its
    component count; all with the same n), or a :class:`Sampler` for a sampler2D. ``uniforms``: values for
    the user's own ``uniform`` declarations (name → number or tuple); a name the program does not use is
    refused by name. ``result``: ``"return"`` or an out/inout parameter (default
    :meth:`Declaration.default_result`). ``front_facing``: (n,) booleans, when the source reads
    ``gl_FrontFacing``.

    Parameters
    ----------
    source : str or Prepared
    decl : Declaration
        The function called.
    arguments : list
        One per value-taking parameter.
    uniforms : dict, optional
        Values of the source's own uniforms.
    result : str, optional, keyword-only
        ``"return"`` or an out parameter's name.
    front_facing : numpy.ndarray (n,), optional, keyword-only
        Fed to ``gl_FrontFacing``.

    Returns
    -------
    numpy.ndarray (n, components)
        float32.
    """
    import moderngl

    prepared = source if isinstance(source, Prepared) else prepare(source, "glsl")
    check_instance("arguments", arguments, (list, tuple))
    result = decl.default_result() if result is None else result
    if result not in decl.outputs:
        raise GLSLError(f"result: {decl.signature()} has no result {result!r}; its results: "
                        f"{', '.join(decl.outputs) or 'none'}")
    if len(arguments) != len(decl.inputs):
        raise GLSLError(f"{decl.signature()} takes {len(decl.inputs)} values, got {len(arguments)}")
    sizes = {np.shape(a)[0] for a in arguments if not isinstance(a, Sampler)}
    if front_facing is not None:
        sizes.add(np.shape(front_facing)[0])
    if len(sizes) != 1:
        raise ValueError(f"arguments must have one number of rows (at least one array argument), got {sorted(sizes)}")
    if prepared.front_facing and front_facing is None:
        raise GLSLError("source: the function reads gl_FrontFacing: the check must say which side each input is on")
    n = sizes.pop()
    rows = max(1, math.ceil(n / _WIDTH))
    ctx = _context()
    with ctx:
        program = _compile(ctx, prepared, decl, result)
        made = [program]
        try:
            feeds = [a if isinstance(a, Sampler) else np.asarray(a, np.float32) for a in arguments]
            names = [f"wp_in{i}" for i in range(len(feeds))]
            if prepared.front_facing:
                feeds.append(np.asarray(front_facing, np.float32).reshape(n, 1))
                names.append("wp_in_ff")
            for i, (name, a) in enumerate(zip(names, feeds)):
                tex = _sampler(ctx, a) if isinstance(a, Sampler) else _texture(ctx, a, rows)
                made.append(tex)
                tex.use(i)
                if name in program:
                    program[name].value = i
            for name, value in (uniforms or {}).items():
                if name not in program:
                    raise GLSLError(f"uniforms: {name!r} is not a uniform the function uses")
                program[name].value = value
            target = ctx.texture((_WIDTH, rows), 4, dtype="f4")
            fbo = ctx.framebuffer(color_attachments=[target])
            vao = ctx.vertex_array(program, [])
            made += [target, fbo, vao]
            fbo.use()
            ctx.disable(moderngl.BLEND)
            vao.render(moderngl.TRIANGLES, vertices=3)
            out = np.frombuffer(fbo.read(components=4, dtype="f4"), np.float32).reshape(-1, 4)
        finally:
            for obj in reversed(made):
                obj.release()
    return out[:n, :GLSL_TYPES[decl.result_type(result)]].copy()
