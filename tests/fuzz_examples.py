"""Valid values for the fuzz harness (``tests/fuzzing.py``): by parameter name, with overrides.

Every value is a factory (a fresh object per call). Sizes are small (16 × 16 grids) so a
valid call costs milliseconds. The sets below say what a parameter's name promises:
POSITIVE (> 0) and NON_NEGATIVE (≥ 0) parameters must refuse negative values, INF_OK ones
may be infinite (``depth=inf`` is deep water), NONE_OK ones accept None though their
default is not None, CHOICES are names chosen from a list.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path as FilePath

import jax
import jax.numpy as jnp
import numpy as np

from optics.rendering import Camera, Effects, Scene
from optics.rendering.textures import EncodedHeight
from wavephys import Grid, Stones, Water
from wavephys.harness import Check, DispersionSamples
from wavephys.physics.forcing import Forcing
from wavephys.physics.ship_waves import Hull, Path, Ship, straight_path
from wavephys.physics.wake import GaussianPressure, HullSource
from wavephys.physics.wind import WindSea
from wavephys.simulation import Model, Simulation, Surface, initial_state, operators
from wavephys.surfaces.gerstner import GerstnerWaves

N = 16
RNG = np.random.default_rng(7)
TMP = FilePath(tempfile.mkdtemp(prefix="wavephys-fuzz-"))


def _grid():
    return Grid(N, 2.0)


def _model():
    return Model(_grid(), Water(), dt=0.05, margin=2)


def _field(scale=1e-3):
    return (scale * RNG.standard_normal((N, N))).astype(np.float32)


def _scene():
    return Scene(np.full((N, N), -1.0), _field(), 4.0, Camera(eye=(0.0, -6.0, 4.0), target=(0.0, 0.0, -0.5)))


def _surface():
    return Surface(np.stack([_field(), _field()]), np.float32(0.0))


def _floor():
    from wavephys.simulation.depth import Floor

    return Floor(np.full((N, N), 0.5), levels=2)


def _depth_state():
    from wavephys.simulation.depth import depth_state

    return depth_state(_model(), _field(), _field())


def _ship():
    return Ship(Hull("gaussian", 0.3, 0.15), straight_path((0.0, 0.0), (0.4, 0.0)), 0.01)


EXAMPLES = {
    "elevation": lambda: 35.0, "sun_elevation": lambda: 35.0, "azimuth": lambda: 120.0,
    # core objects
    "grid": _grid, "patch": lambda: Grid(8, 1.0), "water": Water, "model": _model,
    "state": lambda: initial_state(_model()), "before": _surface, "after": _surface,
    "stones": lambda: Stones(0.1, -0.2, 0.25, 1e-3), "source": lambda: GaussianPressure(50.0, 0.25),
    "ship": _ship, "hull": lambda: Hull("gaussian", 0.3, 0.15), "path": lambda: straight_path((0.0, 0.0), (0.4, 0.0)),
    "scene": _scene, "camera": Camera, "effects": Effects,
    "samples": lambda: DispersionSamples(np.array([1.0, 2.0]), np.array([3.1, 4.4]), np.array([1.0, 1.0]), 0.1),
    "check": lambda: Check("x", 1.0, 1.0, 0.1), "tex": lambda: EncodedHeight(
        np.zeros((N, N), np.uint16), 16, 0.0, 1.0, 2.0),
    "key": lambda: jax.random.PRNGKey(0), "pressure": lambda: (lambda x, y, t: 10.0 * jnp.exp(-(x * x + y * y))),
    "pose": lambda: (lambda t: (0.0, 0.0, 0.0)),
    # numbers
    "dt": lambda: 0.05, "dx": lambda: 0.125, "spacing": lambda: 0.125, "length": lambda: 2.0, "n": lambda: N,
    "depth": lambda: 1.0, "radius": lambda: 0.25, "speed": lambda: 1.0, "half": lambda: 4, "t": lambda: 0.0,
    "s": lambda: 0.5, "x": lambda: 0.1, "y": lambda: -0.2, "factor": lambda: 2, "margin": lambda: 2,
    "size": lambda: 3, "steps": lambda: 3, "count": lambda: 2, "frames": lambda: 16, "ratio": lambda: 0.5,
    "steepness": lambda: 0.1, "omega_dt": lambda: 1.0, "courant": lambda: 0.5, "wind_speed": lambda: 5.0,
    "fetch": lambda: 1e4, "amplitude": lambda: 0.002, "wavenumber": lambda: 3.0, "near": lambda: 0.2,
    "far": lambda: 0.9, "epsilon": lambda: 1e-3, "n1": lambda: 1.000293, "n2": lambda: 1.333,
    "n_air": lambda: 1.000293, "n_water": lambda: 1.333, "n_ratio": lambda: 1.333, "bits": lambda: 16,
    "width": lambda: 16, "height": lambda: 12, "angle_deg": lambda: 30.0, "target_speed": lambda: np.array([0.5, 1.0]),
    "measured": lambda: 1.0, "expected": lambda: 1.0, "limit": lambda: 2.0, "quantity": lambda: "speed",
    "name": lambda: "pool", "xlabel": lambda: "x", "ylabel": lambda: "y", "mode": lambda: 0, "refine": lambda: 4,
    "shape": lambda: (N, N), "items": lambda: [Water(), Water(depth=2.0)],
    "theta0": lambda: 0.3, "depth0": lambda: 1.0, "slope": lambda: 0.1, "levels": lambda: np.array([0.5, 1.0, 2.0]),
    "walls": lambda: "all", "length_x": lambda: 2.0, "length_y": lambda: 1.5, "modes": lambda: 3,
    "periodic_images": lambda: False, "tank": lambda: False, "mirror": lambda: (False, False),
    # arrays
    "eta": _field, "eta_prev": _field, "eta0": _field, "eta1": _field, "eta_dot": _field, "eta_dot0": _field,
    "eta_dot1": _field, "field": _field, "values": lambda: np.ones(5), "u": lambda: np.linspace(0.0, 14.0, 5),
    "v": lambda: np.linspace(0.0, 14.0, 5), "psi": lambda: (_field() + 1j * _field()).astype(np.complex64),
    "k": lambda: np.linspace(0.1, 10.0, 8), "omega": lambda: np.linspace(0.1, 10.0, 8),
    "kx": lambda: np.linspace(-5.0, 5.0, 8)[None, :], "ky": lambda: np.linspace(-5.0, 5.0, 8)[:, None],
    "alpha": lambda: np.linspace(-1.0, 1.0, 9), "cos_theta": lambda: np.linspace(0.0, 1.0, 5),
    "n_dot_h": lambda: np.linspace(-1.0, 1.0, 5), "wavelength_nm": lambda: np.array([450.0, 550.0, 650.0]),
    "distance": lambda: np.array([0.5, 2.0]), "coefficient": lambda: np.array([0.3, 0.05, 0.001]),
    "coefficients": lambda: np.array([0.3, 0.05, 0.001]), "absorption": lambda: np.array([0.3, 0.05, 0.001]),
    "ground": lambda: np.ones(3), "diffuse": lambda: np.ones(3) * 0.2,
    "d": lambda: np.array([0.1, 0.2, -1.0]), "light": lambda: np.array([0.2, 0.0, 1.0]),
    "view": lambda: np.array([0.0, 0.3, 1.0]), "sun": lambda: np.array([0.3, -0.4, 0.866]),
    "eye": lambda: (0.0, -5.0, 3.0), "target": lambda: (0.0, 0.0, 0.0), "center": lambda: (0.0, 0.0),
    "start": lambda: (0.0, 0.0), "velocity": lambda: (0.5, 0.0), "image": lambda: RNG.random((N, N, 3)),
    "reference": lambda: RNG.random((N, N, 3)), "images": lambda: [RNG.random((8, 8, 3))],
    "stencil": lambda: np.array([[0.0, -1.0, 0.0], [-1.0, 4.0, -1.0], [0.0, -1.0, 0.0]]),
    "phi_hat": lambda: np.ones((4, 3), np.complex64), "chi_hat": lambda: np.ones((4, 3), np.complex64),
    "cos_wt": lambda: np.ones((4, 3)), "sin_wt": lambda: np.zeros((4, 3)),
    "q": _field, "lam_eta": _field, "lam_q": _field, "f0_hat": lambda: np.ones((8, 8), np.complex64),
    "f1_hat": lambda: np.ones((8, 8), np.complex64), "spectrum": lambda: np.ones((N, N)) * 1e-8,
    "curves": lambda: {"a": ([1.0, 2.0], [1.0, 0.5])},
    "rows": lambda: [dict(method="a", seconds=1e-3, error=0.1), dict(method="a", seconds=2e-3, error=0.05)],
    "wavevectors": lambda: np.array([[3.0, 0.0], [0.0, 6.0]]), "amplitudes": lambda: np.array([0.02, 0.01]),
    "phases": lambda: np.array([0.0, 1.0]), "control": lambda: RNG.standard_normal((8, 8)) * 0.01,
    "displacement": lambda: np.stack([_field(), _field()]), "heights": _field, "previous": lambda: np.zeros((N, N)),
    "coverage": lambda: np.full((N, N), 0.5), "jacobian": lambda: np.full((N, N), 0.5), "threshold": lambda: 0.3,
    "softness": lambda: 0.1, "decay_time": lambda: 2.0, "choppiness": lambda: 0.5, "order": lambda: 1,
    "sea": lambda: (_field() + 1j * _field()).astype(np.complex64), "hurst": lambda: 1.0, "octaves": lambda: 2,
    "frequency": lambda: 1.0, "floor": lambda: 1e-3, "z": lambda: 0.3, "tile": lambda: 2.0, "step": lambda: 0.01, "period": lambda: 4, "evolution": lambda: 1.0, "time_exponent": lambda: 1.0, 
    "devices": lambda: jax.devices()[:1], "mesh": lambda: None, "axis": lambda: "rows", "mesh_axis": lambda: "rows", "per_device": lambda: 1, "shards": lambda: 2,
    "planes": lambda: 2, "itemsize": lambda: 8, "compiled_text": lambda: "%a = f32[4]{0} all-reduce(%b)",
    "fields": lambda: np.zeros((2, N, N), np.float32), "time": lambda: np.float32(0.0), "angle": lambda: 19.5, "time_error": lambda: 0.0, "fn": lambda: (lambda x: x), "damping": lambda: 0.05,
    "froude": lambda: 1.0, "lateral": lambda: np.linspace(-0.5, 0.5, 5), "sections": lambda: 8,
    "direction": lambda: 0.0, "sigma": lambda: 0.0728,
}

def _plan_scene():
    from wavephys.planner import Scene, StoneSpec

    return Scene(1.0, 1.0 / 32, depth=0.5, open_water=False, duration=2 / 30, fps=30.0, height_range=0.01,
                 stones=(StoneSpec(0.1, -0.1, 0.1, 0.005),), name="fuzz")


def _scene_model():
    from wavephys.planner import SceneModel

    return SceneModel(_plan_scene())


def _plan():
    from wavephys.planner import plan

    return plan(_plan_scene(), 1e-3)


def _wind_model():
    from wavephys.planner import Choices, Scene, SceneModel, WindSpec

    scene = Scene(8.0, 0.25, open_water=False, duration=2 / 30, fps=30.0, wind=WindSpec(5.0), name="fuzz-sea")
    return SceneModel(scene, Choices(surface="noise", second_order=False))


def _plan_output():
    from wavephys.planner import run

    return run(_plan_scene(), _scene_model())


def _scene_toml():
    path = TMP / "scene.toml"
    path.write_text('extent = 1.0\npixel = 0.03125\ndepth = 0.5\nopen_water = false\nduration = 0.0667\n'
                    '[[stones]]\nx = 0.1\ny = -0.1\nradius = 0.1\ndepth = 0.005\n')
    return path


_PLANNER = {"scene": _plan_scene, "model": _scene_model}
_SCENE_FIELDS = {"extent": lambda: 1.0, "pixel": lambda: 1.0 / 32, "depth": lambda: 0.5, "duration": lambda: 2 / 30,
                 "fps": lambda: 30.0, "height_range": lambda: 0.01, "water": Water, "name": lambda: "fuzz",
                 "stones": lambda: _plan_scene().stones, "ships": lambda: (), "wind": lambda: None,
                 "open_water": lambda: False}


def _wake_field():
    return (1e-3 * np.random.default_rng(0).standard_normal((N, N))).astype(np.float32)


def _npz():
    from optics.rendering.textures import save_npz

    return save_npz(TMP / "valid.npz", a=np.ones(3))


def _exr():
    from optics.rendering.textures import save_exr

    return save_exr(TMP / "valid.exr", {"Y": np.ones((4, 4))})


def _dispersion_record():
    from wavephys import Simulation

    sim = Simulation(Grid(8, 8.0), Water(sigma=0.0), dt=0.4)
    _, surf = sim.run(sim.add_height(sim.initial_state(), RNG.standard_normal((8, 8)) * 1e-3), 64)
    return np.asarray(surf.eta)


def _frames():
    """A small travelling sea, 24 frames of 16² (dx 0.125 m, dt 0.05 s): a valid record for every check."""
    k1 = 2 * np.pi * np.fft.fftfreq(N, 0.125)
    kx, ky = np.meshgrid(k1, k1)
    k = np.hypot(kx, ky)
    spec = np.fft.fft2(np.random.default_rng(3).standard_normal((N, N))) * (kx > 0) * np.exp(-(k / 12.0) ** 2)
    w = np.sqrt(9.81 * k)
    return np.stack([1e-3 * np.fft.ifft2(spec * np.exp(-1j * w * i * 0.05)).real for i in range(24)])


def _record():
    from wavephys.harness import Record

    return Record(_frames(), 0.125, 0.05)


def _frames_folder():
    from optics.rendering.textures import export_height_frames

    out = TMP / "frames_valid"
    if not out.exists():
        export_height_frames(list(_frames()), 2.0, 0.05, out)
    return out


def _wake_frame():
    from wavephys.physics.wake import steady_wake

    return np.asarray(steady_wake(Grid(256, 16.0), Water(sigma=0.0), 1.0, GaussianPressure(100.0, 0.15), damping=0.1))


def _normal_map():
    h = _field(1e-2).astype(np.float64)
    sx = (np.roll(h, -1, 1) - np.roll(h, 1, 1)) / 0.25
    sy = (np.roll(h, -1, 0) - np.roll(h, 1, 0)) / 0.25
    n = np.stack([-sx, -sy, np.ones_like(sx)], -1)
    return h, n / np.linalg.norm(n, axis=-1, keepdims=True)


_RECORD = {"record": _record}
_HEIGHTS_AND_NORMALS = {}


def _heights_normals(part):
    def make():
        if "pair" not in _HEIGHTS_AND_NORMALS:
            _HEIGHTS_AND_NORMALS["pair"] = _normal_map()
        return _HEIGHTS_AND_NORMALS["pair"][part]
    return make


def _validation_json():
    import json

    path = TMP / "validation.json"
    path.write_text(json.dumps([dict(quantity="x", expected=1.0, measured=1.0, relation="~=", margin=0.5, ok=True)]))
    return path


def _bed():
    return np.linspace(-0.5, 0.6, N * N).reshape(N, N)  # a slope whose top rises out of the water


def _ritter_frames():
    from wavephys.physics.shallow_water import ritter

    x = (np.arange(128) + 0.5) * 0.1 - 3.2
    return np.stack([ritter(x, t, 1.0)[0] if t > 0 else np.where(x < 0, 1.0, 0.0) for t in np.arange(8) * 0.05])


def _sw_state():
    from wavephys.simulation.shallow_water import sw_state

    return sw_state(_bed(), 0.5)


def _pipes_state():
    from wavephys.models.pipes import pipes_state

    return pipes_state(_bed(), 0.5)


_CG = {"x": lambda: np.array([0.0, 1e4]), "t": lambda: 0.0, "h0": lambda: 500.0, "length": lambda: 5e4,
       "amplitude": lambda: 1.0, "period": lambda: 900.0}
_SOLITARY = {"h": lambda: 0.01, "d": lambda: 1.0, "cot_beta": lambda: 19.85}
_SW = {"solver": lambda: __import__("wavephys.simulation.shallow_water", fromlist=["x"]).ShallowWater(0.1),
       "bed": _bed, "state": _sw_state}
_SPLIT = {"split": lambda: __import__("wavephys.simulation.split", fromlist=["x"]).Split(
    __import__("wavephys.simulation.shallow_water", fromlist=["x"]).ShallowWater(0.1), levels=(0.5,)),
    "bed": _bed, "state": _sw_state}


def _coastal():
    from wavephys.planner.regime import CoastalScene

    return CoastalScene(depth=(0.0, 2.0), wave_height=0.1, wavelength=(4.0, 20.0), extent=64.0)


_PIPES = {"pipes": lambda: __import__("wavephys.models.pipes", fromlist=["x"]).Pipes(0.1), "bed": _bed,
          "state": _pipes_state}

_SPRAY = {"positions": lambda: np.zeros((4, 3)), "velocities": lambda: np.array([[1.0, 0.0, 2.0]] * 4),
          "radius": lambda: 1e-3, "dt": lambda: 0.01, "wind": lambda: np.array([3.0, 0.0, 0.0]),
          "law": lambda: "schiller_naumann", "air_density": lambda: 1.204, "air_viscosity": lambda: 1.81e-5,
          "water_density": lambda: 1000.0, "reynolds": lambda: np.array([0.5, 50.0, 5000.0]), "speed": lambda: 2.0}
OVERRIDES = {
    "wavephys.app.report.read_validation": {"path": _validation_json},
    "wavephys.core.frames.resolve_axes": {"shape": lambda: (24, 16, 16), "axes": lambda: "tyx"},
    # the harness's records and the checks on them
    "wavephys.harness.record.Record": {"eta": _frames, "dx": lambda: 0.125, "dt": lambda: 0.05},
    "wavephys.harness.record.time_derivative": {"eta": _frames, "dt": lambda: 0.05},
    "wavephys.harness.travel.measure_travel": {"eta": _frames, "dx": lambda: 0.125, "dt": lambda: 0.05},
    "wavephys.harness.energy.measure_damping": {**_RECORD, "water": lambda: Water(sigma=0.0)},
    "wavephys.harness.energy.energy_check": {**_RECORD, "water": lambda: Water(sigma=0.0)},
    "wavephys.simulation.model.Model.inverse_transform": {"spectra": lambda: np.zeros((N, N // 2 + 1), np.complex64)},
    "wavephys.physics.depth.mild_slope_transmission": {"omega": lambda: 2.0, "x": lambda: np.array([0.0, 5.0]),
                                                        "depth": lambda: np.array([1.0, 0.5])},
    "wavephys.physics.depth.shoaling_coefficient": {"omega": lambda: 2.0},
    **{f"wavephys.physics.spray.{name}": {k: v for k, v in _SPRAY.items() if k in __import__("inspect").signature(
        getattr(__import__("wavephys.physics.spray", fromlist=["x"]), name)).parameters} for name in (
        "drag_coefficient_schiller_naumann", "drag_coefficient_newton", "drag_rate", "terminal_speed", "euler_stable_dt",
        "drops_ballistic", "advance_drops_exponential", "advance_drops_euler", "advance_drops")},
    "wavephys.physics.depth.refraction_angle": {"omega": lambda: 2.0},
    "wavephys.physics.depth.lamb_beach": {"x": lambda: np.linspace(0.0, 5.0, 6), "omega": lambda: 2.0},
    "wavephys.physics.depth.depth_weights": {"depth": lambda: np.full((4, 4), 1.2)},
    "wavephys.physics.depth.depth_levels": {"depth": lambda: np.full((4, 4), 1.2)},
    "wavephys.simulation.depth.Floor": {"depth": lambda: np.full((N, N), 0.5), "levels": lambda: 2},
    "wavephys.simulation.depth.Floor.check": {"model": _model},
    "wavephys.simulation.depth.DepthState": {"fields": lambda: np.zeros((2, N, N), np.float32),
                                             "time": lambda: np.float32(0.0)},
    "wavephys.simulation.depth.depth_state": {"eta": _field, "phi": _field},
    "wavephys.simulation.depth.step_levels": {"floor": _floor, "state": _depth_state},
    "wavephys.simulation.depth.step_shallow": {"floor": _floor, "state": _depth_state},
    "wavephys.simulation.depth.run_depth": {"floor": _floor, "state": _depth_state, "steps": lambda: 2},
    "wavephys.simulation.depth.shallow_substeps": {"floor": _floor},
    "wavephys.simulation.depth.symmetric_work": {"floor": _floor},
    "wavephys.checks.depth.packet_potential": {"k": lambda: np.abs(2 * np.pi * np.fft.fftfreq(8, 0.1)),
                                              "analytic": lambda: 1e-3 * np.exp(2j * np.pi * np.arange(8) / 8),
                                              "omega": lambda: (lambda k: np.sqrt(9.81 * k))},
    "wavephys.simulation.depth.step_symmetric": {"floor": _floor, "state": _depth_state},
    "wavephys.simulation.depth.symmetric_levels": {"depth": lambda: np.array([[0.0, 0.5], [1.0, 2.0]]),
                                                   "count": lambda: 2},
    "wavephys.simulation.depth.run_profile": {"depth": lambda: np.linspace(0.5, 1.0, 16), "dx": lambda: 0.1,
                                              "dt": lambda: 0.05, "eta": lambda: 1e-3 * np.sin(np.arange(16.0)),
                                              "phi": lambda: np.zeros(16), "steps": lambda: 2},
    "wavephys.physics.shallow_water.water_depth": {"bed": _bed, "eta": lambda: 0.5},
    "wavephys.physics.shallow_water.ritter": {"x": lambda: np.linspace(-2.0, 2.0, 5), "t": lambda: 0.5,
                                              "h0": lambda: 1.0},
    "wavephys.physics.shallow_water.stoker": {"x": lambda: np.linspace(-2.0, 2.0, 5), "t": lambda: 0.5,
                                              "hl": lambda: 1.0, "hr": lambda: 0.1},
    "wavephys.physics.shallow_water.stoker_middle": {"hl": lambda: 1.0, "hr": lambda: 0.1},
    "wavephys.physics.shallow_water.thacker_period": {"h0": lambda: 0.1, "a": lambda: 1.0},
    "wavephys.physics.shallow_water.thacker": {"x": lambda: np.linspace(-1.0, 1.0, 5),
                                               "y": lambda: np.linspace(-1.0, 1.0, 5), "t": lambda: 0.3},
    "wavephys.physics.shallow_water.carrier_greenspan": _CG,
    "wavephys.physics.shallow_water.carrier_greenspan_runup": {k: v for k, v in _CG.items() if k not in ("x", "t")},
    "wavephys.physics.shallow_water.solitary_wave": {"x": lambda: np.linspace(0.0, 20.0, 5), "h": lambda: 0.01,
                                                     "d": lambda: 1.0, "x0": lambda: 10.0},
    "wavephys.physics.shallow_water.solitary_potential": {"x": lambda: np.linspace(0.0, 20.0, 5),
                                                          "h": lambda: 0.01, "d": lambda: 1.0, "x0": lambda: 10.0},
    "wavephys.physics.shallow_water.solitary_breaking_limit": {"cot_beta": lambda: 19.85},
    "wavephys.physics.shallow_water.solitary_runup": _SOLITARY,
    "wavephys.physics.shallow_water.solitary_runup_linear": {**_SOLITARY, "samples": lambda: 2048},
    "wavephys.physics.shallow_water.solitary_rundown_linear": {**_SOLITARY, "samples": lambda: 2048},
    "wavephys.harness.shallow_water.shoreline_elevation": {"depth": lambda: np.maximum(np.linspace(-0.5, 1.0, N), 0.0)[None],
                                                           "bed": lambda: np.linspace(0.5, -1.0, N)},
    "wavephys.simulation.shallow_water.ShallowWater": {"dx": lambda: 0.1, "sides": lambda: "wall"},
    "wavephys.simulation.shallow_water.Inflow": {"times": lambda: np.array([0.0, 1.0]),
                                                 "eta": lambda: np.array([0.0, 0.1]), "u": lambda: np.zeros(2)},
    "wavephys.simulation.shallow_water.Inflow.at": {"t": lambda: 0.5},
    "wavephys.simulation.shallow_water.Open": {"level": lambda: 0.0, "depth": lambda: np.ones(N)},
    "wavephys.simulation.shallow_water.ShallowWater.settle": {"bed": _bed, "state": _sw_state},
    "wavephys.harness.shallow_water.mass_check": {"depth": lambda: np.ones((3, N, N)), "dx": lambda: 0.1},
    "wavephys.harness.shallow_water.lake_at_rest_check": {"depth": lambda: np.stack([0.5 - _bed().clip(max=0.5)] * 3),
                                                          "bed": _bed, "dx": lambda: 0.1, "atol": lambda: 1e-3},
    "wavephys.harness.shallow_water.dam_break_check": {"depth": _ritter_frames, "dx": lambda: 0.1,
                                                       "dt": lambda: 0.05, "h0": lambda: 1.0, "dam": lambda: 3.2},
    "wavephys.simulation.shallow_water.SWState": {"fields": lambda: np.ones((3, N, N)), "time": lambda: 0.0},
    "wavephys.simulation.shallow_water.sw_state": {"bed": _bed, "eta": lambda: 0.5, "u": lambda: np.zeros((N, N)),
                                                   "v": lambda: np.zeros((N, N)), "time": lambda: 0.0},
    "wavephys.simulation.shallow_water.stable_dt": {"solver": _SW["solver"], "state": _sw_state},
    "wavephys.simulation.shallow_water.sw_step": {**_SW, "dt": lambda: 0.01},
    "wavephys.simulation.shallow_water.sw_run": {**_SW, "until": lambda: 0.05, "max_steps": lambda: 1000},
    "wavephys.simulation.shallow_water.sw_frames": {**_SW, "times": lambda: np.array([0.01, 0.02])},
    "wavephys.simulation.shallow_water.sw_mass": {"state": _sw_state, "dx": lambda: 0.1},
    "wavephys.simulation.shallow_water.sw_surface": {"state": _sw_state, "bed": _bed},
    "wavephys.simulation.shallow_water.advance_fields": {"solver": _SW["solver"], "bed": _bed,
                                                         "fields": lambda: np.asarray(_sw_state().fields),
                                                         "t": lambda: 0.0, "dt": lambda: 0.01},
    "wavephys.simulation.shallow_water.stable_dt_fields": {"solver": _SW["solver"],
                                                           "fields": lambda: np.asarray(_sw_state().fields)},
    "wavephys.simulation.shallow_water.check_run": {"solver": _SW["solver"],
                                                    "fields": lambda: np.asarray(_sw_state().fields), "t": lambda: 0.0},
    "wavephys.simulation.split.MovingPressure": {"start": lambda: (0.5, 0.5), "velocity": lambda: (1.0, 0.0),
                                                 "head": lambda: 0.05, "length": lambda: 0.3, "beam": lambda: 0.2},
    "wavephys.simulation.split.MovingPressure.head_at": {"x": lambda: np.linspace(0.0, 1.0, 4),
                                                         "y": lambda: np.linspace(0.0, 1.0, 4), "t": lambda: 0.1,
                                                         "period": lambda: (None, 2.0)},
    "wavephys.simulation.split.Split": {"solver": _SW["solver"], "levels": lambda: (0.5,), "bulk_length": lambda: 0.5,
                                        "taper": lambda: (0.1, 0.5)},
    "wavephys.simulation.split.split_step": {**_SPLIT, "dt": lambda: 0.01},
    "wavephys.simulation.split.split_run": {**_SPLIT, "until": lambda: 0.02, "max_steps": lambda: 100},  # a huge until: 100 steps
    "wavephys.simulation.split.split_frames": {**_SPLIT, "times": lambda: np.array([0.01, 0.02])},
    "wavephys.simulation.split.split_parts": _SPLIT,
    "wavephys.planner.regime.CoastalScene": {"depth": lambda: (0.0, 2.0), "wave_height": lambda: 0.1,
                                             "wavelength": lambda: (4.0, 20.0), "extent": lambda: 64.0},
    "wavephys.planner.regime.choose_regime": {"scene": _coastal, "tolerance": lambda: 0.02},
    "wavephys.planner.regime.linear_error": {"scene": _coastal},
    "wavephys.planner.regime.shallow_water_dispersion": {"scene": _coastal},
    "wavephys.planner.regime.measure_speed_error": {"regime": lambda: "split", "kh": lambda: 1.0, "cells": lambda: 8},
    "wavephys.models.pipes.Pipes": {"dx": lambda: 0.1, "area": lambda: 0.01, "sides": lambda: "wall"},
    "wavephys.models.pipes.PipesState": {"depth": lambda: np.full((N, N), 0.5), "flows": lambda: np.zeros((4, N, N)),
                                         "time": lambda: 0.0},
    "wavephys.models.pipes.pipes_state": {"bed": _bed, "eta": lambda: 0.5},
    "wavephys.models.pipes.pipes_step": {**_PIPES, "dt": lambda: 0.01},
    "wavephys.models.pipes.pipes_run": {**_PIPES, "dt": lambda: 0.01, "steps": lambda: 2},
    "wavephys.models.pipes.pipes_courant": {"pipes": lambda: __import__("wavephys.models.pipes", fromlist=["x"]).Pipes(
        0.1), "depth_max": lambda: 0.5, "dt": lambda: 0.01},
    "wavephys.harness.tank.measure_seiches": {"eta": _frames, "dx": lambda: 0.125, "dt": lambda: 0.05},
    "wavephys.harness.shoaling.shoaling_check": {**_RECORD, "water": lambda: Water(sigma=0.0),
                                                 "depth": lambda: np.linspace(1.0, 0.5, N)},
    "wavephys.harness.tank.seiche_check": {**_RECORD, "water": lambda: Water(sigma=0.0)},
    "wavephys.harness.tank.wall_reflection_check": {**_RECORD, "water": lambda: Water(sigma=0.0)},
    "wavephys.harness.tank.looks_like_tank": {**_RECORD, "water": lambda: Water(sigma=0.0)},
    "wavephys.harness.travel.standing_check": _RECORD,
    "wavephys.harness.travel.direction_check": {**_RECORD, "direction": lambda: 0.0},
    "wavephys.harness.packets.group_velocity_check": {**_RECORD, "water": lambda: Water(sigma=0.0)},
    "wavephys.harness.packets.ring_arrival_check": {**_RECORD, "water": lambda: Water(sigma=0.0)},
    "wavephys.harness.packets.minimum_group_speed": {"k_max": lambda: 100.0},
    "wavephys.harness.suite.check_record": {**_RECORD, "water": lambda: Water(sigma=0.0)},
    "wavephys.harness.maps.resolution_check": {"eta_a": _field, "dx_a": lambda: 0.125,
                                               "eta_b": lambda: (1e-3 * RNG.standard_normal((2 * N, 2 * N))),
                                               "dx_b": lambda: 0.0625},
    "wavephys.harness.maps.normals_check": {"heights": _heights_normals(0), "normals": _heights_normals(1),
                                            "dx": lambda: 0.125},
    "wavephys.harness.maps.caustics_flux_check": {"irradiance": lambda: 1.0 + 0.1 * _field(1.0)},
    "wavephys.harness.wake.wake_angle_darmon": {"eta": _wake_field, "radii": lambda: np.array([0.4, 0.8])},
    "wavephys.harness.wake.darmon_angle_theory": {"source": lambda: GaussianPressure(50.0, 0.05),
                                                  "radii": lambda: np.array([1.0, 2.0])},
    "wavephys.harness.wake.wake_angle_theory": {"source": lambda: GaussianPressure(50.0, 0.05), "method": lambda: "cusp"},
    "optics.light.attenuation.transmittance_table": {"method": lambda: "rgb", "size": lambda: 64},
    "wavephys.harness.wake.darmon_crests": {"source": lambda: GaussianPressure(50.0, 0.05),
                                            "radii": lambda: np.array([1.0, 2.0])},
    "wavephys.harness.steady.wake_check": {"eta": _wake_frame, "dx": lambda: 0.0625, "near": lambda: 2.0,
                                           "far": lambda: 7.0, "size": lambda: 0.15},
    "wavephys.physics.wake.wake_surface": {"x": lambda: np.array([-1.0, -2.0]), "y": lambda: np.array([0.1, 0.2]),
                                           "source": lambda: GaussianPressure(50.0, 0.05)},
    "wavephys.app.pytest_plugin.Checker.record": {"frames": _frames, "dx": lambda: 0.125, "dt": lambda: 0.05,
                                                  "only": lambda: ["tiling", "quantization"]},
    "wavephys.harness.record.Record.save": {"path": lambda: TMP / "record.npz"},
    "wavephys.app.pytest_plugin.Checker.wake_angle": {"eta": _wake_frame, "dx": lambda: 0.0625,
                                                      "near": lambda: 2.0, "far": lambda: 7.0, "size": lambda: 0.15},
    "wavephys.core.frames.read_exr": {"path": _exr},
    "wavephys.core.frames.read_map": {"path": _exr},
    "wavephys.core.frames.read_frames": {"source": _frames_folder},
    "optics.rendering.textures.export_height_frames": {"heights": lambda: list(_frames()[:8]), "length": lambda: 2.0,
                                                       "out_dir": lambda: TMP / "frames_out"},

    "wavephys.planner.scene.Scene": _SCENE_FIELDS,
    "wavephys.planner.scene.Scene.from_dict": {"data": lambda: _plan_scene().as_dict(), "name": lambda: "fuzz"},
    "wavephys.planner.scene.Scene.from_toml": {"path": _scene_toml},
    "wavephys.planner.scene.StoneSpec": {"x": lambda: 0.0, "y": lambda: 0.0, "radius": lambda: 0.1,
                                         "depth": lambda: 0.01},
    "wavephys.planner.scene.ShipSpec": {"x": lambda: 0.0, "y": lambda: 0.0, "speed": lambda: 1.0,
                                        "heading": lambda: 0.0, "length": lambda: 2.0, "width": lambda: 0.8,
                                        "strength": lambda: 0.02},
    "wavephys.planner.scene.ShipSpec.position": {"t": lambda: 1.0},
    "wavephys.planner.scene.FloorSpec": {"slope": lambda: 0.05, "direction": lambda: 30.0},
    "wavephys.planner.scene.FloorSpec.depth": {"depth": lambda: 1.0, "x": lambda: np.linspace(-1.0, 1.0, 5),
                                               "y": lambda: np.zeros(5)},
    "wavephys.planner.scene.WindSpec": {"speed": lambda: 5.0, "direction": lambda: 0.0, "amplitude": lambda: 1e-4,
                                        "seed": lambda: 0},
    "wavephys.planner.model.SceneModel": {"scene": _plan_scene, "choices": lambda: __import__(
        "wavephys.planner", fromlist=["Choices"]).Choices(), "dtype": lambda: "float32"},
    "wavephys.planner.model.Choices.get": {"name": lambda: "fresnel"},
    "wavephys.planner.model.Choices.set": {"name": lambda: "fresnel", "value": lambda: "schlick", "term": lambda: None},
    "wavephys.planner.plan.plan": {"scene": _plan_scene, "tolerance": lambda: 1e-3, "colour_tolerance": lambda: 0.01,
                                   "budget": lambda: 100.0, "texture_slack": lambda: 0.05},
    "wavephys.planner.plan.full_model": {"scene": _plan_scene}, "wavephys.planner.plan.candidates": {"scene": _plan_scene},
    "wavephys.planner.plan.plan_context": {"scene": _plan_scene}, "wavephys.planner.colour.colour_errors": {
        "scene": _plan_scene},
    "wavephys.planner.plan.colour_errors": {"scene": _plan_scene},
    "wavephys.planner.runner.run": _PLANNER,
    "wavephys.planner.runner.shade": {**_PLANNER, "heights": lambda: np.zeros((32, 32))},
    "wavephys.planner.runner.floor_light": {**_PLANNER, "heights": lambda: np.zeros((32, 32))},
    "wavephys.planner.runner.compare": {"output": _plan_output, "reference": _plan_output},
    "wavephys.planner.runner.surface_frames": {"model": _wind_model},
    "wavephys.planner.runner.encode_texture": {"heights": lambda: np.zeros((2, 32, 32), np.float32),
                                               "fmt": lambda: "u8", "grid": lambda: __import__(
                                                   "wavephys", fromlist=["Grid"]).Grid(32, 1.0)},
    "wavephys.planner.runner.decode_texture": {"stored": lambda: np.zeros((2, 32, 32), np.float32)},
    "wavephys.planner.plan.Plan.to_json": {"path": lambda: TMP / "plan.json"},
    # one table (a second); a full calibration takes minutes, and its input checks come first
    "wavephys.planner.measure.calibrate": {"out": lambda: TMP / "calibration.json", "only": lambda: "texture",
                                           "base": lambda: None, "progress": lambda: (lambda line: None)},
    "wavephys.planner.cost.load_calibration": {"path": lambda: __import__("pathlib").Path(__import__(
        "wavephys.planner.cost", fromlist=["x"]).__file__).with_name("data") / "calibration.json"},
    "wavephys.planner.charts.plot_plan": {"p": _plan, "measured": lambda: None},
    "wavephys.planner.generate.generate_scenes": {"count": lambda: 2, "seed": lambda: 0},
    "wavephys.planner.builtin.builtin_scene": {"name": lambda: "lake"},
    "wavephys.planner.builtin.builtin_path": {"name": lambda: "lake"},
    "wavephys.parallel.fft.rfft2": {"x": _field},
    "wavephys.parallel.fft.irfft2": {"spectrum": lambda: np.ones((N, N // 2 + 1), np.complex64)},
    "wavephys.parallel.hosts.gather": {"x": _field},
    "wavephys.simulation.driver.Simulation.add_wind": {"wind_speed": lambda: 5.0},
    "wavephys.physics.wind.wind_spectrum": {"wind_speed": lambda: 5.0},
    "wavephys.harness.checks.compare": {"rtol": lambda: 0.1},
    "wavephys.app.pytest_plugin.Checker.close": {"rtol": lambda: 0.1},
    "wavephys.physics.ship_waves.max_patch_dt": {"half": lambda: 8, "grid": lambda: Grid(64, 8.0)},
    "optics.checks.plain_numpy_water_srgb": {"distance": lambda: 1.0},
    "optics.checks.flat_pool_colour": {"scene": lambda: __import__("optics.checks").checks.flat_pool()},
    "optics.light.attenuation.transmittance": {"distance": lambda: np.array([0.5, 2.0])[:, None]},
    "optics.light.attenuation.underwater_radiance": {"distance": lambda: 2.0, "depth": lambda: 1.0},
    "optics.light.fresnel.approximation_errors": {"method": lambda: "schlick", "samples": lambda: 64},
    "optics.rendering.scene.Scene": {"ground": lambda: np.full((N, N), -1.0), "water": _field, "length": lambda: 4.0},
    "optics.rendering.renderer.save_png": {"path": lambda: TMP / "frame.png"},
    "optics.rendering.meshes.water_mesh": {"technique": lambda: "uniform"},
    "optics.rendering.meshes.mesh_errors": {"mesh": lambda: _water_mesh(), "renderer": lambda: instance(_renderer_class()),
                                            "width": lambda: 16, "height": lambda: 12, "repeats": lambda: 1,
                                            "bands": lambda: (0.0, 4.0, 1e9), "heights": lambda: True},
    "optics.rendering.meshes.mesh_seconds": {"mesh": lambda: _water_mesh(), "renderer": lambda: instance(_renderer_class()),
                                             "repeats": lambda: 1},
    "optics.rendering.meshes.render_mesh": {"mesh": lambda: _water_mesh(), "renderer": lambda: instance(_renderer_class())},
    "optics.rendering.meshes.mesh_coverage": {"mesh": lambda: _water_mesh(), "renderer": lambda: instance(_renderer_class())},
    "optics.rendering.meshes.mesh_heights": {"mesh": lambda: _water_mesh()},
    "optics.rendering.meshes.displaced_mesh": {"mesh": lambda: _water_mesh(),
                                               "displacement": lambda: np.zeros((2, N, N))},
    "optics.rendering.meshes.height_errors": {"mesh": lambda: _water_mesh(), "bands": lambda: (0.0, 4.0, 1e9),
                                              "aspect": lambda: 4 / 3},
    "optics.rendering.meshes.water_pixels": {"width": lambda: 16, "height": lambda: 12, "steps": lambda: 16,
                                             "refine": lambda: 2},
    "optics.rendering.meshes.WaterMesh": {
        "positions": lambda: np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]], np.float32),
        "parents": lambda: np.zeros((3, 4), np.float32), "morph": lambda: np.zeros(3, np.float32),
        "triangles": lambda: np.array([[0, 1, 2]], np.uint32), "technique": lambda: "uniform", "spacing": lambda: 1.0},
    "optics.rendering.textures.save_height_png": {"path": lambda: TMP / "height.png"},
    "optics.rendering.textures.save_npz": {"path": lambda: TMP / "textures.npz", "a": lambda: np.ones(3)},
    "optics.rendering.textures.load_npz": {"path": _npz},
    "optics.rendering.textures.save_exr": {"path": lambda: TMP / "t.exr", "channels": lambda: {"Y": np.ones((4, 4))}},
    "optics.rendering.textures.load_exr": {"path": _exr},
    "optics.rendering.textures.export_scene": {"out_dir": lambda: TMP / "export"},
    "optics.rendering.textures.save_vector_displacement": {"path": lambda: TMP / "d.exr",
                                                           "displacement": lambda: np.stack([_field()] * 3)},
    "wavephys.app.registry.run": {"names": lambda: ["dispersion-minima"]},
    "wavephys.physics.heights.second_order_breakdown": {"steepness": lambda: (0.26, 0.30)},
    "wavephys.app.scenes.default_scene": {"n": lambda: 128, "steps": lambda: 2},
    "wavephys.app.scenes.builtin_scene": {"n": lambda: 64, "caustics": lambda: False},
    "wavephys.app.scenes.scene_water": {"n": lambda: 64},
    "wavephys.app.scenes.scene_frames": {"n": lambda: 64},
    "wavephys.app.scenes.scene_grid": {"n": lambda: 64},
    "wavephys.app.scenes.scene_caustics": {"name": lambda: "calm", "water": lambda: np.zeros((64, 64), np.float32),
                                         "method": lambda: "beam"},
    "wavephys.harness.dispersion.measure_dispersion": {"eta": lambda: RNG.standard_normal((16, 8, 8))},
    "wavephys.app.pytest_plugin.Checker.dispersion": {
        "eta": _dispersion_record, "dx": lambda: 1.0, "dt": lambda: 0.4, "water": lambda: Water(sigma=0.0)},
    "wavephys.app.pytest_plugin.Checker.energy_conserved": {"eta": lambda: np.stack([np.ones((N, N))] * 2),
                                                                "eta_dot": lambda: np.stack([np.ones((N, N))] * 2)},
    "optics.light.directions.reflect": {"n": lambda: np.array([0.0, 0.0, 1.0])},
    "optics.shaders.check.check_glsl": {"source": lambda: _GLSL_FRESNEL, "function": lambda: "f",
                                        "against": lambda: "fresnel", "chart": lambda: TMP / "shader.png",
                                        "tolerance": lambda: 2e-4},
    "optics.shaders.check.describe_check": {"against": lambda: "fresnel"},
    "wavephys.app.pytest_plugin.Checker.glsl": {"source": lambda: _GLSL_FRESNEL, "function": lambda: "f",
                                                "against": lambda: "fresnel", "tolerance": lambda: 2e-4},
    "wavephys.app.pytest_plugin.Checker.hlsl": {"source": lambda: _HLSL_FRESNEL, "function": lambda: "F",
                                                "against": lambda: "fresnel"},
    "optics.light.fresnel.IndexRange": {"low": lambda: 1.33, "high": lambda: 1.35},
    "optics.light.fresnel.IndexRange.f0_contains": {"f0": lambda: 0.02},
    "wavephys.harness.claims.Claims.with_record": {"record": lambda: _record()},
    "wavephys.harness.claims.parse_number": {"text": lambda: "1/60"},
    "wavephys.harness.claims.Claims.get": {"name": lambda: "depth"},
    "wavephys.harness.claims.Claims.given": {"name": lambda: "sea"},
    "wavephys.harness.spectra.spacetime_spectrum": {"eta": _frames},
    "optics.light.directions.refract": {"n": lambda: np.array([0.0, 0.0, 1.0])},
    "optics.light.directions.refract_components": {"d": lambda: (0.1, 0.2, -1.0), "n": lambda: (0.0, 0.0, 1.0)},
    "optics.rendering.reference.effect_change": {"effect": lambda: "caustics", "width": lambda: 8, "height": lambda: 6},
    "optics.light.directions.normalize": {"v": lambda: np.array([1.0, 2.0, 2.0])},
    "wavephys.core.grid.Grid.deposit": {"x": lambda: np.zeros(5), "y": lambda: np.zeros(5)},
    "wavephys.core.grid.Grid.sample": {"x": lambda: np.zeros(5), "y": lambda: np.zeros(5)},
    # a fixed field: a third of random 16² fields have too few sections with a clear maximum,
    # so the valid call must not depend on the order in which the shared RNG was drawn
    "wavephys.harness.wake.wake_angle": {"near": lambda: 0.2, "far": lambda: 0.9, "eta": _wake_field},
    "wavephys.harness.wake.wake_angle_max": {"eta": _wake_field},
    "wavephys.harness.wake.wake_angle_cusp": {"eta": _wake_field},
    "wavephys.harness.wake.track_wavelength": {"eta": lambda: np.cos(np.arange(N) * 3.0)[None, :] * np.ones((N, 1))},
    "wavephys.physics.ship_waves.hull_spectrum": {"center": lambda: (0.0, 0.0), "pose": lambda: (0.0, 0.0, 0.0)},
    "wavephys.physics.ship_waves.Hull.evaluate": {"u": lambda: np.zeros(3), "v": lambda: np.zeros(3)},
    "wavephys.simulation.driver.Simulation.drop": {"stones": lambda: Stones(0.1, -0.2, 0.25, 1e-3)},
    "optics.rendering.reference.march": {"o": lambda: np.array([[0.0, -5.0, 3.0]]),
                                         "d": lambda: np.array([[0.0, 0.8, -0.6]])},
    "optics.rendering.reference.environment": {"d": lambda: np.array([[0.0, 0.0, 1.0]])},
    "optics.rendering.reference.shade_ground": {"p": lambda: np.array([[0.0, 0.0, -1.0]])},
    "optics.rendering.reference.sample": {"field": _field, "xy": lambda: np.zeros((3, 2))},
    "optics.rendering.scene.texture_sample": {"field": _field},
    # the reference refines until two levels agree: a loose tolerance keeps the valid call short
    "optics.caustics.reference.floor_irradiance_reference": {"tolerance": lambda: 0.05, "max_refine": lambda: 8},
    "optics.caustics.jacobian.floor_irradiance_jacobian": {"supersample": lambda: 2, "refine": lambda: 1},
    "optics.caustics.reference.converged_floor_irradiance": {"tolerance": lambda: 0.05, "max_refine": lambda: 8},
    "optics.caustics.common.bilateral_filter": {"image": _field},
    "optics.caustics.common.blur_121": {"image": _field},
    "optics.rendering.renderer.to_srgb8": {"image": lambda: RNG.random((4, 4, 3))},
    "optics.rendering.renderer.Renderer.texture": {"name": lambda: "extra", "array": _field},
    "wavephys.simulation.stepping.add_source": {"source": lambda: Stones(0.1, -0.2, 0.25, 1e-3)},
    "wavephys.physics.wake.steady_wake": {"speed": lambda: 1.0},
    "wavephys.physics.wake.froude_number": {"size": lambda: 0.05},
    "wavephys.physics.wake.wake_envelope": {"source": lambda: GaussianPressure(50.0, 0.05),
                                            "distance": lambda: np.array([1.0, 2.0])},
    "wavephys.harness.wake.max_amplitude_angle_theory": {"source": lambda: GaussianPressure(50.0, 0.023),
                                                         "near": lambda: 1.0, "far": lambda: 4.0,
                                                         "spacing": lambda: 0.02},
    "optics.rendering.textures.height_precision": {"eta": lambda: _field() + np.float32(0.01)},
    "wavephys.physics.wake.HullSource": {"hull": lambda: Hull("gaussian", 0.3, 0.15)},
    "optics.rendering.renderer.render_sequence": {"renderer": lambda: instance(_renderer_class()),
                                                  "scenes": lambda: [_scene()], "out_dir": lambda: TMP / "frames",
                                                  "progress": lambda: False},
    "optics.rendering.renderer.Renderer.frame_seconds": {"repeats": lambda: 1},
    "wavephys.models.finite_difference.fd_angular_frequency": {"kx": lambda: np.linspace(0.0, 1.0, 4),
                                                               "ky": lambda: np.zeros(4), "dx": lambda: 1.0},
    "wavephys.physics.wake.cusp_line": {"samples": lambda: 101},
    "wavephys.core.spectral.fourier_refine": {"field": _field},
    "wavephys.simulation.state.State": {}, "wavephys.simulation.state.Surface": {},
    "wavephys.surfaces.noise.NoiseSea": {"length": lambda: 2.0, "frequency": lambda: 1.0},
    "wavephys.surfaces.noise.NoiseSea.heights": {"grid": lambda: Grid(2 * N, 16.0)},
    "wavephys.surfaces.noise.NoiseSea.gradient": {"grid": lambda: Grid(2 * N, 16.0)},
    "wavephys.surfaces.noise.fbm": {"x": lambda: np.linspace(-1.0, 1.0, 5), "y": lambda: np.zeros(5)},
    "wavephys.surfaces.noise.noise_gradient": {"x": lambda: np.linspace(-1.0, 1.0, 5), "y": lambda: np.zeros(5)},
    "wavephys.surfaces.gerstner.GerstnerWaves.heights": {"grid": lambda: Grid(N, 2 * math.pi)},
    "wavephys.surfaces.gerstner.GerstnerWaves.fold_fraction": {"grid": lambda: Grid(N, 2 * math.pi)},
    **{f"wavephys.surfaces.choppy.{f}": {"height": _field} for f in (
        "displacement", "jacobian", "jacobian_std", "fold_choppiness", "foam_fraction_estimate")},
    "optics.rendering.textures.EncodedHeight": {"data": lambda: np.zeros((N, N), np.uint16), "offset": lambda: 0.0,
                                                "amplitude": lambda: 1.0},
}

_GLSL_FRESNEL = """float f(float c, float n1, float n2) {
    float s2 = (n1 / n2) * (n1 / n2) * (1.0 - c * c);
    if (s2 >= 1.0) return 1.0;
    float t = sqrt(1.0 - s2);
    float rs = (n1 * c - n2 * t) / (n1 * c + n2 * t), rp = (n1 * t - n2 * c) / (n1 * t + n2 * c);
    return 0.5 * (rs * rs + rp * rp);
}"""

_HLSL_FRESNEL = "float F(float cosTheta) { return 0.0204 + 0.9796 * pow(saturate(1 - cosTheta), 5); }"

SKIP = {
    # the shallow-water validation's own scenes (seconds per call), run by check_shallow_water and the tests
    "wavephys.checks.shallow_water.dam_break_errors", "wavephys.checks.shallow_water.thacker_errors",
    "wavephys.checks.shallow_water.lake_at_rest", "wavephys.checks.shallow_water.carrier_greenspan_errors",
    "wavephys.checks.shallow_water.solitary_runup_run", "wavephys.checks.shallow_water.pipes_seiche",
    "wavephys.checks.shallow_water.pipes_dam_break", "wavephys.checks.shallow_water.convergence_order",
    # the depth validation's own scenes (seconds per call), run by check_depth and tests/simulation/test_depth.py
    "wavephys.checks.depth.travelling_packet", "wavephys.checks.depth.measure_shoaling",
    "wavephys.checks.depth.lamb_beach_error", "wavephys.checks.depth.lamb_shoreline_errors",
    # the abstract stepper (its pieces are the subclasses'), and a run's result record
    "wavephys.core.stepper.Stepper", "wavephys.core.stepper.Run",
    # the steppers: their bad inputs are refused by name in tests/simulation/test_steppers.py (fuzzed, a step
    # count or a time drawn large runs up to 10⁶ compiled steps a call: 14 minutes for the set)
    *(f"{cls}{method}" for cls in ("wavephys.simulation.steppers.SpectralStepper",
                                   "wavephys.simulation.depth.DepthStepper",
                                   "wavephys.simulation.depth.ProfileStepper",
                                   "wavephys.simulation.shallow_water.ShallowWaterStepper",
                                   "wavephys.simulation.split.SplitStepper", "wavephys.models.pipes.PipesStepper",
                                   "wavephys.models.finite_difference.FiniteDifferenceStepper",
                                   "wavephys.models.truncated_kernel.KernelStepper")
      for method in ("", ".init", ".step", ".run", ".advance", ".advance_to", ".frames", ".trajectory")),
    "wavephys.simulation.depth.DepthStepper.surfaces",  # of a trajectory's states (tested in test_steppers)
    # a method of a floor made by the caller (its argument is checked by the steppers, tested in test_depth)
    "wavephys.simulation.depth.Floor.check",
    # the harness's fitted tank modes, made by measure_seiches (its fields are what was measured)
    "wavephys.harness.tank.Seiches",
    # the shader check's verdict, made by check_glsl (its fields are what was measured)
    "optics.shaders.check.ShaderReport",
    # the planner's answers and records, made by it (their fields are what it predicted)
    "wavephys.planner.plan.Term", "wavephys.planner.plan.Candidate", "wavephys.planner.plan.Infeasible",
    "wavephys.planner.terms.Term", "wavephys.planner.terms.Candidate",
    "wavephys.planner.plan.Plan", "wavephys.planner.regime.RegimeChoice",
    # the report runs every section (minutes); its options are checked by tests/app/test_report.py
    "wavephys.app.report.build_report",
    "wavephys.planner.runner.Output",
    # result records, made by the library and returned (their fields are what was measured)
    "wavephys.harness.wake.WakeAngle", "wavephys.physics.wake.CuspLine", "wavephys.harness.energy.Energy",
    "wavephys.harness.record.Rate", "wavephys.harness.energy.Damping", "wavephys.harness.travel.Travel",
    "wavephys.core.frames.Frames", "wavephys.harness.suite.RecordReport",
    # a registry entry (name, words, claims, runner): the library's own table, not user input
    "wavephys.harness.suite.RecordCheck",
    # a claim's declaration (name, kind, words, check): a check author's table entry, like RecordCheck
    "wavephys.harness.claims.Claim", "wavephys.harness.claims.Claim.given", "wavephys.harness.claims.Claim.validate",
    # register adds to the registry (a valid call would stay registered): tests/harness/test_claims.py
    "wavephys.harness.suite.register", "wavephys.harness.suite.unregister", "wavephys.harness.claims.add_claims",
    "wavephys.harness.dispersion.DispersionSamples", "wavephys.physics.stokes.StokesWave",
    "wavephys.simulation.model.Operators", "wavephys.simulation.sources.Source",
    # a matplotlib Figure: its methods are matplotlib's
    "wavephys.plot.WaveFigure",
    # the validation groups and the registry run whole scenes and take no data
    "wavephys.app.registry.check_builtin_scenes",
    # jax.distributed: a valid call connects to a coordinator (tested with two real processes
    # in tests/parallel/test_parallel.py), and hosts_mesh needs one
    "wavephys.parallel.hosts.initialize", "wavephys.parallel.hosts.hosts_mesh",
}
# the source protocol's hooks are called by the step with the model's own operators
for cls in ("wavephys.physics.disturbances.Stones", "wavephys.physics.wind.WindSea",
            "wavephys.physics.forcing.Forcing", "wavephys.physics.ship_waves.Ship"):
    SKIP |= {f"{cls}.impulse", f"{cls}.rate", f"{cls}.add"}

NONE_OK = {"axes", "wind", "colour_tolerance", "budget", "measured", "mesh", "devices", "resolution", "ship_patch", "damping", "camera", "progress", "limit", "environment", "albedo",
           "caustics", "count", "video", "speed", "columns", "mask", "iterations"}
CHOICES = {"method", "kind", "mode", "cutoff", "spectrum", "illuminant", "gamut", "norm", "normals", "relation",
           "name", "ship_method", "dtype", "walls", "law"}
POSITIVE = {"dt", "dx", "spacing", "length", "n", "radius", "half", "factor", "size", "steps", "count", "frames",
            "ratio", "steepness", "wind_speed", "fetch", "amplitude", "wavenumber", "near", "far", "epsilon", "n1",
            "n2", "n_air", "n_water", "n_ratio", "width", "height", "bits", "fps", "resolution", "samples",
            "oversample", "photons_per_texel", "exponent", "tolerance", "max_depth", "repeats", "refine_steps",
            "g", "rho", "sigma_space", "sigma_range", "bandwidth", "threshold", "lo", "hi", "growth", "strength_abs",
            "leak_tolerance", "max_distance", "ship_patch", "fov", "length_x", "length_y", "modes", "reynolds",
            "air_density", "air_viscosity", "water_density"}
NON_NEGATIVE = {"depth_m", "margin", "s", "omega_dt", "k", "omega", "distance", "coefficient", "coefficients",
                "absorption", "sigma", "blur", "exclude", "filter_radius", "seed", "cos_theta", "alpha_abs",
                "refine", "mode"}
SHAPED = {"eta", "eta_prev", "eta0", "eta1", "eta_dot", "eta_dot0", "eta_dot1", "field", "psi", "fields", "image",
          "reference", "sun", "d", "eye", "target", "center", "start", "velocity", "light", "view", "stencil",
          "spectrum", "q", "lam_eta", "lam_q", "phi_hat", "chi_hat", "f0_hat", "f1_hat", "xy", "o", "p", "data",
          "mask", "albedo", "environment", "caustics", "ground", "water", "images", "wavevectors", "amplitudes",
          "phases", "control", "displacement", "heights", "previous", "coverage", "sea", "positions", "velocities"}
# parameters whose shape variants are valid input: rectangular grids, RGBA images, single
# channels, batches of points, elementwise functions
SHAPE_FREE = {
    ("wavephys.simulation.shallow_water.stable_dt_fields", "fields"),  # any rectangle of cells, as SWState
    ("wavephys.simulation.shallow_water.check_run", "fields"),
    ("wavephys.simulation.shallow_water.SWState", "fields"),  # shallow water runs on any rectangle of cells
    ("wavephys.core.grid.Grid.sample", "field"), ("optics.light.directions.normalize", "v"),
    ("wavephys.harness.dispersion.measure_dispersion", "eta"),
    ("wavephys.harness.spectra.spacetime_spectrum", "eta"),  # any rectangle of frames, one row included
    ("wavephys.harness.tank.measure_seiches", "eta"),  # any rectangle of frames is a tank
    ("wavephys.harness.record.Record", "eta"),  # a strip of frames (n_y != n_x) is a record
    ("wavephys.app.pytest_plugin.Checker.dispersion", "eta"),
    ("wavephys.plot.plot_surface", "eta"), ("wavephys.plot.plot_wake", "eta"), ("wavephys.plot.plot_images", "images"),
    ("wavephys.models.finite_difference.laplacian", "eta"), ("wavephys.models.truncated_kernel.convolve_periodic", "eta"),
    ("optics.caustics.common.bilateral_filter", "image"), ("optics.caustics.common.blur_121", "image"),
    ("optics.light.attenuation.underwater_radiance", "ground"),
    ("optics.light.attenuation.underwater_radiance", "diffuse"),
    ("optics.rendering.textures.EncodedHeight", "data"),
    ("optics.rendering.scene.Scene", "ground"), ("optics.rendering.scene.Scene", "water"),
    ("optics.rendering.scene.texture_sample", "field"),
    ("optics.rendering.renderer.to_srgb8", "image"),
    # a record's frames may be rectangular (n_y != n_x), the same dx along both axes
    ("wavephys.harness.record.time_derivative", "eta"),
    ("wavephys.harness.travel.measure_travel", "eta"), ("wavephys.harness.maps.tiling_check", "field"),
    ("wavephys.harness.maps.quantization_check", "eta"),
}
RANGE_FREE = {("wavephys.physics.wake.GaussianPressure", "amplitude"),  # signed by nature
              ("wavephys.physics.shallow_water.carrier_greenspan", "amplitude"),  # a phase: either sign
              ("wavephys.physics.shallow_water.carrier_greenspan_runup", "amplitude"),
              ("wavephys.surfaces.choppy.foam", "threshold"),  # a Jacobian level: 0 (folds only) is valid
              ("wavephys.surfaces.choppy.foam_fraction_estimate", "threshold"),
              ("wavephys.surfaces.gerstner.GerstnerWaves", "steepness"),  # Q = 0: a plain sum of cosines
              ("wavephys.harness.checks.Check", "tolerance"),  # 0 for bound rows
              ("wavephys.harness.packets.ring_arrival_check", "radius"),  # 0: a point disturbance
              ("wavephys.harness.suite.check_record", "radius"),
              ("wavephys.harness.claims.Claims", "radius")}  # 0: a point disturbance
INF_OK = {"depth", "depth0", "limit", "expected", "measured"}
NAN_OK = {"measured"}
FREE_TEXT = {("wavephys.core.frames.read_map", "name"),  # the caller's argument name, for messages
             ("optics.rendering.renderer.Renderer.texture", "name"),  # any slot name is valid
             ("wavephys.planner.scene.Scene", "name"), ("wavephys.planner.scene.Scene.from_dict", "name")}
# results that hold NaN by design, for huge but valid inputs (documented in the function)
NAN_RESULT_OK = {"wavephys.models.finite_difference.fd_angular_frequency"}  # no real ω where unstable  # a Check row whose measurement gave NaN is a failed row, by design


def _water_mesh():
    from optics.rendering.meshes import uniform_mesh

    return uniform_mesh(_scene())


def _renderer_class():
    from optics.rendering import Renderer

    return Renderer


_INSTANCES = {}


def instance(cls):
    """A valid instance of a public class, to call its methods on (cached per class)."""
    from optics.rendering import Renderer
    from wavephys.harness import Record

    if cls not in _INSTANCES and cls in _STEPPER_MAKERS:
        _INSTANCES[cls] = _STEPPER_MAKERS[cls]()
    if cls not in _INSTANCES:
        makers = {Grid: _grid, Water: Water, Model: _model, Simulation: lambda: Simulation(_grid(), Water(), dt=0.05),
                  Stones: lambda: Stones(0.1, -0.2, 0.25, 1e-3), Hull: lambda: Hull("gaussian", 0.3, 0.15),
                  Path: lambda: straight_path((0.0, 0.0), (0.4, 0.0)), Ship: _ship, Scene: _scene, Effects: Effects,
                  Camera: Camera, Renderer: lambda: Renderer(16, 12), GaussianPressure: lambda: GaussianPressure(),
                  WindSea: lambda: WindSea(jax.random.PRNGKey(0), "phillips", dict(wind_speed=5.0)),
                  Forcing: lambda: Forcing(EXAMPLES["pressure"]()),
                  HullSource: lambda: HullSource(Hull("gaussian", 0.3, 0.15)),
                  DispersionSamples: EXAMPLES["samples"], Check: EXAMPLES["check"], Record: _record,
                  GerstnerWaves: lambda: GerstnerWaves(EXAMPLES["wavevectors"](), EXAMPLES["amplitudes"]())}
        from wavephys import planner as pl
        from wavephys.simulation.shallow_water import Inflow

        from wavephys.simulation.shallow_water import ShallowWater

        makers[Inflow] = lambda: Inflow(np.array([0.0, 1.0]), np.array([0.0, 0.1]))
        makers[ShallowWater] = lambda: ShallowWater(0.1, sides={"left": "open"})
        from wavephys.simulation.split import MovingPressure

        makers[MovingPressure] = lambda: MovingPressure((0.5, 0.5), (1.0, 0.0), 0.05, 0.3, 0.2)
        makers.update({pl.Scene: _plan_scene, pl.SceneModel: _scene_model, pl.Plan: _plan, pl.Choices: pl.Choices,
                       pl.ShipSpec: lambda: pl.ShipSpec(0.0, 0.0, 1.0), pl.StoneSpec: lambda: pl.StoneSpec(0, 0, 0.1, 0.01),
                       pl.WindSpec: lambda: pl.WindSpec(5.0), pl.FloorSpec: lambda: pl.FloorSpec(0.05, 30.0)})
        from optics.light.fresnel import IndexRange

        makers[IndexRange] = lambda: IndexRange(1.33, 1.35)
        from optics.rendering.meshes import WaterMesh, uniform_mesh

        makers[WaterMesh] = lambda: uniform_mesh(_scene())
        for base, make in makers.items():
            if issubclass(cls, base):
                _INSTANCES[cls] = make()
                break
        else:
            _INSTANCES[cls] = cls()
    return _INSTANCES[cls]


# -- the steppers (wavephys.steppers): one instance and one state each, and the calls of the interface --------
def _stepper_cases():
    """{class: (make the stepper, make a valid state)} on small grids."""
    from wavephys.core.stepper import TwoLevelState
    from wavephys.models.finite_difference import FiniteDifferenceStepper
    from wavephys.models.pipes import Pipes, PipesStepper, pipes_state
    from wavephys.models.truncated_kernel import KernelStepper
    from wavephys.simulation.depth import Floor, ProfileState, ProfileStepper, depth_state
    from wavephys.simulation.shallow_water import ShallowWater, ShallowWaterStepper
    from wavephys.simulation.split import Split, SplitStepper
    from wavephys.simulation.steppers import DepthStepper, SpectralStepper

    flat = -np.full((N, N), 0.5)
    return {
        SpectralStepper: (lambda: SpectralStepper(_model()), lambda: initial_state(_model())),
        DepthStepper: (lambda: DepthStepper(_model(), Floor(np.full((N, N), 0.5)), "shallow"),
                       lambda: depth_state(_model(), np.zeros((N, N)))),
        ProfileStepper: (lambda: ProfileStepper(np.full(N, 0.5), 0.1, Water(), 0.05),
                         lambda: ProfileState(np.zeros(N), np.zeros(N))),
        ShallowWaterStepper: (lambda: ShallowWaterStepper(ShallowWater(0.1), _bed()), _sw_state),
        SplitStepper: (lambda: SplitStepper(Split(ShallowWater(0.1), levels=(0.5,)), flat),
                       lambda: __import__("wavephys.simulation.shallow_water", fromlist=["x"]).sw_state(flat, 0.0)),
        PipesStepper: (lambda: PipesStepper(Pipes(0.1), flat, 0.005), lambda: pipes_state(flat, 0.0)),
        FiniteDifferenceStepper: (lambda: FiniteDifferenceStepper(0.5, 0.05),
                                  lambda: TwoLevelState(np.zeros((N, N)), np.zeros((N, N)))),
        KernelStepper: (lambda: KernelStepper(EXAMPLES["stencil"](), 0.05),
                        lambda: TwoLevelState(np.zeros((N, N)), np.zeros((N, N)))),
    }


def _register_steppers():
    from wavephys.models.pipes import Pipes
    from wavephys.simulation.depth import Floor
    from wavephys.simulation.shallow_water import ShallowWater
    from wavephys.simulation.split import Split

    for cls, (make, state) in _stepper_cases().items():
        name = f"{cls.__module__}.{cls.__qualname__}"
        _STEPPER_MAKERS[cls] = make
        OVERRIDES[f"{name}.init"] = {"state": state}
        OVERRIDES[f"{name}.step"] = {"state": state}
        OVERRIDES[f"{name}.run"] = {"state": state, "steps": lambda: 2}
        OVERRIDES[f"{name}.advance"] = {"state": state, "steps": lambda: 2}
        OVERRIDES[f"{name}.advance_to"] = {"state": state, "until": lambda: 0.05}
        OVERRIDES[f"{name}.frames"] = {"state": state, "times": lambda: np.array([0.05, 0.1])}
    mod = "wavephys.simulation"
    OVERRIDES.update({
        f"{mod}.steppers.SpectralStepper": {"model": _model},
        f"{mod}.depth.DepthStepper": {"model": _model, "floor": lambda: Floor(np.full((N, N), 0.5)),
                                         "method": lambda: "shallow"},
        f"{mod}.depth.ProfileStepper": {"depth": lambda: np.full(N, 0.5), "dx": lambda: 0.1, "dt": lambda: 0.05,
                                        "method": lambda: "shallow", "ends": lambda: "walls"},
        f"{mod}.depth.ProfileState": {"eta": lambda: np.zeros(N), "phi": lambda: np.zeros(N)},
        f"{mod}.shallow_water.ShallowWaterStepper": {"solver": lambda: ShallowWater(0.1), "bed": _bed},
        f"{mod}.split.SplitStepper": {"split": lambda: Split(ShallowWater(0.1), levels=(0.5,)),
                                      "bed": lambda: -np.full((N, N), 0.5)},
        "wavephys.models.pipes.PipesStepper": {"pipes": lambda: Pipes(0.1), "bed": lambda: -np.full((N, N), 0.5),
                                               "dt": lambda: 0.005},
        "wavephys.models.finite_difference.FiniteDifferenceStepper": {"courant": lambda: 0.5, "dt": lambda: 0.05},
        "wavephys.models.truncated_kernel.KernelStepper": {"dt": lambda: 0.05},
        "wavephys.core.stepper.TwoLevelState": {"eta": lambda: np.zeros((N, N)), "eta_prev": lambda: np.zeros((N, N))},
    })


_STEPPER_MAKERS = {}
_register_steppers()
