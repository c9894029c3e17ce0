"""The validation harness: measure the physics of *any* simulator's output.

Users call these from their own test suites on height fields produced by whatever code
they want to check (ours, a shader, a finite-difference toy):

* :func:`measure_dispersion`, :func:`dispersion_error`, :func:`dispersion_check` — the ω–k
  ridge against theory (the check names the band, the worst k and the likely cause);
* :func:`measure_energy` — potential, capillary and kinetic energy per unit area;
* :func:`wake_angle` (``"max"``, ``"cusp"``), :func:`track_wavelength` — wake geometry;
* :class:`Check`, :func:`compare`, :func:`bound`, :func:`assert_check` — result rows that
  report expected against measured against tolerance, and fail with that line.

The pytest plugin (:mod:`wavephys.app.pytest_plugin`, registered as ``pytest11``; the old
path ``wavephys.harness.pytest_plugin`` still imports, with a DeprecationWarning) exposes
them as fixtures. Names load on first use: the plugin costs test sessions that
do not use its fixtures no JAX import.
"""

import importlib

from wavephys.core.aliases import install as _install

_EXPORTS = {
    "DispersionSamples": "dispersion", "measure_dispersion": "dispersion", "dispersion_error": "dispersion",
    "dispersion_check": "dispersion",
    "Energy": "energy", "measure_energy": "energy",
    "WakeAngle": "wake", "wake_angle": "wake", "wake_angle_max": "wake", "wake_angle_cusp": "wake",
    "WAKE_ANGLE_METHODS": "wake", "track_wavelength": "wake",
    "Check": "checks", "compare": "checks", "bound": "checks", "assert_check": "checks",
}
__all__ = list(_EXPORTS)


_moved = _install(__name__, {"pytest_plugin": "wavephys.app.pytest_plugin"}, deprecated=("pytest_plugin",))


def __getattr__(name):
    if name in _EXPORTS:
        value = getattr(importlib.import_module(f"wavephys.harness.{_EXPORTS[name]}"), name)
        globals()[name] = value
        return value
    return _moved(name)


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))
