"""``python -m bench walls``: the walled step (cosine transforms) against today's periodic step at the same
N, and against what a user would write instead for a reflecting tank with FFTs alone: the periodic step
on the mirror-doubled domain (2N × 2N holding the field and its images, docs/physics.md §1.11).

Rows (JSON): boundary, n, seconds (median of interleaved rounds), ratio to the periodic step in the same
rounds (median and quartiles), temp_bytes (the compiled step's scratch memory), state_bytes, and the
float32 energy drift over 1000 steps.
"""

from __future__ import annotations

import statistics

import jax
import numpy as np

from bench.timing import interleaved, paired_ratio
from wavephys import Grid, Stones, Water
from wavephys.simulation import Model
from wavephys.simulation.stepping import add_source, energy, initial_state, run, step

WATER = Water(sigma=0.0, depth=1.5)
CASES = (("periodic", {}, 1), ("walls all", dict(walls="all"), 1), ("walls x", dict(walls="x"), 1),
         ("walls bottom + margin", dict(walls=("bottom",), margin=None), 1),
         ("tank 8 x 4 m in 8 m", dict(walls="all", tank=(8.0, 4.0)), 1), ("doubled periodic", {}, 2))


def _model(n, kw, factor):
    kw = dict(kw)
    if "margin" in kw:
        kw["margin"] = n // 16
    return Model(Grid(factor * n, factor * 8.0), WATER, dt=1 / 30, **kw)


def _temp_bytes(model, state):
    compiled = jax.jit(lambda s: step(model, s)).lower(state).compile()
    analysis = compiled.memory_analysis()
    return int(getattr(analysis, "temp_size_in_bytes", 0)) if analysis is not None else 0


def wall_rows(sizes=(256, 512, 1024), progress=print) -> list[dict]:
    """One row per boundary and size (module doc)."""
    rows = []
    for n in sizes:
        models, states = {}, {}
        for name, kw, factor in CASES:
            m = _model(n, kw, factor)
            models[name] = m
            states[name] = add_source(m, initial_state(m), Stones(1.0, 0.5, 0.2, 0.01))
        progress(f"walls: timing n={n}")
        fns = {name: (lambda m=models[name], s=states[name]: step(m, s)) for name in models}
        times = interleaved(fns, repeats=15 if n <= 512 else 7)
        for name, kw, factor in CASES:
            m, s = models[name], states[name]
            ratio, q1, q3 = paired_ratio(times, name, ["periodic"])
            drift = float("nan")
            if n <= 512 and factor == 1 and not m.margin:
                e0 = float(energy(m, s))
                drift = abs(float(energy(m, run(m, s, 1000)[0])) / e0 - 1)
            rows.append(dict(boundary=name, n=n, grid=factor * n, seconds=statistics.median(times[name]),
                             ratio=ratio, ratio_quartiles=[q1, q3], temp_bytes=_temp_bytes(m, s),
                             state_bytes=int(np.asarray(s.fields).nbytes), energy_drift_1000=drift))
    return rows


def depth_step_rows(sizes=(256, 512), progress=print) -> list[dict]:
    """The steppers over a varying floor against the periodic step at the same N (interleaved rounds)."""
    from wavephys.simulation.depth import Floor, depth_state, step_levels, step_shallow, step_symmetric

    rows = []
    for n in sizes:
        progress(f"depth: timing n={n}")
        periodic = _model(n, {}, 1)
        state = add_source(periodic, initial_state(periodic), Stones(1.0, 0.5, 0.2, 0.01))
        x = np.asarray(periodic.grid.mesh()[0])
        floor = Floor(np.clip(1.5 - 0.15 * (x + 4.0), 0.1, 1.5), levels=4)
        eta = np.asarray(periodic.grid.mesh()[1]) * 0 + 1e-3 * np.exp(-(x ** 2) / 0.5)
        ds = depth_state(periodic, eta)
        fns = {"periodic": lambda: step(periodic, state), "levels (4)": lambda: step_levels(periodic, floor, ds),
               "shallow": lambda: step_shallow(periodic, floor, ds),
               "symmetric (4)": lambda: step_symmetric(periodic, floor, ds)}
        times = interleaved(fns, repeats=9)
        for name in fns:
            ratio, q1, q3 = paired_ratio(times, name, ["periodic"])
            rows.append(dict(boundary=f"floor: {name}", n=n, grid=n, seconds=statistics.median(times[name]),
                             ratio=ratio, ratio_quartiles=[q1, q3], temp_bytes=0,
                             state_bytes=int(np.asarray(ds.fields).nbytes), energy_drift_1000=float("nan")))
    return rows


def shoaling_rows(progress=print) -> list[dict]:
    """Each stepper's amplitude up a ramp (1 m → 0.25 m) against the mild-slope reference, over kh and the ramp's
    length: the failure boundary in kh and slope (docs/physics.md §1.12). Packets of σ = 6 wavelengths (their own
    spreading 0.2 %); the split (issue 32's model) on gentle ramps only."""
    import jax

    from wavephys.checks.depth import measure_shoaling
    from wavephys.physics.depth import mild_slope_transmission

    rows = []
    with jax.enable_x64(True):
        for method, per, ramps, levels in (("symmetric", 16, (10.0, 3.0, 1.0), 4), ("symmetric", 16, (1.0,), 2),
                                           ("levels", 8, (10.0, 1.0), 4), ("shallow", 16, (10.0, 1.0), 4),
                                           ("split", 16, (10.0,), 2)):
            for kh0 in (0.1, 0.3, 1.0, 3.0):
                for ramp in ramps:
                    if method == "split" and kh0 < 0.3:
                        continue  # 150 wavelengths of 63 m at 16 samples: minutes; the bulk carries these
                    progress(f"shoaling: {method} ({levels}) kh0={kh0} ramp={ramp}")
                    amp, omega = measure_shoaling(method, 1.0, 0.25, kh0, per, ramp, 6.0, levels)
                    lam = 2 * np.pi / kh0
                    true_omega = float(np.sqrt(9.81 * kh0 * np.tanh(kh0)))
                    reference, reflection = mild_slope_transmission(true_omega, [0.0, ramp * lam], [1.0, 0.25])
                    rows.append(dict(method=method, levels=levels, kh0=kh0, ramp_wavelengths=ramp,
                                     slope=0.75 / (ramp * lam), samples_per_wavelength=per, amplitude=amp,
                                     reference=reference, reference_reflection=reflection, error=amp / reference - 1))
    return rows
