"""The environments say at reset when their trim takes the linear structure beyond its range
(flexsim.model.linear_range; limits: tests/model/test_linear_range.py): the GTM with a wing four times as flexible
in bending (tip 3.0 m = 16 % of 18.25 m in the level-hold task's cruise) gives ``info["linear_range"]`` at every reset
and one warning per environment; the GTM (4 %) gives neither.
"""

from __future__ import annotations

from dataclasses import replace

import gymnasium as gym
import pytest

from flexsim import envs  # noqa: F401 (registers the environments)
from flexsim.aircraft.toml_loader import load_aircraft


def _flexible_gtm():
    gtm = load_aircraft("gtm")
    comps = tuple(replace(c, sections=replace(c.sections, ei_nm2=c.sections.ei_nm2 / 4.0))
                  if c.name in ("right_wing", "left_wing") else c for c in gtm.components)
    return replace(gtm, components=comps, name="GTM with a 4x softer wing")


@pytest.mark.parametrize("aircraft, said", [("gtm", False), ("soft", True)])
def test_environments_say_it_at_reset(aircraft, said, recwarn):
    env = gym.make("FlexSim/GTM-LevelHold-v1", aero="quasi-steady", turbulence="none",
                   aircraft=_flexible_gtm() if aircraft == "soft" else aircraft)
    try:
        _, info = env.reset(seed=0)
        _, info2 = env.reset(seed=1)
    finally:
        env.close()
    mine = [str(w.message) for w in recwarn if "linear structure beyond its range" in str(w.message)]
    if said:
        assert "right_wing tip deflection" in info["linear_range"] and "linear_range" in info2
        assert len(mine) == 1  # once per environment, not at every reset
        assert "FlexSim/GTM-LevelHold-v1: linear structure beyond its range: right_wing tip deflection" in mine[0]
    else:
        assert "linear_range" not in info and not mine
