"""wavephys: physically validated water waves for real-time rendering, on JAX.

Layers, bottom to top (``docs/architecture.md``):

* :mod:`wavephys.core` — :class:`Water`, :class:`Grid` (the one coordinate convention),
  spectral derivatives, sampling, input checks, method families;
* :mod:`wavephys.physics` — dispersion, ring waves, heights, the open-ocean cutoff,
  frames between steps, stones, wind seas, Stokes waves, ship waves, steady wakes;
* :mod:`wavephys.simulation` — the pure step ``step(model, state, sources)`` and the
  :class:`Simulation` convenience wrapper;
* :mod:`wavephys.models` — the peer methods we compare against (finite differences,
  truncated kernels);
* :mod:`wavephys.surfaces` — the cheap surface models engines ship (gradient-noise fBm,
  Gerstner sums, choppy displacement and foam; ``wavephys.noise``, ``wavephys.gerstner``,
  ``wavephys.choppy``) and the resampling of displaced surfaces onto a grid;
* :mod:`wavephys.harness` — measurement of *any* simulator's output (dispersion,
  energy, wake angles), check rows and the pytest plugin;
* :mod:`wavephys.checks` — the built-in validations of the wave physics;
* :mod:`wavephys.plot` — figures;
* :mod:`wavephys.app` — the ``wavephys`` command, built-in scenes and the check
  registry, and :mod:`wavephys.planner` — the scene planner: the only code that uses
  both wavephys and :mod:`optics`.

Importing ``wavephys`` is cheap: names load on first use. Old module paths
(``wavephys.dispersion``, ``wavephys.validate``, …) still import.
"""

from __future__ import annotations

import importlib

from wavephys.core.aliases import install as _install

__version__ = "0.2.0"

_EXPORTS = {
    "Grid": "wavephys.core", "Water": "wavephys.core", "stack": "wavephys.core",
    "Model": "wavephys.simulation", "State": "wavephys.simulation", "Surface": "wavephys.simulation",
    "Simulation": "wavephys.simulation", "step": "wavephys.simulation",
    "Stones": "wavephys.physics.disturbances",
}
__all__ = sorted(_EXPORTS)

_legacy_getattr = _install(__name__, {
    "params": ("wavephys.core.water", "wavephys.core.grid"),
    "dispersion": "wavephys.physics.dispersion",
    "ring_waves": "wavephys.physics.ring_waves",
    "heights": "wavephys.physics.heights",
    "boundary": "wavephys.physics.boundary",
    "interpolation": "wavephys.physics.interpolation",
    "disturbances": "wavephys.physics.disturbances",
    "wind": "wavephys.physics.wind",
    "stokes": "wavephys.physics.stokes",
    "ship_waves": "wavephys.physics.ship_waves",
    "wake": ("wavephys.physics.wake", "wavephys.harness.wake"),
    "finite_difference": "wavephys.models.finite_difference",
    "truncated_kernel": "wavephys.models.truncated_kernel",
    "validate": "wavephys.harness",
    "pytest_plugin": "wavephys.app.pytest_plugin",
    "cli": "wavephys.app.cli",
    "noise": "wavephys.surfaces.noise",
    "gerstner": "wavephys.surfaces.gerstner",
    "choppy": "wavephys.surfaces.choppy",
    "scenes": "wavephys.app.scenes",
})  # every old name warns when imported (removed in 0.4)


def __getattr__(name: str):
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    return _legacy_getattr(name)


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))
