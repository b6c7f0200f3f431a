"""Coordinated turn of the GTM: the figures of docs/options.md.

Trims the coordinated level turn at 9144 m, M 0.78, R = 5 km (zero sideslip at the CG, heading free),
prints sideslip, bank angles and load factors against the closed forms tan(mu) = V^2/(gR),
|F|/W = 1/cos(mu), tan(phi) = G/cos(alpha) (Stevens & Lewis 2003, sec. 3.6), then holds the trim's controls
for 30 s with the nonlinear model and unsteady aerodynamics and prints the altitude, bank and heading-rate
drifts. Takes about 1 min on 2 cores.

Run: python studies/coordinated_turn.py [--duration 30] [--aero unsteady|quasi-steady]
"""

from __future__ import annotations

import argparse
import math
from typing import NamedTuple

import numpy as np

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.simulate import simulate
from flexsim.trimming import SteadyManoeuvre, trim


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--duration", type=float, default=30.0, help="hold time [s]")
    parser.add_argument("--aero", default="unsteady", choices=["unsteady", "quasi-steady"])
    args = parser.parse_args()
    gtm = load_aircraft("gtm")
    radius = 5000.0
    qs = AircraftModel(gtm, aero="quasi-steady")
    man = SteadyManoeuvre.turn(9144.0, radius, mach=0.78, coordinated=True)
    point = trim(qs, man)
    g = qs.terms.gravity_m_s2
    v = man.speed_m_s
    ratio = v * v / (g * radius)
    print(f"coordinated turn R = {radius:.0f} m, 9144 m, M 0.78: V^2/(gR) = {ratio:.5f}")
    print(f"  sideslip at the CG {math.degrees(point.sideslip_cg):+.2e} deg (at o {math.degrees(point.beta):+.4f} deg), "
          f"heading - track {math.degrees(point.heading_offset):.3f} deg")
    print(f"  Euler bank phi {math.degrees(point.phi):.4f} deg: tan(phi)/(V^2/gR) = {math.tan(point.phi) / ratio:.5f}, "
          f"1/cos(phi) = {1 / math.cos(point.phi):.5f}")
    print(f"  wind-axis bank mu {math.degrees(point.bank_wind):.4f} deg: tan(mu)/(V^2/gR) = {math.tan(point.bank_wind) / ratio:.5f}, "
          f"1/cos(mu) = {1 / math.cos(point.bank_wind):.5f}")
    print(f"  load factor |F|/W = {point.load_factor_total:.5f} (closed form {math.hypot(1, ratio):.5f}), n_z = {point.load_factor:.5f}")
    print(f"  controls: thrust {point.u[0] / 1e3:.2f} kN, aileron {math.degrees(point.u[1]):.3f}, elevator "
          f"{math.degrees(point.u[2]):.3f}, rudder {math.degrees(point.u[3]):.3f} deg")
    hold = hold_trim(gtm, point, man, args.duration, args.aero)
    print(f"hold {args.duration:.0f} s ({args.aero}, {hold.method}, {hold.status}): max |altitude drift| "
          f"{hold.altitude_drift_m:.3e} m, max |bank drift| {hold.bank_drift_deg:.3e} deg, heading rate "
          f"{hold.heading_rate_rad_s:.6f} rad/s (V/R = {hold.v_over_r_rad_s:.6f})")


class Hold(NamedTuple):
    """Drifts of a trimmed turn flown with the trim's controls held (``hold_trim``)."""

    altitude_drift_m: float  # max |altitude - altitude at t = 0| [m]
    bank_drift_deg: float  # max |phi - trim phi| [deg]
    heading_rate_rad_s: float  # mean heading rate over the run [rad/s]
    v_over_r_rad_s: float  # the turn rate V/R of the manoeuvre [rad/s]
    method: str  # integration method of ``simulate`` (its default for the aero model)
    status: str


def hold_trim(gtm, point, man: SteadyManoeuvre, duration_s: float, aero: str = "unsteady") -> Hold:
    """Fly the trim point ``point`` of ``man`` for ``duration_s`` with its controls held (nonlinear model, inflow
    states starting at zero, ``simulate``'s default integrator) and measure the drifts."""
    model = AircraftModel(gtm, aero=aero)
    x0 = np.concatenate([point.x, np.zeros(model.layout.n_inflow)])
    result = simulate(model, x0, duration_s, controls=point.u)
    lay = model.layout
    alt = -result.x[:, lay.position][:, 2]
    phi = result.x[:, lay.euler][:, 0]
    psi = result.x[:, lay.euler][:, 2]
    rate = (psi[-1] - psi[0]) / (result.t[-1] - result.t[0])
    return Hold(float(np.abs(alt - alt[0]).max()), float(np.degrees(np.abs(phi - point.phi).max())), float(rate),
                man.speed_m_s / man.turn_radius_m, result.method, result.status)

if __name__ == "__main__":
    main()
