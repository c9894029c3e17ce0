"""A corpus of water simulators written the way engines write them: correct ones, and real
techniques and real bugs. Each returns what an engine would export (frames, and sometimes
normals, caustics or a second resolution); tests/harness/test_corpus.py holds the verdict
and the cause the harness must give for each.

Everything is numpy, small (64² texels, a few hundred frames) and seeded.
"""

from __future__ import annotations

import math

import numpy as np

G = 9.81
N = 64


def wavenumbers(n, dx):
    k1 = 2 * np.pi * np.fft.fftfreq(n, dx)
    kx, ky = np.meshgrid(k1, k1)
    return kx, ky, np.hypot(kx, ky)


def omega(k, depth=math.inf, sigma=0.0, g=G, rho=1000.0):
    t = np.tanh(k * depth) if math.isfinite(depth) else 1.0
    return np.sqrt((g * k + sigma / rho * k**3) * t)


def minus_k(a):
    """a(-k) on numpy's FFT grid."""
    return np.roll(np.flip(a, (0, 1)), 1, (0, 1))


def strip_h0(ny, nx, dx, rng, heading):
    """A one-way wind sea on an (n_y, n_x) grid (a strip when n_y != n_x): Phillips' spectrum for a 2 m/s wind
    along ``heading`` (radians), rms height about 1 cm; h0 per mode, numpy's FFT order."""
    kx = 2 * np.pi * np.fft.fftfreq(nx, dx)[None, :]
    ky = 2 * np.pi * np.fft.fftfreq(ny, dx)[:, None]
    ks = np.maximum(np.hypot(kx, ky), 1e-9)
    along = (kx * math.cos(heading) + ky * math.sin(heading)) / ks
    p = np.exp(-1 / (ks * 4 / G) ** 2) / ks ** 4 * np.maximum(along, 0) ** 2 * np.exp(-(ks * dx) ** 2)
    p[0, 0] = 0.0
    h = (rng.standard_normal((ny, nx)) + 1j * rng.standard_normal((ny, nx))) * np.sqrt(p / 2)
    return h * 0.01 / np.sqrt(np.sum(np.abs(h) ** 2))


def strip_frames(h0, dx, dt, omega_of_k, nt=128, standing=False):
    """η(t) = Re ifft(h0 e^{−iωt} + conj(h0(−k)) e^{iωt}) on h0's (n_y, n_x) grid, ω = ``omega_of_k(|k|)``
    (``standing``: both halves turning alike, the classic bug)."""
    ny, nx = h0.shape
    k = np.hypot(2 * np.pi * np.fft.fftfreq(nx, dx)[None, :], 2 * np.pi * np.fft.fftfreq(ny, dx)[:, None])
    w, h0m = omega_of_k(k), np.conj(minus_k(h0))
    t = np.arange(nt)[:, None, None] * dt
    spec = (h0 + h0m) * np.cos(w * t) if standing else h0 * np.exp(-1j * w * t) + h0m * np.exp(1j * w * t)
    return np.real(np.fft.ifft2(spec, axes=(1, 2))) * nx * ny


def phillips_h0(n, dx, wind=(1.0, 0.0), speed=2.0, seed=0, one_way=True, normalize=True, cutoff=None):
    """Tessendorf's h0(k) = (xi_r + i xi_i) sqrt(P(k)/2), Phillips spectrum, small-wave cutoff.

    ``one_way`` keeps only k . wind > 0 (a sea that runs downwind); ``normalize`` scales by the grid
    (the spectrum is a density: amplitude per mode ~ sqrt(P dk^2), and the FFT's n^2); ``cutoff`` (m, default
    one texel) is the small-wave cutoff length."""
    rng = np.random.default_rng(seed)
    kx, ky, k = wavenumbers(n, dx)
    w = np.asarray(wind, float) / np.hypot(*wind)
    big_l = speed**2 / G
    ks = np.maximum(k, 1e-9)
    p = np.exp(-1.0 / (ks * big_l) ** 2) / ks**4 * ((kx * w[0] + ky * w[1]) / ks) ** 2 * np.exp(-(ks * (dx if cutoff is None else cutoff)) ** 2)
    p[0, 0] = 0.0
    if one_way:
        p = np.where(kx * w[0] + ky * w[1] > 0, p, 0.0)
    dk = 2 * np.pi / (n * dx)
    amp = np.sqrt(p * dk * dk) * n * n if normalize else np.sqrt(p)
    xi = rng.standard_normal((2, n, n))
    h0 = (xi[0] + 1j * xi[1]) * amp / math.sqrt(2)
    return 0.05 * h0 if normalize else 0.05e-3 * h0  # about 2 cm rms at n = 64 (normalized)


def fft_ocean(h0, dx, dt, frames, sign=-1, standing=False, depth=math.inf, sigma=0.0, t_start=0.0):
    """h(k, t) = h0(k) e^{sign i w t} + conj(h0(-k)) e^{-sign i w t} (a wave along +k for sign = -1 here)."""
    n = h0.shape[0]
    _, _, k = wavenumbers(n, dx)
    w = omega(k, depth, sigma)
    h0m = np.conj(minus_k(h0))
    out = []
    for i in range(frames):
        t = t_start + i * dt
        if standing:  # the classic bug: both halves of the spectrum turning the same way
            hk = (h0 + h0m) * np.cos(w * t)
        else:
            hk = h0 * np.exp(sign * 1j * w * t) + h0m * np.exp(-sign * 1j * w * t)
        out.append(np.real(np.fft.ifft2(hk)))
    return np.array(out)


def spectral_model(eta0, dx, dt, frames, *, depth=math.inf, sigma=0.0, velocity_factor=1.0, smoothing=0.0,
                   substeps=1, g=G):
    """An exact linear step per frame in Fourier space (heights and rates), with the damping bugs engines add:
    ``velocity_factor`` multiplies eta_dot each step; ``smoothing`` nu multiplies both by exp(-nu k^2 dt)."""
    n = eta0.shape[0]
    _, _, k = wavenumbers(n, dx)
    w = omega(k, depth, sigma, g)
    eh, vh = np.fft.fft2(eta0), np.zeros((n, n), complex)
    h = dt / substeps
    c, s = np.cos(w * h), np.sin(w * h)
    ws = np.where(w > 0, w, 1.0)
    out, rates = [], []
    for _ in range(frames):
        out.append(np.real(np.fft.ifft2(eh)))
        rates.append(np.real(np.fft.ifft2(vh)))
        for _ in range(substeps):
            eh, vh = eh * c + vh * np.where(w > 0, s / ws, h), -eh * w * s + vh * c
            vh = vh * velocity_factor
            if smoothing:
                f = np.exp(-smoothing * k**2 * h)
                eh, vh = eh * f, vh * f
    return np.array(out), np.array(rates)


def random_heights(n, seed=0, k_cut=0.35, amplitude=1e-3):
    """Band-limited random heights (a disturbance that excites many wavelengths)."""
    rng = np.random.default_rng(seed)
    _, _, k = wavenumbers(n, 1.0)
    spec = np.fft.fft2(rng.standard_normal((n, n))) * np.exp(-(k / (k_cut * np.pi)) ** 2)
    eta = np.real(np.fft.ifft2(spec))
    return amplitude * eta / eta.std()


def webgl_water(n=N, frames=256, seed=0, clamp=False):
    """Evan Wallace's WebGL Water update: average of 4 neighbours, velocity += (avg - h) * 2, *= 0.995.
    ``clamp`` reads the texture with CLAMP_TO_EDGE, as the demo does (a neighbour past the edge is the edge)."""
    height = random_heights(n, seed)
    velocity = np.zeros((n, n))
    out = []
    for _ in range(frames):
        if clamp:
            p = np.pad(height, 1, mode="edge")
            average = 0.25 * (p[:-2, 1:-1] + p[2:, 1:-1] + p[1:-1, :-2] + p[1:-1, 2:])
        else:
            average = 0.25 * (np.roll(height, 1, 0) + np.roll(height, -1, 0) + np.roll(height, 1, 1)
                              + np.roll(height, -1, 1))
        velocity = (velocity + 2.0 * (average - height)) * 0.995
        height = height + velocity
        out.append(height.copy())
    return np.array(out)


def iwave(n=N, frames=256, seed=0, dt=0.03, alpha=0.3, gravity=9.8, kernel_radius=6):
    """Tessendorf's iWave (2004): the vertical derivative as a truncated convolution kernel normalized to
    G(0) = 1, and a damping term alpha; grid units (dx = 1)."""
    from scipy.special import j0

    q = np.arange(1, 10001) * 0.001
    r = np.hypot(*np.meshgrid(np.arange(-kernel_radius, kernel_radius + 1),
                              np.arange(-kernel_radius, kernel_radius + 1)))
    kernel = np.array([[np.sum(q * q * np.exp(-q * q) * j0(q * rr)) for rr in row] for row in r])
    kernel /= kernel[kernel_radius, kernel_radius]
    full = np.zeros((n, n))
    for i in range(-kernel_radius, kernel_radius + 1):
        for j in range(-kernel_radius, kernel_radius + 1):
            full[i % n, j % n] = kernel[i + kernel_radius, j + kernel_radius]
    symbol = np.real(np.fft.fft2(full))
    h = random_heights(n, seed, k_cut=0.2)
    prev = h.copy()
    out = []
    for _ in range(frames):
        vd = np.real(np.fft.ifft2(np.fft.fft2(h) * symbol))
        new = (h * (2 - alpha * dt) - prev - gravity * dt * dt * vd) / (1 + alpha * dt)
        prev, h = h, new
        out.append(h.copy())
    return np.array(out), dt


def gaussian_bump(n, dx, radius, centre=(0.0, 0.0), amplitude=1e-3):
    c = -0.5 * n * dx + (np.arange(n) + 0.5) * dx
    x, y = np.meshgrid(c - centre[0], c - centre[1])
    return amplitude * np.exp(-(x * x + y * y) / radius**2)


def packet(n, dx, k0, width, direction=0.0):
    c = -0.5 * n * dx + (np.arange(n) + 0.5) * dx
    x, y = np.meshgrid(c, c)
    u = x * math.cos(direction) + y * math.sin(direction)
    return 1e-3 * np.exp(-(x * x + y * y) / width**2) * np.cos(k0 * u), 1e-3 * np.exp(-(x * x + y * y) / width**2)


def travelling_packet(n, dx, dt, frames, k0, width, wave_equation_speed=None):
    """A Gaussian packet launched along +x: eta_hat(k, t) = a(k) e^{-i w t} for k_x > 0 (one way)."""
    eta0, _ = packet(n, dx, k0, width)
    kx, _, k = wavenumbers(n, dx)
    w = omega(k) if wave_equation_speed is None else wave_equation_speed * k
    spec = np.fft.fft2(eta0) * 2 * (kx > 0)
    return np.array([np.real(np.fft.ifft2(spec * np.exp(-1j * w * i * dt))) for i in range(frames)])


def normals_from_heights(eta, dx, green=1.0, strength=1.0):
    """An engine's normal map: central differences, n = normalize(-s dh/dx, -s dh/dy, 1), packed 0.5 + 0.5 n."""
    sx = (np.roll(eta, -1, 1) - np.roll(eta, 1, 1)) / (2 * dx) * strength
    sy = (np.roll(eta, -1, 0) - np.roll(eta, 1, 0)) / (2 * dx) * strength
    n = np.stack([-sx, -green * sy, np.ones_like(sx)], -1)
    n /= np.linalg.norm(n, axis=-1, keepdims=True)
    return np.round((0.5 + 0.5 * n) * 255) / 255


def steady_wake_engine(n, dx, speed, size, wave_speed=None, depth=math.inf, damping=None, g=G):
    """A steady wake as an engine computes it in the ship's frame: per mode, psi = -p/rho / (i (w - kx U) + eps),
    eta = i (K/w) psi, K = k tanh(kh); ``wave_speed`` c replaces w(k) by c k (a non-dispersive wave equation)."""
    kx, _, k = wavenumbers(n, dx)
    c = -0.5 * n * dx + (np.arange(n) + 0.5) * dx
    x, y = np.meshgrid(c, c)
    p = 100.0 * np.exp(-(x * x + y * y) / (2 * size * size))
    p_hat = np.fft.fft2(np.fft.ifftshift(p))
    big_k = k * (np.tanh(k * depth) if math.isfinite(depth) else 1.0)
    w = wave_speed * k if wave_speed is not None else np.sqrt(g * big_k)
    eps = 2.0 * speed / (n * dx) if damping is None else damping
    psi = (-p_hat / 1000.0) / (1j * (w - kx * speed) + eps)
    eta_hat = 1j * np.where(w > 0, big_k / np.where(w > 0, w, 1.0), 0.0) * psi
    return np.fft.fftshift(np.real(np.fft.ifft2(eta_hat)))
