"""Every way of stepping water in time, behind one interface (:class:`~wavephys.core.stepper.Stepper`).

Each stepper is one small class beside its scheme; this package gathers them and keeps the registry:

===========================  ==========================================  ======================  ==================
class                        method                                      state                   Δt
===========================  ==========================================  ======================  ==================
:class:`SpectralStepper`      exact linear waves (the spectral step)      ``State``               ``model.dt`` (any)
:class:`DepthStepper`         a varying floor (levels, symmetric,         ``DepthState``          ``model.dt``
                              linear shallow water)
:class:`ProfileStepper`       the same on one row: plane waves over h(x)  ``ProfileState``        fixed ``dt``
:class:`ShallowWaterStepper`  nonlinear shallow water, wet/dry            ``SWState``             adaptive (``cfl``)
:class:`SplitStepper`         shallow water + dispersive waves            ``SWState``             adaptive
:class:`PipesStepper`         virtual pipes                               ``PipesState``          fixed ``dt``
:class:`FiniteDifferenceStepper`  the explicit wave equation              ``TwoLevelState``       fixed ``dt``
:class:`KernelStepper`        truncated kernels (leapfrog)                ``TwoLevelState``       fixed ``dt``
===========================  ==========================================  ======================  ==================

All share ``init``, ``step``, ``run(until=|steps=, every=, callback=)``, the pure ``advance``, ``advance_to``
and ``frames``, one clock and one vocabulary of ``sides`` (:data:`SIDE_KINDS`). The problem set that runs every
stepper on the same physics, or records its refusal by name: ``tests/simulation/test_steppers.py``.

Examples
--------
>>> import numpy as np
>>> from wavephys.simulation.shallow_water import ShallowWater, sw_state
>>> bed = -np.ones((1, 64))
>>> stepper = ShallowWaterStepper(ShallowWater(0.1), bed)
>>> run = stepper.run(sw_state(bed, 0.01 * np.cos(np.linspace(0, np.pi, 64))[None]), until=1.0, every=0.5)
>>> run.times.tolist(), run.frames.shape
([0.5, 1.0], (2, 1, 64))
"""

from wavephys.core.stepper import SIDE_KINDS, Run, Stepper, TwoLevelState
from wavephys.models.finite_difference import FiniteDifferenceStepper
from wavephys.models.pipes import PipesStepper
from wavephys.models.truncated_kernel import KernelStepper
from wavephys.simulation.shallow_water import ShallowWaterStepper
from wavephys.simulation.split import SplitStepper
from wavephys.simulation.depth import ProfileState, ProfileStepper
from wavephys.simulation.steppers import DepthStepper, SpectralStepper

__all__ = ["Stepper", "Run", "TwoLevelState", "SIDE_KINDS", "STEPPERS", "SpectralStepper", "DepthStepper",
           "ProfileStepper", "ProfileState", "ShallowWaterStepper", "SplitStepper", "PipesStepper",
           "FiniteDifferenceStepper", "KernelStepper"]

STEPPERS = {cls.__name__: cls for cls in (SpectralStepper, DepthStepper, ProfileStepper, ShallowWaterStepper,
                                          SplitStepper, PipesStepper, FiniteDifferenceStepper, KernelStepper)}
"""Every stepper class by name (a new stepper is one class beside its scheme plus its entry here and its problems
in the set)."""
