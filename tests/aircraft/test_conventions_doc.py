"""docs/conventions.md: the figures it quotes about the bundled GTM are the data's (docs cannot drift).

The page's example orientation ("For the GTM right wing (0°, 5.16°, 110.55°), x_w points outboard, aft
(20.55° sweep) and up (5.16° dihedral)") and its elastic-axis positions ("GTM wing and stabilizer: 0.375 → a =
−0.25 ... fin 0.5 → a = 0") are read from the page and compared with ``load_aircraft("gtm")``: the Euler angles,
the plan-view angle of x_w behind the y axis, atan(-x_w . x_body / x_w . y_body) [deg], its elevation
asin(-x_w . z_body) [deg] (z down), and ``ea_fraction`` with Theodorsen's a = 2 ea_fraction - 1 (Theodorsen 1935).
"""

import re
from pathlib import Path

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft

DOC = (Path(__file__).resolve().parents[2] / "docs" / "conventions.md").read_text(encoding="utf-8")
_NUM = r"([−-]?\d+(?:\.\d+)?)"


def _float(text: str) -> float:
    return float(text.replace("−", "-"))


@pytest.fixture(scope="module")
def gtm():
    return load_aircraft("gtm")


def test_right_wing_orientation_as_quoted(gtm):
    m = re.search(rf"GTM\s+right wing \({_NUM}°, {_NUM}°, {_NUM}°\), x_w points outboard, aft \({_NUM}° sweep\) and"
                  rf"\s+up \({_NUM}° dihedral\)", DOC)
    assert m, "docs/conventions.md: the GTM right-wing orientation sentence is gone or reworded; update this test"
    euler, sweep, dihedral = [_float(g) for g in m.groups()[:3]], _float(m.group(4)), _float(m.group(5))
    wing = gtm.component("right_wing")
    np.testing.assert_allclose(np.rad2deg(wing.euler_rad), euler, atol=5e-3)
    x_w = wing.axes_in_body[:, 0]
    assert x_w[1] > 0.9  # outboard
    assert np.rad2deg(np.arctan2(-x_w[0], x_w[1])) == pytest.approx(sweep, abs=5e-3)  # aft of the y axis in plan view
    assert np.rad2deg(np.arcsin(-x_w[2])) == pytest.approx(dihedral, abs=5e-3)  # up (body z points down)


def test_elastic_axis_positions_as_quoted(gtm):
    m = re.search(rf"GTM wing and stabilizer: {_NUM} → a = {_NUM}.*?fin {_NUM} → a = {_NUM}\)", DOC, re.DOTALL)
    assert m, "docs/conventions.md: the GTM elastic-axis sentence is gone or reworded; update this test"
    surfaces_ea, surfaces_a, fin_ea, fin_a = (_float(g) for g in m.groups())
    assert surfaces_a == pytest.approx(2 * surfaces_ea - 1) and fin_a == pytest.approx(2 * fin_ea - 1)
    for name in ("right_wing", "left_wing", "right_htail", "left_htail"):
        np.testing.assert_array_equal(gtm.component(name).sections.ea_fraction, surfaces_ea, err_msg=name)
    np.testing.assert_array_equal(gtm.component("vtail").sections.ea_fraction, fin_ea)
