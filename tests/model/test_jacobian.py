"""Structured Jacobian over the inflow states against the dense central difference and the exact derivative.

Reference: the fourth-order Richardson extrapolation of central differences with steps 1e-2 and 5e-3 m/s
(error O(h^4 f^(5)), far below the others). Tolerances from the measured truncation + round-off errors of
the differences: the structured columns within 1e-8 of the largest inflow column of the reference
(measured 2.8e-9), the dense difference with its 1e-7 steps within 2e-8 (measured 6.4e-9), and the two
within 2e-8 of the largest entry of J.
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.jacobian import _column, jacobian
from flexsim.trimming import SteadyManoeuvre, trim


def _gust(t, positions):
    """A steady, spatially varying wind [m/s] (NED) exercising the strip-wind path of the rhs."""
    w = np.zeros_like(positions)
    w[:, 2] = 2.0 * np.sin(0.05 * positions[:, 0]) + 0.01 * positions[:, 1]
    w[:, 1] = 0.5
    return w


@pytest.fixture(scope="module")
def gtm_state():
    gtm = load_aircraft("gtm")
    qs = AircraftModel(gtm, aero="quasi-steady")
    fs = AircraftModel(gtm, aero="unsteady")  # the gust is passed per call
    point = trim(qs, SteadyManoeuvre.level(3048.0, mach=0.7))
    rng = np.random.default_rng(1)
    x = np.concatenate([point.x, rng.normal(0.0, 0.5, fs.layout.n_inflow)])
    x[fs.layout.s] += rng.normal(0.0, 0.05, fs.layout.nq)
    return fs, x, point.u


def _exact_inflow_columns(model, x, u, t):
    lay = model.layout
    ref = np.empty((x.size, lay.n_inflow))
    for k, j in enumerate(range(lay.inflow.start, lay.n_states)):
        e = np.zeros(x.size)
        e[j] = 1.0
        d1, d2 = _column(model, t, x, u, e, 1e-2, _gust), _column(model, t, x, u, e, 5e-3, _gust)
        ref[:, k] = (4.0 * d2 - d1) / 3.0
    return ref


def test_structured_jacobian_equals_dense_and_exact(gtm_state, monkeypatch):
    model, x, u = gtm_state
    lay = model.layout
    calls = []
    rhs = type(model).rhs
    # the model is immutable: the rhs is wrapped on its class to count the calls, for this block only
    monkeypatch.setattr(type(model), "rhs", lambda self, t, xx, uu, wind=None: calls.append(1) or rhs(self, t, xx, uu, wind))
    try:
        a_s, b_s = jacobian(model, x, u, t=0.3, wind=_gust)
        n_structured = len(calls)
    finally:
        monkeypatch.undo()
    a_d, b_d = jacobian(model, x, u, t=0.3, method="dense", wind=_gust)
    n_strips = lay.n_inflow // model.aero.options.n_inflow
    assert n_structured == 2 * (lay.inflow.start + n_strips) + 8  # 192 rhs instead of 2 n + 8 = 512
    # columns over the non-inflow states and B: the same differences, bit for bit
    np.testing.assert_array_equal(a_s[:, : lay.inflow.start], a_d[:, : lay.inflow.start])
    np.testing.assert_array_equal(b_s, b_d)
    ref = _exact_inflow_columns(model, x, u, 0.3)
    scale = np.abs(ref).max()
    assert np.abs(a_s[:, lay.inflow] - ref).max() <= 1e-8 * scale
    assert np.abs(a_d[:, lay.inflow] - ref).max() <= 2e-8 * scale
    assert np.abs(a_s - a_d).max() <= 2e-8 * np.abs(a_d).max()


def test_structured_jacobian_restrained_wing():
    """A restrained model (not all DOFs active; the wing's strips only) takes the same path."""
    wing = load_aircraft("goland_wing")
    model = AircraftModel(wing, variant="restrained", gravity_m_s2=0.0, aero="unsteady",
                          restrained_velocity_m_s=[120.0, 0.0, 0.0])
    rng = np.random.default_rng(2)
    x = rng.normal(0.0, 0.01, model.layout.n_states)
    x[model.layout.inflow] = rng.normal(0.0, 1.0, model.layout.n_inflow)
    u = np.zeros(4)
    a_s, _ = jacobian(model, x, u, controls=False)
    ref = _exact_inflow_columns(model, x, u, 0.0)
    assert np.abs(a_s[:, model.layout.inflow] - ref).max() <= 1e-8 * np.abs(ref).max()


def test_bad_method_is_named():
    wing = load_aircraft("goland_wing")
    model = AircraftModel(wing, variant="restrained", gravity_m_s2=0.0, aero="quasi-steady",
                          restrained_velocity_m_s=[120.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="method = 'complex-step'"):
        jacobian(model, model.layout.zeros(), np.zeros(4), method="complex-step")
