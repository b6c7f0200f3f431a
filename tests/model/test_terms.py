"""The physical terms chosen at model construction (:class:`flexsim.model.terms.Terms`): each switch does what its
documentation says, checked against the full model at a shifted input (an exact identity of the equations) or a
closed form; bad values are refused with the field named; the loose keyword arguments are the same terms."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.model.terms import Terms
from flexsim.trimming import SteadyManoeuvre, trim

QS = AeroOptions("quasi-steady")


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


@pytest.fixture(scope="module")
def point(gtm):
    """A level trim of the GTM at 3000 m, M 0.6, its elastic coordinates perturbed (so that q enters every term)."""
    p = trim(AircraftModel(gtm, aero="quasi-steady"), SteadyManoeuvre.level(3000.0, mach=0.6))
    x = p.x.copy()
    lay = AircraftModel(gtm, aero="quasi-steady").layout
    x[lay.q] += 0.05 * np.sin(np.arange(lay.q.stop - lay.q.start) + 1.0)
    x[lay.velocity.start + 4] = 0.02  # a pitch rate
    return x, p.u.copy()


@pytest.mark.parametrize("field, value, match", [
    ("gravity_m_s2", -1.0, "gravity_m_s2 = -1.0"), ("structural_damping", 1.0, "structural_damping = 1.0"),
    ("aero_density_kg_m3", 0.0, "aero_density_kg_m3 = 0.0"), ("compressibility_mach", 1.2, "compressibility_mach = 1.2"),
    ("force_resolution", "tilted", "force_resolution = 'tilted'"),
    ("thrust_follows_deflection", 1, "thrust_follows_deflection = 1"),
    ("aero_velocity_offset_m_s", (1.0, 2.0), "aero_velocity_offset_m_s .* 3 entries"),
    ("inertia_q_offset_m", (1.0, math.nan), "inertia_q_offset_m .* finite"), ("aero", "unsteady", "aero = 'unsteady'")])
def test_bad_values_name_the_field(field, value, match):
    with pytest.raises(ValueError, match=match):
        Terms(**{field: value})


def test_vacuum_refuses_aerodynamic_switches():
    with pytest.raises(ValueError, match="compressibility_mach = 0.8: a model without aerodynamics"):
        Terms(aero=None, compressibility_mach=0.8)


def test_keywords_are_the_same_terms(gtm, point):
    x, u = point
    loose = AircraftModel(gtm, aero="quasi-steady", gravity_m_s2=9.0, structural_damping=0.01, aero_density_kg_m3=0.8)
    terms = Terms(aero=QS, gravity_m_s2=9.0, structural_damping=0.01, aero_density_kg_m3=0.8)
    model = AircraftModel(gtm, terms=terms)
    assert loose.terms == terms == model.terms
    np.testing.assert_array_equal(loose.rhs(0.0, x, u), model.rhs(0.0, x, u))
    with pytest.raises(ValueError, match="terms and gravity_m_s2: give the physical terms either"):
        AircraftModel(gtm, terms=terms, gravity_m_s2=9.0)
    with pytest.raises(ValueError, match="inertia_q_offset_m: 2 entries"):
        AircraftModel(gtm, terms=Terms(inertia_q_offset_m=(0.0, 0.0)))


def test_record_is_json(gtm):
    model = AircraftModel(gtm, terms=Terms(aero=QS, compressibility_mach=0.8, aero_velocity_offset_m_s=(0.0, 0.0, 1.0)))
    rec = json.loads(json.dumps(model.terms.record()))
    assert rec["compressibility_mach"] == 0.8 and rec["aero"]["model"] == "quasi-steady"
    assert rec["aero_velocity_offset_m_s"] == [0.0, 0.0, 1.0] and rec["force_resolution"] == "full"
    assert json.loads(json.dumps(AircraftModel(gtm, aero=None).terms.record()))["aero"] is None


def test_frozen_compressibility_mach(gtm, point):
    """beta frozen at M_f: every strip's circulatory lift is that of the incompressible strips times
    1/sqrt(1 - M_f^2) (Prandtl-Glauert, Glauert 1928), whatever the flight Mach; frozen at the flight's own Mach
    number, the right-hand side is the full model's bit for bit."""
    x, u = point
    aero = AeroOptions("quasi-steady", downwash=False)
    m_f = 0.8
    frozen = AircraftModel(gtm, terms=Terms(aero=aero, compressibility_mach=m_f))
    flat = AircraftModel(gtm, aero=AeroOptions("quasi-steady", downwash=False, compressibility="none"))
    _, _, q, xi, vel = flat.unpack(x)
    rho = flat.air_density(x)
    lift_f = frozen.aero.strip_loads(q, xi, vel, np.zeros(0), u, rho, 0.3).lift_n_m
    lift_0 = flat.aero.strip_loads(q, xi, vel, np.zeros(0), u, rho, 0.3).lift_n_m
    np.testing.assert_allclose(lift_f, lift_0 / math.sqrt(1.0 - m_f**2), rtol=1e-13)
    full = AircraftModel(gtm, aero="quasi-steady")
    from flexsim.atmosphere import speed_of_sound

    mach = float(np.linalg.norm(vel[0:3]) / speed_of_sound(-x[2]))
    own = AircraftModel(gtm, terms=Terms(aero=QS, compressibility_mach=mach))
    np.testing.assert_allclose(own.rhs(0.0, x, u), full.rhs(0.0, x, u), rtol=0, atol=1e-13 * np.max(np.abs(full.rhs(0.0, x, u))))


def test_force_resolution_switches(gtm, point):
    """"normal": no drag and no lift tilt on any strip, the lift unchanged; "fin-normal": so on the fin's strips
    only (those without inflow states), the others as in the full resolution; ``fin_drag_per_lift``: the fin's drag
    kappa times its lift."""
    x, u = point
    full = AircraftModel(gtm, aero="quasi-steady")
    _, _, q, xi, vel = full.unpack(x)
    rho = full.air_density(x)
    loads = {r: AircraftModel(gtm, terms=Terms(aero=QS, force_resolution=r)).aero.strip_loads(q, xi, vel, np.zeros(0), u,
                                                                                             rho, 0.6)
             for r in ("full", "normal", "fin-normal")}
    fin = ~full.aero.strips.unsteady
    assert fin.any() and (~fin).any()
    for r in ("normal", "fin-normal"):
        np.testing.assert_array_equal(loads[r].lift_n_m, loads["full"].lift_n_m)
    assert np.all(loads["normal"].drag_n_m == 0.0) and np.all(loads["full"].drag_n_m[~fin] != 0.0)
    assert np.all(loads["fin-normal"].drag_n_m[fin] == 0.0)
    np.testing.assert_array_equal(loads["fin-normal"].drag_n_m[~fin], loads["full"].drag_n_m[~fin])
    # the paper's fin drag law (eq. 30): d_v = kappa l_v on the fin's strips, the others' drag unchanged
    paper_fin = AircraftModel(gtm, terms=Terms(aero=QS, fin_drag_per_lift=0.3)).aero.strip_loads(q, xi, vel, np.zeros(0),
                                                                                                u, rho, 0.6)
    np.testing.assert_allclose(paper_fin.drag_n_m[fin], 0.3 * paper_fin.lift_n_m[fin], rtol=1e-14, atol=0)
    np.testing.assert_array_equal(paper_fin.drag_n_m[~fin], loads["full"].drag_n_m[~fin])


def test_thrust_line(gtm, point):
    """f(T_e) - f(0) = T_e (t0 + t1 q) with the thrust following the deflection (eqs. 17-24), T_e t0 without."""
    x, u = point
    u0 = u.copy()
    u0[0] = 0.0
    t = gtm and AircraftModel(gtm, aero=None).structure.thrust
    _, _, q, _, _ = AircraftModel(gtm, aero=None).unpack(x)
    for follows, expected in ((True, u[0] * (t.t0 + t.t1 @ q)), (False, u[0] * t.t0)):
        model = AircraftModel(gtm, terms=Terms(aero=None, thrust_follows_deflection=follows))
        df = model.generalized_forces(x, u)[1] - model.generalized_forces(x, u0)[1]
        np.testing.assert_allclose(df, expected, rtol=0, atol=1e-9 * np.max(np.abs(expected)))
    assert np.max(np.abs(t.t1 @ q)) > 1e-6 * np.max(np.abs(t.t0))  # the two cases differ at this state


def test_inertia_offset(gtm, point):
    """With dq the system matrix is M(q + dq) (vacuum: E = M(q), eq. 8) and the kinetic energy 1/2 V^T M(q + dq) V;
    the aerodynamics stay at q."""
    x, u = point
    nq = AircraftModel(gtm, aero=None).structure.dofs.nq
    dq = 0.03 * np.cos(np.arange(nq))
    plain = AircraftModel(gtm, aero=None)
    shifted = AircraftModel(gtm, terms=Terms(aero=None, inertia_q_offset_m=tuple(dq)))
    _, _, q, _, vel = plain.unpack(x)
    m_expected = plain.structure.inertia.mass_matrix(q + dq)
    np.testing.assert_allclose(shifted.generalized_forces(x, u)[0], m_expected, rtol=0, atol=1e-12 * np.max(np.abs(m_expected)))
    assert shifted.kinetic_energy(x) == pytest.approx(0.5 * vel @ m_expected @ vel, rel=1e-13)
    qs, qs_shifted = AircraftModel(gtm, aero="quasi-steady"), AircraftModel(gtm, terms=Terms(aero=QS, inertia_q_offset_m=tuple(dq)))
    np.testing.assert_array_equal(qs.aerodynamic_force(x, u), qs_shifted.aerodynamic_force(x, u))
    delta = qs_shifted.generalized_forces(x, u)[0] - qs.generalized_forces(x, u)[0]
    np.testing.assert_allclose(delta, m_expected - plain.structure.inertia.mass_matrix(q), rtol=0,
                               atol=1e-10 * np.max(np.abs(m_expected)))


def test_aero_velocity_offset(gtm, point):
    """The strips at v + dv: the strip airloads of the offset model at v are those of the full model at v + dv
    (incompressible strips, so that the Mach number, which keeps the true v, does not enter)."""
    x, u = point
    aero = AeroOptions("quasi-steady", compressibility="none", parasite_drag=False, body_moments=False)
    dv = np.array([-3.0, 1.0, 4.0])
    plain = AircraftModel(gtm, aero=aero)
    offset = AircraftModel(gtm, terms=Terms(aero=aero, aero_velocity_offset_m_s=tuple(dv)))
    x2 = x.copy()
    x2[plain.layout.v] += dv
    expected = plain.aerodynamic_force(x2, u)
    np.testing.assert_allclose(offset.aerodynamic_force(x, u), expected, rtol=0, atol=1e-12 * np.max(np.abs(expected)))
    assert np.max(np.abs(offset.aerodynamic_force(x, u) - plain.aerodynamic_force(x, u))) > 1e-3 * np.max(np.abs(expected))


def test_flutter_points_record_their_terms(gtm):
    """A flutter point names the terms of its eigen-analysis's model (here the fixed density of the linearised
    aerodynamics)."""
    from flexsim.linear.flutter import FlutterAnalysis

    analysis = FlutterAnalysis(gtm, "quasi-steady", linear_aero_density_kg_m3=0.9)
    p = analysis.search(SteadyManoeuvre.level(9144.0, mach=0.8), mach_guess=0.81)
    assert p.terms == analysis.qs_linear.terms.record() and p.terms["aero_density_kg_m3"] == 0.9
    assert json.loads(json.dumps(p.terms))["aero"]["model"] == "quasi-steady"
