"""The one nonlinear model of the aircraft: ``rhs(t, x, u)``.

Source: Tuzcu & Nguyen (2014), eqs. (2)-(4), (12), (33). The paper integrates momenta p = M(q) V
(eq. 12); flexsim integrates the velocities with the equivalent velocity form, which keeps the implicit
aerodynamic coupling clean (E(x) x_dot = f(x), docs/design.md):

    M(q) V_dot = -M_dot V + g(V, p) + [0, 0, dT/dq, 0] - K [0, 0, q, xi] + Q_gravity + Q_thrust + Q_aero

with p = M V and the quasi-coordinate terms of eq. (33)

    g_v = -omega x p_v,      g_omega = -v x p_v - omega x rho_omega

and the kinematics R_dot = C^T v, Theta_dot = E^-1 omega, q_dot = s, xi_dot = eta (eq. 4).

Trim, linearisation, simulation and the gymnasium environments all call :meth:`AircraftModel.rhs`.
The model is immutable after construction: atmospheric disturbances (gusts, turbulence) are passed per
call, ``rhs(t, x, u, wind)``, as python-control passes its parameters to ``updfcn(t, x, u, params)``, so
one model serves still-air trims and any number of windy runs without being changed or reset.
"""

from __future__ import annotations

from collections.abc import Callable
from enum import Enum

import numpy as np
from scipy.linalg.lapack import dgesv as _dgesv

from flexsim.aircraft.definition import Aircraft
from flexsim._immutable import Immutable
from flexsim.atmosphere import G0, isa_density, speed_of_sound
from flexsim.model.coupling import AeroCoupling, AeroOptions
from flexsim.model.bodies import SlenderBodies
from flexsim.model.drag import ParasiteDrag
from flexsim.model.layout import StateLayout
from flexsim.kinematics import dcm_321, euler_rate_matrix_inverse
from flexsim.structure.model import StructuralModel

__all__ = ["Variant", "AircraftModel", "STANDARD_GRAVITY", "CONTROL_NAMES", "Wind"]

#: Standard gravitational acceleration [m/s^2] (paper eq. 32's g): the atmosphere module's one definition.
STANDARD_GRAVITY = G0
#: An atmospheric disturbance: ``wind(t [s], positions_ned_m (k, 3)) -> air velocity (k, 3)`` [m/s], NED.
Wind = Callable[[float, np.ndarray], np.ndarray]
#: The control vector u of the paper (text after eq. 33): [T_e (N), delta_a, delta_e, delta_r (rad)].
CONTROL_NAMES = ("thrust", "aileron", "elevator", "rudder")


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


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


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
    aero : AeroOptions, str or None, optional
        Aerodynamic model: an :class:`AeroOptions`, a model name (``"unsteady"`` default,
        ``"quasi-steady"``), or None for no aerodynamics (vacuum).
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
    layout : StateLayout
    """

    def __init__(
        self,
        aircraft: Aircraft,
        *,
        variant: Variant | str = Variant.FREE,
        gravity_m_s2: float = STANDARD_GRAVITY,
        aero: AeroOptions | str | None = "unsteady",
        restrained_euler_rad: np.ndarray | None = None,
        restrained_velocity_m_s: np.ndarray | None = None,
        altitude_m: float = 0.0,
        air_density_kg_m3: float | None = None,
        frozen_q: np.ndarray | None = None,
        frozen_xi: np.ndarray | None = None,
        structural_damping: float | None = None,
        aero_density_kg_m3: float | None = None,
    ) -> None:
        try:
            self.variant = Variant(variant)
        except ValueError:
            raise ValueError(
                f"variant = {variant!r}: must be one of {', '.join(v.value for v in Variant)}"
            ) from None
        if not np.isfinite(gravity_m_s2) or gravity_m_s2 < 0:
            raise ValueError(f"gravity_m_s2 = {gravity_m_s2!r}: must be a finite number >= 0")
        self.aircraft = aircraft
        self.structure = StructuralModel(aircraft)
        if structural_damping is None:
            structural_damping = aircraft.structural_damping_ratio
        if not (np.isfinite(structural_damping) and 0.0 <= structural_damping < 1.0):
            raise ValueError(f"structural_damping = {structural_damping!r}: must be a damping ratio in [0, 1)")
        self.structural_damping = float(structural_damping)
        self._c_el = self.structure.damping(self.structural_damping) if structural_damping else None
        self.gravity_m_s2 = float(gravity_m_s2)
        dofs = self.structure.dofs
        rigid = self.variant is not Variant.RESTRAINED
        elastic = self.variant is not Variant.QUASI_RIGID
        if isinstance(aero, str):
            aero = AeroOptions(model=aero)
        if aero is not None and aero.model == "theodorsen":
            raise ValueError(
                'aero model = "theodorsen": the Theodorsen function is a frequency-domain model for linear '
                'flutter analysis (flexsim.linear); the time-domain model takes "unsteady" or "quasi-steady"'
            )
        self.aero = None if aero is None else AeroCoupling(self.structure, aero)
        if aero_density_kg_m3 is not None and not (np.isfinite(aero_density_kg_m3) and 0.0 < aero_density_kg_m3 < 2.0):
            raise ValueError(f"aero_density_kg_m3 = {aero_density_kg_m3!r}: must be an air density in (0, 2) kg/m^3 (or None: the ISA density)")
        self.aero_density_kg_m3 = None if aero_density_kg_m3 is None else float(aero_density_kg_m3)
        # parasite drag belongs to the physical force resolution; the paper's (eq. 28) has the strips' drag only
        has_drag = (aero is not None and aero.parasite_drag and bool(aircraft.aero_settings.drag)
                    and self.aero.formulation == "physical")
        #: Parasite drag of the file's drag items (:mod:`flexsim.model.drag`), or None.
        self.parasite_drag = ParasiteDrag(self.structure) if has_drag else None
        has_bodies = (aero is not None and aero.body_moments and bool(aircraft.aero_settings.bodies)
                      and self.aero.formulation == "physical")
        #: Munk moments of the file's slender bodies (:mod:`flexsim.model.bodies`), or None.
        self.bodies = SlenderBodies(self.structure) if has_bodies else None
        if self.aero is not None:
            strips = self.aero.strips
            self._strip_dcm = np.stack([self.aircraft.component(c).dcm for c in strips.component]) if strips.n_strips else np.zeros((0, 3, 3))
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
        lay = self.layout
        if lay.rigid:
            pos, eul = x[lay.position], x[lay.euler]
        else:
            pos, eul = np.zeros(3), self._euler_fixed
        if lay.nq or lay.nxi or self.variant is not Variant.QUASI_RIGID:
            q, xi = x[lay.q], x[lay.xi]
        else:
            q, xi = self._q_frozen, self._xi_frozen
        if self._all_active:
            vel = x[lay.velocity]
        else:
            vel = np.zeros(self.structure.dofs.n_v)
            vel[self._active] = x[lay.velocity]
            if not lay.rigid:
                vel[0:3] = self._v_fixed
        return pos, eul, q, xi, vel

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
        m, f, _ = self._assemble(x, u, t, wind)
        return m, f

    def strip_wind(self, t: float, x: np.ndarray, wind: Wind | None) -> np.ndarray | None:
        """Air velocity at every aerodynamic strip in its component axes [m/s], shape (n_s, 3), or None.

        From the wind field ``wind`` (see :meth:`rhs`) at time t [s] and the strips' inertial positions at
        state x; None in still air (``wind`` None) or without aerodynamics.
        """
        pos, eul, _, _, _ = self.unpack(x)
        return self._strip_wind(t, pos, eul, wind)

    def _strip_wind(self, t: float, pos: np.ndarray, eul: np.ndarray, wind: Wind | None) -> np.ndarray | None:
        if wind is None or self.aero is None:
            return None
        if not callable(wind):
            raise ValueError(f"wind = {wind!r}: must be None or a callable wind(t, positions_ned_m) -> (k, 3) array")
        c = dcm_321(*eul)
        r_strips = self.aero.strips.position_body_m
        positions = pos[None, :] + r_strips @ c  # inertial: R + C^T r
        w_ned = np.asarray(wind(t, positions), dtype=float)
        if w_ned.shape != r_strips.shape or not np.all(np.isfinite(w_ned)):
            raise ValueError(f"wind(t, positions) returned shape {w_ned.shape} or non-finite values; expected finite {r_strips.shape}")
        return np.einsum("sab,sb->sa", self._strip_dcm, w_ned @ c.T)

    def _assemble(self, x: np.ndarray, u: np.ndarray, t: float, wind: Wind | None):
        st = self.structure
        nq = st.dofs.nq
        pos, eul, q, xi, vel = self.unpack(x)
        v, w, s = vel[0:3], vel[3:6], vel[6 : 6 + nq]
        m, dtdq, mdot_v = st.inertia.evaluate(vel, q, s)
        p = m @ vel
        f = -mdot_v
        f[0:3] -= _cross(w, p[0:3])
        f[3:6] -= _cross(v, p[0:3]) + _cross(w, p[3:6])
        f[6 : 6 + nq] += dtdq - st.k_bending @ q
        f[6 + nq :] -= st.k_torsion @ xi
        if self._c_el is not None:
            f[6:] -= self._c_el @ vel[6:]
        if self.gravity_m_s2:
            sf, cf = np.sin(eul[0]), np.cos(eul[0])
            st_, ct = np.sin(eul[1]), np.cos(eul[1])
            g_b = self.gravity_m_s2 * np.array([-st_, sf * ct, cf * ct])  # C [0, 0, g] (eq. 32)
            f += m[:, 0:3] @ g_b
        if u[0]:
            f += st.thrust.force(u[0], q)
        inflow_terms = None
        if self.aero is not None:
            altitude = -x[self.layout.position][2] if self.layout.rigid else self.altitude_m
            rho = self.air_density(x)
            mach = float(np.sqrt(v @ v)) / speed_of_sound(float(altitude))
            wind_c = self._strip_wind(t, pos, eul, wind)
            m_a, q_a, inflow_terms = self.aero.evaluate(q, xi, vel, x[self.layout.inflow], u, rho, mach, wind_c)
            m = m + m_a
            f = f + q_a
            if self.parasite_drag is not None:
                f = f + self.parasite_drag.generalized_force(q, vel, rho)
            if self.bodies is not None:
                f = f + self.bodies.generalized_force(q, vel, rho)
        return m, f, inflow_terms

    def air_density(self, x: np.ndarray) -> float:
        """Air density of the aerodynamics at state x [kg/m^3]: the restrained model's tunnel density, else the
        fixed ``aero_density_kg_m3`` if given, else ISA at the altitude -Z (restrained: ``altitude_m``)."""
        if self._rho_fixed is not None:
            return self._rho_fixed
        if self.aero_density_kg_m3 is not None:
            return self.aero_density_kg_m3
        altitude = -x[self.layout.position][2] if self.layout.rigid else self.altitude_m
        return isa_density(float(altitude))

    def aerodynamic_force(self, x: np.ndarray, u: np.ndarray, t: float = 0.0, wind: Wind | None = None) -> np.ndarray:
        """Generalized aerodynamic force at a state, without the apparent-mass terms, shape (n_v,).

        Strip airloads (explicit part of :meth:`AeroCoupling.evaluate`) plus parasite drag and body moments; rows 0-2 are the
        resultant force in body axes [N], rows 3-5 the moment about o [N m]. Zero without aerodynamics.
        ``wind``: the disturbance (see :meth:`rhs`), None for still air.
        """
        pos, eul, q, xi, vel = self.unpack(x)
        out = np.zeros(self.structure.dofs.n_v)
        if self.aero is None:
            return out
        altitude = -x[self.layout.position][2] if self.layout.rigid else self.altitude_m
        rho = self.air_density(x)
        mach = float(np.sqrt(vel[0:3] @ vel[0:3])) / speed_of_sound(float(altitude))
        _, q_a, _ = self.aero.evaluate(q, xi, vel, x[self.layout.inflow], u, rho, mach, self._strip_wind(t, pos, eul, wind))
        out += q_a
        if self.parasite_drag is not None:
            out += self.parasite_drag.generalized_force(q, vel, rho)
        if self.bodies is not None:
            out += self.bodies.generalized_force(q, vel, rho)
        return out

    def rhs(self, t: float, x: np.ndarray, u: np.ndarray, wind: Wind | None = None) -> np.ndarray:
        """State derivative x_dot = rhs(t, x, u, wind) of the nonlinear model (eqs. 4, 33).

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
            (gusts, turbulence; :mod:`flexsim.sim.disturbances`). None (default): still air. Passed per
            call (``solve_ivp(model.rhs, ..., args=(u, wind))``); the model stores none.

        Returns
        -------
        ndarray, shape (n_states,)
        """
        lay = self.layout
        m, f, inflow_terms = self._assemble(x, u, t, wind)
        if not self._all_active:
            a = self._active
            m, f = m[np.ix_(a, a)], f[a]
        dx = np.empty_like(x)
        _, _, vdot, info = _dgesv(m, f)
        if info != 0:
            raise np.linalg.LinAlgError(f"system matrix of the equations of motion is singular (LAPACK dgesv info = {info})")
        dx[lay.velocity] = vdot
        if lay.n_inflow:
            if not self._all_active:
                full = np.zeros(self.structure.dofs.n_v)
                full[self._active] = vdot
                vdot = full
            dx[lay.inflow] = self.aero.inflow_rate(inflow_terms, vdot)
        vel = x[lay.velocity]
        if lay.rigid:
            eul = x[lay.euler]
            c = dcm_321(*eul)
            dx[lay.position] = c.T @ vel[0:3]
            dx[lay.euler] = euler_rate_matrix_inverse(eul[0], eul[1]) @ vel[3:6]
        n_el = lay.nq + lay.nxi
        if n_el:
            off = 6 if lay.rigid else 0
            dx[lay.q.start : lay.xi.stop] = vel[off : off + n_el]
        return dx

    # ------------------------------------------------------------------ invariants
    def kinetic_energy(self, x: np.ndarray) -> float:
        """T = 1/2 V^T M(q) V [J] (eq. 8)."""
        _, _, q, _, vel = self.unpack(x)
        return 0.5 * float(vel @ self.structure.inertia.mass_matrix(q) @ vel)

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
        p = self.structure.inertia.mass_matrix(q) @ vel
        c = dcm_321(*eul)
        p_lin = c.T @ p[0:3]
        return p_lin, c.T @ p[3:6] + np.cross(pos, p_lin)
