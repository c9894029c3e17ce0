r"""Caustics from the Jacobian of the landing map, gathered on the floor (docs/physics.md §2.4).

Below its first fold every floor point X is lit by exactly one surface point x, so the floor
irradiance is the flux that crosses z = 0 over a small patch divided by the area that patch
lands on:

.. math::

    E(X) = E_0\,T(x)\,s(x)\,\frac{\det \partial c/\partial x}{\det \partial X/\partial x},
    \qquad X(x) = x + D(x),\quad D = \frac{\eta + d}{-t_z}\,\mathbf t_h,\quad
    c(x) = x - \eta\,\frac{\mathbf s_h}{s_z}

(t the refracted direction, d the depth of the flat floor, s the sunlight's direction of travel, T the Fresnel
transmittance, s(x) = 1 where the sun reaches the surface and 0 in shadow, c where the ray
crossed z = 0: det ∂c/∂x = 1 − s_h·∇η/s_z). The slopes and curvatures of η are spectral
(exact for a band-limited surface); D, its Jacobian and the numerator are exact functions
of them (forward-mode derivatives through the refraction). The inverse map is found per
floor texel by Newton's method on the periodic cubic B-spline of D (interpolating, third
order, its derivative consistent with the values so Newton converges quadratically),
started from X − D(X − D̄) (D̄ the mean displacement), with one chord step (:func:`_gather`); E
there is the numerator over det ∂X/∂x, each from the spline of its exact samples.

A texel of the reference holds the average of E over the texel; the gathered E is a point
value, which differs by Δx²∇²E/24 to leading order. The map is corrected by the texel's
box filter in Fourier space (sinc(k_xΔx/2)·sinc(k_yΔx/2)), exact for its band-limited part;
towards the first fold E has peaks narrower than a texel, so the gather is made on a floor
grid ``supersample`` times finer and averaged down (``"auto"`` chooses from how fast log E
changes across a floor texel, :data:`SHARPNESS_LIMIT`, measured over surface families, and
gathers at least as many points a side as the surface fields have samples: where the
surface is refined for its fine waves, E has their wavenumbers, above the floor map's
Nyquist when the map is no finer than the surface).

On a ground height field the rays land on the ground by the beam's own fixed point (bilinear
ground, 5 steps), and the forward-mode derivatives go through it.

Folds are never answered silently. The map counts as folded where det ∂X/∂x falls below
:data:`MIN_AREA_RATIO`, where the light varies faster than the gather resolves, where the
ground is too steep for the landing ray to settle (:data:`MAX_CONTRACTION`), where the map jumps
between neighbouring samples (:data:`MAX_GAP`: light either side of a wall's edge), or where
Newton does not converge. (A crest's shadow at a low sun steps the light, but its edge is where
the sunlight grazes the facet and the transmittance falls steeply, which the sharpness test
already leaves to the beam: measured on generated seas at 15°, the same maps with and without
a rule of its own.) ``fold="windows"`` (default) keeps the gather where one smooth sheet
lights the floor and rasterizes the exact beam on the texels that the folded parts of the
surface can reach (their landed cells' boxes, plus one texel; around a jump, the
:data:`JUMP_REACH` samples the spline rings over); those texels are the beam's, the others the
gather's, corrected to texel averages by the local Δx²∇²E/24. ``fold="beam"`` returns the beam
everywhere with a warning; ``fold="raise"`` refuses by name.
"""

from __future__ import annotations

import math
import warnings
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from optics.caustics.common import land, prepare, shadow_steps, sunlit, walled_tank
from optics.light.fresnel import N_WATER
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_bool, check_choice, check_int
from wavephys.core.sampling import bspline
from wavephys.core.spectral import bspline_coefficients, central_gradient, spectral_derivatives

__all__ = ["floor_irradiance_jacobian", "CausticsFold", "SHARPNESS_LIMIT", "MIN_AREA_RATIO", "MAX_CONTRACTION", "MAX_KINK", "MAX_GAP",
           "JUMP_REACH", "MAX_WINDOWS", "MAX_FINE_CONTENT", "FOLD_CHOICES"]

SHARPNESS_LIMIT = 0.4
"""``supersample="auto"`` gathers s = 1, 2, 4 or 8 points per floor texel side, the fewest with
β/s ≤ this, β = Δx·max|∇_X log E| (how much log E changes across one floor texel, from the
surface's own fields) and at least as many points a side as the fields have samples (waves at
the grid scale give E wavenumbers past the map's Nyquist). Measured over the surface families
(docs/physics.md §2.4): at β/s ≤ 0.4 the map stays within 0.5 % of the peak; past s = 8 the
map counts as folded."""

MIN_AREA_RATIO = 0.02
"""Smallest det ∂X/∂x (E up to 50 E0) the method answers; below it the map counts as folded."""

MAX_CONTRACTION = 0.5
"""Steepest ground the gather lands on: |∇z_g·t_h|/(−t_z), the rate at which the ray–ground
fixed point (5 steps, as the beam) contracts; steeper ground is a folded window."""

MAX_WINDOWS = 0.5
"""Largest fraction of the floor whose folded windows ``fold="windows"`` rasterizes by the beam
(checked before texels where Newton did not converge join them, so a map may end a little over);
past it the beam draws the whole map (the gather would save nothing)."""

MAX_KINK = 0.02
"""Largest jump in E (relative) where the bilinear ground's slope changes between its texels,
|Δ∇z_g|·|t_h|/(−t_z); a sharper bend (a kink in the ground) is a folded window."""

MAX_FINE_CONTENT = 0.01
"""``refine="auto"`` refines the surface twice when more of its curvature's power than this
lies above half the Nyquist wavenumber: measured 0.0–0.04 % on the resolved families (band,
swell, Phillips, JONSWAP, k⁻² at 128²) and on the pool, shore and ship scenes; 11–21 % on the
calm pond's noise, the storm and k⁻² at 64², where refine 1 erred 0.9–2.4 % of the peak."""

MAX_GAP = 0.1
"""On a ground height field, the largest step (surface samples) between two neighbouring samples'
landing points beyond what their Jacobians predict; a larger one is a jump in the map (light
either side of a steep wall's edge). Over a flat floor the map is smooth and this is not tested."""

JUMP_REACH = 8
"""Surface samples around a jump left to the beam: the interpolating spline's ringing decays as
(2 − √3)^k per sample, below 1e-3 of a 20-texel jump after 8."""

FOLD_CHOICES = ("windows", "beam", "raise")
"""What a folded map gets (``fold``)."""

NEWTON_TOLERANCE = 1e-3
"""Largest Newton residual |X(x) − X| accepted, in floor texels (converged ones reach 1e-5–1e-4)."""

CHORD_REACH = 0.3
"""The chord step (the first Newton step's Jacobian again, the spline's values only) moves the points
whose first Newton step was at most this (texels of the gathered grid): the Jacobian changed little
between them. Measured on the surface families at 0.8 of the first fold under a 40° sun: with the
chord on every point, some diverged (residual 0.018 texel after 3 more Newton steps, against 1e-5);
at 0.3 and 0.5 the worst residuals of 240 gathers up to 0.8 of the fold are those of Newton steps
alone. At 0.1 the rippled pond's points that the chord left cost it a third Newton step (9 ms at 512²)."""

CHORD_SLACK = 10.0
"""After the chord step the steps stop only if the points it moved were within :data:`NEWTON_STOP`
before it (it multiplies a residual that small by 0.05 or less: 5e-3 went to 2.7e-4, measured) and
the points it left (their first step longer than :data:`CHORD_REACH`) are within NEWTON_STOP / this
(1e-4 texel) already; otherwise Newton steps go on. (Without it, a mild swell's points that the
first step moved far stayed at up to 1e-3 texel and the map was refused as unconverged.)"""

NEWTON_STOP = 1e-3
"""Newton stops after the step from points whose residuals (each component, gathered texels) are all
below this: the step squares the error, reaching the float32 floor (about 1e-5 texel; measured
on the surface families, docs/physics.md §2.4); the chord step, see :data:`CHORD_SLACK`."""


class CausticsFold(ValueError):
    """The surface's landing map folds (or comes too close to folding) for the Jacobian method."""


@jax.jit
def _derivatives(eta, dx):
    """First program (FFT first, the CPU note in wavephys.core.spectral): slopes and curvatures."""
    return spectral_derivatives(eta, dx)


@partial(jax.jit, static_argnames=("fresnel", "shadow", "ground", "coarse"))
def _fields(eta, derivs, d, floor, n_water, fresnel, shadow, length, ground, coarse):
    """On the surface grid: D = X − x (2 planes), the numerator T·s·det ∂c/∂x and det ∂X/∂x,
    stacked; det ∂X/∂x; how fast E changes on the floor, |J⁻ᵀ∇ log E| (1/m); and on a ground height
    field how far it is from landing smoothly (at most 1: the ray–ground fixed point contracts,
    |∇z_g·t_h|/(−t_z) ≤ :data:`MAX_CONTRACTION`, and E jumps by at most :data:`MAX_KINK` where the
    bilinear ground's slope changes; 0 on a flat floor); on a ground, the gap between a sample's landed neighbours and what their Jacobians predict
    (surface samples: large where the map jumps between them; 0 on a flat floor); and whether η is finite."""
    gx, gy, hxx, hxy, hyy = derivs
    grid = Grid(eta.shape[-1], length)
    xv, yv = (jnp.broadcast_to(c, eta.shape).astype(eta.dtype) for c in grid.mesh())  # eta's dtype (x64 mode too)
    floor_fn = (lambda x, y: Grid(coarse, length).sample(floor, x, y)) if ground else floor
    one, zero = jnp.ones_like(eta), jnp.zeros_like(eta)

    def landing(x, y, e, sx, sy):
        return land(x, y, e, sx, sy, d, floor_fn, n_water, fresnel)

    point = (xv, yv, eta, gx, gy)
    (X, Y, trans), (a, c, _) = jax.jvp(landing, point, (one, zero, gx, hxx, hxy))
    _, (b, e, _) = jax.jvp(landing, point, (zero, one, gy, hxy, hyy))
    det = a * e - b * c
    if ground:  # the fixed point s = (η − z_g(x + s t_h))/(−t_z) contracts by |dz_g/ds|/(−t_z)
        t_x, t_y, drop = (X - xv), (Y - yv), jnp.maximum(eta - floor_fn(X, Y), 1e-6)
        _, slope = jax.jvp(lambda s: floor_fn(X + s * t_x, Y + s * t_y), (zero,), (one,))
        contraction = jnp.abs(slope) / drop
        # the bilinear ground's slope changes from texel to texel: E jumps by about that change × |t_h|/(−t_z)
        hg = length / coarse
        bend = jnp.maximum(jnp.abs(jnp.roll(floor, -1, 1) - 2 * floor + jnp.roll(floor, 1, 1)),
                           jnp.abs(jnp.roll(floor, -1, 0) - 2 * floor + jnp.roll(floor, 1, 0))) / hg
        for axis in (0, 1):  # a point samples the four texels around it
            bend = jnp.maximum(bend, jnp.maximum(jnp.roll(bend, 1, axis), jnp.roll(bend, -1, axis)))
        kink = Grid(coarse, length).sample(bend, X, Y) * jnp.hypot(t_x, t_y) / drop
    else:
        contraction = kink = zero
    if ground:  # a jump (rays either side of a wall's edge; over a flat floor D is smooth): a step
        # between neighbours against the step their Jacobians predict, in surface samples
        h = grid.dx
        step = lambda f, axis: jnp.roll(f, -1, axis) - f
        mean = lambda f, axis: 0.5 * (jnp.roll(f, -1, axis) + f)
        gap_x = jnp.hypot(step(X - xv, 1) - h * (mean(a, 1) - 1.0), step(Y - yv, 1) - h * mean(c, 1))
        gap_y = jnp.hypot(step(X - xv, 0) - h * mean(b, 0), step(Y - yv, 0) - h * (mean(e, 0) - 1.0))
        gap = jnp.maximum(jnp.maximum(gap_x, jnp.roll(gap_x, 1, 1)), jnp.maximum(gap_y, jnp.roll(gap_y, 1, 0))) / h
    else:
        gap = zero
    lit = sunlit(eta, grid, d, shadow)
    flux = trans * (1.0 - (d[0] * gx + d[1] * gy) / d[2])
    numerator = flux * lit
    # how fast E changes on the floor: |J⁻ᵀ ∇ log E| (1/m), E at the surface samples (lit ones)
    log_e = jnp.log(jnp.maximum(flux, 1e-6) / jnp.maximum(det, 1e-6))
    lx, ly = central_gradient(log_e, grid.dx)
    sharpness = jnp.hypot(e * lx - c * ly, -b * lx + a * ly) / jnp.maximum(det, 1e-6)
    return (jnp.stack([X - xv, Y - yv, numerator, det]), det, sharpness, jnp.maximum(contraction / MAX_CONTRACTION, kink / MAX_KINK),
            gap, jnp.isfinite(eta).all())


@jax.jit
def _coefficients(planes):
    """Third program (FFT first): B-spline coefficients of D, the numerator and det ∂X/∂x, channels last."""
    return jnp.moveaxis(bspline_coefficients(planes), 0, -1)


@partial(jax.jit, static_argnames=("m", "iterations", "side"))
def _gather(coefficients, length, m, iterations, side=None):
    """Newton per floor point of Grid(m, L): E at the preimage, the residual |X(x) − X| (floor
    texels; inf where the area ratio there is at most :data:`MIN_AREA_RATIO`), and the preimage
    x, y (m, not wrapped into the square). ``coefficients``: the splines of D (2 channels), the
    numerator and det ∂X/∂x. ``side``: only the map's rows and columns −1 … side − 2 (periodic; a
    tank's own floor on its extension with a ring of one point around it), arrays (side, side).

    The first guess is X − D(X − D̄), D̄ the mean displacement (a slanted sun's shift), so its error
    is that of a vertical sun's. Then one Newton step on the spline of D; one chord step (the same
    Jacobian, the spline's values only: a third of the cost) on the points that step moved at most
    :data:`CHORD_REACH` (it takes a residual of 5e-3 to 3e-4 texel where a Newton step reaches
    1e-5, measured on the surface families; from points further off, near a fold, it can diverge);
    and Newton steps while any point's residual before the last step was above :data:`NEWTON_STOP`
    (each squares the error), at most ``iterations`` Newton steps in all (the chord step is not
    counted; none with ``iterations=1``). E = numerator / det at the preimage from their own
    splines (the exact samples interpolated; the derivative of D's spline, a third-order
    interpolant, gave 1.35 × the L2 error, median over 68 generated cases, docs/physics.md §2.4).

    The points are one (P, 2) array. The first Newton step and the chord step are written out (in
    a ``while_loop`` a step costs 2 ms more on 512², measured), and the last values are two
    branches of one loop (written as one expression whose value several consumers take, XLA's CPU
    backend gathers the taps once per consumer: 31 against 4.5 ms, measured)."""
    n = coefficients.shape[0]
    h = length / n
    X, Y = (c.astype(coefficients.dtype) for c in Grid(m, length).mesh())  # the splines' dtype (x64 mode too)
    k = m if side is None else side
    if side is not None:
        X, Y = (jnp.roll(a, (1, 1), (0, 1))[:k, :k] for a in jnp.broadcast_arrays(X, Y))
    target = jnp.stack([X.ravel(), Y.ravel()], 1)

    def tex(p):
        q = (p + 0.5 * length) / h - 0.5
        return q[:, 0], q[:, 1]

    disp = coefficients[..., :2]
    mean = jnp.nanmean(disp, axis=(0, 1))  # the spline's mean is the field's (its filter passes 0 unchanged)

    def step(p, value, jac, weight=1.0, scale=1.0):  # the step that the Jacobian jac of X gives (× weight),
        a, b, c, e = jac                                # and the largest residual before it (× scale)
        r = p + value - target
        move = jnp.stack([e * r[:, 0] - b * r[:, 1], a * r[:, 1] - c * r[:, 0]], 1) / (a * e - b * c)[:, None]
        return p - weight * move, jnp.max(jnp.abs(r) * scale) / (length / m)

    def newton(state):  # also its Jacobian, and 1 where the step was at most CHORD_REACH, else 0
        k, p, _ = state
        value, du, dv = bspline(disp, *tex(p), derivatives=True)
        jac = (1.0 + du[:, 0] / h, dv[:, 0] / h, du[:, 1] / h, 1.0 + dv[:, 1] / h)
        q, worst = step(p, value, jac)
        short = jnp.max(jnp.abs(q - p), axis=1, keepdims=True) <= CHORD_REACH * (length / m)
        return (k + 1, q, worst), (jac, short.astype(p.dtype))

    def more(state):  # a NaN residual (a hopeless point) keeps the steps going, as fixed steps would
        k, _, worst = state
        return (k < iterations) & ~(worst <= NEWTON_STOP)

    first = target - bspline(disp, *tex(target - mean))
    state, (jac, short) = newton((0, first, jnp.asarray(jnp.inf, first.dtype)))
    if iterations > 1:  # a chord step (not a counted step): the first step's Jacobian, the spline's values only,
        # where that step was short (further off, near a fold, the Jacobian changes too much: it can diverge).
        # (The mask comes from the Newton step: from the chord's own residual, XLA gathers the taps twice.)
        # The points it leaves where they are keep their residual: more Newton steps unless all of those
        # are within NEWTON_STOP / CHORD_SLACK already (one reduction, for the reason above).
        state = (state[0], *step(state[1], bspline(disp, *tex(state[1])), jac, short,
                                 short + (1.0 - short) * CHORD_SLACK))
    _, p, _ = jax.lax.while_loop(more, lambda state: newton(state)[0], state)
    value = jnp.concatenate(jax.lax.map(  # as the branches of one loop: one expression would gather per consumer
        lambda j: jax.lax.switch(j, [lambda: bspline(coefficients[..., :2], *tex(p)),
                                     lambda: bspline(coefficients[..., 2:], *tex(p))]), jnp.arange(2)), 1)
    det = value[:, 3]
    residual = jnp.hypot(p[:, 0] + value[:, 0] - target[:, 0], p[:, 1] + value[:, 1] - target[:, 1]) / (length / m)
    irradiance = jnp.maximum(value[:, 2], 0.0) / det  # a spline of a shadow edge may undershoot 0
    return (irradiance.reshape(k, k), jnp.where(det > MIN_AREA_RATIO, residual, jnp.inf).reshape(k, k),
            p[:, 0].reshape(k, k), p[:, 1].reshape(k, k))


@partial(jax.jit, static_argnames=("s",))
def _texel_average(point, length, s):
    """Fourth program (FFT first): the box filter of one fine texel in Fourier space, then the
    average of s × s fine texels per floor texel."""
    fine = point.shape[-1]
    ky, kx = Grid(fine, length).wavenumbers(real=True)
    p = length / fine
    box = jnp.sinc(kx * p / (2 * math.pi)) * jnp.sinc(ky * p / (2 * math.pi))
    averaged = jnp.fft.irfft2(jnp.fft.rfft2(point) * box, s=(fine, fine))
    m = fine // s
    return averaged.reshape(m, s, m, s).mean(axis=(1, 3))


def _supersampling(sharpness: float, texel: float, supersample, m: int, samples: int = 0):
    """The floor supersampling that resolves E (1, 2, 4 or 8, and m·s ≤ 8192), or None when none does:
    with ``"auto"``, the fewest that keep β/s within :data:`SHARPNESS_LIMIT` and gather at least as
    many points a side as the fields have ``samples`` (the light has their wavenumbers: fewer
    points alias them, past what the texel's box filter can take out), or 8 a texel where the
    fields have more than that."""
    if supersample != "auto":
        return supersample
    for s in (1, 2, 4, 8):
        if m * s <= 8192 and sharpness * texel <= SHARPNESS_LIMIT * s and m * s >= min(samples, 8 * m, 8192):
            return s
    return None


def _cell_footprints(displacement, bad, m: int, length: float):
    """Floor texels (m, m, bool) that the landed cells touching a ``bad`` surface sample can
    reach: each such cell marks the texels of its landed corners' bounding box (numpy, host)."""
    disp = np.asarray(displacement, np.float64)
    n = bad.shape[0]
    h, p = length / n, length / m
    cells = bad | np.roll(bad, -1, 0) | np.roll(bad, -1, 1) | np.roll(bad, (-1, -1), (0, 1))
    iy, ix = np.nonzero(cells)
    mask = np.zeros((m, m), bool)
    if iy.size == 0:
        return mask
    base = (np.arange(n) + 0.5) * h
    us = [(base[ix] + b * h + disp[0, (iy + a) % n, (ix + b) % n]) / p - 0.5 for a, b in ((0, 0), (0, 1), (1, 1), (1, 0))]
    vs = [(base[iy] + a * h + disp[1, (iy + a) % n, (ix + b) % n]) / p - 0.5 for a, b in ((0, 0), (0, 1), (1, 1), (1, 0))]
    u0, u1 = np.floor(np.min(us, 0) + 0.5).astype(np.int64), np.floor(np.max(us, 0) + 0.5).astype(np.int64)
    v0, v1 = np.floor(np.min(vs, 0) + 0.5).astype(np.int64), np.floor(np.max(vs, 0) + 0.5).astype(np.int64)
    wu, wv = np.minimum(u1 - u0, m - 1), np.minimum(v1 - v0, m - 1)
    narrow = (wu < 8) & (wv < 8)
    for du in range(8):
        for dv in range(8):
            sel = narrow & (du <= wu) & (dv <= wv)
            mask[(v0[sel] + dv) % m, (u0[sel] + du) % m] = True
    for k in np.flatnonzero(~narrow):  # the few cells that spread wide: their boxes one by one
        mask[np.ix_(np.arange(v0[k], v0[k] + wv[k] + 1) % m, np.arange(u0[k], u0[k] + wu[k] + 1) % m)] = True
    return mask


def _grow(mask, steps: int = 1):
    """``mask`` grown by ``steps`` texels (3 × 3 neighbourhoods, periodic)."""
    for _ in range(steps):
        mask = mask | np.roll(mask, 1, 0) | np.roll(mask, -1, 0)
        mask = mask | np.roll(mask, 1, 1) | np.roll(mask, -1, 1)
    return mask


def _field_supersampling(m: int, samples: int) -> int:
    """Points a floor texel side that the folded-window and tank paths gather: enough for as many
    points a side as the fields have ``samples`` (their light has those wavenumbers), at most
    8192 in all."""
    return max(1, min(-(-samples // m), 8192 // m))


@partial(jax.jit, static_argnames=("s", "ring"))
def _local_texels(point, s: int, lit=None, ring: bool = False):
    """Texel averages of a floor map from its values at s × s points per texel: each point's
    own fine texel by :func:`_point_to_texel` (local), 0 where ``lit`` is False, then the mean
    of the s × s (local too, so values outside the gathered region never enter). ``ring``: the
    points have a ring of one point around the map, its neighbours there, dropped after."""
    fine = _point_to_texel(point)
    if lit is not None:
        fine = jnp.where(lit, fine, 0.0)
    if ring:
        fine = fine[1:-1, 1:-1]
    rows, cols = fine.shape[0] // s, fine.shape[1] // s
    return fine.reshape(rows, s, cols, s).mean(axis=(1, 3))


def _block_max(values, s: int):
    """The largest of each s × s block (numpy, host)."""
    values = np.asarray(values)
    m = values.shape[-1] // s
    return values.reshape(m, s, m, s).max(axis=(1, 3))


@jax.jit
def _point_to_texel(point):
    """Texel average of a smooth field from its centre values: E + Δx²∇²E/24, by the 5-point
    Laplacian (local, so values outside the gathered region never enter)."""
    lap = (jnp.roll(point, 1, 0) + jnp.roll(point, -1, 0) + jnp.roll(point, 1, 1) + jnp.roll(point, -1, 1)
           - 4.0 * point)
    return point + lap / 24.0


def _auto_refine(eta, m: int):
    """``refine="auto"``: the fields at least as fine as the floor map (⌈m/n⌉), and twice finer
    where more than :data:`MAX_FINE_CONTENT` of the surface's curvature lies above half its
    Nyquist wavenumber (under 4 samples per wave the spline of D misses the map); capped at 8
    and 8192 samples. Returns (refine, that fraction)."""
    n = eta.shape[-1]
    fine = float(_fine_content(jnp.asarray(eta, jnp.float32)))
    r = max(-(-m // n), 2 if fine > MAX_FINE_CONTENT else 1)
    return int(min(r, 8, max(1, 8192 // n))), fine


@jax.jit
def _fine_content(eta):
    """Fraction of Σ k⁴|η̂|² (the curvature's power) above half the Nyquist wavenumber."""
    n = eta.shape[-1]
    ky, kx = jnp.fft.fftfreq(n) * n, jnp.fft.rfftfreq(n) * n
    kk = jnp.hypot(ky[:, None], kx[None, :])
    twice = jnp.where((kx > 0) & (kx < n / 2), 2.0, 1.0)  # the half spectrum: the other half mirrors these columns
    power = twice * kk**4 * jnp.abs(jnp.fft.rfft2(eta)) ** 2
    return jnp.sum(jnp.where(kk > n / 4, power, 0.0)) / jnp.maximum(jnp.sum(power), 1e-30)


def _beam_refine(n: int) -> int:
    """The beam's refinement for the windows and the hand-over: its default 3, at most 8192/n."""
    return max(1, min(3, 8192 // n))


@jax.jit
def _groups_near(tri_u, tri_v, origin, near):
    """Which triangle groups (the two of a traced cell) can reach a texel of ``windows``: a
    narrow group (under 2 texels across) lies within 2 texels of its first vertex, so it is
    tested there against ``near`` (the windows grown by 2); every wide group is kept.
    On the device: only the flags come back."""
    m = near.shape[0]
    u, v = tri_u.reshape(3, 2, -1), tri_v.reshape(3, 2, -1)
    first_u = origin[0].ravel() + jnp.floor(u[0, 0] + 0.5).astype(jnp.int32)
    first_v = origin[1].ravel() + jnp.floor(v[0, 0] + 0.5).astype(jnp.int32)
    wide = (jnp.ptp(u, axis=(0, 1)) >= 2) | (jnp.ptp(v, axis=(0, 1)) >= 2)
    return near[first_v % m, first_u % m] | wide


def _beam_windows(light, fresnel, windows, refine: int = 3, tank=None):
    """The exact beam rasterization (refine ``refine``) of every triangle that can reach a texel
    of ``windows``: right on those texels, partial elsewhere (E/E0, (m, m)); in a ``tank`` (its
    extension's light), only the tank's cells carry light."""
    from optics.caustics.beam import beam_triangles, deposit_light

    m, length = light.resolution, float(light.grid.length)
    tri_u, tri_v, flux, origin = beam_triangles(light, refine, fresnel, tank=tank)
    index = np.flatnonzero(np.asarray(_groups_near(tri_u, tri_v, origin, jnp.asarray(_grow(windows, 2)))))
    if index.size == 0:
        return jnp.zeros((m, m), jnp.float32)
    quantum = 1 << max(int(index.size).bit_length() - 4, 0)  # padded to 1/8–1/16 of its octave: few programs
    size = -(-index.size // quantum) * quantum
    keep = jnp.asarray(np.arange(size) < index.size)
    index = jnp.asarray(np.pad(index, (0, size - index.size), constant_values=index[0]))
    pick = lambda a: jnp.take(a.reshape(a.shape[:-2] + (-1,)), index, axis=-1)
    deposited = deposit_light(pick(tri_u), pick(tri_v), jnp.where(keep, pick(flux), 0.0), (m, m),
                              (pick(origin[0]), pick(origin[1])))
    return deposited / (length / m) ** 2


def floor_irradiance_jacobian(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                              n_water: float = N_WATER, fresnel: bool = True, refine="auto", supersample="auto",
                              iterations: int = 4, fold: str = "windows", explain: bool = False, walls=None):
    """Floor irradiance E/E0 from the Jacobian of the landing map (module doc), shape (m, m).

    Parameters
    ----------
    eta, grid, sun, resolution, n_water, fresnel
        As :func:`optics.caustics.floor_irradiance`.
    depth : float or array_like (n, n)
        Depth of a flat floor, m, > 0; or a ground height field z_g (m, below the water
        everywhere) on the surface's grid, landed on as the beam does; where it is too steep
        for the ray to settle (:data:`MAX_CONTRACTION`) the folded-window rule applies.
    refine : "auto" or int
        Fourier-refine the surface this many times (1 to 8, n·refine ≤ 8192) before the fields
        are built. ``"auto"`` makes them at least as fine as the floor map and twice finer where
        the surface has waves of under 4 samples (:data:`MAX_FINE_CONTENT`). Must be 1 on a
        ground height field (the ground lives on the surface's grid): where ``"auto"`` would
        refine there, the beam answers (or, with ``fold="raise"``, :class:`CausticsFold`).
    supersample : "auto" or int
        Gather on a floor grid this many times finer (1 to 8, resolution × supersample ≤ 8192)
        and average down; ``"auto"`` takes the fewest of 1, 2, 4, 8 that resolve E
        (:data:`SHARPNESS_LIMIT`) and gather at least as many points a side as the surface
        fields have samples. The folded-window path gathers as many points as the fields have
        samples (what it cannot resolve is a window).
    iterations : int
        At most this many Newton steps per floor point (1 to 16; they stop once converged, and with
        2 or more a chord step follows the first); a residual above 1e-3 texel counts as a fold.
    fold : {"windows", "beam", "raise"}
        What a map that folds (or nearly folds) somewhere gets: ``"windows"`` gathers the
        floor where it is lit by one smooth sheet and rasterizes the exact beam (refine 3)
        on the texels the folded or sharp parts of the surface reach, plus one texel;
        once the windows would cover more than :data:`MAX_WINDOWS` of the floor, the beam draws
        all of it (no warning: it is as right as the windows); ``"beam"`` the exact beam
        rasterization everywhere, with a warning; ``"raise"`` :class:`CausticsFold` (a
        ValueError) naming the reason. The beam here is refined 3 times (at most 8192/n).

    explain : bool
        Also return how the map was answered (below).
    walls : str or None
        The square is a tank with opaque vertical walls on these sides (``"all"``, ``"x"``, ``"y"``,
        or both side names of an axis; default None: periodic), as
        :func:`~optics.caustics.floor_irradiance_beam` has it: the fields come from the surface's even
        extension (its cosine modes: exact derivatives up to the walls), floor texels whose light would
        have come through a wall are dark, and the texels around the edge of that shadow (the landed
        cells by the walls) are the beam's windows, so the answer is always ``"windows"`` or ``"beam"``.

    Returns
    -------
    jax.Array (m, m)
        Floor irradiance / E0 at the cell centres of ``Grid(m, L)``.
    dict, with ``explain=True``
        ``answer`` (``"gather"``, ``"windows"`` or ``"beam"``), ``windows`` (the fraction of the
        floor the beam drew), ``supersample`` (the gather's, or None) and ``mask`` (numpy bool
        (m, m): the texels the beam drew).
    """
    check_bool("explain", explain)
    out, info = _jacobian(eta, grid, depth, sun, resolution, n_water, fresnel, refine, supersample, iterations, fold,
                          walls)
    return (out, info) if explain else out


def _jacobian(eta, grid, depth, sun, resolution, n_water, fresnel, refine, supersample, iterations, fold, walls=None):
    """:func:`floor_irradiance_jacobian`, and how it answered: ``{"answer": "gather" | "windows" |
    "beam", "windows": fraction of the floor rasterized, "supersample": s}``."""
    light = prepare(eta, grid, depth, sun, resolution, n_water, fresnel, check_values=False)
    if supersample != "auto":
        supersample = check_int("supersample", supersample, lo=1, hi=8)
    iterations = check_int("iterations", iterations, lo=1, hi=16)
    check_choice("fold", fold, FOLD_CHOICES)
    if refine != "auto":
        refine = check_int("refine", refine, lo=1, hi=8)
    tank = walled_tank(light, walls)
    if tank is not None:
        return _tank_jacobian(tank, (eta, grid, depth, sun, resolution, n_water, fresnel, walls), refine, iterations,
                              fold)
    length, m, d = float(grid.length), light.resolution, jnp.asarray(light.direction, jnp.float32)
    if refine == "auto":
        r, fine_content = _auto_refine(light.eta, m)
        if light.ground and r > 1:  # the fields need the ground on a finer grid than it is given on
            reason = (f"on a ground height field the gather needs refine 1, but the surface wants {r} "
                      f"(floor map {m}² over {grid.n}² samples; {fine_content:.1%} of its curvature above half "
                      f"the Nyquist wavenumber, at most {MAX_FINE_CONTENT:.0%})")
            return _not_gathered(eta, grid, depth, sun, resolution, n_water, fresnel, fold, reason)
    else:
        r = check_int("refine", refine, lo=1, hi=8)
        if light.ground and r > 1:
            raise ValueError("refine must be 1 on a ground height field (the ground lives on the surface's grid)")
    if grid.n * r > 8192:
        raise ValueError(f"refine {r} traces {grid.n * r}² samples: n·refine must be at most 8192")
    fine = Grid(grid.n * r, grid.length)
    surface = grid.refine(light.eta, r) if r > 1 else light.eta
    planes, det, sharpness, rough, gap, finite = _fields(
        surface, _derivatives(surface, fine.dx), d, light.floor, light.n_water, fresnel,
        shadow_steps(surface, fine, light.direction), length, light.ground, grid.n)
    finite, min_det, steepest, jump, sharpest = (float(v) for v in np.asarray(_summary(finite, det, rough, gap,
                                                                                          sharpness)))
    if not finite:
        raise ValueError("eta must be finite everywhere; it contains NaN or inf")
    s = (_supersampling(sharpest, length / m, supersample, m, fine.n)
         if min_det > MIN_AREA_RATIO and steepest <= 1.0 and jump <= MAX_GAP else None)
    if s is not None and m * s > 8192:
        raise ValueError(f"resolution × supersample = {m * s} must be at most 8192")
    if s is not None:
        point, residual, _, _ = _gather(_coefficients(planes), length, m * s, iterations)
        worst = float(jnp.max(residual))
        if worst <= NEWTON_TOLERANCE:
            return _texel_average(point, length, s), dict(answer="gather", windows=0.0, supersample=s,
                                                          mask=np.zeros((m, m), bool))
        reason = f"Newton did not converge (residual {worst:.2g} texel)"
    elif min_det <= MIN_AREA_RATIO:
        reason = (f"the smallest area ratio det ∂X/∂x on the surface is {min_det:.3g} (the map folds at 0; the "
                  f"method answers down to {MIN_AREA_RATIO})")
    elif jump > MAX_GAP:
        reason = (f"the landing map jumps between neighbouring samples on the ground (by up to {jump:.3g} samples "
                  f"more than their Jacobians predict; at most {MAX_GAP})")
    elif steepest > 1.0:
        reason = (f"the ground is too steep or bends too sharply between its samples for a smooth landing "
                  f"({steepest:.3g} × the most the gather lands on: MAX_CONTRACTION, MAX_KINK)")
    else:
        reason = (f"the light varies too fast on the floor (log E changes by "
                  f"{sharpest * length / m:.3g} per texel; the finest supersampling of a "
                  f"{m}² map, at most 8 and 8192 texels, resolves {min(8, 8192 // m) * SHARPNESS_LIMIT:.3g})")
    if fold == "windows":
        bad = np.array((det <= MIN_AREA_RATIO) | (sharpness * (length / m) > SHARPNESS_LIMIT)
                         | (rough > 1.0))
        bad |= _grow(np.asarray(gap > MAX_GAP), JUMP_REACH)  # the spline rings around a jump
        folded = _cell_footprints(planes[:2], bad, m, length)
        if _grow(folded).mean() <= MAX_WINDOWS:
            s = _field_supersampling(m, fine.n)
            point, residual, _, _ = _gather(_coefficients(planes), length, m * s, iterations)
            windows = _grow(folded | (_block_max(residual, s) > NEWTON_TOLERANCE))
            beam = _beam_windows(light, fresnel, windows, _beam_refine(grid.n))
            out = jnp.where(jnp.asarray(windows), beam, _local_texels(point, s))
            return out, dict(answer="windows", windows=float(windows.mean()), supersample=s, mask=windows)
    return _not_gathered(eta, grid, depth, sun, resolution, n_water, fresnel, fold, reason)


@jax.jit
def _summary(finite, det, rough, gap, sharpness):
    """The numbers the gather decides on, in one transfer to the host: all finite (1/0), the
    smallest area ratio, the roughest ground, the largest jump, the sharpest light."""
    return jnp.stack([jnp.asarray(finite, jnp.float32), jnp.min(det), jnp.max(rough), jnp.max(gap),
                      jnp.max(sharpness)]).astype(jnp.float32)


def _map_side(eta, resolution) -> int:
    """The floor map's side: ``resolution``, or the surface's."""
    return int(resolution) if resolution is not None else int(np.shape(eta)[-1])


def _not_gathered(eta, grid, depth, sun, resolution, n_water, fresnel, fold, reason, walls=None):
    """The beam everywhere for a map the gather does not answer (a warning with ``fold="beam"``),
    or :class:`CausticsFold` with ``fold="raise"``."""
    if fold == "raise":
        raise CausticsFold(f"depth: the gather cannot answer this floor (the landing map folds, nearly folds or is "
                           f"not resolved): {reason}; "
                           "use fold='windows', fold='beam' or method='beam'")
    from optics.caustics.beam import floor_irradiance_beam

    if fold == "beam":
        warnings.warn(f"jacobian caustics: {reason}; the exact beam rasterization is used instead", stacklevel=4)
    refine = _beam_refine(grid.n if walls is None else 2 * grid.n)
    return (floor_irradiance_beam(eta, grid, depth, sun, resolution=resolution, n_water=n_water, fresnel=fresnel,
                                  refine=refine, walls=walls),
            dict(answer="beam", windows=1.0, supersample=None,
                 mask=np.ones((_map_side(eta, resolution),) * 2, bool)))


def _tank_jacobian(tank, call, refine, iterations, fold):
    """:func:`_jacobian` in a walled tank (``walls``): the gather on the tank's even extension, dark where
    the preimage lies past a wall, the beam (the tank's cells only) on the windows: the folded parts'
    footprints and the landed cells by the walls, where the shadow of a wall begins."""
    light, (wx, wy) = tank.light, tank.walls
    big_n, big_m, length = light.grid.n, light.resolution, float(light.grid.length)
    d = jnp.asarray(light.direction, jnp.float32)
    if refine == "auto":
        r, fine_content = _auto_refine(light.eta, big_m)
        if light.ground and r > 1:
            reason = (f"on a ground height field the gather needs refine 1, but the surface wants {r} "
                      f"({fine_content:.1%} of its curvature above half the Nyquist wavenumber)")
            return _not_gathered(*call[:7], fold, reason, walls=call[7])
    else:
        r = refine
        if light.ground and r > 1:
            raise ValueError("refine must be 1 on a ground height field (the ground lives on the surface's grid)")
    if big_n * r > 8192:
        raise ValueError(f"refine {r} traces the tank's even extension on {big_n * r}² samples: 2·n·refine must "
                         f"be at most 8192")
    fine = Grid(big_n * r, length)
    surface = light.grid.refine(light.eta, r) if r > 1 else light.eta
    planes, det, sharpness, rough, gap, finite = _fields(
        surface, _derivatives(surface, fine.dx), d, light.floor, light.n_water, call[6],
        shadow_steps(surface, fine, light.direction), length, light.ground, big_n)
    if not bool(finite):
        raise ValueError("eta must be finite everywhere; it contains NaN or inf")
    inside = r * tank.n  # the tank's samples a side on the traced extension
    own = np.zeros((big_n * r,) * 2, bool)
    own[:inside if wy else None, :inside if wx else None] = True
    folds = own & np.asarray((det <= MIN_AREA_RATIO) | (sharpness * (length / big_m) > SHARPNESS_LIMIT) | (rough > 1.0))
    folds |= own & _grow(np.asarray(gap > MAX_GAP), JUMP_REACH)
    if folds.any() and fold != "windows":
        reason = (f"the landing map of the tank's surface folds, nearly folds or is not resolved at "
                  f"{int(folds.sum())} of its samples")
        return _not_gathered(*call[:7], fold, reason, walls=call[7])
    edge = np.zeros_like(own)  # the samples by each wall: the cells across it carry half their light
    if wx:
        edge[:, [0, inside - 1, inside, big_n * r - 1]] = True
    if wy:
        edge[[0, inside - 1, inside, big_n * r - 1], :] = True
    folded = _cell_footprints(planes[:2], folds | edge, big_m, length)
    crop = (slice(0, tank.m), slice(0, tank.m))
    if _grow(folded)[crop].mean() > MAX_WINDOWS:
        return _tank_beam(call)
    s = _field_supersampling(big_m, fine.n)
    # the tank's own floor only (a quarter of the extension's; the rest mirrors it)
    point, residual, x, y = _gather(_coefficients(planes), length, big_m * s, iterations, tank.m * s + 2)
    unconverged = _block_max(np.asarray(residual)[1:-1, 1:-1], s) > NEWTON_TOLERANCE
    unconverged = np.concatenate([unconverged, unconverged[:, ::-1] if wx else unconverged], 1)  # as the extension
    unconverged = np.concatenate([unconverged, unconverged[::-1] if wy else unconverged], 0)  # mirrors or repeats it
    windows = _grow(folded | unconverged)
    windows[tank.m:, :] = windows[:, tank.m:] = False  # nothing past the tank is drawn
    beam = _beam_windows(light, call[6], windows, _beam_refine(big_n), tank=tank)
    lit = jnp.ones_like(point, bool)
    half = 0.5 * length  # the extension spans [-L_ext/2, L_ext/2); the tank its first half along a walled axis
    if wx:
        lit &= jnp.mod(x + half, length) < 0.5 * length
    if wy:
        lit &= jnp.mod(y + half, length) < 0.5 * length
    out = jnp.where(jnp.asarray(windows[crop]), beam[crop], _local_texels(point, s, lit, ring=True))
    return out, dict(answer="windows", windows=float(windows[crop].mean()), supersample=s, mask=windows[crop])


def _tank_beam(call):
    """The beam everywhere in a tank whose windows would cover most of its floor (no warning: it is as
    right as the windows)."""
    from optics.caustics.beam import floor_irradiance_beam

    eta, grid, depth, sun, resolution, n_water, fresnel, walls = call
    out = floor_irradiance_beam(eta, grid, depth, sun, resolution=resolution, n_water=n_water, fresnel=fresnel,
                                refine=_beam_refine(2 * grid.n), walls=walls)
    return out, dict(answer="beam", windows=1.0, supersample=None, mask=np.ones((_map_side(eta, resolution),) * 2, bool))
