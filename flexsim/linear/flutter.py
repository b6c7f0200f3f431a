"""Flutter speed of a manoeuvring aircraft, and of a restrained structure in a wind tunnel.

Source: Tuzcu & Nguyen (2014), "Numerical Model": the flutter speed is the lowest speed of the nominal
(steady) flight at which an eigenvalue of the linearised equations crosses the imaginary axis. Here the
crossing must be made by an elastic-dominated mode (:mod:`flexsim.linear.stability`); rigid-body
instabilities (spiral, phugoid) met on the way are reported separately, never as flutter. The aircraft is
re-trimmed at every Mach number; the crossing is bracketed on a Mach grid and refined with Brent's
method to 1e-4 in Mach.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from scipy.optimize import brentq

from flexsim.aircraft.definition import Aircraft
from flexsim.atmosphere import isa_density, speed_of_sound
from flexsim.errors import FlexsimError
from flexsim.linear.participation import Participation, describe_mode
from flexsim.linear.stability import Mode, Spectrum, spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AERO_MODELS, AeroOptions
from flexsim.trim import SteadyManoeuvre, TrimPoint, trim

__all__ = ["FlutterPoint", "FlutterNotFound", "FlutterAnalysis", "wind_tunnel_flutter"]


class FlutterNotFound(FlexsimError, RuntimeError):
    """No elastic mode crossed the imaginary axis in the searched range."""


@dataclass(frozen=True, eq=False)
class FlutterPoint:
    """The flutter point of a manoeuvre.

    Attributes
    ----------
    aero_model : str
    mach, speed_m_s, frequency_rad_s : float
        Flutter Mach number, true airspeed [m/s] and frequency |Im(lambda)| [rad/s].
    trim : TrimPoint or None
        Trim at the flutter speed (None for a wind-tunnel case).
    mode : Mode
        The crossing mode.
    mode_shape : ndarray (complex), shape (n_v,)
        Displacement amplitudes over [R, Theta, q, xi]-rates order of V (eq. 9), i.e. shape / lambda,
        normalised so that the fuselage's first bending coordinate q_f1 = 1 m (paper Figs. 11, 16) when
        it takes part (|q_f1| >= 1e-3 of the largest elastic amplitude); otherwise (an antisymmetric mode
        in symmetric flight, where q_f1 vanishes by symmetry, or no flexible fuselage) so that the
        largest elastic coordinate is 1.
    labels : tuple of str
        DOF label of every entry of ``mode_shape``.
    normalised_by : str
        Label of the coordinate set to 1 in ``mode_shape``.
    mode_symmetry : {"symmetric", "antisymmetric", "mixed", "n/a"}
        From the physical mirror of the two halves' coordinates (:mod:`flexsim.structure.mirror`): at
        least 90 % of the mode's kinetic energy in the mirror-symmetric (antisymmetric) part; "n/a" for
        an aircraft that is not left-right symmetric.
    symmetric_fraction : float
        Share of the mode's kinetic energy in its mirror-symmetric part [-].
    participation : tuple of Participation
        Leading linear coordinates [m] then leading angles [deg] of ``mode_shape`` with their phase
        relative to the normalising coordinate (paper Figs. 11, 16; :mod:`flexsim.linear.participation`).
    formulation : {"physical", "paper"}
        Resolution of the strip airloads used (docs/design.md, "Force resolution").
    aero_density_kg_m3 : float
        Air density of the linearised aerodynamics of the eigen-analysis [kg/m^3]: the ISA density at the
        flight altitude unless the analysis fixed it (``linear_aero_density_kg_m3``).
    aero_density_fixed : bool
        True when that density was fixed by the analysis rather than the flight's true density.
    rigid_instabilities : tuple of (float, complex, str)
        (Mach, eigenvalue, dominant DOF) of unstable rigid-body modes met during the search.
    evaluations : int
        Number of trims + eigen-analyses.
    """

    aero_model: str
    mach: float
    speed_m_s: float
    frequency_rad_s: float
    trim: TrimPoint | None
    mode: Mode
    mode_shape: np.ndarray
    labels: tuple[str, ...]
    rigid_instabilities: tuple = field(default=())
    evaluations: int = 0
    normalised_by: str = ""
    mode_symmetry: str = "n/a"
    symmetric_fraction: float = math.nan
    participation: tuple[Participation, ...] = ()
    formulation: str = "physical"
    aero_density_kg_m3: float = math.nan
    aero_density_fixed: bool = False


class FlutterAnalysis:
    """Flutter of an aircraft in a steady manoeuvre, with the paper's aerodynamic models.

    Parameters
    ----------
    aircraft : Aircraft
    aero_model : {"quasi-steady", "unsteady", "theodorsen"}
        ``theodorsen`` is the paper's "US" model (p-k); ``unsteady`` the finite-state state space.
    n_inflow : int
        Finite-state inflow states per strip (``unsteady`` and the p-k input/output matrices).
    structural_damping : float, optional
        Modal damping ratio of the clamped elastic modes (default None: the aircraft's
        ``structural_damping_ratio``; 0 reproduces the paper's undamped structure).
    formulation : {"physical", "paper"}, optional
        Resolution of the strip airloads (docs/design.md, "Force resolution"); default None: the aircraft
        file's ``formulation``.
    linear_aero_density_kg_m3 : float, optional
        A paper-replication setting (docs/flutter.md): the air density [kg/m^3] of the *linearised*
        aerodynamics of every eigen-analysis, while each trim keeps the true density of its altitude.
        Default None: the flight's true density (the physical choice). Mach number and compressibility
        stay the flight's.
    """

    def __init__(self, aircraft: Aircraft, aero_model: str = "theodorsen", n_inflow: int = 6,
                 structural_damping: float | None = None, formulation: str | None = None,
                 linear_aero_density_kg_m3: float | None = None) -> None:
        if aero_model not in AERO_MODELS:
            raise ValueError(f"aero_model = {aero_model!r}: must be one of {', '.join(AERO_MODELS)}")
        self.aircraft = aircraft
        self.aero_model = aero_model
        self.linear_aero_density_kg_m3 = linear_aero_density_kg_m3
        qs_opts = AeroOptions("quasi-steady", formulation=formulation)
        self.qs = AircraftModel(aircraft, aero=qs_opts, structural_damping=structural_damping)
        self.formulation = self.qs.formulation
        lin = dict(structural_damping=structural_damping, aero_density_kg_m3=linear_aero_density_kg_m3)
        # the model of the eigen-analysis: the trim model unless the linearised aerodynamics' density is fixed
        self.qs_linear = self.qs if linear_aero_density_kg_m3 is None else AircraftModel(aircraft, aero=qs_opts, **lin)
        self.fs = (AircraftModel(aircraft, aero=AeroOptions("unsteady", n_inflow, formulation=formulation), **lin)
                   if aero_model != "quasi-steady" else None)

    def evaluate(self, manoeuvre: SteadyManoeuvre, guess: TrimPoint | None = None) -> tuple[TrimPoint, Spectrum]:
        """Trim (limits not enforced: the paper's climbs need negative thrust) and eigen-analysis.

        The trim uses the true density of the manoeuvre's altitude; the eigen-analysis the density of
        ``linear_aero_density_kg_m3`` when the analysis fixes it.
        """
        point = trim(self.qs, manoeuvre, guess=guess, check_limits=False)
        if self.aero_model == "quasi-steady":
            return point, spectrum(self.qs_linear, point.x, point.u, aero_model="quasi-steady")
        if self.aero_model == "unsteady":
            x = np.concatenate([point.x, np.zeros(self.fs.layout.n_inflow)])
            return point, spectrum(self.fs, x, point.u, aero_model="unsteady")
        return point, spectrum(self.qs_linear, point.x, point.u, aero_model="theodorsen", pk_model=self.fs)

    def search(self, manoeuvre: SteadyManoeuvre, *, mach_range: tuple[float, float] = (0.3, 0.95),
               mach_step: float = 0.05, tol: float = 1e-4, mach_guess: float | None = None) -> FlutterPoint:
        """Lowest flutter Mach number of ``manoeuvre`` (its speed is replaced by the searched one).

        With ``mach_guess`` (e.g. the flutter Mach of a neighbouring manoeuvre in a study) the crossing is
        first bracketed within +-0.01 of the guess, widening geometrically; it falls back to the full grid
        scan when the crossing found that way might not be the lowest (an unstable point below the guess
        is always re-checked down to the lower end of ``mach_range`` on the coarse grid).

        Speeds whose trim needs a control surface beyond its limit (too slow to fly the manoeuvre) are
        skipped; thrust limits are not enforced (the paper's descents need negative thrust).

        Raises
        ------
        FlutterNotFound
            When no elastic mode becomes unstable in ``mach_range``.
        """
        lo, hi = mach_range
        if not 0.0 < lo < hi < 1.0:
            raise ValueError(f"mach_range = {mach_range!r}: must satisfy 0 < lo < hi < 1")
        a_sound = speed_of_sound(float(manoeuvre.altitude_m))
        state = {"guess": None, "n": 0, "rigid": []}

        def g(mach: float) -> float:
            man = manoeuvre.with_speed(mach * a_sound)
            point, spec = self.evaluate(man, state["guess"])
            state["guess"], state["n"] = point, state["n"] + 1
            state["last"] = (point, spec)
            rig = spec.max_real("rigid", min_frequency_rad_s=0.0)
            if rig > 0:
                crit = max((m for m in spec.of_kind("rigid")), key=lambda m: m.eigenvalue.real)
                state["rigid"].append((mach, crit.eigenvalue, crit.dominant_dof))
            return spec.max_real("elastic")

        if mach_guess is not None and lo < mach_guess < hi:
            bracket = self._bracket_near(g, mach_guess, lo, hi)
            if bracket is not None:
                a, b = bracket
                # the crossing near the guess is the lowest one if the coarse grid below it is stable
                below = [m for m in np.arange(lo, a, mach_step)]
                if all(g(float(m)) <= 0 for m in below[-2:]):
                    state["guess"] = None
                    return self._point(manoeuvre, brentq(g, a, b, xtol=tol), a_sound, state)
        grid = np.arange(lo, hi + 1e-12, mach_step)
        prev_m, prev_g = None, None
        _, surf_hi = self.aircraft.control_limits()
        for mach in grid:
            val = g(float(mach))
            trim_point = state["last"][0]
            if np.any(np.abs(trim_point.u[1:]) > surf_hi[1:] + 1e-12):
                state["guess"] = None  # trim needs a surface beyond its limit: not flyable, skip this speed
                continue
            if val > 0:
                if prev_m is None:
                    raise FlutterNotFound(
                        f"{self.aero_model}: already unstable at the lower end of the search, M = {mach:.4f} "
                        f"({manoeuvre.describe()}); lower mach_range[0]"
                    )
                state["guess"] = None
                return self._point(manoeuvre, brentq(g, prev_m, float(mach), xtol=tol), a_sound, state)
            prev_m, prev_g = float(mach), val
        if prev_m is None:
            raise FlutterNotFound(f"{self.aero_model}: no flyable trim (surfaces within limits) for {lo:.3f} <= M <= {hi:.3f} ({manoeuvre.describe()})")
        raise FlutterNotFound(
            f"{self.aero_model}: no elastic mode crosses the imaginary axis for {lo:.3f} <= M <= {hi:.3f} "
            f"({manoeuvre.describe()}); largest elastic real part {prev_g:.4g} 1/s at M = {prev_m:.3f}"
        )

    @staticmethod
    def _bracket_near(g, guess: float, lo: float, hi: float) -> tuple[float, float] | None:
        """[a, b] with g(a) <= 0 < g(b) near ``guess``, widening by factors of 2 from +-0.01."""
        step = 0.01
        g0 = g(guess)
        a = b = guess
        for _ in range(6):
            if g0 > 0:
                a = max(lo, b - step)
                if g(a) <= 0:
                    return a, b
                b = a
            else:
                b = min(hi, a + step)
                if g(b) > 0:
                    return a, b
                a = b
            step *= 2
            if a <= lo or b >= hi:
                return None
        return None

    def _point(self, manoeuvre: SteadyManoeuvre, mach_f: float, a_sound: float, state: dict) -> FlutterPoint:
        point, spec = self.evaluate(manoeuvre.with_speed(mach_f * a_sound))
        mode = spec.critical("elastic")
        desc = describe_mode(self.qs.structure, mode.shape, mode.eigenvalue)
        return FlutterPoint(
            aero_model=self.aero_model,
            mach=float(mach_f),
            speed_m_s=float(mach_f * a_sound),
            frequency_rad_s=mode.frequency_rad_s,
            trim=point,
            mode=mode,
            mode_shape=desc.shape,
            labels=self.qs.structure.dofs.labels,
            normalised_by=self.qs.structure.dofs.labels[desc.normalised_by],
            mode_symmetry=desc.symmetry,
            symmetric_fraction=desc.symmetric_fraction,
            participation=desc.leading,
            formulation=self.formulation,
            aero_density_kg_m3=(float(isa_density(float(manoeuvre.altitude_m))) if self.linear_aero_density_kg_m3 is None
                                else float(self.linear_aero_density_kg_m3)),
            aero_density_fixed=self.linear_aero_density_kg_m3 is not None,
            rigid_instabilities=tuple(state["rigid"]),
            evaluations=state["n"] + 1,
        )


def wind_tunnel_flutter(aircraft: Aircraft, *, aero_model: str = "unsteady", speed_range: tuple[float, float] = (10.0, 300.0),
                        speed_step: float = 5.0, altitude_m: float = 0.0, tol_m_s: float = 1e-3, n_inflow: int = 6) -> tuple[float, float]:
    """Flutter speed [m/s] and frequency [rad/s] of a restrained aircraft (e.g. a clamped wing) in an airflow.

    The structure is clamped at the body origin and the air flows at -speed along body x (zero angle
    of attack, no gravity): the classical wind-tunnel flutter problem, e.g. the Goland wing.
    """
    if aero_model not in AERO_MODELS:
        raise ValueError(f"aero_model = {aero_model!r}: must be one of {', '.join(AERO_MODELS)}")

    def spec_at(speed: float) -> Spectrum:
        kw = dict(variant="restrained", gravity_m_s2=0.0, restrained_velocity_m_s=[speed, 0.0, 0.0], altitude_m=altitude_m)
        if aero_model == "theodorsen":
            qs = AircraftModel(aircraft, aero="quasi-steady", **kw)
            fs = AircraftModel(aircraft, aero=AeroOptions("unsteady", n_inflow), **kw)
            return spectrum(qs, qs.layout.zeros(), np.zeros(4), aero_model="theodorsen", pk_model=fs)
        model = AircraftModel(aircraft, aero=AeroOptions(aero_model, n_inflow), **kw)
        return spectrum(model, model.layout.zeros(), np.zeros(4), aero_model=aero_model)

    g: Callable[[float], float] = lambda sp: spec_at(sp).max_real("elastic")
    prev = None
    for speed in np.arange(speed_range[0], speed_range[1] + 1e-9, speed_step):
        if g(float(speed)) > 0:
            if prev is None:
                raise FlutterNotFound(f"already unstable at {speed} m/s; lower speed_range[0]")
            u_f = brentq(g, prev, float(speed), xtol=tol_m_s)
            return float(u_f), spec_at(u_f).critical("elastic").frequency_rad_s
        prev = float(speed)
    raise FlutterNotFound(f"no flutter for {speed_range[0]} <= U <= {speed_range[1]} m/s ({aero_model})")
