"""Outputs never lose earlier work and are never written through a symbolic link (flexsim.io.output_paths).

* Default log names are reserved atomically: runs in the same second, in one process or several, get distinct files.
* A log path, a V-g or mode path, a Rerun --save path that is a symbolic link (dangling or not) is refused before any
  work, and the link's target is not created.
* A second FlightLogRecorder on the same path refuses to start instead of overwriting the first's episodes.
* Derived names that print alike (V-g PNGs of altitudes 9144 and 9144.4 m) stay distinct.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from flexsim.io.output_paths import check_not_link, open_output, reserve_new, unique_names


def test_reserved_names_are_distinct_across_calls_and_processes(tmp_path):
    names = [reserve_new(tmp_path, "run-20261204-221500", ".mcap") for _ in range(4)]
    assert [p.name for p in names] == ["run-20261204-221500.mcap", "run-20261204-221500-2.mcap",
                                       "run-20261204-221500-3.mcap", "run-20261204-221500-4.mcap"]
    code = ("import sys; from flexsim.io.output_paths import reserve_new; "
            f"print(reserve_new({str(tmp_path)!r}, 'other', '.mcap'))")
    procs = [subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, text=True) for _ in range(4)]
    got = {p.communicate(timeout=60)[0].strip() for p in procs}
    assert len(got) == 4 and all(Path(g).exists() for g in got)


def test_default_log_paths_of_one_second_are_four_files(tmp_path, monkeypatch):
    from flexsim.sim import recording

    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(recording.time, "strftime", lambda fmt: "20261204-221500")  # four runs in the same second
    paths = [recording.resolve_log_path(True, "elevator-doublet") for _ in range(4)]
    assert len(set(paths)) == 4 and all(p.exists() and p.suffix == ".mcap" for p in paths)


def test_no_output_through_a_symbolic_link(tmp_path):
    target = tmp_path / "authorized_keys"
    link = tmp_path / "run.mcap"
    link.symlink_to(target)  # dangling
    with pytest.raises(ValueError, match=r"is a symbolic link .*does not write through links"):
        check_not_link("log_path", link)
    with pytest.raises(ValueError, match="symbolic link"):
        open_output(link)
    from flexsim.sim.recording import resolve_log_path

    with pytest.raises(ValueError, match=r"log_path = .*run.mcap.*symbolic link"):
        resolve_log_path(link)
    from flexsim.cli.main import main

    assert main(["simulate", "climb", "--duration", "0.1", "--log", str(link)]) == 2
    vg_link = tmp_path / "vg.png"
    vg_link.symlink_to(tmp_path / "elsewhere.png")
    assert main(["flutter", "goland_wing", "--altitudes", "0", "--models", "QS", "--vg", str(vg_link), "--workers", "1"]) == 2
    rrd_link = tmp_path / "out.rrd"
    rrd_link.symlink_to(tmp_path / "other.rrd")
    from flexsim.io.rerun_view import log_to_recording

    with pytest.raises(ValueError, match="rrd_path = .*symbolic link"):
        log_to_recording(str(tmp_path / "missing.mcap"), rrd_path=rrd_link)
    assert not target.exists() and not (tmp_path / "elsewhere.png").exists() and not (tmp_path / "other.rrd").exists()


def test_an_existing_file_that_is_not_a_log_is_kept(tmp_path):
    from flexsim.sim.recording import resolve_log_path

    notes = tmp_path / "notes.mcap"
    notes.write_text("my notes")
    with pytest.raises(FileExistsError, match="not a flight log; it is not overwritten"):
        resolve_log_path(notes)
    assert notes.read_text() == "my notes"


def test_vg_names_of_altitudes_that_print_alike_are_distinct():
    from flexsim.cli.flutter_commands import vg_paths

    assert [p.name for p in vg_paths("vg.png", [9144.0, 9144.4, 0.0])] == ["vg_9144m.png", "vg_9144m-2.png", "vg_0m.png"]
    assert unique_names([Path("a.png")] * 3) == [Path("a.png"), Path("a-2.png"), Path("a-3.png")]


def test_a_second_flight_log_recorder_does_not_overwrite_the_first(tmp_path):
    import gymnasium as gym

    from flexsim import envs  # noqa: F401
    from flexsim.io.env_log import FlightLogRecorder

    path = tmp_path / "agent.mcap"
    env = FlightLogRecorder(gym.make("FlexSim/GTM-LevelHold-v1", aero="quasi-steady"), path)
    env.reset(seed=1)
    env.reset(seed=2)
    env.close()
    first = {p: p.read_bytes() for p in tmp_path.glob("agent*.mcap")}
    assert len(first) == 2
    with pytest.raises(FileExistsError, match=r"2 log\(s\) of an earlier recording are there .*not overwritten"):
        FlightLogRecorder(gym.make("FlexSim/GTM-LevelHold-v1", aero="quasi-steady"), path)
    pattern = tmp_path / "ep{episode}.mcap"
    (tmp_path / "ep3.mcap").write_bytes(b"x")
    with pytest.raises(FileExistsError, match="ep3.mcap"):
        FlightLogRecorder(gym.make("FlexSim/GTM-LevelHold-v1", aero="quasi-steady"), pattern)
    assert {p: p.read_bytes() for p in tmp_path.glob("agent*.mcap")} == first


def test_vg_path_is_checked_before_the_search(tmp_path, capsys, monkeypatch):
    """A --vg file in a folder that does not exist is refused before any flutter point is computed (the search used
    to run to the end, and its table was then not printed)."""
    from flexsim.cli.main import main
    from flexsim.linear import study

    def no_search(*args, **kwargs):
        raise AssertionError("the search ran before the output path was checked")

    monkeypatch.setattr(study, "run_point", no_search)
    monkeypatch.setattr(study, "run_points", no_search)
    assert main(["flutter", "goland_wing", "--altitudes", "0", "1000", "--models", "QS", "--workers", "1",
                 "--vg", str(tmp_path / "missing" / "vg.png")]) == 2
    assert "--vg" in capsys.readouterr().err
