"""The bundled Pazy wing (flexsim/aircraft/data/pazy_wing.md) against its source beam and the literature.

* Mass: the spanwise integral of the section table equals the sum of the 16 node masses of the AePW3-LDWG equivalent
  beam (inertia_skin1.xlsx), 0.3566 kg, exactly by the construction (tributary densities, trapezoid rule; 1e-5
  relative asserted, the file's 6 printed digits).
* Natural frequencies, clamped, in vacuo, within 3 % of UM/NAST's beam on the same properties (4.191, 28.49, 41.88
  Hz; Riso & Cesnik, J. Aircraft 2023, tabulated in LDWG 03_2023_JA_Riso_Cesnik/01_Modal_Undeformed/00_Comparisons/
  GFEM_vs_Beam.xlsx) and of the ground vibration test (4.26, 28.5, 42.0 Hz; Avin et al., AIAA J. 2022): the beam's
  stiffness couplings left out of flexsim's uncoupled linear structure and the shape-function truncation (< 0.5 %,
  pazy_wing.md) stay within it.
"""

from __future__ import annotations

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel
from flexsim.structure.model import StructuralModel

UM_NAST_HZ = (4.1906, 28.493, 41.879)  # out-of-plane 1, 2, torsion 1 (with skin)
GVT_HZ = (4.26, 28.5, 42.0)


@pytest.fixture(scope="module")
def pazy():
    return load_aircraft("pazy_wing")


def test_mass_is_the_sum_of_the_node_masses(pazy):
    sections = pazy.component("right_wing").sections
    integral = np.trapezoid(sections.mass_kg_per_m, sections.station_m)
    assert integral == pytest.approx(0.3565955, rel=1e-5)
    assert StructuralModel(pazy).mass_properties.mass_kg == pytest.approx(integral, rel=1e-9)


def test_natural_frequencies(pazy):
    modes = in_vacuo_modes(AircraftModel(pazy, variant="restrained")).modes[:3]
    assert [m.dominant_dof for m in modes] == ["right_wing bending 1", "right_wing bending 2", "right_wing torsion 1"]
    hz = [m.frequency_hz for m in modes]
    print(f"\nflexsim {np.round(hz, 3)} Hz, UM/NAST {UM_NAST_HZ}, GVT {GVT_HZ}")
    assert hz == pytest.approx(UM_NAST_HZ, rel=0.03)
    assert hz == pytest.approx(GVT_HZ, rel=0.03)
