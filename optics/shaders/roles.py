"""What each parameter of a user's shader function is: the roles a check feeds, and reading them from names.

A check feeds a function's parameters by *role* (``cos_theta``, ``f0``, ``incident``, …). The
user may say the role of each (``takes=``); when they do not, and the function's parameters do
not match the check's default roles, :func:`infer_takes` reads the roles from the parameters'
names and types — what the code itself states (``float cosTheta, float F0`` is ``cos_theta, f0``;
``vec3 I, vec3 N, float eta`` is ``incident, facing_normal, eta``). A name it cannot place, or
two parameters that claim one role, are refused by name, never guessed.
"""

from __future__ import annotations

import re

__internal__ = True  # the runner's pieces: users call optics.shaders.check_glsl
__all__ = ["ROLES", "SIDE_ROLES", "NAMES", "infer_takes", "role_type", "is_constant"]

ROLES = {
    "cos_theta": ("float", "cos θ of the incoming ray against the normal, in the incident medium (0 grazing, 1 normal)"),
    "cos_theta_t": ("float", "cos θt of the transmitted (refracted) ray; 0 under total internal reflection"),
    "n1": ("float", "refractive index of the incident medium"),
    "n2": ("float", "refractive index beyond the surface"),
    "eta": ("float", "n1 / n2"),
    "ior": ("float", "water's refractive index relative to air (air taken as 1), whichever side the ray is on"),
    "f0": ("float", "reflectance at normal incidence, ((n1 − n2)/(n1 + n2))²"),
    "f0_rgb": ("vec3", "reflectance at normal incidence as a colour (a PBR F0), the same in every channel"),
    "front_facing": ("bool", "true when the ray comes from the air (the water's front face), as gl_FrontFacing"),
    "incident": ("vec3", "unit direction of travel of the incoming ray (towards the surface)"),
    "view": ("vec3", "unit vector from the surface back along the incoming ray (−incident; engines' V)"),
    "normal": ("vec3", "unit surface normal pointing into the air, whichever side the ray comes from"),
    "facing_normal": ("vec3", "unit surface normal facing the incoming ray (dot(incident, N) < 0), as GLSL's "
                              "refract and reflect want it"),
    "reflected_color": ("vec3", "radiance arriving along the reflected ray (fed white, 1): the result is R × it "
                                "plus T × the refracted colour"),
    "refracted_color": ("vec3", "radiance arriving along the refracted ray (fed black, 0)"),
    "distance": ("float", "path length through the water, m"),
    "coefficient": ("float", "absorption coefficient, 1/m"),
    "coefficients": ("vec3", "RGB absorption coefficients, 1/m"),
    "color": ("vec3", "the colour the absorption acts on (fed white, 1): the result is T × it"),
    "texel": ("vec4", "the normal map's texel as the shader samples it (alpha 1)"),
    "texel_rgb": ("vec3", "the normal map's texel, RGB only"),
    "texel_rg": ("vec2", "a two-channel normal map's texel (z to be reconstructed)"),
    "heights": ("sampler2D", "height texture: metres in red, repeat wrap, linear filter, row 0 at v = 0"),
    "displacement": ("sampler2D", "displacement texture of a choppy surface: RGB = (Dx, Dy, height) in metres for "
                                  "z up, (Dx, height, Dz) for y up; repeat wrap, linear filter"),
    "uv": ("vec2", "texture coordinate of a texel centre"),
    "texel_uv": ("vec2", "one texel in texture coordinates (1/width, 1/height)"),
    "texel_size": ("float", "one texel, m"),
}
"""Argument roles: name → (GLSL type, meaning). A user says which role each parameter plays (``takes``)."""

SIDE_ROLES = ("n1", "n2", "eta", "front_facing", "incident", "view", "normal", "facing_normal", "cos_theta_t")
"""Roles that tell a function which side of the surface the ray comes from. A Fresnel or refraction function
that takes none of them (and does not read gl_FrontFacing) cannot tell, and is checked from the air side."""

# Parameter names as public engines, tutorials and books write them (lower case, underscores dropped), by role.
NAMES = {
    "cos_theta": ("c", "cos", "costheta", "costhetai", "cosi", "costhetaincident", "cosine", "cosangle", "ndotv",
                  "vdotn", "nov", "nv", "ndotview", "viewdotnormal", "mu", "mui", "cosincident", "costheta1", "cos1",
                  "hdotv", "vdoth", "voh", "ldoth", "coscritical", "x", "angle", "cosview", "facing"),
    "cos_theta_t": ("ct", "cost", "costhetat", "costransmitted", "costheta2", "cos2", "cosr", "costhetar", "cosrefr",
                    "cosrefracted", "mut"),
    "n1": ("n1", "eta1", "etai", "ior1", "iori", "ni", "nair", "nfrom", "iorin", "nincident", "etaincident", "n0"),
    "n2": ("n2", "eta2", "etat", "ior2", "iort", "nt", "nwater", "nto", "iorout", "ntransmitted", "etatransmitted"),
    "eta": ("eta", "ratio", "iorratio", "etaratio", "n1n2", "n1overn2", "relativeior", "eta12", "refractionratio",
            "indexratio", "etai_etat", "etaiovereta"),
    "ior": ("ior", "n", "index", "refractiveindex", "indexofrefraction", "iorwater", "wateriior", "wateri", "waterior",
            "refractionindex"),
    "f0": ("f0", "r0", "fresnel0", "specular", "reflectance0", "f0water", "basereflectance", "spec", "specularcolor",
           "fresnelbias", "bias", "minreflectance", "fresnelmin", "reflectivity", "specularf0", "f0value"),
    "f0_rgb": ("f0", "r0", "fresnel0", "specular", "reflectance0", "f0water", "basereflectance", "spec",
               "specularcolor", "fresnelbias", "reflectivity", "specularf0", "f0color", "f0rgb", "speccolor"),
    "front_facing": ("frontfacing", "isfrontface", "frontface", "above", "fromabove", "isabove", "abovewater",
                     "outside", "entering", "isentering", "frontfacingside"),
    "incident": ("i", "incident", "dir", "raydir", "rd", "d", "indir", "incoming", "incidentdir", "ray", "direction",
                 "rdir", "raydirection", "incidentvector", "viewray", "camray", "eyeray", "camerara", "rayws",
                 "viewrayw", "viewrayws", "raydirws", "cameraray"),
    "view": ("v", "view", "viewdir", "toeye", "tocamera", "wo", "viewvector", "toviewer", "viewdirection", "vdir",
             "viewws", "viewdirws", "tocam", "eyevec", "eyevector"),
    "normal": ("n", "normal", "nrm", "norm", "surfnormal", "wn", "worldnormal", "surfacenormal", "nw", "normalws",
               "waternormal"),
    "facing_normal": ("n", "normal", "nrm", "norm", "facingnormal", "nf", "ffnormal", "surfnormal", "worldnormal",
                      "surfacenormal"),
    "reflected_color": ("reflection", "refl", "sky", "reflected", "reflcol", "reflectioncolor", "reflectedcolor",
                        "skycolor", "envcolor", "env", "reflectcolor", "specularcolor_in"),
    "refracted_color": ("refraction", "refr", "refracted", "refrcol", "refractioncolor", "refractedcolor", "under",
                        "watercolor", "underwater", "transmitted", "scene", "bottom", "refractcolor"),
    "distance": ("d", "dist", "distance", "pathlength", "path", "len", "length", "t", "thickness", "l", "depth",
                 "waterdepth", "traveled", "travelled", "z"),
    "coefficient": ("a", "sigma", "absorption", "coeff", "coefficient", "extinction", "mu", "sigmaa", "absorb",
                    "attenuation", "k", "kappa", "absorptioncoefficient", "density"),
    "coefficients": ("a", "sigma", "absorption", "coeff", "coefficients", "extinction", "mu", "sigmaa", "absorb",
                     "attenuation", "k", "kappa", "absorptioncoefficients", "absorptioncolor", "density"),
    "color": ("color", "col", "c", "radiance", "light", "albedo", "rgb", "colour", "incolor", "scenecolor", "src"),
    "uv": ("uv", "texcoord", "tc", "coord", "st", "uv0", "texcoords", "p", "pos", "coords"),
    "texel_uv": ("texel", "texelsize", "invsize", "pixel", "onepixel", "step", "delta", "texelsizeuv", "offset",
                 "texeluv", "e", "eps", "du", "duv", "invres", "invresolution", "pixelsize"),
    "heights": ("h", "height", "heights", "heightmap", "heighttex", "heighttexture", "heightfield", "hmap", "tex",
                "heightsampler", "water", "waterheight"),
    "displacement": ("disp", "displacement", "displace", "dispmap", "displacementmap", "disptex", "offsets",
                     "displacementtex", "displacementtexture"),
    "texel_size": ("dx", "texelsize", "cellsize", "gridspacing", "texelworld", "worldtexel", "spacing", "h",
                   "texelmeters", "texelmetres", "scale", "worldscale", "size", "meterspertexel", "dxworld", "step",
                   "gridsize", "texelsizeworld"),
}
"""Parameter names by role (lower case, underscores dropped) that :func:`infer_takes` recognizes."""


def is_constant(role) -> bool:
    """Whether a ``takes`` entry is a number: a parameter held at that value rather than fed by a role.

    Parameters
    ----------
    role : str or float
        A ``takes`` entry.

    Returns
    -------
    bool
    """
    return isinstance(role, (int, float)) and not isinstance(role, bool)


def role_type(role) -> str:
    """The GLSL type a ``takes`` entry feeds (a constant is a float).

    Parameters
    ----------
    role : str or float
        A ``takes`` entry.

    Returns
    -------
    str
    """
    return "float" if is_constant(role) else ROLES[role][0]


def _key(name: str) -> str:
    return name.lower().replace("_", "")


def infer_takes(check, decl) -> tuple:
    """The role of each value-taking parameter of ``decl`` for ``check``, from the parameters' names and types.

    Parameters
    ----------
    check : ShaderCheck
        The check (its ``roles`` are the candidates; its default ``takes`` win when the types match).
    decl : Declaration
        The function.

    Returns
    -------
    (tuple of str, str)
        The roles, in order, and how they were found (``""`` for the check's defaults, else a note
        "takes read from the names: cosTheta → cos_theta, …").

    Raises
    ------
    GLSLError
        When a parameter's name says no role the check feeds, or two parameters claim one role.
    """
    from optics.shaders.glsl import GLSLError

    inputs = decl.inputs
    defaults = tuple(p.type for p in inputs) == tuple(ROLES[r][0] for r in check.takes)
    chosen, unplaced = [], []
    for p in inputs:
        key = _key(p.name)
        fits = [r for r in check.roles if ROLES[r][0] == p.type and key in NAMES.get(r, ())]
        if len(fits) > 1:  # "N" is a normal for Fresnel and a facing normal for refract: the check's default wins
            fits = [r for r in fits if r in check.takes] or fits[:1]
        if not fits:  # a type that only one of the check's roles has (a sampler2D, a vec4 texel) is that role
            typed = [r for r in check.roles if ROLES[r][0] == p.type]
            fits = typed if len(typed) == 1 else []
        if not fits:
            unplaced.append(p)
            chosen.append(None)
        else:
            chosen.append(fits[0])
    taken = [r for r in chosen if r is not None]
    doubled = sorted({r for r in taken if taken.count(r) > 1})
    if defaults and (unplaced or doubled or tuple(chosen) == tuple(check.takes)):
        return tuple(check.takes), ""  # the names say nothing else: the check's own roles, by their types
    if unplaced or doubled:
        what = []
        if unplaced:
            what.append("cannot tell what " + ", ".join(f"{p.type} {p.name}" for p in unplaced) + " is")
        if doubled:
            what.append("two parameters read as " + ", ".join(doubled))
        roles = ", ".join(f"{r} ({ROLES[r][0]})" for r in check.roles)
        raise GLSLError(f"takes: {decl.signature()}: {'; '.join(what)}: say the role of each parameter with "
                        f"takes=(...) (--takes a,b,…), or a number for a parameter the check should hold fixed (a "
                        f"curve's exponent: takes=(5.0, 'normal', 'view')); the roles of {check.name!r}: {roles}")
    how = ", ".join(f"{p.name} → {r}" for p, r in zip(inputs, chosen))
    return tuple(chosen), f"takes read from the parameter names: {how}"
