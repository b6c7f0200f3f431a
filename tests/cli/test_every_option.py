"""Every option of every ``flexsim`` command is honoured or refused.

The options are read from the argparse parsers (:func:`flexsim.cli.main._parser`), so a new option without a case
here fails :func:`test_every_option_has_a_case`. Each case runs a small command (the 0.45 kg glider of
``tests/cli/small_aircraft.py``, one altitude, one model) without and with the option and checks one of:

* ``CHANGES``: at least one of the two commands succeeds, and their exit statuses or standard outputs differ
  (wall-clock times and paths removed): a trim of a subset that cannot fly is an answer to the question asked;
* ``writes(name)``: the file the option names is written;
* ``refused(text)``: exit status 2 (or argparse's usage error) with ``text`` on stderr: the option is read and a value
  or combination it cannot honour is refused with a message.
"""

from __future__ import annotations

import argparse
import re
from dataclasses import dataclass

import pytest

from flexsim.cli.main import _parser, main
from tests.cli.small_aircraft import rc_glider_toml

CHANGES = "changes"


@dataclass(frozen=True)
class Expect:
    kind: str  # "changes", "writes", "refused"
    text: str = ""


def writes(name: str) -> Expect:
    return Expect("writes", name)


def refused(text: str) -> Expect:
    return Expect("refused", text)


G = "{glider}"
FLUTTER = ["flutter", G, "--altitudes", "0", "--models", "US", "--workers", "1"]
TUNNEL = ["flutter", G, "--wind-tunnel", "--models", "US", "--speed-range-m-s", "5", "60"]
SWEEP = ["sweep", "--turn", G, "--altitudes", "0", "--models", "US", "--radii-m", "300", "--workers", "1", "--out", "{new}"]
LINEARIZE = ["linearize", G, "--out", "{tmp}/lin.npz"]
SIMULATE = ["simulate", G, "--no-log", "--duration", "0.2"]
VIEW = ["view", "{log}", "--save", "{tmp}/view.rrd"]

#: (command, option or positional dest) -> (command line without the option, the option's words, expectation).
CASES: dict[tuple[str, str], tuple[list[str], list[str], Expect]] = {
    ("info", "aircraft"): (["info", G], ["info", "goland_wing"], Expect(CHANGES)),
    ("info", "--json"): (["info", G], ["--json"], Expect(CHANGES)),
    ("info", "--components"): (["info", G], ["--components", "right_wing"], Expect(CHANGES)),
    ("modes", "aircraft"): (["modes", G], ["modes", "goland_wing"], Expect(CHANGES)),
    ("modes", "--json"): (["modes", G], ["--json"], Expect(CHANGES)),
    ("modes", "--components"): (["modes", G], ["--components", "right_wing"], Expect(CHANGES)),
    ("modes", "--variant"): (["modes", G], ["--variant", "restrained"], Expect(CHANGES)),
    ("modes", "--bending-modes"): (["modes", G], ["--bending-modes", "3"], Expect(CHANGES)),
    ("modes", "--torsion-modes"): (["modes", G], ["--torsion-modes", "2"], Expect(CHANGES)),
    ("modes", "--count"): (["modes", G], ["--count", "3"], Expect(CHANGES)),
    ("aero", "aircraft"): (["aero", G], ["aero", "goland_wing"], Expect(CHANGES)),
    ("aero", "--json"): (["aero", G], ["--json"], Expect(CHANGES)),
    ("aero", "--components"): (["aero", G], ["--components", "right_wing"], Expect(CHANGES)),
    ("aero", "--mach"): (["aero", G], ["--mach", "0.5"], Expect(CHANGES)),
    ("aero", "--plot"): (["aero", G], ["--plot", "{tmp}/cla.png"], writes("cla.png")),
    ("trim", "aircraft"): (["trim", G], ["trim", "gtm"], Expect(CHANGES)),
    ("trim", "--json"): (["trim", G], ["--json"], Expect(CHANGES)),
    ("trim", "--components"): (["trim", G], ["--components", "right_wing", "left_wing"], Expect(CHANGES)),
    ("trim", "--altitude-m"): (["trim", G], ["--altitude-m", "2000"], Expect(CHANGES)),
    ("trim", "--mach"): (["trim", G], ["--mach", "0.035"], Expect(CHANGES)),
    ("trim", "--speed-m-s"): (["trim", G], ["--speed-m-s", "12"], Expect(CHANGES)),
    ("trim", "--turn-radius-m"): (["trim", G], ["--turn-radius-m", "200"], Expect(CHANGES)),
    ("trim", "--climb-deg"): (["trim", G], ["--climb-deg", "2"], Expect(CHANGES)),
    ("trim", "--glide"): (["trim", G], ["--glide"], Expect(CHANGES)),
    ("trim", "--coordinated"): (["trim", G, "--turn-radius-m", "200"], ["--coordinated"], Expect(CHANGES)),
    ("trim", "--no-limits"): (["trim", G, "--speed-m-s", "4"], ["--no-limits"], Expect(CHANGES)),
    ("trim", "--formulation"): (["trim", G], ["--formulation", "paper"], Expect(CHANGES)),
    ("trim", "--roots"): (["trim", G], ["--roots"], Expect(CHANGES)),
    ("trim", "--load-factor"): (["trim", G], ["--load-factor", "1.5"], Expect(CHANGES)),
    ("trim", "--nonlinear-beams"): (["trim", "phc_hale"], ["--nonlinear-beams", "4"], Expect(CHANGES)),
    ("flutter", "aircraft"): (FLUTTER, ["flutter", "maewing1", "--altitudes", "0"], Expect(CHANGES)),
    ("flutter", "--json"): (FLUTTER, ["--json"], Expect(CHANGES)),
    ("flutter", "--components"): (FLUTTER, ["--components", "right_wing"], refused("--components: apply to --wind-tunnel")),
    ("flutter", "--altitudes"): (FLUTTER, ["--altitudes", "2000"], Expect(CHANGES)),
    ("flutter", "--models"): (FLUTTER, ["--models", "QS"], Expect(CHANGES)),
    ("flutter", "--mach-min"): (FLUTTER, ["--mach-min", "0.05"], Expect(CHANGES)),
    ("flutter", "--mach-max"): (FLUTTER, ["--mach-max", "0.2"], Expect(CHANGES)),
    ("flutter", "--turn-radius-m"): (FLUTTER, ["--turn-radius-m", "200"], Expect(CHANGES)),
    ("flutter", "--climb-deg"): (FLUTTER, ["--climb-deg", "3"], Expect(CHANGES)),
    ("flutter", "--glide"): (FLUTTER, ["--glide"], Expect(CHANGES)),
    ("flutter", "--coordinated"): (FLUTTER, ["--coordinated"], refused("--coordinated: applies to turns only")),
    ("flutter", "--vg"): (FLUTTER, ["--vg", "{tmp}/vg.png", "--vg-points", "4"], writes("vg.png")),
    ("flutter", "--vg-points"): (FLUTTER, ["--vg-points", "9"], refused("--vg-points 9: applies to --vg")),
    ("flutter", "--workers"): (FLUTTER, ["--workers", "0"], refused("--workers = 0: must be an integer >= 1")),
    ("flutter", "--wind-tunnel"): (FLUTTER, ["--wind-tunnel"], refused("--wind-tunnel: --workers describe a flight")),
    ("flutter", "--speed-range-m-s"): (TUNNEL, ["--speed-range-m-s", "5", "150"], Expect(CHANGES)),
    ("flutter", "--speed-step-m-s"): (TUNNEL + ["--json"], ["--speed-step-m-s", "2.5"], Expect(CHANGES)),
    ("flutter", "--mach-step"): (FLUTTER, ["--mach-step", "0"], refused("--mach-step")),
    ("flutter", "--structural-damping"): (FLUTTER, ["--structural-damping", "0.09", "--mach-max", "0.3"], Expect(CHANGES)),
    ("flutter", "--formulation"): (FLUTTER, ["--formulation", "paper", "--mach-max", "0.3"], Expect(CHANGES)),
    ("flutter", "--linear-density-altitude-m"): (FLUTTER, ["--linear-density-altitude-m", "5000", "--mach-max", "0.3"],
                                                 Expect(CHANGES)),
    ("flutter", "--paper-replication"): (FLUTTER, ["--paper-replication"],
                                         refused("--paper-replication and AIRCRAFT: the paper-replication settings fix")),
    ("flutter", "--mode"): (FLUTTER, ["--mode", "{tmp}/mode.txt"], refused("--mode")),
    ("flutter", "--load-factor"): (FLUTTER, ["--load-factor", "1.2"],
                                   refused("--load-factor 1.2: the pull-up's flutter is searched with the geometrically")),
    ("flutter", "--nonlinear-beams"): (FLUTTER, ["--nonlinear-beams"], refused("--models US: with --nonlinear-beams")),
    ("flutter", "--free-aircraft"): (FLUTTER, ["--free-aircraft"], refused("--free-aircraft: applies to --nonlinear-beams")),
    ("sweep", "aircraft"): (SWEEP, ["sweep", "--turn", "maewing1", "--altitudes", "0", "--models", "US", "--radii-m", "300",
                                    "--workers", "1", "--out", "{new}"], Expect(CHANGES)),
    ("sweep", "--json"): (SWEEP, ["--json"], Expect(CHANGES)),
    ("sweep", "--components"): (SWEEP, ["--components", "right_wing"], refused("--components: a sweep flies the whole")),
    ("sweep", "--turn"): (SWEEP, ["--climb"], refused("not allowed with argument")),
    ("sweep", "--climb"): (["sweep", "--climb", G, "--altitudes", "0", "--models", "US", "--workers", "1", "--out", "{new}"],
                           ["--angles-deg", "2"], Expect(CHANGES)),
    ("sweep", "--altitudes"): (SWEEP, ["--altitudes", "2000"], Expect(CHANGES)),
    ("sweep", "--mach-min"): (SWEEP, ["--mach-min", "0.05"], Expect(CHANGES)),
    ("sweep", "--mach-max"): (SWEEP, ["--mach-max", "0.2"], Expect(CHANGES)),
    ("sweep", "--models"): (SWEEP, ["--models", "QS"], Expect(CHANGES)),
    ("sweep", "--coordinated"): (SWEEP, ["--coordinated"], Expect(CHANGES)),
    ("sweep", "--radii-m"): (SWEEP, ["--radii-m", "500"], Expect(CHANGES)),
    ("sweep", "--angles-deg"): (SWEEP, ["--angles-deg", "2"], refused("--angles-deg: applies to --climb sweeps")),
    ("sweep", "--scheduler"): (SWEEP, ["--scheduler", "tcp://127.0.0.1:1"], refused("--scheduler, --workers")),
    ("sweep", "--workers"): (SWEEP, ["--workers", "0"], refused("--workers = 0: must be an integer >= 1")),
    ("sweep", "--chain-length"): (SWEEP, ["--chain-length", "0"], refused("--chain-length = 0: must be an integer >= 1")),
    ("sweep", "--structural-damping"): (SWEEP, ["--structural-damping", "0.09", "--mach-max", "0.3"], Expect(CHANGES)),
    ("sweep", "--out"): (SWEEP, ["--out", "{tmp}/named"], writes("named/flutter_turn.json")),
    ("sweep", "--pull-up"): (["sweep", G, "--altitudes", "0", "--models", "US", "--load-factors", "1.5", "--out", "{new}"],
                             ["--pull-up"], Expect(CHANGES)),
    ("sweep", "--load-factors"): (SWEEP, ["--load-factors", "1.5"], refused("--load-factors: applies to --pull-up")),
    ("sweep", "--nonlinear-beams"): (SWEEP, ["--nonlinear-beams"], refused("--nonlinear-beams: applies to --pull-up")),
    ("sweep", "--resume"): (SWEEP, ["--resume", "--out", "{tmp}/done"], writes("done/flutter_turn.jsonl")),
    ("sweep", "--formulation"): (SWEEP, ["--formulation", "paper", "--mach-max", "0.3"], Expect(CHANGES)),
    ("sweep", "--linear-density-altitude-m"): (SWEEP, ["--linear-density-altitude-m", "5000", "--mach-max", "0.3"],
                                               Expect(CHANGES)),
    ("sweep", "--paper-replication"): (SWEEP, ["--paper-replication", "--formulation", "paper"],
                                       refused("--paper-replication and AIRCRAFT, --formulation")),
    ("linearize", "aircraft"): (LINEARIZE, ["linearize", "gtm", "--out", "{tmp}/gtm.npz"], Expect(CHANGES)),
    ("linearize", "--json"): (LINEARIZE, ["--json"], Expect(CHANGES)),
    ("linearize", "--components"): (LINEARIZE, ["--components", "right_wing", "left_wing"], Expect(CHANGES)),
    ("linearize", "--altitude-m"): (LINEARIZE, ["--altitude-m", "2000"], Expect(CHANGES)),
    ("linearize", "--mach"): (LINEARIZE, ["--mach", "0.035"], Expect(CHANGES)),
    ("linearize", "--speed-m-s"): (LINEARIZE, ["--speed-m-s", "12"], Expect(CHANGES)),
    ("linearize", "--turn-radius-m"): (LINEARIZE, ["--turn-radius-m", "200"], Expect(CHANGES)),
    ("linearize", "--climb-deg"): (LINEARIZE, ["--climb-deg", "2"], Expect(CHANGES)),
    ("linearize", "--coordinated"): (LINEARIZE, ["--coordinated"], refused("--coordinated: applies to turns only")),
    ("linearize", "--aero"): (LINEARIZE, ["--aero", "unsteady", "--n-inflow", "2"], Expect(CHANGES)),
    ("linearize", "--n-inflow"): (LINEARIZE, ["--n-inflow", "2"], refused("--n-inflow 2: applies to --aero unsteady")),
    ("linearize", "--formulation"): (LINEARIZE, ["--formulation", "paper"], Expect(CHANGES)),
    ("linearize", "--state-outputs"): (LINEARIZE, ["--state-outputs"], Expect(CHANGES)),
    ("linearize", "--no-limits"): (LINEARIZE + ["--speed-m-s", "4"], ["--no-limits"], Expect(CHANGES)),
    ("linearize", "--out"): (LINEARIZE, ["--out", "{tmp}/other.npz"], writes("other.npz")),
    ("simulate", "manoeuvre"): (SIMULATE, ["simulate", "aileron-roll", "--aircraft", G, "--no-log", "--duration", "0.2"],
                                Expect(CHANGES)),
    ("simulate", "--aircraft"): (["simulate", "elevator-doublet", "--no-log", "--duration", "0.2", "--aero", "quasi-steady"],
                                 ["--aircraft", G], Expect(CHANGES)),
    ("simulate", "--altitude-m"): (SIMULATE, ["--altitude-m", "2000"], Expect(CHANGES)),
    ("simulate", "--mach"): (SIMULATE, ["--mach", "0.035"], Expect(CHANGES)),
    ("simulate", "--speed-m-s"): (SIMULATE, ["--speed-m-s", "12"], Expect(CHANGES)),
    ("simulate", "--duration"): (SIMULATE, ["--duration", "0.1"], Expect(CHANGES)),
    ("simulate", "--log"): (SIMULATE[:2] + ["--duration", "0.2"], ["--log", "{tmp}/run.mcap"], writes("run.mcap")),
    ("simulate", "--no-log"): (SIMULATE[:2] + ["--duration", "0.2", "--log", "{tmp}/x.mcap"], ["--no-log"],
                               refused("--log and --no-log: give at most one")),
    ("simulate", "--aero"): (SIMULATE, ["--aero", "quasi-steady"], Expect(CHANGES)),
    ("simulate", "--formulation"): (SIMULATE, ["--formulation", "paper"], Expect(CHANGES)),
    ("simulate", "--method"): (SIMULATE, ["--method", "DOP853", "--aero", "quasi-steady"], Expect(CHANGES)),
    ("simulate", "--rtol"): (SIMULATE, ["--rtol", "1e-3"], refused("--rtol 0.001: applies to the adaptive methods")),
    ("simulate", "--nonlinear-beams"): (["simulate", "gust-encounter", "--aircraft", "phc_hale", "--no-log", "--duration",
                                         "0.2", "--aero", "quasi-steady"], ["--nonlinear-beams", "2"], Expect(CHANGES)),
    ("view", "log"): (VIEW, ["view", "{tmp}/missing.mcap", "--save", "{tmp}/m.rrd"], refused("no such flight log file")),
    ("view", "--save"): (["view", "{log}", "--connect", "rerun+http://127.0.0.1:1/proxy"], ["--save", "{tmp}/v.rrd", "--port",
                         "9000"], refused("--port: apply to the viewer that flexsim view starts")),
    ("view", "--connect"): (VIEW, ["--connect", "http://example"], refused("--connect = 'http://example': must be")),
    ("view", "--port"): (VIEW, ["--port", "9001"], refused("--port: apply to the viewer that flexsim view starts")),
    ("view", "--viewer"): (VIEW, ["--viewer", "sh"], refused("--viewer: apply to the viewer that flexsim view starts")),
    ("validate", "cases"): (["validate", "coordinated-turn-load-factor"], ["validate", "phugoid-lanchester"],
                            Expect(CHANGES)),
    ("validate", "--json"): (["validate", "coordinated-turn-load-factor"], ["--json"], Expect(CHANGES)),
}


def _options() -> set[tuple[str, str]]:
    parser = _parser()
    sub = next(a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return {(name, (a.option_strings or [a.dest])[0]) for name, p in sub.choices.items() for a in p._actions
            if not isinstance(a, argparse._HelpAction)}


def test_every_option_has_a_case():
    options = _options()
    assert options - set(CASES) == set(), "an option of the CLI without a case in CASES"
    assert set(CASES) - options == set(), "a case for an option the CLI does not have"


_TIMES = re.compile(r"[\d.]+ s wall|\([\d.]+x real time\)|in [\d.]+ s \([\d.]+ s CPU\)|\"(cpu_)?seconds\": [\d.e-]+|"
                    r"written to \S+ \(\d+ bytes|\"(out|bytes)\": \S+|/tmp\S*|pytest-\S*")


def _run(argv: list[str], capsys) -> tuple[int, str, str]:
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse's usage errors
        code = exc.code
    out = capsys.readouterr()
    return code, _TIMES.sub("", out.out), out.err


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    root = tmp_path_factory.mktemp("every")
    glider = root / "rc.toml"
    glider.write_text(rc_glider_toml("min_speed_eas_m_s = 6.0\nmax_speed_eas_m_s = 30.0\ncruise_altitude_m = 500.0\n"
                                     "cruise_speed_m_s = 10.0"))
    log = root / "doublet.mcap"
    assert main(["simulate", str(glider), "--duration", "0.1", "--aero", "quasi-steady", "--log", str(log)]) == 0
    return {"glider": str(glider), "log": str(log)}


@pytest.mark.parametrize("key", sorted(CASES), ids=lambda k: f"{k[0]} {k[1]}")
def test_option_is_honoured_or_refused(key, files, tmp_path, capsys, monkeypatch):
    base, extra, expect = CASES[key]
    monkeypatch.chdir(tmp_path)  # a default output path (logs/...) lands here
    counter = iter(range(100))

    def fill(words):
        return [w.format(glider=files["glider"], log=files["log"], tmp=tmp_path,
                         new=tmp_path / f"new{next(counter)}") for w in words]

    with_option = fill(extra) if extra[0] == base[0] else fill(base) + fill(extra)
    if key == ("sweep", "--resume"):  # a finished study in the folder: --resume reads it instead of refusing
        assert main(fill(base[:-1]) + [str(tmp_path / "done")]) == 0
        capsys.readouterr()
    code, out, err = _run(with_option, capsys)
    if expect.kind == "refused":
        assert code == 2 and expect.text in err, (code, err)
        return
    if expect.kind == "writes":
        assert code == 0, err
        assert (tmp_path / expect.text).stat().st_size > 0
        return
    base_code, base_out, base_err = _run(fill(base), capsys)
    # at least one of them answers (``--no-limits`` turns the refusal of a trim beyond the limits into its solution)
    assert 0 in (code, base_code), (code, err, base_code, base_err)
    assert (code, out) != (base_code, base_out), f"{key}: the same answer with and without the option"
