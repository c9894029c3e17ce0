"""Shader code as shipped: water's constants judged against their physical range, roles read from names,
GLSL ES / WebGL / Shadertoy / Godot / HLSL read as written, out parameters, gl_FrontFacing, includes and
macros, and the translator's absence said plainly."""

import os
import shutil

import numpy as np
import pytest

pytest.importorskip("moderngl")


@pytest.fixture(scope="module")
def check():
    from optics.gpu import RendererUnavailable
    from optics.shaders import check_glsl

    try:
        check_glsl("float f(float c){ return c; }", "f", "fresnel", takes=("cos_theta",), samples=16)
    except RendererUnavailable as exc:  # pragma: no cover - CI installs EGL
        pytest.skip(str(exc))
    return check_glsl


def test_quan_fry_reproduces_its_published_values_and_the_range_of_water():
    """Quan & Fry's fit at points of its own table (Austin & Halikas' selected data, relative to air), and the
    range SPEC §2.7 gives rounded outward: n1/n2 0.740–0.753, f0 0.0199–0.0223 (the sea at 400 nm, 0 °C reaches
    f0 0.02238: the spec's 0.0223 rounded)."""
    from optics.light.fresnel import water_index_range, water_refractive_index_quan_fry as n

    assert n(589.3, 20.0, 0.0) == pytest.approx(1.33302, abs=3e-5)  # the sodium D line, 20 °C: 1.33299 measured
    assert n(400.0, 0.0, 35.0) - n(400.0, 0.0, 0.0) == pytest.approx(0.0064 + 0.00101, abs=3e-4)  # the sea is higher
    assert n(500.0, 30.0, 0.0) < n(500.0, 10.0, 0.0) < n(500.0, 0.0, 0.0)  # falls with temperature
    r = water_index_range()
    assert 0.7395 <= r.eta[0] <= 0.740 and 0.752 <= r.eta[1] <= 0.753
    assert 0.0199 <= r.f0[0] <= 0.0200 and 0.0223 <= r.f0[1] <= 0.0224
    assert 1.3294 in r and 1.333 / 1.000293 in r and 1.5 not in r
    fresh = water_index_range(salinity=(0.0, 0.0))
    assert fresh.high < r.high and fresh.low == r.low
    with pytest.raises(ValueError, match="temperature_c"):
        water_index_range(temperature_c=(-5.0, 10.0))
    with pytest.raises(ValueError, match="wavelength_nm"):
        n(350.0)


@pytest.mark.parametrize("source,function,against", [
    # the correct shaders: a textbook Schlick with F0 = 0.02, refract with 1.0/1.333, two-sided 1.33
    ("float fresnelSchlick(float cosTheta) { float F0 = 0.02; return F0 + (1.0 - F0) * pow(1.0 - cosTheta, 5.0); }",
     "fresnelSchlick", "fresnel"),
    ("vec3 refractWater(vec3 I, vec3 N) { return refract(I, N, 1.0 / 1.333); }", "refractWater", "refract"),
    ("float fr(float c, float n1, float n2) { float e = n1 / n2; float s2 = e * e * (1.0 - c * c);\n"
     "  if (s2 > 1.0) return 1.0; float ct = sqrt(1.0 - s2);\n"
     "  float rs = (n1 * c - n2 * ct) / (n1 * c + n2 * ct); float rp = (n1 * ct - n2 * c) / (n1 * ct + n2 * c);\n"
     "  return 0.5 * (rs * rs + rp * rp); }\n"
     "float fresnel(float cosTheta, float n1, float n2) { return n1 < n2 ? fr(cosTheta, 1.0, 1.33) : "
     "fr(cosTheta, 1.33, 1.0); }", "fresnel", "fresnel"),
])
def test_correct_constants_pass_with_no_options(check, source, function, against):
    report = check(source, function, against)
    assert report.ok, report.report()
    assert "m = n_water/n_air" in report.fitted or "m = 1.3" in report.fitted


@pytest.mark.parametrize("index", [1.27, 1.36, 1.45, 1.5, 2.0])
def test_an_index_outside_waters_range_fails_and_is_named(check, index):
    """Just outside the range fails too (1.36: f0 0.0231; 1.27: 0.0141): judged by the constant, not the
    display tolerance alone."""
    f0 = ((index - 1) / (index + 1)) ** 2
    report = check(f"float f(float cosTheta) {{ return {f0:.7f} + {1 - f0:.7f} * pow(1.0 - cosTheta, 5.0); }}", "f",
                   "fresnel")
    assert not report.ok and "F0 from the wrong indices" in report.cause
    implied = float(report.cause.split("f0 of an index ")[1].split()[0])
    assert implied == pytest.approx(index, rel=2e-3)


def test_the_display_sets_the_tolerance_and_says_so(check):
    src = "float f(float cosTheta) { return 0.0204 + 0.9796 * pow(1.0 - cosTheta, 5.0) + 0.001; }"
    assert check(src, "f", "fresnel").ok  # a 1e-3 bias is under half an 8-bit level (1.96e-3)
    r = check(src, "f", "fresnel", bits=10)
    assert not r.ok and "10-bit display" in r.tolerance_note and r.tolerance == pytest.approx(0.5 / 1023)
    r = check(src, "f", "fresnel", radiance=4.0)
    assert not r.ok and r.tolerance == pytest.approx(0.5 / 255 / 4)


def test_a_function_that_cannot_tell_the_side_is_checked_from_the_air(check):
    r = check("float f(float cosTheta, float F0) { return F0 + (1.0 - F0) * pow(1.0 - cosTheta, 5.0); }", "f",
              "fresnel")
    assert r.ok and r.samples == 2048 and any("checked from the air only" in n for n in r.notes)
    both = check("float f(float cosTheta, float F0) { return F0 + (1.0 - F0) * pow(1.0 - cosTheta, 5.0); }", "f",
                 "fresnel", sides=("above", "below"))
    assert not both.ok and both.cause.startswith("above: right") and "below: no total internal" in both.cause


def test_roles_are_read_from_names_and_said(check):
    r = check("vec3 refr(vec3 viewRay, vec3 surfaceNormal, float eta) { return refract(viewRay, surfaceNormal, eta); }",
              "refr", "refract")
    assert r.takes == ("incident", "facing_normal", "eta") and r.ok
    r = check("vec3 refl(vec3 V, vec3 N) { return reflect(-V, N); }", "refl", "reflect")
    assert r.takes == ("view", "facing_normal") and r.ok
    r = check("float f(float ior, float cosi) { float r0 = (1.0 - ior) / (1.0 + ior); r0 *= r0;\n"
              "  return r0 + (1.0 - r0) * pow(1.0 - cosi, 5.0); }", "f", "fresnel")
    assert r.takes == ("ior", "cos_theta") and r.ok and any("ior → ior" in n for n in r.notes)


def test_a_constant_argument_in_takes(check):
    src = "float fresnel(float amount, vec3 normal, vec3 view) { return pow(1.0 - clamp(dot(normal, view), 0.0, " \
          "1.0), amount); }"
    r = check(src, "fresnel", "fresnel", takes=(5.0, "normal", "view"), sides="above")
    assert not r.ok and "F0 = 0.0000" in r.cause  # Schlick with no f0
    r = check(src, "fresnel", "fresnel", takes=("3", "normal", "view"), sides="above")
    assert not r.ok and "p = 3" in r.cause


def test_out_parameters_and_results(check):
    src = "void fresnelOut(float cosTheta, out float reflected, out float transmitted) {\n" \
          "  reflected = 0.02 + 0.98 * pow(1.0 - cosTheta, 5.0); transmitted = 1.0 - reflected; }"
    r = check(src, "fresnelOut", "fresnel", result="reflected")
    assert r.ok and r.result == "reflected" and r.function.startswith("void fresnelOut(float cosTheta, out float")
    bad = check(src, "fresnelOut", "fresnel", result="transmitted")
    assert not bad.ok


def test_gl_front_facing_is_fed_from_the_side(check):
    src = "float f(float cosTheta) { float f0 = 0.0204; float c = cosTheta;\n" \
          "  if (!gl_FrontFacing) { float s2 = 1.333 * 1.333 * (1.0 - c * c); if (s2 > 1.0) return 1.0; " \
          "c = sqrt(1.0 - s2); }\n  return f0 + (1.0 - f0) * pow(1.0 - c, 5.0); }"
    r = check(src, "f", "fresnel")
    assert r.ok and r.samples == 4096, r.report()


def test_webgl_shadertoy_and_godot_sources_are_read_as_written(check):
    webgl = ("#version 100\nprecision mediump float;\nvarying vec2 vUv;\nuniform sampler2D uTex;\n"
             "float f(float cosTheta) { return 0.02 + 0.98 * pow(1.0 - cosTheta, 5.0); }\n"
             "void main() { gl_FragColor = texture2D(uTex, vUv) * f(0.5); }\n")
    r = check(webgl, "f", "fresnel")
    assert r.ok and r.language == "webgl" and any("main()" in n for n in r.notes)
    toy = "float f(float cosTheta) { return 0.02 + 0.98 * pow(1.0 - cosTheta, 5.0) + 0.0 * iTime; }\n" \
          "void mainImage(out vec4 c, in vec2 p) { c = vec4(f(p.x / iResolution.x)); }"
    assert check(toy, "f", "fresnel").language == "shadertoy"
    godot = ("shader_type spatial;\nrender_mode unshaded, cull_disabled;\ngroup_uniforms water;\n"
             "uniform float f0 : hint_range(0.0, 0.1) = 0.02;\ninstance uniform vec4 tint : source_color;\n"
             "float schlick(float cos_theta) { return f0 + (1.0 - f0) * pow(1.0 - cos_theta, 5.0) + 0.0 * TIME "
             "* PI; }\nvoid fragment() {\n  ALBEDO = vec3(schlick(dot(NORMAL, VIEW)));\n}\n")
    r = check(godot, "schlick", "fresnel")
    assert r.ok and r.language == "godot", r.report()
    assert any("fragment()" in n for n in r.notes)


def test_macros_and_includes(check, tmp_path):
    from optics.shaders import GLSLError

    src = '#include "water_consts.glsl"\nfloat f(float cosTheta) { return WATER_F0 + (1.0 - WATER_F0) * ' \
          'pow(1.0 - cosTheta, 5.0); }'
    with pytest.raises(GLSLError, match="includes 'water_consts.glsl'"):
        check(src, "f", "fresnel")
    (tmp_path / "water_consts.glsl").write_text("#define WATER_F0 0.0204\n")
    assert check(src, "f", "fresnel", include_dirs=[tmp_path]).ok
    bare = src.split("\n", 1)[1]
    with pytest.raises(GLSLError, match="WATER_F0 is not defined"):
        check(bare, "f", "fresnel")
    assert check(bare, "f", "fresnel", defines={"WATER_F0": "0.0204"}).ok
    assert check(bare, "f", "fresnel", defines=["WATER_F0=0.0204"]).ok


@pytest.mark.skipif(shutil.which("glslangValidator") is None or shutil.which("spirv-cross") is None,
                    reason="the HLSL translator is not installed (apt-get install glslang-tools spirv-cross)")
def test_hlsl_through_the_translator(check, tmp_path):
    from optics.shaders import GLSLError

    src = ("cbuffer UnityPerMaterial { float _F0; };\n"
           "float Fresnel(float NdotV) { return _F0 + (1 - _F0) * pow(saturate(1 - NdotV), 5); }\n"
           "void FresnelOut(float NdotV, out half R) { R = lerp(0.0204, 1.0, pow(1 - NdotV, 5)); }\n")
    r = check(src, "Fresnel", "fresnel", language="hlsl", uniforms={"_F0": 0.02})
    assert r.ok and r.language == "hlsl", r.report()
    assert check(src, "FresnelOut", "fresnel").ok  # told from the text (saturate, half)
    with pytest.raises(GLSLError, match="line") as info:
        check("float F(float c) { return c +; }", "F", "fresnel", language="hlsl")
    assert "source.hlsl:1" in str(info.value) and "/tmp" not in str(info.value)
    with pytest.raises(GLSLError, match="UNITY_PI"):
        check("float F(float c) { return c * UNITY_PI; }", "F", "fresnel", language="hlsl")


def test_a_missing_translator_is_said_and_the_command_exits_3(check, tmp_path, monkeypatch, capsys):
    from optics.shaders import TranslatorMissing
    from wavephys.app.cli import main

    monkeypatch.setenv("PATH", str(tmp_path))  # no glslangValidator, no spirv-cross
    with pytest.raises(TranslatorMissing, match="apt-get install glslang-tools spirv-cross"):
        check("float F(float c) { return c; }", "F", "fresnel", language="hlsl")
    src = tmp_path / "w.hlsl"
    src.write_text("float F(float NdotV) { return 0.02 + 0.98 * pow(1 - NdotV, 5); }")
    assert main(["check", "--hlsl", str(src), "--function", "F", "--against", "fresnel"]) == 3
    assert "glslang-tools" in capsys.readouterr().err
    assert os.environ["PATH"] == str(tmp_path)


def test_colour_results_are_checked_per_channel(check):
    good = check("vec3 f(float cosTheta) { vec3 F0 = vec3(0.02); return F0 + (1.0 - F0) * pow(1.0 - cosTheta, 5.0); }",
                 "f", "fresnel")
    assert good.ok and any("equal channels" in n for n in good.notes)
    bad = check("vec3 f(float cosTheta) { vec3 F0 = vec3(0.02, 0.02, 0.03); return F0 + (1.0 - F0) * "
                "pow(1.0 - cosTheta, 5.0); }", "f", "fresnel")
    assert not bad.ok and "R, above G: right" in bad.cause and "above B: F0 from the wrong indices" in bad.cause
    assert np.isclose(float(bad.cause.split("F0 = ")[-1][:6]), 0.03, atol=2e-4)
