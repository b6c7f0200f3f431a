"""Opening a flight log in a Rerun viewer: ``flexsim view LOG``, ``log_to_recording(spawn=True | connect=URL)``.

Headless and loopback only. The viewer is replaced by Rerun's own executable run as a headless gRPC server that
saves what it receives (``rerun --bind 127.0.0.1 --port N --save OUT.rrd``): either spawned by flexsim's spawn
path (through ``viewer_executable``, a wrapper adding ``--bind``/``--save`` to the arguments rerun-sdk passes), or
started by the test for ``--connect``. The entities that arrive are compared with the ``.rrd`` file flexsim writes
for the same log (exact: the same entity paths with the same row counts). Without a display, spawning fails in
well under a second with a message naming ``--save``.
"""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
import warnings
from pathlib import Path

import pytest
import rerun_cli
from rerun.chunk import RrdReader
from rerun.error_utils import RerunWarning

from flexsim.cli.main import main as cli_main
from flexsim.io.rerun_view import log_to_recording
from flexsim.io.viewer import ViewerUnavailableError, viewer_unavailable_reason
from tests.io.test_rerun_view import N_SAMPLES, _rows_by_entity, _write_circle_log

RERUN_EXE = Path(rerun_cli.__file__).resolve().parent / ("rerun.exe" if sys.platform == "win32" else "rerun")
posix_only = pytest.mark.skipif(os.name != "posix", reason="the viewer stand-in is a POSIX shell wrapper")


@pytest.fixture(scope="module")
def log_and_reference(tmp_path_factory):
    """A synthetic flight log and the entity rows of the .rrd file flexsim writes for it (the reference)."""
    folder = tmp_path_factory.mktemp("viewer")
    log = folder / "circle.mcap"
    _write_circle_log(log)
    log_to_recording(log, rrd_path=folder / "reference.rrd")
    rows, _ = _rows_by_entity(RrdReader(folder / "reference.rrd").stream().collect().stream())
    assert rows[("/world/aircraft", False)] == N_SAMPLES and rows[("/events", False)] == 2
    return log, rows


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _stop_and_read(pid: int, rrd: Path, expected_rows: dict, timeout_s: float = 30.0) -> dict:
    """Wait until the server's .rrd has every expected row, stop the server (SIGINT), return the rows found."""
    deadline, rows = time.monotonic() + timeout_s, {}
    try:
        while time.monotonic() < deadline:
            if rrd.exists() and rrd.stat().st_size > 0:
                try:
                    with warnings.catch_warnings():  # no footer yet: the server is still writing the file
                        warnings.filterwarnings("ignore", "RRD file has no footer", RerunWarning)
                        rows, _ = _rows_by_entity(RrdReader(rrd).stream().collect().stream())
                except Exception:  # a partly written chunk
                    rows = {}
                if all(rows.get(key, 0) >= n for key, n in expected_rows.items()):
                    break
            time.sleep(0.3)
    finally:
        _stop(pid)
    return rows


def _stop(pid: int) -> None:
    """SIGINT the server (it finishes its .rrd), SIGKILL it if still running after 10 s."""
    for sig, wait_s in ((signal.SIGINT, 10.0), (signal.SIGKILL, 5.0)):
        try:
            os.kill(pid, sig)
        except ProcessLookupError:
            return
        deadline = time.monotonic() + wait_s
        while time.monotonic() < deadline:
            if not _running(pid):
                return
            time.sleep(0.1)


def _running(pid: int) -> bool:
    """Whether ``pid`` still runs; reaps it if it is a child of this process (rerun-sdk may spawn it as one)."""
    try:
        done, _ = os.waitpid(pid, os.WNOHANG)
        return done == 0
    except ChildProcessError:  # not our child: ask the kernel
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return False
        return True


def test_viewer_unavailable_reason_follows_the_display():
    assert "no display" in viewer_unavailable_reason({}, "linux")
    assert viewer_unavailable_reason({"DISPLAY": ":0"}, "linux") is None
    assert viewer_unavailable_reason({"WAYLAND_DISPLAY": "wayland-0"}, "linux") is None
    assert viewer_unavailable_reason({}, "darwin") is None
    assert viewer_unavailable_reason({}, "win32") is None


def test_spawn_without_display_fails_fast_and_says_what_to_do(log_and_reference, monkeypatch, capsys):
    log, _ = log_and_reference
    for name in ("DISPLAY", "WAYLAND_DISPLAY", "WAYLAND_SOCKET"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setattr(sys, "platform", "linux")
    start = time.monotonic()
    with pytest.raises(ViewerUnavailableError, match=r"no display.*--save run\.rrd.*--connect"):
        log_to_recording(log, spawn=True)
    assert time.monotonic() - start < 1.0
    assert cli_main(["view", str(log)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("flexsim view: error: cannot open a Rerun viewer: no display")


@posix_only
def test_spawned_viewer_receives_every_entity(log_and_reference, tmp_path, monkeypatch):
    """`flexsim view LOG --viewer EXE`: the spawn path (rerun.spawn through the recording) starts the viewer stand-in
    and streams every entity of the log to it."""
    log, reference = log_and_reference
    monkeypatch.setenv("DISPLAY", ":flexsim-test")  # the stand-in needs none; the check must let it start
    received, pid_file = tmp_path / "received.rrd", tmp_path / "viewer.pid"
    wrapper = tmp_path / "rerun-viewer"
    wrapper.write_text(f'#!/bin/sh\necho $$ > "{pid_file}"\n'
                       f'exec "{RERUN_EXE}" --bind 127.0.0.1 --save "{received}" "$@"\n')
    wrapper.chmod(0o755)
    monkeypatch.setenv("RERUN_ANALYTICS", "0")
    assert cli_main(["view", str(log), "--port", str(_free_port()), "--viewer", str(wrapper)]) == 0
    rows = _stop_and_read(int(pid_file.read_text()), received, reference)
    assert rows == reference


def test_view_with_a_viewer_that_is_not_executable_is_refused(log_and_reference, tmp_path, capsys):
    log, _ = log_and_reference
    with pytest.raises(SystemExit) as exit_info:
        cli_main(["view", str(log), "--viewer", str(tmp_path / "no-such-rerun")])
    assert exit_info.value.code == 2
    assert "--viewer = " in capsys.readouterr().err


@posix_only
def test_flexsim_view_connect_streams_to_a_running_server(log_and_reference, tmp_path, capsys):
    log, reference = log_and_reference
    port, received = _free_port(), tmp_path / "received.rrd"
    server = subprocess.Popen([str(RERUN_EXE), "--bind", "127.0.0.1", "--port", str(port), "--save", str(received)],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                              env={**os.environ, "RERUN_ANALYTICS": "0"})
    try:
        deadline = time.monotonic() + 20.0
        while True:  # wait until the server listens
            try:
                socket.create_connection(("127.0.0.1", port), timeout=0.5).close()
                break
            except OSError:
                assert time.monotonic() < deadline, "the Rerun server did not start listening"
                time.sleep(0.2)
        assert cli_main(["view", str(log), "--connect", f"rerun+http://127.0.0.1:{port}/proxy"]) == 0
        assert f"sending the log to rerun+http://127.0.0.1:{port}/proxy" in capsys.readouterr().out
        rows = _stop_and_read(server.pid, received, reference)
    finally:
        server.wait(timeout=30)
    assert rows == reference
