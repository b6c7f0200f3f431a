"""Disturbances against closed forms.

Sources and tolerances:
* 1-cos gust, CS-25.341(a): U(s) = (U_ds/2)(1 - cos(pi s/H)) on 0 <= s <= 2H, zero outside; MIL-F-8785C
  3.7.3 (persistent) stays at U_ds after H. Exact to 1e-12.
* Dryden spectra, MIL-F-8785C 3.7.2.2: each one-sided spectrum integrates to sigma^2 (quadrature, 1e-6);
  the low-altitude scale lengths and intensities of MIL-F-8785C 3.7.2.3 and the Figure 7 intensity at
  30 000 ft (1e-12).
* Generated Dryden field: the variance of one realisation is sum_k (a_k^2 + b_k^2)/2 with a_k, b_k ~
  N(0, Phi_k dW), so its mean is sum Phi_k dW (the integral of Phi over the band the grid resolves, 1e-3;
  ~1 % below sigma^2 for L = 20 spacings) and its standard deviation sqrt(sum (Phi_k dW)^2); the test
  allows 4 of those (~1.5 %). The Welch spectrum averaged over
  the band 0.1/L < W < 3/L agrees with Phi to 10 % (64 segments: ~3 % scatter per averaged band).
* Seeded generation: the same seed gives identical fields, another seed a different one.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.signal import welch

from flexsim.sim.disturbances import (
    DrydenTurbulence,
    OneMinusCosineGust,
    combine,
    dryden_spectrum,
    mil_f_8785c_turbulence,
)

FT = 0.3048


def test_one_minus_cosine_profile_matches_closed_form():
    gust = OneMinusCosineGust(8.0, 30.0, direction_ned=[0, 0, -2.0], normal_ned=[1, 0, 0], front_position_ned_m=[100.0, 0, 0])
    s = np.array([-5.0, 0.0, 7.5, 15.0, 30.0, 45.0, 60.0, 60.001, 200.0])
    positions = np.column_stack([100.0 + s, np.full(s.size, 3.0), np.full(s.size, -9144.0)])
    wind = gust(0.0, positions)
    expected = np.where((s >= 0) & (s <= 60.0), 4.0 * (1 - np.cos(np.pi * s / 30.0)), 0.0)
    np.testing.assert_allclose(wind[:, 2], -expected, atol=1e-12)  # up-gust: NED z negative
    np.testing.assert_allclose(wind[:, :2], 0.0, atol=1e-15)
    assert wind[4, 2] == pytest.approx(-8.0, abs=1e-12)  # peak U_ds at s = H
    # independent of time; lateral offsets along the front do not matter
    np.testing.assert_array_equal(gust(123.0, positions), wind)


def test_persistent_gust_stays_at_its_peak():
    gust = OneMinusCosineGust(5.0, 20.0, persistent=True)
    s = np.array([-1.0, 10.0, 20.0, 21.0, 500.0])
    u = gust.profile(s)
    np.testing.assert_allclose(u, [0.0, 2.5, 5.0, 5.0, 5.0], atol=1e-12)


def test_encounter_puts_the_front_where_a_straight_flight_meets_it_at_start_time():
    pos, vel, t0 = np.array([10.0, -5.0, -9000.0]), np.array([200.0, 50.0, -3.0]), 1.5
    gust = OneMinusCosineGust.encounter(6.0, 40.0, position_ned_m=pos, velocity_ned_m_s=vel, start_time_s=t0)
    speed = np.linalg.norm(vel)
    for t in (1.0, 1.5, 1.6, 1.5 + 40.0 / speed, 1.5 + 80.0 / speed, 3.0):
        s = speed * (t - t0)
        expected = 3.0 * (1 - math.cos(math.pi * s / 40.0)) if 0 <= s <= 80.0 + 1e-9 else 0.0
        assert -gust(t, (pos + vel * t)[None, :])[0, 2] == pytest.approx(expected, abs=1e-9)


@pytest.mark.parametrize("kwargs, match", [
    ({"amplitude_m_s": math.nan, "gradient_length_m": 30.0}, "amplitude_m_s"),
    ({"amplitude_m_s": 5.0, "gradient_length_m": 0.0}, r"gradient_length_m = 0.0: must be a finite number > 0"),
    ({"amplitude_m_s": 5.0, "gradient_length_m": 30.0, "direction_ned": [0, 0, 0]}, "direction_ned .* non-zero"),
    ({"amplitude_m_s": 5.0, "gradient_length_m": 30.0, "normal_ned": [1, 0]}, "normal_ned .* 3 finite numbers"),
])
def test_gust_rejects_bad_parameters(kwargs, match):
    with pytest.raises(ValueError, match=match):
        OneMinusCosineGust(**kwargs)


def test_gust_rejects_badly_shaped_positions_and_zero_velocity():
    with pytest.raises(ValueError, match=r"positions_ned_m: expected shape \(k, 3\)"):
        OneMinusCosineGust(5.0, 30.0)(0.0, np.zeros(3))
    with pytest.raises(ValueError, match="velocity_ned_m_s .* non-zero"):
        OneMinusCosineGust.encounter(5.0, 30.0, position_ned_m=[0, 0, 0], velocity_ned_m_s=[0, 0, 0], start_time_s=0.0)


@pytest.mark.parametrize("component", ["u", "v", "w"])
def test_dryden_spectra_integrate_to_the_variance(component):
    sigma, length = 1.7, 250.0
    total, _ = quad(lambda w: dryden_spectrum(component, w, sigma, length), 0.0, np.inf, limit=200)
    assert total == pytest.approx(sigma**2, rel=1e-6)


def test_mil_f_8785c_intensities_and_scale_lengths():
    h_ft = 500.0
    sigma, length = mil_f_8785c_turbulence(h_ft * FT, "moderate")
    k = 0.177 + 0.000823 * h_ft
    sigma_w = 0.1 * 30.0 * 0.514444  # 0.1 W20, W20 = 30 kt [m/s]
    np.testing.assert_allclose(sigma, [sigma_w / k**0.4, sigma_w / k**0.4, sigma_w], rtol=1e-12)
    np.testing.assert_allclose(length, np.array([h_ft / k**1.2, h_ft / k**1.2, h_ft]) * FT, rtol=1e-12)
    sigma, length = mil_f_8785c_turbulence(30000.0 * FT, "moderate")  # Figure 7, 1e-3: 6.6 (25 kft), 5.0 (35 kft)
    np.testing.assert_allclose(sigma, 5.8 * FT, rtol=1e-12)
    np.testing.assert_allclose(length, 1750.0 * FT, rtol=1e-12)
    with pytest.raises(ValueError, match="severity = 'extreme'"):
        mil_f_8785c_turbulence(1000.0, "extreme")
    with pytest.raises(ValueError, match=r"altitude_m = 30000.0: must be in"):
        mil_f_8785c_turbulence(30000.0)


@pytest.fixture(scope="module")
def long_field():
    return DrydenTurbulence([1.0, 1.5, 2.0], [10.0, 20.0, 15.0], seed=7, spacing_m=0.5, n_points=2**19)


def test_dryden_field_variance_matches_the_spectrum(long_field):
    f = long_field
    expected = f.variance_on_grid()
    d_omega = 2 * np.pi / f.period_m
    for i, comp in enumerate("uvw"):  # the grid resolves the band d_omega/2 .. pi/spacing (~1 % of sigma^2 cut)
        band, _ = quad(lambda w: dryden_spectrum(comp, w, f.sigma_m_s[i], f.length_m[i]), d_omega / 2,
                       np.pi / f.spacing_m - d_omega / 2, limit=500)
        assert expected[i] == pytest.approx(band, rel=1e-3)
        assert expected[i] == pytest.approx(f.sigma_m_s[i] ** 2, rel=0.015)
    omega = d_omega * np.arange(1, f.n_points // 2)
    values = f.along_track(np.arange(f.n_points) * f.spacing_m)
    for i, comp in enumerate("uvw"):
        std_of_variance = np.sqrt(np.sum((dryden_spectrum(comp, omega, f.sigma_m_s[i], f.length_m[i]) * d_omega) ** 2))
        assert abs(values[:, i].var() - expected[i]) < 4 * std_of_variance
        assert abs(values[:, i].mean()) < 1e-12


def test_dryden_field_spectrum_matches_the_dryden_spectrum(long_field):
    f = long_field
    values = f.along_track(np.arange(f.n_points) * f.spacing_m)
    for i, comp in enumerate("uvw"):
        freq, psd = welch(values[:, i], fs=1.0 / f.spacing_m, nperseg=f.n_points // 64)  # per cycle/m
        omega = 2 * np.pi * freq
        band = (omega > 0.1 / f.length_m[i]) & (omega < 3.0 / f.length_m[i])
        measured = psd[band] / (2 * np.pi)  # per rad/m
        assert np.mean(measured / dryden_spectrum(comp, omega[band], f.sigma_m_s[i], f.length_m[i])) == pytest.approx(1.0, abs=0.1)


def test_dryden_is_reproducible_by_seed_and_frozen_along_the_track():
    a = DrydenTurbulence([1.0, 1.0, 1.0], [100.0, 100.0, 100.0], seed=3, heading_rad=math.radians(30), n_points=2**12, spacing_m=2.0)
    b = DrydenTurbulence([1.0, 1.0, 1.0], [100.0, 100.0, 100.0], seed=3, heading_rad=math.radians(30), n_points=2**12, spacing_m=2.0)
    c = DrydenTurbulence([1.0, 1.0, 1.0], [100.0, 100.0, 100.0], seed=4, heading_rad=math.radians(30), n_points=2**12, spacing_m=2.0)
    rng = np.random.default_rng(0)
    p = rng.uniform(-3000, 3000, size=(50, 3))
    np.testing.assert_array_equal(a(0.0, p), b(5.0, p))
    assert np.abs(a(0.0, p) - c(0.0, p)).max() > 0.1
    d = np.array([math.cos(math.radians(30)), math.sin(math.radians(30)), 0.0])
    across = np.array([-d[1], d[0], 0.0])
    # moving across the flight direction or vertically does not change the field; along it, it is the track
    np.testing.assert_allclose(a(0.0, p + 37.0 * across + [0, 0, 12.0]), a(0.0, p), atol=1e-12)
    xi = p @ d
    track = a.along_track(xi)
    np.testing.assert_allclose(a(0.0, p), track[:, 0:1] * d + track[:, 1:2] * across + track[:, 2:3] * [0, 0, 1], atol=1e-12)
    # periodic with the grid's period
    np.testing.assert_allclose(a.along_track(xi + a.period_m), track, atol=1e-9)


@pytest.mark.parametrize("kwargs, match", [
    ({"sigma_m_s": [1, 1, -1]}, r"sigma_m_s .* >= 0"),
    ({"length_m": [100, 0, 100]}, r"length_m .* > 0"),
    ({"seed": -1}, "seed = -1"),
    ({"spacing_m": 30.0}, r"spacing_m = 30.0: must be <= min\(length_m\) / 4"),
    ({"n_points": 3000}, "n_points = 3000: must be a power of 2"),
    ({"n_points": 1024, "spacing_m": 1.0}, "the period must be >= 20 max"),
])
def test_dryden_rejects_bad_parameters(kwargs, match):
    base = {"sigma_m_s": [1, 1, 1], "length_m": [100, 100, 100]}
    with pytest.raises(ValueError, match=match):
        DrydenTurbulence(**{**base, **kwargs})


def test_combine_adds_wind_fields():
    gust = OneMinusCosineGust(4.0, 10.0)
    turb = DrydenTurbulence([1, 1, 1], [50, 50, 50], seed=1, n_points=2**12)
    p = np.array([[10.0, 0.0, 0.0], [500.0, 3.0, -2.0]])
    np.testing.assert_allclose(combine(gust, turb)(0.0, p), gust(0.0, p) + turb(0.0, p), atol=1e-15)
    with pytest.raises(ValueError, match="not a callable"):
        combine(gust, 3.0)
