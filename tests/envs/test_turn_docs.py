"""The turn figures quoted in the Turn env's docstrings and docs/environments.md are those of the trim.

The quoted numbers are read from the text itself (so editing either side without the other fails) and compared
with ``trim(SteadyManoeuvre.turn(9144 m, R, M 0.75))`` of the bundled gtm (quasi-steady aerodynamics; the steady
turn is the same with the finite-state model, whose inflow states are at rest in a trim): the bank range over
R = 7-12 km (to the degree quoted), and the body-axis sideslip asin(sin phi sin theta) and rudder at R = +-8 km
(to the 0.1 deg quoted). Measured 2026-12-01 (with the GTM's fuselage/nacelle moments and tail downwash,
docs/options.md): bank 40.92 deg (7 km) to 25.94 deg (12 km), 36.78 deg at 8 km; sideslip +-5.339 deg, rudder
+-6.363 deg at R = +-8 km.
"""

import math
import re
from pathlib import Path

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.envs.turn import TurnEnv, TurnTask
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre, trim

DOC = Path(__file__).resolve().parents[2] / "docs" / "environments.md"


@pytest.fixture(scope="module")
def turns():
    """R [m] -> (bank [deg], body sideslip [deg], rudder [deg]) of the steady turn at 9144 m, M 0.75."""
    task = TurnTask()
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    lay = model.layout
    out = {}
    for radius in (7000.0, 8000.0, -8000.0, 12000.0):
        point = trim(model, task.turn(radius))
        phi, theta, _ = point.x[lay.euler]
        v = point.x[lay.v]
        beta = math.asin(v[1] / np.linalg.norm(v))
        assert beta == pytest.approx(math.asin(math.sin(phi) * math.sin(theta)), abs=1e-9)  # the docstring's formula
        out[radius] = (math.degrees(phi), math.degrees(beta), math.degrees(point.u[3]))
    return out


def _number(pattern: str, text: str) -> tuple[float, ...]:
    """The numbers of ``pattern`` in ``text``, whitespace collapsed and generated-region markers (HTML comments) removed."""
    match = re.search(pattern, " ".join(re.sub(r"<!--.*?-->", "", text).split()))
    assert match, f"quoted figure not found: {pattern!r}"
    return tuple(float(g) for g in match.groups())


def test_bank_range_quoted_for_the_radius_range(turns):
    assert TurnTask().radius_range_m == (7000.0, 12000.0)
    lo, hi = _number(r"7000-12000 m: bank (\d+) to (\d+) deg", TurnTask.__doc__)
    assert (lo, hi) == (round(turns[12000.0][0]), round(turns[7000.0][0]))
    (bank_8km,) = _number(r"bank about (\d+) deg for R = 8000 m", TurnEnv.__doc__)
    assert bank_8km == round(turns[8000.0][0])


def test_sideslip_and_rudder_quoted_for_r_8_km(turns):
    beta_right, beta_left, rudder = _number(
        r"about ([+-][\d.]+) deg at R = \+8000 m, ([+-][\d.]+) deg at R = -8000 m\), held with about ([\d.]+) deg of rudder",
        TurnEnv.__doc__)
    assert beta_right == round(turns[8000.0][1], 1) and beta_left == round(turns[-8000.0][1], 1)
    assert rudder == round(abs(turns[8000.0][2]), 1) == round(abs(turns[-8000.0][2]), 1)
    doc_beta, doc_rudder = _number(r"asin\(sin phi sin theta\) \(([+-][\d.]+) deg at R = \+8000 m, with the sign of R\) "
                                   r"and the trim needs about ([\d.]+) deg of rudder", DOC.read_text(encoding="utf-8"))
    assert (doc_beta, doc_rudder) == (beta_right, rudder)
