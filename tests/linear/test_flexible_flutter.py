"""Flutter of a very flexible aircraft's wing about its nonlinear trim (flexsim.linear.flexible_flutter)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import flexsim as fs
from flexsim.linear.flexible_flutter import NEGLECTED, flexible_flutter

DOCS = Path(__file__).resolve().parents[2] / "docs" / "flutter.md"


def test_undeformed_limit_is_the_clamped_wings_flutter():
    """With gravity near zero the trimmed HALE is undeformed (tip 5e-4 of the semispan): its wing's flutter is the
    clamped PHC wing's, 32.21 m/s and 22.61 rad/s (Patil, Hodges & Cesnik, J. Aircraft 38(1), 2001); 8 elements
    and 6 inflow states: within 1 % (the element discretisation: 32.16 with 8, 32.13 with 16 elements)."""
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(gravity_m_s2=0.01))
    point = flexible_flutter(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0), (25.0, 40.0),
                             speed_step_m_s=2.5)
    assert point.tip_deflection_fraction < 1e-3
    assert point.speed_m_s == pytest.approx(32.21, rel=1e-2)
    assert point.frequency_rad_s == pytest.approx(22.61, rel=1e-2)
    assert point.warnings[0] == NEGLECTED


def test_bad_ranges_are_refused():
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    man = fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0)
    with pytest.raises(ValueError, match="speed_range_m_s"):
        flexible_flutter(model, man, (30.0, 20.0))
    with pytest.raises(ValueError, match="speed_step_m_s"):
        flexible_flutter(model, man, (20.0, 30.0), speed_step_m_s=0.0)


def _docs_rows() -> dict[float, list[str]]:
    text = DOCS.read_text().split("<!-- hale-load-factor-table -->", 1)[1]
    rows = {}
    for line in text.splitlines()[3:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip("|").split("|")]
        rows[float(cells[0])] = cells
    return rows


@pytest.mark.slow
@pytest.mark.parametrize("n", [1.0, 1.3])
def test_docs_table_is_current(n):
    """The docs' HALE table against the current code, at its printed precision (Brent tolerance 1e-3 m/s)."""
    cells = _docs_rows()[n]
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    man = fs.SteadyManoeuvre.pull_up(20000.0, n, speed_m_s=25.0)
    linear = fs.flutter(model, man, "theodorsen")
    nonlinear = flexible_flutter(model, man, (20.0, 45.0), speed_step_m_s=2.5)
    assert float(cells[1]) == pytest.approx(linear.speed_m_s, abs=0.006)
    assert float(cells[2]) == pytest.approx(linear.frequency_rad_s, abs=0.006)
    assert float(cells[3].rstrip(" %")) == pytest.approx(-100 * linear.trim.tip_deflection_m / 16.0, abs=0.06)
    assert float(cells[5]) == pytest.approx(nonlinear.speed_m_s, abs=0.006)
    assert float(cells[6]) == pytest.approx(nonlinear.frequency_rad_s, abs=0.006)
    assert float(cells[7].rstrip(" %")) == pytest.approx(100 * nonlinear.tip_deflection_fraction, abs=0.06)
    phugoid = [r.eigenvalue for r in linear.trim.stability.unstable if r.name == "phugoid"][0]
    re_, im = (float(x) for x in re.findall(r"[-+]?\d+\.\d+", cells[4]))
    assert re_ == pytest.approx(phugoid.real, abs=6e-5) and im == pytest.approx(abs(phugoid.imag), abs=6e-5)
    assert float(cells[8]) == pytest.approx(nonlinear.speeds_m_s[0], abs=1e-9)
