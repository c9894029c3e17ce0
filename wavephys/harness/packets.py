"""How fast energy travels: the group velocity of a packet and the arrival of ring waves.

* :func:`group_velocity_check` — the centroid of a packet's energy (η², its circular mean
  on the periodic grid, unwrapped in time) moves at the power-weighted mean of the
  components' group velocities c_g(k)·k̂, exactly, for linear waves; the check fits the
  centroid's speed along the direction of travel and compares it with that mean, computed
  from the record's own spectrum and theory's c_g.
* :func:`ring_arrival_check` — behind the first ring of a point disturbance, the disc
  r < c_g,min·(t − t₀) stays calm: no wave of the water is slower than the minimum group
  speed (0.178 m/s for clean water; on a grid without surface tension, the group speed of
  its shortest wave). The check measures the share of η² inside that disc, shrunk by the
  source's radius.
"""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.inputs import check_array, check_instance, check_scalar
from wavephys.core.spectral import angular_wavenumbers
from wavephys.core.water import Water

__all__ = ["group_velocity_check", "ring_arrival_check", "minimum_group_speed"]


def _group_speed(k, water: Water) -> np.ndarray:
    import jax

    from wavephys.physics.dispersion import group_speed

    with jax.enable_x64(True):
        import jax.numpy as jnp

        return np.asarray(group_speed(jnp.asarray(np.maximum(k, 1e-12), jnp.float64), water), np.float64)


def minimum_group_speed(water: Water, k_max: float, k_min: float = 0.0) -> float:
    """The smallest group speed of ``water``'s waves with k_min < k ≤ k_max, m/s.

    Parameters
    ----------
    water : Water
        The water (g, σ, depth).
    k_max : float
        Largest wavenumber, rad/m, > 0 (a grid's √2·π/Δx).
    k_min : float, optional
        Smallest wavenumber, rad/m, in [0, k_max) (default 0).

    Returns
    -------
    float
        min c_g over the band, m/s.
    """
    check_instance("water", water, Water, "wavephys.Water")
    from wavephys.physics.dispersion import K_MAX

    check_scalar("k_max", k_max, lo=0.0, hi=K_MAX, lo_open=True)
    check_scalar("k_min", k_min, lo=0.0, hi=k_max)
    k = np.geomspace(max(k_min, k_max * 1e-4), k_max, 4096)
    return float(_group_speed(k, water).min())


def group_velocity_check(record, water: Water, *, rtol: float = 0.05, direction=None):
    """A :class:`~wavephys.harness.Check` of a packet's energy speed against theory's group velocity.

    Parameters
    ----------
    record : Record
        Frames of one wave packet (:class:`wavephys.harness.Record`) that stays on the grid's torus.
    water : Water
        The water whose c_g(k) is the theory.
    rtol : float, optional, keyword-only
        Allowed relative error of the speed, > 0 (default 0.05).
    direction : float, optional, keyword-only
        Direction of travel, degrees (0 = +x); default: the record's measured mean direction.

    Returns
    -------
    Check
        A ``"~="`` row of the centroid's speed (m/s) against the power-weighted mean group velocity along the
        direction of travel; on failure its note compares it with the phase speed (a scheme whose energy moves
        at the phase speed is not dispersive).
    """
    from wavephys.harness.checks import compare
    from wavephys.harness.record import Record
    from wavephys.harness.travel import measure_travel

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_instance("water", water, Water, "wavephys.Water")
    check_scalar("rtol", rtol, lo=0.0, lo_open=True)
    if direction is None:
        direction = measure_travel(record.eta, record.dx, record.dt, locking=False,
                                   spectrum=record.spectrum()).direction
    check_scalar("direction", direction)
    u = np.array([math.cos(math.radians(direction)), math.sin(math.radians(direction))])
    eta = record.eta - record.eta.mean(axis=0)
    nt, ny, nx = eta.shape
    # theory: the mean of c_g(k) k_hat . u over the wave components travelling along +k (numpy: e^{-i w t})
    spec = record.spectrum()  # the frames less their mean, Hann in time, FFT in x, y, t
    f = np.fft.fftfreq(nt)
    along = np.sum(np.abs(spec[f < 0].astype(np.complex128)) ** 2, axis=0)
    ky, kx = angular_wavenumbers((ny, nx), record.dx, xp=np)
    kx, ky = np.broadcast_to(kx, (ny, nx)), np.broadcast_to(ky, (ny, nx))
    k = np.hypot(kx, ky)
    cg = np.where(k > 0, _group_speed(k, water) * (kx * u[0] + ky * u[1]) / np.maximum(k, 1e-300), 0.0)
    expected = float(np.sum(along * cg) / np.sum(along))
    k_mean = float(np.sum(along * k) / np.sum(along))
    # measured: the circular mean of eta^2 along u, unwrapped
    x = (np.arange(nx) + 0.5) * record.dx
    y = (np.arange(ny) + 0.5) * record.dx
    e = eta**2
    cx = np.unwrap(np.angle(np.sum(e * np.exp(2j * np.pi * x / (nx * record.dx)), axis=(1, 2))))
    cy = np.unwrap(np.angle(np.sum(e * np.exp(2j * np.pi * y[:, None] / (ny * record.dx)), axis=(1, 2))))
    px, py = cx * nx * record.dx / (2 * np.pi), cy * ny * record.dx / (2 * np.pi)
    t = np.arange(nt) * record.dt
    speed = float(np.polyfit(t, px * u[0] + py * u[1], 1)[0])
    from wavephys.physics.dispersion import phase_speed

    c = float(np.asarray(phase_speed(np.float32(k_mean), water)))
    note = (f"direction {direction:.1f} deg; power-weighted mean k {k_mean:.4g} rad/m; phase speed there {c:.4g} "
            f"m/s; over {record.duration:.4g} s")
    row = compare("speed of the packet's energy centroid", speed, expected, rtol=rtol, unit="m/s", note=note)
    if not row.ok and abs(speed - c) < abs(speed - expected):
        row = compare(row.quantity, speed, expected, rtol=rtol, unit="m/s",
                      note=f"{note}; likely cause: the energy moves at the phase speed, not the group speed: "
                           f"no dispersion (a wave equation)")
    return row


def ring_arrival_check(record, water: Water, *, source=(0.0, 0.0), t0: float = 0.0, radius: float = 0.0,
                       max_share: float = 0.02):
    """A :class:`~wavephys.harness.Check` that the disc behind the first ring stays calm.

    Parameters
    ----------
    record : Record
        Frames of ring waves from one disturbance (:class:`wavephys.harness.Record`), before they wrap around.
    water : Water
        The water whose minimum group speed sets the calm disc.
    source : (float, float), optional, keyword-only
        Where the disturbance was, m, in the grid convention (the grid centred on 0; default (0, 0)).
    t0 : float, optional, keyword-only
        When it happened, s from the first frame (default 0; may be negative).
    radius : float, optional, keyword-only
        The disturbance's radius, m, >= 0 (default 0): the disc is shrunk by it.
    max_share : float, optional, keyword-only
        Largest share of η² allowed inside the disc, in (0, 1) (default 0.02).

    Returns
    -------
    Check
        A ``"<="`` row of the largest share over the frames whose disc is at least 3 texels wide and whose
        fastest waves have not wrapped around; on failure the note names the likely cause.
    """
    from wavephys.harness.checks import bound
    from wavephys.harness.record import Record

    check_instance("record", record, Record, "wavephys.harness.Record")
    check_instance("water", water, Water, "wavephys.Water")
    check_array("source", source, ndim=1, shape_tail=(2,))
    check_scalar("t0", t0)
    check_scalar("radius", radius, lo=0.0)
    check_scalar("max_share", max_share, lo=0.0, hi=1.0, lo_open=True, hi_open=True)
    nt, ny, nx = record.shape
    dx = record.dx
    c_min = minimum_group_speed(water, math.sqrt(2) * math.pi / dx, 2 * math.pi / (max(nx, ny) * dx))
    x = -0.5 * nx * dx + (np.arange(nx) + 0.5) * dx - float(source[0])
    y = -0.5 * ny * dx + (np.arange(ny) + 0.5) * dx - float(source[1])
    r = np.hypot(x[None, :], y[:, None])
    eta = record.eta - record.eta[0].mean()
    shares, used = [], 0
    half = 0.5 * min(nx, ny) * dx
    for i in range(nt):
        t = i * record.dt - t0
        disc = c_min * t - radius
        if disc < 3 * dx or disc > half:
            continue
        e = eta[i] ** 2
        shares.append(float(e[r < disc].sum() / max(e.sum(), 1e-300)))
        used += 1
    if not used:
        return bound("frames with a calm disc to measure", 0, 1, relation=">=",
                     note=f"c_g,min = {c_min:.4g} m/s: the disc is under 3 texels or past the grid's half-width in "
                          f"every frame; record longer, or from earlier")
    worst = max(shares)
    note = f"c_g,min = {c_min:.4g} m/s; {used} frames; disc radius up to {c_min * ((nt - 1) * record.dt - t0) - radius:.3g} m"
    row = bound("share of eta^2 inside r < c_g,min (t - t0)", worst, max_share, note=note)
    if not row.ok:
        row = bound(row.quantity, worst, max_share,
                    note=f"{note}; likely cause: waves slower than c_g,min stay behind the first ring: the short "
                         f"waves are too slow (surface tension missing or too weak, or a scheme whose group speed "
                         f"falls at short wavelengths, as finite differences' does)")
    return row
