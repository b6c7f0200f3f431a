"""The V-g diagram of a very flexible aircraft's wing about its nonlinear trim (flexsim.linear.flexible_vg).

Invariant checked: the diagram's refined crossing (branches continued by eigenvector correlation, regula falsi on the
branch) and the flutter search (the largest damping ratio of any oscillatory root, Brent's method on it) are two
routes to the same flutter point of the same equations; they agree to the diagram's crossing tolerance.
"""

from __future__ import annotations

import numpy as np
import pytest

import flexsim as fs
from flexsim.linear.flexible_vg import MODE_WORDS, flexible_vg
from flexsim.linear.vg import CROSSING_TOL_M_S
from flexsim.model.terms import NonlinearBeams

LEVEL = fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0)


@pytest.fixture(scope="module")
def model():
    return fs.AircraftModel(fs.load_aircraft("phc_hale"), terms=fs.Terms(nonlinear_beams=NonlinearBeams(4)))


def test_crossing_is_the_flutter_point(model):
    diagram = fs.vg_diagram(model, manoeuvre=LEVEL, models=("FS",), speeds_m_s=np.arange(32.0, 41.0, 2.0))
    point = fs.flexible_flutter(model, LEVEL, (32.0, 40.0), speed_step_m_s=2.0, tol_m_s=1e-3)
    crossing = diagram.flutter("unsteady")
    assert crossing is not None and crossing.refined, diagram.crossings
    assert abs(crossing.speed_m_s - point.speed_m_s) < CROSSING_TOL_M_S
    assert crossing.frequency_rad_s == pytest.approx(point.frequency_rad_s, rel=2e-3)  # sampled 2 mm/s apart
    words = {t.label.split(" ", 1)[1].rsplit(" ", 1)[0] for t in diagram.tracks}
    assert words <= set(MODE_WORDS.values()) and "bending" in words
    assert all(t.aero_model == "unsteady" and t.kind == "elastic" for t in diagram.tracks)
    assert diagram.warnings and "clamped" in diagram.warnings[0]


def test_bad_speeds_and_models_are_refused(model):
    with pytest.raises(ValueError, match="speeds_m_s"):
        flexible_vg(model, LEVEL, (30.0, 29.0))
    with pytest.raises(ValueError, match=r"models = \['QS'\].*Peters"):
        fs.vg_diagram(model, manoeuvre=LEVEL, models=("QS",), speeds_m_s=(30.0, 31.0))
