"""Many hosts: ``jax.distributed`` wiring for the sharded simulation and the sweeps.

Every process runs the same script (one per host, each using all of its host's devices;
for one process per GPU, give each its own ``CUDA_VISIBLE_DEVICES`` or ``local_device_ids``). :func:`initialize` connects it to the others (on
CPU it selects the gloo collectives, so plain processes on one or many machines work);
afterwards ``jax.devices()`` lists the devices of every process, :func:`hosts_mesh` puts
them all on one mesh axis, and a ``Model(..., mesh=hosts_mesh())`` steps one grid over all
of them. :func:`gather` brings a sharded result back to every process as numpy.

Launch (docs/architecture.md, "Scale-out"): plain processes —
``python script.py`` once per process with ``WAVEPHYS_COORDINATOR=host:port``,
``WAVEPHYS_NUM_PROCESSES`` and ``WAVEPHYS_PROCESS_ID`` set; under Slurm, ``srun python
script.py`` and :func:`initialize` with no arguments (JAX reads Slurm's variables).
"""

from __future__ import annotations

import os

import jax
import numpy as np

from wavephys.core.inputs import check_array, check_int, describe
from wavephys.parallel.layout import AXIS, row_mesh

__all__ = ["initialize", "is_initialized", "hosts_mesh", "gather"]

_ENV = ("WAVEPHYS_COORDINATOR", "WAVEPHYS_NUM_PROCESSES", "WAVEPHYS_PROCESS_ID")


def _env_int(name: str, text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise ValueError(f"the environment variable {name} must be an integer, got {text!r}") from None


def is_initialized() -> bool:
    """Whether ``jax.distributed`` is connected (by :func:`initialize` or by hand).

    Returns
    -------
    bool
    """
    return bool(jax.distributed.is_initialized())


def initialize(coordinator_address: str | None = None, num_processes: int | None = None,
               process_id: int | None = None, *, local_device_ids=None, timeout_s: int = 300) -> None:
    """Connect this process to the others (``jax.distributed.initialize``), before any JAX work.

    Arguments not given are read from ``WAVEPHYS_COORDINATOR`` ("host:port"),
    ``WAVEPHYS_NUM_PROCESSES`` and ``WAVEPHYS_PROCESS_ID``; with none of them set, JAX
    detects the cluster itself (Slurm, Open MPI, Kubernetes). On CPU the collectives
    are gloo's.

    Parameters
    ----------
    coordinator_address : str, optional
        "host:port" of process 0.
    num_processes : int, optional
        Processes in the run, ≥ 1.
    process_id : int, optional
        This process's number, in [0, num_processes).
    local_device_ids : sequence of int, optional
        This process's devices (JAX's default: all).
    timeout_s : int
        Seconds to wait for the other processes.
    """
    env = [os.environ.get(k) for k in _ENV]
    coordinator_address = coordinator_address if coordinator_address is not None else env[0]
    if coordinator_address is not None and (not isinstance(coordinator_address, str) or ":" not in coordinator_address):
        where = f" (from {_ENV[0]})" if env[0] is not None and coordinator_address == env[0] else ""
        raise ValueError(f"coordinator_address{where} must be 'host:port', got {describe(coordinator_address)}")
    if num_processes is None and env[1] is not None:
        num_processes = _env_int(_ENV[1], env[1])
    if process_id is None and env[2] is not None:
        process_id = _env_int(_ENV[2], env[2])
    if num_processes is not None:
        num_processes = check_int("num_processes", num_processes, lo=1)
    if process_id is not None:
        process_id = check_int("process_id", process_id, lo=0)
        if num_processes is not None and process_id >= num_processes:
            raise ValueError(f"process_id must be < num_processes = {num_processes}, got {process_id}")
    check_int("timeout_s", timeout_s, lo=1)
    if is_initialized():
        raise RuntimeError("jax.distributed is already initialized in this process")
    jax.config.update("jax_cpu_collectives_implementation", "gloo")
    jax.distributed.initialize(coordinator_address, num_processes, process_id, local_device_ids=local_device_ids,
                               initialization_timeout=timeout_s)


def hosts_mesh(axis: str = AXIS):
    """One mesh axis over the devices of every process (``jax.devices()``, process by process).

    Parameters
    ----------
    axis : str
        The mesh axis's name (default ``"rows"``).

    Returns
    -------
    jax.sharding.Mesh

    Raises
    ------
    RuntimeError
        If ``jax.distributed`` is not initialized (then only this process's devices exist, and
        a "many hosts" run would silently be a one-host run).
    """
    if not is_initialized():
        raise RuntimeError("hosts_mesh needs jax.distributed: call wavephys.parallel.initialize(...) in every "
                           "process first (or use row_mesh(jax.devices()) for this process's devices alone)")
    return row_mesh(jax.devices(), axis)


def gather(x) -> np.ndarray:
    """A (possibly sharded, possibly multi-process) array as one numpy array in every process.

    Parameters
    ----------
    x : jax.Array or array_like
        Finite numbers.

    Returns
    -------
    numpy.ndarray
        The whole array, in every process.
    """
    if not (isinstance(x, jax.Array) or hasattr(x, "__array__") or isinstance(x, (int, float, list, tuple))):
        raise TypeError(f"x must be an array, got {describe(x)}")
    out = _gather(x)
    check_array("x", out)  # the same check in one process and across processes
    return out


def _gather(x) -> np.ndarray:
    if isinstance(x, jax.Array) and not x.is_fully_addressable:
        from jax.experimental import multihost_utils

        return np.asarray(multihost_utils.process_allgather(x, tiled=True))
    return np.asarray(x)
