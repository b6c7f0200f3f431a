"""Linear models for control design about the nonlinear trim: the free aircraft with geometrically nonlinear beams.

The state-space model ``dx_dot = A dx + B du, dy = C dx + D du`` of the free-flight equations of
:meth:`flexsim.model.flexible_aircraft.FlexibleAircraft.free_flight_rate` (quasi-steady strips on the deformed wing,
the preload's geometric stiffness included) about a :class:`~flexsim.trimming.flexible_trim.FlexibleTrimPoint`, as
:class:`flexsim.linear.control.LinearSystem` with named states, inputs and outputs — what
:func:`flexsim.linear.control.linear_system` returns for a model with ``Terms(nonlinear_beams=...)``.

* States: the free-flight state without the position ``X`` (the rate does not depend on it at a held density):
  the attitude quaternion ``q0..q3`` (body→NED; one direction of it, its norm, is a neutral root), the strains
  ``strain_<component>_<element>_<extension|twist|flap_curvature|chord_curvature>`` [-, 1/m], the body velocity
  ``u_m_s, v_m_s, w_m_s``, rates ``p_rad_s, q_rad_s, r_rad_s`` and the strain rates (``strain_rate_...``).
  A is :meth:`~flexsim.model.flexible_aircraft.FlexibleAircraft.free_flight_jacobian`, the matrix whose eigenvalues
  :func:`flexsim.linear.flexible_stability.free_aircraft_spectrum` names.
* Inputs: thrust [N], aileron, elevator, rudder [rad] and the vertical gust ``gust_up_m_s`` (air moving up, uniform
  over the aircraft, the wind of :func:`flexsim.sim.flexible_run.simulate_flexible`), central differences.
* Outputs, per flexible component: ``tip_deflection_<c>_m`` (the tip's displacement along body z from its jig
  position, down positive as the linear model's), its rate, ``tip_twist_<c>_rad`` (the integrated twist strain
  ``Σ κ1 ℓ``, nose up on the right wing), its rate, ``root_bending_moment_<c>_N_m`` (``EI_flap κ2`` of the root
  element); optionally followed by the states. D = 0.

Units SI and radians; body axes x forward, z down.
"""

from __future__ import annotations

import numpy as np

from flexsim.io.vocabulary import check_names
from flexsim.linear.control import INPUT_NAMES, LinearSystem, ModelRecord
from flexsim.structure.free_flexible import quaternion_matrix
from flexsim.structure.strain_beam import STRAIN_NAMES
from flexsim.trimming.flexible_trim import FlexibleTrimPoint

__all__ = ["flexible_linear_system"]


def _state_names(flex) -> tuple[str, ...]:
    strains = []
    for comp, beam in zip(flex.beam_components, flex.structure.beams):
        kinds = STRAIN_NAMES if beam.extensible else STRAIN_NAMES[1:]
        strains += [f"{comp}_{j}_{k.replace(' ', '_')}" for j in range(beam.n_elements) for k in kinds]
    return (("q0", "q1", "q2", "q3") + tuple(f"strain_{s}" for s in strains)
            + ("u_m_s", "v_m_s", "w_m_s", "p_rad_s", "q_rad_s", "r_rad_s") + tuple(f"strain_rate_{s}" for s in strains))


def _sensor_rows(flex, structure, eps: np.ndarray) -> np.ndarray:
    """Rows (5 per flexible component, module docstring) of C over ``[ε (n), ε̇ (n)]`` at strains ``eps``: the
    derivatives of the aircraft's tip heights, tip twists and root moments
    (:meth:`~flexsim.model.flexible_aircraft.FlexibleAircraft.tip_heights_m` and its siblings) by central differences;
    a rate's row is its quantity's row on ``ε̇`` (the trim has ``ε̇ = 0``)."""
    n = structure.n_strains

    def sensors(e):
        return np.stack([-flex.tip_heights_m(e), flex.tip_twists_rad(e), flex.root_bending_moments_n_m(e)])

    jac = np.zeros((3, len(structure.beams), n))
    for k in range(n):
        h = 1e-6 * max(1.0, abs(eps[k]))
        up, down = eps.copy(), eps.copy()
        up[k] += h
        down[k] -= h
        jac[:, :, k] = (sensors(up) - sensors(down)) / (2.0 * h)
    zero = np.zeros(n)
    rows = []
    for i in range(len(structure.beams)):
        deflection, twist, root = jac[:, i]
        rows += [np.concatenate([deflection, zero]), np.concatenate([zero, deflection]), np.concatenate([twist, zero]),
                 np.concatenate([zero, twist]), np.concatenate([root, zero])]
    return np.array(rows)


def flexible_linear_system(model, point: FlexibleTrimPoint, *, state_outputs: bool = False) -> LinearSystem:
    """The linear model of the free aircraft with nonlinear beams about its nonlinear trim ``point`` (module docstring).

    Parameters
    ----------
    model : AircraftModel
        The model the trim was computed for (its gravity).
    point : FlexibleTrimPoint
    state_outputs : bool
        Append every state to the outputs (C = [S; I]).

    Returns
    -------
    LinearSystem
    """
    if not isinstance(point, FlexibleTrimPoint):
        raise ValueError(f"point = {point!r}: the linear model about the nonlinear trim needs a FlexibleTrimPoint "
                         "(fs.trim of a model with Terms(nonlinear_beams=...))")
    flex = point.aircraft
    structure = flex.free_structure(model.terms.gravity_m_s2)
    y0, u0, rho = point.state(), np.asarray(point.controls, float), point.density_kg_m3
    keep = np.arange(3, y0.size)
    a = flex.free_flight_jacobian(structure, y0, u0, rho)[3:]
    b = np.zeros((keep.size, len(INPUT_NAMES)))
    for j in range(4):
        h = 1e-6 * max(1.0, abs(u0[j]))
        up, down = u0.copy(), u0.copy()
        up[j] += h
        down[j] -= h
        b[:, j] = (flex.free_flight_rate(structure, 0.0, y0, up, rho)
                   - flex.free_flight_rate(structure, 0.0, y0, down, rho))[3:] / (2.0 * h)
    gust_body = quaternion_matrix(y0[3:7]).T @ np.array([0.0, 0.0, -1.0])  # air moving up, body axes, per m/s
    h = 1e-4
    b[:, 4] = (flex.free_flight_rate(structure, 0.0, y0, u0, rho, h * gust_body)
               - flex.free_flight_rate(structure, 0.0, y0, u0, rho, -h * gust_body))[3:] / (2.0 * h)
    names = []
    for comp in flex.beam_components:
        names += [f"tip_deflection_{comp}_m", f"tip_deflection_rate_{comp}_m_s", f"tip_twist_{comp}_rad",
                  f"tip_twist_rate_{comp}_rad_s", f"root_bending_moment_{comp}_N_m"]
    names = check_names("signal", names)
    n = structure.n_strains
    sensors = _sensor_rows(flex, structure, y0[7:7 + n])
    c = np.zeros((len(names), keep.size))
    c[:, 4:4 + n] = sensors[:, :n]  # keep = y[3:]: quaternion (4), ε (n), v, ω (6), ε̇ (n)
    c[:, 10 + n:] = sensors[:, n:]
    states = _state_names(flex)
    if state_outputs:
        c = np.vstack([c, np.eye(keep.size)])
        names = names + states
    return LinearSystem(a, b, c, np.zeros((c.shape[0], b.shape[1])), states, INPUT_NAMES, names, keep, y0, u0,
                        point.manoeuvre, ModelRecord.of(model))
