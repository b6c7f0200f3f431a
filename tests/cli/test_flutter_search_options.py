"""``flexsim flutter``'s scan-step options and the V-g diagram of a wind tunnel.

* ``--wind-tunnel --vg``: the Goland wing's V-g diagram (p-k, "US") is written and its first crossing into
  instability is the flutter speed of the table: both are the same p-k roots, the table's refined by Brent to
  1e-3 m/s, the diagram's on the tracked branch to 0.01 m/s (:data:`flexsim.linear.vg.CROSSING_TOL_M_S`), so they
  agree to 0.05 m/s; the speed of Goland (1945), 137.2 m/s, within 2 % as docs/validation.md.
* ``--speed-step-m-s``: honoured (the JSON row says the step used; a 10 m/s scan finds the same crossing as the
  default 5 m/s one, to twice the Brent tolerance) and refused outside (0, HI - LO] or without ``--wind-tunnel``.
* ``--mach-step``: honoured by the flight search (the row carries it) and refused with ``--wind-tunnel``; the
  flight table prints the flutter point's warnings (a pitch-unstable trim, tests/linear/test_validity.py).
* ``--vg`` with several altitudes writes one file per altitude, altitudes that round alike included.
"""

import json

import pytest

from flexsim.cli.main import main
from tests.linear.hale_like import write_hale


def _json(capsys, *argv):
    assert main(list(argv)) == 0
    return json.loads(capsys.readouterr().out)


def test_wind_tunnel_vg_diagram_agrees_with_the_table(capsys, tmp_path):
    png = tmp_path / "goland_vg.png"
    doc = _json(capsys, "flutter", "goland_wing", "--wind-tunnel", "--models", "US", "--speed-range-m-s", "100", "180",
                "--vg", str(png), "--vg-points", "9", "--json")
    (row,) = doc["wind_tunnel"]
    assert row["flutter_speed_m_s"] == pytest.approx(137.2, rel=0.02)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    (vg,) = doc["vg"]
    first = next(c for c in vg["crossings"] if c["kind"] == "elastic" and c["direction"] == "unstable")
    assert abs(first["speed_m_s"] - row["flutter_speed_m_s"]) <= 0.05


def test_wind_tunnel_speed_step_is_honoured_or_refused(capsys):
    base = ("flutter", "goland_wing", "--wind-tunnel", "--models", "US", "--speed-range-m-s", "100", "180", "--json")
    fine = _json(capsys, *base)["wind_tunnel"][0]
    coarse = _json(capsys, *base, "--speed-step-m-s", "10")["wind_tunnel"][0]
    assert fine["speed_step_m_s"] == 5.0 and coarse["speed_step_m_s"] == 10.0
    assert abs(fine["flutter_speed_m_s"] - coarse["flutter_speed_m_s"]) <= 2e-3
    for bad in ("0", "-5", "81", "nan"):
        assert main([*base[:-1], "--speed-step-m-s", bad]) == 2
        assert "--speed-step-m-s" in capsys.readouterr().err
    assert main(["flutter", "goland_wing", "--speed-step-m-s", "5"]) == 2
    assert "--speed-step-m-s" in capsys.readouterr().err
    assert main([*base[:-1], "--mach-step", "0.01"]) == 2
    assert "--mach-step" in capsys.readouterr().err


def test_flight_search_mach_step_is_honoured_and_warnings_printed(capsys, tmp_path):
    hale = str(write_hale(tmp_path, payload_x_m=2.0))  # pitch-unstable: the flutter point's trim is not stable
    argv = ["flutter", hale, "--altitudes", "20000", "--models", "US", "--workers", "1", "--mach-step", "0.02"]
    doc = _json(capsys, *argv, "--json")
    (row,) = doc["rows"]
    assert row["mach_step"] == 0.02 and row["warnings"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "warning: US h=20000 m: the trim at the flutter point is not a stable equilibrium" in out


def test_vg_files_of_close_altitudes_are_distinct(tmp_path):
    from flexsim.cli.flutter_commands import vg_paths

    target = tmp_path / "vg.png"
    names = [p.name for p in vg_paths(str(target), [9144.0, 9144.4])]
    assert len(set(names)) == 2 and names[0] == "vg_9144m.png"
    assert [p.name for p in vg_paths(str(target), [0.0, 3048.0])] == ["vg_0m.png", "vg_3048m.png"]
    assert vg_paths(str(target), [0.0]) == [target]
