"""Benchmarks: speed against accuracy for every family of methods (``python -m bench``)."""
