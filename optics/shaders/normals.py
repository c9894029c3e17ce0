"""Shader checks of normals: decoding a normal map's texel, and normals from a height or displacement texture.

``normal_decode`` feeds texels of known normals, encoded as the texture holds them (OpenGL or
DirectX green, packed or float, 8/10/16 bits, two or three channels), and expects the unit
normal back, z up or y up (``up=``). ``height_normal`` feeds a periodic band-limited height
texture (or a choppy surface's displacement texture, the role ``displacement``) and expects the
normals of its surface from spectral slopes; the stencil and scale a failing function uses are
fitted (central differences not halved, one-sided differences, slopes scaled by a factor).
"""

from __future__ import annotations

import math

import numpy as np

from optics.shaders.domain import Domain, f32, length_cause, samples_option, tolerance_option, unit, vector_error
from optics.shaders.models import Model, Param

__internal__ = True  # the registry's pieces: users call optics.shaders.check_glsl
__all__ = ["normal_decode_domain", "normal_decode_late", "height_normal_domain", "height_normal_late"]


def _hemisphere(n, max_angle=80.0):
    """Unit normals on the upper hemisphere up to ``max_angle`` from +z (a Fibonacci spiral)."""
    i = np.arange(n) + 0.5
    cos = 1.0 - (1.0 - math.cos(math.radians(max_angle))) * i / n
    phi = i * math.pi * (3.0 - math.sqrt(5.0))
    s = np.sqrt(1.0 - cos ** 2)
    return np.column_stack([s * np.cos(phi), s * np.sin(phi), cos])


def _encode(normals, convention, packed, bits, channels):
    e = normals * np.array([1.0, -1.0 if convention == "directx" else 1.0, 1.0])
    t = 0.5 + 0.5 * e if packed else e
    if bits is not None:
        q = 2 ** bits - 1
        t = np.round(t * q) / q
    if channels == 2:
        t[:, 2] = 0.0
    return f32(t)


def _decode_exact(texel, convention, packed, channels):
    e = 2.0 * texel - 1.0 if packed else texel.copy()
    if channels == 2:
        e[:, 2] = np.sqrt(np.clip(1.0 - e[:, 0] ** 2 - e[:, 1] ** 2, 0.0, None))
    e[:, 1] *= -1.0 if convention == "directx" else 1.0
    return unit(e)


def _swizzle(v, up):
    return v if up == "z" else v[..., [0, 2, 1]]


def normal_decode_domain(*, convention="opengl", packed=True, bits=8, channels=3, samples=4096, up="z",
                         tolerance=None):
    """Decoding a normal map's texel: unit normals up to 80° from +z, encoded as the texture
    holds them (``convention`` "opengl": green = +y, "directx": green = −y; ``packed``:
    rgb = 0.5 + 0.5 n, else n itself; ``bits``: 8, 10, 16 or None (float); ``channels`` 3 or 2,
    z reconstructed). The decoded normal must be the tangent-space normal, z up (``up="z"``), or
    the world normal of a y-up engine whose texture v runs along world z (``up="y"``: n.xzy).
    Default tolerance: 1.5 × an exact decoder's error on the same quantized texels.

    Parameters
    ----------
    convention : str, keyword-only
        ``"opengl"`` or ``"directx"``.
    packed : bool, keyword-only
        rgb = 0.5 + 0.5 n.
    bits : int or None, keyword-only
        8, 10, 16 or None (float).
    channels : int, keyword-only
        3, or 2 (z reconstructed).
    samples : int, keyword-only
        Normals checked.
    up : str, keyword-only
        ``"z"`` or ``"y"``.
    tolerance : float, optional, keyword-only
        Overrides the default.

    Returns
    -------
    Domain
        The inputs, the tolerance, and the correct and faulty models.
    """
    from wavephys.core.inputs import check_bool, check_choice

    check_choice("convention", convention, ("opengl", "directx"))
    check_bool("packed", packed)
    check_choice("bits", bits, (8, 10, 16, None))
    check_choice("channels", channels, (2, 3))
    check_choice("up", up, ("z", "y"))
    if bits is not None and not packed:
        raise ValueError("bits must be None when packed is False (an unpacked normal map is a float texture)")
    n = samples_option(samples)
    normals = _hemisphere(n)
    texel = _encode(normals, convention, packed, bits, channels)
    exact = _decode_exact(texel, convention, packed, channels)
    floor = float(np.max(vector_error(exact, normals)))
    if tolerance is None:
        tol, tol_note = 1.5 * floor + 1e-5, (f"tolerance {1.5 * floor + 1e-5:.3g}: 1.5 × an exact decoder's error on "
                                             f"these {'quantized ' if bits else ''}texels")
    else:
        tol, tol_note = tolerance_option(tolerance), f"tolerance {tolerance:.3g} as given"
    other = "directx" if convention == "opengl" else "opengl"
    e = 2.0 * texel - 1.0 if packed else texel
    flip = np.array([1.0, -1.0, 1.0])
    other_up = "z" if up == "y" else "y"

    def fixed(name, v, cause):
        return Model(name, lambda _: _swizzle(v, up), (), False, cause)

    correct = [Model("the encoded normal", lambda _: _swizzle(normals, up), (), True)]
    faults = [
        fixed("green flipped", normals * flip, f"the green channel is flipped: the texture is {convention} (green = "
              f"{'+' if convention == 'opengl' else '−'}y) and the function decodes {other}"),
        fixed("not unpacked" if packed else "unpacked", unit(texel) if packed else unit(2.0 * texel - 1.0),
              "the texel is not unpacked: n = 2·rgb − 1 is missing (the texture is packed)" if packed else
              "the texel is unpacked (2·rgb − 1) but the texture holds n itself (a float normal map)"),
        fixed("unpacked twice", unit(2.0 * e - 1.0), "it unpacks twice (2·(2·rgb − 1) − 1)"),
        fixed("swapped", normals[:, [1, 0, 2]], "x and y are swapped (red holds x, green y)"),
        Model("other up", lambda _: _swizzle(normals, other_up), (), False,
              f"it returns the normal {other_up} up where {up} up is asked (up={other_up!r} if that is your "
              f"convention)"),
        Model("strength", lambda v: _swizzle(unit(normals * np.array([v[0], v[0], 1.0])), up),
              (Param("s", (0.05, 20.0), log=True),), False,
              lambda v: f"the normal's x and y are scaled by {v[0]:.4g} (a normal-map strength) before normalizing"),
    ]
    inputs = {"texel": np.column_stack([texel, np.ones(n)]), "texel_rgb": texel, "texel_rg": texel[:, :2]}
    polar = np.degrees(np.arccos(normals[:, 2]))
    return Domain(inputs, tol, tol_note, ("normal's angle from +z (degrees)", polar), np.full(n, convention),
                  dict(polar_deg=polar, azimuth_deg=np.degrees(np.arctan2(normals[:, 1], normals[:, 0]))),
                  f"{convention}, {'packed 0.5 + 0.5 n' if packed else 'unpacked n'}, "
                  f"{f'{bits}-bit' if bits else 'float'}, {channels} channels, {up} up; {n} normals up to 80° from +z "
                  f"(an exact decoder errs {floor:.3g})", correct, faults)


def normal_decode_late(values, domain, errors):
    """Vectors that are not unit length.

    Parameters
    ----------
    values : numpy.ndarray (n, c)
        The function's outputs over the domain.
    domain : Domain
        The check's domain.
    errors : numpy.ndarray (n,)
        Each row's error against the correct answer.

    Returns
    -------
    str
        The cause in words ("" when this does not explain it).
    """
    return length_cause(values)


def _band_limited(grid, max_slope, seed):
    """A random periodic surface with wavelengths of 16 texels and longer, scaled to ``max_slope``."""
    rng = np.random.default_rng(seed)
    ky, kx = (np.asarray(k, np.float64) for k in grid.wavenumbers(real=False))
    k = np.hypot(kx, ky)
    k_max = 2.0 * math.pi / (16.0 * float(grid.dx))
    spec = (rng.standard_normal(k.shape) + 1j * rng.standard_normal(k.shape)) * np.where(
        (k > 0) & (k <= k_max), 1.0 / np.maximum(k, 1e-9) ** 1.5, 0.0)
    eta = np.fft.ifft2(spec).real
    gx, gy = (np.asarray(g, np.float64) for g in grid.gradient(eta))
    return eta * (max_slope / np.max(np.hypot(gx, gy)))


def _spectral(grid, field):
    """(∂f/∂x, ∂f/∂y) of a periodic field, spectrally."""
    return tuple(np.asarray(g, np.float64) for g in grid.gradient(field))


def _choppy(grid, h, choppiness):
    """Tessendorf's horizontal displacement D = −λ i k/|k| ĥ of heights ``h``."""
    ky, kx = (np.asarray(k, np.float64) for k in grid.wavenumbers(real=False))
    k = np.hypot(kx, ky)
    spec = np.fft.fft2(h)
    safe = np.where(k > 0, k, 1.0)
    dx = np.real(np.fft.ifft2(-1j * kx / safe * spec)) * choppiness
    dy = np.real(np.fft.ifft2(-1j * ky / safe * spec)) * choppiness
    return dx, dy


def _surface_normals(grid, h, dx, dy, up):
    """Unit normals of the surface P(x, y) = (x + Dx, y + Dy, h), (n², 3), in the ``up`` frame."""
    hx, hy = _spectral(grid, h)
    dxx, dxy = _spectral(grid, dx)
    dyx, dyy = _spectral(grid, dy)
    px = np.stack([1.0 + dxx, dyx, hx], -1)
    py = np.stack([dxy, 1.0 + dyy, hy], -1)
    return _swizzle(unit(np.cross(px, py)).reshape(-1, 3), up)


def _fd(h, dx, kind):
    """Finite-difference slopes of a periodic texture: central, forward or backward."""
    if kind == "central":
        return (np.roll(h, -1, 1) - np.roll(h, 1, 1)) / (2 * dx), (np.roll(h, -1, 0) - np.roll(h, 1, 0)) / (2 * dx)
    if kind == "forward":
        return (np.roll(h, -1, 1) - h) / dx, (np.roll(h, -1, 0) - h) / dx
    return (h - np.roll(h, 1, 1)) / dx, (h - np.roll(h, 1, 0)) / dx


def height_normal_domain(*, n=128, texel_size=0.05, max_slope=0.35, up="z", seed=0, choppiness=1.0, roles=(),
                         tolerance=None):
    """Normals of a periodic band-limited height texture (n × n texels of ``texel_size`` m,
    shortest wave 16 texels, steepest slope ``max_slope``), against spectral slopes:
    normalize(−∂η/∂x, −∂η/∂y, 1) for ``up`` = "z", normalize(−∂η/∂x, 1, −∂η/∂v) for "y"
    (texture v along world z). When the function takes a ``displacement`` texture, the surface is
    choppy (Tessendorf's horizontal displacement times ``choppiness``) and the reference is the
    normal of the displaced surface at each texel. Default tolerance: 1° (2 sin 0.5°).

    Parameters
    ----------
    n : int, keyword-only
        Texels a side.
    texel_size : float, keyword-only
        m.
    max_slope : float, keyword-only
        The steepest slope.
    up : str, keyword-only
        ``"z"`` or ``"y"``.
    seed : int, keyword-only
        Of the random heights.
    choppiness : float, keyword-only
        λ of a displacement texture.
    roles : tuple, keyword-only
        The roles the function takes.
    tolerance : float, optional, keyword-only
        Overrides the default.

    Returns
    -------
    Domain
        The inputs, the tolerance, and the correct and faulty models.
    """
    from wavephys.core.grid import Grid
    from wavephys.core.inputs import check_choice, check_int, check_scalar

    from optics.shaders.glsl import Sampler

    n = check_int("n", n, lo=32, hi=1024)
    check_scalar("texel_size", texel_size, lo=1e-4, hi=100.0)
    check_scalar("max_slope", max_slope, lo=0.01, hi=2.0)
    check_scalar("choppiness", choppiness, lo=0.0, hi=2.0)
    check_choice("up", up, ("z", "y"))
    displaced = "displacement" in roles
    grid = Grid(n, n * float(texel_size))
    h = _band_limited(grid, max_slope, seed)
    zero = np.zeros_like(h)
    dx, dy = _choppy(grid, h, choppiness) if displaced else (zero, zero)
    expected = _surface_normals(grid, h, dx, dy, up)
    other = "z" if up == "y" else "y"

    def slopes(sx, sy, scale=1.0, frame=up):
        return _swizzle(unit(np.stack([-scale * sx, -scale * sy, np.ones_like(sx)], -1)).reshape(-1, 3), frame)

    def stencil(kind, words):
        sx, sy = _fd(h, texel_size, kind)
        return Model(f"{kind} differences", lambda v: slopes(sx, sy, v[0]), (Param("s", (-8.0, 8.0)),), False,
                     lambda v: "; ".join(w for w in (words, _scale_words(v[0])) if w) or f"{kind} differences")

    cx, cy = _fd(h, texel_size, "central")
    faults = [
        Model("other up", lambda _: _surface_normals(grid, h, dx, dy, other), (), False,
              f"the normal's up axis is {other}: pass up={other!r} if that is your convention"),
        stencil("central", ""),
        stencil("forward", "one-sided differences (h₊ − h)/Δx: the normal is half a texel off"),
        stencil("backward", "one-sided differences (h − h₋)/Δx: the normal is half a texel off"),
        Model("swapped", lambda v: slopes(cy, cx, v[0]), (Param("s", (-8.0, 8.0)),), False,
              lambda v: "; ".join(w for w in ("x and y are swapped", _scale_words(v[0])) if w)),
    ]
    if displaced:
        faults.insert(0, Model("heights only", lambda _: _surface_normals(grid, h, zero, zero, up), (), False,
                               "it ignores the horizontal displacement: these are the normals of the heights alone, "
                               "not of the displaced (choppy) surface"))
        faults.insert(1, Model("displacement sign", lambda _: _surface_normals(grid, h, -dx, -dy, up), (), False,
                               "the horizontal displacement has the wrong sign"))
    j, i = np.meshgrid(np.arange(n), np.arange(n))
    uv = np.column_stack([(j.ravel() + 0.5) / n, (i.ravel() + 0.5) / n])
    texture = np.stack([dx, h, dy], -1) if up == "y" else np.stack([dx, dy, h], -1)
    inputs = {"heights": Sampler(h.astype(np.float32)), "displacement": Sampler(texture.astype(np.float32)),
              "uv": f32(uv), "texel_uv": f32(np.full((n * n, 2), 1.0 / n)),
              "texel_size": f32(np.full((n * n, 1), texel_size))}
    gx, gy = _spectral(grid, h)
    slope = np.degrees(np.arctan(np.hypot(gx, gy))).ravel()
    border = np.minimum.reduce([i, j, n - 1 - i, n - 1 - j]).ravel()
    if tolerance is None:
        tol, tol_note = 2.0 * math.sin(math.radians(0.5)), "tolerance 1° (2 sin 0.5°)"
    else:
        tol, tol_note = tolerance_option(tolerance), f"tolerance {tolerance:.3g} as given"
    correct = [Model("the surface's normals", lambda _: expected, (), True)]
    return Domain(inputs, tol, tol_note, ("slope angle (degrees)", slope), np.full(n * n, f"{up} up"),
                  dict(u=uv[:, 0], v=uv[:, 1], slope_deg=slope, texels_from_border=border.astype(float)),
                  f"{n}² texels of {texel_size:g} m, shortest wave 16 texels, slopes up to {slope.max():.1f}°, "
                  + (f"choppy (displacement × {choppiness:g}), " if displaced else "") + f"{up} up", correct, faults,
                  extra=dict(up=up))


def _scale_words(s: float) -> str:
    if abs(s - 1.0) < 0.02:
        return ""
    if abs(s - 2.0) < 0.04:
        return ("the difference is not divided by 2: slopes twice too steep ((h₊ − h₋)/Δx for a central "
                "difference)")
    if abs(s + 1.0) < 0.02:
        return "the slopes have the wrong sign: the normal leans uphill"
    return (f"the slopes are scaled by {s:.4g}: check the division by the texel size in metres (texel_size) and "
            f"the height units")


def height_normal_late(values, domain, errors):
    """Errors only at the border (a clamped sampler on a tiling texture), or vectors not normalized.

    Parameters
    ----------
    values : numpy.ndarray (n, c)
        The function's outputs over the domain.
    domain : Domain
        The check's domain.
    errors : numpy.ndarray (n,)
        Each row's error against the correct answer.

    Returns
    -------
    str
        The cause in words ("" when this does not explain it).
    """
    border = domain.context["texels_from_border"]
    inside = errors[border >= 2]
    if errors.max() > domain.tolerance and inside.size and inside.max() <= domain.tolerance:
        return ("errors only at the texture's border: the heights are not sampled periodically there "
                "(a clamped sampler or uv clamped; the texture tiles)")
    return length_cause(values)
