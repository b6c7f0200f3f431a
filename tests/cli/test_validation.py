"""The CLI never silently changes the question: conflicting or out-of-validity options are
errors naming the option, the value and the allowed range, checked before any computation; names from
files are printed with terminal escape sequences shown escaped."""

import pytest

from flexsim.cli import validation
from flexsim.cli.main import main


@pytest.mark.parametrize("argv, needle", [
    (["trim", "gtm", "--turn-radius-m", "0"], "--turn-radius-m = 0.0"),
    (["trim", "gtm", "--turn-radius-m", "50"], "--turn-radius-m = 50.0"),
    (["trim", "gtm", "--glide", "--climb-deg", "5"], "--glide and --climb-deg 5"),
    (["trim", "gtm", "--climb-deg", "89"], "--climb-deg = 89.0: must be within +-30 deg"),
    (["trim", "gtm", "--mach", "0"], "--mach = 0.0"),
    (["trim", "gtm", "--mach", "1.2"], "--mach = 1.2"),
    (["trim", "gtm", "--mach", "nan"], "--mach = nan"),
    (["trim", "gtm", "--altitude-m", "1e6"], "--altitude-m = 1000000.0"),
    (["aero", "gtm", "--mach", "1.0"], "--mach = 1.0"),
    (["modes", "gtm", "--count", "-3"], "--count = -3"),
    (["flutter", "gtm", "--workers", "0"], "--workers = 0"),
    (["flutter", "gtm", "--workers", "-1"], "--workers = -1"),
    (["flutter", "gtm", "--mach-min", "0.9", "--mach-max", "0.5"], "--mach-min, --mach-max = 0.9, 0.5"),
    (["flutter", "gtm", "--altitudes", "1e6"], "--altitudes = 1000000.0"),
    (["flutter", "gtm", "--structural-damping", "0.5"], "--structural-damping = 0.5"),
    (["sweep", "--turn", "--models", "QS,ZZ"], "--models entry 'ZZ'"),
    (["sweep", "--turn", "--workers", "0"], "--workers = 0"),
    (["sweep", "--turn", "--chain-length", "0"], "--chain-length = 0: must be an integer >= 1"),
])
def test_bad_options_are_errors_before_computing(argv, needle, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert needle in err and "Traceback" not in err


def test_mach_beyond_prandtl_glauert_warns(capsys):
    assert main(["trim", "gtm", "--mach", "0.97", "--json"]) == 0
    assert "beyond the Prandtl-Glauert range" in capsys.readouterr().err
    assert main(["aero", "goland_wing", "--mach", "0.97", "--json"]) == 0  # same rule as trim, no refusal
    assert "beyond the Prandtl-Glauert range" in capsys.readouterr().err


def test_prandtl_glauert_cap_is_the_models():
    from flexsim.model import coupling

    assert validation.PRANDTL_GLAUERT_MACH_MAX == coupling._MACH_CAP


def test_output_paths_checked_first(tmp_path, capsys, monkeypatch):
    import flexsim.cli.flutter_commands as fc

    monkeypatch.setattr(fc, "run_study", lambda *a, **k: pytest.fail("computed before checking --out"))
    existing = tmp_path / "f"
    existing.write_text("x")
    assert main(["sweep", "--turn", "--altitudes", "9144", "--models", "QS", "--out", str(existing)]) == 2
    assert "exists and is not a directory" in capsys.readouterr().err
    assert main(["aero", "goland_wing", "--plot", str(tmp_path)]) == 2
    assert "is a directory" in capsys.readouterr().err
    assert main(["aero", "goland_wing", "--plot", str(tmp_path / "cla.txt")]) == 2
    assert "suffix must be one of" in capsys.readouterr().err
    text = tmp_path / "notes.mcap"
    text.write_text("my notes")
    assert main(["simulate", "climb", "--duration", "0.1", "--log", str(text)]) == 2
    assert "not a flight log" in capsys.readouterr().err and text.read_text() == "my notes"


def test_escape_sequences_in_names_are_printed_escaped(tmp_path, capsys):
    from importlib import resources

    src = (resources.files("flexsim.aircraft") / "data" / "goland_wing.toml").read_text()
    path = tmp_path / "esc.toml"
    path.write_text(src.replace('name = "Goland wing"', 'name = "Goland \\u001b[31mRED\\u001b]0;pwned\\u0007 wing"'))
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    assert "\x1b" not in out and "\x07" not in out and "Goland \\x1b[31mRED" in out
    assert validation.printable("a\x1bb\x9bc\nd\te") == "a\\x1bb\\x9bc\nd\te"
