"""The validation harness: measure the physics of *any* simulator's output.

Users call these from their own test suites on height fields produced by whatever code
they want to check (ours, a shader, a finite-difference toy):

* :func:`measure_dispersion`, :func:`dispersion_error`, :func:`dispersion_check` — the ω–k
  ridge against theory (the check names the band, the worst k and the likely cause);
* :func:`measure_energy` — potential, capillary and kinetic energy per unit area;
* :func:`wake_angle` (``"max"``, ``"cusp"``, ``"darmon"``), :func:`track_wavelength` — wake geometry;
  :func:`wake_check` — a frame's wake angle (outer edge, or the angle of maximum amplitude by
  Darmon et al.'s definition) against theory, degrees in and out;
* :class:`Record` — frames + Δx + Δt (+ η̇, claimed depth and σ) from arrays with named axes,
  from exported frames (EXR, 16-bit PNG, npy, npz) or a saved record; :func:`time_derivative`;
* laws on a record: :func:`energy_check` (with the damping per k), :func:`standing_check`,
  :func:`direction_check`, :func:`group_velocity_check`, :func:`ring_arrival_check`; on
  textures: :func:`tiling_check`, :func:`normals_check`, :func:`resolution_check`,
  :func:`caustics_flux_check`, :func:`quantization_check`; all of a record's at once:
  :func:`check_record` over the registry :data:`RECORD_CHECKS`;
* a shallow-water simulator's depth frames: :func:`mass_check`, :func:`lake_at_rest_check`,
  :func:`dam_break_check` (Ritter's front, Stoker's bore), each naming the likely cause;
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
    "WAKE_ANGLE_METHODS": "wake", "track_wavelength": "wake", "wake_angle_darmon": "wake",
    "darmon_angle_theory": "wake", "darmon_crests": "wake", "cusp_angle_theory": "wake",
    "max_amplitude_angle_theory": "wake", "WAKE_ANGLE_THEORIES": "wake",
    "wake_angle_theory": "wake", "wake_check": "steady", "WAKE_ANGLES": "steady",
    "Check": "checks", "compare": "checks", "bound": "checks", "assert_check": "checks",
    "Record": "record", "Rate": "record", "time_derivative": "record",
    "Damping": "energy", "measure_damping": "energy", "energy_check": "energy",
    "Travel": "travel", "measure_travel": "travel", "standing_check": "travel", "direction_check": "travel",
    "group_velocity_check": "packets", "ring_arrival_check": "packets",
    "tiling_check": "maps", "normals_check": "maps", "resolution_check": "maps", "caustics_flux_check": "maps",
    "quantization_check": "maps",
    "RECORD_CHECKS": "suite", "RecordReport": "suite", "check_record": "suite",
    "mass_check": "shallow_water", "lake_at_rest_check": "shallow_water", "dam_break_check": "shallow_water",
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
