"""Classical baselines of the flexsim tasks (LQR on the linearised model; PID + fin or aileron damper for flutter;
the trim's controls held for the very flexible HALE).

Each policy is designed from the environment's own model at a trim (``lqr_design``) and then acts on
observations only (run from ``examples/agents`` or put it on ``sys.path``; these are scripts, not a package)::

    import gymnasium as gym, flexsim.envs
    from baselines import make_baseline
    env = gym.make("FlexSim/GTM-LevelHold-v0")
    policy = make_baseline("FlexSim/GTM-LevelHold-v0", env)
    obs, info = env.reset(seed=0); policy.reset(info)
    obs, reward, terminated, truncated, info = env.step(policy(obs))

Run ``python examples/agents/evaluate_baselines.py`` to compare them with a random policy.
"""

from __future__ import annotations

import math

import numpy as np

from lqr_design import (StateFeedback, _discrete_full_model, _rigid_indices, checked_feedback, design_fin_damper, design_rigid_lqr,
                        rigid_state_from_obs)

__all__ = ["LevelHoldLqr", "TurnLqr", "GustLqr", "FlutterPidDamper", "WingFlutterAileronDamper", "TrimHold", "RandomPolicy", "make_baseline",
           "BASELINES"]

_ALL = ("z_m", "phi_rad", "theta_rad", "psi_rad", "u_m_s", "v_m_s", "w_m_s", "p_rad_s", "q_rad_s", "r_rad_s")


class _LqrPolicy:
    """Common part: Bryson-weighted LQR about a trim, mapped to normalised actions."""

    max_state: dict[str, float] = {"z_m": 10.0, "phi_rad": 0.05, "theta_rad": 0.02, "psi_rad": 0.02, "u_m_s": 1.0, "v_m_s": 2.0,
                                   "w_m_s": 2.0, "p_rad_s": 0.05, "q_rad_s": 0.02, "r_rad_s": 0.02}
    #: Acceptable control deviations as fractions of the control limits (thrust, aileron, elevator, rudder).
    max_control_fraction = np.array([0.05, 0.2, 0.12, 0.2])

    def __init__(self, env) -> None:
        self.env = env.unwrapped
        self.names = self.env.observation_names
        self._designs: dict = {}
        self.lqr: StateFeedback | None = None

    reduction = "residualise"

    def _design(self, manoeuvre, states: dict[str, float], extra_feedback: np.ndarray | None = None) -> StateFeedback:
        if manoeuvre not in self._designs:
            dyn = self.env.dynamics
            point = dyn.trim(manoeuvre)
            max_control = self.max_control_fraction * dyn.u_high
            self._designs[manoeuvre] = design_rigid_lqr(dyn.model, point.x, point.u, states, max_control, dt_s=self.env.dt,
                                                        extra_feedback=extra_feedback, reduction=self.reduction)
        return self._designs[manoeuvre]

    def reset(self, info: dict) -> None:
        """Prepare for an episode from the reset ``info`` (designs are cached per trim)."""
        self.lqr = self._design(self.env.task.manoeuvre, self.max_state)

    def controls(self, obs: np.ndarray) -> np.ndarray:
        x = rigid_state_from_obs(obs, self.names, self.lqr.states)
        return self.lqr.controls(x)

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        """Normalised action (float32) for observation ``obs``."""
        return self.env.controls_to_action(self.controls(obs))


class LevelHoldLqr(_LqrPolicy):
    """LQR on [z, phi, theta, psi, u, v, w, p, q, r] about the level trim (heading reference 0)."""


class GustLqr(_LqrPolicy):
    """LQR attitude/altitude hold about the level trim with tight pitch and roll weights (the GTM's
    antisymmetric ailerons cannot unload the wings symmetrically; the elevator holds the attitude)."""

    max_state = {**_LqrPolicy.max_state, "theta_rad": 0.01, "phi_rad": 0.02, "q_rad_s": 0.01}


class TurnLqr(_LqrPolicy):
    """LQR about the trim of the commanded steady turn (heading not fed back): it rolls into the turn
    and holds its bank, pitch, body rates, speed and altitude."""

    max_state = {k: v for k, v in _LqrPolicy.max_state.items() if k != "psi_rad"}

    def reset(self, info: dict) -> None:
        self.lqr = self._design(self.env.task.turn(info["reference"]["radius_m"]), self.max_state)


class FlutterPidDamper(_LqrPolicy):
    """Hold beyond the flutter speed: hand-set PID-type gains plus a sampled fin damper.

    * fin damper: the rudder moves by -k . [fin tip twist rate, twist, deflection rate, deflection] about
      the trim, k sized on the full linear model with the environment's zero-order hold
      (:func:`lqr_design.design_fin_damper`; at 50 Hz the fin flutter mode, 28.7 Hz, is above the
      Nyquist frequency and the stabilising gains lie in a narrow window; figures in docs/environments.md);
    * speed: thrust = trim - 3000 N/(m/s) x airspeed error; pitch and altitude: elevator = trim + 0.2 dtheta
      + 0.05 q + 0.0005 rad/m x altitude error (trailing edge down when high); roll: aileron = trim + 0.2 phi.

    The gains are checked together on the sampled full model (``self.lqr.full_model_growth`` < 0). An
    LQR on the residualised rigid-body model is not used here: at this condition the residualisation
    is ill-posed (see :mod:`lqr_design`).
    """

    sensors = ("tip_twist_rate_vtail_rad_s", "tip_twist_vtail_rad", "tip_deflection_rate_vtail_m_s", "tip_deflection_vtail_m")
    #: K entries (control index, state) of du = -K dx: thrust on u, elevator on z, theta, q, aileron on phi.
    gains = {(0, "u_m_s"): 3000.0, (2, "z_m"): 0.0005, (2, "theta_rad"): -0.2, (2, "q_rad_s"): -0.05, (1, "phi_rad"): -0.2}

    def __init__(self, env) -> None:
        super().__init__(env)
        self.damper_gains: np.ndarray | None = None
        self._i_sensors = [self.names.index(n) for n in self.sensors]

    def reset(self, info: dict) -> None:
        if self.damper_gains is not None:
            return
        dyn = self.env.dynamics
        point = dyn.trim(self.env.target)
        rows = fin_sensor_rows(dyn)
        self.damper_gains, self.open_loop_growth, self.closed_loop_growth = design_fin_damper(dyn.model, point.x, point.u, self.env.dt, rows)
        damper = np.zeros((4, dyn.layout.n_states))
        damper[3] = self.damper_gains @ rows
        self._y_trim = rows @ point.x
        self.lqr = checked_feedback(dyn.model, point.x, point.u, self.gains, self.env.dt, extra_feedback=damper)

    def controls(self, obs: np.ndarray) -> np.ndarray:
        u = super().controls(obs)
        y = np.asarray(obs, float)[self._i_sensors]
        u[3] -= float(self.damper_gains @ (y - self._y_trim))
        return u


class WingFlutterAileronDamper(_LqrPolicy):
    """FlutterMargin-v1: the holds of :class:`FlutterPidDamper` plus an antisymmetric-aileron twist-rate damper.

    * damper: aileron = trim - k x (antisymmetric wing tip twist rate 0.5 (psi_R' + psi_L'), observation
      ``wing_twist_rate_rad_s``), k = 0.015 rad per rad/s. Chosen on the environment's own linearisation
      at the trim (full model discretised with the 50 Hz zero-order hold, together with the holds): the
      largest growth rate of the modes faster than 20 rad/s (:func:`elastic_growth`) is +0.42 1/s without
      the damper and -0.20 1/s with it; the fast modes are stable for k in about 0.0076-0.0237, and the
      largest growth rate over all modes (``lqr_design.checked_feedback``) is -0.036 1/s, a slow
      rigid-body mode (docs/environments.md, regenerated by tools/regenerate_docs_figures.py);
    * speed, pitch, altitude and roll holds: as :class:`FlutterPidDamper` (thrust on airspeed, elevator on
      theta, q and altitude, aileron on bank).

    ``self.lqr.full_model_growth`` (all modes) and ``self.elastic_growth`` (modes faster than 20 rad/s)
    report the check (made at the first reset).
    """

    damper_gain = 0.015
    gains = FlutterPidDamper.gains

    def __init__(self, env) -> None:
        super().__init__(env)
        self._i_rate = self.names.index("wing_twist_rate_rad_s")
        self.elastic_growth = math.nan

    def reset(self, info: dict) -> None:
        if self.lqr is not None:
            return
        dyn = self.env.dynamics
        point = dyn.trim(self.env.target)
        row = np.zeros(dyn.layout.n_states)
        for c in ("right_wing", "left_wing"):
            row[dyn.sensors[c].eta_idx] += 0.5 * dyn.sensors[c].psi_tip
        damper = np.zeros((4, dyn.layout.n_states))
        damper[1] = self.damper_gain * row
        self.lqr = checked_feedback(dyn.model, point.x, point.u, self.gains, self.env.dt, extra_feedback=damper)
        self.elastic_growth = elastic_growth(self.env, self.gains, damper)

    def controls(self, obs: np.ndarray) -> np.ndarray:
        u = super().controls(obs)
        u[1] -= self.damper_gain * float(np.asarray(obs, float)[self._i_rate])
        return u


def fin_sensor_rows(dyn) -> np.ndarray:
    """Rows (4, n_states) of the fin damper's sensors as linear functions of the state (``dyn``: the env's
    dynamics): fin tip twist rate, twist, deflection rate, deflection."""
    fin = dyn.sensors["vtail"]
    rows = np.zeros((4, dyn.layout.n_states))
    for row, (idx, shape) in zip(rows, ((fin.eta_idx, fin.psi_tip), (fin.xi_idx, fin.psi_tip), (fin.s_idx, fin.w_tip),
                                        (fin.q_idx, fin.w_tip))):
        row[idx] = shape
    return rows


def elastic_growth(env, gains: dict, extra_feedback: np.ndarray) -> float:
    """Largest growth rate [1/s] of the sampled closed loop's modes faster than 20 rad/s (the elastic modes)
    at the trim of ``env.target`` (full linearisation, zero-order hold at the control period)."""
    dyn = env.dynamics
    point = dyn.trim(env.target)
    lay = dyn.layout
    fb = checked_feedback(dyn.model, point.x, point.u, gains, env.dt)
    drop = [lay.position.start, lay.position.start + 1, lay.euler.start + 2]
    ad, bd, keep = _discrete_full_model(dyn.model, point.x, point.u, env.dt, drop)
    states = fb.states
    rigid = np.zeros((4, len(keep)))
    cols = [keep.index(i) for i in _rigid_indices(lay, states)]
    rigid[:, cols] = fb.gain
    z = np.linalg.eigvals(ad - bd @ (rigid + np.asarray(extra_feedback, float)[:, keep]))
    s = np.log(z.astype(complex)) / env.dt
    fast = s[np.abs(s.imag) > 20.0]
    return float(fast.real.max())


class TrimHold:
    """Holds the controls of the episode's trim (``info["trim_action"]`` at reset): the open-loop reference that
    a gust-alleviation controller has to beat (the very flexible HALE's baseline)."""

    def __init__(self, env) -> None:
        self.action = None

    def reset(self, info: dict) -> None:
        self.action = np.asarray(info["trim_action"], dtype=np.float32)

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        return self.action


class RandomPolicy:
    """Uniform random actions from the action space (seeded at every reset)."""

    def __init__(self, env) -> None:
        self.space = env.action_space
        self._episode = 0

    def reset(self, info: dict, seed: int | None = None) -> None:
        self.space.seed(seed if seed is not None else self._episode)
        self._episode += 1

    def __call__(self, obs: np.ndarray) -> np.ndarray:
        return self.space.sample()


BASELINES = {"FlexSim/GTM-LevelHold-v0": LevelHoldLqr, "FlexSim/GTM-LevelHold-v1": LevelHoldLqr, "FlexSim/GTM-Turn-v0": TurnLqr,
             "FlexSim/GTM-GustAlleviation-v0": GustLqr, "FlexSim/GTM-FlutterMargin-v0": FlutterPidDamper,
             "FlexSim/GTM-FlutterMargin-v1": WingFlutterAileronDamper, "FlexSim/HALE-GustAlleviation-v0": TrimHold}


def make_baseline(env_id: str, env):
    """The baseline policy of ``env_id`` for ``env``."""
    if env_id not in BASELINES:
        raise ValueError(f"env_id = {env_id!r}: must be one of {', '.join(BASELINES)}")
    return BASELINES[env_id](env)


def run_episode(env, policy, seed: int) -> tuple[float, int, str]:
    """Return, length and termination reason ("" if truncated) of one seeded episode."""
    obs, info = env.reset(seed=seed)
    if isinstance(policy, RandomPolicy):
        policy.reset(info, seed=seed)
    else:
        policy.reset(info)
    total, steps = 0.0, 0
    while True:
        obs, reward, terminated, truncated, info = env.step(policy(obs))
        total += reward
        steps += 1
        if terminated or truncated:
            return total, steps, info.get("termination_reason", "") if terminated else ""
        if not math.isfinite(total):
            raise RuntimeError(f"non-finite return after {steps} steps")


def main(argv: list[str] | None = None) -> None:
    """Command line: run one seeded episode of an environment's baseline and print its return."""
    import argparse
    import os

    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    import gymnasium as gym

    import flexsim.envs  # noqa: F401  (registers the ids)

    parser = argparse.ArgumentParser(
        prog="python examples/agents/baselines.py", description=__doc__.splitlines()[0],
        epilog="Example: python examples/agents/baselines.py --env FlexSim/GTM-LevelHold-v0 --seed 0. "
               "Compare with a random policy over many episodes: python examples/agents/evaluate_baselines.py")
    parser.add_argument("--env", default="FlexSim/GTM-LevelHold-v0", choices=list(BASELINES), help="task id [%(default)s]")
    parser.add_argument("--seed", type=int, default=0, help="episode seed [%(default)s]")
    args = parser.parse_args(argv)
    env = gym.make(args.env)
    total, steps, reason = run_episode(env, make_baseline(args.env, env), args.seed)
    env.close()
    print(f"{args.env} baseline, seed {args.seed}: return {total:.2f} over {steps} steps "
          f"({'ended by ' + reason if reason else 'time limit'})")


if __name__ == "__main__":
    main()
