"""The water drawn as a displaced mesh, the way engines draw it, beside the ray-marcher.

Engines do not march the view rays through the water's volume (:mod:`optics.rendering.renderer`):
they lay a mesh over the water, move each vertex to the height the height texture gives it, and
rasterize the triangles. Where the vertices lie is the technique (:data:`MESH_TECHNIQUES`, one
function each):

* ``"uniform"`` (:func:`uniform_mesh`): one grid of equal square cells over the water's region;
* ``"clipmap"`` (:func:`clipmap_mesh`): concentric square rings around the eye, each level's
  spacing twice the one inside it (Losasso & Hoppe 2004, geometry clipmaps); over each level's
  outer band a vertex's height blends to the coarser level's surface at its point, so the level's
  outer edge is the coarser level's edge, and zero-area triangles close the T-junctions there;
* ``"projected"`` (:func:`projected_grid`): Johanson's (2004) projected grid, a regular grid in
  screen space whose vertices are the points where their view rays meet the mean water plane.

The height a vertex gets is the ray-marcher's own (``water_h``: the same texture, bilinear, faded
with distance where the water is tiled), and every fragment is shaded by the ray-marcher's own
shading (``shade_water``: the normal, reflection, refraction, absorption, foam and distance
filtering of the texture at the fragment's point), so what differs between the two images is only
where the surface is: the mesh's piecewise-linear surface against the exact bilinear one.
:func:`mesh_errors` measures that per distance band, in the image (PSNR against the ray-marcher's
picture) and in the heights (the mesh's surface against the texture's, on the visible triangles),
with the cost (vertices, triangles, time). ``python -m bench meshes`` charts it
(docs/meshes.md).

A frame is two passes: a full-screen pass draws what is not water (the ground by the ray-marcher's
march, the far field, the sky), then the mesh with a depth test; its fragments march to the ground
first, so land in front of the water hides it as in the ray-marcher.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from optics.rendering.scene import FAR_TILES, Scene
from wavephys.core.inputs import check_bool, check_instance, check_int, check_scalar, describe

__all__ = ["WaterMesh", "MESH_TECHNIQUES", "uniform_mesh", "clipmap_mesh", "projected_grid", "water_mesh",
           "displaced_mesh",
           "mesh_region", "mesh_heights", "height_errors", "mesh_errors", "render_mesh", "mesh_seconds",
           "mesh_coverage", "water_pixels", "BANDS",
           "MESH_VERTEX", "MESH_MAIN", "BACKGROUND_MAIN", "MAX_VERTICES"]

MESH_TECHNIQUES = ("uniform", "clipmap", "projected")
"""The ways to lay the water's mesh (module doc), each a function of this module."""

BANDS = (0.0, 4.0, 16.0, 64.0, 256.0, math.inf)
"""Edges of the distance bands :func:`mesh_errors` reports, in eye heights above the mean water
level: a pixel's band is where its view ray meets that level, at horizontal distance r from the eye
(r/H from 0 to 4, 4 to 16, …). A projected grid's vertex spacing grows as r²/H along the view."""


@dataclass(frozen=True)
class WaterMesh:
    """A mesh of the water: vertices in the plane and the triangles between them.

    Attributes
    ----------
    positions : numpy.ndarray (N, 2) float32
        Each vertex's (x, y), m; its height is read from the height texture when drawn.
    parents : numpy.ndarray (N, 4) float32
        (x₁, y₁, x₂, y₂): two points whose mean height is the coarser level's surface at the
        vertex (a clipmap's blend; the vertex itself twice elsewhere).
    morph : numpy.ndarray (N,) float32
        How far the vertex's height blends to its parents' mean, in [0, 1] (0: its own height).
    triangles : numpy.ndarray (M, 3) uint32
        Vertex indices, counter-clockwise seen from above.
    technique : str
        A name in :data:`MESH_TECHNIQUES`.
    spacing : float
        The finest spacing between vertices, m (a projected grid's: its nearest row's).
    """

    positions: np.ndarray
    parents: np.ndarray
    morph: np.ndarray
    triangles: np.ndarray
    technique: str
    spacing: float

    def __post_init__(self):
        from wavephys.core.inputs import check_array

        pos = check_array("positions", self.positions, ndim=2, shape_tail=(2,))
        n = pos.shape[0]
        check_array("parents", self.parents, ndim=2, shape_tail=(n, 4))
        morph = check_array("morph", self.morph, ndim=1, shape_tail=(n,))
        if not (np.all(morph >= 0) and np.all(morph <= 1)):
            raise ValueError("morph must lie in [0, 1]")
        tris = np.asarray(self.triangles)
        if tris.ndim != 2 or tris.shape[1:] != (3,) or not np.issubdtype(tris.dtype, np.integer):
            raise TypeError(f"triangles must be an (M, 3) integer array, got {describe(self.triangles)}")
        if tris.size and (tris.min() < 0 or tris.max() >= n):
            raise ValueError(f"triangles must index the {n} positions, got indices {tris.min()}–{tris.max()}")
        if not isinstance(self.technique, str):
            raise TypeError(f"technique must be a str, got {describe(self.technique)}")
        if self.technique not in MESH_TECHNIQUES:
            raise ValueError(f"technique must be one of {', '.join(MESH_TECHNIQUES)}, got {self.technique!r}")
        check_scalar("spacing", self.spacing, lo=0.0, lo_open=True)

    @property
    def vertices(self) -> int:
        """The number of vertices."""
        return int(self.positions.shape[0])

    @property
    def triangle_count(self) -> int:
        """The number of triangles (zero-area ones included)."""
        return int(self.triangles.shape[0])

    @property
    def texel_reads(self) -> int:
        """Height texels the vertex shader reads a frame: 4 a bilinear sample, 3 samples at a
        blended vertex (its own and its parents')."""
        return int(4 * (self.vertices + 2 * np.count_nonzero(self.morph)))


# -- where the water is -------------------------------------------------------------------------------

def mesh_region(scene: Scene) -> tuple:
    """The square a mesh of ``scene`` must cover: (cx, cy, half), m.

    Without surroundings the water is the scene's square; with them (``"extend"``, ``"tile"``) the
    ray-marcher follows the water out to ``FAR_TILES`` sides from the eye (horizontally) and draws
    flat planes beyond, so the mesh covers the square of that half-side around the eye, and the
    mesh path's fragments past that distance are dropped as the march drops them.

    Parameters
    ----------
    scene : Scene

    Returns
    -------
    (float, float, float)
    """
    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    if scene.surroundings == "none":
        return 0.0, 0.0, 0.5 * scene.length
    eye = scene.camera.eye
    return float(eye[0]), float(eye[1]), FAR_TILES * scene.length


def _eye_height(scene: Scene) -> float:
    """The eye's height above the water's mean level, m (> 0: the mesh path draws the water from above)."""
    return float(scene.camera.eye[2]) - float(np.mean(scene.water, dtype=np.float64))


def _check_above(scene: Scene) -> None:
    h = _eye_height(scene)
    if not h > 0:
        raise ValueError(f"scene's eye is {-h:.3g} m below the water's mean level: the mesh path draws the water "
                         f"from above (the ray-marcher draws it from below)")


# -- laying the mesh -------------------------------------------------------------------------------------

def _lattice(i0: int, i1: int, j0: int, j1: int):
    """Integer lattice points (i, j) for i in [i0, i1], j in [j0, j1] (j the slow axis) and the
    triangles of its cells, each cell cut along its (i, j)–(i+1, j+1) diagonal (counter-clockwise)."""
    ni, nj = i1 - i0 + 1, j1 - j0 + 1
    jj, ii = np.meshgrid(np.arange(j0, j1 + 1), np.arange(i0, i1 + 1), indexing="ij")
    idx = np.arange(ni * nj).reshape(nj, ni)
    a, b, c, d = idx[:-1, :-1], idx[:-1, 1:], idx[1:, 1:], idx[1:, :-1]  # (i,j) (i+1,j) (i+1,j+1) (i,j+1)
    tris = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    cells = np.concatenate([np.stack([ii[:-1, :-1], jj[:-1, :-1]], -1).reshape(-1, 2)] * 2)
    return np.stack([ii.ravel(), jj.ravel()], -1), tris, cells


def _mesh(technique, xy, parents, morph, tris, spacing) -> WaterMesh:
    """A :class:`WaterMesh` of the vertices the triangles use, one per point (vertices at the same
    point merged, the one of least ``morph`` kept: levels meet at vertices both have, which the
    coarser level leaves unblended), indices renumbered."""
    used = np.unique(tris)
    order = used[np.lexsort((morph[used], xy[used, 1], xy[used, 0]))]  # by point, least morph first
    pts = xy[order]
    first = np.ones(len(order), bool)
    first[1:] = np.any(pts[1:] != pts[:-1], axis=1)
    keep = order[first]
    index = np.full(len(xy), -1, np.int64)
    index[order] = np.cumsum(first) - 1
    return WaterMesh(np.ascontiguousarray(xy[keep], np.float32), np.ascontiguousarray(parents[keep], np.float32),
                     np.ascontiguousarray(morph[keep], np.float32), np.ascontiguousarray(index[tris], np.uint32),
                     technique, float(spacing))


def _texel(scene: Scene) -> float:
    """The water texture's texel, m (half the square for a flat water level)."""
    return scene.length / max(np.shape(scene.water)[:2]) if np.ndim(scene.water) else scene.length / 2


def _on_texels(scene: Scene, x, step: float):
    """``x`` moved down to the lattice of ``step`` through a texel centre (vertices there read texels)."""
    origin = -0.5 * scene.length + 0.5 * _texel(scene)
    return origin + step * np.floor((np.asarray(x, float) - origin) / step + 1e-9)


def _spacing(scene: Scene, spacing) -> float:
    if spacing is None:
        return float(_texel(scene))
    return check_scalar("spacing", spacing, lo=0.0, lo_open=True)


MAX_VERTICES = 1 << 24
"""The most vertices a mesh may have (16.7 M: 64 bytes each on the GPU, about 1 GiB)."""


def _check_size(vertices: float, what: str) -> None:
    if vertices > MAX_VERTICES:
        raise ValueError(f"{what} would make {vertices:.3g} vertices, over MAX_VERTICES = {MAX_VERTICES}: "
                         f"take a coarser spacing or a smaller ring")


def uniform_mesh(scene: Scene, spacing: Optional[float] = None) -> WaterMesh:
    """One grid of equal square cells over the water's region (:func:`mesh_region`).

    Parameters
    ----------
    scene : Scene
    spacing : float, optional
        The cells' side, m (default the water texture's texel).

    Returns
    -------
    WaterMesh
        ``(2·half/spacing + 1)²`` vertices (rounded up), every vertex its own height.
    """
    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    s = _spacing(scene, spacing)
    cx, cy, half = mesh_region(scene)
    x0, y0 = _on_texels(scene, cx - half, s), _on_texels(scene, cy - half, s)
    cells = max(int(math.ceil(max(cx + half - x0, cy + half - y0) / s - 1e-9)), 1)
    _check_size((cells + 1.0) ** 2, f"spacing {s:.3g} m over {2 * half:.3g} m")
    ij, tris, _ = _lattice(0, cells, 0, cells)
    xy = np.stack([x0 + ij[:, 0] * s, y0 + ij[:, 1] * s], -1)
    return _mesh("uniform", xy, np.concatenate([xy, xy], -1), np.zeros(len(xy)), tris, s)


def clipmap_mesh(scene: Scene, spacing: Optional[float] = None, *, cells: int = 32, band: float = 0.25,
                 levels: Optional[int] = None) -> WaterMesh:
    """Concentric square rings around the eye, each level's spacing twice the one inside it
    (geometry clipmaps, Losasso & Hoppe 2004).

    Level k is a square of ``2·cells`` cells of side ``spacing·2ᵏ`` a side, all levels centred on
    one point (the eye, snapped to the finest level's doubled lattice, which has a vertex on a texel
    centre), less the square of the level inside it; level 0 is whole. Over the outer ``band`` of
    each level but the last, a vertex's height blends linearly to the next level's surface at its
    point (the mean of the two next-level vertices at the ends of the coarse edge or diagonal it
    lies on), reaching it at the level's edge, so the edge is the coarser level's edge; a zero-area
    triangle over each edge vertex between two coarse ones closes the T-junction's hairline cracks.
    Levels are added until the rings cover :func:`mesh_region`.

    Parameters
    ----------
    scene : Scene
    spacing : float, optional
        The finest level's spacing, m (default the water texture's texel).
    cells : int
        Half the cells a side of each level, even, in [4, 512].
    band : float
        The blended band's width as a fraction of a level's half-side, in (0, 0.5).
    levels : int, optional
        The number of levels (default: as many as cover the region), in [1, 24].

    Returns
    -------
    WaterMesh
    """
    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    s0 = _spacing(scene, spacing)
    m = check_int("cells", cells, lo=4, hi=512)
    if m % 2:
        raise ValueError(f"cells must be even (the inner level's edge lies on the outer level's vertices), got {m}")
    band = check_scalar("band", band, lo=0.0, hi=0.5, lo_open=True, hi_open=True)
    cx, cy, half = mesh_region(scene)
    centre = _on_texels(scene, np.asarray(scene.camera.eye[:2], float) + s0, 2 * s0)  # the eye, rounded
    reach = half + float(np.max(np.abs(centre - (cx, cy))))  # the region, seen from the centre
    need = max(int(math.ceil(math.log2(max(reach / (m * s0), 1.0)) - 1e-9)) + 1, 1)
    count = need if levels is None else check_int("levels", levels, lo=1, hi=24)
    _check_size(count * (2 * m + 1.0) ** 2, f"{count} levels of {2 * m} cells")
    xy_all, par_all, mor_all, tri_all, offset = [], [], [], [], 0
    for k in range(count):
        s = s0 * 2**k
        ij, tris, cell = _lattice(-m, m, -m, m)
        if k > 0:  # the hole the level inside fills: cells within ±m/2
            inside = np.all((cell >= -m // 2) & (cell + 1 <= m // 2), axis=1)
            tris = tris[~inside]
        i, j = ij[:, 0], ij[:, 1]
        xy = centre + s * ij
        # the next level's surface at each vertex: the mean of the ends of the coarse edge or diagonal it is on
        di, dj = i % 2, j % 2
        p1 = centre + s * np.stack([i - di, j - dj], -1)
        p2 = centre + s * np.stack([i + di, j + dj], -1)
        if k == count - 1:
            morph = np.zeros(len(xy))
        else:
            d = np.maximum(np.abs(i), np.abs(j)) * s
            width = band * m * s
            morph = np.clip((d - (m * s - width)) / width, 0.0, 1.0)
        # zero-area triangles over the odd vertices of the outer edge (T-junctions with the next level)
        edge = []
        n = 2 * m + 1
        idx = (j + m) * n + (i + m)
        grid_index = np.full((n, n), -1)
        grid_index[j + m, i + m] = idx
        if k < count - 1:
            for a in range(-m + 1, m, 2):
                for (pa, pm, pb) in (((a - 1, -m), (a, -m), (a + 1, -m)), ((m, a - 1), (m, a), (m, a + 1)),
                                     ((a + 1, m), (a, m), (a - 1, m)), ((-m, a + 1), (-m, a), (-m, a - 1))):
                    edge.append([grid_index[pa[1] + m, pa[0] + m], grid_index[pm[1] + m, pm[0] + m],
                                 grid_index[pb[1] + m, pb[0] + m]])
        tris = np.concatenate([tris, np.asarray(edge, np.int64).reshape(-1, 3)])
        xy_all.append(xy)
        par_all.append(np.concatenate([p1, p2], -1))
        mor_all.append(morph)
        tri_all.append(tris + offset)
        offset += len(xy)
    return _mesh("clipmap", np.concatenate(xy_all), np.concatenate(par_all), np.concatenate(mor_all),
                 np.concatenate(tri_all), s0)


def projected_grid(scene: Scene, columns: int = 128, rows: int = 256, *, aspect: float = 4 / 3,
                   margin: float = 0.1) -> WaterMesh:
    """Johanson's (2004) projected grid: a regular grid over the screen whose vertices are the
    points where their view rays meet the water's mean level.

    The grid spans the screen and ``margin`` more of it on every side (waves lift vertices, which
    would otherwise leave the screen's edge bare). A ray that does not meet the level within the
    region's reach (above the horizon, or past the mesh's far edge) is cut there: its vertex goes
    to the far edge along its horizontal direction, so the rows above the horizon collapse onto it.
    From an eye H above the level a row step of δ rad lands about δ·r²/H apart along the view at
    distance r: the grid is dense near the eye and sparse near the horizon, where it fails.

    Parameters
    ----------
    scene : Scene
        Its camera is the projector.
    columns, rows : int
        Cells across and up the screen, in [1, 4096].
    aspect : float
        The image's width over its height (the renderer's), in (0, 16].
    margin : float
        Extra screen on each side, as a fraction of the screen's half-size, in [0, 1].

    Returns
    -------
    WaterMesh
    """
    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    nx, ny = check_int("columns", columns, lo=1, hi=4096), check_int("rows", rows, lo=1, hi=4096)
    aspect = check_scalar("aspect", aspect, lo=0.0, hi=16.0, lo_open=True)
    margin = check_scalar("margin", margin, lo=0.0, hi=1.0)
    _check_above(scene)
    cam = scene.camera
    f, r, u = (np.asarray(v, float) for v in cam.basis())
    eye = np.asarray(cam.eye, float)
    tan_half = math.tan(math.radians(cam.fov) / 2)
    level = float(np.mean(scene.water, dtype=np.float64))
    cx, cy, half = mesh_region(scene)
    reach = half if scene.surroundings != "none" else math.hypot(abs(eye[0]) + half, abs(eye[1]) + half)
    ij, tris, _ = _lattice(0, nx, 0, ny)
    sx = (1 + margin) * (2 * ij[:, 0] / nx - 1)
    sy = (1 + margin) * (2 * ij[:, 1] / ny - 1)
    d = f + sx[:, None] * tan_half * aspect * r + sy[:, None] * tan_half * u
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    horiz = np.linalg.norm(d[:, :2], axis=1)
    down = d[:, 2] < 0
    t = np.full(len(d), np.inf)
    t[down] = (level - eye[2]) / d[down, 2]
    hit = down & (t * horiz <= reach)
    ahead = f[:2] / np.linalg.norm(f[:2]) if np.linalg.norm(f[:2]) > 0 else np.array([1.0, 0.0])
    away = np.where(horiz[:, None] > 0, d[:, :2] / np.maximum(horiz, 1e-300)[:, None], ahead)
    xy = np.where(hit[:, None], eye[:2] + np.where(hit, t, 0.0)[:, None] * d[:, :2], eye[:2] + reach * away)
    near = np.linalg.norm(xy[1:nx + 1] - xy[:nx], axis=1)
    spacing = float(np.min(near[near > 0])) if np.any(near > 0) else float(reach)
    return _mesh("projected", xy, np.concatenate([xy, xy], -1), np.zeros(len(xy)), tris, spacing)


def displaced_mesh(scene: Scene, mesh: WaterMesh, displacement) -> WaterMesh:
    """``mesh`` moved by a choppy surface's horizontal displacement, as engines move their vertices.

    An engine with a choppy sea (:func:`wavephys.surfaces.choppy.displacement`) keeps its vertices on
    the rest lattice and moves each by the displacement Δ(p) at its rest point p, lifting it to the
    height there; the exact surface is the height field resampled at the displaced points
    (:func:`wavephys.surfaces.resample.resample_heights`), which is what the scene's ``water`` holds
    and the march draws. This moves every vertex (and the parents it blends to) from p to p + f·Δ(p)
    (Δ sampled as the water is: clamped, or tiled, and faded by the same factor f with distance);
    drawn, each takes the scene's height at its moved point, the rest point's height z(p) up to the
    resampling's error. What the image then shows against the march is the engine's error: the
    surface sampled at the displaced, uneven points (crowded on crests, sparse in troughs) instead
    of a regular lattice.

    Parameters
    ----------
    scene : Scene
        Its ``water`` the resampled heights of the displaced surface.
    mesh : WaterMesh
        Laid at rest (any technique).
    displacement : array_like (2, ny, nx) or (3, ny, nx)
        (Δx, Δy[, z]), m, at the water texture's texel centres (only Δx, Δy are read), finite.

    Returns
    -------
    WaterMesh
    """
    from optics.rendering.reference import _fade, _surface_sample
    from wavephys.core.inputs import check_array

    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    check_instance("mesh", mesh, WaterMesh, "optics.rendering.meshes.WaterMesh")
    d = check_array("displacement", displacement, ndim=3)
    if d.shape[0] not in (2, 3) or d.shape[1:] != np.shape(scene.water):
        raise ValueError(f"displacement must have shape (2 or 3, {', '.join(map(str, np.shape(scene.water)))}) "
                         f"(the water texture's texels), got {d.shape}")
    if not np.all(np.isfinite(d[:2])):
        raise ValueError("displacement must be finite")

    def moved(xy):  # p + f·Δ(p): the faded sample f·Δ + (1 − f)·mean less the (1 − f)·mean (Δ fades to 0)
        xy = np.asarray(xy, np.float64)
        f = _fade(scene, xy)
        return xy + np.stack([_surface_sample(scene, d[c], xy) - (1 - f) * float(np.mean(d[c], dtype=np.float64))
                              for c in (0, 1)], -1)

    par = mesh.parents.astype(np.float64)
    parents = np.concatenate([moved(par[:, :2]), moved(par[:, 2:])], -1)
    return WaterMesh(moved(mesh.positions).astype(np.float32), parents.astype(np.float32), mesh.morph,
                     mesh.triangles, mesh.technique, mesh.spacing)


def water_mesh(scene: Scene, technique: str, **options) -> WaterMesh:
    """The mesh of ``technique`` for ``scene``, with its function's options.

    Parameters
    ----------
    scene : Scene
    technique : str
        A name in :data:`MESH_TECHNIQUES`.
    **options
        :func:`uniform_mesh`'s, :func:`clipmap_mesh`'s or :func:`projected_grid`'s.

    Returns
    -------
    WaterMesh
    """
    if not isinstance(technique, str):
        raise TypeError(f"technique must be a str, got {describe(technique)}")
    if technique not in MESH_TECHNIQUES:
        raise ValueError(f"technique must be one of {', '.join(MESH_TECHNIQUES)}, got {technique!r}")
    return {"uniform": uniform_mesh, "clipmap": clipmap_mesh, "projected": projected_grid}[technique](scene, **options)


# -- the heights the mesh draws, and their error ------------------------------------------------------

def mesh_heights(scene: Scene, mesh: WaterMesh) -> np.ndarray:
    """Each vertex's height as the vertex shader gives it, m, float64: the water as drawn at the
    vertex (:func:`optics.rendering.reference.water_level`), blended by ``morph`` to the mean at its
    two parents.

    Parameters
    ----------
    scene : Scene
    mesh : WaterMesh

    Returns
    -------
    numpy.ndarray (N,)
    """
    from optics.rendering.reference import water_level

    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    check_instance("mesh", mesh, WaterMesh, "optics.rendering.meshes.WaterMesh")
    h = water_level(scene, mesh.positions.astype(np.float64))
    w = mesh.morph.astype(np.float64)
    if np.any(w > 0):
        par = mesh.parents.astype(np.float64)
        coarse = 0.5 * (water_level(scene, par[:, :2]) + water_level(scene, par[:, 2:]))
        h = h + w * (coarse - h)
    return h


_BARY = np.array([(a, b, 4 - a - b) for a in range(5) for b in range(5 - a)], float) / 4
"""The 15 points of the order-4 barycentric lattice of a triangle (corners, edges, inside)."""


def height_errors(scene: Scene, mesh: WaterMesh, *, bands=BANDS, aspect: float = 4 / 3) -> list:
    """The mesh's surface against the water's, per distance band, over the triangles in view.

    Every triangle with a corner inside the view (and within the region's reach, in front of the
    eye) is sampled at the 15 points of its order-4 barycentric lattice where the water stands above
    the ground (under dry land the water's mesh is hidden): the mesh's height there
    (linear between its corners' :func:`mesh_heights`) against the water as drawn
    (:func:`optics.rendering.reference.water_level`), binned by the point's horizontal distance
    from the eye in eye heights (``bands``).

    Parameters
    ----------
    scene : Scene
    mesh : WaterMesh
    bands : sequence of float
        Increasing band edges, in eye heights above the mean level (default :data:`BANDS`).
    aspect : float
        The image's width over its height.

    Returns
    -------
    list of dict
        One per band: ``lo``, ``hi`` (edges, m), ``points`` (samples in it), ``max`` and ``rms``
        (m; NaN where the band has no sample).
    """
    from optics.rendering.reference import _sample, water_level

    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    check_instance("mesh", mesh, WaterMesh, "optics.rendering.meshes.WaterMesh")
    edges = _check_bands(bands)
    aspect = check_scalar("aspect", aspect, lo=0.0, hi=16.0, lo_open=True)
    _check_above(scene)
    edges = edges * _eye_height(scene)
    cam = scene.camera
    f, r, u = (np.asarray(v, float) for v in cam.basis())
    eye = np.asarray(cam.eye, float)
    tan_half = math.tan(math.radians(cam.fov) / 2)
    z = mesh_heights(scene, mesh)
    p = np.concatenate([mesh.positions.astype(np.float64), z[:, None]], -1)
    v = p - eye
    w = v @ f
    with np.errstate(divide="ignore", invalid="ignore"):
        sx, sy = (v @ r) / (w * tan_half * aspect), (v @ u) / (w * tan_half)
    seen = (w > 0) & (np.abs(sx) <= 1) & (np.abs(sy) <= 1)
    tris = mesh.triangles[np.any(seen[mesh.triangles], axis=1)]
    sq, sum2, top = np.zeros(len(edges) - 1, int), np.zeros(len(edges) - 1), np.zeros(len(edges) - 1)
    cx, cy, half = mesh_region(scene)
    for start in range(0, len(tris), 65536):
        t = tris[start:start + 65536]
        pts = np.einsum("kc,tcd->tkd", _BARY, p[t]).reshape(-1, 3)
        keep = np.abs(pts[:, 0] - cx) <= half
        keep &= np.abs(pts[:, 1] - cy) <= half
        if scene.surroundings != "none":
            keep &= np.hypot(pts[:, 0] - eye[0], pts[:, 1] - eye[1]) <= half
        pts = pts[keep]
        exact = water_level(scene, pts[:, :2])
        wet = exact > _sample(scene.ground, scene.length, pts[:, :2])  # under dry land nothing is seen
        pts, exact = pts[wet], exact[wet]
        err = np.abs(pts[:, 2] - exact)
        dist = np.hypot(pts[:, 0] - eye[0], pts[:, 1] - eye[1])
        band = np.searchsorted(edges, dist, side="right") - 1
        ok = (band >= 0) & (band < len(edges) - 1)
        np.add.at(sq, band[ok], 1)
        np.add.at(sum2, band[ok], err[ok] ** 2)
        np.maximum.at(top, band[ok], err[ok])
    return [dict(lo=float(edges[b]), hi=float(edges[b + 1]), points=int(sq[b]),
                 max=float(top[b]) if sq[b] else math.nan,
                 rms=float(math.sqrt(sum2[b] / sq[b])) if sq[b] else math.nan) for b in range(len(edges) - 1)]


def _check_bands(bands) -> np.ndarray:
    try:
        edges = np.asarray(bands, float)
    except (TypeError, ValueError):
        raise TypeError(f"bands must be a sequence of numbers, got {describe(bands)}") from None
    if edges.ndim != 1 or len(edges) < 2 or np.isnan(edges).any() or not np.all(np.diff(edges) > 0) or edges[0] < 0:
        raise ValueError(f"bands must be increasing edges ≥ 0, at least two, got {bands!r}")
    return edges


def _pixel_distances(scene: Scene, width: int, height: int) -> np.ndarray:
    """Each pixel's horizontal distance from the eye to where its view ray meets the mean level, m
    (inf for rays that do not), row 0 at the top."""
    from optics.rendering.reference import ray_directions

    d = ray_directions(scene.camera, width, height)
    h = _eye_height(scene)
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(d[..., 2] < 0, h / -d[..., 2], np.inf)
    return t * np.hypot(d[..., 0], d[..., 1])


def water_pixels(scene: Scene, width: int, height: int, *, steps: int = 256, refine: int = 10) -> np.ndarray:
    """Where the ray-marcher's view rays meet the water first (the CPU reference's march, float64).

    Parameters
    ----------
    scene : Scene
    width, height : int
        The image, pixels.
    steps, refine : int
        March steps and bisections (the renderer's defaults).

    Returns
    -------
    numpy.ndarray (height, width) bool
        Row 0 at the top.
    """
    from optics.rendering.reference import march, ray_directions

    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    d = ray_directions(scene.camera, check_int("width", width, lo=1), check_int("height", height, lo=1))
    d = d.reshape(-1, 3)
    o = np.broadcast_to(np.asarray(scene.camera.eye, float), d.shape).copy()
    _, hit, which = march(scene, o, d, 0, check_int("steps", steps, lo=1), check_int("refine", refine, lo=0))
    return (hit & (which == 1)).reshape(height, width)


def mesh_errors(scene: Scene, mesh: WaterMesh, width: int = 160, height: int = 120, *, renderer=None,
                bands=BANDS, repeats: int = 3, heights: bool = True) -> dict:
    """The mesh path's picture of ``scene`` against the ray-marcher's, per distance band, with its cost.

    Parameters
    ----------
    scene : Scene
        Seen from above the water's mean level.
    mesh : WaterMesh
        Made for this scene (and, for a projected grid, this image's aspect).
    width, height : int
        The image, pixels.
    renderer : Renderer, optional
        One of that size to draw with (default: a new one, released after).
    bands : sequence of float
        Band edges in eye heights (default :data:`BANDS`).
    repeats : int
        Timed draws of each path (median), ≥ 1.
    heights : bool
        Also measure the heights (:func:`height_errors`).

    Returns
    -------
    dict
        ``bands``: one dict per band (``lo``, ``hi`` in m, ``pixels``, ``psnr`` in dB, ``max`` the
        largest channel error on the image's [0, 1] scale, ``p99`` its 99th percentile over the
        band's pixels (a pixel whose reflected ray grazes a crest flips with a hundredth of a pixel's
        shift, as in :func:`optics.rendering.reference.psnr_against_reference`), ``water`` the pixels
        where the march sees the water (:func:`water_pixels`), ``bare`` the pixels where the march sees
        water and the mesh draws nothing (:func:`water_pixels`, :func:`mesh_coverage`), and with
        ``heights`` the height error's ``height_max``, ``height_rms``, m); ``psnr`` and ``bare`` over
        the whole image; ``vertices``, ``triangles``, ``texel_reads`` (the vertex shader's,
        :attr:`WaterMesh.texel_reads`), ``passes`` (2: the background and the mesh);
        ``mesh_seconds`` and ``march_seconds`` (median draw, this machine); ``image`` and
        ``reference`` (the two pictures).
    """
    from optics.rendering.reference import psnr
    from optics.rendering.renderer import Renderer

    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    check_instance("mesh", mesh, WaterMesh, "optics.rendering.meshes.WaterMesh")
    width, height = check_int("width", width, lo=1), check_int("height", height, lo=1)
    repeats = check_int("repeats", repeats, lo=1)
    heights = check_bool("heights", heights)
    edges = _check_bands(bands)
    if renderer is not None:
        from optics.rendering.renderer import Renderer as _Renderer

        check_instance("renderer", renderer, _Renderer, "optics.rendering.Renderer")
    _check_above(scene)
    own = renderer is None
    r = Renderer(width, height) if own else renderer
    try:
        if (r.width, r.height) != (width, height):
            raise ValueError(f"renderer draws {r.width}×{r.height}, not width×height {width}×{height}")
        image, reference = render_mesh(r, scene, mesh), r.render(scene)
        water = water_pixels(scene, width, height)
        bare = water & ~mesh_coverage(r, scene, mesh)
        mesh_s, march_s = mesh_seconds(r, scene, mesh, repeats), r.frame_seconds(scene, repeats)
    finally:
        if own:
            r.release()
    dist = _pixel_distances(scene, width, height) / _eye_height(scene)
    rows = []
    for b in range(len(edges) - 1):
        sel = (dist >= edges[b]) & (dist < edges[b + 1])
        diff = np.abs(image[sel] - reference[sel])
        rows.append(dict(lo=float(edges[b] * _eye_height(scene)), hi=float(edges[b + 1] * _eye_height(scene)),
                         pixels=int(sel.sum()), psnr=psnr(image[sel], reference[sel]) if sel.any() else math.nan,
                         max=float(diff.max()) if sel.any() else math.nan,
                         p99=float(np.percentile(diff.max(axis=-1), 99)) if sel.any() else math.nan,
                         water=int((water & sel).sum()), bare=int((bare & sel).sum())))
    if heights:
        for row, h in zip(rows, height_errors(scene, mesh, bands=edges, aspect=width / height)):
            row.update(height_max=h["max"], height_rms=h["rms"])
    return dict(bands=rows, psnr=psnr(image, reference), bare=int(bare.sum()), vertices=mesh.vertices,
                triangles=mesh.triangle_count, texel_reads=mesh.texel_reads, passes=2,
                mesh_seconds=mesh_s, march_seconds=march_s, image=image, reference=reference)


# -- GLSL ---------------------------------------------------------------------------------------------

MESH_VERTEX = """
#version 330
uniform sampler2D water_tex; uniform ivec2 water_size;
uniform float extent, water_mean, near_tiles, far_tiles;
uniform int surroundings;
uniform vec3 eye, cam_f, cam_r, cam_u;
uniform float tan_half;
uniform vec2 resolution;
uniform vec2 depth_range;  // near and far planes, m along the view
in vec2 position;
in vec4 parents;
in float morph;
out vec3 world;
%SAMPLING%
%WATER_HEIGHT%
void main() {
    float h = water_h(position);
    if (morph > 0.0) h = mix(h, 0.5 * (water_h(parents.xy) + water_h(parents.zw)), morph);
    world = vec3(position, h);
    vec3 v = world - eye;
    float x = dot(v, cam_r), y = dot(v, cam_u), w = dot(v, cam_f);
    float n = depth_range.x, f = depth_range.y;
    gl_Position = vec4(x / (tan_half * resolution.x / resolution.y), y / tan_half,
                       (w * (f + n) - 2.0 * f * n) / (f - n), w);
}
"""
"""The mesh path's vertex shader: a vertex's height is the ray-marcher's ``water_h`` at it, blended by
``morph`` to its parents' mean; the projection is the ray-marcher's view rays inverted (a pixel's
centre sees along the ray the march sends through it)."""

MESH_MAIN = """
in vec3 world;
uniform float reach;  // the mesh's horizontal reach from the eye with surroundings, m
void main() {
    eps = 1e-4 * extent;
    vec3 v = world - eye;
    if (surroundings == 0 ? max(abs(world.x), abs(world.y)) > 0.5 * extent : length(v.xy) > reach) discard;
    float t = length(v);
    frag = vec4(shade_water(world, v / t, t), 1.0);
}
"""
"""The mesh path's fragment ``main``: the ray-marcher's shading of the water at the mesh's point
(what is in front of it, the ground, is in the depth buffer from :data:`BACKGROUND_MAIN`)."""

BACKGROUND_MAIN = """
uniform vec2 depth_range;
uniform bool marker;  // draw -1 where the mesh leaves the pixel bare (coverage)
void main() {
    eps = 1e-4 * extent;
    vec3 d = view_ray();
    if (marker) { frag = vec4(-1.0); gl_FragDepth = 1.0; return; }
    int which;
    float t = march(eye, d, 2, which);
    if (t >= 0.0) {
        frag = vec4(shade_ground(eye + t * d), 1.0);
        float w = t * dot(d, cam_f), n = depth_range.x, f = depth_range.y;
        gl_FragDepth = clamp(0.5 * (w * (f + n) - 2.0 * f * n) / ((f - n) * w) + 0.5, 0.0, 1.0);
    } else {
        frag = vec4(surroundings != 0 ? far_field(eye, d) : environment(d), 1.0);
        gl_FragDepth = 1.0;
    }
}
"""
"""The mesh path's first pass: what is not the water (the ground by the ray-marcher's march, with
its depth, as an engine's terrain; the far field; the sky)."""


# -- drawing ------------------------------------------------------------------------------------------

def _check_live(renderer) -> None:
    if renderer.ctx is None:
        raise RuntimeError("this Renderer has been released (renderer)")


def _programs(renderer):
    """The mesh path's two programs on ``renderer``'s context (compiled once per renderer)."""
    from optics.gpu import GLSL_SAMPLING
    from optics.rendering.renderer import SHADING, WATER_HEIGHT, VERTEX

    progs = getattr(renderer, "_mesh_programs", None)
    if progs is None:
        vertex = MESH_VERTEX.replace("%SAMPLING%", GLSL_SAMPLING).replace("%WATER_HEIGHT%", WATER_HEIGHT)
        background = renderer.ctx.program(vertex_shader=VERTEX, fragment_shader=SHADING.replace("%MAIN%",
                                                                                                BACKGROUND_MAIN))
        mesh = renderer.ctx.program(vertex_shader=vertex, fragment_shader=SHADING.replace("%MAIN%", MESH_MAIN))
        quad = renderer.ctx.vertex_array(background, [(renderer._vbo, "2f", "position")])
        fbo = renderer.ctx.framebuffer(
            color_attachments=[renderer.ctx.renderbuffer((renderer.width, renderer.height), 4, dtype="f4")],
            depth_attachment=renderer.ctx.depth_renderbuffer((renderer.width, renderer.height)))
        progs = renderer._mesh_programs = dict(background=background, mesh=mesh, quad=quad, fbo=fbo, held=None)
    return progs


def _mesh_arrays(renderer, progs, mesh: WaterMesh):
    """The mesh's vertex array on the GPU (kept while the same mesh is drawn again)."""
    held = progs["held"]
    if held is not None and held[0] is mesh:
        return held[1]
    if held is not None:
        for obj in held[2]:
            obj.release()
    data = np.concatenate([mesh.positions, mesh.parents, mesh.morph[:, None]], -1).astype(np.float32)
    vbo = renderer.ctx.buffer(np.ascontiguousarray(data).tobytes())
    ibo = renderer.ctx.buffer(np.ascontiguousarray(mesh.triangles, np.uint32).tobytes())
    vao = renderer.ctx.vertex_array(progs["mesh"], [(vbo, "2f 4f 1f", "position", "parents", "morph")],
                                    index_buffer=ibo, index_element_size=4)
    progs["held"] = (mesh, vao, (vao, vbo, ibo))
    return vao


def _depth_range(scene: Scene) -> tuple:
    """Near and far planes (m along the view) that hold the mesh's region and the volume's box."""
    cx, cy, half = mesh_region(scene)
    zlo, zhi = scene.bounds()
    eye = np.asarray(scene.camera.eye, float)
    far = math.sqrt((abs(eye[0] - cx) + half) ** 2 + (abs(eye[1] - cy) + half) ** 2
                    + max(abs(eye[2] - zlo), abs(eye[2] - zhi)) ** 2)
    return 1e-3 * max(_eye_height(scene), 1e-6), 1.01 * far


def _draw(renderer, scene: Scene, mesh: WaterMesh, marker: bool = False):
    progs = _programs(renderer)
    vao = _mesh_arrays(renderer, progs, mesh)
    renderer._bind(scene, (progs["background"], progs["mesh"]))
    depth = _depth_range(scene)
    reach = mesh_region(scene)[2]
    for name in ("background", "mesh"):
        renderer._uniforms(scene, progs[name], depth_range=depth, reach=reach, marker=marker)
    ctx = renderer.ctx
    progs["fbo"].use()
    progs["fbo"].clear(0.0, 0.0, 0.0, 1.0, depth=1.0)
    ctx.enable(ctx.DEPTH_TEST)
    ctx.depth_func = "<="
    try:
        progs["quad"].render(mode=ctx.TRIANGLE_STRIP)
        vao.render(mode=ctx.TRIANGLES)
    finally:
        ctx.disable(ctx.DEPTH_TEST)
    return progs["fbo"]


def mesh_coverage(renderer, scene: Scene, mesh: WaterMesh) -> np.ndarray:
    """Where ``mesh`` draws: every pixel its triangles cover within its region (nothing is drawn in
    front of them here, not even land).

    Parameters
    ----------
    renderer : Renderer
    scene : Scene
    mesh : WaterMesh

    Returns
    -------
    numpy.ndarray (height, width) bool
        Row 0 at the top.
    """
    return _read(renderer, scene, mesh, marker=True)[..., 0] >= 0.0


def render_mesh(renderer, scene: Scene, mesh: WaterMesh) -> np.ndarray:
    """Draw ``scene`` with its water as ``mesh`` (module doc): (height, width, 3) float32, linear RGB,
    row 0 at the top, as :meth:`Renderer.render <optics.rendering.renderer.Renderer.render>` draws it
    by marching.

    Parameters
    ----------
    renderer : Renderer
        The renderer (its size, context and textures).
    scene : Scene
        Seen from above the water's mean level.
    mesh : WaterMesh
        Made for this scene.

    Returns
    -------
    numpy.ndarray (height, width, 3) float32
    """
    return _read(renderer, scene, mesh)


def _check_call(renderer, scene, mesh) -> None:
    """The drawing calls' arguments checked, by name."""
    from optics.rendering.renderer import Renderer

    check_instance("renderer", renderer, Renderer, "optics.rendering.Renderer")
    check_instance("scene", scene, Scene, "optics.rendering.Scene")
    check_instance("mesh", mesh, WaterMesh, "optics.rendering.meshes.WaterMesh")
    _check_live(renderer)
    _check_above(scene)


def _read(renderer, scene, mesh, marker: bool = False) -> np.ndarray:
    """One frame of the mesh path read back: (height, width, 3) float32, row 0 at the top."""
    _check_call(renderer, scene, mesh)
    with renderer.ctx:
        data = _draw(renderer, scene, mesh, marker).read(components=3, dtype="f4")
    img = np.frombuffer(data, np.float32).reshape(renderer.height, renderer.width, 3)
    return np.ascontiguousarray(img[::-1])


def mesh_seconds(renderer, scene: Scene, mesh: WaterMesh, repeats: int = 5) -> float:
    """Median wall time of one mesh-path frame (bind, both passes, finish; the mesh already on the GPU),
    after one warm-up, as :meth:`Renderer.frame_seconds
    <optics.rendering.renderer.Renderer.frame_seconds>` times the march.

    Parameters
    ----------
    renderer : Renderer
    scene : Scene
    mesh : WaterMesh
    repeats : int
        Timed frames, ≥ 1.

    Returns
    -------
    float
        Seconds.
    """
    import time

    _check_call(renderer, scene, mesh)
    times = []
    for _ in range(check_int("repeats", repeats, lo=1) + 1):
        t = time.perf_counter()
        with renderer.ctx:
            _draw(renderer, scene, mesh)
            renderer.ctx.finish()
        times.append(time.perf_counter() - t)
    return float(np.median(times[1:]))
