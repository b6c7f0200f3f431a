"""Flight logs written by simulate(): round trip, crash safety, Rerun readers, ``flexsim view``.

Sources and tolerances:
* Round trip: the log holds exactly (bit for bit) the samples of the result at the log times, with the
  state, control and signal names of OutputMaps, 11 nodes per component, and the start/end events.
* Crash safety: a simulation killed with SIGKILL leaves a log readable up to about 1 s of simulated time
  before the last time it reported (the writer flushes every 0.5 s of sim time or 1 s of wall time).
* Rerun: its own MCAP importer (rerun.chunk.McapReader) maps the log to Transform3D, Points3D, TextLog and
  the raw state; ``flexsim view --save`` writes an .rrd whose entities (3-D aircraft, flight path, plots)
  are read back with rerun.chunk.RrdReader.
"""

import os
import signal
import subprocess
import sys
import textwrap
import time
from collections import Counter

import numpy as np
import pytest
from rerun.chunk import McapReader, RrdReader

from flexsim.cli.main import main
from flexsim.io.flight_log import FlightLogRecoveryWarning, read_flight_log
from flexsim.sim.manoeuvres import build_manoeuvre
from flexsim.sim.outputs import OutputMaps
from flexsim.sim.run_settings import OutputSettings
from tests.installed import child_env

COMPONENTS = ("fuselage", "right_wing", "left_wing", "right_htail", "left_htail", "vtail")


@pytest.fixture(scope="module")
def logged_run(tmp_path_factory):
    path = tmp_path_factory.mktemp("log") / "doublet.mcap"
    setup = build_manoeuvre("elevator-doublet", aero="quasi-steady", duration_s=1.6)
    result = setup.simulate(output=OutputSettings(rate_hz=50.0, log_path=path, log_rate_hz=50.0))
    return path, result


def test_log_round_trip_gives_the_same_arrays(logged_run):
    path, result = logged_run
    log = read_flight_log(path)
    assert log.complete
    np.testing.assert_array_equal(log.t, result.t)
    np.testing.assert_array_equal(log.state, result.x)
    np.testing.assert_array_equal(log.controls, result.u)
    out = OutputMaps(result.model)
    assert log.state_names == out.state_names and log.control_names == ("thrust_N", "aileron_rad", "elevator_rad", "rudder_rad")
    assert log.state_names[:6] == ("x_north_m", "y_east_m", "z_down_m", "phi_rad", "theta_rad", "psi_rad")
    assert "q_right_wing_1_m" in log.state_names and "xi_vtail_2_rad" in log.state_names
    assert log.signal_names == out.signal_names and log.format_version == "2"
    for name in log.signal_names:  # the result and the log compute every signal with the one output layer
        np.testing.assert_allclose(log.signal(name), result.signal(name), rtol=1e-12, atol=1e-12, err_msg=name)
    # the header records the model's terms: the quasi-steady strips of the manoeuvre's model, every other term on
    assert log.terms == result.terms == result.model.terms.record() and log.terms["aero"]["model"] == "quasi-steady"
    assert log.terms["gravity_m_s2"] == 9.80665 and log.formulation == result.model.formulation == "physical"
    assert set(log.structure) == set(COMPONENTS)
    k = 40
    for name, nodes in out.structure(result.x[k]).items():
        assert log.structure[name].shape == (result.t.size, 11, 3)
        np.testing.assert_array_equal(log.structure[name][k], nodes)
    np.testing.assert_allclose(log.position_m[:, 2], -result.altitude_m)
    texts = [e.text for e in log.events]
    assert texts[0].startswith("simulation start") and texts[-1].startswith("simulation completed")
    assert any("elevator doublet" in t for t in texts)
    assert log.metadata["manoeuvre"] == "elevator-doublet" and log.metadata["aero"] == "quasi-steady"


def test_rerun_mcap_reader_loads_the_log(logged_run):
    path, result = logged_run
    chunks = list(McapReader(path, timeline_type="duration_ns").stream())
    rows = Counter()
    for chunk in chunks:
        for name in chunk.to_record_batch().schema.names:
            rows[(chunk.entity_path, name)] += chunk.num_rows
    n = result.t.size
    assert rows[("/tf", "Transform3D:translation")] == n
    for comp in COMPONENTS:
        assert rows[(f"/structure/{comp}", "Points3D:positions")] == n
    assert rows[("/events", "TextLog:text")] == len(read_flight_log(path).events)
    assert rows[("/aircraft/state", "flexsim.AircraftState:message")] == n


def test_flexsim_view_save_writes_an_rrd_with_the_aircraft_path_and_plots(logged_run, tmp_path, capsys):
    path, result = logged_run
    rrd = tmp_path / "doublet.rrd"
    assert main(["view", str(path), "--save", str(rrd)]) == 0
    out = capsys.readouterr().out
    assert f"{result.t.size} samples" in out and "complete" in out
    chunks = list(RrdReader(rrd).stream().collect().stream())
    temporal, static = Counter(), set()
    for chunk in chunks:
        if chunk.is_static:
            static.add(chunk.entity_path)
        else:
            temporal[chunk.entity_path] += chunk.num_rows
    n = result.t.size
    for entity in ["/world/aircraft", *[f"/world/aircraft/structure/{c}" for c in COMPONENTS], "/plots/attitude",
                   "/plots/altitude", "/plots/speed", "/plots/tip_deflections", "/plots/modal/bending",
                   "/plots/modal/torsion", "/plots/controls/elevator_rad"]:
        assert temporal[entity] == n, entity
    assert "/world/flight_path" in static


def test_flexsim_view_reports_bad_and_truncated_logs(logged_run, tmp_path, capsys):
    path, result = logged_run
    garbage = tmp_path / "garbage.mcap"
    garbage.write_bytes(b"this is not a flight log")
    assert main(["view", str(garbage), "--save", str(tmp_path / "g.rrd")]) == 2
    assert "not an MCAP file" in capsys.readouterr().err
    cut = tmp_path / "cut.mcap"
    data = path.read_bytes()
    cut.write_bytes(data[: int(len(data) * 0.6)])
    assert main(["view", str(cut), "--save", str(tmp_path / "cut.rrd")]) == 0
    captured = capsys.readouterr()
    assert "incomplete" in captured.err and "recovered" in captured.err and "incomplete (recovered)" in captured.out
    with pytest.warns(FlightLogRecoveryWarning, match="recovered"):
        log = read_flight_log(cut)
    assert 0 < log.t.size < result.t.size and not log.complete
    np.testing.assert_array_equal(log.state, result.x[: log.t.size])


_KILL_SCRIPT = textwrap.dedent("""
    import sys
    from flexsim.sim.manoeuvres import build_manoeuvre
    from flexsim.sim.run_settings import OutputSettings
    setup = build_manoeuvre("elevator-doublet", aero="quasi-steady", duration_s=60.0)
    setup.simulate(output=OutputSettings(log_path=sys.argv[1], progress=lambda t: print(f"{t:.6f}", flush=True)))
""")


@pytest.mark.skipif(not hasattr(signal, "SIGKILL"), reason="needs SIGKILL")
def test_sigkill_leaves_a_log_readable_up_to_about_one_second_before(tmp_path):
    path = tmp_path / "killed.mcap"
    script = tmp_path / "run.py"
    script.write_text(_KILL_SCRIPT)
    env = child_env(base={**os.environ, "OPENBLAS_NUM_THREADS": "1"})  # the flexsim the tests import
    proc = subprocess.Popen([sys.executable, str(script), str(path)], stdout=subprocess.PIPE, text=True, env=env)
    reported = 0.0
    deadline = time.monotonic() + 60.0
    try:
        for line in proc.stdout:
            reported = float(line)
            if reported >= 3.0 or time.monotonic() > deadline:
                break
        os.kill(proc.pid, signal.SIGKILL)
    finally:
        proc.wait(timeout=30)
        proc.stdout.close()
    assert proc.returncode == -signal.SIGKILL and reported >= 3.0
    with pytest.warns(FlightLogRecoveryWarning):
        log = read_flight_log(path)
    assert not log.complete
    assert log.recovered_until_s >= reported - 1.0, (log.recovered_until_s, reported)
    assert log.events[0].text.startswith("simulation start")
