"""Effect of the options beyond the paper on the GTM: drag, body moments and downwash, coordinated turn, bending incidence.

Prints (docs/flutter.md "Options beyond the paper" and docs/options.md quote these figures):

* the level-flight flutter point at sea level (finite-state unsteady model, the paper's US within 0.3 %) with
  the bundled GTM's parasite drag on and off, its fuselage/nacelle moments and tail downwash off, and with the
  bending-incidence coupling on;
* the flutter point in a level turn of R = 5 km at sea level: the paper's heading-on-track turn against the
  coordinated turn;
* static aeroelastic figures at 9144 m, M 0.78 (trim at 1 g: pitch, elevator, tip deflection and twist, tip
  strip pitch) and the aileron effectiveness with and without the bending-incidence coupling: the rolling
  moment of 1 deg of aileron on the flexible aircraft held in the stream at the cruise trim's angle of attack
  (restrained model, static elastic equilibrium) over that of the rigid aircraft (Bisplinghoff, Ashley &
  Halfman 1955, sec. 8-5), plus the roll-subsidence root of the free aircraft (quasi-steady).

Takes 5-10 min on 2 cores. Run: python studies/options_effects.py [--skip-flutter]
"""

from __future__ import annotations

import argparse
import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import root

from flexsim.aircraft.toml_loader import load_aircraft
from flexsim.linear.flutter import FlutterAnalysis
from flexsim.linear.stability import spectrum
from flexsim.model.aircraft_model import AircraftModel
from flexsim.model.coupling import AeroOptions
from flexsim.trimming import SteadyManoeuvre, trim


def _with(aircraft, **settings):
    from dataclasses import replace

    return replace(aircraft, aero_settings=replace(aircraft.aero_settings, **settings))


def flutter(aircraft, manoeuvre, label: str) -> None:
    fp = FlutterAnalysis(aircraft, "unsteady").search(manoeuvre, mach_range=(0.6, 0.8), mach_step=0.05)
    t = fp.trim
    print(f"  {label:<44} M_F {fp.mach:.4f}  omega_F {fp.frequency_rad_s:7.3f} rad/s  thrust {t.thrust_n / 1e3:7.2f} kN  "
          f"sideslip(CG) {math.degrees(t.sideslip_cg):+6.2f} deg  rudder {math.degrees(t.u[3]):+6.2f} deg  "
          f"tip {t.tip_deflection_m:+.3f} m  ({fp.mode.dominant_dof})")


def aileron_effectiveness(aircraft, bending: bool, cruise) -> float:
    """Rolling moment of 1 deg aileron, flexible / rigid, restrained at the cruise trim's body velocity."""
    lay_free = AircraftModel(aircraft, aero="quasi-steady").layout
    v_body = cruise.x[lay_free.v]
    model = AircraftModel(aircraft, variant="restrained", aero=AeroOptions("quasi-steady", bending_incidence=bending),
                          gravity_m_s2=0.0, restrained_velocity_m_s=v_body, altitude_m=cruise.manoeuvre.altitude_m)
    lay = model.layout
    el = slice(lay.q.start, lay.xi.stop)

    def moment(delta_a: float, flexible: bool) -> float:
        u = np.array([0.0, delta_a, 0.0, 0.0])
        x = lay.zeros()
        if flexible:
            sol = root(lambda z: model.rhs(0.0, np.concatenate([z, np.zeros(lay.n_states - z.size)]), u)[lay.velocity],
                       np.zeros(el.stop - el.start), method="hybr", options={"xtol": 1e-12})
            x[el] = sol.x
        return float(model.aerodynamic_force(x, u)[3])

    d = math.radians(1.0)
    flex = moment(d, True) - moment(-d, True)
    rigid = moment(d, False) - moment(-d, False)
    return flex / rigid


@dataclass(frozen=True)
class StaticFigures:
    """Static aeroelastic figures of the GTM cruise trim (9144 m, M 0.78, quasi-steady), one bending-incidence setting."""

    theta_rad: float  #: trim pitch [rad]
    elevator_rad: float  #: trim elevator [rad]
    tip_deflection_m: float  #: right-wing tip deflection [m]
    tip_twist_rad: float  #: right-wing tip torsion [rad]
    tip_strip_pitch_rad: float  #: elastic pitch of the right-wing tip strip (torsion + bending slope + rigging) [rad]
    roll_subsidence_1_s: float  #: real part of the roll-subsidence root of the free aircraft [1/s]
    aileron_effectiveness: float  #: rolling moment flexible / rigid [-]


def static_figures(aircraft, bending: bool) -> StaticFigures:
    """Trim the cruise with bending incidence ``bending`` and return its :class:`StaticFigures`."""
    model = AircraftModel(aircraft, aero=AeroOptions("quasi-steady", bending_incidence=bending))
    cruise = trim(model, SteadyManoeuvre.level(9144.0, mach=0.78))
    _, _, q, xi, vel = model.unpack(cruise.x)
    kin = model.aero.kinematics(q, xi, vel, np.zeros(0), cruise.u)
    tip = [i for i, c in enumerate(model.aero.strips.component) if c == "right_wing"][-1]
    spec = spectrum(model, cruise.x, cruise.u, aero_model="quasi-steady")
    roll = min((m for m in spec.of_kind("rigid") if m.eigenvalue.imag == 0.0), key=lambda m: m.eigenvalue.real)
    return StaticFigures(cruise.theta, cruise.u[2], cruise.tip_deflection_m, cruise.tip_twist_rad,
                         float(kin.alpha_el[tip]), roll.eigenvalue.real, aileron_effectiveness(aircraft, bending, cruise))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--skip-flutter", action="store_true")
    args = parser.parse_args()
    gtm = load_aircraft("gtm")
    print("static aeroelastic figures at 9144 m, M 0.78 (quasi-steady):")
    for bending in (False, True):
        f = static_figures(gtm, bending)
        print(f"  bending incidence {'on ' if bending else 'off'}: theta {math.degrees(f.theta_rad):.3f} deg, elevator "
              f"{math.degrees(f.elevator_rad):.3f} deg, tip w {f.tip_deflection_m:+.3f} m, tip twist "
              f"{math.degrees(f.tip_twist_rad):+.3f} deg, tip strip pitch {math.degrees(f.tip_strip_pitch_rad):+.3f} deg, "
              f"roll subsidence {f.roll_subsidence_1_s:.3f} 1/s, aileron effectiveness (flexible/rigid) "
              f"{f.aileron_effectiveness:.3f}")
    if args.skip_flutter:
        return
    print("flutter, sea level, finite-state unsteady model:")
    level = SteadyManoeuvre.level(0.0, mach=0.65)
    flutter(gtm, level, "level flight, parasite drag on (bundled)")
    flutter(_with(gtm, drag=()), level, "level flight, parasite drag off")
    flutter(_with(gtm, bodies=(), downwash_gradient=0.0), level, "level flight, body moments and downwash off")
    flutter(_with(gtm, bending_incidence=True), level, "level flight, bending incidence on")
    flutter(gtm, SteadyManoeuvre.turn(0.0, 5000.0, mach=0.65), "turn R = 5 km, paper (heading on track)")
    flutter(gtm, SteadyManoeuvre.turn(0.0, 5000.0, mach=0.65, coordinated=True), "turn R = 5 km, coordinated")


if __name__ == "__main__":
    main()
