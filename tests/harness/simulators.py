"""Simulators written the way engines and tutorials write them, each with its truth decided from its own scheme.

Each entry is a small numpy simulator written here from facts about what real code does (named in ``fact``),
never copied. Beside its frames it carries its *symbol*: the angular frequency each Fourier mode turns at under
its update rule (exact for a spectral scheme, the von Neumann symbol for a finite-difference one), and its
amplitude factor per step. From that alone, with no measurement, :func:`truth` decides whether each check must
pass: the scheme's ω(k) against linear theory on the modes the record holds and the frames can sample, its
energy change over the record, its direction of travel. tests/harness/test_simulators.py holds the harness's
verdicts and causes to that truth, through Python, the pytest fixture and the command.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from corpus import G, minus_k, omega, phillips_h0, random_heights, wavenumbers

N, DX, DT = 64, 0.25, 1 / 15


@dataclass(frozen=True)
class Simulator:
    name: str
    fact: str
    run: Callable          # () -> (eta (n_t, n, n), dx, dt, power (n, n): each mode's share of the heights)
    symbol: Callable       # (kx, ky) rad/m -> omega rad/s each mode turns at under the scheme
    claims: dict           # what the code states (sea, direction, depth, sigma, tank …)
    causes: dict           # check -> cause fragment for the checks that must fail
    heading: float = None  # the direction the scheme's waves travel, degrees (None: not one way)
    gain: Callable = None  # (kx, ky) -> amplitude factor per frame (1: conservative)
    water: dict = field(default_factory=lambda: dict(sigma=0.0))
    maps: Callable = None  # (eta, dx) -> {claim: array}: textures the engine exports beside the frames


def _ocean(h0, dx, dt, frames, w):
    """An FFT ocean: h(k, t) = h0(k) e^{−iω t} + conj(h0(−k)) e^{iω t} with the scheme's ω(k)."""
    h0m = np.conj(minus_k(h0))
    return np.array([np.real(np.fft.ifft2(h0 * np.exp(-1j * w * i * dt) + h0m * np.exp(1j * w * i * dt)))
                     for i in range(frames)])


def _spectrum_power(h0):
    p = np.abs(h0) ** 2 + np.abs(minus_k(h0)) ** 2
    return p / p.sum()


def _fft_sim(omega_of_k, h0_of=lambda: phillips_h0(N, DX, seed=1), frames=192):
    def run():
        h0 = h0_of()
        _, _, k = wavenumbers(N, DX)
        return _ocean(h0, DX, DT, frames, omega_of_k(k)), DX, DT, _spectrum_power(h0)
    return run


def _isotropic(omega_of_k):
    return lambda kx, ky: omega_of_k(np.hypot(kx, ky))


def _looped(period):
    w0 = 2 * math.pi / period
    return lambda k: np.floor(omega(k) / w0) * w0


def _gerstner_sum(speed_of, frames=192, waves=10, seed=7):
    """GPU Gems' sum of waves: wavelengths L_i and directions around the wind, each at the phase speed
    ``speed_of(L)`` (a sine per wave: Gerstner with Q = 0), laid on the grid's wavenumbers so that it tiles."""
    def pick():
        rng = np.random.default_rng(seed)
        m = rng.integers(2, 14, waves)
        q = rng.integers(-4, 5, waves)
        amp = rng.uniform(0.2, 1.0, waves) * 0.01
        phase = rng.uniform(0, 2 * np.pi, waves)
        return m, q, amp, phase

    def run():
        m, q, amp, phase = pick()
        length = N * DX
        kx, ky = 2 * np.pi * m / length, 2 * np.pi * q / length
        k = np.hypot(kx, ky)
        w = k * speed_of(2 * np.pi / k)
        c = -0.5 * length + (np.arange(N) + 0.5) * DX
        x, y = np.meshgrid(c, c)
        t = np.arange(frames)[:, None, None] * DT
        eta = sum(a * np.sin(kxi * x + kyi * y - wi * t + p)
                  for a, kxi, kyi, wi, p in zip(amp, kx, ky, w, phase))
        power = np.zeros((N, N))
        for a, mi, qi in zip(amp, m, q):
            power[qi % N, mi % N] += a * a
            power[-qi % N, -mi % N] += a * a
        return eta, DX, DT, power / power.sum()
    return run


def _pipes_tank(depth, nx=48, frames=300, length=2.0, dt=0.01, substeps=2):
    """Virtual pipes in a closed pool (O'Brien & Hodgins' flow between columns, as height-field games run it),
    linearized: flux on each face += dt g Δh / dx · depth, then the columns' heights change by the net flux;
    walls are faces with no flux."""
    def run():
        dx = length / nx
        rng = np.random.default_rng(3)
        c = (np.arange(nx) + 0.5) * dx
        x, y = np.meshgrid(c, c)
        h = 2e-3 * np.exp(-((x - 0.7) ** 2 + (y - 1.2) ** 2) / 0.08) + 1e-4 * rng.standard_normal((nx, nx))
        h -= h.mean()
        fx = np.zeros((nx, nx + 1))
        fy = np.zeros((nx + 1, nx))
        out = []
        for _ in range(frames):
            out.append(h.copy())
            for _ in range(substeps):
                fx[:, 1:-1] += dt * G * depth * (h[:, :-1] - h[:, 1:]) / dx
                fy[1:-1, :] += dt * G * depth * (h[:-1, :] - h[1:, :]) / dx
                h = h - dt * ((fx[:, 1:] - fx[:, :-1]) + (fy[1:, :] - fy[:-1, :])) / dx
        return np.array(out), dx, dt * substeps, None
    return run, length / nx, dt


def _pipes_symbol(depth, dx, dt):
    """The pipes' staggered (leapfrog) symbol for a tank's cosine mode (kx, ky):
    2 sin(ω dt/2)/dt = √(g h)·(2/dx)·√(sin²(kx dx/2) + sin²(ky dx/2))."""
    def symbol(kx, ky):
        s = math.sqrt(G * depth) * dt / dx * np.sqrt(np.sin(kx * dx / 2) ** 2 + np.sin(ky * dx / 2) ** 2)
        return 2 / dt * np.arcsin(np.minimum(s, 1.0))
    return symbol


def _webgl(frames=256):
    """Evan Wallace's WebGL Water update, periodic: v += (avg4 − h)·2; v *= 0.995; h += v (one texel 5 cm, one
    update 1/60 s)."""
    def run():
        h = random_heights(N, 0)
        v = np.zeros_like(h)
        out = []
        for _ in range(frames):
            avg = 0.25 * (np.roll(h, 1, 0) + np.roll(h, -1, 0) + np.roll(h, 1, 1) + np.roll(h, -1, 1))
            v = (v + 2.0 * (avg - h)) * 0.995
            h = h + v
            out.append(h.copy())
        spec = np.abs(np.fft.fft2(random_heights(N, 0))) ** 2
        return np.array(out), 0.05, 1 / 60, spec / spec.sum()
    return run


def _webgl_symbol(kx, ky, dx=0.05, dt=1 / 60):
    """Its symbol: a mode's neighbour average is s·h, s = (cos kx dx + cos ky dx)/2, so v' = d v + 2d(s − 1) h and
    h' = h + v'; the eigenvalues z of that map solve z² − (1 + d + 2d(s − 1)) z + d = 0 (d = 0.995), and the mode
    turns at arg(z)/dt (and keeps |z| = √d of its amplitude per step)."""
    d = 0.995
    s = (np.cos(kx * dx) + np.cos(ky * dx)) / 2
    b = 1 + d + 2 * d * (s - 1)
    disc = b * b - 4 * d + 0j
    z = (b + np.sqrt(disc)) / 2
    return np.abs(np.angle(z)) / dt


SIMULATORS = [
    Simulator("Tessendorf FFT ocean, one way downwind (correct)", "Tessendorf's h(k,t) with ω = √(g k) and the "
              "Phillips spectrum masked to k·wind > 0", _fft_sim(omega), _isotropic(omega), dict(sea=True, direction=0.0), {},
              heading=0.0),
    Simulator("looping FFT ocean, ω rounded down to 2π/T, T = 8 s", "Tessendorf's looping ocean: ω quantized to "
              "multiples of ω0 = 2π/T so the sea repeats", _fft_sim(_looped(8.0)), _isotropic(_looped(8.0)), dict(sea=True),
              {"dispersion": "on a lattice"}),
    Simulator("looping FFT ocean, T = 200 s (correct within 2 %)", "the same with a long loop",
              _fft_sim(_looped(200.0)), _isotropic(_looped(200.0)), dict(sea=True), {}),
    Simulator("Phillips spectrum keeping the upwind half", "the one-way mask written k·wind < 0",
              _fft_sim(omega, lambda: np.where(wavenumbers(N, DX)[0] < 0, phillips_h0(N, DX, seed=2, one_way=False),
                                               0.0)), _isotropic(omega), dict(direction=0.0),
              {"direction": "opposite to the claim"},
              heading=180.0),
    Simulator("a sum of sines, every wave at one speed", "GPU Gems' sum of sines with speed a per-wave constant "
              "set the same for all", _gerstner_sum(lambda wavelength: 1.2), _isotropic(lambda k: 1.2 * k), {},
              {"dispersion": "non-dispersive"}),
    Simulator("a sum of sines at ω = √(g 2π/L) (correct)", "GPU Gems' ω = √(g·2π/L), the deep-water relation",
              _gerstner_sum(lambda wavelength: np.sqrt(G * wavelength / (2 * math.pi))), _isotropic(omega), {}, {}),
    Simulator("ω = g·k (a typo for √(g k)) at 15 fps", "omega = g * k", _fft_sim(lambda k: G * k),
              _isotropic(lambda k: G * k), {}, {"dispersion": "c = 9.8"}),
    Simulator("WebGL water, periodic", "Evan Wallace's WebGL Water update", _webgl(), _webgl_symbol, {},
              {"dispersion": "non-dispersive", "energy": "uniform damping"}, gain=lambda kx, ky: 0.995 ** 0.5 + 0 * kx),
]


def pipes_entries():
    """Virtual pipes in a closed pool: non-dispersive at √(g h) where the tank's depth makes water dispersive."""
    run, dx, dt = _pipes_tank(0.3)
    return Simulator("virtual pipes in a closed pool, 0.3 m deep", "O'Brien & Hodgins' virtual pipes, walls as "
                     "closed faces", run, _pipes_symbol(0.3, dx, dt), dict(tank=True, depth=0.3),
                     {"seiche": "one speed c"}, water=dict(sigma=0.0))


SIMULATORS.append(pipes_entries())


def _normal_map(kind):
    """An engine's normal-map bake from the first frame's heights: central or forward differences, packed
    0.5 + 0.5 n and stored in 16 bits."""
    def bake(eta, dx):
        h = eta[0]
        if kind == "central":
            sx = (np.roll(h, -1, 1) - np.roll(h, 1, 1)) / (2 * dx)
            sy = (np.roll(h, -1, 0) - np.roll(h, 1, 0)) / (2 * dx)
        else:
            sx = (np.roll(h, -1, 1) - h) / dx
            sy = (np.roll(h, -1, 0) - h) / dx
        n = np.stack([-sx, -sy, np.ones_like(sx)], -1)
        n /= np.linalg.norm(n, axis=-1, keepdims=True)
        return {"normals": np.round((0.5 + 0.5 * n) * 65535) / 65535}
    return bake


for _kind, _causes in (("central", {}), ("forward", {"normals": "one-sided differences"})):
    SIMULATORS.append(Simulator(f"a normal map baked by {_kind} differences", "engines' normal-map bakes from "
                                "heights", _fft_sim(omega, frames=16), _isotropic(omega), {}, _causes,
                                maps=_normal_map(_kind)))


def truth(sim: Simulator, eta, dx, dt, power, rtol=0.02, energy_rtol=0.01) -> dict:
    """Which checks the scheme must pass, from its symbol alone (module doc)."""
    nt, n, _ = eta.shape
    result = {}
    res = 2 * np.pi / (nt * dt)
    nyq = np.pi / dt
    if sim.claims.get("tank"):
        # the tank's modes (m, q) at k = π √((m/L)² + (q/L)²), the strong ones as the pipes run them
        length = n * dx
        m, q = (a.ravel()[1:] for a in np.meshgrid(np.arange(8), np.arange(8)))
        kx, ky = np.pi * m / length, np.pi * q / length
        theory = omega(np.hypot(kx, ky), depth=sim.claims["depth"], sigma=sim.water.get("sigma", 0.0))
        err = np.abs(sim.symbol(kx, ky) / theory - 1)
        result["seiche"] = bool(np.max(err) <= rtol / 2)
        return result
    kx, ky, k = wavenumbers(n, dx)
    if sim.maps is not None:  # the map against the exact normals of the first frame's heights
        return {"normals": _normals_truth(sim.maps(eta, dx)["normals"], eta[0], kx, ky)}
    w = sim.symbol(kx, ky)
    theory = omega(k, sigma=sim.water.get("sigma", 0.0))
    held = (power > 1e-6 * power.max()) & (k > 0)
    # the modes the frames can show: more than 4 bins from 0, below the Nyquist frequency
    seen = held & (theory > 4 * res) & (theory < nyq - 4 * res)
    aliased = held & (w > nyq - 4 * res)
    result["dispersion"] = bool(np.max(np.abs(w[seen] / theory[seen] - 1)) <= rtol and not aliased.any())
    gain = 1.0 if sim.gain is None else float(np.mean(np.asarray(sim.gain(kx[held], ky[held]))))
    result["energy"] = abs(gain ** (2 * (nt - 1)) - 1.0) <= energy_rtol
    if sim.heading is not None and "direction" in sim.claims:
        result["direction"] = abs((sim.heading - sim.claims["direction"] + 180) % 360 - 180) <= 15
    return result


def _normals_truth(packed, h, kx, ky, tolerance_deg=1.0) -> bool:
    """Whether a packed normal map is, within 1° everywhere, the normals of the heights' slopes: spectral, or the
    texture's own central differences (the two derivatives the check accepts, docs/harness.md)."""
    spec = np.fft.fft2(h)
    dx = np.pi / np.abs(kx).max()
    slopes = [(np.real(np.fft.ifft2(1j * kx * spec)), np.real(np.fft.ifft2(1j * ky * spec))),
              ((np.roll(h, -1, 1) - np.roll(h, 1, 1)) / (2 * dx), (np.roll(h, -1, 0) - np.roll(h, 1, 0)) / (2 * dx))]
    n = 2 * packed - 1
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    for sx, sy in slopes:
        exact = np.stack([-sx, -sy, np.ones_like(sx)], -1)
        exact /= np.linalg.norm(exact, axis=-1, keepdims=True)
        if np.degrees(np.arccos(np.clip(np.sum(n * exact, -1), -1, 1))).max() <= tolerance_deg:
            return True
    return False
