"""Wave physics, one module per topic (docs/physics.md §1):

* :mod:`~wavephys.physics.dispersion` — ω(k) of capillary-gravity waves, deep and finite depth;
* :mod:`~wavephys.physics.ring_waves` — exact propagation in Fourier space;
* :mod:`~wavephys.physics.heights` — first- and second-order heights from the wave field;
* :mod:`~wavephys.physics.boundary` — the open-ocean cutoff and its measured reflection;
* :mod:`~wavephys.physics.interpolation` — Hermite frames between steps;
* :mod:`~wavephys.physics.disturbances` — stones (an impulse source);
* :mod:`~wavephys.physics.wind` — wind-sea spectra and the wind-sea source;
* :mod:`~wavephys.physics.forcing` — surface pressure forcing (a continuous source);
* :mod:`~wavephys.physics.stokes` — exact Stokes waves (a reference);
* :mod:`~wavephys.physics.ship_waves` — Loviscach's Φ1/Φ2 ship kernels, hulls, paths, ships;
* :mod:`~wavephys.physics.wake` — steady wakes of pressure sources, Kelvin's angle, cusp lines;
* :mod:`~wavephys.physics.spray` — spray drops in flight: gravity and the air's drag, two steps.

Everything here is a pure function of arrays and the :class:`~wavephys.Water`/
:class:`~wavephys.Grid` pytrees; nothing here steps a simulation (that is
:mod:`wavephys.simulation`) or measures one (:mod:`wavephys.harness`).
"""
