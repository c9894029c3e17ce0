"""The simulation model: grid, water, Δt and the numerical options, as one frozen pytree.

The grid's side length, the water's g, ρ, σ and depth, and Δt are leaves (``jit``,
``vmap`` and ``grad`` sweep them); the sizes and switches are static (they fix array
shapes and compiled programs). ``dataclasses.replace(model, water=...)`` makes variants.
:func:`operators` turns a model into the Fourier multipliers the step applies.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass, field
from typing import NamedTuple, Optional

import jax
import jax.numpy as jnp
import numpy as np
from jax.sharding import Mesh

from wavephys.core.grid import Grid
from wavephys.core.inputs import check_array, check_bool, check_instance, check_int, check_scalar, is_traced
from wavephys.core.pytree import register
from wavephys.core.water import Water
from wavephys.parallel.layout import (AXIS, check_mesh, constrain, device_count, field_sharding, place, spectrum_sharding,
                                      spectrum_width)
from wavephys.physics.boundary import CUTOFF_METHODS, cutoff_mask
from wavephys.physics.dispersion import angular_frequency, surface_operator
from wavephys.physics.heights import height_multiplier
from wavephys.physics.ship_waves import SHIP_METHODS
from wavephys.physics.walls import check_walls, wall_axes
from wavephys.core.spectral import inverse_mode_transform, mode_transform, mode_wavenumbers

__all__ = ["Model", "Operators", "operators", "DTYPES"]

DTYPES = ("float32", "float64")


def _dtype_name(dtype) -> str:
    try:
        name = jnp.dtype(dtype).name
    except TypeError as exc:
        raise TypeError(f"dtype must be float32 or float64, got {dtype!r}") from exc
    if name not in DTYPES:
        raise ValueError(f"dtype must be float32 or float64, got {name}")
    if name == "float64" and not jax.config.jax_enable_x64:
        raise ValueError("dtype float64 needs jax_enable_x64: "
                         "jax.config.update('jax_enable_x64', True) before creating arrays")
    return name


@dataclass(frozen=True)
class Model:
    """What the spectral step needs to know: grid, water, Δt and numerical options.

    Parameters
    ----------
    grid : Grid
        The n × n periodic grid.
    water : Water
        Water properties (σ = 0 switches capillarity off, depth = inf finite depth).
    dt : float
        Time step Δt, s, finite and > 0. The propagation is exact for any Δt; what limits
        Δt is what you do with the frames (Hermite error grows with ωΔt) and ships'
        patches.
    margin : int
        Open-ocean cutoff margin M, samples, 0 ≤ M < n/2 (0: periodic, no cutoff).
    cutoff : {"quadratic", "linear"}
        Cutoff shape, a name in :data:`wavephys.physics.boundary.CUTOFF_METHODS`.
    second_order : bool
        Add the second-order height term to η (docs/physics.md §1.5).
    dtype : "float32" (default) or "float64" (needs ``jax_enable_x64``).
    ship_patch : int
        Side 2M of the patch on which each ship's new waves are computed (even, 4 ≤ 2M ≤ n;
        default min(64, n)).
    leak_tolerance : float
        Largest fraction of a step's ship waves the patch may miss
        (:func:`wavephys.physics.ship_waves.patch_leak`); a larger leak is refused.
    ship_method : {"kernels", "impulses"}
        A name in :data:`wavephys.physics.ship_waves.SHIP_METHODS`.
    mesh : jax.sharding.Mesh or None
        Shard the state by rows over this mesh's axis ``mesh_axis`` (n divisible by its
        size); the FFTs become slab transforms (:mod:`wavephys.parallel`). None: one device.
    mesh_axis : str
        The mesh axis the rows are split over (default ``"rows"``).
    walls : str or sequence of str
        Sides that are reflecting vertical walls (no flux; docs/physics.md §1.11): ``"all"`` (a
        tank), ``"x"`` (left and right), ``"y"`` (bottom and top), side names from
        :data:`wavephys.physics.walls.SIDES`, or ``()`` (default, none). An axis with a wall is
        stepped on its cosine modes (exact per mode, like the periodic step); its other sides
        are open when ``margin`` > 0 (the cutoff sits only on the sides that are not walls),
        periodic otherwise. Not yet with a mesh (a distributed cosine transform).
    tank : (float, float), optional
        (width along x, height along y), m: a rectangular tank smaller than the grid's square (Lx ≠ Ly),
        centred in it, with ``walls="all"``; the rest of the grid is land (its heights stay 0). Each side
        an even number of cells (a multiple of 2·dx), at most the grid's side. The step is exact on the
        tank's own cosine modes cos(mπx/Lx)·cos(pπy/Ly). Ships are not supported in it yet. None
        (default): the tank is the grid's whole square.

    Examples
    --------
    >>> from dataclasses import replace
    >>> from wavephys import Grid, Water
    >>> model = Model(Grid(64, 2.0), Water(), dt=0.02, margin=8)
    >>> shallow = replace(model, water=Water(depth=0.1))
    >>> tank = Model(Grid(64, 2.0), Water(depth=0.1), dt=0.02, walls="all")
    >>> lane = Model(Grid(64, 2.0), Water(depth=0.1), dt=0.02, walls="all", tank=(2.0, 0.5))
    """

    grid: Grid
    water: Water = Water()
    dt: float = 1.0 / 30.0
    margin: int = 0
    cutoff: str = "quadratic"
    second_order: bool = False
    dtype: str = "float32"
    ship_patch: Optional[int] = None
    leak_tolerance: float = 1e-3
    ship_method: str = "kernels"
    mesh: Optional[Mesh] = None
    mesh_axis: str = AXIS
    walls: tuple = ()
    tank: Optional[tuple] = None
    tank_cells: Optional[tuple] = field(default=None, init=False, repr=False, compare=False)

    def __post_init__(self):
        check_instance("grid", self.grid, Grid, "wavephys.Grid")
        check_instance("water", self.water, Water, "wavephys.Water")
        check_scalar("dt", self.dt, lo=0.0, lo_open=True)
        set_ = lambda k, v: object.__setattr__(self, k, v)
        set_("margin", check_int("margin", self.margin, lo=0))
        if 2 * self.margin >= self.grid.n:
            raise ValueError(f"margin must be < n/2 = {self.grid.n // 2}, got {self.margin}")
        CUTOFF_METHODS.check(self.cutoff, "cutoff")
        set_("second_order", check_bool("second_order", self.second_order))
        set_("dtype", _dtype_name(self.dtype))
        patch = min(64, self.grid.n) if self.ship_patch is None else self.ship_patch
        set_("ship_patch", check_int("ship_patch", patch, lo=4, hi=self.grid.n, even=True))
        check_scalar("leak_tolerance", self.leak_tolerance, lo=0.0, hi=1.0, lo_open=True)
        set_("leak_tolerance", float(self.leak_tolerance))
        SHIP_METHODS.check(self.ship_method, "ship_method")
        set_("walls", check_walls(self.walls, self.margin))
        if self.walls and self.mesh is not None:
            raise ValueError("walls with a mesh (sharded model) are not supported yet: the distributed cosine "
                             "transform is not written; step a walled tank on one device (mesh=None)")
        set_("tank", self._check_tank())
        if self.mesh is not None:
            check_mesh(self.mesh, self.mesh_axis, self.grid.n)
        elif not isinstance(self.mesh_axis, str):
            raise TypeError(f"mesh_axis must be a str, got {type(self.mesh_axis).__name__}")
        elif self.mesh_axis != AXIS:
            raise ValueError(f"mesh_axis {self.mesh_axis!r} names an axis of a mesh, but mesh is None (no sharding): "
                             f"give the mesh too, or leave mesh_axis at {AXIS!r}")

    def _check_tank(self):
        """The tank as (width, height) floats, its cells set in :attr:`tank_cells` = (rows, columns)."""
        if self.tank is None:
            object.__setattr__(self, "tank_cells", None)
            return None
        check_array("tank", self.tank, ndim=1, shape_tail=(2,), lo=0.0, lo_open=True)
        if len(self.walls) != 4:
            raise ValueError(f"tank: a tank smaller than the grid is closed by walls on all four sides: give "
                             f"walls='all' (got walls={self.walls!r})")
        if is_traced(self.grid.length):
            raise ValueError("tank: the grid's length must be a concrete number (it fixes the tank's cells)")
        n, length = self.grid.n, float(self.grid.length)
        dx = length / n
        cells = []
        for name, value in zip(("width", "height"), (float(v) for v in np.asarray(self.tank, np.float64))):
            count = value / dx
            whole = int(round(count))
            if abs(count - whole) > 1e-6 * max(1.0, count) or whole % 2 or whole < 2:
                raise ValueError(f"tank {name} {value:g} m must be an even number of cells, a multiple of 2·dx = "
                                 f"{2 * dx:g} m")
            if whole > n:
                raise ValueError(f"tank {name} {value:g} m must be at most the grid's side {length:g} m")
            cells.append(whole)
        object.__setattr__(self, "tank_cells", (cells[1], cells[0]))
        return tuple(float(v) for v in np.asarray(self.tank, np.float64))

    @property
    def real_dtype(self):
        """The model's floating dtype as a numpy dtype."""
        return np.dtype(self.dtype)

    @property
    def wall_axes(self) -> tuple[bool, bool]:
        """(x walled, y walled): the axes stepped on cosine modes."""
        return wall_axes(self.walls) if self.walls else (False, False)

    @property
    def device_count(self) -> int:
        """Devices the rows are split over (1 without a mesh)."""
        return device_count(self.mesh, self.mesh_axis)

    @property
    def spectrum_width(self) -> int:
        """Columns of the model's half spectra: n//2 + 1, padded to a multiple of the
        devices when sharded (:func:`wavephys.parallel.layout.spectrum_width`)."""
        n = self.grid.n
        return n // 2 + 1 if self.mesh is None else spectrum_width(n, self.device_count)

    def mesh_fields(self):
        """The grid's sample coordinates ``(x, y)``, m, each ``(n, n)`` and laid out like the
        model's real fields (split by rows over the mesh when sharded): what a source evaluates
        a field on, block by block on the devices."""
        x, y = self.grid.mesh()
        if self.mesh is None:
            return x, y
        sharding = field_sharding(self.mesh, self.mesh_axis, 2)
        return tuple(constrain(jnp.broadcast_to(a, (self.grid.n,) * 2), sharding) for a in (x, y))

    def rfft2(self, field):
        """The rfft2 half spectrum of a real field ``(..., n, n)`` in the model's layout: the
        slab-decomposed transform on a sharded model (:func:`wavephys.parallel.fft.rfft2`), so
        a source's spectrum is never gathered on one device. A walled model's modes are not
        Fourier modes: ValueError (use :meth:`transform`)."""
        from wavephys.parallel.fft import rfft2

        n = self.grid.n
        check_array("field", field, min_ndim=2, shape_tail=(n, n))
        if self.walls:
            raise ValueError(f"model.rfft2: this model has walls ({', '.join(self.walls)}), whose modes are "
                             f"cosines, not Fourier modes: use model.transform(field)")
        return rfft2(field, self.mesh, self.mesh_axis)

    def transform(self, field):
        """A real field ``(..., n, n)`` on the model's modes, in the layout its multipliers and
        sources use: :meth:`rfft2` without walls; with walls the cosine transform along walled
        axes (:func:`wavephys.core.spectral.mode_transform`)."""
        if not self.walls:
            return self.rfft2(field)
        n = self.grid.n
        check_array("field", field, min_ndim=2, shape_tail=(n, n))
        return mode_transform(field, self.wall_axes, self.tank_cells)

    def inverse_transform(self, spectra):
        """Real fields ``(..., n, n)`` from spectra in the model's layout (the inverse of :meth:`transform`)."""
        from wavephys.parallel.fft import irfft2

        check_array("spectra", spectra, complex_ok=True, min_ndim=2)
        if not self.walls:
            return irfft2(spectra, self.grid.n, self.mesh, self.mesh_axis)
        return inverse_mode_transform(spectra, self.grid.n, self.wall_axes, self.tank_cells)

    def mode_wavenumbers(self):
        """``(ky, kx)``, rad/m, on the model's spectral layout (broadcastable): Fourier
        wavenumbers along periodic axes, mπ/L along walled ones (L the tank's side with ``tank``)."""
        return mode_wavenumbers(self.grid.n, self.grid.dx, self.wall_axes, xp=jnp, extent=self.tank_cells)


register(Model, ("grid", "water", "dt"),
         ("margin", "cutoff", "second_order", "dtype", "ship_patch", "leak_tolerance", "ship_method", "mesh",
          "mesh_axis", "walls", "tank", "tank_cells"))


class Operators(NamedTuple):
    """Fourier multipliers of one model on its spectral layout: the rfft2 half spectrum
    ``(n, n//2 + 1)``, or the cosine modes of a walled model (:meth:`Model.transform`).

    ``cos``, ``sin``: rotation of (φ̂, χ̂) by ωΔt; ``height`` K/ω (s/m) and
    ``inverse_height`` ω/K; ``K`` = |k| tanh(|k|h) (rad/m); ``k`` = |k| (rad/m);
    ``omega`` = ω(|k|) (rad/s);
    ``duhamel_sin`` = sin(ωΔt)/ω and ``duhamel_cos`` = (1 − cos ωΔt)/ω (s) for
    continuous sources; ``mask`` the cutoff weights ``(n, n)`` or None.

    Attributes
    ----------
    cos, sin, height, inverse_height, K, k, omega, duhamel_sin, duhamel_cos : jax.Array
        As above, each on the half spectrum.
    mask : jax.Array or None
    """

    cos: jax.Array
    sin: jax.Array
    height: jax.Array
    inverse_height: jax.Array
    K: jax.Array
    k: jax.Array
    omega: jax.Array
    duhamel_sin: jax.Array
    duhamel_cos: jax.Array
    mask: Optional[jax.Array]


def _build(model: Model, dtype, out_dtype=None) -> Operators:
    """The multipliers computed in ``dtype`` and returned in ``out_dtype`` (default ``dtype``),
    in the model's layout."""
    if model.walls:
        ky, kx = model.mode_wavenumbers()
        k = jnp.sqrt(ky * ky + kx * kx)
    else:
        k = model.grid.wavenumber_magnitude(real=True)
    omega = angular_frequency(k, model.water)
    phase = omega * model.dt
    pos = omega > 0
    w = jnp.where(pos, omega, 1.0)
    hm = height_multiplier(k, model.water)
    ops = Operators(
        cos=jnp.cos(phase), sin=jnp.sin(phase), height=hm,
        inverse_height=jnp.where(hm > 0, 1.0 / jnp.where(hm > 0, hm, 1.0), 0.0),
        K=surface_operator(k, model.water), k=k, omega=omega,
        duhamel_sin=jnp.where(pos, jnp.sin(phase) / w, model.dt),
        duhamel_cos=jnp.where(pos, (1.0 - jnp.cos(phase)) / w, 0.0),
        mask=cutoff_mask(model.grid.n, model.margin, model.cutoff, dtype, model.walls) if model.margin else None)
    out_dtype = dtype if out_dtype is None else out_dtype
    return _lay_out(model, Operators(*(None if a is None else jnp.asarray(jnp.asarray(a, dtype), out_dtype)
                                       for a in ops)))


def _lay_out(model: Model, ops: Operators) -> Operators:
    """Sharded models: multipliers padded to the spectrum width and split by columns, the
    cutoff mask split by rows, like the arrays they multiply (:mod:`wavephys.parallel`)."""
    if model.mesh is None:
        return ops
    pad = model.spectrum_width - (model.grid.n // 2 + 1)
    spread = lambda a: place(jnp.pad(a, [(0, 0)] * (a.ndim - 1) + [(0, pad)]),
                             spectrum_sharding(model.mesh, model.mesh_axis, a.ndim))
    mask = None if ops.mask is None else place(ops.mask, field_sharding(model.mesh, model.mesh_axis, 2))
    return Operators(*(spread(a) for a in ops[:-1]), mask)


def natural(model: Model, ops: Operators) -> Operators:
    """The multipliers on the natural rfft2 half spectrum ``(n, n//2 + 1)`` (what sources use)."""
    if model.mesh is None:
        return ops
    half = model.grid.n // 2 + 1
    return Operators(*(a[..., :half] for a in ops[:-1]), ops.mask)


_build_once = jax.jit(_build, static_argnums=(1, 2))
"""The multipliers in one program (the grid's length, the water and Δt traced: one compilation per size and
options, not one per operation)."""


@functools.lru_cache(maxsize=8)
def _concrete(model: Model) -> Operators:
    return _build_float64(model)


def _build_float64(model: Model) -> Operators:
    """Concrete models: multipliers computed in float64, then cast, so that the phase ωΔt
    keeps its digits for any Δt (docs/physics.md §1.2). A sharded model's are computed in
    one program whose outputs are split like the spectra: each device computes its own
    columns, so no device ever holds the whole float64 spectrum."""
    with jax.enable_x64(True):
        if model.mesh is None:
            return _build_once(model, jnp.float64, model.dtype)
        n, mesh, axis = model.grid.n, model.mesh, model.mesh_axis
        spread = spectrum_sharding(mesh, axis, 2)
        shardings = Operators(*([spread] * 9), field_sharding(mesh, axis, 2) if model.margin else None)
        return jax.jit(lambda m: _build(m, jnp.float64, m.dtype), out_shardings=shardings)(model)


def operators(model: Model) -> Operators:
    """The Fourier multipliers of a model (cached for concrete models, traced otherwise).

    Parameters
    ----------
    model : Model

    Returns
    -------
    Operators
        In the model's layout (padded and split by columns when sharded).
    """
    check_instance("model", model, Model, "wavephys.simulation.Model")
    if is_traced(model):
        return _build(model, model.dtype)
    try:
        return _concrete(model)
    except TypeError:  # unhashable leaves (arrays): build without the cache
        return _build_float64(model)
