"""One ocean over every device of every process: a sharded simulation and a sweep.

Run it as one process (all of this machine's devices; on a CPU, add
``XLA_FLAGS=--xla_force_host_platform_device_count=4`` to try 4 devices)::

    python examples/sharded_ocean.py --n 512 --steps 100 --out eta.npz

as plain processes, one per host (every process runs the same command and uses all of
its host's devices; for one process per GPU give each its own ``CUDA_VISIBLE_DEVICES``)::

    WAVEPHYS_COORDINATOR=host0:12355 WAVEPHYS_NUM_PROCESSES=2 WAVEPHYS_PROCESS_ID=0 python examples/sharded_ocean.py
    WAVEPHYS_COORDINATOR=host0:12355 WAVEPHYS_NUM_PROCESSES=2 WAVEPHYS_PROCESS_ID=1 python examples/sharded_ocean.py

or under Slurm, where JAX reads the job's own variables::

    srun --nodes=2 --ntasks-per-node=1 python examples/sharded_ocean.py --hosts

Process 0 writes the last surface and a sweep over depths (the rings of a stone after 1 s,
max |η|) to ``--out`` (numpy .npz).
"""

from __future__ import annotations

import argparse
import os


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=256, help="grid points per side (divisible by the devices)")
    parser.add_argument("--length", type=float, default=20.0, help="domain side, m")
    parser.add_argument("--steps", type=int, default=30)
    parser.add_argument("--out", default="sharded_ocean.npz")
    parser.add_argument("--sweep-n", type=int, default=64, help="grid of the depth sweep's models")
    parser.add_argument("--hosts", action="store_true", help="join other processes (Slurm, or WAVEPHYS_* set)")
    args = parser.parse_args(argv)

    from wavephys import parallel

    if args.hosts or "WAVEPHYS_COORDINATOR" in os.environ:
        parallel.initialize()  # before any other JAX work

    import jax
    import jax.numpy as jnp
    import numpy as np

    from wavephys import Grid, Stones, Water
    from wavephys.core.files import atomic_path, output_file
    from wavephys.simulation import Model, Simulation, add_source, initial_state, run

    out = output_file(args.out, "--out", (".npz",))
    mesh = parallel.hosts_mesh() if parallel.is_initialized() else parallel.row_mesh(jax.devices())
    grid = Grid(args.n, args.length)
    sim = Simulation(grid, Water(depth=3.0), dt=1 / 30, margin=args.n // 16, mesh=mesh)
    state = sim.add_wind(sim.initial_state(), jax.random.PRNGKey(7), "phillips", wind_speed=4.0, direction=0.3)
    state = sim.drop(state, Stones(0.1 * args.length, -0.15 * args.length, 0.02 * args.length, 0.05))
    state, surfaces = sim.run(state, args.steps)
    eta = parallel.gather(surfaces.eta[-1])

    def ring_height(model):  # what a calibration sweep asks of each model: the rings after 1 s
        start = add_source(model, initial_state(model), Stones(0.0, 0.0, 0.5, 0.02))
        _, surfaces = run(model, start, 20)
        return jnp.max(jnp.abs(surfaces.eta[-1]))

    depths = [0.2, 0.5, 1.0, 2.0, 5.0, float("inf")]
    models = [Model(Grid(args.sweep_n, 8.0), Water(depth=d), dt=0.05, margin=args.sweep_n // 16) for d in depths]
    rings = np.array([float(h) for h in parallel.sweep(ring_height, models)])

    if jax.process_index() == 0:
        with atomic_path(out) as tmp:
            with open(tmp, "wb") as f:
                np.savez(f, eta=eta, depths=np.array(depths), rings=rings)
        print(f"{jax.process_count()} process(es), {mesh.size} devices ({mesh.devices.flat[0].platform}): "
              f"{args.n}² grid, {args.steps} steps, max |eta| = {np.abs(eta).max():.4g} m -> {out}")


if __name__ == "__main__":
    main()
