"""The environments reproduce the recorded reference (tests/envs/data/env_reference.npz).

The reference holds the observations and rewards of 6 steps of every registered id, single (``gym.make``) and
batched (``gym.make_vec`` with the vector entry point: 3 rows, and 40 rows in light turbulence, which take the
products over the rows as matrix products), plus two quasi-steady cases integrated with DOP853; recorded by
tests/envs/data/record_env_reference.py from the environments before their integration moved into
:mod:`flexsim.sim.periods`. The episodes here are the same (same seeds and actions, :func:`run_case`).

Tolerances, from the spread measured across CPU targets (``python tools/reference_spread.py``: OpenBLAS's kernels for
the core types Haswell, Zen, Sandybridge, SkylakeX and its oldest (``OPENBLAS_CORETYPE=Prescott``, run as Katmai), and
numba's ``NUMBA_CPU_NAME=generic``; 2026-12-04, AMD EPYC with AVX-512). flexsim's compiled kernels give the
same results on every target (the generic target reproduced the native results bit for bit); the BLAS/LAPACK products of the ETD2RK step are not: their sums run in another order per core type. The largest
differences are in the elastic rates (here the left-wing tip twist rate of Turn-v0, scale 0.10 rad/s). Largest
measured difference of an observation component, relative to that component's largest magnitude in the recorded
episode: 9.3e-7 between two targets (13 float32 spacings, vector3 Turn-v0), 7.9e-7 from the recorded reference
(generic numba with Prescott's BLAS; 11 float32 spacings with Haswell's, where a tolerance of 4 spacings failed).
Tolerance: 4e-6 of the component's scale (4x the largest spread). Rewards: largest relative difference 1.2e-8
(FlutterMargin-v0, vector3); tolerance 1e-6 relative (80x) plus 1e-12 absolute for zero parts.
"""

import sys
from pathlib import Path

import numpy as np
import pytest

DATA = Path(__file__).with_name("data")
sys.path.insert(0, str(DATA))
from record_env_reference import CASES, run_case  # noqa: E402

sys.path.remove(str(DATA))
REFERENCE = np.load(DATA / "env_reference.npz")
OBS_TOL = 4e-6  # of each component's largest magnitude: 4x the spread measured across CPU targets (docstring)


@pytest.mark.parametrize("name, env_id, num_envs, kwargs", CASES, ids=[c[0] for c in CASES])
def test_observations_and_rewards_equal_the_recorded_reference(name, env_id, num_envs, kwargs):
    obs, reward = run_case(env_id, num_envs, kwargs)
    ref_obs, ref_reward = REFERENCE[f"{name}/obs"], REFERENCE[f"{name}/reward"]
    assert obs.shape == ref_obs.shape and obs.dtype == np.float32
    scale = np.abs(ref_obs).reshape(-1, ref_obs.shape[-1]).max(axis=0)  # each component's largest magnitude
    tolerance = OBS_TOL * scale.astype(np.float64)
    excess = np.abs(obs.astype(np.float64) - ref_obs.astype(np.float64)) - tolerance
    assert excess.max() <= 0.0, (name, np.unravel_index(np.argmax(excess), excess.shape), float(excess.max()))
    np.testing.assert_allclose(reward, ref_reward, rtol=1e-6, atol=1e-12)
