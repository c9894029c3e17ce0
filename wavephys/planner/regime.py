"""Which water model a coastal scene needs: linear, nonlinear shallow water, or the split (docs/planner.md §8).

Three models run a scene of varying depth: the linear spectral step at depth levels (exact ω(k), no dry land,
no amplitude effects; :mod:`wavephys.simulation.depth`), nonlinear shallow water (run-up, bores and drying,
every wave at √(gh); :mod:`wavephys.simulation.shallow_water`), and the split of the two
(:mod:`wavephys.simulation.split`). :func:`choose_regime` bounds the error each would make on a
:class:`CoastalScene` as the worst relative error of a wave's speed, and picks the cheapest model within the
tolerance:

* **linear**: it neglects the waves' amplitude. A wave of height H over depth h travels faster by up to
  3H/(4h) at its crest in shallow water (the crest of a simple wave of the shallow-water equations moves at
  3√(g(h+a)) − 2√(gh) ≈ √(gh)(1 + 3a/(2h)), a = H/2; measured against the nonlinear solver:
  tests/planner/test_regime.py) and by ½(ka)² in deep water (Stokes 1847); it cannot have dry land.
* **nonlinear**: every wave at √(gh), so √(kh/tanh kh) − 1 at the shortest wave over the deepest water
  (exact), plus the finite volumes' own error at the scene's cells per wavelength (measured, :data:`FV_ERROR`),
  plus ½(ka)² (it has no Stokes correction either).
* **split**: exact dispersion; what is left is the finite volumes' error on the bulk at its default length
  (measured, :data:`SPLIT_ERROR`), and the surface waves' neglected amplitude, ½(ka)².

Costs per second of scene time are the measured seconds per cell-step (:data:`STEP_COST`, relative to the
linear step, ``python -m bench shallow``) times the steps a second needs: the linear step takes one per frame
(it is exact in time and space: it is costed at 16 cells per shortest wavelength, the least the others are
offered), the other two the shallow-water Courant limit, Δt = 0.45·dx/(2√(g h_max)).
"""

from __future__ import annotations

import math
from typing import Optional
from dataclasses import dataclass, field

from wavephys.core.inputs import check_scalar

__all__ = ["CoastalScene", "RegimeChoice", "choose_regime", "measure_speed_error", "linear_error",
           "shallow_water_dispersion", "REGIMES", "FV_ERROR", "SPLIT_ERROR", "STEP_COST"]

REGIMES = ("linear", "nonlinear", "split")
"""The models :func:`choose_regime` chooses from, cheapest first."""

FV_ERROR = ((16, 0.013), (32, 0.0045), (64, 0.0015))
"""(cells per shortest wavelength, worst |ω/(k√(gh)) − 1|) of the finite-volume solver (order 2, float32): the
largest measured by :func:`measure_speed_error` over kh 0.02, 0.1, 0.4 and three seeds (1.28 / 0.41 / 0.13 %),
rounded up; fewer than 16 cells per wavelength are not offered."""

SPLIT_ERROR = ((16, 0.002), (32, 0.002), (64, 0.002))
"""(cells per shortest wavelength, worst |ω/ω_exact − 1|) of the split at its default bulk length (float32): the
largest measured by :func:`measure_speed_error` over kh 0.02 … 25 and two seeds (0.14 / 0.18 / 0.16 %, each at
kh 25), rounded up; re-measured with the split's symmetric blend over five seeds: 0.15 / 0.17 / 0.17 %. It holds
for waves above about 10⁻⁴ of the depth in float32: smaller, the state's rounding of h adds to it (waves of
8·10⁻⁵ and 4·10⁻⁵ of the depth: 0.24 % and 0.59 % at 16 cells; float64 0.144 %)."""

STEP_COST = {"linear": 1.0, "nonlinear": 0.26, "split": 12.0}
"""Seconds per step over the linear step's (4 depth levels) on the same grid, 256² with walls, measured by
``python -m bench shallow --quick`` on 2 CPU cores: 7.7 ms (levels), 2.0 ms (finite volumes, order 2),
92 ms (split, 4 levels)."""

CELLS = (16, 32, 64)


@dataclass(frozen=True)
class CoastalScene:
    """What a coastal scene holds, for choosing its model.

    Parameters
    ----------
    depth : (float, float)
        Shallowest and deepest still water, m, 0 ≤ shallow ≤ deep, deep > 0 (0: a shoreline, dry land).
    wave_height : float
        Crest-to-trough height H of the largest waves, m, ≥ 0.
    wavelength : (float, float)
        Shortest and longest wavelength that matter, m, 0 < shortest ≤ longest.
    extent : float
        Side of the square domain, m, > 0 (at least the longest wavelength).
    fps : float
        Frames per second the scene is shown at, > 0 (default 30).
    """

    depth: tuple
    wave_height: float
    wavelength: tuple
    extent: float
    fps: float = 30.0

    def __post_init__(self):
        for name in ("depth", "wavelength"):
            value = getattr(self, name)
            if not isinstance(value, (tuple, list)) or len(value) != 2:
                raise TypeError(f"{name} must be a pair (low, high), got {value!r}")
            for v in value:
                check_scalar(name, v, lo=0.0)
            object.__setattr__(self, name, (float(value[0]), float(value[1])))
        if not self.depth[1] > 0 or self.depth[0] > self.depth[1]:
            raise ValueError(f"depth must be (shallow, deep) with 0 <= shallow <= deep and deep > 0, got {self.depth}")
        if not self.wavelength[0] > 0 or self.wavelength[0] > self.wavelength[1]:
            raise ValueError(f"wavelength must be (shortest, longest) with 0 < shortest <= longest, got "
                             f"{self.wavelength}")
        check_scalar("wave_height", self.wave_height, lo=0.0)
        check_scalar("extent", self.extent, lo=0.0, lo_open=True)
        check_scalar("fps", self.fps, lo=0.0, lo_open=True)
        if self.extent < self.wavelength[1]:
            raise ValueError(f"extent ({self.extent} m) must hold the longest wavelength ({self.wavelength[1]} m)")
        for name in ("wave_height", "extent", "fps"):
            object.__setattr__(self, name, float(getattr(self, name)))

    @property
    def dry_land(self) -> bool:
        """True when the scene has a shoreline (shallowest depth 0)."""
        return self.depth[0] == 0.0


@dataclass(frozen=True)
class RegimeChoice:
    """The chosen model, its bound and cost, and every model's, with the reasons (made by :func:`choose_regime`).

    Attributes
    ----------
    regime : str
        One of :data:`REGIMES`.
    bound : float
        Its speed-error bound, dimensionless.
    cells : int
        Cells per shortest wavelength it runs at.
    cost : float
        Predicted cost of a second of scene time (the linear step on 10⁶ cells once = 1).
    rows : tuple of dict
        Each model's best row: ``regime``, ``cells``, ``bound``, ``cost``, ``note``.
    reason : str
        Why this model, and why not each other.
    """

    regime: str
    bound: float
    cells: int
    cost: float
    rows: tuple = field(default=())
    reason: str = ""

    def __str__(self):
        lines = [f"model: {self.regime} ({self.cells} cells per shortest wavelength): speed error <= "
                 f"{self.bound:.2%}, cost {self.cost:.3g} (linear-step units per second of scene)", self.reason]
        for r in self.rows:
            lines.append(f"  {r['regime']:<10} bound {r['bound']:.2%}  cost {r['cost']:.3g}  {r['note']}")
        return "\n".join(lines)


def _table(table, cells):
    for c, e in table:
        if c == cells:
            return e
    raise KeyError(cells)


def _scene(scene):
    if not isinstance(scene, CoastalScene):
        raise TypeError(f"scene must be a wavephys.planner.regime.CoastalScene, got {type(scene).__name__}")
    return scene


def linear_error(scene: CoastalScene) -> float:
    """The linear model's bound: max(3H/(4h), ½(ka)²) at the shallowest wet depth and the shortest wave (a = H/2).

    Parameters
    ----------
    scene : CoastalScene

    Returns
    -------
    float
        Relative speed error, dimensionless (inf with dry land).
    """
    _scene(scene)
    a = scene.wave_height / 2
    k = 2 * math.pi / scene.wavelength[0]
    shallow = scene.depth[0]
    long_wave = 1.5 * a / shallow if shallow > 0 else math.inf
    return max(long_wave, 0.5 * (k * a) ** 2)


def shallow_water_dispersion(scene: CoastalScene) -> float:
    """√(kh/tanh kh) − 1 at the shortest wave over the deepest water: shallow water's speed error (exact).

    Parameters
    ----------
    scene : CoastalScene

    Returns
    -------
    float
        Relative speed error, dimensionless.
    """
    _scene(scene)
    kh = 2 * math.pi / scene.wavelength[0] * scene.depth[1]
    return math.sqrt(kh / math.tanh(kh)) - 1


def _cost(scene: CoastalScene, regime: str, cells: int) -> float:
    dx = scene.wavelength[0] / cells
    n = scene.extent / dx
    per_step = STEP_COST[regime] * n * n
    if regime == "linear":
        steps = scene.fps
    else:
        dt = 0.45 * dx / (2 * math.sqrt(9.81 * scene.depth[1]))
        steps = max(scene.fps, 1.0 / dt)
    return per_step * steps / 1e6


def choose_regime(scene: CoastalScene, tolerance: float) -> RegimeChoice:
    """The cheapest model (and cells per shortest wavelength) whose speed-error bound is within ``tolerance``.

    Parameters
    ----------
    scene : CoastalScene
    tolerance : float
        Largest relative error of a wave's speed, > 0 (0.01: 1 %).

    Returns
    -------
    RegimeChoice
        The choice, its bound and cost (the linear step on 10⁶ cells once = 1), every model's rows, the reason.

    Raises
    ------
    ValueError
        When no model meets the tolerance (the message gives each one's best bound).
    """
    _scene(scene)
    check_scalar("tolerance", tolerance, lo=0.0, lo_open=True)
    lin = linear_error(scene)
    sw = shallow_water_dispersion(scene)
    stokes = 0.5 * (2 * math.pi / scene.wavelength[0] * scene.wave_height / 2) ** 2
    rows = []
    for regime in REGIMES:
        for cells in CELLS:
            if regime == "linear":
                bound = lin
                note = ("has dry land: it cannot run up a shore" if scene.dry_land else
                        f"amplitude: 3H/4h = {1.5 * scene.wave_height / 2 / scene.depth[0]:.2%}, ½(ka)² = {stokes:.2%}")
            elif regime == "nonlinear":
                bound = sw + _table(FV_ERROR, cells) + stokes
                note = (f"√(kh/tanh kh) − 1 = {sw:.2%} at the shortest wave, + finite volumes "
                        f"{_table(FV_ERROR, cells):.2%} + ½(ka)² = {stokes:.2%}")
            else:
                bound = _table(SPLIT_ERROR, cells) + stokes
                note = f"bulk {_table(SPLIT_ERROR, cells):.2%} + ½(ka)² = {stokes:.2%}"
            rows.append(dict(regime=regime, cells=cells, bound=bound, cost=_cost(scene, regime, cells), note=note))
            if regime == "linear":
                break  # exact in space: one row, costed at the least resolution the others are offered
    fits = [r for r in rows if r["bound"] <= tolerance]
    best = {}  # each model's best row: the cheapest within the tolerance, else the one with the smallest bound
    for g in REGIMES:
        own = [r for r in rows if r["regime"] == g]
        within = [r for r in own if r["bound"] <= tolerance]
        best[g] = min(within, key=lambda r: r["cost"]) if within else min(own, key=lambda r: r["bound"])
    shown = tuple(best[g] for g in REGIMES)
    if not fits:
        raise ValueError(f"no model meets tolerance = {tolerance:.3g}: " +
                         "; ".join(f"{r['regime']} {r['bound']:.2%} at {r['cells']} cells per wavelength "
                                   f"({r['note']})" for r in shown))
    pick = min(fits, key=lambda r: r["cost"])
    others = [r for r in shown if r["regime"] != pick["regime"]]
    why = []
    for r in others:
        if r["bound"] > tolerance:
            why.append(f"{r['regime']} is out ({r['bound']:.2%} > {tolerance:.2%}: {r['note']})")
        else:
            why.append(f"{r['regime']} costs {r['cost'] / pick['cost']:.3g}× as much")
    reason = f"{pick['regime']}: {pick['note']}; " + "; ".join(why)
    return RegimeChoice(pick["regime"], pick["bound"], pick["cells"], pick["cost"], shown, reason)


def measure_speed_error(regime: str, kh: float, cells: int, *, seed: int = 1, x64: bool = False,
                        amplitude: Optional[float] = None) -> dict:
    """Run ``regime`` on small waves and measure its speed error: four waves k/4, k/2, 3k/4, k (kh = ``kh`` over 1 m)
    on a periodic line, ``cells`` cells per shortest wavelength, eight periods of the longest, read by the harness
    (:func:`wavephys.harness.measure_dispersion`).

    Parameters
    ----------
    regime : {"nonlinear", "split"}
    kh : float
        k·h of the shortest wave, in (0, 1000].
    cells : int
        Cells per shortest wavelength, 8 … 256.
    seed : int
        The waves' random phases.
    x64 : bool
        Run in float64 (default float32, as the scenes).
    amplitude : float, optional
        Each wave's amplitude over the depth, in (0, 0.1] (default: 10⁻³, and 4·10⁻³/kh for waves steeper than
        that). In float32 the split's error grows as waves shrink below about 10⁻⁴ of the depth (the state's
        rounding of h): 0.24 % at kh 50 and 0.59 % at kh 100 with the default (waves of 8·10⁻⁵ and 4·10⁻⁵ of
        the depth), 0.144 % at both in float64.

    Returns
    -------
    dict
        ``exact``: worst |ω/ω_exact − 1|, the published ω² = gk tanh kh; ``own``: worst |ω/ω_model − 1| against
        the model's own continuous law (k√(gh) for shallow water: its finite volumes' error; the exact law for
        the split).
    """
    import jax
    import jax.numpy as jnp
    import numpy as np

    from wavephys.core.inputs import check_bool, check_choice, check_int
    from wavephys.core.water import Water
    from wavephys.harness.dispersion import measure_dispersion
    from wavephys.physics.dispersion import angular_frequency
    from wavephys.simulation.shallow_water import ShallowWater, _sw_frames, sw_state
    from wavephys.simulation.split import Split, _split_frames

    check_choice("regime", regime, ("nonlinear", "split"))
    check_scalar("kh", kh, lo=0.0, hi=1000.0, lo_open=True)
    cells = check_int("cells", cells, lo=8, hi=256)
    seed = check_int("seed", seed, lo=0)
    x64 = check_bool("x64", x64)
    if amplitude is not None:
        amplitude = check_scalar("amplitude", amplitude, lo=0.0, hi=0.1, lo_open=True)
    water = Water(sigma=0.0, depth=1.0)
    k = float(kh)
    n = 4 * cells
    dx = 2 * math.pi / (k / 4) / n
    x = (np.arange(n) + 0.5) * dx
    rng = np.random.default_rng(seed)
    height = (lambda m: amplitude) if amplitude is not None else (lambda m: 1e-3 * min(1.0, 4.0 / (m * k)))
    eta = sum(height(m) * np.cos(m * k / 4 * x + rng.uniform(0, 2 * math.pi)) for m in (1, 2, 3, 4))
    bed = np.full((1, n), -1.0)
    with jax.enable_x64(x64):
        w0 = float(angular_frequency(jnp.asarray(k / 4), water))
        dt = math.pi / float(angular_frequency(jnp.asarray(k), water)) / 3
        times = np.arange(1, int(8 * 2 * math.pi / w0 / dt) + 1) * dt
        solver = ShallowWater(dx, sides="periodic")
        state = sw_state(bed, eta[None], dtype=jnp.float64 if x64 else jnp.float32)
        if regime == "split":
            frames = _split_frames(Split(solver, levels=(1.0,)), bed, state, times)
        else:
            frames = _sw_frames(solver, bed, state, times)
        record = np.asarray(frames.fields[:, 0] + bed, np.float64)
        samples = measure_dispersion(record, dx, dt)
        keep = (samples.k > 0.2 * k) & (samples.k < 1.03 * k)
        ks, ws = samples.k[keep], samples.omega[keep]
        exact = np.asarray(angular_frequency(jnp.asarray(ks), water), np.float64)
    own = ks * math.sqrt(water.g) if regime == "nonlinear" else exact
    return dict(exact=float(np.max(np.abs(ws / exact - 1))), own=float(np.max(np.abs(ws / own - 1))),
                shells=int(keep.sum()))
