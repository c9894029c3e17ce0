"""The planner's calibration (``python -m bench calibrate``) and its proof (``python -m bench planner``).

``calibrate`` measures, on this machine and after compilation, what the planner's cost
model (:mod:`wavephys.planner.cost`) needs (:mod:`wavephys.planner.measure`, which
``wavephys calibrate --out FILE`` runs anywhere) and writes the shipped
``wavephys/planner/data/calibration.json`` atomically.

``planner`` is the proof over scenes nobody picked: for each generated scene
(:func:`wavephys.planner.generate_scenes`, 32–128 texels) it plans at a tolerance of one
height quantum, runs the full and the planned model, and records predicted against measured
error and predicted against measured cost (each run timed warm, after a first run). The
colour prediction covers the optics terms (Fresnel form, absorption), so it is measured on
the full model's surface (``measured_colour_optics``); ``measured_colour`` is the whole
image difference, heights included.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

CAL_PATH = Path(__file__).resolve().parents[1] / "wavephys" / "planner" / "data" / "calibration.json"

# the measurements live in the package (``wavephys calibrate`` runs them on any machine)
from wavephys.planner.measure import (CAUSTICS_CELLS, KAPPA_SCENES, SHADE_SIZES, STEP_SIZES,  # noqa: E402,F401
                                      SURFACE_SIZES, TABLES, caustics_jacobian_seconds, caustics_seconds,
                                      frame_seconds, kappa, optics_seconds, overhead_seconds, shade_seconds,
                                      ship_seconds, step_seconds, step_symmetric_seconds, step_walls_seconds,
                                      surface_seconds, texture_seconds)


def calibrate(progress=print, only=None) -> dict:
    """Measure everything the cost model needs and write the shipped calibration file (module
    doc); ``only``: a table name or names of :data:`wavephys.planner.measure.TABLES`, measured
    alone, the rest kept from the shipped file."""
    from wavephys.planner.measure import calibrate as measure

    return measure(CAL_PATH, only=only, base=CAL_PATH if only else None, progress=progress)


def _total(output, frames: int = 1) -> float:
    """Wall seconds of one run: simulation and frames, and the shading of the image (measured on
    the last frame, counted ``frames`` times as the cost model counts it; the first run also
    compiles)."""
    return output.seconds + output.shade_seconds * frames


def proof_rows(count: int = 50, seed: int = 2026, quanta: float = 1.0, progress=print,
               texels=(32, 48, 64, 96, 128)) -> list:
    """Plan each of ``count`` generated scenes at ``quanta`` height quanta, run the full and the
    planned model (each five times; the fastest run timed), and record predicted and measured."""
    from wavephys.planner import Infeasible, compare, full_model, generate_scenes, plan, run
    from wavephys.planner.runner import shade

    rows = []
    for i, scene in enumerate(generate_scenes(count, seed=seed, texels=texels)):
        tol = quanta * scene.height_quantum
        t = time.perf_counter()
        try:
            p = plan(scene, tol)
        except Infeasible as exc:
            rows.append(dict(scene=scene.name, infeasible=str(exc)))
            progress(f"[{i + 1}/{count}] {scene.name}: infeasible: {exc}")
            continue
        planning = time.perf_counter() - t
        full_m = full_model(scene)
        cost = lambda o: _total(o, scene.frames)
        ref = min((run(scene, full_m) for _ in range(5)), key=cost)  # the first compiles
        out = min((run(scene, p.model) for _ in range(5)), key=cost)
        err = compare(out, ref)
        optics_only = float(np.abs(shade(scene, p.model, ref.heights[-1]) - ref.image).max())
        row = dict(scene=scene.name, kind=scene.name.split("-")[0], texels=scene.texels, frames=scene.frames,
                   tolerance=tol, predicted_error=p.predicted_error, measured_error=err["height_max"],
                   measured_rms=err["height_rms"], predicted_rms=p.predicted_rms,
                   predicted_colour=p.predicted_colour_error, measured_colour=err["colour_max"],
                   measured_colour_optics=optics_only,
                   colour_tolerance=p.colour_tolerance, predicted_cost=p.cost, predicted_full_cost=p.full_cost,
                   measured_cost=cost(out), measured_full_cost=cost(ref), caustics=scene.caustics,
                   planning_seconds=planning, choices=p.model.choices.as_dict())
        row["measured_saving"] = row["measured_full_cost"] / row["measured_cost"]
        row["predicted_saving"] = p.saving
        rows.append(row)
        progress(f"[{i + 1}/{count}] {scene.name}: {p.model.describe()}; error {err['height_max']:.3g} ≤ predicted "
                 f"{p.predicted_error:.3g} ≤ tol {tol:.3g}; colour of the optics terms {optics_only:.2g} ≤ "
                 f"{p.predicted_colour_error:.2g}, with the heights' {err['colour_max']:.2g}; saving ×{row['measured_saving']:.2f} (predicted "
                 f"×{p.saving:.2f})")
    return rows


def savings_rows(scenes, quanta=(0.5, 1.0), rounds: int = 7, progress=print) -> list:
    """The measured saving of each scene's plan at each tolerance (``quanta`` height quanta):
    the plan and the full model run in interleaved rounds, the order alternating (full then plan,
    plan then full, …; both warm: a fixed order favoured the second, a plan identical to the full
    model measured ×0.95, slower in all 7 rounds), each run's time as :func:`_total` counts it; per
    round the ratio full ÷ plan. A plan slower than the full model in every round is flagged
    (``slower_every_round``); ``same_as_full``: the plan's choices are the full model's."""
    from wavephys.planner import Infeasible, full_model, plan, run

    rows = []
    for scene in scenes:
        full_m = full_model(scene)
        cost = lambda o, s=scene: _total(o, s.frames)
        for q in quanta:
            try:
                p = plan(scene, q * scene.height_quantum)
            except Infeasible as exc:
                rows.append(dict(scene=scene.name, quanta=q, infeasible=str(exc)))
                continue
            run(scene, full_m), run(scene, p.model)  # compile both
            full_t, plan_t = [], []
            for k in range(rounds):
                if k % 2:
                    plan_t.append(cost(run(scene, p.model)))
                    full_t.append(cost(run(scene, full_m)))
                else:
                    full_t.append(cost(run(scene, full_m)))
                    plan_t.append(cost(run(scene, p.model)))
            ratios = np.divide(full_t, plan_t)
            q1, med, q3 = (float(x) for x in np.percentile(ratios, [25, 50, 75]))
            row = dict(scene=scene.name, kind=scene.name.split("-")[0], quanta=q, texels=scene.texels,
                       frames=scene.frames, model=p.model.describe(), choices=p.model.choices.as_dict(),
                       predicted_saving=p.saving, measured_saving=med, saving_quartiles=[q1, q3],
                       slower_every_round=bool(np.all(ratios < 1.0)), predicted_cost=p.cost,
                       same_as_full=p.model.choices == full_m.choices,
                       predicted_full_cost=p.full_cost, measured_cost=float(np.median(plan_t)),
                       measured_full_cost=float(np.median(full_t)))
            rows.append(row)
            progress(f"{scene.name} at {q:g} quanta: {p.model.describe()}; saving measured ×{med:.2f} "
                     f"({q1:.2f}–{q3:.2f}), predicted ×{p.saving:.2f}; plan {1e3 * row['measured_cost']:.1f} ms, "
                     f"full {1e3 * row['measured_full_cost']:.1f} ms"
                     + ("; SLOWER THAN THE FULL MODEL IN EVERY ROUND" if row["slower_every_round"] else ""))
    return rows


def savings_figure(rows):
    """Measured saving (median and quartiles of the interleaved rounds) against predicted, per
    scene and tolerance, with ×1 and the ×2 goal marked."""
    import matplotlib.figure

    ok = [r for r in rows if "measured_saving" in r]
    fig = matplotlib.figure.Figure(figsize=(12, 4.8))
    ax1, ax2 = fig.subplots(1, 2, gridspec_kw=dict(width_ratios=[2.2, 1]))
    quanta = sorted({r["quanta"] for r in ok})
    names = list(dict.fromkeys(r["scene"] for r in ok))
    width = 0.8 / len(quanta)
    for j, q in enumerate(quanta):
        sel = {r["scene"]: r for r in ok if r["quanta"] == q}
        xs = [i + (j - (len(quanta) - 1) / 2) * width for i, name in enumerate(names) if name in sel]
        med = [sel[name]["measured_saving"] for name in names if name in sel]
        lo = [m - sel[name]["saving_quartiles"][0] for m, name in zip(med, [n for n in names if n in sel])]
        hi = [sel[name]["saving_quartiles"][1] - m for m, name in zip(med, [n for n in names if n in sel])]
        ax1.bar(xs, med, width, yerr=[lo, hi], capsize=2, label=f"{q:g} " + ("quantum" if q == 1 else "quanta"))
        ax2.scatter([sel[n]["predicted_saving"] for n in names if n in sel], med, s=16, label=f"{q:g} q")
    ax1.axhline(1.0, color="k", lw=0.8)
    ax1.axhline(2.0, color="r", lw=0.8, ls="--", label="the ×2 goal")
    ax1.set_xticks(range(len(names)), names, rotation=70, fontsize=7)
    ax1.set(yscale="log", ylabel="measured saving (full ÷ plan, median of rounds)",
            title=f"saving per scene, interleaved rounds ({len(names)} scenes)")
    ax1.legend(fontsize=7)
    top = max([r["measured_saving"] for r in ok] + [r["predicted_saving"] for r in ok] + [2.5])
    ax2.plot([0.5, top], [0.5, top], "k--", lw=0.8)
    ax2.set(xscale="log", yscale="log", xlabel="predicted saving", ylabel="measured saving",
            title="measured against predicted")
    ax2.legend(fontsize=7)
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator

    ticks = [t for t in (0.5, 1, 1.5, 2, 3, 5, 8, 12) if t <= 1.3 * top]
    for ax, axes in ((ax1, (ax1.yaxis,)), (ax2, (ax2.xaxis, ax2.yaxis))):
        for axis in axes:
            axis.set_major_locator(FixedLocator(ticks))
            axis.set_major_formatter(FuncFormatter(lambda v, _: f"×{v:g}"))
            axis.set_minor_locator(NullLocator())
    fig.tight_layout()
    return fig


def figures(rows) -> dict:
    """Predicted against measured error and cost over the proof's scenes."""
    import matplotlib.figure

    ok = [r for r in rows if "measured_error" in r]
    fig = matplotlib.figure.Figure(figsize=(16, 4.6))
    ax1, ax2, ax3 = fig.subplots(1, 3)
    kinds = sorted({r["kind"] for r in ok})
    for kind in kinds:
        sel = [r for r in ok if r["kind"] == kind]
        nz = [r for r in sel if r["measured_error"] > 0]
        pts = ax1.scatter([r["predicted_error"] / r["tolerance"] for r in nz],
                          [r["measured_error"] / r["tolerance"] for r in nz], label=kind, s=18)
        zero = [r for r in sel if r["measured_error"] == 0]
        if zero:  # the plan is the full model's heights: no error to draw on a log axis
            ax1.scatter([r["predicted_error"] / r["tolerance"] for r in zero], [1e-7] * len(zero), marker="v", s=18,
                        color=pts.get_facecolor()[0])
        ax2.scatter([r["predicted_saving"] for r in sel], [r["measured_saving"] for r in sel], label=kind, s=18)
    lo = 1e-6
    ax1.plot([lo, 1], [lo, 1], "k--", lw=0.8, label="measured = predicted")
    ax1.axhline(1.0, color="r", lw=0.8, label="tolerance")
    ax1.set(xscale="log", yscale="log", xlabel="predicted error / tolerance",
            ylabel="measured error / tolerance (▼: exactly 0)", title=f"height error, {len(ok)} generated scenes")
    ax1.legend(fontsize=7)
    top = max([r["measured_saving"] for r in ok] + [r["predicted_saving"] for r in ok] + [1.5])
    ax2.plot([0.8, top], [0.8, top], "k--", lw=0.8)
    ax2.set(xscale="log", yscale="log", xlabel="predicted saving (full cost / plan cost)",
            ylabel="measured saving", title="cost saving of the plan")
    ax2.legend(fontsize=7)
    floor = 1e-4
    for caustics, marker in ((False, "o"), (True, "s")):
        sel = [r for r in ok if r.get("caustics", False) == caustics]
        if not sel:
            continue
        ax3.scatter([max(r["predicted_colour"] / r["colour_tolerance"], floor) for r in sel],
                    [max(r["measured_colour_optics"] / r["colour_tolerance"], floor) for r in sel], marker=marker,
                    s=18, label=f"optics terms{' and caustics' if caustics else ''} ({len(sel)} scenes)")
        ax3.scatter([max(r["predicted_colour"] / r["colour_tolerance"], floor) for r in sel],
                    [max(r["measured_colour"] / r["colour_tolerance"], floor) for r in sel], marker=marker,
                    s=18, facecolors="none", edgecolors="grey", label="whole image (heights too)" if caustics else None)
    ax3.plot([floor, 1], [floor, 1], "k--", lw=0.8)
    ax3.axhline(1.0, color="r", lw=0.8, label="colour tolerance")
    ax3.set(xscale="log", yscale="log", xlabel="predicted colour error / tolerance (floored at 1e-4)",
            ylabel="measured / tolerance", title="colour (image quanta)")
    ax3.legend(fontsize=7)
    fig.tight_layout()
    return {"proof": fig}
