"""Model variants from one definition: free, restrained, quasi-rigid, component subsets."""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.modes import in_vacuo_modes
from flexsim.model.aircraft_model import AircraftModel, Variant


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


def test_layouts_of_variants(gtm):
    free = AircraftModel(gtm, aero=None)
    d = free.structure.dofs
    assert free.layout.n_states == 12 + 2 * (d.nq + d.nxi) == 12 * (1 + 2 + 2)  # paper: 12(1+m+n)
    restrained = AircraftModel(gtm, variant="restrained", aero=None)
    assert restrained.layout.n_states == 2 * (d.nq + d.nxi)
    rigid = AircraftModel(gtm, variant=Variant.QUASI_RIGID, aero=None)
    assert rigid.layout.n_states == 12
    # finite-state inflow: N = 6 states on each of the 2 x 10 wing and 2 x 6 stabilizer strips
    unsteady = AircraftModel(gtm, aero="unsteady")
    assert unsteady.layout.n_inflow == 6 * (2 * 10 + 2 * 6)
    assert unsteady.layout.n_states == 60 + unsteady.layout.n_inflow
    assert AircraftModel(gtm, aero="quasi-steady").layout.n_inflow == 0


def test_restrained_modes_are_the_elastic_modes_with_body_clamped(gtm):
    a = in_vacuo_modes(AircraftModel(gtm, variant="restrained"))
    assert a.n_rigid == 0
    assert a.frequencies_rad_s.min() > 1.0


def test_quasi_rigid_model_is_a_rigid_body(gtm):
    # With elastic coordinates frozen at zero, the rigid-body equations use M0's rigid block:
    # a thrust T along x gives v_dot = T / m at zero rates (Newton), and no elastic states exist.
    model = AircraftModel(gtm, variant="quasi-rigid", gravity_m_s2=0.0, aero=None)
    x = model.pack()
    dx = model.rhs(0.0, x, np.array([1e5, 0, 0, 0]))
    m0 = model.structure.inertia.m0[:6, :6]
    expected = np.linalg.solve(m0, model.structure.thrust.force(1e5, np.zeros(model.structure.dofs.nq))[:6])
    np.testing.assert_allclose(dx[model.layout.velocity], expected, rtol=1e-12)


def test_quasi_rigid_uses_frozen_deformation(gtm):
    d = AircraftModel(gtm).structure.dofs
    q0 = np.full(d.nq, 0.1)
    model = AircraftModel(gtm, variant="quasi-rigid", frozen_q=q0, gravity_m_s2=0.0)
    _, _, q, _, _ = model.unpack(model.pack())
    np.testing.assert_array_equal(q, q0)


def test_single_wing_subset_clamped_at_root(gtm):
    wing = gtm.subset(["right_wing"])
    assert wing.component_names == ("right_wing",)
    assert [e.name for e in wing.engines] == ["right_engine"]
    a = in_vacuo_modes(AircraftModel(wing, variant="restrained"))
    assert len(a.modes) == 4


def test_bad_variant_and_gravity_rejected(gtm):
    with pytest.raises(ValueError, match="variant = 'flying'"):
        AircraftModel(gtm, variant="flying")
    with pytest.raises(ValueError, match="gravity_m_s2"):
        AircraftModel(gtm, gravity_m_s2=-1.0)
