"""The packed kernel data is generated from the terms' data classes (:mod:`flexsim._kernels.layout`): every field
is declared once, documented, packed at its declared rank and read back by its generated index; an undeclared
name is refused."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import flexsim._kernels as k
from flexsim._kernels import layout
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel


def test_every_field_is_declared_once_and_documented():
    names = [f.name for term in k.TERMS for f in dataclasses.fields(term)]
    assert len(names) == len(set(names))
    assert {n for n, _ in k.float_fields()} | set(k.flag_names()) | set(k.int_fields()) == set(names) | {"ints"}
    for term in k.TERMS:
        assert term.__dataclass_params__.frozen and term.__doc__
        for f in dataclasses.fields(term):
            assert f.metadata["doc"].strip(), (term.__name__, f.name)


def test_a_models_fields_read_back_by_their_index():
    """Each float field of a GTM model's F, read through its generated index, is the array the builder packed."""
    model = AircraftModel(load_aircraft("gtm"), aero="unsteady", structural_damping=0.01)
    F, I = model.kernel_data
    views = {1: k._f1, 2: k._f2, 3: k._f3, 4: k._f4}
    structure = model.structure
    expected = {"m0": structure.inertia.m0, "k_bending": structure.k_bending, "k_torsion": structure.k_torsion,
                "thrust_t1": structure.thrust.t1, "semichord": model.aero.strips.semichord_m, "g": [9.80665],
                "a_inv": model.aero.inflow.A_inv}
    for term in k.TERMS:
        for f in dataclasses.fields(term):
            if f.name in expected:
                got = views[f.metadata["rank"]](F, I, term.index[f.name])
                np.testing.assert_array_equal(got, np.asarray(expected[f.name]))
    flags = dict(zip(k.flag_names(), (int(k._flag(I, i)) for i in range(len(k.flag_names())))))
    assert flags["n_v"] == 30 and flags["nq"] == 12 and flags["has_damping"] == 1 and flags["finite_state"] == 1


def test_pack_refuses_an_undeclared_field():
    with pytest.raises(ValueError, match=r"kernel fields \['not_a_field'\]: not fields of any registered"):
        k.pack({"not_a_field": np.zeros(1)}, {})
    with pytest.raises(ValueError, match=r"kernel field m0: rank 1, expected 2"):
        k.pack({"m0": np.zeros(3)}, {})


def test_registration_refuses_duplicates_and_mutable_classes():
    @dataclasses.dataclass
    class Mutable:
        x: np.ndarray = layout.packed(1, "x")

    with pytest.raises(TypeError, match="Mutable: a term's data must be a frozen dataclass"):
        layout.term_data(Mutable)

    @dataclasses.dataclass(frozen=True)
    class Again:
        m0: np.ndarray = layout.packed(2, "a second M0")

    with pytest.raises(ValueError, match="Again.m0: a field of that name is already registered"):
        layout.term_data(Again)


def test_every_term_fills_its_own_fields_from_the_model():
    """One way to build kernel data: each registered class but the derived sparsity has ``fields_of(model)``, which
    returns fields of its own class only, and the model's data are exactly their union, packed."""
    from flexsim._kernels.layout import SparsityData

    model = AircraftModel(load_aircraft("gtm"), aero="unsteady", structural_damping=0.01)
    for term in k.TERMS:
        if term is SparsityData:
            assert not hasattr(term, "fields_of")
            continue
        assert set(term.fields_of(model)) <= set(term.index), term.__name__
    data = k.pack_fields(k.fields_of(model))
    assert np.array_equal(data.F, model.kernel_data.F, equal_nan=True) and np.array_equal(data.I, model.kernel_data.I)

    class Stray:  # a builder that writes another class's field is refused, naming both
        index = {"g": 0}

        @staticmethod
        def fields_of(model):
            return {"m0": np.zeros((1, 1))}

    with pytest.raises(ValueError, match=r"Stray.fields_of: \['m0'\] are not fields of Stray"):
        k.fields_of(model, (Stray,))
    with pytest.raises(ValueError, match="kernel field 'nonsense'"):
        k.pack_fields({"nonsense": [1.0]})
