"""The stall estimate of the flutter search range (``flexsim.linear.envelope``) uses the model's own terms.

Its quasi-steady sibling of an unsteady model carries every term of the model, so a heavier gravity (the weight
the lift must carry at stall) raises the estimate like the level-flight lift balance L = W at the stall angle:
V_stall proportional to sqrt(g) for a linear lift curve (3 %: the Prandtl-Glauert factor and the elastic twist
change with the speed), and the unsteady model's estimate equals that of a quasi-steady model with the same terms
(1e-12), here a fixed density of the aerodynamics (``Terms.aero_density_kg_m3``, the density of 9144 m).
"""

from __future__ import annotations

import math
from dataclasses import replace

import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.atmosphere import isa_density
from flexsim.linear.envelope import _stall_mach
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre


def test_the_stall_estimate_follows_the_models_gravity():
    gtm = load_aircraft("gtm")
    man = SteadyManoeuvre.level(3048.0, mach=0.5)
    base = AircraftModel(gtm)
    heavy = AircraftModel(gtm, terms=replace(base.terms, gravity_m_s2=1.5 * base.terms.gravity_m_s2))
    m0, _ = _stall_mach(base, man)
    m1, _ = _stall_mach(heavy, man)
    assert m1 / m0 == pytest.approx(math.sqrt(1.5), rel=0.03)


def test_the_stall_estimate_of_an_unsteady_model_is_its_quasi_steady_siblings_with_every_term():
    gtm = load_aircraft("gtm")
    man = SteadyManoeuvre.level(3048.0, mach=0.5)
    terms = replace(AircraftModel(gtm).terms, aero_density_kg_m3=float(isa_density(9144.0)))
    unsteady = AircraftModel(gtm, terms=terms)
    quasi_steady = AircraftModel(gtm, terms=replace(terms, aero=replace(terms.aero, model="quasi-steady")))
    assert _stall_mach(unsteady, man)[0] == pytest.approx(_stall_mach(quasi_steady, man)[0], rel=1e-12)
