"""The batched form of the structural outputs (flexsim.model.sensors.SensorBank) equals the per-component sensors.

``SensorBank.evaluate(X)`` places each component's rows (U_k(L), Psi_k(L), EI(0) U_k''(0)) at its state indices, so
for every state row it is the same dot products as :class:`ComponentSensor`'s methods, summed with zeros in between:
equal to rounding (1e-14 relative seen bound; exact structure: one column per output and component).
"""

import numpy as np

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.sensors import SENSOR_QUANTITIES, SensorBank, structural_sensors


def test_sensor_bank_equals_the_component_sensors():
    model = AircraftModel(load_aircraft("gtm"), aero="quasi-steady")
    sensors = structural_sensors(model)
    names = tuple(sensors)
    n = model.layout.n_states
    bank = SensorBank.of(sensors, names, n)
    x = np.random.default_rng(0).normal(0.0, 1.0, (7, n))
    out = bank.evaluate(x)
    assert out.shape == (7, len(SENSOR_QUANTITIES), len(names))
    for c, name in enumerate(names):
        s = sensors[name]
        for k, method in enumerate((s.tip_deflection_m, s.tip_deflection_rate_m_s, s.tip_twist_rad, s.tip_twist_rate_rad_s,
                                    s.root_bending_moment_n_m)):
            expected = method(x)
            np.testing.assert_allclose(out[:, k, c], expected, rtol=1e-13, atol=1e-13 * (1.0 + np.abs(expected).max()))
            np.testing.assert_allclose(bank.evaluate(x[3:4])[0, k, c], method(x[3]), rtol=1e-13, atol=1e-13 * (1.0 + abs(expected).max()))
    assert not bank.matrix.flags.writeable
