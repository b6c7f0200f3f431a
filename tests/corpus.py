"""A corpus of malformed aircraft files and damaged flight logs (reliability).

Used by the fuzz tests (``tests/test_fuzz.py``) and by the census ``studies/reliability_census.py``,
which re-measures the reliability table. The aircraft cases are 117 variants of
the bundled ``gtm.toml`` and ``goland_wing.toml`` (parsed with ``tomllib``, mutated, written back with :func:`dumps`), each with what a correct reader must do:
``"error"`` (a flexsim error naming the field) or ``"ok"`` (legal input, a sane result).
"""

from __future__ import annotations

import copy
import json
import math
import tomllib
from dataclasses import dataclass
from importlib import resources
from typing import Any, Callable

__all__ = ["AircraftCase", "aircraft_cases", "dumps", "LogDamage", "log_damages"]


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(float(v))
    if isinstance(v, str):
        return json.dumps(v)  # a TOML basic string (\\uXXXX escapes are TOML too)
    if isinstance(v, list):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(k)} = {_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def dumps(doc: dict, prefix: str = "") -> str:
    """A TOML document of ``doc`` (plain values first, then tables, then arrays of tables)."""
    plain = {k: v for k, v in doc.items() if not isinstance(v, dict) and not (isinstance(v, list) and v and all(isinstance(x, dict) for x in v))}
    lines = [f"{json.dumps(k)} = {_value(v)}" for k, v in plain.items()]
    out = "\n".join(lines) + ("\n" if lines else "")
    for k, v in doc.items():
        name = f"{prefix}.{json.dumps(k)}" if prefix else json.dumps(k)
        if isinstance(v, dict):
            out += f"\n[{name}]\n" + dumps(v, name)
        elif isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
            for item in v:
                out += f"\n[[{name}]]\n" + dumps(item, name)
    return out


def _bundled(name: str) -> dict:
    text = (resources.files("flexsim.aircraft") / "data" / f"{name}.toml").read_text(encoding="utf-8")
    return tomllib.loads(text)


@dataclass(frozen=True)
class AircraftCase:
    """One aircraft file of the corpus.

    Attributes
    ----------
    id, category : str
    mutation : str
        What was changed, in words.
    content : bytes or None
        The file's bytes; None for a path case (``path``).
    expect : {"error", "ok"}
        What a correct reader does: refuse with a flexsim error, or accept a legal file.
    base : {"gtm", "goland_wing"}
    path : str or None
        For path cases: the path given instead of a file (relative to the directory of the corpus).
    """

    id: str
    category: str
    mutation: str
    content: bytes | None
    expect: str
    base: str
    path: str | None = None


def _walk(doc: dict, path: str) -> tuple[Any, str]:
    parts = path.split(".")
    node: Any = doc
    for p in parts[:-1]:
        node = node[int(p)] if isinstance(node, list) else node[p]
    return node, parts[-1]


def _set(path: str, value: Any) -> Callable[[dict], None]:
    def f(doc: dict) -> None:
        node, key = _walk(doc, path)
        if isinstance(node, list):
            node[int(key)] = value
        else:
            node[key] = value
    return f


def _del(path: str) -> Callable[[dict], None]:
    def f(doc: dict) -> None:
        node, key = _walk(doc, path)
        del node[key]
    return f


def _all(*fs: Callable[[dict], None]) -> Callable[[dict], None]:
    def f(doc: dict) -> None:
        for g in fs:
            g(doc)
    return f


def _scale(path: str, k: float) -> Callable[[dict], None]:
    def f(doc: dict) -> None:
        node, key = _walk(doc, path)
        v = node[key]
        node[key] = [x * k for x in v] if isinstance(v, list) else v * k
    return f


def _scale_lengths(k: float) -> Callable[[dict], None]:
    """Scale every length of the Goland wing consistently (a unit mistake that stays self-consistent)."""
    w = "components.right_wing"
    return _all(_scale(f"{w}.length_m", k), _scale(f"{w}.sections.station_m", k), _scale(f"{w}.sections.chord_m", k),
                _scale(f"{w}.sections.cg_offset_m", k), _scale(f"{w}.control_surface.start_m", k),
                _scale(f"{w}.control_surface.end_m", k))


W = "components.right_wing"
WS = f"{W}.sections"

# (id, category, base, mutation words, mutate(doc) or text function, expect)
_DICT_CASES: list[tuple[str, str, str, str, Callable[[dict], None], str]] = [
    ("miss_schema", "missing", "goland_wing", "no schema_version", _del("schema_version"), "error"),
    ("miss_name", "missing", "goland_wing", "no name", _del("name"), "error"),
    ("miss_components", "missing", "goland_wing", "no [components]", _del("components"), "error"),
    ("miss_sections", "missing", "goland_wing", "right_wing without [sections]", _del(WS), "error"),
    ("miss_ei", "missing", "goland_wing", "sections without ei_nm2", _del(f"{WS}.ei_nm2"), "error"),
    ("miss_length", "missing", "goland_wing", "no length_m", _del(f"{W}.length_m"), "error"),
    ("miss_right_wing_gtm", "missing", "gtm", "GTM without right_wing (its engine left)", _del(W), "error"),
    ("miss_right_wing_and_engine", "missing", "gtm", "GTM without right_wing, its engine and its drag and body items (legal)",
     _all(_del(W), lambda d: d.__setitem__("engines", [e for e in d["engines"] if e["component"] != "right_wing"]),
          lambda d: d.get("aero", {}).__setitem__("drag", [i for i in d.get("aero", {}).get("drag", [])
                                                           if i["component"] != "right_wing"]),
          lambda d: d.get("aero", {}).__setitem__("body", [i for i in d.get("aero", {}).get("body", [])
                                                           if i["component"] != "right_wing"])), "ok"),
    ("miss_thrust", "missing", "gtm", "engine without max_thrust_n", _del("engines.0.max_thrust_n"), "error"),
    ("miss_mass_component", "missing", "gtm", "lumped mass without component", _del("lumped_masses.0.component"), "error"),
    ("miss_hinge", "missing", "goland_wing", "no hinge_fraction", _del(f"{W}.control_surface.hinge_fraction"), "error"),
    ("miss_torsional_inertia", "missing", "goland_wing", "no torsional_inertia_kg_m", _del(f"{WS}.torsional_inertia_kg_m"), "error"),
    ("type_length_str", "wrong_type", "goland_wing", 'length_m = "6.096"', _set(f"{W}.length_m", "6.096"), "error"),
    ("type_modes_float", "wrong_type", "goland_wing", "bending_modes = 2.0", _set(f"{W}.bending_modes", 2.0), "error"),
    ("type_modes_str", "wrong_type", "goland_wing", 'bending_modes = "3"', _set(f"{W}.bending_modes", "3"), "error"),
    ("type_rigid_str", "wrong_type", "goland_wing", 'rigid = "yes"', _set(f"{W}.rigid", "yes"), "error"),
    ("type_mass_scalar", "wrong_type", "goland_wing", 'mass_kg_per_m = "35.71"', _set(f"{WS}.mass_kg_per_m", "35.71"), "error"),
    ("type_station_mixed", "wrong_type", "goland_wing", 'station_m = [0, "6.096"]', _set(f"{WS}.station_m", [0.0, "6.096"]), "error"),
    ("type_euler_short", "wrong_type", "goland_wing", "euler_deg with 2 entries", _set(f"{W}.euler_deg", [0.0, 90.0]), "error"),
    ("type_chord_nested", "wrong_type", "goland_wing", "chord_m nested", _set(f"{WS}.chord_m", [[1.8288], [1.8288]]), "error"),
    ("type_mass_bool", "wrong_type", "gtm", "lumped mass_kg = true", _set("lumped_masses.0.mass_kg", True), "error"),
    ("type_component_int", "wrong_type", "goland_wing", "components.right_wing = 5", _set(W, 5), "error"),
    ("type_strips_float", "wrong_type", "goland_wing", "strips = 12.5", _set(f"{W}.aero.strips", 12.5), "error"),
    ("type_lift_slope_str", "wrong_type", "goland_wing", 'lift_slope = "foo"', _set(f"{W}.aero.lift_slope", "foo"), "error"),
    ("type_damping_str", "wrong_type", "goland_wing", 'structural_damping_ratio = "0.01"', _set("structural_damping_ratio", "0.01"), "error"),
    ("type_schema_2", "wrong_type", "goland_wing", "schema_version = 2", _set("schema_version", 2), "error"),
    ("type_name_int", "wrong_type", "goland_wing", "name = 42 (legal, read as '42')", _set("name", 42), "ok"),
    ("type_surface_kind_int", "wrong_type", "gtm", "control_surface.kind = 7", _set(f"{W}.control_surface.kind", 7), "error"),
    ("type_inertia_3x2", "wrong_type", "gtm", "engine inertia 3x2", _set("engines.0.inertia_kg_m2", [[1.0, 2.0], [3.0, 4.0], [5.0, 6.0]]), "error"),
    ("mass_neg", "mass", "goland_wing", "mass_kg_per_m = [-35.71, 35.71]", _set(f"{WS}.mass_kg_per_m", [-35.71, 35.71]), "error"),
    ("mass_zero_wing", "mass", "goland_wing", "mass_kg_per_m = 0, cg offset 0",
     _all(_set(f"{WS}.mass_kg_per_m", [0.0, 0.0]), _set(f"{WS}.cg_offset_m", [0.0, 0.0])), "error"),
    ("mass_all_zero", "mass", "goland_wing", "massless beam",
     _all(_set(f"{WS}.mass_kg_per_m", [0.0, 0.0]), _set(f"{WS}.cg_offset_m", [0.0, 0.0]), _set(f"{WS}.torsional_inertia_kg_m", [0.0, 0.0])), "error"),
    ("mass_nan", "mass", "goland_wing", "mass_kg_per_m = nan", _set(f"{WS}.mass_kg_per_m", [math.nan, math.nan]), "error"),
    ("mass_inf", "mass", "goland_wing", "mass_kg_per_m = inf", _set(f"{WS}.mass_kg_per_m", [math.inf, math.inf]), "error"),
    ("mass_huge_1e300", "mass", "goland_wing", "mass 1e300 kg/m",
     _all(_set(f"{WS}.mass_kg_per_m", [1e300, 1e300]), _set(f"{WS}.torsional_inertia_kg_m", [1e300, 1e300])), "error"),
    ("lump_neg", "mass", "gtm", "lumped mass -10800 kg", _set("lumped_masses.0.mass_kg", -10800.0), "error"),
    ("lump_zero", "mass", "gtm", "lumped mass 0 kg", _set("lumped_masses.0.mass_kg", 0.0), "error"),
    ("lump_nan", "mass", "gtm", "lumped mass nan", _set("lumped_masses.0.mass_kg", math.nan), "error"),
    ("lump_inf", "mass", "gtm", "lumped mass inf", _set("lumped_masses.0.mass_kg", math.inf), "error"),
    ("lump_huge", "mass", "gtm", "lumped mass 1e30 kg", _set("lumped_masses.0.mass_kg", 1e30), "error"),
    ("thrust_zero", "mass", "gtm", "max_thrust_n = 0", _set("engines.0.max_thrust_n", 0.0), "error"),
    ("thrust_nan", "mass", "gtm", "max_thrust_n = nan", _set("engines.0.max_thrust_n", math.nan), "error"),
    ("inertia_neg", "mass", "gtm", "engine inertia not PSD", _set("engines.0.inertia_kg_m2", [-2200.0, 9900.0, 9900.0]), "error"),
    ("gtm_wing_mass_huge", "mass", "gtm", "GTM wing mass x1e6",
     _all(_scale(f"{WS}.mass_kg_per_m", 1e6), _scale(f"{WS}.torsional_inertia_kg_m", 1e6)), "error"),
    ("ei_zero", "stiffness", "goland_wing", "EI = 0", _set(f"{WS}.ei_nm2", [0.0, 0.0]), "error"),
    ("ei_neg", "stiffness", "goland_wing", "EI = -1", _set(f"{WS}.ei_nm2", [-1.0, -1.0]), "error"),
    ("ei_nan", "stiffness", "goland_wing", "EI = nan", _set(f"{WS}.ei_nm2", [math.nan, math.nan]), "error"),
    ("ei_inf", "stiffness", "goland_wing", "EI = inf", _set(f"{WS}.ei_nm2", [math.inf, math.inf]), "error"),
    ("ei_tiny", "stiffness", "goland_wing", "EI = 1e-300", _set(f"{WS}.ei_nm2", [1e-300, 1e-300]), "error"),
    ("gj_huge", "stiffness", "goland_wing", "GJ = 1e300", _set(f"{WS}.gj_nm2", [1e300, 1e300]), "error"),
    ("gtm_wing_ei_huge", "stiffness", "gtm", "GTM wing EI = 1e30", lambda d: d["components"]["right_wing"]["sections"].__setitem__(
        "ei_nm2", [1e30] * len(d["components"]["right_wing"]["sections"]["ei_nm2"])), "error"),
    ("gtm_wing_gj_tiny", "stiffness", "gtm", "GTM wing GJ = 1e-3", lambda d: d["components"]["right_wing"]["sections"].__setitem__(
        "gj_nm2", [1e-3] * len(d["components"]["right_wing"]["sections"]["gj_nm2"])), "error"),
    ("len_zero", "length", "goland_wing", "length 0", _all(_set(f"{W}.length_m", 0.0), _set(f"{WS}.station_m", [0.0, 0.0])), "error"),
    ("len_neg", "length", "goland_wing", "length -6.096", _set(f"{W}.length_m", -6.096), "error"),
    ("len_nan", "length", "goland_wing", "length nan", _set(f"{W}.length_m", math.nan), "error"),
    ("len_inf", "length", "goland_wing", "length inf", _set(f"{W}.length_m", math.inf), "error"),
    ("len_mismatch", "length", "goland_wing", "length 7, stations end at 6.096", _set(f"{W}.length_m", 7.0), "error"),
    ("len_huge", "length", "goland_wing", "1000 km wing", _scale_lengths(1e6 / 6.096), "error"),
    ("len_tiny", "length", "goland_wing", "1 nm wing", _scale_lengths(1e-9 / 6.096), "error"),
    ("station_nonmono", "length", "goland_wing", "stations [0, 3, 2, 6.096]",
     lambda d: d["components"]["right_wing"]["sections"].update(
         {k: ([0.0, 3.0, 2.0, 6.096] if k == "station_m" else [v[0]] * 4) for k, v in d["components"]["right_wing"]["sections"].items()}), "error"),
    ("station_len_mismatch", "length", "goland_wing", "3 masses, 2 stations", _set(f"{WS}.mass_kg_per_m", [35.71] * 3), "error"),
    ("chord_zero_aero", "chord", "goland_wing", "chord 0 with aero",
     _all(_set(f"{WS}.chord_m", [0.0, 0.0]), _set(f"{WS}.cg_offset_m", [0.0, 0.0])), "error"),
    ("chord_neg", "chord", "goland_wing", "chord -1.8288", _set(f"{WS}.chord_m", [-1.8288, -1.8288]), "error"),
    ("chord_nan", "chord", "goland_wing", "chord nan", _set(f"{WS}.chord_m", [math.nan, math.nan]), "error"),
    ("chord_huge", "chord", "goland_wing", "1000 km chord", _set(f"{WS}.chord_m", [1e6, 1e6]), "error"),
    ("ea_out", "chord", "goland_wing", "ea_fraction 1.5", _set(f"{WS}.ea_fraction", [1.5, 1.5]), "error"),
    ("cg_offset_big", "chord", "goland_wing", "cg_offset 100 m", _set(f"{WS}.cg_offset_m", [100.0, 100.0]), "error"),
    ("hinge_percent", "chord", "goland_wing", "hinge_fraction 80", _set(f"{W}.control_surface.hinge_fraction", 80.0), "error"),
    ("strips_0", "strips", "goland_wing", "strips 0", _set(f"{W}.aero.strips", 0), "error"),
    ("strips_m1", "strips", "goland_wing", "strips -1", _set(f"{W}.aero.strips", -1), "error"),
    ("strips_1000", "strips", "goland_wing", "strips 1000", _set(f"{W}.aero.strips", 1000), "error"),
    ("strips_1", "strips", "goland_wing", "strips 1 (legal)", _set(f"{W}.aero.strips", 1), "ok"),
    ("strips_200", "strips", "goland_wing", "strips 200 (legal)", _set(f"{W}.aero.strips", 200), "ok"),
    ("modes_0_0", "shape_functions", "goland_wing", "m = n = 0 (legal)",
     _all(_set(f"{W}.bending_modes", 0), _set(f"{W}.torsion_modes", 0)), "ok"),
    ("modes_m1", "shape_functions", "goland_wing", "bending_modes -1", _set(f"{W}.bending_modes", -1), "error"),
    ("modes_1000", "shape_functions", "goland_wing", "bending_modes 1000", _set(f"{W}.bending_modes", 1000), "error"),
    ("modes_11", "shape_functions", "goland_wing", "torsion_modes 11", _set(f"{W}.torsion_modes", 11), "error"),
    ("modes_1_1", "shape_functions", "goland_wing", "m = n = 1 (legal)", _all(_set(f"{W}.bending_modes", 1), _set(f"{W}.torsion_modes", 1)), "ok"),
    ("modes_10_10", "shape_functions", "goland_wing", "m = n = 10 (legal)", _all(_set(f"{W}.bending_modes", 10), _set(f"{W}.torsion_modes", 10)), "ok"),
    ("typo_lenght", "unknown_key", "goland_wing", "lenght_m", lambda d: d["components"]["right_wing"].__setitem__(
        "lenght_m", d["components"]["right_wing"].pop("length_m")), "error"),
    ("typo_top", "unknown_key", "goland_wing", "nmae", _set("nmae", "x"), "error"),
    ("typo_section", "unknown_key", "goland_wing", "mass_kg_per_meter", lambda d: d["components"]["right_wing"]["sections"].__setitem__(
        "mass_kg_per_meter", d["components"]["right_wing"]["sections"].pop("mass_kg_per_m")), "error"),
    ("unknown_component", "unknown_key", "goland_wing", "right_wingg", lambda d: d["components"].__setitem__(
        "right_wingg", d["components"].pop("right_wing")), "error"),
    ("surface_wrong_kind", "unknown_key", "goland_wing", 'kind = "elevator" on a wing', _set(f"{W}.control_surface.kind", "elevator"), "error"),
    ("lump_bad_component", "unknown_key", "gtm", 'component = "wing"', _set("lumped_masses.0.component", "wing"), "error"),
    ("typo_frame_kind", "unknown_key", "gtm", 'frame.kind = "desing"', _set("frame.kind", "desing"), "error"),
    ("dup_lump_names", "duplicate", "gtm", "two lumped masses named main_gear", _set("lumped_masses.0.name", "main_gear"), "error"),
    ("dup_engine_lump_name", "duplicate", "gtm", "engine named like a lumped mass", _set("engines.0.name", "nose_gear"), "error"),
    ("dup_geometry_left_eq_right", "duplicate", "gtm", "left_wing a copy of right_wing",
     lambda d: d["components"].__setitem__("left_wing", copy.deepcopy(d["components"]["right_wing"])), "error"),
    ("unit_length_mm", "units", "goland_wing", "lengths in mm", _scale_lengths(1000.0), "error"),
    ("unit_mass_g", "units", "goland_wing", "mass in g/m", _scale(f"{WS}.mass_kg_per_m", 1000.0), "error"),
    ("unit_ei_nmm2", "units", "goland_wing", "EI in N mm^2", _scale(f"{WS}.ei_nm2", 1e6), "error"),
    ("unit_euler_rad", "units", "goland_wing", "euler_deg in radians", _set(f"{W}.euler_deg", [0.0, 0.0, 1.5708]), "error"),
    ("unit_frame_swap", "units", "gtm", 'frame "body" with design positions', _all(_set("frame", {"kind": "body"})), "error"),
    ("unit_thrust_kn", "units", "gtm", "max_thrust_n in kN (legal file; trim refuses)",
     _all(_set("engines.0.max_thrust_n", 178.0), _set("engines.1.max_thrust_n", 178.0)), "ok"),
    ("unit_damping_percent", "units", "goland_wing", "structural_damping_ratio = 1", _set("structural_damping_ratio", 1.0), "error"),
    ("frame_design_no_origin", "units", "gtm", "design frame without body_origin_m", _set("frame", {"kind": "design"}), "error"),
    ("root_nan", "geometry", "gtm", "right_wing root_m [nan, 1.88, -1.6]", lambda d: d["components"]["right_wing"]["root_m"].__setitem__(0, math.nan), "error"),
    ("euler_huge", "geometry", "goland_wing", "euler_deg 1e300", _set(f"{W}.euler_deg", [0.0, 0.0, 1e300]), "error"),
    ("lump_off_component", "geometry", "gtm", "lumped mass 1 km beside its component",
     lambda d: d["lumped_masses"][0]["position_m"].__setitem__(1, 1000.0), "error"),
    ("fuselage_off_origin", "geometry", "gtm", "fuselage root not at the body origin",
     lambda d: d["components"]["fuselage"]["root_m"].__setitem__(0, d["components"]["fuselage"]["root_m"][0] - 4.0), "error"),
    ("components_empty", "geometry", "goland_wing", "components = {}", _set("components", {}), "error"),
    ("name_escape", "file", "goland_wing", "name with terminal escape sequences (legal; printed sanitised)",
     _set("name", "Goland \x1b[31mRED\x1b[0m \x1b]0;pwned\x07 wing"), "ok"),
]


def _text_cases(goland: str, big: bool) -> list[tuple[str, str, str, bytes | None, str, str | None]]:
    """File-level cases: (id, category, mutation, bytes, expect, path)."""
    dup_table = goland + "\n[components.right_wing.aero]\nstrips = 3\n"
    dup_key = goland.replace("length_m = 6.096\n", "length_m = 6.096\nlength_m = 6.096\n", 1)
    stations = 700_000 if big else 60_000
    n = stations
    xs = [6.096 * i / (n - 1) for i in range(n)]
    head = goland.split("[components.right_wing.sections]")[0]
    table = ("[components.right_wing.sections]\n" + f"station_m = [{', '.join(f'{x:.9g}' for x in xs[:-1])}, 6.096]\n"
             + "".join(f"{k} = [{', '.join([v] * n)}]\n" for k, v in (("mass_kg_per_m", "35.71"), ("cg_offset_m", "0.18288"),
                                                                      ("torsional_inertia_kg_m", "8.64"), ("ei_nm2", "9.77e6"),
                                                                      ("gj_nm2", "0.987e6"), ("chord_m", "1.8288"), ("ea_fraction", "0.33"))))
    pad = 50_000_000 if big else 3_000_000
    return [
        ("dup_component_table", "duplicate", "[components.right_wing.aero] twice", dup_table.encode(), "error", None),
        ("dup_key", "duplicate", "length_m twice", dup_key.encode(), "error", None),
        ("file_empty", "file", "empty file", b"", "error", None),
        ("file_garbage", "file", "4 KiB of random bytes", bytes((i * 7919 + 13) % 256 for i in range(4096)), "error", None),
        ("file_garbage_ascii", "file", "ASCII noise", b"lorem ipsum = = [ dolor\n" * 20, "error", None),
        ("file_latin1", "file", "name in Latin-1", goland.replace('"Goland wing"', '"G\xf6land wing"').encode("latin-1"), "error", None),
        ("file_bom", "file", "UTF-8 BOM before the text (legal)", b"\xef\xbb\xbf" + goland.encode(), "ok", None),
        ("file_nested_tables", "file", "10 000-level dotted table", (goland + "\n[" + ".".join(["x"] * 10_000) + "]\n").encode(), "error", None),
        ("file_nested_arrays", "file", "100 000 nested arrays", goland.replace('description = ', 'description = ' + "[" * 100_000 + "]" * 100_000 + "\n#", 1).encode(), "error", None),
        ("file_nested_inline", "file", "inline tables nested 50 000 deep", goland.replace('description = ', 'description = ' + "{a = " * 50_000 + "1" + "}" * 50_000 + "\n#", 1).encode(), "error", None),
        ("file_50MB_comment", "file", f"valid file padded with {pad // 1_000_000} MB of comments", (goland + ("# " + "x" * 98 + "\n") * (pad // 100)).encode(), "error", None),
        ("file_50MB_stations", "file", f"valid wing with {stations} stations", (head + table).encode(), "error", None),
        ("file_50MB_description", "file", f"{pad // 1_000_000} MB description", goland.replace('description = "', 'description = "' + "y" * pad, 1).encode(), "error", None),
        ("path_missing", "file", "path that does not exist", None, "error", "does_not_exist.toml"),
        ("path_directory", "file", "a directory given as the aircraft", None, "error", "."),
    ]


def aircraft_cases(big: bool = True) -> list[AircraftCase]:
    """The corpus: 117 malformed or edge-case aircraft files (``big=False``: the 50 MB cases at 3 MB)."""
    bases = {name: _bundled(name) for name in ("gtm", "goland_wing")}
    out = []
    for cid, cat, base, words, mutate, expect in _DICT_CASES:
        doc = copy.deepcopy(bases[base])
        mutate(doc)
        out.append(AircraftCase(cid, cat, words, dumps(doc).encode(), expect, base))
    goland = (resources.files("flexsim.aircraft") / "data" / "goland_wing.toml").read_text(encoding="utf-8")
    for cid, cat, words, content, expect, path in _text_cases(goland, big):
        out.append(AircraftCase(cid, cat, words, content, expect, "goland_wing", path))
    out.append(AircraftCase("base_gtm", "baseline", "unmodified gtm.toml", dumps(bases["gtm"]).encode(), "ok", "gtm"))
    out.append(AircraftCase("base_goland", "baseline", "unmodified goland_wing.toml", dumps(bases["goland_wing"]).encode(), "ok", "goland_wing"))
    return out


@dataclass(frozen=True)
class LogDamage:
    """One way of damaging a finished flight log: ``kind`` at ``fraction`` of the file length."""

    kind: str  # "truncate", "flip_byte", "zero_block", "random_block"
    fraction: float
    seed: int = 0

    def apply(self, data: bytes) -> bytes:
        """The damaged bytes."""
        import random

        rng = random.Random(self.seed)
        i = min(len(data) - 1, max(0, int(self.fraction * len(data))))
        if self.kind == "truncate":
            return data[:i]
        b = bytearray(data)
        if self.kind == "flip_byte":
            b[i] ^= 1 << rng.randrange(8)
        elif self.kind == "zero_block":
            b[i:i + 64] = bytes(len(b[i:i + 64]))
        elif self.kind == "random_block":
            block = bytes(rng.randrange(256) for _ in range(64))
            b[i:i + 64] = block[: len(b[i:i + 64])]
            if bytes(b) == data:
                b[i] ^= 0xFF
        else:
            raise ValueError(f"kind = {self.kind!r}: must be truncate, flip_byte, zero_block or random_block")
        return bytes(b)


def log_damages(n: int = 40, seed: int = 12) -> list[LogDamage]:
    """``n`` damages at pseudo-random positions (every kind), plus cuts at the first and last bytes."""
    import random

    rng = random.Random(seed)
    kinds = ("truncate", "flip_byte", "zero_block", "random_block")
    out = [LogDamage("truncate", 8 / 1e9), LogDamage("truncate", 0.999999), LogDamage("flip_byte", 0.99999, 1),
           LogDamage("random_block", 20 / 1e9, 2)]
    out += [LogDamage(kinds[k % 4], rng.uniform(0.0, 1.0), rng.randrange(1 << 30)) for k in range(n - len(out))]
    return out
