"""Stability of the whole free-flying very flexible aircraft about its nonlinear trim
(flexsim.linear.flexible_stability)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import flexsim as fs
from flexsim.linear.flexible_stability import free_aircraft_spectrum


def _stiff(aircraft, factor):
    def one(c):
        if not c.is_flexible:
            return c
        s = c.sections
        return dataclasses.replace(c, sections=dataclasses.replace(
            s, ei_nm2=s.ei_nm2 * factor, gj_nm2=s.gj_nm2 * factor, ei_chord_nm2=s.ei_chord_nm2 * factor))
    return dataclasses.replace(aircraft, components=tuple(one(c) for c in aircraft.components))


def _nearest(values, target):
    return values[np.argmin(np.abs(values - target))]


def test_stiff_aircraft_has_the_linear_models_flight_modes():
    """Small-deflection limit (EI, GJ x 1e4): the rigid-body modes of the nonlinear free aircraft (quasi-steady
    strips) are the linear model's quasi-steady ones — spiral and Dutch roll within 1 %, phugoid frequency within
    0.5 % and its damping within 10 % (the phugoid's damping scales with the drag, and the two models resolve the
    tail's flap force differently: trim thrust 11.8 N against 9.9 N)."""
    aircraft = _stiff(fs.load_aircraft("phc_hale"), 1e4)
    man = fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0)
    model = fs.AircraftModel(aircraft)
    spectrum = free_aircraft_spectrum(model, fs.trim_flexible(model, man))
    linear_model = fs.AircraftModel(aircraft, terms=fs.Terms(aero=fs.AeroOptions("quasi-steady")))
    trim = fs.trim(linear_model, man)
    modes = {m.name.split(" [")[0]: m.eigenvalue for m in fs.spectrum(linear_model, trim.x, trim.u).modes}
    lam = spectrum.eigenvalues
    for name in ("spiral", "Dutch roll"):
        assert _nearest(lam, modes[name]) == pytest.approx(modes[name], rel=1e-2)
    (phugoid,) = spectrum.phugoid
    assert phugoid.imag == pytest.approx(abs(modes["phugoid"].imag), rel=5e-3)
    assert phugoid.real == pytest.approx(modes["phugoid"].real, rel=0.1)
    # the modes are named as the linear model names them (kinetic energy in the rigid-body velocities)
    named = {m.name: m.eigenvalue for m in spectrum.modes if m.kind == "rigid"}
    for name in ("spiral", "Dutch roll", "phugoid"):
        assert named[name] == pytest.approx(modes[name] if modes[name].imag >= 0 else modes[name].conjugate(), rel=0.1)


def test_flexible_hale_phugoid_is_found():
    """The bundled HALE at its cruise point: a phugoid below 1 rad/s, and the neutral roots of the heading and of
    the quaternion's norm (invariants of the equations: |lambda| < 1e-6, central differences' error ~1e-8)."""
    model = fs.AircraftModel(fs.load_aircraft("phc_hale"))
    spectrum = free_aircraft_spectrum(model, fs.trim_flexible(model, fs.SteadyManoeuvre.level(20000.0, speed_m_s=25.0)))
    (phugoid,) = spectrum.phugoid
    assert 0.1 < phugoid.imag < 1.0
    assert np.sum(np.abs(spectrum.eigenvalues) < 1e-6) >= 2
    names = [m.name for m in spectrum.modes]
    assert "phugoid" in names and "wings bending 1 (antisymmetric)" in names and "wings bending 1 (symmetric)" in names
    # an unstable mode of the verdict lies in the converged band
    assert all(abs(m.eigenvalue) <= 200.0 for m in spectrum.unstable)
