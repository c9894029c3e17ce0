"""The spectral step in tanks with reflecting walls (docs/physics.md §1.11), against theory: energy,
seiche frequencies measured back, the image method for every kind of source, a packet's reflection."""

import math
from dataclasses import replace

import jax
import jax.numpy as jnp
import numpy as np
import pytest

from wavephys import Grid, Stones, Water
from wavephys.physics.disturbances import stone_height
from wavephys.physics.forcing import Forcing
from wavephys.physics.ship_waves import Hull, Ship, straight_path
from wavephys.physics.walls import image_points, seiche_frequencies
from wavephys.physics.wind import WindSea
from wavephys.simulation import Model
from wavephys.simulation.stepping import add_height, add_source, energy, initial_state, run, step, surface

pytestmark = pytest.mark.usefixtures("x64")


@pytest.fixture
def x64():
    with jax.enable_x64(True):
        yield


def _tank(n=64, length=2.0, depth=0.25, walls="all", **kw):
    return Model(Grid(n, length), Water(sigma=0.0, depth=depth), dt=0.01, walls=walls, dtype="float64", **kw)


@pytest.mark.parametrize("walls", ["all", pytest.param("x", marks=pytest.mark.slow),
                                   pytest.param("y", marks=pytest.mark.slow)])
def test_energy_is_conserved_to_rounding_without_a_margin(walls):
    model = _tank(walls=walls, depth=0.4)
    rng = np.random.default_rng(7)
    for seed in range(3):
        xy = rng.uniform(-0.95, 0.95, (2, 3))
        state = add_source(model, initial_state(model), Stones(xy[0], xy[1], [0.05] * 3, [0.01] * 3))
        state = add_source(model, state, WindSea(jax.random.PRNGKey(seed), "phillips", dict(wind_speed=2.0)))
        e0 = float(energy(model, state))
        later, _ = run(model, state, 400)
        assert abs(float(energy(model, later)) / e0 - 1) < 1e-11


def test_seiche_frequencies_measured_back_from_the_step():
    """A tank's mode cos(mπx'/L)cos(qπy'/L) oscillates at ω(k_mq): its projection over the run is fitted
    by a cosine and the fitted frequency compared with Lamb's formula (written out independently)."""
    rng = np.random.default_rng(11)
    for depth in (0.05, 0.5, math.inf):
        model = _tank(n=32, length=1.0, depth=depth)
        x = -0.5 + (np.arange(32) + 0.5) / 32
        for _ in range(3):
            m, q = rng.integers(0, 6, 2)
            if m == q == 0:
                m = 1
            mode = np.cos(q * np.pi * (x[:, None] + 0.5)) * np.cos(m * np.pi * (x[None, :] + 0.5))
            state = add_height(model, initial_state(model), 0.001 * mode)
            _, surf = run(model, state, 256)
            a = np.tensordot(np.asarray(surf.eta), mode, axes=((1, 2), (0, 1))) / np.sum(mode * mode) / 0.001
            k = np.pi * math.hypot(m, q)
            want = math.sqrt(9.81 * k * math.tanh(k * depth))
            t = np.arange(256) * 0.01
            trial = np.linspace(0.9 * want, 1.1 * want, 4001)
            misfit = [np.sum((a - np.cos(w * t)) ** 2) for w in trial]
            measured = trial[int(np.argmin(misfit))]
            assert measured == pytest.approx(want, rel=1e-4), (m, q, depth)
            assert want == pytest.approx(seiche_frequencies(1.0, 1.0, model.water, 6)[q, m], rel=1e-9)


def _open_reference(model, factor=4):
    """A periodic model ``factor`` times larger with the same spacing: open water for the time the
    test runs (no wave crosses its border)."""
    g = model.grid
    return replace(model, grid=Grid(g.n * factor, g.length * factor), walls=())


def _inner(big_field, n, factor=4):
    lo = (factor * n - n) // 2
    return np.asarray(big_field)[..., lo:lo + n, lo:lo + n]


@pytest.mark.parametrize("second_order", [False, pytest.param(True, marks=pytest.mark.slow)])
def test_a_stone_near_a_wall_and_in_a_corner_is_open_water_plus_its_images(second_order):
    """Image method: inside the tank, the walled field equals the open-water field of the stone and its
    mirror images in the walls (one reflection each, corners' double images; a 4L periodic domain as open
    water), until waves reflected twice arrive (≥ 2L away: after 30 steps of 0.01 s they have gone ≤ 0.5 m). Stones drawn near a wall and in a corner; second-order heights too (products of even
    fields are even)."""
    model = _tank(n=64, length=2.0, depth=0.25, second_order=second_order)
    big = _open_reference(model)
    rng = np.random.default_rng(5 + second_order)
    cases = [(rng.uniform(0.55, 0.85), rng.uniform(-0.5, 0.5)),  # near the right wall
             (rng.uniform(0.55, 0.85), rng.uniform(0.55, 0.85)),  # in the top-right corner
             (rng.uniform(-0.85, -0.55), rng.uniform(-0.85, -0.55))]  # the bottom-left corner
    for x0, y0 in cases:
        radius = rng.uniform(0.04, 0.08)
        xs, ys, _ = image_points(x0, y0, 2.0, "all")  # one reflection in each wall, and the corners' double ones
        walled = add_source(model, initial_state(model), Stones(x0, y0, radius, 0.01))
        # the walled model puts the sampled crater on its modes; open water gets the same samples
        crater = stone_height(Stones(xs, ys, [radius] * len(xs), [0.01] * len(xs)), big.grid)
        opened = add_height(big, initial_state(big), crater)
        steps = 30
        a, _ = run(model, walled, steps)
        b, _ = run(big, opened, steps)
        want = _inner(surface(big, b).eta, 64)
        got = np.asarray(surface(model, a).eta)
        scale = np.abs(want).max()
        assert np.abs(got - want).max() <= 1e-5 * scale, (x0, y0)
        assert np.sqrt(np.mean((got - want) ** 2)) <= 1e-6 * scale


def test_a_pressure_forcing_near_a_wall_is_open_water_plus_its_mirror_image():
    model = _tank(n=64, length=2.0, depth=0.25)
    big = _open_reference(model)
    x0, y0 = 0.6, -0.2  # the pressure acts on the tank's water only: its tail at the wall is below 1e-7

    def pressure(x, y, t):
        return 30.0 * jnp.exp(-((x - x0) ** 2 + (y - y0) ** 2) / 0.01) * jnp.sin(8.0 * t)

    a, _ = run(model, initial_state(model), 40, [Forcing(pressure, substeps=2)])
    xs, ys, _ = image_points(x0, y0, 2.0, "all")

    def images(x, y, t):
        return sum(30.0 * jnp.exp(-((x - px) ** 2 + (y - py) ** 2) / 0.01) * jnp.sin(8.0 * t) for px, py in zip(xs, ys))

    both = Forcing(images, substeps=2)
    b, _ = run(big, initial_state(big), 40, [both])
    want = _inner(surface(big, b).eta, 64)
    got = np.asarray(surface(model, a).eta)
    assert np.abs(got - want).max() <= 1e-5 * np.abs(want).max()  # the tail beyond the wall: measured 1.3e-6


def test_a_ship_near_the_walls_is_the_doubled_periodic_tank_with_its_three_mirror_ships():
    """A ship 3 samples from the top wall, sailing towards a corner: its patch crosses the walls and is
    folded back in, mirrored. The tank must equal, for all time, the periodic tank of twice the side
    holding the ship and its mirror images in x, in y and in both (the image method exactly; the mirror
    ships' patches cover the mirrored samples and truncate the same waves). Ship waves reach everywhere
    at once through the potential's non-local operator, so no open-water window would do here."""
    n, length = 64, 2.0
    model = replace(_tank(n=n, length=length, depth=0.25), ship_patch=16)
    twin = Model(Grid(2 * n, 2 * length), model.water, dt=model.dt, dtype="float64", ship_patch=16)
    # blurred: an even patch's Nyquist mode has no mirror image (4e-4 of the waves unblurred, measured)
    hull = Hull("gaussian", 0.12, 0.05, blur=0.06)
    start, velocity = np.array([0.5, 1.0 - 3 * length / n]), np.array([0.3, 0.05])
    ship = Ship(hull, straight_path(start, velocity))
    shift = start - 1.0  # the tank is the twin's lower-left quarter [−2, 0]²
    images = [Ship(hull, straight_path(shift * m, velocity * m)) for m in
              (np.array([1, 1]), np.array([-1, 1]), np.array([1, -1]), np.array([-1, -1]))]
    a, b = initial_state(model), initial_state(twin)
    for _ in range(25):
        a, _ = step(model, a, [ship])
        b, _ = step(twin, b, images)
    want = np.asarray(surface(twin, b).eta)[:n, :n]
    got = np.asarray(surface(model, a).eta)
    assert np.abs(want).max() > 0
    assert np.abs(got - want).max() <= 1e-9 * np.abs(want).max()


@pytest.mark.slow
def test_a_packet_reflects_with_coefficient_one_and_the_right_phase():
    """A packet travelling towards the right wall: after it has reflected, the walled field less the
    open-water packet is fitted by the mirror-image packet and its quadrature (ψ turned by 90°): the
    reflection coefficient R = |a + ib| is 1 and the phase atan2(b, a) is 0 (no flux: ∂φ/∂n = 0)."""
    n, length = 128, 4.0
    for depth, k0 in ((0.3, 14.0), (2.0, 20.0)):
        model = Model(Grid(n, length), Water(sigma=0.0, depth=depth), dt=0.01, walls="x", dtype="float64")
        big = _open_reference(model)
        def packet(m, x0, direction):
            x, y = m.grid.mesh()
            env = np.exp(-((np.asarray(x) - x0) ** 2) / (2 * 0.35 ** 2))  # k₀σ ≥ 4.9: one-sided to 1e-5
            eta = 0.002 * env * np.cos(k0 * (np.asarray(x) - x0))  # crest at the centre: mirrors into itself
            # a travelling packet: ψ from η with the right direction (η̇ from the one-way operator)
            from wavephys.simulation.stepping import state_from_psi
            spec = np.fft.fft2(eta)
            ky, kx = np.meshgrid(np.fft.fftfreq(m.grid.n, float(m.grid.dx)) * 2 * np.pi,
                                 np.fft.fftfreq(m.grid.n, float(m.grid.dx)) * 2 * np.pi, indexing="ij")
            spec = np.where(direction * kx > 0, 2 * spec, 0)  # one direction only: analytic signal in x
            k = np.hypot(kx, ky)
            w = np.sqrt(9.81 * k * np.tanh(k * depth))
            ratio = np.where(k > 0, w / np.where(k > 0, k * np.tanh(k * depth), 1), 0)
            psi = np.fft.ifft2(-1j * ratio * spec)  # ψ̂ = −i(ω/K)ĥ, as WindSea
            return state_from_psi(m, psi)
        x0 = 0.2
        speed = 0.5 * math.sqrt(9.81 / k0)  # group speed (kh ≥ 4: deep water)
        steps = int(round((length / 2 - x0 + 0.8) / speed / 0.01))  # to the wall, and 0.8 m back
        walled, _ = run(model, packet(model, x0, +1), steps)
        incident, _ = run(big, packet(big, x0, +1), steps)
        image, _ = run(big, packet(big, length - x0, -1), steps)
        quad = type(image)(jnp.stack([-image.fields[1], image.fields[0]]), image.time, image.time_error)  # iψ
        got = np.asarray(surface(model, walled).eta) - _inner(surface(big, incident).eta, n)
        basis = [_inner(surface(big, s).eta, n).ravel() for s in (image, quad)]
        (a, b), *_ = np.linalg.lstsq(np.stack(basis, 1), got.ravel(), rcond=None)
        assert math.hypot(a, b) == pytest.approx(1.0, abs=1e-5), depth  # the one-sided packet is one-sided to 1e-5
        assert abs(math.atan2(b, a)) < 1e-5, depth
        assert np.abs(basis[0]).max() > 0.2 * 0.002  # the reflected packet is inside the tank


def test_a_wall_side_opened_by_the_margin_absorbs_and_the_walls_reflect():
    """walls='bottom' with a margin: the top, left and right are open. A ring from a stone keeps more of
    its energy than in fully open water (the bottom wall reflects) and less than in the closed tank."""
    kw = dict(n=64, length=2.0, depth=0.25)
    tank = _tank(walls="all", **kw)
    half = _tank(walls="bottom", margin=8, **kw)
    opened = Model(tank.grid, tank.water, dt=0.01, margin=8, dtype="float64")
    left = {}
    for name, model in (("tank", tank), ("half", half), ("open", opened)):
        s = add_source(model, initial_state(model), Stones(0.0, -0.5, 0.06, 0.01))
        e0 = float(energy(model, s))
        later, _ = run(model, s, 300)
        left[name] = float(energy(model, later)) / e0
    assert left["open"] < left["half"] < left["tank"]
    assert left["tank"] == pytest.approx(1.0, abs=1e-10)


def test_the_walled_step_under_jit_vmap_and_grad():
    model = _tank(n=32, length=1.0, depth=0.2)
    state = add_source(model, initial_state(model), Stones(0.4, 0.3, 0.05, 0.01))

    def height(depth):
        m = replace(model, water=Water(sigma=0.0, depth=depth))
        return step(m, state)[1].eta[20, 25]

    grad = float(jax.grad(height)(0.2))
    eps = 1e-5
    assert grad == pytest.approx((float(height(0.2 + eps)) - float(height(0.2 - eps))) / (2 * eps), rel=1e-5)
    batch = jax.vmap(height)(jnp.array([0.1, 0.2, 0.3]))
    assert float(batch[1]) == pytest.approx(float(height(0.2)), rel=1e-12)


@pytest.mark.slow
def test_float32_walled_step_drifts_no_more_than_the_periodic_step():
    """float32 rounding moves the energy a little every step; the cosine transform must not add to it.
    Mean drift over four stone fields after 1000 steps (measured 1.4–5.7e-4 periodic, 1.8e-4 walled)."""
    drift = {"all": [], (): []}
    rng = np.random.default_rng(2)
    with jax.enable_x64(False):
        for _ in range(4):
            xy = rng.uniform(-0.8, 0.8, (2, 2))
            for walls in drift:
                model = Model(Grid(64, 2.0), Water(sigma=0.0, depth=0.25), dt=0.01, walls=walls)
                s = add_source(model, initial_state(model), Stones(xy[0], xy[1], [0.05, 0.05], [0.01, 0.01]))
                e0 = float(energy(model, s))
                later, surf = run(model, s, 1000)
                assert surf.eta.dtype == jnp.float32
                drift[walls].append(abs(float(energy(model, later)) / e0 - 1))
    assert np.mean(drift["all"]) <= 1.5 * np.mean(drift[()]), drift
    assert max(drift["all"]) < 1e-3


def test_bad_walls_are_refused_by_name():
    grid, water = Grid(32, 1.0), Water()
    with pytest.raises(ValueError, match="unknown side"):
        Model(grid, water, walls=("left", "west"))
    with pytest.raises(ValueError, match="cannot be periodic opposite a wall"):
        Model(grid, water, walls="left")
    with pytest.raises(ValueError, match="use model.transform"):
        Model(grid, water, walls="all").rfft2(np.zeros((32, 32)))
    devices = jax.devices()
    from wavephys.parallel.layout import row_mesh

    with pytest.raises(ValueError, match="walls with a mesh"):
        Model(grid, water, walls="all", mesh=row_mesh(devices[:1]))
