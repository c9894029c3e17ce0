"""Scale-out: the sharded step equals the one-device step, its memory falls as 1/devices, its
collectives move what the slab decomposition says, sweeps equal loops, and two processes
equal one. Several devices need XLA_FLAGS set before JAX starts, so those checks run in
fresh interpreters (tests/sharded_checks.py; examples/sharded_ocean.py for the processes)."""

import json
import os
import socket
import subprocess
import sys
import types
from pathlib import Path

import jax
import numpy as np
import pytest
from jax.sharding import Mesh

from wavephys import Grid, Water
from wavephys.parallel import exchanged_bytes, hosts_mesh, row_mesh, spectrum_width, sweep
from wavephys.parallel.fft import collective_bytes
from wavephys.simulation import Model, Simulation

ROOT = Path(__file__).resolve().parents[2]


def _env(devices=None):
    env = {k: v for k, v in os.environ.items() if not k.startswith(("WAVEPHYS_", "XLA_FLAGS"))}
    env["PYTHONPATH"] = str(ROOT) + os.pathsep + env.get("PYTHONPATH", "")
    if devices:
        env["XLA_FLAGS"] = f"--xla_force_host_platform_device_count={devices}"
    return env


def _sharded_checks(tmp_path_factory, what):
    env = _env()
    env["WAVEPHYS_EXAMPLE_OUT"] = str(tmp_path_factory.mktemp("sharded") / "one.npz")
    out = subprocess.run([sys.executable, str(ROOT / "tests" / "sharded_checks.py"), *what], env=env, cwd=ROOT,
                         capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    return json.loads(out.stdout.strip().splitlines()[-1])


@pytest.fixture(scope="module")
def checks(tmp_path_factory):
    """One fresh interpreter with 4 host devices runs the multi-device checks (JSON out), and
    examples/sharded_ocean.py as the one-process reference of the two-process test."""
    return _sharded_checks(tmp_path_factory, ["loop", "programs", "sweeps", "errors", "example"])


@pytest.fixture(scope="module")
def family_checks(tmp_path_factory):
    """The sharded step against the one-device step over the seeded family, in its own interpreter
    (the slow run's: about 30 s)."""
    return _sharded_checks(tmp_path_factory, ["family"])


@pytest.mark.slow
def test_sharded_step_equals_one_device_over_a_family(family_checks):
    """Random scenes (grid 64–128, 2 or 4 devices, deep and finite depth, σ on/off, cutoff
    on/off, second order on/off; wind sea, a stone every step, a moving pressure, ships):
    the state is the one-device state to ≤ 1e-6 (L2, float32) and ≤ 2e-15 (float64), and
    the sharded surface is as close to float64 as the one-device surface is (within 2×;
    η̇ amplifies float32 rounding at high k: both runs are ~1e-5 from float64 there)."""
    rows = family_checks["family"]
    assert len(rows) >= 3 and {r["devices"] for r in rows} == {2, 4} and any(r["ships"] for r in rows)
    assert {r["dtype"] for r in rows} == {"float32", "float64"}
    for r in rows:
        assert "rows" in r["sharding"], r
        assert r["time"] == 0.0, r
        if r["dtype"] == "float64":
            assert max(r["phi"], r["chi"]) < 2e-15 and max(r["eta"], r["eta_dot"]) < 1e-13, r
            continue
        assert r["l2_state"] <= 1e-6, r
        assert max(r["phi"], r["chi"]) <= 2e-6, r
        for field in ("eta", "eta_dot", "phi", "chi"):
            assert r["rounding_sharded"][field] <= 2.0 * r["rounding"][field] + 1e-7, (field, r)


@pytest.mark.slow
def test_sharded_run_loop_and_wrapper(checks):
    """Simulation(..., devices=4 host devices): drop, add_height, run (scan) and energy equal
    one device (the states to ≤ 1e-6)."""
    loop = checks["loop"]
    assert "rows" in loop["run_sharding"]
    assert loop["run_eta"] <= 1e-6 and loop["run_state"] <= 1e-6
    # energy is a float32 mean over 2·64² values, summed in another order across the shards
    assert loop["energy"] <= 1e-5


@pytest.mark.slow
def test_memory_per_device_falls_as_one_over_devices(checks):
    """The compiled step's arguments + outputs + temporaries per device (memory analysis),
    N = 128: within 20 % of (one device)/P, and halving from 2 to 4 devices."""
    rows = {r["devices"]: r for r in checks["programs"]}
    one = rows[1]["bytes_per_device"]
    for p in (2, 4):
        assert rows[p]["bytes_per_device"] <= 1.2 * one / p, (p, rows[p], one)
    assert rows[4]["bytes_per_device"] <= 0.55 * rows[2]["bytes_per_device"]


@pytest.mark.slow
def test_collectives_are_the_slab_transposes(checks):
    """Each step sends exactly what three slab transposes of two planes send (forward state,
    inverse state, inverse surface), and nothing else: no gather of the whole field."""
    for r in checks["programs"]:
        if r["devices"] == 1:
            assert r["sent"] == {}
        else:
            assert set(r["sent"]) == {"all-to-all"}, r
            assert r["sent"]["all-to-all"] == r["expected_sent"], r


@pytest.mark.slow
def test_sweeps_equal_the_loop(checks):
    """sweep() over 7 models of two grid sizes on 4 devices (one padded batch) and on 2
    devices × 2 per device equals [jax.jit(fn)(m) for m in models] to float32 rounding
    (within 2× the loop's own difference from float64; batched FFTs round differently),
    and the sweep is not flat (depths differ)."""
    s = checks["sweeps"]
    assert s["items"] == 7
    assert max(s["worst"], s["worst_two"]) <= max(2 * s["rounding"], 1e-7), s
    assert s["depth_spread"] > 1e-5


@pytest.mark.slow
def test_bad_inputs_needing_several_devices(checks):
    kind, message = checks["errors"]["indivisible"]
    assert kind == "ValueError" and "n = 66" in message and "divisible" in message
    kind, message = checks["errors"]["repeated"]
    assert kind == "ValueError" and "repeat" in message


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.slow
def test_two_processes_equal_one(tmp_path, checks):
    """examples/sharded_ocean.py as two processes on 127.0.0.1 (2 host devices each, one
    coordinator port) gives the surface and the depth sweep of one process with 4 devices
    (the fixture's interpreter ran it)."""
    import sharded_checks

    script = str(ROOT / "examples" / "sharded_ocean.py")
    args = sharded_checks.EXAMPLE_ARGS
    port = _free_port()
    procs = []
    for pid in range(2):
        env = _env(2)
        env.update(WAVEPHYS_COORDINATOR=f"127.0.0.1:{port}", WAVEPHYS_NUM_PROCESSES="2", WAVEPHYS_PROCESS_ID=str(pid))
        procs.append(subprocess.Popen([sys.executable, script, *args, "--out", str(tmp_path / f"two{pid}.npz")],
                                      env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True))
    outs = [p.communicate(timeout=300) for p in procs]
    for p, (stdout, stderr) in zip(procs, outs):
        assert p.returncode == 0, stderr[-3000:]
    assert "2 process(es), 4 devices" in outs[0][0]
    assert not (tmp_path / "two1.npz").exists()  # only process 0 writes
    a, b = np.load(checks["example"]), np.load(tmp_path / "two0.npz")
    assert np.abs(a["eta"]).max() > 1e-3
    assert np.abs(a["eta"] - b["eta"]).max() <= 1e-6 * np.abs(a["eta"]).max()
    assert np.allclose(a["rings"], b["rings"], rtol=1e-6, atol=0)
    assert np.all(np.diff(a["rings"]) != 0)  # every depth gives its own rings


# -- in this process (one device) -----------------------------------------------------------
def test_one_device_mesh_equals_no_mesh():
    """A mesh of one device runs the slab code path (padding, shard_map) and must equal the
    plain step exactly enough (float32) on a random surface."""
    grid = Grid(32, 2.0)
    rng = np.random.default_rng(3)
    eta = 0.002 * rng.standard_normal((32, 32))
    plain = Simulation(grid, Water(depth=0.4), dt=0.03, margin=6)
    meshed = Simulation(grid, Water(depth=0.4), dt=0.03, margin=6, devices=jax.devices()[:1])
    outs = []
    for sim in (plain, meshed):
        state = sim.add_height(sim.initial_state(), eta)
        state, surf = sim.step(sim.step(state)[0])
        outs.append(np.asarray(surf.fields))
    assert np.abs(outs[0] - outs[1]).max() <= 1e-6 * np.abs(outs[0]).max()


def test_sweep_in_one_process_equals_loop_and_keeps_order():
    """sweep() equals the loop of the same compiled function exactly (one device, batches of
    2, two structures interleaved), and the eager loop to float32 rounding: eager calls build
    the multipliers in float64 on the host, traced ones on the device in float32."""
    import jax.numpy as jnp

    from wavephys import Stones
    from wavephys.simulation import add_source, initial_state, run

    def fn(model):
        state = add_source(model, initial_state(model), Stones(0.0, 0.0, 0.2, 0.01))
        return jnp.max(jnp.abs(run(model, state, 5)[1].eta[-1]))

    models = [Model(Grid(16, 1.0), Water(depth=d), dt=0.02) for d in (0.03, 0.1, float("inf"))]
    models.insert(1, Model(Grid(8, 1.0), Water(), dt=0.02))  # another structure in between
    swept = np.array([float(s) for s in sweep(fn, models, per_device=2)])
    jitted = np.array([float(jax.jit(fn)(m)) for m in models])
    eager = np.array([float(fn(m)) for m in models])
    assert np.array_equal(swept, jitted)
    assert np.abs(swept / eager - 1).max() <= 1e-6
    assert len(set(np.round(swept, 6))) == 4  # depths and grids give different rings
    assert sweep(fn, []) == []


def test_slab_formula():
    assert spectrum_width(256, 4) == 132 and spectrum_width(256, 1) == 129 and spectrum_width(6, 4) == 4
    assert exchanged_bytes(256, 1, 2) == 0
    assert exchanged_bytes(256, 4, 2) == 2 * 64 * 132 * 8 * 3 // 4
    text = "%all-to-all = (c64[2,64,33]{2,1,0}, c64[2,64,33]{2,1,0}, c64[2,64,33]{2,1,0}, c64[2,64,33]{2,1,0}) all-to-all(%a, %b)"
    assert collective_bytes(text) == {"all-to-all": 3 * 2 * 64 * 33 * 8}
    text = "%all-gather.1 = f32[256,256]{1,0} all-gather(%p), replica_groups={{0,1}}"
    assert collective_bytes(text) == {"all-gather": 256 * 256 * 4}


def test_bad_meshes_and_hosts():
    cpu = jax.devices()[0]
    with pytest.raises(ValueError, match="no axis named 'rows'"):
        Model(Grid(32, 1.0), mesh=Mesh(np.array([cpu]), ("x",)))
    Model(Grid(32, 1.0), mesh=Mesh(np.array([cpu]), ("x",)), mesh_axis="x")  # named: fine
    with pytest.raises(ValueError, match="one kind"):
        row_mesh([cpu, types.SimpleNamespace(platform="gpu")])
    with pytest.raises(TypeError, match="devices\\[0\\] must be a jax.Device"):
        row_mesh(["cpu"])
    with pytest.raises(TypeError, match="devices must be a sequence"):
        row_mesh("cpu")
    with pytest.raises(ValueError, match="at least one device"):
        row_mesh([])
    with pytest.raises(TypeError, match="mesh must be"):
        Model(Grid(32, 1.0), mesh="rows")
    with pytest.raises(ValueError, match="devices or mesh, not both"):
        Simulation(Grid(32, 1.0), devices=[cpu], mesh=row_mesh([cpu]))
    with pytest.raises(RuntimeError, match="jax.distributed"):
        hosts_mesh()
    with pytest.raises(TypeError, match="fn must be"):
        sweep(3, [])
    with pytest.raises(TypeError, match="items must be"):
        sweep(lambda m: m, 5)
    with pytest.raises(ValueError, match="per_device"):
        sweep(lambda m: m, [], per_device=0)
    # one structure, two leaf shapes: two programs, results in order
    assert [float(v) for v in sweep(lambda a: a.sum(), [np.ones(3), np.ones(4), np.ones(3)])] == [3.0, 4.0, 3.0]
    with pytest.raises(TypeError, match="mesh_axis"):
        Simulation(Grid(32, 1.0), devices=[cpu], mesh_axis=3)


def test_initialize_names_bad_settings(monkeypatch):
    """Refused before connecting to anything (jax.distributed is never started here)."""
    from wavephys.parallel import initialize

    monkeypatch.setenv("WAVEPHYS_NUM_PROCESSES", "two")
    with pytest.raises(ValueError, match="WAVEPHYS_NUM_PROCESSES"):
        initialize("127.0.0.1:1")
    monkeypatch.delenv("WAVEPHYS_NUM_PROCESSES")
    monkeypatch.setenv("WAVEPHYS_COORDINATOR", "nowhere")
    with pytest.raises(ValueError, match="WAVEPHYS_COORDINATOR"):
        initialize()
    with pytest.raises(ValueError, match="process_id must be < num_processes"):
        initialize("127.0.0.1:1", 2, 5)
