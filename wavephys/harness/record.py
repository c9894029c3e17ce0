"""A record of a simulator's output: frames, their spacing in space and time, and the claims.

:class:`Record` is what every check of :mod:`wavephys.harness` reads: heights
``(n_t, n_y, n_x)`` in metres, the grid spacing ``dx`` (m), the time between frames ``dt``
(s), optionally the vertical velocity η̇ (m/s), and what the user claims of their water
(its depth, its surface tension). It is built from arrays with named axes
(:meth:`Record.from_array`), from exported frames (:meth:`Record.from_files`: a folder or
glob of EXR, 16-bit PNG, ``.npy`` or ``.npz`` files, through :mod:`wavephys.core.frames`),
or from a saved record (:meth:`Record.load`).

A layout that could be read more than one way is refused, never guessed: ``(n, n, n_t)``
(time last, as many engines export) and a cube ``(n, n, n)`` need ``axes=``; a correct
simulator must never get a wrong verdict from a transposed record.

η̇ from frames (:func:`time_derivative`): the 5-point central difference in time
(``"fd4"``; its relative error for a mode of frequency ω is 1 − (8 sin θ − sin 2θ)/(6θ),
θ = ωΔt, about θ⁴/30), or, for a record that loops (the frame after the last is the first,
as in a tiling ocean), the spectral derivative in time (``"spectral"``, exact for a loop).
Each returns its own error estimate, from the record's measured frequencies.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Optional

import numpy as np

from wavephys.core.files import atomic_path, output_file
from wavephys.core.inputs import check_array, check_choice, check_instance, check_scalar, describe
from pathlib import Path

from wavephys.core.frames import AXES, _to_tyx, resolve_axes  # noqa: F401  (AXES: this module's name too)
from wavephys.core.water import Water

__all__ = ["Record", "Rate", "time_derivative", "AXES", "RATE_METHODS"]

RATE_METHODS = ("auto", "fd4", "spectral")
"""How :func:`time_derivative` differentiates frames in time (``auto``: spectral for a loop, else fd4)."""


@dataclass(frozen=True)
class Rate:
    """η̇ estimated from frames.

    Attributes
    ----------
    eta_dot : numpy.ndarray (n_t', n_y, n_x)
        The rate, m/s, at the frames ``frames`` of the record.
    frames : slice
        The record's frames it belongs to (fd4 drops two at each end).
    method : str
        ``"fd4"`` or ``"spectral"``.
    error : float
        Estimated relative error of η̇ at the frequency below which 99 % of the record's power lies, dimensionless.
    """

    eta_dot: np.ndarray
    frames: slice
    method: str
    error: float


def _loops(eta: np.ndarray) -> bool:
    """Whether the frame after the last is the first: the wrap step is like an ordinary step."""
    steps = np.sqrt(np.mean(np.diff(eta, axis=0) ** 2, axis=(1, 2)))
    wrap = float(np.sqrt(np.mean((eta[0] - eta[-1]) ** 2)))
    typical = float(np.median(steps))
    return typical > 0 and wrap <= 1.5 * typical and wrap >= 0.5 * typical


def _dominant_frequencies(eta: np.ndarray, dt: float, fraction: float = 0.99) -> float:
    """The temporal angular frequency below which ``fraction`` of the record's power lies, rad/s (Hann window;
    refined between bins)."""
    nt = eta.shape[0]
    window = np.hanning(nt + 2)[1:-1]
    import scipy.fft

    from wavephys.harness.spectra import workers

    spec = np.abs(scipy.fft.rfft((eta - eta.mean(axis=0)) * window[:, None, None], axis=0, workers=workers())) ** 2
    power = spec.sum(axis=(1, 2))
    if power.sum() <= 0:
        return 0.0
    cum = np.cumsum(power) / power.sum()
    i = int(np.searchsorted(cum, fraction))
    below = cum[i - 1] if i > 0 else 0.0
    bins = i - 1 + (fraction - below) / max(cum[i] - below, 1e-300) if i > 0 else 0.0  # between bins
    return 2 * math.pi * max(bins, 0.0) / (nt * dt)


def time_derivative(eta, dt: float, *, method: str = "auto") -> Rate:
    """η̇ from frames ``dt`` apart, with its estimated error.

    Parameters
    ----------
    eta : array_like (n_t, n_y, n_x)
        Heights, m, finite, n_t ≥ 8 (fd4) frames.
    dt : float
        Time between frames, s, > 0.
    method : {"auto", "fd4", "spectral"}, optional, keyword-only
        ``"fd4"``: the 5-point central difference (frames 2 … n_t − 3); ``"spectral"``: the spectral derivative
        in time, for a record that loops (every frame); ``"auto"`` (default): spectral when the record loops
        (the step from the last frame to the first is like the others), else fd4.

    Returns
    -------
    Rate
        η̇ (m/s), the frames it covers, the method used and its estimated worst relative error: for fd4,
        1 − (8 sin θ − sin 2θ)/(6θ) at θ = ω₉₉Δt (ω₉₉ the frequency below which 99 % of the power lies);
        for spectral, the square root of the power fraction in the top eighth of the temporal band.

    Raises
    ------
    ValueError
        When ``eta`` is not 3-D with ≥ 8 frames, or ``method="spectral"`` on a record that does not loop.
    """
    check_array("eta", eta, ndim=3)
    check_scalar("dt", dt, lo=0.0, lo_open=True)
    check_choice("method", method, RATE_METHODS)
    eta = np.asarray(eta, np.float64)
    nt = eta.shape[0]
    if nt < 8:
        raise ValueError(f"eta must have at least 8 frames to differentiate in time, got {nt}")
    loops = _loops(eta)
    if method == "spectral" and not loops:
        raise ValueError("method: 'spectral' needs a record that loops (the frame after the last is the first); "
                         "this one does not (its last-to-first step is unlike its other steps): use 'fd4'")
    if method == "spectral" or (method == "auto" and loops):
        w = 2 * math.pi * np.fft.fftfreq(nt, dt)
        if nt % 2 == 0:
            w[nt // 2] = 0.0
        import scipy.fft

        from wavephys.harness.spectra import workers

        rate = np.real(scipy.fft.ifft(1j * w[:, None, None] * scipy.fft.fft(eta, axis=0, workers=workers()), axis=0,
                                      workers=workers()))
        spec = np.abs(scipy.fft.rfft(eta - eta.mean(axis=0), axis=0, workers=workers())) ** 2
        power = spec.sum(axis=(1, 2))
        top = power[-max(1, power.size // 8):].sum() / max(power.sum(), 1e-300)
        return Rate(rate, slice(0, nt), "spectral", float(math.sqrt(top)))
    rate = (8 * (eta[3:-1] - eta[1:-3]) - (eta[4:] - eta[:-4])) / (12 * dt)
    theta = _dominant_frequencies(eta, dt) * dt
    error = 0.0 if theta == 0 else 1.0 - (8 * math.sin(theta) - math.sin(2 * theta)) / (6 * theta)
    return Rate(rate, slice(2, nt - 2), "fd4", float(abs(error)))


@dataclass(frozen=True)
class Record:
    """Frames of a water surface with their spacing and the user's claims.

    Parameters
    ----------
    eta : numpy.ndarray (n_t, n_y, n_x)
        Heights, m, finite; n_t ≥ 8 frames, n_y, n_x ≥ 4.
    dx : float
        Grid spacing, m, > 0 (the same along x and y).
    dt : float
        Time between frames, s, > 0.
    eta_dot : numpy.ndarray (n_t, n_y, n_x), optional
        The vertical velocity, m/s, when the simulator gives it (else estimated by :func:`time_derivative`).
    depth : float, optional
        The claimed still-water depth, m, > 0 (inf: deep water).
    sigma : float, optional
        The claimed surface tension, N/m, >= 0.
    source : str, optional
        Where the frames came from, in words.
    tank : bool, optional
        The frames say they are water between four reflecting walls (their files' ``boundary`` is ``walls``):
        :func:`~wavephys.harness.check_record` then checks them as a tank, as ``tank=True`` does.
    """

    eta: np.ndarray
    dx: float
    dt: float
    eta_dot: Optional[np.ndarray] = None
    depth: Optional[float] = None
    sigma: Optional[float] = None
    source: str = ""
    tank: bool = False
    _cache: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self):
        check_array("eta", self.eta, ndim=3)
        eta = np.asarray(self.eta, np.float64)
        if eta.shape[0] < 8:
            raise ValueError(f"eta must have at least 8 frames on its time axis, got shape {eta.shape}")
        if min(eta.shape[1:]) < 4:
            raise ValueError(f"eta must be at least 4 x 4 per frame, got shape {eta.shape}")
        object.__setattr__(self, "eta", eta)
        object.__setattr__(self, "dx", check_scalar("dx", self.dx, lo=0.0, lo_open=True))
        object.__setattr__(self, "dt", check_scalar("dt", self.dt, lo=0.0, lo_open=True))
        if self.eta_dot is not None:
            check_array("eta_dot", self.eta_dot, ndim=3, shape_tail=eta.shape)
            object.__setattr__(self, "eta_dot", np.asarray(self.eta_dot, np.float64))
        if self.depth is not None:
            object.__setattr__(self, "depth", check_scalar("depth", self.depth, lo=0.0, lo_open=True,
                                                           allow_inf=True))
        if self.sigma is not None:
            object.__setattr__(self, "sigma", check_scalar("sigma", self.sigma, lo=0.0))
        if not isinstance(self.source, str):
            raise TypeError(f"source must be a string, got {describe(self.source)}")
        if not isinstance(self.tank, bool):
            raise TypeError(f"tank must be True or False, got {describe(self.tank)}")

    @property
    def shape(self) -> tuple:
        """(n_t, n_y, n_x)."""
        return self.eta.shape

    def spectrum(self) -> np.ndarray:
        """The frames' windowed space–time spectrum (:func:`wavephys.harness.spectra.spacetime_spectrum`),
        computed on first use and kept: the checks of one record share it.

        Returns
        -------
        numpy.ndarray (n_t, n_y, n_x)
            Complex, axes (ω, k_y, k_x) in numpy's FFT order.
        """
        if "spectrum" not in self._cache:
            from wavephys.harness.spectra import spacetime_spectrum

            self._cache["spectrum"] = spacetime_spectrum(self.eta)
        return self._cache["spectrum"]

    @property
    def duration(self) -> float:
        """n_t Δt, s."""
        return self.eta.shape[0] * self.dt

    def water(self, base: Optional[Water] = None) -> Water:
        """``base`` (default :class:`~wavephys.Water`) with the record's claimed depth and surface tension.

        Parameters
        ----------
        base : Water, optional
            The water the claims modify (default ``Water()``).

        Returns
        -------
        Water
            ``base`` with ``depth`` and ``sigma`` replaced where the record claims them.
        """
        base = Water() if base is None else check_instance("base", base, Water, "wavephys.Water")
        changes = {k: v for k, v in (("depth", self.depth), ("sigma", self.sigma)) if v is not None}
        return replace(base, **changes) if changes else base

    def rate(self, method: str = "auto") -> Rate:
        """η̇: the record's own when it has one (error 0), else :func:`time_derivative` of the frames.

        Parameters
        ----------
        method : {"auto", "fd4", "spectral"}, optional
            How to differentiate frames (ignored when the record holds η̇).

        Returns
        -------
        Rate
            η̇, the frames it covers, the method and its estimated relative error.
        """
        if self.eta_dot is not None:
            check_choice("method", method, RATE_METHODS)
            return Rate(self.eta_dot, slice(0, self.shape[0]), "given", 0.0)
        return time_derivative(self.eta, self.dt, method=method)

    @classmethod
    def from_array(cls, data, dx: float, dt: float, *, axes: Optional[str] = None, eta_dot=None,
                   depth: Optional[float] = None, sigma: Optional[float] = None, source: str = "") -> "Record":
        """A record from a 3-D array of heights in any layout.

        Parameters
        ----------
        data : array_like, 3-D
            Heights, m, finite.
        dx : float
            Grid spacing, m, > 0.
        dt : float
            Time between frames, s, > 0.
        axes : str, optional, keyword-only
            The layout, one of :data:`AXES` (``"tyx"``: time first; ``"yxt"``: time last). Needed unless the
            shape is ``(n_t, n, n)`` with n_t ≠ n; an ambiguous shape is refused, never guessed.
        eta_dot : array_like, optional, keyword-only
            η̇, m/s, in the same layout as ``data``.
        depth, sigma : float, optional, keyword-only
            The claimed depth (m) and surface tension (N/m).
        source : str, optional, keyword-only
            Where the frames came from.

        Returns
        -------
        Record
            Frames ``(n_t, n_y, n_x)``.

        Raises
        ------
        ValueError
            When the layout is ambiguous or ``axes`` is not one of :data:`AXES`, or a value is out of range.

        Examples
        --------
        >>> import numpy as np
        >>> Record.from_array(np.zeros((64, 64, 256)), 0.05, 1 / 60, axes="yxt").shape
        (256, 64, 64)
        """
        check_array("data", data, ndim=3)
        data = np.asarray(data, np.float64)
        axes = resolve_axes(data.shape, axes)
        if eta_dot is not None:
            check_array("eta_dot", eta_dot, ndim=3, shape_tail=data.shape)
            eta_dot = _to_tyx(np.asarray(eta_dot, np.float64), axes)
        return cls(_to_tyx(data, axes), dx, dt, eta_dot, depth, sigma, source)

    @classmethod
    def from_files(cls, source, *, dx: Optional[float] = None, dt: Optional[float] = None,
                   channel: Optional[str] = None, depth: Optional[float] = None,
                   sigma: Optional[float] = None, axes: Optional[str] = None, png_range=None) -> "Record":
        """A record from exported frames (:func:`wavephys.core.frames.read_frames`).

        Parameters
        ----------
        source : str, os.PathLike or list of them
            A folder, a glob pattern, a list of frame files in time order, or one ``.npy``/``.npz`` record.
        dx : float, optional, keyword-only
            Grid spacing, m, > 0; needed when the files do not say (and must agree when they do).
        dt : float, optional, keyword-only
            Time between frames, s, > 0; needed when the files do not say (and must agree when they do).
        channel : str, optional, keyword-only
            The EXR channel of the heights (default ``Y`` or the only one).
        depth, sigma : float, optional, keyword-only
            The claimed depth (m) and surface tension (N/m); a saved record's own claims otherwise.
        axes : str, optional, keyword-only
            The layout of one ``.npy``/``.npz`` array of frames (``"tyx"``, ``"yxt"``, …): needed when its shape
            can be read more than one way (time last, a cube); never guessed.
        png_range : (float, float), optional, keyword-only
            For 16-bit PNGs without a JSON sidecar: (offset, amplitude), m (heights = offset + amplitude ×
            level/65535); such PNGs are refused without it.

        Returns
        -------
        Record
            The frames in metres, with dx and dt from the files or the arguments.

        Raises
        ------
        ValueError
            When the files cannot be read as one record, or dx or dt is neither in the files nor given.
        """
        from wavephys.core.frames import read_frames

        frames = read_frames(source, channel=channel, dx=dx, dt=dt, axes=axes, png_range=png_range)
        for name, value in (("dx", frames.dx), ("dt", frames.dt)):
            if value is None:
                raise ValueError(f"{name}: the frames ({frames.paths[0]}, ...) do not say their {name}; give "
                                 f"{name}= (--{name} on the command line)")
        meta = frames.metadata
        eta_dot = meta.get("eta_dot") if isinstance(meta.get("eta_dot"), np.ndarray) else None
        depth = depth if depth is not None else _claim(meta, "depth")
        sigma = sigma if sigma is not None else _claim(meta, "sigma")
        where = frames.paths[0] if len(frames.paths) == 1 else f"{frames.paths[0]} ... ({len(frames.paths)} files)"
        boundary = meta.get("boundary")
        if boundary is not None and boundary not in ("walls", "periodic", "open"):
            raise ValueError(f"source: {frames.paths[0]} says boundary = {boundary!r}; it must be 'walls', 'periodic' "
                             f"or 'open'")
        return cls(frames.heights, frames.dx, frames.dt, eta_dot, depth, sigma, where, tank=boundary == "walls")

    @classmethod
    def load(cls, path) -> "Record":
        """A record saved by :meth:`save` (an ``.npz`` with ``eta``, ``dx``, ``dt`` and the claims).

        Parameters
        ----------
        path : str or os.PathLike
            The ``.npz`` file.

        Returns
        -------
        Record
            The saved record.

        Raises
        ------
        ValueError
            When ``path`` is not a file, or not a record (an unreadable or foreign ``.npz``).
        """
        from wavephys.core.files import _as_path

        p = _as_path("path", path)
        if not p.is_file():
            raise ValueError(f"path: {str(p)!r} is not a file (a record saved by Record.save)")
        try:
            return cls.from_files(p)
        except ValueError as exc:
            text = str(exc)
            raise ValueError("path" + text[len("source"):] if text.startswith("source") else f"path: {text}") \
                from None

    def save(self, path) -> "Path":
        """Write the record as one ``.npz`` (atomically): ``eta``, ``dx``, ``dt``, ``units``, and η̇ and the
        claims when present (a tank as ``boundary = "walls"``).

        Parameters
        ----------
        path : str or os.PathLike
            Output file, ending in ``.npz``, in an existing folder.

        Returns
        -------
        pathlib.Path
            The path written.
        """
        path = output_file(path, "path", (".npz",))
        entries = dict(eta=self.eta, dx=self.dx, dt=self.dt, units="m", axes="tyx")
        if self.tank:
            entries["boundary"] = "walls"
        if self.eta_dot is not None:
            entries["eta_dot"] = self.eta_dot
        for name in ("depth", "sigma"):
            if getattr(self, name) is not None:
                entries[name] = getattr(self, name)
        with atomic_path(path) as tmp, open(tmp, "wb") as f:
            np.savez_compressed(f, **entries)
        return path


def _claim(meta: dict, key: str):
    value = meta.get(key)
    if value is None or isinstance(value, (str, np.ndarray)) or isinstance(value, bool):
        return None
    return float(value)
