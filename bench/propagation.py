"""``python -m bench propagation``: the simulation step against the bare FFT work it needs,
and error against time for the spectral, finite-difference and truncated-kernel methods.

Rows (JSON): method, n, dtype, seconds, baseline_seconds, ratio, error, and details.
"""

from __future__ import annotations

import math
import statistics

import jax.numpy as jnp
import numpy as np

from bench.timing import fft_work, interleaved, median_seconds, paired_ratio
from wavephys import Grid, Simulation, Stones, Water
from wavephys.core.stepper import TwoLevelState
from wavephys.models.finite_difference import FiniteDifferenceStepper
from wavephys.models.truncated_kernel import KernelStepper, max_stable_dt, truncated_kernel
from wavephys.physics import dispersion as disp
from wavephys.physics.heights import first_order_height
from wavephys.physics.ring_waves import propagate
from wavephys.simulation import operators


def step_rows(sizes=(256, 512, 1024, 2048), progress=print) -> list[dict]:
    """Full step (cutoff + propagate + η + η̇) vs the bare FFTs it needs (2 rfft2 + 4 irfft2).

    ``error``: max |ψ_step − ψ_exact| / max |ψ_exact| of the float32 step against the
    complex-FFT propagation of the same field, then cut off. ``ratio``: median over rounds of
    step time / fastest bare-FFT time in the same round (runs interleaved, blocks of 5),
    with its quartiles over rounds (the machine's noise).
    """
    rows = []
    water = Water()
    for n in sizes:
        progress(f"step timing n={n}")
        grid = Grid(n, 16.0)
        sim = Simulation(grid, water, dt=1 / 30, margin=n // 8)
        state = sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.2, 0.01))
        work = fft_work(n, 2, 4)
        times = interleaved({"step": lambda: sim.step(state), **work}, repeats=25 if n <= 1024 else 7)
        base = {k: statistics.median(times[k]) for k in work}
        best = min(base, key=base.get)
        seconds = statistics.median(times["step"])
        ratio, q1, q3 = paired_ratio(times, "step", list(work))
        new, _ = sim.step(state)
        exact = propagate(state.psi, grid, water, 1 / 30) * operators(sim.model).mask
        err = float(jnp.max(jnp.abs(new.psi - exact)) / jnp.max(jnp.abs(exact)))
        rows.append(dict(method="spectral step", n=n, dtype="float32", seconds=seconds,
                         baseline_seconds=base[best], baseline=best, ratio=ratio,
                         ratio_quartiles=[q1, q3],
                         error=err, baselines=base))
    return rows


# -- error against time on a wave packet ---------------------------------------------------
LENGTH, WAVELENGTH, WIDTH, DURATION = 64.0, 4.0, 4.0, 8.0
"""Packet scene: 64 m domain, 4 m carrier, 4 m Gaussian envelope, 8 s (5 periods)."""
WATER = Water(sigma=0.0)


def _packet_at(grid: Grid, t: float):
    """Exact ψ(t) of a deep-water packet that starts at x = −16 m moving in +x (any t)."""
    x, y = grid.mesh()
    k0 = 2 * math.pi / WAVELENGTH
    env = jnp.exp(-0.5 * ((x + 16.0) ** 2 + y**2) / WIDTH**2)
    a = 0.01 * float(disp.angular_frequency(k0, WATER)) / k0  # 1 cm height amplitude
    psi = a * env * jnp.exp(1j * k0 * x)
    omega = disp.angular_frequency(grid.wavenumber_magnitude(), WATER)
    return jnp.fft.ifft2(jnp.fft.fft2(psi) * jnp.exp(-1j * omega * t))


def _height_at(grid: Grid, t: float):
    return np.asarray(first_order_height(_packet_at(grid, t), grid, WATER))


def _rel_l2(a, b):
    return float(np.linalg.norm(np.asarray(a) - b) / np.linalg.norm(b))


def accuracy_rows(progress=print) -> list[dict]:
    """Relative L2 error of η after 8 s against the exact packet, and the seconds it took."""
    rows = []
    k0 = 2 * math.pi / WAVELENGTH
    c0 = float(disp.phase_speed(k0, WATER))
    for n in (128, 256, 512):
        grid = Grid(n, LENGTH)
        dx = float(grid.dx)
        exact = _height_at(grid, DURATION)
        # spectral: exact for any Δt; stepped at 30 frames per second of output
        steps = int(DURATION * 30)
        sim = Simulation(grid, WATER, dt=DURATION / steps)
        st = sim.state_from_psi(_packet_at(grid, 0.0))
        progress(f"spectral n={n}")
        seconds = median_seconds(lambda: sim.run(st, steps), 3)
        end, _ = sim.run(st, steps)
        rows.append(dict(method="spectral", n=n, dtype="float32", seconds=seconds, label=f"n={n}",
                         error=_rel_l2(sim.surface(end).eta, exact), steps=steps))
        # finite differences at the carrier's phase speed (their best case)
        e0 = _height_at(grid, 0.0)
        for courant in (0.5, 0.25):
            steps = int(round(DURATION / (courant * dx / c0)))
            dt = DURATION / steps
            em = _height_at(grid, -dt)
            c = c0 * dt / dx
            progress(f"finite differences n={n} C={courant}")
            fd = FiniteDifferenceStepper(c, dt)  # every step kept, as the spectral run above keeps its surfaces
            seconds = median_seconds(lambda: fd.trajectory(TwoLevelState(e0, em), steps), 3)
            out = fd.trajectory(TwoLevelState(e0, em), steps)[0].eta
            rows.append(dict(method="finite difference", n=n, dtype="float32", seconds=seconds,
                             label=f"n={n} C={courant}", error=_rel_l2(out, exact), steps=steps))
    grid = Grid(256, LENGTH)
    exact = _height_at(grid, DURATION)
    e0 = _height_at(grid, 0.0)
    for size in (3, 9, 17, 33, 65):
        stencil = truncated_kernel(grid, WATER, size)
        steps = int(math.ceil(DURATION / min(0.5 * max_stable_dt(stencil, grid), 0.02)))
        dt = DURATION / steps
        em = _height_at(grid, -dt)
        progress(f"truncated kernel P={size}")
        kernel = KernelStepper(stencil, dt)
        seconds = median_seconds(lambda: kernel.advance(TwoLevelState(e0, em), steps), 3)
        out = kernel.advance(TwoLevelState(e0, em), steps).eta
        rows.append(dict(method="truncated kernel", n=256, dtype="float32", seconds=seconds,
                         label=f"P={size}", error=_rel_l2(out, exact), steps=steps))
    for r in rows:
        r["baseline_seconds"] = None
    return rows


# -- on an accelerator -----------------------------------------------------------------------
def device_step_rows(kind: str, sizes=(1024, 2048, 4096, 8192), progress=print) -> list[dict]:
    """The step on one device of ``kind`` ("gpu", "tpu" or "cpu") against that device's own FFT
    floor: the same 2 batched rfft2 + 4 batched irfft2, each in its own compiled program,
    through ``jnp.fft`` (cuFFT on an NVIDIA GPU). Ratio: median over interleaved rounds."""
    import jax

    try:
        device = jax.devices(kind)[0]
    except RuntimeError as exc:
        raise SystemExit(f"--device {kind}: no such device here ({exc}); jax.devices() = {jax.devices()}") from None
    rows = []
    for n in sizes:
        progress(f"step on {device.platform} n={n}")
        with jax.default_device(device):
            grid = Grid(n, 16.0)
            sim = Simulation(grid, Water(), dt=1 / 30, margin=n // 8)
            state = sim.drop(sim.initial_state(), Stones(0.0, 0.0, 0.2, 0.01))
            x = jax.device_put(jnp.zeros((2, n, n), jnp.float32), device)
            spec = jax.device_put(jnp.zeros((2, n, n // 2 + 1), jnp.complex64), device)
            forward = jax.jit(jnp.fft.rfft2)
            inverse = jax.jit(lambda s: jnp.fft.irfft2(s, s=(n, n)))
            floor = lambda: (forward(x), inverse(spec), inverse(spec))
            times = interleaved({"step": lambda: sim.step(state), "fft floor": floor},
                                repeats=15 if n <= 4096 else 7)
        ratio, q1, q3 = paired_ratio(times, "step", ["fft floor"])
        rows.append(dict(method="spectral step", device=str(device), n=n, dtype="float32",
                         seconds=statistics.median(times["step"]), baseline="jnp.fft on the device",
                         baseline_seconds=statistics.median(times["fft floor"]), ratio=ratio,
                         ratio_quartiles=[q1, q3], error=float("nan")))
    return rows
