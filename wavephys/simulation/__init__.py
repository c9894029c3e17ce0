"""The spectral wave simulation: a pure step over a model pytree, and a convenience wrapper.

* :class:`Model` — grid, water, Δt and numerical options (a frozen pytree);
* :class:`State`, :class:`Surface` — the wave field, and the surface (η, η̇) it shows;
* :func:`step` — ``step(model, state, sources=()) -> (state, surface)``, pure and
  ``jit``/``vmap``/``grad``-able; :func:`run`, :func:`surface`, :func:`energy`,
  :func:`frame`, :func:`initial_state`, :func:`state_from_psi`, :func:`add_height`,
  :func:`add_source`;
* :class:`Source` — the protocol of everything that makes waves (stones, wind seas,
  forcing functions, ships; :mod:`wavephys.simulation.sources`);
* :class:`Simulation` — today's object API, a thin wrapper holding one model.
"""

from wavephys.simulation.driver import Simulation
from wavephys.simulation.model import Model, Operators, operators
from wavephys.simulation.sources import Source
from wavephys.simulation.state import State, Surface
from wavephys.simulation.stepping import (add_height, add_source, checked, energy, frame, initial_state, run,
                                          state_from_psi, step, surface)

__all__ = ["Model", "Operators", "operators", "State", "Surface", "Source", "Simulation", "step", "run", "surface",
           "energy", "frame", "initial_state", "state_from_psi", "add_height", "add_source", "checked"]
