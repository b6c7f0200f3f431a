"""Named outputs of a simulated state: state and control names, flight signals, deformed structure.

One :class:`OutputMaps` per model serves the simulation result (:mod:`flexsim.sim.result`) and the flight
log (:mod:`flexsim.sim.recording`), so that both name and compute every quantity the same way. Frames
and signs follow ``docs/conventions.md``: NED inertial axes, FRD body axes, 3-2-1 Euler angles; tip
deflection positive down along z_i and tip twist positive nose up on the right wing, as in the paper's
Tables 2-3 and :class:`~flexsim.trim.TrimPoint` (nose down on the left wing, whose y_i points forward).
"""

from __future__ import annotations

import numpy as np

from flexsim.atmosphere import isa_density, speed_of_sound
from flexsim.model.aircraft_model import AircraftModel
from flexsim.kinematics import dcm_321
from flexsim.structure.shapes import bending_shapes, torsion_shapes

__all__ = ["OutputMaps", "CONTROL_LOG_NAMES", "WINGS", "STRUCTURE_NODES"]

#: Names of the control vector entries in logs and results (units in the names).
CONTROL_LOG_NAMES = ("thrust_N", "aileron_rad", "elevator_rad", "rudder_rad")
#: Components whose tip deflection, twist and root bending moment are reported (when present and flexible).
WINGS = ("right_wing", "left_wing")
#: Beam nodes per component in the logged deformed structure (root to tip, equally spaced).
STRUCTURE_NODES = 11


class OutputMaps:
    """Names and output maps of one model (built once; pure functions of (t, x, u) afterwards).

    Parameters
    ----------
    model : AircraftModel
    wind : callable, optional
        The run's disturbance (:meth:`AircraftModel.rhs`), for air data and loads; None for still air.
    n_nodes : int, optional
        Beam nodes per component for :meth:`structure` (default 11).

    Attributes
    ----------
    state_names : tuple of str
        One name per state entry, with the unit: ``x_north_m``, ``phi_rad``, ``q_<component>_<k>_m``,
        ``xi_<component>_<k>_rad``, ``v_x_m_s``, ``omega_x_rad_s``, ``s_<component>_<k>_m_s``,
        ``eta_<component>_<k>_rad_s``, ``lambda_<component>_<strip>_<n>_m_s``.
    control_names : tuple of str
    signal_names : tuple of str
        The flight signals of :meth:`signals` (see there).
    wings : tuple of str
        Flexible wings present (for tip and root quantities).
    """

    def __init__(self, model: AircraftModel, n_nodes: int = STRUCTURE_NODES, wind=None) -> None:
        self.model = model
        self.wind = wind
        aircraft, dofs, lay = model.aircraft, model.structure.dofs, model.layout
        self.n_nodes = int(n_nodes)
        self.control_names = CONTROL_LOG_NAMES
        self.state_names = self._state_names()
        self.wings = tuple(w for w in WINGS if w in aircraft.component_names and lay.nq + lay.nxi > 0
                           and (aircraft.component(w).bending_modes or aircraft.component(w).torsion_modes))
        self._tip_w: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        self._tip_t: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        self._root_m: dict[str, tuple[np.ndarray, np.ndarray]] = {}
        for w in self.wings:
            c = aircraft.component(w)
            length = c.length_m
            qi = np.arange(lay.q.start, lay.q.stop)[dofs.bending[w]]
            xi = np.arange(lay.xi.start, lay.xi.stop)[dofs.torsion[w]]
            self._tip_w[w] = (qi, bending_shapes(length, length, c.bending_modes)[0] if c.bending_modes else np.zeros(0))
            self._tip_t[w] = (xi, torsion_shapes(length, length, c.torsion_modes)[0] if c.torsion_modes else np.zeros(0))
            curvature = bending_shapes(0.0, length, c.bending_modes, derivative=2)[0] if c.bending_modes else np.zeros(0)
            self._root_m[w] = (qi, float(c.sections.at("ei_nm2", np.array([0.0]))[0]) * curvature)
        self._maps = {c.name: model.structure.point_maps(c.name, np.linspace(0.0, c.length_m, self.n_nodes))
                      for c in aircraft.components}
        self._wing_strips = np.zeros(0, int)
        if model.aero is not None:
            comp = np.array(model.aero.strips.component)
            self._wing_strips = np.flatnonzero(np.isin(comp, WINGS))
        names = ["airspeed_m_s", "altitude_m", "alpha_deg", "beta_deg", "phi_deg", "theta_deg", "psi_deg",
                 "roll_rate_deg_s", "pitch_rate_deg_s", "yaw_rate_deg_s", "load_factor"]
        if self._wing_strips.size:
            names.append("wing_lift_N")
        names += [f"tip_deflection_{w}_m" for w in self.wings]
        names += [f"tip_twist_{w}_deg" for w in self.wings]
        names += [f"root_bending_{w}_Nm" for w in self.wings]
        self.signal_names = tuple(names)

    # ------------------------------------------------------------------ names
    def _state_names(self) -> tuple[str, ...]:
        model = self.model
        lay, dofs = model.layout, model.structure.dofs
        names: list[str] = []
        if lay.rigid:
            names += ["x_north_m", "y_east_m", "z_down_m", "phi_rad", "theta_rad", "psi_rad"]
        elastic = lay.nq + lay.nxi > 0

        def per_component(table: dict[str, slice], prefix: str, unit: str) -> list[str]:
            return [f"{prefix}_{c}_{k + 1}_{unit}" for c in dofs.component_names
                    for k in range(table[c].stop - table[c].start)]

        if elastic:
            names += per_component(dofs.bending, "q", "m") + per_component(dofs.torsion, "xi", "rad")
        if lay.rigid:
            names += ["v_x_m_s", "v_y_m_s", "v_z_m_s", "omega_x_rad_s", "omega_y_rad_s", "omega_z_rad_s"]
        if elastic:
            names += per_component(dofs.bending, "s", "m_s") + per_component(dofs.torsion, "eta", "rad_s")
        if lay.n_inflow:
            strips = model.aero.strips
            n_per = model.aero.options.n_inflow
            counter: dict[str, int] = {}
            for j, comp in enumerate(strips.component):
                counter[comp] = counter.get(comp, 0) + 1
                if strips.unsteady[j]:
                    names += [f"lambda_{comp}_{counter[comp]:02d}_{n + 1}_m_s" for n in range(n_per)]
        if len(names) != lay.n_states:
            raise RuntimeError(f"state names: built {len(names)} names for {lay.n_states} states")
        return tuple(names)

    # ------------------------------------------------------------------ kinematics
    def position_euler(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Inertial NED position of the body origin [m] and Euler angles [rad] of one state, shapes (3,), (3,).

        A restrained model sits at altitude ``model.altitude_m`` with its fixed attitude.
        """
        pos, eul, _, _, _ = self.model.unpack(x)
        if not self.model.layout.rigid:
            pos = np.array([0.0, 0.0, -self.model.altitude_m])
        return np.asarray(pos, float), np.asarray(eul, float)

    def air_velocity_body(self, t: float, x: np.ndarray) -> np.ndarray:
        """Velocity of the body origin relative to the air, body axes [m/s], shape (3,): v - C w(R)."""
        pos, eul, _, _, vel = self.model.unpack(x)
        v = np.asarray(vel[0:3], float)
        if self.wind is not None:
            w_ned = np.asarray(self.wind(t, np.asarray(pos, float)[None, :]), float)[0]
            v = v - dcm_321(*eul) @ w_ned
        return v

    def tip_deflection_m(self, wing: str, x: np.ndarray) -> np.ndarray:
        """Tip bending deflection w(L) of ``wing`` [m], positive down along z_i; x of shape (n,) or (N, n)."""
        idx, phi = self._tip(self._tip_w, wing)
        return np.asarray(x)[..., idx] @ phi

    def tip_twist_rad(self, wing: str, x: np.ndarray) -> np.ndarray:
        """Tip torsion psi(L) of ``wing`` [rad] (nose up on the right wing); x of shape (n,) or (N, n)."""
        idx, psi = self._tip(self._tip_t, wing)
        return np.asarray(x)[..., idx] @ psi

    def root_bending_moment_nm(self, wing: str, x: np.ndarray) -> np.ndarray:
        """Mode-displacement root bending moment EI(0) w''(0) of ``wing`` [N m] (w positive down: negative when
        the wing bends up under lift)."""
        idx, k = self._tip(self._root_m, wing)
        return np.asarray(x)[..., idx] @ k

    def _tip(self, table: dict, wing: str) -> tuple[np.ndarray, np.ndarray]:
        if wing not in table:
            raise KeyError(f"wing = {wing!r}: no flexible wing of that name; available: {list(self.wings)}")
        return table[wing]

    def structure(self, x: np.ndarray) -> dict[str, np.ndarray]:
        """Deformed beam nodes of every component, body axes (FRD) [m]: name -> (n_nodes, 3)."""
        _, _, q, xi, _ = self.model.unpack(x)
        return {name: maps.positions(q, xi) for name, maps in self._maps.items()}

    # ------------------------------------------------------------------ loads
    def _air(self, x: np.ndarray) -> tuple[float, float]:
        lay = self.model.layout
        altitude = float(-x[lay.position][2]) if lay.rigid else self.model.altitude_m
        return altitude, float(speed_of_sound(altitude))

    def load_factor_and_lift(self, t: float, x: np.ndarray, u: np.ndarray) -> tuple[float, float]:
        """Load factor and total wing lift at one state.

        Load factor: aerodynamic plus thrust force along -z_body over the weight [-], as
        :attr:`flexsim.trim.TrimPoint.load_factor` (1 in level trim up to the thrust's share); the
        aerodynamic force is the explicit generalized force of the strips (circulatory and the
        velocity-dependent apparent-mass terms), without the added-mass reaction M_a V_dot, which would
        need the accelerations (the GTM strips' added mass is 0.3 % of the aircraft's mass at 9144 m). NaN
        without gravity. Wing lift: sum of the circulatory strip lifts of both wings [N].
        """
        model = self.model
        pos, eul, q, xi, vel = model.unpack(x)
        st = model.structure
        force = st.thrust.force(float(u[0]), q)[0:3]
        lift = 0.0
        if model.aero is not None:
            altitude, a = self._air(x)
            rho = float(isa_density(altitude))
            mach = float(np.linalg.norm(vel[0:3])) / a
            wind_c = model.strip_wind(t, x, self.wind)  # the run's strip wind (component axes)
            _, q_a, _ = model.aero.evaluate(q, xi, vel, x[model.layout.inflow], u, rho, mach, wind_c)
            force = force + q_a[0:3]
            if self._wing_strips.size:
                loads = model.aero.strip_loads(q, xi, vel, x[model.layout.inflow], u, rho, mach, wind_c)
                w = self._wing_strips
                lift = float(loads.lift_n_m[w] @ model.aero.strips.width_m[w])
        weight = st.mass_properties.mass_kg * model.gravity_m_s2
        return (float(-force[2] / weight) if weight > 0 else float("nan")), lift

    # ------------------------------------------------------------------ signals
    def signals(self, t: float, x: np.ndarray, u: np.ndarray) -> np.ndarray:
        """The flight signals of one sample, shape (len(signal_names),), in the order of ``signal_names``.

        airspeed_m_s, alpha_deg, beta_deg: speed, angle of attack atan(w/u) and sideslip asin(v/|v|) of the
        body origin relative to the air (wind included) [m/s, deg]; altitude_m = -Z [m]; phi/theta/psi_deg
        Euler angles; roll/pitch/yaw_rate_deg_s body rates [deg/s]; load_factor and wing_lift_N (see
        :meth:`load_factor_and_lift`); tip_deflection_<wing>_m, tip_twist_<wing>_deg,
        root_bending_<wing>_Nm (see the methods of the same names).
        """
        pos, eul = self.position_euler(x)
        _, _, _, _, vel = self.model.unpack(x)
        va = self.air_velocity_body(t, x)
        speed = float(np.linalg.norm(va))
        alpha = float(np.degrees(np.arctan2(va[2], va[0])))
        beta = float(np.degrees(np.arcsin(np.clip(va[1] / speed, -1.0, 1.0)))) if speed > 0 else 0.0
        n_z, lift = self.load_factor_and_lift(t, x, u)
        out = [speed, float(-pos[2]), alpha, beta, *np.degrees(eul), *np.degrees(vel[3:6]), n_z]
        if self._wing_strips.size:
            out.append(lift)
        out += [float(self.tip_deflection_m(w, x)) for w in self.wings]
        out += [float(np.degrees(self.tip_twist_rad(w, x))) for w in self.wings]
        out += [float(self.root_bending_moment_nm(w, x)) for w in self.wings]
        return np.array(out, dtype=float)
