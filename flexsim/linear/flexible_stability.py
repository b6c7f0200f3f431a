"""Stability of the whole free-flying very flexible aircraft about its nonlinear trim (quasi-steady strips).

The state of the free-flying aircraft (:mod:`flexsim.structure.free_flexible`, the paper's eq. 2 in Kane's form) is
``y = [X (3), quaternion (4), ε (n), v (3), ω (3), ε̇ (n)]``; its rate is :func:`free_flight_rhs` with the
generalized airloads and thrust of :meth:`flexsim.model.flexible_aircraft.FlexibleAircraft.airloads` (quasi-steady
strips: no apparent mass, no wake) added to ``Q``. The Jacobian ``A = ∂ẏ/∂y`` about a trim point
(:func:`flexsim.trimming.flexible_trim.trim_flexible`) is taken by central differences (step ``10⁻⁶ max(1, |y_j|)``,
truncation O(h²) and round-off O(ε/h): about 1e-8 relative in the eigenvalues that matter here) on every state but
the position (the density is held at the trim's), so the eigenvalues include the rigid-body modes (phugoid, short
period, Dutch roll, roll, spiral) coupled with the deformed wings, and four neutral roots: the heading and, from the
quaternion's norm, one more. The preload's geometric stiffness enters through the dependence of the equations on ε.
About the bottom of a pull-up (``ω ≠ 0``) the attitude turns, so the linearisation is the frozen one of the linear
model's pull-up (:mod:`flexsim.trimming.manoeuvre`). SI units, radians.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import NDArray

from flexsim.linear.flexible_flutter import MAX_FREQUENCY_RAD_S
from flexsim.trimming.flexible_trim import FlexibleTrimPoint

__all__ = ["FreeAircraftSpectrum", "FreeMode", "free_aircraft_spectrum", "NEUTRAL_1_S"]

#: Roots closer to zero than this [1/s] count as neutral (a period over 20 min; module docstring).
NEUTRAL_1_S = 5e-3
#: Growth rate under which a root counts as neutral in :attr:`FreeAircraftSpectrum.unstable` [1/s] (a doubling time of
#: 8 days): the frozen linearisation of a turn leaves its heading's rotation, ±V/(2R) j, with a real part of round-off
#: (9e-12 1/s on the bundled HALE at R = 1000 m).
GROWTH_FLOOR_1_S = 1e-6


@dataclass(frozen=True, eq=False)
class FreeAircraftSpectrum:
    """Eigenvalues of the free aircraft about a nonlinear trim.

    Attributes
    ----------
    eigenvalues : ndarray of complex, shape (m,)
        [1/s], all states but the position.
    eigenvectors : ndarray of complex, shape (m, m)
        Columns, in the reduced state ``[quaternion, ε, v, ω, ε̇]``.
    n_strains : int
    point : FlexibleTrimPoint or None
        The trim linearised about (names the modes: :attr:`modes`).
    aero : str
        The strips' model: ``"quasi-steady"`` (:func:`free_aircraft_spectrum`) or ``"unsteady"`` (Peters' strips,
        :meth:`flexsim.linear.flexible_unsteady.UnsteadyFreeAircraft.spectrum`: the eigenvectors' structural rows).
    """

    eigenvalues: NDArray
    eigenvectors: NDArray
    n_strains: int
    point: FlexibleTrimPoint | None = None
    aero: str = "quasi-steady"

    @cached_property
    def modes(self) -> tuple[FreeMode, ...]:
        """Every root of the upper half-plane, named (:func:`name_modes`), by increasing ``|λ|``."""
        return name_modes(self)

    @property
    def unstable(self) -> tuple[FreeMode, ...]:
        """The non-neutral modes with ``Re λ >`` :data:`GROWTH_FLOOR_1_S` in the converged band (``|λ| <=``
        :data:`~flexsim.linear.flexible_flutter.MAX_FREQUENCY_RAD_S`; above it the beams' discretisation has not
        converged, as in :func:`~flexsim.linear.flexible_flutter.wing_stability`)."""
        return tuple(m for m in self.modes if m.kind != "neutral" and m.eigenvalue.real > GROWTH_FLOOR_1_S
                     and abs(m.eigenvalue) <= MAX_FREQUENCY_RAD_S)

    def verdict(self) -> str:
        """One line: stable, or the most unstable mode with its root and how many more (the strips' model named)."""
        bad = self.unstable
        if not bad:
            return f"stable about the nonlinear trim ({self.aero} strips; neutral roots aside)"
        worst = max(bad, key=lambda m: m.eigenvalue.real)
        z = worst.eigenvalue
        root = f"{z.real:+.4g}" + (f" ± {z.imag:.4g}j" if z.imag else "")
        more = f" and {len(bad) - 1} more" if len(bad) > 1 else ""
        return f"unstable about the nonlinear trim ({self.aero} strips): {worst.name} ({root}){more}"

    @property
    def phugoid(self) -> tuple:
        """The phugoid's roots: the non-neutral roots below 1 rad/s whose eigenvectors are led by the forward speed
        ``v_x`` (more than half of the unit eigenvector; the long-period exchange of speed and height). One
        complex root (its upper half) while it oscillates; two real roots once it has split (a very flexible
        aircraft at high speed); empty when none is found. Roots within :data:`NEUTRAL_1_S` of zero are left out:
        the heading's and the quaternion norm's neutral roots, which the frozen linearisation of a pull-up (a
        turning attitude) shifts by up to 3e-3 1/s on the bundled HALE."""
        n = self.n_strains
        lam, vec = self.eigenvalues, self.eigenvectors
        out = []
        for k in np.flatnonzero((np.abs(lam) < 1.0) & (np.abs(lam) > NEUTRAL_1_S) & (lam.imag >= 0.0)):
            if abs(vec[4 + n, k]) / np.linalg.norm(vec[:, k]) > 0.5:
                out.append(complex(lam[k]) if lam[k].imag > 1e-9 else complex(lam[k].real, 0.0))
        return tuple(sorted(out, key=lambda z: (z.real, z.imag)))


def free_aircraft_spectrum(model, point: FlexibleTrimPoint) -> FreeAircraftSpectrum:
    """Eigenvalues and eigenvectors of the free aircraft linearised about ``point`` (module docstring).

    Parameters
    ----------
    model : AircraftModel
        The model the trim was computed for (its gravity).
    point : FlexibleTrimPoint

    Returns
    -------
    FreeAircraftSpectrum
    """
    flex = point.aircraft
    structure = flex.free_structure(model.terms.gravity_m_s2)
    n = structure.n_strains
    y0 = point.state()
    a = flex.free_flight_jacobian(structure, y0, point.controls, point.density_kg_m3)[3:]
    lam, vec = np.linalg.eig(a)
    return FreeAircraftSpectrum(eigenvalues=lam, eigenvectors=vec, n_strains=n, point=point)


@dataclass(frozen=True)
class FreeMode:
    """One root of the free aircraft about the nonlinear trim, named.

    Attributes
    ----------
    eigenvalue : complex
        [1/s] (upper half-plane).
    name : str
        A rigid-body mode's flight-dynamics name (:func:`flexsim.trimming.roots.rigid_mode_name`: phugoid, short
        period, Dutch roll, roll subsidence, spiral, ...), an elastic mode's ``"<component or wings> <bending |
        chordwise bending | torsion | extension> k [(symmetric | antisymmetric)]"``, or ``"neutral"``.
    kind : {"rigid", "elastic", "neutral"}
    rigid_share : float
        Share of the mode's kinetic energy in the rigid-body velocities ``v, ω`` [-].
    """

    eigenvalue: complex
    name: str
    kind: str
    rigid_share: float


#: Body-axes rigid-body velocities in the order of ``V = [v, ω, ε̇]`` (Etkin & Reid's u, v, w, p, q, r).
_RIGID = ("u", "v", "w", "p", "q", "r")
_MIRROR = np.diag([1.0, -1.0, 1.0])


def _symmetry(flex, kin: list, dq: NDArray, right: int, left: int) -> str:
    """"symmetric" or "antisymmetric" for the strain perturbation ``dq`` of two mirror-image beams: the left beam's
    point displacements against the mirror images of the right beam's (``y → −y``; rotations are pseudovectors,
    ``r → −M r``), the smaller residual wins."""
    slices = flex.structure.strain_slices()
    moves = []
    for b in (right, left):
        k, d = kin[b], dq[slices[b]]
        length = flex.structure.beams[b].length_m
        moves.append((np.einsum("pik,k->pi", k.jac_position, d), length * np.einsum("pik,k->pi", k.jac_rotation, d)))
    (d_r, r_r), (d_l, r_l) = moves
    sym = np.linalg.norm(d_l - d_r @ _MIRROR) ** 2 + np.linalg.norm(r_l + r_r @ _MIRROR) ** 2
    anti = np.linalg.norm(d_l + d_r @ _MIRROR) ** 2 + np.linalg.norm(r_l - r_r @ _MIRROR) ** 2
    return "symmetric" if sym <= anti else "antisymmetric"


def name_modes(spectrum: FreeAircraftSpectrum) -> tuple[FreeMode, ...]:
    """Name the roots of ``spectrum`` (upper half-plane, by increasing ``|λ|``).

    A root within :data:`NEUTRAL_1_S` of zero is "neutral". Otherwise its kinetic energy ``T = ½ V^H M(ε0) V`` at the
    trim (Shearer & Cesnik 2007 eq. 12, :func:`flexsim.structure.free_flexible.generalized_mass_matrix`) is split over
    the coordinates of ``V = [v, ω, ε̇]`` (share of coordinate k: ``Re(conj(V_k) (M V)_k) / T``): a mode with more than
    half of it in ``v, ω`` is a rigid-body mode named from its largest rigid coordinate
    (:func:`flexsim.trimming.roots.rigid_mode_name`, Etkin & Reid 1996 ch. 6-7); else an elastic mode named by the
    component and strain type that store most of its strain energy ``½ K_kk |δε_k|²`` (Su & Cesnik 2011 eq. 9;
    "wings" when the two wing halves share it, with the mode's symmetry from the mirror images of their points'
    displacements), numbered by frequency among modes of the same name (a second rigid-body root of one name, a
    rigid-body motion coupled with the wings, is numbered too).
    """
    from flexsim.linear.flexible_vg import MODE_WORDS
    from flexsim.structure.free_flexible import generalized_mass_matrix
    from flexsim.structure.strain_beam import STRAIN_NAMES, stiffness_matrix
    from flexsim.trimming.roots import rigid_mode_name

    point = spectrum.point
    if point is None:
        raise ValueError("spectrum.point is None: the modes are named from the trim the spectrum was computed about")
    flex, n = point.aircraft, spectrum.n_strains
    mass = generalized_mass_matrix(flex.structure, point.strains)
    kin = flex.kinematics(point.strains)
    stiff = np.concatenate([np.diag(stiffness_matrix(b)) for b in flex.structure.beams]) if n else np.zeros(0)
    owner = np.concatenate([np.full(b.n_coordinates, i) for i, b in enumerate(flex.structure.beams)]) if n else \
        np.zeros(0, int)
    kind_of = np.concatenate([np.array([k % b.strains_per_element + 4 - b.strains_per_element
                                        for k in range(b.n_coordinates)]) for b in flex.structure.beams]) if n else \
        np.zeros(0, int)
    names = flex.beam_components
    wings = ("right_wing" in names and "left_wing" in names)
    lam, vec = spectrum.eigenvalues, spectrum.eigenvectors
    raw = []
    for k in np.flatnonzero(lam.imag >= 0.0):
        z = complex(lam[k])
        if abs(z) < NEUTRAL_1_S:
            raw.append((z, "neutral", "neutral", 0.0))
            continue
        vel = vec[4 + n:, k]
        share = np.real(np.conj(vel) * (mass @ vel))
        total = max(float(share.sum()), 1e-300)
        rigid = float(share[:6].sum()) / total
        if rigid > 0.5:
            raw.append((z, rigid_mode_name(z, _RIGID[int(np.argmax(share[:6]))]), "rigid", rigid))
            continue
        dq = vec[4:4 + n, k]
        energy = stiff * np.abs(dq) ** 2
        table = np.zeros((len(names), 4))
        np.add.at(table, (owner, kind_of), energy)
        b, t = np.unravel_index(int(np.argmax(table)), table.shape)
        word = MODE_WORDS[STRAIN_NAMES[t]]
        name = names[b]
        if wings and name in ("right_wing", "left_wing"):
            r, l_ = names.index("right_wing"), names.index("left_wing")
            if min(table[r, t], table[l_, t]) > 0.1 * max(table[r, t], table[l_, t]):
                phase = np.exp(-1j * np.angle(dq[np.argmax(np.abs(dq))]))
                name = f"wings|{_symmetry(flex, kin, np.real(dq * phase), r, l_)}"
        raw.append((z, f"{name}|{word}", "elastic", rigid))
    raw.sort(key=lambda m: abs(m[0]))
    counts: dict[str, int] = {}
    out = []
    for z, key, kind, rigid in raw:
        counts[key] = counts.get(key, 0) + 1
        if kind == "neutral":
            out.append(FreeMode(z, key, kind, rigid))
            continue
        if kind == "rigid":  # a second root of one name (a rigid-body motion coupled with the wings): numbered
            out.append(FreeMode(z, key if counts[key] == 1 else f"{key} {counts[key]}", kind, rigid))
            continue
        parts = key.split("|")
        label = f"{parts[0]} {parts[-1]} {counts[key]}" + (f" ({parts[1]})" if len(parts) == 3 else "")
        out.append(FreeMode(z, label, kind, rigid))
    return tuple(out)
