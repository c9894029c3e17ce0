"""The simulation layer's steppers behind the one interface (:mod:`wavephys.core.stepper`): the spectral model
(:class:`SpectralStepper`); the varying floors (:class:`DepthStepper`, :class:`ProfileStepper`), nonlinear
shallow water and the split live beside their schemes and are re-exported here. Every stepper and the
registry: :mod:`wavephys.steppers`.
"""

from __future__ import annotations

import jax.numpy as jnp

from wavephys.core.inputs import check_instance
from wavephys.core.stepper import Stepper, _fixed_dt
from wavephys.simulation.depth import DepthStepper, ProfileStepper
from wavephys.simulation.shallow_water import ShallowWaterStepper
from wavephys.simulation.split import SplitStepper

__all__ = ["SpectralStepper", "DepthStepper", "ProfileStepper", "ShallowWaterStepper", "SplitStepper"]


class SpectralStepper(Stepper):
    """Exact linear waves on the model's grid (:func:`wavephys.simulation.step`): any Δt, walls and tanks as
    the :class:`~wavephys.simulation.Model` has them; continuous sources (forcing) act in the loop.

    Parameters
    ----------
    model : Model
    sources : sequence, optional
        Continuous sources (a ``rate`` hook); impulses go in with :func:`~wavephys.simulation.add_source`.
    """

    def __init__(self, model, sources=()):
        from wavephys.simulation.model import Model
        from wavephys.simulation.sources import sort_sources

        check_instance("model", model, Model, "wavephys.simulation.Model")
        impulses, rates, adders = sort_sources(model, sources)
        if impulses or adders:
            raise ValueError("sources: the SpectralStepper stepper takes continuous sources (forcing) only; add impulses "
                             "with add_source first, and step ships with wavephys.simulation.step")
        self.model, self.rates = model, tuple(rates)
        from wavephys.simulation.state import State
        self.state_type = State

    def _parts(self):
        from wavephys.simulation.model import operators
        return None, (self.model, operators(self.model), self.rates)

    def _checked_state(self, state):
        from wavephys.simulation.stepping import _check_state, _laid
        super()._checked_state(state)
        _check_state(self.model, state)
        return _laid(self.model, state)

    @classmethod
    def _advance(cls, static, dynamic, state, dt):
        from wavephys.simulation.stepping import _dt_error, _pure_step
        model, ops, rates = dynamic
        return _pure_step(model, ops, state, (), rates, _dt_error(model))[0]

    @classmethod
    def _dt(cls, static, dynamic, state):
        return jnp.asarray(dynamic[0].dt, state.time.dtype)

    @classmethod
    def _height(cls, static, dynamic, state):
        from wavephys.simulation.stepping import _surface
        model, ops, _ = dynamic
        return _surface(model, ops, state.fields, state.time).eta

    def _check_dt(self, state, dt):
        return _fixed_dt(self, float(self.model.dt), dt)

    @property
    def sides(self):
        wx, wy = self.model.wall_axes
        x = "wall" if wx else ("open" if self.model.margin else "periodic")
        y = "wall" if wy else ("open" if self.model.margin else "periodic")
        return (x, x, y, y)
