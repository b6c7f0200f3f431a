"""The bundled mAEWing1 flying wing: regenerated from its NASTRAN Bulk Data, mass properties of the FEM, body-freedom flutter.

Reference values are the FEM's own NASTRAN output (public repository zhaowei0566/mAEWing1, commit
7683349c7711a14607347f8fc0b40095774cf549, "Design/FEM/FEM v5.2/NASTRAN files"; quoted in
flexsim/aircraft/data/maewing1.md): the grid-point weight generator of sol145_maewing1_femv5p2.f06 (reference
GRID 18888 at x = 8.20 in) gives the mass 13.80127 lb, the CG x = 8.20 + 8.591490e-4 in, y = 2.599961e-6 in, z = 0
and the inertia about the CG Ixx 9034.453, Iyy 1575.078, Izz 9231.149 lb in^2.
"""

import json
import shutil
import subprocess
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from flexsim.aircraft.definition import Engine, LumpedMass
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.errors import AircraftDefinitionError
from flexsim.linear.flutter import FlutterAnalysis
from flexsim.linear.stability import spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.structure.model import StructuralModel
from flexsim.trimming import SteadyManoeuvre
from tests.installed import child_env

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "flexsim" / "aircraft" / "data"
IN, LB = 0.0254, 0.45359237
NASTRAN_MASS_KG = 13.80127 * LB
NASTRAN_CG_M = np.array([8.20 + 8.591490e-4, 2.599961e-6, 0.0]) * IN  # the FEM's frame: x aft, y right, z up
NASTRAN_INERTIA_KG_M2 = np.array([9034.453, 1575.078, 9231.149]) * LB * IN**2


def test_bundled_maewing1_regenerates_from_the_repository(tmp_path):
    tool = tmp_path / "make_maewing1_toml.py"
    shutil.copy(ROOT / "tools" / "make_maewing1_toml.py", tool)
    out = subprocess.run([sys.executable, str(tool), "--source", str(DATA / "sources")], cwd=tmp_path,
                         capture_output=True, text=True, timeout=120, env=child_env())
    assert out.returncode == 0, out.stderr
    assert out.stdout == (DATA / "maewing1.toml").read_text(encoding="utf-8")


def test_converter_totals_are_nastrans(tmp_path):
    """The converter's sum over the Bulk Data equals NASTRAN's weight generator: mass and CG to its 6 printed digits;
    inertia within 0.4 % (the converter lumps each beam's mass at its offset ends with its polar inertia rho (I1 + I2);
    measured: Ixx +0.14 %, Iyy +0.37 %, Izz +0.20 %)."""
    tool = ROOT / "tools" / "make_maewing1_toml.py"
    out = subprocess.run([sys.executable, str(tool), "--totals"], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    values = {k.strip(): v.strip() for k, v in (line.split("=") for line in out.stdout.splitlines())}
    assert float(values["mass_kg"]) == pytest.approx(NASTRAN_MASS_KG, rel=1e-6)
    cg = np.array(json.loads(values["cg_m"]))
    assert cg == pytest.approx(NASTRAN_CG_M, abs=1e-6)
    inertia = np.array(json.loads(values["inertia_kg_m2"]))
    assert inertia == pytest.approx(NASTRAN_INERTIA_KG_M2, rel=4e-3)


def test_mass_properties_match_the_fem():
    """Mass to 1e-5 (6 printed digits); CG within 1 mm (0.3 % of the 0.30 m chord: the winglets' CG is moved 0.9 in
    inboard onto the tip, and the foam's 0.2 in spanwise mass offset becomes streamwise; measured -0.6 mm in x);
    inertia within 1 % (measured Ixx -0.66 %, Iyy +0.30 %, Izz -0.41 %: the distributed mass and the spanwise part
    of the foam's offset, as for the CG)."""
    aircraft = load_aircraft("maewing1")
    mp = StructuralModel(aircraft).mass_properties
    assert mp.mass_kg == pytest.approx(NASTRAN_MASS_KG, rel=1e-5)
    cg_design = aircraft.to_design_frame(mp.cg_m)
    assert np.abs(cg_design - NASTRAN_CG_M).max() < 1e-3
    assert np.diag(mp.inertia_cg_kg_m2) == pytest.approx(NASTRAN_INERTIA_KG_M2, rel=0.01)


def _structural(spec):
    """Oscillatory structural roots (not inflow lag), by increasing frequency."""
    return sorted((m for m in spec.modes if m.kind != "aerodynamic" and m.frequency_rad_s > 1.0), key=lambda m: m.frequency_rad_s)


def test_body_freedom_flutter_in_the_free_aircraft_only():
    """Body-freedom flutter. Free: the symmetric wing-bending branch (7.7 Hz at 20 m/s) falls in frequency and merges
    with the short period; at 42 m/s the root between 1 and 8 Hz with the least damping is unstable, at 3-6 Hz with
    mostly rigid-body kinetic energy (crossing at 33.7 m/s, maewing1.md). At 30 m/s every root there is stable.
    Restrained (clamped at the centre body, no rigid-body freedom): the wings' first-bending branches (the two lowest
    roots) are heavily damped at 42 m/s (damping ratio > 0.3); what is unstable there is the right wing's own
    bending-torsion flutter above 6.5 Hz (from 20.8 m/s at 8.77 Hz, 7.7 Hz at 42 m/s; maewing1.md), not a
    body-freedom mode.
    Sea level, Theodorsen p-k (the paper's "US")."""
    aircraft = load_aircraft("maewing1")
    analysis = FlutterAnalysis(aircraft, aero_model="theodorsen")
    band = lambda spec: [m for m in _structural(spec) if m.frequency_rad_s <= 2 * np.pi * 8.0]
    _, below = analysis.evaluate(SteadyManoeuvre.level(0.0, speed_m_s=30.0))
    assert band(below) and all(m.eigenvalue.real < 0 for m in band(below))
    _, above = analysis.evaluate(SteadyManoeuvre.level(0.0, speed_m_s=42.0))
    bff = max(band(above), key=lambda m: m.eigenvalue.real)
    assert bff.eigenvalue.real > 0
    assert 3.0 < bff.frequency_rad_s / (2 * np.pi) < 6.0
    assert bff.elastic_fraction < 0.5
    tunnel = dict(variant="restrained", gravity_m_s2=0.0, altitude_m=0.0, restrained_velocity_m_s=[42.0, 0.0, 0.0])
    qs = AircraftModel(aircraft, aero=AeroOptions("quasi-steady"), **tunnel)
    us = AircraftModel(aircraft, aero=AeroOptions("unsteady"), **tunnel)
    clamped = _structural(spectrum(qs, qs.layout.zeros(), np.zeros(4), aero_model="theodorsen", pk_model=us))
    first_bending = [m for m in clamped if "bending" in m.dominant_dof][:4]  # two branches, each a conjugate pair
    assert len(first_bending) == 4 and all(m.damping_ratio > 0.3 for m in first_bending)
    unstable = [m for m in clamped if m.eigenvalue.real > 0]
    assert unstable and min(m.frequency_rad_s for m in unstable) > 2 * np.pi * 6.5


def test_a_lumped_mass_of_zero_mass_needs_an_inertia():
    """A pure rotary inertia (the FEM's foam CONM2 of zero mass) is a lumped mass with mass_kg = 0 and an inertia; zero
    mass without inertia is refused naming the field; an engine needs a mass."""
    wing = load_aircraft("maewing1")
    assert any(m.mass_kg == 0.0 and np.any(m.inertia_kg_m2) for m in wing.lumped_masses)
    base = dict(name="foam", component="right_wing", position_m=wing.component("right_wing").root_m + [-0.05, 0.5, 0.0])
    assert LumpedMass(**base, mass_kg=0.0, inertia_kg_m2=[1e-3, 2e-3, 0.0]).mass_kg == 0.0
    refused = r"lumped_masses\.foam\.mass_kg = 0\.0: must be in \(0\.0, inf\], or 0 with a nonzero inertia"
    with pytest.raises(AircraftDefinitionError, match=refused):
        LumpedMass(**base, mass_kg=0.0)
    with pytest.raises(AircraftDefinitionError, match=r"mass_kg = 0\.0: must be in \(0\.0, inf\]"):
        Engine(**base, mass_kg=0.0, inertia_kg_m2=[1e-3, 2e-3, 0.0], max_thrust_n=10.0)


def _restrained(aircraft, speed_m_s, aero, **kw):
    return AircraftModel(aircraft, aero=None if aero is None else AeroOptions(aero), variant="restrained", gravity_m_s2=0.0,
                         altitude_m=0.0, restrained_velocity_m_s=[speed_m_s, 0.0, 0.0], **kw)


def test_restrained_quasi_steady_torsion_is_undamped_from_zero_speed():
    """Why the clamped aircraft is unstable in the quasi-steady model at every speed: the torsion modes' airloads.

    In vacuo every clamped root is neutral (|Re| <= 1e-9 |lambda|: no structural artefact; measured 5e-12 1/s).
    Quasi-steady at 1 m/s the least-damped root is the right wing's first torsion, growing with the density
    (aerodynamic; half the density: 0.521 of the growth, the rest the apparent mass's shift of the frequency), and
    on the wing's strips its point at rest lies between mid-chord and 1/(2 kappa) semichords aft of it. There
    the quasi-steady strip damping is negative: flexsim's strip loads (Theodorsen, NACA Rep. 496, 1935, with
    C(k) = 1 and the circulatory part scaled by kappa = Cl_alpha / 2 pi) absorb the power per unit span
    pi rho U b [2 kappa |hdot|^2 + (1 - 4 kappa a) Re(hdot conj(b alphadot)) + a (2 kappa a - 1) |b alphadot|^2],
    whose roots in hdot / (b alphadot) are a and a - 1/(2 kappa): it is negative exactly when the point at rest,
    a - hdot / (b alphadot) semichords aft of mid-chord, lies in (0, 1/(2 kappa)) (the three-quarter chord for
    kappa = 1). The mAEWing1's elastic axis is at 48 % chord (a = -0.035) and its torsion mode turns about 0.01 to
    0.13 semichords aft of mid-chord. The finite-state root (the wake's lag) at 1 m/s is damped."""
    aircraft = load_aircraft("maewing1")
    vacuo = _restrained(aircraft, 1.0, None)
    roots = spectrum(vacuo, vacuo.layout.zeros(), np.zeros(4), aero_model="quasi-steady").modes
    assert all(abs(m.eigenvalue.real) <= 1e-9 * abs(m.eigenvalue) for m in roots)

    def least_damped(model, aero):
        spec = spectrum(model, model.layout.zeros(), np.zeros(4), aero_model=aero)
        return max((m for m in spec.modes if m.kind == "elastic"), key=lambda m: m.eigenvalue.real)

    qs = _restrained(aircraft, 1.0, "quasi-steady")
    root = least_damped(qs, "quasi-steady")
    assert root.dominant_dof == "right_wing torsion 1" and root.eigenvalue.real > 0
    thin = least_damped(_restrained(aircraft, 1.0, "quasi-steady", air_density_kg_m3=0.6125), "quasi-steady")
    assert thin.eigenvalue.real / root.eigenvalue.real == pytest.approx(0.5, rel=0.06)
    assert not qs.aero.bending_incidence  # the strips pitch with the torsion alone (proj_p)
    strips = qs.aero.strips
    wing = np.array([c == "right_wing" for c in strips.component]) & (strips.station_m > 0.25)
    hdot, b_alphadot = strips.proj_n0 @ root.shape, strips.semichord_m * (strips.proj_p @ root.shape)
    node = strips.a[wing] + np.real(-hdot[wing] / b_alphadot[wing])
    kappa = strips.lift_slope0[wing] / (2 * np.pi)
    assert np.all((node > 0.0) & (node < 0.5 / kappa) & (node < 0.5))
    fs = least_damped(_restrained(aircraft, 1.0, "unsteady"), "unsteady")
    assert fs.dominant_dof == "right_wing torsion 1" and fs.eigenvalue.real < 0


def test_restrained_is_the_free_aircraft_with_an_infinitely_heavy_centre_body():
    """The clamp is the limit of a free aircraft whose centre body's mass and inertia grow without bound: at 28 m/s
    (finite-state strips, no gravity, wings undeformed) the restrained wing-flutter root and the free aircraft's
    with the centre body 10^4 times heavier agree within 0.02 1/s (measured 3e-3 + 4e-3 j; the difference falls as
    1 / factor: 0.053 at 10^3). With the aircraft's own 3.0 kg centre body that root is damped at 28 m/s: the
    body's plunge and pitch take part in the wing modes (free wing flutter 41.3 m/s here, the body heavier by
    10: 31.5 m/s, by 100: 18.2 m/s, clamped 20.6 m/s; maewing1.md), so a clamped mAEWing1 flutters at half the
    free one's speed."""
    aircraft = load_aircraft("maewing1")
    speed = 28.0

    def wing_flutter_root(model, x0):
        spec = spectrum(model, x0, np.zeros(4), aero_model="unsteady")
        return max((m for m in spec.modes if m.kind != "aerodynamic" and m.frequency_rad_s > 2 * np.pi * 6.5),
                   key=lambda m: m.eigenvalue.real)

    clamped = _restrained(aircraft, speed, "unsteady")
    root = wing_flutter_root(clamped, clamped.layout.zeros())
    assert root.eigenvalue.real > 0

    def free(body_factor):
        heavier = lambda m: replace(m, mass_kg=m.mass_kg * body_factor, inertia_kg_m2=np.asarray(m.inertia_kg_m2) * body_factor)
        masses = tuple(heavier(m) if m.name == "centre_body" else m for m in aircraft.lumped_masses)
        model = AircraftModel(replace(aircraft, lumped_masses=masses), aero=AeroOptions("unsteady"), gravity_m_s2=0.0)
        x0 = model.layout.zeros()
        x0[model.layout.velocity.start] = speed  # body-x velocity, wings level at zero incidence
        return wing_flutter_root(model, x0)

    assert abs(free(1e4).eigenvalue - root.eigenvalue) < 0.02
    assert free(1.0).eigenvalue.real < 0
