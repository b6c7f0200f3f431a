"""The range of the linear structure, stated: one check used by the trim, the flutter search, ``simulate`` and the
environments.

The paper's structure (Tuzcu & Nguyen 2014, eqs. 1 and 14; :mod:`flexsim.structure.kinematic_map`) moves each beam
point by ``e3 U(x) q`` and twists each section by ``Psi(x) xi``: displacements and rotations enter linearly, so the
beam neither shortens as it bends nor turns its sections through finite angles. That is exact in the limit of small
deflections and errs increasingly beyond. The limits below are where the error reaches
:data:`LINEAR_RANGE_ERROR` (2 %), from two closed forms:

* **Bending** — a cantilever under a dead tip load P. Linear theory gives the tip deflection P L^3 / (3 EI); the
  exact (elastica) solution, EI theta'' = -P cos(theta), theta(0) = 0, theta'(L) = 0, gives less (Bisshopp &
  Drucker 1945, Q. Appl. Math. 3(3), 272-275: 0.30172 L at P L^2 / EI = 1, where the linear 0.33333 L is 10.5 %
  high). The linear value is 2 % above the elastica's at P L^2 / EI = 0.4219, a linear tip deflection of
  0.1406 L (elastica 0.1379 L, tip slope 11.9 deg, the tip 1.2 % of L closer to the root): hence
  :data:`DEFLECTION_LIMIT_FRACTION` = 0.14 (``tests/model/test_linear_range.py`` integrates the elastica).
* **Twist** — a section twisted by psi moves a point at distance d from the elastic axis by d sin(psi) across the
  chord line and d (1 - cos psi) along it; the linear map gives d psi and 0. The first errs by
  1 - sin(psi)/psi = 2 % at psi = 0.3475 rad (19.9 deg): :data:`TWIST_LIMIT_RAD`.

Beyond either limit the answers of the linear structure are outside its validity; the geometrically nonlinear
beam (docs/nonlinear-beams.md) is the model for them. :func:`linear_range_note` returns the one line the trim
(:attr:`flexsim.trimming.TrimPoint.linear_range`), ``flexsim trim``, ``flexsim flutter``, ``simulate``
(:meth:`flexsim.sim.result.SimulationResult.summary`) and the environments (``info["linear_range"]`` at reset) print.
"""

from __future__ import annotations

import math

import numpy as np

from flexsim.model.sensors import structural_sensors

__all__ = ["LINEAR_RANGE_ERROR", "DEFLECTION_LIMIT_FRACTION", "TWIST_LIMIT_RAD", "NONLINEAR_OPTION",
           "linear_range_note", "nonlinear_fields_note"]

#: Relative error of the linear structure at its stated limits [-] (module docstring).
LINEAR_RANGE_ERROR = 0.02
#: Largest |tip deflection| / beam length of the linear structure's range [-] (elastica, Bisshopp & Drucker 1945).
DEFLECTION_LIMIT_FRACTION = 0.14
#: Largest |tip twist| of the linear structure's range [rad]: 1 - sin(psi)/psi = 0.02.
TWIST_LIMIT_RAD = 0.3475
#: What to use beyond the range.
NONLINEAR_OPTION = "the geometrically nonlinear beam, Terms(nonlinear_beams=NonlinearBeams()), docs/nonlinear-beams.md"


def linear_range_note(model, x: np.ndarray, where: str = "", sensors: dict | None = None) -> str | None:
    """One line when state(s) ``x`` bend or twist a beam of the linear structure beyond its range, else None.

    Parameters
    ----------
    model : flexsim.model.aircraft_model.AircraftModel
        The model whose linear structure the states belong to (any variant; without elastic coordinates: None).
    x : ndarray, shape (n_states,) or (N, n_states)
        One state or a trajectory of states (the largest excursion counts); extra trailing entries (inflow states of
        an unsteady model's state) are ignored, as the sensors read the structural block only.
    where : str
        Optional context for the line (e.g. ``"at the flutter point"``), placed after the quantity.
    sensors : dict, optional
        ``structural_sensors(model)`` when the caller has it already (it costs about 0.8 ms on the GTM, 8 % of a trim).

    Returns
    -------
    str or None
        ``"linear structure beyond its range: right_wing tip deflection -6.667 m = 42 % of its 16 m length (limit
        14 %, where linear beam theory errs by 2 % against the elastica); results need the geometrically nonlinear
        beam, Terms(nonlinear_beams=NonlinearBeams()), docs/nonlinear-beams.md"`` for the worst beam (``... and N
        more beams`` when several are beyond).
    """
    worst, count = None, 0
    x = np.asarray(x, dtype=float)
    for name, sensor in (structural_sensors(model) if sensors is None else sensors).items():
        length = model.aircraft.component(name).length_m
        if x.ndim == 1:  # one state (a trim): plain dot products, no temporaries (this runs in every trim)
            w, psi = [float(x[sensor.q_idx] @ sensor.w_tip)], [float(x[sensor.xi_idx] @ sensor.psi_tip)]
            k_w = k_psi = 0
        else:
            w, psi = sensor.tip_deflection_m(x), sensor.tip_twist_rad(x)
            k_w, k_psi = int(np.argmax(np.abs(w))), int(np.argmax(np.abs(psi)))
        ratios = (abs(w[k_w]) / length / DEFLECTION_LIMIT_FRACTION, abs(psi[k_psi]) / TWIST_LIMIT_RAD)
        if max(ratios) <= 1.0:
            continue
        count += 1
        if ratios[0] >= ratios[1]:
            text = (f"{name} tip deflection {w[k_w]:+.4g} m = {abs(w[k_w]) / length:.0%} of its {length:g} m length"
                    f"{where} (limit {DEFLECTION_LIMIT_FRACTION:.0%}, where linear beam theory errs by "
                    f"{LINEAR_RANGE_ERROR:.0%} against the elastica)")
        else:
            text = (f"{name} tip twist {math.degrees(psi[k_psi]):+.3g} deg{where} (limit "
                    f"{math.degrees(TWIST_LIMIT_RAD):.0f} deg, where the linear section rotation errs by "
                    f"{LINEAR_RANGE_ERROR:.0%})")
        if worst is None or max(ratios) > worst[0] * (1.0 + 1e-6):  # ties (mirror halves): the first in file order
            worst = (max(ratios), text)
    if worst is None:
        return None
    more = f" and {count - 1} more beam{'s' if count > 2 else ''}" if count > 1 else ""
    return f"linear structure beyond its range: {worst[1]}{more}; results need {NONLINEAR_OPTION}"


def nonlinear_fields_note(aircraft) -> str | None:
    """One line naming the section fields of ``aircraft`` the linear structure does not use, else None.

    Parameters
    ----------
    aircraft : flexsim.aircraft.definition.Aircraft

    Returns
    -------
    str or None
        ``"sections.ei_chord_nm2 of right_wing, left_wing; sections.ea_n of right_wing: used by the geometrically
        nonlinear beam only (docs/nonlinear-beams.md); the linear structure (the paper's) bends each beam in one
        plane and twists it"``.
    """
    by_field: dict[str, list[str]] = {}
    for path in aircraft.nonlinear_beam_fields:  # components.<name>.sections.<field>
        _, name, _, field = path.split(".")
        by_field.setdefault(field, []).append(name)
    if not by_field:
        return None
    given = "; ".join(f"sections.{field} of {', '.join(names)}" for field, names in by_field.items())
    return (f"{given}: used by the geometrically nonlinear beam only (docs/nonlinear-beams.md); the linear "
            f"structure (the paper's) bends each beam in one plane and twists it")
