"""The environments reproduce the recorded reference (tests/envs/data/env_reference.npz).

The reference holds the observations and rewards of 6 steps of every registered id, single (``gym.make``) and
batched (``gym.make_vec`` with the vector entry point: 3 rows, and 40 rows in light turbulence, which take the
products over the rows as matrix products), plus two quasi-steady cases integrated with DOP853; recorded by
tests/envs/data/record_env_reference.py from the environments before their integration moved into
:mod:`flexsim.sim.periods`. The episodes here are the same (same seeds and actions, :func:`run_case`).

Tolerances: observations (float32) within 4 float32 spacings of each observation component's largest magnitude in
the recorded episode (2.4e-7 of that scale); rewards within 1e-6 relative (plus 1e-12 absolute for zero parts). The
right-hand side sums its terms in another order than when the reference was recorded (it agrees within 3e-15
relative: tests/model/test_reference_values.py); the FlutterMargin tasks fly a growing flutter mode and their
ETD2RK linear part is a finite-difference Jacobian of that right-hand side, which turns the round-off into
observation changes of up to 1.2e-7 of a component's scale (2 spacings; measured), the other tasks 5.5e-9 or less.
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


@pytest.mark.parametrize("name, env_id, num_envs, kwargs", CASES, ids=[c[0] for c in CASES])
def test_observations_and_rewards_equal_the_recorded_reference(name, env_id, num_envs, kwargs):
    obs, reward = run_case(env_id, num_envs, kwargs)
    ref_obs, ref_reward = REFERENCE[f"{name}/obs"], REFERENCE[f"{name}/reward"]
    assert obs.shape == ref_obs.shape and obs.dtype == np.float32
    scale = np.abs(ref_obs).reshape(-1, ref_obs.shape[-1]).max(axis=0)  # each component's largest magnitude
    tolerance = 4.0 * np.spacing(scale).astype(np.float64)
    excess = np.abs(obs.astype(np.float64) - ref_obs.astype(np.float64)) - tolerance
    assert excess.max() <= 0.0, (name, np.unravel_index(np.argmax(excess), excess.shape), float(excess.max()))
    np.testing.assert_allclose(reward, ref_reward, rtol=1e-6, atol=1e-12)
