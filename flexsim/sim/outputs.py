"""The output layer: named outputs of a state — state and control names, flight signals, deformed structure.

One :class:`OutputMaps` per model computes every output quantity for the simulation result
(:mod:`flexsim.sim.result`), the simulator's flight log (:mod:`flexsim.sim.recording`) and the environments'
observations and flight logs (:mod:`flexsim.sim.periods`, :mod:`flexsim.io.env_log`), and names each from the
one vocabulary :data:`flexsim.io.vocabulary.QUANTITIES` (SI units and radians, the unit in the name; table in
``docs/logs.md``). The structural outputs come from :mod:`flexsim.model.sensors`, the aerodynamic force from
:meth:`AircraftModel.aerodynamic_force` — the same code the trim uses. The disturbance (``wind``) is passed per call,
as to ``model.rhs``; nothing here stores it. Frames and signs follow ``docs/conventions.md``: NED inertial axes,
FRD body axes, 3-2-1 Euler angles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexsim import _kernels as _k
from flexsim._arrays import frozen_array, kernel_arg
from flexsim.atmosphere import speed_of_sound
from flexsim.io.vocabulary import CONTROL_NAMES, check_names
from flexsim.kinematics import dcm_321
from flexsim.model.aircraft_model import AircraftModel, Wind
from flexsim.model.naming import state_names
from flexsim.model.sensors import ComponentSensor, structural_sensors
from flexsim.sim import _output_kernels as _ok
from flexsim.sim.measurements import air_angles_rows, heading_rate_rows

__all__ = ["OutputMaps", "AirData", "air_angles", "heading_rate", "CONTROL_NAMES", "WINGS", "STRUCTURE_NODES"]

#: The wing halves (root bending moments of both and the wing lift are reported when present).
WINGS = ("right_wing", "left_wing")
#: Beam nodes per component in the logged and rendered deformed structure (root to tip, equally spaced).
STRUCTURE_NODES = 11

_AIR = ("airspeed_m_s", "mach", "alpha_rad", "beta_rad")
_KINEMATIC = ("altitude_m", "heading_rate_rad_s")
_LOADS = ("load_factor", "wing_lift_N")


@dataclass(frozen=True)
class AirData:
    """Air data of the body origin o relative to the air (wind included), arrays of shape (N,).

    Attributes
    ----------
    airspeed_m_s, alpha_rad, beta_rad, mach : ndarray
        True airspeed [m/s], angle of attack atan2(w_a, u_a) [rad], sideslip asin(v_a / |v_a|) [rad] (0 at zero
        airspeed), Mach number over the ISA speed of sound at the altitude [-].
    """

    airspeed_m_s: np.ndarray
    alpha_rad: np.ndarray
    beta_rad: np.ndarray
    mach: np.ndarray


def air_angles(v_air_body: np.ndarray) -> tuple:
    """Airspeed [m/s], angle of attack atan2(w_a, u_a) [rad] and sideslip asin(v_a / |v_a|) [rad] (0 at zero
    airspeed) from the velocity relative to the air in body axes (u_a, v_a, w_a) [m/s]
    (:func:`flexsim.sim.measurements.air_data`, the one implementation the environments' measurements use too).

    ``v_air_body`` of shape (3,) gives three floats; of shape (N, 3) three arrays (N,) (batched environments)."""
    v = np.asarray(v_air_body, dtype=float)
    out = np.empty((max(v.size // 3, 0), 3))
    air_angles_rows(np.ascontiguousarray(v.reshape(-1, 3)), out)
    if v.ndim == 1:
        return float(out[0, 0]), float(out[0, 1]), float(out[0, 2])
    return out[:, 0], out[:, 1], out[:, 2]


def heading_rate(euler_rad: np.ndarray, velocity: np.ndarray):
    """psi_dot = (Q sin(phi) + R cos(phi)) / cos(theta) [rad/s] (the turn rate of a level turn; NaN at
    cos(theta) = 0) from the Euler angles [rad] and the velocity vector V = [v, omega, ...] (omega = V[3:6])
    (:func:`flexsim.sim.measurements.heading_rate_rows`).

    Shapes (3,) and (n_v,) give a float; (N, 3) and (N, n_v) an array (N,) (batched environments)."""
    eul, vel = np.asarray(euler_rad, dtype=float), np.asarray(velocity, dtype=float)
    rows = np.ascontiguousarray(eul.reshape(-1, 3))
    rates = np.ascontiguousarray(vel.reshape(rows.shape[0], -1)[:, 3:6])
    out = np.empty(rows.shape[0])
    heading_rate_rows(rows, rates, out)
    return float(out[0]) if eul.ndim == 1 else out


class OutputMaps:
    """Names and output maps of one model (pure functions of (t, x, u, wind) after construction).

    Parameters
    ----------
    model : AircraftModel
    n_nodes : int, optional
        Beam nodes per component for :meth:`structure` (default :data:`STRUCTURE_NODES`).

    Attributes
    ----------
    state_names : tuple of str
        One vocabulary name per state entry: ``x_north_m``, ``phi_rad``, ``q_<component>_<k>_m``,
        ``xi_<component>_<k>_rad``, ``v_x_m_s``, ``omega_x_rad_s``, ``s_<component>_<k>_m_s``,
        ``eta_<component>_<k>_rad_s``, ``lambda_<component>_<strip>_<n>_m_s``.
    control_names : tuple of str
        :data:`flexsim.io.vocabulary.CONTROL_NAMES`.
    signal_names : tuple of str
        The flight signals of :meth:`signals`, in its order.
    sensors : dict of str to ComponentSensor
        Structural outputs of every flexible component (:func:`flexsim.model.sensors.structural_sensors`).
    wings : tuple of str
        Flexible wing halves present (structural-limit events, root bending moments).
    n_nodes : int
    """

    def __init__(self, model: AircraftModel, n_nodes: int = STRUCTURE_NODES) -> None:
        self.model = model
        self.n_nodes = int(n_nodes)
        self.control_names = CONTROL_NAMES
        self.state_names = state_names(model)
        self.sensors: dict[str, ComponentSensor] = structural_sensors(model)
        self.wings = tuple(w for w in WINGS if w in self.sensors)
        lay = model.layout
        self._maps = {c.name: model.structure.point_maps(c.name, np.linspace(0.0, c.length_m, self.n_nodes))
                      for c in model.aircraft.components}
        self._wing_strips = np.zeros(0, int)
        if model.aero is not None:
            self._wing_strips = np.flatnonzero(np.isin(np.array(model.aero.strips.component), WINGS))
        names = list(_AIR + _KINEMATIC) + ["load_factor"] + (["wing_lift_N"] if self._wing_strips.size else [])
        for c, s in self.sensors.items():
            if s.w_tip.size:
                names += [f"tip_deflection_{c}_m", f"tip_deflection_rate_{c}_m_s"]
            if s.psi_tip.size:
                names += [f"tip_twist_{c}_rad", f"tip_twist_rate_{c}_rad_s"]
        names += [f"root_bending_moment_{c}_N_m" for c, s in self.sensors.items() if s.w_tip.size]
        self.signal_names = check_names("signal", names)
        self._index = {name: j for j, name in enumerate(self.signal_names)}
        self._rigid_z = lay.position.start + 2 if lay.rigid else None

    # ------------------------------------------------------------------ kinematics and air data
    def position_euler(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Inertial NED position of the body origin [m] and Euler angles [rad] of one state, shapes (3,), (3,).

        A restrained model sits at altitude ``model.variant.altitude_m`` with its fixed attitude.
        """
        pos, eul, _, _, _ = self.model.unpack(x)
        if not self.model.layout.rigid:
            pos = np.array([0.0, 0.0, -self.model.variant.altitude_m])
        return np.array(pos, float), np.array(eul, float)

    def altitude_m(self, x: np.ndarray) -> np.ndarray:
        """Altitude -Z of the body origin [m] of state(s) x, (n,) -> scalar array or (N, n) -> (N,)."""
        x = np.asarray(x)
        if self._rigid_z is None:
            return np.full(x.shape[:-1], self.model.variant.altitude_m)
        return -x[..., self._rigid_z]

    def air_velocity_body(self, t: float, x: np.ndarray, wind: Wind | None = None) -> np.ndarray:
        """Velocity of the body origin relative to the air, body axes [m/s], shape (3,): v - C w(R)."""
        pos, eul, _, _, vel = self.model.unpack(x)
        v = np.array(vel[0:3], float)
        if wind is not None:
            w_ned = np.asarray(wind(t, np.asarray(pos, float)[None, :]), float)[0]
            v = v - dcm_321(*eul) @ w_ned
        return v

    def air_data(self, t: np.ndarray, x: np.ndarray, wind: Wind | None = None) -> AirData:
        """:class:`AirData` of samples at times t (N,) [s] with states x (N, n) in the disturbance ``wind``: the
        :meth:`air_velocity_body` of each sample, with the wind of a field of :mod:`flexsim.sim.disturbances`
        (evaluated point by point, independent of t) asked for all samples' positions in one call."""
        t, x = np.atleast_1d(np.asarray(t, float)), np.atleast_2d(np.asarray(x, float))
        if not len(t):
            return AirData(*(np.zeros(0) for _ in range(4)))
        pos, eul, _, _, vel = self._blocks(x)
        v = np.array(vel[:, 0:3], float)
        if wind is not None:
            if isinstance(getattr(wind, "wind_data", None), _k.WindData):
                w_ned = np.asarray(wind(float(t[0]), np.ascontiguousarray(pos, dtype=float)), float)
            else:
                w_ned = np.array([np.asarray(wind(float(tk), np.asarray(p, float)[None, :]), float)[0] for tk, p in zip(t, pos)])
            v = v - np.array([dcm_321(*e) @ w for e, w in zip(eul, w_ned)])
        speed, alpha, beta = air_angles(v)
        a = np.asarray(speed_of_sound(np.asarray(self.altitude_m(x), float)), float).reshape(-1)
        return AirData(speed, alpha, beta, speed / a)

    def _blocks(self, x: np.ndarray) -> tuple[np.ndarray, ...]:
        """(R, Theta, q, xi, V) of N states x (N, n), each (N, size): :meth:`AircraftModel.unpack` of every state (the
        blocks of x itself when x holds all of them, as unpack then copies them)."""
        model, lay = self.model, self.model.layout
        first = model.unpack(x[0])
        blocks = (lay.position, lay.euler, lay.q, lay.xi, slice(lay.v.start, lay.v.start + first[4].size))  # V = [v, omega, s, eta]
        if lay.rigid and all(np.array_equal(x[0, sl], b) for sl, b in zip(blocks, first)):
            return tuple(x[:, sl] for sl in blocks)
        rows = [first] + [model.unpack(xk) for xk in x[1:]]
        return tuple(np.array([r[j] for r in rows], float).reshape(len(x), -1) for j in range(5))

    def heading_rate_rad_s(self, x: np.ndarray) -> np.ndarray:
        """:func:`heading_rate` of state(s) x, (N, n) -> (N,) [rad/s]."""
        x = np.atleast_2d(np.asarray(x, float))
        if not len(x):
            return np.zeros(0)
        _, euler, _, _, velocity = self._blocks(x)
        return heading_rate(euler, velocity)

    # ------------------------------------------------------------------ structure
    def _sensor(self, component: str) -> ComponentSensor:
        if component not in self.sensors:
            raise KeyError(f"component = {component!r}: no flexible component of that name; available: {list(self.sensors)}")
        return self.sensors[component]

    def tip_deflection_m(self, component: str, x: np.ndarray) -> np.ndarray:
        """Tip bending deflection w(L) of ``component`` [m], positive along z_i (down on a wing); x (n,) or (N, n)."""
        return self._sensor(component).tip_deflection_m(x)

    def tip_twist_rad(self, component: str, x: np.ndarray) -> np.ndarray:
        """Tip torsion psi(L) of ``component`` [rad] (nose up on the right wing); x (n,) or (N, n)."""
        return self._sensor(component).tip_twist_rad(x)

    def root_bending_moment_n_m(self, component: str, x: np.ndarray) -> np.ndarray:
        """Mode-displacement root bending moment EI(0) w''(0) of ``component`` [N m]; x (n,) or (N, n)."""
        return self._sensor(component).root_bending_moment_n_m(x)

    def structure(self, x: np.ndarray) -> dict[str, np.ndarray]:
        """Deformed beam nodes of every component, body axes (FRD) [m]: name -> (n_nodes, 3)."""
        _, _, q, xi, _ = self.model.unpack(x)
        return {name: maps.positions(q, xi) for name, maps in self._maps.items()}

    def structure_series(self, x: np.ndarray) -> dict[str, np.ndarray]:
        """:meth:`structure` of N states x (N, n) at once: name -> (N, n_nodes, 3) [m], body axes (FRD). The products
        of :meth:`flexsim.structure.kinematic_map.PointMaps.positions`, with the same BLAS calls per state (the
        displacements of all components as one stack of matrix-vector products, then per component the rotation of
        all states as one product), so equal to :meth:`structure` bit for bit."""
        x = np.atleast_2d(np.asarray(x, float))
        names = list(self._maps)
        if not len(x):
            return {name: np.zeros((0, self._maps[name].g0.shape[0], 3)) for name in names}
        _, _, q, xi, _ = self._blocks(x)
        elastic = np.ascontiguousarray(np.concatenate([q, xi], axis=1))
        n_el = elastic.shape[1]
        stack = np.concatenate([self._maps[n].g0[:, 0:3, 6:6 + n_el] for n in names])  # (all nodes, 3, n_el)
        disp = np.array([stack @ e for e in elastic]).reshape(len(x), -1, 3)
        out, at = {}, 0
        for name in names:
            maps = self._maps[name]
            k = maps.g0.shape[0]
            rows = np.ascontiguousarray(disp[:, at:at + k]).reshape(-1, 3)
            out[name] = maps.r0 + (rows @ maps.dcm).reshape(len(x), k, 3)
            at += k
        return out

    # ------------------------------------------------------------------ loads
    def load_factor_and_lift(self, t: float, x: np.ndarray, u: np.ndarray, wind: Wind | None = None) -> tuple[float, float]:
        """Load factor and total wing lift at one state.

        Load factor: aerodynamic plus thrust force along -z_body over the weight [-], exactly as
        :attr:`flexsim.trimming.TrimPoint.load_factor` (:meth:`AircraftModel.aerodynamic_force`: the explicit strip
        airloads and parasite drag, without the added-mass reaction M_a V_dot, which would need the accelerations;
        the GTM strips' added mass is 0.3 % of the aircraft's mass at 9144 m). NaN without gravity. Wing lift: sum
        of the circulatory strip lifts of both wings [N].
        """
        model = self.model
        _, _, q, xi, vel = model.unpack(x)
        st = model.structure
        force = st.thrust.force(float(u[0]), q)[0:3] + model.aerodynamic_force(x, u, t, wind)[0:3]
        lift = 0.0
        if self._wing_strips.size:
            altitude = float(self.altitude_m(x))
            mach = float(np.linalg.norm(vel[0:3])) / speed_of_sound(altitude)
            loads = model.aero.strip_loads(q, xi, vel, x[model.layout.inflow], u, model.air_density(x), mach,
                                           model.strip_wind(t, x, wind))
            w = self._wing_strips
            lift = float(loads.lift_n_m[w] @ model.aero.strips.width_m[w])
        weight = st.mass_properties.mass_kg * model.terms.gravity_m_s2
        return (float(-force[2] / weight) if weight > 0 else math.nan), lift

    def _loads_series(self, t: np.ndarray, x: np.ndarray, u: np.ndarray, wind: Wind | None) -> np.ndarray:
        """:meth:`load_factor_and_lift` of N samples, (N, 2): the aerodynamic force and wing lift of all samples in one
        compiled call (:func:`flexsim.sim._output_kernels.loads_rows`, the same kernels with the same arguments) for a
        model with aerodynamics in still air or a field of :mod:`flexsim.sim.disturbances` within its altitude range;
        otherwise sample by sample."""
        model = self.model
        data = None if wind is None else getattr(wind, "wind_data", None)
        lo, hi = model.altitude_range_m
        altitude = -x[:, 2] if model.layout.rigid else np.zeros(len(t))
        if (model.aero is None or (wind is not None and not isinstance(data, _k.WindData)) or not len(t)
                or not np.all((lo <= altitude) & (altitude <= hi))):
            return np.array([self.load_factor_and_lift(float(tk), xk, uk, wind) for tk, xk, uk in zip(t, x, u)],
                            float).reshape(-1, 2)
        st = model.structure
        n = len(t)
        xs, us = kernel_arg(x), kernel_arg(u)
        force, lift = np.empty((n, 3)), np.zeros(n)
        wing = self._wing_strips.astype(np.int64)
        inflow = np.array([model.layout.inflow.start, model.layout.inflow.stop], np.int64)
        one = model.pack_winds([wind])
        winds = one._replace(rows=frozen_array(np.repeat(one.rows, n, axis=0), np.int64))  # every sample in the one wind
        sound = np.asarray(speed_of_sound(np.asarray(self.altitude_m(xs), float)), float).reshape(n)
        data = _ok.LoadsData(st.thrust.t0, st.thrust.t1, wing, kernel_arg(model.aero.strips.width_m),
                             bool(model.aero.downwash_gradient), inflow)
        _ok.loads_rows(model.kernel_data, winds, _ok.LoadSamples(xs, us, kernel_arg(sound)), data, _ok.LoadsOut(force, lift))
        weight = st.mass_properties.mass_kg * model.terms.gravity_m_s2
        return np.column_stack([-force[:, 2] / weight if weight > 0 else np.full(n, math.nan), lift])

    # ------------------------------------------------------------------ signals
    def series(self, names, t: np.ndarray, x: np.ndarray, u: np.ndarray, wind: Wind | None = None) -> dict[str, np.ndarray]:
        """Time histories of the named signals (each of :attr:`signal_names`), name -> shape (N,).

        Parameters
        ----------
        names : sequence of str
        t : ndarray, shape (N,)
            Sample times [s].
        x : ndarray, shape (N, n_states)
        u : ndarray, shape (N, 4)
            Controls [T_e (N), delta_a, delta_e, delta_r (rad)].
        wind : callable, optional
            The disturbance (:meth:`AircraftModel.rhs`); None: still air.

        Raises
        ------
        KeyError
            A name that is not one of :attr:`signal_names`.
        """
        names = [names] if isinstance(names, str) else list(names)
        unknown = [n for n in names if n not in self._index]
        if unknown:
            raise KeyError(f"no signal named {unknown[0]!r}; available: {list(self.signal_names)}")
        t, x, u = np.atleast_1d(np.asarray(t, float)), np.atleast_2d(np.asarray(x, float)), np.atleast_2d(np.asarray(u, float))
        out: dict[str, np.ndarray] = {}
        if any(n in _AIR for n in names):
            air = self.air_data(t, x, wind)
            out.update(airspeed_m_s=air.airspeed_m_s, mach=air.mach, alpha_rad=air.alpha_rad, beta_rad=air.beta_rad)
        if "altitude_m" in names:
            out["altitude_m"] = np.asarray(self.altitude_m(x), float)
        if "heading_rate_rad_s" in names:
            out["heading_rate_rad_s"] = self.heading_rate_rad_s(x)
        if any(n in _LOADS for n in names):
            loads = self._loads_series(t, x, u, wind)
            out.update(load_factor=loads[:, 0], wing_lift_N=loads[:, 1])
        for c, s in self.sensors.items():
            for name, f in ((f"tip_deflection_{c}_m", s.tip_deflection_m), (f"tip_deflection_rate_{c}_m_s", s.tip_deflection_rate_m_s),
                            (f"tip_twist_{c}_rad", s.tip_twist_rad), (f"tip_twist_rate_{c}_rad_s", s.tip_twist_rate_rad_s),
                            (f"root_bending_moment_{c}_N_m", s.root_bending_moment_n_m)):
                if name in names:
                    out[name] = np.asarray(f(x), float)
        return {n: out[n] for n in names}

    def signals(self, t: float, x: np.ndarray, u: np.ndarray, wind: Wind | None = None) -> np.ndarray:
        """The flight signals of one sample, shape (len(signal_names),), in the order of :attr:`signal_names`
        (definitions: :data:`flexsim.io.vocabulary.QUANTITIES`)."""
        cols = self.series(self.signal_names, np.array([t], float), np.asarray(x, float)[None, :], np.asarray(u, float)[None, :], wind)
        return np.array([cols[n][0] for n in self.signal_names], dtype=float)
