"""Re-measure the reliability table (docs/validation.md, "Bad input"): malformed aircraft files, bad CLI input and infeasible trims, damaged flight
logs, and interrupted sweeps.

    python studies/reliability_census.py aircraft|cli|logs|sweeps|all [--out DIR] [--quick]

Each part writes ``DIR/<part>.json`` (every case with its command, exit code, time and verdict) and prints
its counts; ``all`` runs the parts in turn and prints the table. Verdicts as in the review:
CLEAR = a flexsim error naming the field/option and the value; OBSCURE = an error message from inside a
library (LAPACK, numpy, recursion); TRACEBACK = a Python traceback reached the user; SILENT = exit 0 with
NaN/absurd output or a different question answered where an error was due; HANG = over the time limit;
OK = legal input, sane output; WARNED = legal but out of validity, answered with an explicit warning.

Aircraft files and CLI cases run in this process through ``flexsim.cli.main.main`` (an exception escaping
it counts as a traceback), each under a wall-clock alarm; Ctrl-C, kills and sweeps run ``flexsim`` as
child processes. ``--quick`` builds the two 50 MB aircraft files at 3 MB (same size-limit path).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import math
import os
import re
import signal
import subprocess
import sys
import tempfile
import time
import warnings
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from flexsim.cli.main import main as flexsim_main  # noqa: E402
from tests.corpus import aircraft_cases, log_damages  # noqa: E402

OBSCURE = re.compile(r"LAPACK|leading minor|zero-size array|recursion depth|not positive definite \(|singular matrix|"
                     r"unsupported operand|object has no attribute|codec can't decode byte 0x[0-9a-f]+ in position 0", re.I)
NONFINITE = re.compile(r"(?<![A-Za-z_])(nan|-?inf|NaN|-?Infinity)(?![A-Za-z_])")
FLEXSIM = [sys.executable, "-m", "flexsim.cli.main"]


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout()


def run_cli(argv: list[str], limit_s: float = 300.0) -> dict:
    """Run ``flexsim ARGV`` in this process: exit code, stdout, stderr, seconds, traceback/hang flags."""
    out, err = io.StringIO(), io.StringIO()
    t0 = time.monotonic()
    traceback_text = ""
    signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, limit_s)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err), warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            rc = flexsim_main(argv)
        hang = False
    except _Timeout:
        rc, hang = None, True
    except SystemExit as exc:  # argparse errors
        rc, hang = (exc.code if isinstance(exc.code, int) else 2), False
    except BaseException as exc:  # noqa: BLE001 - escaping the CLI = a traceback for the user
        import traceback

        rc, hang, traceback_text = 1, False, "".join(traceback.format_exception(exc))
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
    return {"argv": argv, "rc": rc, "seconds": round(time.monotonic() - t0, 2), "stdout": out.getvalue()[-3000:],
            "stderr": err.getvalue()[-3000:], "hang": hang, "traceback": traceback_text[-2000:]}


def verdict(result: dict, expect: str) -> str:
    """Classify one command result against what was due (``error``, ``ok``, ``ok_or_error``, ``warn``)."""
    if result["hang"]:
        return "HANG"
    if result["traceback"] or "Traceback (most recent call last)" in result["stderr"]:
        return "TRACEBACK"
    err = result["stderr"]
    rc = result["rc"]
    if rc not in (0, None):
        if OBSCURE.search(err):
            return "OBSCURE"
        return "CLEAR" if expect in ("error", "ok_or_error") else ("CLEAR" if "error:" in err else "OBSCURE")
    # exit 0
    if expect == "error":
        return "SILENT"
    text = result["stdout"].strip()
    if text.startswith(("{", "[")):  # --json: strict JSON without NaN (the radius of straight flight is "inf")
        try:
            json.loads(text, parse_constant=lambda token: (_ for _ in ()).throw(ValueError(token)))
        except ValueError:
            return "SILENT"
        if re.search(r'"nan"', text):
            return "SILENT"
    elif NONFINITE.search(text):
        return "SILENT"
    if expect == "warn":
        return "WARNED" if "warning:" in err else "SILENT"
    return "OK"


# ----------------------------------------------------------------------------------------------- aircraft
def part_aircraft(out: Path, quick: bool) -> dict:
    work = Path(tempfile.mkdtemp(prefix="census-aircraft-"))
    cases = aircraft_cases(big=not quick)
    results = []
    for c in cases:
        path = work / (c.path if c.path is not None else f"{c.id}.toml")
        if c.content is not None:
            path.write_bytes(c.content)
        commands = [["info", str(path)]]
        if c.base == "goland_wing":
            commands += [["modes", str(path), "--variant", "restrained", "--count", "8"], ["aero", str(path)], ["trim", str(path)]]
        else:
            commands += [["modes", str(path), "--count", "14"], ["trim", str(path)]]
        runs = []
        for argv in commands:
            r = run_cli(argv, limit_s=240.0)
            # the unmodified Goland wing cannot be trimmed (a clamped single wing): a clear trim failure is its reference
            expect = c.expect if not (argv[0] == "trim" and c.expect == "ok") else "ok_or_error"
            r["verdict"] = verdict(r, expect)
            runs.append(r)
            if c.expect == "error" and r["rc"] not in (0, None) and argv[0] == "info":
                break  # the loader refused the file: every command gives the same message (review: "= loader error")
        order = ["HANG", "TRACEBACK", "SILENT", "OBSCURE", "CLEAR", "WARNED", "OK"]
        worst = min((r["verdict"] for r in runs), key=order.index)
        if c.expect == "ok" and worst == "CLEAR":
            worst = "OK"  # legal file; a command refused it clearly (e.g. trim of a clamped wing)
        results.append({"id": c.id, "category": c.category, "mutation": c.mutation, "expect": c.expect, "verdict": worst,
                        "message": next((r["stderr"].strip().splitlines()[-1] for r in runs if r["stderr"].strip()), ""),
                        "runs": [{k: r[k] for k in ("argv", "rc", "seconds", "verdict")} for r in runs]})
        print(f"{c.id:28s} {worst:9s} {results[-1]['message'][:150]}", flush=True)
    return _save(out, "aircraft", results)


# ----------------------------------------------------------------------------------------------- CLI
def _cli_cases(work: Path) -> list[tuple[str, list[str], str]]:
    """(id, argv, expect) — the review's 73 commands (section 2), its 21 infeasible trims (section 3) and
    the brief's additions; paths relative to ``work``."""
    w = str(work)
    ok_log = f"{w}/existing_ok.mcap"
    cases = [
        ("trim_mach_0", ["trim", "gtm", "--mach", "0"], "error"),
        ("trim_mach_neg", ["trim", "gtm", "--mach", "-0.5"], "error"),
        ("trim_mach_0.99", ["trim", "gtm", "--mach", "0.99"], "warn"),
        ("trim_mach_1.2", ["trim", "gtm", "--mach", "1.2"], "error"),
        ("trim_mach_0.95", ["trim", "gtm", "--mach", "0.95"], "warn"),
        ("trim_mach_5", ["trim", "gtm", "--mach", "5"], "error"),
        ("trim_mach_nan", ["trim", "gtm", "--mach", "nan"], "error"),
        ("trim_mach_inf", ["trim", "gtm", "--mach", "inf"], "error"),
        ("trim_alt_-1000", ["trim", "gtm", "--altitude-m", "-1000"], "ok"),
        ("trim_alt_1e6", ["trim", "gtm", "--altitude-m", "1e6"], "error"),
        ("trim_alt_nan", ["trim", "gtm", "--altitude-m", "nan"], "error"),
        ("trim_alt_20000", ["trim", "gtm", "--altitude-m", "20000"], "error"),
        ("trim_R_10", ["trim", "gtm", "--turn-radius-m", "10"], "error"),
        ("trim_R_-10", ["trim", "gtm", "--turn-radius-m", "-10"], "error"),
        ("trim_R_0", ["trim", "gtm", "--turn-radius-m", "0"], "error"),
        ("trim_R_100", ["trim", "gtm", "--turn-radius-m", "100"], "error"),
        ("trim_R_-8000", ["trim", "gtm", "--turn-radius-m", "-8000"], "ok"),
        ("trim_R_nan", ["trim", "gtm", "--turn-radius-m", "nan"], "error"),
        ("trim_R_inf", ["trim", "gtm", "--turn-radius-m", "inf"], "ok"),
        ("trim_climb_89", ["trim", "gtm", "--climb-deg", "89"], "error"),
        ("trim_climb_-89", ["trim", "gtm", "--climb-deg", "-89"], "error"),
        ("trim_climb_nan", ["trim", "gtm", "--climb-deg", "nan"], "error"),
        ("trim_glide_and_climb", ["trim", "gtm", "--glide", "--climb-deg", "5"], "error"),
        ("trim_no_limits_R_500", ["trim", "gtm", "--no-limits", "--turn-radius-m", "500"], "error"),
        ("trim_bad_aircraft_name", ["trim", "gtmm"], "error"),
        ("aero_mach_0.99", ["aero", "gtm", "--mach", "0.99"], "warn"),
        ("aero_mach_-1", ["aero", "gtm", "--mach", "-1"], "error"),
        ("aero_mach_1", ["aero", "gtm", "--mach", "1"], "error"),
        ("aero_plot_nodir", ["aero", "gtm", "--plot", "/nonexistent/dir/cla.png"], "error"),
        ("aero_plot_txt", ["aero", "gtm", "--plot", f"{w}/cla.txt"], "error"),
        ("aero_plot_rofs", ["aero", "gtm", "--plot", "/proc/flexsim-census/cla.png"], "error"),
        ("aero_plot_dir", ["aero", "gtm", "--plot", f"{w}/outdir"], "error"),
        ("modes_m_-1", ["modes", "gtm", "--bending-modes", "-1"], "error"),
        ("modes_m_1000", ["modes", "gtm", "--bending-modes", "1000"], "error"),
        ("modes_count_-3", ["modes", "gtm", "--count", "-3", "--variant", "restrained"], "error"),
        ("modes_components_bad", ["modes", "gtm", "--components", "foo"], "error"),
        ("modes_components_dup", ["modes", "gtm", "--components", "right_wing", "right_wing", "--variant", "restrained", "--count", "3"], "ok"),
        ("modes_goland_free", ["modes", "goland_wing", "--count", "8"], "ok"),
        ("flutter_mach_0_5", ["flutter", "gtm", "--models", "QS", "--altitudes", "9144", "--mach-min", "0", "--mach-max", "5"], "error"),
        ("flutter_mach_inverted", ["flutter", "gtm", "--models", "QS", "--altitudes", "9144", "--mach-min", "0.9", "--mach-max", "0.5"], "error"),
        ("flutter_mach_nan", ["flutter", "gtm", "--models", "QS", "--altitudes", "9144", "--mach-min", "nan"], "error"),
        ("flutter_alt_1e6", ["flutter", "gtm", "--models", "QS", "--altitudes", "1e6"], "error"),
        ("flutter_alt_-1000", ["flutter", "gtm", "--models", "QS", "--altitudes", "-1000", "--json", "--workers", "1"], "ok"),
        ("flutter_models_bad", ["flutter", "gtm", "--models", "XX"], "error"),
        ("flutter_workers_0", ["flutter", "gtm", "--models", "QS", "--altitudes", "9144", "--workers", "0", "--json"], "error"),
        ("flutter_workers_-1", ["flutter", "gtm", "--models", "QS", "--altitudes", "9144", "--workers", "-1", "--json"], "error"),
        ("flutter_damping_-1", ["flutter", "gtm", "--models", "QS", "--altitudes", "9144", "--structural-damping", "-1"], "error"),
        ("flutter_damping_5", ["flutter", "gtm", "--models", "QS", "--altitudes", "9144", "--structural-damping", "5"], "error"),
        ("sim_unknown", ["simulate", "nosuch-manoeuvre"], "error"),
        ("sim_empty", ["simulate", ""], "error"),
        ("sim_duration_0", ["simulate", "climb", "--duration", "0", "--no-log"], "error"),
        ("sim_duration_-5", ["simulate", "climb", "--duration", "-5", "--no-log"], "error"),
        ("sim_duration_nan", ["simulate", "climb", "--duration", "nan", "--no-log"], "error"),
        ("sim_rtol_0", ["simulate", "climb", "--duration", "1", "--rtol", "0", "--no-log"], "error"),
        ("sim_rtol_10", ["simulate", "climb", "--duration", "1", "--rtol", "10", "--no-log"], "error"),
        ("sim_rtol_nan", ["simulate", "climb", "--duration", "1", "--rtol", "nan", "--no-log"], "error"),
        ("sim_log_nodir", ["simulate", "climb", "--duration", "1", "--log", "/nonexistent/dir/x.mcap"], "error"),
        ("sim_log_txt", ["simulate", "climb", "--duration", "1", "--log", f"{w}/out.txt"], "error"),
        ("sim_log_dir", ["simulate", "climb", "--duration", "1", "--log", f"{w}/adir.mcap"], "error"),
        ("sim_log_existing", ["simulate", "aileron-roll", "--duration", "0.5", "--log", f"{w}/existing.mcap"], "error"),
        ("sim_log_existing_txt", ["simulate", "aileron-roll", "--duration", "0.5", "--log", f"{w}/existing.txt"], "error"),
        ("sim_log_rofs", ["simulate", "climb", "--duration", "1", "--log", "/proc/flexsim-census/x.mcap"], "error"),
        ("sim_log_and_nolog", ["simulate", "climb", "--duration", "1", "--log", f"{w}/x.mcap", "--no-log"], "error"),
        ("sim_script_missing", ["simulate", f"{w}/missing_script.py"], "error"),
        ("sim_script_method", ["simulate", str(ROOT / "examples" / "climb.py"), "--method", "DOP853"], "error"),
        ("view_missing", ["view", f"{w}/nonexistent.mcap"], "error"),
        ("view_empty", ["view", f"{w}/empty.mcap", "--save", f"{w}/e.rrd"], "error"),
        ("view_toml", ["view", str(ROOT / "flexsim" / "aircraft" / "data" / "gtm.toml"), "--save", f"{w}/t.rrd"], "error"),
        ("view_save_nodir", ["view", ok_log, "--save", "/nonexistent/dir/x.rrd"], "error"),
        ("view_save_txt", ["view", ok_log, "--save", f"{w}/x.txt"], "error"),
        ("view_save_rofs", ["view", ok_log, "--save", "/proc/flexsim-census/x.rrd"], "error"),
        ("view_save_dir", ["view", ok_log, "--save", f"{w}/outdir"], "error"),
        ("sweep_out_rofs", ["sweep", "--turn", "--altitudes", "9144", "--models", "QS", "--workers", "1", "--out", "/proc/flexsim-census/study"], "error"),
        ("sweep_out_file", ["sweep", "--turn", "--altitudes", "9144", "--models", "QS", "--workers", "1", "--out", f"{w}/existing_file"], "error"),
        ("sweep_scheduler_nothing", ["sweep", "--turn", "--altitudes", "9144", "--models", "QS", "--scheduler", "tcp://127.0.0.1:9", "--out", f"{w}/s9"], "error"),
        ("sweep_models_bad", ["sweep", "--climb", "--altitudes", "9144", "--models", "QS,ZZ"], "error"),
        ("sweep_workers_0", ["sweep", "--climb", "--altitudes", "9144", "--models", "QS", "--workers", "0"], "error"),
        ("sweep_workers_-1", ["sweep", "--climb", "--altitudes", "9144", "--models", "QS", "--workers", "-1"], "error"),
        ("sweep_alt_nan", ["sweep", "--climb", "--altitudes", "nan", "--models", "QS"], "error"),
        ("sweep_damping_1", ["sweep", "--climb", "--altitudes", "9144", "--models", "QS", "--structural-damping", "1"], "error"),
    ]
    trims = [  # review section 3: infeasible trims (feasible ones expected ok)
        ("slow_M0.2_9144", ["trim", "gtm", "--mach", "0.2", "--altitude-m", "9144"], "error"),
        ("slow_M0.1_0", ["trim", "gtm", "--mach", "0.1", "--altitude-m", "0"], "error"),
        ("slow_M0.02_0", ["trim", "gtm", "--mach", "0.02", "--altitude-m", "0"], "error"),
        ("slow_M0.3_9144_nolimits", ["trim", "gtm", "--mach", "0.3", "--altitude-m", "9144", "--no-limits", "--json"], "ok"),
        ("turn_R1000", ["trim", "gtm", "--turn-radius-m", "1000"], "error"),
        ("turn_R2000", ["trim", "gtm", "--turn-radius-m", "2000"], "error"),
        ("turn_R3000", ["trim", "gtm", "--turn-radius-m", "3000"], "error"),
        ("turn_R1000_nolimits", ["trim", "gtm", "--turn-radius-m", "1000", "--no-limits", "--json"], "error"),
        ("turn_R300_M0.3_0", ["trim", "gtm", "--turn-radius-m", "300", "--mach", "0.3", "--altitude-m", "0"], "error"),
        ("climb_10", ["trim", "gtm", "--climb-deg", "10"], "ok"),
        ("climb_15", ["trim", "gtm", "--climb-deg", "15"], "ok"),
        ("climb_25", ["trim", "gtm", "--climb-deg", "25"], "error"),
        ("climb_30", ["trim", "gtm", "--climb-deg", "30"], "error"),
        ("climb_30_nolimits", ["trim", "gtm", "--climb-deg", "30", "--no-limits", "--json"], "ok"),
        ("descent_-30", ["trim", "gtm", "--climb-deg", "-30"], "error"),
        ("glide_M0.3", ["trim", "gtm", "--glide", "--mach", "0.3", "--altitude-m", "3000"], "error"),
        ("glide_M0.95", ["trim", "gtm", "--glide", "--mach", "0.95"], "warn"),
        ("climbing_turn_R2000_15", ["trim", "gtm", "--turn-radius-m", "2000", "--climb-deg", "15"], "error"),
        ("goland_trim", ["trim", "goland_wing"], "error"),
        ("strips1_gtm_nolimits", ["trim", f"{w}/s1.toml", "--no-limits"], "error"),
        ("strips1_gtm", ["trim", f"{w}/s1.toml"], "error"),
    ]
    return [(i, a, e, "cli") for i, a, e in cases] + [(i, a, e, "trim") for i, a, e in trims]


def part_cli(out: Path, quick: bool) -> dict:
    work = Path(tempfile.mkdtemp(prefix="census-cli-"))
    (work / "outdir").mkdir()
    (work / "adir.mcap").mkdir()
    (work / "empty.mcap").write_bytes(b"")
    (work / "existing.mcap").write_text("my notes, not a log\n")
    (work / "existing.txt").write_text("my notes\n")
    (work / "existing_file").write_text("x\n")
    gtm = (ROOT / "flexsim" / "aircraft" / "data" / "gtm.toml").read_text()
    (work / "s1.toml").write_text(re.sub(r"(?m)^strips = [0-9]+", "strips = 1", gtm))
    run_cli(["simulate", "aileron-roll", "--duration", "0.3", "--log", str(work / "existing_ok.mcap")])
    results = []
    for cid, argv, expect, group in _cli_cases(work):
        before = (work / "existing.mcap").read_bytes()
        r = run_cli(argv, limit_s=420.0)
        v = verdict(r, expect)
        if cid == "sim_log_existing" and (work / "existing.mcap").read_bytes() != before:
            v = "SILENT"  # the user's file was overwritten
        results.append({"id": cid, "group": group, "argv": argv, "expect": expect, "verdict": v, "rc": r["rc"],
                        "seconds": r["seconds"], "message": (r["stderr"].strip().splitlines() or [""])[-1][:400],
                        "traceback": r["traceback"][-400:]})
        print(f"{cid:26s} {v:9s} rc={r['rc']} {r['seconds']:6.1f}s {results[-1]['message'][:140]}", flush=True)
    # Ctrl-C during simulate (child process, SIGINT to its process group once the log exists)
    log = work / "ctrlc.mcap"
    p = subprocess.Popen([*FLEXSIM, "simulate", "gust-encounter", "--duration", "60", "--log", str(log)], cwd=ROOT,
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    t_end = time.monotonic() + 180
    while time.monotonic() < t_end and not (log.exists() and log.stat().st_size > 20000):
        time.sleep(0.2)
    time.sleep(2.0)
    t0 = time.monotonic()
    os.killpg(p.pid, signal.SIGINT)
    _, err = p.communicate(timeout=60)
    from flexsim.io.flight_log import read_flight_log

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        lg = read_flight_log(log)
    v = "TRACEBACK" if "Traceback" in err else ("CLEAR" if p.returncode == 130 else "OBSCURE")
    results.append({"id": "sim_ctrl_c", "group": "cli", "argv": ["simulate", "gust-encounter", "--duration", "60", "<SIGINT>"],
                    "expect": "error", "verdict": v, "rc": p.returncode, "seconds": round(time.monotonic() - t0, 2),
                    "message": err.strip().splitlines()[-1] if err.strip() else "",
                    "log": {"complete": lg.complete, "samples": len(lg.t), "last_event": lg.events[-1].text if lg.events else ""}})
    print(f"sim_ctrl_c                 {v:9s} rc={p.returncode} log complete={lg.complete} samples={len(lg.t)}", flush=True)
    return _save(out, "cli", results)


# ----------------------------------------------------------------------------------------------- logs
def part_logs(out: Path, quick: bool) -> dict:
    import numpy as np

    from flexsim.io.flight_log import FlightLogError, read_flight_log

    work = Path(tempfile.mkdtemp(prefix="census-logs-"))
    ref_path = work / "ref.mcap"
    r = run_cli(["simulate", "gust-encounter", "--duration", "3", "--log", str(ref_path)])
    assert r["rc"] == 0, r
    ref = read_flight_log(ref_path)
    data = ref_path.read_bytes()
    results = []
    for k, d in enumerate(log_damages(40)):
        bad = d.apply(data)
        path = work / f"bad_{k}.mcap"
        path.write_bytes(bad)
        row = {"id": k, "kind": d.kind, "fraction": round(d.fraction, 5), "offset": int(d.fraction * len(data)), "identical": bad == data}
        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                lg = read_flight_log(path)
            idx = np.searchsorted(ref.t, lg.t)
            same_t = bool(len(lg.t) == 0 or np.all(ref.t[np.minimum(idx, len(ref.t) - 1)] == lg.t))
            wrong = 0 if not len(lg.t) else int(np.sum(np.any(lg.state != ref.state[idx], axis=1) | np.any(lg.signals != ref.signals[idx], axis=1)))
            flagged = (not lg.complete) and bool(caught)
            row.update(outcome="recovered", complete=lg.complete, samples=len(lg.t), wrong_samples=wrong if same_t else -1,
                       warning=str(caught[0].message)[len(str(path)) + 2:][:300] if caught else "")
            if bad == data:
                row["verdict"] = "INTACT (no change)"
            elif flagged and wrong == 0 and same_t:
                row["verdict"] = "FLAGGED"
            elif not flagged and wrong == 0 and same_t and len(lg.t) == len(ref.t):
                row["verdict"] = "UNFLAGGED, values intact"
            else:
                row["verdict"] = "SILENT (altered values)" if not flagged else "FLAGGED but altered values"
        except FlightLogError as exc:
            row.update(outcome="error", verdict="ERROR (clear)", message=str(exc)[len(str(path)) + 2:][:300])
        except Exception as exc:  # noqa: BLE001
            row.update(outcome="traceback", verdict="TRACEBACK", message=f"{type(exc).__name__}: {exc}"[:300])
        results.append(row)
        print(f"{k:2d} {d.kind:12s} {d.fraction:.4f} {row['verdict']:24s} {row.get('warning', row.get('message', ''))[:110]}", flush=True)
    return _save(out, "logs", results)


# ----------------------------------------------------------------------------------------------- sweeps
def _sweep_run(out_dir: Path, action: str, resume: bool = False, scheduler: str | None = None, wait_points: int = 3,
               limit_s: float = 900.0) -> dict:
    """One ``flexsim sweep --climb --altitudes 0 9144 --models QS`` (14 points, 2 chains) interrupted by ``action``
    (``kill_worker``, ``ctrl_c`` or ``none``) once ``wait_points`` points have finished; returns what was kept."""
    argv = [*FLEXSIM, "sweep", "--climb", "--altitudes", "0", "9144", "--models", "QS", "--workers", "2", "--out", str(out_dir)]
    if resume:
        argv.append("--resume")
    if scheduler:
        argv += ["--scheduler", scheduler]
    p = subprocess.Popen(argv, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    lines: list[str] = []
    import threading

    def reader():
        for line in p.stderr:
            lines.append(line.rstrip())

    th = threading.Thread(target=reader, daemon=True)
    th.start()
    t0 = time.monotonic()
    acted_at = None
    finished_before = None
    killed_pid = None
    while p.poll() is None and time.monotonic() - t0 < limit_s:
        done = sum(1 for x in lines if re.match(r"\[\d+/\d+\]", x))
        if acted_at is None and action != "none" and done >= wait_points:
            finished_before = done
            if action == "ctrl_c":
                os.killpg(p.pid, signal.SIGINT)
            elif action == "kill_worker":
                killed_pid = _kill_a_worker(p.pid, scheduler)
            acted_at = time.monotonic()
        if action == "kill_worker" and acted_at is not None and done >= finished_before + 2:
            os.killpg(p.pid, signal.SIGINT)  # continuation shown; stop here to keep the census short
            action = "kill_worker+stopped"
        time.sleep(0.2)
    hang = p.poll() is None
    if hang:
        os.killpg(p.pid, signal.SIGKILL)
    p.wait()
    th.join(timeout=5)
    stdout = p.stdout.read()
    record = out_dir / "flutter_climb.jsonl"
    kept = len(record.read_text().splitlines()) if record.exists() else 0
    lost_note = next((x for x in lines if "worker process died" in x or "lost" in x), "")
    return {"argv": argv[3:], "action": action, "rc": p.returncode, "hang": hang, "seconds": round(time.monotonic() - t0, 1),
            "stop_seconds_after_sigint": round(time.monotonic() - acted_at, 1) if acted_at and "ctrl_c" in action else None,
            "finished_before_action": finished_before, "progress_lines": sum(1 for x in lines if re.match(r"\[\d+/\d+\]", x)),
            "kept_in_jsonl": kept, "killed_pid": killed_pid, "lost_report": lost_note[:300],
            "traceback": any("Traceback" in x for x in lines), "last_stderr": lines[-1][:300] if lines else "",
            "stdout_tail": stdout[-300:]}


def _kill_a_worker(parent: int, scheduler: str | None) -> int | None:
    """SIGKILL one worker process: a child of the sweep (process pool) or a Dask worker of the cluster."""
    if scheduler:
        out = subprocess.run(["pgrep", "-f", "distributed.cli.dask_worker|dask worker|dask-worker|spawn_main"], capture_output=True, text=True).stdout.split()
        pids = [int(x) for x in out if int(x) != os.getpid()]
        workers = [pid for pid in pids if _is_descendant(pid, _CLUSTER_PID[0])] if _CLUSTER_PID else pids
    else:
        workers = [int(x) for x in subprocess.run(["pgrep", "-P", str(parent)], capture_output=True, text=True).stdout.split()]
    workers = [w for w in workers if _is_python(w)]
    if not workers:
        return None
    os.kill(workers[-1], signal.SIGKILL)
    return workers[-1]


_CLUSTER_PID: list[int] = []


def _is_python(pid: int) -> bool:
    try:
        return "python" in Path(f"/proc/{pid}/cmdline").read_bytes().decode(errors="replace")
    except OSError:
        return False


def _is_descendant(pid: int, ancestor: int) -> bool:
    while pid > 1:
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            return False
        pid = int(stat.rsplit(")", 1)[1].split()[1])
        if pid == ancestor:
            return True
    return False


def part_sweeps(out: Path, quick: bool, runs_wanted: list[int] | None = None) -> dict:
    """Eight interrupted sweeps (``runs_wanted`` selects some, to keep each invocation short; results are
    merged into ``sweeps.json`` by run number)."""
    work = Path(tempfile.mkdtemp(prefix="census-sweeps-"))
    previous = {r["run"]: r for r in json.loads((out / "sweeps.json").read_text())} if (out / "sweeps.json").exists() else {}
    runs = []
    plan = [("pool", "kill_worker"), ("pool", "kill_worker"), ("pool", "kill_worker"), ("pool", "ctrl_c"), ("pool", "ctrl_c"),
            ("pool", "ctrl_c"), ("dask", "kill_worker"), ("dask", "ctrl_c")]
    cluster_proc = None
    scheduler = None
    for k, (backend, action) in enumerate(plan):
        if runs_wanted is not None and k not in runs_wanted:
            continue
        if backend == "dask" and scheduler is None:
            cluster_proc, scheduler = _start_cluster(work)
        d = work / f"run{k}"
        r = _sweep_run(d, action, scheduler=scheduler if backend == "dask" else None)
        r.update(run=k, backend=backend)
        # resume to completion: every point ends up computed exactly once more only if it was lost
        res = _sweep_run(d, "none", resume=True, scheduler=scheduler if backend == "dask" else None)
        total = len((d / "flutter_climb.jsonl").read_text().splitlines()) if (d / "flutter_climb.jsonl").exists() else 0
        r.update(resume_rc=res["rc"], resume_seconds=res["seconds"], total_after_resume=total,
                 finished_points_lost=(r["finished_before_action"] or 0) - min(r["kept_in_jsonl"], r["finished_before_action"] or 0))
        runs.append(r)
        print(json.dumps({k2: r[k2] for k2 in ("run", "backend", "action", "rc", "finished_before_action", "kept_in_jsonl",
                                                "stop_seconds_after_sigint", "lost_report", "traceback", "total_after_resume",
                                                "finished_points_lost")}), flush=True)
    if cluster_proc is not None:
        os.killpg(cluster_proc.pid, signal.SIGTERM)
        cluster_proc.wait(timeout=30)
    previous.update({r["run"]: r for r in runs})
    return _save(out, "sweeps", [previous[k] for k in sorted(previous)])


def _start_cluster(work: Path):
    """A Dask LocalCluster on loopback (2 worker processes with nannies) in a child process."""
    script = ("import time, sys\nfrom dask.distributed import LocalCluster\n"
              "c = LocalCluster(n_workers=2, threads_per_worker=1, host='127.0.0.1', dashboard_address=None)\n"
              "print(c.scheduler_address, flush=True)\nwhile True: time.sleep(1)\n")
    p = subprocess.Popen([sys.executable, "-c", script], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                         start_new_session=True)
    address = p.stdout.readline().strip()
    _CLUSTER_PID[:] = [p.pid]
    return p, address


# ----------------------------------------------------------------------------------------------- table
def _save(out: Path, part: str, results: list) -> dict:
    out.mkdir(parents=True, exist_ok=True)
    (out / f"{part}.json").write_text(json.dumps(results, indent=1, default=str))
    return {"part": part, "results": results}


def summarise(out: Path) -> str:
    lines = ["| part | cases | clear errors | obscure | tracebacks | silent wrong | hangs | warned | ok (legal) | other |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for part, label in (("aircraft", "aircraft files (info / modes / aero / trim)"), ("cli", "CLI bad input (+ Ctrl-C simulate)")):
        f = out / f"{part}.json"
        if not f.exists():
            continue
        rows = json.loads(f.read_text())
        groups = {"cli": [r for r in rows if r.get("group", "cli") == "cli"], "trim": [r for r in rows if r.get("group") == "trim"]} \
            if part == "cli" else {part: rows}
        for g, rs in groups.items():
            c = {v: sum(r["verdict"] == v for r in rs) for v in ("CLEAR", "OBSCURE", "TRACEBACK", "SILENT", "HANG", "WARNED", "OK")}
            name = {"trim": "infeasible trims"}.get(g, label)
            lines.append(f"| {name} | {len(rs)} | {c['CLEAR']} | {c['OBSCURE']} | {c['TRACEBACK']} | {c['SILENT']} | {c['HANG']} | "
                         f"{c['WARNED']} | {c['OK']} | {len(rs) - sum(c.values())} |")
    f = out / "logs.json"
    if f.exists():
        rows = json.loads(f.read_text())
        damaged = [r for r in rows if not r.get("identical")]
        flagged = sum(r["verdict"] in ("FLAGGED", "ERROR (clear)") for r in damaged)
        silent = sum(r["verdict"].startswith("SILENT") or "altered" in r["verdict"] for r in damaged)
        unflagged_intact = sum(r["verdict"] == "UNFLAGGED, values intact" for r in damaged)
        lines.append(f"\ndamaged logs: {len(damaged)} (+{len(rows) - len(damaged)} no-op damages); flagged {flagged} "
                     f"(errors {sum(r['verdict'] == 'ERROR (clear)' for r in damaged)}, recovered with a warning "
                     f"{sum(r['verdict'] == 'FLAGGED' for r in damaged)}); read as complete with altered values {silent}; "
                     f"unflagged with values intact {unflagged_intact}; tracebacks {sum(r['verdict'] == 'TRACEBACK' for r in rows)}")
    f = out / "sweeps.json"
    if f.exists():
        rows = json.loads(f.read_text())
        lines.append(f"sweep interruptions: {len(rows)}; finished points lost {sum(r['finished_points_lost'] for r in rows)}; "
                     f"tracebacks {sum(bool(r['traceback']) for r in rows)}; hangs {sum(bool(r['hang']) for r in rows)}; "
                     f"Ctrl-C stop times {[r['stop_seconds_after_sigint'] for r in rows if r['stop_seconds_after_sigint'] is not None]} s; "
                     f"worker deaths reported {sum(bool(r['lost_report']) for r in rows if 'kill' in r['action'])}/"
                     f"{sum('kill' in r['action'] for r in rows)}; all points present after --resume "
                     f"{sum(r['total_after_resume'] == 14 for r in rows)}/{len(rows)}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("part", choices=["aircraft", "cli", "logs", "sweeps", "all", "table"])
    parser.add_argument("--out", default="logs/reliability_census", help="folder for the JSON results [logs/reliability_census]")
    parser.add_argument("--quick", action="store_true", help="build the 50 MB aircraft files at 3 MB")
    parser.add_argument("--runs", type=int, nargs="+", metavar="K", help="sweeps: run only these of the 8 interruptions (0-7)")
    args = parser.parse_args(argv)
    out = Path(args.out)
    parts = {"aircraft": part_aircraft, "cli": part_cli, "logs": part_logs,
             "sweeps": lambda o, q: part_sweeps(o, q, args.runs)}
    for name in (parts if args.part == "all" else [] if args.part == "table" else [args.part]):
        parts[name](out, args.quick)
    print(summarise(out))
    return 0


if __name__ == "__main__":
    sys.exit(main())
