"""Flutter scans that cannot miss an instability between their points, nor depend on where their range starts.

* :func:`flexsim.linear.flutter.hidden_crossing` (step control, linear-interpolation error bound
  max|g''| h^2 / 8, Dahlquist & Bjorck 2008, eq. 4.2.11): a growth rate that rises above zero and falls back
  between two scan points (a parabola g(x) = 0.05 - (x - 10.3)^2, unstable over 10.08 < x < 10.52, narrower than
  the 1.0 step) is found, its bracket holds a sign change; a growth rate that stays below zero (g = -1 - x^2/100)
  is accepted without any extra evaluation (the bound proves the interval stable).
* :func:`flexsim.linear.flutter.anchored_grid`: the scan points above the lower end are the multiples of the step
  whatever the lower end (a set identity, exact).
* :func:`flexsim.linear.stability.conjugate_slots`: the eigenvalues of a real matrix with two equal complex pairs
  (block diagonal of two equal 2x2 blocks, as the two halves of a clamped wing) get distinct conjugate partners
  (a nearest-conjugate rule gives both the same one and leaves a quasi-steady root in the p-k spectrum).
* A HALE aircraft (Patil, Hodges & Cesnik 2001 wing, written in tests/linear/hale_like.py) in the wind tunnel at
  20 km: the p-k ("US") flutter speed is the same for the lower ends 0.5, 5 and 8 m/s of the range (to the
  Brent tolerance 1e-3 m/s), and its spectrum is closed under conjugation at every scan point (an invariant of a
  real system); in level flight at 20 km its flutter Mach is the same for those lower ends too.
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.flutter import anchored_grid, hidden_crossing, wind_tunnel
from flexsim.linear.stability import conjugate_slots, spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from tests.linear.hale_like import write_hale


def test_a_narrow_instability_between_scan_points_is_found():
    calls = []

    def g(x):
        calls.append(x)
        return 0.05 - (x - 10.3) ** 2

    xs = [8.0, 9.0, 10.0, 11.0, 12.0]
    points = [(x, g(x)) for x in xs]
    assert all(v <= 0 for _, v in points)  # every scan point stable: a plain scan misses it
    a, b = hidden_crossing(g, points, min_step=1.0 / 16)
    assert g(a) <= 0.0 < g(b) and 10.0 <= a < b <= 10.52
    assert 10.3 - 0.05 ** 0.5 <= b  # the bracket holds the lower crossing at 10.08


def test_a_stable_growth_rate_costs_no_extra_evaluation():
    calls = []

    def g(x):
        calls.append(x)
        return -1.0 - x * x / 100.0

    points = [(x, -1.0 - x * x / 100.0) for x in np.arange(0.0, 10.5, 1.0)]
    assert hidden_crossing(g, points, min_step=1.0 / 16) is None
    assert calls == []


@pytest.mark.parametrize("lo", [0.5, 5.0, 8.0])
def test_anchored_grid_is_the_same_above_the_lower_end(lo):
    grid = anchored_grid(lo, 60.0, 5.0)
    assert grid[0] == lo and grid[-1] == 60.0
    assert set(grid[1:-1]) == {5.0 * k for k in range(1, 12) if 5.0 * k > lo}


def test_conjugate_partners_are_distinct_for_equal_pairs():
    block = np.array([[0.1, 30.0], [-30.0, 0.1]])
    a = np.zeros((6, 6))
    a[:2, :2] = a[2:4, 2:4] = block
    a[4:, 4:] = [[-1.0, 2.0], [-2.0, -1.0]]
    vals = np.linalg.eigvals(a)
    track = np.flatnonzero(vals.imag > 0.5)
    slots = conjugate_slots(vals, track)
    assert len(set(slots.tolist())) == track.size and not set(slots.tolist()) & set(track.tolist())
    np.testing.assert_allclose(vals[slots], np.conj(vals[track]), rtol=0, atol=1e-12)


@pytest.fixture(scope="module")
def hale(tmp_path_factory):
    return load_aircraft(write_hale(tmp_path_factory.mktemp("hale")))


def test_hale_wind_tunnel_flutter_does_not_depend_on_the_lower_end(hale):
    speeds = [wind_tunnel(hale, aero_model="theodorsen", speed_range=(lo, 60.0), altitude_m=20000.0,
                          divergence=False).flutter_speed_m_s for lo in (0.5, 5.0, 8.0)]
    assert all(s is not None for s in speeds)
    assert max(speeds) - min(speeds) <= 2e-3  # twice the Brent tolerance tol_m_s = 1e-3


@pytest.mark.parametrize("speed", [10.0, 36.0, 46.0])
def test_hale_pk_spectrum_is_closed_under_conjugation(hale, speed):
    def at(name):
        return AircraftModel(hale, variant="restrained", gravity_m_s2=0.0, altitude_m=20000.0,
                             aero=AeroOptions(name), restrained_velocity_m_s=[speed, 0.0, 0.0])

    qs = at("quasi-steady")
    spec = spectrum(qs, qs.layout.zeros(), np.zeros(4), aero_model="theodorsen", pk_model=at("unsteady"))
    vals = np.sort_complex(np.array([m.eigenvalue for m in spec.modes]))
    conj = np.sort_complex(np.conj(vals))
    np.testing.assert_allclose(vals, conj, rtol=0, atol=1e-9 * np.abs(vals).max())


def test_hale_flight_flutter_does_not_depend_on_the_lower_end(hale):
    """Level flight at 20 km, p-k: the lower ends 0.5, 5 and 8 m/s (below 1 m/s no manoeuvre is defined, and the
    slowest speeds cannot be trimmed: both are skipped, not an error) give the same flutter Mach to twice the Brent
    tolerance (1e-4 in Mach), each with the step flexsim flutter uses (scan_step of the range)."""
    from flexsim.atmosphere import speed_of_sound
    from flexsim.linear.flutter import FlutterAnalysis, scan_step
    from flexsim.trimming import SteadyManoeuvre

    a = speed_of_sound(20000.0)
    analysis = FlutterAnalysis(hale, "theodorsen")
    machs = []
    for lo in (0.5, 5.0, 8.0):
        rng = (lo / a, 60.0 / a)
        machs.append(analysis.search(SteadyManoeuvre.level(20000.0, mach=0.1), mach_range=rng, mach_step=scan_step(rng)).mach)
    assert max(machs) - min(machs) <= 2e-4
