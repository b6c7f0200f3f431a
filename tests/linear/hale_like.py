"""A HALE aircraft in the style of Patil, Hodges & Cesnik (2001) for tests: written here, not read from elsewhere.

Wing: semispan 16 m, chord 1 m, elastic axis and CG at 50 % chord, 0.75 kg/m, I_theta 0.1 kg m, GJ 1e4 N m^2,
EI 2e4 N m^2 (Patil, Hodges & Cesnik, J. Aircraft 38(1), 2001, Table 1); rigid 10 m tail boom and tails; a 50 kg
payload at the wing root carrying the thrust. The two wing halves are rooted at y = +-0.05 m.
"""

from __future__ import annotations

from pathlib import Path


def _beam(name: str, root: str, euler: str, length: float, body: str) -> str:
    return f"""
[components.{name}]
root_m = {root}
euler_deg = {euler}
length_m = {length}
{body}"""


_WING = """bending_modes = 3
torsion_modes = 2
section_inertia = "chordwise"
[components.{n}.aero]
strips = 16
lift_slope = "2pi"
cd0 = 0.01
[components.{n}.control_surface]
kind = "aileron"
hinge_fraction = 0.75
start_m = 10.0
end_m = 16.0
[components.{n}.sections]
station_m = [0.0, 16.0]
mass_kg_per_m = [0.75, 0.75]
cg_offset_m = [0.0, 0.0]
torsional_inertia_kg_m = [0.1, 0.1]
ei_nm2 = [2.0e4, 2.0e4]
gj_nm2 = [1.0e4, 1.0e4]
chord_m = [1.0, 1.0]
ea_fraction = [0.5, 0.5]
"""

_TAIL = """rigid = true
[components.{n}.aero]
strips = 4
lift_slope = "2pi"
cd0 = 0.01
[components.{n}.control_surface]
kind = "{kind}"
hinge_fraction = 0.75
start_m = 0.0
end_m = 2.5
[components.{n}.sections]
station_m = [0.0, 2.5]
mass_kg_per_m = [0.08, 0.08]
torsional_inertia_kg_m = [0.001, 0.001]
ei_nm2 = [1.0e6, 1.0e6]
gj_nm2 = [1.0e6, 1.0e6]
chord_m = [0.5, 0.5]
"""


def hale_toml(envelope: bool = True, rigid_wings: bool = False, payload_x_m: float = 0.0) -> str:
    """The aircraft file's text; ``rigid_wings``: the wings rigid too (no elastic mode at all); ``payload_x_m``: the
    payload that far aft of the wing root [m] (3 m puts the CG behind the neutral point: pitch-unstable)."""
    parts = ['schema_version = 1\nname = "hale-test"\n\n[frame]\nkind = "design"\nbody_origin_m = [10.0, 0.0, 0.0]\n\n'
             "[aero]\nmax_alpha_deg = 12.0\n"]
    parts.append(_beam("fuselage", "[10.0, 0.0, 0.0]", "[0.0, 0.0, 0.0]", 10.0,
                       'rigid = true\nsection_inertia = "axisymmetric"\n[components.fuselage.sections]\n'
                       "station_m = [0.0, 10.0]\nmass_kg_per_m = [0.08, 0.08]\ntorsional_inertia_kg_m = [0.0001, 0.0001]\n"
                       "ei_nm2 = [1.0e8, 1.0e8]\ngj_nm2 = [1.0e8, 1.0e8]\n"))
    wing = _WING.replace("bending_modes = 3\ntorsion_modes = 2\n", "rigid = true\n") if rigid_wings else _WING
    parts.append(_beam("right_wing", "[0.0, 0.05, 0.0]", "[0.0, 0.0, 90.0]", 16.0, wing.format(n="right_wing")))
    parts.append(_beam("left_wing", "[0.0, -0.05, 0.0]", "[0.0, 0.0, -90.0]", 16.0, wing.format(n="left_wing")))
    parts.append(_beam("right_htail", "[10.0, 0.02, 0.0]", "[0.0, 0.0, 90.0]", 2.5, _TAIL.format(n="right_htail", kind="elevator")))
    parts.append(_beam("left_htail", "[10.0, -0.02, 0.0]", "[0.0, 0.0, -90.0]", 2.5, _TAIL.format(n="left_htail", kind="elevator")))
    parts.append(_beam("vtail", "[10.0, 0.0, 0.0]", "[90.0, 90.0, 0.0]", 2.5, _TAIL.format(n="vtail", kind="rudder")))
    parts.append(f'\n[[engines]]\nname = "payload"\ncomponent = "fuselage"\nposition_m = [{payload_x_m!r}, 0.0, 0.0]\nmass_kg = 50.0\n'
                 "inertia_kg_m2 = [200.0, 200.0, 200.0]\nmax_thrust_n = 200.0\n")
    if envelope:
        parts.append("\n[envelope]\nmin_speed_eas_m_s = 4.5\nmax_speed_eas_m_s = 13.5\n")
    return "".join(parts)


def write_hale(folder: Path, envelope: bool = True, rigid_wings: bool = False, payload_x_m: float = 0.0) -> Path:
    """Write the aircraft file into ``folder`` (a test's ``tmp_path``) and return its path."""
    path = Path(folder) / f"hale{'_rigid' if rigid_wings else ''}{f'_{payload_x_m:g}' if payload_x_m else ''}.toml"
    path.write_text(hale_toml(envelope, rigid_wings, payload_x_m), encoding="utf-8")
    return path
