"""HLSL functions checked as written: translated by glslang and SPIRV-Cross, then run as GLSL.

Most real-time water is written in HLSL (Unity, Unreal, Crest). :func:`translate` compiles the
user's source with a generated entry point that calls the function, with glslang's HLSL front
end (``glslangValidator -D``, HLSL to SPIR-V, debug names kept and optimizations off so the
function keeps its name and its body), and turns the SPIR-V back into GLSL 3.30 with
SPIRV-Cross. The function then runs on the same headless context as a GLSL one. Both are
Debian packages (``glslang-tools``, ``spirv-cross``); when either is missing,
:class:`TranslatorMissing` says so (``wavephys check`` exits 3, as for a missing EGL).

What carries over: HLSL's intrinsics (``saturate``, ``lerp``, ``frac``, ``mul``, ``rsqrt`` …) as
glslang defines them; ``in``/``out``/``inout`` parameters; a ``Texture2D`` with its
``SamplerState`` as one texture argument; global variables as uniforms (``uniforms=`` by their
HLSL names). An engine macro or ``#include`` the source relies on but does not hold is named in
the error, with how to give it (``defines=``, ``include_dirs=``).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

from optics.shaders.glsl import Declaration, GLSLError, Parameter, declarations
from optics.shaders.source import Prepared, blank_function, check_defines, check_include_dirs, strip_comments

__internal__ = True  # the runner's pieces: users call optics.shaders.check_glsl(..., language="hlsl")
__all__ = ["TRANSLATOR_PACKAGES", "TranslatorMissing", "Translated", "translate", "hlsl_declaration"]

TRANSLATOR_PACKAGES = "glslang-tools spirv-cross"
"""Debian/Ubuntu packages that provide ``glslangValidator`` and ``spirv-cross``."""

_TYPES = {"float": "float", "half": "float", "min16float": "float", "double": "float", "bool": "bool",
          "Texture2D": "sampler2D", "sampler2D": "sampler2D"}
for _n in (2, 3, 4):
    for _base in ("float", "half", "min16float", "double"):
        _TYPES[f"{_base}{_n}"] = f"vec{_n}"
_WRAPPER_LINE = 1_000_000
_QUALIFIERS = {"in", "const", "uniform", "linear", "centroid", "nointerpolation", "noperspective", "sample",
               "precise", "static"}


class TranslatorMissing(RuntimeError):
    """glslangValidator or spirv-cross is not installed (HLSL cannot be translated)."""


@dataclass(frozen=True)
class Translated:
    """An HLSL function translated to GLSL.

    Attributes
    ----------
    prepared : Prepared
        The GLSL 3.30 source (language ``"hlsl"``).
    declaration : Declaration
        The function as the user wrote it (HLSL parameter names and order, GLSL types; a texture and its
        sampler are one ``sampler2D`` parameter under the texture's name).
    glsl : Declaration
        The translated function (parameters under the HLSL names, in the translated order).
    order : tuple of int
        For each value-taking parameter of ``glsl``, the index of the same parameter among
        ``declaration.inputs``.
    uniforms : dict
        HLSL global name → the uniform's name in the GLSL (``_Globals`` members become ``_N.name``).
    glsl_text : str
        What SPIRV-Cross wrote (for a report or a bug).
    """

    prepared: Prepared
    declaration: Declaration
    glsl: Declaration
    order: tuple
    uniforms: dict
    glsl_text: str = ""


def _tools():
    found = {name: shutil.which(name) for name in ("glslangValidator", "spirv-cross")}
    missing = [name for name, path in found.items() if path is None]
    if missing:
        raise TranslatorMissing(f"HLSL needs a translator: {' and '.join(missing)} not found. Install them: "
                                f"apt-get install {TRANSLATOR_PACKAGES}")
    return found["glslangValidator"], found["spirv-cross"]


def _hlsl_parameter(text: str):
    text = re.sub(r":\s*\w+\s*$", "", text.split("=")[0].strip())  # a semantic, a default value
    words = [w for w in re.split(r"\s+", text.strip()) if w]
    if not words or words == ["void"]:
        return None
    direction = "inout" if "inout" in words else "out" if "out" in words else "in"
    words = [w for w in words if w not in _QUALIFIERS | {"out", "inout"}]
    kind = re.sub(r"<.*>", "", words[0])
    return kind, re.sub(r"\[.*", "", words[-1] if len(words) > 1 else "_"), direction


def hlsl_declaration(source: str, function: str):
    """The HLSL function's parameters as (type, name, direction) and its return type, and the line it is on.

    GLSLError when it is not defined (the message lists the functions that are).

    Parameters
    ----------
    source : str
        HLSL source.
    function : str
        The function's name.

    Returns
    -------
    (str, list of tuple, int)
        The return type, the parameters, the line.
    """
    code = strip_comments(source)
    pattern = re.compile(r"(?m)(?:^|[;}\s])(\w+)\s+(\w+)\s*\(([^()]*)\)\s*(?::\s*\w+\s*)?\{")
    found = [(m.group(1), m.group(2), m.group(3), code.count("\n", 0, m.start(2)) + 1) for m in pattern.finditer(code)
             if m.group(1) not in {"return", "else", "if", "while", "for", "switch"}]
    named = [f for f in found if f[1] == function]
    if not named:
        defined = ", ".join(sorted({f[1] for f in found})) or "none"
        raise GLSLError(f"function: {function!r} is not defined in the source (functions defined there: {defined})")
    returns, _, params, line = named[0]
    parsed = [p for p in (_hlsl_parameter(t) for t in params.split(",")) if p is not None]
    return returns, parsed, line


def _entry(returns: str, params: list, function: str) -> str:
    """An entry point that calls the function once with values from the fragment position and uses its result."""
    swizzle = {"float": "wp_pos.x", "vec2": "wp_pos.xy", "vec3": "wp_pos.xyz", "vec4": "wp_pos",
               "bool": "(wp_pos.x > 0.0)"}
    globals_, locals_, args, uses = [], [], [], []
    for i, (kind, name, direction) in enumerate(params):
        glsl = _TYPES.get(kind)
        if kind == "SamplerState":
            globals_.append(f"SamplerState wp_smp{i};")
            args.append(f"wp_smp{i}")
            continue
        if glsl is None:
            raise GLSLError(f"function: its parameter {kind} {name} is of a type the checker cannot feed (it feeds "
                            f"float, float2–4, half…, bool, Texture2D with a SamplerState)")
        if glsl == "sampler2D":
            globals_.append(f"{kind} wp_tex{i};")
            args.append(f"wp_tex{i}")
        elif direction == "in":
            args.append(swizzle[glsl])
        else:
            locals_.append(f"{kind} wp_a{i} = ({kind})0;")
            args.append(f"wp_a{i}")
            uses.append((f"wp_a{i}", glsl))
    call = f"{function}({', '.join(args)})"
    if returns != "void":
        if _TYPES.get(returns) is None or _TYPES[returns] == "sampler2D":
            raise GLSLError(f"function: it returns {returns}; a checked function returns a float, a vector or a "
                            "bool, or writes one to an out parameter")
        locals_.append(f"{returns} wp_r = {call};")
        uses.append(("wp_r", _TYPES[returns]))
    else:
        locals_.append(call + ";")
    total = " + ".join(f"(float)({u})" if kind in ("float", "bool") else f"({u}).x" for u, kind in uses) or "0.0"
    return ("\n".join(globals_) + "\nfloat4 wp_entry(float4 wp_pos : SV_Position) : SV_Target\n{\n    "
            + "\n    ".join(locals_) + f"\n    return float4({total}, 0.0, 0.0, 0.0);\n}}\n")


def _glslang_error(stderr: str, source_name: str) -> GLSLError:
    lines = [ln for ln in stderr.splitlines() if ln.startswith("ERROR:") or "error at" in ln]
    text = "\n".join(lines) or stderr.strip()
    hints = []
    for include in re.findall(r"include directive for header name: (\S+)", stderr):
        hints.append(f"the source includes {include!r}, which the checker does not have: give the folder that holds "
                     f"it (include_dirs=[...], --include DIR), or paste what the function needs from it")
    for name in dict.fromkeys(re.findall(r"'(\w+)' : (?:unknown variable|undeclared identifier|no matching)", stderr)):
        if name in ("expression", "declaration"):
            continue
        hints.append(f"{name} is not defined in the source: an engine macro or built-in (Unity's, Unreal's …)? define "
                     f"it with defines={{'{name}': ...}} (--define {name}=VALUE), or paste its definition")
    if re.search(rf"\b{_WRAPPER_LINE}\b", stderr):
        hints.append("the error is in the call the checker generates: the function's parameters may be of a kind it "
                     "cannot feed")
    return GLSLError(f"source: the HLSL does not compile; glslang says, with your line numbers:\n{text}"
                     + "".join(f"\n{h}" for h in hints))


def _clean(glsl: str) -> str:
    """SPIRV-Cross's output without its version, extensions, outputs, entry point and main (lines kept)."""
    glsl = re.sub(r"(?m)^#version[^\n]*", "", glsl)
    glsl = re.sub(r"#ifdef GL_ARB_[^\n]*\n#extension[^\n]*\n#endif", lambda m: "\n" * m.group(0).count("\n"), glsl)
    glsl = re.sub(r"(?m)^\s*#extension[^\n]*", "", glsl)
    glsl = re.sub(r"(?m)^\s*layout\s*\(\s*location\s*=\s*\d+\s*\)\s*(in|out)\b[^\n]*", "", glsl)
    for name in ("main", "_wp_entry", "wp_entry"):
        glsl, _ = blank_function(glsl, name)
    return glsl


def _uniform_names(glsl: str) -> dict:
    """HLSL global → GLSL uniform: plain uniforms keep their names; members of a struct uniform (HLSL's
    ``$Globals`` block, emitted as a plain uniform struct) are ``instance.member``."""
    names = {}
    for struct, body in re.findall(r"struct\s+(\w+)\s*\{([^}]*)\};", glsl):
        instance = re.search(rf"\buniform\s+{struct}\s+(\w+)\s*;", glsl)
        if instance:
            for member in re.findall(r"\b\w+\s+(\w+)\s*(?:\[[^\]]*\])?\s*;", body):
                names[member] = f"{instance.group(1)}.{member}"
    for kind, name in re.findall(r"(?m)^\s*uniform\s+(\w+)\s+(\w+)\s*;", glsl):
        if not name.startswith("SPIRV_Cross_Combined") and kind not in {s for s, _ in
                                                                         re.findall(r"struct\s+(\w+)()", glsl)}:
            names.setdefault(name, name)
    return names


def translate(source: str, function: str, *, defines=None, include_dirs=(), name: str = "source.hlsl",
              timeout: float = 60.0) -> Translated:
    """Translate the HLSL ``function`` (and what it calls) in ``source`` to GLSL 3.30 (module doc).

    Parameters
    ----------
    source : str
        HLSL text defining ``function``.
    function : str
        The function's name.
    defines : dict or list of str, optional, keyword-only
        Macros the source relies on (``{"UNITY_PI": "3.14159265"}``), passed as ``-D``.
    include_dirs : sequence of path, optional, keyword-only
        Folders for ``#include``, passed as ``-I``.
    name : str, optional, keyword-only
        The file name errors give (default ``source.hlsl``).
    timeout : float, optional, keyword-only
        Seconds each tool may take.

    Returns
    -------
    Translated

    Raises
    ------
    TranslatorMissing
        glslangValidator or spirv-cross is not installed.
    GLSLError
        The HLSL does not compile (glslang's messages with the source's line numbers, and the missing macro
        or include named), or the function is not defined or has parameters the checker cannot feed.
    """
    glslang, cross = _tools()
    macros = check_defines(defines)
    include_dirs = check_include_dirs(include_dirs)
    returns, params, _ = hlsl_declaration(source, function)
    entry = _entry(returns, params, function)
    safe = re.sub(r"[^\w.-]", "_", Path(name).name) or "source.hlsl"
    with tempfile.TemporaryDirectory(prefix="wavephys-hlsl-") as tmp:
        src = Path(tmp) / safe
        src.write_text(source + f"\n#line {_WRAPPER_LINE}\n" + entry)
        spv = Path(tmp) / "out.spv"
        cmd = [glslang, "-D", "-V", "-S", "frag", "-e", "wp_entry", "-g", "-Od", "-o", str(spv)]
        cmd += [f"-D{k}={v}" for k, v in macros.items()] + [f"-I{Path(d).resolve()}" for d in include_dirs] + [safe]
        done = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, cwd=tmp)
        if done.returncode != 0 or not spv.is_file():
            raise _glslang_error(done.stdout + done.stderr, safe)
        out = subprocess.run([cross, "--version", "330", "--no-es", "--glsl-emit-ubo-as-plain-uniforms", str(spv)],
                             capture_output=True, text=True, timeout=timeout, cwd=tmp)
        if out.returncode != 0:
            raise GLSLError(f"source: SPIRV-Cross could not turn the translated HLSL into GLSL: {out.stderr.strip()}")
    glsl_text = out.stdout
    cleaned = _clean(glsl_text)
    glsl = next((d for d in declarations(cleaned) if d.name == function), None)
    if glsl is None:
        raise GLSLError(f"function: the translated GLSL lost {function!r} (SPIRV-Cross wrote: "
                        f"{', '.join(d.name for d in declarations(cleaned))})")
    return _mapped(cleaned, glsl, returns, params, glsl_text)


def _mapped(cleaned, glsl, returns, params, glsl_text) -> Translated:
    """The user's declaration (HLSL order) and the translated one with the HLSL names, and how they line up."""
    textures = [n for k, n, _ in params if _TYPES.get(k) == "sampler2D"]
    samplers = [n for k, n, _ in params if k == "SamplerState"]
    user = tuple(Parameter(_TYPES.get(k, k), n, d) for k, n, d in params if k != "SamplerState")
    directions = {p.name: p.direction for p in user}
    renamed = []
    for p in glsl.parameters:
        n = p.name
        if p.type == "sampler2D" and n not in directions:
            n = next((t for t in textures if n.startswith("SPIRV_Cross_Combined") and t in n), n)
        if n not in directions and n.lstrip("_") in directions:  # a GLSL keyword renamed (packed → _packed)
            n = n.lstrip("_")
        renamed.append(Parameter(p.type, n, directions.get(n, p.direction)))
    unknown = [p.name for p in renamed if p.name not in directions]
    if unknown or samplers and len(samplers) != len(textures):
        raise GLSLError(f"function: the translated parameters ({', '.join(p.name for p in glsl.parameters)}) do not "
                        f"line up with the HLSL ones ({', '.join(p.name for p in user)})")
    glsl = replace(glsl, parameters=tuple(renamed))
    declaration = Declaration(_TYPES.get(returns, returns), glsl.name, user, glsl.line)
    inputs = [p.name for p in declaration.inputs]
    order = tuple(inputs.index(p.name) for p in glsl.inputs)
    return Translated(Prepared(cleaned, "hlsl", ("HLSL translated by glslang and SPIRV-Cross",)), declaration, glsl,
                      order, _uniform_names(cleaned), glsl_text)
