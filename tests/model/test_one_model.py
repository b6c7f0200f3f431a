"""A model is one value — aircraft, terms, variant — and every analysis evaluates the model it is given.

Invariants checked here (no recorded numbers): a sibling made by :meth:`AircraftModel.replace` changes only the named
fields; a flutter search of a model with switched terms evaluates those terms (its answer differs from the default
model's and equals the answer of the same switches on the quasi-steady model the search trims with, to the last bit:
the two searches evaluate the same siblings); and every field of :class:`Terms`, set to a value other than its
default, reaches the result of trim, flutter, V-g, wind tunnel, linear system, study row and environment.
"""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

import flexsim as fs
from flexsim.linear.control import LinearSystem, ModelRecord, linear_system
from flexsim.linear.flutter import wind_tunnel
from flexsim.linear.study import StudyCase, run_case
from flexsim.linear.vg import vg_diagram
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.model.terms import NonlinearBeams, Terms, aero_term_options
from flexsim.model.variant import Variant, VariantSettings
from flexsim.trimming import SteadyManoeuvre, trim

#: Switches of terms that a flutter search must carry from the model it is given to the siblings it trims and solves.
SWITCHES = dict(force_resolution="normal", thrust_follows_deflection=False, engine_angular_momentum=(2e5, 0.0, 0.0))
CRUISE = SteadyManoeuvre.level(9144.0, mach=0.8)
#: A range around the GTM's quasi-steady level-flight flutter Mach at 9144 m (about 0.815), scanned in two steps.
RANGE = (0.78, 0.85)


@pytest.fixture(scope="module")
def gtm():
    return fs.load_aircraft("gtm")


def test_replace_changes_only_the_named_fields(gtm):
    model = AircraftModel(gtm, aero="unsteady", gravity_m_s2=9.0)
    twin = model.replace(aero=dataclasses.replace(model.terms.aero, model="quasi-steady"), force_resolution="normal",
                         variant="quasi-rigid")
    assert twin.aircraft is model.aircraft
    assert twin.terms == dataclasses.replace(model.terms, aero=AeroOptions("quasi-steady"), force_resolution="normal")
    assert twin.variant == VariantSettings(Variant.QUASI_RIGID) and model.variant == VariantSettings()
    assert twin.terms.gravity_m_s2 == 9.0 and twin.layout.n_inflow == 0
    tunnel = model.replace(variant="restrained", restrained_velocity_m_s=(100.0, 0.0, 0.0), air_density_kg_m3=0.5)
    assert tunnel.variant.restrained_velocity_m_s == (100.0, 0.0, 0.0) and tunnel.air_density(tunnel.layout.zeros()) == 0.5
    with pytest.raises(ValueError, match="gravity: not a field of the model's terms"):
        model.replace(gravity=0.0)
    with pytest.raises(ValueError, match="force_resolution = 'tilted'"):
        model.replace(force_resolution="tilted")


def test_no_copies_of_the_terms_on_the_model(gtm):
    """The model holds its terms once: no attribute repeats a field of Terms or of VariantSettings."""
    model = AircraftModel(gtm, aero="quasi-steady", structural_damping=0.01)
    names = {f.name for f in dataclasses.fields(Terms)} | {f.name for f in dataclasses.fields(VariantSettings)}
    # ``aero`` is the aerodynamic coupling built from terms.aero (strip matrices), not a copy of the options
    assert names & set(vars(model)) == {"aero"} and model.aero.options is model.terms.aero
    assert model.structural_damping_ratio == 0.01
    assert AircraftModel(gtm, aero=None).structural_damping_ratio == gtm.structural_damping_ratio


@pytest.mark.parametrize("kw, match", [
    (dict(kind="flying"), "variant = 'flying'"),
    (dict(kind="free", air_density_kg_m3=1.0), "air_density_kg_m3 = 1.0: only for the restrained variant"),
    (dict(kind="restrained", restrained_velocity_m_s=(1.0, math.nan, 0.0)), "restrained_velocity_m_s .* finite"),
    (dict(kind="restrained", restrained_euler_rad=(0.0, 0.1)), "restrained_euler_rad .* 3 entries"),
    (dict(altitude_m=1e6), "1000000"), (dict(altitude_m=True), "altitude_m = True")])
def test_variant_settings_refuse_bad_values(kw, match):
    with pytest.raises(ValueError, match=match):
        VariantSettings(**kw)


def test_variant_given_once(gtm):
    with pytest.raises(ValueError, match="variant and altitude_m: give the variant either"):
        AircraftModel(gtm, variant=VariantSettings("restrained"), altitude_m=100.0)
    with pytest.raises(ValueError, match=r"frozen_q/frozen_xi: must have \d+ and \d+ entries"):
        AircraftModel(gtm, variant="quasi-rigid", frozen_q=(0.0,))


def test_flutter_evaluates_the_models_terms(gtm):
    """The switched finite-state model's quasi-steady flutter point is that of its own quasi-steady sibling
    (same trims, same roots: equal to the last bit) and differs from the default model's (the switches move it by
    about 1e-4 in Mach at 9144 m; Brent's tolerance here is 1e-7); its recorded terms carry the switches."""
    switched = AircraftModel(gtm, terms=Terms(aero=AeroOptions("unsteady"), **SWITCHES))
    own_qs = AircraftModel(gtm, terms=Terms(aero=AeroOptions("quasi-steady"), **SWITCHES))
    default = AircraftModel(gtm, aero="unsteady")
    search = dict(mach_range=RANGE, mach_step=0.05, tol=1e-7)
    a = fs.flutter(switched, CRUISE, "quasi-steady", **search)
    b = fs.flutter(own_qs, CRUISE, "quasi-steady", **search)
    c = fs.flutter(default, CRUISE, "quasi-steady", **search)
    assert a.mach == b.mach and a.frequency_rad_s == b.frequency_rad_s
    assert abs(a.mach - c.mach) > 10 * 1e-7, (a.mach, c.mach)
    assert a.terms["force_resolution"] == "normal" and a.terms["thrust_follows_deflection"] is False
    assert a.terms["engine_angular_momentum"] == [2e5, 0.0, 0.0] and a.terms["aero"]["model"] == "quasi-steady"
    assert c.terms["force_resolution"] == "full"


def test_linear_systems_of_different_terms_differ(gtm, tmp_path):
    """LinearSystem.model records the terms: systems of models that differ only in a term do not compare equal, and
    the record survives a save and load."""
    point = trim(AircraftModel(gtm, aero="quasi-steady"), SteadyManoeuvre.level(3000.0, mach=0.6))
    plain = linear_system(AircraftModel(gtm, aero="quasi-steady"), point)
    switched_model = AircraftModel(gtm, terms=Terms(aero=AeroOptions("quasi-steady"), **SWITCHES))
    switched = linear_system(switched_model, trim(switched_model, SteadyManoeuvre.level(3000.0, mach=0.6)))
    assert plain.model != switched.model and switched.model.terms.force_resolution == "normal"
    back = LinearSystem.load(switched.save(tmp_path / "switched.npz"))
    assert back.model == switched.model
    assert ModelRecord.from_json(switched.model.as_json()) == switched.model
    # a record of the earlier layout (variant name, aero, gravity and density only) reads as those terms
    old = json.loads(plain.model.as_json())
    old.update(variant="free", aero=old["terms"]["aero"], gravity_m_s2=9.80665, aero_density_kg_m3=None)
    del old["terms"]
    assert ModelRecord.from_json(json.dumps(old)) == plain.model


# --------------------------------------------------------------------------- every field of Terms, every analysis
#: One valid value other than the default per field of Terms (a callable: of the aircraft's nq). A field added to
#: Terms without an entry here fails test_every_field_has_a_value.
NON_DEFAULT = {
    "aero": AeroOptions("unsteady", downwash=False),
    "gravity_m_s2": 9.0,
    "structural_damping": 0.02,
    "aero_density_kg_m3": 0.5,
    "compressibility_mach": 0.7,
    "force_resolution": "normal",
    "fin_drag_per_lift": 0.1,
    "thrust_follows_deflection": False,
    "engine_angular_momentum": (2e5, 0.0, 0.0),
    "inertia_q_offset_m": lambda nq: tuple(0.001 * (i + 1) for i in range(nq)),
    "aero_velocity_offset_m_s": (0.0, 0.0, 0.5),
    "aero_terms": tuple(options() for options in aero_term_options()),  # every registered aerodynamic term, switched on
    "nonlinear_beams": NonlinearBeams(4),
}
#: (field, analysis) pairs refused with a message naming the field instead of evaluated, and why: a flutter search
#: trims at the true density (the fixed density of the linearised aerodynamics is the analysis's
#: ``linear_aero_density_kg_m3``, checked below to reach the recorded terms).
REFUSED = {("aero_density_kg_m3", a) for a in ("flutter", "vg", "study")}
#: The geometrically nonlinear beams need every flexible component's chordwise stiffness, which the GTM's file does not
#: give: each analysis refuses the GTM with them by name (the trim and flutter that evaluate them are checked on the
#: HALE in test_nonlinear_beams_reach_trim_and_flutter; every other analysis refuses them on any aircraft).
REFUSED |= {("nonlinear_beams", a) for a in ("trim", "flutter", "vg", "wind_tunnel", "linear_system", "study", "env")}
TERM_FIELDS = [f.name for f in dataclasses.fields(Terms)]


def test_every_field_has_a_value():
    assert set(NON_DEFAULT) == set(TERM_FIELDS), set(TERM_FIELDS) ^ set(NON_DEFAULT)


def _value(name, nq):
    v = NON_DEFAULT[name]
    return v(nq) if callable(v) else v


def _carried(record: dict, name: str, value) -> bool:
    """The recorded terms carry ``value`` of field ``name`` (of ``aero``: every option but the model's name, which
    each analysis chooses)."""
    got = record[name]
    if name == "aero":
        want = {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
        return {k: v for k, v in got.items() if k != "model"} == {k: v for k, v in want.items() if k != "model"}
    if name == "aero_terms":
        return got == [{"term": type(t).__name__, **dataclasses.asdict(t)} for t in value]
    if dataclasses.is_dataclass(value):
        return got == {f.name: getattr(value, f.name) for f in dataclasses.fields(value)}
    return got == (list(value) if isinstance(value, tuple) else value)


@pytest.mark.parametrize("name", TERM_FIELDS)
def test_every_term_reaches_every_analysis(gtm, name):
    import flexsim.envs as envs  # registers the environments

    nq = AircraftModel(gtm, aero=None).structure.dofs.nq
    value = _value(name, nq)
    terms = dataclasses.replace(Terms(), **{name: value})
    model = AircraftModel(gtm, terms=terms)
    assert _carried(model.terms.record(), name, value)
    results = {}
    if (name, "trim") in REFUSED:
        results["trim"] = lambda: trim(model, CRUISE, check_limits=False).terms
        # the linear system's refusal is of the model: give it a trim of the linear sibling
        point = trim(model.replace(**{name: getattr(Terms(), name)}), CRUISE, check_limits=False)
    else:
        point = trim(model, CRUISE, check_limits=False)
        results["trim"] = lambda: point.terms
    results["flutter"] = lambda: fs.flutter(model, CRUISE, "quasi-steady", mach_range=(0.7, 0.95), mach_step=0.05,
                                            tol=1e-3).terms
    results["vg"] = lambda: vg_diagram(model, manoeuvre=CRUISE, models=("QS",), speeds_m_s=(230.0, 240.0),
                                       refine=False).terms["quasi-steady"]
    results["wind_tunnel"] = lambda: wind_tunnel(model, aero_model="quasi-steady", speed_range=(50.0, 60.0), speed_step=10.0,
                                                 divergence=False).terms
    results["linear_system"] = lambda: linear_system(model, point).model.terms.record()
    results["study"] = lambda: run_case(StudyCase("gtm", "QS", 9144.0, mach_min=0.7, mach_max=0.95,
                                                  terms=terms))["model_terms"]
    results["env"] = lambda: envs.LevelHoldEnv(terms=terms).dynamics.model.terms.record()
    for analysis, recorded in results.items():
        if (name, analysis) in REFUSED:
            if analysis == "study":
                assert name in run_case(StudyCase("gtm", "QS", 9144.0, terms=terms))["error"]
            else:
                with pytest.raises(ValueError, match=name):
                    recorded()
            continue
        assert _carried(recorded(), name, value), (analysis, recorded()[name])
    if name == "aero_density_kg_m3":  # the flutter search's own setting of the same term
        fp = fs.flutter(AircraftModel(gtm), CRUISE, "quasi-steady", mach_range=(0.7, 0.95), mach_step=0.05, tol=1e-3,
                        linear_aero_density_kg_m3=value)
        assert fp.terms["aero_density_kg_m3"] == value


def test_nonlinear_beams_reach_trim_and_flutter():
    """A model with the geometrically nonlinear beams (the PHC HALE, which gives every stiffness they need): the trim
    and the flutter search evaluate them and record the element count used, the linear system is the free aircraft's
    about the nonlinear trim; every analysis of the linear structure refuses the model, naming the field."""
    hale = fs.load_aircraft("phc_hale")
    model = AircraftModel(hale, terms=Terms(nonlinear_beams=NonlinearBeams(4)))
    level = SteadyManoeuvre.level(20000.0, speed_m_s=25.0)
    point = trim(model, level)
    assert isinstance(point, fs.FlexibleTrimPoint) and point.terms["nonlinear_beams"] == {"elements_per_beam": 4, "stability": "clamped-wing"}
    assert point.aircraft.structure.beams[0].n_elements == 4
    # the linear sibling's trim is another answer (the HALE's tips: 47 % linear, 50 % nonlinear at 8 elements)
    assert isinstance(trim(model.replace(nonlinear_beams=None), level, check_limits=False), fs.TrimPoint)
    a = 295.07  # speed of sound at 20 km [m/s] (ISA 216.65 K); the scan covers 30-33 m/s around the 4-element point
    fp = fs.flutter(model, level, "unsteady", mach_range=(30.0 / a, 40.0 / a), mach_step=2.5 / a, tol=1e-3)
    assert fp.terms["nonlinear_beams"] == {"elements_per_beam": 4, "stability": "clamped-wing"} and fp.trim.terms == fp.terms
    with pytest.raises(ValueError, match="aero_model = 'theodorsen'.*nonlinear_beams"):
        fs.flutter(model, level)
    with pytest.raises(ValueError, match="classify = True"):
        trim(model, level, classify=True)
    vg = vg_diagram(model, manoeuvre=level, models=("FS",), speeds_m_s=(30.0, 31.0), refine=False)
    assert vg.terms["unsteady"] == fp.terms
    system = linear_system(model, point)  # the free aircraft about the nonlinear trim
    assert system.model.terms.nonlinear_beams == NonlinearBeams(4) and system.x0.size == point.state().size
    for refused in (lambda: vg_diagram(model, manoeuvre=level, models=("QS",)),
                    lambda: wind_tunnel(model, speed_range=(10.0, 20.0)), lambda: fs.simulate(model, point, 1.0),
                    lambda: fs.spectrum(model, np.zeros(model.layout.n_states), np.zeros(4))):
        with pytest.raises(ValueError, match="nonlinear_beams = NonlinearBeams"):
            refused()
