"""Prototype measurement: would a fourth-order exponential Runge-Kutta method allow longer steps than ETD2RK?

Not the library's integrator: both methods are stepped here from Python with numpy (``model.rhs`` per stage), with
the same frozen linear part J (the Jacobian at the initial state) as the default, and their errors are measured
at the step ends against DOP853 at rtol 1e-9 on a named manoeuvre (default: the first 3 s of ``gust-encounter``,
1-cos gust U_ds = 10 m/s, H = 60 m, reached at 1 s). Printed: largest errors of altitude [m], forward body
velocity u [m/s] and of the elastic coordinates q [m or rad] at the step ends.

Methods, in the form of the f-evaluations only (N = f - J x; D_i = f(U_i) - f(x_n) - J (U_i - x_n) the change of
the remainder, phi_k of Hochbruck & Ostermann 2010, section 2):

* ETD2RK (Cox & Matthews 2002; the library's): U = x + h phi_1(hJ) f(x), x+ = U + h phi_2(hJ) D.
* ETDRK4 of Krogstad (2005) (the tableau in Hochbruck & Ostermann 2010, section 2.3), c = (0, 1/2, 1/2, 1):
  U2 = x + h/2 phi_1(hJ/2) f(x); U3 = U2 + h phi_2(hJ/2) D2; U4 = x + h phi_1(hJ) f(x) + 2 h phi_2(hJ) D3;
  x+ = x + h phi_1(hJ) f(x) + h (2 phi_2 - 4 phi_3)(D2 + D3) + h (4 phi_3 - phi_2) D4 (phi_k of hJ): four
  right-hand sides and nine n x n matrix-vector products per step (ETD2RK: two and three).

The phi functions come from one ``scipy.linalg.expm`` of the augmented block matrix (Al-Mohy & Higham 2011, sec. 2).

Run: python benchmarks/proto_etdrk4.py [manoeuvre] [duration_s]
"""

from __future__ import annotations

import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
os.environ.setdefault("OMP_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from scipy.linalg import expm  # noqa: E402

from flexsim.model.jacobian import jacobian  # noqa: E402
from flexsim.sim.manoeuvres import build_manoeuvre  # noqa: E402
from flexsim.sim.simulate import IntegratorSettings  # noqa: E402
from flexsim.sim.run_settings import OutputSettings  # noqa: E402


def phis(z: np.ndarray, kmax: int) -> list[np.ndarray]:
    """[e^Z, phi_1(Z), ..., phi_kmax(Z)] from the exponential of the augmented block matrix."""
    n = z.shape[0]
    a = np.zeros(((kmax + 1) * n, (kmax + 1) * n))
    a[:n, :n] = z
    for k in range(kmax):
        a[k * n:(k + 1) * n, (k + 1) * n:(k + 2) * n] = np.eye(n)
    e = expm(a)
    return [e[:n, k * n:(k + 1) * n] for k in range(kmax + 1)]


def etd2rk(f, jac, x0, h, t_end):
    _, p1, p2 = phis(h * jac, 2)
    x, k1, t, out = x0.copy(), f(0.0, x0), 0.0, [x0]
    for _ in range(int(round(t_end / h))):
        u = x + h * p1 @ k1
        d = f(t + h, u) - k1 - jac @ (u - x)
        x = u + h * p2 @ d
        t += h
        k1 = f(t, x)
        out.append(x)
    return np.array(out)


def etdrk4_krogstad(f, jac, x0, h, t_end):
    _, q1, q2 = phis(0.5 * h * jac, 2)
    _, p1, p2, p3 = phis(h * jac, 3)
    x, k1, t, out = x0.copy(), f(0.0, x0), 0.0, [x0]
    for _ in range(int(round(t_end / h))):
        u2 = x + 0.5 * h * q1 @ k1
        d2 = f(t + h / 2, u2) - k1 - jac @ (u2 - x)
        u3 = u2 + h * q2 @ d2
        d3 = f(t + h / 2, u3) - k1 - jac @ (u3 - x)
        base = x + h * p1 @ k1
        u4 = base + 2 * h * p2 @ d3
        d4 = f(t + h, u4) - k1 - jac @ (u4 - x)
        x = base + h * (2 * p2 - 4 * p3) @ (d2 + d3) + h * (4 * p3 - p2) @ d4
        t += h
        k1 = f(t, x)
        out.append(x)
    return np.array(out)


def main() -> None:
    name = sys.argv[1] if len(sys.argv) > 1 else "gust-encounter"
    t_end = float(sys.argv[2]) if len(sys.argv) > 2 else 3.0
    setup = build_manoeuvre(name, duration_s=t_end)
    if not isinstance(setup.controls, np.ndarray):
        raise SystemExit(f"{name}: this prototype holds the controls constant; choose a manoeuvre with constant controls")
    model, wind, u = setup.model, setup.wind, np.asarray(setup.controls, dtype=float)
    x0 = np.array(setup.initial.x, dtype=float)
    lay = model.layout

    def f(t, x):
        return model.rhs(t, x, u, wind)

    jac = jacobian(model, x0, u, controls=False, wind=wind)[0]
    c0 = time.process_time()
    ref = setup.simulate(integrator=IntegratorSettings(method="DOP853", rtol=1e-9),
                         output=OutputSettings(rate_hz=100.0))
    print(f"{name}, {t_end:g} s; reference DOP853 rtol 1e-9: {time.process_time() - c0:.1f} s CPU; load average "
          f"{os.getloadavg()[0]:.1f}")
    iz, iu = lay.position.start + 2, lay.v.start
    for label, method, steps in (("ETD2RK", etd2rk, (0.01, 0.02, 0.04)), ("ETDRK4 Krogstad", etdrk4_krogstad, (0.02, 0.04, 0.05))):
        for h in steps:
            xs = method(f, jac, x0, h, t_end)
            r = ref.x[::int(round(h / 0.01))][: xs.shape[0]]
            print(f"{label:<16} h {h * 1e3:4.0f} ms: altitude {np.abs(xs[:, iz] - r[:, iz]).max():.2e} m, u "
                  f"{np.abs(xs[:, iu] - r[:, iu]).max():.2e} m/s, q {np.abs(xs[:, lay.q] - r[:, lay.q]).max():.2e}", flush=True)


if __name__ == "__main__":
    main()
