"""The one nonlinear model of the aircraft: ``rhs(t, x, u)``.

Source: Tuzcu & Nguyen (2014), eqs. (2)-(4), (12), (33). The paper integrates momenta p = M(q) V
(eq. 12); flexsim integrates the velocities with the equivalent velocity form, which keeps the implicit
aerodynamic coupling clean (E(x) x_dot = f(x), docs/design.md):

    M(q) V_dot = -M_dot V + g(V, p) + [0, 0, dT/dq, 0] - K [0, 0, q, xi] + Q_gravity + Q_thrust + Q_aero

with p = M V and the quasi-coordinate terms of eq. (33)

    g_v = -omega x p_v,      g_omega = -v x p_v - omega x rho_omega

and the kinematics R_dot = C^T v, Theta_dot = E^-1 omega, q_dot = s, xi_dot = eta (eq. 4).

Trim, linearisation, simulation and the gymnasium environments all call :meth:`AircraftModel.rhs`. Its
arithmetic is the compiled kernel :func:`flexsim._kernels.rhs` (numba, cached on disk; ``NUMBA_DISABLE_JIT=1``
runs the same code as Python) on the model's frozen arrays (:attr:`AircraftModel.kernel_data`);
:meth:`AircraftModel.rhs_batch` evaluates N states of one model in one call.
The model is immutable after construction: atmospheric disturbances (gusts, turbulence) are passed per
call, ``rhs(t, x, u, wind)``, as python-control passes its parameters to ``updfcn(t, x, u, params)``, so
one model serves still-air trims and any number of windy runs without being changed or reset.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable
import dataclasses

import numpy as np

from flexsim import _kernels as _k
from flexsim._arrays import kernel_arg as _arg
from flexsim.aircraft.definition import Aircraft
from flexsim._immutable import Immutable
from flexsim.atmosphere import G0, Z_MAX, Z_MIN, _range_error
from flexsim.errors import expect_type
from flexsim.model.coupling import AeroCoupling, AeroOptions
from flexsim.model.bodies import SlenderBodies
from flexsim.model.drag import ParasiteDrag
from flexsim.model.layout import StateLayout
from flexsim.model.reference import ReferenceGeometry
from flexsim.model.terms import NONLINEAR_ANALYSES, Terms
from flexsim.model.variant import Variant, VariantSettings
from flexsim.kinematics import dcm_321
from flexsim.structure.model import structural_model

__all__ = ["Variant", "VariantSettings", "AircraftModel", "STANDARD_GRAVITY", "CONTROL_NAMES", "Wind", "check_model",
           "check_aircraft"]

#: Standard gravitational acceleration [m/s^2] (paper eq. 32's g): the atmosphere module's one definition.
STANDARD_GRAVITY = G0
#: An atmospheric disturbance: ``wind(t [s], positions_ned_m (k, 3)) -> air velocity (k, 3)`` [m/s], NED.
Wind = Callable[[float, np.ndarray], np.ndarray]
#: The control vector u of the paper (text after eq. 33): [T_e (N), delta_a, delta_e, delta_r (rad)].
CONTROL_NAMES = ("thrust", "aileron", "elevator", "rudder")


def _split(changes: dict, terms: Terms, variant: VariantSettings) -> tuple[Terms, VariantSettings]:
    """``terms`` and ``variant`` with the named fields of ``changes`` replaced (:meth:`AircraftModel.replace`).

    A name is a field of :class:`Terms` or of :class:`VariantSettings`; ``terms`` and ``variant`` replace the whole
    object (``variant`` may also be a :class:`Variant` or its name: the kind); ``aero`` may be a model name
    (``AeroOptions(model=name)``).
    """
    changes = dict(changes)
    if "terms" in changes:
        terms = changes.pop("terms")
        if not isinstance(terms, Terms):
            raise ValueError(f"terms = {terms!r}: must be a flexsim.model.terms.Terms")
    if "variant" in changes:
        v = changes.pop("variant")
        variant = v if isinstance(v, VariantSettings) else dataclasses.replace(variant, kind=v)
    if isinstance(changes.get("aero"), str):
        changes["aero"] = AeroOptions(model=changes["aero"])
    term_names = {f.name for f in dataclasses.fields(Terms)}
    variant_names = {f.name for f in dataclasses.fields(VariantSettings)} - {"kind"}
    unknown = sorted(set(changes) - term_names - variant_names)
    if unknown:
        raise ValueError(f"{', '.join(unknown)}: not a field of the model's terms (flexsim.model.terms.Terms: "
                         f"{', '.join(sorted(term_names))}) or variant (flexsim.model.variant.VariantSettings: "
                         f"{', '.join(sorted(variant_names))})")
    for_terms = {k: v for k, v in changes.items() if k in term_names}
    for_variant = {k: v for k, v in changes.items() if k in variant_names}
    if for_terms:
        terms = dataclasses.replace(terms, **for_terms)
    if for_variant:
        variant = dataclasses.replace(variant, **for_variant)
    return terms, variant


def check_aircraft(aircraft, name: str = "aircraft") -> None:
    """TypeError naming ``name`` unless ``aircraft`` is an :class:`Aircraft` (a name or a path says how to load it)."""
    hint = ""
    if isinstance(aircraft, (str, os.PathLike)):
        hint = f"load it first: flexsim.load_aircraft({str(aircraft)!r})"
    elif isinstance(aircraft, AircraftModel):
        hint = "give the model's aircraft (model.aircraft)"
    expect_type(name, aircraft, Aircraft, "an Aircraft (flexsim.load_aircraft)", hint)


def check_model(model, name: str = "model", *, nonlinear: bool = False) -> "AircraftModel":
    """``model`` when it is an :class:`AircraftModel`; else a TypeError naming ``name`` and saying how to build one
    (from an :class:`Aircraft`, a bundled name or a TOML path). Every public function taking a model calls it where
    the model enters.

    A model whose terms choose the geometrically nonlinear beams (:attr:`Terms.nonlinear_beams`) is refused with a
    ValueError naming that field unless the caller evaluates it (``nonlinear=True``): the analyses of the paper's
    linear structure never answer for it silently."""
    hint = "build one with flexsim.AircraftModel(aircraft, aero=...)"
    if isinstance(model, Aircraft):
        hint = f"an Aircraft is the definition; build the model with flexsim.AircraftModel({name}, aero=...)"
    elif isinstance(model, (str, os.PathLike)):
        hint = f"build it with flexsim.AircraftModel(flexsim.load_aircraft({str(model)!r}), aero=...)"
    expect_type(name, model, AircraftModel, "an AircraftModel", hint)
    beams = model.terms.nonlinear_beams
    if beams is not None and not nonlinear:
        raise ValueError(f"nonlinear_beams = {beams!r}: this analysis evaluates the paper's linear structure only; a "
                         f"model with the geometrically nonlinear beams is evaluated by {NONLINEAR_ANALYSES} "
                         "(docs/nonlinear-beams.md), or use model.replace(nonlinear_beams=None) for the linear model")
    return model


class AircraftModel(Immutable):
    """Equations of motion of the whole flexible aircraft (eq. 33) in first-order form.

    One immutable value: the aircraft, its physical terms (:class:`Terms`) and its variant (:class:`VariantSettings`).
    Immutable after construction (:class:`flexsim._immutable.Immutable`): attributes cannot be set or deleted and
    every array it holds — its own, the structure's and the aerodynamic coupling's — is read-only; disturbances
    are an argument of :meth:`rhs`. A model that differs in some terms or in its variant is made by
    :meth:`replace` (a sibling of the same aircraft object); analyses that need another aerodynamic model or
    variant of the model they are given build it so, and so evaluate every other term as given.

    Parameters
    ----------
    aircraft : Aircraft
        The definition (use :meth:`Aircraft.subset` for a subset of components).
    terms : Terms, optional
        The physical terms of the model (:class:`flexsim.model.terms.Terms`: aerodynamics, gravity, structural
        damping, the density of the aerodynamics, a frozen compressibility Mach number, the force resolution's
        flow-angle terms, the thrust line, the inertia's and the strips' offsets). Default ``Terms()``: every term on.
    variant : VariantSettings, Variant or str, optional
        The variant (:class:`flexsim.model.variant.VariantSettings`: free, restrained in a wind tunnel, quasi-rigid,
        with their options), or only its kind (``"free"`` default, ``"restrained"``, ``"quasi-rigid"``).
    **fields
        Shorthand: any field of :class:`Terms` (``aero`` may be a model name, ``"unsteady"`` or ``"quasi-steady"``,
        or None for vacuum) or of :class:`VariantSettings` (``restrained_velocity_m_s``, ``altitude_m``, ...) given by
        name, e.g. ``AircraftModel(aircraft, aero="unsteady", gravity_m_s2=0.0)``. A field may not be given both
        this way and inside a ``terms`` or ``variant`` object.

    Attributes
    ----------
    aircraft : Aircraft
    structure : StructuralModel
    terms : Terms
    variant : VariantSettings
    layout : StateLayout
    reference_geometry : ReferenceGeometry or None
        The wing's reference area S, span b, mean chord and mean aerodynamic chord
        (:class:`flexsim.model.reference.ReferenceGeometry`); None without aerodynamics or without a wing.
    """

    def __init__(self, aircraft: Aircraft, *, terms: Terms | None = None,
                 variant: VariantSettings | Variant | str | None = None, **fields) -> None:
        check_aircraft(aircraft)
        if terms is not None:
            if not isinstance(terms, Terms):
                raise ValueError(f"terms = {terms!r}: must be a flexsim.model.terms.Terms (or None)")
            given = [k for k in fields if k in Terms.__dataclass_fields__]
            if given:
                raise ValueError(f"terms and {', '.join(given)}: give the physical terms either as terms=Terms(...) or "
                                 "as these keyword arguments, not both")
        if isinstance(variant, VariantSettings):
            given = [k for k in fields if k in VariantSettings.__dataclass_fields__]
            if given:
                raise ValueError(f"variant and {', '.join(given)}: give the variant either as "
                                 "variant=VariantSettings(...) or as these keyword arguments, not both")
        base = VariantSettings() if variant is None else (variant if isinstance(variant, VariantSettings)
                                                          else VariantSettings(variant))
        terms, variant = _split(fields, Terms() if terms is None else terms, base)
        #: The physical terms of this model (:class:`flexsim.model.terms.Terms`; ``terms.record()`` for logs and rows).
        self.terms = terms
        #: The variant of this model (:class:`flexsim.model.variant.VariantSettings`).
        self.variant = variant
        aero = terms.aero
        self.aircraft = aircraft
        self.structure = structural_model(aircraft)  # one per aircraft content: immutable, shared
        damping = self.structural_damping_ratio
        if not (np.isfinite(damping) and 0.0 <= damping < 1.0):
            raise ValueError(f"structural_damping = {damping!r}: must be a damping ratio in [0, 1)")
        if terms.inertia_q_offset_m is not None and len(terms.inertia_q_offset_m) != self.structure.dofs.nq:
            raise ValueError(f"inertia_q_offset_m: {len(terms.inertia_q_offset_m)} entries; {aircraft.name} has "
                             f"nq = {self.structure.dofs.nq} bending coordinates")
        dofs = self.structure.dofs
        kind = variant.kind
        rigid = kind is not Variant.RESTRAINED
        elastic = kind is not Variant.QUASI_RIGID
        if aero is not None and aero.model == "theodorsen":
            raise ValueError(
                'aero model = "theodorsen": the Theodorsen function is a frequency-domain model for linear '
                'flutter analysis (flexsim.linear); the time-domain model takes "unsteady" or "quasi-steady"'
            )
        self.aero = None if aero is None else AeroCoupling(self.structure, terms)
        # parasite drag belongs to the physical force resolution; the paper's (eq. 28) has the strips' drag only
        has_drag = (aero is not None and aero.parasite_drag and bool(aircraft.aero_settings.drag)
                    and self.aero.formulation == "physical")
        #: Parasite drag of the file's drag items (:mod:`flexsim.model.drag`), or None.
        self.parasite_drag = ParasiteDrag(self.structure) if has_drag else None
        has_bodies = (aero is not None and aero.body_moments and bool(aircraft.aero_settings.bodies)
                      and self.aero.formulation == "physical")
        #: Munk moments of the file's slender bodies (:mod:`flexsim.model.bodies`), or None.
        self.bodies = SlenderBodies(self.structure) if has_bodies else None
        #: The wing's reference area, span and chords (:class:`flexsim.model.reference.ReferenceGeometry`), None
        #: without aerodynamics or without a wing.
        self.reference_geometry = None if self.aero is None else ReferenceGeometry.of_strips(self.aero.strips)
        n_inflow = 0 if self.aero is None else self.aero.n_inflow_states
        self.layout = StateLayout(rigid=rigid, nq=dofs.nq if elastic else 0, nxi=dofs.nxi if elastic else 0, n_inflow=n_inflow)
        self._active = np.concatenate(
            [np.arange(6) if rigid else np.zeros(0, int), np.arange(6, dofs.n_v) if elastic else np.zeros(0, int)]
        ).astype(int)
        self._all_active = self._active.size == dofs.n_v
        for name, n in (("frozen_q", dofs.nq), ("frozen_xi", dofs.nxi)):
            value = getattr(variant, name)
            if value is not None and len(value) != n:
                raise ValueError(f"frozen_q/frozen_xi: must have {dofs.nq} and {dofs.nxi} entries ({name} has {len(value)})")
        #: Frozen arrays of the compiled right-hand side (:class:`flexsim._kernels.KernelData`).
        self.kernel_data = self._build_kernel_data()
        self._packed_parts = (self.aero, self.structure.inertia, self.parasite_drag, self.bodies)
        self._n_strips = 0 if self.aero is None else self.aero.strips.n_strips
        self._check_air = (self.aero is not None and rigid and variant.air_density_kg_m3 is None
                           and terms.aero_density_kg_m3 is None)

    def replace(self, **changes) -> "AircraftModel":
        """A sibling of this model: the same aircraft object, these terms and variant with the named fields replaced.

        Every name is a field of :class:`Terms` or of :class:`VariantSettings` (``aero`` may be a model name: then
        ``AeroOptions(model=name)``, other aerodynamic options at their defaults; give an ``AeroOptions`` built with
        ``dataclasses.replace(model.terms.aero, ...)`` to keep them), or ``terms``/``variant`` for the whole object
        (``variant`` may be only the kind). Every field not named is this model's, so an analysis that needs another
        aerodynamic model or variant evaluates every other term as the model it was given (e.g.
        ``model.replace(aero=dataclasses.replace(model.terms.aero, model="quasi-steady"))``).

        Raises
        ------
        ValueError
            A name that is no such field, or a value the field refuses (named, with the allowed range).
        """
        terms, variant = _split(changes, self.terms, self.variant)
        return AircraftModel(self.aircraft, terms=terms, variant=variant)

    @property
    def structural_damping_ratio(self) -> float:
        """Modal damping ratio zeta in use [-]: ``terms.structural_damping``, else the aircraft's
        ``structural_damping_ratio`` (derived on each call, not stored)."""
        z = self.terms.structural_damping
        return float(self.aircraft.structural_damping_ratio if z is None else z)

    def _build_kernel_data(self) -> _k.KernelData:
        """The packed data of the compiled right-hand side: every registered term's data class fills its own fields
        from this model (``fields_of(model)``, :func:`flexsim._kernels.fields_of`), then :func:`flexsim._kernels.pack_fields`."""
        return _k.pack_fields(_k.fields_of(self))

    @property
    def formulation(self) -> str | None:
        """Resolution of the strip airloads in use ("physical" or "paper"), None without aerodynamics."""
        return None if self.aero is None else self.aero.formulation

    @property
    def active_dofs(self) -> np.ndarray:
        """Indices of the entries of V = [v, omega, s, eta] that are degrees of freedom of this variant."""
        return self._active

    # ------------------------------------------------------------------ state unpacking
    def unpack(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """Full-size (R, Theta, q, xi, V) from a state vector, filling fixed or frozen blocks.

        Returns
        -------
        position_m (3,), euler_rad (3,), q (nq,), xi (nxi,), velocity (n_v,)
        """
        return _k.unpack(*self.kernel_data, _arg(x))

    def pack(self, position_m=None, euler_rad=None, q=None, xi=None, velocity=None) -> np.ndarray:
        """A state vector from full-size blocks (missing blocks are zero; inactive ones are dropped)."""
        lay = self.layout
        x = lay.zeros()
        if lay.rigid:
            if position_m is not None:
                x[lay.position] = position_m
            if euler_rad is not None:
                x[lay.euler] = euler_rad
        if self.variant.kind is not Variant.QUASI_RIGID:
            if q is not None:
                x[lay.q] = q
            if xi is not None:
                x[lay.xi] = xi
        if velocity is not None:
            x[lay.velocity] = np.asarray(velocity, float)[self._active]
        return x

    # ------------------------------------------------------------------ equations of motion
    def generalized_forces(self, x: np.ndarray, u: np.ndarray, t: float = 0.0, wind: Wind | None = None) -> tuple[np.ndarray, np.ndarray]:
        """System matrix E = M(q) + M_a and right-hand side f of E V_dot = f (full size, eq. 33).

        Includes the aerodynamic added mass M_a and generalized forces when the model has aerodynamics.

        Parameters
        ----------
        x : ndarray, shape (n_states,)
        u : ndarray, shape (4,)
            Controls [T_e (N), delta_a, delta_e, delta_r (rad)].
        t : float
            Time [s] (for the wind field).
        wind : callable, optional
            Atmospheric disturbance (see :meth:`rhs`); None for still air.

        Returns
        -------
        m : ndarray, shape (n_v, n_v)
        f : ndarray, shape (n_v,)
        """
        x = self._state(x)
        m, f, _, _, _ = _k.assemble(*self.kernel_data, x, _arg(u), *self._strip_wind(t, x, wind))
        return m, f

    def strip_wind(self, t: float, x: np.ndarray, wind: Wind | None) -> np.ndarray | None:
        """Air velocity at every aerodynamic strip in its component axes [m/s], shape (n_s, 3), or None.

        From the wind field ``wind`` (see :meth:`rhs`) at time t [s] and the strips' inertial positions at
        state x; None in still air (``wind`` None) or without aerodynamics.
        """
        wind_c, has_wind = self._strip_wind(t, _arg(x), wind)
        return wind_c if has_wind else None

    def _state(self, x) -> np.ndarray:
        """x as a kernel argument, with the altitude checked against the ISA range when the air density needs it."""
        self._check_parts()
        x = _arg(x)
        if self._check_air:
            altitude = -x[2]
            if not Z_MIN <= altitude <= Z_MAX:
                raise _range_error(float(altitude), False)
        return x

    def _check_parts(self) -> None:
        """Refuse a model whose parts were swapped after construction (the kernels would ignore the new part)."""
        p = self._packed_parts
        if p[0] is not self.aero or p[1] is not self.structure.inertia or p[2] is not self.parasite_drag or p[3] is not self.bodies:
            raise RuntimeError("AircraftModel: a part (aero, structure.inertia, parasite_drag, bodies) was replaced after "
                               "construction; the compiled right-hand side uses the arrays packed when the model was built, "
                               "so the replacement would be ignored: build a new model with the option instead")

    def _strip_wind(self, t: float, x: np.ndarray, wind: Wind | None) -> tuple[np.ndarray, bool]:
        """(strip air velocity (n_s, 3) in component axes [m/s], whether there is wind) for the kernels.

        A wind field of :mod:`flexsim.sim.disturbances` carries its arrays (``wind_data``) and is evaluated
        inside the compiled kernel; any other callable ``wind(t, positions_ned_m)`` is called here.
        """
        if wind is None or self.aero is None:
            return np.zeros((self._n_strips, 3)), False
        data = getattr(wind, "wind_data", None)
        if isinstance(data, _k.WindData):
            return _k.strip_wind_at(*self.kernel_data, *data, x)
        if not callable(wind):
            raise ValueError(f"wind = {wind!r}: must be None or a callable wind(t, positions_ned_m) -> (k, 3) array")
        pos, eul, _, _, _ = _k.unpack(*self.kernel_data, x)
        c = _k.dcm_321(eul[0], eul[1], eul[2])
        positions = _k.strip_positions(*self.aero.kernel_data, pos, c)
        w_ned = np.asarray(wind(t, positions), dtype=float)
        if w_ned.shape != positions.shape or not np.all(np.isfinite(w_ned)):
            raise ValueError(f"wind(t, positions) returned shape {w_ned.shape} or non-finite values; expected finite {positions.shape}")
        return _k.strip_wind(*self.aero.kernel_data, _arg(w_ned), c), True

    @property
    def altitude_range_m(self) -> tuple[float, float]:
        """Altitudes -Z [m] at which :meth:`rhs` evaluates: the ISA range (Z_MIN, Z_MAX) when the air density comes
        from the ISA at the aircraft's altitude, else (-inf, inf) (compiled steppers check it per step)."""
        return (Z_MIN, Z_MAX) if self._check_air else (-math.inf, math.inf)

    def air_density(self, x: np.ndarray) -> float:
        """Air density of the aerodynamics at state x [kg/m^3]: the restrained model's tunnel density, else the
        fixed ``aero_density_kg_m3`` if given, else ISA at the altitude -Z (restrained: ``altitude_m``)."""
        if self.variant.air_density_kg_m3 is not None:
            return self.variant.air_density_kg_m3
        if self.terms.aero_density_kg_m3 is not None:
            return self.terms.aero_density_kg_m3
        x = _arg(x)
        if self.layout.rigid and not Z_MIN <= -x[2] <= Z_MAX:
            raise _range_error(float(-x[2]), False)
        return _k.air(*self.kernel_data, x)[1]

    def aerodynamic_force(self, x: np.ndarray, u: np.ndarray, t: float = 0.0, wind: Wind | None = None) -> np.ndarray:
        """Generalized aerodynamic force at a state, without the apparent-mass terms, shape (n_v,).

        Strip airloads (explicit part of :meth:`AeroCoupling.evaluate`) plus parasite drag and body moments; rows 0-2 are the
        resultant force in body axes [N], rows 3-5 the moment about o [N m]. Zero without aerodynamics.
        ``wind``: the disturbance (see :meth:`rhs`), None for still air.
        """
        x = self._state(x)
        return _k.aerodynamic_force(*self.kernel_data, x, _arg(u), *self._strip_wind(t, x, wind))

    def rhs(self, t: float, x: np.ndarray, u: np.ndarray, wind: Wind | None = None) -> np.ndarray:
        """State derivative x_dot = rhs(t, x, u, wind) of the nonlinear model (eqs. 4, 33).

        The compiled kernel :func:`flexsim._kernels.rhs`: E(x) V_dot = f(x) solved for the accelerations
        (no acceleration lagged), the inflow rates with them, R_dot = C^T v, Theta_dot = E^-1 omega,
        [q, xi]_dot = [s, eta].

        Parameters
        ----------
        t : float
            Time [s] (enters only through the wind field).
        x : ndarray, shape (n_states,)
        u : ndarray, shape (4,)
            Controls [T_e (N), delta_a, delta_e, delta_r (rad)].
        wind : callable, optional
            Atmospheric disturbance ``wind(t, positions_ned_m) -> (k, 3)``: air velocity [m/s] in inertial
            north-east-down axes at the inertial positions (k, 3) of the aerodynamic strips at time t [s]
            (gusts, turbulence; :mod:`flexsim.sim.disturbances`, whose fields are evaluated inside the
            compiled kernel). None (default): still air. Passed per call
            (``solve_ivp(model.rhs, ..., args=(u, wind))``); the model stores none.

        Returns
        -------
        ndarray, shape (n_states,)
        """
        x = self._state(x)
        u = _arg(u)
        try:
            if wind is None:
                return _k.rhs(*self.kernel_data, *_k.NO_WIND, x, u)
            data = getattr(wind, "wind_data", None)
            if isinstance(data, _k.WindData) and self.aero is not None:
                return _k.rhs(*self.kernel_data, *data, x, u)
            return _k.rhs_strip_wind(*self.kernel_data, x, u, self._strip_wind(t, x, wind)[0])
        except ZeroDivisionError:
            raise np.linalg.LinAlgError("system matrix of the equations of motion is singular") from None

    def rhs_batch(self, t: float, x: np.ndarray, u: np.ndarray, wind=None) -> np.ndarray:
        """x_dot of N states of this model in one compiled call (batched environments; the kernel of :meth:`rhs`).

        Parameters
        ----------
        t : float
            Time [s] (the fields of :mod:`flexsim.sim.disturbances` do not depend on it).
        x : ndarray, shape (N, n_states)
        u : ndarray, shape (N, 4)
            Controls [T_e (N), delta_a, delta_e, delta_r (rad)] of each aircraft.
        wind : None, a wind field, a sequence of N wind fields or a BatchWind
            Still air; one field of :mod:`flexsim.sim.disturbances` for all aircraft; one per aircraft (None
            entries: still air); or those packed once by :meth:`pack_winds` (cheapest per call: packing copies
            the Dryden grids).

        Returns
        -------
        ndarray, shape (N, n_states)

        Raises
        ------
        ValueError
            Shapes, a wind that is not a field of :mod:`flexsim.sim.disturbances`, or an altitude outside the
            ISA range (the row is named).
        numpy.linalg.LinAlgError
            A singular system matrix in any row.
        """
        self._check_parts()
        xs = _arg(x)
        us = _arg(u)
        if xs.ndim != 2 or xs.shape[1] != self.layout.n_states or us.shape != (xs.shape[0], 4):
            raise ValueError(f"x, u: shapes {xs.shape}, {us.shape}; expected (N, {self.layout.n_states}) and (N, 4)")
        n = xs.shape[0]
        if self._check_air:
            ok = (-xs[:, 2] >= Z_MIN) & (-xs[:, 2] <= Z_MAX)
            if not np.all(ok):
                row = int(np.flatnonzero(~ok)[0])
                raise ValueError(f"row {row}: {_range_error(float(-xs[row, 2]), False)}")
        if not isinstance(wind, _k.BatchWind):
            winds = [wind] * n if (wind is None or callable(wind)) else list(wind)
            if len(winds) != n:
                raise ValueError(f"wind: {len(winds)} wind fields for {n} states")
            wind = self.pack_winds(winds)
        elif wind.rows.shape[0] != n:
            raise ValueError(f"wind: a BatchWind of {wind.rows.shape[0]} aircraft for {n} states")
        try:
            return _k.rhs_batch(*self.kernel_data, *wind, xs, us)
        except ZeroDivisionError:
            raise np.linalg.LinAlgError("system matrix of the equations of motion is singular") from None

    @staticmethod
    def pack_winds(winds) -> "_k.BatchWind":
        """Pack one wind field per aircraft (None: still air) for :meth:`rhs_batch`, once (e.g. at reset).

        The fields must be those of :mod:`flexsim.sim.disturbances` (their arrays are evaluated inside the
        kernel); a plain Python callable cannot be batched (ValueError).
        """
        data = []
        for i, w in enumerate(winds):
            d = None if w is None else getattr(w, "wind_data", None)
            if w is not None and not isinstance(d, _k.WindData):
                raise ValueError(f"winds[{i}] = {w!r}: only the fields of flexsim.sim.disturbances (or None) can be batched")
            data.append(d)
        return _k.pack_winds(data)

    # ------------------------------------------------------------------ invariants
    def _q_inertia(self, q: np.ndarray) -> np.ndarray:
        """q at which the inertia term is evaluated: q + dq (``terms.inertia_q_offset_m``) or q."""
        dq = self.terms.inertia_q_offset_m
        return q if dq is None else q + np.asarray(dq)

    def kinetic_energy(self, x: np.ndarray) -> float:
        """T = 1/2 V^T M(q) V [J] (eq. 8)."""
        _, _, q, _, vel = self.unpack(x)
        return 0.5 * float(vel @ self.structure.inertia.mass_matrix(self._q_inertia(q)) @ vel)

    def strain_energy(self, x: np.ndarray) -> float:
        """V = 1/2 (q^T K q + xi^T K~ xi) [J] (eq. 15)."""
        _, _, q, xi, _ = self.unpack(x)
        st = self.structure
        return 0.5 * float(q @ st.k_bending @ q + xi @ st.k_torsion @ xi)

    def momentum_inertial(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Inertial linear momentum P = C^T p_v [kg m/s] and angular momentum about O [kg m^2/s].

        H_O = C^T rho_omega + R x C^T p_v; both are conserved without external forces
        (consequence of eq. 33, see docs/design.md).
        """
        pos, eul, q, _, vel = self.unpack(x)
        p = self.structure.inertia.mass_matrix(self._q_inertia(q)) @ vel
        c = dcm_321(*eul)
        p_lin = c.T @ p[0:3]
        return p_lin, c.T @ p[3:6] + np.cross(pos, p_lin)
