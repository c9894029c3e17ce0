"""Figures: functions that take data and return a matplotlib ``Figure`` (no physics here).

The figures are made without pyplot and never choose a backend, so they work in scripts,
on servers and in notebooks alike: in Jupyter (and in notebooks executed by nbclient) a
figure that is a cell's value shows once, inline, as a PNG (:class:`WaveFigure` renders
itself); ``fig.savefig(path)`` writes a file anywhere. Figures are not kept by pyplot,
so nothing accumulates in long scripts.
"""

from __future__ import annotations

import io

import numpy as np
from matplotlib.figure import Figure

from wavephys.core.inputs import Array, Bool, Int, Items, Mapping, Maybe, Real, Spec, Text, Vector, describe, validate

_ETA = Array(ndim=2)
_DX = Real(lo=0.0, lo_open=True)
_TEXT = Text()


class _Samples(Spec):
    """Measured dispersion samples: an object with arrays ``k`` and ``omega``."""

    def __call__(self, name, value, arguments):
        if not (hasattr(value, "k") and hasattr(value, "omega")):
            raise TypeError(f"{name} must be wavephys.harness.DispersionSamples, got {describe(value)}")
        return value


class _Angles(Spec):
    """A measured angle (degrees in (−90, 90), or an object with ``angle``), or a list or tuple of
    them (a wake's maximum on the track measures about 0, a little either side)."""

    def __call__(self, name, value, arguments):
        items = list(value) if isinstance(value, (list, tuple)) else [value]
        for i, a in enumerate(items):
            Real(lo=-90.0, hi=90.0, lo_open=True, hi_open=True)(name if len(items) == 1 else f"{name}[{i}]", getattr(a, "angle", a), arguments)
        return value

__all__ = ["WaveFigure", "plot_surface", "plot_dispersion", "plot_error_vs_time", "plot_curves", "plot_wake",
           "plot_images"]


class WaveFigure(Figure):
    """A matplotlib Figure that shows itself as a PNG wherever rich output is available.

    In Jupyter (and notebooks executed by nbclient) a figure that is a cell's value shows once,
    inline, as a PNG at 100 dpi; it is not registered with pyplot.

    Parameters
    ----------
    *args, **kwargs
        The arguments of :class:`matplotlib.figure.Figure` (``figsize`` in inches, ``dpi``, …).
    """

    def _repr_png_(self):
        buf = io.BytesIO()
        self.savefig(buf, format="png", dpi=100, bbox_inches="tight")
        return buf.getvalue()


def _figure(**kw):
    return WaveFigure(**kw)


@validate(eta=_ETA, dx=_DX, title=_TEXT, limit=Maybe(_DX))
def plot_surface(eta, dx: float, title: str = "", limit: float | None = None):
    """Height field η (m) on a grid of spacing dx (m), centred axes in metres.

    ``limit`` (m) sets the symmetric colour range (default: max |η|).

    Parameters
    ----------
    eta : array_like
        Heights η, m, 2-D (n_y, n_x), finite; shown in mm.
    dx : float
        Grid spacing, m, > 0.
    title : str
        Axes title (default none).
    limit : float, optional
        Colour range ±``limit``, m, > 0 (default: max |η|, or 1 m for flat water).

    Returns
    -------
    WaveFigure
        One axes in metres centred on the grid, with a colour bar in mm.
    """
    eta = np.asarray(eta)
    ny, nx = eta.shape
    ext = np.array([-nx / 2, nx / 2, -ny / 2, ny / 2]) * dx  # cell edges: samples sit at the cell centres
    fig = _figure(figsize=(5.5, 4.5))
    ax = fig.add_subplot()
    lim = limit or float(np.abs(eta).max()) or 1.0
    im = ax.imshow(eta * 1000, origin="lower", extent=ext, cmap="RdBu_r", vmin=-lim * 1000, vmax=lim * 1000)
    fig.colorbar(im, ax=ax, label="η (mm)")
    ax.set_xlabel("x (m)")
    ax.set_ylabel("y (m)")
    ax.set_title(title)
    fig.tight_layout()
    return fig


@validate(samples=_Samples(), theory_k=Maybe(Array(lo=0.0, ndim=1)), theory_omega=Maybe(Array(lo=0.0, ndim=1)),
          title=_TEXT)
def plot_dispersion(samples, theory_k=None, theory_omega=None, title: str = ""):
    """Measured (k, ω) samples against a theory curve (``theory_k``, ``theory_omega``: 1-D, rad/m
    and rad/s, given together).

    Parameters
    ----------
    samples : DispersionSamples
        Measured points: an object with arrays ``k`` (rad/m) and ``omega`` (rad/s), e.g. from
        :func:`wavephys.harness.measure_dispersion`.
    theory_k : array_like, optional
        Wavenumbers of the theory curve, rad/m, 1-D, ≥ 0.
    theory_omega : array_like, optional
        Angular frequencies of the theory curve, rad/s, 1-D, ≥ 0, the shape of ``theory_k``.
    title : str
        Axes title (default none).

    Returns
    -------
    WaveFigure
        Log-log axes of ω against k: the measured ridge as points, the theory as a line.

    Raises
    ------
    ValueError
        When only one of ``theory_k`` and ``theory_omega`` is given, or their shapes differ.
    TypeError
        When ``samples`` has no ``k`` and ``omega``.
    """
    if (theory_k is None) != (theory_omega is None) or (
            theory_k is not None and np.shape(theory_k) != np.shape(theory_omega)):
        raise ValueError(f"theory_k and theory_omega must be given together with one shape, got "
                         f"{np.shape(theory_k)} and {np.shape(theory_omega)}")
    fig = _figure(figsize=(5.5, 4))
    ax = fig.add_subplot()
    ax.loglog(samples.k, samples.omega, ".", ms=3, label="measured ridge")
    if theory_k is not None:
        ax.loglog(theory_k, theory_omega, "-", lw=1, label="theory")
    ax.set_xlabel("k (rad/m)")
    ax.set_ylabel("ω (rad/s)")
    ax.set_title(title)
    ax.legend()
    fig.tight_layout()
    return fig


class _Row(Spec):
    def __call__(self, name, value, arguments):
        if not isinstance(value, dict) or not {"method", "seconds", "error"} <= set(value):
            raise TypeError(f"{name} must be a dict with 'method', 'seconds' and 'error', got {describe(value)}")
        Real(lo=0.0, lo_open=True)(f"{name}['seconds']", value["seconds"], arguments)
        Real(lo=0.0, lo_open=True)(f"{name}['error']", value["error"], arguments)
        return value


@validate(rows=Items(_Row(), min_len=1), title=_TEXT, ylabel=_TEXT, floor=Maybe(Real(lo=0.0, lo_open=True)))
def plot_error_vs_time(rows, title: str = "error against cost", ylabel: str = "relative L2 error of η",
                       floor=None):
    """Log-log error against seconds, one line per method; ``rows`` are dicts with
    ``method``, ``seconds``, ``error`` and optionally ``label``. ``floor``: a dashed line
    at the measurement's own resolution.

    Parameters
    ----------
    rows : list of dict
        At least one row, each with ``method`` (the line it belongs to), ``seconds`` (cost, s, > 0),
        ``error`` (> 0) and optionally ``label`` (annotated next to the point).
    title : str
        Axes title.
    ylabel : str
        Label of the error axis.
    floor : float, optional
        Error at the measurement's own resolution, > 0: drawn as a dashed line.

    Returns
    -------
    WaveFigure
        Log-log axes of error against seconds (median), one line per method.
    """
    fig = _figure(figsize=(6, 4.5))
    ax = fig.add_subplot()
    methods = sorted({r["method"] for r in rows})
    for m in methods:
        pts = sorted((r["seconds"], r["error"], r.get("label", "")) for r in rows if r["method"] == m)
        xs, ys, labels = zip(*pts)
        ax.loglog(xs, ys, "o-", label=m)
        for x, y, lab in pts:
            if lab:
                ax.annotate(lab, (x, y), fontsize=7, xytext=(3, 3), textcoords="offset points")
    if floor is not None:
        ax.axhline(floor, ls="--", lw=0.8, color="gray")
        ax.annotate("measurement resolution", (ax.get_xlim()[0], floor), fontsize=7, xytext=(2, 2),
                    textcoords="offset points")
    ax.set_xlabel("seconds (median)")
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig


class _Curve(Spec):
    def __call__(self, name, value, arguments):
        Items(length=2)(name, value, arguments)
        x, y = value
        Array(ndim=1)(f"{name}[0]", x, arguments)
        Array(ndim=1, allow_inf=True)(f"{name}[1]", y, arguments)
        if np.shape(x) != np.shape(y):
            raise ValueError(f"{name}: x and y must have one length, got {np.shape(x)} and {np.shape(y)}")
        return value


@validate(curves=Mapping(_Curve()), xlabel=_TEXT, ylabel=_TEXT, title=_TEXT, logx=Bool(), logy=Bool(),
          hlines=Maybe(Mapping(Real())))
def plot_curves(curves: dict, xlabel: str, ylabel: str, title: str = "", logx=False, logy=True,
                hlines: dict | None = None):
    """Several (x, y) curves by label, e.g. a failure boundary; ``hlines`` label→y.

    Parameters
    ----------
    curves : dict
        Label (str) → ``(x, y)``: two 1-D arrays of one length (x finite; y may hold ±inf).
    xlabel : str
        Label of the x axis.
    ylabel : str
        Label of the y axis.
    title : str
        Axes title (default none).
    logx : bool
        Logarithmic x axis (default False).
    logy : bool
        Logarithmic y axis (default True).
    hlines : dict, optional
        Label (str) → y (a real number): dashed horizontal lines, annotated with their labels.

    Returns
    -------
    WaveFigure
        One axes with a line per curve and a legend.
    """
    fig = _figure(figsize=(6, 4.2))
    ax = fig.add_subplot()
    for label, (x, y) in curves.items():
        ax.plot(x, y, "o-", ms=3, label=label)
    for label, y in (hlines or {}).items():
        ax.axhline(y, ls="--", lw=0.8, color="gray")
        ax.annotate(label, (ax.get_xlim()[0], y), fontsize=7, xytext=(2, 2), textcoords="offset points")
    if logx:
        ax.set_xscale("log")
    if logy:
        ax.set_yscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return fig


@validate(eta=_ETA, dx=_DX, source=Vector(2), angle=Maybe(_Angles()), kelvin=Real(lo=0.0, hi=90.0), title=_TEXT,
          window=Maybe(Vector(4)))
def plot_wake(eta, dx: float, *, source=(0.0, 0.0), angle=None, kelvin: float = 19.47, title: str = "",
              window: tuple | None = None):
    """A wake height field with Kelvin's lines (dashed) and measured angles (solid, dotted, …).

    ``angle`` is a :class:`wavephys.wake.WakeAngle` (or degrees), or a sequence of them
    (e.g. the angle of maximum amplitude and the outer edge); ``window`` =
    (x_min, x_max, y_min, y_max) in m limits the view.

    Parameters
    ----------
    eta : array_like
        Wake heights η, m, 2-D (n_y, n_x), finite; the colour range is the 99.5th percentile of |η|.
    dx : float
        Grid spacing, m, > 0.
    source : (float, float), keyword-only
        Position (x, y) of the source, m, where the lines start (default the centre).
    angle : WakeAngle or float or sequence of them, optional, keyword-only
        Measured half-angles, degrees in (−90, 90) (or objects with an ``angle`` attribute), drawn
        solid, dotted, dash-dotted, dashed in turn.
    kelvin : float, keyword-only
        Kelvin's angle drawn dashed, degrees, 0 to 90 (default 19.47).
    title : str, keyword-only
        Axes title (default none).
    window : (float, float, float, float), optional, keyword-only
        View (x_min, x_max, y_min, y_max), m (default: the whole grid).

    Returns
    -------
    WaveFigure
        The :func:`plot_surface` figure with the lines and a legend.
    """
    import math

    fig = plot_surface(eta, dx, title=title, limit=float(np.percentile(np.abs(np.asarray(eta)), 99.5)))
    ax = fig.axes[0]
    x0, y0 = source
    n = np.asarray(eta).shape[-1]
    reach = n * dx
    measured = [] if angle is None else list(angle) if isinstance(angle, (list, tuple)) else [angle]
    lines = [(kelvin, "--", f"Kelvin {kelvin:.2f}°")]
    lines += [(getattr(a, "angle", a), style, f"measured {a}" if hasattr(a, "angle") else f"measured {a:.2f}°")
              for a, style in zip(measured, ("-", ":", "-.", (0, (5, 1))))]
    for deg, style, lab in lines:
        t = math.tan(math.radians(deg))
        ax.plot([x0, x0 - reach], [y0, y0 + t * reach], style, color="k", lw=0.8, label=lab)
        ax.plot([x0, x0 - reach], [y0, y0 - t * reach], style, color="k", lw=0.8)
    if window:
        ax.set_xlim(window[0], window[1])
        ax.set_ylim(window[2], window[3])
    ax.legend(loc="lower left", fontsize=7)
    return fig


class _Image(Spec):
    def __call__(self, name, value, arguments):
        Array(min_ndim=2)(name, value, arguments)
        shape = np.shape(value)
        if len(shape) > 3 or (len(shape) == 3 and shape[2] not in (3, 4)):
            raise ValueError(f"{name} must have shape (height, width), (height, width, 3) or (..., 4), got {shape}")
        return value


@validate(images=Items(_Image(), min_len=1, iterable=True), titles=Items(_TEXT, iterable=True),
          columns=Maybe(Int(lo=1)), size=Real(lo=0.0, hi=100.0, lo_open=True))
def plot_images(images, titles=(), columns: int | None = None, size: float = 3.2):
    """A row (or grid) of RGB images, e.g. rendered frames (uint8 or linear float in [0, 1]).

    Parameters
    ----------
    images : iterable of array_like
        At least one image, each of shape (height, width), (height, width, 3) or (height, width, 4);
        the first one's aspect ratio sets the figure's.
    titles : iterable of str
        Titles of the first images, in order (missing ones are empty).
    columns : int, optional
        Images per row, ≥ 1 (default: all in one row).
    size : float
        Height of each row of images, inches, in (0, 100] (default 3.2).

    Returns
    -------
    WaveFigure
        One axes (without ticks) per image, filled row by row.
    """
    images = list(images)
    cols = columns or len(images)
    rows = -(-len(images) // cols)
    h, w = np.asarray(images[0]).shape[:2]
    fig = _figure(figsize=(size * cols * w / max(h, 1), size * rows + 0.4))
    titles = list(titles) + [""] * (len(images) - len(titles))
    for i, (img, title) in enumerate(zip(images, titles)):
        ax = fig.add_subplot(rows, cols, i + 1)
        ax.imshow(img)
        ax.set_title(title, fontsize=9)
        ax.axis("off")
    fig.tight_layout()
    return fig
