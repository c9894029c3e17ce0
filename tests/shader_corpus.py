"""A corpus of shader functions written the way public engines, tutorials and demos write them.

Each entry is written here from facts about what real code does (its form, constants, conventions
and mistakes: which are named in ``fact``), never copied. Each carries a numpy transcription of the
function (``numpy``: the same arithmetic on the same arguments, GLSL's built-ins as the spec
defines them), from which tests/shaders/test_shaders.py decides the truth independently of the
checker: the function is correct when some water the physics allows (an index in water's range,
scanned by brute force, against optics.light's reference formulas) explains its output within the
stated tolerance on every side it can tell apart. ``cause`` is the fragment the checker's cause must
contain for a faulty one ("" for a correct one). ``options`` are what the code itself states (its
language, a form it names, a constant it is called with, macros it expects), nothing more.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np


@dataclass(frozen=True)
class Shader:
    name: str
    fact: str
    against: str
    source: str
    function: str
    numpy: Callable
    cause: str = ""
    options: dict = field(default_factory=dict)

    @property
    def ok(self) -> bool:
        return self.cause == ""


# -- GLSL's built-ins, transcribed (column vectors: arrays (n, c)) -------------------------------
def sat(x):
    return np.clip(x, 0.0, 1.0)


def dot(a, b):
    return np.sum(a * b, axis=-1, keepdims=True)


def normalize(v):
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


def mix(a, b, t):
    return a + (b - a) * t


def glsl_refract(i, n, eta):
    c = dot(n, i)
    k = 1.0 - eta * eta * (1.0 - c * c)
    return np.where(k < 0.0, 0.0, eta * i - (eta * c + np.sqrt(np.maximum(k, 0.0))) * n)


def glsl_reflect(i, n):
    return i - 2.0 * dot(n, i) * n


def texture(sampler, uv):
    """Bilinear, repeat, texel centres at (j + 0.5)/w (GL's sampling of a float texture)."""
    data = sampler.data
    h, w, _ = data.shape
    x = uv[:, 0] * w - 0.5
    y = uv[:, 1] * h - 0.5
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = (x - x0)[:, None], (y - y0)[:, None]

    def at(i, j):
        return data[j % h, i % w].astype(np.float64)

    return ((1 - fx) * (1 - fy) * at(x0, y0) + fx * (1 - fy) * at(x0 + 1, y0) + (1 - fx) * fy * at(x0, y0 + 1)
            + fx * fy * at(x0 + 1, y0 + 1))


def texture_clamped(sampler, uv):
    h, w, _ = sampler.data.shape
    return texture(sampler, np.clip(uv, [0.5 / w, 0.5 / h], [1 - 0.5 / w, 1 - 0.5 / h]))


def f0_of(n1, n2):
    return ((n1 - n2) / (n1 + n2)) ** 2


def schlick(c, f0, power=5.0):
    return f0 + (1.0 - f0) * (1.0 - c) ** power


def exact(c, n1, n2):
    s2 = (n1 / n2) ** 2 * (1.0 - c * c)
    ct = np.sqrt(np.maximum(1.0 - s2, 0.0))
    with np.errstate(invalid="ignore", divide="ignore"):
        rs = ((n1 * c - n2 * ct) / (n1 * c + n2 * ct)) ** 2
        rp = ((n1 * ct - n2 * c) / (n1 * ct + n2 * c)) ** 2
    return np.where(s2 >= 1.0, 1.0, 0.5 * (rs + rp))


def schlick_two_sided(c, n1, n2, tir=True):
    r0 = f0_of(n1, n2)
    s2 = (n1 / n2) ** 2 * (1.0 - c * c)
    ct = np.where(n1 > n2, np.sqrt(np.maximum(1.0 - s2, 0.0)), c) if tir else c
    r = r0 + (1.0 - r0) * (1.0 - ct) ** 5
    return np.where((n1 > n2) & (s2 > 1.0), 1.0, r) if tir else r


def side_indices(front):
    return np.where(front > 0.5, 1.0, 1.33), np.where(front > 0.5, 1.33, 1.0)


# -- Fresnel ---------------------------------------------------------------------------------
PBRT_DIELECTRIC = """
// The full dielectric Fresnel written with both indices and the transmitted cosine (pbrt's FrDielectric)
float frDielectric(float cosThetaI, float etaI, float etaT) {
    cosThetaI = clamp(cosThetaI, 0.0, 1.0);
    float sinThetaI = sqrt(max(0.0, 1.0 - cosThetaI * cosThetaI));
    float sinThetaT = etaI / etaT * sinThetaI;
    if (sinThetaT >= 1.0) return 1.0;
    float cosThetaT = sqrt(max(0.0, 1.0 - sinThetaT * sinThetaT));
    float Rparl = ((etaT * cosThetaI) - (etaI * cosThetaT)) / ((etaT * cosThetaI) + (etaI * cosThetaT));
    float Rperp = ((etaI * cosThetaI) - (etaT * cosThetaT)) / ((etaI * cosThetaI) + (etaT * cosThetaT));
    return (Rparl * Rparl + Rperp * Rperp) / 2.0;
}
"""

LEARNOPENGL_SCHLICK = """
// The PBR tutorials' Schlick term with F0 given
float fresnelSchlick(float cosTheta, float F0) {
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}
"""

PBR_SCHLICK_RGB = """
vec3 fresnelSchlick(float cosTheta, vec3 F0) {
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}
"""

PBR_DIELECTRIC_F0 = """
// A PBR material's default F0 for dielectrics, used for the water too
vec3 specularFresnel(float NdotV) {
    vec3 F0 = vec3(0.04);
    return F0 + (1.0 - F0) * pow(1.0 - NdotV, 5.0);
}
"""

UNREAL_F_SCHLICK = """
// Unreal's shading model: F_Schlick(SpecularColor, VoH) with the "anything under 2% is shadowing" term
float3 F_Schlick(float3 SpecularColor, float VoH)
{
    float Fc = pow(1 - VoH, 5);
    return saturate(50.0 * SpecularColor.g) * Fc + (1 - Fc) * SpecularColor;
}
"""

CREST_FRESNEL = """
// Crest's Schlick from the two indices, with the power a material property
uniform float _RefractiveIndexOfAir;
uniform float _RefractiveIndexOfWater;
uniform float _FresnelPower;
float CalculateFresnelReflectionCoefficient(float cosTheta)
{
    float R_0 = (_RefractiveIndexOfAir - _RefractiveIndexOfWater) / (_RefractiveIndexOfAir + _RefractiveIndexOfWater);
    R_0 *= R_0;
    const float R_theta = R_0 + (1.0 - R_0) * pow(max(0., 1.0 - cosTheta), _FresnelPower);
    return R_theta;
}
"""

STYLIZED_DEFINES = """
#define WATER_RI 1.333
#define AIR_RI 1.000293
#define SCHLICK_EXPONENT 5.0
float FresnelReflection(float angle)
{
    float r = (AIR_RI - WATER_RI) / (AIR_RI + WATER_RI);
    r = r * r;
    return r + (1.0 - r) * pow(1.0 - angle, SCHLICK_EXPONENT);
}
"""

R0_CONSTANT = """
// R0 computed once from 1.3333 and written out as a constant
const float R0 = 0.02040781341208;
float fresnel(float3 view, float3 normal)
{
    float c = saturate(dot(view, normal));
    return R0 + (1.0 - R0) * pow(1.0 - c, 5.0);
}
"""

WEBTIDE_STYLE = """
// water fresnel from the view ray and the surface normal (the surface is only ever seen from above)
float waterFresnel(vec3 viewRay, vec3 normal) {
    return 0.02 + 0.98 * pow(1.0 - dot(-viewRay, normal), 5.0);
}
"""

FRONT_FACING_SCHLICK = """
// two-sided: the water's back face is seen from under the surface
float fresnelTwoSided(float cosTheta) {
    float n1 = gl_FrontFacing ? 1.0 : 1.33;
    float n2 = gl_FrontFacing ? 1.33 : 1.0;
    float r0 = (n1 - n2) / (n1 + n2);
    r0 *= r0;
    float c = cosTheta;
    if (n1 > n2) {
        float s2 = (n1 / n2) * (n1 / n2) * (1.0 - c * c);
        if (s2 > 1.0) return 1.0;
        c = sqrt(1.0 - s2);
    }
    float x = 1.0 - c;
    return r0 + (1.0 - r0) * x * x * x * x * x;
}
"""

FRONT_FACING_NO_TIR = """
float fresnelTwoSided(float cosTheta) {
    float n1 = gl_FrontFacing ? 1.0 : 1.33;
    float n2 = gl_FrontFacing ? 1.33 : 1.0;
    float r0 = (n1 - n2) / (n1 + n2);
    r0 *= r0;
    return r0 + (1.0 - r0) * pow(1.0 - cosTheta, 5.0);
}
"""

EXACT_133_TWO_SIDED = """
// the exact formula with 1.33 and air as 1, from either side
float fr(float c, float n1, float n2) {
    float e = n1 / n2;
    float s2 = e * e * (1.0 - c * c);
    if (s2 > 1.0) return 1.0;
    float ct = sqrt(1.0 - s2);
    float rs = (n1 * c - n2 * ct) / (n1 * c + n2 * ct);
    float rp = (n1 * ct - n2 * c) / (n1 * ct + n2 * c);
    return 0.5 * (rs * rs + rp * rp);
}
float fresnelWater(float cosTheta, bool frontFacing) {
    return frontFacing ? fr(cosTheta, 1.0, 1.33) : fr(cosTheta, 1.33, 1.0);
}
"""

WEBGL_WATER_MIX = """
// a WebGL water demo's reflectance: a mix from a quarter to one on a cube of the grazing term
float reflectance(vec3 normal, vec3 ray) {
    return mix(0.25, 1.0, pow(1.0 - dot(normal, -ray), 3.0));
}
"""

SEASCAPE_STYLE = """
// a Shadertoy sea's fresnel: a cube of the clamped grazing term, halved
float getFresnel(vec3 n, vec3 eye) {
    float fresnel = clamp(1.0 - dot(n, -eye), 0.0, 1.0);
    return pow(fresnel, 3.0) * 0.5;
}
void mainImage(out vec4 fragColor, in vec2 fragCoord) {
    vec2 uv = fragCoord / iResolution.xy;
    fragColor = vec4(vec3(getFresnel(vec3(0.0, 1.0, 0.0), normalize(vec3(uv, -1.0)))), 1.0);
}
"""

CG_TUTORIAL_EMPIRICAL = """
// the Cg tutorial's empirical approximation: bias + scale * (1 + I.N)^power
uniform float fresnelBias;
uniform float fresnelScale;
uniform float fresnelPower;
float reflectionFactor(vec3 I, vec3 N) {
    return fresnelBias + fresnelScale * pow(1.0 + dot(I, N), fresnelPower);
}
"""

GODOT_FRESNEL = """shader_type spatial;
render_mode cull_disabled;

uniform vec4 albedo : source_color = vec4(0.05, 0.2, 0.3, 1.0);
uniform float metallic : hint_range(0.0, 1.0) = 0.0;

// the Godot tutorials' fresnel: a power of the clamped grazing term, called with amount = 5.0
float fresnel(float amount, vec3 normal, vec3 view) {
    return pow((1.0 - clamp(dot(normalize(normal), normalize(view)), 0.0, 1.0)), amount);
}

void fragment() {
    float f = fresnel(5.0, NORMAL, VIEW);
    ALBEDO = albedo.rgb * (1.0 - f);
    METALLIC = metallic;
}
"""

GODOT_SCHLICK = """shader_type spatial;
uniform float water_f0 : hint_range(0.0, 0.1) = 0.02;

float water_fresnel(float cos_theta) {
    return water_f0 + (1.0 - water_f0) * pow(1.0 - cos_theta, 5.0);
}

void fragment() {
    float fr = water_fresnel(dot(NORMAL, VIEW));
    ALBEDO = vec3(fr);
}
"""

COS5_MISPRINT = """
// Schlick with the power of the cosine itself (a misprint carried into code)
float fresnelTypo(vec3 V, vec3 N) {
    float c = dot(N, V);
    float f0 = 0.0204;
    return f0 + (1.0 - f0) * pow(c, 5.0);
}
"""

SCHLICK_WRONG_RAY = """
float schlickT(float cosI, float n1, float n2) {
    float r0 = pow((n1 - n2) / (n1 + n2), 2.0);
    float s2 = (n1 / n2) * (n1 / n2) * (1.0 - cosI * cosI);
    if (s2 > 1.0) return 1.0;
    float ct = sqrt(1.0 - s2);
    return r0 + (1.0 - r0) * pow(1.0 - ct, 5.0);
}
"""

EXACT_INVERTED = PBRT_DIELECTRIC.replace("float sinThetaT = etaI / etaT * sinThetaI;",
                                         "float sinThetaT = etaT / etaI * sinThetaI;")

SCHLICK_NOT_SQUARED = """
float schlickR0(float c, float n1, float n2) {
    float r0 = abs((n1 - n2) / (n1 + n2));   // forgot to square
    return r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
}
"""

JENSEN_GOLIAS = """
// Deep-water animation and rendering's cheap Fresnel for water seen from the air
float fresnelJensenGolias(float c) { return 1.0 / pow(1.0 + c, 8.0); }
"""

LOVISCACH = """
// Loviscach's cheap reflectance for water seen from the air
float fresnelLoviscach(float cosTheta) { return clamp(1.0 - 2.5 * cosTheta, 0.0, 1.0); }
"""
RIM_RAMP = """
// a rim term used as the reflection weight: a clamped linear ramp of the facing ratio
float rimFresnel(vec3 N, vec3 V) { return clamp(1.0 - dot(N, V) * 1.5, 0.0, 1.0); }
"""

SHADE_MIX = """
// a water shader's final mix: the reflected colour by Fresnel, the rest refracted
float3 ShadeWater(float3 reflection, float3 refraction, float NdotV)
{
    float F = 0.02 + 0.98 * pow(saturate(1.0 - NdotV), 5.0);
    return lerp(refraction, reflection, F);
}
"""

ABS_DOT_NO_TIR = """
// two-sided by abs(): the same Schlick from under the water, with no total internal reflection
float fresnelAbs(vec3 normal, vec3 view) {
    float c = abs(dot(normal, view));
    return 0.02 + 0.98 * pow(1.0 - c, 5.0);
}
"""

IOR_ONLY_EXACT = """
// exact Fresnel for light from the air into a medium of index ior (air taken as 1)
float fresnelIor(float cosi, float ior) {
    float sint = sqrt(max(0.0, 1.0 - cosi * cosi)) / ior;
    float cost = sqrt(max(0.0, 1.0 - sint * sint));
    float rs = (cosi - ior * cost) / (cosi + ior * cost);
    float rp = (ior * cosi - cost) / (ior * cosi + cost);
    return 0.5 * (rs * rs + rp * rp);
}
"""

VOID_OUT_SCHLICK = """
// a helper that writes its result to an out parameter
void waterReflectance(in float NdotV, out float R) {
    R = 0.0204 + (1.0 - 0.0204) * pow(1.0 - NdotV, 5.0);
}
"""


def _fr(c, n1, n2):
    return exact(c, n1, n2)


def _webtide(i, n):
    return 0.02 + 0.98 * (1.0 - dot(-i, n)) ** 5


def _front_facing(c, front, tir=True):
    n1, n2 = side_indices(front)
    return schlick_two_sided(c, n1, n2, tir)


def _schlick_t(c, a, b):
    s2 = (a / b) ** 2 * (1 - c * c)
    ct = np.sqrt(np.maximum(1 - s2, 0))
    return np.where(s2 > 1, 1.0, f0_of(a, b) + (1 - f0_of(a, b)) * (1 - ct) ** 5)


def _inverted(c, a, b):
    return exact(np.clip(c, 0, 1), b, a)


FRESNEL = [
    Shader("pbrt's dielectric Fresnel", "pbrt's FrDielectric: both indices, cos θt, TIR test", "fresnel",
           PBRT_DIELECTRIC, "frDielectric", lambda c, a, b: exact(np.clip(c, 0, 1), a, b)),
    Shader("Schlick with F0, from the air", "LearnOpenGL's fresnelSchlick(cosTheta, F0)", "fresnel",
           LEARNOPENGL_SCHLICK, "fresnelSchlick", lambda c, f0: schlick(np.clip(c, 0, 1), f0)),
    Shader("Schlick with a colour F0", "the PBR form with vec3 F0", "fresnel", PBR_SCHLICK_RGB, "fresnelSchlick",
           lambda c, f0: schlick(np.clip(c, 0, 1), f0)),
    Shader("a PBR dielectric F0 of 0.04 used for water", "engines' default F0 = 0.04 for non-metals", "fresnel",
           PBR_DIELECTRIC_F0, "specularFresnel", lambda c: np.repeat(schlick(c, 0.04), 3, 1), cause="0.04"),
    Shader("Unreal's F_Schlick (HLSL)", "Unreal's BRDF: saturate(50 SpecularColor.g) Fc + (1 − Fc) SpecularColor",
           "fresnel", UNREAL_F_SCHLICK, "F_Schlick",
           lambda f0, c: np.clip(50 * f0[:, 1:2], 0, 1) * (1 - c) ** 5 + (1 - (1 - c) ** 5) * f0),
    Shader("Crest's Schlick from the indices (HLSL, power 5)", "Crest: R_0 from _RefractiveIndexOfAir/Water, "
           "pow(max(0, 1 − cosθ), _FresnelPower)", "fresnel", CREST_FRESNEL, "CalculateFresnelReflectionCoefficient",
           lambda c: schlick(c, f0_of(1.0, 1.333)),
           options=dict(language="hlsl", uniforms={"_RefractiveIndexOfAir": 1.0, "_RefractiveIndexOfWater": 1.333,
                                                   "_FresnelPower": 5.0})),
    Shader("Crest's Schlick with its power set to 3 (HLSL)", "Crest exposes the Schlick power as _FresnelPower",
           "fresnel", CREST_FRESNEL, "CalculateFresnelReflectionCoefficient",
           lambda c: schlick(c, f0_of(1.0, 1.333), 3.0), cause="p = 3",
           options=dict(language="hlsl", uniforms={"_RefractiveIndexOfAir": 1.0, "_RefractiveIndexOfWater": 1.333,
                                                   "_FresnelPower": 3.0})),
    Shader("Schlick from #defined indices (HLSL)", "asset-store water: WATER_RI 1.333, AIR_RI 1.000293, exponent 5",
           "fresnel", STYLIZED_DEFINES, "FresnelReflection", lambda c: schlick(c, f0_of(1.000293, 1.333)),
           options=dict(language="hlsl", takes=("cos_theta",))),
    Shader("R0 written out as a constant (HLSL)", "R0 = 0.02040781341208, from 1.3333", "fresnel", R0_CONSTANT,
           "fresnel", lambda v, n: schlick(np.clip(dot(v, n), 0, 1), 0.02040781341208), cause="constant 1",
           options=dict(language="hlsl")),
    Shader("Schlick of the view ray, seen from above only", "a WebGL water's 0.02 + 0.98 pow(1 − dot(−V, N), 5) "
           "with the up normal", "fresnel", WEBTIDE_STYLE, "waterFresnel", _webtide, cause="above: right"),
    Shader("two-sided Schlick with TIR by gl_FrontFacing", "the back face of the water mesh is the view from "
           "below", "fresnel", FRONT_FACING_SCHLICK, "fresnelTwoSided", lambda c, front: _front_facing(c, front)),
    Shader("two-sided Schlick without TIR by gl_FrontFacing", "the same without the TIR test", "fresnel",
           FRONT_FACING_NO_TIR, "fresnelTwoSided", lambda c, front: _front_facing(c, front, tir=False),
           cause="no total internal reflection"),
    Shader("exact Fresnel with 1.33 from either side", "two-sided code written with 1.33 and air as 1", "fresnel",
           EXACT_133_TWO_SIDED, "fresnelWater",
           lambda c, front: _fr(c, *side_indices(front))),
    Shader("a WebGL demo's mix(0.25, 1, (1 − cos)^3)", "a popular WebGL water's reflectance term", "fresnel",
           WEBGL_WATER_MIX, "reflectance", lambda n, i: mix(0.25, 1.0, (1.0 - dot(n, -i)) ** 3),
           cause="(1 − f0)(1 − cos θ)^p with f0 = 0.25, p = 3"),
    Shader("a Shadertoy sea's halved cube", "a Shadertoy sea: pow(clamp(1 − dot(n, −eye)), 3) × 0.5", "fresnel",
           SEASCAPE_STYLE, "getFresnel", lambda n, i: sat(1.0 - dot(n, -i)) ** 3 * 0.5,
           cause="R = b (1 − cos θ)^p with b = 0.5, p = 3",
           options=dict(takes=("normal", "incident"), sides=("above",))),
    Shader("the Cg tutorial's empirical reflection factor", "bias 0.1, scale 1, power 2 in bias + scale (1 + I·N)^p",
           "fresnel", CG_TUTORIAL_EMPIRICAL, "reflectionFactor", lambda i, n: 0.1 + (1.0 + dot(i, n)) ** 2,
           cause="bias = 0.1, scale = 1, power = 2", options=dict(uniforms={"fresnelBias": 0.1, "fresnelScale": 1.0,
                                                               "fresnelPower": 2.0}, sides=("above",))),
    Shader("Godot's fresnel(amount, normal, view) at amount 5", "the Godot tutorials' pow(1 − clamp(dot(N, V)), "
           "amount)", "fresnel", GODOT_FRESNEL, "fresnel", lambda a, n, v: (1 - np.clip(dot(normalize(n),
                                                                                            normalize(v)), 0, 1)) ** a,
           cause="F0 = 0.0000", options=dict(takes=(5.0, "normal", "view"))),
    Shader("Godot Schlick with a uniform F0", "a Godot shader with uniform float water_f0 : hint_range = 0.02",
           "fresnel", GODOT_SCHLICK, "water_fresnel", lambda c: schlick(c, 0.02)),
    Shader("Schlick with the power of cos θ", "Schneider & Westermann's printed ⟨N, V⟩⁵ for (1 − ⟨N, V⟩)⁵",
           "fresnel", COS5_MISPRINT, "fresnelTypo", lambda v, n: 0.0204 + 0.9796 * dot(n, v) ** 5, cause="misprint",
           options=dict(sides=("above",))),
    Shader("Schlick with the refracted ray's cosine", "cos θt on both sides", "fresnel", SCHLICK_WRONG_RAY,
           "schlickT", _schlick_t, cause="wrong ray"),
    Shader("exact Fresnel with the index ratio inverted", "etaT/etaI where etaI/etaT is due", "fresnel",
           EXACT_INVERTED, "frDielectric", _inverted, cause="index ratio is inverted"),
    Shader("Schlick with r0 not squared", "r0 = |n1 − n2|/(n1 + n2)", "fresnel", SCHLICK_NOT_SQUARED, "schlickR0",
           lambda c, a, b: np.abs((a - b) / (a + b)) + (1 - np.abs((a - b) / (a + b))) * (1 - c) ** 5,
           cause="not squared", options=dict(sides=("above",))),
    Shader("Jensen & Goliáš as itself", "1/(1 + cos θ)⁸ (Jensen & Goliáš 2001), named in the code", "fresnel",
           JENSEN_GOLIAS, "fresnelJensenGolias", lambda c: 1.0 / (1.0 + c) ** 8, options=dict(form="jensen_golias")),
    Shader("Jensen & Goliáš taken for Fresnel", "the same, with no form named", "fresnel", JENSEN_GOLIAS,
           "fresnelJensenGolias", lambda c: 1.0 / (1.0 + c) ** 8, cause="form='jensen_golias'"),
    Shader("Loviscach's clamp taken for Fresnel", "clamp(1 − 2.5 cos θ), with no form named", "fresnel", LOVISCACH,
           "fresnelLoviscach", lambda c: np.clip(1.0 - 2.5 * c, 0.0, 1.0), cause="form='loviscach'"),
    Shader("a clamped rim ramp as Fresnel", "clamp(1 − 1.5 N·V, 0, 1)", "fresnel", RIM_RAMP, "rimFresnel",
           lambda n, v: np.clip(1.0 - 1.5 * dot(n, v), 0.0, 1.0), cause="a linear ramp R = a + b (1 − cos θ) with "
                                                                          "a = -0.5, b = 1.5",
           options=dict(sides=("above",))),
    Shader("the reflected/refracted mix (HLSL)", "lerp(refraction, reflection, F) with F Schlick's", "fresnel",
           SHADE_MIX, "ShadeWater", lambda refl, refr, c: mix(refr, refl, 0.02 + 0.98 * sat(1 - c) ** 5),
           options=dict(language="hlsl")),
    Shader("two-sided by abs(dot(N, V)) without TIR", "1 − abs(dot(normal, view)) for both faces", "fresnel",
           ABS_DOT_NO_TIR, "fresnelAbs", lambda n, v: 0.02 + 0.98 * (1 - np.abs(dot(n, v))) ** 5,
           cause="no total internal reflection"),
    Shader("exact Fresnel from the air with ior", "an exact formula taking only the medium's index", "fresnel",
           IOR_ONLY_EXACT, "fresnelIor", lambda c, ior: exact(c, 1.0, ior)),
    Shader("Schlick written to an out parameter", "void helpers with out parameters", "fresnel", VOID_OUT_SCHLICK,
           "waterReflectance", lambda c: schlick(c, 0.0204)),
]


# -- refraction and reflection -------------------------------------------------------------------
REFRACT_BUILTIN = "vec3 refractWater(vec3 I, vec3 N, float eta) { return refract(I, N, eta); }"
REFRACT_FIXED = "vec3 refractFromAir(vec3 I, vec3 N) { return refract(I, N, 1.0 / 1.333); }"
REFRACT_075 = "vec3 refractRay(vec3 viewRay, vec3 normal) { return refract(viewRay, normal, 0.75); }"
REFRACT_INVERTED = "vec3 refractWrong(vec3 I, vec3 N) { return refract(I, N, 1.333); }"
REFRACT_FRONT_ONE_ETA = """
vec3 refractTwoSided(vec3 I, vec3 N, bool frontFacing) {
    return refract(I, N, frontFacing ? 1.0 / 1.33 : 1.0 / 1.33);   // the same ratio on both faces
}
"""
REFRACT_FRONT = """
vec3 refractTwoSided(vec3 I, vec3 N, bool frontFacing) {
    return refract(I, N, frontFacing ? 1.0 / 1.33 : 1.33);
}
"""
REFRACT_UP_NORMAL = """
// The water normal always points up; from below the engine forgot to flip it
vec3 refrUp(vec3 I, vec3 N, float n1, float n2) { return refract(I, N, n1 / n2); }
"""
REFRACT_NO_TIR = """
vec3 refrManual(vec3 I, vec3 N, float eta) {
    float cosi = dot(-I, N);
    float k = 1.0 - eta * eta * (1.0 - cosi * cosi);
    return eta * I + (eta * cosi - sqrt(k)) * N;      // no k < 0 test
}
"""
REFRACT_NEGATED = "vec3 refrNeg(vec3 I, vec3 N, float eta) { return refract(I, -N, eta); }   // N negated"
REFRACT_HLSL = "float3 RefractWater(float3 I, float3 N, float eta) { return refract(I, N, eta); }"
REFRACT_VIEW = "vec3 refrV(vec3 V, vec3 N, float eta) { return refract(V, N, eta); }   // V points to the eye"
REFLECT_BUILTIN = "vec3 reflectRay(vec3 I, vec3 N) { return reflect(I, N); }"
REFLECT_HAND = "vec3 mirror(vec3 d, vec3 n) { return d - 2.0 * dot(d, n) * n; }"
REFLECT_VIEW = "vec3 reflView(vec3 V, vec3 N) { return reflect(V, N); }   // V points to the eye"
REFLECT_HLSL_YUP = """
// a y-up engine's reflection of the camera ray, with the ray from the camera
float3 ReflectCamera(float3 rayDir, float3 normalWS) { return reflect(rayDir, normalWS); }
"""


def _manual_refract(i, n, eta):
    cosi = dot(-i, n)
    with np.errstate(invalid="ignore"):
        k = 1 - eta * eta * (1 - cosi * cosi)
        return eta * i + (eta * cosi - np.sqrt(k)) * n


RAYS = [
    Shader("GLSL refract with eta", "the built-in refract(I, N, eta)", "refract", REFRACT_BUILTIN, "refractWater",
           glsl_refract),
    Shader("refract from the air with 1.0/1.333", "refract(I, N, 1.0/1.333) written for rays from the air",
           "refract", REFRACT_FIXED, "refractFromAir", lambda i, n: glsl_refract(i, n, 1.0 / 1.333)),
    Shader("refract with 0.75", "a WebGL water's refract(viewRay, normal, 0.75)", "refract", REFRACT_075,
           "refractRay", lambda i, n: glsl_refract(i, n, 0.75)),
    Shader("refract with 1.333 from the air", "the index where its inverse is due", "refract", REFRACT_INVERTED,
           "refractWrong", lambda i, n: glsl_refract(i, n, 1.333), cause="index ratio is inverted"),
    Shader("two-sided refract with one ratio", "1/1.33 on both faces", "refract", REFRACT_FRONT_ONE_ETA,
           "refractTwoSided", lambda i, n, f: glsl_refract(i, n, 1 / 1.33), cause="below: the index ratio is "
                                                                                   "inverted"),
    Shader("two-sided refract by gl face", "1/1.33 from the air, 1.33 from the water", "refract", REFRACT_FRONT,
           "refractTwoSided", lambda i, n, f: glsl_refract(i, n, np.where(f > 0.5, 1 / 1.33, 1.33))),
    Shader("refract with the up normal from below", "the normal not flipped for rays from the water", "refract",
           REFRACT_UP_NORMAL, "refrUp", lambda i, n, a, b: glsl_refract(i, n, a / b),
           cause="from below, the normal faces the wrong way", options=dict(takes=("incident", "normal", "n1", "n2"))),
    Shader("hand-written refract without a TIR test", "sqrt(k) without k < 0", "refract", REFRACT_NO_TIR,
           "refrManual", _manual_refract, cause="NaN past the critical angle"),
    Shader("refract with the normal negated", "refract(I, −N, eta) on every ray", "refract", REFRACT_NEGATED,
           "refrNeg", lambda i, n, e: glsl_refract(i, -n, e), cause="the normal faces the wrong way on every ray"),
    Shader("HLSL refract (HLSL)", "HLSL's refract intrinsic", "refract", REFRACT_HLSL, "RefractWater", glsl_refract,
           options=dict(language="hlsl")),
    Shader("refract of the view vector", "V towards the eye passed as I", "refract", REFRACT_VIEW, "refrV",
           lambda v, n, e: glsl_refract(v, n, e), cause="view vector"),
    Shader("GLSL reflect", "the built-in reflect(I, N)", "reflect", REFLECT_BUILTIN, "reflectRay", glsl_reflect),
    Shader("hand-written reflect", "d − 2(d·n)n", "reflect", REFLECT_HAND, "mirror", glsl_reflect),
    Shader("reflect of the view vector", "reflect(V, N) with V towards the eye", "reflect", REFLECT_VIEW,
           "reflView", lambda v, n: glsl_reflect(v, n), cause="mirrored view vector"),
    Shader("HLSL reflect in a y-up engine (HLSL)", "world space y up", "reflect", REFLECT_HLSL_YUP, "ReflectCamera",
           glsl_reflect, options=dict(language="hlsl", up="y")),
]

# -- absorption ------------------------------------------------------------------------------------
BEER = "vec3 beer(float d, vec3 sigma) { return exp(-sigma * d); }"
BEER_SCALAR = "float beer1(float dist, float absorption) { return exp(-absorption * dist); }"
BEER_INOUT = """
// attenuate a colour along the refracted path (HLSL, in place)
void ApplyAbsorption(inout float3 color, float dist, float3 absorption) { color *= exp(-absorption * dist); }
"""
CREST_FOG = """
// depth fog: the colour through the water path
float3 DepthFog(float3 density, float pathLength) { return exp(-density * pathLength); }
"""
BEER_TWICE = """
// absorption on the way down to the floor and back up: the path counted twice
vec3 beer2(float d, vec3 sigma) { return exp(-sigma * 2.0 * d); }
"""
BEER_OFFSET = """
// a minimum path added so that shallow water is never clear
vec3 beerMin(float d, vec3 sigma) { return exp(-sigma * (d + 0.5)); }
"""
BEER_BGR = "vec3 beerBgr(float d, vec3 sigma) { return exp(-sigma.bgr * d); }"
BEER_LINEAR = "vec3 beerLin(float d, vec3 sigma) { return clamp(1.0 - sigma * d, 0.0, 1.0); }"
BEER_EXP2 = "vec3 beerExp2(float d, vec3 sigma) { return exp2(-sigma * d); }"
BEER_TINTED = "vec3 beerTint(float d, vec3 sigma) { return 0.9 * exp(-sigma * d); }   // a tint folded in"
BEER_PER_CM = "vec3 beerCm(float distance, vec3 absorption) { return exp(-absorption * distance * 100.0); }"
WATER_FIT = "vec3 waterTint(float d) { return exp(-vec3(0.3353, 0.05035, 0.000547) * d); }"
WATER_BGR = "vec3 waterBgr(float d) { return exp(-vec3(0.000547, 0.05035, 0.3353) * d); }"
WATER_PER_CM = "vec3 waterCm(float d) { return exp(-vec3(0.3353, 0.05035, 0.000547) * d * 100.0); }"
WATER_TWICE = "vec3 waterTwice(float d) { return exp(-vec3(0.3353, 0.05035, 0.000547) * 2.0 * d); }"
_WATER = np.array([0.3353, 0.05035, 0.000547])

ABSORPTION = [
    Shader("Beer–Lambert RGB", "exp(−σ d) per channel", "transmittance", BEER, "beer", lambda d, s: np.exp(-s * d)),
    Shader("Beer–Lambert, one channel", "exp(−a d)", "transmittance", BEER_SCALAR, "beer1",
           lambda d, a: np.exp(-a * d)),
    Shader("absorption in place on a colour (HLSL)", "color *= exp(−absorption · dist)", "transmittance", BEER_INOUT,
           "ApplyAbsorption", lambda col, d, s: col * np.exp(-s * d), options=dict(language="hlsl")),
    Shader("depth fog along the path (HLSL)", "exp(−density · pathLength)", "transmittance", CREST_FOG, "DepthFog",
           lambda s, d: np.exp(-s * d), options=dict(language="hlsl")),
    Shader("Beer–Lambert with the path counted twice", "down to the floor and back", "transmittance", BEER_TWICE,
           "beer2", lambda d, s: np.exp(-s * 2 * d), cause="counted twice"),
    Shader("Beer–Lambert with a minimum path", "an offset of 0.5 m added", "transmittance", BEER_OFFSET, "beerMin",
           lambda d, s: np.exp(-s * (d + 0.5)), cause="offset of 0.5"),
    Shader("Beer–Lambert with the channels reversed", "σ read as BGR", "transmittance", BEER_BGR, "beerBgr",
           lambda d, s: np.exp(-s[:, ::-1] * d), cause="reversed"),
    Shader("linear absorption", "1 − σd clamped", "transmittance", BEER_LINEAR, "beerLin",
           lambda d, s: np.clip(1 - s * d, 0, 1), cause="not exponential"),
    Shader("exp2 absorption", "exp2(−σd)", "transmittance", BEER_EXP2, "beerExp2", lambda d, s: 2.0 ** (-s * d),
           cause="exp2"),
    Shader("Beer–Lambert with a tint folded in", "0.9 exp(−σd)", "transmittance", BEER_TINTED, "beerTint",
           lambda d, s: 0.9 * np.exp(-s * d), cause="the transmittance is scaled by 0.9"),
    Shader("Beer–Lambert per cm", "coefficients per cm with the path in metres", "transmittance", BEER_PER_CM,
           "beerCm", lambda d, s: np.exp(-s * d * 100), cause="per cm"),
    Shader("pure water's RGB fit", "exp(−(0.3353, 0.05035, 0.000547) d)", "rgb_absorption", WATER_FIT, "waterTint",
           lambda d: np.exp(-_WATER * d)),
    Shader("water colour with the channels reversed", "blue absorbed most", "rgb_absorption", WATER_BGR, "waterBgr",
           lambda d: np.exp(-_WATER[::-1] * d), cause="reversed"),
    Shader("water colour per cm", "×100", "rgb_absorption", WATER_PER_CM, "waterCm",
           lambda d: np.exp(-_WATER * d * 100), cause="per cm"),
    Shader("water colour with the path twice", "×2", "rgb_absorption", WATER_TWICE, "waterTwice",
           lambda d: np.exp(-_WATER * 2 * d), cause="counted twice"),
]

# -- normal maps -------------------------------------------------------------------------------------
DECODE = "vec3 decodeNormal(vec4 t) { return normalize(t.rgb * 2.0 - 1.0); }"
DECODE_SWAPPED = "vec3 decodeSwizzled(vec4 t) { return normalize(t.grb * 2.0 - 1.0); }   // a swizzle typo"
DECODE_RAW = "vec3 decodeRaw(vec4 t) { return normalize(t.rgb); }"
DECODE_TWICE = """
vec3 unpack(vec3 t) { return t * 2.0 - 1.0; }
vec3 decodeTwice(vec4 t) { return normalize(unpack(unpack(t.rgb))); }
"""
DECODE_RG = """
vec3 decodeRG(vec2 t) {
    vec2 xy = t * 2.0 - 1.0;
    return vec3(xy, sqrt(max(0.0, 1.0 - dot(xy, xy))));
}
"""
DECODE_DX = "vec3 decodeDX(vec4 t) { vec3 n = t.rgb * 2.0 - 1.0; n.g = -n.g; return normalize(n); }"
DECODE_YUP = """
// tangent space to a y-up world whose texture v runs along world z
vec3 decodeWorld(vec4 t) { vec3 n = normalize(t.rgb * 2.0 - 1.0); return n.xzy; }
"""
DECODE_HLSL_STRENGTH = """
// an HLSL unpack with a normal strength of 2
float3 UnpackNormalStrength(float4 packed) {
    float3 n = packed.rgb * 2 - 1;
    n.xy *= 2.0;
    return normalize(n);
}
"""


def _unpack(t):
    return t[:, :3] * 2 - 1


NORMAL_MAPS = [
    Shader("decode an OpenGL normal map", "normalize(rgb · 2 − 1)", "normal_decode", DECODE, "decodeNormal",
           lambda t: normalize(_unpack(t))),
    Shader("decode a DirectX map as OpenGL", "a DirectX-green map through an OpenGL decoder", "normal_decode",
           DECODE, "decodeNormal", lambda t: normalize(_unpack(t)), cause="green channel is flipped",
           options=dict(convention="directx")),
    Shader("decode a DirectX map", "green negated", "normal_decode", DECODE_DX, "decodeDX",
           lambda t: normalize(_unpack(t) * [1, -1, 1]), options=dict(convention="directx")),
    Shader("decode with x and y swapped", "t.grb for t.rgb", "normal_decode", DECODE_SWAPPED, "decodeSwizzled",
           lambda t: normalize(t[:, [1, 0, 2]] * 2.0 - 1.0), cause="x and y are swapped"),
    Shader("decode without unpacking", "normalize(rgb)", "normal_decode", DECODE_RAW, "decodeRaw",
           lambda t: normalize(t[:, :3]), cause="not unpacked"),
    Shader("decode unpacking twice", "2(2 rgb − 1) − 1", "normal_decode", DECODE_TWICE, "decodeTwice",
           lambda t: normalize(_unpack(_unpack(t))), cause="unpacks twice"),
    Shader("decode two channels", "z from x and y", "normal_decode", DECODE_RG, "decodeRG",
           lambda t: np.column_stack([t * 2 - 1, np.sqrt(np.maximum(0, 1 - np.sum((t * 2 - 1) ** 2, 1)))]),
           options=dict(channels=2)),
    Shader("decode to a y-up world", "n.xzy", "normal_decode", DECODE_YUP, "decodeWorld",
           lambda t: normalize(_unpack(t))[:, [0, 2, 1]], options=dict(up="y")),
    Shader("a y-up decode checked as tangent space", "n.xzy where z up is asked", "normal_decode", DECODE_YUP,
           "decodeWorld", lambda t: normalize(_unpack(t))[:, [0, 2, 1]], cause="y up where z up"),
    Shader("an unpack with a normal strength of 2 (HLSL)", "n.xy × 2 before normalizing", "normal_decode",
           DECODE_HLSL_STRENGTH, "UnpackNormalStrength", lambda t: normalize(_unpack(t) * [2, 2, 1]),
           cause="scaled by 2", options=dict(language="hlsl")),
]

HEIGHT_CENTRAL = """
vec3 heightNormal(sampler2D h, vec2 uv, vec2 texel, float dx) {
    float l = texture(h, uv - vec2(texel.x, 0.0)).r;
    float r = texture(h, uv + vec2(texel.x, 0.0)).r;
    float d = texture(h, uv - vec2(0.0, texel.y)).r;
    float u = texture(h, uv + vec2(0.0, texel.y)).r;
    return normalize(vec3((l - r) / (2.0 * dx), (d - u) / (2.0 * dx), 1.0));
}
"""
HEIGHT_SWAPPED = HEIGHT_CENTRAL.replace("vec3((l - r) / (2.0 * dx), (d - u) / (2.0 * dx), 1.0)",
                                        "vec3((d - u) / (2.0 * dx), (l - r) / (2.0 * dx), 1.0)").replace(
    "heightNormal", "heightSwapped")
HEIGHT_SOBEL = """
float hs(sampler2D h, vec2 uv, vec2 t, float i, float j) { return texture(h, uv + vec2(i, j) * t).r; }
vec3 heightSobel(sampler2D h, vec2 uv, vec2 t, float dx) {
    float gx = (hs(h, uv, t, 1.0, -1.0) + 2.0 * hs(h, uv, t, 1.0, 0.0) + hs(h, uv, t, 1.0, 1.0)
              - hs(h, uv, t, -1.0, -1.0) - 2.0 * hs(h, uv, t, -1.0, 0.0) - hs(h, uv, t, -1.0, 1.0)) / (8.0 * dx);
    float gy = (hs(h, uv, t, -1.0, 1.0) + 2.0 * hs(h, uv, t, 0.0, 1.0) + hs(h, uv, t, 1.0, 1.0)
              - hs(h, uv, t, -1.0, -1.0) - 2.0 * hs(h, uv, t, 0.0, -1.0) - hs(h, uv, t, 1.0, -1.0)) / (8.0 * dx);
    return normalize(vec3(-gx, -gy, 1.0));
}
"""
HEIGHT_ONE_SIDED = """
vec3 heightForward(sampler2D h, vec2 uv, vec2 texel, float dx) {
    float c = texture(h, uv).r;
    float r = texture(h, uv + vec2(texel.x, 0.0)).r;
    float u = texture(h, uv + vec2(0.0, texel.y)).r;
    return normalize(vec3((c - r) / dx, (c - u) / dx, 1.0));
}
"""
HEIGHT_BACKWARD = """
vec3 heightBackward(sampler2D h, vec2 uv, vec2 texel, float dx) {
    float c = texture(h, uv).r;
    float l = texture(h, uv - vec2(texel.x, 0.0)).r;
    float d = texture(h, uv - vec2(0.0, texel.y)).r;
    return normalize(vec3((l - c) / dx, (d - c) / dx, 1.0));
}
"""
HEIGHT_NO_HALF = HEIGHT_CENTRAL.replace("(2.0 * dx)", "dx").replace("heightNormal", "heightNoHalf")
HEIGHT_SIGN = HEIGHT_CENTRAL.replace("(l - r)", "(r - l)").replace("(d - u)", "(u - d)").replace(
    "heightNormal", "heightSign")
HEIGHT_UNNORMALIZED = HEIGHT_CENTRAL.replace("return normalize(vec3(", "return (vec3(").replace(
    "heightNormal", "heightRaw")
HEIGHT_Y_UP = """
vec3 heightYUp(sampler2D h, vec2 uv, vec2 texel, float dx) {
    float l = texture(h, uv - vec2(texel.x, 0.0)).r;
    float r = texture(h, uv + vec2(texel.x, 0.0)).r;
    float d = texture(h, uv - vec2(0.0, texel.y)).r;
    float u = texture(h, uv + vec2(0.0, texel.y)).r;
    return normalize(vec3(l - r, 2.0 * dx, d - u));      // y up, as most engines
}
"""
HEIGHT_CLAMPED = """
vec3 heightClamped(sampler2D h, vec2 uv, vec2 texel, float dx) {
    vec2 lo = texel * 0.5, hi = 1.0 - texel * 0.5;        // clamps at the edges: the texture tiles
    float l = texture(h, clamp(uv - vec2(texel.x, 0.0), lo, hi)).r;
    float r = texture(h, clamp(uv + vec2(texel.x, 0.0), lo, hi)).r;
    float d = texture(h, clamp(uv - vec2(0.0, texel.y), lo, hi)).r;
    float u = texture(h, clamp(uv + vec2(0.0, texel.y), lo, hi)).r;
    return normalize(vec3((l - r) / (2.0 * dx), (d - u) / (2.0 * dx), 1.0));
}
"""
HEIGHT_HLSL = """
// the same central differences, with a texture and its sampler (HLSL)
float3 HeightToNormal(Texture2D heights, SamplerState samp, float2 uv, float2 texel, float dx)
{
    float l = heights.SampleLevel(samp, uv - float2(texel.x, 0), 0).r;
    float r = heights.SampleLevel(samp, uv + float2(texel.x, 0), 0).r;
    float d = heights.SampleLevel(samp, uv - float2(0, texel.y), 0).r;
    float u = heights.SampleLevel(samp, uv + float2(0, texel.y), 0).r;
    return normalize(float3((l - r) / (2 * dx), (d - u) / (2 * dx), 1));
}
"""
DISPLACED = """
// normals of a choppy surface from its displacement texture: positions of the neighbours, crossed
vec3 displacedNormal(sampler2D disp, vec2 uv, vec2 texel, float dx) {
    vec3 l = texture(disp, uv - vec2(texel.x, 0.0)).xyz + vec3(-dx, 0.0, 0.0);
    vec3 r = texture(disp, uv + vec2(texel.x, 0.0)).xyz + vec3(dx, 0.0, 0.0);
    vec3 d = texture(disp, uv - vec2(0.0, texel.y)).xyz + vec3(0.0, -dx, 0.0);
    vec3 u = texture(disp, uv + vec2(0.0, texel.y)).xyz + vec3(0.0, dx, 0.0);
    return normalize(cross(r - l, u - d));
}
"""
DISPLACED_HEIGHT_ONLY = """
// a choppy surface's normals taken from its heights alone (the displacement's z)
vec3 displacedFlat(sampler2D disp, vec2 uv, vec2 texel, float dx) {
    float l = texture(disp, uv - vec2(texel.x, 0.0)).z;
    float r = texture(disp, uv + vec2(texel.x, 0.0)).z;
    float d = texture(disp, uv - vec2(0.0, texel.y)).z;
    float u = texture(disp, uv + vec2(0.0, texel.y)).z;
    return normalize(vec3((l - r) / (2.0 * dx), (d - u) / (2.0 * dx), 1.0));
}
"""


def _central(h, uv, t, dx, sample=texture, half=2.0, sign=1.0, y_up=False, raw=False):
    def s(o):
        return sample(h, uv + o)[:, :1]
    zero = np.zeros_like(t[:, :1])
    l, r = s(np.column_stack([-t[:, :1], zero])), s(np.column_stack([t[:, :1], zero]))
    d, u = s(np.column_stack([zero, -t[:, 1:]])), s(np.column_stack([zero, t[:, 1:]]))
    if y_up:
        return normalize(np.column_stack([l - r, 2 * dx, d - u]))
    v = np.column_stack([sign * (l - r) / (half * dx), sign * (d - u) / (half * dx), np.ones_like(l)])
    return v if raw else normalize(v)


def _sobel(h, uv, t, dx):
    def s(i, j):
        return texture(h, uv + np.column_stack([i * t[:, 0], j * t[:, 1]]))[:, :1]
    gx = (s(1, -1) + 2 * s(1, 0) + s(1, 1) - s(-1, -1) - 2 * s(-1, 0) - s(-1, 1)) / (8 * dx)
    gy = (s(-1, 1) + 2 * s(0, 1) + s(1, 1) - s(-1, -1) - 2 * s(0, -1) - s(1, -1)) / (8 * dx)
    return normalize(np.column_stack([-gx, -gy, np.ones_like(gx)]))


def _forward(h, uv, t, dx):
    c = texture(h, uv)[:, :1]
    r = texture(h, uv + np.column_stack([t[:, 0], 0 * t[:, 0]]))[:, :1]
    u = texture(h, uv + np.column_stack([0 * t[:, 1], t[:, 1]]))[:, :1]
    return normalize(np.column_stack([(c - r) / dx, (c - u) / dx, np.ones_like(c)]))


def _backward(h, uv, t, dx):
    c = texture(h, uv)[:, :1]
    l = texture(h, uv - np.column_stack([t[:, 0], 0 * t[:, 0]]))[:, :1]
    d = texture(h, uv - np.column_stack([0 * t[:, 1], t[:, 1]]))[:, :1]
    return normalize(np.column_stack([(l - c) / dx, (d - c) / dx, np.ones_like(c)]))


def _displaced(p, uv, t, dx, heights_only=False):
    def s(o):
        return texture(p, uv + o)[:, :3]
    zero = np.zeros_like(t[:, :1])
    ox, oy = np.column_stack([t[:, :1], zero]), np.column_stack([zero, t[:, 1:]])
    if heights_only:
        l, r, d, u = (s(o)[:, 2:3] for o in (-ox, ox, -oy, oy))
        return normalize(np.column_stack([(l - r) / (2 * dx), (d - u) / (2 * dx), np.ones_like(l)]))
    ex, ey = np.column_stack([dx, zero, zero]), np.column_stack([zero, dx, zero])
    ex = np.column_stack([dx * np.ones_like(zero), zero, zero])
    ey = np.column_stack([zero, dx * np.ones_like(zero), zero])
    return normalize(np.cross((s(ox) + ex) - (s(-ox) - ex), (s(oy) + ey) - (s(-oy) - ey)))


HEIGHTS = [
    Shader("central differences", "the textbook 4-tap normal", "height_normal", HEIGHT_CENTRAL, "heightNormal",
           _central),
    Shader("Sobel filter", "a 3×3 Sobel normal", "height_normal", HEIGHT_SOBEL, "heightSobel", _sobel),
    Shader("one-sided differences", "(h₊ − h)/Δx", "height_normal", HEIGHT_ONE_SIDED, "heightForward", _forward,
           cause="one-sided differences (h₊ − h)/Δx"),
    Shader("backward differences", "(h − h₋)/Δx, the other one-sided stencil", "height_normal", HEIGHT_BACKWARD,
           "heightBackward", _backward, cause="one-sided differences (h − h₋)/Δx"),
    Shader("slopes in the wrong components", "the y slope written to x and the x slope to y", "height_normal",
           HEIGHT_SWAPPED, "heightSwapped", lambda *a: _central(*a)[:, [1, 0, 2]], cause="x and y are swapped"),
    Shader("central difference not halved", "(h₊ − h₋)/Δx", "height_normal", HEIGHT_NO_HALF, "heightNoHalf",
           lambda *a: _central(*a, half=1.0), cause="not divided by 2"),
    Shader("slopes of the wrong sign", "(h₊ − h₋) for (h₋ − h₊)", "height_normal", HEIGHT_SIGN, "heightSign",
           lambda *a: _central(*a, sign=-1.0), cause="wrong sign"),
    Shader("normal not normalized", "the vector returned as is", "height_normal", HEIGHT_UNNORMALIZED, "heightRaw",
           lambda *a: _central(*a, raw=True), cause="not normalized"),
    Shader("y-up normal checked as z-up", "(l − r, 2Δx, d − u)", "height_normal", HEIGHT_Y_UP, "heightYUp",
           lambda *a: _central(*a, y_up=True), cause="up axis is y"),
    Shader("y-up normal checked as y-up", "the same with up stated", "height_normal", HEIGHT_Y_UP, "heightYUp",
           lambda *a: _central(*a, y_up=True), options=dict(up="y")),
    Shader("clamped at the texture's edges", "uv clamped on a tiling texture", "height_normal", HEIGHT_CLAMPED,
           "heightClamped", lambda *a: _central(*a, sample=texture_clamped), cause="only at the texture's border"),
    Shader("central differences (HLSL)", "Texture2D + SamplerState", "height_normal", HEIGHT_HLSL, "HeightToNormal",
           _central, options=dict(language="hlsl")),
    Shader("a choppy surface's normals from its displacement", "cross of neighbour positions", "height_normal",
           DISPLACED, "displacedNormal", _displaced),
    Shader("a choppy surface's normals from its heights alone", "the horizontal displacement ignored",
           "height_normal", DISPLACED_HEIGHT_ONLY, "displacedFlat", lambda *a: _displaced(*a, heights_only=True),
           cause="ignores the horizontal displacement"),
]

CORPUS = FRESNEL + RAYS + ABSORPTION + NORMAL_MAPS + HEIGHTS
"""Every entry, by check."""
