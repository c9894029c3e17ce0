"""Shader checks (optics.shaders): a corpus of engine-style GLSL, correct and broken, gets the right
verdict and cause from Python, the pytest fixture and the command; bad calls are refused by name."""

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from shader_corpus import CORPUS, SCHLICK_F0

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


def _split(options):
    options = dict(options)
    return options.pop("takes", None), options.pop("uniforms", None), options


IDS = [entry[0] for entry in CORPUS]


@pytest.mark.parametrize("name,against,source,function,options,ok,cause", CORPUS, ids=IDS)
def test_corpus_from_python(shaders, name, against, source, function, options, ok, cause):
    takes, uniforms, opts = _split(options)
    report = shaders.check_glsl(source, function, against, takes=takes, uniforms=uniforms, **opts)
    assert report.ok is ok, report.report()
    assert cause in report.cause, report.report()
    if ok:
        assert report.error <= report.tolerance and report.cause == ""
    else:
        assert not report.error <= report.tolerance  # NaN counts as failed
        assert "likely cause" in report.report()


def test_every_check_has_correct_and_broken_entries(shaders):
    verdicts = {}
    for _, against, *_, ok, _ in CORPUS:
        verdicts.setdefault(against, set()).add(ok)
    assert verdicts == {name: {True, False} for name in shaders.SHADER_CHECKS}


def test_corpus_from_the_fixture(shaders, wavephys_check):
    for name, against, source, function, options, ok, cause in CORPUS:
        takes, uniforms, opts = _split(options)
        if ok:
            report = wavephys_check.glsl(source, function, against, takes=takes, uniforms=uniforms, **opts)
            assert report.ok, name
        else:
            with pytest.raises(AssertionError, match="likely cause") as info:
                wavephys_check.glsl(source, function, against, takes=takes, uniforms=uniforms, **opts)
            assert cause in str(info.value), name


def _argv(tmp_path, name, against, source, function, options):
    takes, uniforms, opts = _split(options)
    path = tmp_path / (name.replace(" ", "_").replace("/", "_") + ".glsl")
    path.write_text(source)
    argv = ["check", "--glsl", str(path), "--function", function, "--against", against]
    if takes:
        argv += ["--takes", ",".join(takes)]
    for key, value in (uniforms or {}).items():
        argv += ["--uniform", f"{key}={value}"]
    for key, value in opts.items():
        text = ",".join(map(str, value)) + ("," if len(value) == 1 else "") if isinstance(value, tuple) else value
        argv += ["--option", f"{key}={text}"]
    return argv


def test_corpus_from_the_command(shaders, tmp_path, capsys):
    from wavephys.app.cli import main

    for name, against, source, function, options, ok, cause in CORPUS:
        code = main(_argv(tmp_path, name, against, source, function, options))
        out = capsys.readouterr().out
        assert code == (0 if ok else 1), (name, out)
        assert cause in out, (name, out)


def test_command_writes_json_and_chart(shaders, tmp_path, capsys):
    from PIL import Image

    from wavephys.app.cli import main

    src = tmp_path / "f.glsl"
    src.write_text(SCHLICK_F0)
    code = main(["check", "--glsl", str(src), "--function", "fresnelSchlick", "--against", "fresnel",
                 "--takes", "cos_theta,f0", "--option", "form=schlick", "--json", str(tmp_path / "r.json"),
                 "--chart", str(tmp_path / "r.png")])
    assert code == 1  # from below, no TIR
    data = json.loads((tmp_path / "r.json").read_text())
    assert data["ok"] is False and data["cause"].startswith("no total internal reflection")
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
        (["check", "--function", "f", "--against", "fresnel"], "or --glsl FILE, --function NAME"),
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
    from optics.gpu import GLSL_OPTICS

    fresnel = shaders.check_glsl(GLSL_OPTICS, "fresnel_exact", "fresnel")
    refract = shaders.check_glsl(GLSL_OPTICS, "refract_dir", "refract", tir="zero")
    assert fresnel.ok and refract.ok, fresnel.report() + "\n" + refract.report()
    # the shader forms the renderer draws for a plan, each against its own float64 form
    for form, takes in (("schlick", None), ("lut", None), ("jensen_golias", ("cos_theta",)),
                        ("loviscach", ("cos_theta",))):
        kw = dict(takes=takes) if takes else {}
        report = shaders.check_glsl(GLSL_OPTICS, f"fresnel_{form}", "fresnel", form=form, **kw)
        assert report.ok, report.report()


@pytest.mark.parametrize("source,function,kwargs,error,words", [
    ("float f(float c) { return c; }", "g", dict(takes=("cos_theta",)), "GLSLError", "'g' is not defined"),
    ("float f(vec3 v, vec3 n) { return v.x; }", "f", {}, "GLSLError", "does not take (float, float, float)"),
    ("vec3 f(float c, float a, float b) { return vec3(c); }", "f", {}, "GLSLError", "returns vec3"),
    ("float f(float c, float a, float b) { return c; }", "f", dict(returns="vec3"), "GLSLError", "not vec3"),
    ("float f(float c) { return c; }", "f", dict(takes=("colour",)), "ValueError", "roles"),
    ("float f(float c) { return c; }", "f", dict(takes=("cos_theta",), samplez=8), "TypeError", "options"),
    ("float f(float c) { return c; }", "f", dict(takes=("cos_theta",), uniforms={"uX": 1.0}), "GLSLError",
     "'uX' is not a uniform"),
    ("void f(float c, out float r) { r = c; }", "f", dict(takes=("cos_theta", "n1")), "GLSLError", "out/inout"),
    ("void g(out float r) { r = 1.0; }\nfloat f(float c) { float r; g(r); return c * r; }", "f",
     dict(takes=("cos_theta",), sides="above", form="loviscach"), None, ""),  # out helpers are fine
    ("float f(float c, out float r) { r = c; return c; }", "f", dict(takes=("cos_theta", "n1")), "GLSLError",
     "out/inout"),
    ("void f(float c) { }", "f", dict(takes=("cos_theta",)), "GLSLError", "returns void"),
    ("float f(float c) { return c; }", "f", dict(takes=("cos_theta",), tolerance=-1.0), "ValueError", "tolerance"),
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

    takes = ("heights", "uv", "texel_uv", "texel_size")
    good = shaders.check_glsl(HEIGHT_CENTRAL, "height_normal", "height_normal", takes=takes, seed=seed,
                              max_slope=slope, n=64)
    assert good.ok, good.report()
    if slope > 0.3:  # one-sided differences err by about half a texel's slope change
        bad = shaders.check_glsl(HEIGHT_ONE_SIDED, "height_fwd", "height_normal", takes=takes, seed=seed,
                                 max_slope=slope, n=64)
        assert not bad.ok


def test_reference_is_evaluated_at_the_shaders_float32_inputs(shaders):
    """Rounding the inputs to float32 is not counted against the function: the exact GLSL Fresnel
    errs by float32 arithmetic only (a few 1e-6 at most, near the critical angle)."""
    from shader_corpus import FRESNEL_EXACT

    r = shaders.check_glsl(FRESNEL_EXACT, "fr_dielectric", "fresnel", samples=8192)
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
