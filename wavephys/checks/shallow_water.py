"""Validations of nonlinear shallow water and the virtual pipes against exact solutions (docs/physics.md
§§1.13–1.14): each function runs one case and returns its errors, so the tests (over families of cases),
``wavephys validate`` and ``python -m bench shallow`` measure the same thing.

Errors are reported in the max norm and in L1 (the mean absolute error over the domain's cells), in
metres of depth unless said otherwise.
"""

from __future__ import annotations

import math

import numpy as np

from wavephys.core.inputs import check_int, check_scalar
from wavephys.harness.checks import Check, bound

__all__ = ["dam_break_errors", "thacker_errors", "lake_at_rest", "carrier_greenspan_errors", "solitary_runup_run",
           "RUNUP_MODELS",
           "pipes_seiche", "pipes_dam_break", "convergence_order", "check_shallow_water"]

G = 9.81


def _dtype(name):
    import jax.numpy as jnp

    return {"float32": jnp.float32, "float64": jnp.float64}[name]


def convergence_order(errors, sizes) -> float:
    """Least-squares slope of −log(error) against log(n): the observed order of convergence.

    Parameters
    ----------
    errors : array_like
        Positive errors, one per size.
    sizes : array_like
        Cells (per side), same length.

    Returns
    -------
    float
    """
    e, n = np.log(np.asarray(errors, float)), np.log(np.asarray(sizes, float))
    return float(-np.polyfit(n, e, 1)[0])


def dam_break_errors(n: int, hl: float = 1.0, hr: float = 0.0, t: float = 1.0, order: int = 2,
                     dtype: str = "float64", front: float = 1e-2, cfl: float = 0.45) -> dict:
    """A dam at x = 0 on a flat bed of 20·hl/1 m … released for ``t`` s on ``n`` cells, against Ritter (hr = 0)
    or Stoker (hr > 0).

    Parameters
    ----------
    n : int
        Cells (≥ 16).
    hl, hr : float
        Depths behind and ahead of the dam, m (hr = 0: a dry bed).
    t : float
        s.
    order : {1, 2}
    dtype : {"float64", "float32"}
    front : float
        Depth fraction θ of hl marking the front on a dry bed.
    cfl : float
        The solver's Courant number.

    Returns
    -------
    dict
        ``l1``, ``max`` (m), ``front`` (the position error of the front where h = θ·hl on a dry bed, or of
        the bore where h = (h_m + h_r)/2 on a wet one, m), ``dx`` (m), ``mass`` (relative change; the
        water has not reached the domain's open ends), ``min_depth`` (m).
    """
    from wavephys.physics.shallow_water import ritter, stoker, stoker_middle
    from wavephys.simulation.shallow_water import ShallowWater, _past_limit, _sw_run, sw_state

    n = check_int("n", n, lo=16)
    check_scalar("hl", hl, lo=0.0, lo_open=True)
    check_scalar("hr", hr, lo=0.0)
    c0 = math.sqrt(G * hl)
    half = 1.2 * 2 * c0 * t  # the front stays inside
    dx = 2 * half / n
    x = (np.arange(n) + 0.5) * dx - half
    bed = np.zeros((1, n))
    solver = _past_limit(ShallowWater(dx, sides="open", order=order), cfl)  # cfl past 1 measures the failure
    state = sw_state(bed, depth=np.where(x < 0, hl, hr)[None], dtype=_dtype(dtype))
    end, _ = _sw_run(solver, bed, state, until=t)
    h = np.asarray(end.h[0], np.float64)
    if hr == 0:
        want, _ = ritter(x, t, hl)
        level = front * hl
        where = 2 * c0 * t * (1 - 1.5 * math.sqrt(front))
    else:
        want, _ = stoker(x, t, hl, hr)
        hm, _, s = stoker_middle(hl, hr)
        level = 0.5 * (hm + hr)
        where = s * t
    past = np.nonzero(h > level)[0].max()  # last cell above the level; interpolate to the crossing
    x_cross = x[past] + dx * (h[past] - level) / (h[past] - h[past + 1])
    mass0 = float(np.sum(np.where(x < 0, hl, hr)))
    return dict(l1=float(np.abs(h - want).mean()), max=float(np.abs(h - want).max()), front=float(x_cross - where),
                dx=dx, mass=abs(float(h.sum()) / mass0 - 1), min_depth=float(h.min()))


def thacker_errors(n: int, h0: float = 0.1, a: float = 1.0, shift: float = 0.5, periods: float = 1.0,
                   order: int = 2, dtype: str = "float64", cfl: float = 0.45) -> dict:
    """Thacker's planar oscillation in a paraboloid bowl on an n × n grid of side 4a, after ``periods`` periods.

    Parameters
    ----------
    n : int
        Cells per side, ≥ 8.
    h0, a, shift : float
        The bowl (:func:`wavephys.physics.shallow_water.thacker`).
    periods : float
        > 0.
    order : {1, 2}
    dtype : {"float64", "float32"}
    cfl : float

    Returns
    -------
    dict
        ``l1``, ``max`` (depth errors, m), ``mass`` (relative change), ``min_depth`` (m), ``steps``.
    """
    from wavephys.physics.shallow_water import thacker, thacker_period
    from wavephys.simulation.shallow_water import ShallowWater, _past_limit, sw_mass, _sw_run, sw_state

    n = check_int("n", n, lo=8)
    side = 4.0 * a
    dx = side / n
    c = (np.arange(n) + 0.5) * dx - side / 2
    xx, yy = np.meshgrid(c, c)
    bed, h, u, v = thacker(xx, yy, 0.0, h0, a, shift)
    solver = _past_limit(ShallowWater(dx, order=order), cfl)  # cfl past 1 measures the failure
    state = sw_state(bed, depth=h, u=u, v=v, dtype=_dtype(dtype))
    t = periods * thacker_period(h0, a)
    end, steps = _sw_run(solver, bed, state, until=t)
    _, want, _, _ = thacker(xx, yy, t, h0, a, shift)
    got = np.asarray(end.h, np.float64)
    m0, m1 = float(sw_mass(state, dx)), float(sw_mass(end, dx))
    return dict(l1=float(np.abs(got - want).mean()), max=float(np.abs(got - want).max()), mass=abs(m1 / m0 - 1),
                min_depth=float(got.min()), steps=steps)


def lake_at_rest(n: int = 48, seed: int = 0, order: int = 2, dtype: str = "float64", sides="wall",
                 until: float = 2.0) -> dict:
    """A lake at rest (surface 0.5 m) over a random bed with islands that break the surface: its largest
    change after ``until`` s.

    Parameters
    ----------
    n : int
        Cells per side of the unit square.
    seed : int
        The bed's random draw.
    order : {1, 2}
    dtype : {"float64", "float32"}
    sides : str
        As :class:`~wavephys.simulation.shallow_water.ShallowWater`.
    until : float
        s.

    Returns
    -------
    dict
        ``eta`` (max |η − 0.5| over wet cells, m), ``momentum`` (max |h u|, |h v|, m²/s), ``dry_wetted``
        (cells dry at the start and wet at the end), ``islands`` (dry cells), ``steps``.
    """
    from wavephys.simulation.shallow_water import ShallowWater, _sw_run, sw_state

    rng = np.random.default_rng(seed)
    n = check_int("n", n, lo=4)
    dx = 1.0 / n
    c = (np.arange(n) + 0.5) * dx
    xx, yy = np.meshgrid(c, c)
    bed = np.zeros((n, n))
    for _ in range(4):  # bumps, some above the surface
        x0, y0, r, top = rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0.05, 0.2), rng.uniform(0.2, 0.9)
        bed += top * np.exp(-((xx - x0) ** 2 + (yy - y0) ** 2) / (2 * r * r))
    bed += 0.05 * rng.standard_normal((n, n))  # rough
    solver = ShallowWater(dx, sides=sides, order=order)
    state = sw_state(bed, 0.5, dtype=_dtype(dtype))
    end, steps = _sw_run(solver, bed, state, until=until)
    h0, h1 = np.asarray(state.h), np.asarray(end.h)
    wet = h1 > 0
    eta = np.abs(h1 + np.asarray(bed, h1.dtype) - np.asarray(0.5, h1.dtype))
    return dict(eta=float(eta[wet].max()), momentum=float(np.abs(np.asarray(end.fields[1:])).max()),
                dry_wetted=int(np.sum((h0 == 0) & (h1 > 0))), islands=int(np.sum(h0 == 0)), steps=steps)


def carrier_greenspan_errors(n: int = 1100, periods: float = 1.0, amplitude: float = 1.0, frames: int = 64,
                             order: int = 2) -> dict:
    """Carrier & Greenspan's standing wave on a 50 km beach (h₀ = 500 m, T = 900 s, ``amplitude`` m at the
    offshore end, which is an :class:`~wavephys.simulation.shallow_water.Inflow` of the exact solution),
    on n cells over 1.1 × the beach, sampled at ``frames`` times per period.

    Parameters
    ----------
    n : int
        Cells, ≥ 64.
    periods : float
        Periods run.
    amplitude : float
        m.
    frames : int
        Samples per period.
    order : {1, 2}

    Returns
    -------
    dict
        ``max``, ``l1`` (surface errors over cells wet in either solution, m), ``runup`` (the highest
        shoreline elevation seen, m), ``runup_exact`` (m), ``rundown`` (the lowest shoreline elevation seen,
        m), ``rundown_exact`` (the exact shoreline's lowest elevation at the same frames, m), ``dx`` (m).
    """
    from wavephys.physics.shallow_water import carrier_greenspan, carrier_greenspan_runup
    from wavephys.simulation.shallow_water import Inflow, ShallowWater, _sw_frames, sw_state

    h0, length, period = 500.0, 5e4, 900.0
    n = check_int("n", n, lo=64)
    dx = 1.1 * length / n
    x = (np.arange(n) + 0.5) * dx
    bed = (h0 * (x / length - 1))[None]
    ts = np.linspace(0.0, (periods + 0.1) * period, int(40 * (periods + 1)) + 1)
    edge = [carrier_greenspan([-0.5 * dx], t, h0, length, amplitude, period)[:2] for t in ts]
    solver = ShallowWater(dx, sides={"left": Inflow(ts, [e[0][0] for e in edge], [e[1][0] for e in edge])},
                          dry=1e-4, order=order)
    eta0, u0, _ = carrier_greenspan(x, 0.0, h0, length, amplitude, period)
    state = sw_state(bed, eta0[None], u=u0[None], dtype=_dtype("float64"))
    times = np.linspace(period * periods / frames, period * periods, int(frames * periods))
    out = _sw_frames(solver, bed, state, times)
    depth = np.asarray(out.h)[:, 0]
    errs, l1s, shore, exact_shore = [], [], [], []
    for i, t in enumerate(times):
        want, _, at = carrier_greenspan(x, t, h0, length, amplitude, period)
        exact_shore.append(h0 * (at / length - 1))  # the bed's height where the exact shoreline is
        eta = depth[i] + bed[0]
        wet = (depth[i] > 1e-3) | (want > bed[0] + 1e-3)
        errs.append(np.abs(eta - want)[wet].max())
        l1s.append(np.abs(eta - want)[wet].mean())
        shore.append(eta[np.nonzero(depth[i] > 1e-3)[0].max()])
    return dict(max=float(max(errs)), l1=float(np.mean(l1s)), runup=float(max(shore)),
                runup_exact=carrier_greenspan_runup(h0, length, amplitude, period), rundown=float(min(shore)),
                rundown_exact=float(min(exact_shore)), dx=dx)


RUNUP_MODELS = ("shallow_water", "split", "pipes")
""":func:`solitary_runup_run`'s models: nonlinear shallow water, the split (shallow water with dispersive
surface waves), the virtual pipes."""


def solitary_runup_run(height: float, cot_beta: float, per_depth: int = 20, order: int = 2,
                       dtype: str = "float64", model: str = "shallow_water") -> dict:
    """A solitary wave of height H (depth d = 1 m) from the flat floor up a plane beach of slope 1/cot β
    (the NTHMP set-up: crest one wavelength off the toe), on cells of d/``per_depth``, by one of
    :data:`RUNUP_MODELS`.

    Parameters
    ----------
    height : float
        H, m (d = 1 m), below the breaking limit.
    cot_beta : float
        The beach's slope as cot β.
    per_depth : int
        Cells per depth, ≥ 4.
    order : {1, 2}
        The shallow-water solver's order (its bulk's, in the split).
    dtype : {"float64", "float32"}
    model : {"shallow_water", "split", "pipes"}
        ``"shallow_water"`` (default; the offshore side open), ``"split"`` (its surface waves at the depths
        0.25, 0.5 and 1 m, faded into the bulk between 0.5 and 0.2 m deep: run-up −4.1 % at d/10 and
        −2.7 % at d/20, shallow water's −1.0 % and +0.18 %; with its earlier blend −6.0 % at d/10, and
        −6.8 % with the default taper; a wall offshore, far enough not to return in time), ``"pipes"`` (area "depth"; the wave's velocity given as the pipes' outflows; a wall
        offshore likewise).

    Returns
    -------
    dict
        ``runup`` (the highest shoreline elevation, from 1000 frames, m; the shoreline read from the sea in:
        :func:`~wavephys.harness.shallow_water.shoreline_elevation`), ``linear`` (the exact linear run-up),
        ``law`` (Synolakis' law), ``cells``, ``gamma_x0`` (γ·x₀: the law's asymptotic parameter), ``rundown``
        and ``rundown_linear`` (the lowest shoreline elevation, and the exact linear one, m).
    """
    from wavephys.harness.shallow_water import shoreline_elevation
    from wavephys.physics.shallow_water import (solitary_rundown_linear, solitary_runup, solitary_runup_linear,
                                                solitary_wave)
    from wavephys.core.inputs import check_choice
    from wavephys.simulation.shallow_water import ShallowWater, sw_state

    d = 1.0
    check_scalar("height", height, lo=0.0, lo_open=True)
    check_scalar("cot_beta", cot_beta, lo=0.0, lo_open=True)
    check_choice("model", model, RUNUP_MODELS)
    law = solitary_runup(height, d, cot_beta)  # refuses breaking waves
    gamma = math.sqrt(3 * height / (4 * d))
    wave = math.acosh(math.sqrt(20)) / gamma * d
    toe = d * cot_beta
    crest = toe + wave
    dx = d / check_int("per_depth", per_depth, lo=4)
    c = math.sqrt(G * d)
    end = (crest - toe) / c + 2 * toe / c + 2 * wave / c
    # open offshore, or a wall far enough that what it returns (the tail, a reflection) arrives after `end`
    xa, xb = -3 * law * cot_beta - 0.5 * d, crest + 1.5 * wave + (0.0 if model == "shallow_water" else 0.6 * c * end)
    n = int((xb - xa) / dx)
    x = xa + (np.arange(n) + 0.5) * dx
    bed = np.maximum(-x / cot_beta, -d)[None]
    eta, u = solitary_wave(x, height, d, crest)
    times = np.linspace(0.0, end, 1000)
    if model == "pipes":
        from wavephys.models.pipes import Pipes, PipesState
        from wavephys.models.pipes import PipesStepper

        h = np.maximum(eta - bed[0], 0.0)
        flows = np.zeros((4, 1, n))
        flows[0, 0] = np.maximum(-u, 0.0) * h * dx  # the pipe's flow A·v through the left face, A = dx·h
        flows[1, 0] = np.maximum(u, 0.0) * h * dx
        frame = end / 999
        dt = frame / math.ceil(frame / (0.4 * dx / (math.sqrt(2) * c)))  # Courant ≤ 0.4 at their speed √(2gh)
        state = PipesState(*(np.asarray(a, _dtype(dtype)) for a in (h[None], flows, 0.0)))
        run = PipesStepper(Pipes(dx), bed, dt).run(state, until=end, every=end / 999)
        depth = np.maximum(np.asarray(run.frames, np.float64)[:, 0] - bed[0], 0.0)
    else:
        state = sw_state(bed, eta[None], u=u[None], dtype=_dtype(dtype))
        if model == "split":
            from wavephys.simulation.split import Split
            from wavephys.simulation.split import SplitStepper

            stepper = SplitStepper(Split(ShallowWater(dx, order=order), levels=(0.25, 0.5, 1.0), taper=(0.2, 0.5)),
                                   bed)
        else:
            from wavephys.simulation.shallow_water import ShallowWaterStepper

            stepper = ShallowWaterStepper(ShallowWater(dx, sides={"right": "open"}, order=order), bed)
        run = stepper.run(state, until=end, every=end / 999)
        depth = np.maximum(np.asarray(run.frames, np.float64)[:, 0] - bed[0], 0.0)
    shore = shoreline_elevation(depth, bed[0])
    return dict(runup=float(np.nanmax(shore)), linear=solitary_runup_linear(height, d, cot_beta), law=law, cells=n,
                gamma_x0=gamma * toe, rundown=float(np.nanmin(shore)),
                rundown_linear=solitary_rundown_linear(height, d, cot_beta))


def pipes_seiche(depth: float = 0.05, n: int = 64, area="depth", courant: float = 0.5, periods: int = 10,
                 amplitude: float = 1e-3, rows: int = 1, dtype: str = "float64") -> dict:
    """The first seiche of a 1 m tank (walls at both ends; ``rows`` > 1: a 2-D tank, mode along x) in the
    virtual pipes, Δt = ``courant``·dx/√(gh): its fitted frequency and damping.

    Parameters
    ----------
    depth : float
        m.
    n : int
        Cells along the tank.
    area : "depth" or float
        As :class:`~wavephys.models.pipes.Pipes`.
    courant : float
        √(gh)·Δt/dx.
    periods : int
        Periods run.
    amplitude : float
        The mode's amplitude, m.
    rows : int
        Cells across (1: a 1-D tank).
    dtype : {"float64", "float32"}

    Returns
    -------
    dict
        ``frequency_ratio`` (fitted ω over the shallow-water seiche π√(gh)/L), ``damping`` (amplitude lost
        per period, fraction), ``mass`` (relative change), ``growth`` (max |η − h| at the end over the
        amplitude: ≫ 1 means the run blew up).
    """
    from scipy.optimize import curve_fit

    import jax.numpy as jnp

    from wavephys.models.pipes import Pipes, PipesState, _run_program, pipes_state

    n = check_int("n", n, lo=8)
    dx = 1.0 / n
    x = (np.arange(n) + 0.5) * dx
    bed = np.zeros((rows, n))
    rng = np.random.default_rng(0)
    eta = depth + amplitude * np.cos(np.pi * x)[None] + 1e-3 * amplitude * rng.standard_normal((rows, n))
    pipes = Pipes(dx, area=area)
    state = pipes_state(bed, eta, dtype=_dtype(dtype))
    c = math.sqrt(G * depth)
    dt = courant * dx / c
    period = 2.0 / c
    chunk = max(1, int(period / dt / 40))
    samples, t = [], []
    s = state
    for i in range(int(periods * period / dt) // chunk):
        # the compiled run itself: this measures where the pipes fail, past the Courant limit pipes_run refuses
        s = PipesState(*_run_program(pipes, jnp.asarray(bed, s.depth.dtype), s.depth, s.flows, s.time,
                                     jnp.asarray(dt, s.depth.dtype), chunk))
        samples.append(float(np.mean((np.asarray(s.depth, np.float64) - depth) * np.cos(np.pi * x)[None])) * 2)
        t.append((i + 1) * chunk * dt)
    growth = float(np.abs(np.asarray(s.depth, np.float64) - depth).max() / amplitude)
    mass = abs(float(np.sum(s.depth, dtype=np.float64)) / float(np.sum(state.depth, dtype=np.float64)) - 1)
    if not growth < 10:
        return dict(frequency_ratio=float("nan"), damping=float("nan"), mass=mass, growth=growth)
    w0 = math.pi * c

    def model(t, amp, w, ph, gam):
        return amp * np.exp(-gam * t) * np.cos(w * t + ph)

    section = dx * depth if isinstance(area, str) else float(area)
    guess = math.pi * math.sqrt(2 * G * section / dx)  # both pipes of a face carry flow: c² = 2gA/l
    fit, _ = curve_fit(model, np.asarray(t), np.asarray(samples), p0=[amplitude, guess, 0.0, 0.0], maxfev=20000)
    return dict(frequency_ratio=float(abs(fit[1]) / w0), damping=float(1 - math.exp(-fit[3] * period)), mass=mass,
                growth=growth)


def pipes_dam_break(n: int = 400, hl: float = 1.0, hr: float = 0.0, t: float = 1.0, courant: float = 0.25) -> dict:
    """The dam break of :func:`dam_break_errors` run by the virtual pipes (``area="depth"``).

    Parameters
    ----------
    n : int
        Cells.
    hl, hr : float
        Depths behind and ahead of the dam, m.
    t : float
        s.
    courant : float
        √(g hl)·Δt/dx.

    Returns
    -------
    dict
        ``l1``, ``max`` (m), ``front`` (position error of the front or bore, m), ``mass`` (relative change).
    """
    import jax.numpy as jnp

    from wavephys.models.pipes import Pipes, _pipes_run, pipes_state
    from wavephys.physics.shallow_water import ritter, stoker, stoker_middle

    n = check_int("n", n, lo=16)
    c0 = math.sqrt(G * hl)
    half = 1.2 * 2 * c0 * t
    dx = 2 * half / n
    x = (np.arange(n) + 0.5) * dx - half
    bed = np.zeros((1, n))
    state = pipes_state(bed, depth=np.where(x < 0, hl, hr)[None], dtype=jnp.float64)
    steps = int(math.ceil(t / (courant * dx / c0)))
    end = _pipes_run(Pipes(dx), bed, state, steps, t / steps)
    h = np.asarray(end.depth[0], np.float64)
    if hr == 0:
        want, _ = ritter(x, t, hl)
        level, where = 1e-3 * hl, 2 * c0 * t * (1 - 1.5 * math.sqrt(1e-3))
    else:
        want, _ = stoker(x, t, hl, hr)
        hm, _, s = stoker_middle(hl, hr)
        level, where = 0.5 * (hm + hr), s * t
    past = np.nonzero(h > level)[0].max()
    return dict(l1=float(np.abs(h - want).mean()), max=float(np.abs(h - want).max()), front=float(x[past] - where),
                mass=abs(float(h.sum()) / float(np.asarray(state.depth).sum()) - 1))


def check_shallow_water() -> list[Check]:
    """The finite-volume solver on the exact solutions, and the virtual pipes' measured failures.

    Returns
    -------
    list of Check
        A lake at rest with islands (float64: max |Δη| ≤ 1e-12 m); Ritter's dam break (L1 order ≥ 0.8 from
        200 to 800 cells, front within 4 cells); Stoker's (L1 order ≥ 0.8); Thacker's bowl after one period
        (L1 order ≥ 1.2 from 50² to 100², mass to 1e-12); the solitary-wave run-up at cot β = 19.85,
        H/d = 0.01 (within 3 % of the exact linear run-up); the pipes' seiche frequency over √(gh)'s
        (√2: their failure) and their dam-break front (behind Ritter's by more than half the distance).
    """
    import jax

    with jax.enable_x64(True):
        lake = lake_at_rest(32, seed=3)
        ritters = [dam_break_errors(n) for n in (200, 400, 800)]
        stokers = [dam_break_errors(n, hr=0.1) for n in (200, 400, 800)]
        thackers = [thacker_errors(n) for n in (50, 100)]
        run = solitary_runup_run(0.01, 19.85)
        seiche = pipes_seiche()
        pipes = pipes_dam_break()
    sizes = (200, 400, 800)
    return [
        bound("lake at rest over a bed with islands, float64, 2 s: max |eta - eta0| over wet cells", lake["eta"],
              1e-12, unit="m", note=f"{lake['islands']} dry cells, {lake['steps']} steps"),
        bound("Ritter's dam break: L1 convergence order, 200-800 cells", convergence_order(
            [r["l1"] for r in ritters], sizes), 0.8, relation=">=",
              note=", ".join(f"{r['l1']:.2e}" for r in ritters) + " m"),
        bound("Ritter's dam break: front (h = 1 % of h0) position error at 800 cells / dx",
              abs(ritters[-1]["front"]) / ritters[-1]["dx"], 4.0),
        bound("Stoker's dam break (hr/hl = 0.1): L1 convergence order, 200-800 cells",
              convergence_order([r["l1"] for r in stokers], sizes), 0.8, relation=">=",
              note=", ".join(f"{r['l1']:.2e}" for r in stokers) + " m"),
        bound("Thacker's bowl after one period: L1 convergence order, 50^2-100^2",
              convergence_order([r["l1"] for r in thackers], (50, 100)), 1.2, relation=">=",
              note=", ".join(f"{r['l1']:.2e}" for r in thackers) + " m"),
        bound("Thacker's bowl: relative mass change over one period", thackers[-1]["mass"], 1e-12),
        bound("solitary wave up a 1:19.85 beach, H/d = 0.01: |runup / exact linear runup - 1|",
              abs(run["runup"] / run["linear"] - 1), 0.03,
              note=f"runup {run['runup']:.5f} d, linear {run['linear']:.5f} d, Synolakis' law {run['law']:.5f} d"),
        bound("virtual pipes (A = l h): seiche frequency / sqrt(gh) seiche (their failure: sqrt 2)",
              seiche["frequency_ratio"], 1.3, relation=">=", note=f"damping {seiche['damping']:.2%} per period"),
        bound("virtual pipes: dam-break front behind Ritter's after 1 s (their failure), m",
              -pipes["front"], 3.0, relation=">=", note=f"L1 {pipes['l1']:.3f} m vs the solver's "
                                                         f"{ritters[1]['l1']:.4f} m at 400 cells"),
    ]
