"""The peer and cheap surface models that wavephys compares against, one module each:

* :mod:`~wavephys.models.finite_difference` — the explicit 5-point wave equation
  (Kass & Miller 1990; Gomez 2000): non-dispersive, stable to cΔt/Δx = 1/√2;
* :mod:`~wavephys.models.truncated_kernel` — the exact ω² kernel cut to a P × P stencil
  (iWave, Tessendorf 2004);
* :mod:`~wavephys.models.two_level` — the shared leapfrog driver of both.

Each has its failure boundary measured (``wavephys.checks``, ``python -m bench boundaries``).
"""
