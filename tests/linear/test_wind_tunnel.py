"""Wind-tunnel inputs, the divergence finder and the compressibility switch.

* Goland wing (Goland 1945: 137.2 m/s, 70.7 rad/s, incompressible strip theory; SI data of Patil, Hodges
  & Cesnik 2001): switched off (the bundled file), Theodorsen p-k and Peters N = 6 within 2 %; with the
  Prandtl-Glauert factor on, the flutter speed is 3.4 % lower (M = 0.39 at flutter; regression values).
* Divergence of a uniform unswept cantilever in strip theory (Hodges & Pierce, *Introduction to
  Structural Dynamics and Aeroelasticity*, 2nd ed., 2011, sec. 4.2): q_D = pi^2 GJ / (4 L^2 e c Cl_alpha),
  U_D = sqrt(2 q_D / rho), e the distance of the aerodynamic centre (quarter chord) ahead of the elastic axis.
  The exact divergence mode is sin(pi x / 2L), the model's first torsion shape, so the finder must
  reproduce it to the Brent tolerance (1e-6 relative asserted).
* A density given directly equals the ISA altitude with that density.
"""

import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.flutter import FlutterNotFound, _growth, wind_tunnel
from flexsim.linear.stability import spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions

GOLAND_SPEED, GOLAND_FREQ = 137.2, 70.7  # Goland (1945) via Patil, Hodges & Cesnik (2001), Table 1


@pytest.fixture(scope="module")
def goland():
    return load_aircraft("goland_wing")


def goland_divergence_closed_form(rho: float) -> float:
    """U_D [m/s] of the Goland wing in incompressible strip theory, Cl_alpha = 2 pi (Hodges & Pierce sec. 4.2)."""
    gj, length, chord = 0.987e6, 6.096, 1.8288
    e = (0.33 - 0.25) * chord  # aerodynamic centre at the quarter chord, elastic axis at 33 % chord
    q_d = math.pi**2 * gj / (4.0 * length**2 * e * chord * 2.0 * math.pi)
    return math.sqrt(2.0 * q_d / rho)


def test_bundled_goland_file_is_incompressible_and_the_default_elsewhere_is_prandtl_glauert(goland):
    assert goland.aero_settings.compressibility == "none"
    assert load_aircraft("gtm").aero_settings.compressibility == "prandtl-glauert"
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    assert model.aero.compressibility_factor(0.6) == pytest.approx(0.8, rel=1e-15)  # sqrt(1 - 0.36)
    off = AircraftModel(load_aircraft("gtm"), aero=AeroOptions("quasi-steady", compressibility="none"))
    assert off.aero.compressibility_factor(0.6) == 1.0
    with pytest.raises(ValueError, match="compressibility = 'glauert'"):
        AeroOptions(compressibility="glauert")


@pytest.mark.parametrize("aero, speed_pg", [("theodorsen", 132.35), ("unsteady", 131.64)])
def test_goland_flutter_with_and_without_prandtl_glauert(goland, aero, speed_pg):
    off = wind_tunnel(goland, aero_model=aero, speed_range=(120.0, 150.0), speed_step=10.0, divergence=False)
    on = wind_tunnel(goland, aero_model=aero, speed_range=(120.0, 150.0), speed_step=10.0, divergence=False,
                     compressibility="prandtl-glauert")
    assert off.compressibility == "none" and on.compressibility == "prandtl-glauert"
    assert off.flutter_speed_m_s == pytest.approx(GOLAND_SPEED, rel=0.02)
    assert off.flutter_frequency_rad_s == pytest.approx(GOLAND_FREQ, rel=0.02)
    # switching Prandtl-Glauert on lowers the flutter speed by ~3.4 % (M = 0.39 at flutter); regression value
    assert on.flutter_speed_m_s == pytest.approx(speed_pg, abs=0.05)
    assert on.flutter_speed_m_s / off.flutter_speed_m_s == pytest.approx(0.966, abs=0.003)


@pytest.mark.parametrize("rho", [1.225, 1.02])
def test_goland_divergence_matches_strip_theory_closed_form(goland, rho):
    res = wind_tunnel(goland, aero_model="quasi-steady", speed_range=(200.0, 320.0), speed_step=20.0, density_kg_m3=rho,
                      tol_m_s=1e-6, flutter=False)
    assert res.density_kg_m3 == rho
    assert res.divergence_speed_m_s == pytest.approx(goland_divergence_closed_form(rho), rel=1e-6)


def test_density_given_directly_equals_the_isa_altitude_with_that_density(goland):
    from flexsim.atmosphere import isa_density

    rho = isa_density(2000.0)
    a = wind_tunnel(goland, aero_model="quasi-steady", speed_range=(40.0, 120.0), speed_step=20.0, altitude_m=2000.0,
                    divergence=False)
    b = wind_tunnel(goland, aero_model="quasi-steady", speed_range=(40.0, 120.0), speed_step=20.0, density_kg_m3=rho,
                    divergence=False)
    assert a.flutter_speed_m_s == pytest.approx(b.flutter_speed_m_s, rel=1e-9)
    assert a.first_instability == "flutter"


def test_wind_tunnel_errors_are_true(goland):
    bare = goland.subset(["right_wing"])
    from dataclasses import replace

    no_aero = replace(bare, components=(replace(bare.components[0], aero=None, control_surface=None),))
    with pytest.raises(ValueError, match="no aerodynamic strips"):
        wind_tunnel(no_aero)
    with pytest.raises(ValueError, match="speed_range"):
        wind_tunnel(goland, speed_range=(100.0, 50.0))
    with pytest.raises(ValueError, match="air_density_kg_m3 = -1.0"):
        wind_tunnel(goland, density_kg_m3=-1.0)
    with pytest.raises(ValueError, match="only for the restrained variant"):
        AircraftModel(goland, air_density_kg_m3=1.0)
    with pytest.raises(FlutterNotFound, match="already unstable at the lowest speed 140"):
        wind_tunnel(goland, aero_model="unsteady", speed_range=(140.0, 150.0), speed_step=5.0, divergence=False)


def test_round_off_on_a_neutral_structure_is_not_an_instability(goland):
    """An undamped structure in vacuum has real parts of round-off size (either sign): growth 0, not > 0."""
    model = AircraftModel(goland, variant="restrained", aero=None, gravity_m_s2=0.0, structural_damping=0.0)
    spec = spectrum(model, model.layout.zeros(), np.zeros(4))
    assert max(abs(m.eigenvalue.real) for m in spec.modes) < 1e-9 * max(abs(m.eigenvalue) for m in spec.modes)
    assert _growth(spec) == 0.0
