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
from enum import Enum

import numpy as np

from flexsim import _kernels as _k
from flexsim._arrays import kernel_arg as _arg
from flexsim.aircraft.definition import Aircraft
from flexsim._immutable import Immutable
from flexsim.atmosphere import G0, Z_MAX, Z_MIN, _range_error, speed_of_sound
from flexsim.errors import expect_type
from flexsim.model.coupling import AeroCoupling, AeroOptions
from flexsim.model.bodies import SlenderBodies
from flexsim.model.drag import ParasiteDrag
from flexsim.model.layout import StateLayout
from flexsim.model.terms import Terms
from flexsim.kinematics import dcm_321
from flexsim.structure.model import StructuralModel, structural_model

__all__ = ["Variant", "AircraftModel", "STANDARD_GRAVITY", "CONTROL_NAMES", "Wind", "check_model", "check_aircraft"]

#: Standard gravitational acceleration [m/s^2] (paper eq. 32's g): the atmosphere module's one definition.
STANDARD_GRAVITY = G0
#: An atmospheric disturbance: ``wind(t [s], positions_ned_m (k, 3)) -> air velocity (k, 3)`` [m/s], NED.
Wind = Callable[[float, np.ndarray], np.ndarray]
#: The control vector u of the paper (text after eq. 33): [T_e (N), delta_a, delta_e, delta_r (rad)].
CONTROL_NAMES = ("thrust", "aileron", "elevator", "rudder")


_UNSET = object()  # a keyword argument not given (the terms then come from ``terms`` or Terms' defaults)


def _terms(terms: "Terms | None", **legacy) -> "Terms":
    """The model's :class:`Terms`: ``terms``, or the keyword arguments that map onto it (``aero`` may be a model name)."""
    given = {k: v for k, v in legacy.items() if v is not _UNSET}
    if terms is not None:
        if not isinstance(terms, Terms):
            raise ValueError(f"terms = {terms!r}: must be a flexsim.model.terms.Terms (or None)")
        if given:
            raise ValueError(f"terms and {', '.join(given)}: give the physical terms either as terms=Terms(...) or as "
                             "these keyword arguments, not both")
        return terms
    if isinstance(given.get("aero"), str):
        given["aero"] = AeroOptions(model=given["aero"])
    return Terms(**given)


class Variant(str, Enum):
    """Model variants built from one definition (docs/design.md, "Model variants").

    FREE: free-flying flexible aircraft (6 rigid-body + all elastic DOFs).
    RESTRAINED: rigid-body motion fixed, the aircraft clamped at its body origin o (ground vibration
    test; with a single-component aircraft, a clamped wing).
    QUASI_RIGID: elastic coordinates frozen at given values, rigid-body DOFs free.
    """

    FREE = "free"
    RESTRAINED = "restrained"
    QUASI_RIGID = "quasi-rigid"


def check_aircraft(aircraft, name: str = "aircraft") -> None:
    """TypeError naming ``name`` unless ``aircraft`` is an :class:`Aircraft` (a name or a path says how to load it)."""
    hint = ""
    if isinstance(aircraft, (str, os.PathLike)):
        hint = f"load it first: flexsim.load_aircraft({str(aircraft)!r})"
    elif isinstance(aircraft, AircraftModel):
        hint = "give the model's aircraft (model.aircraft)"
    expect_type(name, aircraft, Aircraft, "an Aircraft (flexsim.load_aircraft)", hint)


def check_model(model, name: str = "model") -> "AircraftModel":
    """``model`` when it is an :class:`AircraftModel`; else a TypeError naming ``name`` and saying how to build one
    (from an :class:`Aircraft`, a bundled name or a TOML path). Every public function taking a model calls it where
    the model enters."""
    hint = "build one with flexsim.AircraftModel(aircraft, aero=...)"
    if isinstance(model, Aircraft):
        hint = f"an Aircraft is the definition; build the model with flexsim.AircraftModel({name}, aero=...)"
    elif isinstance(model, (str, os.PathLike)):
        hint = f"build it with flexsim.AircraftModel(flexsim.load_aircraft({str(model)!r}), aero=...)"
    return expect_type(name, model, AircraftModel, "an AircraftModel", hint)


class AircraftModel(Immutable):
    """Equations of motion of the whole flexible aircraft (eq. 33) in first-order form.

    Immutable after construction (:class:`flexsim._arrays.Immutable`): attributes cannot be set or deleted and
    every array it holds — its own, the structure's and the aerodynamic coupling's — is read-only; disturbances
    are an argument of :meth:`rhs`. To change an input, build a new model.

    Parameters
    ----------
    aircraft : Aircraft
        The definition (use :meth:`Aircraft.subset` for a subset of components).
    variant : Variant or str, optional
        ``"free"`` (default), ``"restrained"`` or ``"quasi-rigid"``.
    gravity_m_s2 : float, optional
        Gravitational acceleration g [m/s^2] of eq. (32); 0 for vacuum-and-no-gravity studies.
    terms : Terms, optional
        The physical terms of the model (:class:`flexsim.model.terms.Terms`: aerodynamics, gravity, structural
        damping, the density of the aerodynamics, a frozen compressibility Mach number, the force resolution's
        flow-angle terms, the thrust line, the inertia's and the strips' offsets). Default: every term on. The
        keyword arguments ``aero``, ``gravity_m_s2``, ``structural_damping`` and ``aero_density_kg_m3`` are the
        same fields of :class:`Terms` given loose (either ``terms`` or those, not both).
    aero : AeroOptions, str or None, optional
        Aerodynamic model: an :class:`AeroOptions`, a model name (``"unsteady"`` default,
        ``"quasi-steady"``), or None for no aerodynamics (vacuum) (``Terms.aero``).
    restrained_euler_rad : array_like, shape (3,), optional
        Attitude [phi, theta, psi] of a restrained aircraft [rad] (sets the direction of gravity).
    restrained_velocity_m_s : array_like, shape (3,), optional
        Body-axes velocity [m/s] of a restrained aircraft: the air flows past the clamped structure at
        minus this velocity (a wind tunnel). Default zero (still air).
    altitude_m : float, optional
        Altitude of a restrained aircraft [m] (air density and speed of sound; ISA). A free aircraft
        uses its own altitude -Z.
    air_density_kg_m3 : float, optional
        Air density of a restrained aircraft [kg/m^3], in (0, 10], instead of the ISA density at
        ``altitude_m`` (a wind tunnel at a given density; the speed of sound stays ISA's at ``altitude_m``).
    frozen_q, frozen_xi : array_like, optional
        Values of the elastic coordinates of a quasi-rigid model [m], [rad] (default zero).
    structural_damping : float, optional
        Modal damping ratio zeta of every clamped elastic mode, 0 <= zeta < 1 (default None: the
        aircraft's ``structural_damping_ratio``, 0 unless its file sets it; the paper's structure is undamped).
    aero_density_kg_m3 : float, optional
        Air density the aerodynamics use [kg/m^3], instead of the ISA density at the current altitude
        (default None: the true density). A paper-replication setting for the *linearised* aerodynamics of
        a flutter search (:class:`flexsim.linear.flutter.FlutterAnalysis`, docs/flutter.md); Mach number
        and compressibility keep the true altitude.

    Attributes
    ----------
    aircraft : Aircraft
    structure : StructuralModel
    variant : Variant
    terms : Terms
    layout : StateLayout
    """

    def __init__(
        self,
        aircraft: Aircraft,
        *,
        variant: Variant | str = Variant.FREE,
        terms: Terms | None = None,
        gravity_m_s2: float = _UNSET,
        aero: AeroOptions | str | None = _UNSET,
        restrained_euler_rad: np.ndarray | None = None,
        restrained_velocity_m_s: np.ndarray | None = None,
        altitude_m: float = 0.0,
        air_density_kg_m3: float | None = None,
        frozen_q: np.ndarray | None = None,
        frozen_xi: np.ndarray | None = None,
        structural_damping: float | None = _UNSET,
        aero_density_kg_m3: float | None = _UNSET,
    ) -> None:
        check_aircraft(aircraft)
        try:
            self.variant = Variant(variant)
        except ValueError:
            raise ValueError(
                f"variant = {variant!r}: must be one of {', '.join(v.value for v in Variant)}"
            ) from None
        terms = _terms(terms, gravity_m_s2=gravity_m_s2, aero=aero, structural_damping=structural_damping,
                       aero_density_kg_m3=aero_density_kg_m3)
        aero = terms.aero
        self.aircraft = aircraft
        self.structure = structural_model(aircraft)  # one per aircraft content: immutable, shared
        structural_damping = terms.structural_damping
        if structural_damping is None:
            structural_damping = aircraft.structural_damping_ratio
        if not (np.isfinite(structural_damping) and 0.0 <= structural_damping < 1.0):
            raise ValueError(f"structural_damping = {structural_damping!r}: must be a damping ratio in [0, 1)")
        if terms.inertia_q_offset_m is not None and len(terms.inertia_q_offset_m) != self.structure.dofs.nq:
            raise ValueError(f"inertia_q_offset_m: {len(terms.inertia_q_offset_m)} entries; {aircraft.name} has "
                             f"nq = {self.structure.dofs.nq} bending coordinates")
        #: The physical terms of this model (:class:`flexsim.model.terms.Terms`; ``terms.record()`` for logs and rows).
        self.terms = terms
        self.structural_damping = float(structural_damping)
        self._c_el = self.structure.damping(self.structural_damping) if structural_damping else None
        self.gravity_m_s2 = terms.gravity_m_s2
        dofs = self.structure.dofs
        rigid = self.variant is not Variant.RESTRAINED
        elastic = self.variant is not Variant.QUASI_RIGID
        if aero is not None and aero.model == "theodorsen":
            raise ValueError(
                'aero model = "theodorsen": the Theodorsen function is a frequency-domain model for linear '
                'flutter analysis (flexsim.linear); the time-domain model takes "unsteady" or "quasi-steady"'
            )
        self.aero = None if aero is None else AeroCoupling(
            self.structure, aero, compressibility_mach=terms.compressibility_mach, force_resolution=terms.force_resolution,
            fin_drag_per_lift=terms.fin_drag_per_lift, velocity_offset_m_s=terms.aero_velocity_offset_m_s)
        self.aero_density_kg_m3 = terms.aero_density_kg_m3
        # parasite drag belongs to the physical force resolution; the paper's (eq. 28) has the strips' drag only
        has_drag = (aero is not None and aero.parasite_drag and bool(aircraft.aero_settings.drag)
                    and self.aero.formulation == "physical")
        #: Parasite drag of the file's drag items (:mod:`flexsim.model.drag`), or None.
        self.parasite_drag = ParasiteDrag(self.structure) if has_drag else None
        has_bodies = (aero is not None and aero.body_moments and bool(aircraft.aero_settings.bodies)
                      and self.aero.formulation == "physical")
        #: Munk moments of the file's slender bodies (:mod:`flexsim.model.bodies`), or None.
        self.bodies = SlenderBodies(self.structure) if has_bodies else None
        n_inflow = 0 if self.aero is None else self.aero.n_inflow_states
        self.layout = StateLayout(rigid=rigid, nq=dofs.nq if elastic else 0, nxi=dofs.nxi if elastic else 0, n_inflow=n_inflow)
        self._active = np.concatenate(
            [np.arange(6) if rigid else np.zeros(0, int), np.arange(6, dofs.n_v) if elastic else np.zeros(0, int)]
        ).astype(int)
        self._all_active = self._active.size == dofs.n_v
        self._euler_fixed = np.zeros(3) if restrained_euler_rad is None else np.asarray(restrained_euler_rad, float)
        if self._euler_fixed.shape != (3,):
            raise ValueError(f"restrained_euler_rad = {restrained_euler_rad!r}: must have 3 entries [rad]")
        self._v_fixed = np.zeros(3) if restrained_velocity_m_s is None else np.asarray(restrained_velocity_m_s, float)
        if self._v_fixed.shape != (3,) or not np.all(np.isfinite(self._v_fixed)):
            raise ValueError(f"restrained_velocity_m_s = {restrained_velocity_m_s!r}: must be 3 finite numbers [m/s]")
        self.altitude_m = float(altitude_m)
        speed_of_sound(self.altitude_m)  # validates the ISA range with a clear message
        if air_density_kg_m3 is not None:
            if self.variant is not Variant.RESTRAINED:
                raise ValueError(f"air_density_kg_m3 = {air_density_kg_m3!r}: only for the restrained variant (a wind tunnel); "
                                 "a free or quasi-rigid aircraft takes the ISA density at its own altitude")
            if not (isinstance(air_density_kg_m3, (int, float)) and np.isfinite(air_density_kg_m3) and 0.0 < air_density_kg_m3 <= 10.0):
                raise ValueError(f"air_density_kg_m3 = {air_density_kg_m3!r}: must be a density in (0, 10] kg/m^3")
            air_density_kg_m3 = float(air_density_kg_m3)
        self._rho_fixed = air_density_kg_m3
        self._q_frozen = np.zeros(dofs.nq) if frozen_q is None else np.asarray(frozen_q, float)
        self._xi_frozen = np.zeros(dofs.nxi) if frozen_xi is None else np.asarray(frozen_xi, float)
        if self._q_frozen.shape != (dofs.nq,) or self._xi_frozen.shape != (dofs.nxi,):
            raise ValueError(f"frozen_q/frozen_xi: must have {dofs.nq} and {dofs.nxi} entries")
        #: Frozen arrays of the compiled right-hand side (:class:`flexsim._kernels.KernelData`).
        self.kernel_data = self._build_kernel_data()
        self._packed_parts = (self.aero, self.structure.inertia, self.parasite_drag, self.bodies)
        self._n_strips = 0 if self.aero is None else self.aero.strips.n_strips
        self._check_air = self.aero is not None and rigid and self._rho_fixed is None and self.aero_density_kg_m3 is None

    def _build_kernel_data(self) -> _k.KernelData:
        st, d, lay = self.structure, self.structure.dofs, self.layout
        n_el = d.nq + d.nxi
        nan = float("nan")
        inertia = st.inertia
        floats = dict(
            g=[self.gravity_m_s2], air=[self.altitude_m, nan if self._rho_fixed is None else self._rho_fixed,
                                        nan if self.aero_density_kg_m3 is None else self.aero_density_kg_m3],
            euler_fixed=self._euler_fixed, v_fixed=self._v_fixed, q_frozen=self._q_frozen, xi_frozen=self._xi_frozen,
            m0=inertia.m0, h=inertia.h, m2=inertia.m2, k_bending=st.k_bending, k_torsion=st.k_torsion,
            c_el=np.zeros((n_el, n_el)) if self._c_el is None else self._c_el, thrust_t0=st.thrust.t0,
            thrust_t1=st.thrust.t1 if self.terms.thrust_follows_deflection else np.zeros_like(st.thrust.t1),
            inertia_dq=np.zeros(d.nq) if self.terms.inertia_q_offset_m is None else np.asarray(self.terms.inertia_q_offset_m),
            proj_n0=np.zeros((0, d.n_v)), proj_d0=np.zeros((0, d.n_v)), proj_p=np.zeros((0, d.n_v)), rel=np.zeros((0, n_el)),
            proj_n1=np.zeros((0, 3, d.nq)), proj_d1=np.zeros((0, 3, d.nq)), a_inv=np.zeros((1, 1)), a_inv_c=np.zeros(1),
            b_vec=np.zeros(1), downwash_gradient=[0.0], strip_mach=[nan], drag_g0=np.zeros((0, 6, d.n_v)), drag_g1=np.zeros((0, 3, 3, d.nq)),
            body_g0=np.zeros((0, 6, d.n_v)), body_g1=np.zeros((0, 3, 3, d.nq)))
        flags = dict(n_v=d.n_v, nq=d.nq, nxi=d.nxi, rigid=lay.rigid, use_frozen=self.variant is Variant.QUASI_RIGID,
                     all_active=self._all_active, n_states=lay.n_states, vel_start=lay.velocity.start,
                     inflow_start=lay.inflow.start, n_inflow=lay.n_inflow, has_aero=self.aero is not None,
                     has_drag=self.parasite_drag is not None, has_bodies=self.bodies is not None,
                     has_damping=self._c_el is not None, q_start=lay.q.start,
                     has_inertia_offset=self.terms.inertia_q_offset_m is not None,
                     xi_start=lay.xi.start, n_inflow_per_strip=1)
        ints = dict(active=self._active)
        if self.aero is not None:
            floats.update(self.aero.kernel_fields[0])
            flags.update(self.aero.kernel_fields[1]["ints"])
            ints.update({k: v for k, v in self.aero.kernel_fields[1].items() if k != "ints"})
        if self.parasite_drag is not None:
            floats.update(self.parasite_drag.kernel_fields)
        if self.bodies is not None:
            floats.update(self.bodies.kernel_fields)
        for term in _k.TERMS:  # terms that build their own data from the model (flexsim._kernels.layout.term_data)
            build = getattr(term, "fields_of", None)
            if build is not None:
                term_floats, term_flags = build(self)
                floats.update(term_floats)
                flags.update(term_flags)
        ints["ints"] = flags
        return _k.pack(floats, ints)

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
        if self.variant is not Variant.QUASI_RIGID:
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
        if self._rho_fixed is not None:
            return self._rho_fixed
        if self.aero_density_kg_m3 is not None:
            return self.aero_density_kg_m3
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
