"""The block-sparse right-hand side equals the dense one it replaced, and its sparsity is exact.

``data/rhs_reference.npz`` holds state derivatives computed by the earlier compiled kernel (``data/README.md`` names its commit; a dense
30 x 30 elimination of E V_dot = f, apparent mass as one dense product; ``data/README.md`` gives the script) at
near-trim states of seven GTM models: quasi-steady and unsteady, bending-incidence coupling, the paper's force
resolution, vacuum, restrained with structural damping, quasi-rigid; the fourth state of each in a 1-cos gust.
The kernel now skips the exact zeros of each strip's rows and eliminates the lifting surfaces' 4 x 4 blocks into a
Schur complement of the rigid-body and fuselage entries (:func:`flexsim._kernels.solve_structure`). Same algebra,
other rounding (both eliminations are backward stable; the dense LU against LAPACK differs by about 1e-14 at these
states, measured). The state derivatives near trim are small in the accelerations, so the acceleration block is also
checked against its own largest entry. Largest differences measured across CPU targets (``python
tools/reference_spread.py``: OpenBLAS core types Haswell, Zen, Sandybridge, SkylakeX, Prescott and numba's
``NUMBA_CPU_NAME=generic``; 2026-12-04): 2.9e-13 of the largest derivative, 1.3e-12 of the largest acceleration.
Tolerances: 2e-12 and 1e-10 (7x and 80x those).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from flexsim import _kernels as k
from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.sim.disturbances import OneMinusCosineGust

DATA = Path(__file__).parent / "data" / "rhs_reference.npz"


def _cases() -> dict[str, AircraftModel]:
    gtm = load_aircraft("gtm")
    return {"qs": AircraftModel(gtm, aero="quasi-steady"), "us": AircraftModel(gtm),
            "us_bending_incidence": AircraftModel(gtm, aero=AeroOptions(model="unsteady", bending_incidence=True)),
            "qs_paper": AircraftModel(gtm, aero=AeroOptions(model="quasi-steady", formulation="paper")),
            "vacuum": AircraftModel(gtm, aero=None),
            "restrained": AircraftModel(gtm, variant="restrained", aero="quasi-steady",
                                        restrained_velocity_m_s=[200.0, 0.0, 8.0], altitude_m=3000.0,
                                        structural_damping=0.02),
            "quasi_rigid": AircraftModel(gtm, variant="quasi-rigid", aero="unsteady")}


@pytest.fixture(scope="module")
def cases():
    return _cases()


def test_equal_to_the_dense_kernel_of_9d7f24c(cases):
    ref = np.load(DATA)
    gust = OneMinusCosineGust(5.0, 25.0, front_position_ned_m=[-8.0, 0.0, 0.0])
    worst = {}
    for name, model in cases.items():
        vs = model.layout.velocity
        for s in range(ref[f"{name}_x"].shape[0]):
            old = ref[f"{name}_dx"][s]
            new = model.rhs(0.0, ref[f"{name}_x"][s], ref[f"{name}_u"][s], gust if s == 3 else None)
            whole = np.max(np.abs(new - old)) / np.max(np.abs(old))
            accel = np.max(np.abs(new[vs] - old[vs])) / np.max(np.abs(old[vs]))
            worst[name] = max(worst.get(name, 0.0), whole)
            assert whole <= 2e-12, (name, s, whole)
            assert accel <= 1e-10, (name, s, accel)
    print("largest difference / max |dx| per model:", {n: f"{w:.1e}" for n, w in worst.items()})


def test_gtm_splits_into_surface_blocks_and_a_core(cases):
    """The GTM's E: rigid body + fuselage modes (10) couple with everything; each lifting surface's two bending and
    two torsion modes (4) couple only with them (modes of one component, strips of one component)."""
    F, I = cases["us"].kernel_data
    perm, ptr = k._i1(I, k.SOLVE_PERM), k._i1(I, k.SOLVE_PTR)
    assert np.diff(ptr).tolist() == [4, 4, 4, 4, 4, 10]
    assert sorted(perm.tolist()) == list(range(30))
    F, I = cases["restrained"].kernel_data  # elastic entries only: the fuselage's modes are the core
    assert np.diff(k._i1(I, k.SOLVE_PTR)).tolist() == [4, 4, 4, 4, 4, 4]
    F, I = cases["quasi_rigid"].kernel_data  # rigid body only: one dense elimination
    assert k._i1(I, k.SOLVE_PTR).tolist() == [0, 6]


@pytest.mark.parametrize("name", ["us", "us_bending_incidence", "qs_paper", "restrained", "vacuum"])
def test_pattern_holds_at_random_states(cases, name):
    """At states far from trim (every coordinate random), E has no entry between two blocks (the solver would
    otherwise fall back to one dense elimination), and the block elimination equals LAPACK's solve (1e-12)."""
    model = cases[name]
    F, I = model.kernel_data
    perm, ptr = k._i1(I, k.SOLVE_PERM), k._i1(I, k.SOLVE_PTR)
    for seed in range(5):
        rng = np.random.default_rng(seed)
        lay = model.layout
        x = 0.2 * rng.standard_normal(lay.n_states)
        if lay.rigid:
            x[lay.position] = [0.0, 0.0, -1000.0 - 2000.0 * seed]
            x[lay.v] = [150.0 + 20.0 * seed, 5.0, 10.0]
        m, f = model.generalized_forces(x, np.array([3e4, 0.05, -0.05, 0.02]))
        assert k.blocks_decoupled(m, perm, ptr)
        act = np.sort(perm)
        lapack = np.linalg.solve(m[np.ix_(act, act)], f[act])
        ours = k.block_solve(m, f, perm, ptr)[act]
        assert np.max(np.abs(ours - lapack)) <= 1e-12 * np.max(np.abs(lapack))


def test_block_solve_falls_back_when_blocks_couple():
    """An entry between two blocks that the pattern did not foresee: one dense elimination, still exact."""
    rng = np.random.default_rng(1)
    a = rng.standard_normal((7, 7)) + 7.0 * np.eye(7)
    b = rng.standard_normal(7)
    perm = np.array([0, 1, 2, 3, 4, 5, 6], np.int64)
    ptr = np.array([0, 2, 4, 7], np.int64)  # blocks {0, 1}, {2, 3}, core {4, 5, 6}
    assert not k.blocks_decoupled(a, perm, ptr)
    np.testing.assert_allclose(k.block_solve(a, b, perm, ptr), np.linalg.solve(a, b), rtol=1e-12, atol=1e-14)
    a[np.ix_([0, 1], [2, 3])] = 0.0
    a[np.ix_([2, 3], [0, 1])] = 0.0
    assert k.blocks_decoupled(a, perm, ptr)
    np.testing.assert_allclose(k.block_solve(a, b, perm, ptr), np.linalg.solve(a, b), rtol=1e-12, atol=1e-14)
