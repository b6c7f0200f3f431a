"""A spanwise lift slope on the strips of flexsim.model.beam_aero (WingAero.lift_slope_per_rad).

The option scales each strip's airloads, steady and unsteady, by lift_slope / 2π, i.e. as a strip in air of density
ρ lift_slope / 2π (every term of the Peters airloads is proportional to ρ; reference §1.3): a uniform slope c_lα on
the strips equals thin-airfoil strips (2π) in air of density ρ c_lα / 2π — steady loads and the whole linear
aeroelastic state matrix, to round-off (1e-12 relative). The default (2π) is thin-airfoil theory unchanged.
"""

import numpy as np
import pytest

from flexsim.model.beam_aero import StripAirloads, TunnelFlow, WingAero, aeroelastic_system, static_stiffness
from flexsim.structure.strain_beam import BeamProperties, beam_kinematics


def _wing():
    return BeamProperties(length_m=4.0, n_elements=4, gj_nm2=1e4, ei_flap_nm2=2e4, ei_chord_nm2=4e6,
                          mass_kg_per_m=0.75, torsion_inertia_kg_m=0.1, flap_inertia_kg_m=1e-3,
                          chord_inertia_kg_m=0.05, root_rotation=[[1, 0, 0], [0, np.cos(0.05), -np.sin(0.05)],
                                                                  [0, np.sin(0.05), np.cos(0.05)]])


def test_a_uniform_lift_slope_equals_thin_airfoil_strips_in_scaled_air():
    beam = _wing()
    q = 0.01 * np.sin(np.arange(beam.n_coordinates) + 1.0)
    kin = beam_kinematics(beam, q)
    slope = 5.0
    given = WingAero(chord_m=1.0, axis_fraction=0.4, lift_slope_per_rad=slope)
    thin = WingAero(chord_m=1.0, axis_fraction=0.4)
    flow, scaled = TunnelFlow(20.0, 1.2), TunnelFlow(20.0, 1.2 * slope / (2 * np.pi))
    qa = StripAirloads(given, flow).generalized_force(beam, kin)
    qb = StripAirloads(thin, scaled).generalized_force(beam, kin)
    assert np.allclose(qa, qb, rtol=1e-12, atol=1e-12 * np.abs(qb).max())
    ka = static_stiffness(beam, q, None, given, flow)
    a = aeroelastic_system(beam, given, flow, q, ka).state_matrix
    b = aeroelastic_system(beam, thin, scaled, q, ka).state_matrix
    assert np.allclose(a, b, rtol=1e-12, atol=1e-12 * np.abs(b).max())


def test_a_strip_without_lift_slope_carries_no_airload():
    beam = _wing()
    kin = beam_kinematics(beam, np.zeros(beam.n_coordinates))
    aero = WingAero(chord_m=1.0, lift_slope_per_rad=[2 * np.pi, 2 * np.pi, 2 * np.pi, 0.0])
    full = WingAero(chord_m=1.0, lift_slope_per_rad=[2 * np.pi, 2 * np.pi, 2 * np.pi, 2 * np.pi])
    qa = StripAirloads(aero, TunnelFlow(20.0, 1.2)).generalized_force(beam, kin)
    qb = StripAirloads(full, TunnelFlow(20.0, 1.2)).generalized_force(beam, kin)
    n = beam.n_coordinates // beam.n_elements
    assert np.abs(qa[-n:]).max() == 0.0 and np.abs(qb[-n:]).max() > 0.0  # the tip element's strains: no load


@pytest.mark.parametrize("value", [-1.0, np.nan, 20.0, [1.0, 2.0]])
def test_bad_lift_slope_names_the_field(value):
    beam = _wing()
    with pytest.raises(ValueError, match="lift_slope_per_rad"):
        aero = WingAero(chord_m=1.0, lift_slope_per_rad=value)
        aero.strips(beam, beam_kinematics(beam, np.zeros(beam.n_coordinates)))
