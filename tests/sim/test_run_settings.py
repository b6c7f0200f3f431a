"""The settings objects of a simulate run besides the integrator (:mod:`flexsim.sim.run_settings`): frozen, validated
on construction with the field named, and one name per setting with the environments (the structural limit is
``wing_tip_deflection_m``, as in :class:`flexsim.envs.config.FlightLimits`)."""

from __future__ import annotations

import dataclasses
import math

import pytest

from flexsim.envs.config import FlightLimits
from flexsim.sim.run_settings import DEFAULT_EVENTS, EventSettings, OutputSettings, SimEvent


def test_defaults_and_frozen():
    events, output = EventSettings(), OutputSettings()
    assert events.names == DEFAULT_EVENTS and events.wing_tip_deflection_m is None
    assert (output.rate_hz, output.log_path, output.log_rate_hz, dict(output.metadata), output.notes) == (100.0, None, 50.0, {}, ())
    with pytest.raises(dataclasses.FrozenInstanceError):
        events.names = ()  # type: ignore[misc]
    with pytest.raises(TypeError):
        output.metadata["a"] = "b"  # type: ignore[index]


def test_one_name_with_the_environments():
    assert "wing_tip_deflection_m" in {f.name for f in dataclasses.fields(FlightLimits)}
    assert "wing_tip_deflection_m" in {f.name for f in dataclasses.fields(EventSettings)}


def test_values_are_normalised():
    stop = SimEvent("stop", lambda t, x: 1.0)
    e = EventSettings(["ground", stop], wing_tip_deflection_m=3)
    assert e.names == ("ground", stop) and e.wing_tip_deflection_m == 3.0
    o = OutputSettings(rate_hz=10, log_path=False, metadata={"a": 1}, notes=[(1, "gust")])
    assert o.rate_hz == 10.0 and o.log_path is None and dict(o.metadata) == {"a": "1"} and o.notes == ((1.0, "gust"),)
    assert OutputSettings(rate_hz=None).rate_hz is None


@pytest.mark.parametrize("kind, kwargs, match", [
    (EventSettings, {"names": "ground"}, "names = 'ground': must be a sequence"),
    (EventSettings, {"names": ("stall",)}, "names: unknown event 'stall'"),
    (EventSettings, {"names": (3,)}, "names: 3 is neither a built-in event name nor a SimEvent"),
    (EventSettings, {"wing_tip_deflection_m": 0.0}, r"wing_tip_deflection_m = 0.0: must be a finite number > 0 \[m\]"),
    (EventSettings, {"wing_tip_deflection_m": math.inf}, "wing_tip_deflection_m = inf"),
    (OutputSettings, {"rate_hz": 0.0}, r"rate_hz = 0.0: must be a finite number > 0 \[Hz\] \(or None\)"),
    (OutputSettings, {"log_rate_hz": None}, r"log_rate_hz = None: must be a finite number > 0 \[Hz\]"),
    (OutputSettings, {"log_rate_hz": True}, "log_rate_hz = True"),
    (OutputSettings, {"log_path": 3}, "log_path = 3: must be a path"),
    (OutputSettings, {"metadata": [1]}, r"metadata = \[1\]: must be a mapping"),
    (OutputSettings, {"notes": [(math.nan, "x")]}, "notes = .*every time must be finite"),
    (OutputSettings, {"notes": [1.0]}, r"notes = \[1.0\]: must be a sequence of \(time \[s\], text\) pairs"),
    (OutputSettings, {"progress": "yes"}, "progress = 'yes'"),
])
def test_bad_values_name_the_field(kind, kwargs, match):
    with pytest.raises(ValueError, match=match):
        kind(**kwargs)
