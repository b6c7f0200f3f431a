"""The fixed-step exponential integrator ETD2RK (flexsim.sim.fixed_step) against closed forms.

Sources and tolerances:
* phi functions: phi_1(z) = (e^z - 1)/z, phi_2(z) = (e^z - 1 - z)/z^2 (phi_1(0) = 1, phi_2(0) = 1/2;
  Hochbruck & Ostermann 2010, section 2.3); for a diagonalisable J = S D S^-1, phi(hJ) = S phi(hD) S^-1.
  Rounding of scipy's expm: 1e-10 relative (the stiff entry, hJ = -20, has e^{hJ} = 2e-9).
* Linear problems x' = J x + g with the method's J: exact for every step size (Cox & Matthews 2002,
  section 2): x(t) = e^{tJ} x0 + t phi_1(tJ) g, to 1e-9 relative over 1 s in steps of 20 ms and 5 ms, with stiff
  (-1000 1/s, -577 +- 1395i 1/s) and lightly growing oscillatory (0.2 +- 178i 1/s) modes.
* Order 2 for a J that is not the Jacobian: the observed order log2(e(h) / e(h/2)) is 2 +- 0.2 for
  (a) the stiff linear system above over 0.2 s with J = A + P, P a random non-stiff perturbation
  (entries ~2 1/s), h = 1.25 ms to 0.16 ms (asymptotic range: h * 178 rad/s <= 0.22), exact
  solution e^{tA} x0; (b) the logistic equation x' = x (1 - x), x(t) = 1 / (1 + (1/x0 - 1) e^-t),
  with J = 0 (the method is then Heun's) and J = 1 - 2 x0.
* Stiff order 2 (Hochbruck & Ostermann 2005, SIAM J. Numer. Anal. 43, 1069-1090: the error bound
  C h^2 does not depend on the stiffness): Prothero-Robinson y' = lambda (y - sin t) + cos t,
  y(t) = sin t, J = lambda: error(t = 1) / h^2 < 0.08 for lambda = -10, -1e4 and -1e6 and h = 0.1 to
  0.0125 (the non-stiff limit of the constant is 0.0701, measured); for lambda = -1e4 and -1e6 the
  error is O(h / |lambda|), below that bound (the observed order is 1 there); for lambda = -10 the
  observed order is 2 +- 0.2.
* The scaled (n x n) matrix functions equal the augmented 3n x 3n expm to 1e-12 relative (largest entry) on
  the stiff matrix above, on a singular matrix with a nilpotent Jordan block (like the GTM's heading and
  position), scaled by 1e4 between states, and on a random matrix with 1-norm 1e3; the fallback returns the
  augmented result. (Skaflestad & Wright 2009; both forms are accurate to ~1e-13 here.)
* ETD2RK.step (the compiled stages around a Python right-hand side) equals the numpy transcription of the method
  (tests/sim/etd2rk_reference.py) to 1e-13 of the largest entry over 10 steps (rounding of the products' order).
* Invalid J, h or x shapes raise ValueError naming the argument and the value.
"""

import math

import numpy as np
import pytest
from scipy.linalg import expm

from flexsim.sim import fixed_step
from flexsim.sim.fixed_step import ETD2RK, ETD2RKSolver, phi_functions, quintic_hermite, step_accelerations
from tests.sim.etd2rk_reference import reference_step


def _phi_scalar(z):
    if z == 0.0:
        return 1.0, 0.5
    return math.expm1(z) / z, (math.expm1(z) - z) / (z * z)


def _stiff_matrix():
    """Real 7 x 7 matrix with eigenvalues -1000, -577 +- 1395i, 0.2 +- 178i, -3, 0 (a fixed random basis)."""
    blocks = np.zeros((7, 7))
    blocks[0, 0] = -1000.0
    blocks[1:3, 1:3] = [[-577.0, 1395.0], [-1395.0, -577.0]]
    blocks[3:5, 3:5] = [[0.2, 178.0], [-178.0, 0.2]]
    blocks[5, 5] = -3.0
    s = np.eye(7) + 0.3 * np.random.default_rng(3).standard_normal((7, 7))
    return s @ blocks @ np.linalg.inv(s)


def _observed_orders(errors):
    e = np.asarray(errors)
    return np.log2(e[:-1] / e[1:])


def test_phi_functions_diagonal_and_similar_matrices():
    h = 0.02
    d = np.array([-1000.0, -3.0, 0.0, 2.5])
    e, p1, p2 = phi_functions(np.diag(d), h)
    for i, lam in enumerate(d):
        f1, f2 = _phi_scalar(h * lam)
        assert e[i, i] == pytest.approx(math.exp(h * lam), rel=1e-10, abs=1e-15)
        assert p1[i, i] == pytest.approx(f1, rel=1e-10)
        assert p2[i, i] == pytest.approx(f2, rel=1e-10)
    np.testing.assert_allclose(e - np.diag(np.diag(e)), 0.0, atol=1e-15)
    s = np.eye(4) + 0.2 * np.random.default_rng(1).standard_normal((4, 4))
    _, q1, q2 = phi_functions(s @ np.diag(d) @ np.linalg.inv(s), h)
    np.testing.assert_allclose(q1, s @ p1 @ np.linalg.inv(s), rtol=0, atol=1e-10)
    np.testing.assert_allclose(q2, s @ p2 @ np.linalg.inv(s), rtol=0, atol=1e-10)


def _jordan_scaled_matrix():
    """Singular 6 x 6: a nilpotent Jordan pair (psi -> y), a zero column, a stiff and an oscillatory mode, with
    state scales from 1 to 1e4 (metres against radians)."""
    a = np.zeros((6, 6))
    a[0, 1] = 230.0  # y_dot = V psi
    a[1, 2] = 1.0  # psi_dot = r
    a[2:4, 2:4] = [[-0.5, 3.0], [-3.0, -0.5]]
    a[4, 4] = -650.0
    a[5, 2:5] = [1.0, -2.0, 5.0]
    d = np.array([1e4, 1.0, 1.0, 1e-2, 1e2, 1.0])
    return d[:, None] * a / d[None, :]


@pytest.mark.parametrize("h", [0.02, 0.005])
@pytest.mark.parametrize("which", ["stiff", "jordan", "random"])
def test_scaled_phi_functions_equal_the_augmented_expm(h, which):
    jac = {"stiff": _stiff_matrix, "jordan": _jordan_scaled_matrix,
           "random": lambda: 1e3 / 7 * np.random.default_rng(5).standard_normal((7, 7))}[which]()
    for got, ref in zip(phi_functions(jac, h), phi_functions(jac, h, method="augmented")):
        assert np.abs(got - ref).max() <= 1e-12 * np.abs(ref).max()


def test_phi_functions_fall_back_to_the_augmented_expm(monkeypatch):
    jac = _stiff_matrix()
    monkeypatch.setattr(fixed_step, "PHI_RESIDUAL_LIMIT", -1.0)  # no residual passes: always the fallback
    for got, ref in zip(phi_functions(jac, 0.02), phi_functions(jac, 0.02, method="augmented")):
        np.testing.assert_array_equal(got, ref)
    with pytest.raises(ValueError, match="method = 'pade'"):
        phi_functions(jac, 0.02, method="pade")


def test_step_equals_the_numpy_transcription():
    """ETD2RK.step (the compiled stages around a Python right-hand side) equals the numpy transcription of the formulas
    (tests/sim/etd2rk_reference.py) to rounding: 1e-13 of the largest entry over 10 steps of a stiff nonlinear system
    (the two sum the products in different orders)."""
    a = _stiff_matrix()
    method = ETD2RK(a, 0.02)

    def f(t, x):
        return a @ x + 0.1 * np.sin(x) + np.cos(t)

    x = y = np.arange(1.0, 8.0)
    for k in range(10):
        x = method.step(f, 0.02 * k, x)
        y = reference_step(method, f, 0.02 * k, y)
    assert np.abs(x - y).max() <= 1e-13 * np.abs(y).max()


@pytest.mark.parametrize("h", [0.02, 0.005])
def test_linear_problem_is_integrated_exactly(h):
    a = _stiff_matrix()
    g = np.linspace(-1.0, 1.0, 7)
    x0 = np.arange(1.0, 8.0)
    method = ETD2RK(a, h)
    calls = []

    def f(t, x, forcing):
        calls.append(t)
        return a @ x + forcing

    x, t, steps = x0.copy(), 0.0, round(1.0 / h)
    for _ in range(steps):
        x = method.step(f, t, x, (g,))
        t += h
    _, phi1, _ = phi_functions(a, t)
    exact = expm(t * a) @ x0 + t * phi1 @ g
    np.testing.assert_allclose(x, exact, rtol=1e-9, atol=1e-9 * np.abs(exact).max())
    assert len(calls) == method.nfev_per_step * steps
    assert calls[:2] == [0.0, h]


def test_order_two_with_a_perturbed_jacobian():
    a = _stiff_matrix()
    perturbation = 2.0 * np.random.default_rng(7).standard_normal((7, 7))
    x0 = np.arange(1.0, 8.0)
    exact = expm(0.2 * a) @ x0
    errors = []
    for n in (160, 320, 640, 1280):
        method = ETD2RK(a + perturbation, 0.2 / n)
        x = x0.copy()
        for k in range(n):
            x = method.step(lambda t, y: a @ y, k * method.h, x)
        errors.append(np.abs(x - exact).max())
    orders = _observed_orders(errors)
    assert np.all(np.abs(orders - 2.0) < 0.2), (errors, orders)


@pytest.mark.parametrize("lam", [-10.0, -1e4, -1e6])
def test_prothero_robinson_error_is_order_two_uniformly_in_stiffness(lam):
    def f(t, y):
        return lam * (y - np.sin(t)) + np.cos(t)

    steps = (10, 20, 40, 80)
    errors = []
    for n in steps:
        method = ETD2RK([[lam]], 1.0 / n)
        y = np.zeros(1)
        for k in range(n):
            y = method.step(f, k * method.h, y)
        errors.append(abs(y[0] - math.sin(1.0)))
    scaled = np.array(errors) * np.array(steps) ** 2
    assert np.all(scaled < 0.08), scaled
    if lam == -10.0:
        orders = _observed_orders(errors)
        assert np.all(np.abs(orders - 2.0) < 0.2), (errors, orders)


@pytest.mark.parametrize("jac", [0.0, 1.0 - 2.0 * 0.1])
def test_order_two_logistic(jac):
    x0 = 0.1
    exact = 1.0 / (1.0 + (1.0 / x0 - 1.0) * math.exp(-2.0))
    errors = []
    for n in (10, 20, 40, 80):
        method = ETD2RK([[jac]], 2.0 / n)
        x = np.array([x0])
        for k in range(n):
            x = method.step(lambda t, y: y * (1.0 - y), k * method.h, x)
        errors.append(abs(x[0] - exact))
    orders = _observed_orders(errors)
    assert np.all(np.abs(orders - 2.0) < 0.2), (errors, orders)


def test_invalid_arguments_are_named():
    with pytest.raises(ValueError, match=r"jac: must be a non-empty square matrix \(n, n\), got shape \(2, 3\)"):
        ETD2RK(np.zeros((2, 3)), 0.01)
    with pytest.raises(ValueError, match=r"jac: must be finite, got jac\[0, 1\] = nan"):
        ETD2RK([[0.0, math.nan], [0.0, 0.0]], 0.01)
    for h in (0.0, -1e-3, math.inf, "x"):
        with pytest.raises(ValueError, match=r"h = .*: must be a finite number > 0 \[s\]"):
            ETD2RK(np.eye(2), h)
    with pytest.raises(ValueError, match=r"x: expected shape \(2,\) to match jac, got shape \(3,\)"):
        ETD2RK(np.eye(2), 0.01).step(lambda t, y: y, 0.0, np.zeros(3))


def test_solver_interface_exact_on_linear_problem_and_lands_on_t_bound():
    """ETD2RKSolver (scipy OdeSolver interface): the linear problem above exactly (1e-9), two evaluations
    per step, a shortened last step landing on t_bound, and a dense output that is the quintic Hermite
    interpolant of the step's end values, derivatives and second derivatives (exact for x = t^5 from exact end
    data; mid-step error within the quintic's (omega h)^6 / 46080 of the amplitude, the cubic's was
    (omega h)^4 / 384: 6.7e-4 against 2.6e-2 here)."""
    a = _stiff_matrix()
    g = np.linspace(-1.0, 1.0, 7)
    x0 = np.arange(1.0, 8.0)
    calls = []

    def f(t, x):
        calls.append(t)
        return a @ x + g

    solver = ETD2RKSolver(f, 0.0, x0, 0.53, jac=a, step=0.02)
    while solver.status == "running":
        solver.step()
    assert solver.t == 0.53
    _, phi1, _ = phi_functions(a, 0.53)
    exact = expm(0.53 * a) @ x0 + 0.53 * phi1 @ g
    np.testing.assert_allclose(solver.y, exact, rtol=1e-9, atol=1e-9 * np.abs(exact).max())
    assert len(calls) == 1 + 2 * 27  # 26 steps of 20 ms and one of 10 ms
    # dense output: the Hermite interpolant of the step's end values and derivatives
    dense = solver.dense_output()
    np.testing.assert_allclose(dense(np.array([solver.t_old, solver.t])).T, [dense.y_old, solver.y], rtol=1e-14)
    eps = 1e-8  # one-sided difference: error |x''| eps / 2 < 1e-3
    slope = (dense(solver.t) - dense(solver.t - eps)) / eps
    np.testing.assert_allclose(slope, solver.f, rtol=1e-4, atol=1e-4 * np.abs(solver.f).max())
    # exact for polynomials of degree 5: y = t^5 on [0.5, 1] from values, slopes and second derivatives at the ends
    ts = np.linspace(0.5, 1.0, 7)
    a0, a1 = 20 * 0.5**3, 20.0
    quintic = quintic_hermite((ts - 0.5) / 0.5, 0.5, np.array([0.5**5]), np.array([1.0]), np.array([5 * 0.5**4]),
                              np.array([5.0]), np.array([(a0 + a1) / 2]), np.array([(a1 - a0) / 2]))
    np.testing.assert_allclose(quintic[:, 0], ts**5, rtol=1e-14)
    # mid-step samples of the solver's dense output: on this linear problem (forcing constant) step_accelerations are
    # exact, so the interpolant's error is the quintic's, (omega h)^6 / 46080 of the amplitude at most
    omega = 178.0  # the undamped mode; the ones of |lambda| >= 1000 1/s have decayed by e^(-577 t) < 1e-100 at t = 0.52 s
    bound = (omega * (solver.t - solver.t_old)) ** 6 / 46080 * np.abs(exact).max() + 1e-9 * np.abs(exact).max()
    for theta in (0.25, 0.5, 0.75):  # the midpoint uses only the mean second derivative (quintic_hermite)
        t_in = solver.t_old + theta * (solver.t - solver.t_old)
        exact_in = expm(t_in * a) @ x0 + t_in * phi_functions(a, t_in)[1] @ g
        assert np.abs(dense(t_in) - exact_in).max() <= bound
        assert np.abs(dense(np.array([t_in]))[:, 0] - exact_in).max() <= bound


def test_step_accelerations_exact_for_linear_forcing():
    """x'' = J f + g' at both ends of a step of f = J x + g0 + g1 t (g linear in t), whatever the step's end states
    (the formula uses only f and J at the ends: Hochbruck & Ostermann's remainder N = f - J x is then linear in t)."""
    rng = np.random.default_rng(3)
    n, h, t0 = 5, 0.02, 0.3
    jac = rng.normal(size=(n, n))
    g0, g1 = rng.normal(size=n), rng.normal(size=n)
    y0, y1 = rng.normal(size=n), rng.normal(size=n)
    f0, f1 = jac @ y0 + g0 + g1 * t0, jac @ y1 + g0 + g1 * (t0 + h)
    mean, half_diff = step_accelerations(h, y1 - y0, f0, f1, jac)
    a0, a1 = mean - half_diff, mean + half_diff
    np.testing.assert_allclose(a0, jac @ f0 + g1, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(a1, jac @ f1 + g1, rtol=1e-12, atol=1e-12)


def test_chunk_dense_output_equals_the_numpy_interpolant():
    """The compiled dense output of a chunk of steps (flexsim.sim.compiled_run._Steps, kernel hermite_samples) equals
    quintic_hermite with step_accelerations evaluated step by step, to 1e-12 of the values' scale: at step ends,
    midpoints (mean second derivative only) and other fractions, for scalar and array times."""
    from flexsim.sim.compiled_run import _Steps

    rng = np.random.default_rng(7)
    n, k, h = 9, 6, 0.02
    t = 1.0 + h * np.arange(k + 1)
    t[-1] = t[-2] + 0.013  # a shortened last step
    x, f, jac = rng.normal(size=(k + 1, n)), rng.normal(size=(k + 1, n)), rng.normal(size=(n, n))
    for times in (t[1:], t[:-1] + 0.5 * np.diff(t), np.sort(rng.uniform(t[0], t[-1], 15))):
        got = _Steps(t, x, f, jac)(times).T
        j = np.clip(np.searchsorted(t, times, side="left") - 1, 0, k - 1)
        hj = t[j + 1] - t[j]
        mean, half = step_accelerations(hj[:, None], x[j + 1] - x[j], f[j], f[j + 1], jac)
        want = quintic_hermite((times - t[j]) / hj, hj, x[j], x[j + 1], f[j], f[j + 1], mean, half)
        np.testing.assert_allclose(got, want, rtol=0.0, atol=1e-12 * np.abs(want).max())
        np.testing.assert_allclose(_Steps(t, x, f, jac)(float(times[2])), want[2], rtol=0.0, atol=1e-12 * np.abs(want).max())
