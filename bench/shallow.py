"""``python -m bench shallow``: nonlinear shallow water (finite volumes, order 1 and 2) and the virtual pipes —
speed against accuracy on the exact dam breaks, and the cost of a step against the spectral step.

Rows (JSON):

* ``family="dam break"``: method, case (Ritter: dry bed; Stoker: hr/hl = 0.1), n, seconds (median time to
  solution after compiling, t = 1 s), error (L1, m), max_error (m), front (position error, m);
* ``family="step"``: method, n (n × n cells), seconds per step (median of interleaved rounds), ratio to the
  spectral step of the same grid in the same rounds (median, quartiles);
* ``family="compile"``: method, form (the step's two stages as one loop, as shipped, or written out, as before
  0.3.0), n, lower_seconds and compile_seconds (median of fresh compiles of the stepper's loop program), lines
  (StableHLO);
* ``family="split dispersion"``: model (split, finite volumes order 2), kh band (kh0 … 4 kh0), worst
  |ω/ω_exact − 1| by the harness's dispersion check over four waves on 128 periodic cells.
"""

from __future__ import annotations

import math
import statistics

import jax
import jax.numpy as jnp
import numpy as np

from bench.timing import interleaved, median_seconds, paired_ratio

G = 9.81


def _dam(n, hr):
    c0 = math.sqrt(G)
    half = 2.4 * c0
    dx = 2 * half / n
    x = (np.arange(n) + 0.5) * dx - half
    return x, dx, np.zeros((1, n)), np.where(x < 0, 1.0, hr)


def dam_break_rows(sizes=(100, 200, 400, 800, 1600), progress=print) -> list[dict]:
    """Time to solution and error of each method on Ritter's and Stoker's dam breaks (module doc)."""
    from wavephys.models.pipes import Pipes, _pipes_run, pipes_state
    from wavephys.physics.shallow_water import ritter, stoker
    from wavephys.simulation.shallow_water import ShallowWater, _sw_run, sw_state

    rows = []
    with jax.enable_x64(True):
        for case, hr in (("Ritter (dry bed)", 0.0), ("Stoker (hr/hl = 0.1)", 0.1)):
            for n in sizes:
                progress(f"shallow: {case}, n = {n}")
                x, dx, bed, depth = _dam(n, hr)
                want = ritter(x, 1.0, 1.0)[0] if hr == 0 else stoker(x, 1.0, 1.0, hr)[0]
                runs = {}
                for order in (1, 2):
                    solver = ShallowWater(dx, sides="open", order=order)
                    state = sw_state(bed, depth=depth[None], dtype=jnp.float64)
                    runs[f"finite volumes, order {order}"] = (
                        lambda s=solver, st=state: _sw_run(s, bed, st, until=1.0)[0].h[0])
                steps = int(math.ceil(1.0 / (0.25 * dx / math.sqrt(G))))
                pstate = pipes_state(bed, depth=depth[None], dtype=jnp.float64)
                runs["virtual pipes"] = lambda st=pstate, dx=dx, k=steps: _pipes_run(Pipes(dx), bed, st, k, 1.0 / k).depth[0]
                for method, fn in runs.items():
                    h = np.asarray(fn(), np.float64)
                    seconds = median_seconds(fn, repeats=3)
                    rows.append(dict(family="dam break", case=case, method=method, n=n, seconds=seconds,
                                     error=float(np.abs(h - want).mean()), max_error=float(np.abs(h - want).max())))
    return rows


def step_rows(sizes=(256, 512), progress=print) -> list[dict]:
    """Seconds per step of each model at n × n against the spectral step (module doc)."""
    from wavephys import Grid, Stones, Water
    from wavephys.models.pipes import Pipes, _pipes_run, pipes_state
    from wavephys.simulation import Model
    from wavephys.simulation.depth import Floor, depth_state
    from wavephys.simulation.steppers import DepthStepper
    from wavephys.simulation.shallow_water import ShallowWater, _sw_run, sw_state
    from wavephys.simulation.stepping import add_source, initial_state, run

    rows = []
    for n in sizes:
        progress(f"shallow: step cost at {n}^2")
        length = 8.0
        dx = length / n
        c = (np.arange(n) + 0.5) * dx - length / 2
        xx, yy = np.meshgrid(c, c)
        bed = -1.5 + 0.1 * xx
        eta = 0.02 * np.exp(-(xx * xx + yy * yy))
        dt = 0.45 * dx / math.sqrt(G * 2.0)
        model = Model(Grid(n, length), Water(sigma=0.0, depth=1.5), dt=dt, walls="all")
        spectral = add_source(model, initial_state(model), Stones(0.5, 0.5, 0.2, 0.01))
        floor = Floor(-bed)
        linear = depth_state(model, eta)
        fv2, fv1 = ShallowWater(dx, order=2), ShallowWater(dx, order=1)
        sw = sw_state(bed, eta)
        pipes = Pipes(dx)
        ps = pipes_state(bed, eta + 0 * bed)
        from wavephys.simulation.split import Split, _split_run

        wet_floor = Floor(np.maximum(-bed, 0.05))
        split2 = Split(fv2, levels=(0.5, 2.0))
        split4 = Split(fv2, levels=(0.5, 0.8, 1.3, 2.0))
        k = 10
        shallow, levels = DepthStepper(model, floor, "shallow"), DepthStepper(model, wet_floor, "levels")
        fns = {
            "spectral step (walls)": lambda: run(model, spectral, k)[0].psi,
            "linear shallow water (varying depth)": lambda: shallow.advance(linear, k).fields,
            "finite volumes, order 2": lambda: _sw_run(fv2, bed, sw, steps=k, dt=dt)[0].fields,
            "finite volumes, order 1": lambda: _sw_run(fv1, bed, sw, steps=k, dt=dt)[0].fields,
            "virtual pipes": lambda: _pipes_run(pipes, bed, ps, k, dt).depth,
            "levels (4 depths, linear, dispersive)": lambda: levels.advance(linear, k).fields,
            "split, 2 levels": lambda: _split_run(split2, bed, sw, steps=k, dt=dt)[0].fields,
            "split, 4 levels": lambda: _split_run(split4, bed, sw, steps=k, dt=dt)[0].fields,
        }
        times = interleaved(fns, repeats=7, block=3)
        for name in fns:
            ratio, q1, q3 = paired_ratio(times, name, ["spectral step (walls)"])
            rows.append(dict(family="step", method=name, n=n, seconds=statistics.median(times[name]) / k,
                             ratio=ratio, ratio_quartiles=[q1, q3]))
    return rows


def _two_stages_written_out(solver, bed, fields, t, dt, limited=True):
    """The order-2 step with its two stages as two copies of the rate in the program (the solver's form before
    0.3.0, the same arithmetic): the baseline of :func:`compile_rows`."""
    from wavephys.simulation.shallow_water import _dry_out, _rate

    u1 = _dry_out(fields + dt * _rate(solver, bed, fields, t, limited), solver.dry)
    return _dry_out(0.5 * fields + 0.5 * (u1 + dt * _rate(solver, bed, u1, t + dt, limited)), solver.dry)


def compile_rows(n=32, repeats=3, progress=print) -> list[dict]:
    """Seconds to lower and to compile the loop program of each nonlinear stepper at n × n (walls, float32), the
    median of ``repeats`` fresh compiles, and its StableHLO lines; against the same stepper with the two stages
    of its step written out (:func:`_two_stages_written_out`), in the same run (module doc)."""
    from wavephys.simulation import shallow_water as sw
    from wavephys.simulation.split import Split, SplitStepper

    dx = 8.0 / n
    c = (np.arange(n) + 0.5) * dx - 4.0
    xx, yy = np.meshgrid(c, c)
    bed = jnp.asarray(-1.5 + 0.1 * xx + 0.2 * np.sin(yy), jnp.float32)
    cases = {"finite volumes, order 2": sw.ShallowWaterStepper(sw.ShallowWater(dx), bed),
             "split, 1 level": SplitStepper(Split(sw.ShallowWater(dx), levels=(1.0,)), bed),
             "split, 2 levels": SplitStepper(Split(sw.ShallowWater(dx), levels=(0.5, 2.0)), bed)}
    rows = []
    cached = jax.config.jax_enable_compilation_cache  # fresh compiles, not a persistent cache's copies
    jax.config.update("jax_enable_compilation_cache", False)
    try:
        for name, stepper in cases.items():
            rows += _compile_case(name, stepper, bed, xx, yy, n, repeats, progress)
    finally:
        jax.config.update("jax_enable_compilation_cache", cached)
        jax.clear_caches()  # the written-out form's programs go
    return rows


def _compile_case(name, stepper, bed, xx, yy, n, repeats, progress) -> list[dict]:
    """:func:`compile_rows`' two rows of one stepper."""
    import contextlib
    import time
    from unittest import mock

    from wavephys.core.stepper import _loop_program
    from wavephys.simulation import shallow_water as sw

    progress(f"shallow: compiling {name} at {n}^2")
    state = stepper.init(sw.sw_state(bed, 0.01 * np.exp(-(xx * xx + yy * yy))))
    static, dynamic = stepper._parts()
    args = (type(stepper), static, dynamic, state, jnp.asarray(np.inf, jnp.float32), jnp.asarray(10, jnp.int32),
            jnp.asarray(np.nan, jnp.float32))
    rows = []
    for form in ("one loop of two stages", "two stages written out"):
        lower, build, lines = [], [], 0
        for _ in range(repeats):
            jax.clear_caches()
            with (contextlib.nullcontext() if form == "one loop of two stages"
                  else mock.patch.object(sw, "_advance", _two_stages_written_out)):
                start = time.perf_counter()
                lowered = _loop_program.lower(*args)
                middle = time.perf_counter()
                lowered.compile()
                lower.append(middle - start)
                build.append(time.perf_counter() - middle)
                lines = lowered.as_text().count("\n")
        rows.append(dict(family="compile", method=name, form=form, n=n, lower_seconds=statistics.median(lower),
                         compile_seconds=statistics.median(build), lines=lines))
    return rows


def split_dispersion_rows(bands=(0.1, 0.4, 1.6, 6.4), progress=print) -> list[dict]:
    """The split's and shallow water's worst dispersion error per kh band by the harness (module doc)."""
    from wavephys.core.water import Water
    from wavephys.harness.dispersion import dispersion_check, measure_dispersion
    from wavephys.physics.dispersion import angular_frequency
    from wavephys.simulation.shallow_water import ShallowWater, _sw_frames, sw_state
    from wavephys.simulation.split import Split, _split_frames

    water = Water(sigma=0.0, depth=1.0)
    rows = []
    for kh0 in bands:
        progress(f"shallow: split dispersion, kh {kh0}..{4 * kh0}")
        k0, n = kh0, 128
        dx = 2 * np.pi / k0 / n
        x = (np.arange(n) + 0.5) * dx
        rng = np.random.default_rng(1)
        eta = sum(1e-3 * min(1.0, 1.0 / (m * kh0)) * np.cos(m * k0 * x + rng.uniform(0, 2 * np.pi)) for m in (1, 2, 3, 4))
        bed = np.full((1, n), -1.0)
        w0 = float(angular_frequency(jnp.asarray(k0), water))
        dt = np.pi / float(angular_frequency(jnp.asarray(4 * k0), water)) / 3
        times = np.arange(1, int(8 * 2 * np.pi / w0 / dt) + 1) * dt
        solver = ShallowWater(dx, sides="periodic")
        for model, run in (("split", lambda st: _split_frames(Split(solver, levels=(1.0,)), bed, st, times)),
                           ("finite volumes, order 2", lambda st: _sw_frames(solver, bed, st, times))):
            frames = run(sw_state(bed, eta[None]))
            record = np.asarray(frames.fields[:, 0] + bed, np.float64)
            row = dispersion_check(measure_dispersion(record, dx, dt), water, dt, k_range=(0.9 * k0, 4.1 * k0))
            rows.append(dict(family="split dispersion", model=model, kh=[kh0, 4 * kh0], error=float(row.measured),
                             cells_per_wavelength=[n / 4, n]))
    return rows


_MEMORY_CASE = r"""
import json, resource, sys
import numpy as np
import jax

method, steps, n = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])


def resident_mb():  # Linux's count of resident pages; NaN where there is no /proc
    try:
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * (resource.getpagesize() / 2**20)
    except OSError:
        return float("nan")


def peak_mb():  # ru_maxrss: KB on Linux, bytes on macOS
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / (2**20 if sys.platform == "darwin" else 1024)


def held(tree):
    return int(sum(np.asarray(x).nbytes for x in jax.tree_util.tree_leaves(tree)))


if method.startswith("ShallowWaterStepper"):
    from wavephys.simulation import shallow_water as sw
    from wavephys.steppers import ShallowWaterStepper

    x = (np.arange(n) + 0.5) * (16.0 / n) - 8.0
    bed = -np.clip(0.2 + 0.1 * (x + 8.0), 0.05, 1.5) * np.ones((n, 1))
    start = sw.sw_state(bed, np.where(-bed > 0.06, 0.01 * np.exp(-(x ** 2) / 2.0), 0.0))
    stepper = ShallowWaterStepper(sw.ShallowWater(16.0 / n), bed)
    run = lambda k, keep: stepper.run(start, steps=k, every=60, callback=keep)
else:
    from wavephys import Grid, Water
    from wavephys.simulation import Model
    from wavephys.simulation.depth import Floor, depth_state
    from wavephys.steppers import DepthStepper

    grid = Grid(n, 16.0)
    model = Model(grid, Water(sigma=0.0), dt=1 / 30, walls="all")
    x = np.asarray(grid.mesh()[0])
    floor = Floor(np.clip(0.2 + 0.1 * (x + 8.0), 0.05, 1.5))
    start = depth_state(model, 0.01 * np.exp(-(x ** 2) / 2.0))
    stepper = DepthStepper(model, floor, "shallow")
    if method == "trajectory":
        run = lambda k, keep: stepper.trajectory(start, k)
    else:
        run = lambda k, keep: stepper.run(start, steps=k, every=60, callback=keep)

kept = []
warm = run(60, lambda i, t, eta: kept.append(float(np.max(eta))))  # compiled (the steppers: one program for any count)
del warm
kept.clear()
before, peak_before = resident_mb(), peak_mb()
out = run(steps, lambda i, t, eta: kept.append(float(np.max(eta))))
print(json.dumps(dict(bytes_held=held(out), resident_growth_mb=resident_mb() - before,
                      peak_growth_mb=peak_mb() - peak_before,
                      frames=len(kept))))
"""


def memory_rows(steps=(60, 960, 3840), n=256, progress=print) -> list[dict]:
    """Memory a long run holds: each run in a process of its own, warmed up by a run of 60 steps, then measured:
    the bytes of the arrays the call leaves the caller, and the growth over the measured run of the resident size
    (what the process still holds at its end) and of the peak resident size (at its worst; it includes compiling
    where a run of this length compiles a program of its own, as ``trajectory`` does), MB.

    Runs: the linear depth stepper (floor ``"shallow"`` over a 1.5 m slope, n × n) behind the one interface,
    streaming a frame every 60 steps to a callback (``DepthStepper.run``), against ``DepthStepper.trajectory``
    (what the deprecated ``run_depth`` did), which returns the state of every step (run up to 960 steps: 3840
    would hold 1 GB at 256²); and nonlinear shallow water
    (``ShallowWaterStepper.run``, the same slope, n/2 × n/2, its adaptive steps) streaming likewise. Each
    process imports wavephys from this checkout, on the CPU unless ``JAX_PLATFORMS`` says otherwise.

    Parameters
    ----------
    steps : sequence of int
        Run lengths (multiples of 60).
    n : int
        Cells a side of the depth stepper's grid.
    progress : callable

    Returns
    -------
    list of dict
        ``family="run memory"``: method, steps, n, bytes_held, resident_growth_mb, peak_growth_mb, frames.
    """
    import json
    import os
    import subprocess
    import sys

    cases = [("DepthStepper.run, a frame every 60 steps to a callback", "DepthStepper", n, steps),
             ("DepthStepper.trajectory (the state of every step)", "trajectory", n, [k for k in steps if k <= 960]),
             ("ShallowWaterStepper.run, a frame every 60 steps to a callback", "ShallowWaterStepper", n // 2, steps)]
    rows = []
    for label, method, size, lengths in cases:
        for k in lengths:
            progress(f"memory: {method}, {k} steps at {size}^2 (a process of its own)")
            root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
            paths = [root] + [p for p in [os.environ.get("PYTHONPATH")] if p]
            env = dict(os.environ, PYTHONPATH=os.pathsep.join(paths))
            env.setdefault("JAX_PLATFORMS", "cpu")
            done = subprocess.run([sys.executable, "-c", _MEMORY_CASE, method, str(k), str(size)],
                                  capture_output=True, text=True, env=env, cwd=root)
            if done.returncode:
                raise RuntimeError(f"memory case {method} at {k} steps failed:\n{done.stderr[-2000:]}")
            rows.append(dict(family="run memory", method=label, steps=k, n=size,
                             **json.loads(done.stdout.strip().splitlines()[-1])))
    return rows


def figures(rows) -> dict:
    from wavephys.plot import plot_error_vs_time

    out = {}
    for case, key in (("Ritter (dry bed)", "ritter"), ("Stoker (hr/hl = 0.1)", "stoker")):
        sel = [dict(method=r["method"], seconds=r["seconds"], error=r["error"], label=str(r["n"]))
               for r in rows if r.get("family") == "dam break" and r["case"] == case]
        if sel:
            out[key] = plot_error_vs_time(sel, f"dam break, {case}, t = 1 s: error against time to solution",
                                          ylabel="L1 error of the depth, m")
    return out
