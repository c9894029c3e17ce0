"""Run by tests/parallel/test_parallel.py in a fresh interpreter with 4 forced host devices (the flag
must be set before JAX starts): the sharded step against the one-device step over a seeded
family of scenes, the compiled programs' memory and collectives. Prints one JSON object."""

import json
import os
import sys

if __name__ == "__main__":  # (pytest's doctest collection imports this file: change nothing then)
    os.environ["XLA_FLAGS"] = os.environ.get("XLA_FLAGS", "") + " --xla_force_host_platform_device_count=4"

import jax  # noqa: E402
import jax.numpy as jnp  # noqa: E402
import numpy as np  # noqa: E402
from dataclasses import replace  # noqa: E402

from wavephys import Grid, Stones, Water  # noqa: E402
from wavephys.physics.forcing import Forcing  # noqa: E402
from wavephys.physics.ship_waves import Hull, Ship, straight_path  # noqa: E402
from wavephys.physics.wind import WindSea  # noqa: E402
from wavephys.parallel import collective_bytes, exchanged_bytes, row_mesh  # noqa: E402
from wavephys.simulation import Model, Simulation, add_source, energy, initial_state, run, step  # noqa: E402


def rel(a, b):
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)
    return float(np.abs(a - b).max() / max(np.abs(b).max(), 1e-300))


def scene(rng, case):
    """One random scene: grid, water, options, sources, device count."""
    devices = int(rng.choice([2, 4]))
    n = int(rng.choice([64, 96, 128]))
    length = float(rng.uniform(1.0, 8.0))
    depth = float("inf") if rng.random() < 0.4 else float(rng.uniform(0.05, 2.0))
    sigma = 0.0 if rng.random() < 0.3 else 0.0728
    margin = int(rng.choice([0, n // 8]))
    model = Model(Grid(n, length), Water(depth=depth, sigma=sigma), dt=float(rng.uniform(0.005, 0.05)),
                  margin=margin, second_order=bool(rng.random() < 0.5),
                  dtype="float64" if case == 2 else "float32")
    wind = WindSea(jax.random.PRNGKey(case), "phillips", (("wind_speed", float(rng.uniform(0.5, 3.0))),
                                                       ("direction", float(rng.uniform(0, 6.28)))))
    x, y = rng.uniform(-0.2, 0.2, 2) * length
    stones = Stones(float(x), float(y), 0.04 * length, 0.004 * length)
    px, py, vx = float(rng.uniform(-0.2, 0.2) * length), float(rng.uniform(-0.2, 0.2) * length), float(rng.uniform(0.1, 0.5))
    force = Forcing(lambda X, Y, t: 50.0 * jnp.exp(-((X - px - vx * t) ** 2 + (Y - py) ** 2) / (0.03 * length) ** 2))
    ships = []
    if margin and case % 2 == 0:
        hull = Hull("gaussian", length=0.06 * length, width=0.02 * length, blur=2 * length / n)
        ships = [Ship(hull, straight_path((float(-0.05 * length), 0.0), (0.2, 0.0)), 0.01)]
        model = replace(model, ship_patch=n // 2, leak_tolerance=0.5)
    return model, devices, wind, stones, force, ships


def l2(a, b):
    a, b = np.asarray(a, np.float64), np.asarray(b, np.float64)
    return float(np.sqrt(np.sum((a - b) ** 2) / max(np.sum(b * b), 1e-300)))


def simulate(model, wind, stones, force, ships, steps=4, start=None):
    state = add_source(model, initial_state(model), wind) if start is None else start
    for i in range(steps):
        sources = [force, stones] + ships  # one program per model: a stone every step
        state, surf = step(model, state, sources)
    return state, surf


def family(cases=3, seed=20261201):
    rng = np.random.default_rng(seed)
    rows = []
    for case in range(cases):
        with jax.enable_x64(True):  # float64 where asked for (the reference runs, one case)
            rows.append(_family_case(rng, case))
    return rows


def _family_case(rng, case):
    if True:
        model, p, *sources = scene(rng, case)
        sharded = replace(model, mesh=row_mesh(jax.devices()[:p]))
        start = add_source(model, initial_state(model), sources[0])
        (s1, f1) = simulate(model, *sources, start=start)
        (sp, fp) = simulate(sharded, *sources, start=start)
        # the float rounding of this very computation: the one-device run against the same
        # run in float64 from the same start
        wide = replace(model, dtype="float64")
        s64, f64 = simulate(wide, *sources, start=type(start)(start.fields.astype(np.float64),
                                                                start.time.astype(np.float64)))
        rounding = {k: rel(getattr(f1, k), getattr(f64, k)) for k in ("eta", "eta_dot")}
        rounding.update({k: rel(getattr(s1, k), getattr(s64, k)) for k in ("phi", "chi")})
        rounding_sharded = {k: rel(getattr(fp, k), getattr(f64, k)) for k in ("eta", "eta_dot")}
        rounding_sharded.update({k: rel(getattr(sp, k), getattr(s64, k)) for k in ("phi", "chi")})
        return (dict(case=case, n=model.grid.n, devices=p, dtype=model.dtype, depth=float(model.water.depth),
                         second_order=model.second_order, margin=model.margin, ships=len(sources[3]),
                         sharding=str(sp.fields.sharding.spec),
                         phi=rel(sp.phi, s1.phi), chi=rel(sp.chi, s1.chi), eta=rel(fp.eta, f1.eta),
                         eta_dot=rel(fp.eta_dot, f1.eta_dot), time=float(sp.time) - float(s1.time),
                         l2_state=l2(sp.fields, s1.fields), l2_surface=l2(fp.fields, f1.fields),
                         rounding=rounding, rounding_sharded=rounding_sharded))


HEIGHT = 0.002 * np.sin(2 * np.pi * np.arange(64) / 16)[:, None] * np.cos(2 * np.pi * np.arange(64) / 32)[None, :]


def loop_and_wrapper():
    """run() and the Simulation(devices=...) wrapper against one device."""
    grid = Grid(64, 4.0)
    one = Simulation(grid, Water(), dt=0.02, margin=8)
    four = Simulation(grid, Water(), dt=0.02, margin=8, devices=jax.devices())
    out = {}
    for name, sim in (("one", one), ("four", four)):
        state = sim.drop(sim.initial_state(), Stones(0.2, -0.3, 0.16, 0.01))
        state = sim.add_height(state, HEIGHT)  # the sharded path transforms it with the slab FFTs
        state, surfs = sim.run(state, 6)
        out[name] = (state, surfs, float(sim.energy(state)))
    return dict(run_eta=rel(out["four"][1].eta, out["one"][1].eta), run_state=rel(out["four"][0].fields, out["one"][0].fields),
                energy=abs(out["four"][2] / out["one"][2] - 1.0),
                run_sharding=str(out["four"][1].eta.sharding.spec))


def programs(n=128):
    """Per-device memory of the compiled step for 1, 2 and 4 devices, and the bytes its
    collectives move against the slab formula."""
    rows = []
    for p in (1, 2, 4):
        model = Model(Grid(n, 4.0), Water(), dt=0.02, margin=n // 8,
                      mesh=None if p == 1 else row_mesh(jax.devices()[:p]))
        state = initial_state(model)
        from wavephys.simulation.model import operators
        from wavephys.simulation.stepping import _pure_step

        compiled = jax.jit(lambda m, o, s: _pure_step(m, o, s)).lower(model, operators(model), state).compile()
        mem = compiled.memory_analysis()
        total = mem.argument_size_in_bytes + mem.output_size_in_bytes + mem.temp_size_in_bytes
        sent = collective_bytes(compiled.as_text())
        expected = sum(exchanged_bytes(n, p, planes) for planes in (2, 2, 2))  # forward state; inverse state, surface
        rows.append(dict(devices=p, bytes_per_device=int(total), temp=int(mem.temp_size_in_bytes),
                         arguments=int(mem.argument_size_in_bytes), sent=sent, expected_sent=int(expected)))
    return rows


EXAMPLE_ARGS = ["--n", "64", "--steps", "5", "--sweep-n", "32"]


def ring_measure(model):
    """What a calibration sweep would ask of one model: a stone's rings after 8 steps."""
    state = add_source(model, initial_state(model), Stones(0.1, -0.2, 0.15, 0.01))
    final, surfaces = run(model, state, 8)
    return {"eta_max": jnp.max(jnp.abs(surfaces.eta), axis=(-2, -1)), "energy": energy(model, final)}


def sweeps():
    """sweep() over models of two structures (two grid sizes), 7 items on 4 devices (one
    padded batch), against the plain loop."""
    from wavephys.parallel import sweep

    items = []
    for n in (32, 48):
        for depth in (0.05, 0.3, 1.0, float("inf")):
            items.append(Model(Grid(n, 2.0), Water(depth=depth), dt=0.02, margin=n // 8))
    items = items[:7]
    loop = [jax.tree_util.tree_map(np.asarray, jax.jit(ring_measure)(m)) for m in items]
    with jax.enable_x64(True):  # the float32 rounding of this measure: the same models in float64
        wide = [jax.tree_util.tree_map(np.asarray, jax.jit(ring_measure)(replace(m, dtype="float64")))
                for m in items[:2]]
    rounding = max(rel(l[k], w[k]) for l, w in zip(loop, wide) for k in l)
    swept = sweep(ring_measure, items)
    swept2 = sweep(ring_measure, items, per_device=2, devices=jax.devices()[:2])
    worst = lambda other: max(rel(o[k], l[k]) for o, l in zip(other, loop) for k in l)
    return dict(items=len(items), worst=worst(swept), worst_two=worst(swept2), rounding=rounding,
                depth_spread=float(np.ptp([l["eta_max"][-1] for l in loop[:4]])))


def bad_inputs():
    """Named errors before any work, on inputs that need several devices."""
    from wavephys.parallel import row_mesh as mesh_of

    out = {}
    for name, make in (("indivisible", lambda: Model(Grid(66, 1.0), mesh=mesh_of(jax.devices()))),
                       ("repeated", lambda: mesh_of([jax.devices()[0]] * 2))):
        try:
            make()
            out[name] = None
        except Exception as exc:  # noqa: BLE001 - the test checks the kind and the message
            out[name] = [type(exc).__name__, str(exc)]
    return out


if __name__ == "__main__":
    what = sys.argv[1:] or ["family", "loop", "programs", "sweeps", "errors", "example"]
    result = {}
    checks = {"family": family, "loop": loop_and_wrapper, "programs": programs, "sweeps": sweeps,
              "errors": bad_inputs}
    for name in what:
        if name in checks:
            result[name] = checks[name]()
    if "example" in what:  # examples/sharded_ocean.py in this process: the two-process test's reference
        import runpy

        out = os.environ.get("WAVEPHYS_EXAMPLE_OUT", "sharded_ocean_one.npz")
        script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "examples", "sharded_ocean.py")
        runpy.run_path(script, run_name="sharded_ocean")["main"](EXAMPLE_ARGS + ["--out", out])
        result["example"] = out
    print(json.dumps(result))
