"""Tests of the ISA 1976 atmosphere (flexsim.atmosphere).

Source: U.S. Standard Atmosphere 1976 (NOAA/NASA/USAF), Table I values at geometric altitudes (5 significant
digits) and the layer-base values at 11 km geopotential. Tolerances stated per test.
"""

import math

import numpy as np
import pytest

from flexsim.atmosphere import (
    geometric_altitude,
    geopotential_altitude,
    isa,
    isa_density,
    mach_to_true_airspeed,
    speed_of_sound,
    true_airspeed_to_mach,
)


def test_sea_level():
    """1976 standard sea level: ρ = 1.2250 kg/m³, p = 101325 Pa, T = 288.15 K, a = 340.294 m/s (1e-6 rel)."""
    state = isa(0.0)
    assert state.density == pytest.approx(1.225, rel=1e-6)
    assert state.pressure == pytest.approx(101325.0, rel=1e-12)
    assert state.temperature == pytest.approx(288.15, rel=1e-12)
    assert state.speed_of_sound == pytest.approx(340.294, rel=1e-6)


def test_tropopause_base_geopotential_11km():
    """Layer base at H = 11 km: T = 216.65 K, p = 22632.06 Pa, ρ = 0.363918 kg/m³ (1976 standard; tol 1e-6 rel);
    continuous across the layer boundary (tol 1e-12 rel)."""
    state = isa(11_000.0, geopotential=True)
    assert state.temperature == pytest.approx(216.65, rel=1e-12)
    assert state.pressure == pytest.approx(22632.06, rel=1e-6)
    assert state.density == pytest.approx(0.363918, rel=1e-6)
    below, above = isa(11_000.0 - 1e-7, geopotential=True), isa(11_000.0 + 1e-7, geopotential=True)
    for x, y in zip(below, above):
        assert x == pytest.approx(y, rel=1e-10)


def test_9144_m_geometric_and_geopotential():
    """30 000 ft = 9144 m. Geometric (H = 9130.87 m): ρ = 0.45904, T = 228.80 K; geopotential: ρ = 0.45831,
    T = 228.714 K. Computed from the 1976 standard's defining equations (tol 1e-4 relative). The often
    quoted 0.4583 is the geopotential value."""
    geometric = isa(9144.0)
    assert geometric.density == pytest.approx(0.45904, rel=1e-4)
    assert geometric.temperature == pytest.approx(228.80, rel=1e-4)
    geopotential = isa(9144.0, geopotential=True)
    assert geopotential.density == pytest.approx(0.45831, rel=1e-4)
    assert geopotential.temperature == pytest.approx(228.714, rel=1e-5)


@pytest.mark.parametrize(
    ("z", "temperature", "pressure", "density"),
    [
        (1000.0, 281.651, 8.9876e4, 1.1117),
        (5000.0, 255.676, 5.4048e4, 0.73643),
        (10_000.0, 223.252, 2.6500e4, 0.41351),
        (15_000.0, 216.650, 1.2111e4, 0.19476),
        (20_000.0, 216.650, 5.5293e3, 0.088910),
    ],
)
def test_table_values_geometric(z, temperature, pressure, density):
    """U.S. Standard Atmosphere 1976 Table I (geometric altitude, 5 significant digits): tol 1e-4 relative."""
    state = isa(z)
    assert state.temperature == pytest.approx(temperature, rel=1e-5)
    assert state.pressure == pytest.approx(pressure, rel=1e-4)
    assert state.density == pytest.approx(density, rel=1e-4)


def test_vectorised_equals_scalar():
    """Array input gives the scalar results element-wise (tol 1e-14) and keeps the shape."""
    z = np.array([[0.0, 3000.0, 9144.0], [11_500.0, 15_000.0, 20_000.0]])
    state = isa(z)
    assert state.density.shape == z.shape
    for i, j in np.ndindex(z.shape):
        scalar = isa(float(z[i, j]))
        for vec, sca in zip(state, scalar):
            assert vec[i, j] == pytest.approx(sca, rel=1e-14)
    np.testing.assert_allclose(isa_density(z), state.density, rtol=1e-14)
    np.testing.assert_allclose(speed_of_sound(z), state.speed_of_sound, rtol=1e-14)


def test_scalar_fast_path_returns_python_floats():
    """Scalar (incl. numpy float64) input returns plain floats."""
    assert type(isa_density(np.float64(5000.0))) is float
    assert all(type(x) is float for x in isa(5000))


def test_altitude_conversions_round_trip():
    """H = r0 z/(r0 + z) and its inverse (1976 standard eq. 18); tol 1e-9 m."""
    z = np.array([-4000.0, 0.0, 9144.0, 20_000.0])
    np.testing.assert_allclose(geometric_altitude(geopotential_altitude(z)), z, atol=1e-9)
    assert geopotential_altitude(9144.0) == pytest.approx(9130.8655, abs=1e-3)


def test_mach_true_airspeed():
    """V = M a: Mach 0.8 at 11 km geopotential is 0.8 × 295.0696 m/s (tol 1e-6 rel); round trip exact."""
    v = mach_to_true_airspeed(0.8, 11_000.0, geopotential=True)
    assert v == pytest.approx(0.8 * 295.0696, rel=1e-6)
    mach = np.array([0.3, 0.6, 0.85])
    z = np.array([0.0, 5000.0, 12_000.0])
    np.testing.assert_allclose(true_airspeed_to_mach(mach_to_true_airspeed(mach, z), z), mach, rtol=1e-14)
    assert math.isclose(true_airspeed_to_mach(340.294, 0.0), 1.0, rel_tol=1e-6)


@pytest.mark.parametrize("bad", [-6000.0, 25_000.0, float("nan"), np.array([0.0, -6000.0])])
def test_out_of_range_altitude_raises(bad):
    """Altitudes outside the supported range raise ValueError naming the value and the range."""
    message = r"altitude .* outside the supported ISA range \[-4996\.07, 20063\.12\] m"
    with pytest.raises(ValueError, match=message):
        isa(bad)
    with pytest.raises(ValueError, match="outside the supported ISA range"):
        isa_density(bad)
    with pytest.raises(ValueError, match="outside the supported ISA range"):
        mach_to_true_airspeed(0.5, bad)


def test_error_message_names_the_value():
    """The message contains the offending altitude."""
    with pytest.raises(ValueError, match="-6000.0"):
        isa(-6000.0)
    with pytest.raises(ValueError, match=r"geopotential altitude 20001\.0 m .*\[-5000\.00, 20000\.00\]"):
        isa(20_001.0, geopotential=True)
