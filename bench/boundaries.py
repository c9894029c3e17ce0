"""``python -m bench boundaries``: where each method fails, measured over its range.

* open-ocean cutoff: reflected energy vs λ/M, quadratic and linear, two step rates;
* Hermite frames: error at Δt/3 vs ωΔt;
* second-order heights: error against the exact Stokes wave vs kA (1st and 2nd order);
* finite differences: growth over 400 steps vs Courant number.
"""

from __future__ import annotations

import math

import jax
import jax.numpy as jnp
import numpy as np

from wavephys import checks
from wavephys.core.stepper import TwoLevelState
from wavephys.models.finite_difference import STABILITY_LIMIT, FiniteDifferenceStepper
from wavephys.plot import plot_curves


def boundary_data(quick: bool = False, progress=print):
    rows, figs = [], {}
    ratios = (0.25, 0.5, 1.0, 2.0) if quick else (0.125, 0.25, 0.375, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0)
    curves = {}
    for kind in ("quadratic", "linear"):
        for rate in (0.5, 0.1):
            progress(f"cutoff reflection {kind}, {rate} cells/step")
            r = [checks.cutoff_reflection(x, kind, group_cells_per_step=rate) for x in ratios]
            curves[f"{kind}, group {rate} cells/step"] = (ratios, r)
            rows += [dict(boundary="cutoff reflection", kind=kind, cells_per_step=rate, wavelength_over_margin=x,
                          reflected_energy=v) for x, v in zip(ratios, r)]
    figs["cutoff"] = plot_curves(curves, "λ / M", "reflected energy fraction",
                                 "open-ocean margin: reflection", logx=True, hlines={"0.1 %": 1e-3})

    progress("Hermite frames")
    x = np.geomspace(0.05, 6.0, 40)
    for s in (1 / 3, 2 / 3):
        e = [checks.hermite_error(v, s) for v in x]
        curves_h = figs.setdefault("_h", {})
        curves_h[f"s = {s:.3f}"] = (x, e)
        rows += [dict(boundary="Hermite frame", s=s, omega_dt=float(a), error=b) for a, b in zip(x, e)]
    figs["hermite"] = plot_curves(figs.pop("_h"), "ωΔt", "|error| / amplitude", "Hermite frames between steps",
                                  logx=True, hlines={"1 %": 0.01, "10 %": 0.1})

    progress("second-order heights vs exact Stokes waves")
    ks = checks.STEEPNESS[::2] if quick else checks.STEEPNESS
    errs = [checks.second_order_error(float(k)) for k in ks]
    rows += [dict(boundary="second-order height", steepness=float(k), first_order_error=e["first"],
                  second_order_error=e["second"]) for k, e in zip(ks, errs)]
    figs["second_order"] = plot_curves({"1st order": (ks, [e["first"] for e in errs]),
                                        "2nd order": (ks, [e["second"] for e in errs])},
                                       "steepness kA", "max |η − η_Stokes| / A",
                                       "heights against the exact Stokes wave", hlines={"10 %": 0.1})

    progress("finite-difference stability")
    eta0 = jax.random.normal(jax.random.PRNGKey(0), (32, 32))
    cs = np.linspace(0.9, 1.1, 21) * STABILITY_LIMIT
    growth = []
    for c in cs:
        out = FiniteDifferenceStepper(float(c), 1.0, check_stability=False).trajectory(TwoLevelState(eta0, eta0),
                                                                                       400)[0].eta
        g = float(jnp.max(jnp.abs(out)) / jnp.max(jnp.abs(eta0)))
        growth.append(g if math.isfinite(g) else 1e38)
    rows += [dict(boundary="FD stability", courant=float(c), growth_400_steps=g) for c, g in zip(cs, growth)]
    figs["fd_stability"] = plot_curves({"max|η| growth in 400 steps": (cs / STABILITY_LIMIT, growth)},
                                       "Courant number / (1/√2)", "growth factor", "explicit FD wave equation")
    return rows, figs
