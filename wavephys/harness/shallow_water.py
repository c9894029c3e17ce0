"""A user's shallow-water simulator measured against the exact cases (docs/physics.md §1.13; docs/harness.md).

A record here is a stack of *depth* frames h (m, ≥ 0) on square cells of ``dx``, ``dt`` apart, from any
solver: a game's height-field water, a finite-volume code, virtual pipes. Three checks, each a
:class:`~wavephys.harness.Check` row whose note names the likely cause when it fails:

* :func:`mass_check` — the water's volume Σh·dx² over the frames of a closed domain (walls): it
  must not change beyond rounding;
* :func:`lake_at_rest_check` — a lake at rest over an uneven bed must stay at rest: the surface
  b + h of every wet cell must not move;
* :func:`dam_break_check` — a dam released at rest (depth h₀ behind it, dry or h_r ahead): the
  front must run at Ritter's 2√(gh₀) (on a dry bed, measured where h = 1 % of h₀) or the bore at
  Stoker's speed (on a wet bed).
"""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.inputs import check_array, check_scalar

__all__ = ["mass_check", "lake_at_rest_check", "dam_break_check", "shoreline_elevation"]


def _frames(name, depth):
    check_array(name, depth, lo=0.0)
    h = np.asarray(depth, np.float64)
    if h.ndim == 2:
        h = h[:, None, :]
    if h.ndim != 3 or h.shape[0] < 2:
        raise ValueError(f"{name} must be frames (t, y, x) or (t, x) with at least 2 frames, got shape {np.shape(depth)}")
    return h


def mass_check(depth, dx: float, *, rtol: float = 1e-5):
    """The largest relative change of the water's volume over the frames (a closed domain).

    Parameters
    ----------
    depth : array_like (t, y, x) or (t, x)
        Depth frames, m, ≥ 0, of a domain nothing flows into or out of.
    dx : float
        Cell size, m, > 0.
    rtol : float, optional, keyword-only
        Largest relative change (default 1e-5: float32 rounding over thousands of steps).

    Returns
    -------
    Check
        A ``"<="`` row; on failure the note says whether water was gained or lost, and when.
    """
    from wavephys.harness.checks import bound

    h = _frames("depth", depth)
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    check_scalar("rtol", rtol, lo=0.0, lo_open=True)
    volume = h.sum(axis=(1, 2)) * dx * dx
    if not volume[0] > 0:
        raise ValueError("depth: the first frame holds no water")
    change = volume / volume[0] - 1
    worst = int(np.argmax(np.abs(change)))
    note = f"volume {volume[0]:.6g} m^3 at the first frame, {volume[-1]:.6g} m^3 at the last"
    if abs(change[worst]) > rtol:
        if change[worst] > 0:
            cause = ("water gained: negative depths clipped to zero (a step past its stable Courant number, or no "
                     "outflow limit), or an inflow at a side that should be closed")
        else:
            cause = ("water lost: a side that leaks (an open or absorbing edge), water removed where it is thin (a "
                     "dry threshold that zeroes small depths), or evaporation/damping on the depth")
        note = f"{note}; {cause} (largest change at frame {worst})"
    return bound("relative change of the water's volume over the frames", abs(change[worst]), rtol, note=note)


def lake_at_rest_check(depth, bed, dx: float, *, atol: float | None = None):
    """A lake at rest over an uneven bed stays at rest: the largest movement of the surface b + h of the cells wet
    at the first frame, and any water appearing on dry land.

    Parameters
    ----------
    depth : array_like (t, y, x) or (t, x)
        Depth frames, m, of water started at rest with a flat surface (islands may stand out of it).
    bed : array_like (y, x) or (x,)
        Bed elevation, m.
    dx : float
        Cell size, m, > 0 (used in the note).
    atol : float, optional, keyword-only
        Largest movement of the surface, m (default 1e-5 × the deepest water: float32 rounding).

    Returns
    -------
    Check
        A ``"<="`` row in m; on failure the note names where the surface moved most: over steep bed slopes
        (a scheme that is not well balanced: the pressure gradient and the bed's slope discretized apart), at
        the shoreline (the wet/dry treatment), or on dry land (water appearing).
    """
    from wavephys.harness.checks import bound

    h = _frames("depth", depth)
    check_scalar("dx", dx, lo=0.0, lo_open=True)
    check_array("bed", bed)
    b = np.asarray(bed, np.float64)
    if b.ndim == 1:
        b = b[None, :]
    if b.shape != h.shape[1:]:
        raise ValueError(f"bed must have the frames' shape {h.shape[1:]}, got {np.shape(bed)}")
    deepest = float(h[0].max())
    if not deepest > 0:
        raise ValueError("depth: the first frame holds no water")
    atol = 1e-5 * deepest if atol is None else check_scalar("atol", atol, lo=0.0, lo_open=True)
    wet = h[0] > 1e-9 * deepest
    eta = h + b
    level = float(np.median(eta[0][wet]))
    if np.abs(eta[0][wet] - level).max() > max(atol, 1e-9 * deepest) * 10:
        raise ValueError("depth: the first frame is not a lake at rest (its surface b + h is not flat where wet)")
    moved = np.abs(eta[:, wet] - eta[0][wet]).max(axis=0)
    worst = float(moved.max())
    flooded = int(np.sum((h[:, ~wet] > 1e-6 * deepest).any(axis=0)))
    note = f"{int(wet.sum())} wet cells, {int((~wet).sum())} dry at the start"
    measured = worst
    if flooded:
        measured = max(worst, float(h[:, ~wet].max()))
    if measured > atol:
        gx = np.gradient(b, dx, axis=-1) if b.shape[-1] > 1 else np.zeros_like(b)
        gy = np.gradient(b, dx, axis=0) if b.shape[0] > 1 else np.zeros_like(b)
        slope = np.hypot(gx, gy)[wet]
        near_dry = np.zeros_like(wet)
        near_dry[:, 1:] |= ~wet[:, :-1]
        near_dry[:, :-1] |= ~wet[:, 1:]
        if wet.shape[0] > 1:
            near_dry[1:] |= ~wet[:-1]
            near_dry[:-1] |= ~wet[1:]
        causes = []
        inner = ~near_dry[wet]
        if inner.any() and float(moved[inner].max()) > atol:
            where = int(np.flatnonzero(inner)[np.argmax(moved[inner])])
            steep = slope[where] >= np.percentile(slope, 75)
            causes.append("the surface moved away from the shore, most over " + ("steep" if steep else "uneven")
                          + " bed: the scheme is not well balanced (the pressure gradient and the bed's slope "
                          "discretized apart; a hydrostatic reconstruction or a balanced source term keeps a lake "
                          "at rest)")
        if flooded:
            causes.append(f"water appeared on {flooded} dry cells: the shoreline at rest leaks (the wet/dry treatment)")
        elif not causes:
            causes.append("the surface moved at the shoreline only: the wet/dry treatment is not at rest")
        cause = "; ".join(causes)
        note = f"{note}; {cause}"
    return bound("largest movement of a lake at rest's surface", measured, atol, unit="m", note=note)


def dam_break_check(depth, dx: float, dt: float, h0: float, *, dam: float, hr: float = 0.0, t0: float = 0.0,
                    g: float = 9.81, rtol: float = 0.05):
    """The speed of a dam break's front (dry bed: where h = 1 % of h₀) or bore (wet bed: where h is halfway between
    Stoker's middle depth and h_r) against the exact one, fitted over the frames where it has left the dam.

    Parameters
    ----------
    depth : array_like (t, y, x) or (t, x)
        Depth frames, m, of water at rest released at ``t0`` (the first frame's time after release, s): depth
        ``h0`` for x < ``dam``, ``hr`` beyond, a flat bed, the front running towards +x (rows averaged).
    dx, dt : float
        Cell size (m) and time between frames (s), > 0.
    h0 : float
        Depth behind the dam, m, > 0.
    dam : float, keyword-only
        The dam's position, m, from the left edge of the frames (cell j's centre is at (j + ½)·dx).
    hr : float, keyword-only
        Depth ahead of the dam, m (0: a dry bed; else below h0).
    t0 : float, keyword-only
        s, ≥ 0.
    g : float, keyword-only
        m/s².
    rtol : float, keyword-only
        Largest relative error of the speed (default 0.05).

    Returns
    -------
    Check
        A ``"~="`` row of the fitted speed, m/s; the note gives the rarefaction's head speed (where h = 0.99 h₀,
        a smooth part of the flow) against its exact one, and on failure the likely cause: the whole flow, head
        too, off by one factor (g or the frame time); a front at 0.15–0.75 of the exact speed with the head right
        (no momentum carried, as in virtual pipes or a linear wave equation); a front that lags a few per cent
        (numerical friction, a dry threshold, coarse cells: it converges with finer ones); a front that does not
        move (water kept off dry cells).

    References
    ----------
    A. Ritter (1892); J. J. Stoker (1957), *Water Waves* §10.8.
    """
    from wavephys.harness.checks import compare
    from wavephys.physics.shallow_water import stoker_middle

    h = _frames("depth", depth).mean(axis=1)
    for name, v in (("dx", dx), ("dt", dt), ("h0", h0), ("g", g), ("rtol", rtol)):
        check_scalar(name, v, lo=0.0, lo_open=True)
    check_scalar("dam", dam)
    check_scalar("hr", hr, lo=0.0)
    check_scalar("t0", t0, lo=0.0)
    if not hr < h0:
        raise ValueError(f"hr must be below h0 (the front runs into the shallower side), got hr={hr}, h0={h0}")
    nt, nx = h.shape
    x = (np.arange(nx) + 0.5) * dx
    if hr == 0:
        level = 0.01 * h0
        speed = 2 * math.sqrt(g * h0) * (1 - 1.5 * math.sqrt(0.01))
        what = "Ritter's front (h = 1 % of h0)"
    else:
        hm, _, s = stoker_middle(h0, hr, g)
        level, speed = 0.5 * (hm + hr), s
        what = "Stoker's bore"
    times, fronts = [], []
    for i in range(nt):
        above = np.nonzero(h[i] > level)[0]
        if above.size == 0 or above.max() >= nx - 1:
            continue
        j = above.max()
        pos = x[j] + dx * (h[i, j] - level) / (h[i, j] - h[i, j + 1])
        t = t0 + i * dt
        if t > 0 and pos - dam > 3 * dx and dam + speed * t < x[-1] - 3 * dx:
            times.append(t)
            fronts.append(pos)
    if len(times) < 3:
        raise ValueError(f"depth, dt, t0: fewer than 3 frames (frame i at t0 + i*dt = {t0} + i*{dt} s) show the "
                         f"front between the dam and the domain's end ({len(times)}); give more frames, a longer "
                         f"domain, or check dam and h0")
    fitted = float(np.polyfit(times, fronts, 1)[0])
    ratio = fitted / speed
    # the rarefaction's head runs back into the still water at 2 c0 (1 - 1.5 sqrt(0.99)) where h = 0.99 h0: a smooth
    # part of the flow that any consistent solver gets right, unless g (or the frame time) is off
    heads = []
    for i in [int(round((t - t0) / dt)) for t in times]:
        below = np.nonzero(h[i] < 0.99 * h0)[0]
        if below.size and below.min() > 0:
            j = below.min()
            heads.append((t0 + i * dt, x[j - 1] + dx * (h[i, j - 1] - 0.99 * h0) / (h[i, j - 1] - h[i, j])))
    head_ratio = math.nan
    if len(heads) >= 3:
        head_speed = 2 * math.sqrt(g * h0) * (1 - 1.5 * math.sqrt(0.99))
        head_ratio = float(np.polyfit(*zip(*heads), 1)[0]) / head_speed
    note = (f"{what}: fitted over {len(times)} frames from t = {times[0]:.3g} s to {times[-1]:.3g} s; the "
            f"rarefaction's head at {head_ratio:.3g}x its exact speed")
    if abs(ratio - 1) > rtol:
        if abs(fitted) < 0.05 * speed:
            cause = "the front does not move: water is kept off dry cells (a wet/dry threshold or clamp that blocks it)"
        elif abs(head_ratio - ratio) < 0.5 * abs(ratio - 1) and abs(head_ratio - 1) > rtol:
            cause = (f"the whole flow runs {ratio:.3g}x the exact speed (the rarefaction's head too): check g "
                     f"({g} m/s^2 here) and the time between frames (dt = {dt} s here); speeds go as sqrt(g)")
        elif 0.15 < ratio < 0.75:
            cause = ("the front runs at a fraction of the exact speed: no momentum is carried (virtual pipes, a "
                     "linear wave equation or a height-field model without u·grad u)")
        elif 0.75 <= ratio < 1 - rtol:
            cause = ("the front lags: numerical friction or damping of the velocity, or a dry threshold that holds "
                     "the thin tip back (it converges with finer cells in a consistent solver)")
        else:
            cause = (f"the front runs {ratio:.3g}x the exact speed: check g ({g} m/s^2 here) and the time between "
                     f"frames (dt = {dt} s here); the speed goes as sqrt(g)")
        note = f"{note}; {cause}"
    return compare(f"speed of {what}", fitted, speed, rtol=rtol, unit="m/s", note=note)


def shoreline_elevation(depth, bed, *, threshold: float = 1e-4, sea: str = "right"):
    """The shoreline's elevation in each frame of a 1-D run-up: the surface at the landward end of the water
    that is connected to the sea, m.

    Read from the sea inwards, the shoreline is the last cell deeper than ``threshold`` before the first one that
    is not: a film or puddle left up the beach by the run-down (a few 1e-4 m, draining slowly) is not the
    shoreline. (Taking the most landward wet cell instead follows such a film and then drops all at once when
    it dries: 0.039 d to −0.0006 d at t = 23.2 s for a 0.01 d wave on a 1:19.85 beach.)

    Parameters
    ----------
    depth : array_like (T, n)
        Water depth along the profile in each frame, m, ≥ 0.
    bed : array_like (n,)
        Bed elevation, m.
    threshold : float
        Depth above which a cell is water, m, > 0.
    sea : {"right", "left"}
        Which end of the profile is the sea.

    Returns
    -------
    numpy.ndarray (T,)
        m (the sea's edge cell's surface when the whole profile is water).

    Raises
    ------
    ValueError
        When the sea's edge cell holds no more than ``threshold`` in a frame.

    Examples
    --------
    >>> import numpy as np
    >>> bed = np.linspace(0.5, -1.0, 7)           # land on the left, the sea on the right
    >>> depth = np.maximum(-bed, 0.0)[None]
    >>> depth[0, 1] = 0.01                          # a puddle up the beach
    >>> float(shoreline_elevation(depth, bed)[0])
    0.0
    """
    depth = np.asarray(check_array("depth", depth, ndim=2, lo=0.0), np.float64)
    bed = np.asarray(check_array("bed", bed, ndim=1, shape_tail=depth.shape[1:]), np.float64)
    check_scalar("threshold", threshold, lo=0.0, lo_open=True)
    if sea not in ("right", "left"):
        raise ValueError(f"sea must be 'right' or 'left', got {sea!r}")
    if sea == "left":
        depth, bed = depth[:, ::-1], bed[::-1]
    wet = depth > threshold
    if not np.all(wet[:, -1]):
        frame = int(np.nonzero(~wet[:, -1])[0][0])
        raise ValueError(f"depth: the sea's edge cell ({sea} end) holds no more than threshold = {threshold:g} m in "
                         f"frame {frame}: there is no water joined to the sea to read a shoreline from")
    out = np.empty(depth.shape[0])
    for i, row in enumerate(wet):
        dry = np.nonzero(~row)[0]
        last = dry.max() + 1 if dry.size else 0  # the landward end of the water joined to the sea
        out[i] = depth[i, last] + bed[last]
    return out
