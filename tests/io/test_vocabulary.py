"""One output vocabulary (flexsim.io.vocabulary) and the flight-log format versions 1 and 2.

* The table: every name ends in the unit the table gives it; patterns are unique; the writer rejects a name
  outside the vocabulary (and a format-1-only name), naming the name and its position.
* Format 2 is written, with the units of every column in the file.
* Format 1 still loads, in both of its dialects: ``tests/io/data/v1_simulate.mcap`` and ``v1_env.mcap`` were
  written by format-1 code (``tests/io/data/README.md`` names the commit and says how). The reader's
  translated arrays are checked against the raw messages decoded here independently with the ``mcap`` library:
  states bit for bit, degree signals times pi/180 (to 1 ulp), renamed signals bit for bit, and the dropped
  attitude/rate signals equal to the state entries they duplicated (to 1e-12 deg), so nothing is lost.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest
from mcap.reader import make_reader
from mcap_protobuf.decoder import DecoderFactory

from flexsim.io.flight_log import FORMAT_VERSION, FlightLogWriter, read_flight_log
from flexsim.io.vocabulary import CONTROL_NAMES, QUANTITIES, check_names, quantity, unit, upgrade_v1

DATA = Path(__file__).parent / "data"
SUFFIX_UNITS = {"_rad_s": "rad/s", "_m_s": "m/s", "_N_m": "N m", "_rad": "rad", "_N": "N", "_m": "m"}


def _suffix_unit(pattern: str) -> str:
    return next((u for s, u in SUFFIX_UNITS.items() if pattern.endswith(s)), "1")


def _raw(path):
    """(metadata 'flexsim' record, [decoded AircraftState messages]) read with the mcap library alone."""
    with open(path, "rb") as f:
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        meta = {m.name: dict(m.metadata) for m in reader.iter_metadata()}
        f.seek(0)
        reader = make_reader(f, decoder_factories=[DecoderFactory()])
        states = [m for _, ch, _, m in reader.iter_decoded_messages() if ch.topic == "/aircraft/state"]
    return meta["flexsim"], states


def test_every_name_ends_in_the_unit_the_table_gives_it():
    patterns = [q.pattern for q in QUANTITIES]
    assert len(set(patterns)) == len(patterns)
    for q in QUANTITIES:
        assert q.kind in ("state", "control", "signal") and q.description
        if q.unit != "as named":
            assert _suffix_unit(q.pattern) == q.unit, q
    assert CONTROL_NAMES == ("thrust_N", "aileron_rad", "elevator_rad", "rudder_rad")
    assert unit("tip_twist_rate_vtail_rad_s") == "rad/s" and unit("root_bending_moment_left_wing_N_m") == "N m"
    assert unit("error_altitude_error_m") == "m" and unit("error_root_moment_increment") == "1" and unit("mach") == "1"
    assert quantity("lambda_left_htail_06_6_m_s").pattern == "lambda_{component}_{strip}_{n}_m_s"
    assert quantity("tip_deflection_rate_right_wing_m_s").pattern == "tip_deflection_rate_{component}_m_s"


@pytest.mark.parametrize("kind, name", [("signal", "alpha_deg"), ("signal", "root_bending_right_wing_Nm"),
                                        ("state", "north_m"), ("state", "inflow_3_m_s"), ("control", "thrust")])
def test_names_outside_the_vocabulary_are_rejected(kind, name):
    with pytest.raises(ValueError, match=rf"{kind}_names\[1\] = '{name}': not a {kind} name of the flexsim output vocabulary"):
        check_names(kind, [{"signal": "mach", "state": "phi_rad", "control": "thrust_N"}[kind], name])


def test_writer_rejects_a_dialect_name_and_writes_format_2_with_units(tmp_path):
    kwargs = dict(control_names=CONTROL_NAMES, signal_names=["alpha_rad", "tip_twist_right_wing_rad"],
                  structure_topology={"right_wing": 2})
    with pytest.raises(ValueError, match=r"state_names\[0\] = 'north_m'"):
        FlightLogWriter(tmp_path / "bad.mcap", state_names=["north_m"], **kwargs)
    path = tmp_path / "ok.mcap"
    with FlightLogWriter(path, state_names=["x_north_m", "q_right_wing_1_m"], **kwargs) as w:
        w.write(0.0, position_m=np.zeros(3), euler_rad=np.zeros(3), state=[1.0, 2.0], controls=np.zeros(4),
                signals=[0.1, 0.2], structure={"right_wing": np.zeros((2, 3))})
    meta, states = _raw(path)
    assert FORMAT_VERSION == "2" and meta["format_version"] == "2" and len(states) == 1
    assert json.loads(meta["state_units"]) == ["m", "m"] and json.loads(meta["signal_units"]) == ["rad", "rad"]
    assert json.loads(meta["control_units"]) == ["N", "rad", "rad", "rad"]
    log = read_flight_log(path)
    assert log.format_version == "2" and log.dialect == "" and log.unit("tip_twist_right_wing_rad") == "rad"


def test_format_1_simulator_dialect_still_loads_in_todays_names_and_units():
    path = DATA / "v1_simulate.mcap"
    meta, raw = _raw(path)
    assert meta["format_version"] == "1"
    old_states, old_signals = json.loads(meta["state_names"]), json.loads(meta["signal_names"])
    assert "alpha_deg" in old_signals and "root_bending_right_wing_Nm" in old_signals  # really the old dialect
    log = read_flight_log(path)
    assert log.complete and log.format_version == "1" and log.dialect == "simulate" and len(log.t) == len(raw) == 4
    check_names("state", log.state_names)
    check_names("signal", log.signal_names)
    assert log.state_names == tuple(old_states)  # this dialect's state names are today's
    np.testing.assert_array_equal(log.state, [list(m.state) for m in raw])
    old = np.array([list(m.signals) for m in raw])
    col = {n: j for j, n in enumerate(old_signals)}
    np.testing.assert_allclose(log.signal("alpha_rad"), np.radians(old[:, col["alpha_deg"]]), rtol=1e-15, atol=0)
    np.testing.assert_allclose(log.signal("tip_twist_left_wing_rad"), np.radians(old[:, col["tip_twist_left_wing_deg"]]),
                               rtol=1e-15, atol=0)
    np.testing.assert_array_equal(log.signal("root_bending_moment_right_wing_N_m"), old[:, col["root_bending_right_wing_Nm"]])
    np.testing.assert_array_equal(log.signal("wing_lift_N"), old[:, col["wing_lift_N"]])
    # the dropped signals duplicated state entries, in degrees: nothing is lost
    for sig, state in [("theta_deg", "theta_rad"), ("pitch_rate_deg_s", "omega_y_rad_s"), ("phi_deg", "phi_rad")]:
        assert sig not in log.signal_names
        np.testing.assert_allclose(old[:, col[sig]], np.degrees(log.state[:, log.state_names.index(state)]), atol=1e-12)
    assert set(log.structure) == {"fuselage", "right_wing", "left_wing", "right_htail", "left_htail", "vtail"}


def test_format_1_environment_dialect_still_loads_in_todays_names():
    path = DATA / "v1_env.mcap"
    meta, raw = _raw(path)
    old_states, old_signals = json.loads(meta["state_names"]), json.loads(meta["signal_names"])
    assert meta["format_version"] == "1" and old_states[0] == "north_m" and "twist_tip_vtail_rad" in old_signals
    log = read_flight_log(path)
    assert log.complete and log.format_version == "1" and log.dialect == "env" and len(log.t) == 3
    assert log.state_names[:6] == ("x_north_m", "y_east_m", "z_down_m", "phi_rad", "theta_rad", "psi_rad")
    k = old_states.index("u_m_s")
    assert log.state_names[k:k + 6] == ("v_x_m_s", "v_y_m_s", "v_z_m_s", "omega_x_rad_s", "omega_y_rad_s", "omega_z_rad_s")
    legacy = [n for n in log.state_names if quantity(n).legacy]
    assert legacy and all(n.startswith("inflow_") for n in legacy)  # the strip of an inflow state is not in those files
    check_names("state", [n for n in log.state_names if n not in legacy])
    check_names("signal", log.signal_names)
    np.testing.assert_array_equal(log.state, [list(m.state) for m in raw])
    old = np.array([list(m.signals) for m in raw])
    np.testing.assert_array_equal(log.signals, old)  # renames only, same units
    assert log.signal_names[9:14] == ("tip_twist_right_wing_rad", "tip_twist_left_wing_rad", "tip_twist_vtail_rad",
                                      "root_bending_moment_right_wing_N_m", "root_bending_moment_left_wing_N_m")
    assert log.signal_names[-1] == "reward" and log.metadata["env"] == "LevelHoldEnv"


def test_upgrade_keeps_unknown_names_and_a_later_version_is_refused(tmp_path):
    up = upgrade_v1(["a_m", "q_1"], ["tip_z_m", "alpha_deg"])
    assert up.dialect == "simulate" and up.state_names == ("a_m", "q_1") and up.signal_names == ("tip_z_m", "alpha_rad")
    assert up.signal_factors == (1.0, math.pi / 180)
    from flexsim.io import flight_log

    path = tmp_path / "v3.mcap"
    original = flight_log.FORMAT_VERSION
    flight_log.FORMAT_VERSION = "3"  # a file from a future flexsim
    try:
        FlightLogWriter(path, state_names=["x_north_m"], control_names=CONTROL_NAMES, signal_names=["mach"],
                        structure_topology={"wing": 1}).close()
    finally:
        flight_log.FORMAT_VERSION = original
    with pytest.raises(flight_log.FlightLogError, match="unsupported flight-log format version '3'; this reader reads 1, 2"):
        read_flight_log(path)


def test_docs_logs_md_prints_the_vocabulary_table_as_the_code_has_it():
    text = (Path(__file__).parents[2] / "docs" / "logs.md").read_text(encoding="utf-8")
    table = text.split("<!-- vocabulary-table -->")[1].split("<!-- /vocabulary-table -->")[0]
    rows = [[c.strip() for c in line.strip().strip("|").split("|")] for line in table.strip().splitlines()[2:]]
    assert [(r[0].strip("`"), r[1].split(" ")[0], r[2], r[3]) for r in rows] == [
        (q.pattern, q.kind, q.unit, q.description) for q in QUANTITIES]
    assert [r[1].endswith("(format 1 only)") for r in rows] == [q.legacy for q in QUANTITIES]
