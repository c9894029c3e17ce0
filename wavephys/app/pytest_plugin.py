"""pytest plugin (entry point ``pytest11: wavephys``): physics checks as fixtures.

Installed with wavephys; any test suite can then ask for these fixtures::

    def test_my_waves(wavephys_check):
        eta = run_my_simulator(...)              # (n_t, n_y, n_x) heights, m
        wavephys_check.dispersion(eta, dx, dt, Water(sigma=0.0), rtol=0.01,
                                  k_range=(1.0, 20.0))

    def test_my_fresnel(wavephys_check):
        wavephys_check.glsl(open("water.glsl").read(), function="fresnel", against="fresnel",
                            form="schlick")

    def test_my_export(wavephys_check):
        wavephys_check.record("export/frames/", Water(sigma=0.0), sea=True, direction=0.0)

    def test_my_wake(wavephys_check):
        wavephys_check.wake_angle(frame, dx=0.05, speed=1.5, angle="edge")   # degrees out

Fixtures: ``wavephys_water`` (default :class:`~wavephys.Water`) and ``wavephys_check``
(a :class:`Checker`). Each method returns the row or report it made and fails the test
with expected / measured / tolerance (and the likely cause) when it is not ok. This module
imports nothing heavy: JAX, NumPy and OpenGL load when a fixture is first used.

The plugin lives in the application layer because it uses both the wave harness
(:mod:`wavephys.harness`) and the optics (:mod:`optics.shaders`); its old path
``wavephys.harness.pytest_plugin`` still imports, with a ``DeprecationWarning``.
"""

from __future__ import annotations

import pytest

__all__ = ["Checker"]


class Checker:
    """Assertion helpers over :mod:`wavephys.harness` for use in tests.

    Each method builds a :class:`~wavephys.harness.Check` row (or a shader report), returns it
    when it is ok and otherwise raises ``AssertionError`` with expected / measured / tolerance
    (and the likely cause), which fails the test. The ``wavephys_check`` fixture gives one;
    ``Checker()`` takes no arguments and holds no state.
    """

    def close(self, quantity, measured, expected, *, rtol=None, atol=None, unit=""):
        """Assert measured ≈ expected (exactly one of ``rtol``, ``atol``, ≥ 0).

        Parameters
        ----------
        quantity : str
            What is measured (non-empty; a sentence fragment, with its conditions).
        measured : float
            The measured value, a real scalar in ``unit`` (NaN or inf fail the row).
        expected : float
            The expected value in ``unit``, real (±inf allowed).
        rtol : float, optional, keyword-only
            Relative tolerance, dimensionless, ≥ 0. Give exactly one of ``rtol`` and ``atol``.
        atol : float, optional, keyword-only
            Absolute tolerance in ``unit``, ≥ 0. Give exactly one of ``rtol`` and ``atol``.
        unit : str, optional, keyword-only
            Unit of ``measured`` and ``expected`` (default ``""``).

        Returns
        -------
        Check
            The ``"~="`` row (:func:`wavephys.harness.compare`), when it is ok.

        Raises
        ------
        AssertionError
            When the row is not ok; the message is the row's report.
        ValueError
            When neither or both of ``rtol`` and ``atol`` are given, or a tolerance is negative.
        """
        __tracebackhide__ = True
        from wavephys.harness.checks import assert_check, compare

        return assert_check(compare(quantity, measured, expected, rtol=rtol, atol=atol, unit=unit))

    def at_most(self, quantity, measured, limit, unit=""):
        """Assert measured <= limit.

        Parameters
        ----------
        quantity : str
            What is measured (non-empty; a sentence fragment, with its conditions).
        measured : float
            The measured value, a real scalar in ``unit`` (NaN or inf fail the row).
        limit : float
            The upper bound in ``unit``, real (±inf allowed).
        unit : str, optional
            Unit of ``measured`` and ``limit`` (default ``""``).

        Returns
        -------
        Check
            The ``"<="`` row (:func:`wavephys.harness.bound`), when it is ok.

        Raises
        ------
        AssertionError
            When ``measured`` exceeds ``limit``; the message is the row's report.
        """
        __tracebackhide__ = True
        from wavephys.harness.checks import assert_check, bound

        return assert_check(bound(quantity, measured, limit, unit=unit))

    def dispersion(self, eta, dx, dt, water, *, rtol=0.005, k_range=(0.0, float("inf")), min_samples=3):
        """Assert the measured ω(k) of ``eta`` (n_t, n_y, n_x) matches ``water``'s theory.

        The largest relative error over the shells with k in ``k_range`` (rad/m) must be
        <= ``rtol``, and at least ``min_samples`` shells must be measured there.

        Parameters
        ----------
        eta : array_like
            Heights, m, shape (n_t, n_y, n_x): frames ``dt`` apart on square cells (n_y ≠ n_x: a strip).
        dx : float
            Grid spacing, m, > 0.
        dt : float
            Time between frames, s, > 0.
        water : Water
            The water whose linear dispersion relation is the theory (a :class:`wavephys.Water`).
        rtol : float, optional, keyword-only
            Allowed max |ω_measured/ω_theory − 1|, dimensionless, ≥ 0 (default 0.005).
        k_range : (float, float), optional, keyword-only
            Band (k_min, k_max) of shells checked, rad/m, both ≥ 0, k_min < k_max (k_max may be inf;
            default: all shells).
        min_samples : int, optional, keyword-only
            Fewest shells in the band for the row to pass, ≥ 1 (default 3).

        Returns
        -------
        Check
            The row of :func:`wavephys.harness.dispersion_check`, when it is ok.

        Raises
        ------
        TypeError
            When ``water`` is not a :class:`wavephys.Water`.
        AssertionError
            When the error exceeds ``rtol`` or too few shells are measured; the message names the
            band, the worst k and, where recognizable, the likely cause.
        """
        __tracebackhide__ = True
        from wavephys.core.inputs import check_instance
        from wavephys.core.water import Water
        from wavephys.harness.checks import assert_check
        from wavephys.harness.dispersion import dispersion_check, measure_dispersion

        check_instance("water", water, Water, "wavephys.Water")
        samples = measure_dispersion(eta, dx, dt)
        return assert_check(dispersion_check(samples, water, dt, rtol=rtol, k_range=k_range,
                                             min_samples=min_samples))

    def energy_conserved(self, eta, eta_dot, dx, water, *, rtol=1e-3):
        """Assert the total energy of a time series (n_t, n_y, n_x) stays within ``rtol``.

        The drift is max |E(t)/E(0) − 1| of the total energy per unit area measured by
        :func:`wavephys.harness.measure_energy` at each frame.

        Parameters
        ----------
        eta : array_like
            Heights, m, shape (n_t, n_y, n_x).
        eta_dot : array_like
            Vertical velocities ∂η/∂t, m/s, the shape of ``eta``.
        dx : float
            Grid spacing, m, > 0.
        water : Water
            The water (density, gravity, surface tension, depth) the energy is measured in.
        rtol : float, optional, keyword-only
            Allowed drift, dimensionless, ≥ 0 (default 1e-3).

        Returns
        -------
        Check
            The ``"~="`` row of the drift against 0 with ``atol=rtol``, when it is ok.

        Raises
        ------
        ValueError
            When ``eta`` is not 3-D or ``rtol`` is negative.
        AssertionError
            When the drift exceeds ``rtol``.
        """
        __tracebackhide__ = True
        import numpy as np

        from wavephys.harness.checks import assert_check, compare
        from wavephys.harness.energy import measure_energy

        from wavephys.core.inputs import check_scalar

        check_scalar("rtol", rtol, lo=0.0)
        if np.ndim(eta) != 3:
            raise ValueError(f"eta must be a time series (n_t, n_y, n_x), got shape {np.shape(eta)}")
        e = np.asarray(measure_energy(eta, eta_dot, dx, water).total)
        drift = np.max(np.abs(e / e[0] - 1.0))
        return assert_check(compare("energy drift", drift, 0.0, atol=rtol))

    def record(self, frames, water=None, *, dx=None, dt=None, axes=None, png_range=None, only=None, **claims):
        """Assert that a record passes every check of :data:`wavephys.harness.RECORD_CHECKS` that applies.

        Parameters
        ----------
        frames : Record, array_like, str or os.PathLike
            A :class:`wavephys.harness.Record`; or heights, m, with ``dx``, ``dt`` and (when the layout is not
            ``(n_t, n, n)``) ``axes``; or a folder, glob or file of exported frames (EXR, 16-bit PNG, npy, npz),
            whose headers give dx and dt where they say.
        water : Water, optional
            The water of the theory (default ``Water()``; the record's claimed depth and σ apply).
        dx, dt : float, optional, keyword-only
            Grid spacing, m, and time between frames, s, > 0 (for arrays; for files when the headers lack them).
        axes : str, optional, keyword-only
            The layout of an array, or of one ``.npy``/``.npz`` file of frames, e.g. ``"tyx"`` or ``"yxt"``
            (time last): needed when the shape could be read more than one way.
        png_range : (float, float), optional, keyword-only
            For 16-bit PNGs without a JSON sidecar: (offset, amplitude), m.
        only : list of str, optional, keyword-only
            The checks to run (default: every one whose claims are given).
        **claims
            What the record is claimed to be, by name: every field of :class:`wavephys.harness.Claims`
            (``direction``, ``sea=True``, ``depth``, ``tank=True``, ``bed=``, ``rtol`` …) and any claim a registered
            check brings.

        Returns
        -------
        RecordReport
            The report, when every row is ok.

        Raises
        ------
        AssertionError
            When a row fails; the message is the table of rows, each with its likely cause.
        ValueError
            When the layout is ambiguous, a claim a named check needs is missing, or a value is out of range.
        """
        __tracebackhide__ = True
        import os

        from wavephys.harness.record import Record
        from wavephys.harness.suite import check_record

        from wavephys.core.inputs import check_instance
        from wavephys.core.water import Water

        if water is not None:
            check_instance("water", water, Water, "wavephys.Water")
        if png_range is not None:
            from wavephys.core.inputs import check_array

            check_array("png_range", png_range, ndim=1, shape_tail=(2,))
        try:
            if isinstance(frames, Record):
                record = frames
            elif isinstance(frames, (str, os.PathLike, list, tuple)) and not _is_numeric(frames):
                record = Record.from_files(frames, dx=dx, dt=dt, axes=axes, png_range=png_range)
            else:
                if dx is None or dt is None:
                    raise ValueError("dx and dt: heights given as an array need dx (m) and dt (s)")
                record = Record.from_array(frames, dx, dt, axes=axes)
        except (TypeError, ValueError) as exc:
            import re

            if re.match(r"(dx|dt|axes|channel)\b", str(exc)):
                raise
            raise type(exc)(f"frames: {exc}") from None
        report = check_record(record, water, only=only, **claims)
        if not report.ok:
            raise AssertionError(report.table())
        return report

    def wake_angle(self, eta, dx, *, speed, angle="edge", source=(0.0, 0.0), direction=0.0, size=None,
                   water=None, atol=1.0, rtol=0.1, **options):
        """Assert that a frame's wake angle is linear theory's, degrees in and out.

        Parameters
        ----------
        eta : array_like (n, n)
            Heights, m, one frame in the grid convention (the origin at the square's centre).
        dx : float
            Grid spacing, m, > 0.
        speed : float, keyword-only
            The source's speed, m/s, > 0.
        angle : {"edge", "max"}, optional, keyword-only
            ``"edge"``: the outer edge (cusp line, Kelvin's 19.47° in deep water); ``"max"``: the angle of maximum
            amplitude by Darmon, Benzaquen & Raphaël's definition (needs ``size``).
        source : (float, float), optional, keyword-only
            Where the source is, m (default the centre).
        direction : float, optional, keyword-only
            Its heading, degrees, 0 = +x (default 0).
        size : float, optional, keyword-only
            σ of the source as a Gaussian pressure, m (for ``"max"``).
        water : Water, optional, keyword-only
            Default deep water, gravity waves only.
        atol, rtol : float, optional, keyword-only
            Tolerance max(``atol`` degrees, ``rtol`` × theory's angle) (default 1° and 10 %).
        **options
            ``near``, ``far`` (``"edge"``) or ``radii`` (``"max"``), m: see :func:`wavephys.harness.wake_check`.

        Returns
        -------
        Check
            The row, degrees, when it is ok.

        Raises
        ------
        AssertionError
            When the angle is off; the message is the row with the likely cause.
        """
        __tracebackhide__ = True
        from wavephys.harness.checks import assert_check
        from wavephys.harness.steady import wake_check

        return assert_check(wake_check(eta, dx, speed=speed, water=water, source=source, direction=direction,
                                       angle=angle, size=size, atol=atol, rtol=rtol, **options))

    def glsl(self, source, function, against, *, takes=None, result=None, returns=None, uniforms=None,
             tolerance=None, language="auto", defines=None, include_dirs=(), chart=None, **options):
        """Assert that the shader ``function`` in ``source`` meets the physics of the check ``against``
        over its whole input domain (:func:`optics.shaders.check_glsl`, same arguments).

        Fails the test with the worst error, the input where it occurs, what the function computes (its
        fitted form and constants) and the likely cause; returns the :class:`~optics.shaders.ShaderReport`
        when it passes. A source that does not compile, or a function that is missing or cannot be called
        as asked, raises :class:`~optics.shaders.GLSLError` (a ValueError) with the driver's message.

        Parameters
        ----------
        source : str
            The shader source as shipped (GLSL, GLSL ES, WebGL, Shadertoy, a Godot shader file, or HLSL).
        function : str
            The function's name.
        against : str
            The check: a name in :data:`optics.shaders.SHADER_CHECKS` (e.g. ``"fresnel"``).
        takes : sequence of str, optional, keyword-only
            The role of each value-taking parameter, in order (default: the check's own, else read from the
            parameter names).
        result : str, optional, keyword-only
            ``"return"`` or the out parameter that holds the result (default: the return value, or a void
            function's only out parameter).
        returns : str, optional, keyword-only
            The result type expected (``"float"``, ``"vec3"``): refused if the declaration differs.
        uniforms : dict, optional, keyword-only
            Values for uniforms the function reads (name → number or tuple).
        tolerance : float, optional, keyword-only
            The largest error allowed, > 0 (default: the check's, from physics and the display).
        language : str, optional, keyword-only
            "auto" (default), "glsl", "glsl_es", "webgl", "shadertoy", "godot" or "hlsl".
        defines : dict or list of str, optional, keyword-only
            Macros the source relies on.
        include_dirs : sequence of path, optional, keyword-only
            Folders for ``#include``.
        chart : path, optional, keyword-only
            Also draw the error over the domain to this PNG.
        **options
            The check's domain options (``form="schlick"``, ``sides=("above",)``, ``bits=10`` …).

        Returns
        -------
        ShaderReport
            The report of :func:`optics.shaders.check_glsl`, when it is ok.

        Raises
        ------
        AssertionError
            When the function does not meet the physics; the message is the report.
        GLSLError
            When the source does not compile or the function is missing or cannot be called as asked.
        TranslatorMissing
            When HLSL is given and glslangValidator or spirv-cross is not installed.
        """
        __tracebackhide__ = True
        from optics.shaders import check_glsl

        report = check_glsl(source, function, against, takes=takes, result=result, returns=returns, uniforms=uniforms,
                            tolerance=tolerance, language=language, defines=defines, include_dirs=include_dirs,
                            chart=chart, **options)
        if not report.ok:
            raise AssertionError(report.report())
        return report

    def hlsl(self, source, function, against, **kwargs):
        """:meth:`glsl` for an HLSL source (``language="hlsl"``): translated by glslang and SPIRV-Cross, then
        checked as written.

        Parameters
        ----------
        source : str
            HLSL text defining ``function``.
        function : str
            The function's name.
        against : str
            The check (a name in :data:`optics.shaders.SHADER_CHECKS`).
        **kwargs
            The keyword arguments of :meth:`glsl`.

        Returns
        -------
        ShaderReport
            The report, when it is ok.

        Raises
        ------
        AssertionError
            When the function does not meet the physics.
        TranslatorMissing
            When glslangValidator or spirv-cross is not installed.
        """
        __tracebackhide__ = True
        return self.glsl(source, function, against, language="hlsl", **kwargs)


def _is_numeric(value) -> bool:
    """Whether a list or tuple holds numbers (heights) rather than paths."""
    if isinstance(value, (str, bytes)) or not isinstance(value, (list, tuple)):
        return False
    first = value[0] if value else None
    while isinstance(first, (list, tuple)) and first:
        first = first[0]
    return isinstance(first, (int, float)) or type(first).__module__ == "numpy"


@pytest.fixture
def wavephys_water():
    """Deep, clean water with the SI defaults of docs/physics.md."""
    from wavephys.core.water import Water

    return Water()


@pytest.fixture
def wavephys_check() -> Checker:
    """Physics assertion helpers (:class:`Checker`)."""
    return Checker()
