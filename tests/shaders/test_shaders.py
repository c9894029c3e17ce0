"""Shader checks (optics.shaders): a corpus of engine-style GLSL, correct and broken, gets the right
verdict and cause from Python, the pytest fixture and the command; bad calls are refused by name."""

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shader_corpus import CORPUS, LEARNOPENGL_SCHLICK
from truth import is_correct

pytest.importorskip("moderngl")


@pytest.fixture(scope="module")
def shaders():
    from optics.gpu import RendererUnavailable

    import optics.shaders

    try:
        optics.shaders.check_glsl("float f(float c){ return c; }", "f", "fresnel", takes=("cos_theta",),
                                  sides="above", samples=16)
    except RendererUnavailable as exc:  # pragma: no cover - CI installs EGL
        pytest.skip(str(exc))
    return optics.shaders


IDS = [entry.name for entry in CORPUS]


@pytest.mark.parametrize("entry", CORPUS, ids=IDS)
def test_corpus_from_python(shaders, entry):
    """Each function gets the verdict its numpy transcription earns against the physics (decided without the
    checker), and a faulty one the cause written beside it."""
    report = shaders.check_glsl(entry.source, entry.function, entry.against, **entry.options)
    truth = is_correct(entry, report)
    assert truth is entry.ok, f"the corpus label is wrong: {entry.name}"
    assert report.ok is truth, report.report()
    assert entry.cause in report.cause, report.report()
    if entry.ok:
        assert report.error <= report.tolerance and report.cause == ""
    else:
        assert not report.error <= report.tolerance  # NaN counts as failed
        assert "likely cause" in report.report()


def test_the_corpus_covers_every_check_language_and_fault(shaders):
    verdicts = {}
    for e in CORPUS:
        verdicts.setdefault(e.against, set()).add(e.ok)
    assert verdicts == {name: {True, False} for name in shaders.SHADER_CHECKS}
    languages = {e.options.get("language", "glsl") for e in CORPUS} | {
        "godot" for e in CORPUS if "shader_type" in e.source} | {"webgl" for e in CORPUS if "mainImage" in e.source}
    assert {"glsl", "hlsl", "godot"} <= languages
    assert len({(e.source, e.function) for e in CORPUS}) >= 40 and len({e.cause for e in CORPUS if e.cause}) >= 30


@pytest.mark.parametrize("entry", CORPUS[::2], ids=IDS[::2])
def test_corpus_from_the_fixture(shaders, wavephys_check, entry):
    if entry.ok:
        assert wavephys_check.glsl(entry.source, entry.function, entry.against, **entry.options).ok
    else:
        with pytest.raises(AssertionError, match="likely cause") as info:
            wavephys_check.glsl(entry.source, entry.function, entry.against, **entry.options)
        assert entry.cause in str(info.value), entry.name


def _argv(tmp_path, entry):
    options = dict(entry.options)
    takes, uniforms = options.pop("takes", None), options.pop("uniforms", None)
    language, defines = options.pop("language", None), options.pop("defines", None)
    path = tmp_path / (entry.function + (".hlsl" if language == "hlsl" else ".glsl"))
    path.write_text(entry.source)
    argv = ["check", "--hlsl" if language == "hlsl" else "--glsl", str(path), "--function", entry.function,
            "--against", entry.against]
    if takes:
        argv += ["--takes", ",".join(map(str, takes))]
    for key, value in (uniforms or {}).items():
        argv += ["--uniform", f"{key}={value}"]
    for key, value in (defines or {}).items():
        argv += ["--define", f"{key}={value}"]
    for key, value in options.items():
        text = ",".join(map(str, value)) + ("," if len(value) == 1 else "") if isinstance(value, tuple) else value
        argv += ["--option", f"{key}={text}"]
    return argv


@pytest.mark.parametrize("entry", CORPUS[1::2], ids=IDS[1::2])
def test_corpus_from_the_command(shaders, tmp_path, capsys, entry):
    from wavephys.app.cli import main

    code = main(_argv(tmp_path, entry))
    out = capsys.readouterr().out
    assert code == (0 if entry.ok else 1), (entry.name, out)
    assert entry.cause in out, (entry.name, out)


def test_command_writes_json_and_chart(shaders, tmp_path, capsys):
    from PIL import Image

    from wavephys.app.cli import main

    src = tmp_path / "f.glsl"
    src.write_text(LEARNOPENGL_SCHLICK)
    code = main(["check", "--glsl", str(src), "--function", "fresnelSchlick", "--against", "fresnel",
                 "--option", "sides=above,below", "--json", str(tmp_path / "r.json"), "--chart",
                 str(tmp_path / "r.png")])
    assert code == 1  # asked to, from below too: no TIR
    data = json.loads((tmp_path / "r.json").read_text())
    assert data["ok"] is False and "below: no total internal reflection" in data["cause"]
    assert data["cause"].startswith("above: right (Schlick's approximation, F0 = 0.0203")
    assert data["worst"]["side"] == "below" and data["worst"]["theta_deg"] > 48.6
    assert Image.open(tmp_path / "r.png").size[0] > 300
    assert sorted(p.name for p in tmp_path.iterdir()) == ["f.glsl", "r.json", "r.png"]  # no partial files


def test_command_usage_errors(shaders, tmp_path, capsys):
    from wavephys.app.cli import main

    src = tmp_path / "f.glsl"
    src.write_text("float f(float c) {\n    return c +;\n}\n")
    assert main(["check", "--glsl", str(src), "--function", "f", "--against", "fresnel", "--takes", "cos_theta"]) == 2
    err = capsys.readouterr().err
    assert "does not compile" in err and "0:2(" in err  # the driver's message with the user's line number
    for argv, words in [
        (["check", "--glsl", str(tmp_path / "missing.glsl"), "--function", "f", "--against", "fresnel"], "no file"),
        (["check", "--function", "f", "--against", "fresnel"], "or --glsl FILE (or --hlsl, --shader)"),
        (["check", "--glsl", str(src), "--hlsl", str(src), "--function", "f", "--against", "fresnel"],
         "not --glsl and --hlsl"),
        (["check", "--glsl", str(src), "--function", "f", "--against", "fresnel", "--include", str(tmp_path / "no")],
         "--include"),
        (["check", "--glsl", str(src), "--function", "f", "--against", "fresnel", "--option", "nonsense"],
         "KEY=VALUE"),
        (["check", "--glsl", str(src), "--function", "f", "--against", "colour"], "against must be one of"),
        (["check", "--glsl", str(src), "--function", "f", "--against", "fresnel", "--json", str(tmp_path / "x.txt")],
         "--json"),
    ]:
        with pytest.raises(SystemExit) as exit_info:
            main(argv)
        assert exit_info.value.code == 2
        assert words in capsys.readouterr().err


def test_list_names_every_check(shaders, capsys):
    from wavephys.app.cli import main

    assert main(["check", "--list"]) == 0
    out = capsys.readouterr().out
    for name in shaders.SHADER_CHECKS:
        assert f"{name}:" in out


def test_library_glsl_passes_its_own_checks(shaders):
    """The renderer's and the GL caustics' shared GLSL (optics.gpu) meets the physics."""
    from optics.gpu import GLSL_FRESNEL_FORMS, GLSL_OPTICS

    fresnel = shaders.check_glsl(GLSL_OPTICS, "fresnel_exact", "fresnel")
    refract = shaders.check_glsl(GLSL_OPTICS, "refract_dir", "refract", tir="zero")
    assert fresnel.ok and refract.ok, fresnel.report() + "\n" + refract.report()
    # every shader form the renderer can draw for a plan (generated from the family's registry), each
    # against its own float64 form
    assert GLSL_FRESNEL_FORMS[0] == "exact" and len(GLSL_FRESNEL_FORMS) >= 5
    for form in GLSL_FRESNEL_FORMS[1:]:
        report = shaders.check_glsl(GLSL_OPTICS, f"fresnel_{form}", "fresnel", form=form)
        assert report.ok, report.report()


def test_a_new_fresnel_form_is_one_function_and_its_glsl_beside_it(shaders):
    """A throwaway Fresnel method registered with its GLSL (one decorator, one registry entry) is generated
    into the family's GLSL: its own function and the switch's next index, which a shader compiles and calls."""
    from optics.light.fresnel import N_AIR, N_WATER, REFLECTANCE_METHODS, reflectance_exact
    from optics.shaders.glsl import evaluate, find_function
    from wavephys.core.methods import Methods, glsl_family, shader_form

    @shader_form("fresnel_half", "float fresnel_half(float cos_i, float n1, float n2) "
                                 "{ return 0.5 * fresnel_exact(cos_i, n1, n2); }")
    def reflectance_half(cos_theta, n1=N_AIR, n2=N_WATER):
        return 0.5 * reflectance_exact(cos_theta, n1, n2)

    family = Methods("Fresnel reflectance", **dict(REFLECTANCE_METHODS), half=reflectance_half,
                     plain=lambda cos_theta, n1=N_AIR, n2=N_WATER: cos_theta)  # no shader form: no index
    glsl = glsl_family(family, "fresnel_form", "float cos_i, float n1, float n2", "cos_i, n1, n2")
    index = len(REFLECTANCE_METHODS)
    assert list(family.glsl_forms) == list(REFLECTANCE_METHODS) + ["half"]
    assert f"if (form == {index}) return fresnel_half(cos_i, n1, n2);" in glsl and "plain" not in glsl
    source = glsl + f"float picked(float cos_i, float n1, float n2) {{ return fresnel_form({index}, cos_i, n1, n2); }}\n"
    c = np.linspace(0.0, 1.0, 33, dtype=np.float32)[:, None]
    n1, n2 = np.full_like(c, N_AIR), np.full_like(c, N_WATER)
    got = evaluate(source, find_function(source, "picked"), [c, n1, n2])[:, 0]
    np.testing.assert_allclose(got, reflectance_half(c[:, 0].astype(np.float64)), atol=2e-6)
    with pytest.raises(ValueError, match="no method has a shader form"):
        glsl_family(Methods("q", plain=lambda x: x), "f", "float x", "x")
    with pytest.raises(TypeError, match="name"):
        shader_form(3, "float f() { return 1.0; }")
    with pytest.raises(ValueError, match="source must define g"):
        shader_form("g", "float f() { return 1.0; }")


@pytest.mark.parametrize("source,function,kwargs,error,words", [
    ("float f(float c) { return c; }", "g", dict(takes=("cos_theta",)), "GLSLError", "'g' is not defined"),
    ("float f(vec3 v, vec3 n) { return v.x; }", "f", dict(takes=("cos_theta", "n1", "n2")), "GLSLError",
     "does not take (float, float, float)"),
    ("float f(float q, float zz) { return q; }", "f", {}, "GLSLError", "cannot tell what float q"),
    ("float f(float cosTheta, float cosine) { return cosTheta; }", "f", {}, "GLSLError", "two parameters read as"),
    ("vec4 f(float c, float a, float b) { return vec4(c); }", "f", {}, "GLSLError", "gives vec4"),
    ("float f(float c, float a, float b) { return c; }", "f", dict(returns="vec3"), "GLSLError", "not vec3"),
    ("float f(float c) { return c; }", "f", dict(takes=("colour",)), "ValueError", "roles"),
    ("float f(float c) { return c; }", "f", dict(takes=("cos_theta",), samplez=8), "TypeError", "options"),
    ("float f(float c) { return c; }", "f", dict(takes=("cos_theta",), uniforms={"uX": 1.0}), "GLSLError",
     "'uX' is not a uniform"),
    ("void f(float c, out float r, out float s) { r = c; s = c; }", "f", {}, "GLSLError", "result='r'"),
    ("void f(float c, out float r) { r = c; }", "f", dict(result="q"), "GLSLError", "has no result 'q'"),
    ("void g(out float r) { r = 1.0; }\nfloat f(float c) { float r; g(r); return c * r; }", "f",
     dict(takes=("cos_theta",), sides="above", form="loviscach"), None, ""),  # out helpers are fine
    ("void f(float c) { }", "f", dict(takes=("cos_theta",)), "GLSLError", "no out parameter"),
    ("float f(float c) { return c; }", "f", dict(takes=("cos_theta",), tolerance=-1.0), "ValueError", "tolerance"),
    ("float f(float c) { return c; }", "f", dict(language="cuda"), "ValueError", "language must be one of"),
    ("float f(float c) { return UNITY_F0 + c; }", "f", {}, "GLSLError", "defines={'UNITY_F0'"),
    ('#include "UnityCG.cginc"\nfloat f(float c) { return c; }', "f", {}, "GLSLError", "includes 'UnityCG.cginc'"),
    (42, "f", {}, "TypeError", "source"),
    ("float f(float c) { return c; }", "f(", {}, "ValueError", "identifier"),
])
def test_bad_calls_are_refused_by_name(shaders, source, function, kwargs, error, words):
    if error is None:  # a valid call beside the invalid ones
        shaders.check_glsl(source, function, "fresnel", **kwargs)
        return
    exc = {"GLSLError": shaders.GLSLError, "ValueError": ValueError, "TypeError": TypeError}[error]
    with pytest.raises(exc, match=None) as info:
        shaders.check_glsl(source, function, "fresnel", **kwargs)
    assert words in str(info.value)


def test_against_is_checked(shaders):
    with pytest.raises(ValueError, match="against must be one of"):
        shaders.check_glsl("float f(float c) { return c; }", "f", "fresnell")
    with pytest.raises(TypeError, match="against"):
        shaders.check_glsl("float f(float c) { return c; }", "f", None)


def test_nan_output_is_a_failure_not_a_pass(shaders):
    r = shaders.check_glsl("float f(float c) { return sqrt(c - 2.0); }", "f", "fresnel", takes=("cos_theta",),
                           sides="above")
    assert not r.ok and math.isnan(r.error) and "NaN" in r.cause
    assert r.as_dict()["error"] is None and not r.as_check().ok


@settings(max_examples=6, deadline=None, derandomize=True)
@given(index=st.floats(1.15, 2.4))
def test_wrong_f0_names_the_index_it_belongs_to(shaders, index):
    """Schlick written for another material: the cause names f0 and the index it comes from."""
    f0 = ((index - 1.0) / (index + 1.0)) ** 2
    if abs(index - 1.333) < 0.05:
        return
    src = f"float s(float c) {{ float f0 = {f0:.8f}; return f0 + (1.0 - f0) * pow(1.0 - c, 5.0); }}"
    r = shaders.check_glsl(src, "s", "fresnel", takes=("cos_theta",), form="schlick", sides="above")
    assert not r.ok and "F0 from the wrong indices" in r.cause
    implied = float(r.cause.split("f0 of an index ")[1].split()[0])
    assert implied == pytest.approx(index, rel=2e-3)


@settings(max_examples=6, deadline=None, derandomize=True)
@given(scale=st.floats(1.05, 6.0))
def test_scaled_path_is_measured(shaders, scale):
    """A Beer–Lambert with an extra factor on the path: the cause gives the factor."""
    if abs(scale - 2.0) < 0.01:
        return
    src = f"vec3 t(float d, vec3 a) {{ return exp(-a * d * {scale:.6f}); }}"
    r = shaders.check_glsl(src, "t", "transmittance")
    assert not r.ok and "scaled by" in r.cause
    assert float(r.cause.split("scaled by ")[1].split(":")[0]) == pytest.approx(scale, rel=1e-3)


@settings(max_examples=5, deadline=None, derandomize=True)
@given(seed=st.integers(0, 10_000), slope=st.floats(0.05, 0.6))
def test_central_differences_pass_on_generated_surfaces(shaders, seed, slope):
    """The verdict on a correct function holds on surfaces the test draws, not only the default one."""
    from shader_corpus import HEIGHT_CENTRAL, HEIGHT_ONE_SIDED

    good = shaders.check_glsl(HEIGHT_CENTRAL, "heightNormal", "height_normal", seed=seed, max_slope=slope, n=64)
    assert good.ok, good.report()
    if slope > 0.3:  # one-sided differences err by about half a texel's slope change
        bad = shaders.check_glsl(HEIGHT_ONE_SIDED, "heightForward", "height_normal", seed=seed, max_slope=slope, n=64)
        assert not bad.ok and "one-sided" in bad.cause


def test_reference_is_evaluated_at_the_shaders_float32_inputs(shaders):
    """Rounding the inputs to float32 is not counted against the function: the exact GLSL Fresnel
    errs by float32 arithmetic only (a few 1e-6 at most, near the critical angle)."""
    from shader_corpus import PBRT_DIELECTRIC

    r = shaders.check_glsl(PBRT_DIELECTRIC, "frDielectric", "fresnel", samples=8192)
    assert r.ok and r.error < 5e-5


def test_report_is_plain_data(shaders):
    r = shaders.check_glsl("float f(float c) { return 0.0204 + 0.9796 * pow(1.0 - c, 5.0); }", "f", "fresnel",
                           takes=("cos_theta",), form="schlick", sides="above")
    d = json.loads(json.dumps(r.as_dict()))
    assert d["against"] == "fresnel" and d["takes"] == ["cos_theta"] and isinstance(d["samples"], int)
    assert "llvmpipe" in d["renderer"] or d["renderer"]
    assert np.isfinite(d["error"]) and d["seconds"] > 0


def test_chart_leaves_the_matplotlib_backend_alone(shaders, tmp_path):
    """A notebook keeps its inline backend: the chart is drawn without pyplot."""
    import subprocess
    import sys

    code = ("import matplotlib, sys; before = matplotlib.get_backend()\n"
            "def refuse(*a, **k):\n    raise AssertionError('matplotlib.use called')\n"
            "matplotlib.use = refuse\n"
            "from optics.shaders import check_glsl\n"
            "check_glsl('float f(float c) { return 0.0204 + 0.9796 * pow(1.0 - c, 5.0); }', 'f', 'fresnel', "
            f"takes=('cos_theta',), form='schlick', sides='above', chart={str(tmp_path / 'c.png')!r})\n"
            "print(matplotlib.get_backend() == before)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.split() == ["True"]
    assert (tmp_path / "c.png").stat().st_size > 1000
