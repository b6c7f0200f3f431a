"""Compiled dense output of the ETD2RK runs (numba): the quintic Hermite interpolant of a chunk of steps at many
sample times, and its weights.

The interpolant and its second derivatives are documented in :func:`flexsim.sim.fixed_step.quintic_hermite` and
:func:`flexsim.sim.fixed_step.step_accelerations`; the weights are computed here only (:func:`quintic_weights`),
for the one-step dense output of :class:`~flexsim.sim.fixed_step.ETD2RKSolver` and for the chunks of
:mod:`flexsim.sim.compiled_run` (:func:`hermite_samples`). Times [s]; states as the model's layout. Independent
of the right-hand side (numba's cache of this file is keyed on this file alone).
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["NODE_TOLERANCE", "quintic_weights", "hermite_samples", "sample_needs"]

#: Fraction of a step within which a sample counts as the step's end or its midpoint (the interpolant's terms in
#: the second derivatives are then below rounding: s^2 h^2 |x''| / 2 near an end, |s - 1/2| h^2 |x''| at the middle).
NODE_TOLERANCE = 1e-9

_jit = njit(cache=True, nogil=True)


@_jit
def _weights(s, h, w):
    """The six weights at step fraction s of a step h into w (6,): 1 - H5, H5, h H1, h H4, h^2 (H2 + H3), h^2 (H3 - H2)."""
    s2 = s * s
    s3 = s2 * s
    s4 = s3 * s
    s5 = s4 * s
    h5 = 10.0 * s3 - 15.0 * s4 + 6.0 * s5
    h2 = 0.5 * (s2 - 3.0 * s3 + 3.0 * s4 - s5)
    h3 = 0.5 * (s3 - 2.0 * s4 + s5)
    w[0] = 1.0 - h5
    w[1] = h5
    w[2] = h * (s - 6.0 * s3 + 8.0 * s4 - 3.0 * s5)
    w[3] = h * (-4.0 * s3 + 7.0 * s4 - 3.0 * s5)
    w[4] = h * h * (h2 + h3)
    w[5] = h * h * (h3 - h2)


@_jit
def quintic_weights(s, h, out):
    """Weights of the quintic Hermite interpolant at step fractions s (m,) of steps h (m,) [s] into out (6, m)."""
    w = np.empty(6)
    for i in range(s.shape[0]):
        _weights(s[i], h[i], w)
        for r in range(6):
            out[r, i] = w[r]


@_jit
def _locate(t, time):
    """(step j, fraction s) of a time in the step ends t (k+1,): t[j] < time <= t[j+1], clipped to the chunk."""
    j = np.searchsorted(t, time) - 1  # side="left"
    j = min(max(j, 0), t.shape[0] - 2)
    return j, (time - t[j]) / (t[j + 1] - t[j])


@_jit
def sample_needs(t, times):
    """(a sample lies inside a step, a sample lies inside a step away from its midpoint): whether
    :func:`hermite_samples` needs the steps' mean second derivatives, and their half differences."""
    inside = off = False
    for i in range(times.shape[0]):
        _, s = _locate(t, times[i])
        if NODE_TOLERANCE < s < 1.0 - NODE_TOLERANCE:
            inside = True
            if abs(s - 0.5) > NODE_TOLERANCE:
                off = True
    return inside, off


@_jit
def hermite_samples(t, x, f, mean, half_diff, times, out):
    """The interpolant of the steps t (k+1,), x and f (k+1, n) at times (m,) into out (m, n); mean and half_diff
    (k, n): the steps' second derivatives (:func:`flexsim.sim.fixed_step.step_accelerations`), used only for the
    samples inside a step (and away from its midpoint), so (0, n) arrays where :func:`sample_needs` says so."""
    w = np.empty(6)
    for i in range(times.shape[0]):
        j, s = _locate(t, times[i])
        _weights(s, t[j + 1] - t[j], w)
        inside = NODE_TOLERANCE < s < 1.0 - NODE_TOLERANCE
        off = inside and abs(s - 0.5) > NODE_TOLERANCE
        for m in range(x.shape[1]):
            v = w[0] * x[j, m] + w[1] * x[j + 1, m] + w[2] * f[j, m] + w[3] * f[j + 1, m]
            if inside:
                v += w[4] * mean[j, m]
                if off:
                    v += w[5] * half_diff[j, m]
            out[i, m] = v
