"""The spectral wave simulation as pure functions: Loviscach (2003), §3, on real FFTs.

State: the complex wave field ψ = φ + iχ (m²/s) stored as its two real parts, stacked,
so each step needs only real transforms, batched. :func:`step` does, in the paper's order:

1. one batched ``rfft2`` of (φ, χ);
2. impulse sources (stones, wind seas) added in Fourier space at t;
3. the surface of this state: η = −F⁻¹[(K/ω)χ̂] (+ the second-order term if enabled)
   and η̇ = F⁻¹[Kφ̂] (:mod:`wavephys.physics.heights`);
4. exact propagation by Δt, a rotation of (φ̂, χ̂) by ωΔt (:mod:`wavephys.physics.ring_waves`),
   plus continuous sources integrated exactly over the step;
5. two batched ``irfft2``: (φ', χ') → the next state, (η̂, η̇̂) → the surface
   [and (q̂, Λη̂, Λq̂) for the second-order term];
6. the open-ocean cutoff on the next state (if ``margin`` > 0; :mod:`wavephys.physics.boundary`);
7. host-side sources (ships) add this step's waves after the cutoff.

It returns the state at t + Δt and the surface at t: 2 forward and 4 inverse real
transforms per step (7 inverse with second order). Steps 1–4 and 5–6 are two compiled
programs that each start with their FFTs (the XLA CPU note in :mod:`wavephys.core.spectral`);
under a user's ``jit``/``vmap``/``grad`` they fuse into the caller's program.
"""

from __future__ import annotations

import functools
from functools import partial

import jax
import jax.numpy as jnp
import numpy as np

from wavephys.core.spectral import inverse_mode_transform, mode_transform
from wavephys.core.inputs import check_array, check_instance, check_int, check_scalar, is_traced
from wavephys.physics.heights import potential_from_height, second_order_correction
from wavephys.physics.interpolation import hermite_frame
from wavephys.physics.ring_waves import rotate_pair
from wavephys.parallel.fft import irfft2, rfft2
from wavephys.parallel.layout import constrain, field_sharding, place, spectrum_sharding
from wavephys.simulation.model import Model, Operators, natural, operators
from wavephys.simulation.sources import sort_sources
from wavephys.simulation.state import State, Surface, advance_clock, split_time, unchecked

__all__ = ["step", "run", "surface", "energy", "frame", "initial_state", "state_from_psi", "add_height",
           "add_source", "checked"]


# -- the compiled pieces (pure) ---------------------------------------------------------
def _rfft2(model: Model, fields):
    """The model's forward transform: ``rfft2``, the slab transform of a sharded model, or the
    cosine transform along walled axes (:meth:`Model.transform`)."""
    if model.walls:
        return mode_transform(fields, model.wall_axes, model.tank_cells)
    return rfft2(fields, model.mesh, model.mesh_axis)


def _irfft2(model: Model, spectra):
    if model.walls:
        return inverse_mode_transform(spectra, model.grid.n, model.wall_axes, model.tank_cells)
    return irfft2(spectra, model.grid.n, model.mesh, model.mesh_axis)


def _widen(model: Model, spectrum):
    """A source's half spectrum in the model's layout: a natural ``(..., n, n//2 + 1)`` one is
    padded with zero columns and split by columns when sharded; one already in the padded
    layout (a source that used the model's own transform) is kept."""
    if spectrum is None or model.mesh is None:
        return spectrum
    pad = model.spectrum_width - spectrum.shape[-1]
    spectrum = jnp.pad(spectrum, [(0, 0)] * (spectrum.ndim - 1) + [(0, pad)])
    return constrain(spectrum, spectrum_sharding(model.mesh, model.mesh_axis, spectrum.ndim))


def _spectra(model: Model, ops: Operators, fields, time, impulses):
    """rfft2 of the state with the impulses of t added: (φ̂, χ̂)."""
    spec = _rfft2(model, fields)
    ph, ch = spec[..., 0, :, :], spec[..., 1, :, :]
    for source in impulses:
        d_ph, d_ch = (_widen(model, d) for d in source.impulse(model, natural(model, ops), time))
        ph = ph if d_ph is None else ph + d_ph
        ch = ch if d_ch is None else ch + d_ch
    return ph, ch


def _surface_spectra(model: Model, ops: Operators, ph, ch):
    eta_hat = -ops.height * ch
    surf = [eta_hat, ops.K * ph]
    if model.second_order:
        q_hat = ops.height * ph
        surf += [q_hat, ops.k * eta_hat, ops.k * q_hat]
    return jnp.stack(surf, axis=-3)


@jax.jit
def _forward(model: Model, ops: Operators, fields, time, impulses, rates):
    """Steps 1–4: transforms, impulses, surface spectra, propagation and continuous sources.

    Returns the next state's half spectra (φ̂', χ̂') and the surface's, as two stacks."""
    ph, ch = _spectra(model, ops, fields, time, impulses)
    surf = _surface_spectra(model, ops, ph, ch)
    ph, ch = rotate_pair(ph, ch, ops.cos, ops.sin)
    for source in rates:
        for s_hat, a, b in _duhamel(model, ops, source, time):
            ph, ch = ph + a * s_hat, ch - b * s_hat
    return jnp.stack([ph, ch], axis=-3), surf


def _duhamel(model: Model, ops: Operators, source, time):
    """(Ŝ_j, a_j, b_j) for a continuous source over [t, t + Δt]: composite midpoint rule on the
    source's ``substeps`` M sub-intervals δ = Δt/M, each propagated exactly to the step's end:
    Δψ̂ = Σ_j Ŝ(t + (j + ½)δ)·e^{−iω(M−1−j)δ}(1 − e^{−iωδ})/(iω) = Σ_j Ŝ_j (a_j − i b_j)."""
    m = getattr(source, "substeps", 1)
    rate = lambda t: _widen(model, source.rate(model, natural(model, ops), t))
    if m == 1:
        return [(rate(time + 0.5 * model.dt), ops.duhamel_sin, ops.duhamel_cos)]
    delta = model.dt / m
    pos = ops.omega > 0
    w = jnp.where(pos, ops.omega, 1.0)
    big_a = jnp.where(pos, jnp.sin(ops.omega * delta) / w, delta)
    big_b = jnp.where(pos, (1.0 - jnp.cos(ops.omega * delta)) / w, 0.0)
    terms = []
    for j in range(m):
        c, s = jnp.cos(ops.omega * (m - 1 - j) * delta), jnp.sin(ops.omega * (m - 1 - j) * delta)
        s_hat = rate(time + (j + 0.5) * delta)
        terms.append((s_hat, c * big_a - s * big_b, c * big_b + s * big_a))
    return terms


def _surface_fields(model: Model, surf):
    if model.second_order:
        eta = surf[..., 0, :, :] + second_order_correction(surf[..., 0, :, :], surf[..., 2, :, :],
                                                           surf[..., 3, :, :], surf[..., 4, :, :])
        return jnp.stack([eta, surf[..., 1, :, :]], axis=-3)
    return surf


@jax.jit
def _inverse(model: Model, ops: Operators, state_spec, surf_spec, time, time_error, dt_error):
    """Steps 5–6: the two batched irfft2 (next state, surface), both first, then the cutoff.

    Two transforms into two buffers: one transform of all four planes would need a copy to
    split them (measured 23 % slower at N = 2048)."""
    new = _irfft2(model, state_spec)
    surf = _irfft2(model, surf_spec)
    if ops.mask is not None:
        new = new * ops.mask
    surf = _surface_fields(model, surf)
    dtype = model.real_dtype
    later, error = advance_clock(time, time_error + dt_error, jnp.asarray(model.dt, dtype))
    return (unchecked(State, new.astype(dtype), later, error),
            unchecked(Surface, surf.astype(dtype), time))


def _dt_error(model):
    """Δt − Δt rounded to the model's dtype, s (0 for traced models): added to the clock's error
    term each step, so that even a Δt float32 cannot hold (1/60 s) does not bias long runs."""
    if is_traced(model.dt):
        return jnp.zeros((), model.real_dtype)
    return jnp.asarray(float(model.dt) - float(np.asarray(model.dt, model.real_dtype)), model.real_dtype)


def _pure_step(model, ops, state, impulses=(), rates=(), dt_error=0.0):
    return _inverse(model, ops, *_forward(model, ops, state.fields, state.time, impulses, rates), state.time,
                    state.time_error, dt_error)


def _lay(model: Model, fields):
    """Fields in the model's layout: split by rows over the mesh of a sharded model."""
    if model.mesh is None:
        return fields
    return place(fields, field_sharding(model.mesh, model.mesh_axis, np.ndim(fields)))


def _laid(model: Model, state: State) -> State:
    if model.mesh is None or is_traced(state):
        return state
    ndim = np.ndim(state.fields)
    sharding = field_sharding(model.mesh, model.mesh_axis, ndim)
    current = getattr(state.fields, "sharding", None)
    if current is not None and current.is_equivalent_to(sharding, ndim):
        return state
    return unchecked(State, place(state.fields, sharding), state.time, state.time_error)


# -- checks -------------------------------------------------------------------------------
def _check_model(model):
    check_instance("model", model, Model, "wavephys.simulation.Model")


def _check_state(model: Model, state, name: str = "state"):
    check_instance(name, state, State, "wavephys.simulation.State")
    n = model.grid.n
    shape = np.shape(state.fields)
    if shape[-3:] != (2, n, n):
        raise ValueError(f"{name}.fields must have shape (..., 2, {n}, {n}) for this model's grid, got {shape}")
    if np.dtype(state.fields.dtype) != model.real_dtype:
        raise ValueError(f"{name}.fields must be {model.dtype} like the model, got {state.fields.dtype}")


# -- public -------------------------------------------------------------------------------
def step(model: Model, state: State, sources=()):
    """Advance ``state`` by Δt: returns ``(state at t + Δt, surface at t)``.

    Pure: the same inputs give the same outputs, and it works under ``jax.jit``,
    ``jax.vmap`` (e.g. over a batch of :class:`~wavephys.Water`) and ``jax.grad``
    (e.g. with respect to ``model.water.depth``) when no host-side source (ship) is given.

    Parameters
    ----------
    model : Model
        Grid, water, Δt and numerical options.
    state : State
        The wave field at t (``initial_state(model)`` for still water).
    sources : sequence of sources
        Objects of the source protocol (:mod:`wavephys.simulation.sources`): impulses
        (``Stones``, ``WindSea``) are added at t, before the surface is taken; continuous
        sources (``Forcing``) act over [t, t + Δt]; ships add their waves after the cutoff.

    Returns
    -------
    (State, Surface)
        The state at t + Δt, and the surface (η in m, η̇ in m/s) at t.

    Examples
    --------
    >>> from wavephys import Grid, Water, Stones
    >>> model = Model(Grid(64, 2.0), Water(), dt=0.02, margin=8)
    >>> new, surf = step(model, initial_state(model), [Stones(0.0, 0.0, 0.1, 0.01)])
    >>> surf.eta.shape, round(float(new.time), 2)
    ((64, 64), 0.02)
    """
    _check_model(model)
    _check_state(model, state)
    impulses, rates, adders = sort_sources(model, sources)
    new, surf = _pure_step(model, operators(model), _laid(model, state), impulses, rates, _dt_error(model))
    if adders:
        if is_traced(state) or is_traced(model):
            raise TypeError("ships (host-side sources) cannot be stepped under jit/vmap/grad: call step "
                            "outside JAX transformations, or leave them out")
        fields, t = new.fields, state.exact_time
        for source in adders:
            fields = source.add(model, fields, t)
        new = unchecked(State, _lay(model, fields), new.time, new.time_error)
    return new, surf


@partial(jax.jit, static_argnames=("steps",))
def _run(model, ops, state, rates, steps, dt_error):
    return jax.lax.scan(lambda s, _: _pure_step(model, ops, s, (), rates, dt_error), state, None, length=steps)


def run(model: Model, state: State, steps: int, sources=()):
    """``steps`` steps in one compiled loop: ``(final state, Surface of stacked arrays)``.

    The surfaces are those at t, t + Δt, …, t + (steps − 1)Δt (shape ``(steps, n, n)``).
    Only continuous sources (``rate``: forcing functions) can act in the loop; add
    impulses with :func:`add_source` first, and step ships one :func:`step` at a time.

    Parameters
    ----------
    model : Model
        The pure step's model (grid, water, Δt).
    state : State
        A state of that model (:func:`initial_state`).
    steps : int
        Steps, ≥ 1.
    sources : sequence
        Continuous sources (with a ``rate`` hook, e.g. :class:`wavephys.physics.forcing.Forcing`).

    Returns
    -------
    (State, Surface)
        The state after ``steps`` steps, and the surfaces at each step's start stacked on a
        leading axis (``eta`` and ``eta_dot`` of shape ``(steps, n, n)``, m and m/s).
    """
    _check_model(model)
    _check_state(model, state)
    steps = check_int("steps", steps, lo=1)
    impulses, rates, adders = sort_sources(model, sources)
    if impulses or adders:
        raise ValueError("run takes continuous sources (forcing functions) only: apply impulses (stones, "
                         "wind) with add_source before the loop, and step ships with step()")
    return _run(model, operators(model), _laid(model, state), rates, steps, _dt_error(model))


@jax.jit
def _surface(model, ops, fields, time):
    ph, ch = _spectra(model, ops, fields, time, ())
    surf = _irfft2(model, _surface_spectra(model, ops, ph, ch))
    return unchecked(Surface, _surface_fields(model, surf).astype(model.real_dtype), time)


def surface(model: Model, state: State) -> Surface:
    """The surface of a state, without stepping.

    Parameters
    ----------
    model : Model
        The pure step's model (grid, water, Δt).
    state : State
        A state of that model (:func:`initial_state`).

    Returns
    -------
    Surface
        η (m) and η̇ (m/s), each ``(n, n)``.
    """
    _check_model(model)
    _check_state(model, state)
    return _surface(model, operators(model), _laid(model, state).fields, state.time)


def energy(model: Model, state: State):
    """Wave energy per unit area of ``state`` (linear theory), J/m².

    E = ½ρ⟨φ·Kφ + χ·Kχ⟩, which equals potential + capillary + kinetic energy of the
    first-order surface (docs/physics.md §1.8); conserved exactly by propagation.

    Parameters
    ----------
    model : Model
        The pure step's model (grid, water, Δt).
    state : State
        A state of that model (:func:`initial_state`).

    Returns
    -------
    jax.Array
        A scalar, J/m².
    """
    _check_model(model)
    _check_state(model, state)
    fields = _laid(model, state).fields
    kf = _irfft2(model, operators(model).K * _rfft2(model, fields))
    return model.water.rho * jnp.mean(fields * kf, axis=(-3, -2, -1))


def frame(model: Model, before: Surface, after: Surface, s: float):
    """The height between two consecutive steps, by cubic Hermite interpolation.

    Parameters
    ----------
    model : Model
    before, after : Surface
        The surfaces at t and t + Δt (from :func:`step` or :func:`run`).
    s : float
        Fraction of the step, in [0, 1].

    Returns
    -------
    jax.Array (n, n)
        η at t + sΔt, m (from η and η̇ at both ends: docs/physics.md, Hermite frames).
    """
    _check_model(model)
    check_instance("before", before, Surface, "wavephys.simulation.Surface")
    check_instance("after", after, Surface, "wavephys.simulation.Surface")
    return hermite_frame(before.eta, after.eta, before.eta_dot, after.eta_dot, model.dt, s)


def initial_state(model: Model, time: float = 0.0) -> State:
    """Still water.

    Parameters
    ----------
    model : Model
    time : float
        The state's time, s, finite.

    Returns
    -------
    State
        Zero fields, laid out like the model (split over its mesh when sharded).
    """
    _check_model(model)
    check_scalar("time", time)
    n = model.grid.n
    if model.mesh is None:
        fields = jnp.zeros((2, n, n), model.dtype)
    else:  # made in place on every device (no host copy; works across processes)
        fields = _zeros(n, model.dtype, field_sharding(model.mesh, model.mesh_axis, 3))()
    return unchecked(State, fields, *split_time(time, model.real_dtype))


@functools.lru_cache(maxsize=16)
def _zeros(n: int, dtype: str, sharding):
    return jax.jit(lambda: jnp.zeros((2, n, n), dtype), out_shardings=sharding)


def state_from_psi(model: Model, psi, time: float = 0.0) -> State:
    """A state from the complex wave field ψ = φ + iχ.

    Parameters
    ----------
    model : Model
    psi : array_like (n, n), complex
        ψ, m²/s.
    time : float
        The state's time, s.

    Returns
    -------
    State
    """
    _check_model(model)
    n = model.grid.n
    check_array("psi", psi, complex_ok=True, ndim=2, shape_tail=(n, n))
    check_scalar("time", time)
    psi = jnp.asarray(psi)
    return unchecked(State, _lay(model, jnp.stack([jnp.real(psi), jnp.imag(psi)]).astype(model.dtype)),
                     *split_time(time, model.real_dtype))


def _check_height_units(eta, grid):
    """Heights are metres: a wave higher than a tenth of the domain is steeper than any water
    wave can be (Stokes' limit H/λ ≈ 0.14), so it is almost surely in other units."""
    top = float(np.max(np.abs(np.asarray(eta))))
    if top > 0.1 * float(grid.length):
        raise ValueError(f"eta: heights are in metres and must stay below a tenth of the {float(grid.length):g} m "
                         f"domain (a steeper wave breaks), got max |eta| = {top:.4g}; were they in mm or cm?")


def add_height(model: Model, state: State, eta) -> State:
    """Add a height disturbance with the fluid at rest (its mean drops).

    Parameters
    ----------
    model : Model
        The pure step's model (grid, water, Δt).
    state : State
        A state of that model (:func:`initial_state`).
    eta : array_like (n, n)
        The disturbance, m, below L/10 (larger is refused as a units mistake).

    Returns
    -------
    State
    """
    _check_model(model)
    _check_state(model, state)
    n = model.grid.n
    check_array("eta", eta, ndim=2, shape_tail=(n, n))
    _check_height_units(eta, model.grid)
    if model.mesh is not None or model.walls:  # fluid at rest: χ̂ −= (ω/K)·η̂, with the model's own transforms
        state = _laid(model, state)
        eta = _lay(model, np.asarray(eta, model.dtype))
        return unchecked(State, _add_height_sharded(model, operators(model), state.fields, eta), state.time,
                         state.time_error)
    psi = potential_from_height(jnp.asarray(eta, model.dtype), model.grid, model.water)
    return unchecked(State, state.fields + jnp.stack([psi.real, psi.imag]).astype(model.dtype), state.time,
                     state.time_error)


@jax.jit
def _add_height_sharded(model, ops, fields, eta):
    chi = _irfft2(model, -ops.inverse_height * _rfft2(model, eta)).astype(model.real_dtype)
    return fields + jnp.stack([jnp.zeros_like(chi), chi])


@jax.jit
def _apply(model, ops, fields, time, impulses):
    ph, ch = _spectra(model, ops, fields, time, impulses)
    return _irfft2(model, jnp.stack([ph, ch], axis=-3)).astype(model.real_dtype)


def add_source(model: Model, state: State, source) -> State:
    """Apply an impulse source to a state now, without stepping.

    Parameters
    ----------
    model : Model
        The pure step's model (grid, water, Δt).
    state : State
        A state of that model (:func:`initial_state`).
    source : object
        An impulse source (with an ``impulse`` hook: :class:`wavephys.Stones`, a wind sea).

    Returns
    -------
    State
    """
    _check_model(model)
    _check_state(model, state)
    impulses, rates, adders = sort_sources(model, (source,))
    if not impulses:
        raise TypeError(f"source must be an impulse source (Stones, WindSea), got {type(source).__name__}: "
                        f"continuous sources and ships act during step()")
    return unchecked(State, _apply(model, operators(model), _laid(model, state).fields, state.time, impulses),
                     state.time, state.time_error)


def checked(fn):
    """``fn`` with its traced values checked too: NaN/inf produced inside it raise.

    Boundary checks see only kinds and shapes of traced arguments; this wraps ``fn`` (a
    :func:`step`, a jitted loop, your own function) with
    :func:`jax.experimental.checkify.checkify` (float checks and user checks) and raises
    ``ValueError`` with checkify's message when a NaN or inf appears.

    >>> from wavephys import Grid, Water
    >>> model = Model(Grid(16, 1.0), Water(), dt=0.01)
    >>> new, surf = checked(step)(model, initial_state(model))

    Parameters
    ----------
    fn : callable
        Any JAX-traceable function.

    Returns
    -------
    callable
        ``fn``'s results, after raising ``ValueError`` if a check failed inside it.
    """
    import functools

    from jax.experimental import checkify

    if not callable(fn):
        raise TypeError(f"fn must be a function, got {type(fn).__name__}")
    wrapped = checkify.checkify(fn, errors=checkify.float_checks | checkify.user_checks)

    @functools.wraps(fn)
    def run_checked(*args, **kwargs):
        err, out = wrapped(*args, **kwargs)
        message = err.get()
        if message is not None:
            raise ValueError(f"{getattr(fn, '__name__', 'fn')}: a traced value is not finite: {message}")
        return out

    return run_checked
