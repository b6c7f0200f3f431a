"""Flutter speed of a manoeuvring aircraft, and of a restrained structure in a wind tunnel.

Source: Tuzcu & Nguyen (2014), "Numerical Model": the flutter speed is the lowest speed of the nominal
(steady) flight at which an eigenvalue of the linearised equations crosses the imaginary axis. Here the
crossing must be made by an elastic-dominated mode (:mod:`flexsim.linear.stability`); rigid-body
instabilities (spiral, phugoid) met on the way are reported separately, never as flutter. The aircraft is
re-trimmed at every Mach number; the crossing is bracketed on a Mach grid anchored at the multiples of its step,
with a step control that looks between stable grid points (:mod:`flexsim.linear.scan`), and refined with Brent's
method to 1e-4 in Mach.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace
from typing import Callable

import numpy as np
from scipy.optimize import brentq

from flexsim._threads import single_blas_thread
from flexsim.errors import float_array
from flexsim.aircraft.definition import Aircraft, ContentKey
from flexsim.atmosphere import isa_density, speed_of_sound
from flexsim.errors import FlexsimError
from flexsim.linear.linearize import LinearModel, jacobian, linearize
from flexsim.linear.participation import Participation, describe_mode
from flexsim.linear.stability import Mode, Spectrum, linear_spectrum, spectrum
from flexsim.linear.scan import MIN_TRIM_SPEED_M_S, REFINE_LEVELS, _growth, anchored_grid, hidden_crossing, scan_step
from flexsim.linear.validity import mach_note
from flexsim.model.aircraft_model import AircraftModel, check_aircraft, check_model
from flexsim.model.coupling import AERO_MODELS, AeroOptions
from flexsim.model.terms import Terms
from flexsim.model.variant import VariantSettings
from flexsim.trimming import SteadyManoeuvre, TrimError, TrimPoint, trim
from flexsim.trimming.equilibrium import with_stability

__all__ = ["FlutterPoint", "FlutterNotFound", "FlutterAnalysis", "flutter", "scan_step", "anchored_grid", "hidden_crossing",
           "SharedEvaluations", "WindTunnelResult", "wind_tunnel", "wind_tunnel_flutter",
           "FlutterCondition", "flutter_condition"]


class FlutterNotFound(FlexsimError, RuntimeError):
    """No elastic mode crossed the imaginary axis in the searched range.

    Attributes
    ----------
    mach_range : (float, float) or None
        The searched Mach range (None when the search did not get as far as a range).
    """

    def __init__(self, message: str, mach_range: tuple[float, float] | None = None) -> None:
        super().__init__(message)
        self.mach_range = mach_range


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
    terms : dict
        The physical terms of the eigen-analysis's model (:meth:`flexsim.model.terms.Terms.record`).
    rigid_instabilities : tuple of (float, complex, str)
        (Mach, eigenvalue, dominant DOF) of unstable rigid-body modes met during the search.
    evaluations : int
        Number of trims + eigen-analyses.
    mach_range : (float, float)
        The Mach range of the search [-].
    warnings : tuple of str
        What makes the result doubtful, in words: a flutter Mach outside the range of the aerodynamics
        (:func:`flexsim.linear.validity.mach_note`), a trim at the flutter point that is itself unstable
        (a rigid-body instability: the flight is not held open-loop). Empty when none.
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
    mach_range: tuple[float, float] = (math.nan, math.nan)
    terms: dict = field(default_factory=dict)
    warnings: tuple[str, ...] = ()


@dataclass
class _SearchState:
    """What one flutter search carries between its evaluations: the last trim (warm start of the next), the
    number of evaluations, the last (trim, spectrum), the rigid-body instabilities met (Mach, eigenvalue,
    dominant coordinate), and every evaluation by its Mach number (Brent's method starts from the two ends of
    the bracket, already evaluated by the scan, and returns one of the Mach numbers it evaluated: neither is
    computed twice)."""

    guess: object = None
    n: int = 0
    last: tuple | None = None
    rigid: list = field(default_factory=list)
    done: dict = field(default_factory=dict)


class SharedEvaluations:
    """Trims and linearisations shared by the searches of one :class:`FlutterAnalysis` with several aerodynamic models.

    The quasi-steady ("QS") and p-k ("US") searches of one manoeuvre trim the same model at the same Mach numbers of
    their scan, each from the trim of the previous one, and linearise the same quasi-steady model there: passed to
    both searches (``search(..., shared=shared)``), such a point is computed once, and the second search gets
    exactly the trim and linearisation it would have computed. Entries are keyed by content: the manoeuvre (with
    its speed) and the state and controls of the warm-start trim; a linearisation by the trim's state and controls.
    Create one per batch of searches (e.g. one study job) and drop it afterwards: it grows with every point.

    Parameters
    ----------
    analysis : FlutterAnalysis
        The analysis whose models the entries belong to; the searches of other analyses refuse it.
    """

    def __init__(self, analysis: "FlutterAnalysis") -> None:
        self.analysis = analysis
        self._trims: dict[tuple, TrimPoint] = {}
        self._linear: dict[tuple, LinearModel] = {}
        self.hits = 0

    @staticmethod
    def _state_key(point: TrimPoint | None) -> tuple:
        if point is None:
            return ()
        return (point.x.tobytes(), point.u.tobytes(), point.theta, point.phi, point.gamma)

    def trim(self, manoeuvre: SteadyManoeuvre, guess: TrimPoint | None) -> TrimPoint:
        """``trim(analysis.qs, manoeuvre, guess=guess, check_limits=False)``, computed once per content."""
        key = (manoeuvre, self._state_key(guess))
        if key in self._trims:
            self.hits += 1
            return self._trims[key]
        point = self._trims[key] = trim(self.analysis.qs, manoeuvre, guess=guess, check_limits=False, classify=False)
        return point

    def linearize(self, point: TrimPoint) -> LinearModel:
        """``linearize(analysis.qs_linear, point.x, point.u)``, computed once per content."""
        key = (point.x.tobytes(), point.u.tobytes())
        if key in self._linear:
            self.hits += 1
            return self._linear[key]
        lin = self._linear[key] = linearize(self.analysis.qs_linear, point.x, point.u)
        return lin


class FlutterAnalysis:
    """Flutter of an aircraft in a steady manoeuvre, with the paper's aerodynamic models.

    Built from the model the user made (:meth:`from_model`, or :func:`flutter`) or from an aircraft definition.
    The analysis needs up to three models of the one aircraft: the quasi-steady model that every trim uses, the
    model of the eigen-analysis (the same one unless the density of the linearised aerodynamics is fixed), and
    the finite-state model of the "unsteady" analysis and of the p-k method's input and output matrices. From a
    model they are that model itself where it is of the kind needed, otherwise its siblings: the same aircraft
    object (not re-loaded) and every term of the model (:meth:`AircraftModel.replace`: the aerodynamic options,
    gravity, structural damping, force resolution, frozen compressibility Mach, thrust line, engine angular
    momentum, offsets), only the aerodynamic model (and a fixed linearisation density) changed.

    Parameters
    ----------
    aircraft : Aircraft or AircraftModel
        An aircraft definition, or a free-flying model with aerodynamics (then ``n_inflow`` of an "unsteady" model,
        ``structural_damping`` and ``formulation`` are the model's and must not be given).
    aero_model : {"quasi-steady", "unsteady", "theodorsen"}
        ``theodorsen`` is the paper's "US" model (p-k); ``unsteady`` the finite-state state space.
    n_inflow : int, optional
        Finite-state inflow states per strip (``unsteady`` and the p-k input/output matrices) [default 6, or the
        model's own for an ``unsteady`` model].
    structural_damping : float, optional
        Modal damping ratio of the clamped elastic modes (default None: the aircraft's
        ``structural_damping_ratio``; 0 reproduces the paper's undamped structure). Aircraft only.
    formulation : {"physical", "paper"}, optional
        Resolution of the strip airloads (docs/design.md, "Force resolution"); default None: the aircraft
        file's ``formulation``. Aircraft only.
    linear_aero_density_kg_m3 : float, optional
        A paper-replication setting (docs/flutter.md): the air density [kg/m^3] of the *linearised*
        aerodynamics of every eigen-analysis, while each trim keeps the true density of its altitude.
        Default None: the flight's true density (the physical choice). Mach number and compressibility
        stay the flight's.
    """

    def __init__(self, aircraft: Aircraft | AircraftModel, aero_model: str = "theodorsen", n_inflow: int | None = None,
                 structural_damping: float | None = None, formulation: str | None = None,
                 linear_aero_density_kg_m3: float | None = None) -> None:
        if aero_model not in AERO_MODELS:
            raise ValueError(f"aero_model = {aero_model!r}: must be one of {', '.join(AERO_MODELS)}")
        if isinstance(aircraft, AircraftModel):
            model = aircraft
            given = {k: v for k, v in (("structural_damping", structural_damping), ("formulation", formulation)) if v is not None}
            if given:
                raise ValueError(f"{', '.join(given)}: set on the model (AircraftModel(...)), not on the flutter analysis "
                                 "of a model")
            _check_flutter_model(model)
            options = model.aero.options
            if n_inflow is not None and options.model == "unsteady" and n_inflow != options.n_inflow:
                raise ValueError(f"n_inflow = {n_inflow!r}: the model has {options.n_inflow} inflow states per strip; "
                                 "build the model with the number wanted")
        else:
            options = AeroOptions("quasi-steady", formulation=formulation)
            model = AircraftModel(aircraft, aero=options, structural_damping=structural_damping)
        n_inflow = options.n_inflow if options.model == "unsteady" else (6 if n_inflow is None else n_inflow)
        self.model = model
        self.aircraft = model.aircraft
        self.aero_model = aero_model
        self.linear_aero_density_kg_m3 = linear_aero_density_kg_m3

        def sibling(name: str, n: int, density: float | None) -> AircraftModel:
            if options.model == name and (name != "unsteady" or options.n_inflow == n) and density is None:
                return model
            return model.replace(aero=replace(options, model=name, n_inflow=n), aero_density_kg_m3=density)

        #: The quasi-steady model of every trim.
        self.qs = sibling("quasi-steady", options.n_inflow, None)
        self.formulation = self.qs.formulation
        #: The model of the eigen-analysis: the trim model unless the linearised aerodynamics' density is fixed.
        self.qs_linear = self.qs if linear_aero_density_kg_m3 is None else sibling("quasi-steady", options.n_inflow,
                                                                                    linear_aero_density_kg_m3)
        #: The finite-state model ("unsteady" analysis, p-k input/output matrices), None for a quasi-steady analysis.
        self.fs = sibling("unsteady", n_inflow, linear_aero_density_kg_m3) if aero_model != "quasi-steady" else None

    @classmethod
    def from_model(cls, model: AircraftModel, aero_model: str = "theodorsen", *,
                   linear_aero_density_kg_m3: float | None = None) -> "FlutterAnalysis":
        """The flutter analysis of ``model`` (see the class): its aircraft and options, with ``aero_model``."""
        if not isinstance(model, AircraftModel):
            raise TypeError(f"model: an AircraftModel, not {type(model).__name__} (load_aircraft gives an Aircraft; "
                            "build AircraftModel(aircraft, ...) or pass the aircraft to FlutterAnalysis)")
        return cls(model, aero_model, linear_aero_density_kg_m3=linear_aero_density_kg_m3)

    def _model_name(self, aero_model: str | None) -> str:
        """The aerodynamic model of a search: ``aero_model`` when given (one this analysis has the models for)."""
        if aero_model is None:
            return self.aero_model
        allowed = ("quasi-steady",) if self.fs is None else AERO_MODELS
        if aero_model not in allowed:
            raise ValueError(f"aero_model = {aero_model!r}: this analysis ({self.aero_model}) has the models of "
                             f"{', '.join(allowed)} only")
        return aero_model

    @single_blas_thread
    def evaluate(self, manoeuvre: SteadyManoeuvre, guess: TrimPoint | None = None, *, aero_model: str | None = None,
                 shared: SharedEvaluations | None = None) -> tuple[TrimPoint, Spectrum]:
        """Trim (limits not enforced: the paper's climbs need negative thrust) and eigen-analysis.

        The trim uses the true density of the manoeuvre's altitude; the eigen-analysis the density of
        ``linear_aero_density_kg_m3`` when the analysis fixes it. ``aero_model`` (default: the analysis's) may name
        another model this analysis has the models for: "quasi-steady" always, all three when it was built for
        "unsteady" or "theodorsen". ``shared``: trims and linearisations already computed by another search of
        this analysis (:class:`SharedEvaluations`). The trim's ``stability`` is classified from this eigen-analysis.
        """
        name = self._model_name(aero_model)
        if shared is not None and shared.analysis is not self:
            raise ValueError("shared: a SharedEvaluations of another FlutterAnalysis (its trims belong to other models)")
        point = (trim(self.qs, manoeuvre, guess=guess, check_limits=False, classify=False) if shared is None
                 else shared.trim(manoeuvre, guess))
        if name == "unsteady":
            x = np.concatenate([point.x, np.zeros(self.fs.layout.n_inflow)])
            spec = spectrum(self.fs, x, point.u, aero_model="unsteady")
        else:
            pk = dict(pk_model=self.fs) if name == "theodorsen" else {}
            spec = (spectrum(self.qs_linear, point.x, point.u, aero_model=name, **pk) if shared is None
                    else linear_spectrum(self.qs_linear, shared.linearize(point), aero_model=name, **pk))
        return with_stability(self.qs, point, spec), spec  # the trim classified from this analysis's own roots

    @single_blas_thread
    def search(self, manoeuvre: SteadyManoeuvre, *, mach_range: tuple[float, float] = (0.3, 0.95),
               mach_step: float = 0.05, tol: float = 1e-4, mach_guess: float | None = None,
               aero_model: str | None = None, shared: SharedEvaluations | None = None) -> FlutterPoint:
        """Lowest flutter Mach number of ``manoeuvre`` (its speed is replaced by the searched one).

        With ``mach_guess`` (e.g. the flutter Mach of a neighbouring manoeuvre in a study) the crossing is
        first bracketed within +-0.01 of the guess, widening geometrically. That crossing is accepted when the two
        coarse-grid points just below its bracket are stable; otherwise the full grid scan from the lower end of
        ``mach_range`` runs. A flutter region lying wholly more than two grid steps below the bracket (a lower
        crossing that restabilises before it) is therefore not looked for with a guess; search without one to
        scan the whole grid.

        The scan points are the multiples of ``mach_step`` inside the range (:func:`flexsim.linear.scan.anchored_grid`),
        and between two stable ones the step control halves an interval whose growth-rate curvature could hide an
        instability (:func:`flexsim.linear.scan.hidden_crossing`, down to ``mach_step / 16``). Speeds whose trim needs a
        control surface beyond its limit, or below the first flyable one has no trim or is under 1 m/s (too slow to
        fly the manoeuvre), are skipped; thrust limits are not enforced (the paper's descents need negative thrust).

        ``aero_model`` and ``shared`` as in :meth:`evaluate`: e.g. the "QS" and "US" searches of one manoeuvre on a
        "theodorsen" analysis, passed the same :class:`SharedEvaluations`, compute the trims and linearisations of
        their common scan points once (the results are those of separate searches, bit for bit).

        Raises
        ------
        FlutterNotFound
            When no elastic mode becomes unstable in ``mach_range``, or a trim of the grid scan is statically
            divergent before any crossing (``TrimPoint.stability``; the message names its roots).
        """
        lo, hi, mach_step, tol = _scan_settings("mach_range", mach_range, "mach_step", mach_step, "tol", tol, "[-]", upper=1.0)
        name = self._model_name(aero_model)
        a_sound = speed_of_sound(float(manoeuvre.altitude_m))
        state = _SearchState()

        def g(mach: float) -> float:
            mach = float(mach)
            if mach in state.done:
                state.last = state.done[mach]
                return _growth(state.last[1])
            man = manoeuvre.with_speed(mach * a_sound)
            point, spec = self.evaluate(man, state.guess, aero_model=name, shared=shared)
            state.guess, state.n = point, state.n + 1
            state.last = state.done[mach] = (point, spec)
            rig = spec.max_real("rigid", min_frequency_rad_s=0.0)
            if rig > 0:
                crit = max((m for m in spec.of_kind("rigid")), key=lambda m: m.eigenvalue.real)
                state.rigid.append((mach, crit.eigenvalue, crit.dominant_dof))
            return _growth(spec)

        if mach_guess is not None and lo < mach_guess < hi:
            bracket = self._bracket_near(g, mach_guess, lo, hi)
            if bracket is not None:
                a, b = bracket
                # the crossing near the guess is the lowest one if the coarse grid below it is stable
                below = [m for m in np.arange(lo, a, mach_step)]
                if all(g(float(m)) <= 0 for m in below[-2:]):
                    near = [(float(m), g(float(m))) for m in below[-2:] if float(m) < a] + [(a, g(a))]
                    a, b = hidden_crossing(g, near, mach_step / 2 ** REFINE_LEVELS) or (a, b)  # step control there too
                    return self._point(manoeuvre, brentq(g, a, b, xtol=tol), a_sound, state, name, shared, (lo, hi))
        grid = anchored_grid(lo, hi, mach_step)  # the same points above lo whatever lo is; ends at hi
        prev_m, prev_g = None, None
        skipped: list[float] = []
        points: list[tuple[float, float]] = []  # flyable, stable scan points since the last skipped one
        min_step = mach_step / 2 ** REFINE_LEVELS
        _, surf_hi = self.aircraft.control_limits()
        for mach in grid:
            if prev_m is None and mach * a_sound < MIN_TRIM_SPEED_M_S:
                skipped.append(float(mach))  # below the slowest manoeuvre flexsim trims: not flyable
                continue
            try:
                val = g(float(mach))
            except TrimError:
                if prev_m is not None:
                    raise
                state.guess = None  # no trim at the slow end of the range: not flyable, skip this speed
                skipped.append(float(mach))
                continue
            trim_point = state.last[0]
            if np.any(np.abs(trim_point.u[1:]) > surf_hi[1:] + 1e-12):
                state.guess = None  # trim needs a surface beyond its limit: not flyable, skip this speed
                skipped.append(float(mach))
                points = []
                continue
            if trim_point.stability.is_divergent:  # not an equilibrium the aircraft stays in: no flutter above it
                where = "the lower end of the search" if prev_m is None else "below any flutter crossing"
                raise FlutterNotFound(f"{name}: the trim at M = {mach:.4f} ({where}, {manoeuvre.describe()}) is not a valid "
                                      f"equilibrium: {trim_point.stability.message}")
            if val > 0:
                if prev_m is None:
                    if skipped:
                        raise FlutterNotFound(
                            f"{name}: unstable at M = {mach:.4f}, the first flyable Mach number of the search "
                            f"({manoeuvre.describe()}); the lower Mach numbers {skipped[0]:.3f} to {skipped[-1]:.3f} cannot "
                            "be flown (no trim, or a control surface beyond its limit), so the crossing cannot be bracketed there "
                            f"(a lower mach_range[0] would not help; searched {lo:.3f} <= M <= {hi:.3f})", (lo, hi)
                        )
                    raise FlutterNotFound(
                        f"{name}: already unstable at the lower end of the search, M = {mach:.4f} "
                        f"({manoeuvre.describe()}; searched {lo:.3f} <= M <= {hi:.3f}); lower mach_range[0]", (lo, hi)
                    )
                a, b = hidden_crossing(g, points, min_step) or (prev_m, float(mach))  # step control
                return self._point(manoeuvre, brentq(g, a, b, xtol=tol), a_sound, state, name, shared, (lo, hi))
            prev_m, prev_g = float(mach), val
            points.append((prev_m, val))
        hidden = hidden_crossing(g, points, min_step)
        if hidden is not None:
            return self._point(manoeuvre, brentq(g, *hidden, xtol=tol), a_sound, state, name, shared, (lo, hi))
        if prev_m is None:
            raise FlutterNotFound(f"{name}: no flyable trim (surfaces within limits) for {lo:.3f} <= M <= {hi:.3f} "
                                  f"({manoeuvre.describe()})", (lo, hi))
        if not math.isfinite(prev_g):
            raise FlutterNotFound(f"{name}: {self.aircraft.name} has no oscillatory elastic mode at M = {prev_m:.3f} "
                                  f"({manoeuvre.describe()}), so no flutter to find (rigid components only, or every "
                                  "elastic root real)", (lo, hi))
        raise FlutterNotFound(
            f"{name}: no elastic mode crosses the imaginary axis for {lo:.3f} <= M <= {hi:.3f} "
            f"({manoeuvre.describe()}); largest elastic real part {prev_g:.4g} 1/s at M = {prev_m:.3f}", (lo, hi)
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

    def _point(self, manoeuvre: SteadyManoeuvre, mach_f: float, a_sound: float, state: _SearchState, name: str,
               shared: SharedEvaluations | None, mach_range: tuple[float, float]) -> FlutterPoint:
        mach_f = float(mach_f)
        if mach_f not in state.done:  # Brent returns a Mach number it evaluated; kept for other root finders
            state.done[mach_f] = self.evaluate(manoeuvre.with_speed(mach_f * a_sound), state.guess, aero_model=name,
                                               shared=shared)
            state.n += 1
        point, spec = state.done[mach_f]
        mode = spec.critical("elastic")
        point = with_stability(self.qs, point, spec, neutral=mode.eigenvalue)  # the crossing mode is neutral here
        desc = describe_mode(self.qs.structure, mode.shape, mode.eigenvalue)
        notes = [mach_note("flutter", mach_f, self.qs.aero.compressibility)]
        if point.stability is not None and point.stability.verdict not in ("stable", "slowly unstable"):
            notes.append(f"the trim at the flutter point is not a stable equilibrium ({point.stability.aero_model} roots): "
                         f"{point.stability.message}; the flutter Mach is that of a flight the aircraft does not hold "
                         "without control")
        return FlutterPoint(
            warnings=tuple(n for n in notes if n),
            aero_model=name,
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
            terms=self.qs_linear.terms.record(),
            rigid_instabilities=tuple(state.rigid),
            evaluations=state.n,
            mach_range=(float(mach_range[0]), float(mach_range[1])),
        )


def _check_flutter_model(model: AircraftModel) -> None:
    """Refuse a model a flutter search of a manoeuvre cannot use, naming what is wrong."""
    check_model(model)
    if model.variant.kind.value != "free":
        raise ValueError(f"model.variant = {model.variant.kind.value!r}: a flutter search of a manoeuvre needs the free aircraft; "
                         "a restrained structure in an airflow is flexsim.wind_tunnel(aircraft, ...)")
    if model.aero is None:
        raise ValueError("model.aero = None: a model without aerodynamics has no flutter; build it with aero=\"quasi-steady\" "
                         "or \"unsteady\"")
    if model.terms.aero_density_kg_m3 is not None:
        raise ValueError(f"model.terms.aero_density_kg_m3 = {model.terms.aero_density_kg_m3!r}: trims need the true density; fix the "
                         "density of the linearised aerodynamics with linear_aero_density_kg_m3 of the analysis instead")


def _scan_settings(range_name: str, rng, step_name: str, step, tol_name: str, tol, unit: str,
                   upper: float | None = None) -> tuple[float, float, float, float]:
    """(lo, hi, step, tol) of a scan, each checked where it enters: ``rng`` two finite numbers 0 < lo < hi (< ``upper``),
    ``step`` a finite number in (0, hi - lo], ``tol`` a finite number in (0, step]; a ValueError names the argument,
    its value and the allowed range otherwise (``unit``: e.g. ``"[m/s]"``)."""
    lo, hi = float_array(range_name, rng, (2,), what=f"(lo, hi) {unit}")
    if not (0.0 < lo < hi and (upper is None or hi < upper)):
        raise ValueError(f"{range_name} = {tuple(rng)!r}: must satisfy 0 < lo < hi{f' < {upper:g}' if upper else ''} {unit}")
    for name, value, top in ((step_name, step, hi - lo), (tol_name, tol, None)):
        if isinstance(value, bool) or not isinstance(value, (int, float, np.floating, np.integer)):
            raise ValueError(f"{name} = {value!r}: must be a number {unit}")
        top = step if top is None else top
        if not (math.isfinite(value) and 0.0 < value <= top):
            raise ValueError(f"{name} = {value!r}: must be a finite number in (0, {top:g}] {unit}"
                             + (f" (at most the width of {range_name})" if name == step_name else f" (at most {step_name})"))
    return float(lo), float(hi), float(step), float(tol)


@single_blas_thread
def flutter(model: AircraftModel, manoeuvre: SteadyManoeuvre, aero_model: str = "theodorsen", *,
            mach_range: tuple[float, float] | None = None, mach_step: float | None = None, tol: float = 1e-4,
            linear_aero_density_kg_m3: float | None = None) -> FlutterPoint:
    """Lowest flutter Mach number of ``model`` flying ``manoeuvre`` (Tuzcu & Nguyen 2014, "Numerical Model").

    Parameters
    ----------
    model : AircraftModel
        The free aircraft with its aerodynamic options (``AircraftModel(aircraft, aero=...)``): its aircraft, force
        resolution, compressibility, damping and gravity are used, no file is re-loaded (:class:`FlutterAnalysis`).
    manoeuvre : SteadyManoeuvre
        The steady manoeuvre (level, turn, climb, glide); its altitude and kind are kept and its speed searched.
    aero_model : {"theodorsen", "unsteady", "quasi-steady"}
        The paper's "US" p-k model (default), finite state ("FS") or quasi-steady ("QS").
    mach_range : (float, float), optional
        Searched Mach numbers; default the aircraft's envelope at the altitude
        (:func:`flexsim.linear.envelope.search_range`).
    mach_step : float, optional
        Scan step in Mach [-]; default :func:`scan_step` of the range.
    tol : float
        Brent tolerance in Mach [-].
    linear_aero_density_kg_m3 : float, optional
        Paper-replication setting of :class:`FlutterAnalysis`.

    Returns
    -------
    FlutterPoint or FlexibleFlutterPoint
        With ``mach_range``, the range searched. For a model with ``terms.nonlinear_beams`` (aero_model
        ``"unsteady"`` only), the flutter of its wing about the nonlinear trim at each scanned speed
        (:func:`flexsim.linear.flexible_flutter.flexible_flutter`; the Mach range, step and tolerance become true
        airspeeds at the altitude, the default range the envelope of the model's linear sibling).

    Raises
    ------
    FlutterNotFound
        When no elastic mode crosses in the range; its message and ``mach_range`` say where it searched.
    """
    from flexsim.linear.envelope import search_range

    if isinstance(model, AircraftModel) and model.terms.nonlinear_beams is not None:
        return _nonlinear_flutter(model, manoeuvre, aero_model, mach_range, mach_step, tol, linear_aero_density_kg_m3)
    _check_flutter_model(model)
    if mach_range is None:
        mach_range = (lambda r: (r.mach_min, r.mach_max))(search_range(model, manoeuvre))
    analysis = FlutterAnalysis(model, aero_model, linear_aero_density_kg_m3=linear_aero_density_kg_m3)
    step = scan_step(mach_range) if mach_step is None else mach_step
    return analysis.search(manoeuvre, mach_range=mach_range, mach_step=step, tol=tol)


def _nonlinear_flutter(model: AircraftModel, manoeuvre: SteadyManoeuvre, aero_model: str, mach_range, mach_step, tol,
                       linear_aero_density_kg_m3):
    """:func:`flutter` of a model with the geometrically nonlinear beams: the wing's flutter about the nonlinear trim
    (:func:`flexsim.linear.flexible_flutter.flexible_flutter`), its Mach range, step and tolerance as true airspeeds at
    the manoeuvre's altitude."""
    from flexsim.linear.envelope import search_range
    from flexsim.linear.flexible_flutter import flexible_flutter

    beams = model.terms.nonlinear_beams
    if aero_model != "unsteady":
        raise ValueError(f"aero_model = {aero_model!r}: the flutter of the geometrically nonlinear beams (nonlinear_beams "
                         f"= {beams!r}) is solved with Peters finite-state strips; give aero_model='unsteady'")
    if linear_aero_density_kg_m3 is not None:
        raise ValueError(f"linear_aero_density_kg_m3 = {linear_aero_density_kg_m3!r}: the linear model's paper-replication "
                         f"setting; not available with nonlinear_beams = {beams!r}")
    if model.variant.kind.value != "free":
        raise ValueError(f"model.variant = {model.variant.kind.value!r}: a flutter search of a manoeuvre needs the free "
                         "aircraft")
    if mach_range is None:  # the envelope (or the stall estimate) of the model's linear sibling
        found = search_range(model.replace(nonlinear_beams=None), manoeuvre)
        mach_range = (found.mach_min, found.mach_max)
    step = scan_step(mach_range) if mach_step is None else mach_step
    lo, hi, step, tol = _scan_settings("mach_range", mach_range, "mach_step", step, "tol", tol, "[-]", upper=1.0)
    a = float(speed_of_sound(float(manoeuvre.altitude_m)))
    return flexible_flutter(model, manoeuvre, (lo * a, hi * a), speed_step_m_s=step * a, tol_m_s=tol * a)


@dataclass(frozen=True, eq=False)
class WindTunnelResult:
    """Flutter and divergence of a restrained structure in an airflow (:func:`wind_tunnel`).

    Attributes
    ----------
    aero_model : str
    density_kg_m3 : float
        Air density of the tunnel [kg/m^3].
    compressibility : str
        Compressibility correction in force ("prandtl-glauert" or "none").
    flutter_speed_m_s, flutter_frequency_rad_s : float or None
        Lowest speed at which an oscillatory elastic mode crosses the imaginary axis [m/s], and its
        frequency [rad/s]; None when no crossing lies in the speed range.
    divergence_speed_m_s : float or None
        Lowest speed at which the static aeroelastic stiffness becomes singular [m/s] (a real root
        through zero); None when it lies outside the speed range or was not searched.
    speed_range_m_s : tuple of float
        The searched range [m/s].
    terms : dict
        The physical terms of the tunnel's model of ``aero_model`` (:meth:`flexsim.model.terms.Terms.record`).
    warnings : tuple of str
        A flutter or divergence speed outside the range of the aerodynamics
        (:func:`flexsim.linear.validity.mach_note`), or a structure without an oscillatory elastic mode; empty
        when none.
    """

    aero_model: str
    density_kg_m3: float
    compressibility: str
    flutter_speed_m_s: float | None
    flutter_frequency_rad_s: float | None
    divergence_speed_m_s: float | None
    speed_range_m_s: tuple[float, float]
    terms: dict = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    @property
    def first_instability(self) -> str:
        """Which instability comes first: "flutter", "divergence" or "none"."""
        f, d = self.flutter_speed_m_s, self.divergence_speed_m_s
        if f is None and d is None:
            return "none"
        if d is None or (f is not None and f <= d):
            return "flutter"
        return "divergence"


@single_blas_thread
def wind_tunnel(aircraft: Aircraft | AircraftModel, *, aero_model: str = "unsteady", speed_range: tuple[float, float] = (10.0, 300.0),
                speed_step: float = 5.0, density_kg_m3: float | None = None, altitude_m: float = 0.0,
                compressibility: str = "file", tol_m_s: float = 1e-3, n_inflow: int = 6,
                flutter: bool = True, divergence: bool = True) -> WindTunnelResult:
    """Flutter and divergence speeds of a restrained aircraft (e.g. a clamped wing) in an airflow.

    The structure is clamped at the body origin and the air flows at -speed along body x (zero angle of
    attack, no gravity): the classical wind-tunnel problem, e.g. the Goland wing. Flutter: the lowest
    speed at which an oscillatory elastic mode crosses the imaginary axis (scan on ``speed_step``, Brent
    to ``tol_m_s``). Divergence: the lowest speed at which det K_eff(U) = 0, K_eff = K - K_aero(U) the
    static aeroelastic stiffness, i.e. a real root passing through zero. It is taken from the
    quasi-steady model whatever ``aero_model``: in steady flow the wake lag vanishes (C(0) = 1, Peters'
    lambda0 -> 0), so every model has the same static stiffness (Hodges & Pierce, *Introduction to
    Structural Dynamics and Aeroelasticity*, 2nd ed., 2011, ch. 4).

    Parameters
    ----------
    aircraft : Aircraft or AircraftModel
        An aircraft definition (its tunnel models have every term at its default but gravity, 0), or a model: the
        tunnel evaluates that model's siblings (:meth:`AircraftModel.replace`: its variant replaced by this tunnel's,
        restrained at each speed at ``altitude_m`` and ``density_kg_m3``, and the aerodynamic model ``aero_model``),
        with every term of the model as given, gravity included.
    aero_model : {"quasi-steady", "unsteady", "theodorsen"}
    speed_range : (float, float)
        Searched speeds [m/s], 0 < lo < hi.
    speed_step : float
        Scan step [m/s], > 0.
    density_kg_m3 : float, optional
        Tunnel air density [kg/m^3]; default the ISA density at ``altitude_m``.
    altitude_m : float
        ISA altitude [m] for the density (when not given) and the speed of sound (Mach for the
        compressibility correction).
    compressibility : {"file", "prandtl-glauert", "none"}
        See :class:`~flexsim.model.coupling.AeroOptions` (for a model: ``"file"`` keeps the model's own setting).
    n_inflow : int
        Finite-state inflow states per strip of the "unsteady" models (for an "unsteady" model: its own).
    flutter, divergence : bool
        Search the flutter speed, the divergence speed (default both).

    Raises
    ------
    ValueError
        For a bad argument (named, with the allowed range).
    """
    if aero_model not in AERO_MODELS:
        raise ValueError(f"aero_model = {aero_model!r}: must be one of {', '.join(AERO_MODELS)}")
    if not isinstance(aircraft, AircraftModel):
        check_aircraft(aircraft)
    lo, hi, speed_step, tol_m_s = _scan_settings("speed_range", speed_range, "speed_step", speed_step, "tol_m_s", tol_m_s, "[m/s]")
    tunnel = VariantSettings("restrained", altitude_m=altitude_m, air_density_kg_m3=density_kg_m3)
    if isinstance(aircraft, AircraftModel):
        given = check_model(aircraft, "aircraft")
        if given.aero is None:
            raise ValueError("aircraft: a model without aerodynamics (aero None) has nothing for a wind tunnel to act on")
        options = given.terms.aero
        if compressibility != "file":
            options = replace(options, compressibility=compressibility)
        if options.model == "unsteady":
            n_inflow = options.n_inflow
        aircraft = given.aircraft
    else:
        given = AircraftModel(aircraft, aero=AeroOptions("quasi-steady", compressibility=compressibility), gravity_m_s2=0.0,
                              variant=replace(tunnel, restrained_velocity_m_s=(lo, 0.0, 0.0)))
        options = given.terms.aero

    def model(speed: float, name: str) -> AircraftModel:
        return given.replace(aero=replace(options, model=name, n_inflow=n_inflow),
                             variant=replace(tunnel, restrained_velocity_m_s=(speed, 0.0, 0.0)))

    probe = model(lo, "quasi-steady")
    if probe.aero is None or probe.aero.strips.n_strips == 0:
        raise ValueError(f"aircraft {aircraft.name!r} has no aerodynamic strips: a wind tunnel has nothing to act on")
    rho = probe.air_density(probe.layout.zeros())  # the tunnel's, else the model's fixed aerodynamic density, else ISA
    if probe.active_dofs.size == 0:  # clamped and rigid: nothing can move, so neither flutter nor divergence
        used = replace(options, model="unsteady" if aero_model == "unsteady" else "quasi-steady", n_inflow=n_inflow)
        return WindTunnelResult(aero_model, float(rho), probe.aero.compressibility, None, None, None, (lo, hi),
                                replace(given.terms, aero=used).record(),
                                (f"{aircraft.name} has no elastic degree of freedom (every component rigid, clamped at the "
                                 "body origin): no flutter or divergence to find",))

    def spec_at(speed: float) -> Spectrum:
        if aero_model == "theodorsen":
            qs = model(speed, "quasi-steady")
            return spectrum(qs, qs.layout.zeros(), np.zeros(4), aero_model="theodorsen", pk_model=model(speed, "unsteady"))
        m = model(speed, aero_model)
        return spectrum(m, m.layout.zeros(), np.zeros(4), aero_model=aero_model)

    speeds = anchored_grid(lo, hi, speed_step)
    u_f = w_f = None
    done: dict[float, float] = {}

    def g(sp: float) -> float:
        sp = float(sp)
        if sp not in done:
            done[sp] = _growth(spec_at(sp))
        return done[sp]

    points: list[tuple[float, float]] = []
    bracket = None
    for speed in speeds if flutter else ():
        val = g(float(speed))
        if val > 0:
            if not points:
                raise FlutterNotFound(f"{aero_model}: an elastic mode is already unstable at the lowest speed "
                                      f"{speed:g} m/s (growth rate {val:.3g} 1/s); lower speed_range[0]")
            bracket = (points[-1][0], float(speed))
            break
        points.append((float(speed), val))
    if flutter:  # step control: an instability between two stable scan points (hidden_crossing)
        bracket = hidden_crossing(g, points, speed_step / 2 ** REFINE_LEVELS) or bracket
    if bracket is not None:
        u_f = float(brentq(g, *bracket, xtol=tol_m_s))
        w_f = spec_at(u_f).critical("elastic").frequency_rad_s
    u_d = _divergence_speed(lambda sp: model(sp, "quasi-steady"), speeds, tol_m_s) if divergence else None
    comp = probe.aero.compressibility
    used = replace(options, model="unsteady" if aero_model == "unsteady" else "quasi-steady", n_inflow=n_inflow)
    a_sound = speed_of_sound(float(altitude_m))
    notes = [mach_note(what, v / a_sound, comp) for what, v in (("flutter", u_f), ("divergence", u_d)) if v is not None]
    if flutter and points and not any(math.isfinite(v) for _, v in points):
        notes.append(f"{aircraft.name} has no oscillatory elastic mode in the stream (rigid components only, or every "
                     "elastic root real): no flutter to find")
    return WindTunnelResult(aero_model, float(rho), comp, u_f, w_f, u_d, (lo, hi), replace(given.terms, aero=used).record(),
                            tuple(n for n in notes if n))


def _static_stiffness_sign(model: AircraftModel) -> float:
    """sign(det K_eff) |det K_eff|^(1/n) of the static aeroelastic stiffness per unit mass [1/s^2].

    K_eff = -d(V_dot)/d[q; xi] at rest in the stream: M^-1 (K - K_aero) of the restrained quasi-steady
    model; its determinant is positive at zero speed and changes sign at divergence.
    """
    lay = model.layout
    x0 = model.layout.zeros()
    a, _ = jacobian(model, x0, np.zeros(4))
    conf = np.arange(lay.q.start, lay.xi.stop)
    rows = np.arange(lay.velocity.start, lay.velocity.stop)
    k_eff = -a[np.ix_(rows, conf)]
    sign, logdet = np.linalg.slogdet(k_eff)
    return float(sign * np.exp(logdet / conf.size))


def _divergence_speed(model_at: Callable[[float], AircraftModel], speeds: np.ndarray, tol_m_s: float) -> float | None:
    """Lowest speed in ``speeds`` (scan + Brent) at which det K_eff changes sign, or None."""
    f = lambda sp: _static_stiffness_sign(model_at(sp))
    prev = None
    for speed in speeds:
        val = f(float(speed))
        if val <= 0.0:
            if prev is None:
                return float(speed)
            return float(brentq(f, prev, float(speed), xtol=tol_m_s))
        prev = float(speed)
    return None


def wind_tunnel_flutter(aircraft: Aircraft, *, aero_model: str = "unsteady", speed_range: tuple[float, float] = (10.0, 300.0),
                        speed_step: float = 5.0, altitude_m: float = 0.0, tol_m_s: float = 1e-3, n_inflow: int = 6,
                        density_kg_m3: float | None = None, compressibility: str = "file") -> tuple[float, float]:
    """Flutter speed [m/s] and frequency [rad/s] of a restrained aircraft in an airflow (see :func:`wind_tunnel`).

    Raises
    ------
    FlutterNotFound
        When no elastic mode crosses the imaginary axis in ``speed_range``.
    """
    res = wind_tunnel(aircraft, aero_model=aero_model, speed_range=speed_range, speed_step=speed_step, altitude_m=altitude_m,
                      tol_m_s=tol_m_s, n_inflow=n_inflow, density_kg_m3=density_kg_m3, compressibility=compressibility,
                      divergence=False)
    if res.flutter_speed_m_s is None:
        raise FlutterNotFound(f"no flutter for {speed_range[0]} <= U <= {speed_range[1]} m/s ({aero_model})")
    return res.flutter_speed_m_s, res.flutter_frequency_rad_s


@dataclass(frozen=True)
class FlutterCondition:
    """The open-loop flutter point of level flight at one altitude (:meth:`FlutterAnalysis.search`, from M 0.6), the
    target of the environments' flutter-margin tasks.

    Attributes
    ----------
    mach, speed_m_s, frequency_rad_s : float
        Flutter Mach number, true airspeed [m/s] and frequency [rad/s].
    mode : str
        Name of the crossing mode (:func:`flexsim.structure.mode_names.mode_name`, e.g.
        ``"wings torsion 1 (antisymmetric)"``).
    """

    mach: float
    speed_m_s: float
    frequency_rad_s: float
    mode: str


@functools.lru_cache(maxsize=8)
def _cached_condition(key: ContentKey, terms: Terms | None, aero: str, altitude_m: float,
                      mach_range: tuple[float, float]) -> FlutterCondition:
    return _search(key.aircraft if terms is None else AircraftModel(key.aircraft, terms=terms), aero, altitude_m, mach_range)


def _search(aircraft: Aircraft | AircraftModel, aero: str, altitude_m: float, mach_range: tuple[float, float]) -> FlutterCondition:
    analysis = FlutterAnalysis.from_model(aircraft, aero) if isinstance(aircraft, AircraftModel) else FlutterAnalysis(aircraft, aero)
    aircraft = analysis.aircraft
    try:
        point = analysis.search(SteadyManoeuvre.level(altitude_m, mach=0.6), mach_range=mach_range, mach_step=0.02)
    except FlutterNotFound as exc:
        raise ValueError(f"aero = {aero!r}: no usable open-loop flutter point of {aircraft.name} at {altitude_m:g} m for Mach in "
                         f"{mach_range} ({exc}); the GTM flutter points are those of the finite-state model, aero = 'unsteady'") from None
    return FlutterCondition(point.mach, point.speed_m_s, point.frequency_rad_s, point.mode.name)


def flutter_condition(aircraft: Aircraft | AircraftModel, aero: str, altitude_m: float,
                      mach_range: tuple[float, float]) -> FlutterCondition:
    """Flutter point of level flight of ``aircraft``, or of a free model with all its terms (cached by the aircraft's
    content, the model's terms, aerodynamic model, altitude and range: a modified aircraft or model gets its own point)."""
    key = (float(altitude_m), tuple(float(m) for m in mach_range))
    if isinstance(aircraft, AircraftModel):
        _check_flutter_model(aircraft)
        return _cached_condition(aircraft.aircraft.content_key(), aircraft.terms, aero, *key)
    return _cached_condition(aircraft.content_key(), None, aero, *key)
