"""The bundled PHC wing (flexsim/aircraft/data/phc_wing.md) against closed forms and Patil, Hodges & Cesnik (2001).

* Natural frequencies, clamped, in vacuo: the exact Euler-Bernoulli and uniform-torsion values (the shape functions
  are the exact modes: 1e-6 relative asserted); flap 1 and torsion 1 within 2 % of PHC (their figure of frequencies
  against tip displacement at its smallest displacement, digitised in AeroBeams.jl
  test/referenceData/SMW/freqsVsTipOOP.txt: 2.268 and 31.07 rad/s; the digitisation scatters by about 1 %).
* Linear flutter and divergence at 20 km in the wind-tunnel mode: PHC 32.21 m/s, 22.61 rad/s and 37.29 m/s (quoted
  in AeroBeams.jl test/SMWLinearFlutter.jl), within 2 % with Peters' finite-state inflow (PHC's model) and with
  Theodorsen's p-k; the divergence speed also against strip theory's closed form, U_D = sqrt(2 q_D / rho),
  q_D = pi^2 GJ / (4 L^2 e c Cl_alpha), e = c/4 (Hodges & Pierce 2011, sec. 4.2), to the 1e-6 search tolerance.
The published values are printed beside the computed ones (``pytest -s``); they do not enter the computation.
"""

from __future__ import annotations

import math

import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.atmosphere import isa_density
from flexsim.linear.flutter import wind_tunnel
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel

L, M, I_THETA, EI, GJ, CHORD = 16.0, 0.75, 0.1, 2.0e4, 1.0e4, 1.0
PHC_FLUTTER_SPEED, PHC_FLUTTER_FREQ, PHC_DIVERGENCE = 32.21, 22.61, 37.29  # PHC (2001)
PHC_FLAP1, PHC_TORSION1 = 2.268, 31.07  # PHC (2001) figure, digitised (AeroBeams.jl freqsVsTipOOP.txt)


@pytest.fixture(scope="module")
def wing():
    return load_aircraft("phc_wing")


def test_natural_frequencies(wing):
    omega = in_vacuo_modes(AircraftModel(wing, variant="restrained")).frequencies_rad_s
    flap = [(beta / L) ** 2 * math.sqrt(EI / M) for beta in (1.87510407, 4.69409113, 7.85475744)]
    torsion = math.pi / (2.0 * L) * math.sqrt(GJ / I_THETA)
    assert omega[:4] == pytest.approx(sorted([*flap, torsion]), rel=1e-6)
    print(f"\nflap 1 {omega[0]:.4f} rad/s (PHC {PHC_FLAP1}), torsion 1 {omega[2]:.4f} rad/s (PHC {PHC_TORSION1})")
    assert omega[0] == pytest.approx(PHC_FLAP1, rel=0.02)
    assert omega[2] == pytest.approx(PHC_TORSION1, rel=0.02)


@pytest.mark.parametrize("aero_model", ["unsteady", "theodorsen"])
def test_linear_flutter_and_divergence_at_20_km(wing, aero_model):
    res = wind_tunnel(wing, aero_model=aero_model, altitude_m=20000.0, speed_range=(5.0, 45.0), speed_step=2.0,
                      tol_m_s=1e-6, divergence=aero_model == "unsteady")
    print(f"\n{aero_model}: flutter {res.flutter_speed_m_s:.3f} m/s (PHC {PHC_FLUTTER_SPEED}), "
          f"{res.flutter_frequency_rad_s:.3f} rad/s (PHC {PHC_FLUTTER_FREQ}); divergence {res.divergence_speed_m_s} m/s "
          f"(PHC {PHC_DIVERGENCE})")
    assert res.flutter_speed_m_s == pytest.approx(PHC_FLUTTER_SPEED, rel=0.02)
    assert res.flutter_frequency_rad_s == pytest.approx(PHC_FLUTTER_FREQ, rel=0.02)
    if aero_model == "unsteady":
        q_d = math.pi**2 * GJ / (4.0 * L**2 * (0.25 * CHORD) * CHORD * 2.0 * math.pi)
        assert res.divergence_speed_m_s == pytest.approx(math.sqrt(2.0 * q_d / isa_density(20000.0)), rel=1e-6)
        assert res.divergence_speed_m_s == pytest.approx(PHC_DIVERGENCE, rel=0.02)


def test_the_fields_of_the_nonlinear_beam_are_given_and_named(wing):
    assert wing.nonlinear_beam_fields == ("components.right_wing.sections.ei_chord_nm2",
                                          "components.right_wing.sections.flap_inertia_kg_m")
