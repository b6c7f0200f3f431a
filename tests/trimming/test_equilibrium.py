"""A trim says whether it is a valid equilibrium: physically inconsistent aircraft built here from the bundled GTM file.

Each aircraft is the GTM's TOML with one change, written under tmp_path as a user would (flexsim/aircraft/data/gtm.toml):

* every wing ``gj_nm2`` x 0.02: the wing twists -18 deg at the tip at 9144 m, M 0.78 (a statically divergent
  equilibrium: real roots +37.9 and +32.5 1/s of the quasi-steady linearisation, measured 2026-12-03);
* the horizontal tail 34 m forward (root and profile-drag item): the neutral point moves ahead of the CG;
* 10 t of ballast at the fuselage tail: the CG moves behind the neutral point;
* every horizontal-tail ``gj_nm2`` x 0.002: the tail diverges while every local angle stays small.

The verdicts are checked against quantities computed apart from the classification: the static margin of
:func:`flexsim.trimming.margin.static_margin` (Etkin & Reid 1996, sec. 2.3), the eigenvalues of
:func:`flexsim.linear.stability.spectrum` (the flutter search's analysis), and the local angle recomputed from the
strip kinematics; the GTM itself must stay stable with every angle inside its +-11 deg.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.cli.main import main
from flexsim.linear.linearize import linearize
from flexsim.linear.modes import in_vacuo_modes
from flexsim.linear.stability import spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre, TrimError, trim
from flexsim.trimming.equilibrium import PHUGOID_MIN_DOUBLING_S, UNSTABLE_DAMPING
from flexsim.trimming.margin import static_margin
from flexsim.trimming.roots import _first_elastic_of, reduced_jacobian

GTM_TOML = Path(__file__).resolve().parents[2] / "flexsim" / "aircraft" / "data" / "gtm.toml"
CRUISE = SteadyManoeuvre.level(9144.0, mach=0.78)
CRUISE_ARGS = ["--altitude-m", "9144", "--mach", "0.78"]


def _scale_gj(text: str, components: tuple[str, ...], factor: float) -> str:
    """``text`` with the ``gj_nm2`` row of every named component's sections scaled by ``factor``."""
    out, current = [], None
    for line in text.split("\n"):
        if line.startswith("["):
            m = re.match(r"\[components\.(\w+)\.sections\]", line)
            current = m.group(1) if m else None
        if current in components and line.startswith("gj_nm2"):
            values = [float(v) * factor for v in line.split("=")[1].strip(" []").split(",")]
            line = "gj_nm2 = [" + ", ".join(f"{v:.6g}" for v in values) + "]"
        out.append(line)
    return "\n".join(out)


def _variants() -> dict[str, str]:
    text = GTM_TOML.read_text()
    forward = text
    for old, new in (("[39.6175, ", "[5.6175, "), ("[40.821, ", "[6.821, ")):  # design x is aft: 34 m forward
        assert forward.count(old) == 2
        forward = forward.replace(old, new)
    ballast = text + ('\n[[lumped_masses]]\nname = "tail_ballast"\ncomponent = "fuselage"\nposition_m = [42.0, 0.0, 0.0]\n'
                      'mass_kg = 10000\n')
    return {"wing_gj": _scale_gj(text, ("right_wing", "left_wing"), 0.02), "tail_forward": forward, "cg_aft": ballast,
            "tail_gj": _scale_gj(text, ("right_htail", "left_htail"), 0.002)}


@pytest.fixture(scope="module")
def files(tmp_path_factory) -> dict[str, Path]:
    folder = tmp_path_factory.mktemp("aircraft")
    out = {}
    for name, text in _variants().items():
        out[name] = folder / f"{name}.toml"
        out[name].write_text(text)
    return out


@pytest.fixture(scope="module")
def models(files) -> dict[str, AircraftModel]:
    found = {name: AircraftModel(load_aircraft(str(path)), aero="quasi-steady") for name, path in files.items()}
    return {"gtm": AircraftModel(load_aircraft("gtm"), aero="quasi-steady"), **found}


@pytest.fixture(scope="module")
def points(models):
    return {name: trim(m, CRUISE, check_limits=False) for name, m in models.items()}


def _unstable_eigenvalues(model, point) -> np.ndarray:
    """Unstable roots of the flutter search's quasi-steady analysis at the trim (apart from the classification)."""
    lam = np.array([m.eigenvalue for m in spectrum(model, point.x, point.u, aero_model="quasi-steady").modes])
    return lam[(lam.real > UNSTABLE_DAMPING * np.abs(lam)) & (lam.imag >= 0.0)]


def test_the_bundled_gtm_is_stable_with_every_strip_in_range(models, points):
    point = points["gtm"]
    assert point.stability.verdict == "stable" and point.stability.is_stable and point.stability.message == ""
    assert _unstable_eigenvalues(models["gtm"], point).size == 0
    assert point.stability.static_margin_mac == pytest.approx(static_margin(models["gtm"], point).fraction_of_mac, rel=1e-12)
    local = point.max_local_alpha
    assert local.component == "right_wing" and abs(local.alpha_rad) < math.radians(11.0)
    assert trim(models["gtm"], CRUISE).stability == point.stability  # the limits pass: the same trim


def test_local_angle_is_the_strip_kinematics(models, points):
    """atan(w_EA / u0) of every strip from the coupling's strip loads (no downwash: the tail's angles fall by the
    downwash, the wing's, where the largest angle is, do not change)."""
    model, point = models["gtm"], points["gtm"]
    _, _, q, xi, vel = model.unpack(point.x)
    loads = model.aero.strip_loads(q, xi, vel, point.x[model.layout.inflow], point.u, model.air_density(point.x), CRUISE.mach)
    alpha = np.arctan2(loads.w_ea_m_s, loads.u0_m_s)
    j = int(np.argmax(np.abs(alpha)))
    local = point.max_local_alpha
    assert (local.strip, local.alpha_rad) == (j, pytest.approx(float(alpha[j]), abs=1e-12))
    assert local.station_m == model.aero.strips.station_m[j]
    assert local.number == [c for c in model.aero.strips.component[: j + 1]].count(local.component)


def test_wing_gj_002_is_statically_divergent_and_refused_by_the_local_angle(models, points):
    point = points["wing_gj"]
    assert math.degrees(point.tip_twist_rad) == pytest.approx(-18.27, abs=0.01)  # the trim of the report
    st = point.stability
    assert st.verdict == "statically divergent" and st.is_divergent
    assert re.match(r"statically divergent: wings bending 1 \(antisymmetric\) \(real root \+37\.9 1/s, time to double 0\.0183 s\) and "
                    r"fuselage bending 1 \(symmetric\) \(real root \+32\.5\d 1/s", st.message), st.message
    # the divergent roots are real roots > 0 of the flutter search's own analysis too
    lam = _unstable_eigenvalues(models["wing_gj"], point)
    divergent = sorted(r.eigenvalue.real for r in st.unstable if r.verdict == "statically divergent")
    assert divergent == pytest.approx(sorted(lam[(lam.imag == 0.0) & (lam.real > 10.0)].real), rel=1e-9)
    with pytest.raises(TrimError, match=r"local angle of attack -17\.09 deg at right_wing strip 10 \(station 17\.3 m from "
                                        r"its root\) beyond the range of the linear \(no-stall\) aerodynamics, \+-11 deg"):
        trim(models["wing_gj"], CRUISE)


@pytest.mark.parametrize("name", ["tail_forward", "cg_aft"])
def test_neutral_point_ahead_of_the_cg_is_statically_unstable(models, points, name):
    point = points[name]
    margin = static_margin(models[name], point).fraction_of_mac
    assert margin < 0.0
    st = point.stability
    assert st.verdict == "statically unstable" and st.static_margin_mac == pytest.approx(margin, rel=1e-12)
    assert st.message.startswith(f"statically unstable: static margin {margin:.4g} MAC (the neutral point ahead of the CG)")
    # the negative margin's pitch divergence: a real root > 0 dominated by the plunge
    assert any(r.name == "pitch divergence" and r.eigenvalue.imag == 0.0 for r in st.unstable), st.message
    assert trim(models[name], CRUISE).stability == st  # within every limit: a trim, with its verdict


def test_tiny_tail_gj_diverges_with_small_local_angles(models, points):
    point = trim(models["tail_gj"], CRUISE)  # accepted: no angle beyond the range
    assert abs(point.max_local_alpha.alpha_rad) < math.radians(11.0)
    st = point.stability
    assert st.is_divergent and st.unstable[0].kind == "elastic"
    # the tail's torsion diverges with the fuselage's bending it loads: both name real roots of about +35 1/s
    names = [r.coordinate for r in st.unstable if r.verdict == "statically divergent"]
    assert names[:2] == ["fuselage bending 1 (symmetric)", "htails torsion 1 (antisymmetric)"], st.message
    assert re.match(r"statically divergent: fuselage bending 1 \(symmetric\) \(real root \+35\.37 1/s, time to double 0\.0196 s\) and "
                    r"htails torsion 1 \(antisymmetric\) \(real root \+34\.94 1/s", st.message), st.message


def test_the_trim_linearisation_is_the_linear_layers(models, points):
    """The trim's A is linearize's (one Jacobian), and the cut between rigid-body and elastic roots uses the same
    first in-vacuo elastic frequency as flexsim.linear.modes."""
    model, point = models["tail_gj"], points["tail_gj"]
    assert np.array_equal(reduced_jacobian(model, point.x, point.u).a, linearize(model, point).a)
    analysis = in_vacuo_modes(AircraftModel(model.aircraft, aero=None, gravity_m_s2=0.0))
    assert _first_elastic_of(model.aircraft.content_key()) == analysis.frequencies_rad_s[analysis.n_rigid]


def test_slowly_unstable_phugoid_is_reported_not_refused(models):
    """The paper's turn of R = 10 km at 9144 m, M 0.78 (sideslipping, heading on track): a phugoid root +0.0036 1/s,
    doubling in about 190 s, above MIL-F-8785C's Level 3 minimum of 55 s."""
    point = trim(models["gtm"], SteadyManoeuvre.turn(9144.0, 10_000.0, mach=0.78))
    st = point.stability
    assert st.verdict == "slowly unstable" and not st.is_stable and not st.is_divergent
    (root,) = st.unstable
    assert root.kind == "rigid" and root.name == "phugoid" and root.time_to_double_s > PHUGOID_MIN_DOUBLING_S
    assert st.message.startswith("slowly unstable: rigid-body mode phugoid [u] (real root +0.00")


@pytest.mark.parametrize("radius_m, verdict, doubling_s", [(5000.0, "statically unstable", 24.7),
                                                           (7000.0, "statically unstable", 54.0),
                                                           (10_000.0, "slowly unstable", 193.0)])
def test_the_papers_turns_phugoid(models, radius_m, verdict, doubling_s):
    """The paper's (sideslipping) turns at 9144 m, M 0.78, as docs/flutter.md quotes them: the phugoid doubles in
    25 s, 54 s and 193 s at R = 5, 7 and 10 km; at 5 km the CG sideslips 11.5 deg and the fin's tip strip is at -12 deg."""
    point = trim(models["gtm"], SteadyManoeuvre.turn(9144.0, radius_m, mach=0.78), check_limits=False)
    (root,) = point.stability.unstable
    assert point.stability.verdict == verdict and root.name == "phugoid"
    assert root.time_to_double_s == pytest.approx(doubling_s, rel=0.005)
    if radius_m == 5000.0:
        assert math.degrees(point.sideslip_cg) == pytest.approx(11.5, abs=0.05)
        local = point.max_local_alpha
        assert (local.component, local.number, round(math.degrees(local.alpha_rad))) == ("vtail", 5, -12)
        with pytest.raises(TrimError, match=r"local angle of attack -12\.02 deg at vtail strip 5"):
            trim(models["gtm"], SteadyManoeuvre.turn(9144.0, radius_m, mach=0.78))


def test_classify_false_leaves_it_to_the_caller(models):
    assert trim(models["gtm"], CRUISE, classify=False).stability is None


# ------------------------------------------------------------------ CLI
def test_cli_divergent_trim_is_refused_then_named_with_no_limits(files, capsys):
    assert main(["trim", str(files["wing_gj"]), *CRUISE_ARGS]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "local angle of attack -17.09 deg at right_wing strip 10" in err
    assert main(["trim", str(files["wing_gj"]), *CRUISE_ARGS, "--no-limits"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert lines[-1].startswith("statically divergent: wings bending 1 (antisymmetric) (real root +37.9 1/s")
    assert lines[-1] in (GTM_TOML.parents[3] / "docs" / "flutter.md").read_text()  # the line docs/flutter.md quotes
    assert any(re.match(r"\s+equilibrium\s+statically divergent \(quasi-steady roots\)$", line) for line in lines)
    assert main(["trim", str(files["wing_gj"]), *CRUISE_ARGS, "--no-limits", "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["stability"]["verdict"] == "statically divergent"
    assert lines[-1] == f"{doc['stability']['message']} ({doc['stability']['aero_model']} roots)"
    assert doc["max_local_alpha"]["component"] == "right_wing" and doc["max_local_alpha"]["alpha_deg"] == pytest.approx(-17.09, abs=0.01)


def test_cli_statically_unstable_line(files, capsys):
    assert main(["trim", str(files["tail_forward"]), *CRUISE_ARGS]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert lines[-1].startswith("statically unstable: static margin -0.1")
    margin = next(float(line.split()[1]) for line in lines if line.strip().startswith("static_margin_mac"))
    assert margin < 0.0


def test_cli_stable_trim_prints_no_verdict_line(capsys):
    assert main(["trim", "gtm", *CRUISE_ARGS]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert re.match(r"\s+equilibrium\s+stable \(quasi-steady roots\)$", lines[-1])
    assert re.match(r"\s+max_local_alpha\s+4\.4\d+ deg at right_wing strip 10 \(station 17\.3 m from its root\)$", lines[-2])
