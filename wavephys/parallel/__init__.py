"""Scale-out on JAX's own engine: one grid over many devices, many scenes over many devices.

* :mod:`~wavephys.parallel.layout` — :func:`row_mesh`, and where a sharded model's
  fields (rows split) and half spectra (kx columns split, padded) live;
* :mod:`~wavephys.parallel.fft` — the slab-decomposed :func:`rfft2`/:func:`irfft2`
  (``shard_map`` + one ``all_to_all`` each) the sharded step uses, and the bytes they move;
* :mod:`~wavephys.parallel.sweep` — :func:`sweep`, ``vmap`` in a device and the batch over
  devices;
* :mod:`~wavephys.parallel.hosts` — :func:`initialize`, :func:`hosts_mesh`, :func:`gather`
  for ``jax.distributed`` runs over many processes or hosts.

A sharded simulation is a model with a mesh: ``Model(grid, ..., mesh=row_mesh(devices))``
or ``Simulation(grid, ..., devices=jax.devices())``; everything else (stones, wind, forcing,
ships, the cutoff, ``run``) is unchanged.
"""

from wavephys.parallel.fft import collective_bytes, exchanged_bytes, irfft2, rfft2
from wavephys.parallel.hosts import gather, hosts_mesh, initialize, is_initialized
from wavephys.parallel.layout import row_mesh, spectrum_width
from wavephys.parallel.sweep import sweep

__all__ = ["row_mesh", "spectrum_width", "rfft2", "irfft2", "exchanged_bytes", "collective_bytes", "sweep",
           "initialize", "is_initialized", "hosts_mesh", "gather"]
