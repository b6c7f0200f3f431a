"""Models are immutable after construction (house style: state passed per call, not stored).

* Setting or deleting an attribute of an ``AircraftModel`` or of what it is built from (``StructuralModel``,
  ``AeroCoupling``, ``ParasiteDrag``) raises AttributeError naming the class and the attribute.
* Every ndarray reachable from a built model — its own, the structure's, the coupling's, the strips', the frozen
  aircraft definition's — is read-only, so writing into one raises ValueError ("read-only"); the walk visits
  the whole object graph (checked to find more than 100 arrays, so the test can fail).
* A ``TrimPoint``'s x and u are read-only copies; ``simulate`` and ``trim`` still work on the frozen model.
"""

import dataclasses

import numpy as np
import pytest

from flexsim._immutable import Immutable
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre, trim
from flexsim.sim.run_settings import OutputSettings


@pytest.fixture(scope="module")
def model():
    m = AircraftModel(load_aircraft("gtm"), aero="unsteady", structural_damping=0.01)
    m.structure.mass_properties, m.structure.mirror  # cached properties computed after construction too
    return m


def _arrays(value, path="model", seen=None):
    """(path, array) of every ndarray reachable through Immutable objects, dataclasses, tuples, lists, dicts."""
    seen = set() if seen is None else seen
    if id(value) in seen:
        return
    seen.add(id(value))
    if isinstance(value, np.ndarray):
        yield path, value
    elif isinstance(value, (tuple, list)):
        for i, item in enumerate(value):
            yield from _arrays(item, f"{path}[{i}]", seen)
    elif isinstance(value, dict):
        for k, item in value.items():
            yield from _arrays(item, f"{path}[{k!r}]", seen)
    elif isinstance(value, Immutable) or (dataclasses.is_dataclass(value) and not isinstance(value, type)):
        for k, item in vars(value).items():
            yield from _arrays(item, f"{path}.{k}", seen)


def test_every_array_of_a_built_model_is_read_only(model):
    found = list(_arrays(model))
    assert len(found) > 100
    writable = [p for p, a in found if a.flags.writeable and a.dtype != object]
    assert writable == []
    for write in (lambda: model.structure.k_bending.__setitem__((0, 0), 1.0),
                  lambda: model.structure.inertia.m0.__setitem__((0, 0), 1.0),
                  lambda: model.aero.strips.semichord_m.__setitem__(0, 1.0),
                  lambda: model.aircraft.component("right_wing").sections.ei_nm2.__setitem__(0, 1.0),
                  lambda: model.structure.mass_properties.cg_m.__setitem__(0, 1.0)):
        with pytest.raises(ValueError, match="read-only"):
            write()


@pytest.mark.parametrize("owner, name", [("model", "rhs"), ("model", "aero"), ("model", "layout"),
                                         ("structure", "k_bending"), ("aero", "strips")])
def test_attributes_cannot_be_set_or_deleted(model, owner, name):
    obj = {"model": model, "structure": model.structure, "aero": model.aero}[owner]
    cls = type(obj).__name__
    with pytest.raises(AttributeError, match=rf"{cls} is immutable after construction: cannot set attribute '{name}'"):
        setattr(obj, name, None)
    with pytest.raises(AttributeError, match=rf"{cls} is immutable after construction: cannot delete attribute '{name}'"):
        delattr(obj, name)


def test_trim_point_arrays_are_read_only_and_the_frozen_model_still_flies(model):
    qs = AircraftModel(model.aircraft, aero="quasi-steady")
    point = trim(qs, SteadyManoeuvre.level(9144.0, mach=0.75))
    with pytest.raises(ValueError, match="read-only"):
        point.x[0] = 1.0
    with pytest.raises(ValueError, match="read-only"):
        point.u[0] = 1.0
    from flexsim.sim.simulate import simulate

    result = simulate(qs, point, 0.1, output=OutputSettings(rate_hz=20.0))
    assert result.completed and abs(result.altitude_m[-1] - 9144.0) < 0.01  # 0.1 s from a trim: no drift to speak of
