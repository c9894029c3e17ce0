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

__internal__ = True  # the registry's and the runner's pieces: users call optics.shaders.check_glsl
__all__ = ["GLSL_TYPES", "Parameter", "Declaration", "Sampler", "GLSLError", "declarations", "find_function",
           "evaluate"]

GLSL_TYPES = {"float": 1, "vec2": 2, "vec3": 3, "vec4": 4, "sampler2D": 0}
"""The parameter and return types a checked function may use, with their component counts."""

_QUALIFIERS = {"in", "const", "highp", "mediump", "lowp", "precise"}
_WIDTH = 1024  # texels per row of the input and output textures
_WRAPPER_LINE = 1_000_000  # the #line of the generated main(): a message there is about the call, not the user


class GLSLError(ValueError):
    """The user's GLSL does not compile or link (the driver's message, with the source's line numbers),
    or a function cannot be called as asked."""


@dataclass(frozen=True)
class Parameter:
    """One declared parameter: its GLSL type, name and direction ("in", "out" or "inout")."""

    type: str
    name: str
    direction: str = "in"


@dataclass(frozen=True)
class Declaration:
    """A function defined in a GLSL source: return type, name, parameters, and the line it starts on."""

    returns: str
    name: str
    parameters: tuple
    line: int

    @property
    def types(self) -> tuple:
        """The parameter types, in order."""
        return tuple(p.type for p in self.parameters)

    def signature(self) -> str:
        """The declaration as GLSL: ``float fresnel(float cos_theta, float n1, float n2)``."""
        return f"{self.returns} {self.name}({', '.join(f'{p.type} {p.name}' for p in self.parameters)})"


@dataclass(frozen=True)
class Sampler:
    """A texture argument: ``data`` (h, w) or (h, w, c ≤ 4) float values, row 0 at v = 0;
    ``wrap`` "repeat" or "clamp"; ``filter`` "linear" or "nearest"."""

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


def _strip_comments(source: str) -> str:
    """The source with comments blanked out (newlines kept, so line numbers stay)."""
    def blank(match):
        return re.sub(r"[^\n]", " ", match.group(0))

    return re.sub(r"//[^\n]*|/\*.*?\*/", blank, source, flags=re.S)


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
    """Every function *defined* (with a body) in ``source``, in order (comments ignored)."""
    if not isinstance(source, str):
        raise TypeError(f"source must be GLSL text (str), got {describe(source)}")
    code = _strip_comments(source)
    found = []
    for m in _DEFINITION.finditer(code):
        returns, name, params = m.group(1), m.group(2), m.group(3)
        if returns in {"return", "else", "if", "while", "for", "switch"} or name in {"if", "while", "for", "switch"}:
            continue
        parameters = tuple(p for p in (_parameter(t) for t in params.split(",")) if p is not None)
        found.append(Declaration(returns, name, parameters, code.count("\n", 0, m.start(2)) + 1))
    return found


def find_function(source: str, function: str, types: tuple | None = None) -> Declaration:
    """The definition of ``function`` in ``source`` whose parameter types are ``types`` (any, if None).

    GLSLError when the function is not defined, or no overload takes ``types``."""
    if not isinstance(function, str):
        raise TypeError(f"function must be the name of a GLSL function (str), got {describe(function)}")
    if not re.fullmatch(r"[A-Za-z_]\w*", function):
        raise ValueError(f"function must be a GLSL identifier, got {function!r}")
    found = declarations(source)
    named = [d for d in found if d.name == function]
    if not named:
        defined = ", ".join(sorted({d.name for d in found})) or "none"
        raise GLSLError(f"function: {function!r} is not defined in the source (functions defined there: {defined})")
    if types is None:
        return named[0]
    for d in named:
        if d.types == tuple(types):
            outs = [p.name for p in d.parameters if p.direction != "in"]
            if outs:
                raise GLSLError(f"function: {d.signature()} has out/inout parameters ({', '.join(outs)}); only "
                                "in parameters can be checked: wrap it in a function that returns the value")
            if d.returns not in GLSL_TYPES or d.returns == "sampler2D":
                raise GLSLError(f"function: {d.signature()} returns {d.returns}; a checked function returns a "
                                "float or a vector")
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
_PACK = {"float": "vec4({}, 0.0, 0.0, 0.0)", "vec2": "vec4({}, 0.0, 0.0)", "vec3": "vec4({}, 0.0)", "vec4": "{}"}


def _fragment(source: str, decl: Declaration) -> str:
    body = re.sub(r"(?m)^[ \t]*#version[^\n]*", "", source)  # the wrapper says the version; lines stay
    head = ["#version 330"]
    args = []
    for i, p in enumerate(decl.parameters):
        head.append(f"uniform sampler2D wp_in{i};")
        if p.type == "sampler2D":
            args.append(f"wp_in{i}")
        else:
            args.append(f"texelFetch(wp_in{i}, wp_p, 0){_SWIZZLE[GLSL_TYPES[p.type]]}")
    head.append("out vec4 wp_result;")
    call = f"{decl.name}({', '.join(args)})"
    main = (f"#line {_WRAPPER_LINE}\nvoid main() {{\n    ivec2 wp_p = ivec2(gl_FragCoord.xy);\n"
            f"    wp_result = {_PACK[decl.returns].format(call)};\n}}\n")
    return "\n".join(head) + "\n#line 1\n" + body + "\n" + main


def _compile(ctx, source: str, decl: Declaration):
    import moderngl

    try:
        return ctx.program(vertex_shader=_VERTEX, fragment_shader=_fragment(source, decl))
    except moderngl.Error as exc:
        message = str(exc).strip()
        where = (f" (the error is in the call {decl.signature()} that the check makes)"
                 if re.search(rf"\b{_WRAPPER_LINE}\b", message) else "")
        raise GLSLError(f"source: the GLSL does not compile; the driver says, with your line numbers:\n"
                        f"{message}{where}") from None


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


def evaluate(source: str, decl: Declaration, arguments: list, uniforms: dict | None = None) -> np.ndarray:
    """Call ``decl`` from ``source`` once per row of the arguments; returns (n, components) float32.

    ``arguments``: one per parameter, in order: an (n, c) array for a float/vecN parameter
    (c its component count; all with the same n), or a :class:`Sampler` for a sampler2D.
    ``uniforms``: values for the user's own ``uniform`` declarations (name → number or
    tuple); a name the program does not use is refused by name.
    """
    import moderngl

    check_instance("arguments", arguments, (list, tuple))
    if len(arguments) != len(decl.parameters):
        raise GLSLError(f"{decl.signature()} takes {len(decl.parameters)} arguments, got {len(arguments)}")
    sizes = {np.shape(a)[0] for a in arguments if not isinstance(a, Sampler)}
    if len(sizes) != 1:
        raise ValueError(f"arguments must have one number of rows (at least one array argument), got {sorted(sizes)}")
    n = sizes.pop()
    rows = max(1, math.ceil(n / _WIDTH))
    ctx = _context()
    with ctx:
        program = _compile(ctx, source, decl)
        made = [program]
        try:
            for i, (p, a) in enumerate(zip(decl.parameters, arguments)):
                tex = _sampler(ctx, a) if isinstance(a, Sampler) else _texture(ctx, np.asarray(a, np.float32), rows)
                made.append(tex)
                tex.use(i)
                if f"wp_in{i}" in program:
                    program[f"wp_in{i}"].value = i
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
    return out[:n, :GLSL_TYPES[decl.returns]].copy()
