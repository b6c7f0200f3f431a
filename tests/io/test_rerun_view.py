"""Tests of the MCAP -> Rerun conversion (flexsim.io.rerun_view) and of Rerun's own MCAP importer.

Headless: recordings are written to ``.rrd`` files under ``tmp_path`` and read back with
``rerun.chunk.RrdReader``; no viewer is spawned. The synthetic flight is a level circle (radius
500 m at 50 m/s, 1000 m altitude) with a sinusoidally bending 5-node right wing, 200 samples.
"""

import os
import math
from collections import Counter

import numpy as np
import pyarrow as pa
import pytest
from rerun.chunk import McapReader, RrdReader

from flexsim.io.flight_log import FlightLogRecoveryWarning, FlightLogWriter, read_flight_log, viewer_pose
from flexsim.io.rerun_view import log_to_recording

N_SAMPLES, DT_S, RADIUS_M, SPEED_M_S, ALTITUDE_M = 200, 0.05, 500.0, 50.0, 1000.0
HALF_SPAN_M, N_NODES, BEND_AMPLITUDE_M, BEND_FREQUENCY_HZ = 10.0, 5, 0.5, 1.5
CONTROL_NAMES = ("thrust_N", "aileron_rad", "elevator_rad", "rudder_rad")


def _write_circle_log(path, n_samples=N_SAMPLES):
    """Write the synthetic circle flight; return the node positions (n_samples, N_NODES, 3)."""
    omega = SPEED_M_S / RADIUS_M
    span = np.linspace(0.0, HALF_SPAN_M, N_NODES)
    bank = math.atan(SPEED_M_S * omega / 9.81)
    all_nodes = []
    with FlightLogWriter(path, state_names=["v_x_m_s", "q_right_wing_1_m", "q_right_wing_2_m", "xi_right_wing_1_rad"],
                         control_names=CONTROL_NAMES, signal_names=["airspeed_m_s", "tip_deflection_right_wing_m"],
                         structure_topology={"right_wing": N_NODES},
                         metadata={"case": "circle"}) as writer:
        for k in range(n_samples):
            t = k * DT_S
            tip_z = BEND_AMPLITUDE_M * math.sin(2 * math.pi * BEND_FREQUENCY_HZ * t)
            nodes = np.column_stack([np.zeros(N_NODES), span, tip_z * (span / HALF_SPAN_M) ** 2])
            all_nodes.append(nodes)
            writer.write(t, position_m=[RADIUS_M * math.sin(omega * t),
                                        RADIUS_M * (1 - math.cos(omega * t)), -ALTITUDE_M],
                         euler_rad=[bank, 0.02, omega * t], state=[SPEED_M_S, tip_z, 0.1 * tip_z, 0.01],
                         controls=[2e3, 0.0, -0.02, 0.001], signals=[SPEED_M_S, tip_z],
                         structure={"right_wing": nodes})
            if k in (20, 150):
                writer.event(t, f"sample {k}", level="warning" if k == 150 else "info")
    return np.array(all_nodes)


def _rows_by_entity(chunks):
    """(entity path, static?) -> number of rows, and entity path -> set of column names."""
    rows, columns = Counter(), {}
    for chunk in chunks:
        rows[(chunk.entity_path, chunk.is_static)] += chunk.num_rows
        columns.setdefault(chunk.entity_path, set()).update(chunk.to_record_batch().schema.names)
    return rows, columns


def _temporal_column(chunks, entity_path, column):
    """Concatenate ``column`` of the non-static chunks of ``entity_path``, sorted by sim_time."""
    batches = [c.to_record_batch() for c in chunks if c.entity_path == entity_path and not c.is_static]
    table = pa.Table.from_batches(batches).sort_by("sim_time")
    return table.column(column).to_pylist()


@pytest.fixture(scope="module")
def circle_log(tmp_path_factory):
    path = tmp_path_factory.mktemp("circle") / "circle.mcap"
    nodes = _write_circle_log(path)
    return path, nodes


def test_rrd_has_the_expected_entities_row_counts_and_timeline(circle_log, tmp_path):
    """Every entity of the layout exists with one row per sample (events: one per event)."""
    mcap_path, _ = circle_log
    rrd_path = tmp_path / "circle.rrd"
    log_to_recording(mcap_path, rrd_path=rrd_path)
    reader = RrdReader(rrd_path)
    chunks = list(reader.stream().collect().stream())
    rows, columns = _rows_by_entity(chunks)

    temporal = {path: n for (path, static), n in rows.items() if not static}
    per_sample = ["/world/aircraft", "/world/aircraft/structure/right_wing", "/plots/attitude",
                  "/plots/altitude", "/plots/speed", "/plots/tip_deflections",
                  "/plots/modal/bending", "/plots/modal/torsion",
                  *[f"/plots/controls/{name}" for name in CONTROL_NAMES]]
    assert temporal == {**{path: N_SAMPLES for path in per_sample}, "/events": 2}
    assert rows[("/world/flight_path", True)] == 1
    assert {"LineStrips3D:strips", "Points3D:positions"} <= columns["/world/aircraft/structure/right_wing"]
    assert {"Transform3D:translation", "Transform3D:quaternion"} <= columns["/world/aircraft"]
    assert {name for chunk in chunks for name in chunk.timeline_names} == {"sim_time"}
    assert [entry.application_id for entry in reader.recordings()] == ["flexsim"]
    assert len(reader.blueprints()) == 1


def test_rrd_values_match_the_log(circle_log, tmp_path):
    """Pose, deformed wing, attitude [deg], modal coordinates, speeds and altitude match the log."""
    mcap_path, nodes = circle_log
    log = read_flight_log(mcap_path)
    rrd_path = tmp_path / "circle.rrd"
    log_to_recording(log, rrd_path=rrd_path)
    chunks = list(RrdReader(rrd_path).stream().collect().stream())

    translation, quaternion = viewer_pose(log.position_m, log.euler_rad)
    rrd_translation = _temporal_column(chunks, "/world/aircraft", "Transform3D:translation")
    rrd_quaternion = _temporal_column(chunks, "/world/aircraft", "Transform3D:quaternion")
    np.testing.assert_allclose(np.array(rrd_translation)[:, 0], translation, rtol=1e-6, atol=1e-4)
    np.testing.assert_allclose(np.array(rrd_quaternion)[:, 0], quaternion, atol=1e-6)
    strips = _temporal_column(chunks, "/world/aircraft/structure/right_wing", "LineStrips3D:strips")
    np.testing.assert_allclose(np.array(strips)[:, 0], nodes, atol=1e-6)
    attitude = np.array(_temporal_column(chunks, "/plots/attitude", "Scalars:scalars"))
    np.testing.assert_allclose(attitude, np.rad2deg(log.euler_rad), rtol=1e-12)
    modal = np.array(_temporal_column(chunks, "/plots/modal/bending", "Scalars:scalars"))
    np.testing.assert_array_equal(modal, log.state[:, 1:3])
    # Speed panel: the airspeed signal, then the ground speed from the circle's positions (= V).
    speed = np.array(_temporal_column(chunks, "/plots/speed", "Scalars:scalars"))
    np.testing.assert_array_equal(speed[:, 0], SPEED_M_S)
    np.testing.assert_allclose(speed[:, 1], SPEED_M_S, rtol=1e-4)
    altitude = np.array(_temporal_column(chunks, "/plots/altitude", "Scalars:scalars"))
    np.testing.assert_array_equal(altitude[:, 0], ALTITUDE_M)


def test_truncated_log_converts_with_a_warning(circle_log, tmp_path):
    mcap_path, _ = circle_log
    cut = tmp_path / "cut.mcap"
    cut.write_bytes(mcap_path.read_bytes()[:-200])
    with pytest.warns(FlightLogRecoveryWarning):
        log_to_recording(cut, rrd_path=tmp_path / "cut.rrd")
    rows, _ = _rows_by_entity(RrdReader(tmp_path / "cut.rrd").stream().collect().stream())
    assert 0 < rows[("/world/aircraft", False)] <= N_SAMPLES


@pytest.mark.parametrize("kwargs, error, match", [
    ({}, ValueError, "rrd_path.*spawn"),
    ({"rrd_path": "out.mcap"}, ValueError, r"rrd_path: the suffix must be '\.rrd'"),
    ({"rrd_path": "missing/out.rrd"}, FileNotFoundError, "rrd_path: directory"),
])
def test_log_to_recording_rejects_bad_arguments(circle_log, tmp_path, kwargs, error, match):
    if "rrd_path" in kwargs:
        kwargs = {"rrd_path": tmp_path / kwargs["rrd_path"]}
    with pytest.raises(error, match=match):
        log_to_recording(circle_log[0], **kwargs)


def test_rerun_mcap_importer_reads_our_mcap(circle_log):
    """Rerun's own importer maps /tf to Transform3D (world -> body) and the structure to Points3D."""
    mcap_path, nodes = circle_log
    chunks = list(McapReader(mcap_path, timeline_type="duration_ns").stream())
    rows, columns = _rows_by_entity(chunks)
    entities = {path for path, _ in rows}
    assert {"/tf", "/structure/right_wing", "/aircraft/state", "/events"} <= entities

    def rows_with(entity, column):
        return sum(c.num_rows for c in chunks if c.entity_path == entity
                   and column in c.to_record_batch().schema.names)

    assert rows_with("/tf", "Transform3D:translation") == N_SAMPLES
    assert rows_with("/structure/right_wing", "Points3D:positions") == N_SAMPLES
    assert rows_with("/events", "TextLog:text") == 2
    assert "flexsim.AircraftState:message" in columns["/aircraft/state"]
    tf = pa.Table.from_batches([c.to_record_batch() for c in chunks if c.entity_path == "/tf"
                                and "Transform3D:parent_frame" in c.to_record_batch().schema.names])
    assert {tuple(f) for f in tf.column("Transform3D:parent_frame").to_pylist()} == {("world",)}
    assert {tuple(f) for f in tf.column("Transform3D:child_frame").to_pylist()} == {("body",)}
    cloud = [c.to_record_batch() for c in chunks if c.entity_path == "/structure/right_wing"
             and "Points3D:positions" in c.to_record_batch().schema.names]
    table = pa.Table.from_batches(cloud).sort_by("message_log_time")
    np.testing.assert_allclose(np.array(table.column("Points3D:positions").to_pylist()), nodes, atol=1e-6)
    assert {tuple(f) for f in table.column("CoordinateFrame:frame").to_pylist()} == {("body",)}


@pytest.mark.skipif(not os.path.exists("/dev/full"), reason="needs /dev/full (writes fail with ENOSPC)")
def test_save_onto_a_full_disk_fails_at_once_naming_the_file(circle_log, tmp_path, monkeypatch, capsys):
    """`flexsim view --save` onto a full disk: an error naming the file (ENOSPC from the kernel's /dev/full), no
    partial file, and no hang (rerun's own file sink waited forever on a full disk)."""
    from flexsim.cli.main import main
    from flexsim.io import output_paths, rerun_view

    mcap_path, _ = circle_log
    target = tmp_path / "full.rrd"
    monkeypatch.setattr(rerun_view, "open_output", lambda path: output_paths.open_output("/dev/full"))
    assert main(["view", str(mcap_path), "--save", str(target)]) == 2
    err = capsys.readouterr().err
    assert "full.rrd" in err and "could not be written" in err and "No space left" in err
    assert not target.exists()
