"""What the renderer draws: two height fields, a sun, a sky and a camera (docs/physics.md §2.5).

World coordinates are metres, z up. Both height fields cover the square
[−length/2, length/2]² with texel centres at −length/2 + (i + ½)·length/n, the grid
convention of :class:`wavephys.Grid` (docs/physics.md §0): a simulated field of n samples
over the same square lands texel for texel. Outside the square, lookups clamp to the
border texels (:func:`texture_sample`). The ground may poke through the water (shores,
pool walls). Everything here is plain data with checked values;
:mod:`optics.rendering.renderer` draws it on the GPU and
:func:`optics.rendering.reference.trace` on the CPU, from the same description.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from optics.light.fresnel import N_AIR, N_WATER
from wavephys.core.inputs import _real_kind, check_array, check_bool, check_choice, check_instance, check_scalar
from wavephys.core.sampling import bilinear, texel_coordinates

__all__ = ["Camera", "Effects", "Scene", "look_at", "DEFAULT_ABSORPTION", "texture_sample", "sun_in_water", "SKIES",
           "SURROUNDINGS", "NEAR_TILES", "FAR_TILES"]

DEFAULT_ABSORPTION = (0.3353, 0.05035, 0.000547)
"""Effective RGB absorption of pure water, 1/m: ``optics.light.attenuation.fit_rgb_coefficients()``
(spectral absorption, D65, fitted over 0–5 m) to 4 digits (a test keeps them in step)."""


def _check_field(name, value):
    check_array(name, value, min_ndim=2)
    if np.ndim(value) > 3:
        raise ValueError(f"{name} must have shape (ny, nx) or (ny, nx, channels), got {np.shape(value)}")
    return value


def texture_sample(field, length: float, x, y):
    """Bilinear sample of a texture (ny, nx[, c]) covering [−L/2, L/2]² at points (x, y), m.

    Texel centres follow the grid convention; points outside clamp to the border texels.
    NumPy float64 for NumPy input.

    Parameters
    ----------
    field : array_like (ny, nx) or (ny, nx, c)
        The texture, finite, any unit.
    length : float
        Side L of the square the texture covers, m, in (0, ``MAX_LENGTH``] (1e7).
    x, y : array_like
        Sample positions, m, finite, broadcastable to one shape (empty arrays are allowed).

    Returns
    -------
    numpy.ndarray or jax.Array
        The samples, shape of the broadcast ``x``, ``y`` (with a trailing channel axis c for a 3-D ``field``),
        in the unit of ``field``; float64 for NumPy input.
    """
    _check_field("field", field)
    check_scalar("length", length, lo=0.0, lo_open=True, hi=MAX_LENGTH)
    for name, v in (("x", x), ("y", y)):  # empty point sets are fine (nothing to sample)
        check_array(name, v) if np.size(v) else _real_kind(name, v, "an array of numbers")
    f = np.asarray(field, np.float64) if isinstance(field, np.ndarray) else field
    return _texture_sample(f, length, x, y)


def _texture_sample(field, length, x, y):
    """:func:`texture_sample` without its checks (for callers that checked their textures once)."""
    ny, nx = np.shape(field)[:2]
    return bilinear(field, texel_coordinates(x, length, nx), texel_coordinates(y, length, ny), "clamp")


SKIES = ("gradient", "preetham")
SURROUNDINGS = ("none", "extend", "tile")
NEAR_TILES, FAR_TILES = 1.5, 4.0
"""Distance filtering with surroundings: the water's waves fade to their mean level between
these many scene sides from the eye (horizontally); beyond the far one the world is flat
planes."""

MAX_LENGTH = 1e7
"""Largest scene side accepted, m (float32 positions lose the texel beyond)."""
MAX_INDEX = 10.0
"""Largest refractive index accepted (water 1.333, diamond 2.42)."""


def check_indices(n_air, n_water, names=("n_air", "n_water")):
    """1 ≤ n_air < n_water ≤ MAX_INDEX: light goes from the thinner medium into the water."""
    check_scalar(names[0], n_air, lo=1.0, hi=MAX_INDEX)
    check_scalar(names[1], n_water, lo=1.0, hi=MAX_INDEX)
    if not n_water > n_air:
        raise ValueError(f"{names[1]} must exceed {names[0]} (water is the denser medium), got "
                         f"{names[0]}={n_air!r}, {names[1]}={n_water!r}")


def _vec3(name, v):
    check_array(name, v, ndim=1)
    a = np.asarray(v, np.float64)
    if a.shape != (3,):
        raise ValueError(f"{name} must be 3 numbers, got shape {a.shape}")
    if not np.isfinite(a).all():
        raise ValueError(f"{name} must be finite, got {a.tolist()}")
    return a


def _colour(name, v):
    a = _vec3(name, v)
    if (a < 0).any():
        raise ValueError(f"{name} must be ≥ 0 in every channel, got {a.tolist()}")
    return a


@dataclass(frozen=True)
class Camera:
    """A pinhole camera at ``eye`` looking at ``target`` (m), vertical field of view ``fov`` (degrees).

    Parameters
    ----------
    eye : tuple of 3 float
        Camera position (x, y, z), m, finite (default (0, −6, 4)).
    target : tuple of 3 float
        Point looked at, m, finite and different from ``eye`` (default (0, 0, −0.5)).
    up : tuple of 3 float
        Up direction, finite, any length, not parallel to the view direction (default +z).
    fov : float
        Vertical field of view, degrees, in (0, 179] (default 50).

    Raises
    ------
    ValueError
        When ``target`` equals ``eye``, ``up`` is parallel to the view direction, or a value is out of range.
    """

    eye: tuple = (0.0, -6.0, 4.0)
    target: tuple = (0.0, 0.0, -0.5)
    up: tuple = (0.0, 0.0, 1.0)
    fov: float = 50.0

    def __post_init__(self):
        eye, target, up = _vec3("eye", self.eye), _vec3("target", self.target), _vec3("up", self.up)
        check_scalar("fov", self.fov, lo=0.0, hi=179.0, lo_open=True)
        f = target - eye
        if np.linalg.norm(f) == 0:
            raise ValueError("camera target must differ from eye")
        if np.linalg.norm(np.cross(f, up)) < 1e-9 * np.linalg.norm(f) * max(np.linalg.norm(up), 1e-300):
            raise ValueError("camera up must not be parallel to the view direction")

    def basis(self):
        """(forward, right, up) unit vectors, float64."""
        f = np.asarray(self.target, float) - np.asarray(self.eye, float)
        f /= np.linalg.norm(f)
        r = np.cross(f, np.asarray(self.up, float))
        r /= np.linalg.norm(r)
        return f, r, np.cross(r, f)


def look_at(eye, target, fov: float = 50.0) -> Camera:
    """A camera with z up (or y up when looking straight up or down).

    Parameters
    ----------
    eye : array_like (3,)
        Camera position, m, finite.
    target : array_like (3,)
        Point looked at, m, finite and different from ``eye``.
    fov : float, optional
        Vertical field of view, degrees, in (0, 179] (default 50).

    Returns
    -------
    Camera
        The camera at ``eye`` looking at ``target``.

    Raises
    ------
    ValueError
        When ``target`` equals ``eye`` or a value is out of range.
    """
    eye, target = _vec3("eye", eye), _vec3("target", target)
    check_scalar("fov", fov, lo=0.0, hi=179.0, lo_open=True)
    f = target - eye
    up = (0.0, 0.0, 1.0) if np.linalg.norm(np.cross(f, (0, 0, 1))) > 1e-6 * np.linalg.norm(f) else (0.0, 1.0, 0.0)
    return Camera(tuple(map(float, eye)), tuple(map(float, target)), up, fov)


@dataclass(frozen=True)
class Effects:
    """Switches for each term of the water model (all on by default).

    Parameters
    ----------
    refraction : bool
        Bend the transmitted ray by Snell's law (off: it goes straight on).
    reflection : bool
        Trace the reflected ray to the ground (off: the reflection is the
        environment only, the cheap shader's choice).
    fresnel : bool
        Fresnel weights by ``fresnel_form`` (off: the normal-incidence value everywhere, and 1
        under TIR).
    absorption : bool
        Beer–Lambert along every underwater path (off: clear water).
    caustics : bool
        Light the underwater ground with the caustics map (off: flat-surface light).
    foam : bool
        Whiten the water surface by the scene's foam coverage (off: no foam drawn).
    fresnel_form : str
        The Fresnel reflectance drawn: a name in :data:`optics.light.fresnel.REFLECTANCE_METHODS`
        that the GLSL has (:data:`optics.gpu.GLSL_FRESNEL_FORMS`; default ``"exact"``), so a
        shader form a plan chooses can be seen.
    absorption_form : str
        The water's transmittance drawn: a name in
        :data:`optics.light.attenuation.WATER_TRANSMITTANCE_METHODS`. ``"rgb"`` (default) is
        Beer–Lambert with the scene's three coefficients (:attr:`Scene.absorption`, by default the
        fit to the spectral answer); any other method (``"spectral"``: pure water's absorption
        spectrum integrated against the eye) is drawn through its
        :func:`~optics.light.attenuation.transmittance_table`, and the scene's coefficients are not
        used. So an absorption method a plan chooses can be seen.
    filtering : bool
        Distance filtering of the water's normals (:mod:`optics.rendering.filtering`): a pixel is
        shaded with the distribution of slopes its footprint covers, read from a pyramid of slope
        moments (off: the one normal at its centre, which aliases far away). Where a pixel covers less
        than a texel inside the waves' fade (``NEAR_TILES``) and its normal faces the eye, the picture
        is the same either way. Last of the fields, so
        that positional calls written before it keep their meaning.
    """

    refraction: bool = True
    reflection: bool = True
    fresnel: bool = True
    absorption: bool = True
    caustics: bool = True
    foam: bool = True
    fresnel_form: str = "exact"
    absorption_form: str = "rgb"
    filtering: bool = True

    SWITCHES = ("refraction", "reflection", "fresnel", "absorption", "caustics", "foam", "filtering")

    def __post_init__(self):
        for name in self.SWITCHES:
            check_bool(name, getattr(self, name))
        from optics.gpu import GLSL_FRESNEL_FORMS
        from optics.light.fresnel import REFLECTANCE_METHODS

        from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS

        REFLECTANCE_METHODS.check(self.fresnel_form, "fresnel_form")
        WATER_TRANSMITTANCE_METHODS.check(self.absorption_form, "absorption_form")
        if self.fresnel_form not in GLSL_FRESNEL_FORMS:
            raise ValueError(f"fresnel_form {self.fresnel_form!r} has no GLSL in optics.gpu (it draws "
                             f"{list(GLSL_FRESNEL_FORMS)})")

    def only(self, *names) -> "Effects":
        """These effects on, every other off (the Fresnel and absorption forms kept).

        Parameters
        ----------
        *names : str
            Names of the switches (:attr:`SWITCHES`) to keep on.

        Returns
        -------
        Effects
        """
        unknown = set(names) - set(self.SWITCHES)
        if unknown:
            raise ValueError(f"unknown effect(s) {sorted(unknown)}; choose from {list(self.SWITCHES)}")
        return Effects(**{k: k in names for k in self.SWITCHES}, fresnel_form=self.fresnel_form,
                       absorption_form=self.absorption_form)


def _height(name, h, max_size=16384):
    check_array(name, h, ndim=2)
    a = np.asarray(h, np.float32)
    if a.ndim != 2:
        raise ValueError(f"{name} must be a 2-D height field, got shape {a.shape}")
    if min(a.shape) < 2:
        raise ValueError(f"{name} must be at least 2×2 texels, got {a.shape}")
    if max(a.shape) > max_size:
        raise ValueError(f"{name} is {a.shape[1]}×{a.shape[0]} texels, more than the largest texture "
                         f"({max_size}); downsample it")
    if not np.isfinite(a).all():
        raise ValueError(f"{name} contains NaN or inf ({int((~np.isfinite(a)).sum())} texels)")
    return a


@dataclass(frozen=True, eq=False)
class Scene:
    """Ground and water height fields (m, z up) over a square of side ``length`` (m), lit by a sun and a sky.

    Parameters
    ----------
    ground, water : array_like (ny, nx)
        Heights, m. They may differ in resolution; ``water`` may be a number (flat).
        Finite, at least 2×2 and at most 16384 texels a side.
    length : float
        Side of the square both cover, m, in (0, ``MAX_LENGTH``] (1e7).
    camera : Camera
        The view (default :class:`Camera`'s); its eye must not be inside the ground.
    sun : 3 numbers
        Direction toward the sun (normalized here), z > 0.
    sun_color, ambient : RGB
        Irradiance of the sun on a surface facing it, and the sky's diffuse light, linear RGB
        (3 finite numbers ≥ 0, as for every RGB below).
    sky_zenith, sky_horizon : RGB
        Sky radiance overhead and at the horizon (used without ``environment``).
    sun_glow : float
        Strength of a smooth glow around the sun in the sky, >= 0; 0 to switch off.
    sky : {"gradient", "preetham"}
        The background and reflected sky without ``environment``: a zenith-to-horizon
        gradient, or Preetham et al.'s analytic daylight with the sun
        (:func:`optics.light.sky.preetham_sky`, zenith luminance ``sky_brightness``).
    turbidity, sky_brightness : float
        Preetham's turbidity T (1.7–10) and the zenith luminance in scene units (in [0, 1e6]).
    surroundings : {"none", "extend", "tile"}
        What lies beyond the square: nothing (the sky or backdrop, as drawn inside a
        studio), the ground and water extended from their border texels (a pool deck, a
        beach), or the water field repeated periodically to the horizon with the ground
        extended (an open sea). With either, the march follows the ray over a distance of
        ``FAR_TILES`` sides from the eye; the waves fade to their mean level between
        ``NEAR_TILES`` and ``FAR_TILES`` sides from the eye (distance filtering: far waves
        smaller than a pixel do not alias), and past that the ray meets flat water and
        ground planes at the levels under its last point, to the horizon.
    environment : array_like (h, w, 3), optional
        Equirectangular environment map (row 0 = zenith, column 0 = azimuth −π), linear RGB;
        finite, ≥ 0, h, w ≥ 2.
    albedo : array_like (ny, nx, 3), optional
        Ground colour over the same square (default: a sand colour); finite, ≥ 0.
    caustics : array_like (ny, nx), optional
        Irradiance on the underwater ground relative to a flat surface (1 = flat), ≥ 0; see
        :func:`optics.caustics.floor_irradiance`. ``None`` = 1 everywhere.
    foam : array_like (ny, nx), optional
        Foam coverage of the water surface in [0, 1] over the same square (e.g.
        :func:`wavephys.choppy.foam`): seen from above, the surface colour becomes
        (1 − f)·water + f·foam_albedo·(ambient + sun_color·max(n·sun, 0)), a Lambertian
        white layer. ``None``: no foam.
    foam_albedo : RGB
        Reflectance of foam (whitecaps ≈ 0.8, slightly blue-white).
    absorption : RGB
        Beer–Lambert coefficients, 1/m.
    deep_color : RGB
        Radiance of an underwater ray that leaves the scene without meeting the ground.
    n_air, n_water : float
        Refractive indices, 1 ≤ n_air < n_water ≤ 10 (default air 1.000293, water 1.333).
    effects : Effects
        Which terms of the model are drawn (default: all).

    Raises
    ------
    ValueError
        When a field is out of range (above), or the camera's eye is inside the ground.

    References
    ----------
    L. Baboud & X. Décoret (2006). Realistic water volumes in real-time. *Eurographics Workshop on Natural
    Phenomena* (docs/physics.md §2.5).
    """

    ground: np.ndarray
    water: object
    length: float
    camera: Camera = field(default_factory=Camera)
    sun: tuple = (0.3, -0.4, 0.866)
    sun_color: tuple = (1.0, 0.96, 0.9)
    ambient: tuple = (0.12, 0.14, 0.18)
    sky_zenith: tuple = (0.25, 0.45, 0.85)
    sky_horizon: tuple = (0.75, 0.82, 0.92)
    sun_glow: float = 0.5
    sky: str = "gradient"
    turbidity: float = 3.0
    sky_brightness: float = 0.45
    surroundings: str = "none"
    environment: object = None
    albedo: object = None
    caustics: object = None
    foam: object = None
    foam_albedo: tuple = (0.8, 0.82, 0.84)
    absorption: tuple = DEFAULT_ABSORPTION
    deep_color: tuple = (0.0, 0.02, 0.04)
    n_air: float = N_AIR
    n_water: float = N_WATER
    effects: Effects = field(default_factory=Effects)

    def __post_init__(self):
        set_ = lambda k, v: object.__setattr__(self, k, v)
        set_("ground", _height("ground", self.ground))
        if np.ndim(self.water) == 0:
            check_scalar("water", self.water)
            set_("water", np.full((2, 2), float(self.water), np.float32))
        else:
            set_("water", _height("water", self.water))
        check_scalar("length", self.length, lo=0.0, lo_open=True, hi=MAX_LENGTH)
        check_instance("camera", self.camera, Camera, "optics.rendering.Camera")
        check_instance("effects", self.effects, Effects, "optics.rendering.Effects")
        sun = _vec3("sun", self.sun)
        if sun[2] <= 0:
            raise ValueError(f"sun must point up (z > 0), got {sun.tolist()}")
        set_("sun", sun / np.linalg.norm(sun))
        for name in ("sun_color", "ambient", "sky_zenith", "sky_horizon", "absorption", "deep_color", "foam_albedo"):
            set_(name, _colour(name, getattr(self, name)))
        check_scalar("sun_glow", self.sun_glow, lo=0.0)
        check_choice("sky", self.sky, SKIES)
        check_scalar("turbidity", self.turbidity, lo=1.7, hi=10.0)
        check_scalar("sky_brightness", self.sky_brightness, lo=0.0, hi=1e6)
        check_choice("surroundings", self.surroundings, SURROUNDINGS)
        check_indices(self.n_air, self.n_water)
        if self.albedo is not None:
            check_array("albedo", self.albedo, ndim=3)
            a = np.asarray(self.albedo, np.float32)
            if a.ndim != 3 or a.shape[2] != 3:
                raise ValueError(f"albedo must have shape (ny, nx, 3), got {a.shape}")
            _height("albedo", a[..., 0])
            if not np.isfinite(a).all() or (a < 0).any() or (a > 1).any():
                raise ValueError(f"albedo must be a reflectance in [0, 1], got values in [{a.min():.3g}, "
                                 f"{a.max():.3g}]")
            set_("albedo", a)
        if self.caustics is not None:
            c = _height("caustics", self.caustics)
            if (c < 0).any():
                raise ValueError("caustics must be ≥ 0 (irradiance relative to a flat surface)")
            set_("caustics", c)
        if self.foam is not None:
            f = _height("foam", self.foam)
            if (f < 0).any() or (f > 1).any():
                raise ValueError(f"foam must be a coverage in [0, 1], got values in [{f.min():.3g}, {f.max():.3g}]")
            set_("foam", f)
        if self.environment is not None:
            check_array("environment", self.environment, ndim=3)
            e = np.asarray(self.environment, np.float32)
            if e.ndim != 3 or e.shape[2] != 3 or min(e.shape[:2]) < 2:
                raise ValueError(f"environment must have shape (h, w, 3) with h, w ≥ 2, got {e.shape}")
            if not np.isfinite(e).all() or (e < 0).any():
                raise ValueError("environment must be finite and ≥ 0")
            set_("environment", e)
        eye = np.asarray(self.camera.eye, float)
        half = self.length / 2
        if abs(eye[0]) <= half and abs(eye[1]) <= half:
            g = float(texture_sample(self.ground, self.length, eye[0], eye[1]))
            if eye[2] <= g:
                raise ValueError(f"camera eye {eye.tolist()} is inside the ground (ground height {g:.3f} m there)")

    def with_effects(self, **switches) -> "Scene":
        """The same scene with some effects switched (``scene.with_effects(caustics=False)``)."""
        return replace(self, effects=replace(self.effects, **switches))

    def with_camera(self, camera: Camera) -> "Scene":
        return replace(self, camera=camera)

    @property
    def default_albedo(self) -> np.ndarray:
        """Uniform sand colour used when ``albedo`` is None, (2, 2, 3)."""
        return np.broadcast_to(np.array([0.76, 0.70, 0.50], np.float32), (2, 2, 3)).copy()

    def bounds(self) -> tuple[float, float]:
        """(z_min, z_max) of the volume that holds both height fields, m."""
        lo = float(min(self.ground.min(), self.water.min()))
        hi = float(max(self.ground.max(), self.water.max()))
        pad = 1e-3 * max(self.length, hi - lo)
        return lo - pad, hi + pad


def sun_in_water(sun, n_air: float, n_water: float):
    """Direction toward the sun as seen under a flat surface (refracted, unit, z > 0).

    ``sun`` points toward the sun (3 numbers, z > 0, any length); 1 ≤ n_air < n_water ≤ 10.

    Parameters
    ----------
    sun : array_like (3,)
        Direction toward the sun, finite, z > 0, any length.
    n_air : float
        Refractive index above the surface, dimensionless, in [1, 10], less than ``n_water``.
    n_water : float
        Refractive index of the water, dimensionless, in [1, 10], greater than ``n_air``.

    Returns
    -------
    numpy.ndarray (3,)
        Unit direction toward the refracted sun, z > 0, float64.

    Raises
    ------
    ValueError
        When the sun is not above the horizon, or ``n_water`` does not exceed ``n_air``.
    """
    s = _vec3("sun", sun)
    if s[2] <= 0:
        raise ValueError(f"sun must point above the horizon (z > 0), got {s.tolist()}")
    s = s / np.linalg.norm(s)
    check_indices(n_air, n_water)
    eta = n_air / n_water
    sin_t = eta * math.hypot(s[0], s[1])
    h = math.hypot(s[0], s[1])
    if h == 0:
        return np.array([0.0, 0.0, 1.0])
    return np.array([s[0] / h * sin_t, s[1] / h * sin_t, math.sqrt(max(0.0, 1 - sin_t * sin_t))])
