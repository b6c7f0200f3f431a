"""Small user aircraft for the command-line tests, written as a new user would from docs/aircraft-format.md.

``rc_glider_toml`` is a 2 m foam glider of 0.45 kg (fuselage, two wings with ailerons, rigid stabilizers, an elastic fin
without a ``lift_slope``, so the fin's documented default applies); ``envelope`` adds an ``[envelope]`` table.
"""

from __future__ import annotations


def _beam(name: str, root: str, euler: str, length: float, mass: float, ei: float, gj: float, chord: float | None,
          strips: int | None, extra: str = "", rigid: bool = False) -> str:
    modes = "rigid = true" if rigid else "bending_modes = 2\ntorsion_modes = 1"
    aero = f"[components.{name}.aero]\nstrips = {strips}\n{extra}\n" if strips else ""
    chord_line = f"chord_m = [{chord}, {chord}]\nea_fraction = [0.3, 0.3]\n" if chord else ""
    return (f"[components.{name}]\nroot_m = {root}\neuler_deg = {euler}\nlength_m = {length}\n{modes}\n{aero}"
            f"[components.{name}.sections]\nstation_m = [0.0, {length}]\nmass_kg_per_m = [{mass}, {mass}]\n"
            f"torsional_inertia_kg_m = [2e-4, 2e-4]\nei_nm2 = [{ei}, {ei}]\ngj_nm2 = [{gj}, {gj}]\n{chord_line}\n")


def rc_glider_toml(envelope: str = "min_speed_eas_m_s = 6.0\nmax_speed_eas_m_s = 30.0", rigid_fin: bool = False) -> str:
    """TOML text of the glider; ``envelope`` is the body of its ``[envelope]`` table ("" for none); ``rigid_fin``: a
    rigid vertical tail (no elastic modes)."""
    head = ('schema_version = 1\nname = "rc-glider"\nstructural_damping_ratio = 0.02\n'
            '[frame]\nkind = "design"\nbody_origin_m = [1.0, 0.0, 0.0]\n[aero]\nmax_alpha_deg = 10.0\n')
    if envelope:
        head += f"[envelope]\n{envelope}\n"
    wing = 'cd0 = 0.015\nincidence_deg = 2.0'
    body = (_beam("fuselage", "[1.0, 0.0, 0.0]", "[0.0, 0.0, 0.0]", 1.0, 0.05, 200.0, 100.0, None, None)
            + _beam("right_wing", "[0.3, 0.02, 0.0]", "[0.0, 3.0, 90.0]", 1.0, 0.1, 50.0, 20.0, 0.2, 8, wing)
            + _beam("left_wing", "[0.3, -0.02, 0.0]", "[0.0, 3.0, -90.0]", 1.0, 0.1, 50.0, 20.0, 0.2, 8, wing)
            + _beam("right_htail", "[0.95, 0.01, 0.0]", "[0.0, 0.0, 90.0]", 0.25, 0.03, 20.0, 10.0, 0.1, 3, rigid=True)
            + _beam("left_htail", "[0.95, -0.01, 0.0]", "[0.0, 0.0, -90.0]", 0.25, 0.03, 20.0, 10.0, 0.1, 3, rigid=True)
            + _beam("vtail", "[0.95, 0.0, 0.0]", "[90.0, 100.0, 0.0]", 0.2, 0.04, 20.0, 10.0, 0.12, 3, rigid=rigid_fin))
    surfaces = "".join(
        f'[components.{c}.control_surface]\nkind = "{k}"\nhinge_fraction = 0.7\nstart_m = {s}\nend_m = {e}\n'
        for c, k, s, e in (("right_wing", "aileron", 0.5, 1.0), ("left_wing", "aileron", 0.5, 1.0),
                           ("right_htail", "elevator", 0.0, 0.25), ("left_htail", "elevator", 0.0, 0.25),
                           ("vtail", "rudder", 0.0, 0.2)))
    engine = ('[[engines]]\nname = "motor"\ncomponent = "fuselage"\nposition_m = [0.05, 0.0, 0.0]\nmass_kg = 0.17\n'
              'inertia_kg_m2 = [1e-4, 1e-4, 1e-4]\nmax_thrust_n = 5.0\n')
    return head + body + surfaces + engine
