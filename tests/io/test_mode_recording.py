"""Recordings of a mode in 3-D (flexsim.linear.mode_animation, flexsim.io.mode_recording, flexsim flutter --mode,
flexsim view FILE.rrd).

Headless: recordings are written under tmp_path, checked by Rerun's own ``rerun rrd verify`` and read back with
``rerun.chunk.RrdReader``. The animation is checked against the mode it shows: over one period, the Fourier
coefficient of every elastic coordinate at the mode's frequency is a d_k (d = phi / lambda the mode's displacements,
exact for a sinusoid sampled uniformly over a whole period), so the coordinates' ratios to the normalising one equal
the normalised mode shape of flexsim.linear.participation.describe_mode to round-off (asserted 1e-9); the motion is
periodic and its largest beam-node displacement is the requested one (1e-12).
"""

from __future__ import annotations

import os
import subprocess
import sys

import numpy as np
import pytest
from rerun.chunk import RrdReader

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.cli.main import main as cli_main
from flexsim.io.mode_recording import ModeAnimation, ParticipationBar, write_mode_recording
from flexsim.linear.flutter import FlutterAnalysis
from flexsim.linear.mode_animation import mode_animation, record_flutter_mode
from flexsim.linear.participation import describe_mode
from flexsim.linear.stability import spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre
from tests.io.test_rerun_view import _rows_by_entity

FRAMES, CYCLES = 24, 2


def _verify(path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "rerun", "rrd", "verify", str(path)], capture_output=True, text=True,
                          timeout=120, env={**os.environ, "RERUN_ANALYTICS": "0"})


@pytest.fixture(scope="module")
def goland():
    """The Goland wing clamped in a wind tunnel above its flutter speed, and its least stable elastic mode."""
    model = AircraftModel(load_aircraft("goland_wing"), variant="restrained", aero="quasi-steady", gravity_m_s2=0.0,
                          restrained_velocity_m_s=[150.0, 0.0, 0.0], altitude_m=0.0)
    x0 = model.layout.zeros()
    mode = spectrum(model, x0, np.zeros(4), aero_model="quasi-steady").critical("elastic")
    return model, x0, mode


def test_animation_shows_the_mode_shape(goland):
    model, x0, mode = goland
    desc = describe_mode(model.structure, mode.shape, mode.eigenvalue)
    anim = mode_animation(model, x0, mode.shape, mode.eigenvalue, peak_deflection_m=0.3, cycles=CYCLES,
                          frames_per_cycle=FRAMES)
    assert anim.t_s.size == CYCLES * FRAMES + 1
    one = slice(0, FRAMES)  # one whole period, without its end point
    coef = 2.0 / FRAMES * (anim.coordinates[one] * np.exp(-1j * mode.frequency_rad_s * anim.t_s[one])[:, None]).sum(axis=0)
    # the coordinates in state order are V's elastic entries (a restrained model: V = [s, eta])
    reference = desc.normalised_by - 6
    np.testing.assert_allclose(coef / coef[reference], desc.shape[6:], rtol=0, atol=1e-9)
    for name, nodes in anim.structure.items():  # periodic
        np.testing.assert_allclose(nodes[FRAMES], nodes[0], rtol=0, atol=1e-12)
    rest = {c.name: model.structure.point_maps(c.name, np.linspace(0.0, c.length_m, 21)).positions(
        np.zeros(model.structure.dofs.nq), np.zeros(model.structure.dofs.nxi)) for c in model.aircraft.components}
    peak = max(np.linalg.norm(nodes - rest[name][None], axis=2).max() for name, nodes in anim.structure.items())
    assert peak == pytest.approx(0.3, rel=1e-12)
    np.testing.assert_array_equal(anim.position_ned_m, 0.0)  # a clamped wing does not move as a rigid body


def test_recording_is_verified_by_rerun_and_has_its_entities(goland, tmp_path):
    model, x0, mode = goland
    desc = describe_mode(model.structure, mode.shape, mode.eigenvalue)
    bars = tuple(ParticipationBar(p.label, p.magnitude, p.unit, p.phase_deg) for p in desc.leading)
    anim = mode_animation(model, x0, mode.shape, mode.eigenvalue, participation=bars, cycles=CYCLES,
                          frames_per_cycle=FRAMES, title="Goland wing, least stable mode at 150 m/s")
    path = write_mode_recording(anim, tmp_path / "goland.rrd")
    result = _verify(path)
    assert result.returncode == 0, result.stderr
    assert "verified without error" in result.stdout + result.stderr
    reader = RrdReader(path)
    chunks = list(reader.stream().collect().stream())
    rows, columns = _rows_by_entity(chunks)
    n = CYCLES * FRAMES + 1
    for entity in ("/world/aircraft", "/world/aircraft/structure/right_wing", "/plots/attitude", "/plots/modal/bending",
                   "/plots/modal/torsion"):
        assert rows[(entity, False)] == n, entity
    for entity in ("/participation/linear_m", "/participation/angles_deg", "/participation/table", "/description"):
        assert rows[(entity, True)] == 1, entity
    assert "BarChart:values" in columns["/participation/linear_m"]
    assert {name for chunk in chunks for name in chunk.timeline_names} == {"sim_time"}
    assert [entry.application_id for entry in reader.recordings()] == ["flexsim"] and len(reader.blueprints()) == 1


@pytest.fixture(scope="module")
def gtm_flutter():
    analysis = FlutterAnalysis(load_aircraft("gtm"), aero_model="quasi-steady")
    return analysis, analysis.search(SteadyManoeuvre.level(9144.0, mach=0.7), mach_range=(0.5, 0.95))


def test_flutter_point_of_the_free_aircraft_is_recorded(gtm_flutter, tmp_path):
    analysis, point = gtm_flutter
    path = record_flutter_mode(analysis.qs, point, tmp_path / "gtm.rrd", cycles=1, frames_per_cycle=16)
    assert _verify(path).returncode == 0
    rows, _ = _rows_by_entity(RrdReader(path).stream().collect().stream())
    for comp in analysis.qs.aircraft.component_names:
        assert rows[(f"/world/aircraft/structure/{comp}", False)] == 17
    anim = mode_animation(analysis.qs, point.trim.x, point.mode.shape, point.mode.eigenvalue, cycles=1,
                          frames_per_cycle=16)
    # the rigid-body part of the free aircraft's mode moves the pose, about the trim attitude
    np.testing.assert_allclose(anim.euler_rad[:16].mean(axis=0), point.trim.x[analysis.qs.layout.euler], atol=1e-12)
    assert np.ptp(anim.euler_rad[:, 0]) > 0.0 and np.ptp(anim.position_ned_m, axis=0).max() > 0.0


def test_bad_input_is_refused(goland, tmp_path):
    model, x0, mode = goland
    with pytest.raises(ValueError, match="must be oscillatory"):
        mode_animation(model, x0, mode.shape, complex(mode.eigenvalue.real, 0.0))
    with pytest.raises(ValueError, match="velocity_shape: expected"):
        mode_animation(model, x0, mode.shape[:3], mode.eigenvalue)
    with pytest.raises(ValueError, match="frames_per_cycle = 2: must be an integer >= 8"):
        mode_animation(model, x0, mode.shape, mode.eigenvalue, frames_per_cycle=2)
    anim = mode_animation(model, x0, mode.shape, mode.eigenvalue, cycles=1, frames_per_cycle=8)
    with pytest.raises(ValueError, match="suffix must be '.rrd'"):
        write_mode_recording(anim, tmp_path / "mode.mcap")
    with pytest.raises(FileNotFoundError, match="does not exist"):
        write_mode_recording(anim, tmp_path / "no" / "mode.rrd")
    with pytest.raises(ValueError, match="t_s: must be at least 2"):
        ModeAnimation(np.zeros(1), np.zeros((1, 3)), np.zeros((1, 3)), {}, (), np.zeros((1, 0)), (), 1.0)
    with pytest.raises(ValueError, match="unit = 'rad'"):
        ParticipationBar("w", 1.0, "rad", 0.0)


def test_flutter_mode_option_checks_its_path_first(tmp_path, capsys):
    assert cli_main(["flutter", "gtm", "--altitudes", "9144", "--models", "QS", "--mode", str(tmp_path / "m.png")]) == 2
    assert "--mode = " in capsys.readouterr().err


def test_view_of_a_recording(goland, tmp_path, monkeypatch, capsys):
    """``flexsim view FILE.rrd``: without a display it fails at once saying how to open the file; --save is refused;
    a file that is not a recording is named."""
    model, x0, mode = goland
    path = write_mode_recording(mode_animation(model, x0, mode.shape, mode.eigenvalue, cycles=1, frames_per_cycle=8),
                                tmp_path / "mode.rrd")
    for name in ("DISPLAY", "WAYLAND_DISPLAY", "WAYLAND_SOCKET"):
        monkeypatch.delenv(name, raising=False)
    assert cli_main(["view", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("flexsim view: error: cannot open a Rerun viewer: no display") and f"`rerun {path}`" in err
    assert cli_main(["view", str(path), "--save", str(tmp_path / "again.rrd")]) == 2
    assert "is already a Rerun recording" in capsys.readouterr().err
    fake = tmp_path / "fake.rrd"
    fake.write_bytes(b"not a recording")
    assert cli_main(["view", str(fake), "--connect", "rerun+http://127.0.0.1:1/proxy"]) == 2
    assert "not a Rerun recording" in capsys.readouterr().err


@pytest.mark.skipif(os.name != "posix", reason="the viewer stand-in is started as on POSIX")
def test_view_connect_sends_the_recording_to_a_running_server(goland, tmp_path, capsys):
    from tests.io.test_viewer import RERUN_EXE, _free_port, _stop_and_read

    import socket
    import time

    model, x0, mode = goland
    path = write_mode_recording(mode_animation(model, x0, mode.shape, mode.eigenvalue, cycles=1, frames_per_cycle=8),
                                tmp_path / "mode.rrd")
    port, received = _free_port(), tmp_path / "received.rrd"
    server = subprocess.Popen([str(RERUN_EXE), "--bind", "127.0.0.1", "--port", str(port), "--save", str(received)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env={**os.environ, "RERUN_ANALYTICS": "0"})
    try:
        deadline = time.monotonic() + 20.0
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
                break
            except OSError:
                assert time.monotonic() < deadline, "the Rerun server did not start listening"
                time.sleep(0.2)
        url = f"rerun+http://127.0.0.1:{port}/proxy"
        assert cli_main(["view", str(path), "--connect", url]) == 0
        assert f"sent {path} to {url}" in capsys.readouterr().out
        rows = _stop_and_read(server.pid, received, {("/world/aircraft/structure/right_wing", False): 9})
    finally:
        server.wait(timeout=30)
    assert rows[("/world/aircraft/structure/right_wing", False)] == 9


def test_flutter_mode_option_writes_a_verified_recording(tmp_path, capsys):
    path = tmp_path / "qs.rrd"
    assert cli_main(["flutter", "gtm", "--altitudes", "9144", "--models", "QS", "--workers", "1", "--paper-replication",
                     "--mode", str(path)]) == 0
    out = capsys.readouterr().out
    assert f"recorded to {path}" in out and "wings torsion 1 (antisymmetric)" in out
    assert _verify(path).returncode == 0


@pytest.mark.skipif(os.name != "posix", reason="the viewer stand-in is a POSIX shell wrapper")
def test_view_spawns_a_viewer_with_the_recording(goland, tmp_path, monkeypatch):
    """``flexsim view FILE.rrd --viewer EXE``: the spawn path of ``flexsim view`` starts the viewer (a stand-in that
    saves what it receives, as in tests/io/test_viewer.py) and sends it the recording."""
    from tests.io.test_viewer import RERUN_EXE, _free_port, _stop_and_read

    model, x0, mode = goland
    path = write_mode_recording(mode_animation(model, x0, mode.shape, mode.eigenvalue, cycles=1, frames_per_cycle=8),
                                tmp_path / "mode.rrd")
    monkeypatch.setenv("DISPLAY", ":flexsim-test")  # the stand-in needs none; the check must let it start
    monkeypatch.setenv("RERUN_ANALYTICS", "0")
    received, pid_file = tmp_path / "received.rrd", tmp_path / "viewer.pid"
    wrapper = tmp_path / "rerun-viewer"
    wrapper.write_text(f'#!/bin/sh\necho $$ > "{pid_file}"\nexec "{RERUN_EXE}" --bind 127.0.0.1 --save "{received}" "$@"\n')
    wrapper.chmod(0o755)
    assert cli_main(["view", str(path), "--port", str(_free_port()), "--viewer", str(wrapper)]) == 0
    rows = _stop_and_read(int(pid_file.read_text()), received, {("/world/aircraft/structure/right_wing", False): 9})
    assert rows[("/world/aircraft/structure/right_wing", False)] == 9
