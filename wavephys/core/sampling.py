"""Bilinear sampling, its adjoint (cloud-in-cell deposition), and exact triangle coverage:
the one implementation.

Both work in *texel coordinates*: u = j is the centre of column j, v = i the centre of
row i, so a field of ``n`` samples over a square of side L with the library's convention
(sample centres at −L/2 + (j + ½)·L/n, ``docs/physics.md`` §0) has
u = (x + L/2)/(L/n) − ½ (:func:`texel_coordinates`). Edges either wrap (periodic fields:
the simulation, caustics) or clamp to the border texel (finite textures: the renderer's
ground). NumPy in → NumPy out (float64, for the reference tracer and measurements); JAX
in → JAX out (traceable).

:func:`deposit_triangles` spreads a value uniformly over each triangle and adds to every
texel exactly the share that falls in it (the triangle's area inside the texel square over
its whole area): the rasterization of a flux, computed, not sampled at points.
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

__internal__ = True  # tooling for the library's own modules (users call the Grid's methods)
__all__ = ["texel_coordinates", "bilinear", "bspline", "cloud_in_cell", "array_module", "triangle_window",
           "deposit_triangles", "rasterize_triangles", "TriangleSpread"]

MODES = ("wrap", "clamp")


def array_module(*arrays):
    """``jax.numpy`` if any argument is a JAX array or tracer, else ``numpy``.

    Parameters
    ----------
    *arrays : object
        The inputs of a formula.

    Returns
    -------
    module
        ``jax.numpy`` or ``numpy``.
    """
    return jnp if any(isinstance(a, (jax.Array, jax.core.Tracer)) for a in arrays) else np


def texel_coordinates(x, length, n: int):
    """Continuous texel index of coordinate ``x`` (m) on ``n`` cell-centred samples over
    [−L/2, L/2): (x + L/2)/(L/n) − ½ (0 at the first sample's centre).

    Parameters
    ----------
    x : array_like
        Coordinates, m.
    length : float
        L, the side of the square, m.
    n : int
        Samples along it.

    Returns
    -------
    array_like
        Texel indices (continuous), shape of ``x``.
    """
    return (x + 0.5 * length) * (n / length) - 0.5


def _corners(xp, u, v, shape, mode):
    rows, cols = shape
    i0f, j0f = xp.floor(v), xp.floor(u)
    fv, fu = v - i0f, u - j0f
    i0, j0 = i0f.astype(xp.int32), j0f.astype(xp.int32)
    if mode == "wrap":
        i0, j0 = i0 % rows, j0 % cols
        i1, j1 = (i0 + 1) % rows, (j0 + 1) % cols
    else:
        i1, j1 = xp.clip(i0 + 1, 0, rows - 1), xp.clip(j0 + 1, 0, cols - 1)
        i0, j0 = xp.clip(i0, 0, rows - 1), xp.clip(j0, 0, cols - 1)
    return (i0, i1, j0, j1), (fu, fv)


def bilinear(field, u, v, mode: str = "wrap"):
    """Bilinear interpolation of ``field`` (rows, cols[, channels]) at texel coordinates (u, v).

    ``u`` runs along columns (x), ``v`` along rows (y); any broadcastable shapes. Channels
    (a trailing axis) are interpolated together. ``mode`` "wrap" (periodic) or "clamp".

    Parameters
    ----------
    field : array_like (rows, cols[, channels])
        Values at the texel centres.
    u, v : array_like
        Texel coordinates along columns and rows (texel (i, j)'s centre at (j, i)).
    mode : str
        ``"wrap"`` or ``"clamp"``.

    Returns
    -------
    array_like
        The interpolated values, shape of ``u`` and ``v`` broadcast (then the channels).
    """
    xp = array_module(field, u, v)
    f = xp.asarray(field)
    (i0, i1, j0, j1), (fu, fv) = _corners(xp, xp.asarray(u), xp.asarray(v), f.shape[:2], mode)
    if f.ndim == 3:
        fu, fv = fu[..., None], fv[..., None]
    return ((f[i0, j0] * (1 - fu) + f[i0, j1] * fu) * (1 - fv)
            + (f[i1, j0] * (1 - fu) + f[i1, j1] * fu) * fv)


def _bspline_weights(t):
    """Cubic B-spline weights of the taps −1..2 around a point at fraction t, and their d/dt."""
    t2, t3 = t * t, t * t * t
    w = (((1 - t) ** 3) / 6, (3 * t3 - 6 * t2 + 4) / 6, (-3 * t3 + 3 * t2 + 3 * t + 1) / 6, t3 / 6)
    dw = (-((1 - t) ** 2) / 2, (3 * t2 - 4 * t) / 2, (-3 * t2 + 2 * t + 1) / 2, t2 / 2)
    return w, dw


def bspline(coefficients, u, v, derivatives: bool = False):
    """The periodic cubic B-spline with ``coefficients`` (rows, cols, channels) at texel
    coordinates ``u``, ``v`` (1-D, the same length P): values (P, channels), and with
    ``derivatives`` also d/du and d/dv (per texel). Coefficients come from
    :func:`wavephys.core.spectral.bspline_coefficients` (channels last).

    Each of the 16 taps is one gather of (P, channels) rows from the periodically padded,
    flattened coefficients, contracted separably (along u, then v), so XLA fuses the gathers
    into the contraction's loop; the value and the two derivatives are three such contractions
    run as the branches of one ``lax.switch`` (written as one expression, XLA's CPU backend
    stores the 16 shared gathers instead). Measured on 512² points, two channels, with
    derivatives: 7.9 ms against 40 ms for one gather of 4 × 4 windows contracted by
    ``einsum`` and 13 ms for the shared gathers (docs/physics.md §2.4). JAX only (traceable).

    Parameters
    ----------
    coefficients : jax.Array (rows, cols, channels)
        The spline's coefficients.
    u, v : jax.Array (P,)
        Texel coordinates along columns and rows.
    derivatives : bool
        Also return the derivatives per texel.

    Returns
    -------
    jax.Array (P, channels) or tuple of three
        The values; with ``derivatives``, (values, d/du, d/dv).
    """
    rows, cols, channels = coefficients.shape
    side = cols + 3
    flat = jnp.pad(coefficients, ((1, 2), (1, 2), (0, 0)), mode="wrap").reshape((rows + 3) * side, channels)
    iu, iv = jnp.floor(u), jnp.floor(v)
    fu, fv = u - iu, v - iv
    corner = (iv.astype(jnp.int32) % rows) * side + iu.astype(jnp.int32) % cols  # the window's first tap

    def contract(d_u: bool, d_v: bool):
        (wu, dwu), (wv, dwv) = _bspline_weights(fu), _bspline_weights(fv)
        wu, wv = dwu if d_u else wu, dwv if d_v else wv
        return sum(wv[a][:, None] * sum(wu[b][:, None] * flat.at[corner + (a * side + b)].get(mode="promise_in_bounds")
                                        for b in range(4)) for a in range(4))

    if not derivatives:
        return contract(False, False)
    branches = [lambda: contract(False, False), lambda: contract(True, False), lambda: contract(False, True)]
    value, du, dv = jax.lax.map(lambda k: jax.lax.switch(k, branches), jnp.arange(3))
    return value, du, dv


def cloud_in_cell(u, v, values, shape: tuple[int, int], mode: str = "wrap"):
    """Deposit ``values`` at texel coordinates (u, v) onto a ``shape`` map (sums, not densities).

    The adjoint of :func:`bilinear`: each value is split over the four nearest texels with
    the bilinear weights, so the map's total equals the total of ``values`` exactly.

    Parameters
    ----------
    u, v : array_like
        Texel coordinates along columns and rows.
    values : array_like
        What each point carries (shape of ``u`` and ``v``).
    shape : tuple of int
        (rows, cols) of the map.
    mode : str
        ``"wrap"`` (periodic) or ``"clamp"``.

    Returns
    -------
    array_like (rows, cols)
        The deposited sums.
    """
    xp = array_module(u, v, values)
    u, v, w = (xp.ravel(xp.asarray(a)) for a in (u, v, values))
    (i0, i1, j0, j1), (fu, fv) = _corners(xp, u, v, shape, mode)
    cols = shape[1]
    index = xp.concatenate([i0 * cols + j0, i0 * cols + j1, i1 * cols + j0, i1 * cols + j1])
    weight = xp.concatenate([w * (1 - fu) * (1 - fv), w * fu * (1 - fv), w * (1 - fu) * fv, w * fu * fv])
    size = shape[0] * shape[1]
    if xp is np:
        return np.bincount(index, weights=weight, minlength=size).reshape(shape)
    total = jnp.zeros(size, weight.dtype).at[index].add(weight, mode="promise_in_bounds")  # wrapped or clamped above
    return total.reshape(shape)


def _quadrant_area(p, X: float, Y: float):
    """Area of the counter-clockwise triangle ``p`` ∩ {x < X, y < Y}, elementwise over triangles.

    Green's theorem, area = ∮ x dy over the boundary of the intersection: each edge's part
    inside the quadrant (a parameter interval [t0, t1], clipped by both lines) contributes
    Δy·(t1 − t0)·(x(t0) + x(t1))/2, and the quadrant's own edge x = X inside the triangle
    (its vertical chord below Y) contributes X times the chord's length."""
    inf = jnp.inf
    total, low, high = 0.0, inf, -inf
    for (ax, ay), (bx, by) in ((p[0], p[1]), (p[1], p[2]), (p[2], p[0])):
        dx, dy = bx - ax, by - ay
        tx = (X - ax) / jnp.where(dx == 0, 1.0, dx)
        ty = (Y - ay) / jnp.where(dy == 0, 1.0, dy)
        out_x, out_y = (dx == 0) & ~(ax < X), (dy == 0) & ~(ay < Y)  # a parallel edge wholly outside
        lo = jnp.maximum(jnp.where(dx < 0, tx, jnp.where(out_x, inf, -inf)),
                         jnp.where(dy < 0, ty, jnp.where(out_y, inf, -inf)))
        hi = jnp.minimum(jnp.where(dx > 0, tx, jnp.where(out_x, -inf, inf)),
                         jnp.where(dy > 0, ty, jnp.where(out_y, -inf, inf)))
        t0 = jnp.clip(lo, 0.0, 1.0)
        t1 = jnp.maximum(jnp.clip(hi, 0.0, 1.0), t0)
        total = total + dy * (t1 - t0) * (ax + 0.5 * dx * (t1 + t0))
        crosses = (dx != 0) & ((X - ax) * (X - bx) <= 0)
        yc = ay + tx * dy
        low = jnp.where(crosses, jnp.minimum(low, yc), low)
        high = jnp.where(crosses, jnp.maximum(high, yc), high)
    return total + X * jnp.where(high > low, jnp.maximum(jnp.minimum(high, Y) - low, 0.0), 0.0)


@jax.jit
def _extents(u, v, values):
    """Per group: the larger of its x and y extents (texels), 0 for a group that carries nothing."""
    span = lambda a: jnp.max(a, (0, 1)) - jnp.min(a, (0, 1))
    return jnp.where(jnp.any(values != 0, 0), jnp.maximum(span(u), span(v)), 0.0)


def triangle_window(u, v, values=None) -> int:
    """The window side K (texels) that holds every group of triangles of vertices ``(u, v)``
    (``(3, G, ...)`` texel coordinates, as :func:`deposit_triangles` takes them) from the
    texel of its lowest corner: ⌊extent⌋ + 2, at least 2; groups whose ``values`` are all 0
    do not count. Concrete arrays (reduced where they live; one number comes back).

    Parameters
    ----------
    u, v : array_like (3, G, ...)
        Texel coordinates of the vertices.
    values : array_like (G, ...), optional
        What each triangle carries.

    Returns
    -------
    int
        K.
    """
    if not np.size(u):
        return 2
    w = jnp.ones(jnp.shape(u)[1:]) if values is None else jnp.asarray(values)
    extent = float(jnp.max(_extents(jnp.asarray(u), jnp.asarray(v), w)))
    if not math.isfinite(extent):
        raise ValueError("triangle vertices must be finite")
    return max(int(math.floor(extent)) + 2, 2)


def _shares(local, twice, w, K: int):
    """Each triangle's value split over the K × K texels of its window, ``(K, K, ...)``.

    The corner areas are taken in the triangle's own frame (shifted by the integer floor of its
    lowest corner, exact), so their rounding is ε times its own size squared wherever it lies in
    the window. Small windows evaluate the K² − 2K corner areas one by one (XLA fuses them into
    one pass); large ones broadcast over the corners."""
    (x0, y0), (x1, y1), (x2, y2) = local
    low = lambda a, b, c: jnp.minimum(jnp.minimum(a, b), c)
    high = lambda a, b, c: jnp.maximum(jnp.maximum(a, b), c)
    sx, sy = jnp.floor(low(x0, x1, x2)), jnp.floor(low(y0, y1, y2))
    own = ((x0 - sx, y0 - sy), (x1 - sx, y1 - sy), (x2 - sx, y2 - sy))
    if K <= 3:
        corner = {}
        for i in range(K + 1):
            for j in range(K + 1):
                corner[i, j] = (jnp.zeros_like(twice) if i == 0 or j == 0 else 0.5 * jnp.abs(twice) if i == K == j
                                else _quadrant_area(own, i - sx, j - sy))
        G = jnp.stack([jnp.stack([corner[i, j] for j in range(K + 1)]) for i in range(K + 1)])
    else:
        lattice = jnp.arange(K + 1, dtype=twice.dtype)
        X = lattice.reshape((K + 1, 1) + (1,) * twice.ndim) - sx[None, None]
        Y = lattice.reshape((1, K + 1) + (1,) * twice.ndim) - sy[None, None]
        G = _quadrant_area(tuple((a[None, None], b[None, None]) for a, b in own), X, Y)
    # never negative (rounding is clipped), then normalized: each value is conserved exactly,
    # even for a sliver at a fold; a triangle of no area (below the rounding of its coverage,
    # ε × its own size², in its own frame) goes to the texel of its centroid
    cover = jnp.maximum(G[1:, 1:] - G[:-1, 1:] - G[1:, :-1] + G[:-1, :-1], 0.0)
    total = jnp.sum(cover, (0, 1))
    size = jnp.maximum(high(*(a for a, _ in own)), high(*(b for _, b in own))) + 1.0
    tiny = ~(total > 64 * float(jnp.finfo(jnp.result_type(twice)).eps) * size * size)
    cx, cy = jnp.floor((x0 + x1 + x2) / 3.0), jnp.floor((y0 + y1 + y2) / 3.0)
    ii = jnp.arange(K).reshape((K, 1) + (1,) * twice.ndim)
    jj = jnp.arange(K).reshape((1, K) + (1,) * twice.ndim)
    at_centroid = (cx == ii) & (cy == jj)
    return jnp.where(tiny, jnp.where(at_centroid, w, 0.0), w * cover / jnp.where(tiny, 1.0, total))


def deposit_triangles(u, v, values, shape: tuple[int, int], window: int, origin=None):
    """Spread each of ``values`` uniformly over its triangle and add to every texel of a
    ``shape`` map (periodic) the share inside it: value × area(triangle ∩ texel)/area.

    ``u``, ``v``: texel coordinates of the vertices, ``(3, G, ...)`` — vertex first (texel j
    covers [j − ½, j + ½)), then G triangles per group (e.g. the two of a mesh cell) that
    share one window; ``values`` ``(G, ...)``. Any orientation (a folded sheet adds like any
    other). ``window``: K from :func:`triangle_window` (static; a group wider than K − 1
    texels would put what falls outside it in the window's texels). The shares are clipped
    at 0 and normalized, so every value is conserved exactly and no texel receives a
    negative share from rounding; a triangle of no area puts its value in the texel of its
    centroid. ``origin``: optional integer texel offsets ``(du, dv)`` of each group (shape
    ``(...)``), added to ``u``, ``v`` — pass the large integer part this way and the
    fraction in ``u``, ``v``, and float32 keeps its digits for the coverage on any map size.
    JAX arrays, traceable (the window is static). :func:`rasterize_triangles` chooses the
    windows itself.

    Parameters
    ----------
    u, v : jax.Array (3, G, ...)
        Texel coordinates of the vertices.
    values : jax.Array (G, ...)
        What each triangle carries (e.g. a power, W).
    shape : tuple of int
        (rows, cols) of the map.
    window : int
        K, static.
    origin : tuple of jax.Array, optional
        Integer texel offsets (du, dv) of each group.

    Returns
    -------
    jax.Array (rows, cols)
        The deposited sums.
    """
    K = int(window)
    u, v = jnp.asarray(u) + 0.5, jnp.asarray(v) + 0.5  # texel edges at integers
    w = jnp.asarray(values)
    ox, oy = jnp.floor(jnp.min(u, (0, 1))), jnp.floor(jnp.min(v, (0, 1)))  # one window per group
    x0, x1, x2 = u[0] - ox, u[1] - ox, u[2] - ox
    y0, y1, y2 = v[0] - oy, v[1] - oy, v[2] - oy
    twice = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
    flip = twice < 0  # make every triangle counter-clockwise
    x1, x2 = jnp.where(flip, x2, x1), jnp.where(flip, x1, x2)
    y1, y2 = jnp.where(flip, y2, y1), jnp.where(flip, y1, y2)
    shares = jnp.sum(_shares(((x0, y0), (x1, y1), (x2, y2)), twice, w, K), 2)  # (K, K, ...): the group together
    rows, cols = shape
    oxi, oyi = ox.astype(jnp.int32), oy.astype(jnp.int32)
    if origin is not None:
        oxi, oyi = oxi + jnp.asarray(origin[0], jnp.int32), oyi + jnp.asarray(origin[1], jnp.int32)
    i = jnp.arange(K, dtype=jnp.int32).reshape((K, 1) + (1,) * oxi.ndim)
    j = jnp.arange(K, dtype=jnp.int32).reshape((1, K) + (1,) * oxi.ndim)
    index = ((oyi + j) % rows) * cols + (oxi + i) % cols
    # computed in full first: fused into the scatter, XLA on CPU evaluates them one update at a time
    index, weight = jax.lax.optimization_barrier((index.ravel(), shares.ravel()))
    return jnp.zeros(rows * cols, weight.dtype).at[index].add(weight, mode="promise_in_bounds").reshape(shape)


_deposit = jax.jit(deposit_triangles, static_argnames=("shape", "window"))
_SMALL = 3  # the window of every group under two texels across: one fast pass

PASS_SHARES = 1 << 24
"""Most texel shares (window² × groups) one pass of wide groups computes: bounds its memory (about
0.8 GB of corner areas and shares); also the largest window², so no group may span more than
4094 texels (its window 4096 on the ladder)."""

MAX_SHARES = 1 << 32
"""Most texel shares the wide groups of one rasterization may cost in all (2–4 minutes on a 2-core
CPU at 25–60 ns a share, measured): past it the work is refused before it starts."""


class TriangleSpread(ValueError):
    """The wide triangles of a rasterization would take more memory or work than it allows."""


def _ladder(window):
    """The next power of two (at least 2): few programs, each reused across calls, at most 4 × the
    shares of the exact window."""
    window = np.maximum(np.asarray(window, np.int64), 2)
    return np.left_shift(1, np.ceil(np.log2(window)).astype(np.int64))


def _wide_passes(extent, chunk: int):
    """Passes over the wide groups, their ``extent`` (texels, host numpy) sorted ascending:
    ``(start, count, window)``, the window on :func:`_ladder` (under 2 × each group's own side), each
    pass padded to a power of two, at most ``chunk`` groups and :data:`PASS_SHARES` shares. Refuses by name a group wider than
    the largest window or more than :data:`MAX_SHARES` shares in all."""
    windows = _ladder(np.floor(extent).astype(np.int64) + 2)
    if windows.size and windows[-1] ** 2 > PASS_SHARES:
        raise TriangleSpread(f"a group of triangles spans {float(extent[-1]):.4g} texels: at most "
                         f"{math.isqrt(PASS_SHARES) - 2} (its window's shares are held in memory at once)")
    passes, start = [], 0
    while start < windows.size:
        window = int(windows[start])
        same = int(np.searchsorted(windows, window, side="right")) - start
        count = max(1, min(same, chunk, 1 << (PASS_SHARES // window**2).bit_length() - 1))
        passes.append((start, count, window))
        start += count
    total = sum((1 << (count - 1).bit_length()) * window**2 for _, count, window in passes)
    if total > MAX_SHARES:
        raise TriangleSpread(f"the wide triangles cover {total:.3g} texel shares in all (window² × groups): at most "
                         f"{MAX_SHARES:.3g}, minutes of work on a 2-core CPU")
    return passes


def rasterize_triangles(u, v, values, shape: tuple[int, int], origin=None, chunk: int = 1 << 15):
    """:func:`deposit_triangles` with the windows chosen here (concrete arrays).

    Groups under two texels across (the common case) go in one pass with a 3 × 3 window;
    the few wider ones (light spreading from a steep facet, a coarse surface on a fine map)
    are sorted by extent and deposited in passes of at most ``chunk`` groups and
    :data:`PASS_SHARES` shares, each with a window that holds them, a power of two under twice their
    own (:func:`_wide_passes`; one window for all, the widest's, cost up to its area over theirs).
    Groups that carry nothing are skipped. Work past :data:`MAX_SHARES` or a group wider than 4094 texels is
    refused (ValueError) before it starts.

    Parameters
    ----------
    u, v : array_like (3, G, ...)
        Texel coordinates of the vertices.
    values : array_like (G, ...)
        What each triangle carries.
    shape : tuple of int
        (rows, cols) of the map.
    origin : tuple of array_like, optional
        Integer texel offsets (du, dv) of each group.
    chunk : int
        Most groups a pass of wide triangles.

    Returns
    -------
    jax.Array (rows, cols)
        The deposited sums.
    """
    shape = (int(shape[0]), int(shape[1]))
    u, v, w = jnp.asarray(u), jnp.asarray(v), jnp.asarray(values)
    flat = lambda a, lead: a.reshape(a.shape[:lead] + (-1,))
    u, v, w = flat(u, 2), flat(v, 2), flat(w, 1)
    du, dv = ((jnp.zeros(w.shape[-1], jnp.int32),) * 2 if origin is None
              else (jnp.ravel(jnp.asarray(origin[0])), jnp.ravel(jnp.asarray(origin[1]))))
    extent = _extents(u, v, w)
    if not bool(jnp.isfinite(jnp.max(extent))):
        raise ValueError("triangle vertices must be finite")
    wide = np.flatnonzero(np.asarray(extent >= _SMALL - 1))
    spans = np.asarray(extent[jnp.asarray(wide)]) if wide.size else np.zeros(0, np.float32)  # only theirs to the host
    order = np.argsort(spans, kind="stable")  # by extent: each pass's window fits its groups
    wide, spans = wide[order], spans[order]
    passes = _wide_passes(spans, chunk)
    w_small = w.at[:, wide].set(0.0)
    out = jnp.zeros(shape, w.dtype)
    step = 1 << 22  # groups a pass (bounds the memory of the corner areas: about 1 GB)
    for start in range(0, w.shape[-1], step):
        part = slice(start, start + step)
        out = out + _deposit(u[:, :, part], v[:, :, part], w_small[:, part], shape, _SMALL, (du[part], dv[part]))
    for start, count, window in passes:
        size = 1 << max(int(count - 1).bit_length(), 0)  # padded to a power of two: few programs
        part = jnp.asarray(np.pad(wide[start:start + count], (0, size - count), constant_values=int(wide[start])))
        keep = jnp.arange(size) < count
        pu, pv = u[:, :, part], v[:, :, part]
        out = out + _deposit(pu, pv, jnp.where(keep, w[:, part], 0.0), shape, window, (du[part], dv[part]))
    return out
