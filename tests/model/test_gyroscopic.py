"""The engines' gyroscopic moment (:mod:`flexsim._kernels.gyroscopic`, ``Terms.engine_angular_momentum``): the closed
form -omega x h_e on the moment rows (Euler's law in body axes, Etkin & Reid 1996 ch. 4), no work done, and nothing else changed."""

from __future__ import annotations

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.model.terms import Terms

H_E = (2.0e4, 0.0, -500.0)  # [kg m^2/s]: two rotors of J ~ 10 kg m^2 at ~1000 rad/s about +x, a little tilted


@pytest.fixture(scope="module")
def models():
    gtm = load_aircraft("gtm")
    aero = AeroOptions("quasi-steady")
    return AircraftModel(gtm, terms=Terms(aero=aero)), AircraftModel(gtm, terms=Terms(aero=aero, engine_angular_momentum=H_E))


def _state(model):
    rng = np.random.default_rng(4)
    x = model.layout.zeros()
    x[model.layout.position] = [0.0, 0.0, -3000.0]
    x[model.layout.velocity] = 0.01 * rng.standard_normal(model.layout.velocity.stop - model.layout.velocity.start)
    x[model.layout.velocity.start] = 190.0
    x[model.layout.velocity.start + 3:model.layout.velocity.start + 6] = [0.1, -0.05, 0.2]  # p, q, r [rad/s]
    return x


def test_closed_form_on_the_moment_rows(models):
    plain, gyro = models
    x, u = _state(plain), np.array([5e4, 0.0, -0.02, 0.0])
    df = gyro.generalized_forces(x, u)[1] - plain.generalized_forces(x, u)[1]
    omega = x[plain.layout.velocity][3:6]
    expected = np.zeros_like(df)
    expected[3:6] = -np.cross(omega, H_E)
    np.testing.assert_allclose(df, expected, rtol=0, atol=1e-9 * np.max(np.abs(expected)))
    # no work: V . Q_gyro = omega . (-omega x h_e) = 0 (the kinetic-energy rate is unchanged)
    assert abs(x[plain.layout.velocity] @ df) <= 1e-12 * np.linalg.norm(x[plain.layout.velocity]) * np.linalg.norm(df)


def test_off_by_default_and_recorded(models):
    plain, gyro = models
    assert plain.terms.engine_angular_momentum is None
    assert gyro.terms.record()["engine_angular_momentum"] == list(H_E)
    with pytest.raises(ValueError, match="engine_angular_momentum .* 3 entries"):
        Terms(engine_angular_momentum=(1.0, 2.0))
