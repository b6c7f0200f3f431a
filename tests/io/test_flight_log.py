"""Tests of the flight-log writer and reader (flexsim.io.flight_log).

Everything is written under pytest's ``tmp_path``. Reference values come from the inputs given to
the writer (round trips) or from independent constructions (the project's direction cosine matrix
``dcm_321``, hand-checked flight cases, a file cut by hand, a child process killed with SIGKILL).
"""

import math
import os
import signal
import subprocess
import sys
import textwrap
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from foxglove_schemas_protobuf.Log_pb2 import Log
from mcap_protobuf.writer import Writer as ProtobufMcapWriter

import flexsim
from flexsim.errors import FlexsimError
from flexsim.io import flight_log
from flexsim.io.flight_log import (
    ENU_FROM_NED,
    FlightLogError,
    FlightLogRecoveryWarning,
    FlightLogWriter,
    LogEvent,
    read_flight_log,
    viewer_pose,
)
from flexsim.kinematics import dcm_321

STATE_NAMES = ["v_x_m_s", "v_z_m_s", "q_right_wing_1_m", "q_right_wing_2_m", "xi_right_wing_1_rad"]
CONTROL_NAMES = ["thrust_N", "aileron_rad", "elevator_rad", "rudder_rad"]
SIGNAL_NAMES = ["airspeed_m_s", "tip_deflection_right_wing_m"]
TOPOLOGY = {"right_wing": 5, "fuselage": 3}


def _writer(path, **overrides):
    kwargs = dict(state_names=STATE_NAMES, control_names=CONTROL_NAMES, signal_names=SIGNAL_NAMES,
                  structure_topology=TOPOLOGY, metadata={"aircraft": "test.toml"})
    kwargs.update(overrides)
    return FlightLogWriter(path, **kwargs)


def _random_samples(n_samples, seed=0, dt_s=0.01):
    """Random but finite samples; time steps of ``dt_s``."""
    rng = np.random.default_rng(seed)
    return [dict(t_s=k * dt_s, position_m=rng.normal(size=3) * 100, euler_rad=rng.normal(size=3),
                 state=rng.normal(size=len(STATE_NAMES)), controls=rng.normal(size=4),
                 signals=rng.normal(size=len(SIGNAL_NAMES)),
                 structure={name: rng.normal(size=(n, 3)) for name, n in TOPOLOGY.items()})
            for k in range(n_samples)]


def _write_log(path, samples, events=(), **overrides):
    with _writer(path, **overrides) as writer:
        for sample in samples:
            writer.write(**sample)
        for event in events:
            writer.event(*event)


def _matrix(q):
    x, y, z, w = q
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


# --------------------------------------------------------------------------------------------
# Frames
# --------------------------------------------------------------------------------------------

def test_viewer_pose_is_the_proper_rotation_enu_from_ned_times_c_transpose():
    """R(q) = T C^T with C from the project's dcm_321 (matrix form); |q| = 1 and det R = +1."""
    rng = np.random.default_rng(1)
    euler = rng.uniform(-3, 3, size=(50, 3))
    position = rng.normal(size=(50, 3)) * 1e3
    translation, quaternion = viewer_pose(position, euler)
    np.testing.assert_allclose(translation, position[:, [1, 0, 2]] * [1, 1, -1], rtol=0, atol=1e-12)
    np.testing.assert_allclose(np.linalg.norm(quaternion, axis=1), 1.0, rtol=0, atol=1e-14)
    for (phi, theta, psi), q in zip(euler, quaternion):
        c_body_from_ned = dcm_321(phi, theta, psi)
        rotation = _matrix(q)
        np.testing.assert_allclose(rotation, ENU_FROM_NED @ c_body_from_ned.T, rtol=0, atol=1e-13)
        assert np.linalg.det(rotation) == pytest.approx(1.0, abs=1e-13)


@pytest.mark.parametrize("euler_deg, body_axis, expected_enu", [
    ((0, 0, 0), (1, 0, 0), (0, 1, 0)),     # level, heading north: nose points north (+y in ENU)
    ((0, 0, 0), (0, 0, 1), (0, 0, -1)),    # body z (down) points down
    ((0, 0, 90), (1, 0, 0), (1, 0, 0)),    # heading east: nose points east (+x)
    ((0, 30, 0), (1, 0, 0), (0, math.cos(math.radians(30)), math.sin(math.radians(30)))),  # nose up
    ((30, 0, 0), (0, 1, 0), (math.cos(math.radians(30)), 0, -math.sin(math.radians(30)))),  # right wing down
])
def test_viewer_pose_maps_body_axes_as_flight_intuition_says(euler_deg, body_axis, expected_enu):
    """Heading, pitch-up and right-roll rotate the body axes in the ENU world as expected."""
    _, q = viewer_pose(np.zeros(3), np.radians(euler_deg))
    np.testing.assert_allclose(_matrix(q) @ np.array(body_axis, float), expected_enu, atol=1e-14)


# --------------------------------------------------------------------------------------------
# Round trip
# --------------------------------------------------------------------------------------------

def test_round_trip_reproduces_arrays_names_events_and_metadata(tmp_path):
    """write -> read gives identical arrays, names, events (1 ns time resolution) and metadata."""
    samples = _random_samples(60)
    events = [(0.25, "gust starts"), (0.5, "load above limit", "warning"), (0.125, "late", "error")]
    path = tmp_path / "run.mcap"
    _write_log(path, samples, events, metadata={"aircraft": "gtm.toml", "run_id": "r-1"})
    log = read_flight_log(path)

    assert log.complete and log.recovered_until_s == samples[-1]["t_s"]
    for key, attr in [("t_s", "t"), ("position_m", "position_m"), ("euler_rad", "euler_rad"),
                      ("state", "state"), ("controls", "controls"), ("signals", "signals")]:
        np.testing.assert_array_equal(getattr(log, attr), np.array([s[key] for s in samples]))
    assert set(log.structure) == set(TOPOLOGY)
    for name in TOPOLOGY:
        np.testing.assert_array_equal(log.structure[name],
                                      np.array([s["structure"][name] for s in samples]))
    assert (log.state_names, log.control_names, log.signal_names) == (
        tuple(STATE_NAMES), tuple(CONTROL_NAMES), tuple(SIGNAL_NAMES))
    assert log.events == (LogEvent(0.125, "error", "late"), LogEvent(0.25, "info", "gust starts"),
                          LogEvent(0.5, "warning", "load above limit"))
    assert log.metadata == {"aircraft": "gtm.toml", "run_id": "r-1"}
    np.testing.assert_array_equal(log.signal("tip_deflection_right_wing_m"), log.signals[:, 1])
    with pytest.raises(ValueError):
        log.state[0, 0] = 1.0  # arrays are read-only


def test_header_records_the_model_terms_and_formulation(tmp_path):
    """Terms given to the writer come back from the header record equal to Terms.record(), field by field (JSON
    round trip: floats exact, tuples as lists); a log written without them reads back terms None."""
    from flexsim.model.coupling import AeroOptions
    from flexsim.model.terms import Terms

    terms = Terms(aero=AeroOptions("quasi-steady"), gravity_m_s2=0.0, compressibility_mach=0.8,
                  engine_angular_momentum=(1.5, 0.0, -2.25)).record()
    _write_log(tmp_path / "terms.mcap", _random_samples(3), terms=terms, formulation="paper")
    log = read_flight_log(tmp_path / "terms.mcap")
    assert log.terms == terms and log.formulation == "paper"
    assert log.terms["aero"]["model"] == "quasi-steady" and log.terms["engine_angular_momentum"] == [1.5, 0.0, -2.25]
    _write_log(tmp_path / "plain.mcap", _random_samples(3))
    plain = read_flight_log(tmp_path / "plain.mcap")
    assert plain.terms is None and plain.formulation is None
    with pytest.raises(ValueError, match="terms"):
        _writer(tmp_path / "bad.mcap", terms={"gravity_m_s2": math.nan})
    with pytest.raises(ValueError, match="formulation"):
        _writer(tmp_path / "bad.mcap", terms=terms, formulation=3)


def test_signal_with_unknown_name_raises_key_error_listing_available_names(tmp_path):
    path = tmp_path / "run.mcap"
    _write_log(path, _random_samples(3))
    with pytest.raises(KeyError, match="airspeed_m_s.*tip_deflection_right_wing_m"):
        read_flight_log(path).signal("altitude_m")


def test_close_is_idempotent_and_write_after_close_raises(tmp_path):
    writer = _writer(tmp_path / "run.mcap")
    writer.write(**_random_samples(1)[0])
    writer.close()
    writer.close()
    with pytest.raises(ValueError, match="closed"):
        writer.write(**_random_samples(2)[1])
    assert len(read_flight_log(tmp_path / "run.mcap").t) == 1


# --------------------------------------------------------------------------------------------
# Crash safety
# --------------------------------------------------------------------------------------------

def test_unfinished_file_is_readable_up_to_the_last_flush(tmp_path):
    """A copy taken while the writer is open (no footer) holds all but < flush_interval_s of data."""
    path, copy = tmp_path / "run.mcap", tmp_path / "copy.mcap"
    samples = _random_samples(251, dt_s=0.01)
    writer = _writer(path, flush_interval_s=0.5)
    for sample in samples:
        writer.write(**sample)
    copy.write_bytes(path.read_bytes())
    writer.close()
    with pytest.warns(FlightLogRecoveryWarning, match=r"up to t = "):
        log = read_flight_log(copy)
    assert not log.complete
    assert samples[-1]["t_s"] - log.recovered_until_s < 0.5
    np.testing.assert_array_equal(log.state, [s["state"] for s in samples[:len(log.t)]])


def test_writer_also_flushes_after_one_second_of_wall_time(tmp_path, monkeypatch):
    """With a huge flush_interval_s, a (fake) wall clock advancing 0.4 s per call forces flushes.

    Clock readings: 0.0 at construction, then 0.4, 0.8, 1.2, 1.6 at samples 0..3. Sample 0 is
    always flushed; 1.6 - 0.4 >= 1 s flushes sample 3, so all 4 samples are in the unfinished file.
    Without the wall-clock rule only sample 0 would be.
    """
    clock = iter(np.arange(0.0, 10.0, 0.4))
    monkeypatch.setattr(flight_log.time, "monotonic", lambda: float(next(clock)))
    path, copy = tmp_path / "run.mcap", tmp_path / "copy.mcap"
    writer = _writer(path, flush_interval_s=1e6)
    for sample in _random_samples(4, dt_s=1e-3):
        writer.write(**sample)
    copy.write_bytes(path.read_bytes())
    writer.close()
    with pytest.warns(FlightLogRecoveryWarning):
        assert len(read_flight_log(copy).t) == 4


_CHILD = textwrap.dedent("""
    import sys, time
    import numpy as np
    from flexsim.io.flight_log import FlightLogWriter
    rate_hz, speedup = float(sys.argv[2]), float(sys.argv[3])
    with FlightLogWriter(sys.argv[1], state_names=["q_right_wing_1_m", "xi_right_wing_1_rad"], control_names=["thrust_N", "aileron_rad", "elevator_rad", "rudder_rad"],
                         signal_names=["tip_deflection_right_wing_m"], structure_topology={"right_wing": 5},
                         flush_interval_s=1.0) as writer:
        start = time.monotonic()
        for k in range(10**9):
            t = k / rate_hz
            ahead = t / speedup - (time.monotonic() - start)
            if ahead > 0:
                time.sleep(ahead)
            nodes = np.column_stack([np.zeros(5), np.linspace(0, 10, 5), np.full(5, np.sin(t))])
            writer.write(t, position_m=[50 * t, 0, -1000], euler_rad=[0, 0.05, 0], state=[t, -t],
                         controls=[1e4, 0, 0, 0], signals=[np.sin(t)],
                         structure={"right_wing": nodes})
            print(repr(t), flush=True)
""")


def test_sigkill_loses_at_most_one_second_of_simulated_flight(tmp_path):
    """Kill a writer (100 samples per sim-s, paced at 20 sim-s per wall-s) with SIGKILL.

    The recovered log must reach to within flush_interval_s = 1 s of simulated flight of the last
    sample the child reported as written.
    """
    rate_hz, speedup, kill_after_s = 100.0, 20.0, 25.0
    path = tmp_path / "killed.mcap"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(Path(flexsim.__file__).resolve().parents[1]), os.environ.get("PYTHONPATH", "")]))
    child = subprocess.Popen([sys.executable, "-c", _CHILD, str(path), str(rate_hz), str(speedup)],
                             stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    last_reported_s = -1.0
    deadline = time.monotonic() + 15
    try:
        while last_reported_s < kill_after_s and time.monotonic() < deadline:
            line = child.stdout.readline()
            if not line:
                pytest.fail(f"child ended early: {child.stderr.read()}")
            last_reported_s = float(line)
        child.send_signal(signal.SIGKILL)
    finally:
        child.kill()
        child.wait(timeout=10)
        child.stdout.close()
        child.stderr.close()
    assert child.returncode == -signal.SIGKILL
    assert last_reported_s >= kill_after_s, "child too slow to reach the kill time"

    with pytest.warns(FlightLogRecoveryWarning):
        log = read_flight_log(path)
    assert not log.complete
    assert last_reported_s - log.recovered_until_s <= 1.0
    np.testing.assert_array_equal(log.t, np.arange(len(log.t)) / rate_hz)
    np.testing.assert_array_equal(log.state[:, 0], log.t)
    np.testing.assert_array_equal(log.structure["right_wing"][:, -1, 2], np.sin(log.t))


def test_truncated_file_is_recovered_with_a_warning(tmp_path):
    """Cutting bytes off a finished file leaves a prefix of the samples, read with a warning."""
    path, cut = tmp_path / "run.mcap", tmp_path / "cut.mcap"
    samples = _random_samples(300)
    _write_log(path, samples, flush_interval_s=0.2)
    data = path.read_bytes()
    cut.write_bytes(data[: int(len(data) * 0.6)])
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        log = read_flight_log(cut)
    assert [w.category for w in caught] == [FlightLogRecoveryWarning]
    assert f"{log.recovered_until_s:.6g} s" in str(caught[0].message)
    assert not log.complete and 0 < len(log.t) < len(samples)
    assert log.recovered_until_s == log.t[-1]
    np.testing.assert_array_equal(log.t, [s["t_s"] for s in samples[:len(log.t)]])
    np.testing.assert_array_equal(log.structure["fuselage"],
                                  [s["structure"]["fuselage"] for s in samples[:len(log.t)]])
    assert log.metadata == {"aircraft": "test.toml"}


# --------------------------------------------------------------------------------------------
# Bad input
# --------------------------------------------------------------------------------------------

@pytest.mark.parametrize("name, overrides, error, match", [
    ("run.json", {}, ValueError, r"path: the suffix must be '\.mcap'"),
    ("missing/run.mcap", {}, FileNotFoundError, r"path: directory .*missing.* does not exist"),
    ("run.mcap", {"state_names": ["a", "a"]}, ValueError, r"state_names: .*unique.*\['a'\]"),
    ("run.mcap", {"signal_names": ["ok", ""]}, ValueError, r"signal_names: .*non-empty"),
    ("run.mcap", {"control_names": "thrust"}, ValueError, r"control_names: expected a sequence"),
    ("run.mcap", {"structure_topology": {"right/wing": 3}}, ValueError, r"structure_topology"),
    ("run.mcap", {"structure_topology": {"wing": 0}}, ValueError, r"'wing'.*>= 1, got 0"),
    ("run.mcap", {"flush_interval_s": 0.0}, ValueError, r"flush_interval_s: .*> 0"),
    ("run.mcap", {"metadata": {"n": 3}}, ValueError, r"metadata: .*str"),
])
def test_constructor_rejects_bad_arguments(tmp_path, name, overrides, error, match):
    with pytest.raises(error, match=match):
        _writer(tmp_path / name, **overrides)
    assert not (tmp_path / name).exists()


@pytest.mark.parametrize("change, match", [
    ({"state": np.zeros(4)}, r"state: expected shape \(5,\), got shape \(4,\)"),
    ({"controls": np.zeros((4, 1))}, r"controls: expected shape \(4,\)"),
    ({"position_m": [1.0, 2.0]}, r"position_m: expected shape \(3,\)"),
    ({"state": [0, 0, math.nan, 0, 0]}, r"state\[2\] \('q_right_wing_1_m'\) = nan"),
    ({"signals": [0, math.inf]}, r"signals\[1\] \('tip_deflection_right_wing_m'\) = inf"),
    ({"structure": {"right_wing": np.zeros((5, 3))}}, r"structure: expected components"),
    ({"structure": {"right_wing": np.zeros((4, 3)), "fuselage": np.zeros((3, 3))}},
     r"structure\['right_wing'\]: expected shape \(5, 3\)"),
    ({"structure": {"right_wing": np.full((5, 3), math.nan), "fuselage": np.zeros((3, 3))}},
     r"structure\['right_wing'\]: .*finite"),
    ({"t_s": 0.01}, r"t_s: simulation time must increase strictly"),
    ({"t_s": 0.005}, r"t_s: simulation time must increase strictly"),
    ({"t_s": math.nan}, r"t_s: simulation time must be a finite number"),
])
def test_write_rejects_bad_samples_and_writes_nothing(tmp_path, change, match):
    """A rejected sample leaves the log as it was: the next good sample is still accepted."""
    path = tmp_path / "run.mcap"
    first, second, third = _random_samples(3)
    with _writer(path) as writer:
        writer.write(**first)
        writer.write(**second)
        with pytest.raises(ValueError, match=match):
            writer.write(**{**third, **change})
        writer.write(**third)
    np.testing.assert_array_equal(read_flight_log(path).t, [0.0, 0.01, 0.02])


def test_event_rejects_unknown_level(tmp_path):
    with _writer(tmp_path / "run.mcap") as writer, \
            pytest.raises(ValueError, match=r"level: expected one of \['info', 'warning', 'error'\]"):
        writer.event(0.0, "hello", level="critical")


@pytest.mark.parametrize("content, match", [
    (b"", r"empty \(0 bytes\)"),
    (np.random.default_rng(2).bytes(4096), r"not an MCAP file"),
])
def test_reader_rejects_files_that_are_not_mcap(tmp_path, content, match):
    path = tmp_path / "bad.mcap"
    path.write_bytes(content)
    with pytest.raises(FlightLogError, match=str(path).replace(".", r"\.") + ".*" + match) as info:
        read_flight_log(path)
    assert isinstance(info.value, FlexsimError) and isinstance(info.value, ValueError)


def test_reader_rejects_an_mcap_file_that_is_not_a_flexsim_log(tmp_path):
    path = tmp_path / "other.mcap"
    with open(path, "wb") as stream, ProtobufMcapWriter(stream) as writer:
        writer.write_message("/log", Log(message="hello"), log_time=0, publish_time=0)
    with pytest.raises(FlightLogError, match="not a flexsim flight log"):
        read_flight_log(path)


def test_reader_raises_file_not_found_for_a_missing_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="nothing.mcap"):
        read_flight_log(tmp_path / "nothing.mcap")


def _batched(samples):
    """The keyword arguments of FlightLogWriter.write_samples for a list of write() samples."""
    return dict(t_s=[s["t_s"] for s in samples], **{key: np.array([s[key] for s in samples]) for key in
                                                       ("position_m", "euler_rad", "state", "controls", "signals")},
                structure={name: np.array([s["structure"][name] for s in samples]) for name in TOPOLOGY})


def test_batched_samples_write_the_bytes_of_single_samples_and_of_protobuf(tmp_path):
    """write_samples in batches gives the file that write() sample by sample gives, byte for byte, with the messages
    appended directly (flexsim.io._wire.Messages) or through mcap's Writer.add_message; every message equals
    protobuf's own serialisation of its decoded content (the direct encoding of the state, pose and point-cloud
    messages), including a sample at t = 0 (no time field, an empty timestamp) and zero entries (left out by proto3)."""
    samples = _random_samples(40)
    samples[0]["position_m"][:] = 0.0
    samples[0]["euler_rad"][:] = 0.0  # a pose of zeros but w (the identity rotation)
    samples[1]["state"][2] = -0.0
    single = tmp_path / "single.mcap"
    _write_log(single, samples, events=[(0.05, "note")])
    for fast in (True, False):
        batched = tmp_path / f"batched-{fast}.mcap"
        with _writer(batched) as writer:
            writer._messages.fast = fast and writer._messages.fast
            writer.write_samples(**_batched(samples[:7]))
            writer.write_samples(**_batched(samples[7:8]))
            writer.write_samples(**_batched(samples[8:]))
            writer.event(0.05, "note")
        assert batched.read_bytes() == single.read_bytes(), fast
    from mcap.reader import make_reader
    from foxglove_schemas_protobuf.FrameTransform_pb2 import FrameTransform
    from foxglove_schemas_protobuf.PointCloud_pb2 import PointCloud
    kinds = {"/tf": FrameTransform, "/aircraft/state": flight_log.AircraftState}
    seen = set()
    with open(single, "rb") as f:
        for _, channel, message in make_reader(f).iter_messages():
            kind = kinds.get(channel.topic, PointCloud if channel.topic.startswith("/structure/") else None)
            if kind is not None:
                decoded = kind()
                decoded.ParseFromString(message.data)
                assert decoded.SerializeToString() == message.data, channel.topic
                seen.add(channel.topic)
    assert seen == {"/tf", "/aircraft/state", "/structure/right_wing", "/structure/fuselage"}


def test_batched_samples_are_checked_before_any_is_written(tmp_path):
    samples = _random_samples(5)
    samples[3]["signals"][1] = math.nan
    with _writer(tmp_path / "bad.mcap") as writer:
        with pytest.raises(ValueError, match=r"signals: values must be finite, got signals\[1\] \('tip_deflection_right_wing_m'\)"):
            writer.write_samples(**_batched(samples))
        batch = _batched(samples[:3])
        batch["t_s"][2] = batch["t_s"][1]
        with pytest.raises(ValueError, match="t_s: simulation time must increase strictly"):
            writer.write_samples(**batch)
        batch = _batched(samples[:3])
        batch["structure"]["fuselage"] = batch["structure"]["fuselage"][:, :2]
        with pytest.raises(ValueError, match=r"structure\['fuselage'\]: expected shape \(3, 3, 3\), got shape \(3, 2, 3\)"):
            writer.write_samples(**batch)
        writer.write_samples(**_batched(samples[:3]))  # nothing of the refused batches was written
    assert read_flight_log(tmp_path / "bad.mcap").t.tolist() == [0.0, 0.01, 0.02]
