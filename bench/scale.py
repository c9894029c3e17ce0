"""``python -m bench scale``: the sharded step on forced host devices — its overhead against
the unsharded step doing the same total work, its memory per device from the compiled
programs (and the largest grid per device memory it implies), and the bytes its collectives
move, checked against the slab formula.

Forced host devices need ``XLA_FLAGS`` before JAX starts, so :func:`scale_rows` runs
``python -m bench.scale`` in a fresh interpreter. On this 2-core VM the 4 "devices" share
two cores: the ratio measures the sharded program's overhead (padding, transposes,
copies), not a speed-up.
"""

from __future__ import annotations

import json
import math
import os
import subprocess
import sys

DEVICES = 8
GIB = 1024**3


def scale_rows(quick: bool = False, progress=print) -> list[dict]:
    """Run the measurements in a fresh interpreter with ``DEVICES`` host devices."""
    env = dict(os.environ, XLA_FLAGS=f"--xla_force_host_platform_device_count={DEVICES}")
    progress(f"sharded step on {DEVICES} forced host devices (a fresh interpreter)")
    out = subprocess.run([sys.executable, "-m", "bench.scale", "--quick" if quick else "--full"], env=env,
                         capture_output=True, text=True, check=False)
    if out.returncode != 0:
        raise RuntimeError(f"bench.scale failed:\n{out.stderr[-4000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def _programs(n, p, mesh_devices):
    """Compile the step for an n × n grid on p devices from shapes alone (nothing allocated):
    (memory per device in bytes, collective bytes per device, the slab formula's bytes)."""
    import jax
    import jax.numpy as jnp

    from wavephys import Grid, Water
    from wavephys.parallel import collective_bytes, exchanged_bytes, row_mesh
    from wavephys.parallel.layout import field_sharding, spectrum_sharding
    from wavephys.simulation import Model, Operators, State
    from wavephys.simulation.stepping import _pure_step

    mesh = None if p == 1 else row_mesh(mesh_devices[:p])
    model = Model(Grid(n, 16.0), Water(), dt=1 / 30, margin=n // 8, mesh=mesh)
    width = model.spectrum_width
    spec = lambda shape, kind: jax.ShapeDtypeStruct(shape, jnp.float32, sharding=None if mesh is None else (
        field_sharding(mesh, "rows", len(shape)) if kind == "field" else spectrum_sharding(mesh, "rows", len(shape))))
    ops = Operators(*(spec((n, width), "spectrum") for _ in range(9)), spec((n, n), "field"))
    scalar = jax.ShapeDtypeStruct((), jnp.float32)
    state = State.__new__(State)
    for k, v in (("fields", spec((2, n, n), "field")), ("time", scalar), ("time_error", scalar)):
        object.__setattr__(state, k, v)
    compiled = jax.jit(lambda m, o, s: _pure_step(m, o, s)).lower(model, ops, state).compile()
    mem = compiled.memory_analysis()
    total = mem.argument_size_in_bytes + mem.output_size_in_bytes + mem.temp_size_in_bytes
    sent = collective_bytes(compiled.as_text())
    return int(total), sent, sum(exchanged_bytes(n, p, 2) for _ in range(3))


def _overhead(n, p, devices, repeats):
    """Sharded (p devices) against unsharded step time, interleaved in one loop."""
    import statistics

    import jax

    from bench.timing import interleaved, paired_ratio
    from wavephys import Grid, Simulation, Stones, Water

    sims = {"one device": Simulation(Grid(n, 16.0), Water(), dt=1 / 30, margin=n // 8),
            f"{p} devices": Simulation(Grid(n, 16.0), Water(), dt=1 / 30, margin=n // 8, devices=devices[:p])}
    states = {k: s.drop(s.initial_state(), Stones(0.0, 0.0, 0.2, 0.01)) for k, s in sims.items()}
    times = interleaved({k: (lambda k=k: sims[k].step(states[k])) for k in sims}, repeats=repeats)
    ratio, q1, q3 = paired_ratio(times, f"{p} devices", ["one device"])
    del jax
    return dict(family="sharded step overhead", n=n, devices=p, seconds=statistics.median(times[f"{p} devices"]),
                baseline_seconds=statistics.median(times["one device"]), ratio=ratio, ratio_quartiles=[q1, q3])


def _big_run(n, p, devices, steps=3):
    """An n × n run actually allocated: ``steps`` steps on one device and sharded over p,
    wall time per step (after one compiled step) and the largest difference of η."""
    import time

    import jax
    import numpy as np

    from wavephys import Grid, Simulation, Stones, Water

    out = {}
    for name, devs in (("one device", None), (f"{p} devices", devices[:p])):
        sim = Simulation(Grid(n, 256.0), Water(), dt=1 / 30, margin=n // 16, devices=devs)
        state = sim.drop(sim.initial_state(), Stones(10.0, -20.0, 2.0, 0.1))
        state, surf = sim.step(state)  # compile
        jax.block_until_ready(surf.fields)
        t = time.perf_counter()
        for _ in range(steps):
            state, surf = sim.step(state)
        jax.block_until_ready(surf.fields)
        out[name] = ((time.perf_counter() - t) / steps, np.asarray(surf.eta))
        del sim, state, surf
    (t1, e1), (tp, ep) = out["one device"], out[f"{p} devices"]
    return dict(family="big run", n=n, devices=p, seconds=tp, baseline_seconds=t1, ratio=tp / t1,
                max_difference=float(np.abs(ep - e1).max() / np.abs(e1).max()))


def huge_rows(n: int = 16384, p: int = 4, progress=print) -> list[dict]:
    """An n × n run on one device and on p forced host devices, each in its own interpreter
    (so that each process's peak memory is its own): setup, one step, peak RSS, and η."""
    import tempfile

    import numpy as np

    rows, etas = [], {}
    with tempfile.TemporaryDirectory() as tmp:
        for devices in (1, p):
            progress(f"{n}² on {devices} device(s)")
            env = dict(os.environ, XLA_FLAGS=f"--xla_force_host_platform_device_count={max(devices, 1)}")
            out = subprocess.run([sys.executable, "-m", "bench.scale", "--huge-one", str(n), str(devices), tmp],
                                 env=env, capture_output=True, text=True, check=False)
            if out.returncode != 0:
                raise RuntimeError(f"bench.scale --huge-one failed:\n{out.stderr[-4000:]}")
            rows.append(json.loads(out.stdout.strip().splitlines()[-1]))
            etas[devices] = np.load(os.path.join(tmp, f"eta{devices}.npy"))
    rows[-1]["max_difference_subsample"] = float(np.abs(etas[p] - etas[1]).max() / np.abs(etas[1]).max())
    return rows


def _huge_one(n: int, devices: int, folder: str) -> dict:
    import resource
    import time

    import jax
    import numpy as np

    from wavephys import Grid, Simulation, Stones, Water

    sim = Simulation(Grid(n, 256.0), Water(), dt=1 / 30, margin=n // 16,
                     devices=jax.devices()[:devices] if devices > 1 else None)
    t0 = time.perf_counter()
    state = sim.drop(sim.initial_state(), Stones(10.0, -20.0, 2.0, 0.1))
    state, surf = sim.step(state)
    jax.block_until_ready(surf.fields)
    t1 = time.perf_counter()
    state, surf = sim.step(state)
    jax.block_until_ready(surf.fields)
    t2 = time.perf_counter()
    np.save(os.path.join(folder, f"eta{devices}.npy"), np.asarray(surf.eta[:: n // 256, :: n // 256]))
    return dict(family="huge run", n=n, devices=devices, setup_seconds=t1 - t0, step_seconds=t2 - t1,
                peak_rss_bytes=resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024)


def _largest(bytes_per_point: float, memory: float, p: int) -> dict:
    """Largest n (and largest power of two, divisible by p) whose step fits ``memory`` per device."""
    n = int(math.sqrt(memory * p / bytes_per_point))
    n -= n % p
    return dict(n=n, power_of_two=2 ** int(math.log2(n)))


def main(quick: bool) -> list[dict]:
    import jax

    devices = jax.devices()
    rows = []
    sizes = (1024,) if quick else (1024, 2048, 4096, 16384)
    for n in sizes:
        for p in (1, 2, 4, 8):
            total, sent, expected = _programs(n, p, devices)
            rows.append(dict(family="sharded step memory", n=n, devices=p, bytes_per_device=total,
                             bytes_per_point=total * p / n**2, sent=sent, expected_sent=expected))
    for p in (1, 2, 4, 8):
        c = max(r["bytes_per_point"] for r in rows if r["devices"] == p)
        for name, memory in (("this VM, 24 GiB", 24 * GIB), ("80 GB GPU", 80e9)):
            rows.append(dict(family="largest grid", devices=p, memory=name, memory_bytes=memory,
                             bytes_per_point=c, **_largest(c, memory, p)))
    for n in ((512,) if quick else (512, 1024, 2048)):
        rows.append(_overhead(n, 4, devices, 5 if quick else (15 if n < 2048 else 7)))
    if not quick:
        rows.append(_big_run(8192, 4, devices))
    return rows


if __name__ == "__main__":
    if sys.argv[1] == "--huge-one":
        print(json.dumps(_huge_one(int(sys.argv[2]), int(sys.argv[3]), sys.argv[4])))
    else:
        print(json.dumps(main("--quick" in sys.argv)))
