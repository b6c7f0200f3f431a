"""Coordinated turn of the GTM: the issue-11 acceptance figures (docs/options.md).

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

import numpy as np

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.model.aircraft_model import AircraftModel
from flexsim.sim.simulate import simulate
from flexsim.trim import SteadyManoeuvre, trim


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
    g = qs.gravity_m_s2
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
    model = AircraftModel(gtm, aero=args.aero)
    x0 = np.concatenate([point.x, np.zeros(model.layout.n_inflow)])
    result = simulate(model, x0, args.duration, controls=point.u)
    lay = model.layout
    alt = -result.x[:, lay.position][:, 2]
    phi = result.x[:, lay.euler][:, 0]
    psi = result.x[:, lay.euler][:, 2]
    rate = (psi[-1] - psi[0]) / (result.t[-1] - result.t[0])
    print(f"hold {args.duration:.0f} s ({args.aero}, {result.status}): max |altitude drift| {np.abs(alt - alt[0]).max():.3e} m, "
          f"max |bank drift| {np.degrees(np.abs(phi - point.phi).max()):.3e} deg, heading rate {rate:.6f} rad/s "
          f"(V/R = {v / radius:.6f})")


if __name__ == "__main__":
    main()
