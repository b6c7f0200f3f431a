"""Rendering and flight logs.

Checks: ``render_mode="rgb_array"`` returns a uint8 (H, W, 3) image that is not blank; render without a
render mode warns and returns None; ``FlightLogRecorder`` writes one MCAP log per episode that
``read_flight_log`` reads back complete, with the model's state names, the physical controls, the
tip-deflection signals, every component's beam nodes and the reset/termination events, the logged
state equal to the env's state (exact), and ``log_to_recording`` converts it to an .rrd file.
"""

import gymnasium as gym
import numpy as np
import pytest

from flexsim.io.flight_log import read_flight_log
from flexsim.io.rerun_view import log_to_recording

from flexsim import envs


def test_rgb_array_render():
    env = gym.make("FlexSim/GTM-Turn-v0", aero="quasi-steady", render_mode="rgb_array")
    _, info = env.reset(seed=0)
    env.step(info["trim_action"])
    frame = env.render()
    assert frame.dtype == np.uint8 and frame.ndim == 3 and frame.shape[2] == 3 and frame.shape[0] >= 200
    assert frame.std() > 5.0
    env.close()


def test_render_without_mode_warns():
    env = envs.LevelHoldEnv(aero="quasi-steady")
    env.reset(seed=0)
    with pytest.warns(UserWarning, match="without a render_mode"):
        assert env.render() is None


def test_flight_log_recorder_round_trip(tmp_path):
    env = envs.FlightLogRecorder(gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady", turbulence="none"),
                                 tmp_path / "run.mcap", metadata={"purpose": "test"})
    for seed in (0, 1):
        _, info = env.reset(seed=seed)
        for _ in range(15):
            env.step(info["trim_action"])
    state = env.unwrapped.state
    env.close()
    assert env.paths == [tmp_path / "run.mcap", tmp_path / "run-0001.mcap"]
    log = read_flight_log(env.paths[1])
    assert log.complete and len(log.t) == 16
    np.testing.assert_allclose(log.t, np.arange(16) * 0.02, atol=1e-12)
    base = env.unwrapped
    assert log.state_names == base.dynamics.state_names() and log.state_names[6].startswith("q_fuselage_1")
    assert log.control_names == ("thrust_N", "aileron_rad", "elevator_rad", "rudder_rad")
    assert "tip_deflection_right_wing_m" in log.signal_names and "reward" in log.signal_names
    # one vocabulary and one output layer: the env log names and computes what a simulate() log of the
    # same model does; the env adds its task errors and the reward after the simulator's signals
    out = base.dynamics.outputs
    assert log.signal_names[: len(out.signal_names)] == out.signal_names and log.format_version == "2"
    errors = tuple(f"error_{spec[0]}" for spec in base.task_errors_spec)
    assert log.signal_names[len(out.signal_names):] == errors + ("reward",)
    np.testing.assert_array_equal(log.signals[-1, : len(out.signal_names)], out.signals(log.t[-1], state, log.controls[-1]))
    assert set(log.structure) == set(base.aircraft.component_names)
    np.testing.assert_array_equal(log.state[-1], state)
    assert log.metadata["purpose"] == "test" and log.metadata["seed"] == "1"
    assert log.terms == base.dynamics.model.terms.record() and log.terms["aero"]["model"] == "quasi-steady"
    assert log.events[0].text.startswith("reset")
    rrd = tmp_path / "run.rrd"
    log_to_recording(env.paths[1], rrd_path=rrd)
    assert rrd.stat().st_size > 1000


def test_flight_log_records_termination(tmp_path):
    env = envs.FlightLogRecorder(gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady", turbulence="none",
                                          limits=envs.FlightLimits(wing_tip_deflection_m=0.5)), tmp_path / "ep{episode}.mcap")
    _, info = env.reset(seed=0)
    env.step(info["trim_action"])
    env.close()
    log = read_flight_log(tmp_path / "ep0.mcap")
    assert log.events[-1].level == "error" and "structural_limit" in log.events[-1].text


def test_human_mode_streams_to_rerun_without_spawning(monkeypatch):
    # The streamer spawns a viewer on its first frame only; here its recording is replaced by an
    # in-memory one beforehand, so the drawing code runs against rerun-sdk without any viewer.
    import rerun as rr

    from flexsim.io.rendering import RerunStreamer

    monkeypatch.setenv("DISPLAY", ":flexsim-test")  # human mode is refused where no viewer can open
    env = envs.LevelHoldEnv(aero="quasi-steady", render_mode="human")
    streamer = RerunStreamer()
    streamer._rec = rr.RecordingStream("flexsim_env_test")
    memory = streamer._rec.memory_recording()
    env._renderer = streamer
    _, info = env.reset(seed=0)
    env.step(info["trim_action"])
    streamer._rec.flush()
    assert memory.drain_as_bytes()[:4] == b"RRF2"
    env.close()


def test_flight_log_records_non_finite_termination(tmp_path):
    """A blow-up in the first sub-step ends the episode without advancing time: the recorder used to
    raise "time must increase strictly" and lose the termination."""
    path = tmp_path / "blowup.mcap"
    env = envs.FlightLogRecorder(gym.make("FlexSim/GTM-LevelHold-v0", aero="quasi-steady", turbulence="none"), path)
    _, info = env.reset(seed=0)
    env.step(info["trim_action"])
    base = env.unwrapped
    base._x[base.dynamics.layout.q.start] = 1e200  # inject a blow-up state
    *_, terminated, _, step_info = env.step(info["trim_action"])
    env.close()
    assert terminated and step_info["termination_reason"] == "non_finite"
    log = read_flight_log(path)
    assert log.complete and np.all(np.diff(log.t) > 0)
    assert any("non_finite" in e.text and e.level == "error" for e in log.events)
