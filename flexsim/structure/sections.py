"""Mass points: quadrature of the beams' distributed mass plus the lumped masses.

The kinetic energy of eq. (7), T_i = 1/2 int v_i^T v_i dm_i, is evaluated by composite Gauss-Legendre
quadrature along each elastic axis. Over the streamwise section through station x (direction d of
:attr:`~flexsim.aircraft.definition.Component.chord_direction`), with position rho of a mass element from
the elastic axis and v = v_ref + omega_sec x rho, the integral reduces to the section's mass m, first
moment S = m e d and second moment J about the reference point (component axes)::

    T_sec = 1/2 [v_ref; omega_sec]^T  [[m I, -skew(S)], [skew(S), J]]  [v_ref; omega_sec]

A lumped mass at offset rho from its station is the same with S = m rho and
J = m (|rho|^2 I - rho rho^T) + J_own. Units: m [kg], S [kg m], J [kg m^2] (quadrature weights included).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim.aircraft.definition import Aircraft, Component
from flexsim.kinematics import skew

__all__ = ["Quadrature", "beam_quadrature", "MassPoints", "mass_points"]

#: Gauss-Legendre points per sub-interval of a beam.
_GAUSS_ORDER = 4


@dataclass(frozen=True, eq=False)
class Quadrature:
    """Composite Gauss-Legendre rule on [0, L]: ``int f dx ~ sum(w * f(x))``.

    Attributes
    ----------
    x : ndarray, shape (k,)
        Nodes [m].
    w : ndarray, shape (k,)
        Weights [m].
    """

    x: np.ndarray
    w: np.ndarray


def beam_quadrature(component: Component) -> Quadrature:
    """Quadrature along a component's elastic axis, exact between stations for the shape-function orders.

    Each station interval (where the section properties are linear) is split into sub-intervals no
    longer than L / (6 + 3 max(m, n)), each with a 4-point Gauss-Legendre rule, so that products of
    shape functions up to the highest mode and a linear property are integrated to ~1e-9 relative.
    """
    st = component.sections.station_m
    length = component.length_m
    h_max = length / (6 + 3 * max(component.bending_modes, component.torsion_modes, 1))
    xi, wi = np.polynomial.legendre.leggauss(_GAUSS_ORDER)
    xs, ws = [], []
    for a, b in zip(st[:-1], st[1:]):
        n_sub = max(1, int(np.ceil((b - a) / h_max)))
        edges = np.linspace(a, b, n_sub + 1)
        half = 0.5 * np.diff(edges)
        mid = 0.5 * (edges[1:] + edges[:-1])
        xs.append((mid[:, None] + half[:, None] * xi[None, :]).ravel())
        ws.append((half[:, None] * wi[None, :]).ravel())
    return Quadrature(np.concatenate(xs), np.concatenate(ws))


@dataclass(frozen=True, eq=False)
class MassPoints:
    """All mass points of the aircraft, grouped by component.

    Attributes
    ----------
    component : tuple of str
        Component name of each group.
    x : tuple of ndarray
        Stations of the points of each group [m].
    mbar : tuple of ndarray
        Generalized section mass matrices of each group, shape (k, 6, 6), component axes (see module
        docstring); quadrature weights included.
    """

    component: tuple[str, ...]
    x: tuple[np.ndarray, ...]
    mbar: tuple[np.ndarray, ...]


def _mbar(m: np.ndarray, s: np.ndarray, j: np.ndarray) -> np.ndarray:
    k = m.size
    out = np.zeros((k, 6, 6))
    out[:, 0:3, 0:3] = m[:, None, None] * np.eye(3)
    out[:, 0:3, 3:6] = -skew(s)
    out[:, 3:6, 0:3] = skew(s)
    out[:, 3:6, 3:6] = j
    return out


def mass_points(aircraft: Aircraft) -> MassPoints:
    """Quadrature mass points of every beam and one point per lumped mass or engine (eq. 7).

    Parameters
    ----------
    aircraft : Aircraft

    Returns
    -------
    MassPoints
    """
    names, xs, mbars = [], [], []
    for comp in aircraft.components:
        quad = beam_quadrature(comp)
        sec = comp.sections
        m = sec.at("mass_kg_per_m", quad.x) * quad.w
        e = sec.at("cg_offset_m", quad.x)
        ith = sec.at("torsional_inertia_kg_m", quad.x) * quad.w
        d = comp.chord_direction
        s = (m * e)[:, None] * d[None, :]
        if comp.section_inertia == "chordwise":
            # mass along the streamwise chord: J = K (I - d d^T), with J_xx = K (1 - d_x^2) = I_theta
            k = ith / (1.0 - d[0] ** 2)
            j = k[:, None, None] * (np.eye(3) - np.outer(d, d))[None, :, :]
        else:
            j = np.zeros((quad.x.size, 3, 3))
            j[:, 0, 0] = ith
            j[:, 1, 1] = j[:, 2, 2] = 0.5 * ith
        names.append(comp.name)
        xs.append(quad.x)
        mbars.append(_mbar(m, s, j))
    for item in (*aircraft.lumped_masses, *aircraft.engines):
        comp = aircraft.component(item.component)
        x = np.clip(comp.station_of(item.position_m), 0.0, comp.length_m)
        c = comp.dcm
        rho = c @ (item.position_m - comp.root_m - x * comp.axes_in_body[:, 0])
        mass = item.mass_kg
        j = mass * (rho @ rho * np.eye(3) - np.outer(rho, rho)) + c @ item.inertia_kg_m2 @ c.T
        names.append(comp.name)
        xs.append(np.array([x]))
        mbars.append(_mbar(np.array([mass]), (mass * rho)[None, :], j[None]))
    return MassPoints(tuple(names), tuple(xs), tuple(mbars))
