"""Time domain and eigen-analysis agree.

The Goland wing clamped in a wind tunnel (finite-state aerodynamics, flutter at 136.2 m/s in our
model) is started on the real part of the eigenvector of its least-stable elastic mode, below (110 m/s)
and above (150 m/s) the flutter speed, and simulated with the nonlinear model. A damped sinusoid
y = A exp(sigma t) cos(omega t + phase) fitted to the tip deflection gives the growth rate and
frequency, which must equal the eigenvalue's real and imaginary parts within 5 % (measured: agreement to
~1e-8, the nonlinear terms being negligible at 1 mm amplitude).
"""

import numpy as np
import pytest
from scipy.optimize import curve_fit

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.stability import spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.simulate import simulate, IntegratorSettings
from flexsim.sim.run_settings import OutputSettings


@pytest.mark.parametrize("speed", [110.0, 150.0], ids=["below flutter", "above flutter"])
def test_perturbation_follows_the_dominant_eigenvalue(speed):
    model = AircraftModel(load_aircraft("goland_wing"), variant="restrained", aero="unsteady", gravity_m_s2=0.0,
                          restrained_velocity_m_s=[speed, 0.0, 0.0], altitude_m=0.0)
    x_eq = model.layout.zeros()
    spec = spectrum(model, x_eq, np.zeros(4))
    mode = spec.critical("elastic")
    lam = mode.eigenvalue
    # full eigenvector in state space: rebuild from A (keep = all states for a restrained model)
    from flexsim.linear.linearize import linearize

    lin = linearize(model, x_eq, np.zeros(4))
    vals, vecs = np.linalg.eig(lin.a)
    k = int(np.argmin(np.abs(vals - lam)))
    v = vecs[:, k]
    lay = model.layout
    v = v / np.abs(v[lay.q.start : lay.xi.stop]).max()
    x0 = x_eq.copy()
    x0[lin.keep] = 1e-3 * np.real(v)  # 1 mm of modal amplitude: linear regime
    periods = 8.0
    t_end = periods * 2 * np.pi / lam.imag
    result = simulate(model, x0, t_end, controls=np.zeros(4),
                      integrator=IntegratorSettings(method="DOP853", rtol=1e-9, atol=1e-12),
                      output=OutputSettings(rate_hz=4000.0))
    t, y = result.t, result.tip_deflection_m("right_wing")
    f = lambda tt, a, s, w, p: a * np.exp(s * tt) * np.cos(w * tt + p)
    guess = (np.abs(y).max(), lam.real, lam.imag, 0.0)
    (a, sigma, omega, _), _ = curve_fit(f, t, y, p0=guess, maxfev=20000)
    assert omega == pytest.approx(lam.imag, rel=0.05)
    assert sigma == pytest.approx(lam.real, rel=0.05)
    assert np.sign(sigma) == np.sign(lam.real)  # grows above, decays below the flutter speed
