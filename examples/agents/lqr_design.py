"""Controller design on the linearised flexsim model, for the classical baselines of the gymnasium tasks.

The design model is :func:`flexsim.model.jacobian.jacobian` of the environment's own model at a trim
(all states: rigid body, elastic, inflow). For the LQR the elastic and inflow states are residualised
(their derivatives set to zero: quasi-static elasticity and inflow), which keeps the static aeroelastic
effects (wing twist under load) in the rigid-body model:

    A_r = A_RR - A_RE A_EE^-1 A_ER,   B_r = B_R - A_RE A_EE^-1 B_E

over R = [Z, phi, theta, (psi), u, v, w, p, q, r]; the gain solves the continuous algebraic Riccati
equation (``scipy.linalg.solve_continuous_are``) with Bryson weights. Every state of R is observed by the
environments (attitude, body rates, airspeed with alpha and beta, altitude), so the controllers read the
observation only.

Two facts of the flexsim GTM shape the designs. (1) The body frame is the fuselage root at the tail, so
the measured body rates carry the elastic modes: every gain is checked on the full flexible model sampled
with the environment's zero-order hold, and an LQR is softened (R doubled) until that loop is stable.
(2) With the rigid-body states frozen, the elastic states of the aircraft clamped at its tail are not
stable (A_EE has eigenvalues with positive real part; at 300 m and M 0.9 one is near zero), so the
residualisation is meaningless near the flutter condition; the flutter baseline uses hand-set PID-type
gains (:func:`checked_feedback`) instead.

:func:`design_fin_damper` sizes a sampled rudder feedback on the fin tip sensors against the flutter
mode, on the full linear model discretised with the zero-order hold.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm, solve_continuous_are
from scipy.optimize import minimize

from flexsim.model.jacobian import jacobian

__all__ = ["StateFeedback", "design_rigid_lqr", "checked_feedback", "rigid_state_from_obs", "design_fin_damper", "RIGID_STATES"]

#: The rigid-body states of the design model, in order.
RIGID_STATES = ("z_m", "phi_rad", "theta_rad", "psi_rad", "u_m_s", "v_m_s", "w_m_s", "p_rad_s", "q_rad_s", "r_rad_s")


@dataclass(frozen=True)
class StateFeedback:
    """A state-feedback law du = -K (x - x_ref) on rigid-body states (an LQR or hand-set gains).

    Attributes
    ----------
    states : tuple of str
        Names (from :data:`RIGID_STATES`) of the fed-back states.
    gain : ndarray, shape (4, n)
        K [N or rad per state unit].
    x_ref : ndarray, shape (n,)
        Reference (trim) values of the states.
    u_ref : ndarray, shape (4,)
        Trim controls [N, rad, rad, rad].
    closed_loop_max_real : float
        Largest real part of the eigenvalues of A_r - B_r K [1/s] (< 0: stable design model; NaN for
        hand-set gains).
    full_model_growth : float
        Largest growth rate ln|z| / dt [1/s] of the sampled full flexible closed loop (-inf if not checked).
    """

    states: tuple[str, ...]
    gain: np.ndarray
    x_ref: np.ndarray
    u_ref: np.ndarray
    closed_loop_max_real: float
    full_model_growth: float = -np.inf

    def controls(self, x: np.ndarray) -> np.ndarray:
        """Physical controls u_ref - K (x - x_ref) [N, rad, rad, rad]."""
        dx = np.asarray(x, float) - self.x_ref
        return self.u_ref - self.gain @ dx


def _rigid_indices(layout, states: tuple[str, ...]) -> list[int]:
    table = {"z_m": layout.position.start + 2, "phi_rad": layout.euler.start, "theta_rad": layout.euler.start + 1,
             "psi_rad": layout.euler.start + 2, "u_m_s": layout.v.start, "v_m_s": layout.v.start + 1,
             "w_m_s": layout.v.start + 2, "p_rad_s": layout.omega.start, "q_rad_s": layout.omega.start + 1,
             "r_rad_s": layout.omega.start + 2}
    return [table[s] for s in states]


def residualised_model(model, x0: np.ndarray, u0: np.ndarray, states: tuple[str, ...],
                       reduction: str = "residualise") -> tuple[np.ndarray, np.ndarray]:
    """(A_r, B_r) of the rigid-body ``states`` with the elastic and inflow states residualised, or
    truncated (frozen at the trim, ``reduction="truncate"``)."""
    a, b = jacobian(model, np.asarray(x0, float), np.asarray(u0, float))
    lay = model.layout
    r = _rigid_indices(lay, states)
    if reduction == "truncate":
        return a[np.ix_(r, r)], b[r]
    if reduction != "residualise":
        raise ValueError(f"reduction = {reduction!r}: must be 'residualise' or 'truncate'")
    e = list(range(lay.q.start, lay.xi.stop)) + list(range(lay.s.start, lay.inflow.stop))
    a_ee = a[np.ix_(e, e)]
    a_re, a_er = a[np.ix_(r, e)], a[np.ix_(e, r)]
    a_r = a[np.ix_(r, r)] - a_re @ np.linalg.solve(a_ee, a_er)
    b_r = b[r] - a_re @ np.linalg.solve(a_ee, b[e])
    return a_r, b_r


def _discrete_full_model(model, x0: np.ndarray, u0: np.ndarray, dt_s: float, drop: list[int]) -> tuple[np.ndarray, np.ndarray, list[int]]:
    """Zero-order-hold discretisation (Phi_xx, Phi_xu) of the full linearisation without the states ``drop``."""
    a, b = jacobian(model, np.asarray(x0, float), np.asarray(u0, float))
    keep = [i for i in range(model.layout.n_states) if i not in set(drop)]
    a, b = a[np.ix_(keep, keep)], b[keep]
    n = a.shape[0]
    phi = expm(np.block([[a, b], [np.zeros((4, n + 4))]]) * dt_s)
    return phi[:n, :n], phi[:n, n:], keep


def _growth(z: np.ndarray, dt_s: float) -> float:
    """Largest ln|z| / dt [1/s] over the eigenvalues away from z = 1 (the integrating X, Y, psi)."""
    z = z[np.abs(z - 1.0) > 1e-6]
    return float(np.log(np.abs(z).max()) / dt_s)


def design_rigid_lqr(model, x0: np.ndarray, u0: np.ndarray, max_state: dict[str, float], max_control: np.ndarray,
                     dt_s: float | None = None, max_softening: int = 12, extra_feedback: np.ndarray | None = None,
                     reduction: str = "residualise") -> StateFeedback:
    """LQR on the residualised rigid-body model at the trim (x0, u0) with Bryson weights.

    Parameters
    ----------
    model : AircraftModel
        The environment's model (``env.unwrapped.dynamics.model``).
    x0, u0 : ndarray
        Trim state and controls.
    max_state : dict
        Acceptable deviation of each fed-back state (keys from :data:`RIGID_STATES`), Q = diag(1/max^2).
    max_control : ndarray, shape (4,)
        Acceptable control deviations [N, rad, rad, rad], R = diag(1/max^2).
    dt_s : float, optional
        Control period [s]. If given, the gain is checked on the full flexible model (elastic and inflow
        states included) sampled with a zero-order hold: the body rates of the GTM's body frame (at the
        tail end of the fuselage) carry the elastic modes, and a gain that is fine on the rigid model can
        destabilise them (spillover). The control weight R is then multiplied by 2 until the sampled
        full closed loop is stable (at most ``max_softening`` times).
    extra_feedback : ndarray, shape (4, n_states), optional
        Another sampled feedback du = -F x acting together with the LQR (e.g. a fin damper), included in
        the full-model check.
    reduction : {"residualise", "truncate"}
        How the elastic and inflow states leave the design model (see :func:`residualised_model`).
    """
    states = tuple(s for s in RIGID_STATES if s in max_state)
    a_r, b_r = residualised_model(model, x0, u0, states, reduction)
    q = np.diag([1.0 / max_state[s] ** 2 for s in states])
    r = np.diag(1.0 / np.asarray(max_control, float) ** 2)
    idx = _rigid_indices(model.layout, states)
    lay = model.layout
    check = None
    if dt_s is not None:
        drop = [lay.position.start, lay.position.start + 1] + ([] if "psi_rad" in states else [lay.euler.start + 2])
        ad, bd, keep = _discrete_full_model(model, x0, u0, dt_s, drop)
        c = np.zeros((len(idx), len(keep)))
        c[np.arange(len(idx)), [keep.index(i) for i in idx]] = 1.0
        extra = np.zeros((4, len(keep))) if extra_feedback is None else np.asarray(extra_feedback, float)[:, keep]
        check = (ad, bd, c, extra)
    for _ in range(max_softening + 1):
        p = solve_continuous_are(a_r, b_r, q, r)
        gain = np.linalg.solve(r, b_r.T @ p)
        full = -np.inf if check is None else _growth(np.linalg.eigvals(check[0] - check[1] @ (gain @ check[2] + check[3])), dt_s)
        if full < 0.0:
            break
        r = 2.0 * r
    x_ref = np.asarray(x0, float)[idx]
    max_real = float(np.linalg.eigvals(a_r - b_r @ gain).real.max())
    return StateFeedback(states, gain, x_ref, np.asarray(u0, float).copy(), max_real, full)


def rigid_state_from_obs(obs: np.ndarray, names: tuple[str, ...], states: tuple[str, ...]) -> np.ndarray:
    """The rigid-body ``states`` read from an observation (names: ``env.observation_names``).

    u, v, w follow from airspeed, alpha and beta; z = -altitude; psi is the observed (wrapped) heading.
    """
    o = dict(zip(names, np.asarray(obs, float)))
    speed, alpha, beta = o["airspeed_m_s"], o["alpha_rad"], o["beta_rad"]
    values = {"z_m": -o["altitude_m"], "phi_rad": o["roll_rad"], "theta_rad": o["pitch_rad"], "psi_rad": o["heading_rad"],
              "u_m_s": speed * math.cos(alpha) * math.cos(beta), "v_m_s": speed * math.sin(beta),
              "w_m_s": speed * math.sin(alpha) * math.cos(beta), "p_rad_s": o["roll_rate_rad_s"],
              "q_rad_s": o["pitch_rate_rad_s"], "r_rad_s": o["yaw_rate_rad_s"]}
    return np.array([values[s] for s in states])


def checked_feedback(model, x0: np.ndarray, u0: np.ndarray, gains: dict[tuple[int, str], float], dt_s: float,
                     extra_feedback: np.ndarray | None = None) -> StateFeedback:
    """A hand-set state feedback (``gains[(control index, state)] = K entry``) with its sampled full-model check.

    Sign convention as everywhere here: du = -K (x - x_ref); controls [thrust N, aileron, elevator, rudder rad].
    """
    states = tuple(s for s in RIGID_STATES if any(s == key[1] for key in gains))
    gain = np.zeros((4, len(states)))
    for (control, state), value in gains.items():
        gain[control, states.index(state)] = value
    lay = model.layout
    idx = _rigid_indices(lay, states)
    drop = [lay.position.start, lay.position.start + 1] + ([] if "psi_rad" in states else [lay.euler.start + 2])
    ad, bd, keep = _discrete_full_model(model, x0, u0, dt_s, drop)
    c = np.zeros((len(idx), len(keep)))
    c[np.arange(len(idx)), [keep.index(i) for i in idx]] = 1.0
    extra = np.zeros((4, len(keep))) if extra_feedback is None else np.asarray(extra_feedback, float)[:, keep]
    full = _growth(np.linalg.eigvals(ad - bd @ (gain @ c + extra)), dt_s)
    return StateFeedback(states, gain, np.asarray(x0, float)[idx], np.asarray(u0, float).copy(), np.nan, full)


def rudder_feedback_growths(model, x0: np.ndarray, u0: np.ndarray, dt_s: float, sensor_rows: np.ndarray,
                            min_frequency_rad_s: float = 25.0):
    """``growths(k) -> (fast, every)``: the largest growth rate [1/s] of the modes faster than
    ``min_frequency_rad_s`` and of all modes, for the rudder feedback delta_r = -k . y (y = ``sensor_rows`` @ x,
    sampled at ``dt_s`` with a zero-order hold) on the full linear model at the trim (X, Y, psi dropped)."""
    lay = model.layout
    ad, bd, keep = _discrete_full_model(model, x0, u0, dt_s, [lay.position.start, lay.position.start + 1, lay.euler.start + 2])
    bd_r = bd[:, 3]
    rows = np.atleast_2d(np.asarray(sensor_rows, float))[:, keep]

    def growths(k: np.ndarray) -> tuple[float, float]:
        z = np.linalg.eigvals(ad - np.outer(bd_r, np.atleast_1d(np.asarray(k, float)) @ rows))
        z = z[np.abs(z - 1.0) > 1e-6]
        rate = np.log(np.abs(z)) / dt_s
        fast = rate[np.abs(np.angle(z)) / dt_s > min_frequency_rad_s]
        return float(fast.max()), float(rate.max())

    return growths


def design_fin_damper(model, x0: np.ndarray, u0: np.ndarray, dt_s: float, sensor_rows: np.ndarray,
                      min_frequency_rad_s: float = 25.0) -> tuple[np.ndarray, float, float]:
    """Rudder gains k of delta_r = -k . y (y = ``sensor_rows`` @ x, sampled, zero-order hold) that damp
    the elastic modes of the full linear model best.

    The full linearisation (X, Y, psi dropped) is discretised exactly with the hold. The objective is the
    largest growth rate ln|z| / dt among the modes faster than ``min_frequency_rad_s`` (the flutter
    mode and its neighbours), with a penalty if any mode is unstable. A scan of the first sensor's gain
    over +-1e-4 to 1 gives the start of a Nelder-Mead search over all gains.

    Parameters
    ----------
    sensor_rows : ndarray, shape (m, n_states)
        Linear sensors of the state (e.g. fin tip twist rate, twist, bending rate, bending).

    Returns
    -------
    gains : ndarray, shape (m,)
        k [rad per sensor unit].
    open_loop_growth, closed_loop_growth : float
        Growth rate of the fastest-growing fast mode without and with the feedback [1/s].
    """
    growths = rudder_feedback_growths(model, x0, u0, dt_s, sensor_rows, min_frequency_rad_s)

    def objective(k: np.ndarray) -> float:
        fast, every = growths(k)
        return fast + 100.0 * max(every, 0.0)

    m = np.atleast_2d(sensor_rows).shape[0]
    scan = np.concatenate([-np.logspace(-4, 0, 41), np.logspace(-4, 0, 41)])
    start = min((np.r_[k, np.zeros(m - 1)] for k in scan), key=objective)
    result = minimize(objective, start, method="Nelder-Mead", options={"xatol": 1e-7, "fatol": 1e-4, "maxfev": 100 * m})
    gains = result.x if result.fun < objective(start) else start
    return gains, growths(np.zeros(m))[0], growths(gains)[0]


def main(argv: list[str] | None = None) -> None:
    """Command line: design the level-flight LQR of LevelHold at its trim and print the gain and checks."""
    import argparse
    import os

    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    import gymnasium as gym

    import flexsim.envs  # noqa: F401  (registers the ids)

    parser = argparse.ArgumentParser(
        prog="python examples/agents/lqr_design.py", description=__doc__.splitlines()[0],
        epilog="A library for examples/agents/baselines.py; run alone, it designs the LQR of "
               "FlexSim/GTM-LevelHold-v0 (residualised elastic and inflow states, Bryson weights) and prints it.")
    parser.add_argument("--aero", default="unsteady", choices=["unsteady", "quasi-steady"], help="aerodynamics [%(default)s]")
    args = parser.parse_args(argv)
    from baselines import LevelHoldLqr  # the baseline's weights (this directory is on sys.path when run as a script)

    env = gym.make("FlexSim/GTM-LevelHold-v0", aero=args.aero).unwrapped
    policy = LevelHoldLqr(env)
    policy.reset({})
    design = policy.lqr
    np.set_printoptions(precision=4, suppress=False, linewidth=140)
    print(f"LQR of FlexSim/GTM-LevelHold-v0 ({args.aero}) at {env.task.manoeuvre.describe()}")
    print("states:", ", ".join(design.states))
    print("gain K [N or rad per state unit], rows thrust, aileron, elevator, rudder:")
    print(design.gain)
    print(f"design-model closed loop: max Re(eig) = {design.closed_loop_max_real:.4f} 1/s; "
          f"full flexible sampled loop: growth {design.full_model_growth:.4f} 1/s (< 0: stable)")


if __name__ == "__main__":
    main()
