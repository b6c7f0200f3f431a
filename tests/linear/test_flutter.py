"""Eigen-analysis and flutter of the linearised model.

* Goland wing (uniform cantilever; Goland 1945, J. Appl. Mech. 12: flutter 137.2 m/s at 70.7 rad/s,
  the value Patil, Hodges & Cesnik 2001 reproduce with Peters' finite-state aerodynamics) clamped in a
  wind tunnel at sea level, incompressible as Goland's problem (the bundled file sets
  ``compressibility = "none"``): finite-state and Theodorsen p-k flutter speeds and frequencies within 2 %
  (measured 136.2 and 137.0 m/s, 70.0 rad/s; with Prandtl-Glauert 131.6 and 132.3 m/s: tests/linear/test_wind_tunnel.py).
* Theodorsen p-k and finite-state flutter speeds agree within 2 %.
* Mode classification: the GTM in cruise has 8 rigid-body dominated roots (spiral, phugoid, Dutch roll,
  roll, short period, after X, Y, Z, psi are removed); in vacuum every elastic mode has elastic fraction 1.
* Steady manoeuvres that tend to level flight give the level-flight flutter point (R = 1e6 m within
  0.5 %, gamma = 0 exactly).
"""

import math

from dataclasses import replace

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.flutter import FlutterAnalysis, FlutterNotFound, wind_tunnel_flutter
from flexsim.linear.paper_data import TABLE_US
from flexsim.linear.stability import spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre, trim

GOLAND_SPEED, GOLAND_FREQ = 137.2, 70.7


@pytest.fixture(scope="module")
def goland():
    return load_aircraft("goland_wing")


@pytest.mark.parametrize("aero", ["unsteady", "theodorsen"])
def test_goland_wing_flutter_matches_published(goland, aero):
    speed, freq = wind_tunnel_flutter(goland, aero_model=aero, speed_range=(100.0, 180.0), speed_step=10.0)
    assert speed == pytest.approx(GOLAND_SPEED, rel=0.02)
    assert freq == pytest.approx(GOLAND_FREQ, rel=0.02)


def test_theodorsen_pk_and_finite_state_agree(goland):
    fs, _ = wind_tunnel_flutter(goland, aero_model="unsteady", speed_range=(120.0, 150.0), speed_step=10.0)
    pk, _ = wind_tunnel_flutter(goland, aero_model="theodorsen", speed_range=(120.0, 150.0), speed_step=10.0)
    assert pk == pytest.approx(fs, rel=0.02)


def test_quasi_steady_flutters_earlier_than_unsteady(goland):
    # The quasi-steady model has no wake lag and is conservative (typical section: 0.94 vs 2.18 b w_theta).
    qs, _ = wind_tunnel_flutter(goland, aero_model="quasi-steady", speed_range=(10.0, 180.0), speed_step=10.0)
    fs, _ = wind_tunnel_flutter(goland, aero_model="unsteady", speed_range=(100.0, 180.0), speed_step=10.0)
    assert qs < fs


def test_gtm_rigid_body_roots_and_vacuum_classification():
    gtm = load_aircraft("gtm")
    model = AircraftModel(gtm, aero="quasi-steady")
    point = trim(model, SteadyManoeuvre.level(9144.0, mach=0.7))
    spec = spectrum(model, point.x, point.u)
    rigid = spec.of_kind("rigid")
    assert len(rigid) == 8
    assert max(abs(m.eigenvalue) for m in rigid) < 5.0
    phugoid = [m for m in rigid if 0.02 < m.frequency_rad_s < 0.3]
    assert len(phugoid) == 2
    vacuum = AircraftModel(gtm, aero=None, gravity_m_s2=0.0)
    spec0 = spectrum(vacuum, vacuum.pack(), np.zeros(4))
    elastic = [m for m in spec0.modes if m.frequency_rad_s > 1.0]
    assert elastic and all(m.elastic_fraction > 1 - 1e-6 and m.kind == "elastic" for m in elastic)


@pytest.fixture(scope="module")
def sea_level_level_flutter():
    analysis = FlutterAnalysis(load_aircraft("gtm"), "unsteady")
    return analysis, analysis.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.6, 0.7), mach_step=0.05)


def test_wide_turn_and_zero_climb_tend_to_level_flight(sea_level_level_flutter):
    analysis, level = sea_level_level_flutter
    assert level.mode.kind == "elastic"
    # the flutter point's trim is an equilibrium of the raw right-hand side (independent of trim's own residual)
    dx = analysis.qs.rhs(0.0, level.trim.x, level.trim.u)
    assert np.abs(dx[analysis.qs.layout.velocity]).max() < 1e-7
    wide = analysis.search(SteadyManoeuvre.turn(0.0, 1e6, mach=0.6), mach_range=(0.6, 0.7), mach_step=0.05)
    assert wide.mach == pytest.approx(level.mach, rel=0.005)
    flat = analysis.search(SteadyManoeuvre.climb(0.0, 0.0, mach=0.6), mach_range=(0.6, 0.7), mach_step=0.05)
    assert flat.mach == pytest.approx(level.mach, abs=2e-4)


def test_flutter_mode_normalised_as_in_the_paper(sea_level_level_flutter):
    """q_f1 = 1 m when the fuselage's first bending takes part (paper Figs. 11, 16); else the largest = 1."""
    _, level = sea_level_level_flutter
    shape = level.mode_shape
    ref = level.labels.index(level.normalised_by)
    assert shape[ref] == pytest.approx(1.0, abs=1e-12)
    i = level.labels.index("fuselage bending 1")
    if level.normalised_by != "fuselage bending 1":
        # normalised by its largest entry (the mirror-image entry of an antisymmetric mode ties to ~3e-7)
        assert np.abs(shape[6:]).max() == pytest.approx(1.0, rel=1e-6)
        # in level flight the flutter mode of the calibrated GTM is antisymmetric: q_f1 vanishes by symmetry
        assert abs(shape[i]) < 1e-3
        right, left = level.labels.index("right_wing bending 1"), level.labels.index("left_wing bending 1")
        assert abs(shape[right] + shape[left]) < 1e-6 * abs(shape[right])


def test_no_crossing_is_reported_clearly():
    analysis = FlutterAnalysis(load_aircraft("gtm"), "unsteady")
    with pytest.raises(FlutterNotFound, match="no elastic mode crosses the imaginary axis"):
        analysis.search(SteadyManoeuvre.level(9144.0, mach=0.6), mach_range=(0.55, 0.65), mach_step=0.05)
    with pytest.raises(ValueError, match="aero_model = 'wake'"):
        FlutterAnalysis(load_aircraft("gtm"), "wake")


@pytest.mark.parametrize("altitude_m, mach_range", [(0.0, (0.65, 0.75)), (3048.0, (0.7, 0.8))])
def test_calibrated_gtm_us_flutter_within_3_percent_of_table_3(altitude_m, mach_range):
    """Paper Table 3 (US): M_F 0.6742 at 0 m, 0.7433 (34.923 rad/s) at 3048 m; docs/calibration.md.

    The two altitudes the calibration meets (3 % in Mach, 10 % in frequency at 3048 m); 6096 and 9144 m
    are +11.6 % and +17.1 % (documented, not asserted). Finite state and p-k agree within 2 %.
    The calibration was fitted to the paper's aerodynamics, strips only: the bundled file's fuselage and nacelle
    moments and tail downwash (beyond the paper, docs/options.md) are taken out here; with them M_F is
    +0.16 % (0 m) and +0.10 % (3048 m) higher (measured p-k: 0.68579 against 0.68466, 0.76587 against 0.76507).
    """
    paper = {row[0]: row for row in TABLE_US}[altitude_m]
    gtm = load_aircraft("gtm")
    gtm = replace(gtm, aero_settings=replace(gtm.aero_settings, bodies=(), downwash_gradient=0.0))
    pk = FlutterAnalysis(gtm, "theodorsen").search(SteadyManoeuvre.level(altitude_m, mach=0.7), mach_range=mach_range)
    fs = FlutterAnalysis(gtm, "unsteady").search(SteadyManoeuvre.level(altitude_m, mach=0.7), mach_range=mach_range)
    assert pk.mach == pytest.approx(paper[1], rel=0.03)
    assert fs.mach == pytest.approx(pk.mach, rel=0.02)
    if altitude_m > 0.0:  # the paper's sea-level point is another mode (17.8 rad/s)
        assert pk.frequency_rad_s == pytest.approx(paper[2], rel=0.10)


def test_flutter_point_reports_symmetry_and_participation(sea_level_level_flutter):
    """The calibrated GTM's level-flight flutter mode is antisymmetric (the mirror image of its
    motion is minus itself: symmetric energy share 0 to round-off); its participation lists linear [m] and
    angle [deg] coordinates by decreasing magnitude, the normalising coordinate first with magnitude 1, phase 0."""
    _, level = sea_level_level_flutter
    assert level.mode_symmetry == "antisymmetric"
    assert level.symmetric_fraction < 1e-8
    linear = [p for p in level.participation if p.kind == "linear"]
    angles = [p for p in level.participation if p.kind == "angle"]
    assert linear and angles and all(p.unit == "m" for p in linear) and all(p.unit == "deg" for p in angles)
    assert [p.magnitude for p in linear] == sorted((p.magnitude for p in linear), reverse=True) or \
        max(abs(a.magnitude - b.magnitude) for a, b in zip(linear, sorted(linear, key=lambda p: -p.magnitude))) <= 1e-4
    ref = next(p for p in level.participation if p.label == level.normalised_by)
    assert ref.magnitude == pytest.approx(1.0 if ref.unit == "m" else math.degrees(1.0)) and ref.phase_deg == pytest.approx(0.0, abs=1e-9)
    # antisymmetric wing motion: left bending 1 is right bending 1 with opposite sign (phase 180 deg)
    by = {p.label: p for p in level.participation}
    if "right_wing bending 1" in by and "left_wing bending 1" in by:
        assert by["left_wing bending 1"].magnitude == pytest.approx(by["right_wing bending 1"].magnitude, rel=1e-4)
        assert abs(abs(by["left_wing bending 1"].phase_deg - by["right_wing bending 1"].phase_deg) - 180.0) < 1e-3


def test_labels_do_not_flip_between_halves_on_round_off():
    """A symmetric and an antisymmetric wing mode, perturbed by 1e-9 noise 50 times: the same normalising
    coordinate, the same participation order, the same symmetry every time (ties: right half first)."""
    from flexsim.linear.participation import describe_mode
    from flexsim.structure.model import StructuralModel

    st = StructuralModel(load_aircraft("gtm"))
    labels = st.dofs.labels
    rng = np.random.default_rng(1)
    for sign, expected in ((1.0, "antisymmetric"), (-1.0, "symmetric")):
        base = np.zeros(st.dofs.n_v, dtype=complex)
        base[labels.index("right_wing torsion 1")], base[labels.index("left_wing torsion 1")] = 1.0, sign
        base[labels.index("right_wing bending 1")], base[labels.index("left_wing bending 1")] = 0.5j, -sign * 0.5j
        seen = set()
        for _ in range(50):
            noisy = base + 1e-9 * (rng.standard_normal(base.size) + 1j * rng.standard_normal(base.size))
            d = describe_mode(st, noisy, 30j)
            seen.add((labels[d.normalised_by], tuple(p.label for p in d.leading[:2]), d.symmetry))
        assert len(seen) == 1
        (ref, _, sym), = seen
        assert ref == "right_wing torsion 1" and sym == expected


def test_flutter_point_reports_formulation_and_density(sea_level_level_flutter):
    _, level = sea_level_level_flutter
    assert level.formulation == "physical" and not level.aero_density_fixed
    assert level.aero_density_kg_m3 == pytest.approx(1.225, rel=1e-4)  # ISA sea level


def test_linear_density_fixed_at_the_flight_altitude_reproduces_the_default():
    """The replication option is exact when it names the flight's own density."""
    from flexsim.atmosphere import isa_density

    gtm = load_aircraft("gtm")
    man = SteadyManoeuvre.level(6096.0, mach=0.75)
    default = FlutterAnalysis(gtm, "quasi-steady")
    fixed = FlutterAnalysis(gtm, "quasi-steady", linear_aero_density_kg_m3=float(isa_density(6096.0)))
    (p0, s0), (p1, s1) = default.evaluate(man), fixed.evaluate(man)
    assert np.array_equal(p0.x, p1.x)
    assert np.array_equal(np.array([m.eigenvalue for m in s0.modes]), np.array([m.eigenvalue for m in s1.modes]))
    lower = FlutterAnalysis(gtm, "quasi-steady", linear_aero_density_kg_m3=float(isa_density(0.0)))
    p2, s2 = lower.evaluate(man)
    assert np.array_equal(p0.x, p2.x)  # the trim keeps the true density
    assert s2.max_real("elastic") != s0.max_real("elastic")


def test_search_evaluates_each_mach_once_and_returns_an_evaluated_point():
    """Brent's bracket ends come from the grid scan and its root is one of the Mach numbers it evaluated: no Mach
    number is trimmed and analysed twice, and the flutter point is that evaluation (QS, sea level: grid 0.5, 0.55,
    then Brent to 1e-4; the growth rate at M_F is within round-off of the bracket's tolerance times its slope)."""
    analysis = FlutterAnalysis(load_aircraft("gtm"), "quasi-steady")
    calls = []
    evaluate = analysis.evaluate

    def counted(man, guess=None, **options):
        calls.append(man.speed_m_s)
        return evaluate(man, guess, **options)

    analysis.evaluate = counted
    point = analysis.search(SteadyManoeuvre.level(0.0, mach=0.6), mach_range=(0.5, 0.95))
    assert len(calls) == len(set(calls)) == point.evaluations
    assert point.speed_m_s in calls
    assert point.trim.manoeuvre.speed_m_s == point.speed_m_s


def test_shared_trims_give_the_separate_searches_results_bit_for_bit():
    """The QS and US searches of one manoeuvre on one "theodorsen" analysis with a SharedEvaluations (what
    ``flexsim flutter`` runs as one job) return exactly the points of separate QS and US analyses (invariant: the
    shared entries are the trims and linearisations the second search would compute, same inputs bit for bit),
    and the US search reuses the QS scan's points (sea level: QS grid 0.5, 0.55; US grid 0.5-0.7)."""
    from flexsim.linear.flutter import SharedEvaluations

    gtm = load_aircraft("gtm")
    man = SteadyManoeuvre.level(0.0, mach=0.5)
    alone = {m: FlutterAnalysis(gtm, m).search(man, mach_range=(0.5, 0.95)) for m in ("quasi-steady", "theodorsen")}
    analysis = FlutterAnalysis(gtm, "theodorsen")
    shared = SharedEvaluations(analysis)
    together = {m: analysis.search(man, mach_range=(0.5, 0.95), aero_model=m, shared=shared)
                for m in ("quasi-steady", "theodorsen")}
    assert shared.hits >= 4  # trim and linearisation at M 0.5 and 0.55
    for m, point in alone.items():
        other = together[m]
        assert other.aero_model == m and other.evaluations == point.evaluations
        assert (other.mach, other.frequency_rad_s) == (point.mach, point.frequency_rad_s)
        np.testing.assert_array_equal(other.trim.x, point.trim.x)
        np.testing.assert_array_equal(other.mode_shape, point.mode_shape)
    with pytest.raises(ValueError, match="shared: a SharedEvaluations of another FlutterAnalysis"):
        FlutterAnalysis(gtm, "theodorsen").evaluate(man, shared=shared)
    with pytest.raises(ValueError, match="aero_model = 'theodorsen': this analysis \\(quasi-steady\\) has the models of quasi-steady only"):
        FlutterAnalysis(gtm, "quasi-steady").search(man, aero_model="theodorsen")


@pytest.mark.parametrize("kwargs, message", [
    ({"mach_step": 0}, r"mach_step = 0: must be a finite number in \(0, 0.2\] \[-\] \(at most the width of mach_range\)"),
    ({"mach_step": -0.05}, r"mach_step = -0.05: must be a finite number in \(0, 0.2\]"),
    ({"mach_step": float("nan")}, r"mach_step = nan: must be a finite number"),
    ({"mach_step": "0.05"}, r"mach_step = '0.05': must be a number"),
    ({"tol": 0.0}, r"tol = 0.0: must be a finite number in \(0, 0.05\] \[-\] \(at most mach_step\)"),
    ({"mach_range": (0.5,)}, r"mach_range = \(0.5,\): must have shape \(2,\)"),
    ({"mach_range": ("a", "b")}, r"mach_range = \('a', 'b'\): must be an array of numbers"),
])
def test_flutter_scan_settings_are_checked_where_they_enter(goland, kwargs, message):
    """A zero, negative, NaN or non-numeric scan step or tolerance, or a malformed range: refused naming the argument
    (a zero step made numpy divide by zero, a negative one an empty grid and an IndexError)."""
    from flexsim.linear.flutter import flutter
    from flexsim.model.aircraft_model import AircraftModel
    from flexsim.trimming import SteadyManoeuvre

    gtm = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    args = {"mach_range": (0.6, 0.8), "mach_step": 0.05, **kwargs}
    with pytest.raises(ValueError, match=message):
        flutter(gtm, SteadyManoeuvre.level(0.0, mach=0.6), "quasi-steady", **args)


def test_wind_tunnel_settings_are_checked_where_they_enter(goland):
    from flexsim.linear.flutter import wind_tunnel
    from flexsim.model.aircraft_model import AircraftModel

    with pytest.raises(ValueError, match=r"speed_step = 0: must be a finite number in \(0, 50\] \[m/s\]"):
        wind_tunnel(goland, speed_range=(100.0, 150.0), speed_step=0)
    with pytest.raises(ValueError, match=r"speed_range = None: must have shape \(2,\)"):
        wind_tunnel(goland, speed_range=None)
    with pytest.raises(TypeError, match=r"aircraft = .*must be an Aircraft.*load it first"):
        wind_tunnel("goland_wing")  # a name: load it first (a model is accepted: its terms are evaluated)
