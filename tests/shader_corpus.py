"""A corpus of shader functions written the way engines write them, correct and broken, with the
verdict and the cause the shader checks must give each (``tests/shaders/test_shaders.py``).

Each entry: (name, against, source, function, options, ok, cause). ``options`` go to
``check_glsl`` (``takes``, domain options); ``cause`` is a fragment the report's cause must
contain ("" for a correct function).
"""

SCHLICK_F0 = """
// The PBR engines' Schlick term with F0 given (learnopengl.com, UE4's shading model)
float fresnelSchlick(float cosTheta, float F0) {
    return F0 + (1.0 - F0) * pow(clamp(1.0 - cosTheta, 0.0, 1.0), 5.0);
}
"""

SCHLICK_INDICES = """
float schlick(float cos_i, float n1, float n2) {
    float r0 = (n1 - n2) / (n1 + n2);
    r0 *= r0;
    return r0 + (1.0 - r0) * pow(1.0 - cos_i, 5.0);
}
"""

SCHLICK_TIR = """
// Schlick from both sides: from the denser side use the transmitted angle, and R = 1 past it
float schlick_tir(float cos_i, float n1, float n2) {
    float r0 = (n1 - n2) / (n1 + n2);
    r0 *= r0;
    float c = cos_i;
    if (n1 > n2) {
        float s2 = (n1 / n2) * (n1 / n2) * (1.0 - cos_i * cos_i);
        if (s2 > 1.0) return 1.0;
        c = sqrt(1.0 - s2);
    }
    float x = 1.0 - c;
    return r0 + (1.0 - r0) * x * x * x * x * x;
}
"""

FRESNEL_EXACT = """
// Full dielectric Fresnel written with eta and the transmitted cosine (pbrt's FrDielectric)
float fr_dielectric(float cosThetaI, float etaI, float etaT) {
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

FRESNEL_INVERTED = FRESNEL_EXACT.replace("float sinThetaT = etaI / etaT * sinThetaI;",
                                         "float sinThetaT = etaT / etaI * sinThetaI;").replace(
    "fr_dielectric", "fr_inverted")

SCHLICK_WRONG_RAY = """
// Schlick with the refracted ray's cosine on both sides
float schlick_t(float cos_i, float n1, float n2) {
    float r0 = pow((n1 - n2) / (n1 + n2), 2.0);
    float s2 = (n1 / n2) * (n1 / n2) * (1.0 - cos_i * cos_i);
    if (s2 > 1.0) return 1.0;
    float ct = sqrt(1.0 - s2);
    return r0 + (1.0 - r0) * pow(1.0 - ct, 5.0);
}
"""

SCHLICK_VECTORS = """
uniform float uF0;
float fresnel(vec3 V, vec3 N) {
    float NdotV = max(dot(N, V), 0.0);   // the usual clamp: negative from under the surface
    return uF0 + (1.0 - uF0) * pow(1.0 - NdotV, 5.0);
}
"""

SCHLICK_NOT_SQUARED = """
float schlick_r0(float c, float n1, float n2) {
    float r0 = abs((n1 - n2) / (n1 + n2));   // forgot to square
    return r0 + (1.0 - r0) * pow(1.0 - c, 5.0);
}
"""

JENSEN_GOLIAS = """
// Deep-water animation and rendering (Jensen & Golias 2001): a cheap Fresnel from air
float fresnel_cheap(float c) { return 1.0 / pow(1.0 + c, 8.0); }
"""

REFRACT_BUILTIN = "vec3 refr(vec3 I, vec3 N, float eta) { return refract(I, N, eta); }"

REFRACT_UP_NORMAL = """
uniform float uIorAir;
uniform float uIorWater;
// The water normal always points up; from below the engine forgot to flip it
vec3 refr_up(vec3 I, vec3 N, float n1, float n2) { return refract(I, N, n1 / n2); }
"""

REFRACT_INVERTED = "vec3 refr_inv(vec3 I, vec3 N, float eta) { return refract(I, N, 1.0 / eta); }"

REFRACT_NO_TIR = """
vec3 refr_manual(vec3 I, vec3 N, float eta) {
    float cosi = dot(-I, N);
    float k = 1.0 - eta * eta * (1.0 - cosi * cosi);
    return eta * I + (eta * cosi - sqrt(k)) * N;      // no k < 0 test
}
"""

REFLECT_BUILTIN = "vec3 refl(vec3 I, vec3 N) { return reflect(I, N); }"
REFLECT_VIEW = "vec3 refl_v(vec3 V, vec3 N) { return reflect(V, N); }   // V points to the eye"

BEER = "vec3 beer(float d, vec3 sigma) { return exp(-sigma * d); }"
BEER_SCALAR = "float beer1(float d, float a) { return exp(-a * d); }"
BEER_TWICE = """
// absorption on the way down to the floor and back up: the path is counted twice
vec3 beer2(float d, vec3 sigma) { return exp(-sigma * 2.0 * d); }
"""
BEER_BGR = "vec3 beer_bgr(float d, vec3 sigma) { return exp(-sigma.bgr * d); }"
BEER_LINEAR = "vec3 beer_lin(float d, vec3 sigma) { return clamp(1.0 - sigma * d, 0.0, 1.0); }"
BEER_EXP2 = "vec3 beer_exp2(float d, vec3 sigma) { return exp2(-sigma * d); }"

WATER_FIT = "vec3 water_tint(float d) { return exp(-vec3(0.3353, 0.05035, 0.000547) * d); }"
WATER_BGR = "vec3 water_bgr(float d) { return exp(-vec3(0.000547, 0.05035, 0.3353) * d); }"
WATER_PER_CM = "vec3 water_cm(float d) { return exp(-vec3(0.3353, 0.05035, 0.000547) * d * 100.0); }"

DECODE = "vec3 decode(vec4 t) { return normalize(t.rgb * 2.0 - 1.0); }"
DECODE_RAW = "vec3 decode_raw(vec4 t) { return normalize(t.rgb); }"
DECODE_TWICE = """
vec3 unpack(vec3 t) { return t * 2.0 - 1.0; }
vec3 decode_twice(vec4 t) { return normalize(unpack(unpack(t.rgb))); }
"""
DECODE_RG = """
vec3 decode_rg(vec2 t) {
    vec2 xy = t * 2.0 - 1.0;
    return vec3(xy, sqrt(max(0.0, 1.0 - dot(xy, xy))));
}
"""
DECODE_DX = "vec3 decode_dx(vec4 t) { vec3 n = t.rgb * 2.0 - 1.0; n.g = -n.g; return normalize(n); }"

HEIGHT_CENTRAL = """
vec3 height_normal(sampler2D h, vec2 uv, vec2 texel, float dx) {
    float l = texture(h, uv - vec2(texel.x, 0.0)).r;
    float r = texture(h, uv + vec2(texel.x, 0.0)).r;
    float d = texture(h, uv - vec2(0.0, texel.y)).r;
    float u = texture(h, uv + vec2(0.0, texel.y)).r;
    return normalize(vec3((l - r) / (2.0 * dx), (d - u) / (2.0 * dx), 1.0));
}
"""
HEIGHT_SOBEL = """
float hs(sampler2D h, vec2 uv, vec2 t, float i, float j) { return texture(h, uv + vec2(i, j) * t).r; }
vec3 height_sobel(sampler2D h, vec2 uv, vec2 t, float dx) {
    float gx = (hs(h, uv, t, 1.0, -1.0) + 2.0 * hs(h, uv, t, 1.0, 0.0) + hs(h, uv, t, 1.0, 1.0)
              - hs(h, uv, t, -1.0, -1.0) - 2.0 * hs(h, uv, t, -1.0, 0.0) - hs(h, uv, t, -1.0, 1.0)) / (8.0 * dx);
    float gy = (hs(h, uv, t, -1.0, 1.0) + 2.0 * hs(h, uv, t, 0.0, 1.0) + hs(h, uv, t, 1.0, 1.0)
              - hs(h, uv, t, -1.0, -1.0) - 2.0 * hs(h, uv, t, 0.0, -1.0) - hs(h, uv, t, 1.0, -1.0)) / (8.0 * dx);
    return normalize(vec3(-gx, -gy, 1.0));
}
"""
HEIGHT_ONE_SIDED = """
vec3 height_fwd(sampler2D h, vec2 uv, vec2 texel, float dx) {
    float c = texture(h, uv).r;
    float r = texture(h, uv + vec2(texel.x, 0.0)).r;
    float u = texture(h, uv + vec2(0.0, texel.y)).r;
    return normalize(vec3((c - r) / dx, (c - u) / dx, 1.0));
}
"""
HEIGHT_NO_HALF = HEIGHT_CENTRAL.replace("(2.0 * dx)", "dx").replace("height_normal", "height_no_half")
HEIGHT_SIGN = HEIGHT_CENTRAL.replace("(l - r)", "(r - l)").replace("(d - u)", "(u - d)").replace(
    "height_normal", "height_sign")
HEIGHT_UNNORMALIZED = HEIGHT_CENTRAL.replace("return normalize(vec3(", "return (vec3(").replace(
    "height_normal", "height_raw")
HEIGHT_Y_UP = """
vec3 height_yup(sampler2D h, vec2 uv, vec2 texel, float dx) {
    float l = texture(h, uv - vec2(texel.x, 0.0)).r;
    float r = texture(h, uv + vec2(texel.x, 0.0)).r;
    float d = texture(h, uv - vec2(0.0, texel.y)).r;
    float u = texture(h, uv + vec2(0.0, texel.y)).r;
    return normalize(vec3(l - r, 2.0 * dx, d - u));      // y up, as most engines
}
"""
HEIGHT_CLAMPED = """
vec3 height_clamped(sampler2D h, vec2 uv, vec2 texel, float dx) {
    vec2 lo = texel * 0.5, hi = 1.0 - texel * 0.5;        // clamps at the edges: the texture tiles
    float l = texture(h, clamp(uv - vec2(texel.x, 0.0), lo, hi)).r;
    float r = texture(h, clamp(uv + vec2(texel.x, 0.0), lo, hi)).r;
    float d = texture(h, clamp(uv - vec2(0.0, texel.y), lo, hi)).r;
    float u = texture(h, clamp(uv + vec2(0.0, texel.y), lo, hi)).r;
    return normalize(vec3((l - r) / (2.0 * dx), (d - u) / (2.0 * dx), 1.0));
}
"""

_HN = dict(takes=("heights", "uv", "texel_uv", "texel_size"))
CORPUS = [
    # Fresnel
    ("fresnel exact (pbrt)", "fresnel", FRESNEL_EXACT, "fr_dielectric", {}, True, ""),
    ("Schlick with F0, from air", "fresnel", SCHLICK_F0, "fresnelSchlick",
     dict(takes=("cos_theta", "f0"), form="schlick", sides=("above",)), True, ""),
    ("Schlick with TIR, both sides", "fresnel", SCHLICK_TIR, "schlick_tir", dict(form="schlick"), True, ""),
    ("Schlick without TIR from below", "fresnel", SCHLICK_INDICES, "schlick", dict(form="schlick"), False,
     "no total internal reflection from below"),
    ("Schlick F0 = 0.04 (glass) for water", "fresnel", SCHLICK_F0.replace("float F0)", "float unused)").replace(
        "return F0", "float F0 = 0.04;\n    return F0"), "fresnelSchlick",
     dict(takes=("cos_theta", "f0"), form="schlick", sides=("above",)), False, "F0 from the wrong indices"),
    ("Schlick, r0 not squared", "fresnel", SCHLICK_NOT_SQUARED, "schlick_r0", dict(form="schlick", sides="above"),
     False, "not squared"),
    ("Schlick of dot(N, V) clamped, from below", "fresnel", SCHLICK_VECTORS, "fresnel",
     dict(takes=("view", "normal"), form="schlick", uniforms={"uF0": 0.0204}), False, "clamp"),
    ("exact Fresnel with the index ratio inverted", "fresnel", FRESNEL_INVERTED, "fr_inverted", {}, False,
     "index ratio is inverted"),
    ("Schlick with the refracted ray's cosine", "fresnel", SCHLICK_WRONG_RAY, "schlick_t", dict(form="schlick"),
     False, "wrong ray"),
    ("Jensen-Golias checked as exact", "fresnel", JENSEN_GOLIAS, "fresnel_cheap",
     dict(takes=("cos_theta",), sides="above"), False, "jensen_golias form"),
    ("Jensen-Golias as itself", "fresnel", JENSEN_GOLIAS, "fresnel_cheap",
     dict(takes=("cos_theta",), form="jensen_golias"), True, ""),
    # refraction and reflection
    ("GLSL refract", "refract", REFRACT_BUILTIN, "refr", {}, True, ""),
    ("refract with the up normal from below", "refract", REFRACT_UP_NORMAL, "refr_up",
     dict(takes=("incident", "normal", "n1", "n2")), False, "from below, the normal faces the wrong way"),
    ("refract with 1/eta", "refract", REFRACT_INVERTED, "refr_inv", {}, False, "index ratio is inverted"),
    ("hand-written refract without a TIR test", "refract", REFRACT_NO_TIR, "refr_manual", {}, False,
     "NaN past the critical angle"),
    ("GLSL reflect", "reflect", REFLECT_BUILTIN, "refl", {}, True, ""),
    ("reflect of the view vector", "reflect", REFLECT_VIEW, "refl_v", dict(takes=("view", "facing_normal")), False,
     "mirrored view vector"),
    # absorption
    ("Beer-Lambert RGB", "transmittance", BEER, "beer", {}, True, ""),
    ("Beer-Lambert, one channel", "transmittance", BEER_SCALAR, "beer1", dict(takes=("distance", "coefficient")),
     True, ""),
    ("Beer-Lambert, path counted twice", "transmittance", BEER_TWICE, "beer2", {}, False, "counted twice"),
    ("Beer-Lambert, channels reversed", "transmittance", BEER_BGR, "beer_bgr", {}, False, "reversed"),
    ("linear absorption", "transmittance", BEER_LINEAR, "beer_lin", {}, False, "not exponential"),
    ("exp2 absorption", "transmittance", BEER_EXP2, "beer_exp2", {}, False, "exp2"),
    ("pure-water RGB fit", "rgb_absorption", WATER_FIT, "water_tint", {}, True, ""),
    ("water colour, channels reversed", "rgb_absorption", WATER_BGR, "water_bgr", {}, False, "reversed"),
    ("water colour, coefficients per cm", "rgb_absorption", WATER_PER_CM, "water_cm", {}, False, "per cm"),
    # normal maps
    ("decode an OpenGL normal map", "normal_decode", DECODE, "decode", {}, True, ""),
    ("decode a DirectX map as OpenGL", "normal_decode", DECODE, "decode", dict(convention="directx"), False,
     "green channel is flipped"),
    ("decode a DirectX map", "normal_decode", DECODE_DX, "decode_dx", dict(convention="directx"), True, ""),
    ("decode without unpacking", "normal_decode", DECODE_RAW, "decode_raw", {}, False, "not unpacked"),
    ("decode unpacking twice", "normal_decode", DECODE_TWICE, "decode_twice", {}, False, "unpacks twice"),
    ("decode two channels", "normal_decode", DECODE_RG, "decode_rg", dict(takes=("texel_rg",), channels=2), True, ""),
    ("unpack a float normal map", "normal_decode", DECODE, "decode", dict(packed=False, bits=None), False,
     "holds n itself"),
    # normals from heights
    ("central differences", "height_normal", HEIGHT_CENTRAL, "height_normal", _HN, True, ""),
    ("Sobel filter", "height_normal", HEIGHT_SOBEL, "height_sobel", _HN, True, ""),
    ("one-sided differences", "height_normal", HEIGHT_ONE_SIDED, "height_fwd", _HN, False, "one-sided"),
    ("central difference not halved", "height_normal", HEIGHT_NO_HALF, "height_no_half", _HN, False,
     "not divided by 2"),
    ("slopes of the wrong sign", "height_normal", HEIGHT_SIGN, "height_sign", _HN, False, "wrong sign"),
    ("normal not normalized", "height_normal", HEIGHT_UNNORMALIZED, "height_raw", _HN, False, "not normalized"),
    ("y-up normal checked as z-up", "height_normal", HEIGHT_Y_UP, "height_yup", _HN, False, "up axis is y"),
    ("y-up normal checked as y-up", "height_normal", HEIGHT_Y_UP, "height_yup", dict(_HN, up="y"), True, ""),
    ("clamped at the texture's edges", "height_normal", HEIGHT_CLAMPED, "height_clamped", _HN, False,
     "only at the texture's border"),
]
