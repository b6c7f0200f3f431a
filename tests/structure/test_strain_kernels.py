"""The block exponential behind the free-flying beams' relative accelerations (flexsim.structure._strain_kernels).

``exp([[A, E, 0], [0, A, E], [0, 0, A]])`` computed block by block (the powers, sums and the Padé solve of a block
upper-triangular Toeplitz matrix stay in that form) equals scipy.linalg.expm of the assembled 12 x 12 matrix, for
1-norms that select each Padé degree (3, 5, 7, 9) and degree 13 with scaling and squaring (Higham 2005, Algorithm
2.3). Tolerance: 1e-13 of the largest entry (both are backward stable to double precision; the scaled case loses a
few digits in the squarings).
"""

import numpy as np
import pytest
from scipy.linalg import expm

from flexsim.structure._strain_kernels import expm_toeplitz_batch


@pytest.mark.parametrize("norm", [1e-3, 0.2, 0.8, 2.0, 5.0, 40.0])
def test_block_toeplitz_exponential_equals_the_full_matrix_exponential(norm):
    rng = np.random.default_rng(7)
    x = rng.normal(size=(5, 3, 4, 4))
    x *= norm / np.abs(x).sum(axis=(1, 2)).max(axis=-1)[:, None, None, None]  # about that 1-norm
    full = np.zeros((5, 12, 12))
    for i in range(3):
        for j in range(i, 3):
            full[:, 4 * i:4 * i + 4, 4 * j:4 * j + 4] = x[:, j - i]
    out = np.empty_like(x)
    expm_toeplitz_batch(x, out)
    ref = expm(full)
    for j in range(3):
        assert np.allclose(out[:, j], ref[:, 0:4, 4 * j:4 * j + 4], rtol=0, atol=1e-13 * np.abs(ref).max())
