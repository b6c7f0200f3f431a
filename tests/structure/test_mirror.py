"""The mirror operator of the coordinates and the tie-breaking of mirror pairs.

* Hand cases (checked by mirroring leading-edge displacements): u, w, q and fuselage vertical bending even; v, p, r, fuselage torsion and the fin odd;
  q_R <-> q_L; xi_R <-> -xi_L (positive xi_R1 with negative xi_L1 is a symmetric nose-up twist).
* Invariants: P^2 = I and P^T M(0) P = M(0) to 1e-12 relative (exact for a symmetric aircraft).
* Independent check: the displacement of points *off* the elastic axes (leading edge at 70 % span, from
  translation + rotation x lever arm) of P c is the mirror image of that of c, for random c, to 1e-10.
* An aircraft with one wing moved is not symmetric: no operator.
"""

import numpy as np
import pytest

from flexsim.aircraft.toml_loader import load_aircraft, resolve_aircraft_path
from flexsim.structure.kinematic_map import DofIndex, point_maps
from flexsim.structure.mirror import TIE_RTOL, mirror_operator, mode_symmetry, ranked
from flexsim.structure.model import StructuralModel


@pytest.fixture(scope="module")
def gtm():
    ac = load_aircraft("gtm")
    return ac, StructuralModel(ac)


def test_hand_cases_of_the_probe(gtm):
    _, st = gtm
    labels = st.dofs.labels
    p = st.mirror
    assert p is not None

    def image(label):
        k = labels.index(label)
        return labels[p.partner[k]], p.sign[k]

    for even in ("u", "w", "q", "fuselage bending 1", "fuselage bending 2"):
        assert image(even) == (even, 1.0)
    for odd in ("v", "p", "r", "fuselage torsion 1", "fuselage torsion 2", "vtail bending 1", "vtail torsion 2"):
        assert image(odd) == (odd, -1.0)
    for k in (1, 2):
        assert image(f"right_wing bending {k}") == (f"left_wing bending {k}", 1.0)
        assert image(f"right_wing torsion {k}") == (f"left_wing torsion {k}", -1.0)
        assert image(f"left_htail torsion {k}") == (f"right_htail torsion {k}", -1.0)


def test_involution_and_mass_invariance(gtm):
    _, st = gtm
    p = st.mirror.matrix
    assert np.allclose(p @ p, np.eye(p.shape[0]), atol=1e-12)
    m0 = st.inertia.mass_matrix(np.zeros(st.dofs.nq))
    assert np.abs(p.T @ m0 @ p - m0).max() <= 1e-12 * np.abs(m0).max()


def _edge_displacements(ac, dofs, c):
    """Body-axis displacement of each wing/tail half's leading edge at 70 % span for coordinates c (over V)."""
    out = {}
    for comp in ac.components:
        if comp.aero is None or comp.name == "vtail":
            continue
        x = 0.7 * comp.length_m
        maps = point_maps(ac, dofs, comp, [x])
        ct = maps.dcm.T
        trans = ct @ (maps.g0[0, 0:3] @ c)
        rot = ct @ (maps.g0[0, 3:6] @ c)
        chord = float(np.interp(x, comp.sections.station_m, comp.sections.chord_m))
        ea = float(np.interp(x, comp.sections.station_m, comp.sections.ea_fraction))
        lever = ct @ (maps.dcm @ np.array([-1.0, 0.0, 0.0]))  # body -x: towards the nose
        lever = ea * chord * lever / np.linalg.norm(lever)
        out[comp.name] = (maps.r0[0] + lever, trans + np.cross(rot, lever))
    return out


def test_off_axis_displacements_are_mirrored(gtm):
    ac, st = gtm
    rng = np.random.default_rng(0)
    s = np.diag([1.0, -1.0, 1.0])
    pairs = {"right_wing": "left_wing", "left_wing": "right_wing", "right_htail": "left_htail", "left_htail": "right_htail"}
    for _ in range(5):
        c = rng.standard_normal(st.dofs.n_v)
        base = _edge_displacements(ac, st.dofs, c)
        mirrored = _edge_displacements(ac, st.dofs, st.mirror.matrix @ c)
        for name, (point, disp) in mirrored.items():
            other_point, other_disp = base[pairs[name]]
            assert np.allclose(point, s @ other_point, atol=1e-9)
            assert np.allclose(disp, s @ other_disp, atol=1e-10 * (1 + np.abs(other_disp).max()))


def test_probe_table_symmetric_twist(gtm):
    """xi_R1 = +0.01, xi_L1 = -0.01 is mirror-symmetric; xi_R1 = xi_L1 = +0.01 antisymmetric (probe section A)."""
    _, st = gtm
    labels = st.dofs.labels
    c = np.zeros(st.dofs.n_v)
    c[labels.index("right_wing torsion 1")], c[labels.index("left_wing torsion 1")] = 0.01, -0.01
    assert np.allclose(st.mirror.matrix @ c, c)
    c[labels.index("left_wing torsion 1")] = 0.01
    assert np.allclose(st.mirror.matrix @ c, -c)
    m0 = st.inertia.mass_matrix(np.zeros(st.dofs.nq))
    assert st.mirror.symmetric_fraction(c, m0) == pytest.approx(0.0, abs=1e-15)


def test_asymmetric_aircraft_has_no_mirror(tmp_path):
    text = resolve_aircraft_path("gtm").read_text().replace("root_m = [21.3917, -1.88, -1.6]", "root_m = [21.0, -1.88, -1.6]", 1)
    path = tmp_path / "lopsided.toml"
    path.write_text(text)
    ac = load_aircraft(path)
    assert mirror_operator(ac, DofIndex.from_aircraft(ac)) is None


def test_mirror_ties_do_not_flip_on_round_off(gtm):
    """Right and left magnitudes within TIE_RTOL: the right half (lower index) ranks first either way."""
    _, st = gtm
    labels = st.dofs.labels
    r, l = labels.index("right_wing torsion 1"), labels.index("left_wing torsion 1")
    for eps in (-1e-9, 0.0, 1e-9, -0.5 * TIE_RTOL, 0.5 * TIE_RTOL):
        v = np.zeros(st.dofs.n_v)
        v[r], v[l] = 1.0, 1.0 + eps
        v[labels.index("u")] = 0.3
        order = ranked(v, st.mirror)
        assert order[:3] == [r, l, labels.index("u")]
    v[r], v[l] = 1.0, 1.01  # a physical difference is not a tie
    assert ranked(v, st.mirror)[:2] == [l, r]


def test_symmetry_classes():
    assert mode_symmetry(1.0) == "symmetric" and mode_symmetry(0.9) == "symmetric"
    assert mode_symmetry(0.0) == "antisymmetric" and mode_symmetry(0.1) == "antisymmetric"
    assert mode_symmetry(0.5) == "mixed"
