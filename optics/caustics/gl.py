"""Beam tracing in hardware: the beams of :mod:`optics.caustics.beam` drawn by OpenGL.

The way Loviscach (2003) and WebGL Water (Wallace 2011) make caustics on a GPU: every cell
of the surface becomes two triangles whose corners the vertex shader refracts and lands on
the floor; a geometry shader gives each triangle its flux E0·T·A₀ (the same as the JAX
method's) over its landed area, and the triangles are drawn with additive blending into a
float target, so folded sheets add. The GPU decides coverage by sampling pixel centres, so
the target is ``supersample`` times finer than the map and averaged down: the texel values
converge to the exact coverage of :func:`~optics.caustics.beam.floor_irradiance_beam` as
``supersample`` grows (measured in ``python -m bench optics``). No JAX in the drawing: the
surface's heights, exact slopes and sunlit mask are uploaded as one float texture.

Runs on any OpenGL 3.3 core context through EGL (Mesa llvmpipe on a CPU-only machine,
the GPU driver elsewhere); without one it raises
:class:`~optics.gpu.RendererUnavailable`.
"""

from __future__ import annotations

import numpy as np

from optics.caustics.common import prepare, shadow_steps, sunlit
from optics.light.fresnel import N_AIR, N_WATER
from optics.gpu import GLSL_OPTICS, GLSL_SAMPLING, gl_context
from wavephys.core.grid import Grid
from wavephys.core.inputs import check_int

__all__ = ["floor_irradiance_gl"]

VERTEX = """
#version 330
uniform sampler2D surf_tex;   // (eta, d eta/dx, d eta/dy, sunlit) on the tracing grid
uniform sampler2D ground_tex; // ground heights z_g (m) on the map's own grid, when use_ground
uniform int N, ground_n;
uniform float L, depth, n_air, n_water;
uniform vec3 d;               // direction of travel of the sunlight (down)
uniform bool fresnel, use_ground;
uniform int m;
out vec2 land_uv;             // landing point, floor texel coordinates (unwrapped)
out vec2 cross_xy;            // where the ray crossed z = 0, m (unwrapped)
out float trans;
%OPTICS%
const ivec2 CORNER[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
float ground_at(vec2 xy) { return bilinear_at(ground_tex, ivec2(ground_n), xy, L, true).r; }  // periodic
void main() {
    int cell = gl_VertexID / 6;
    ivec2 off = CORNER[gl_VertexID % 6];          // (column, row) offset of this corner
    ivec2 ij = ivec2(cell % N, cell / N) + off;   // unwrapped sample (column, row)
    vec4 s = texelFetch(surf_tex, ij % N, 0);
    float h = L / float(N);
    vec2 xy = -0.5 * L + (vec2(ij) + 0.5) * h;
    vec3 nrm = normalize(vec3(-s.g, -s.b, 1.0));
    vec3 t = refract_dir(d, nrm, n_air / n_water);
    float cos_i = clamp(-dot(d, nrm), 0.0, 1.0);
    trans = (fresnel ? 1.0 - fresnel_exact(cos_i, n_air, n_water) : 1.0) * s.a;
    float down = -t.z;
    float reach = (s.r + depth) / down;
    if (use_ground) {
        reach = (s.r - ground_at(xy)) / down;
        for (int k = 0; k < 5; k++) reach = (s.r - ground_at(xy + reach * t.xy)) / down;
    }
    vec2 land = xy + reach * t.xy;
    land_uv = (land + 0.5 * L) * (float(m) / L) - 0.5;
    cross_xy = xy - s.r * d.xy / d.z;
    gl_Position = vec4(0.0, 0.0, 0.0, 1.0);
}
"""

GEOMETRY = """
#version 330
layout(triangles) in;
layout(triangle_strip, max_vertices = 12) out;
in vec2 land_uv[];
in vec2 cross_xy[];
in float trans[];
uniform int m;
uniform float texel;          // floor texel side, m
flat out float density;
float twice_area(vec2 a, vec2 b, vec2 c) { return (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y); }
void main() {
    float source = 0.5 * abs(twice_area(cross_xy[0], cross_xy[1], cross_xy[2]));  // m²
    float landed = 0.5 * abs(twice_area(land_uv[0], land_uv[1], land_uv[2]));    // texel²
    float flux = source * (trans[0] + trans[1] + trans[2]) / 3.0;
    if (landed <= 1e-12 || flux <= 0.0) return;
    density = flux / (landed * texel * texel);   // E/E0 on every pixel it covers
    vec2 lo = min(min(land_uv[0], land_uv[1]), land_uv[2]);
    vec2 hi = max(max(land_uv[0], land_uv[1]), land_uv[2]);
    vec2 base = float(m) * floor((lo + 0.5) / float(m));  // bring the lowest corner into the map
    for (int c = 0; c < 4; c++) {                 // and its periodic copies where it sticks out
        vec2 shift = base + float(m) * vec2(c & 1, c >> 1);
        if ((c & 1) == 1 && hi.x + 0.5 - base.x < float(m)) continue;
        if ((c >> 1) == 1 && hi.y + 0.5 - base.y < float(m)) continue;
        for (int k = 0; k < 3; k++) {
            gl_Position = vec4(2.0 * (land_uv[k] - shift + 0.5) / float(m) - 1.0, 0.0, 1.0);
            EmitVertex();
        }
        EndPrimitive();
    }
}
"""

FRAGMENT = """
#version 330
flat in float density;
out float value;
void main() { value = density; }
"""

_STATE = {}


def _program():
    """The context and the program, made once per process (an EGL context costs tens of ms)."""
    if "program" not in _STATE:
        ctx = gl_context()
        _STATE["ctx"] = ctx
        _STATE["program"] = ctx.program(vertex_shader=VERTEX.replace("%OPTICS%", GLSL_SAMPLING + GLSL_OPTICS),
                                        geometry_shader=GEOMETRY, fragment_shader=FRAGMENT)
        _STATE["vao"] = ctx.vertex_array(_STATE["program"], [])
    return _STATE["ctx"], _STATE["program"], _STATE["vao"]


def _surface_texture(ctx, eta, grid: Grid, refine: int, d, steps: int):
    """Heights, exact (spectral) slopes and the sunlit mask on the refined grid, RGBA float32."""
    fine = Grid(grid.n * refine, grid.length)
    surface = grid.refine(eta, refine) if refine > 1 else eta
    gx, gy = fine.gradient(surface)
    lit = sunlit(surface, fine, np.asarray(d, np.float32), steps)
    data = np.stack([np.asarray(a, np.float32) for a in (surface, gx, gy, lit)], -1)
    return ctx.texture((fine.n, fine.n), 4, np.ascontiguousarray(data).tobytes(), dtype="f4")


def floor_irradiance_gl(eta, grid: Grid, depth, sun=(0.0, 0.0, 1.0), *, resolution: int | None = None,
                        n_water: float = N_WATER, fresnel: bool = True, refine: int = 1, supersample: int = 4):
    """Floor irradiance E/E0 by beams drawn on the GPU (module doc).

    Parameters
    ----------
    eta, grid, depth, sun, resolution, n_water, fresnel
        As :func:`optics.caustics.floor_irradiance` (heights in m on ``grid``; a floor depth
        in m or a ground height field; the direction towards the sun; the map's side).
        A ground height field must be on ``grid``.
    refine : int
        1 to 8: trace the surface Fourier-interpolated that many times finer (1, the default,
        errs up to a few % of the peak: 2.05 % on ``tests/test_families.py``'s sinusoid).
    supersample : int
        1 to 8: draw into a target that many times finer and average it down (coverage by pixel
        centres converges to the exact coverage).

    Returns
    -------
    numpy.ndarray (m, m), float32

    Raises
    ------
    RendererUnavailable
        No headless OpenGL 3.3 context.
    """
    light = prepare(eta, grid, depth, sun, resolution, n_water, fresnel)
    refine = check_int("refine", refine, lo=1, hi=8)
    s = check_int("supersample", supersample, lo=1, hi=8)
    m = light.resolution
    ctx, program, vao = _program()
    with ctx:  # current on this thread: another context (a Renderer's) may have been made since
        limit = int(ctx.info["GL_MAX_TEXTURE_SIZE"])
    if m * s > limit or grid.n * refine > limit:
        raise ValueError(f"resolution × supersample ({m * s}) and n × refine ({grid.n * refine}) must be at most "
                         f"the context's texture size {limit}")
    d = np.asarray(light.direction, np.float64)
    fine = Grid(grid.n * refine, grid.length)
    steps = shadow_steps(grid.refine(light.eta, refine) if refine > 1 else light.eta, fine, d)
    with ctx:
        fine_map = _draw(ctx, program, vao, light, grid, fine, refine, d, steps, m, s, fresnel)
    return fine_map.reshape(m, s, m, s).mean(axis=(1, 3))


def _draw(ctx, program, vao, light, grid: Grid, fine: Grid, refine: int, d, steps: int, m: int, s: int, fresnel: bool):
    """Upload the surface, draw every cell's two triangles additively, read the fine map back."""
    import moderngl

    surf = _surface_texture(ctx, light.eta, grid, refine, d, steps)
    ground = np.asarray(light.floor, np.float32) if light.ground else np.zeros((1, 1), np.float32)
    ground_tex = ctx.texture(ground.shape[::-1], 1, np.ascontiguousarray(ground).tobytes(), dtype="f4")
    target = ctx.texture((m * s, m * s), 1, dtype="f4")
    fbo = ctx.framebuffer(color_attachments=[target])
    try:
        surf.use(0)
        ground_tex.use(1)
        values = dict(surf_tex=0, ground_tex=1, N=fine.n, ground_n=ground.shape[0], L=float(grid.length),
                      depth=0.0 if light.ground else float(light.floor), n_air=float(N_AIR), n_water=light.n_water,
                      d=tuple(float(c) for c in d), fresnel=bool(fresnel), use_ground=bool(light.ground), m=m,
                      texel=float(grid.length) / m)
        for name, value in values.items():
            program[name].value = value
        fbo.use()
        fbo.clear(0.0)
        ctx.enable(moderngl.BLEND)
        ctx.blend_func = moderngl.ONE, moderngl.ONE
        ctx.disable(moderngl.DEPTH_TEST | moderngl.CULL_FACE)
        vao.render(moderngl.TRIANGLES, vertices=6 * fine.n * fine.n)
        return np.frombuffer(fbo.read(components=1, dtype="f4"), np.float32).reshape(m * s, m * s)
    finally:
        for obj in (fbo, target, surf, ground_tex):
            obj.release()
