"""Charts of a plan: the Pareto front of candidate models and the error budget of the chosen one."""

from __future__ import annotations

__all__ = ["plot_plan"]


def plot_plan(p, measured: dict | None = None):
    """A plan's two charts: cost against error of every candidate, and its error budget.

    The first panel draws predicted cost against predicted error of every candidate (the
    Pareto front joined, the tolerance and the chosen model marked); the second the error
    budget of the chosen model by term (each term's error alone, against the tolerance).

    Parameters
    ----------
    p : Plan
        A plan (:func:`wavephys.planner.plan`).
    measured : dict, optional
        {Choices: measured max-norm height error, m}, drawn as crosses.

    Returns
    -------
    matplotlib.figure.Figure
        Drawn without pyplot (no backend is chosen).
    """
    import matplotlib.figure

    from wavephys.core.inputs import check_instance
    from wavephys.planner.plan import Plan, candidates

    check_instance("p", p, Plan, "wavephys.planner.Plan")
    if measured is not None and not isinstance(measured, dict):
        raise TypeError(f"measured must be a dict {{Choices: measured error, m}} or None, got {type(measured).__name__}")
    cands = candidates(p.scene)
    fig = matplotlib.figure.Figure(figsize=(11, 4.2))
    ax1, ax2 = fig.subplots(1, 2, gridspec_kw=dict(width_ratios=(1.3, 1)))
    floor = p.tolerance * 1e-4
    err = [max(c.bounds.total, floor) for c in cands]
    ax1.scatter(err, [c.cost for c in cands], s=10, color="0.6", label="candidates (predicted)")
    front = list(p.front)
    ax1.plot([max(c.bounds.total, floor) for c in front], [c.cost for c in front], "-o", ms=3, color="C0",
             label="Pareto front")
    ax1.axvline(p.tolerance, color="r", lw=0.9, label=f"tolerance {p.tolerance:.2g} m")
    ax1.scatter([max(p.predicted_error, floor)], [p.height_cost], s=80, marker="*", color="C3", zorder=5,
                label="chosen")
    if measured:
        by = {c.choices: c for c in cands}
        pts = [(max(v, floor), by[k].cost) for k, v in measured.items() if k in by]
        if pts:
            ax1.scatter(*zip(*pts), marker="x", color="k", label="measured error")
    ax1.set(xscale="log", yscale="log", xlabel="height error, m (max norm over frames)",
            ylabel="predicted cost, s", title=f"{p.scene.name}: candidate models")
    ax1.legend(fontsize=7)
    rows = [t for t in p.terms if t.unit == "m"]
    names = [f"{t.term}={t.choice}" for t in rows] + ["float32 floor"]
    values = [t.error for t in rows] + [p.bounds.rounding]
    ax2.barh(names, [v - floor if v > floor else 0.0 for v in values], left=floor, color="C0")
    for i, v in enumerate(values):
        if v <= 0:
            ax2.text(floor * 1.5, i, "0 (as the full model)", va="center", fontsize=7, color="0.35")
    ax2.axvline(p.tolerance, color="r", lw=0.9, label=f"tolerance {p.tolerance:.2g} m")
    ax2.axvline(p.predicted_error, color="C3", lw=0.9, ls="--", label=f"chosen model {p.predicted_error:.2g} m")
    ax2.set(xscale="log", xlim=(floor, max(p.tolerance, p.predicted_error) * 3),
            xlabel="height error of the term alone, m", title="error budget")
    ax2.legend(fontsize=7)
    fig.tight_layout()
    return fig
