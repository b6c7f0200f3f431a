"""The horizontal tail's downwash lag (:mod:`flexsim._kernels.downwash_lag`, ``Terms(aero_terms=(DownwashLag(),))``) against the
closed form of the tail's alpha-dot derivatives (Etkin & Reid 1996 ch. 5; USAF DATCOM sec. 7.4.4):
C_L_alpha_dot = 2 a_t V_H (d eps/d alpha), C_m_alpha_dot = -C_L_alpha_dot (l / c_bar) with l the tail's arm from the CG;
off by default, nothing else changed, refused where there is no downwash to lag; its switch is its own options class,
which the terms record by name and read back."""

from __future__ import annotations

import math

import numpy as np
import pytest

from flexsim._kernels.downwash_lag import DownwashLag
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.atmosphere import isa
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.model.terms import Terms, aero_term_options

QS = AeroOptions("quasi-steady")
ALTITUDE_M, SPEED_M_S = 3000.0, 190.0


@pytest.fixture(scope="module")
def models():
    gtm = load_aircraft("gtm")
    return AircraftModel(gtm, terms=Terms(aero=QS)), AircraftModel(gtm, terms=Terms(aero=QS, aero_terms=(DownwashLag(),)))


def _state(model):
    x = model.layout.zeros()
    x[model.layout.position] = [0.0, 0.0, -ALTITUDE_M]
    x[model.layout.velocity.start] = SPEED_M_S
    x[model.layout.velocity.start + 2] = 8.0  # w [m/s]: alpha 0.042 rad
    x[model.layout.velocity.start + 4] = 0.02  # pitch rate q [rad/s]
    return x


def _handbook(model):
    """C_L_alpha_dot, the wing-to-tail distance l_t (the lag's path), the tail's quarter-chord x, the density and
    (d eps/d alpha)_0 l_t / beta^2 [m], from the strips and the
    aircraft file, written independently of the term's module (Etkin & Reid's form, with a_t S_t = sum c w Cl_a0 nz^2
    of the tail strips at Mach M: a_t = Cl_a0 / beta, d eps/d alpha = gradient / beta)."""
    s, gtm = model.aero.strips, model.aircraft
    comps = np.array(s.component)
    dcm = np.stack([gtm.component(c).dcm for c in s.component])
    d_body = np.einsum("sji,sj->si", dcm, s.d)
    n_body = np.einsum("sji,sj->si", dcm, s.n)
    x_qc = s.position_body_m[:, 0] - (s.a + 0.5) * s.semichord_m * d_body[:, 0]
    wing, tail = np.isin(comps, ("right_wing", "left_wing")), np.isin(comps, ("right_htail", "left_htail"))
    cla_w = s.lift_slope0 * s.semichord_m * s.width_m
    x_wing = (cla_w * x_qc)[wing].sum() / cla_w[wing].sum()
    nz = n_body[:, 2]
    x_tail = (cla_w * nz * x_qc)[tail].sum() / (cla_w * nz)[tail].sum()
    x_tail_ea = (cla_w * nz**2 * s.position_body_m[:, 0])[tail].sum() / (cla_w * nz**2)[tail].sum()
    l_t = x_wing - x_tail
    state = isa(ALTITUDE_M)
    mach = math.hypot(SPEED_M_S, 8.0) / state.speed_of_sound
    beta = 1.0 if gtm.aero_settings.compressibility == "none" else math.sqrt(1.0 - mach**2)  # Prandtl-Glauert
    a_t_s_t = (2.0 * s.semichord_m * s.width_m * s.lift_slope0 * nz**2)[tail].sum() / beta
    ref = model.reference_geometry
    deps = gtm.aero_settings.downwash_gradient / beta
    return dict(c_l_ad=2.0 * a_t_s_t * l_t / (ref.area_m2 * ref.mac_m) * deps, l_t=l_t, x_tail=x_tail,
                rho=state.density, x_tail_ea=x_tail_ea, lag_m=gtm.aero_settings.downwash_gradient * l_t / beta**2)


def test_handbook_alpha_dot_derivatives(models):
    plain, lag = models
    x, u = _state(plain), np.array([5e4, 0.0, -0.02, 0.0])
    de = lag.generalized_forces(x, u)[0] - plain.generalized_forces(x, u)[0]
    # only the w column changes: an apparent mass of w_dot
    assert np.all(np.delete(de, 2, axis=1) == 0.0) and de[2, 2] > 0.0
    hb = _handbook(plain)
    c_l_ad, l_t, x_tail, rho = hb["c_l_ad"], hb["l_t"], hb["x_tail"], hb["rho"]
    assert 10.0 < l_t < 25.0  # the GTM's wing-to-tail distance [m] (a sanity bound on the geometry read)
    ref = plain.reference_geometry
    # Z = -(rho S c_bar / 4) C_L_alpha_dot w_dot, so E[2, 2] grows by rho S c_bar C_L_alpha_dot / 4 (round-off only)
    assert de[2, 2] == pytest.approx(rho * ref.area_m2 * ref.mac_m * c_l_ad / 4.0, rel=1e-12)
    # the rigid-body rows: the resultant of the tail strips' extra lift dL_j = rho/beta^2 k_j w_dot along -n_j at their
    # elastic-axis points r_j (E = -df/dw_dot: +dL_j n_j on the force rows, +dL_j r_j x n_j on the moment rows about o)
    s = plain.aero.strips
    dcm = np.stack([plain.aircraft.component(c).dcm for c in s.component])
    n_body = np.einsum("sji,sj->si", dcm, s.n)
    tail = np.isin(np.array(s.component), ("right_htail", "left_htail"))
    lift = np.where(tail, rho * s.semichord_m * s.width_m * s.lift_slope0 * n_body[:, 2], 0.0) * hb["lag_m"]
    expected = np.concatenate([lift @ n_body, lift @ np.cross(s.position_body_m, n_body)])
    np.testing.assert_allclose(de[0:6, 2], expected, rtol=1e-10, atol=1e-10 * np.abs(expected).max())
    # the pitching moment about the CG against the handbook's C_m_alpha_dot = -C_L_alpha_dot (x_cg - x_t) / c_bar, x_t
    # the tail's lift-weighted elastic axis, where the strips' lift acts (the remainder, 0.4 % on the GTM: the lift's
    # body-x component at the tail's height above the CG); the handbook's x_t at the quarter chords gives 2.6 % less
    cg = plain.structure.mass_properties.cg_m
    m_cg = de[4, 2] - (cg[2] * de[0, 2] - cg[0] * de[2, 2])  # -dM_cg/dw_dot, moved to the left-hand side
    c_m_ad = -4.0 * m_cg / (rho * ref.area_m2 * ref.mac_m**2)
    assert c_m_ad < 0.0  # pitch damping: the lag adds to the short period's damping
    assert c_m_ad == pytest.approx(-c_l_ad * (cg[0] - hb["x_tail_ea"]) / ref.mac_m, rel=5e-3)
    assert c_m_ad / (-c_l_ad * (cg[0] - x_tail) / ref.mac_m) == pytest.approx(1.026, abs=0.003)


def test_off_by_default_nothing_else_changed(models):
    plain, lag = models
    assert Terms().aero_term(DownwashLag) is None and lag.terms.aero_term(DownwashLag) == DownwashLag()
    assert DownwashLag in aero_term_options() and lag.terms.record()["aero_terms"] == [{"term": "DownwashLag"}]
    assert Terms.from_record(lag.terms.record()) == lag.terms
    assert Terms.from_record({**plain.terms.record(), "downwash_lag": True}) == lag.terms  # an earlier record's flag
    default = AircraftModel(plain.aircraft, terms=Terms(aero=QS, aero_terms=()))
    assert np.array_equal(default.kernel_data.F, plain.kernel_data.F, equal_nan=True) and np.array_equal(default.kernel_data.I, plain.kernel_data.I)
    # an E term: the explicit aerodynamic force (static margins, outputs) and the right-hand side's f are unchanged
    x, u = _state(plain), np.array([5e4, 0.0, -0.02, 0.0])
    assert np.array_equal(lag.aerodynamic_force(x, u), plain.aerodynamic_force(x, u))
    assert np.array_equal(lag.generalized_forces(x, u)[1], plain.generalized_forces(x, u)[1])


def test_refused_where_there_is_nothing_to_lag(models):
    plain, _ = models
    with pytest.raises(ValueError, match=r"aero_terms = \(1,\): 1 is not the options of an aerodynamic term"):
        Terms(aero_terms=(1,))
    with pytest.raises(ValueError, match="each term at most once"):
        Terms(aero_terms=(DownwashLag(), DownwashLag()))
    with pytest.raises(ValueError, match=r"aero_terms = \(DownwashLag\(\),\): a model without aerodynamics"):
        Terms(aero=None, aero_terms=(DownwashLag(),))
    with pytest.raises(ValueError, match=r"aero_terms: DownwashLag\(\): this model has no wing downwash"):
        AircraftModel(plain.aircraft, terms=Terms(aero=AeroOptions("quasi-steady", downwash=False), aero_terms=(DownwashLag(),)))
