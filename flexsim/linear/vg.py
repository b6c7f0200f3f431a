"""V-g / V-f diagrams: damping and frequency of every root against speed, branches tracked by their eigenvectors.

The standard output of a flutter analysis (NASTRAN SOL 145's "FLUTTER SUMMARY", ZAERO's V-g plots): the roots of
the linearised aircraft at a sweep of speeds at one altitude, each root followed from speed to speed as one branch,
its damping and frequency plotted against speed; a branch whose damping changes sign is a flutter (or a
rigid-body) crossing. Source of the eigen-analysis: Tuzcu & Nguyen (2014), "Numerical Model" (the flutter speed is
where an eigenvalue of the linearised equations crosses the imaginary axis), with the three aerodynamic models of
:mod:`flexsim.linear.stability` (QS, FS finite state, US Theodorsen p-k).

Quantities, per root lambda [1/s] of a branch:

* frequency omega = |Im(lambda)| [rad/s];
* damping g = 2 Re(lambda) / |Im(lambda)| [-]: the "DAMPING" column of the p-k method (NASTRAN's g, the structural
  damping that would make the root neutral; Hassig, J. Aircraft 8(11), 1971, eq. 10 with p = omega (gamma + i),
  g = 2 gamma), positive = unstable; and the damping ratio zeta = -Re(lambda) / |lambda| [-], positive = stable.

Tracking. Branches are continued from one speed to the next by the correlation of their eigenvectors, not by
sorting on frequency: the modal assurance criterion MAC(a, b) = |a^H b|^2 / ((a^H a)(b^H b)) (Allemang & Brown,
1982) of the velocity part of the eigenvectors (V = [v, omega, s, eta], eq. 9: the same coordinates at every
speed), less a small penalty on the distance of the eigenvalue from the branch's linear extrapolation (which
decides only when two candidates have nearly equal MAC, e.g. at a coalescence, where the two eigenvectors become
alike). The pairing maximises the total score over all branches at once (the assignment problem,
:func:`scipy.optimize.linear_sum_assignment`); a root with MAC below :data:`MIN_MAC` to every branch starts a new
branch. A branch is labelled by the name of its first root (:func:`flexsim.structure.mode_names.mode_name`, the
name every output gives a mode, e.g. "wings torsion 1 (antisymmetric)"); a refined crossing by the name of the root
at the crossing, the name the flutter search gives the same point.

Crossings. Where Re(lambda) of a branch changes sign between two speeds, the crossing is refined by regula falsi
(Illinois variant) on the speed, the root at each new speed being the one with the largest MAC to the branch's root
at the bracket's end (to :data:`CROSSING_TOL_M_S`, at most :data:`CROSSING_ITERATIONS` evaluations); where that
continuation fails (MAC below :data:`MIN_MAC`) the linear interpolation of Re(lambda) between the bracketing
speeds is kept and the crossing says so (``refined`` False).

Which roots: every oscillatory elastic root (Im(lambda) >= 0.5 rad/s, upper half-plane) and, for a free aircraft,
the short-period and Dutch-roll roots: the rigid-body oscillatory roots with the largest frequency whose kinetic
energy in the rigid-body coordinates is mostly longitudinal (u, w, q; more in heave and pitch than in forward
speed, which would be the phugoid) or lateral (v, p, r) respectively. A free
aircraft is re-trimmed at every speed (the quasi-steady trim of :class:`~flexsim.linear.flutter.FlutterAnalysis`);
a restrained one (a wind tunnel: the Goland wing) is analysed in the stream at each speed with the density and
altitude of the model given.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Sequence

import numpy as np
from scipy.optimize import linear_sum_assignment

from flexsim.atmosphere import speed_of_sound
from flexsim.linear.stability import Mode, Spectrum, spectrum
from flexsim.linear.validity import mach_note
from flexsim.model.aircraft_model import AircraftModel, check_model
from flexsim.trimming import SteadyManoeuvre, TrimError

__all__ = ["VgCrossing", "VgTrack", "VgDiagram", "vg_diagram", "track_branches", "mac", "MIN_MAC", "VG_MODELS"]

#: The aerodynamic models of a V-g diagram, by their short names (docs/flutter.md).
VG_MODELS = {"QS": "quasi-steady", "FS": "unsteady", "US": "theodorsen"}
#: Smallest MAC at which a root continues a branch [-]; below it, it starts a new one.
MIN_MAC = 0.3
#: Weight of the eigenvalue-distance penalty against MAC in the pairing score [-] (module docstring).
EIG_WEIGHT = 0.05
#: Smallest frequency of an oscillatory root [rad/s] (as the flutter search's).
MIN_FREQUENCY_RAD_S = 0.5
#: Speed tolerance of a refined crossing [m/s], and the most evaluations spent on one.
CROSSING_TOL_M_S = 0.01
CROSSING_ITERATIONS = 12


def mac(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Modal assurance criterion of every column of ``a`` (n, p) with every column of ``b`` (n, r): (p, r) in [0, 1]."""
    num = np.abs(np.conj(a).T @ b) ** 2
    den = np.outer(np.real(np.sum(np.conj(a) * a, axis=0)), np.real(np.sum(np.conj(b) * b, axis=0)))
    return num / np.where(den > 0, den, 1.0)


def track_branches(steps: Sequence[tuple[np.ndarray, np.ndarray]], *, min_mac: float = MIN_MAC,
                   eig_weight: float = EIG_WEIGHT) -> np.ndarray:
    """Continue roots from step to step by eigenvector correlation (module docstring).

    Parameters
    ----------
    steps : sequence of (eigenvalues (k_i,), vectors (n, k_i))
        The roots at each speed, in any order; k_i may differ between steps.
    min_mac : float
        Smallest MAC that continues a branch.
    eig_weight : float
        Weight of |lambda - lambda_predicted| / |lambda_predicted| against MAC.

    Returns
    -------
    ndarray of int, shape (n_branches, n_steps)
        Index of the branch's root at each step, -1 where the branch has no root.
    """
    branches: list[list[int]] = []
    last_vec: list[np.ndarray] = []
    history: list[list[complex]] = []
    for step, (vals, vecs) in enumerate(steps):
        vals = np.asarray(vals, complex)
        vecs = np.asarray(vecs, complex).reshape(-1, vals.size)
        alive = [b for b in range(len(branches)) if branches[b][-1] >= 0 or (step >= 2 and branches[b][-2] >= 0)]
        taken = set()
        if alive and vals.size:
            m = mac(np.stack([last_vec[b] for b in alive], axis=1), vecs)
            pred = np.array([_predict(history[b]) for b in alive])
            dist = np.abs(vals[None, :] - pred[:, None]) / np.maximum(np.abs(pred)[:, None], 1e-12)
            score = m - eig_weight * np.minimum(dist, 10.0)
            rows, cols = linear_sum_assignment(-score)
            for r, c in zip(rows, cols):
                if m[r, c] >= min_mac:
                    b = alive[r]
                    branches[b].append(int(c))
                    last_vec[b] = vecs[:, c]
                    history[b].append(complex(vals[c]))
                    taken.add(int(c))
        for b in range(len(branches)):
            if len(branches[b]) < step + 1:
                branches[b].append(-1)
        for c in range(vals.size):
            if c not in taken:
                branches.append([-1] * step + [c])
                last_vec.append(vecs[:, c])
                history.append([complex(vals[c])])
    return np.array(branches, dtype=int).reshape(len(branches), len(steps))


def _predict(history: list[complex]) -> complex:
    """Linear extrapolation of a branch's last two eigenvalues (its last one when it has one)."""
    return history[-1] if len(history) < 2 else 2 * history[-1] - history[-2]


@dataclass(frozen=True)
class VgCrossing:
    """A branch whose damping changes sign between two speeds of the sweep.

    Attributes
    ----------
    aero_model : str
    label : str
        The branch's label (:class:`VgTrack`).
    kind : {"elastic", "short period", "Dutch roll"}
    speed_m_s, mach, frequency_rad_s : float
        Where Re(lambda) = 0 [m/s], [-], and the frequency there [rad/s].
    direction : {"unstable", "stable"}
        "unstable": the root moves into the right half-plane with increasing speed (flutter); "stable": back.
    refined : bool
        True when refined on the branch (module docstring), False for the linear interpolation between the
        bracketing speeds.
    """

    aero_model: str
    label: str
    kind: str
    speed_m_s: float
    mach: float
    frequency_rad_s: float
    direction: str
    refined: bool = False


@dataclass(frozen=True, eq=False)
class VgTrack:
    """One branch of roots against speed.

    Attributes
    ----------
    aero_model : {"quasi-steady", "unsteady", "theodorsen"}
    label : str
        The dominant coordinate of the branch's first root (e.g. "right_wing torsion 1"), or "short period",
        "Dutch roll".
    kind : {"elastic", "short period", "Dutch roll"}
    speeds_m_s : ndarray, shape (n,)
        True airspeeds of the sweep [m/s].
    eigenvalues : ndarray (complex), shape (n,)
        The branch's root at each speed [1/s]; nan where the branch has no root (not yet born, ended, trim failed).
    shapes : ndarray (complex), shape (n, n_v)
        Velocity part of the eigenvector of each root over V = [v, omega, s, eta] (eq. 9); nan where absent.
    """

    aero_model: str
    label: str
    kind: str
    speeds_m_s: np.ndarray
    eigenvalues: np.ndarray
    shapes: np.ndarray

    @property
    def frequency_rad_s(self) -> np.ndarray:
        """|Im(lambda)| [rad/s], shape (n,)."""
        return np.abs(self.eigenvalues.imag)

    @property
    def damping_g(self) -> np.ndarray:
        """g = 2 Re(lambda) / |Im(lambda)| [-], positive = unstable (module docstring), shape (n,)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return 2.0 * self.eigenvalues.real / np.abs(self.eigenvalues.imag)

    @property
    def damping_ratio(self) -> np.ndarray:
        """zeta = -Re(lambda) / |lambda| [-], positive = stable, shape (n,)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return -self.eigenvalues.real / np.abs(self.eigenvalues)

    def brackets(self) -> tuple[int, ...]:
        """Indices i of the speeds where Re(lambda) changes sign between speeds i and i + 1."""
        re = self.eigenvalues.real
        ok = np.isfinite(re[:-1]) & np.isfinite(re[1:])
        return tuple(int(i) for i in np.flatnonzero(ok & ((re[:-1] <= 0) != (re[1:] <= 0))))

    def as_dict(self) -> dict:
        """Plain lists for JSON: speeds, real and imaginary parts, g, zeta, frequency (None where absent)."""
        def clean(a: np.ndarray) -> list:
            return [None if not np.isfinite(x) else float(x) for x in a]
        return {"aero_model": self.aero_model, "label": self.label, "kind": self.kind,
                "speed_m_s": clean(self.speeds_m_s), "real_1_s": clean(self.eigenvalues.real),
                "imag_rad_s": clean(self.eigenvalues.imag), "frequency_rad_s": clean(self.frequency_rad_s),
                "damping_g": clean(self.damping_g), "damping_ratio": clean(self.damping_ratio)}


@dataclass(frozen=True, eq=False)
class VgDiagram:
    """Damping and frequency of every tracked root against speed at one altitude (:func:`vg_diagram`).

    Attributes
    ----------
    aircraft : str
    condition : str
        The manoeuvre or wind-tunnel condition, in words.
    altitude_m : float
    speed_of_sound_m_s : float
    speeds_m_s : ndarray, shape (n,)
    tracks : tuple of VgTrack
    crossings : tuple of VgCrossing
        Every crossing of every branch, by model and speed.
    failed : tuple of (str, float, str)
        (aero model, speed [m/s], reason) of the speeds without roots (trim failed).
    terms : dict
        Aerodynamic model name -> the physical terms of the model whose roots were computed for it
        (:meth:`flexsim.model.terms.Terms.record`).
    warnings : tuple of str
        Crossings outside the range of the aerodynamics (:func:`flexsim.linear.validity.mach_note`); empty when none.
    """

    aircraft: str
    condition: str
    altitude_m: float
    speed_of_sound_m_s: float
    speeds_m_s: np.ndarray
    tracks: tuple[VgTrack, ...]
    crossings: tuple[VgCrossing, ...] = ()
    failed: tuple[tuple[str, float, str], ...] = ()
    terms: dict = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    def flutter(self, aero_model: str) -> VgCrossing | None:
        """The lowest-speed crossing into instability of an elastic branch of ``aero_model``, or None."""
        for c in self.crossings:
            if c.aero_model == aero_model and c.kind == "elastic" and c.direction == "unstable":
                return c
        return None

    def unstable_throughout(self, aero_model: str) -> tuple[str, ...]:
        """Labels of the elastic branches of ``aero_model`` unstable (Re(lambda) > 0) at every speed where they have a
        root, from the first speed on: an instability below the range, which no crossing in it marks."""
        out = []
        for t in self.tracks_of(aero_model):
            re = t.eigenvalues.real
            ok = np.isfinite(re)
            if t.kind == "elastic" and ok.any() and ok[0] and np.all(re[ok] > 0.0):
                out.append(t.label)
        return tuple(dict.fromkeys(out))

    def tracks_of(self, aero_model: str) -> tuple[VgTrack, ...]:
        """The branches of one aerodynamic model."""
        return tuple(t for t in self.tracks if t.aero_model == aero_model)

    def as_dict(self) -> dict:
        """The diagram as plain JSON-ready data."""
        return {"aircraft": self.aircraft, "condition": self.condition, "altitude_m": self.altitude_m,
                "speed_of_sound_m_s": self.speed_of_sound_m_s, "speeds_m_s": [float(v) for v in self.speeds_m_s],
                "damping": "g = 2 Re(lambda)/|Im(lambda)|, positive = unstable; damping_ratio = -Re(lambda)/|lambda|",
                "tracks": [t.as_dict() for t in self.tracks],
                "crossings": [c.__dict__ for c in self.crossings],
                "failed": [{"aero_model": m, "speed_m_s": v, "reason": r} for m, v, r in self.failed],
                "terms": self.terms,
                "warnings": list(self.warnings)}

    def plot(self, path: str | Path, *, g_limits: tuple[float, float] = (-0.5, 0.2), max_elastic: int = 10) -> Path:
        """V-g (top) and V-f (bottom) panels, one column per aerodynamic model, crossings marked; written as PNG.

        Shows the short-period and Dutch-roll branches and the ``max_elastic`` elastic branches of lowest frequency
        (and any branch that crosses); :meth:`as_dict` has them all.
        """
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        models = list(dict.fromkeys(t.aero_model for t in self.tracks))
        shown: dict[str, list[VgTrack]] = {}
        for name in models:
            elastic = sorted((t for t in self.tracks_of(name) if t.kind == "elastic"),
                             key=lambda t: float(np.nanmin(t.frequency_rad_s)))
            keep = elastic[:max_elastic] + [t for t in elastic[max_elastic:] if t.brackets()]  # and every one that crosses
            shown[name] = [t for t in self.tracks_of(name) if t.kind != "elastic"] + keep
        labels = list(dict.fromkeys(t.label for name in models for t in shown[name]))
        palette = plt.cm.tab20(np.linspace(0, 1, 20))
        colour = {}
        for label in labels:
            colour[label] = ("k" if label == "short period" else "0.45" if label == "Dutch roll"
                             else palette[len([c for c in colour if c not in ("short period", "Dutch roll")]) % 20])
        fig, axes = plt.subplots(2, max(1, len(models)), figsize=(5.2 * max(1, len(models)), 7.5), sharex=True,
                                 squeeze=False)
        short = {v: k for k, v in VG_MODELS.items()}
        drawn: dict[str, object] = {}
        f_top = 0.0
        for j, name in enumerate(models):
            ax_g, ax_f = axes[0, j], axes[1, j]
            for track in shown[name]:
                style = "-" if track.kind == "elastic" else ("--" if track.kind == "short period" else ":")
                (line,) = ax_g.plot(track.speeds_m_s, track.damping_g, style, color=colour[track.label], lw=1.3)
                ax_f.plot(track.speeds_m_s, track.frequency_rad_s, style, color=colour[track.label], lw=1.3)
                drawn.setdefault(track.label, line)
                f_top = max(f_top, float(np.nanmax(track.frequency_rad_s)))
            first = self.flutter(name)
            for c in self.crossings:
                if c.aero_model != name:
                    continue
                marker = "o" if c.direction == "unstable" else "s"
                ax_g.plot(c.speed_m_s, 0.0, marker, mfc="none", mec="k", ms=9, mew=1.6)
                ax_f.plot(c.speed_m_s, c.frequency_rad_s, marker, mfc="none", mec="k", ms=9, mew=1.6)
            if first is not None:
                ax_g.annotate(f"flutter {first.speed_m_s:.1f} m/s (M {first.mach:.4f})\n{first.frequency_rad_s:.2f} rad/s, "
                              f"{first.label}", (first.speed_m_s, 0.0), xytext=(-10, 30), textcoords="offset points",
                              fontsize=7, ha="right", arrowprops=dict(arrowstyle="-", lw=0.6))
            ax_g.axhline(0.0, color="k", lw=0.8)
            ax_g.set_ylim(*g_limits)
            above = self.unstable_throughout(name)
            more = f" and {len(above) - 1} more" if len(above) > 1 else ""
            state = ("" if first else f":\nunstable over the whole range ({above[0]}{more})" if above
                     else ": no flutter in the range")
            ax_g.set_title(f"{short.get(name, name)} ({name}){state}", fontsize=9)
            ax_g.set_ylabel("damping g = 2 Re(λ)/|Im(λ)| [-] (> 0 unstable)")
            ax_f.set_ylabel("frequency |Im(λ)| [rad/s]")
            ax_f.set_xlabel("true airspeed [m/s]")
            ax_g.grid(alpha=0.3)
            ax_f.grid(alpha=0.3)
        for ax in axes[1]:
            ax.set_ylim(0.0, 1.05 * f_top)
        fig.legend(list(drawn.values()), list(drawn), loc="lower center", ncol=min(5, len(drawn)), fontsize=7, frameon=False)
        fig.suptitle(f"V-g / V-f: {self.aircraft}, {self.condition};\nbranches tracked by eigenvector MAC; circles: "
                     f"crossings into instability, squares: back; lowest {max_elastic} elastic branches shown", fontsize=9)
        rows = math.ceil(len(drawn) / 5)
        fig.tight_layout(rect=(0, 0.025 * rows + 0.01, 1, 0.94))
        path = Path(path)
        fig.savefig(path, dpi=110)
        plt.close(fig)
        return path


def _roots(spec: Spectrum, model: AircraftModel) -> list[tuple[Mode, str, str]]:
    """(mode, kind, label) of the roots a V-g diagram shows: oscillatory elastic, short period, Dutch roll."""
    from flexsim.structure.mode_names import mode_name

    st = model.structure
    mass = st.inertia.mass_matrix(np.zeros(st.dofs.nq))
    out = []
    for m in spec.of_kind("elastic"):
        if m.eigenvalue.imag < MIN_FREQUENCY_RAD_S:
            continue
        out.append((m, "elastic", mode_name(st, m.shape, mass, mass) or m.name))
    rigid = [m for m in spec.of_kind("rigid") if m.eigenvalue.imag >= 1e-3]
    if rigid:
        mp = st.mass_properties
        weight = np.array([mp.mass_kg] * 3 + list(np.diag(mp.inertia_cg_kg_m2)))
        best: dict[str, Mode] = {}
        for m in rigid:
            e = np.abs(m.shape[:6]) ** 2 * weight
            if e[[0, 2, 4]].sum() >= e[[1, 3, 5]].sum():
                if e[2] + e[4] < e[0]:
                    continue  # the phugoid: forward speed, not heave and pitch
                kind = "short period"
            else:
                kind = "Dutch roll"
            if kind not in best or m.frequency_rad_s > best[kind].frequency_rad_s:
                best[kind] = m
        out += [(m, kind, kind) for kind, m in best.items()]
    return out


def _nonlinear_vg(model: AircraftModel, altitude_m, speeds_m_s, keys: list[str], manoeuvre, n_speeds: int,
                  refine: bool) -> VgDiagram:
    """:func:`vg_diagram` of a model with the geometrically nonlinear beams: its wing about the nonlinear trim at each
    speed (:func:`flexsim.linear.flexible_vg.flexible_vg`), Peters strips only."""
    from flexsim.linear.envelope import search_range
    from flexsim.linear.flexible_vg import flexible_vg

    if keys != ["FS"]:
        raise ValueError(f"models = {keys!r}: the V-g diagram of the geometrically nonlinear beams (nonlinear_beams = "
                         f"{model.terms.nonlinear_beams!r}) is solved with Peters finite-state strips only: models=('FS',)")
    if model.variant.kind.value != "free":
        raise ValueError(f"model.variant = {model.variant.kind.value!r}: the nonlinear beams' V-g diagram is of the free "
                         "aircraft's wing about its trim; a clamped wing in a tunnel is flexsim.nonlinear_wing_tunnel")
    if manoeuvre is None:
        if altitude_m is None:
            raise ValueError("altitude_m: give the altitude of the sweep (or a manoeuvre)")
        manoeuvre = SteadyManoeuvre.level(float(altitude_m), mach=0.5)
    if speeds_m_s is None:  # the envelope (or stall estimate) of the model's linear sibling
        rng = search_range(model.replace(nonlinear_beams=None), manoeuvre)
        speeds_m_s = np.linspace(rng.mach_min, rng.mach_max, n_speeds) * speed_of_sound(float(manoeuvre.altitude_m))
    return flexible_vg(model, manoeuvre, speeds_m_s, refine=refine)


def vg_diagram(model: AircraftModel, altitude_m: float | None = None, *, speeds_m_s: Sequence[float] | None = None,
               models: Sequence[str] = ("QS", "FS", "US"), manoeuvre: SteadyManoeuvre | None = None,
               n_speeds: int = 25, refine: bool = True) -> VgDiagram:
    """The V-g / V-f diagram of ``model`` (module docstring).

    Parameters
    ----------
    model : AircraftModel
        A free aircraft (re-trimmed at every speed in ``manoeuvre``, level flight by default) or a restrained one
        (a wind tunnel at the model's altitude and density; ``altitude_m`` and ``manoeuvre`` not used). Its
        aerodynamic options are used for every model (:class:`~flexsim.linear.flutter.FlutterAnalysis`).
    altitude_m : float, optional
        Altitude of the sweep of a free aircraft [m] (or give ``manoeuvre``).
    speeds_m_s : sequence of float, optional
        True airspeeds [m/s], increasing; default ``n_speeds`` speeds over the aircraft's flutter search range
        (:func:`flexsim.linear.envelope.search_range`; a restrained model needs them given).
    models : sequence of {"QS", "FS", "US"}
        Aerodynamic models (quasi-steady, finite state, Theodorsen p-k).
    manoeuvre : SteadyManoeuvre, optional
        Steady manoeuvre of a free aircraft (its speed is replaced); default level flight at ``altitude_m``.
    n_speeds : int
        Number of speeds of the default sweep, >= 3.
    refine : bool
        Refine every crossing on its branch (module docstring; default); False keeps the linear interpolation.

    Returns
    -------
    VgDiagram
        For a model with ``terms.nonlinear_beams`` (``models=("FS",)`` only): its wing about the nonlinear trim at
        each speed (:func:`flexsim.linear.flexible_vg.flexible_vg`).

    Raises
    ------
    ValueError
        For a bad argument (named, with the allowed values).
    """
    check_model(model, nonlinear=True)
    from flexsim.linear.envelope import search_range
    from flexsim.linear.flutter import FlutterAnalysis, SharedEvaluations, _check_flutter_model

    keys = [str(k).upper() for k in models]
    bad = [k for k in keys if k not in VG_MODELS]
    if bad or not keys:
        raise ValueError(f"models = {list(models)!r}: each must be one of {', '.join(VG_MODELS)}")
    if isinstance(n_speeds, bool) or not (isinstance(n_speeds, int) and n_speeds >= 3):
        raise ValueError(f"n_speeds = {n_speeds!r}: must be an integer >= 3")
    if model.terms.nonlinear_beams is not None:
        return _nonlinear_vg(model, altitude_m, speeds_m_s, keys, manoeuvre, n_speeds, refine)
    if model.aero is None:
        raise ValueError("model.aero = None: a model without aerodynamics has no V-g diagram")
    restrained = model.variant.kind.value == "restrained"
    names = [VG_MODELS[k] for k in keys]
    terms: dict[str, dict] = {}
    if restrained:
        if speeds_m_s is None:
            raise ValueError("speeds_m_s: a restrained model (wind tunnel) has no flight envelope; give the speeds")
        h = model.variant.altitude_m
        rho = model.air_density(model.layout.zeros())
        condition = f"restrained in a stream of density {rho:.4g} kg/m^3 at H = {h:.0f} m"

        def evaluate(name: str, speed: float, guess) -> tuple[Spectrum, AircraftModel, object]:
            spec, used = _tunnel_spectrum(model, speed, name)
            terms.setdefault(name, used.terms.record())
            return spec, used, None
    else:
        _check_flutter_model(model)
        if manoeuvre is None:
            if altitude_m is None:
                raise ValueError("altitude_m: give the altitude of the sweep (or a manoeuvre)")
            manoeuvre = SteadyManoeuvre.level(float(altitude_m), mach=0.5)
        h = float(manoeuvre.altitude_m)
        if speeds_m_s is None:
            rng = search_range(model, manoeuvre)
            speeds_m_s = np.linspace(rng.mach_min, rng.mach_max, n_speeds) * speed_of_sound(h)
        condition = manoeuvre.describe().split(" at M ")[0] + f", H = {h:.0f} m"
        analysis = FlutterAnalysis(model, "theodorsen" if set(names) - {"quasi-steady"} else "quasi-steady")
        shared = SharedEvaluations(analysis)

        def evaluate(name: str, speed: float, guess) -> tuple[Spectrum, AircraftModel, object]:
            terms.setdefault(name, (analysis.fs if name == "unsteady" else analysis.qs_linear).terms.record())
            point, spec = analysis.evaluate(manoeuvre.with_speed(speed), guess, aero_model=name, shared=shared)
            return spec, analysis.qs, point
    speeds = np.asarray(speeds_m_s, float)
    if speeds.ndim != 1 or speeds.size < 2 or not np.all(np.isfinite(speeds)) or np.any(np.diff(speeds) <= 0) or speeds[0] <= 0:
        raise ValueError(f"speeds_m_s: must be at least 2 finite, positive, increasing speeds [m/s], not {speeds_m_s!r}")
    a_sound = speed_of_sound(h)
    n_v = model.structure.dofs.n_v
    failed: list[tuple[str, float, str]] = []
    tracks: list[VgTrack] = []
    crossings: list[VgCrossing] = []
    for name in names:
        pools: list[list[tuple[Mode, str, str]]] = []
        trims: list[object] = []
        guess = None
        for speed in speeds:
            try:
                spec, used, guess_new = evaluate(name, float(speed), guess)
            except (TrimError, ValueError) as exc:
                pools.append([])
                trims.append(None)
                failed.append((name, float(speed), str(exc)[:200]))
                continue
            guess = guess_new
            trims.append(guess_new)
            pools.append(_roots(spec, used))
        steps = [(np.array([m.eigenvalue for m, _, _ in roots], complex),
                  np.stack([m.shape for m, _, _ in roots], axis=1) if roots else np.zeros((n_v, 0), complex))
                 for roots in pools]
        mine = []
        for row in track_branches(steps):
            first = int(np.flatnonzero(row >= 0)[0])
            _, kind, label = pools[first][row[first]]
            nan = complex(np.nan, np.nan)
            eig = np.array([pools[i][k][0].eigenvalue if k >= 0 else nan for i, k in enumerate(row)])
            shapes = np.array([pools[i][k][0].shape if k >= 0 else np.full(n_v, nan) for i, k in enumerate(row)])
            mine.append(VgTrack(name, label, kind, speeds.copy(), eig, shapes))
        mine.sort(key=lambda t: float(np.nanmin(t.frequency_rad_s)))
        tracks += mine
        for track in mine:
            for i in track.brackets():
                crossings.append(_crossing(track, i, a_sound, (lambda v, g, n=name: evaluate(n, v, g)),
                                           trims[i], refine))
    crossings.sort(key=lambda c: (names.index(c.aero_model), c.speed_m_s))
    notes = [mach_note(f"{c.aero_model} crossing of {c.label} into instability", c.mach, model.aero.compressibility)
             for c in crossings if c.direction == "unstable"]
    return VgDiagram(model.aircraft.name, condition, h, float(a_sound), speeds, tuple(tracks), tuple(crossings), tuple(failed),
                     terms, tuple(n for n in notes if n))


def _crossing(track: VgTrack, i: int, a_sound: float, evaluate, guess, refine: bool) -> VgCrossing:
    """The crossing of ``track`` between speeds i and i + 1: refined on the branch, else interpolated (module docstring)."""
    v, lam = track.speeds_m_s, track.eigenvalues
    direction = "unstable" if lam[i + 1].real > 0 else "stable"
    t = lam[i].real / (lam[i].real - lam[i + 1].real)
    speed = float(v[i] + t * (v[i + 1] - v[i]))
    freq = float(abs(lam[i].imag) + t * (abs(lam[i + 1].imag) - abs(lam[i].imag)))
    if refine:
        found = _refine(track, i, evaluate, guess)
        if found is not None:  # named by the root at the crossing, as the flutter search names its critical mode
            return VgCrossing(track.aero_model, found[2], track.kind, found[0], found[0] / a_sound, found[1], direction, True)
    return VgCrossing(track.aero_model, track.label, track.kind, speed, speed / a_sound, freq, direction, False)


def _refine(track: VgTrack, i: int, evaluate, guess) -> tuple[float, float, str] | None:
    """(speed [m/s], frequency [rad/s], name of the root) where the branch's Re(lambda) = 0 between speeds i and i + 1,
    or None."""
    (a, fa), (b, fb) = (track.speeds_m_s[i], track.eigenvalues[i].real), (track.speeds_m_s[i + 1], track.eigenvalues[i + 1].real)
    ref = [track.shapes[i], track.shapes[i + 1]]
    side = 0  # Illinois: which end was kept last time
    lam, label = track.eigenvalues[i], track.label
    for _ in range(CROSSING_ITERATIONS):
        c = (a * fb - b * fa) / (fb - fa)
        if not a < c < b:
            c = 0.5 * (a + b)
        try:
            spec, used, _ = evaluate(float(c), guess)
        except (TrimError, ValueError):
            return None
        roots = _roots(spec, used)
        if not roots:
            return None
        vecs = np.stack([m.shape for m, _, _ in roots], axis=1)
        score = np.maximum(mac(ref[0][:, None], vecs)[0], mac(ref[1][:, None], vecs)[0])
        k = int(np.argmax(score))
        if score[k] < MIN_MAC:
            return None
        lam, label = roots[k][0].eigenvalue, roots[k][2]
        fc = lam.real
        if (fc <= 0) == (fa <= 0):
            a, fa, ref[0] = c, fc, roots[k][0].shape
            if side == -1:
                fb *= 0.5
            side = -1
        else:
            b, fb, ref[1] = c, fc, roots[k][0].shape
            if side == 1:
                fa *= 0.5
            side = 1
        if b - a < CROSSING_TOL_M_S or fc == 0.0:
            break
    return float(c), float(abs(lam.imag)), label


def _tunnel_spectrum(model: AircraftModel, speed: float, name: str) -> tuple[Spectrum, AircraftModel]:
    """Spectrum of the restrained ``model`` in a stream of ``speed`` [m/s] (as :func:`flexsim.linear.flutter.wind_tunnel`):
    its siblings (:meth:`AircraftModel.replace`) with that stream and the aerodynamic model wanted, every other term
    and the tunnel's attitude, altitude and density the model's."""
    options = model.terms.aero

    def at(aero: str) -> AircraftModel:
        return model.replace(aero=replace(options, model=aero), restrained_velocity_m_s=(speed, 0.0, 0.0))

    qs = at("quasi-steady")
    x0, u0 = qs.layout.zeros(), np.zeros(4)
    if name == "theodorsen":
        return spectrum(qs, x0, u0, aero_model="theodorsen", pk_model=at("unsteady")), qs
    if name == "unsteady":
        fs = at("unsteady")
        return spectrum(fs, fs.layout.zeros(), u0, aero_model="unsteady"), fs
    return spectrum(qs, x0, u0, aero_model="quasi-steady"), qs
