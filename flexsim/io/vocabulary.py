"""The one vocabulary of flexsim's outputs: the name and unit of every state entry, control and signal.

The simulation result (:class:`flexsim.sim.result.SimulationResult`), the output maps that compute the signals
(:class:`flexsim.sim.outputs.OutputMaps`), the environments' flight logs (:class:`flexsim.io.env_log.FlightLogRecorder`),
the simulator's flight log (:mod:`flexsim.sim.recording`), the log reader and the Rerun view
(:mod:`flexsim.io.rerun_view`) all name quantities from :data:`QUANTITIES`, the table below; ``docs/logs.md`` prints
it. Units are SI and angles radians (house style: conversions at I/O only); every name ends in its unit
(``_m``, ``_rad``, ``_m_s``, ``_rad_s``, ``_N``, ``_N_m``; dimensionless names have none).

Flight-log format version 1 had two dialects of these names — the simulator's (``x_north_m``, ``alpha_deg``,
``tip_twist_<wing>_deg``, ``root_bending_<wing>_Nm``) and the environments' (``north_m``, ``u_m_s``,
``inflow_<i>_m_s``, ``twist_tip_<c>_rad``, ``root_bending_moment_<wing>_n_m``). :func:`upgrade_v1` translates
both into this vocabulary (renames, degree -> radian conversions, and dropping the simulator's attitude and
body-rate signals, which duplicate state entries), so that logs written by either keep loading.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from functools import cached_property, lru_cache

__all__ = ["Quantity", "QUANTITIES", "CONTROL_NAMES", "VOCABULARY_VERSION", "quantity", "unit", "suffix_unit", "check_names",
           "V1Upgrade", "upgrade_v1"]

#: Version of this vocabulary; equal to the flight-log format version that introduced it.
VOCABULARY_VERSION = "2"

_PART = {"component": r"[A-Za-z][A-Za-z0-9_]*?", "k": r"[1-9][0-9]*", "strip": r"[0-9]{2,}", "n": r"[1-9][0-9]*",
         "i": r"[0-9]+", "error": r"[a-z][a-z0-9_]*"}


@dataclass(frozen=True)
class Quantity:
    """One row of the vocabulary.

    Attributes
    ----------
    pattern : str
        The name, with ``{component}`` (a component of the aircraft file), ``{k}`` (1-based mode number),
        ``{strip}`` (2-digit 1-based strip number within the component), ``{n}`` (1-based inflow state of a
        strip) or ``{error}`` (a task error name) where the name varies.
    kind : str
        ``"state"``, ``"control"`` or ``"signal"``.
    unit : str
        SI unit as text (``"1"``: dimensionless; ``"as named"``: the unit ends the task error's name).
    description : str
        What the quantity is, with its frame and sign.
    legacy : bool
        A name that only logs of format 1 carry (the reader keeps it; writers may not use it).
    """

    pattern: str
    kind: str
    unit: str
    description: str
    legacy: bool = False

    @cached_property
    def regex(self) -> re.Pattern:
        """The pattern as an anchored regular expression."""
        out, pos = [], 0
        for m in re.finditer(r"\{(\w+)\}", self.pattern):
            out.append(re.escape(self.pattern[pos:m.start()]))
            out.append(f"(?P<{m.group(1)}>{_PART[m.group(1)]})")
            pos = m.end()
        out.append(re.escape(self.pattern[pos:]))
        return re.compile("".join(out) + r"\Z")


_Q = Quantity
#: The vocabulary: every name a flight log, a simulation result or an environment log may carry.
QUANTITIES: tuple[Quantity, ...] = (
    # ---- states (order of flexsim.model.layout.StateLayout; blocks absent in a model variant are left out)
    _Q("x_north_m", "state", "m", "position of the body origin o, north (NED inertial axes)"),
    _Q("y_east_m", "state", "m", "position of the body origin o, east"),
    _Q("z_down_m", "state", "m", "position of the body origin o, down (altitude = -z_down_m)"),
    _Q("phi_rad", "state", "rad", "roll angle phi (3-2-1 Euler angles, NED to body FRD)"),
    _Q("theta_rad", "state", "rad", "pitch angle theta"),
    _Q("psi_rad", "state", "rad", "yaw (heading) angle psi"),
    _Q("q_{component}_{k}_m", "state", "m", "bending coordinate k of a component (paper eq. 1: w = sum_k U_k q_k)"),
    _Q("xi_{component}_{k}_rad", "state", "rad", "torsion coordinate k of a component (paper eq. 1: psi = sum_k Psi_k xi_k)"),
    _Q("v_x_m_s", "state", "m/s", "inertial velocity of o in body axes, x forward (U; entry of V, paper eq. 9)"),
    _Q("v_y_m_s", "state", "m/s", "inertial velocity of o in body axes, y right (V)"),
    _Q("v_z_m_s", "state", "m/s", "inertial velocity of o in body axes, z down (W)"),
    _Q("omega_x_rad_s", "state", "rad/s", "body angular velocity, roll rate P"),
    _Q("omega_y_rad_s", "state", "rad/s", "body angular velocity, pitch rate Q"),
    _Q("omega_z_rad_s", "state", "rad/s", "body angular velocity, yaw rate R"),
    _Q("s_{component}_{k}_m_s", "state", "m/s", "bending rate s_k = dq_k/dt (entry of V, paper eq. 9)"),
    _Q("eta_{component}_{k}_rad_s", "state", "rad/s", "torsion rate eta_k = dxi_k/dt (entry of V, paper eq. 9)"),
    _Q("lambda_{component}_{strip}_{n}_m_s", "state", "m/s",
       "finite-state inflow state lambda_n of unsteady strip number <strip> of a component (Peters, Karunamoorthy & Cao 1995)"),
    _Q("inflow_{i}_m_s", "state", "m/s", "format-1 environment logs: inflow state i (0-based) of the inflow block; "
       "those logs do not record its strip", legacy=True),
    # ---- controls (the control vector u, text after paper eq. 33)
    _Q("thrust_N", "control", "N", "total engine thrust T_e"),
    _Q("aileron_rad", "control", "rad", "aileron deflection delta_a (trailing edge down on the right wing > 0)"),
    _Q("elevator_rad", "control", "rad", "elevator deflection delta_e (trailing edge down > 0)"),
    _Q("rudder_rad", "control", "rad", "rudder deflection delta_r (trailing edge left > 0)"),
    # ---- signals (derived from a state, its controls and the wind; flexsim.sim.outputs.OutputMaps)
    _Q("airspeed_m_s", "signal", "m/s", "true airspeed of o relative to the air (wind included)"),
    _Q("mach", "signal", "1", "Mach number: airspeed over the ISA speed of sound at the altitude"),
    _Q("alpha_rad", "signal", "rad", "angle of attack atan2(w_a, u_a) of the body axes relative to the air"),
    _Q("beta_rad", "signal", "rad", "sideslip asin(v_a / V_a) relative to the air (V_a the airspeed)"),
    _Q("altitude_m", "signal", "m", "altitude of o above the ISA datum, -z_down_m"),
    _Q("heading_rate_rad_s", "signal", "rad/s", "psi_dot = (Q sin(phi) + R cos(phi)) / cos(theta) (turn rate)"),
    _Q("load_factor", "signal", "1", "aerodynamic + thrust force along -z_body over the weight (as TrimPoint.load_factor)"),
    _Q("wing_lift_N", "signal", "N", "sum of the circulatory strip lifts of both wings"),
    _Q("tip_deflection_{component}_m", "signal", "m", "bending deflection w(L) at the tip, along z_i (down on a wing)"),
    _Q("tip_deflection_rate_{component}_m_s", "signal", "m/s", "rate of the tip bending deflection"),
    _Q("tip_twist_{component}_rad", "signal", "rad", "torsion psi(L) at the tip (nose up on the right wing, nose down "
       "on the left wing, whose y_i points forward)"),
    _Q("tip_twist_rate_{component}_rad_s", "signal", "rad/s", "rate of the tip twist"),
    _Q("root_bending_moment_{component}_N_m", "signal", "N m",
       "mode-displacement root bending moment EI(0) w''(0) (w down: negative when a wing bends up under lift)"),
    _Q("error_{error}", "signal", "as named", "environment logs: a task error (its name ends in its unit)"),
    _Q("reward", "signal", "1", "environment logs: the reward of the last step"),
)

#: Names of the control vector entries, in the order of u.
CONTROL_NAMES: tuple[str, ...] = tuple(q.pattern for q in QUANTITIES if q.kind == "control")


@lru_cache(maxsize=8192)  # keyed by the arguments (strings): OutputMaps checks ~290 names per simulate (15 ms)
def quantity(name: str, kind: str | None = None, *, legacy: bool = True) -> Quantity:
    """The vocabulary row that ``name`` matches (of ``kind``, if given; legacy rows only if ``legacy``).

    Raises
    ------
    KeyError
        No row matches; the message names the name and where the vocabulary is documented.
    """
    for q in QUANTITIES:
        if (kind is None or q.kind == kind) and (legacy or not q.legacy) and q.regex.match(name):
            return q
    what = f"{kind} " if kind else ""
    raise KeyError(f"{name!r} is not a {what}name of the flexsim output vocabulary (flexsim.io.vocabulary.QUANTITIES, "
                   f"docs/logs.md)")


_SUFFIX_UNITS = (("_rad_s", "rad/s"), ("_m_s", "m/s"), ("_N_m", "N m"), ("_rad", "rad"), ("_N", "N"), ("_m", "m"))


def suffix_unit(name: str, dimensionless: str = "1") -> str:
    """The unit that the SI suffix of ``name`` states (``_rad_s``, ``_m_s``, ``_N_m``, ``_rad``, ``_N``, ``_m``), or
    ``dimensionless`` when it has none."""
    return next((u for suffix, u in _SUFFIX_UNITS if name.endswith(suffix)), dimensionless)


def unit(name: str) -> str:
    """The unit of a vocabulary name (``"1"`` if dimensionless; a task error's from its name's suffix)."""
    q = quantity(name)
    if q.unit != "as named":
        return q.unit
    return suffix_unit(name)


def check_names(kind: str, names) -> tuple[str, ...]:
    """``names`` as a tuple after checking that each is a current (not legacy) vocabulary name of ``kind``.

    Raises
    ------
    ValueError
        A name outside the vocabulary, naming it, its position and the documentation.
    """
    names = tuple(names)
    for i, name in enumerate(names):
        try:
            quantity(name, kind, legacy=False)
        except KeyError:
            raise ValueError(f"{kind}_names[{i}] = {name!r}: not a {kind} name of the flexsim output vocabulary "
                             f"version {VOCABULARY_VERSION} (flexsim.io.vocabulary.QUANTITIES, docs/logs.md)") from None
    return names


# ------------------------------------------------------------------ format 1 (two dialects)
#: Format-1 state names that changed (environment dialect) -> format-2 name.
_V1_STATE_RENAMES = {"north_m": "x_north_m", "east_m": "y_east_m", "down_m": "z_down_m", "u_m_s": "v_x_m_s",
                     "v_m_s": "v_y_m_s", "w_m_s": "v_z_m_s", "roll_rate_rad_s": "omega_x_rad_s",
                     "pitch_rate_rad_s": "omega_y_rad_s", "yaw_rate_rad_s": "omega_z_rad_s"}
#: Format-1 signals of the simulator dialect that duplicate state entries (in degrees): dropped on reading.
_V1_DROPPED = ("phi_deg", "theta_deg", "psi_deg", "roll_rate_deg_s", "pitch_rate_deg_s", "yaw_rate_deg_s")
#: Format-1 signal renames: (regex, format-2 name template, factor).
_V1_SIGNAL_RULES = (
    (re.compile(r"alpha_deg\Z"), "alpha_rad", math.pi / 180.0),
    (re.compile(r"beta_deg\Z"), "beta_rad", math.pi / 180.0),
    (re.compile(r"tip_twist_(?P<c>\w+?)_deg\Z"), "tip_twist_{c}_rad", math.pi / 180.0),
    (re.compile(r"root_bending_(?P<c>\w+?)_Nm\Z"), "root_bending_moment_{c}_N_m", 1.0),
    (re.compile(r"twist_tip_(?P<c>\w+?)_rad\Z"), "tip_twist_{c}_rad", 1.0),
    (re.compile(r"root_bending_moment_(?P<c>\w+?)_n_m\Z"), "root_bending_moment_{c}_N_m", 1.0),
)


@dataclass(frozen=True)
class V1Upgrade:
    """How the names and signal columns of a format-1 log map onto this vocabulary.

    Attributes
    ----------
    dialect : str
        ``"simulate"`` (written by :func:`flexsim.sim.simulate.simulate`), ``"env"`` (by the environments'
        ``FlightLogRecorder``) or ``"other"`` (neither's names recognised; names kept).
    state_names : tuple of str
        Format-2 names of the state columns (the values are unchanged: no state entry changed its unit).
    signal_names : tuple of str
        Format-2 names of the kept signal columns.
    signal_columns : tuple of int
        Index of each kept column in the format-1 signals.
    signal_factors : tuple of float
        Factor turning each kept column into its format-2 unit (pi/180 for degrees, else 1).
    """

    dialect: str
    state_names: tuple[str, ...]
    signal_names: tuple[str, ...]
    signal_columns: tuple[int, ...]
    signal_factors: tuple[float, ...]


def upgrade_v1(state_names, signal_names) -> V1Upgrade:
    """Translate the names of a format-1 flight log (either dialect) into this vocabulary.

    Control names did not change (``thrust_N``, ``aileron_rad``, ``elevator_rad``, ``rudder_rad`` in both).
    """
    state_names, signal_names = tuple(state_names), tuple(signal_names)
    if "north_m" in state_names or any(n.startswith(("twist_tip_", "inflow_")) for n in state_names + signal_names):
        dialect = "env"
    elif "x_north_m" in state_names or "alpha_deg" in signal_names or any(n.endswith("_deg") for n in signal_names):
        dialect = "simulate"
    else:
        dialect = "other"
    states = tuple(_V1_STATE_RENAMES.get(n, n) for n in state_names)
    names, columns, factors = [], [], []
    for j, name in enumerate(signal_names):
        if name in _V1_DROPPED:
            continue
        new, factor = name, 1.0
        for regex, template, f in _V1_SIGNAL_RULES:
            m = regex.match(name)
            if m:
                new, factor = template.format(**m.groupdict()), f
                break
        names.append(new)
        columns.append(j)
        factors.append(factor)
    return V1Upgrade(dialect, states, tuple(names), tuple(columns), tuple(factors))
