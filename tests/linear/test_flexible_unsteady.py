"""The free aircraft with nonlinear beams and Peters' unsteady strips, linearised about the nonlinear trim
(flexsim.linear.flexible_unsteady), against its two neighbours (HALE at 20 km, 25 m/s, 8 elements per wing):

* slow motion: the phugoid equals the quasi-steady free aircraft's (``free_aircraft_spectrum``): at its frequency,
  0.31 rad/s, the reduced frequency is ~0.006 and the wake's lag is negligible. Measured -0.0503 +- 0.3124j against
  -0.0502 +- 0.3113j; tolerances 2 % in damping, 1 % in frequency.
* the wing's torsion band (35-50 rad/s): the quasi-steady strips make the torsion roots unstable (as the linear
  model's quasi-steady roots are); with the wake they are damped, and the least damped one is near the clamped wing's
  (``wing_system``: the same Peters strips on one wing clamped at its trimmed root; the free aircraft adds the
  rigid-body and the other wing's coupling). Measured -0.882 at 40.73 rad/s against -0.852 at 39.89 rad/s;
  tolerances 15 % in damping and 5 % in frequency.
* about a pull-up and a turn the same neighbours hold (the rotation's terms included).
"""

from __future__ import annotations

import numpy as np
import pytest

import flexsim as fs
from flexsim.linear.flexible_flutter import wing_system
from flexsim.linear.flexible_stability import free_aircraft_spectrum
from flexsim.linear.flexible_unsteady import free_aircraft_unsteady
from flexsim.trimming.flexible_trim import trim_flexible


@pytest.fixture(scope="module")
def hale():
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    point = trim_flexible(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0), elements_per_beam=8)
    return model, point, free_aircraft_unsteady(model, point).eigenvalues


def test_phugoid_is_the_quasi_steady_one(hale):
    model, point, roots = hale
    quasi = free_aircraft_spectrum(model, point).phugoid[0]
    near = roots[np.argmin(np.abs(roots - quasi))]
    assert near.real == pytest.approx(quasi.real, rel=0.02)
    assert abs(near.imag) == pytest.approx(abs(quasi.imag), rel=0.01)


def test_torsion_band_damped_as_the_clamped_wing(hale):
    model, point, roots = hale
    band = lambda lam: lam[(lam.imag > 35.0) & (lam.imag < 50.0)]  # noqa: E731
    quasi = band(free_aircraft_spectrum(model, point).eigenvalues)
    free = band(roots)
    clamped = band(np.linalg.eigvals(wing_system(model, point, "right_wing", 6).state_matrix))
    assert quasi.real.max() > 0.0 and free.real.max() < 0.0
    least, least_clamped = free[np.argmax(free.real)], clamped[np.argmax(clamped.real)]
    assert least.real == pytest.approx(least_clamped.real, rel=0.15)
    assert least.imag == pytest.approx(least_clamped.imag, rel=0.05)


def test_free_hale_has_no_oscillatory_instability_to_42_m_s():
    """docs/flutter.md: the free HALE with Peters' strips in level flight (8 elements) has no unstable oscillatory root
    up to 42.5 m/s (its least damped one, the Dutch roll, at -0.0379 +- 1.563j there); its first instability is
    aperiodic, a real root of the split phugoid, between 35 and 36.25 m/s (+0.0344 1/s at 36.25 m/s) — where the
    wing clamped at its trimmed root flutters at 37.31 m/s, 2.41 rad/s."""
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    guess = None
    found = {}
    for speed in (35.0, 36.25, 42.5):
        guess = trim_flexible(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=speed), elements_per_beam=8,
                              guess=guess, check_limits=False)
        modes = [m for m in free_aircraft_unsteady(model, guess).spectrum().modes
                 if m.kind != "neutral" and abs(m.eigenvalue) < 200.0]
        found[speed] = ([m for m in modes if m.eigenvalue.real > 0.0],
                        max((m for m in modes if m.eigenvalue.imag > 0.5), key=lambda m: m.eigenvalue.real))
    assert not found[35.0][0]
    assert [m.name for m in found[36.25][0]] == ["phugoid"] and found[36.25][0][0].eigenvalue.imag == 0.0
    assert found[42.5][1].eigenvalue.real < 0.0
    print({v: (len(u), o.name, complex(o.eigenvalue)) for v, (u, o) in found.items()})


@pytest.mark.parametrize("manoeuvre", [fs.SteadyManoeuvre.pull_up(20000.0, 1.1, speed_m_s=25.0),
                                       fs.SteadyManoeuvre.turn(20000.0, 1000.0, speed_m_s=25.0)])
def test_rotating_trims_keep_the_neighbours(manoeuvre):
    """About a pull-up and a turn (body rates ω0: each strip's air velocity −(v + ω0 × p) and the rotation's terms in
    ẇ) the same two checks hold: phugoid at the quasi-steady one (measured 1.3 % and 0.4 % in the pull-up, 0.2 % and
    0.35 % in the turn; tolerances 3 % and 1 %) and the torsion band's least damped root near the clamped wing's
    (pull-up -0.835 at 40.08 against -0.806 at 39.16 rad/s; turn -0.880 at 40.71 against -0.879 at 40.06); the turn's
    verdict is stable (its heading root, ±0.0125j, has a real part of round-off)."""
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    point = trim_flexible(model, manoeuvre, elements_per_beam=8)
    spectrum = free_aircraft_unsteady(model, point).spectrum()
    quasi = free_aircraft_spectrum(model, point)
    oscillating = [z for z in quasi.phugoid if z.imag > 0.0]
    near = spectrum.eigenvalues[np.argmin(np.abs(spectrum.eigenvalues - oscillating[0]))]
    assert near.real == pytest.approx(oscillating[0].real, rel=0.03)
    assert near.imag == pytest.approx(oscillating[0].imag, rel=0.01)
    band = lambda lam: lam[(lam.imag > 35.0) & (lam.imag < 50.0)]  # noqa: E731
    free = band(spectrum.eigenvalues)
    clamped = band(np.linalg.eigvals(wing_system(model, point, "right_wing", 6).state_matrix))
    least, least_clamped = free[np.argmax(free.real)], clamped[np.argmax(clamped.real)]
    assert least.real == pytest.approx(least_clamped.real, rel=0.15)
    assert least.imag == pytest.approx(least_clamped.imag, rel=0.05)
    assert spectrum.verdict().startswith("stable")


def test_free_hale_in_a_pull_up_is_stable_where_the_clamped_wing_flutters():
    """docs/flutter.md: in the n = 1.3 pull-up the wing clamped at its trimmed root flutters at 34.72 m/s (the load
    factor table); the free HALE with Peters' strips about the same trims is stable at 35 and at 42.5 m/s (a scan in
    1.25 m/s steps found no unstable root from 32.5 to 42.5 m/s at n = 1.2 and 1.3, and at n = 1.1 only the split
    phugoid's real root from 36.25 m/s, +0.0072 1/s)."""
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    guess = None
    for speed in (32.5, 35.0, 37.5, 40.0, 42.5):
        guess = trim_flexible(model, fs.SteadyManoeuvre.pull_up(20000.0, 1.3, speed_m_s=speed), elements_per_beam=8,
                              guess=guess)
        if speed in (35.0, 42.5):
            assert free_aircraft_unsteady(model, guess).spectrum().verdict().startswith("stable"), speed
