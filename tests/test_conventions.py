"""One convention for space: a feature at a known coordinate lands on the same texel in the
simulation, the caustics map, the exported textures and the rendered frame.

The feature is a stone's crater (axisymmetric) dropped at a sample centre; each stage's
centroid of change must sit within a quarter texel of that coordinate — the old mismatch
(water half a texel off the ground) fails by a factor of two.
"""

import numpy as np
import pytest

from optics.caustics import floor_irradiance
from optics.rendering import Renderer, Scene, look_at
from optics.rendering.reference import ray_directions
from optics.rendering.textures import export_scene, load_npz
from wavephys import Grid, Simulation, Stones, Water

GRID = Grid(64, 8.0)
ROW, COL = 24, 42
X0, Y0 = float(GRID.coordinates[COL]), float(GRID.coordinates[ROW])  # 1.3125, -0.9375 m


@pytest.fixture(scope="module")
def crater():
    sim = Simulation(GRID, Water(), dt=0.05)
    return np.asarray(sim.surface(sim.drop(sim.initial_state(), Stones(X0, Y0, 0.25, 0.05))).eta)


def _centroid(change, x, y):
    w = np.abs(change)
    return float(np.sum(w * x) / np.sum(w)), float(np.sum(w * y) / np.sum(w))


def test_simulation_puts_the_crater_on_its_sample(crater):
    assert np.unravel_index(np.argmin(crater), crater.shape) == (ROW, COL)
    assert GRID.nearest(X0, Y0) == (ROW, COL)


def test_caustics_map_is_centred_on_the_feature(crater):
    flat = np.asarray(floor_irradiance(np.zeros_like(crater), GRID, 1.5))
    wavy = np.asarray(floor_irradiance(crater, GRID, 1.5))
    x, y = (np.asarray(a) for a in GRID.mesh())
    cx, cy = _centroid(wavy - flat, x, y)
    assert abs(cx - X0) < GRID.dx / 4 and abs(cy - Y0) < GRID.dx / 4, (cx, cy)


def test_textures_keep_the_texel_and_say_which_way_is_up(crater, tmp_path):
    from PIL import Image

    scene = Scene(np.full((64, 64), -1.5), crater, 8.0)
    export_scene(scene, tmp_path)
    decoded = load_npz(tmp_path / "textures.npz")["water"]
    assert np.unravel_index(np.argmin(decoded), decoded.shape) == (ROW, COL)
    png = np.asarray(Image.open(tmp_path / "water_height.png"))  # row 0 at the top: y up in viewers
    assert np.unravel_index(np.argmin(png), png.shape) == (63 - ROW, COL)


def test_rendered_frame_shows_the_feature_where_it_is(crater):
    """Straight down from 3 m: the centroid of what the crater changes in the image, projected
    back to z = 0, is the feature's coordinate."""
    camera = look_at((X0, Y0, 3.0), (X0, Y0, -1.5), 30.0)
    ground = np.full((64, 64), -1.5)
    width = height = 160
    light = dict(sun=(0.0, 0.0, 1.0), sun_glow=0.0, sky_zenith=(0.4, 0.5, 0.7), sky_horizon=(0.4, 0.5, 0.7))
    with Renderer(width, height) as renderer:  # an overhead sun and a uniform sky: nothing else breaks the symmetry
        flat = renderer.render(Scene(ground, 0.0, 8.0, camera, **light))
        wavy = renderer.render(Scene(ground, crater, 8.0, camera, **light))
    d = ray_directions(camera, width, height)
    t = -3.0 / d[..., 2]  # where each pixel's ray meets z = 0
    x, y = X0 + t * d[..., 0], Y0 + t * d[..., 1]
    cx, cy = _centroid(np.sum(wavy - flat, axis=-1), x, y)
    assert abs(cx - X0) < GRID.dx / 4 and abs(cy - Y0) < GRID.dx / 4, (cx, cy)
