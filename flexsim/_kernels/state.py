"""The model variant, its state vector and the air state: data and kernels below every term (compiled).

Tuzcu & Nguyen (2014) "Flutter of Maneuvering Aircraft", eqs. (2)-(4): the state x = [R, Theta, q, xi, V, lambda]
of a free, restrained or quasi-rigid model (:class:`flexsim.model.layout.StateLayout`); :func:`unpack` gives the
full-size blocks. The air state of a state x (:func:`air`, :func:`air_state`): the density of the aerodynamics, the
speed of sound and the flight Mach number, ISA 1976 at the altitude -Z (U.S. Standard Atmosphere 1976, eqs. 33a/b,
42, 50; :mod:`flexsim.atmosphere`) unless a tunnel or a fixed aerodynamic density is set. Every term module may
import this module (it imports no term), so an aerodynamic term reads the air state itself or takes it from
:func:`flexsim._kernels.equations.assemble`. Body axes, SI units, radians.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexsim._kernels.isa import _geopotential, _sound_speed, isa_scalar
from flexsim._kernels.layout import _f1, _flag, _i1, inline, kernel, packed, term_data


@term_data
@dataclasses.dataclass(frozen=True)
class ModelData:
    """The model variant and its state vector x (:class:`flexsim.model.aircraft_model.AircraftModel`,
    :class:`flexsim.model.layout.StateLayout`): sizes, where each block of x starts, fixed and frozen blocks, air."""

    air: np.ndarray = packed(1, "[altitude of a restrained model [m], tunnel density [kg/m^3] (nan: none), "
                                "density of the aerodynamics [kg/m^3] (nan: ISA)] (3,)")
    euler_fixed: np.ndarray = packed(1, "attitude of a restrained model (3,) [rad]")
    v_fixed: np.ndarray = packed(1, "body velocity of a restrained model (3,) [m/s]")
    q_frozen: np.ndarray = packed(1, "bending coordinates of a quasi-rigid model (nq,) [m]")
    xi_frozen: np.ndarray = packed(1, "torsion coordinates of a quasi-rigid model (nxi,) [rad]")
    active: np.ndarray = packed(1, "the entries of V that are degrees of freedom", "ints")
    n_v: int = packed(0, "entries of V = [v, omega, s, eta]", "flag")
    nq: int = packed(0, "bending coordinates", "flag")
    nxi: int = packed(0, "torsion coordinates", "flag")
    rigid: int = packed(0, "1: rigid-body motion free (free, quasi-rigid)", "flag")
    use_frozen: int = packed(0, "1: elastic coordinates frozen (quasi-rigid)", "flag")
    all_active: int = packed(0, "1: every entry of V is a degree of freedom", "flag")
    n_states: int = packed(0, "entries of x", "flag")
    vel_start: int = packed(0, "first entry of the velocities in x", "flag")
    inflow_start: int = packed(0, "first inflow state in x", "flag")
    n_inflow: int = packed(0, "inflow states", "flag")
    q_start: int = packed(0, "first bending coordinate in x", "flag")
    xi_start: int = packed(0, "first torsion coordinate in x", "flag")
    has_aero: int = packed(0, "1: the model has aerodynamics", "flag")

    @staticmethod
    def fields_of(model) -> dict:
        """The fields of a model (:class:`flexsim.model.aircraft_model.AircraftModel`): its variant, state layout,
        fixed and frozen blocks and the air of a restrained model."""
        lay, d, v = model.layout, model.structure.dofs, model.variant
        nan = float("nan")
        rho_tunnel, rho_aero = v.air_density_kg_m3, model.terms.aero_density_kg_m3
        vector = lambda value, n: np.zeros(n) if value is None else np.asarray(value, float)  # noqa: E731
        return dict(air=[v.altitude_m, nan if rho_tunnel is None else rho_tunnel, nan if rho_aero is None else rho_aero],
                    euler_fixed=vector(v.restrained_euler_rad, 3), v_fixed=vector(v.restrained_velocity_m_s, 3),
                    q_frozen=vector(v.frozen_q, d.nq), xi_frozen=vector(v.frozen_xi, d.nxi), active=model.active_dofs,
                    n_v=d.n_v, nq=d.nq, nxi=d.nxi, rigid=lay.rigid, use_frozen=v.kind.value == "quasi-rigid",
                    all_active=model.active_dofs.size == d.n_v, n_states=lay.n_states,
                    vel_start=lay.velocity.start, inflow_start=lay.inflow.start, n_inflow=lay.n_inflow,
                    q_start=lay.q.start, xi_start=lay.xi.start, has_aero=model.aero is not None)


AIR = ModelData.index["air"]
EULER_FIXED = ModelData.index["euler_fixed"]
V_FIXED = ModelData.index["v_fixed"]
Q_FROZEN = ModelData.index["q_frozen"]
XI_FROZEN = ModelData.index["xi_frozen"]
ACTIVE = ModelData.index["active"]
N_V = ModelData.index["n_v"]
NQ = ModelData.index["nq"]
NXI = ModelData.index["nxi"]
RIGID = ModelData.index["rigid"]
USE_FROZEN = ModelData.index["use_frozen"]
ALL_ACTIVE = ModelData.index["all_active"]
N_STATES = ModelData.index["n_states"]
VEL_START = ModelData.index["vel_start"]
INFLOW_START = ModelData.index["inflow_start"]
N_INFLOW = ModelData.index["n_inflow"]
Q_START = ModelData.index["q_start"]
XI_START = ModelData.index["xi_start"]
HAS_AERO = ModelData.index["has_aero"]


@kernel
def unpack(F, I, x):
    """Full-size (R, Theta, q, xi, V) from x, filling fixed or frozen blocks (AircraftModel.unpack)."""
    n_v, nq, nxi = _flag(I, N_V), _flag(I, NQ), _flag(I, NXI)
    vs = _flag(I, VEL_START)
    rigid = _flag(I, RIGID)
    if rigid:
        pos = x[0:3].copy()
        eul = x[3:6].copy()
    else:
        pos = np.zeros(3)
        eul = _f1(F, I, EULER_FIXED).copy()
    if _flag(I, USE_FROZEN):
        q = _f1(F, I, Q_FROZEN).copy()
        xi = _f1(F, I, XI_FROZEN).copy()
    else:
        q = x[_flag(I, Q_START):_flag(I, Q_START) + nq].copy()
        xi = x[_flag(I, XI_START):_flag(I, XI_START) + nxi].copy()
    if _flag(I, ALL_ACTIVE):
        vel = x[vs:vs + n_v].copy()
    else:
        vel = np.zeros(n_v)
        active = _i1(I, ACTIVE)
        for i in range(active.shape[0]):
            vel[active[i]] = x[vs + i]
        if not rigid:
            vel[0:3] = _f1(F, I, V_FIXED)
    return pos, eul, q, xi, vel


@kernel
def air(F, I, x):
    """(altitude [m] geometric, density of the aerodynamics [kg/m^3], speed of sound [m/s]) at state x:
    the tunnel density, else the fixed aerodynamic density, else ISA at -Z (restrained: altitude_m)."""
    fl = _f1(F, I, AIR)
    altitude = -x[2] if _flag(I, RIGID) else fl[0]
    hgp = _geopotential(altitude)
    if not math.isnan(fl[1]):
        rho = fl[1]
    elif not math.isnan(fl[2]):
        rho = fl[2]
    else:
        rho = isa_scalar(hgp)[0]
    return altitude, rho, _sound_speed(hgp)


@inline
def air_state(F, I, x, vel):
    """The air state of the aerodynamic terms at state x: (density [kg/m^3], flight Mach number [-], speed of
    sound [m/s]) (:func:`air`; Mach = |v| / a with v = vel[0:3] the body velocity [m/s])."""
    _, rho, a_sound = air(F, I, x)
    mach = math.sqrt(vel[0] * vel[0] + vel[1] * vel[1] + vel[2] * vel[2]) / a_sound
    return rho, mach, a_sound
