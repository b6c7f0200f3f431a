"""Symmetric / antisymmetric halves of the p-k problem (flexsim.linear.symmetry).

Invariants: the bases are orthonormal, complementary and the +1 / -1 eigenspaces of the state mirror; in level
flight and a climb the coupling blocks of A_qs and A(omega) vanish to the Jacobian's round-off (measured 1.3e-10
of max |A|, tolerance COUPLING_RTOL = 1e-8) and the p-k spectrum from the halves equals the full matrix's to 1e-9
relative (measured <= 1.2e-11) with the same kinds; a turn couples the halves (measured >= 9.8e-4) and keeps the
full matrix.
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.linearize import linearize
from flexsim.linear.stability import pk_state_matrix, spectrum
from flexsim.linear.symmetry import COUPLING_RTOL, decoupled, mirror_bases
from flexsim.model.aircraft_model import AircraftModel
from flexsim.trimming import SteadyManoeuvre, trim


@pytest.fixture(scope="module")
def models():
    gtm = load_aircraft("gtm")
    return AircraftModel(gtm, aero="quasi-steady"), AircraftModel(gtm, aero="unsteady")


def _setup(models, manoeuvre):
    qs, fs = models
    point = trim(qs, manoeuvre, check_limits=False)
    lin = linearize(qs, point.x, point.u)
    return point, lin, pk_state_matrix(qs, fs, lin), mirror_bases(qs, lin.keep)


def test_bases_are_the_mirror_eigenspaces(models):
    qs, _ = models
    _, lin, _, bases = _setup(models, SteadyManoeuvre.level(0.0, mach=0.68))
    q_s, q_a = bases
    q = np.hstack([q_s, q_a])
    np.testing.assert_allclose(q.T @ q, np.eye(lin.keep.size), atol=1e-15)
    # the state mirror diag(P_a, P_a) over the kept states maps Q_s to itself and Q_a to minus itself
    p = qs.structure.mirror.matrix
    act = qs.active_dofs
    p_a = p[np.ix_(act, act)]
    t = np.zeros((2 * act.size, 2 * act.size))
    t[: act.size, : act.size] = p_a
    t[act.size :, act.size :] = p_a
    t_k = t[np.ix_(lin.keep, lin.keep)]
    np.testing.assert_allclose(t_k @ q_s, q_s, atol=1e-15)
    np.testing.assert_allclose(t_k @ q_a, -q_a, atol=1e-15)


@pytest.mark.parametrize("manoeuvre", [SteadyManoeuvre.level(0.0, mach=0.68),
                                       SteadyManoeuvre.climb(0.0, np.radians(10.0), mach=0.7)], ids=["level", "climb"])
def test_symmetric_flight_halves_equal_full_matrix(models, manoeuvre):
    qs, fs = models
    point, _, a_of, bases = _setup(models, manoeuvre)
    for a in (a_of.a_qs, a_of(10.0), a_of(40.0)):
        assert decoupled(a, bases)
    split = spectrum(qs, point.x, point.u, aero_model="theodorsen", pk_model=fs)
    full = spectrum(qs, point.x, point.u, aero_model="theodorsen", pk_model=fs, mirror_split=False)
    a = np.array([m.eigenvalue for m in split.modes])
    b = np.array([m.eigenvalue for m in full.modes])
    dist = np.abs(a[:, None] - b[None, :])
    match = np.argmin(dist, axis=1)
    assert sorted(match) == list(range(b.size))  # one to one
    assert np.all(dist[np.arange(a.size), match] <= 1e-9 * np.abs(b[match]))
    assert [m.kind for m in split.modes] == [full.modes[j].kind for j in match]
    assert [m.dominant_dof for m in split.modes] == [full.modes[j].dominant_dof for j in match]


def test_turn_couples_the_halves(models):
    _, lin, a_of, bases = _setup(models, SteadyManoeuvre.turn(0.0, 5000.0, mach=0.7))
    assert not decoupled(a_of.a_qs, bases)
    assert decoupled(a_of.a_qs, bases, rtol=1e3 * COUPLING_RTOL) is False  # far above round-off, not near it
