"""The built-in validations of the wave physics: scenes with known answers, measured.

Each ``check_*`` function runs one scene and returns :class:`~wavephys.harness.Check`
rows. :data:`CHECKS` lists them by name (lower-case words joined by hyphens, usable
unquoted on the command line) in the order ``wavephys validate`` runs them; the
application's registry (:mod:`wavephys.app.registry`) adds the optics checks after them,
and the test suite asserts every row of that registry. Adding a validation: write a
``check_*`` function in the topic's module and add it here.
"""

from wavephys.checks.boundaries import check_cutoff, check_fd_stability, check_second_order
from wavephys.checks.dispersion import (check_dispersion_limits, check_dispersion_minima, check_fd_dispersion,
                                        check_inverse_dispersion, check_measured_dispersion, dispersion_scene)
from wavephys.checks.moving_sources import check_capillary_wake, check_ship_kernels, check_steady_wakes
from wavephys.checks.surfaces import check_choppy, check_gerstner, check_noise_surfaces
from wavephys.checks.depth import check_depth
from wavephys.checks.shallow_water import check_shallow_water
from wavephys.checks.walls import check_walls
from wavephys.checks.propagation import (check_energy_conservation, check_energy_measure, check_hermite,
                                         check_step_composition)
from wavephys.physics.boundary import cutoff_boundary, cutoff_reflection
from wavephys.physics.heights import STEEPNESS, second_order_breakdown, second_order_error
from wavephys.physics.interpolation import hermite_error

CHECKS = {
    "dispersion-limits": check_dispersion_limits,
    "dispersion-minima": check_dispersion_minima,
    "inverse-dispersion": check_inverse_dispersion,
    "measured-dispersion": check_measured_dispersion,
    "fd-dispersion": check_fd_dispersion,
    "energy-conservation": check_energy_conservation,
    "step-composition": check_step_composition,
    "energy-measurement": check_energy_measure,
    "open-ocean-cutoff": check_cutoff,
    "reflecting-walls": check_walls,
    "varying-depth": check_depth,
    "shallow-water": check_shallow_water,
    "second-order-heights": check_second_order,
    "hermite-frames": check_hermite,
    "fd-stability": check_fd_stability,
    "ship-kernels": check_ship_kernels,
    "steady-wakes": check_steady_wakes,
    "capillary-wake": check_capillary_wake,
    "noise-surfaces": check_noise_surfaces,
    "gerstner-waves": check_gerstner,
    "choppy-waves": check_choppy,
}
"""The wave validations by name, in the order ``wavephys validate`` runs them."""

__all__ = ["CHECKS", "dispersion_scene", "cutoff_reflection", "cutoff_boundary", "hermite_error",
           "second_order_error", "second_order_breakdown", "STEEPNESS"] + [f.__name__ for f in CHECKS.values()]
