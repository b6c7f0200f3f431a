"""Trim of the geometrically nonlinear aircraft (flexsim.trimming.flexible_trim) and its model
(flexsim.model.flexible_aircraft): closed forms, the small-deflection limit against the linear model, invariants."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

import flexsim as fs
from flexsim.model.flexible_aircraft import _flap_effectiveness, flexible_aircraft
from flexsim.structure.free_flexible import (FreeFlexibleStructure, free_flight_rhs, generalized_mass_matrix,
                                             initial_state, steady_generalized_force)
from flexsim.trimming.flexible_trim import FlexibleTrimError, trim_flexible

CRUISE = dict(altitude_m=20000.0, speed_m_s=25.0)


@pytest.fixture(scope="module")
def hale():
    return fs.AircraftModel(fs.load_aircraft("phc_hale"))


def _stiff(aircraft, factor):
    """The aircraft with every flexible component's EI, GJ and chordwise EI multiplied by ``factor``."""
    def one(c):
        if not c.is_flexible:
            return c
        s = c.sections
        return dataclasses.replace(c, sections=dataclasses.replace(
            s, ei_nm2=s.ei_nm2 * factor, gj_nm2=s.gj_nm2 * factor, ei_chord_nm2=s.ei_chord_nm2 * factor))
    return dataclasses.replace(aircraft, components=tuple(one(c) for c in aircraft.components))


def test_flap_effectiveness_is_glauerts():
    # Glauert (1927): tau = 1 - (theta - sin theta)/pi, hinge at x/c = 3/4 -> theta = 2 pi/3 from the leading edge
    theta = 2.0 * math.pi / 3.0
    assert _flap_effectiveness(0.5) == pytest.approx(1.0 - (theta - math.sin(theta)) / math.pi, rel=1e-12)
    assert _flap_effectiveness(-1.0) == pytest.approx(1.0, abs=1e-12)  # all-moving surface


def test_steady_force_is_the_free_flight_equations(hale):
    """With strain rates zero, steady_generalized_force is M(eps) V_dot of free_flight_rhs (one implementation)."""
    flex = flexible_aircraft(hale, 2)
    g = np.array([0.0, 0.0, 9.80665])
    structure = FreeFlexibleStructure(flex.structure.body, flex.structure.beams, g)
    rng = np.random.default_rng(1)
    eps = 0.02 * rng.standard_normal(structure.n_strains)
    quat = np.array([0.98, 0.05, 0.15, -0.02])
    quat /= np.linalg.norm(quat)
    y = initial_state(structure, quaternion=quat, strains=eps, velocity_m_s=(25.0, 1.0, 2.0),
                      rate_rad_s=(0.1, 0.2, -0.05))
    vdot = free_flight_rhs(structure, 0.0, y)[7 + structure.n_strains:]
    q = steady_generalized_force(structure, quat, eps, [25.0, 1.0, 2.0, 0.1, 0.2, -0.05], g)
    expected = generalized_mass_matrix(structure, eps) @ vdot
    np.testing.assert_allclose(q, expected, rtol=0, atol=1e-9 * np.abs(expected).max())


def test_mass_matches_the_linear_model(hale):
    """Body + beams at eps = 0 carry the linear model's mass and first moment (paper eq. 8) exactly; the
    inertia up to the beams' element quadrature (8 elements: within 1 %)."""
    flex = flexible_aircraft(hale, 8)
    m = generalized_mass_matrix(flex.structure, np.zeros(flex.n_strains))[:6, :6]
    m0 = hale.structure.inertia.m0[:6, :6]
    np.testing.assert_allclose(m[:3, :], m0[:3, :], rtol=0, atol=1e-9 * m0[0, 0] * 10.0)
    np.testing.assert_allclose(np.diag(m[3:, 3:]), np.diag(m0[3:, 3:]), rtol=1e-2)


def test_stiff_aircraft_trims_like_the_linear_model():
    """Small-deflection limit: EI, GJ x 1e4 leave a tip deflection of ~6e-4 m (4e-5 of the semispan), so the
    geometric terms the linear model neglects are of that relative size. Same strips, same mass: angle of attack
    within 0.1 %, tip deflection within 1 % (quadrature of 8 elements against the linear model's 3 bending modes),
    elevator within 2 % and thrust within 0.5 % of the weight (the flap as an equivalent incidence tilts the tail's
    force with it, Glauert's flap against the linear model's Peters flap terms)."""
    model = fs.AircraftModel(_stiff(fs.load_aircraft("phc_hale"), 1e4))
    man = fs.SteadyManoeuvre.level(**CRUISE)
    nonlinear, linear = trim_flexible(model, man), fs.trim(model, man)
    weight = model.structure.mass_properties.mass_kg * 9.80665
    assert nonlinear.alpha_rad == pytest.approx(linear.alpha, rel=1e-3)
    assert nonlinear.tip_displacement_m[0, 2] == pytest.approx(linear.tip_deflection_m, rel=1e-2)
    assert nonlinear.controls[2] == pytest.approx(linear.u[2], rel=2e-2)
    assert abs(nonlinear.controls[0] - linear.u[0]) < 5e-3 * weight


def test_hale_level_trim_large_deflection(hale):
    """The bundled HALE at its cruise point: converged, symmetric, the tips beyond a third of the semispan (the
    linear model's 47 % at the same point is outside its 14 % range); lateral residual zero by symmetry."""
    point = trim_flexible(hale, fs.SteadyManoeuvre.level(**CRUISE))
    assert point.residual < 1e-8
    tips = point.tip_displacement_m
    np.testing.assert_allclose(tips[0] * [1, -1, 1], tips[1], atol=1e-9)
    assert 0.33 < point.tip_deflection_fraction[0] < 0.7
    assert point.max_strip_alpha_deg < 12.0


def test_pull_up_beyond_the_lift_range_is_refused(hale):
    with pytest.raises(FlexibleTrimError, match="max_alpha_deg"):
        trim_flexible(hale, fs.SteadyManoeuvre.pull_up(20000.0, 1.5, speed_m_s=25.0))


def test_pull_up_trims_and_bends_more(hale):
    level = trim_flexible(hale, fs.SteadyManoeuvre.level(20000.0, speed_m_s=30.0))
    pull = trim_flexible(hale, fs.SteadyManoeuvre.pull_up(20000.0, 1.2, speed_m_s=30.0), guess=level)
    assert pull.residual < 1e-8
    assert pull.rate_rad_s[1] == pytest.approx(0.2 * 9.80665 / 30.0, rel=1e-12)
    assert pull.tip_deflection_fraction[0] > level.tip_deflection_fraction[0]


def test_turn_and_incomplete_data_are_refused(hale):
    with pytest.raises(ValueError, match="turn_radius_m"):
        trim_flexible(hale, fs.SteadyManoeuvre(25.0, 20000.0, turn_radius_m=2000.0, climb_angle_rad=None))
    with pytest.raises(ValueError, match="ei_chord_nm2"):
        flexible_aircraft(fs.AircraftModel(fs.load_aircraft("gtm")))
    with pytest.raises(ValueError, match="elements_per_beam"):
        flexible_aircraft(hale, 0)


def test_climb_and_glide(hale):
    """Climb: the thrust exceeds level flight's by W sin(gamma) (paper eqs. 38-39) within the change of drag with
    the lift, W (1 - cos gamma) = 0.14 % of W less (0.2 % of W allowed); glide: no thrust, a descending path."""
    weight = hale.structure.mass_properties.mass_kg * 9.80665
    level = trim_flexible(hale, fs.SteadyManoeuvre.level(**CRUISE))
    climb = trim_flexible(hale, fs.SteadyManoeuvre.climb(20000.0, math.radians(3.0), speed_m_s=25.0))
    assert climb.controls[0] - level.controls[0] == pytest.approx(weight * math.sin(math.radians(3.0)),
                                                               abs=2e-3 * weight)
    glide = trim_flexible(hale, fs.SteadyManoeuvre.glide(20000.0, speed_m_s=25.0))
    assert glide.controls[0] == 0.0 and glide.climb_angle_rad < 0.0 and glide.residual < 1e-8


def _gtm_with_chordwise_stiffness(tmp_path, bending_modes: int, damping: float = 0.01, rigid_fuselage: bool = True,
                                  torsion_modes: int = 2):
    """The bundled GTM with ``ei_chord_nm2 = 10 x ei_nm2`` on every flexible component (an assumption: the notional
    GTM's sources give no in-plane stiffness; the trim barely loads it), ``bending_modes`` assumed modes per wing, a
    rigid fuselage (the nonlinear structure clamps the wings to the rigid body: a flexible fuselage carrying them is
    refused) and the modal ``structural_damping_ratio`` given."""
    import re
    from importlib import resources

    text = (resources.files("flexsim.aircraft") / "data" / "gtm.toml").read_text()

    def chord(m):
        values = [float(v) for v in m.group(1).split(",")]
        return m.group(0) + "\nei_chord_nm2 = [" + ", ".join(f"{10 * v:.6g}" for v in values) + "]"

    text = re.sub(r"^ei_nm2 = \[([^\]]*)\]", chord, text, flags=re.M)
    wings = "length_m = 18.25\nbending_modes = 2\ntorsion_modes = 2"
    assert text.count(wings) == 2  # both wing halves
    text = text.replace(wings, f"length_m = 18.25\nbending_modes = {bending_modes}\ntorsion_modes = {torsion_modes}")
    if rigid_fuselage:
        text = text.replace('section_inertia = "axisymmetric"\n', 'section_inertia = "axisymmetric"\nrigid = true\n', 1)
    text = re.sub(r"^structural_damping_ratio = [0-9.]+", f"structural_damping_ratio = {damping}", text, flags=re.M)
    path = tmp_path / "gtm_chordwise.toml"
    path.write_text(text)
    return fs.load_aircraft(path)


def test_gtm_small_deflection_limit(tmp_path):
    """The GTM (tips 4 % of the semispan) trimmed by both structures with the same strip physics — the linear model
    switched to what the nonlinear strips have (quasi-steady, no parasite drag, bodies or downwash; the bending
    incidence of its swept strips on, which the deformed strips have by construction; Prandtl-Glauert in both, the
    nonlinear strips' held at the trim's Mach number), level flight at 9144 m, M 0.6, the engines on the wings in both.
    Measured: angle of attack 10.827 against 10.658 deg (1.6 %), thrust 48.0 against 46.7 kN (2.8 %), elevator -18.08
    against -17.19 deg (5.2 %), tip 0.783 against 0.725 m (8.0 %); incompressible, the angle of attack is 13.0 deg.
    The neglected terms that size the tolerances: the linear model's assumed modes (6 uniform-beam modes on a wing
    whose EI falls 600:1; with the file's 2 the tip is 17 % short, so the truncation dominates the tip and the wing's
    load distribution, and on the 25 deg swept wing the bending's wash-out of the incidence follows the tip: the
    angle of attack), the flap's own pitching moment (kept by the linear strips, neglected by the nonlinear: the
    elevator), and the geometric terms of a 4 % deflection (of order 0.1 %)."""
    from flexsim.model.coupling import AeroOptions
    from flexsim.model.terms import NonlinearBeams

    aircraft = _gtm_with_chordwise_stiffness(tmp_path, 6)
    aero = AeroOptions("quasi-steady", parasite_drag=False, downwash=False, body_moments=False, bending_incidence=True)
    man = fs.SteadyManoeuvre.level(9144.0, mach=0.6)
    linear = fs.trim(fs.AircraftModel(aircraft, terms=fs.Terms(aero=aero)), man, check_limits=False)
    nonlinear = fs.trim(fs.AircraftModel(aircraft, terms=fs.Terms(aero=aero, nonlinear_beams=NonlinearBeams(8))), man,
                        check_limits=False)
    wing = nonlinear.aircraft.beam_index("right_wing")
    tip = nonlinear.tip_deflection_fraction[wing] * 18.25
    assert 0.02 < tip / 18.25 < 0.14  # inside the linear structure's range
    assert nonlinear.alpha_rad == pytest.approx(linear.alpha, rel=0.025)
    assert nonlinear.controls[0] == pytest.approx(linear.u[0], rel=0.05)
    assert nonlinear.controls[2] == pytest.approx(linear.u[2], rel=0.08)
    assert tip == pytest.approx(-linear.tip_deflection_m, rel=0.12)


@pytest.mark.slow
def test_gtm_flutter_small_deflection_limit(tmp_path):
    """The GTM's flutter with the nonlinear option (the free aircraft with Peters' strips about the nonlinear trim,
    ``NonlinearBeams(stability="free-aircraft")``) against the linear model's finite-state search at 9144 m, both with
    the physics the nonlinear strips have (Prandtl-Glauert, no parasite drag, bodies or downwash) and the file's 1 %
    modal structural damping, tips 4 % of the semispan. Measured with 8 elements against 10 bending and 8 torsion
    modes per wing: M 0.8788, 34.38 rad/s against M 0.8905, 35.67 rad/s (1.3 % in Mach, 3.6 % in frequency; undamped
    0.8753 against 0.8858). What sizes the tolerances (3 % in Mach, 5 % in frequency) is the discretisation of each
    model, not a neglected large-deflection term (undamped): the linear model's M_F falls with its modes (0.8981 with
    6 + 2, 0.8900 with 8 + 5, 0.8858 with 10 + 8) and the nonlinear one's flutter speed rises with the elements (at
    sea level, incompressible: 240.29 m/s with 8, 245.00 with 16, against the linear 258.56, 251.90, 248.80 m/s),
    converging together within 1.5 %. Left in both: the strips' formulation on the 25 deg swept wing (an unswept variant shows
    the same gap, 235.30 against 255.22 m/s at 8 elements and 6 + 2 modes), the apparent mass scaled with the
    lift slope in the nonlinear strips, the fin's inflow states."""
    from flexsim.atmosphere import isa
    from flexsim.model.coupling import AeroOptions
    from flexsim.model.terms import NonlinearBeams

    aircraft = _gtm_with_chordwise_stiffness(tmp_path, 10, torsion_modes=8)
    aero = AeroOptions("unsteady", parasite_drag=False, downwash=False, body_moments=False, bending_incidence=True)
    man = fs.SteadyManoeuvre.level(9144.0, mach=0.6)
    linear = fs.flutter(fs.AircraftModel(aircraft, terms=fs.Terms(aero=aero)), man, "unsteady", mach_range=(0.5, 0.95))
    beams = NonlinearBeams(8, stability="free-aircraft")
    model = fs.AircraftModel(aircraft, terms=fs.Terms(aero=aero, nonlinear_beams=beams))
    sound = float(isa(9144.0).speed_of_sound)  # the scan in speed: 250-290 m/s in 10 m/s steps
    nonlinear = fs.flutter(model, man, "unsteady", mach_range=(250.0 / sound, 290.0 / sound), mach_step=10.0 / sound,
                           tol=0.05 / sound)
    assert 0.02 < nonlinear.tip_deflection_fraction < 0.06
    assert nonlinear.terms["nonlinear_beams"]["stability"] == "free-aircraft"
    assert nonlinear.mach == pytest.approx(linear.mach, rel=0.03)
    assert nonlinear.frequency_rad_s == pytest.approx(linear.frequency_rad_s, rel=0.05)


def test_flexible_fuselage_carrying_components_is_refused(tmp_path):
    """The nonlinear structure clamps the wings to the rigid body; a bending fuselage carrying them (the linear model's
    topology, paper eq. 6) is refused by name, not answered with another aircraft."""
    aircraft = _gtm_with_chordwise_stiffness(tmp_path, 2, rigid_fuselage=False)
    with pytest.raises(ValueError, match=r"components\.fuselage is flexible.*rigid = true"):
        flexible_aircraft(fs.AircraftModel(aircraft))


def test_engines_ride_on_the_wing_beams(tmp_path):
    """The GTM's engines (4400 kg each) are point masses of the wing beams at their stations, not of the rigid body: the
    free structure's mass and centre of gravity stay the linear model's (to 1e-9), and its first wing modes come within
    4 % of the linear model's in-vacuo modes (16.29 and 22.58 rad/s; measured 15.74 and 21.72: 3.4 % and 3.8 %, the
    linear model's assumed modes against 8 elements) where, with the engines in the rigid body, the nonlinear wing's
    torsion was at 44-46 rad/s against 41.3."""
    from flexsim.linear.modes import in_vacuo_modes
    from flexsim.structure.free_flexible import free_free_frequencies, generalized_mass_matrix

    aircraft = _gtm_with_chordwise_stiffness(tmp_path, 6, damping=0.0)
    flex = flexible_aircraft(fs.AircraftModel(aircraft), 8)
    wing = flex.structure.beams[flex.beam_index("right_wing")]
    assert [pm.mass_kg for pm in wing.point_masses] == [4400.0]
    linear = fs.AircraftModel(aircraft)
    m_nl = generalized_mass_matrix(flex.structure, np.zeros(flex.structure.n_strains))[:6, :6]
    assert np.abs(m_nl - linear.structure.inertia.m0[:6, :6]).max() < 1e-9 * np.abs(m_nl).max()
    nl = free_free_frequencies(flex.structure)[:2]
    lin = in_vacuo_modes(fs.AircraftModel(aircraft, terms=fs.Terms(aero=None))).frequencies_rad_s
    lin = lin[lin > 1.0][:2]  # the elastic modes (the six rigid-body ones are zero)
    assert np.abs(nl / lin - 1).max() < 0.04


def test_terms_the_nonlinear_aircraft_cannot_evaluate_are_refused_and_absent_ones_said(tmp_path):
    """A Terms field the nonlinear aircraft does not evaluate, off its default, is refused by name (not dropped); the
    linear model's aerodynamic terms that the nonlinear strips lack are listed where the aircraft has them (the GTM:
    tail downwash, parasite drag, slender bodies; the PHC HALE: none) and said in the flutter search's warnings."""
    from flexsim.model.coupling import AeroOptions

    gtm = _gtm_with_chordwise_stiffness(tmp_path, 2)
    flex = flexible_aircraft(fs.AircraftModel(gtm), 3)
    with pytest.raises(ValueError, match="elements_per_beam = 2: the beams' mass at this element count"):
        flexible_aircraft(fs.AircraftModel(gtm), 2)  # two elements: too coarse for the GTM's tapered wing mass
    assert [u.split(" (")[0] for u in flex.unmodelled] == ["the tail's downwash", "the parasite-drag items",
                                                           "the slender bodies' Munk moments"]
    assert flexible_aircraft(fs.AircraftModel(fs.load_aircraft("phc_hale")), 2).unmodelled == ()
    with pytest.raises(ValueError, match="force_resolution = 'normal': not available with the geometrically nonlinear"):
        flexible_aircraft(fs.AircraftModel(gtm, terms=fs.Terms(force_resolution="normal")), 3)
    with pytest.raises(ValueError, match="formulation = 'paper'"):
        flexible_aircraft(fs.AircraftModel(gtm, aero=AeroOptions(formulation="paper")), 3)
    from flexsim.linear.flexible_flutter import flexible_flutter

    point = flexible_flutter(fs.AircraftModel(gtm), fs.SteadyManoeuvre.level(9144.0, mach=0.6), (200.0, 210.0),
                             speed_step_m_s=10.0, elements_per_beam=3)
    assert any(w.startswith("not in the nonlinear strips: the tail's downwash") for w in point.warnings)

