"""Where the arrays of a sharded simulation live: rows of the grid over the devices of a mesh.

A sharded model keeps its real fields ``(..., n, n)`` split by rows (y) over the mesh axis
and its half spectra in the transposed layout the slab FFT leaves them in
(:mod:`wavephys.parallel.fft`): every ky, and a block of kx columns per device. The
half spectrum has n/2 + 1 columns, which no even device count divides, so a sharded
spectrum is padded with zero columns to :func:`spectrum_width` (a multiple of the
device count); the padding stays zero through every step (docs/architecture.md,
"Scale-out").
"""

from __future__ import annotations

import jax
import numpy as np
from jax.sharding import Mesh, NamedSharding, PartitionSpec

from wavephys.core.inputs import check_instance, check_int, describe

__internal__ = True  # the layout helpers are the step's tooling; row_mesh and spectrum_width are re-exported
__all__ = ["row_mesh", "check_mesh", "spectrum_width", "field_sharding", "spectrum_sharding", "place", "constrain",
           "device_count"]

AXIS = "rows"
"""The default name of the mesh axis the grid's rows are split over."""


def row_mesh(devices, axis: str = AXIS) -> Mesh:
    """A one-axis :class:`jax.sharding.Mesh` named ``axis`` over ``devices`` (a sequence of
    ``jax.Device``, all of one kind: CPU, GPU or TPU), in the order given.

    Parameters
    ----------
    devices : sequence of jax.Device
        At least one, no repeats, all of one platform.
    axis : str
        The mesh axis's name.

    Returns
    -------
    jax.sharding.Mesh
    """
    if isinstance(devices, (str, bytes)) or not hasattr(devices, "__iter__"):
        raise TypeError(f"devices must be a sequence of jax devices (e.g. jax.devices()), got {describe(devices)}")
    devices = list(devices)
    if not devices:
        raise ValueError("devices must name at least one device, got an empty sequence")
    for i, d in enumerate(devices):
        if not isinstance(getattr(d, "platform", None), str):
            raise TypeError(f"devices[{i}] must be a jax.Device (from jax.devices()), got {describe(d)}")
    kinds = sorted({d.platform for d in devices})
    if len(kinds) > 1:
        raise ValueError(f"devices must all be of one kind to share a sharded program, got a mix of {kinds}")
    for i, d in enumerate(devices):
        if not isinstance(d, jax.Device):
            raise TypeError(f"devices[{i}] must be a jax.Device (from jax.devices()), got {describe(d)}")
    if len(set(devices)) != len(devices):
        raise ValueError("devices must not repeat a device")
    if not isinstance(axis, str) or not axis:
        raise TypeError(f"axis must be a non-empty str, got {describe(axis)}")
    return Mesh(np.array(devices, dtype=object), (axis,))


def check_mesh(mesh, axis: str, n: int) -> int:
    """Check that ``mesh`` can shard an n × n grid by rows over its axis ``axis``; returns the
    number of devices along that axis. Named errors before any work.

    Parameters
    ----------
    mesh : jax.sharding.Mesh
    axis : str
        The axis to split the rows over (named ``mesh_axis`` in messages).
    n : int
        Grid points along a side; a multiple of the devices on ``axis``.

    Returns
    -------
    int
        Devices along ``axis``.
    """
    check_instance("mesh", mesh, Mesh, "jax.sharding.Mesh")
    if not isinstance(axis, str):
        raise TypeError(f"mesh_axis must be a str, got {describe(axis)}")
    if axis not in mesh.axis_names:
        raise ValueError(f"mesh has no axis named {axis!r} (its axes: {tuple(mesh.axis_names)}): pass the name "
                         f"of the axis to split the rows over (mesh_axis={mesh.axis_names[0]!r}, for example)")
    kinds = sorted({d.platform for d in mesh.devices.flat})
    if len(kinds) > 1:
        raise ValueError(f"mesh devices must all be of one kind, got a mix of {kinds}")
    p = int(mesh.shape[axis])
    if n % p:
        raise ValueError(f"grid n = {n} must be divisible by the {p} devices on mesh axis {axis!r} "
                         f"(each device holds n/devices whole rows)")
    return p


def device_count(mesh, axis: str) -> int:
    """Devices along the mesh axis (1 for no mesh).

    Parameters
    ----------
    mesh : jax.sharding.Mesh or None
    axis : str

    Returns
    -------
    int
    """
    return 1 if mesh is None else int(mesh.shape[axis])


def spectrum_width(n: int, shards: int) -> int:
    """Columns of the padded half spectrum: n/2 + 1 rounded up to a multiple of ``shards``
    (the number of devices on the mesh axis).

    Parameters
    ----------
    n : int
        Grid points along a side, ≥ 2.
    shards : int
        Devices on the mesh axis, ≥ 1.

    Returns
    -------
    int
    """
    n, shards = check_int("n", n, lo=2), check_int("shards", shards, lo=1)
    half = n // 2 + 1
    return -(-half // shards) * shards


def _spec(ndim: int, dim: int, axis: str) -> PartitionSpec:
    names = [None] * ndim
    names[dim] = axis
    return PartitionSpec(*names)


def field_sharding(mesh: Mesh, axis: str, ndim: int) -> NamedSharding:
    """Real fields ``(..., n, n)``: rows (axis −2) over the mesh axis.

    Parameters
    ----------
    mesh : jax.sharding.Mesh
    axis : str
        The mesh axis.
    ndim : int
        The fields' number of dimensions (≥ 2).

    Returns
    -------
    jax.sharding.NamedSharding
    """
    return NamedSharding(mesh, _spec(ndim, ndim - 2, axis))


def spectrum_sharding(mesh: Mesh, axis: str, ndim: int) -> NamedSharding:
    """Padded half spectra ``(..., n, W)``: kx columns (axis −1) over the mesh axis.

    Parameters
    ----------
    mesh : jax.sharding.Mesh
    axis : str
        The mesh axis.
    ndim : int
        The spectra's number of dimensions (≥ 2).

    Returns
    -------
    jax.sharding.NamedSharding
    """
    return NamedSharding(mesh, _spec(ndim, ndim - 1, axis))


def place(x, sharding: NamedSharding):
    """``x`` as a global array with ``sharding``. Host data (numpy, Python numbers, or a
    single-process array) is cut into each local device's block, so the same call works in
    one process and under ``jax.distributed`` (every process passes the same values).

    Parameters
    ----------
    x : array_like or jax.Array
        The values (traced: a sharding constraint instead).
    sharding : jax.sharding.NamedSharding

    Returns
    -------
    jax.Array
        A global array laid out by ``sharding``.
    """
    if isinstance(x, jax.core.Tracer):
        return jax.lax.with_sharding_constraint(x, sharding)
    if isinstance(x, jax.Array) and not x.is_fully_addressable:
        return jax.device_put(x, sharding)  # already global: reshard
    if jax.process_count() == 1:
        return jax.device_put(x, sharding)
    host = np.asarray(x)
    return jax.make_array_from_callback(host.shape, sharding, lambda index: host[index])


def constrain(x, sharding: NamedSharding):
    """Inside a traced program: ask XLA to keep ``x`` with ``sharding`` (outside one: :func:`place`).

    Parameters
    ----------
    x : jax.Array or tracer
    sharding : jax.sharding.NamedSharding

    Returns
    -------
    jax.Array
    """
    return jax.lax.with_sharding_constraint(x, sharding) if isinstance(x, jax.core.Tracer) else place(x, sharding)
