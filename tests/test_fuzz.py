"""Fuzz tests: malformed aircraft files and damaged flight logs give a clear flexsim error or
a sane result — never a NaN, never a traceback from inside a library, in bounded time.

Corpus: the 120 aircraft files of :mod:`tests.corpus` (the 117 cases of the reliability review, section
1, plus baselines and an escape-sequence name; the 50 MB files at 3 MB here), random mutations of the
Goland wing drawn by hypothesis, and 40 fixed plus 40 random damages of a flight log.
"""

import math
import time
import tomllib
import warnings
from importlib import resources

import numpy as np
import pytest
from hypothesis import HealthCheck, example, given, settings
from hypothesis import strategies as st

from flexsim.aircraft.toml_loader import load_aircraft, parse_aircraft
from flexsim.errors import FlexsimError
from flexsim.io.flight_log import FlightLogError, FlightLogRecoveryWarning, FlightLogWriter, read_flight_log
from flexsim.structure.model import StructuralModel
from tests.corpus import LogDamage, aircraft_cases, dumps, log_damages

CASE_SECONDS = 10.0  # bound per case (the slowest legal case, the GTM, assembles in ~0.4 s)


def _sane(aircraft) -> None:
    """A loaded aircraft assembles to finite, physical mass properties and clamped frequencies."""
    model = StructuralModel(aircraft)
    mp = model.mass_properties
    assert math.isfinite(mp.mass_kg) and mp.mass_kg > 0
    assert np.all(np.isfinite(mp.cg_m)) and np.linalg.eigvalsh(mp.inertia_cg_kg_m2).min() > 0


@pytest.fixture(scope="module")
def corpus_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("corpus")
    cases = aircraft_cases(big=False)
    for c in cases:
        if c.content is not None:
            (d / f"{c.id}.toml").write_bytes(c.content)
    return d, cases


def test_aircraft_corpus_clear_error_or_sane_result(corpus_dir):
    d, cases = corpus_dir
    assert len(cases) >= 117
    wrong = []
    for c in cases:
        path = d / (c.path if c.path is not None else f"{c.id}.toml")
        t0 = time.monotonic()
        try:
            _sane(load_aircraft(str(path)))
            outcome = "ok"
        except (FlexsimError, FileNotFoundError) as exc:
            outcome = "error"
            message = str(exc)
            assert message and "Traceback" not in message
        elapsed = time.monotonic() - t0
        assert elapsed < CASE_SECONDS, f"{c.id}: {elapsed:.1f} s"
        if outcome != c.expect:
            wrong.append((c.id, c.expect, outcome))
    assert not wrong


_GOLAND = tomllib.loads((resources.files("flexsim.aircraft") / "data" / "goland_wing.toml").read_text())
_LEAVES = [("components", "right_wing", "length_m"), ("components", "right_wing", "euler_deg", 2),
           ("components", "right_wing", "root_m", 0), ("components", "right_wing", "bending_modes"),
           ("components", "right_wing", "aero", "strips"), ("components", "right_wing", "control_surface", "hinge_fraction"),
           ("components", "right_wing", "control_surface", "end_m"), ("structural_damping_ratio",)] + [
    ("components", "right_wing", "sections", key, i) for key in ("station_m", "mass_kg_per_m", "cg_offset_m",
                                                                  "torsional_inertia_kg_m", "ei_nm2", "gj_nm2", "chord_m", "ea_fraction")
    for i in (0, 1)]
_VALUES = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.floats(min_value=-1e3, max_value=1e8),
    st.integers(min_value=-10**6, max_value=10**6),
    st.sampled_from([0.0, -0.0, 1e-300, 1e300, True, "1.0", [1.0]]),
)


def _mutate(doc, leaf, value):
    node = doc
    for key in leaf[:-1]:
        node = node[key]
    node[leaf[-1]] = value


# derandomize: the suite must give the same verdict on every run (CI); the example below is a case a random run found
# (a cg offset of 2.2e153 m overflowed m e^2 before the one-chord check rejected it).
@settings(max_examples=150, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(edits=st.lists(st.tuples(st.sampled_from(_LEAVES), _VALUES), min_size=1, max_size=3))
@example(edits=[(("components", "right_wing", "sections", "cg_offset_m", 0), 2.2e153)])
def test_random_goland_mutations_clear_error_or_sane(edits):
    import copy

    doc = copy.deepcopy(_GOLAND)
    for leaf, value in edits:
        _mutate(doc, leaf, value)
    t0 = time.monotonic()
    try:
        _sane(parse_aircraft(dumps(doc), source="fuzz.toml"))
    except FlexsimError as exc:
        assert str(exc).startswith("fuzz.toml: ")
    assert time.monotonic() - t0 < CASE_SECONDS


STATE_NAMES, CONTROL_NAMES, SIGNAL_NAMES = (["v_x_m_s", "q_right_wing_1_m", "xi_right_wing_1_rad"],
                                           ["thrust_N", "aileron_rad", "elevator_rad", "rudder_rad"], ["airspeed_m_s"])
TOPOLOGY = {"right_wing": 4, "fuselage": 3}


@pytest.fixture(scope="module")
def reference_log(tmp_path_factory):
    """A finished log of 300 samples with chunks flushed every 0.1 s of simulated time."""
    path = tmp_path_factory.mktemp("log") / "ref.mcap"
    rng = np.random.default_rng(0)
    with FlightLogWriter(path, state_names=STATE_NAMES, control_names=CONTROL_NAMES, signal_names=SIGNAL_NAMES,
                         structure_topology=TOPOLOGY, flush_interval_s=0.1) as w:
        for k in range(300):
            w.write(k * 0.01, position_m=rng.normal(size=3), euler_rad=rng.normal(size=3), state=rng.normal(size=3),
                    controls=rng.normal(size=4), signals=rng.normal(size=1),
                    structure={n: rng.normal(size=(m, 3)) for n, m in TOPOLOGY.items()})
        w.event(3.0, "done")
    return path, read_flight_log(path)


def _check_damaged(tmp_path, ref_path, ref, damage: LogDamage) -> str:
    data = ref_path.read_bytes()
    bad = damage.apply(data)
    path = tmp_path / "bad.mcap"
    path.write_bytes(bad)
    t0 = time.monotonic()
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            log = read_flight_log(path)
    except FlightLogError as exc:
        assert str(exc).startswith(str(path))
        return "error"
    assert time.monotonic() - t0 < CASE_SECONDS
    flagged = (not log.complete) and any(issubclass(w.category, FlightLogRecoveryWarning) for w in caught)
    assert flagged or bad == data, f"{damage}: damaged log read as complete"
    assert log.complete == (not log.damage and log.complete)
    # whatever was recovered is exactly what was written, at the same times
    idx = np.searchsorted(ref.t, log.t)
    assert np.all(ref.t[idx] == log.t)
    for name in ("state", "controls", "signals", "position_m", "euler_rad"):
        np.testing.assert_array_equal(getattr(log, name), getattr(ref, name)[idx])
    return "flagged" if flagged else "intact"


def test_fixed_log_damages_are_flagged_and_never_alter_values(tmp_path, reference_log):
    ref_path, ref = reference_log
    outcomes = [_check_damaged(tmp_path, ref_path, ref, d) for d in log_damages(40)]
    assert outcomes.count("intact") == 0


@settings(max_examples=40, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(kind=st.sampled_from(["truncate", "flip_byte", "zero_block", "random_block"]),
       fraction=st.floats(min_value=0.0, max_value=1.0), seed=st.integers(0, 2**30))
def test_random_log_damages(tmp_path, reference_log, kind, fraction, seed):
    ref_path, ref = reference_log
    _check_damaged(tmp_path, ref_path, ref, LogDamage(kind, fraction, seed))
