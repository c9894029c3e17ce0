"""The planner's shading as one compiled program: the same colour as the formula evaluated on the
host in float64 (C = R + (1 − R)·T(d)·albedo·E/E₀, the absorption evaluated directly), on
generated scenes with every Fresnel form and absorption method of the families."""

import math
from dataclasses import replace

import jax.numpy as jnp
import numpy as np
import pytest

from optics.light.attenuation import WATER_TRANSMITTANCE_METHODS
from optics.light.directions import sun_direction
from optics.light.fresnel import N_WATER, REFLECTANCE_METHODS, reflectance
from wavephys.planner import SceneModel, full_model, generate_scenes
from wavephys.planner.runner import FLOOR_ALBEDO, floor_light, shade, transmittance, uniform_interp


def _host_colour(scene, model, heights):
    """The documented formula in float64 on the host, the water path's transmittance evaluated by
    the family's method itself (no table)."""
    gx, gy = (np.asarray(g, np.float64) for g in model.output_grid.gradient(jnp.asarray(heights, jnp.float32)))
    normal = np.stack([-gx, -gy, np.ones_like(gx)], -1)
    normal /= np.linalg.norm(normal, axis=-1, keepdims=True)
    cos_i = np.clip(normal @ np.array(sun_direction(scene.view_elevation, 180.0)), 0.0, 1.0)
    r = np.asarray(reflectance(jnp.asarray(cos_i, jnp.float32), method=model.choices.fresnel), np.float64)[..., None]
    if math.isinf(scene.depth):
        return np.broadcast_to(r, cos_i.shape + (3,))
    sin_t = np.sqrt(1.0 - cos_i**2) / N_WATER
    path = scene.depth * (1.0 / np.sqrt(1.0 - sin_t**2) + 1.0)
    trans = transmittance(scene, model.choices.absorption, path)  # direct (spectral: its own 64-path table)
    light = floor_light(scene, model, heights)[..., None]
    return np.clip(r + (1.0 - r) * trans * FLOOR_ALBEDO * light, 0.0, 1.0)


SCENES = generate_scenes(7, seed=11, texels=(32, 48))  # one of each kind: pools with caustics, deep sea, …
FAST = ("pool", "open_sea", "tank")  # the rest run with the slow tests


@pytest.mark.parametrize("scene", [s if s.name.split("-")[0] in FAST else pytest.param(s, marks=pytest.mark.slow)
                                   for s in SCENES], ids=lambda s: s.name)
def test_compiled_shading_is_the_formula(scene):
    """Within 1e-6 of the float64 formula (float32 rounding: 0.07 of a 16-bit image quantum) for
    every form and method (the floor light off: it does not depend on them), and for the full
    model (its caustics on where the scene shows them), on a frame of the scene's own heights."""
    rng = np.random.default_rng(len(scene.name))
    heights = 0.3 * scene.height_range * rng.standard_normal((scene.texels, scene.texels))
    full = full_model(scene)
    combos = [(f, a, 0) for f in REFLECTANCE_METHODS for a in WATER_TRANSMITTANCE_METHODS]
    combos.append((full.choices.fresnel, full.choices.absorption, full.choices.caustics))
    for fresnel, absorption, caustics in combos:
        model = SceneModel(scene, replace(full.choices, fresnel=fresnel, absorption=absorption, caustics=caustics))
        got = shade(scene, model, heights)
        assert got.shape == (scene.texels, scene.texels, 3) and got.dtype == np.float64
        diff = float(np.abs(got - _host_colour(scene, model, heights)).max())
        assert diff <= 1e-6, (scene.name, fresnel, absorption, caustics, diff)


def test_even_table_interpolation_is_numpys():
    """uniform_interp equals numpy.interp on evenly spaced nodes, held at the ends, over smooth
    tables of every length the shading uses and beyond."""
    rng = np.random.default_rng(0)
    for size in (2, 3, 64, 256, 1000):
        x0, span = rng.uniform(0.0, 5.0), rng.uniform(0.1, 10.0)
        nodes = np.linspace(x0, x0 + span, size)
        table = np.exp(-np.outer(nodes, rng.uniform(0.01, 0.5, 3)))  # transmittance-like
        x = np.concatenate([rng.uniform(x0 - 1.0, x0 + span + 1.0, 2000), nodes])
        want = np.stack([np.interp(x, nodes, table[:, c]) for c in range(3)], -1)
        got = np.asarray(uniform_interp(jnp.asarray(x, jnp.float32), jnp.float32(nodes[0]), jnp.float32(nodes[-1]),
                                        jnp.asarray(table, jnp.float32)))
        assert np.abs(got - want).max() <= 2e-6, size


def test_frames_are_assembled_in_few_block_sizes_that_waste_less_than_half_a_block():
    """A scene's frames go through the compiled assembly in blocks of one size from a short list
    (scenes of different lengths share compiled programs): at most FRAME_BLOCK, as few blocks as
    that allows, the padding under half the frames plus one per block (a 13-frame scene had been padded
    to 64, five times the work its cost predicted); the cost model counts the padding."""
    from wavephys.planner.runner import FRAME_BLOCK, FRAME_BLOCK_SIZES, assembled_frames, frame_block

    assert len(FRAME_BLOCK_SIZES) <= 12 and all(b <= max(1.5 * a, a + 1) for a, b in zip(FRAME_BLOCK_SIZES, FRAME_BLOCK_SIZES[1:]))
    for frames in range(1, 400):
        size = frame_block(frames)
        blocks = -(-frames // size)
        assert size in FRAME_BLOCK_SIZES and blocks == -(-frames // FRAME_BLOCK), frames
        assert 0 <= blocks * size - frames < 0.5 * frames + blocks, (frames, size)
        assert assembled_frames(frames) == blocks * size
