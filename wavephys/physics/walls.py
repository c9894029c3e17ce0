r"""Reflecting walls: rectangular tanks whose vertical walls admit no flux (docs/physics.md §1.11).

A wall at x = ±L/2 imposes ∂φ/∂n = 0, so the wave field is even about it. In a tank walled
on both ends of an axis the eigenmodes are cos(mπ(x + L/2)/L), m = 0, 1, …, with wavenumber
k_m = mπ/L; in two dimensions cos(mπx'/L)·cos(nπy'/L) with k_mn = π√(m² + n²)/L and seiche
frequency ω(k_mn) from the dispersion relation (§1.1). With samples at cell centres the
type-II cosine transform (:func:`wavephys.core.spectral.cosine_transform`) is exactly this
basis, so the spectral step's rotation by ω(k_mn)Δt stays exact per mode, as the periodic
step is per Fourier mode. A side that is not a wall is periodic (when the opposite side is
too) or open (the cutoff margin inside it absorbs, §1.4).

Equivalently, a walled tank is the periodic tank of twice the size holding the field and its
mirror images (the image method): a disturbance near a wall equals the open-water field plus
its image in the wall, until waves come back from the far wall. :func:`image_points` lists
the images, :func:`seiche_frequencies` the modes' frequencies (Merian's T = 2L/(m√(gh)) in
the shallow limit).

References
----------
H. Lamb (1932). *Hydrodynamics*, 6th ed., §§190–191 (rectangular tanks); J. R. Merian (1828),
seiche periods; J. Makhoul (1980). A fast cosine transform in one and two dimensions. *IEEE
Trans. ASSP* 28(1), 27–34.
"""

from __future__ import annotations

import math

import jax.numpy as jnp
import numpy as np

from wavephys.core.inputs import check_bool, check_int, check_scalar, describe
from wavephys.core.water import Water
from wavephys.physics.dispersion import angular_frequency

__all__ = ["SIDES", "check_walls", "wall_axes", "seiche_frequencies", "seiche_wavenumbers", "image_points"]

SIDES = ("left", "right", "bottom", "top")
"""Sides of the square domain: left x = −L/2, right x = +L/2, bottom y = −L/2 (row 0), top y = +L/2."""

_SHORT = {"all": SIDES, "none": (), "": (), "x": ("left", "right"), "y": ("bottom", "top")}


def check_walls(walls, margin: int = 0) -> tuple[str, ...]:
    """The walled sides as a sorted tuple of names in :data:`SIDES`.

    Parameters
    ----------
    walls : str or iterable of str
        ``"all"``, ``"none"``, ``"x"`` (left and right), ``"y"`` (bottom and top), one side name,
        or an iterable of side names.
    margin : int
        The model's cutoff margin, samples: a side that is not a wall is open when the margin is
        > 0 and periodic otherwise. An axis walled on one side only must have its other side
        open, so it needs margin > 0.

    Returns
    -------
    tuple of str
        In the order of :data:`SIDES`.
    """
    if isinstance(walls, str):
        names = _SHORT.get(walls, (walls,))
    elif isinstance(walls, (tuple, list, frozenset, set)):
        names = tuple(walls)
    else:
        raise TypeError(f"walls must be 'all', 'none', 'x', 'y', a side name or a sequence of them, "
                        f"got {describe(walls)}")
    for name in names:
        if not isinstance(name, str) or name not in SIDES:
            raise ValueError(f"walls: unknown side {name!r}; the sides are {', '.join(SIDES)} "
                             f"(or 'all', 'none', 'x', 'y')")
    sides = tuple(s for s in SIDES if s in names)
    margin = check_int("margin", margin, lo=0)
    for a, b in (("left", "right"), ("bottom", "top")):
        if (a in sides) != (b in sides) and margin == 0:
            lone, other = (a, b) if a in sides else (b, a)
            raise ValueError(f"walls: the {lone} side is a wall but the {other} side is not, and a side "
                             f"cannot be periodic opposite a wall: give margin > 0 to make the {other} side "
                             f"open, or make it a wall too")
    return sides


def wall_axes(walls) -> tuple[bool, bool]:
    """Whether each axis has a wall on either end (its transform is the cosine transform).

    Parameters
    ----------
    walls : str or iterable of str
        The walled sides (:func:`check_walls`).

    Returns
    -------
    (bool, bool)
        (x walled, y walled).
    """
    sides = check_walls(walls, margin=1)
    return ("left" in sides or "right" in sides), ("bottom" in sides or "top" in sides)


def seiche_wavenumbers(length_x, length_y, modes: int):
    """k_mn = π√((m/Lx)² + (n/Ly)²), rad/m, for m, n = 0 … ``modes`` − 1, shape (modes, modes) [n, m].

    Parameters
    ----------
    length_x, length_y : float
        The tank's sides, m, > 0.
    modes : int
        Modes per axis, ≥ 1.

    Returns
    -------
    numpy.ndarray (modes, modes)
        k_mn, rad/m, at row n (y), column m (x).
    """
    lx = check_scalar("length_x", length_x, lo=0.0, lo_open=True)
    ly = check_scalar("length_y", length_y, lo=0.0, lo_open=True)
    modes = check_int("modes", modes, lo=1)
    m = np.arange(modes)
    return math.pi * np.sqrt((m[None, :] / lx) ** 2 + (m[:, None] / ly) ** 2)


def seiche_frequencies(length_x, length_y, water: Water, modes: int = 4):
    """Seiche (standing-wave) angular frequencies ω(k_mn) of a rectangular tank, rad/s.

    Parameters
    ----------
    length_x, length_y : float
        The tank's sides between the walls, m, > 0.
    water : Water
        g, σ, ρ and the still-water depth (inf for deep water).
    modes : int
        Modes per axis, ≥ 1.

    Returns
    -------
    numpy.ndarray (modes, modes)
        ω(k_mn) at row n (y), column m (x), rad/s; [0, 0] is 0.

    References
    ----------
    H. Lamb (1932). *Hydrodynamics*, §191; shallow limit ω = k√(gh) (Merian's formula).

    Examples
    --------
    >>> from wavephys import Water
    >>> w = seiche_frequencies(1.0, 1.0, Water(sigma=0.0, depth=0.05), modes=2)
    >>> round(float(w[0, 1]), 3)  # ≈ π√(gh)/L in shallow water
    2.191
    """
    if not isinstance(water, Water):
        raise TypeError(f"water must be a wavephys.Water, got {describe(water)}")
    k = seiche_wavenumbers(length_x, length_y, modes)
    return np.asarray(angular_frequency(jnp.asarray(k), water))


def image_points(x, y, length: float, walls, periodic_images: bool = False):
    """A point and its mirror images in the walls of a square domain [−L/2, L/2]²: the image
    method's sources, within one reflection per wall (a corner adds the double image).

    Parameters
    ----------
    x, y : float
        The point, m, inside the domain.
    length : float
        L, m.
    walls : str or iterable of str
        The walled sides (:func:`check_walls`).
    periodic_images : bool
        Also add the periodic images (±L) along axes without walls.

    Returns
    -------
    (numpy.ndarray, numpy.ndarray, numpy.ndarray)
        x, y of the images (the point first), m, and the sign of each (+1: walls reflect with
        the same sign, ∂φ/∂n = 0).
    """
    half = 0.5 * check_scalar("length", length, lo=0.0, lo_open=True)
    x = check_scalar("x", x, lo=-half, hi=half)
    y = check_scalar("y", y, lo=-half, hi=half)
    sides = check_walls(walls, margin=1)
    periodic_images = check_bool("periodic_images", periodic_images)
    xs, ys = [x], [y]
    if "left" in sides:
        xs.append(-2 * half - x)
    if "right" in sides:
        xs.append(2 * half - x)
    if periodic_images and not ({"left", "right"} & set(sides)):
        xs += [x - 2 * half, x + 2 * half]
    if "bottom" in sides:
        ys.append(-2 * half - y)
    if "top" in sides:
        ys.append(2 * half - y)
    if periodic_images and not ({"bottom", "top"} & set(sides)):
        ys += [y - 2 * half, y + 2 * half]
    gx, gy = np.meshgrid(np.asarray(xs), np.asarray(ys))
    return gx.ravel(), gy.ravel(), np.ones(gx.size)
