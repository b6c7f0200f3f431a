"""The ETD2RK step transcribed in numpy from its formulas: the reference the tests compare the compiled step with.

Cox & Matthews (2002), method ETD2RK, in the form of :mod:`flexsim.sim.fixed_step` (its module docstring):
``k_1 = f(t, x)``, ``a = x + h phi_1(hJ) k_1``, ``k_2 = f(t + h, a)``, ``x_new = a + h phi_2(hJ) (k_2 - k_1 - J (a - x))``,
with the matrix functions of a :class:`flexsim.sim.fixed_step.ETD2RK`. The products are numpy's (BLAS), the compiled
step's its own loops: the two agree to rounding, not bit for bit.
"""

import numpy as np


def reference_step(method, fun, t: float, x: np.ndarray, args: tuple = (), k1: np.ndarray | None = None) -> np.ndarray:
    """One ETD2RK step of ``method`` (an ETD2RK: ``h``, ``h_phi1``, ``h_phi2``, ``jac``) from (t, x) of
    ``fun(t, x, *args) -> x_dot``; ``k1`` = fun(t, x, *args) if known."""
    if k1 is None:
        k1 = fun(t, x, *args)
    a = x + method.h_phi1 @ k1
    k2 = fun(t + method.h, a, *args)
    return a + method.h_phi2 @ (k2 - k1 - method.jac @ (a - x))
