"""The source protocol: everything that puts waves into the simulation is one kind of object.

A source is any object with a ``check(model)`` method (host-side validation, called
before any work) and at least one of three hooks, according to how it acts on the wave
field ψ = φ + iχ during a step [t, t + Δt] (docs/physics.md §1.2):

``impulse(model, ops, t) -> (Δφ̂, Δχ̂)``
    A sudden disturbance at t, added before the surface of t is taken: half spectra
    (``rfft2`` of the two real fields, m²/s per sample; either may be ``None``).
    :class:`~wavephys.physics.disturbances.Stones`, :class:`~wavephys.physics.wind.WindSea`.
``rate(model, ops, t) -> Ŝ``
    A continuous forcing of the potential, ψ̂_t = −iωψ̂ + Ŝ: the half spectrum of the real
    field S at time t, m²/s². The step evaluates it at the midpoints of the source's
    ``substeps`` sub-intervals (attribute, default 1) and propagates each exactly to the
    step's end (Duhamel). :class:`~wavephys.physics.forcing.Forcing` (a user's pressure
    function).
``add(model, fields, t) -> fields``
    Host-side: waves added to the stacked (φ, χ) fields after the step's cutoff (the
    array may be donated). :class:`~wavephys.physics.ship_waves.Ship`.

``impulse`` and ``rate`` are traced into the compiled step, so they must be pure
``jax.numpy`` code of pytree sources; ``add`` runs in Python between compiled programs
(ships follow Python paths) and cannot be used under ``jit``/``vmap``. Writing a new
source means writing one class with ``check`` and one hook; the step needs no change.
"""

from __future__ import annotations

from typing import Protocol, runtime_checkable

from wavephys.core.inputs import describe, is_traced

__internal__ = True  # tooling for the library's own modules: not fuzzed as public API
__all__ = ["Source", "HOOKS"]

HOOKS = ("impulse", "rate", "add")


@runtime_checkable
class Source(Protocol):
    """The protocol (module doc): ``check(model)`` plus one of ``impulse``, ``rate``, ``add``."""

    def check(self, model) -> None:
        ...


def sort_sources(model, sources) -> tuple[tuple, tuple, tuple]:
    """Check every source against ``model`` (host-side, skipped for traced ones) and sort them
    into (impulses, rates, adders). TypeError for an object that is not a source."""
    if isinstance(sources, (str, bytes)) or not hasattr(sources, "__iter__"):
        raise TypeError(f"sources must be a sequence of sources (Stones, WindSea, Forcing, Ship, …), "
                        f"got {describe(sources)}")
    groups = {hook: [] for hook in HOOKS}
    for i, source in enumerate(sources):
        hooks = [h for h in HOOKS if callable(getattr(source, h, None))]
        if not hooks or not callable(getattr(source, "check", None)):
            raise TypeError(f"sources[{i}] is not a simulation source (it needs check(model) and one of "
                            f"{', '.join(HOOKS)}): got {describe(source)}")
        if not is_traced(source):
            source.check(model)
        for h in hooks:
            groups[h].append(source)
    return tuple(groups["impulse"]), tuple(groups["rate"]), tuple(groups["add"])
