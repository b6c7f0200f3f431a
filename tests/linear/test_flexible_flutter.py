"""Flutter of a very flexible aircraft's wing about its nonlinear trim (flexsim.linear.flexible_flutter)."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

import flexsim as fs
from flexsim.linear.flexible_flutter import FREE_AIRCRAFT, NEGLECTED, flexible_flutter
from flexsim.linear.flexible_stability import free_aircraft_spectrum

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


def test_undeformed_free_aircraft_flutters_as_its_clamped_wing():
    """The whole free HALE (six rigid-body degrees of freedom, Peters' strips on every lifting strip), undeformed as
    above: its flutter is the clamped wing's, as Patil, Hodges & Cesnik (2001) find for the complete aircraft; against
    the clamped PHC wing's 32.21 m/s and 22.61 rad/s, measured 32.14 m/s and 22.62 rad/s: within 1 % (the element
    discretisation, as above)."""
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(gravity_m_s2=0.01))
    point = flexible_flutter(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0), (25.0, 40.0),
                             speed_step_m_s=2.5, structure="free-aircraft")
    assert point.speed_m_s == pytest.approx(32.21, rel=1e-2)
    assert point.frequency_rad_s == pytest.approx(22.61, rel=1e-2)
    assert point.warnings[0] == FREE_AIRCRAFT and point.component == ""
    with pytest.raises(ValueError, match="structure = 'wing': must be one of clamped-wing, free-aircraft"):
        flexible_flutter(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0), (25.0, 40.0), structure="wing")


def test_bad_ranges_are_refused():
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    man = fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0)
    with pytest.raises(ValueError, match="speed_range_m_s"):
        flexible_flutter(model, man, (30.0, 20.0))
    with pytest.raises(ValueError, match="speed_step_m_s"):
        flexible_flutter(model, man, (20.0, 30.0), speed_step_m_s=0.0)


def _numbers(cell: str) -> list[float]:
    """The decimal numbers of a table cell, with its signs (U+2212 minus included)."""
    return [float(x) for x in re.findall(r"[-+]?\d+\.\d+", cell.replace("\u2212", "-").replace("± ", "+"))]


def _flat(roots) -> list[float]:
    out = []
    for z in roots:
        out.append(z.real)
        if z.imag > 1e-9:
            out.append(abs(z.imag))
    return out


def _docs_rows(marker: str = "hale-load-factor-table") -> dict[float, list[str]]:
    text = DOCS.read_text().split(f"<!-- {marker} -->", 1)[1]
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
    np.testing.assert_allclose(_numbers(cells[4]), _flat([complex(phugoid.real, abs(phugoid.imag))]), atol=6e-5)
    np.testing.assert_allclose(_numbers(cells[8]), _flat(free_aircraft_spectrum(model, nonlinear.trim).phugoid),
                               atol=6e-5)
    assert float(cells[9]) == pytest.approx(nonlinear.speeds_m_s[0], abs=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize("speed", [25.0, 37.5])
def test_docs_phugoid_table_is_current(speed):
    cells = _docs_rows("hale-phugoid-table")[speed]
    man = fs.SteadyManoeuvre.level(20000.0, speed_m_s=speed)
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    point = fs.trim_flexible(model, man)
    assert float(cells[3].rstrip(" %")) == pytest.approx(100 * point.tip_deflection_fraction[0], abs=0.06)
    np.testing.assert_allclose(_numbers(cells[4]), _flat(free_aircraft_spectrum(model, point).phugoid), atol=6e-5)
    qs = fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(aero=fs.AeroOptions("quasi-steady")))
    trim = fs.trim(qs, man, check_limits=False)
    assert float(cells[1].rstrip(" %")) == pytest.approx(-100 * trim.tip_deflection_m / 16.0, abs=0.06)
    pair = [m.eigenvalue for m in fs.spectrum(qs, trim.x, trim.u).modes
            if m.name.startswith("phugoid") and abs(m.eigenvalue.imag) > 1e-9][0]
    np.testing.assert_allclose(_numbers(cells[2]), [pair.real, abs(pair.imag)], atol=6e-5)
