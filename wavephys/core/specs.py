"""Ready-made argument checks for :func:`wavephys.core.inputs.validate` (one place for each rule)."""

from __future__ import annotations

from wavephys.core.grid import Grid
from wavephys.core.inputs import (Array, Bool, Choice, FilePath, Function, Instance, Int, Items, Mapping, Maybe,
                                  Real, Spec, Text, Vector, field_of)
from wavephys.core.water import Water

__internal__ = True
__all__ = ["model_grid", "GRID", "WATER", "REAL", "POSITIVE", "NON_NEGATIVE", "FRACTION", "BOOL", "INDEX", "COUNT", "ARRAY",
           "NON_NEGATIVE_ARRAY", "POSITIVE_ARRAY", "COMPLEX_ARRAY", "FIELD", "COMPLEX_FIELD", "VECTOR2", "VECTOR3",
           "Array", "Bool", "Choice", "Function", "Instance", "Int", "Maybe", "Real", "Spec", "Vector", "field_of",
           "Text", "Items", "Mapping", "FilePath", "TEXT", "PATH", "FUNCTION"]

GRID = Instance(Grid, "wavephys.Grid")


def model_grid(model, name: str = "model") -> Grid:
    """The grid of a simulation model, for sources that must not import the simulation layer:
    TypeError unless ``model`` looks like a ``wavephys.simulation.Model``.

    Parameters
    ----------
    model : wavephys.simulation.Model
        Anything with a :class:`Grid` ``grid``, a ``water`` and a ``dt``.
    name : str
        The parameter's name in messages.

    Returns
    -------
    Grid
        ``model.grid``.
    """
    from wavephys.core.inputs import describe

    grid = getattr(model, "grid", None)
    if not isinstance(grid, Grid) or not hasattr(model, "water") or not hasattr(model, "dt"):
        raise TypeError(f"{name} must be a wavephys.simulation.Model, got {describe(model)}")
    return grid
WATER = Instance(Water, "wavephys.Water")
REAL = Real()
POSITIVE = Real(lo=0.0, lo_open=True)
NON_NEGATIVE = Real(lo=0.0)
FRACTION = Real(lo=0.0, hi=1.0)
BOOL = Bool()
INDEX = Int(lo=0)
COUNT = Int(lo=1)
ARRAY = Array()
NON_NEGATIVE_ARRAY = Array(lo=0.0)
POSITIVE_ARRAY = Array(lo=0.0, lo_open=True)
COMPLEX_ARRAY = Array(complex_ok=True)
FIELD = field_of("grid")
COMPLEX_FIELD = field_of("grid", complex_ok=True)
VECTOR2 = Vector(2)
VECTOR3 = Vector(3)
TEXT = Text()
PATH = FilePath()
FUNCTION = Function()
