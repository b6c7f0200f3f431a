"""Aerodynamic strips on the structure: geometry, control surfaces and kinematic projections (coupling).

Source: Tuzcu & Nguyen (2014), "Aerodynamic and Gravity Forces" (eqs. 25-31) and "Numerical Model":
the 2-D theory is applied at N_w and N_h spanwise locations of each wing and stabilizer half, with
Cl_alpha from a vortex-lattice model of wing + horizontal stabilizer (Fig. 6); the fin is quasi-steady.

Each strip is the streamwise section through the midpoint of one of ``strips`` equal-width intervals of
the component's elastic axis. In component axes it has a chord direction d (towards the trailing edge,
:attr:`~flexsim.aircraft.definition.Component.chord_direction`), the plunge direction n = z_i (Peters' h
positive down) and the pitch axis p = d x n (nose-up rotation; for a swept beam p . x_i = cos(Lambda), so a
torsion phi gives the paper's pitch alpha = phi cos(Lambda)). The strip's motion comes from the structural
kinematic map G(q) of its elastic-axis point; this module stores the projections of G on d, n and p, so
the coupling (:mod:`flexsim.model.coupling`) needs only a few dense products per right-hand-side call.
This is strip-structure coupling and therefore lives in :mod:`flexsim.model`; the lift-curve slopes from
the vortex lattice come from :mod:`flexsim.aero.lift_slopes`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.aero.lift_slopes import strip_lift_slopes
from flexsim.structure.model import StructuralModel

__all__ = ["StripSet", "FLAP_KINDS"]

#: Control-surface kinds in the order of the control vector entries u[1:4].
FLAP_KINDS = ("aileron", "elevator", "rudder")


@dataclass(frozen=True, eq=False)
class StripSet:
    """All aerodynamic strips of an aircraft (n_s strips), with their kinematic projections.

    Attributes
    ----------
    component : tuple of str, length n_s
    station_m, width_m : ndarray, shape (n_s,)
        Elastic-axis station of the strip midpoint [m], and the strip's span normal to its streamwise
        section, (L / strips) * |p . x_i| = (L / strips) cos(Lambda) [m]: the 2-D loads are per unit of
        that span, so strip load = load per span * width_m.
    semichord_m : ndarray, shape (n_s,)
        b = streamwise chord / 2 [m].
    a : ndarray, shape (n_s,)
        Elastic-axis position, semichords aft of mid-chord [-] (Theodorsen's a).
    lift_slope0 : ndarray, shape (n_s,)
        Incompressible sectional Cl_alpha [1/rad].
    cd0 : ndarray, shape (n_s,)
    incidence_rad : ndarray, shape (n_s,)
        Rigging angle of the chord, nose up [rad].
    unsteady : ndarray of bool, shape (n_s,)
        Strips that carry wake inflow states in the finite-state model: wing and stabilizer. Fin strips
        are quasi-steady (lambda0 = 0, paper eqs. 29-31); all strips carry the apparent mass, which
        the quasi-steady thin-airfoil theory includes (without it the fin would lose the pitch damping
        that cancels its circulatory pitch-rate moment and would flutter spuriously in torsion).
    flap_index : ndarray of int, shape (n_s,)
        Index into u of the strip's control (1 aileron, 2 elevator, 3 rudder), 0 for none.
    flap_sign : ndarray, shape (n_s,)
        Flap angle beta = flap_sign * u[flap_index] (TE down in strip axes); -1 on the left aileron.
    flap_w : ndarray, shape (n_s, 3)
        Chebyshev downwash coefficients w0, w1, w2 of a flap deflection per unit u0 * beta (exact
        projection of the step downwash: w0 = phi_h / pi, w_n = 2 sin(n phi_h) / (n pi)).
    d, n, p : ndarray, shape (n_s, 3)
        Chord direction, plunge direction, pitch axis (component axes).
    proj_d0, proj_n0 : ndarray, shape (n_s, n_v)
        d^T A(0) and n^T A(0): chordwise and normal velocity of the EA point per unit V.
    proj_d1, proj_n1 : ndarray, shape (n_s, 3, nq)
        Their q-derivatives in the omega columns.
    proj_p : ndarray, shape (n_s, n_v)
        p^T B: pitch rate per unit V (constant).
    position_body_m : ndarray, shape (n_s, 3)
        Undeformed EA point of each strip, body axes [m].
    """

    component: tuple[str, ...]
    station_m: np.ndarray
    width_m: np.ndarray
    semichord_m: np.ndarray
    a: np.ndarray
    lift_slope0: np.ndarray
    cd0: np.ndarray
    incidence_rad: np.ndarray
    unsteady: np.ndarray
    flap_index: np.ndarray
    flap_sign: np.ndarray
    flap_w: np.ndarray
    d: np.ndarray
    n: np.ndarray
    p: np.ndarray
    proj_d0: np.ndarray
    proj_n0: np.ndarray
    proj_d1: np.ndarray
    proj_n1: np.ndarray
    proj_p: np.ndarray
    position_body_m: np.ndarray

    @property
    def n_strips(self) -> int:
        """Number of strips n_s."""
        return self.station_m.size

    @classmethod
    def from_model(cls, structure: StructuralModel, lift_slope: str = "file") -> "StripSet":
        """Build the strips of every component that has an ``aero`` table.

        Parameters
        ----------
        structure : StructuralModel
        lift_slope : {"file", "2pi", "vlm"}
            ``"file"`` takes each component's ``lift_slope``; ``"2pi"``/``"vlm"`` override it for the
            wing and stabilizer strips (the paper's two options).
        """
        aircraft = structure.aircraft
        rows: dict[str, list] = {k: [] for k in ("component", "x", "w", "b", "a", "cd0", "inc", "unsteady", "fi", "fs", "fw", "d", "n", "p", "g0", "g1", "pos", "slope")}
        for comp in aircraft.components:
            if comp.aero is None:
                continue
            k = comp.aero.strips
            width = comp.length_m / k
            x = (np.arange(k) + 0.5) * width
            chord = comp.sections.at("chord_m", x)
            frac = comp.sections.at("ea_fraction", x)
            d = comp.chord_direction
            n = np.array([0.0, 0.0, 1.0])
            p = np.cross(d, n)
            maps = structure.point_maps(comp.name, x)
            cs = comp.control_surface
            fi = np.zeros(k, int)
            fs = np.zeros(k)
            fw = np.zeros((k, 3))
            if cs is not None:
                inside = (x >= cs.start_m) & (x <= cs.end_m)
                fi[inside] = 1 + FLAP_KINDS.index(cs.kind)
                fs[inside] = -1.0 if comp.name == "left_wing" else 1.0
                phi_h = np.arccos(cs.hinge_d)
                fw[inside] = [phi_h / np.pi, 2 * np.sin(phi_h) / np.pi, np.sin(2 * phi_h) / np.pi]
            slope = comp.aero.lift_slope if lift_slope == "file" or comp.name == "vtail" else lift_slope
            rows["component"] += [comp.name] * k
            rows["x"].append(x)
            rows["w"].append(np.full(k, width * abs(p[0])))  # span normal to the streamwise section
            rows["b"].append(0.5 * chord)
            rows["a"].append(2.0 * frac - 1.0)
            rows["cd0"].append(np.full(k, comp.aero.cd0))
            rows["inc"].append(np.full(k, comp.aero.incidence_rad))
            rows["unsteady"].append(np.full(k, comp.name != "vtail"))
            rows["fi"].append(fi)
            rows["fs"].append(fs)
            rows["fw"].append(fw)
            rows["d"].append(np.tile(d, (k, 1)))
            rows["n"].append(np.tile(n, (k, 1)))
            rows["p"].append(np.tile(p, (k, 1)))
            rows["g0"].append(maps.g0)
            rows["g1"].append(maps.g1)
            rows["pos"].append(maps.r0)
            rows["slope"].append(np.full(k, 2 * np.pi if slope == "2pi" else (np.nan if slope == "vlm" else float(slope))))
        if not rows["component"]:
            n_v, nq = structure.dofs.n_v, structure.dofs.nq
            empty = np.zeros(0)
            return cls((), empty, empty, empty, empty, empty, empty, empty, empty.astype(bool), empty.astype(int), empty,
                       np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, 3)), np.zeros((0, n_v)),
                       np.zeros((0, n_v)), np.zeros((0, 3, nq)), np.zeros((0, 3, nq)), np.zeros((0, n_v)), np.zeros((0, 3)))
        cat = {k: np.concatenate(v) if k != "component" else tuple(v) for k, v in rows.items()}
        g0, g1 = cat["g0"], cat["g1"]
        d, n, p = cat["d"], cat["n"], cat["p"]
        slope = cat["slope"]
        need_vlm = np.isnan(slope)
        if need_vlm.any():
            slope[need_vlm] = strip_lift_slopes(aircraft, cat["component"], cat["pos"])[need_vlm]
        return cls(
            component=cat["component"],
            station_m=cat["x"],
            width_m=cat["w"],
            semichord_m=cat["b"],
            a=cat["a"],
            lift_slope0=slope,
            cd0=cat["cd0"],
            incidence_rad=cat["inc"],
            unsteady=cat["unsteady"].astype(bool),
            flap_index=cat["fi"].astype(int),
            flap_sign=cat["fs"],
            flap_w=cat["fw"],
            d=d,
            n=n,
            p=p,
            proj_d0=np.einsum("sk,skv->sv", d, g0[:, 0:3, :]),
            proj_n0=np.einsum("sk,skv->sv", n, g0[:, 0:3, :]),
            proj_d1=np.einsum("sk,skal->sal", d, g1),
            proj_n1=np.einsum("sk,skal->sal", n, g1),
            proj_p=np.einsum("sk,skv->sv", p, g0[:, 3:6, :]),
            position_body_m=cat["pos"],
        )
