"""wavephys: physically validated water waves for real-time rendering, on JAX.

Core objects: :class:`Water` (g, ρ, σ, depth) and :class:`Grid` (n, length). Physics by
topic: :mod:`wavephys.dispersion`, :mod:`wavephys.ring_waves`, :mod:`wavephys.heights`,
:mod:`wavephys.boundary`, :mod:`wavephys.interpolation`, :mod:`wavephys.disturbances`,
:mod:`wavephys.wind`, :mod:`wavephys.simulation`; peer methods
:mod:`wavephys.finite_difference`, :mod:`wavephys.truncated_kernel`; the validation
harness :mod:`wavephys.validate`. Formulas: SPEC.md of the project.
"""

from wavephys.params import Grid, Water
from wavephys.simulation import Simulation, State, Surface
from wavephys.disturbances import Stones

__all__ = ["Grid", "Water", "Simulation", "State", "Surface", "Stones"]
__version__ = "0.1.0"
