"""The foundation every other layer builds on: water properties, the grid and its one
coordinate convention, spectral derivatives and sampling, input checks, pytrees, and
method families. Nothing here knows about waves in particular. Names load on first use
(so that ``import wavephys`` and the pytest plugin cost no JAX import)."""

import importlib

_EXPORTS = {"Grid": "wavephys.core.grid", "Water": "wavephys.core.water", "GRAVITY": "wavephys.core.water",
            "DENSITY": "wavephys.core.water", "SURFACE_TENSION": "wavephys.core.water",
            "Methods": "wavephys.core.methods", "stack": "wavephys.core.pytree"}
__all__ = list(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(importlib.import_module(_EXPORTS[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'wavephys.core' has no attribute {name!r}")
