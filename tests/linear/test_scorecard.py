"""Trend scorecard on rows with known slopes; the paper's values never enter a computed field.

Closed forms: the least-squares slope of exactly linear data is its slope (to round-off); a sign change
between two altitudes interpolates linearly: h0 + (h1 - h0) d0 / (d0 - d1).
Paper values (Tables 2-3): US - QS = -0.0018 at 3048 m and +0.0338 at 6096 m, so its crossover is at
3048 + 3048 x 0.0018 / 0.0356 = 3202 m.
"""

import math

import pytest

import flexsim.linear.scorecard as sc
from flexsim.linear.paper_data import paper_crossover_altitude_m


def _turn_rows(h, model, dm_per_km, dw_per_km, m0=0.8, w0=35.0):
    return [{"model": model, "altitude_m": h, "turn_radius_m": r, "climb_angle_deg": 0.0,
             "mach": m0 + dm_per_km * (r / 1e3 - 5.0), "omega_rad_s": w0 + dw_per_km * (r / 1e3 - 5.0)}
            for r in (5000.0, 8000.0, 12000.0)]


def test_signs_slopes_and_matches():
    rows = _turn_rows(0.0, "US", +2e-3, -0.01) + _turn_rows(9144.0, "US", -3e-3, +0.05) + _turn_rows(3048.0, "US", 1e-6, 0.0)
    rows.append({"model": "US", "altitude_m": 9144.0, "turn_radius_m": 6000.0, "error": "no flutter"})
    signs = {(t.altitude_m, t.quantity): t for t in sc.trend_signs(rows, "turn")}
    t = signs[(9144.0, "dM_F/dR")]
    assert t.slope == pytest.approx(-3e-3, rel=1e-9) and t.change == pytest.approx(-0.021, rel=1e-9)
    assert t.sign == -1 and t.paper_sign == -1 and t.match is True and t.n_points == 3
    assert signs[(9144.0, "domega_F/dR")].sign == 1 and signs[(9144.0, "domega_F/dR")].match is True
    assert signs[(0.0, "dM_F/dR")].sign == 1 and signs[(0.0, "dM_F/dR")].match is True  # paper: sea level US rises
    # a change of 7e-6 over the range is below the search resolution: no trend, which is not the paper's "-"
    assert signs[(3048.0, "dM_F/dR")].sign == 0 and signs[(3048.0, "dM_F/dR")].match is False
    assert sc.critical_altitude(list(signs.values())) is not None


def test_paper_signs_do_not_enter_the_computed_fields(monkeypatch):
    rows = _turn_rows(9144.0, "US", -3e-3, +0.05)
    before = [(t.slope, t.change, t.sign) for t in sc.trend_signs(rows, "turn")]
    monkeypatch.setattr(sc, "PAPER_TREND_SIGNS", {})
    after = sc.trend_signs(rows, "turn")
    assert [(t.slope, t.change, t.sign) for t in after] == before
    assert all(t.paper_sign is None and t.match is None for t in after)


def test_crossover_and_critical_altitude_interpolate_linearly():
    rows = []
    for h, qs, us in ((0.0, 0.70, 0.68), (3048.0, 0.75, 0.74), (6096.0, 0.76, 0.79), (9144.0, 0.77, 0.82)):
        rows += [{"model": "QS", "altitude_m": h, "mach": qs, "turn_radius_m": math.inf, "climb_angle_deg": 0.0},
                 {"model": "US", "altitude_m": h, "mach": us, "turn_radius_m": math.inf, "climb_angle_deg": 0.0}]
    assert sc.crossover_altitude(rows) == pytest.approx(3048.0 + 3048.0 * 0.01 / 0.04)
    assert sc.crossover_altitude([r for r in rows if r["altitude_m"] > 5000]) is None
    turn = _turn_rows(0.0, "US", +1e-3, 0.0) + _turn_rows(3048.0, "US", -3e-3, 0.0)
    assert sc.critical_altitude(sc.trend_signs(turn, "turn")) == pytest.approx(3048.0 * 1e-3 / 4e-3)


def test_paper_crossover_from_its_tables():
    assert paper_crossover_altitude_m() == pytest.approx(3048.0 + 3048.0 * 0.0018 / 0.0356, abs=1.0)


def test_bad_kind_rejected():
    with pytest.raises(ValueError, match="kind = 'loop'"):
        sc.trend_signs([], "loop")
