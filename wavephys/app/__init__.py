"""The application layer: the ``wavephys`` command (:mod:`~wavephys.app.cli`), the built-in
scenes (:mod:`~wavephys.app.scenes`) and the registry of checks
(:mod:`~wavephys.app.registry`). The only code that uses both wavephys and optics."""

SCENES = ("pool", "shore", "ship", "storm", "calm", "beach", "dambreak", "wakebeach", "harbour")
"""The built-in renderer scenes (:mod:`wavephys.app.scenes`), by name."""
