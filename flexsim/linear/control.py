"""Linear models for control design: the linearised aircraft with named states, inputs and outputs.

The state-space model about an operating point (a trim, :func:`flexsim.trimming.trim`)::

    dx_dot = A dx + B du,      dy = C dx + D du

* A and the first four columns of B (thrust, aileron, elevator, rudder) are :func:`flexsim.linear.linearize.linearize`
  of the one nonlinear model (:meth:`~flexsim.model.aircraft_model.AircraftModel.rhs`, central differences), with the
  ignorable states X, Y, Z and psi removed (density frozen at the trim altitude): the same linearisation as the
  eigen-analysis of :mod:`flexsim.linear.stability`, so the poles are its eigenvalues.
* The fifth input is a vertical gust ``gust_up_m_s`` [m/s]: the air moving up (NED z negative) at the same velocity
  at every aerodynamic strip, the wind argument of ``model.rhs(t, x, u, wind)`` (:mod:`flexsim.sim.disturbances`
  passes frozen fields the same way). Its column of B is the central difference of ``model.rhs`` over that uniform
  wind. A uniform vertical gust does not depend on the heading psi, so the linear model stays time invariant in a
  turn; a gust's penetration delay along the aircraft (nose before tail) is not represented. The column has what
  the model's wind has: the strips see the gust, the parasite drag and the slender-body moments do not (the model's
  documented simplifications, ``docs/options.md``), and the tail's downwash scales with the inertial speed.
* The outputs are the structural sensor bank (:class:`flexsim.model.sensors.SensorBank`: tip deflection and its rate,
  tip twist and its rate, root bending moment of every flexible component, paper eq. 1 with the clamped-free shapes),
  optionally followed by the states themselves; D = 0 (the sensors read the state only).

Units: SI and radians, the unit at the end of each name (:mod:`flexsim.io.vocabulary`). Frames: NED inertial, FRD body
axes, 3-2-1 Euler angles (``docs/conventions.md``).

:meth:`LinearSystem.to_statespace` gives a python-control ``StateSpace`` (``control.ss(A, B, C, D, states=...,
inputs=..., outputs=...)``; python-control is the optional extra ``flexsim[control]``), :meth:`LinearSystem.save` and
:meth:`LinearSystem.load` an ``.npz`` file with the matrices, the names, the trim point and the model options.
"""

from __future__ import annotations

import json
import math
import os
from dataclasses import dataclass, fields
from pathlib import Path

import numpy as np

from flexsim._arrays import readonly
from flexsim.aircraft.definition import Aircraft
from flexsim.errors import FlexsimError, float_array
from flexsim.io.vocabulary import CONTROL_NAMES, check_names
from flexsim.linear.linearize import linearize
from flexsim.model.aircraft_model import AircraftModel, check_model
from flexsim.model.coupling import AeroOptions
from flexsim.model.terms import Terms
from flexsim.model.variant import VariantSettings
from flexsim.model.naming import state_names
from flexsim.model.sensors import SENSOR_QUANTITIES, SensorBank, structural_sensors
from flexsim.trimming.manoeuvre import SteadyManoeuvre
from flexsim.trimming.solver import TrimPoint

__all__ = ["GUST_INPUT", "INPUT_NAMES", "FILE_FORMAT", "ModelRecord", "LinearSystem", "MissingDependencyError",
           "linear_system", "state_space"]

#: Name of the gust input: uniform vertical air velocity, positive up [m/s].
GUST_INPUT = "gust_up_m_s"
#: Inputs of the linear model, in the order of the columns of B and D.
INPUT_NAMES: tuple[str, ...] = CONTROL_NAMES + (GUST_INPUT,)
#: Identifier of the ``.npz`` layout written by :meth:`LinearSystem.save`.
FILE_FORMAT = "flexsim-linear-system-1"

#: Relative step of the gust central difference (as the velocity states' in :mod:`flexsim.model.jacobian`) and its floor [m/s].
_GUST_REL_STEP = 1e-6
_GUST_ABS_STEP = 1e-7
#: Vocabulary name of each sensor quantity of :data:`flexsim.model.sensors.SENSOR_QUANTITIES` for a component.
_SENSOR_NAMES = ("tip_deflection_{c}_m", "tip_deflection_rate_{c}_m_s", "tip_twist_{c}_rad", "tip_twist_rate_{c}_rad_s",
                 "root_bending_moment_{c}_N_m")


class MissingDependencyError(FlexsimError, ImportError):
    """An optional dependency is not installed; the message names the package and how to install it."""


def _control():
    """The ``control`` module (python-control), or :class:`MissingDependencyError` naming the extra."""
    try:
        import control
    except ImportError:
        raise MissingDependencyError(
            "python-control is not installed: LinearSystem.to_statespace needs it; install it with "
            "`pip install 'flexsim[control]'` (or `pip install control`). The matrices and names are available "
            "without it (LinearSystem.a, .b, .c, .d, .state_names, .input_names, .output_names)") from None
    return control


@dataclass(frozen=True)
class ModelRecord:
    """The model a linear system was made from: its aircraft, physical terms and variant (enough to build it again).

    Two records are equal only when every term and the variant are (so are two systems of different models).

    Attributes
    ----------
    aircraft : str
        Aircraft name.
    aircraft_source : str
        Where the definition came from (a file path or a bundled name).
    aircraft_digest : str
        :meth:`flexsim.aircraft.definition.Aircraft.content_digest` of the definition.
    terms : Terms
        The physical terms of the model (:class:`flexsim.model.terms.Terms`).
    variant : VariantSettings
        The variant of the model (:class:`flexsim.model.variant.VariantSettings`).
    formulation : str
        Resolution of the strip airloads in use (``"physical"`` or ``"paper"``; ``""`` without aerodynamics).
    structural_damping : float
        Modal damping ratio of the elastic modes in use [-] (``terms.structural_damping``, else the aircraft's).
    """

    aircraft: str
    aircraft_source: str
    aircraft_digest: str
    terms: Terms
    variant: VariantSettings
    formulation: str
    structural_damping: float

    @property
    def aero(self) -> AeroOptions | None:
        """The aerodynamic options (``terms.aero``; None: no aerodynamics)."""
        return self.terms.aero

    @classmethod
    def of(cls, model: AircraftModel) -> ModelRecord:
        """The record of ``model``."""
        ac = model.aircraft
        return cls(ac.name, str(ac.source), ac.content_digest(), model.terms, model.variant, model.formulation or "",
                   model.structural_damping_ratio)

    def build(self, aircraft: Aircraft) -> AircraftModel:
        """The model of this record for ``aircraft`` (which must have the recorded content digest)."""
        if aircraft.content_digest() != self.aircraft_digest:
            raise ValueError(f"aircraft {aircraft.name!r}: its content differs from the recorded {self.aircraft!r} "
                             f"(digest {self.aircraft_digest[:12]}...)")
        return AircraftModel(aircraft, terms=self.terms, variant=self.variant)

    def as_json(self) -> str:
        """The record as a JSON object (``terms`` and ``variant`` as their ``record()`` dicts)."""
        out = {f.name: getattr(self, f.name) for f in fields(self)}
        out["terms"], out["variant"] = self.terms.record(), self.variant.record()
        return json.dumps(out, sort_keys=True)

    @classmethod
    def from_json(cls, text: str) -> ModelRecord:
        """Inverse of :meth:`as_json` (also reads the records of earlier files: variant name, aero, gravity and density)."""
        d = json.loads(text)
        if "terms" not in d:  # an earlier record: the variant's kind and three of the terms
            rho = d.pop("aero_density_kg_m3", None)
            d["terms"] = {"aero": d.pop("aero"), "gravity_m_s2": d.pop("gravity_m_s2"), "aero_density_kg_m3": rho}
            d["variant"] = {"kind": d["variant"]}
        d["terms"], d["variant"] = Terms.from_record(d["terms"]), VariantSettings(**d["variant"])
        return cls(**d)


@dataclass(frozen=True, eq=False)
class LinearSystem:
    """dx_dot = A dx + B du, dy = C dx + D du about an operating point (module docstring); arrays read-only.

    Attributes
    ----------
    a : ndarray, shape (m, m)
        State matrix over the kept states [1/s and the mixed units of the names].
    b : ndarray, shape (m, 5)
        Input matrix; columns :data:`INPUT_NAMES` (thrust [N], aileron, elevator, rudder [rad], gust [m/s]).
    c : ndarray, shape (p, m)
        Output matrix (the sensor bank, then the states if asked for).
    d : ndarray, shape (p, 5)
        Feedthrough (zero).
    state_names, input_names, output_names : tuple of str
        Names of the entries of dx, du and dy (units at the end of each name).
    keep : ndarray of int, shape (m,)
        Index of each kept state in the model's full state vector.
    x0 : ndarray, shape (n,)
        Full state of the operating point (the model's layout).
    u0 : ndarray, shape (4,)
        Controls of the operating point [T_e (N), delta_a, delta_e, delta_r (rad)] (the gust is zero there).
    manoeuvre : SteadyManoeuvre or None
        The trimmed manoeuvre (None for an operating point given as a state).
    model : ModelRecord
        The options of the model.
    """

    a: np.ndarray
    b: np.ndarray
    c: np.ndarray
    d: np.ndarray
    state_names: tuple[str, ...]
    input_names: tuple[str, ...]
    output_names: tuple[str, ...]
    keep: np.ndarray
    x0: np.ndarray
    u0: np.ndarray
    manoeuvre: SteadyManoeuvre | None
    model: ModelRecord

    def __post_init__(self) -> None:
        for name in ("a", "b", "c", "d", "x0", "u0"):
            object.__setattr__(self, name, readonly(np.array(getattr(self, name), dtype=float)))
        object.__setattr__(self, "keep", readonly(np.array(self.keep, dtype=int)))
        m, k, p = len(self.state_names), len(self.input_names), len(self.output_names)
        shapes = {"a": (m, m), "b": (m, k), "c": (p, m), "d": (p, k), "keep": (m,), "u0": (4,)}
        for name, shape in shapes.items():
            if getattr(self, name).shape != shape:
                raise ValueError(f"{name}: shape {getattr(self, name).shape}, expected {shape} for {m} states, "
                                 f"{k} inputs and {p} outputs")

    def poles(self) -> np.ndarray:
        """Eigenvalues of A [1/s], shape (m,)."""
        return np.linalg.eigvals(self.a)

    def to_statespace(self, name: str | None = None):
        """The python-control ``StateSpace`` with these matrices and names (optional extra ``flexsim[control]``).

        Parameters
        ----------
        name : str, optional
            System name (default: the aircraft's).

        Raises
        ------
        MissingDependencyError
            python-control is not installed.
        """
        control = _control()
        return control.ss(np.array(self.a), np.array(self.b), np.array(self.c), np.array(self.d),
                          states=list(self.state_names), inputs=list(self.input_names),
                          outputs=list(self.output_names), name=name or self.model.aircraft)

    # ------------------------------------------------------------------ file
    def save(self, path: str | os.PathLike) -> Path:
        """Write the system to an ``.npz`` file (numpy, no pickles): matrices ``A``, ``B``, ``C``, ``D``; names
        ``state_names``, ``input_names``, ``output_names``; ``keep``, ``x0``, ``u0``; the manoeuvre
        (``speed_m_s``, ``altitude_m``, ``turn_radius_m``, ``climb_angle_rad`` (NaN: a glide), ``coordinated``,
        ``mach``; absent when the operating point was not a trim); ``model_options`` (JSON of :class:`ModelRecord`)
        and ``format`` (:data:`FILE_FORMAT`). Returns the path written.

        Raises
        ------
        ValueError
            The path does not end in ``.npz`` (numpy would append it) or is a directory.
        FileNotFoundError
            Its directory does not exist.
        """
        path = _npz_path(path)
        if not path.parent.is_dir():
            raise FileNotFoundError(f"path = {str(path)!r}: directory {str(path.parent)!r} does not exist")
        arrays = dict(format=np.array(FILE_FORMAT), A=self.a, B=self.b, C=self.c, D=self.d,
                      state_names=np.array(self.state_names, dtype=str), input_names=np.array(self.input_names, dtype=str),
                      output_names=np.array(self.output_names, dtype=str), keep=self.keep, x0=self.x0, u0=self.u0,
                      model_options=np.array(self.model.as_json()))
        man = self.manoeuvre
        if man is not None:
            from flexsim.atmosphere import speed_of_sound

            arrays.update(speed_m_s=np.array(man.speed_m_s), altitude_m=np.array(man.altitude_m),
                          turn_radius_m=np.array(man.turn_radius_m),
                          climb_angle_rad=np.array(math.nan if man.climb_angle_rad is None else man.climb_angle_rad),
                          coordinated=np.array(bool(man.coordinated)),
                          mach=np.array(man.speed_m_s / speed_of_sound(float(man.altitude_m))))
        np.savez(path, **arrays)
        return path

    @classmethod
    def load(cls, path: str | os.PathLike) -> LinearSystem:
        """Read a file written by :meth:`save`.

        Raises
        ------
        ValueError
            Not such a file (another ``.npz``, another format version, or missing entries).
        """
        import zipfile
        import zlib

        path = Path(path)
        try:
            with np.load(path, allow_pickle=False) as f:
                data = {k: f[k] for k in f.files}
        except (OSError, ValueError, EOFError, zipfile.BadZipFile, zlib.error) as exc:  # a truncated file: BadZipFile, EOFError
            if not path.exists():
                raise FileNotFoundError(f"path = {str(path)!r}: no such file") from None
            raise ValueError(f"path = {str(path)!r}: not a readable .npz file, truncated or damaged "
                             f"({type(exc).__name__}: {exc})") from None
        fmt = str(data.get("format", ""))
        if fmt != FILE_FORMAT:
            raise ValueError(f"path = {str(path)!r}: format = {fmt!r}, expected {FILE_FORMAT!r} (a file written by "
                             "LinearSystem.save / flexsim linearize)")
        missing = [k for k in ("A", "B", "C", "D", "state_names", "input_names", "output_names", "keep", "x0", "u0",
                               "model_options") if k not in data]
        if missing:
            raise ValueError(f"path = {str(path)!r}: entries {', '.join(missing)} missing (a damaged or edited file)")
        man = None
        if "speed_m_s" in data:
            climb = float(data["climb_angle_rad"])
            man = SteadyManoeuvre(float(data["speed_m_s"]), float(data["altitude_m"]), float(data["turn_radius_m"]),
                                  None if math.isnan(climb) else climb, bool(data["coordinated"]))
        return cls(data["A"], data["B"], data["C"], data["D"], tuple(str(s) for s in data["state_names"]),
                   tuple(str(s) for s in data["input_names"]), tuple(str(s) for s in data["output_names"]),
                   data["keep"], data["x0"], data["u0"], man, ModelRecord.from_json(str(data["model_options"])))


def _npz_path(path: str | os.PathLike) -> Path:
    p = Path(path)
    if p.is_dir():
        raise ValueError(f"path = {str(p)!r}: is a directory; give a file name ending in .npz")
    if p.suffix != ".npz":
        raise ValueError(f"path = {str(p)!r}: must end in .npz (numpy's compressed-archive format)")
    return p


def _gust_column(model: AircraftModel, x0: np.ndarray, u0: np.ndarray) -> np.ndarray:
    """d rhs / d w_g of a uniform up-gust w_g [m/s] at (x0, u0), shape (n,): central difference of ``model.rhs`` with
    the wind ``wind(t, p) = (0, 0, -w_g)`` at every strip (NED), step 1e-6 of the flight speed."""
    vel = model.unpack(x0)[4]
    h = max(_GUST_ABS_STEP, _GUST_REL_STEP * float(np.linalg.norm(vel[0:3])))

    def up(w: float):
        return lambda t, positions: np.tile([0.0, 0.0, -w], (np.shape(positions)[0], 1))

    return (model.rhs(0.0, x0, u0, up(h)) - model.rhs(0.0, x0, u0, up(-h))) / (2.0 * h)


def _sensor_rows(model: AircraftModel) -> tuple[np.ndarray, tuple[str, ...]]:
    """Rows (p, n) over the full state and names of the sensor bank's outputs (quantities a component has)."""
    sensors = structural_sensors(model)
    names = tuple(sensors)
    bank = SensorBank.of(sensors, names, model.layout.n_states)
    cols, out = [], []
    for c, comp in enumerate(names):
        s = sensors[comp]
        present = (s.w_tip.size, s.w_tip.size, s.psi_tip.size, s.psi_tip.size, s.w_tip.size)
        for k in range(len(SENSOR_QUANTITIES)):
            if present[k]:
                cols.append(len(SENSOR_QUANTITIES) * c + k)
                out.append(_SENSOR_NAMES[k].format(c=comp))
    return np.asarray(bank.matrix)[:, cols].T, check_names("signal", out)


#: Largest scaled residual (accelerations in g, angular ones in g per 5 m, as the trim's) of a trim accepted as an
#: equilibrium of the model it is linearised with: trims converge to 1e-8 (``flexsim.trimming.solver``); a trim of another
#: aircraft, variant or formulation leaves residuals of order 1 and more.
EQUILIBRIUM_TOLERANCE = 1e-6


def _check_operating_point(model: AircraftModel, x0: np.ndarray, u0: np.ndarray, from_trim: bool) -> None:
    """Refuse a non-finite state or controls and, for a trim, one that is not an equilibrium of ``model``."""
    lay = model.layout
    for name, arr in (("point", x0), ("u0", u0)):
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            what = state_names(model)[bad[0]] if name == "point" else f"entry {bad[0]}"
            raise ValueError(f"{name}: {bad.size} non-finite entries (first: {what} = {float(arr[bad[0]])!r}); the linear model "
                             "of a state that is not finite would be NaN")
    if not from_trim:
        return
    g = max(model.terms.gravity_m_s2, 1.0)
    scale = np.full(lay.velocity.stop - lay.velocity.start, 1.0 / g)
    scale[3:6] = 5.0 / g
    residual = float(np.linalg.norm(model.rhs(0.0, x0, u0)[lay.velocity] * scale))
    if not residual <= EQUILIBRIUM_TOLERANCE:
        raise ValueError(f"point: the trim is not an equilibrium of this model of {model.aircraft.name} (scaled residual "
                         f"{residual:.3g} > {EQUILIBRIUM_TOLERANCE:g}): a trim of another aircraft, variant or formulation; "
                         "trim this model (flexsim.trimming.trim(model, manoeuvre)) and linearise that")


def linear_system(model: AircraftModel, point: TrimPoint | np.ndarray, u0: np.ndarray | None = None, *,
                  state_outputs: bool = False) -> LinearSystem:
    """The linear model of ``model`` about an operating point, with a gust input and the sensor outputs.

    Parameters
    ----------
    model : AircraftModel
        Any variant and aerodynamic model; with the finite-state (``"unsteady"``) aerodynamics the inflow states are
        states of the linear model.
    point : TrimPoint or ndarray, shape (n_states,)
        A trim (which supplies the controls and the manoeuvre) or a state. A trim of the model's quasi-steady twin
        (no inflow states: :func:`flexsim.trimming.trim` trims with quasi-steady aerodynamics) is extended with zero
        inflow, the finite-state wake's steady state.
    u0 : ndarray, shape (4,), optional
        Controls [T_e (N), delta_a, delta_e, delta_r (rad)], with a state only.
    state_outputs : bool
        Append every state to the outputs (C = [S; I]), for state feedback design.

    Returns
    -------
    LinearSystem

    With the geometrically nonlinear beams (``Terms(nonlinear_beams=...)``) ``point`` is the model's nonlinear trim
    (``fs.trim``) and the system is that of :func:`flexsim.linear.flexible_control.flexible_linear_system` (the free
    aircraft about its deformed equilibrium, quasi-steady strips; its own state names).
    """
    if getattr(getattr(model, "terms", None), "nonlinear_beams", None) is not None:
        from flexsim.linear.flexible_control import flexible_linear_system

        if u0 is not None:
            raise ValueError("u0: the nonlinear trim supplies its own controls")
        return flexible_linear_system(model, point, state_outputs=state_outputs)
    check_model(model)
    manoeuvre = None
    if isinstance(point, TrimPoint):
        if u0 is not None:
            raise ValueError("u0: a TrimPoint supplies its own controls; give u0 only with a state vector")
        manoeuvre, x0, u0 = point.manoeuvre, np.asarray(point.x, float), point.u
    elif u0 is None:
        raise ValueError("u0: the controls (4 numbers) are required when point is a state vector")
    else:
        x0 = float_array("point", point, (None,), what="(a state vector)")
    lay = model.layout
    if lay.n_inflow and x0.shape == (lay.inflow.start,):
        x0 = np.concatenate([x0, np.zeros(lay.n_inflow)])
    if x0.shape != (lay.n_states,):
        raise ValueError(f"point: a state of {x0.size} entries for a model of {lay.n_states} states "
                         f"({model.variant.kind.value}, {lay.n_inflow} inflow states)")
    u0 = float_array("u0", u0, (4,), what="[T_e (N), delta_a, delta_e, delta_r (rad)]")
    _check_operating_point(model, x0, u0, manoeuvre is not None)
    lin = linearize(model, x0, u0)
    b = np.column_stack([lin.b, _gust_column(model, lin.x0, lin.u0)[lin.keep]])
    rows, names = _sensor_rows(model)
    c = rows[:, lin.keep]
    if state_outputs:
        c = np.vstack([c, np.eye(lin.keep.size)])
        names = names + lin.state_names
    return LinearSystem(lin.a, b, c, np.zeros((c.shape[0], b.shape[1])), lin.state_names, INPUT_NAMES, names,
                        lin.keep, lin.x0, lin.u0, manoeuvre, ModelRecord.of(model))


def state_space(model: AircraftModel, point: TrimPoint | np.ndarray, u0: np.ndarray | None = None, *,
                state_outputs: bool = False):
    """``linear_system(model, point, u0, state_outputs=...).to_statespace()``: a python-control ``StateSpace``.

    Raises
    ------
    MissingDependencyError
        python-control is not installed (``pip install 'flexsim[control]'``).
    """
    _control()
    return linear_system(model, point, u0, state_outputs=state_outputs).to_statespace()
