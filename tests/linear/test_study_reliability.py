"""Sweeps keep and resume their results: every point is written as it finishes, a killed
worker costs only its in-flight points (retried, reported), Ctrl-C stops within 5 s keeping what is
done, ``resume`` skips finished points, and progress is printed line by line when not on a terminal.

The points are stand-ins (``run_point`` replaced by a function that sleeps and returns a row) so that
the tests measure the study machinery, not the flutter search; worker processes are forked, so they
see the replacement.
"""

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from dataclasses import asdict

import pytest

from flexsim.errors import FlexsimError
from flexsim.linear import study
from flexsim.linear.study import StudyCase, StudyRecord, run_study

CASES = [StudyCase("gtm", m, h, turn_radius_m=r) for m in ("QS",) for h in (0.0, 9144.0) for r in (5000.0, 6000.0, 7000.0)]


def _fake_point(case, mach_guess=None):
    time.sleep(0.05)
    row = asdict(case)
    row.update(mach=0.5 + case.altitude_m / 1e5 + case.turn_radius_m / 1e6, omega_rad_s=40.0, guess=mach_guess)
    if os.environ.get("FLEXSIM_TEST_KILL") and case.turn_radius_m == 6000.0 and case.altitude_m == 0.0:
        marker = os.environ["FLEXSIM_TEST_KILL"]
        if not os.path.exists(marker):
            open(marker, "w").close()
            os.kill(os.getpid(), signal.SIGKILL)  # the worker dies once while computing this point
    return row, 0.05


@pytest.fixture
def fake(monkeypatch):
    monkeypatch.setattr(study, "run_point", _fake_point)


def test_points_written_as_they_finish_and_resumed(tmp_path, fake, capsys):
    rec = StudyRecord(tmp_path / "s.jsonl")
    rows = run_study(CASES[:4], workers=1, record=rec, progress=True)
    rec.close()
    assert len(rows) == 4 and len((tmp_path / "s.jsonl").read_text().splitlines()) == 4
    err = capsys.readouterr().err
    assert "[1/4] QS h=0 m R=5000 m: M_F" in err and "[4/4]" in err  # one line per point when not a terminal
    # chained: each point seeded with the previous one's flutter Mach
    assert rows[1]["guess"] == rows[0]["mach"]
    with pytest.raises(FlexsimError, match="already holds 4 finished points.*--resume"):
        StudyRecord(tmp_path / "s.jsonl")
    with (tmp_path / "s.jsonl").open("a") as f:
        f.write('{"aircraft": "gtm", "mod')  # a partial line from a killed writer
    rec = StudyRecord(tmp_path / "s.jsonl", resume=True)
    assert len(rec.done) == 4 and rec.damaged_lines == 1
    rows = run_study(CASES, workers=1, record=rec, progress=False)
    rec.close()
    lines = (tmp_path / "s.jsonl").read_text().splitlines()
    assert len(rows) == 6 and len(lines) == 6 and all(json.loads(x) for x in lines)
    assert rows[4]["guess"] == rows[3]["mach"]  # the resumed chain starts from its last finished point


def test_killed_worker_costs_only_its_in_flight_point(tmp_path, fake, monkeypatch, capsys):
    monkeypatch.setenv("FLEXSIM_TEST_KILL", str(tmp_path / "killed-once"))
    rec = StudyRecord(tmp_path / "k.jsonl")
    rows = run_study(CASES, workers=2, record=rec, progress=False)
    rec.close()
    assert (tmp_path / "killed-once").exists()
    assert len(rows) == 6 and all("mach" in r for r in rows)
    assert len((tmp_path / "k.jsonl").read_text().splitlines()) == 6
    err = capsys.readouterr().err
    assert "a worker process died" in err and "QS h=0 m R=6000 m" in err


def test_ctrl_c_stops_within_5_s_and_keeps_finished_points(tmp_path):
    script = textwrap.dedent(f"""
        import signal, sys, time
        # a process started in the background by a non-interactive shell inherits SIGINT ignored (POSIX);
        # Ctrl-C at a terminal reaches a foreground process with Python's default handler, as here
        signal.signal(signal.SIGINT, signal.default_int_handler)
        sys.path.insert(0, {os.getcwd()!r})
        from tests.linear.test_study_reliability import CASES
        from flexsim.linear import study
        def slow(case, mach_guess=None):
            time.sleep(0.4)
            return {{"model": case.model, "altitude_m": case.altitude_m, "turn_radius_m": case.turn_radius_m,
                     "climb_angle_deg": 0.0, "mach_min": 0.5, "mach_max": 0.95, "aircraft": "gtm",
                     "structural_damping": None, "mach": 0.6, "omega_rad_s": 1.0}}, 0.4
        study.run_point = slow
        rec = study.StudyRecord({str(tmp_path / "c.jsonl")!r})
        try:
            study.run_study(CASES * 10, workers=2, record=rec, progress=False)
        except KeyboardInterrupt:
            print("interrupted", flush=True)
            sys.exit(130)
        print("completed without an interrupt", flush=True)
    """)
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    record = tmp_path / "c.jsonl"
    deadline = time.monotonic() + 120.0  # start-up on a loaded machine; interrupt once points are being written
    while time.monotonic() < deadline and not (record.exists() and record.read_text().count("\n") >= 2):
        time.sleep(0.1)
    lines_at_signal = record.read_text().count("\n") if record.exists() else 0
    t0 = time.monotonic()
    proc.send_signal(signal.SIGINT)
    out, err = proc.communicate(timeout=30)
    stopped = time.monotonic() - t0
    assert proc.returncode == 130 and "interrupted" in out, (
        f"return code {proc.returncode}, {lines_at_signal} points recorded when SIGINT was sent; stdout: {out!r}; stderr: {err!r}")
    assert stopped < 5.0
    kept = (tmp_path / "c.jsonl").read_text().splitlines()
    assert len(kept) >= 1 and all(json.loads(x)["mach"] == 0.6 for x in kept)


def test_dask_cluster_on_loopback_writes_points_as_they_finish(tmp_path, fake, capsys):
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp", host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        rec = StudyRecord(tmp_path / "d.jsonl")
        rows = run_study(CASES, scheduler=cluster.scheduler_address, record=rec, progress=True)
        rec.close()
    assert len(rows) == 6 and all("mach" in r for r in rows)
    assert len((tmp_path / "d.jsonl").read_text().splitlines()) == 6
    assert rows[2]["guess"] == rows[1]["mach"]
    assert "[6/6]" in capsys.readouterr().err


def test_unreachable_scheduler_is_a_clear_error(fake, monkeypatch):
    pytest.importorskip("dask.distributed")
    monkeypatch.setattr(study, "DASK_CONNECT_TIMEOUT_S", 2.0)
    with pytest.raises(FlexsimError, match="cannot connect to a Dask scheduler"):
        run_study(CASES[:1], scheduler="tcp://127.0.0.1:9", progress=False)


def test_chain_length_cuts_chains_the_same_way_everywhere(tmp_path, fake):
    """chain_length k: position p of a (model, altitude) chain is seeded with the flutter Mach of p - 1 unless
    p is a multiple of k (a new run starts unseeded); serial, process pool and a 2-worker Dask cluster give
    the same rows (the cut depends only on the cases and k)."""
    seen = []
    serial = run_study(CASES, workers=1, progress=False, chain_length=2, on_point=lambda c, r, s: seen.append((c, s)))
    assert [r["guess"] is None for r in serial] == [True, False, True, True, False, True]
    assert serial[1]["guess"] == serial[0]["mach"] and serial[4]["guess"] == serial[3]["mach"]
    assert sorted(c.turn_radius_m for c, _ in seen) == sorted(c.turn_radius_m for c in CASES) and all(s == 0.05 for _, s in seen)
    assert all(r["guess"] is None for r in run_study(CASES, workers=2, progress=False, chain_length=1))
    pool = run_study(CASES, workers=2, progress=False, chain_length=2)
    assert pool == serial
    distributed = pytest.importorskip("dask.distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, protocol="tcp", host="127.0.0.1",
                                  dashboard_address=None) as cluster:
        assert run_study(CASES, scheduler=cluster.scheduler_address, progress=False, chain_length=2) == serial
    with pytest.raises(ValueError, match="chain_length = 0: must be an integer >= 1"):
        run_study(CASES, chain_length=0)


def _children(pid: int) -> set[int]:
    """Live child processes of ``pid`` (Linux /proc)."""
    kids = set()
    for entry in os.listdir("/proc"):
        if entry.isdigit():
            try:
                status = open(f"/proc/{entry}/status").read()
            except OSError:
                continue
            fields = dict(line.split(":\t", 1) for line in status.splitlines() if ":\t" in line)
            if fields.get("PPid", "").strip() == str(pid) and not fields.get("State", "").startswith("Z"):
                kids.add(int(entry))
    return kids


def _alive(pid: int) -> bool:
    try:
        return not open(f"/proc/{pid}/status").read().split("State:\t", 1)[1].startswith("Z")
    except (OSError, IndexError):
        return False


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads child processes from /proc")
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_workers_end_with_their_parent(tmp_path, sig):
    """SIGTERM to a study's process (as `flexsim flutter --workers 2` installs it: raised as Terminated) stops its
    worker processes before it exits with 128 + 15; after SIGKILL, which the parent cannot handle, the kernel ends
    the workers (PR_SET_PDEATHSIG). Either way no worker is left running 10 s later."""
    script = textwrap.dedent(f"""
        import sys, time
        sys.path.insert(0, {os.getcwd()!r})
        from tests.linear.test_study_reliability import CASES
        from flexsim.cli.main import Terminated, _end_on_signals
        from flexsim.linear import study
        def slow(case, mach_guess=None):
            time.sleep(0.4)
            return {{"model": case.model, "altitude_m": case.altitude_m, "turn_radius_m": case.turn_radius_m,
                     "climb_angle_deg": 0.0, "mach_min": 0.5, "mach_max": 0.95, "aircraft": "gtm",
                     "structural_damping": None, "mach": 0.6, "omega_rad_s": 1.0}}, 0.4
        study.run_point = slow
        study._kernels_cached = lambda: True
        _end_on_signals()
        rec = study.StudyRecord({str(tmp_path / "t.jsonl")!r})
        try:
            study.run_study(CASES * 20, workers=2, record=rec, progress=False)
        except Terminated as exc:
            print("terminated", flush=True)
            sys.exit(128 + exc.signum)
    """)
    proc = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    record = tmp_path / "t.jsonl"
    deadline = time.monotonic() + 120.0
    while time.monotonic() < deadline and not (record.exists() and record.read_text().count("\n") >= 2):
        time.sleep(0.1)
    workers = _children(proc.pid)
    assert len(workers) >= 2, f"workers {workers}; stderr so far: {proc.stderr.read() if proc.poll() is not None else ''}"
    proc.send_signal(sig)
    out, err = proc.communicate(timeout=30)
    if sig == signal.SIGTERM:
        assert proc.returncode == 128 + signal.SIGTERM and "terminated" in out, (proc.returncode, out, err)
    deadline = time.monotonic() + 10.0
    while time.monotonic() < deadline and any(_alive(p) for p in workers):
        time.sleep(0.1)
    assert not [p for p in workers if _alive(p)], f"workers still running after {sig.name} to their parent"


def test_resume_recognises_points_whose_rows_resolve_the_case(tmp_path, monkeypatch):
    """A real row resolves its case (formulation None -> the file's "physical"): the record keeps the case's key, so a
    resumed study after a kill skips every finished point instead of computing it again and duplicating its line."""
    calls = []

    def resolving(case, mach_guess=None):
        calls.append(case)
        row = asdict(case)
        row.update(formulation="physical", mach=0.6, omega_rad_s=40.0)
        return row, 0.0

    monkeypatch.setattr(study, "run_point", resolving)
    cases = [StudyCase("gtm", "QS", 0.0, turn_radius_m=r) for r in (5000.0, 6000.0, 7000.0)]
    assert all(c.formulation is None for c in cases)
    rec = StudyRecord(tmp_path / "r.jsonl")
    run_study(cases[:2], workers=1, record=rec, progress=False)
    rec.close()  # as after a SIGKILL: two finished lines on disk
    calls.clear()
    rec = StudyRecord(tmp_path / "r.jsonl", resume=True)
    assert len(rec.done) == 2
    rows = run_study(cases, workers=1, record=rec, progress=False)
    rec.close()
    assert [c.turn_radius_m for c in calls] == [7000.0] and len(rows) == 3
    lines = (tmp_path / "r.jsonl").read_text().splitlines()
    assert len(lines) == 3 and len({json.loads(x)["turn_radius_m"] for x in lines}) == 3


def test_two_studies_cannot_write_one_record_at_once(tmp_path):
    """A second study into the same file while the first runs is refused (it would interleave its rows with the
    first's and then overwrite the first's results); the lock goes with the first's close, or its process."""
    first = StudyRecord(tmp_path / "flutter_turn.jsonl")
    with pytest.raises(FlexsimError, match="another study is writing it now"):
        StudyRecord(tmp_path / "flutter_turn.jsonl")
    code = (f"import sys; sys.path.insert(0, {os.getcwd()!r}); from flexsim.linear.study import StudyRecord; "
            f"StudyRecord({str(tmp_path / 'flutter_turn.jsonl')!r})")
    other = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert other.returncode != 0 and "another study is writing it now" in other.stderr
    first.close()
    StudyRecord(tmp_path / "flutter_turn.jsonl").close()


def test_a_second_sweep_into_one_folder_keeps_the_first_ones_rows(tmp_path, fake, capsys, monkeypatch):
    """`flexsim sweep --resume` into a folder with another altitude's points: the CSV and JSON written at the end
    hold both sweeps' points (they held only the second's, though the record kept both). The figures are left out
    (the stand-in points have no trim values to draw)."""
    from flexsim.cli import flutter_commands
    from flexsim.cli.main import main

    monkeypatch.setattr(flutter_commands, "plot_study", lambda rows, kind, path: path)
    monkeypatch.setattr(flutter_commands, "plot_trim", lambda rows, kind, path, altitude_m: path)

    out = str(tmp_path / "study")
    base = ["sweep", "--turn", "--models", "QS", "--radii-m", "5000", "6000", "--workers", "1", "--out", out,
            "--mach-min", "0.5", "--mach-max", "0.95"]
    assert main(base + ["--altitudes", "0"]) == 0
    assert main(base + ["--altitudes", "3048", "--resume"]) == 0
    rows = json.loads((tmp_path / "study" / "flutter_turn.json").read_text())
    assert sorted({r["altitude_m"] for r in rows}) == [0.0, 3048.0] and len(rows) == 4
    csv_lines = (tmp_path / "study" / "flutter_turn.csv").read_text().splitlines()
    assert len(csv_lines) == 5
