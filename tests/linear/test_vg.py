"""V-g / V-f diagrams (flexsim.linear.vg): branch tracking by eigenvector correlation, and the Goland wing's crossing."""

from __future__ import annotations

import json

import numpy as np
import pytest

import flexsim as fs
from flexsim.linear.vg import mac, track_branches

#: Goland (1945), J. Appl. Mech. 12, flutter speed of the Goland wing at 1.225 kg/m^3 [m/s] and frequency [rad/s]
#: (SI data Patil, Hodges & Cesnik 2001, J. Aircraft 38(1); docs/validation.md, goland-flutter-theodorsen-1.225).
GOLAND_SPEED_M_S = 137.2
GOLAND_FREQUENCY_RAD_S = 70.7
#: The tolerance of docs/validation.md's Goland rows (strip theory against Goland's analysis) [-].
GOLAND_RTOL = 0.02


def _two_mode_roots(u: float, coupling: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Upper-half-plane roots of a 2-DOF damped system whose natural frequencies cross at u = 5.

    M = I, K = diag(w1^2, w2^2) + coupling, C = diag(2 z1 w1, 2 z2 w2) with w1 = 10 + u and w2 = 20 - u [rad/s],
    z1 = 0.02 (stable) and z2 = -0.01 + 0.004 u (crossing into instability at u = 2.5). The roots are returned in
    the order numpy gives them; the vectors are the velocity part of the first-order eigenvectors.
    """
    w1, w2 = 10.0 + u, 20.0 - u
    z1, z2 = 0.02, -0.01 + 0.004 * u
    k = np.array([[w1**2, coupling], [coupling, w2**2]])
    c = np.diag([2 * z1 * w1, 2 * z2 * w2])
    a = np.block([[np.zeros((2, 2)), np.eye(2)], [-k, -c]])
    vals, vecs = np.linalg.eig(a)
    up = vals.imag > 0
    return vals[up], vecs[2:, up]


def test_mac_is_one_for_parallel_and_zero_for_orthogonal_vectors():
    a = np.array([[1.0 + 1j], [2.0], [0.0]])
    b = np.hstack([3j * a, np.array([[2.0], [-1.0 + 1j], [0.0]])])
    m = mac(a, b)
    assert m[0, 0] == pytest.approx(1.0, abs=1e-15)
    assert m[0, 1] == pytest.approx(0.0, abs=1e-15)


def test_tracking_follows_the_eigenvectors_where_frequency_order_swaps():
    """Two modes whose frequencies cross (and whose order in numpy's output is arbitrary): each branch keeps its mode.

    Sorting by frequency would swap the branches at u = 5, so the crossing into instability of mode 2 (at u = 2.5)
    would be followed by a branch that jumps to mode 2's stable partner; the MAC tracking keeps mode 1 stable
    throughout and mode 2 unstable beyond u = 2.5.
    """
    us = np.linspace(0.2, 9.8, 25)
    steps = []
    rng = np.random.default_rng(0)
    for u in us:
        vals, vecs = _two_mode_roots(u, coupling=0.5)
        order = rng.permutation(vals.size)  # the tracker may not rely on the order of the roots
        steps.append((vals[order], vecs[:, order]))
    branches = track_branches(steps)
    assert branches.shape == (2, us.size) and np.all(branches >= 0)
    for row in branches:
        vecs = np.stack([steps[i][1][:, k] for i, k in enumerate(row)], axis=1)
        dominant = np.argmax(np.abs(vecs), axis=0)
        assert np.all(dominant == dominant[0]), "a branch changed mode"
        freq = np.array([abs(steps[i][0][k].imag) for i, k in enumerate(row)])
        expected = 10.0 + us if dominant[0] == 0 else 20.0 - us
        assert np.max(np.abs(freq - expected)) < 0.05  # coupling 0.5 shifts w by < 0.05 rad/s away from the crossing
    # the test provokes what it guards against: by sorting on frequency the lower branch would change mode at u = 5
    low = [int(np.argmin(np.abs(steps[i][0].imag))) for i in range(us.size)]
    low_dominant = [int(np.argmax(np.abs(steps[i][1][:, k]))) for i, k in enumerate(low)]
    assert len(set(low_dominant)) == 2


def test_a_new_root_starts_a_new_branch_and_a_lost_one_ends():
    e1, e2 = np.array([1.0, 0.0]), np.array([0.0, 1.0])
    steps = [(np.array([-1 + 10j]), e1[:, None]),
             (np.array([-1 + 20j, -1 + 10.1j]), np.stack([e2, e1], axis=1)),
             (np.array([-1 + 19.9j]), e2[:, None])]
    assert track_branches(steps).tolist() == [[0, 1, -1], [-1, 0, 0]]


@pytest.fixture(scope="module")
def goland_vg():
    wing = fs.load_aircraft("goland_wing")
    model = fs.AircraftModel(wing, variant="restrained", aero="quasi-steady", gravity_m_s2=0.0, air_density_kg_m3=1.225)
    return fs.vg_diagram(model, speeds_m_s=np.arange(100.0, 171.0, 2.0), models=("FS", "US"))


@pytest.mark.parametrize("aero_model", ["theodorsen", "unsteady"])
def test_goland_torsion_branch_crosses_at_the_published_speed(goland_vg, aero_model):
    """Goland 1945 (docs/validation.md): 137.2 m/s, 70.7 rad/s, within the validation rows' 2 %; the crossing
    branch is the one that starts as the first torsion mode."""
    crossing = goland_vg.flutter(aero_model)
    assert crossing is not None
    # named by its root at the crossing (the name the flutter search gives that point); the branch that crosses is
    # the one that starts as the first torsion mode
    assert crossing.label == "right_wing bending 1"
    assert "right_wing torsion 1" in [t.label for t in goland_vg.tracks_of(aero_model) if t.brackets()]
    assert crossing.speed_m_s == pytest.approx(GOLAND_SPEED_M_S, rel=GOLAND_RTOL)
    assert crossing.frequency_rad_s == pytest.approx(GOLAND_FREQUENCY_RAD_S, rel=GOLAND_RTOL)


def test_goland_vg_agrees_with_the_wind_tunnel_search(goland_vg):
    """The interpolated crossing on a 2 m/s grid against Brent's method to 1e-3 m/s (same model): within 0.1 m/s
    (linear interpolation of Re(lambda) over 2 m/s of a smooth branch)."""
    wing = fs.load_aircraft("goland_wing")
    tunnel = fs.wind_tunnel(wing, aero_model="theodorsen", speed_range=(100.0, 170.0), speed_step=5.0,
                            density_kg_m3=1.225, divergence=False)
    assert goland_vg.flutter("theodorsen").speed_m_s == pytest.approx(tunnel.flutter_speed_m_s, abs=0.1)


def test_goland_branches_are_continuous_through_the_coalescence(goland_vg):
    """Bending 1 and torsion 1 approach each other (the coalescence of bending-torsion flutter): every branch's
    frequency changes smoothly, no jump of more than 5 rad/s between 2 m/s steps (a swap would jump ~20 rad/s)."""
    for track in goland_vg.tracks_of("unsteady"):
        freq = track.frequency_rad_s[np.isfinite(track.frequency_rad_s)]
        assert np.max(np.abs(np.diff(freq))) < 5.0, track.label
    labels = [t.label for t in goland_vg.tracks_of("unsteady")]
    assert len(labels) == len(set(labels)) == 5


def test_vg_diagram_json_and_plot(goland_vg, tmp_path):
    doc = json.loads(json.dumps(goland_vg.as_dict()))
    assert {t["label"] for t in doc["tracks"]} >= {"right_wing torsion 1", "right_wing bending 1"}
    assert any(c["direction"] == "unstable" for c in doc["crossings"])
    png = goland_vg.plot(tmp_path / "vg.png")
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_vg_diagram_refuses_bad_input():
    wing = fs.load_aircraft("goland_wing")
    model = fs.AircraftModel(wing, variant="restrained", aero="quasi-steady", gravity_m_s2=0.0)
    with pytest.raises(ValueError, match="models"):
        fs.vg_diagram(model, speeds_m_s=[100.0, 110.0], models=("XX",))
    with pytest.raises(ValueError, match="speeds_m_s"):
        fs.vg_diagram(model)
    with pytest.raises(ValueError, match="increasing"):
        fs.vg_diagram(model, speeds_m_s=[110.0, 100.0])
