"""A strain-based beam from section tables (flexsim.structure.beam_sections).

Invariants of the element integrals (exact for tables linear between stations): the total mass and first mass moment
are kept (1e-12 relative); uniform tables give the same uniform beam; a linear table's element means are the values
at the element mid-points; the compliance average of a stiffness that is uniform within each element is that
stiffness; the parallel-axis theorem takes the inertias to the mass centre.
"""

from dataclasses import replace

import numpy as np
import pytest

from flexsim.aircraft.sections import SectionTable
from flexsim.structure.beam_sections import beam_from_sections, element_means


def _table(x, **over):
    k = len(x)
    base = dict(station_m=np.array(x, float), mass_kg_per_m=np.full(k, 2.0), cg_offset_m=np.full(k, 0.01),
                torsional_inertia_kg_m=np.full(k, 0.01), ei_nm2=np.full(k, 5.0), gj_nm2=np.full(k, 7.0),
                chord_m=np.full(k, 0.1), ea_fraction=np.full(k, 0.44), ei_chord_nm2=np.full(k, 3e3),
                ea_n=np.full(k, 1e7), flap_inertia_kg_m=np.full(k, 1e-3))
    base.update({key: np.array(v, float) for key, v in over.items()})
    return SectionTable(**base)


def test_uniform_tables_give_the_uniform_beam_with_inertias_at_the_mass_centre():
    beam = beam_from_sections(_table([0.0, 0.3, 1.0]), 5)
    assert np.allclose(beam.mass_kg_per_m, 2.0, rtol=1e-12) and np.allclose(beam.ei_flap_nm2, 5.0, rtol=1e-12)
    assert np.allclose(beam.gj_nm2, 7.0, rtol=1e-12) and np.allclose(beam.ea_n, 1e7, rtol=1e-12)
    assert np.allclose(beam.cg_offset_m, -0.01, rtol=1e-12)  # aft in the table, ahead (+e2) in the beam
    assert np.allclose(beam.torsion_inertia_kg_m, 0.01 - 2.0 * 0.01**2, rtol=1e-12)
    assert np.allclose(beam.chord_inertia_kg_m, 0.01 - 1e-3 - 2.0 * 0.01**2, rtol=1e-12)


def test_mass_and_its_first_moment_are_kept():
    x = [0.0, 0.1, 0.45, 0.5]
    m = [1.0, 0.5, 0.6, 4.0]
    cg = [0.0, 0.002, 0.001, 0.005]
    beam = beam_from_sections(_table(x, mass_kg_per_m=m, cg_offset_m=cg,
                                     torsional_inertia_kg_m=[0.01, 0.01, 0.01, 0.02]), 7)
    le = beam.length_m / 7
    fine = np.linspace(0.0, 0.5, 200001)
    total = np.trapezoid(np.interp(fine, x, m), fine)
    moment = np.trapezoid(np.interp(fine, x, m) * np.interp(fine, x, cg), fine)
    assert abs(beam.mass_kg_per_m.sum() * le / total - 1) < 1e-9
    assert abs(-(beam.mass_kg_per_m * beam.cg_offset_m).sum() * le / moment - 1) < 1e-8


def test_element_means_of_a_linear_table_are_the_mid_point_values():
    assert np.allclose(element_means([0.0, 2.0], [1.0, 5.0], 4), [1.5, 2.5, 3.5, 4.5], rtol=1e-14)


def test_bad_input_names_the_field():
    with pytest.raises(ValueError, match="n_elements"):
        beam_from_sections(_table([0.0, 1.0]), 0)
    with pytest.raises(ValueError, match="ei_chord_nm2"):
        beam_from_sections(replace(_table([0.0, 1.0]), ei_chord_nm2=None), 2)
    with pytest.raises(ValueError, match="station_m"):
        element_means([0.0, 0.0, 1.0], [1.0, 2.0, 3.0], 2)
