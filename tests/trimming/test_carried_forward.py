"""The trim's verdict travels with it: flutter searches, study rows, simulations and the envs.

Aircraft as in tests/trimming/test_equilibrium.py (the GTM file with the wing's, or the horizontal tail's, GJ scaled).
"""

from __future__ import annotations

import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.envs.level_hold import LevelHoldEnv
from flexsim.linear.flutter import FlutterAnalysis, FlutterNotFound
from flexsim.linear.study import StudyCase, run_case
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.simulate import simulate
from flexsim.trimming import SteadyManoeuvre, TrimError, trim
from tests.trimming.test_equilibrium import CRUISE, _variants


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    folder = tmp_path_factory.mktemp("aircraft")
    out = {}
    for name, text in _variants().items():
        out[name] = folder / f"{name}.toml"
        out[name].write_text(text)
    return out


def test_flutter_search_from_a_divergent_trim_says_so(files):
    """At sea level, M 0.5, the wing with 2 % of its GJ is already past divergence: the search names it instead of
    calling the point 'already unstable at the lower end' (what it said before the trims were classified)."""
    analysis = FlutterAnalysis(load_aircraft(str(files["wing_gj"])), "quasi-steady")
    with pytest.raises(FlutterNotFound) as info:
        analysis.search(SteadyManoeuvre.level(0.0, mach=0.5), mach_range=(0.5, 0.95))
    msg = str(info.value)
    assert msg.startswith("quasi-steady: the trim at M = 0.5000 (the lower end of the search, level flight")
    assert "is not a valid equilibrium: statically divergent: wings bending 1 (antisymmetric) (real root +35.46 1/s" in msg
    assert "already unstable" not in msg


def test_the_gtm_flutter_trims_are_stable_and_rows_record_it():
    """The bundled GTM's flutter point at sea level: its trim is classified from the search's own roots, the crossing
    mode counted neutral (it sits on the imaginary axis to Brent's tolerance)."""
    row = run_case(StudyCase("gtm", "QS", 0.0))
    assert row["trim_stability"] == "stable" and row["mach"] == pytest.approx(0.5469, abs=1e-4)
    analysis = FlutterAnalysis(load_aircraft("gtm"), "quasi-steady")
    point = analysis.search(SteadyManoeuvre.level(0.0, mach=0.5), mach_range=(0.5, 0.95))
    assert point.trim.stability.is_stable and point.trim.stability.aero_model == "quasi-steady"


@pytest.mark.parametrize("aircraft, formulation", [("gtm", "physical"), ("gtm_paper", "paper")])
def test_every_level_flutter_row_of_the_gtm_is_stable(aircraft, formulation):
    """The rows of ``flexsim flutter`` (both settings, QS and US at the paper's four altitudes) record stable trims;
    their flutter Mach numbers are those the command printed before trims were classified (its output is unchanged)."""
    from flexsim.linear.study import run_study

    cases = [StudyCase(aircraft, m, h, mach_min=0.5, mach_max=0.95, formulation=formulation)
             for m in ("QS", "US") for h in (0.0, 3048.0, 6096.0, 9144.0)]
    rows = run_study(cases, workers=1, progress=False)
    assert [r.get("trim_stability") for r in rows] == ["stable"] * 8, [r.get("error") for r in rows]


def test_simulation_carries_the_initial_trims_verdict(files):
    model = AircraftModel(load_aircraft(str(files["tail_forward"])), aero="quasi-steady")
    point = trim(model, CRUISE)
    result = simulate(model, point, 0.2)
    assert result.initial_stability is point.stability and result.initial_stability.verdict == "statically unstable"
    assert simulate(model, point.x, 0.2, controls=point.u).initial_stability is None


def test_env_refuses_an_episode_from_a_divergent_trim(files):
    """The tail with 0.2 % of its GJ trims within every limit at 9144 m, M 0.78 (the LevelHold task at the file's cruise
    point), but diverges."""
    env = LevelHoldEnv(aircraft=str(files["tail_gj"]), aero="quasi-steady")
    with pytest.raises(TrimError, match=r"cannot start an episode from the trim of GTM-notional-A in level flight .* "
                                        r"H = 9144 m: it is not an equilibrium the aircraft stays in, statically "
                                        r"divergent: fuselage bending 1 \(symmetric\) \(real root \+"):
        env.reset(seed=0)
