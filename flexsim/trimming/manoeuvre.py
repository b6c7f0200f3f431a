"""Steady (time-invariant) manoeuvres: level flight, level turn, climb/descent, glide, climbing turn, pull-up.

Source: Tuzcu & Nguyen (2014) eqs. (34)-(39). With heading psi = Omega t along the flight path, the
inertial velocity is R_dot = V [cos(gamma) cos(psi), cos(gamma) sin(psi), -sin(gamma)] (north-east-down,
gamma > 0 climbing) and Theta_dot = [0, 0, Omega], Omega = V cos(gamma) / R, so that

    v = C(phi, theta, psi) R_dot,    omega = E(phi, theta) [0, 0, Omega]

(eq. 37 for gamma = 0; eq. 39 for Omega = 0, where v = V [cos(theta - gamma), 0, sin(theta - gamma)]).
The equations stay time-invariant because X, Y and psi do not appear in them; the climbing turn (R and
gamma together) is time-invariant too and is included.

The paper's turn keeps the heading on the track (psi = Omega t), which implies a sideslip
beta = asin(sin(phi) sin(theta)) at the body origin: a slipping, cross-controlled turn. A **coordinated turn**
(``coordinated=True``, beyond the paper) frees the heading: psi = chi + Delta_psi with the track chi = Omega t,
so that v = C(phi, theta, Delta_psi) R_dot(chi = 0), and adds the condition of zero sideslip at the
centre of gravity, v_cg,y = (v + omega x r_cg)_y = 0 (Stevens & Lewis, *Aircraft Control and Simulation*,
2nd ed., 2003, sec. 3.6, "coordinated turn": zero sideslip, bank and heading rate related by the turn
constraint; for gamma = 0 and beta = 0 it reduces to tan(phi) = G / cos(alpha), G = Omega V / g).

A **symmetric pull-up** at load factor n (beyond the paper) is trimmed at the bottom of the manoeuvre: wings
level, flight path horizontal at that instant (gamma = 0), and a constant pitch rate about the body y axis

    q = (n - 1) g0 / V   [rad/s],   omega = [0, q, 0] + E(phi, theta) [0, 0, Omega]  (Omega = 0 here)

from the normal-force equation of the flight path in the vertical plane, V gamma_dot = g0 (n - cos gamma), at
gamma = 0 with alpha constant so that q = theta_dot = gamma_dot (Stevens & Lewis, *Aircraft Control and
Simulation*, 2nd ed., 2003, sec. 3.6, "Steady-State Flight", the pull-up constraint; Etkin & Reid, *Dynamics of
Flight: Stability and Control*, 3rd ed., 1996, the steady symmetric pull-up of the manoeuvre point / elevator per g).
The load factor n is that of the body-frame origin (centripetal acceleration q V) with the standard gravity
g0 = 9.80665 m/s^2; at a centre of gravity r_cg from the origin the resultant force adds m q^2 r_cg. This is not
an exact equilibrium — the pitch angle grows at the rate q — but the quasi-steady instant at the bottom of the
pull-up, the standard treatment in the literature: the velocity equations are stationary there (V_dot = 0) and
trim solves them exactly as for the other manoeuvres. n = 1 is level flight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexsim.atmosphere import G0, mach_to_true_airspeed, speed_of_sound
from flexsim.kinematics import dcm_321, euler_rate_matrix

__all__ = ["SteadyManoeuvre", "LOAD_FACTOR_RANGE"]

#: Load factors accepted for the symmetric pull-up, [min, max] (1: level flight).
LOAD_FACTOR_RANGE = (1.0, 6.0)


@dataclass(frozen=True)
class SteadyManoeuvre:
    """A steady manoeuvre to trim for.

    Attributes
    ----------
    speed_m_s : float
        True airspeed V [m/s], > 0.
    altitude_m : float
        Altitude H [m] (ISA range).
    turn_radius_m : float
        Turn radius R [m]; ``math.inf`` for straight flight; positive turns right.
    climb_angle_rad : float or None
        Flight-path angle gamma [rad] (> 0 climbing); None for a glide, where gamma is an unknown and the
        thrust is zero.
    coordinated : bool
        Turns only: zero sideslip at the centre of gravity with the heading free (module docstring)
        instead of the paper's heading-on-track turn (default False, the paper's eqs. 36-37).
    load_factor : float
        Symmetric pull-up load factor n (lift / weight) in ``LOAD_FACTOR_RANGE``; 1 (default) for every other
        manoeuvre. Other than 1 only in straight flight with gamma = 0 (module docstring: the bottom of the pull-up).
    """

    speed_m_s: float
    altitude_m: float
    turn_radius_m: float = math.inf
    climb_angle_rad: float | None = 0.0
    coordinated: bool = False
    load_factor: float = 1.0

    def __post_init__(self) -> None:
        for name in ("speed_m_s", "altitude_m", "turn_radius_m", "climb_angle_rad"):
            value = getattr(self, name)
            if isinstance(value, (bool, str, bytes)):  # True is not 1 m/s, "100" not 100 m
                raise ValueError(f"{name} = {value!r}: must be a number, got {type(value).__name__}")
        if not (math.isfinite(self.speed_m_s) and 1.0 <= self.speed_m_s <= 400.0):
            raise ValueError(f"speed_m_s = {self.speed_m_s!r}: must be in [1, 400] m/s")
        speed_of_sound(float(self.altitude_m))  # ISA range check with a clear message
        if not (self.turn_radius_m == math.inf or (math.isfinite(self.turn_radius_m) and abs(self.turn_radius_m) >= 100.0)):
            raise ValueError(f"turn_radius_m = {self.turn_radius_m!r}: must be inf (straight) or |R| >= 100 m")
        if self.climb_angle_rad is not None and not abs(self.climb_angle_rad) <= math.radians(30.0):
            raise ValueError(f"climb_angle_rad = {self.climb_angle_rad!r}: must be within +-30 deg (or None for a glide)")
        if not isinstance(self.coordinated, bool):
            raise ValueError(f"coordinated = {self.coordinated!r}: must be True or False")
        if self.coordinated and self.turn_radius_m == math.inf:
            raise ValueError("coordinated = True: applies to turns only (give a finite turn radius); straight flight "
                             "is symmetric and has no sideslip to coordinate")
        lo, hi = LOAD_FACTOR_RANGE
        if isinstance(self.load_factor, bool) or not isinstance(self.load_factor, (int, float)) \
                or not (math.isfinite(self.load_factor) and lo <= self.load_factor <= hi):
            raise ValueError(f"load_factor = {self.load_factor!r}: must be a finite number in [{lo:g}, {hi:g}] "
                             "(1: level flight)")
        if self.load_factor != 1.0 and (self.turn_radius_m != math.inf or self.climb_angle_rad != 0.0):
            raise ValueError(f"load_factor = {self.load_factor!r}: a pull-up is symmetric with a horizontal flight "
                             f"path at its bottom; it needs turn_radius_m = inf and climb_angle_rad = 0 (got "
                             f"{self.turn_radius_m!r} and {self.climb_angle_rad!r})")

    # ------------------------------------------------------------------ constructors
    @classmethod
    def level(cls, altitude_m: float, *, speed_m_s: float | None = None, mach: float | None = None) -> "SteadyManoeuvre":
        """Steady level flight, eqs. (34)-(35)."""
        return cls(_speed(altitude_m, speed_m_s, mach), altitude_m)

    @classmethod
    def turn(cls, altitude_m: float, radius_m: float, *, speed_m_s: float | None = None, mach: float | None = None,
             coordinated: bool = False) -> "SteadyManoeuvre":
        """Steady level turn of radius R: eqs. (36)-(37), or coordinated (zero sideslip, heading free)."""
        return cls(_speed(altitude_m, speed_m_s, mach), altitude_m, turn_radius_m=radius_m, coordinated=coordinated)

    @classmethod
    def climb(cls, altitude_m: float, climb_angle_rad: float, *, speed_m_s: float | None = None, mach: float | None = None) -> "SteadyManoeuvre":
        """Steady climb (gamma > 0) or descent (gamma < 0), eqs. (38)-(39)."""
        return cls(_speed(altitude_m, speed_m_s, mach), altitude_m, climb_angle_rad=climb_angle_rad)

    @classmethod
    def glide(cls, altitude_m: float, *, speed_m_s: float | None = None, mach: float | None = None) -> "SteadyManoeuvre":
        """Steady glide: thrust zero, flight-path angle found by trim (paper: gamma = -3.12 deg at 9144 m)."""
        return cls(_speed(altitude_m, speed_m_s, mach), altitude_m, climb_angle_rad=None)

    @classmethod
    def pull_up(cls, altitude_m: float, load_factor: float, *, speed_m_s: float | None = None,
                mach: float | None = None) -> "SteadyManoeuvre":
        """Bottom of a steady symmetric pull-up at load factor n: wings level, gamma = 0, q = (n - 1) g0 / V.

        Quasi-steady (module docstring); ``load_factor`` in ``LOAD_FACTOR_RANGE``, n = 1 is level flight.
        """
        return cls(_speed(altitude_m, speed_m_s, mach), altitude_m, load_factor=float(load_factor)
                   if isinstance(load_factor, (int, float)) and not isinstance(load_factor, bool) else load_factor)

    @classmethod
    def climbing_turn(cls, altitude_m: float, radius_m: float, climb_angle_rad: float, *, speed_m_s: float | None = None,
                      mach: float | None = None, coordinated: bool = False) -> "SteadyManoeuvre":
        """Steady climbing (or descending) turn: R and gamma together (time-invariant, not in the paper)."""
        return cls(_speed(altitude_m, speed_m_s, mach), altitude_m, turn_radius_m=radius_m, climb_angle_rad=climb_angle_rad,
                   coordinated=coordinated)

    # ------------------------------------------------------------------ derived
    @property
    def mach(self) -> float:
        """Flight Mach number at the manoeuvre's altitude."""
        return self.speed_m_s / speed_of_sound(float(self.altitude_m))

    @property
    def is_glide(self) -> bool:
        """True when gamma is an unknown and the thrust is zero."""
        return self.climb_angle_rad is None

    def with_speed(self, speed_m_s: float) -> "SteadyManoeuvre":
        """The same manoeuvre at another speed (used by the flutter search)."""
        return SteadyManoeuvre(speed_m_s, self.altitude_m, self.turn_radius_m, self.climb_angle_rad, self.coordinated,
                               self.load_factor)

    def describe(self) -> str:
        """Human-readable name, e.g. "level turn R = 5000 m at M 0.740, H = 9144 m"."""
        gamma = "glide" if self.is_glide else f"gamma = {math.degrees(self.climb_angle_rad):+.2f} deg"
        turn = "" if self.turn_radius_m == math.inf else f"{'coordinated ' if self.coordinated else ''}turn R = {self.turn_radius_m:.0f} m, "
        kind = "level flight" if (not turn and not self.is_glide and self.climb_angle_rad == 0.0) else "steady flight"
        if self.load_factor != 1.0:
            return (f"pull-up (n = {self.load_factor:g}, q = {math.degrees(self.pitch_rate):.3f} deg/s) at M {self.mach:.4f} "
                    f"(V = {self.speed_m_s:.2f} m/s), H = {self.altitude_m:.0f} m")
        return f"{kind} ({turn}{gamma}) at M {self.mach:.4f} (V = {self.speed_m_s:.2f} m/s), H = {self.altitude_m:.0f} m"

    def turn_rate(self, gamma: float) -> float:
        """Omega = V cos(gamma) / R [rad/s] (0 for straight flight)."""
        return 0.0 if self.turn_radius_m == math.inf else self.speed_m_s * math.cos(gamma) / self.turn_radius_m

    @property
    def pitch_rate(self) -> float:
        """Pull-up pitch rate q = (n - 1) g0 / V [rad/s] about the body y axis (0 unless n != 1)."""
        return (self.load_factor - 1.0) * G0 / self.speed_m_s

    def body_rates(self, phi: float, theta: float, gamma: float, heading_offset: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
        """Body velocity v and angular velocity omega of the steady manoeuvre (eqs. 35, 37, 39; pull-up: + [0, q, 0]).

        Parameters
        ----------
        phi, theta : float
            Bank and pitch angles [rad].
        gamma : float
            Flight-path angle [rad].
        heading_offset : float
            Heading minus track, psi - chi [rad] (0 in the paper's turn; free in a coordinated turn).
            The track is taken as chi = 0: the equations do not depend on it.

        Returns
        -------
        v : ndarray, shape (3,)  [m/s], body axes
        omega : ndarray, shape (3,)  [rad/s], body axes
        """
        r_dot = self.speed_m_s * np.array([math.cos(gamma), 0.0, -math.sin(gamma)])
        v = dcm_321(phi, theta, heading_offset) @ r_dot
        omega = euler_rate_matrix(phi, theta) @ np.array([0.0, 0.0, self.turn_rate(gamma)])
        omega[1] += self.pitch_rate
        return v, omega


def _speed(altitude_m: float, speed_m_s: float | None, mach: float | None) -> float:
    if (speed_m_s is None) == (mach is None):
        raise ValueError("give exactly one of speed_m_s and mach")
    if mach is not None:
        if not 0.0 < mach < 1.0:
            raise ValueError(f"mach = {mach!r}: must be in (0, 1)")
        return float(mach_to_true_airspeed(mach, altitude_m))
    return float(speed_m_s)
