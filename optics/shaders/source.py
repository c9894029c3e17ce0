"""A user's shader source as shipped, made into GLSL 3.30 that the checker can compile.

Real water shaders come as desktop GLSL, GLSL ES 3.00 and WebGL (GLSL ES 1.00), Shadertoy
snippets, Godot shader files and HLSL (Unity, Unreal, Crest). :func:`prepare` turns the first
four into GLSL 3.30 with every line where it was, so the driver's messages carry the user's own
line numbers; HLSL goes through a real translator first (:mod:`optics.shaders.hlsl`). What it
changes, and nothing else:

* ``#version`` lines are dropped (the checker says 330); ``precision`` statements and precision
  qualifiers stay (3.30 accepts them; they are evaluated at full float32 here, where a phone
  evaluates ``mediump`` at 16 bits);
* GLSL ES 1.00's ``texture2D``/``textureCube``/``…Lod`` become ``texture``/``textureLod``;
  ``varying``/``attribute`` globals become plain globals;
* a program's ``main`` (and Godot's ``vertex``, ``fragment``, ``light`` … processor functions)
  are blanked: they are entry points, not functions to check, and read outputs 3.30 lacks;
* ``gl_FrontFacing`` in a function becomes a variable the checker sets from the side the ray
  comes from (the role ``front_facing``);
* Godot: the ``shader_type``, ``render_mode`` and ``group_uniforms`` lines go, uniform hints
  (``: hint_range(0, 1)``, ``: source_color`` …) and ``global``/``instance`` go, and ``PI``,
  ``TAU``, ``E`` and the common built-ins a helper may read (``TIME`` …) are declared;
* Shadertoy's inputs (``iTime``, ``iResolution``, ``iChannel0`` …) are declared where used;
* ``#include`` is resolved from ``include_dirs`` when given, and otherwise named in the error.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from wavephys.core.inputs import describe

__internal__ = True  # the runner's pieces: users call optics.shaders.check_glsl
__all__ = ["GLSLError", "LANGUAGES", "Prepared", "prepare", "check_include_dirs", "strip_comments", "blank_function", "function_span",
           "detect_language", "check_defines"]

LANGUAGES = ("auto", "glsl", "glsl_es", "webgl", "godot", "shadertoy", "hlsl")
"""Source languages :func:`optics.shaders.check_glsl` reads (``auto``: told from the text)."""

FRONT_FACING = "wp_front_facing"
"""The variable that stands for ``gl_FrontFacing`` in a checked function."""

_GODOT_PROCESSORS = ("vertex", "fragment", "light", "start", "process", "sky", "fog")
_GODOT_BUILTINS = {  # what a helper function may read, declared as uniforms (set by uniforms=)
    "TIME": "float", "VIEW_MATRIX": "mat4", "INV_VIEW_MATRIX": "mat4", "PROJECTION_MATRIX": "mat4",
    "INV_PROJECTION_MATRIX": "mat4", "MODEL_MATRIX": "mat4", "CAMERA_POSITION_WORLD": "vec3",
    "CAMERA_DIRECTION_WORLD": "vec3", "VIEWPORT_SIZE": "vec2",
}
_GODOT_CONSTANTS = {"PI": "3.14159265358979", "TAU": "6.28318530717959", "E": "2.71828182845905"}
_SHADERTOY = {"iTime": "float", "iTimeDelta": "float", "iFrame": "int", "iFrameRate": "float",
              "iResolution": "vec3", "iMouse": "vec4", "iDate": "vec4", "iChannel0": "sampler2D",
              "iChannel1": "sampler2D", "iChannel2": "sampler2D", "iChannel3": "sampler2D"}
_ES_RENAMES = {"texture2D": "texture", "textureCube": "texture", "texture2DLod": "textureLod",
               "textureCubeLod": "textureLod", "texture2DProj": "textureProj", "texture2DLodEXT": "textureLod",
               "textureCubeLodEXT": "textureLod", "texture2DGradEXT": "textureGrad", "shadow2D": "texture"}


class GLSLError(ValueError):
    """The user's shader does not compile or link (the driver's or translator's message, with the source's line
    numbers), or a function cannot be called as asked."""


@dataclass(frozen=True)
class Prepared:
    """A source ready to compile: GLSL 3.30 text with the user's lines in place.

    Attributes
    ----------
    text : str
        The GLSL (no ``#version`` line: the checker adds it).
    language : str
        The language it was read as (:data:`LANGUAGES`).
    notes : tuple of str
        What was changed, in words (shown in the report's domain note when not empty).
    front_facing : bool
        Whether the source reads ``gl_FrontFacing`` (now :data:`FRONT_FACING`).
    header : str
        Declarations the checker puts before the user's first line (macros, built-ins).
    original : str
        The source as given (for error messages).
    """

    text: str
    language: str
    notes: tuple = ()
    front_facing: bool = False
    header: str = ""
    original: str = field(default="", repr=False)


def strip_comments(source: str) -> str:
    """The source with comments blanked out (newlines kept, so line numbers stay).

    Parameters
    ----------
    source : str

    Returns
    -------
    str
    """
    def blank(match):
        return re.sub(r"[^\n]", " ", match.group(0))

    return re.sub(r"//[^\n]*|/\*.*?\*/", blank, source, flags=re.S)


def _blank(text: str, start: int, end: int) -> str:
    return text[:start] + re.sub(r"[^\n]", " ", text[start:end]) + text[end:]


def function_span(code: str, name: str):
    """(start, end) of every definition of function ``name`` (header to closing brace) in comment-free code.

    Parameters
    ----------
    code : str
        Source without comments.
    name : str
        The function's name.

    Returns
    -------
    list of (int, int)
    """
    spans = []
    for m in re.finditer(rf"(?m)(?:^|[;}}\s])(\w+)\s+{re.escape(name)}\s*\(([^()]*)\)\s*\{{", code):
        depth, i = 0, m.end() - 1
        while i < len(code):
            depth += {"{": 1, "}": -1}.get(code[i], 0)
            if depth == 0:
                break
            i += 1
        spans.append((m.start(1), i + 1))
    return spans


def blank_function(code: str, name: str) -> tuple:
    """``code`` with every definition of ``name`` blanked (lines kept); and how many there were.

    Parameters
    ----------
    code : str
        Source without comments.
    name : str
        The function's name.

    Returns
    -------
    (str, int)
    """
    spans = function_span(code, name)
    for start, end in reversed(spans):
        code = _blank(code, start, end)
    return code, len(spans)


_HLSL_MARKERS = re.compile(r"\b(float[234](x[234])?|half[234]?|min16float[234]?|saturate|lerp|frac|SV_\w+|cbuffer|"
                           r"Texture2D|SamplerState|tex2D|mul)\b")
_GLSL_MARKERS = re.compile(r"\b(vec[234]|mat[234]|sampler2D|texture2D|mix|fract|uniform)\b")


def detect_language(source: str) -> str:
    """The language of a source, told from its text: ``godot`` (a ``shader_type`` line), ``hlsl`` (HLSL's
    types and intrinsics and no GLSL ones), ``webgl`` (``#version 100`` or ``texture2D``), ``glsl_es``
    (``#version 300 es``), ``shadertoy`` (a ``mainImage`` function), else ``glsl``.

    Parameters
    ----------
    source : str

    Returns
    -------
    str
    """
    code = strip_comments(source)
    if re.search(r"(?m)^\s*shader_type\s+\w+\s*;", code):
        return "godot"
    if _HLSL_MARKERS.search(code) and not _GLSL_MARKERS.search(code):
        return "hlsl"
    if re.search(r"(?m)^\s*#\s*version\s+100\b", code) or re.search(r"\btexture2D\b|\bgl_FragColor\b", code):
        return "webgl"
    if re.search(r"(?m)^\s*#\s*version\s+\d+\s+es\b", code):
        return "glsl_es"
    if re.search(r"\bmainImage\s*\(", code):
        return "shadertoy"
    return "glsl"


def check_defines(defines) -> dict:
    """``defines`` (name → value, or an iterable of ``NAME`` / ``NAME=VALUE``) as a dict of strings.

    Parameters
    ----------
    defines : dict or iterable of str or None

    Returns
    -------
    dict of str to str
    """
    if defines is None:
        return {}
    if isinstance(defines, dict):
        items = defines.items()
    elif isinstance(defines, (list, tuple)):
        items = []
        for d in defines:
            if not isinstance(d, str):
                raise TypeError(f"defines must be a dict or NAME=VALUE strings, got {describe(d)} in it")
            name, _, value = d.partition("=")
            items.append((name.strip(), value.strip() or "1"))
    else:
        raise TypeError(f"defines must be a dict (name → value) or a list of NAME=VALUE, got {describe(defines)}")
    out = {}
    for name, value in items:
        if not isinstance(name, str) or not re.fullmatch(r"[A-Za-z_]\w*", name):
            raise ValueError(f"defines: {name!r} is not a macro name")
        out[name] = str(value)
    return out


def check_include_dirs(include_dirs) -> tuple:
    """``include_dirs`` as a tuple of folders: one path, or a sequence of them, each an existing folder.

    Parameters
    ----------
    include_dirs : path or sequence of paths

    Returns
    -------
    tuple
    """
    import os

    if isinstance(include_dirs, (str, os.PathLike)):
        include_dirs = (include_dirs,)
    if not isinstance(include_dirs, (tuple, list)) or not all(isinstance(d, (str, os.PathLike))
                                                              for d in include_dirs):
        raise TypeError(f"include_dirs must be a folder or a list of folders, got {describe(include_dirs)}")
    missing = [str(d) for d in include_dirs if not Path(d).is_dir()]
    if missing:
        raise ValueError(f"include_dirs: {', '.join(missing)} is not a folder")
    return tuple(include_dirs)


def _includes(source: str, include_dirs) -> str:
    """``#include "file"`` lines resolved from ``include_dirs`` (each file marked with #line), or a clear error."""
    lines = source.split("\n")
    out = []
    for i, line in enumerate(lines):
        m = re.match(r'\s*#\s*include\s+[<"]([^">]+)[">]', line)
        if not m:
            out.append(line)
            continue
        name = m.group(1)
        found = next((Path(d) / name for d in include_dirs if (Path(d) / name).is_file()), None)
        if found is None:
            where = f" (looked in {', '.join(str(d) for d in include_dirs)})" if include_dirs else ""
            raise _include_error(name, i + 1, where)
        out.append(f"#line 1 {len(out) + 1}\n" + found.read_text() + f"\n#line {i + 2} 0")
    return "\n".join(out)


def _include_error(name, line, where):
    return GLSLError(f"source: line {line} includes {name!r}, which the checker does not have{where}: give the "
                     f"folder that holds it (include_dirs=[...], --include DIR), or paste what the function needs "
                     f"from it into the source")


def _declare_used(code: str, table: dict, skip: str = "") -> list:
    """Uniform declarations for the names of ``table`` the code reads but does not declare."""
    out = []
    for name, kind in table.items():
        if re.search(rf"\b{name}\b", code) and not re.search(rf"\b\w+\s+{name}\s*[;=\[]", code):
            out.append(f"uniform {kind} {name};")
    return out


def _godot(code: str, notes: list, header: list) -> str:
    for pattern, what in ((r"(?m)^[ \t]*shader_type\b[^;]*;", "shader_type"),
                          (r"(?m)^[ \t]*render_mode\b[^;]*;", "render_mode"),
                          (r"(?m)^[ \t]*group_uniforms\b[^;]*;", None)):
        for m in reversed(list(re.finditer(pattern, code))):
            code = _blank(code, m.start(), m.end())
    # uniform hints: `uniform vec4 c : source_color = vec4(1.0);` → `uniform vec4 c = vec4(1.0);`
    code = re.sub(r"(?m)\b(global|instance)(\s+uniform\b)", lambda m: " " * len(m.group(1)) + m.group(2), code)
    code = re.sub(r"(\buniform\s+\w+\s+\w+(?:\s*\[\s*\d*\s*\])?)\s*:\s*[^=;]*", lambda m: m.group(1) + " " * (
        len(m.group(0)) - len(m.group(1))), code)
    blanked = []
    for name in _GODOT_PROCESSORS:
        code, count = blank_function(code, name)
        if count:
            blanked.append(f"{name}()")
    if blanked:
        notes.append(f"Godot: its processor functions {', '.join(blanked)} are not compiled")
    for name, value in _GODOT_CONSTANTS.items():
        if re.search(rf"\b{name}\b", code) and not re.search(rf"#\s*define\s+{name}\b|\b\w+\s+{name}\s*=", code):
            header.append(f"#define {name} {value}")
    header += _declare_used(code, _GODOT_BUILTINS)
    return code


def prepare(source: str, language: str = "auto", *, defines=None, include_dirs=()) -> Prepared:
    """Make a GLSL, GLSL ES, WebGL, Shadertoy or Godot source compilable as GLSL 3.30 (module doc).

    Parameters
    ----------
    source : str
        The shader source as shipped.
    language : str, optional
        One of :data:`LANGUAGES` but ``hlsl`` (translated first, :func:`optics.shaders.hlsl.translate`);
        ``auto`` (default) tells it from the text (:func:`detect_language`).
    defines : dict or list of str, optional, keyword-only
        Macros to define before the source (an engine's ``#define``s that a snippet relies on).
    include_dirs : sequence of path, optional, keyword-only
        Folders to resolve ``#include`` lines from.

    Returns
    -------
    Prepared
        The text, the language read, what was changed, whether ``gl_FrontFacing`` is read.

    Raises
    ------
    GLSLError
        When an ``#include`` cannot be resolved.
    """
    if not isinstance(source, str):
        raise TypeError(f"source must be shader text (str), got {describe(source)}")
    if not isinstance(language, str) or language not in LANGUAGES:
        raise ValueError(f"language must be one of {LANGUAGES}, got {language!r}")
    defines = check_defines(defines)
    include_dirs = check_include_dirs(include_dirs)
    read_as = detect_language(source) if language == "auto" else language
    notes, header = [], [f"#define {k} {v}" for k, v in defines.items()]
    text = strip_comments(source)
    text = re.sub(r"(?m)^[ \t]*#\s*version[^\n]*", "", text)
    if re.search(r"(?m)^\s*#\s*include\b", text):
        text = _includes(text, tuple(include_dirs))
    if read_as == "godot":
        text = _godot(text, notes, header)
    renamed = [old for old in _ES_RENAMES if re.search(rf"\b{old}\b", text)
               and not re.search(rf"#\s*define\s+{old}\b|\b\w+\s+{old}\s*\(", text)]
    header += [f"#define {old} {_ES_RENAMES[old]}" for old in renamed]
    if renamed:
        notes.append(f"GLSL ES 1.00 names read as 3.30's: {', '.join(renamed)}")
    for m in reversed(list(re.finditer(r"(?m)^([ \t]*)(?:(?:flat|smooth|noperspective|highp|mediump|lowp)\s+)*"
                                       r"(varying|attribute)\b", text))):
        word = m.group(2)
        start = m.start(2)
        text = text[:start] + " " * len(word) + text[start + len(word):]
    text, mains = blank_function(text, "main")
    if mains:
        notes.append("the program's main() is not compiled (the checker calls the function itself)")
    if read_as == "shadertoy" or re.search(r"\bmainImage\s*\(", text):
        header += _declare_used(text, _SHADERTOY)
    front_facing = bool(re.search(r"\bgl_FrontFacing\b", text))
    if front_facing:
        text = re.sub(r"\bgl_FrontFacing\b", FRONT_FACING, text)
    return Prepared(text, read_as, tuple(notes), front_facing, "\n".join(header), source)
