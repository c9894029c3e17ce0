"""Built-in example scenes, shipped as TOML files in ``wavephys/planner/data/scenes``.

``ripples`` a 0.4 m tank at 3 mm texels (capillary waves resolved: σ is kept);
``ocean``   128 m of deep open sea at 1 m texels under an 8 m/s wind (σ is dropped);
``pond``    three stones in a 1 m deep pond (finite depth matters);
``lake``    stones in a 40 m deep lake (kh > π everywhere: tanh kh is dropped);
``harbour`` a launch at 3 m/s in a 6 m deep basin;
``pool``    two stones in a walled 6 m pool (reflecting walls);
``shelf``   stones off a floor shelving 5 cm per metre (1.25–2.75 m deep).
"""

from __future__ import annotations

from importlib import resources

from wavephys.core.inputs import check_choice

__all__ = ["BUILTIN_SCENES", "builtin_scene", "builtin_path"]

BUILTIN_SCENES = ("ripples", "ocean", "pond", "lake", "harbour", "pool", "shelf")


def builtin_path(name: str):
    """The TOML file of a built-in scene.

    Parameters
    ----------
    name : str
        A name in :data:`BUILTIN_SCENES`.

    Returns
    -------
    importlib.resources.abc.Traversable
        The file inside the installed package (``str()`` of it is a path on disk).
    """
    check_choice("name", name, BUILTIN_SCENES)
    return resources.files("wavephys.planner").joinpath("data", "scenes", f"{name}.toml")


def builtin_scene(name: str):
    """A built-in scene by name.

    Parameters
    ----------
    name : str
        A name in :data:`BUILTIN_SCENES` (``ripples``, ``ocean``, ``pond``, ``lake``, ``harbour``, ``pool``: a walled pool, ``shelf``: a sloping floor).

    Returns
    -------
    Scene
        The scene read from its TOML file (:func:`builtin_path`).

    Examples
    --------
    >>> builtin_scene("pond").texels
    128
    """
    from wavephys.planner.scene import Scene

    path = builtin_path(name)
    return Scene.from_toml(str(path))
