"""Generate flexsim/aircraft/data/gtm.toml from the notional GTM research note (option A, 100 t).

Source: flexsim/aircraft/data/sources/gtm-notional.md (sections 3a-3d; its gtm_notional_params.json and
wing_stations_optionA_n4.csv beside it, provenance in docs/reference/README.md): a notional full-scale NASA GTM assembled from public data (NASA
GTM_DesignSim T2 sub-scale data scaled by 1/0.055, Boeing 757-200 public data). Positions are written
in the note's design frame (origin at the nose, x aft, y right, z up); flexsim converts them to body axes.
The note's formulas and tables are transcribed below with their section numbers; the tool reads nothing
but its own arguments, so it regenerates the bundled files from the repository alone
(tests/aircraft/test_make_gtm_toml.py). The calibrated default applies the stiffness factors fitted by
studies/calibrate_gtm.py (docs/calibration.md). Run from the repository root:
    python tools/make_gtm_toml.py > flexsim/aircraft/data/gtm_uncalibrated.toml
    python tools/make_gtm_toml.py --calibration tools/gtm_calibration.toml > flexsim/aircraft/data/gtm.toml
    python tools/make_gtm_toml.py --calibration tools/gtm_calibration.toml --paper > flexsim/aircraft/data/gtm_paper.toml
``--paper`` writes the paper-reproduction aircraft: the paper's weight, 889.4 kN (its Tables 2-3 give
T_e = 889.4 kN x sin(theta) in all eight rows), reached by burning centre-tank fuel (the tank a 757
empties first), and the paper's force resolution (``formulation = "paper"``); see gtm.md.
"""

import argparse
import math
import tomllib

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--ea", type=float, default=0.375, help="elastic axis of wing and stabilizer [fraction of chord]")
parser.add_argument("--calibration", help="TOML with a [scaling] table of StructuralScaling factors")
parser.add_argument("--paper", action="store_true",
                    help="paper-reproduction aircraft: weight 889.4 kN (centre-tank fuel burnt), formulation = \"paper\"")
args = parser.parse_args()
SCALE = {"wing_ei": 1.0, "wing_gj": 1.0, "fuselage_ei": 1.0, "fuselage_gj": 1.0, "htail_stiffness": 1.0, "vtail_stiffness": 1.0,
         "mass": 1.0}
DAMPING = 0.0
if args.calibration:
    with open(args.calibration, "rb") as fh:
        calibration = tomllib.load(fh)
    fitted = calibration["scaling"]
    DAMPING = float(calibration.get("fixed", {}).get("structural_damping_ratio", 0.0))
    unknown = sorted(set(fitted) - set(SCALE))
    if unknown:
        raise SystemExit(f"{args.calibration}: [scaling] {unknown[0]}: not one of {', '.join(SCALE)}")
    SCALE.update(fitted)
# flexsim.aircraft.calibration.StructuralScaling: the mass factor multiplies every mass, inertia and stiffness
K = SCALE["mass"]
for key in ("wing_ei", "wing_gj", "fuselage_ei", "fuselage_gj", "htail_stiffness", "vtail_stiffness"):
    SCALE[key] *= K
L_F = 44.35
# Elastic axis of wing and horizontal stabilizer as a fraction of the chord from the leading edge. The
# paper: "x_i is ab = -0.25b behind the respective line of geometric centers"; with Theodorsen's a = -0.25
# (the reading adopted, docs/calibration.md) the axis is at 0.375 c; the research note read a = +0.25
# (0.625 c). The mass axis stays at 0.5 c either way.
EA = args.ea
# Centre-tank fuel [kg]: 10.8 t in option A (note 3d). The paper's weight W = 889.4 kN (T_e / sin(theta)
# = 889.41-889.47 kN in Tables 2-3) is m = 889.4e3 / 9.80665 = 90,693.7 kg, i.e. 9,320.8 kg less than
# option A's 100,014.4 kg as flexsim integrates it (`flexsim info gtm`, gtm.md): the centre tank, emptied
# first in a 757's fuel schedule, keeps 1,479 kg. Wing, tail and engine tables are unchanged.
PAPER_WEIGHT_N = 889.4e3
OPTION_A_MASS_KG = 100014.44
CENTRE_FUEL_KG = 10800.0 - (OPTION_A_MASS_KG - PAPER_WEIGHT_N / 9.80665) if args.paper else 10800.0


out = []
w = out.append


def fmt(values, digits=6):
    return "[" + ", ".join(f"{v:.{digits}g}" for v in values) + "]"


def beam(key, root, euler, length):
    """The head of the beam component [components.KEY] (root and Euler angles as TOML text), 2 + 2 modes."""
    w(f'[components.{key}]')
    w(f'root_m = {root}')
    w(f'euler_deg = {euler}')
    w(f'length_m = {length}')
    w('bending_modes = 2')
    w('torsion_modes = 2')


def lifting(key, strips, lift_slope, kind, hinge_fraction, start_m, end_m):
    """The strips of the beam KEY (``lift_slope`` as TOML text) and its control surface."""
    w(f'[components.{key}.aero]')
    w(f'strips = {strips}')
    w(f'lift_slope = {lift_slope}')
    w(f'[components.{key}.control_surface]')
    w(f'kind = "{kind}"')
    w(f'hinge_fraction = {hinge_fraction}')
    w(f'start_m = {start_m}')
    w(f'end_m = {end_m}')


def item(table, name, component, position, **fields):
    """An entry of the array of tables [[TABLE]] on COMPONENT at POSITION (design frame), ``fields`` as TOML text."""
    w(f'[[{table}]]')
    w(f'name = "{name}"')
    w(f'component = "{component}"')
    w(f'position_m = [{position[0]}, {position[1]}, {position[2]}]')
    for key, value in fields.items():
        w(f'{key} = {value}')
    w('')


def distribute(total, raw, stations):
    """``raw`` scaled so that its trapezoidal integral over ``stations`` is ``total``."""
    integral = sum((raw[k] + raw[k + 1]) / 2 * (stations[k + 1] - stations[k]) for k in range(len(stations) - 1))
    return [total * r / integral for r in raw]


w('# Notional full-scale NASA Generic Transport Model (GTM), '
  + ('the paper\'s weight (889.4 kN: option A less 9.3 t of centre-tank fuel), the paper\'s force resolution'
     if args.paper else 'option A (100 t, mid-cruise)')
  + (', stiffness calibrated to Tuzcu & Nguyen (2014) Table 3.' if args.calibration else ', uncalibrated.'))
w('# Generated by tools/make_gtm_toml.py from flexsim/aircraft/data/sources/gtm-notional.md; provenance and the')
w('# uncertain (calibration) parameters are documented in gtm.md beside this file.')
w('schema_version = 1')
w('name = "GTM-notional-paper"' if args.paper else 'name = "GTM-notional-A"' if args.calibration else 'name = "GTM-notional-A-uncalibrated"')
if args.calibration:
    w('# stiffness factors (docs/calibration.md): ' + ", ".join(f"{k} = {v:.4g}" for k, v in SCALE.items()))
    w(f'structural_damping_ratio = {DAMPING}   # modal damping of every elastic mode (assumed; the paper has none)')
if args.paper:
    w('formulation = "paper"   # force resolution of eq. (28) as the paper\'s trims imply: T_e = W sin(theta) (docs/design.md)')
    w('description = "Notional full-scale NASA GTM at the paper\'s weight (889.4 kN) from public data; structure estimated, see gtm.md"')
else:
    w('description = "Notional full-scale NASA GTM (757-200 class, 100 t) from public data; structure estimated, see gtm.md"')
w('')
w('[frame]')
w('kind = "design"                 # x aft from the nose, y right, z up [m]')
w(f'body_origin_m = [{L_F}, 0.0, 0.0]   # body origin o: fuselage tail end, where the fuselage beam is clamped')
w('')

# Fuselage (note section 3b): mass per length piecewise linear, EI_vert points, GJ = 0.76 EI, I_x = m (1.5 m)^2.
xd = [0.0, 5.0, 15.0, 18.0, 26.0, 35.0, 35.5, 40.0, 44.35]
def m_f(x):
    if x <= 5.0:
        return 441 + (1259 - 441) * x / 5.0
    if x <= 35.5:
        return 1259.0
    return 1259 + (315 - 1259) * (x - 35.5) / (44.35 - 35.5)
ei_pts = [(0, 1.0), (5, 8), (15, 20), (18, 25), (26, 25), (35, 12), (40, 5), (44.35, 1.5)]
def ei_f(x):
    for (x0, e0), (x1, e1) in zip(ei_pts[:-1], ei_pts[1:]):
        if x0 <= x <= x1:
            return 1e9 * (e0 + (e1 - e0) * (x - x0) / (x1 - x0))
    raise ValueError(x)
st = [L_F - x for x in reversed(xd)]
mf = [m_f(L_F - s) for s in st]
eif = [ei_f(L_F - s) for s in st]
beam('fuselage', f'[{L_F}, 0.0, 0.0]', '[0.0, 0.0, 0.0]        # paper Table 1: x_f along body x (forward from the tail)', L_F)
w('section_inertia = "axisymmetric"')
w('[components.fuselage.sections]')
w(f'station_m = {fmt(st)}')
w(f'mass_kg_per_m = {fmt([K * m for m in mf])}')
w(f'torsional_inertia_kg_m = {fmt([K * m * 1.5**2 for m in mf])}')
w(f'ei_nm2 = {fmt([SCALE["fuselage_ei"] * e for e in eif])}')
w(f'gj_nm2 = {fmt([SCALE["fuselage_gj"] * 0.76 * e for e in eif])}')
w('')

# Chords and chordwise offsets are streamwise (flexsim's convention); torsional inertias are about the
# elastic axis, as in the note.
# Wings (note 3a-3b): crank planform in y (streamwise chord 7.74 at the side of body y = 1.88, 5.59 at the
# crank y = 6.56, 1.55 at the tip y = 18.9), beam station s = (y - 1.88) * 18.25 / 17.02;
# m_struct = k c^1.6 with 5500 kg per side; m_fuel = k c^2 for y <= 14.2 m with 6600 kg per side;
# I_EA = m_s (0.25 c_n)^2 + m_f (0.15 c_n)^2 + m ((0.5 - EA) c_n)^2; EI, GJ = (7.76e8, 1.385e9) (c/7.738)^4.
# (The note's 11-station CSV is a coarse sampling of these formulas; linear interpolation of it would
# smear the fuel past y = 14.2 m, so the tables are re-sampled finely here.)
COS_W = math.cos(math.radians(20.55))
DS_DY = 18.25 / (18.9 - 1.88)
def chord_w(y):
    if y <= 6.56:
        return 7.74 + (5.59 - 7.74) * (y - 1.88) / (6.56 - 1.88)
    return 5.59 + (1.55 - 5.59) * (y - 6.56) / (18.9 - 6.56)
Y_FUEL = 14.2
ys = sorted(set([1.88 + (6.56 - 1.88) * k / 4 for k in range(5)]
                + [6.56 + (Y_FUEL - 6.56) * k / 8 for k in range(9)]
                + [Y_FUEL + 0.001] + [Y_FUEL + 0.001 + (18.9 - Y_FUEL - 0.001) * k / 5 for k in range(1, 6)]))
s = [(y - 1.88) * DS_DY for y in ys]
s[-1] = 18.25
c_st = [chord_w(y) for y in ys]
cn = [c * COS_W for c in c_st]
ms = distribute(5500.0, [c**1.6 for c in c_st], s)
mfu = distribute(6600.0, [c**2 if y <= Y_FUEL else 0.0 for c, y in zip(c_st, ys)], s)
mt = [a + b for a, b in zip(ms, mfu)]
iea = [a * (0.25 * c) ** 2 + b * (0.15 * c) ** 2 + (a + b) * ((0.5 - EA) * c) ** 2 for a, b, c in zip(ms, mfu, cn)]
ei = [7.76e8 * (c / 7.738) ** 4 for c in c_st]
gj = [1.385e9 * (c / 7.738) ** 4 for c in c_st]
x_ea_root = 18.49 + EA * 7.738
for side, sign in (("right", 1.0), ("left", -1.0)):
    beam(f'{side}_wing', f'[{x_ea_root:.4f}, {sign * 1.88}, -1.6]     # side of body, elastic axis at {EA} c, low wing',
         f'[0.0, 5.16, {sign * 110.55}]     # paper Table 1', 18.25)
    lifting(f'{side}_wing', 10, '"vlm"              # paper: vortex lattice of wing + stabilizer, Prandtl-Glauert on top',
            'aileron', 0.8, 11.0, 16.4)
    w(f'[components.{side}_wing.sections]')
    w(f'station_m = {fmt(s)}')
    w(f'mass_kg_per_m = {fmt([K * m for m in mt])}')
    w(f'cg_offset_m = {fmt([(0.5 - EA) * c for c in c_st])}   # mass axis 0.5 c')
    w(f'torsional_inertia_kg_m = {fmt([K * i for i in iea])}')
    w(f'ei_nm2 = {fmt([SCALE["wing_ei"] * e for e in ei])}')
    w(f'gj_nm2 = {fmt([SCALE["wing_gj"] * g for g in gj])}')
    w(f'chord_m = {fmt(c_st)}   # streamwise')
    w(f'ea_fraction = {fmt([EA] * len(s))}')
    w('')

# Horizontal tail (note 3a-3b): 7.03 m, chord 4.5 -> 1.55 (streamwise), 650 kg per side ~ c^1.5,
# I_EA 258 -> 6 kg m, EI = GJ = 6e7 (c/4.5)^3.
def lin(a, b, n):
    return [a + (b - a) * k / (n - 1) for k in range(n)]
n = 6
sh = lin(0.0, 7.03, n)
ch = lin(4.5, 1.55, n)
cos_h = math.cos(math.radians(25.51))
mh = distribute(650.0, [c**1.5 for c in ch], sh)
ih = [max(m * (0.28 * c * cos_h) ** 2, m * ((0.5 - EA) * c * cos_h) ** 2) for m, c in zip(mh, ch)]
for side, sign in (("right", 1.0), ("left", -1.0)):
    beam(f'{side}_htail', f'[{40.18 + (EA - 0.5) * 4.5:.4f}, {sign * 1.30}, 0.7]',
         f'[0.0, 6.39, {sign * 115.51}]     # paper Table 1', 7.03)
    lifting(f'{side}_htail', 6, '"vlm"', 'elevator', 0.7, 0.0, 7.03)
    w(f'[components.{side}_htail.sections]')
    w(f'station_m = {fmt(sh)}')
    w(f'mass_kg_per_m = {fmt([K * m for m in mh])}')
    w(f'cg_offset_m = {fmt([(0.5 - EA) * c for c in ch])}')
    w(f'torsional_inertia_kg_m = {fmt([K * i for i in ih])}')
    w(f'ei_nm2 = {fmt([SCALE["htail_stiffness"] * 6e7 * (c / 4.5) ** 3 for c in ch])}')
    w(f'gj_nm2 = {fmt([SCALE["htail_stiffness"] * 6e7 * (c / 4.5) ** 3 for c in ch])}')
    w(f'chord_m = {fmt(ch)}')
    w(f'ea_fraction = {fmt([EA] * n)}')
    w('')

# Vertical tail: 8.97 m, chord 7.0 -> 2.4, 1000 kg ~ c^1.5, EA 0.5 c, mass axis 0.45 c,
# EI 2e8, GJ 1.8e8 (c/7)^3.
sv = lin(0.0, 8.97, n)
cv = lin(7.0, 2.4, n)
cos_v = math.cos(math.radians(35.53))
mv = distribute(1000.0, [c**1.5 for c in cv], sv)
beam('vtail', '[38.29, 0.0, 1.85]', '[90.0, 125.53, 0.0]     # paper Table 1', 8.97)
lifting('vtail', 5, '2.94   # Helmbold, effective aspect ratio 1.55 x 1.55 (geometric x end-plate factor, DATCOM)', 'rudder',
        0.7, 0.0, 8.0)
w('[components.vtail.sections]')
w(f'station_m = {fmt(sv)}')
w(f'mass_kg_per_m = {fmt([K * m for m in mv])}')
w(f'cg_offset_m = {fmt([-0.05 * c for c in cv])}')
w(f'torsional_inertia_kg_m = {fmt([K * m * (0.28 * c * cos_v) ** 2 for m, c in zip(mv, cv)])}')
w(f'ei_nm2 = {fmt([SCALE["vtail_stiffness"] * 2e8 * (c / 7.0) ** 3 for c in cv])}')
w(f'gj_nm2 = {fmt([SCALE["vtail_stiffness"] * 1.8e8 * (c / 7.0) ** 3 for c in cv])}')
w(f'chord_m = {fmt(cv)}')
w(f'ea_fraction = {fmt([0.5] * n)}')
w('')

for name, comp, pos, mass in (
    ("centre_tank_fuel", "fuselage", (21.33, 0.0, -1.3), CENTRE_FUEL_KG),
    ("main_gear", "fuselage", (23.6, 0.0, -1.0), 3700.0),
    ("nose_gear", "fuselage", (4.5, 0.0, -1.2), 600.0),
):
    item('lumped_masses', name, comp, pos, mass_kg=f'{K * mass:.6g}')
for side, sign in (("right", 1.0), ("left", -1.0)):
    item('engines', f'{side}_engine', f'{side}_wing', (19.93, sign * 6.56, -2.2), mass_kg=f'{K * 4400.0:.6g}',
         inertia_kg_m2=fmt([K * 2200.0, K * 9900.0, K * 9900.0]), max_thrust_n=178000.0)
# Parasite (zero-lift) drag of the calibrated default (not in the paper; docs/options.md "Drag"): drag areas
# f = C_fe S_wet with Raymer's equivalent skin-friction coefficient C_fe = 0.0026 for civil transports
# (Raymer, Aircraft Design: A Conceptual Approach, 6th ed., 2018, sec. 12.5). Wetted areas: fuselage
# pi D L (1 - 2/lambda)^(2/3) (1 + 1/lambda^2) with L = 44.35 m, D = 3.76 m (Torenbeek 1982, app. F): 466.2 m^2;
# wing 2 x 155.2 m^2 = S_exposed (1.977 + 0.52 t/c), S_exposed = 181.25 - 3.76 x 7.74 m^2, t/c = 0.12 (Raymer
# ch. 7); horizontal tail 2 x 45.7 m^2 (exposed 45 of 50.4 m^2, t/c = 0.10); fin 69.6 m^2 (34.3 m^2); nacelle and
# pylon 46 m^2 each (RB211-535 class, 2.5 m x 6.0 m). Points: fuselage mid-length, 40 % span of each surface
# on its elastic axis, the engines. Total f = 2.677 m^2: C_D0 = 0.0148 on 181.25 m^2.
# Validity limit of the linear (no-stall) strip aerodynamics, |alpha| of the CG (flexsim/trimming/solver.py
# _check_limits): the end of the NASA GTM's linear lift range in its wind-tunnel database (the T2's, NASA
# GTM_DesignSim, sources/t2_aero_basic_beta0.csv): CN = -CZ stays within 10 % of its line over alpha = 0-6 deg
# up to 11 deg (8.2 % below; 12.6 % at 12 deg). flexsim.aircraft.t2_data.t2_linear_alpha_limit_deg computes it
# from the CSV and tests/aircraft/test_gtm_alpha_limit.py checks this value against it.
w('[aero]')
w('max_alpha_deg = 11.0   # linear range of the GTM\'s lift curve, NASA T2 wind-tunnel database (tools/make_gtm_toml.py)')
if args.calibration and not args.paper:  # the paper-replication file keeps the paper's induced drag only
    # Downwash of the wing at the horizontal tail (not in the paper; flexsim/model/coupling.py tail_downwash):
    # USAF DATCOM sec. 4.4.1 (Hoak et al. 1978), d eps/d alpha at M -> 0 = 4.44 [K_A K_lambda K_H sqrt(cos L_c/4)]^1.19,
    # K_A = 1/A - 1/(1 + A^1.7), K_lambda = (10 - 3 lambda)/7, K_H = (1 - |h_H/b|)/(2 l_H/b)^(1/3), with the reference
    # wing of the note (section 3a): A = 7.88, taper 1.55/8.60, quarter-chord sweep 25 deg, b = 37.8 m; l_H = 20.86 m
    # from the wing's root quarter chord (x = 17.46 + 8.60/4) to the quarter chord of the tail's mean chord
    # (x = 40.47 m), h_H = 2.63 m the height of the tail's mean chord (z = 1.03 m) above the wing root (z = -1.6 m).
    A_W, TAPER_W, SWEEP_W, B_W, L_H, H_H = 7.88, 1.55 / 8.60, math.radians(25.0), 37.8, 20.86, 2.63
    k_a = 1.0 / A_W - 1.0 / (1.0 + A_W**1.7)
    k_lambda = (10.0 - 3.0 * TAPER_W) / 7.0
    k_h = (1.0 - abs(H_H / B_W)) / (2.0 * L_H / B_W) ** (1.0 / 3.0)
    w(f'downwash_gradient = {4.44 * (k_a * k_lambda * k_h * math.sqrt(math.cos(SWEEP_W))) ** 1.19:.4f}   # d eps/d alpha at M -> 0, DATCOM 4.4.1 (tools/make_gtm_toml.py)')
    w('')
    for name, comp, pos, area in (
        ("fuselage", "fuselage", (22.175, 0.0, 0.0), 1.212),
        ("right_wing_profile", "right_wing", (23.944, 8.688, -0.943), 0.4035),
        ("left_wing_profile", "left_wing", (23.944, -8.688, -0.943), 0.4035),
        ("right_nacelle", "right_wing", (19.93, 6.56, -2.2), 0.1196),
        ("left_nacelle", "left_wing", (19.93, -6.56, -2.2), 0.1196),
        ("right_htail_profile", "right_htail", (40.821, 3.822, 1.013), 0.1187),
        ("left_htail_profile", "left_htail", (40.821, -3.822, 1.013), 0.1187),
        ("fin_profile", "vtail", (40.375, 0.0, 4.77), 0.181),
    ):
        item('aero.drag', name, comp, pos, drag_area_m2=area)
# Slender bodies carrying Munk's moment (not in the paper; flexsim/model/bodies.py, docs/options.md "Fuselage and
# nacelle moments"): the fuselage, L = 44.35 m, D = 3.76 m (the drag build-up's), and each nacelle, 6.0 m x 2.5 m
# (RB211-535 class, as above), with volume C_p pi D^2 L / 4 for a prismatic coefficient C_p = 0.8 [E] (a
# cylindrical centre body with nose and tail cones; fuselage 394 m^3, nacelle 23.6 m^3). Reference points: the
# fuselage's mid-length on its axis, the engines.
if args.calibration and not args.paper:  # the paper-replication file keeps the paper's strips only
    for name, comp, pos, length, diameter in (
        ("fuselage", "fuselage", (22.175, 0.0, 0.0), L_F, 3.76),
        ("right_nacelle", "right_wing", (19.93, 6.56, -2.2), 6.0, 2.5),
        ("left_nacelle", "left_wing", (19.93, -6.56, -2.2), 6.0, 2.5),
    ):
        item('aero.body', name, comp, pos, length_m=length, diameter_m=diameter,
             volume_m3=f'{0.8 * math.pi * diameter**2 * length / 4.0:.4f}')
# Flutter search range (docs/aircraft-format.md, [envelope]): the paper's, Mach 0.5-0.95 at every altitude (its
# Tables 2-3 find M_F = 0.67-0.78), so that `flexsim flutter` searches this aircraft where the paper did. Not a
# certified envelope: the notional GTM has none.
if out[-1] != '':
    w('')
w('[envelope]')
w('min_mach = 0.5    # the paper\'s flutter search range (Tables 2-3), not a certified envelope')
w('max_mach = 0.95')
# Cruise point (where `flexsim trim`, `linearize` and `simulate` fly it when no condition is given): 9144 m (30 000 ft,
# the paper's highest altitude) at M 0.78; the flutter altitudes without --altitudes: sea level to 9144 m in four
# levels, the paper's 0, 3048, 6096, 9144 m.
w('cruise_altitude_m = 9144.0')
w('cruise_mach = 0.78')
w('max_altitude_m = 9144.0')
print("\n".join(out))
