"""Is a trim a valid equilibrium? Its classification from the roots of its own linearisation.

A trim solves V_dot = 0 (eqs. 33-39); whether the aircraft stays there follows from the eigenvalues of the model
linearised about it (Tuzcu & Nguyen 2014, "Numerical Model"), each told apart as rigid-body, elastic or
aerodynamic-lag by :mod:`flexsim.trimming.roots`. A root is unstable when its real part exceeds ``UNSTABLE_DAMPING``
times its modulus (the flutter search's test, :data:`flexsim.linear.scan.UNSTABLE_DAMPING`: round-off on a
neutral root is not an instability). The equilibrium's verdict is the worst of its roots' (and of the static
margin's), in the order of :data:`VERDICTS`:

* ``statically divergent``: a real unstable root of an elastic (or aerodynamic-lag) mode, a static aeroelastic
  divergence (Hodges & Pierce, *Introduction to Structural Dynamics and Aeroelasticity*, 2nd ed., 2011, ch. 2-4:
  the aeroelastic stiffness K - K_aero is no longer positive definite); the root is named by the elastic
  coordinate with the largest kinetic-energy share Re(conj(phi_i) (M phi)_i).
* ``statically unstable``: a static margin < 0 (the neutral point ahead of the CG, Etkin & Reid, *Dynamics of
  Flight*, 3rd ed., 1996, sec. 2.3; :mod:`flexsim.trimming.margin`), or a real unstable rigid-body root (an aperiodic
  divergence: in w or q a pitch divergence; in u or the lateral coordinates a split phugoid or spiral faster than the
  slow limits below).
* ``dynamically unstable``: a complex pair with a positive real part (an oscillation that grows): of an elastic mode
  (flutter at the trim), or a phugoid faster than the slow limit below, a short period or a Dutch roll.
* ``slowly unstable``: only rigid-body roots whose time to double T2 = ln 2 / Re(lambda) is at least the
  MIL-F-8785C Level 3 minimum (Military Specification, Flying Qualities of Piloted Airplanes, 1980): 4 s for the
  spiral (sec. 3.3.1.3, every class), 55 s for the phugoid (sec. 3.2.1.2). Such an aircraft is flown every day
  (the pilot or autopilot corrects the drift): reported, not an error.
* ``stable``: no unstable root.

A rigid-body root is named from its dominant DOF (Etkin & Reid 1996, ch. 6-7): u the phugoid (complex, or a real
root of the split phugoid), w or q the short period (complex) or a pitch divergence (real), v, p or r the spiral
(real) or the Dutch roll (complex).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from flexsim.trimming.roots import Spectrum, _classify, _dominant_dofs, reduced_jacobian, rigid_mode_name

if TYPE_CHECKING:
    from flexsim.model.aircraft_model import AircraftModel

__all__ = ["EquilibriumStability", "UnstableRoot", "VERDICTS", "classify_equilibrium", "equilibrium_stability", "with_stability"]

#: Verdicts from the best to the worst.
VERDICTS = ("stable", "slowly unstable", "dynamically unstable", "statically unstable", "statically divergent")
#: A real part counts as positive only above this fraction of the root's modulus (damping ratio below -1e-9).
UNSTABLE_DAMPING = 1e-9
#: MIL-F-8785C sec. 3.3.1.3, Level 3, every class: spiral time to double amplitude >= 4 s.
SPIRAL_MIN_DOUBLING_S = 4.0
#: MIL-F-8785C sec. 3.2.1.2, Level 3: phugoid time to double amplitude >= 55 s.
PHUGOID_MIN_DOUBLING_S = 55.0


@dataclass(frozen=True)
class UnstableRoot:
    """One unstable root of a trim's linearisation (of a conjugate pair, the one with Im >= 0).

    Attributes
    ----------
    eigenvalue : complex
        [1/s], real part > 0.
    kind : {"rigid", "elastic", "aerodynamic"}
        As :class:`flexsim.trimming.roots.Mode`.
    coordinate : str
        Dominant coordinate: a rigid-body mode's dominant DOF (u, v, w, p, q, r), an elastic mode's name
        (:func:`flexsim.structure.mode_names.mode_name`, e.g. "wings bending 1 (symmetric)").
    name : str
        "spiral", "Dutch roll", "phugoid", "longitudinal oscillation", "longitudinal divergence" for a
        rigid-body root, the coordinate for an elastic one.
    verdict : str
        What this root makes of the equilibrium (one of :data:`VERDICTS` but "stable").
    """

    eigenvalue: complex
    kind: str
    coordinate: str
    name: str
    verdict: str

    @property
    def time_to_double_s(self) -> float:
        """ln 2 / Re(eigenvalue) [s]."""
        return math.log(2.0) / self.eigenvalue.real

    def describe(self) -> str:
        """E.g. "right_wing bending 1 (real root +37.9 1/s, time to double 0.0183 s)", "spiral [r] (...)"."""
        lam = self.eigenvalue
        root = f"real root {lam.real:+.4g} 1/s" if lam.imag == 0.0 else f"complex pair {lam.real:+.4g} +-{abs(lam.imag):.4g}j 1/s"
        who = self.name if self.name == self.coordinate else f"{self.name} [{self.coordinate}]"
        return f"{who} ({root}, time to double {self.time_to_double_s:.3g} s)"

    def as_dict(self) -> dict:
        """Plain dict for JSON."""
        return {"real": self.eigenvalue.real, "imag": self.eigenvalue.imag, "kind": self.kind, "coordinate": self.coordinate,
                "name": self.name, "verdict": self.verdict, "time_to_double_s": self.time_to_double_s}


@dataclass(frozen=True)
class EquilibriumStability:
    """The classification of a trim's equilibrium (module docstring).

    Attributes
    ----------
    verdict : str
        One of :data:`VERDICTS`.
    unstable : tuple of UnstableRoot
        Every unstable root, fastest first.
    static_margin_mac : float
        Static margin as a fraction of the mean aerodynamic chord [-] (:mod:`flexsim.trimming.margin`); nan where it
        is not defined (no right wing, a restrained model).
    aero_model : str
        Aerodynamic model of the linearisation the roots come from.
    """

    verdict: str
    unstable: tuple[UnstableRoot, ...] = ()
    static_margin_mac: float = math.nan
    aero_model: str = "quasi-steady"

    @property
    def is_stable(self) -> bool:
        """True when no root is unstable and the static margin is not negative."""
        return self.verdict == "stable"

    @property
    def is_divergent(self) -> bool:
        """True for a statically divergent equilibrium (an elastic real root > 0)."""
        return self.verdict == "statically divergent"

    @property
    def message(self) -> str:
        """One line, "" when stable: the verdict and what makes it, then the other verdicts met with their number of
        roots, e.g. "statically divergent: right_wing bending 1 (real root +37.9 1/s, time to double 0.0183 s) and
        ...; also statically unstable (2 roots), dynamically unstable (2 roots)"."""
        if self.is_stable:
            return ""
        roots = [r.describe() for r in self.unstable if r.verdict == self.verdict]
        if self.verdict == "statically unstable" and self.static_margin_mac < 0.0:
            roots.insert(0, f"static margin {self.static_margin_mac:.4g} MAC (the neutral point ahead of the CG)")
        if self.verdict == "slowly unstable":
            roots = [f"rigid-body mode {r}" for r in roots]
        others = [f"{v} ({n} root{'s' if n > 1 else ''})" for v in reversed(VERDICTS[1:]) if v != self.verdict
                  for n in [sum(r.verdict == v for r in self.unstable)] if n]
        return f"{self.verdict}: {' and '.join(roots)}" + (f"; also {', '.join(others)}" if others else "")

    def as_dict(self) -> dict:
        """Plain dict for JSON."""
        return {"verdict": self.verdict, "message": self.message, "static_margin_mac": self.static_margin_mac,
                "aero_model": self.aero_model, "unstable": [r.as_dict() for r in self.unstable]}


def _elastic_coordinate(model: "AircraftModel", q: np.ndarray, shape: np.ndarray) -> str | None:
    """The elastic coordinate with the largest kinetic-energy share Re(conj(phi_i) (M(q) phi)_i) of a mode (velocity
    shape over V), mirror ties to the right half as :func:`flexsim.trimming.roots._dominant_dofs`; None without one."""
    st = model.structure
    elastic = model.active_dofs[model.active_dofs >= 6]
    if elastic.size == 0:
        return None
    share = np.real(np.conj(shape) * (st.inertia.mass_matrix(q) @ shape))
    return st.dofs.labels[int(_dominant_dofs(share[elastic][:, None], elastic, st.dofs.n_v, st.mirror)[0])]


def _rigid_root(lam: complex, coordinate: str) -> tuple[str, str]:
    """(name, verdict) of an unstable rigid-body root (module docstring): a real root faster than the slow limits is an
    aperiodic divergence, "statically unstable"; only a complex pair is "dynamically unstable"."""
    t2 = math.log(2.0) / lam.real
    real = lam.imag == 0.0
    fast = "statically unstable" if real else "dynamically unstable"
    name = rigid_mode_name(lam, coordinate)  # the name the roots table gives the same root
    if name == "phugoid":
        return name, ("slowly unstable" if t2 >= PHUGOID_MIN_DOUBLING_S else fast)
    if name == "spiral":
        return name, ("slowly unstable" if t2 >= SPIRAL_MIN_DOUBLING_S else fast)
    return name, fast


def classify_equilibrium(model: "AircraftModel", x0: np.ndarray, spectrum: Spectrum,
                         static_margin_mac: float = math.nan, neutral: complex | None = None) -> EquilibriumStability:
    """The verdict on the equilibrium ``x0`` of ``model`` from the roots of its linearisation (module docstring).

    Parameters
    ----------
    model : AircraftModel
        Supplies the mass matrix and coordinate names (a model of the same aircraft as the spectrum's).
    x0 : ndarray, shape (n_states,)
        The trim state (its elastic coordinates set M(q)).
    spectrum : Spectrum
        The classified roots, e.g. :func:`flexsim.linear.stability.spectrum` at the trim.
    static_margin_mac : float
        [-], nan when not known.
    neutral : complex, optional
        A root (and its conjugate) counted neutral whatever the sign of its real part: the crossing mode at a
        flutter point, located on the imaginary axis to the search's tolerance.
    """
    _, _, q, _, _ = model.unpack(np.asarray(x0, float)[: model.layout.n_states])
    unstable = []
    for mode in spectrum.modes:
        lam = mode.eigenvalue
        if not (lam.real > UNSTABLE_DAMPING * abs(lam)) or lam.imag < 0.0 or (neutral is not None and lam in (neutral, neutral.conjugate())):
            continue
        if mode.kind == "rigid":
            name, verdict = _rigid_root(lam, mode.dominant_dof)
            coordinate = mode.dominant_dof
        else:
            coordinate = (mode.name or _elastic_coordinate(model, q, mode.shape)) if mode.kind == "elastic" else None
            coordinate = coordinate or mode.dominant_dof
            name, verdict = coordinate, ("statically divergent" if lam.imag == 0.0 else "dynamically unstable")
        unstable.append(UnstableRoot(complex(lam), mode.kind, coordinate, name, verdict))
    unstable.sort(key=lambda r: -r.eigenvalue.real)
    worst = max([VERDICTS.index(r.verdict) for r in unstable] + [VERDICTS.index("statically unstable") if static_margin_mac < 0.0 else 0])
    return EquilibriumStability(VERDICTS[worst], tuple(unstable), float(static_margin_mac), spectrum.aero_model)


def equilibrium_stability(model: "AircraftModel", x0: np.ndarray, u0: np.ndarray) -> EquilibriumStability:
    """Linearise ``model`` about (x0, u0) (:func:`flexsim.trimming.roots.reduced_jacobian`), classify its roots and the
    static margin, and give the verdict (:func:`classify_equilibrium`).

    The eigenvalues come first without eigenvectors; only when one of them is unstable are the eigenvectors computed
    and every root classified (a stable trim, the usual one, costs the Jacobian and ``eigvals``)."""
    from flexsim.trimming.margin import static_margin_of_state

    rj = reduced_jacobian(model, x0, u0)
    label = "none" if model.aero is None else model.aero.options.model
    margin = static_margin_of_state(model, x0, u0)
    margin_mac = math.nan if margin is None else margin.fraction_of_mac
    lam = np.linalg.eigvals(rj.a)
    if not np.any(lam.real > UNSTABLE_DAMPING * np.abs(lam)):
        return classify_equilibrium(model, x0, Spectrum((), label), margin_mac)
    vals, vecs = np.linalg.eig(rj.a)
    return classify_equilibrium(model, x0, _classify(model, rj, vals, vecs, label), margin_mac)


def with_stability(model: "AircraftModel", point, spectrum: Spectrum, neutral: complex | None = None):
    """``point`` (a :class:`~flexsim.trimming.TrimPoint`) with its ``stability`` classified from ``spectrum``, an
    eigen-analysis at that trim made anyway (e.g. by a flutter search: the classification then costs the static
    margin's two force evaluations, not a second linearisation); ``neutral`` as in :func:`classify_equilibrium`."""
    from dataclasses import replace

    from flexsim.trimming.margin import static_margin_of_state

    margin = static_margin_of_state(model, point.x, point.u)
    return replace(point, stability=classify_equilibrium(model, point.x, spectrum,
                                                         math.nan if margin is None else margin.fraction_of_mac, neutral))
