"""Read aircraft definition files (TOML) into :class:`~flexsim.aircraft.definition.Aircraft`.

The format is documented in ``docs/aircraft-format.md``. Every problem — unknown key, missing field,
wrong type, value out of range — raises one :class:`~flexsim.errors.AircraftDefinitionError` whose
message starts with the file name and names the field, the value and what is allowed.

Frames: positions may be written in body axes (``[frame] kind = "body"``: x forward, y right, z down,
origin o) or in a design frame (``kind = "design"``: origin anywhere, x aft, y right, z up, with the body
origin o given as ``body_origin_m``). Euler angles are always relative to body axes (paper Table 1).
"""

from __future__ import annotations

import tomllib
from importlib import resources
from pathlib import Path
from typing import Any

import numpy as np

from flexsim.aircraft.definition import (
    COMPONENT_NAMES,
    Envelope,
    DEFAULT_MAX_ALPHA_DEG,
    MAX_ALPHA_LIMIT_DEG,
    AeroSettings,
    Aircraft,
    Component,
    ControlSurface,
    BodyItem,
    DragItem,
    Engine,
    LumpedMass,
    MAX_STATIONS,
    PLAUSIBLE,
    SectionTable,
    StripAero,
)
from flexsim.errors import AircraftDefinitionError

__all__ = ["load_aircraft", "load_envelope", "parse_aircraft", "bundled_aircraft_names", "resolve_aircraft_path"]

SCHEMA_VERSION = 1
#: Largest aircraft file read [bytes]: the bundled files are about 10 kB; a table of a few hundred
#: stations per beam stays far below. Bigger files are refused before they are read, so a runaway
#: generator (e.g. 700 000 stations, 49 MB) fails at once instead of running for minutes.
MAX_FILE_BYTES = 2_000_000
_DESIGN_TO_BODY = np.diag([-1.0, 1.0, -1.0])

_TOP_KEYS = {"schema_version": True, "name": True, "description": False, "frame": False,
             "components": True, "lumped_masses": False, "engines": False, "structural_damping_ratio": False,
             "formulation": False, "aero": False, "envelope": False}
_ENVELOPE_KEYS = {"min_mach": False, "max_mach": False, "min_speed_eas_m_s": False, "max_speed_eas_m_s": False}
_AIRCRAFT_AERO_KEYS = {"compressibility": False, "drag": False, "bending_incidence": False, "body": False,
                       "downwash_gradient": False, "max_alpha_deg": False}
_DRAG_KEYS = {"name": True, "component": True, "position_m": True, "drag_area_m2": True}
_BODY_KEYS = {"name": True, "component": True, "position_m": True, "length_m": True, "diameter_m": True, "volume_m3": True}
_COMPONENT_KEYS = {"root_m": True, "euler_deg": True, "length_m": True, "bending_modes": False,
                   "torsion_modes": False, "rigid": False, "section_inertia": False, "sweep_deg": False,
                   "sections": True, "control_surface": False, "aero": False}
_AERO_KEYS = {"strips": False, "lift_slope": False, "cd0": False, "incidence_deg": False}
_SECTION_KEYS = {"station_m": True, "mass_kg_per_m": True, "cg_offset_m": False,
                 "torsional_inertia_kg_m": True, "ei_nm2": True, "gj_nm2": True, "chord_m": False,
                 "ea_fraction": False, "ei_chord_nm2": False, "ea_n": False, "flap_inertia_kg_m": False}
_SURFACE_KEYS = {"kind": True, "hinge_fraction": True, "start_m": True, "end_m": True, "max_deflection_deg": False}
_MASS_KEYS = {"name": True, "component": True, "position_m": True, "mass_kg": True, "inertia_kg_m2": False}
_ENGINE_KEYS = dict(_MASS_KEYS, max_thrust_n=True)


def bundled_aircraft_names() -> tuple[str, ...]:
    """Names of the aircraft shipped with flexsim (usable wherever an AIRCRAFT argument is taken)."""
    data = resources.files("flexsim.aircraft") / "data"
    return tuple(sorted(p.name[:-5] for p in data.iterdir() if p.name.endswith(".toml")))


def resolve_aircraft_path(aircraft: str | Path) -> Path:
    """Path of a bundled aircraft name (e.g. ``"gtm"``) or of a TOML file.

    Raises
    ------
    FileNotFoundError
        Naming the argument and the bundled names when neither exists.
    """
    name = str(aircraft)
    if name in bundled_aircraft_names():
        return Path(str(resources.files("flexsim.aircraft") / "data" / f"{name}.toml"))
    path = Path(name)
    if path.is_file():
        return path
    raise FileNotFoundError(
        f"aircraft {name!r}: neither a bundled aircraft ({', '.join(bundled_aircraft_names())}) nor an existing TOML file"
    )


def load_aircraft(aircraft: str | Path) -> Aircraft:
    """Load a bundled aircraft by name or a TOML file by path.

    Raises
    ------
    FileNotFoundError, AircraftDefinitionError
    """
    path = resolve_aircraft_path(aircraft)
    try:
        size = path.stat().st_size
        if size > MAX_FILE_BYTES:
            raise AircraftDefinitionError(f"{path}: file size = {size} bytes: at most {MAX_FILE_BYTES} bytes are read "
                                          f"(an aircraft file is normally about 10 kB)")
        if size == 0:
            raise AircraftDefinitionError(f"{path}: the file is empty (0 bytes), not an aircraft definition")
        text = path.read_text(encoding="utf-8-sig")  # a leading UTF-8 byte-order mark is allowed
    except (OSError, UnicodeDecodeError) as exc:
        raise AircraftDefinitionError(f"{path}: cannot be read: {exc}") from None
    return parse_aircraft(text, source=str(path))


def _check_keys(where: str, table: Any, spec: dict[str, bool]) -> None:
    if not isinstance(table, dict):
        raise AircraftDefinitionError(f"{where} = {table!r}: must be a table")
    for key in table:
        if key not in spec:
            raise AircraftDefinitionError(
                f"{where}.{key}: unknown key; allowed keys: {', '.join(spec)}"
            )
    for key, required in spec.items():
        if required and key not in table:
            raise AircraftDefinitionError(f"{where}.{key}: missing required field")


def _number(where: str, value: Any) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        raise AircraftDefinitionError(f"{where} = {value!r}: must be a number")
    return float(value)


def _vector(where: str, value: Any, n: int = 3) -> np.ndarray:
    if not isinstance(value, list) or len(value) != n:
        raise AircraftDefinitionError(f"{where} = {value!r}: must be a list of {n} numbers")
    out = np.array([_number(f"{where}[{i}]", v) for i, v in enumerate(value)])
    if not np.all(np.isfinite(out)):
        raise AircraftDefinitionError(f"{where} = {value!r}: must be finite")
    return out


def _numbers(where: str, value: Any) -> np.ndarray:
    if not isinstance(value, list) or not value:
        raise AircraftDefinitionError(f"{where} = {value!r}: must be a non-empty list of numbers")
    if len(value) > MAX_STATIONS:
        raise AircraftDefinitionError(f"{where}: {len(value)} entries: at most {MAX_STATIONS} stations are allowed")
    return np.array([_number(f"{where}[{i}]", v) for i, v in enumerate(value)])


class _Frame:
    """Conversion of file positions/tensors to body axes."""

    def __init__(self, table: Any) -> None:
        table = {} if table is None else table
        _check_keys("frame", table, {"kind": False, "body_origin_m": False})
        self.kind = table.get("kind", "body")
        if self.kind not in ("body", "design"):
            raise AircraftDefinitionError(f'frame.kind = {self.kind!r}: must be "body" or "design"')
        if self.kind == "design":
            if "body_origin_m" not in table:
                raise AircraftDefinitionError("frame.body_origin_m: missing required field (for kind = \"design\")")
            self.origin = _vector("frame.body_origin_m", table["body_origin_m"])
        elif "body_origin_m" in table:
            raise AircraftDefinitionError('frame.body_origin_m: only allowed with kind = "design"')

    def point(self, p: np.ndarray) -> np.ndarray:
        return p if self.kind == "body" else _DESIGN_TO_BODY @ (p - self.origin)

    def tensor(self, t: np.ndarray) -> np.ndarray:
        return t if self.kind == "body" else _DESIGN_TO_BODY @ t @ _DESIGN_TO_BODY


def _sections(where: str, table: Any, length: float) -> SectionTable:
    _check_keys(where, table, _SECTION_KEYS)
    arrays = {k: _numbers(f"{where}.{k}", table[k]) for k in _SECTION_KEYS if k in table}
    k = arrays["station_m"].size
    arrays.setdefault("cg_offset_m", np.zeros(k))
    arrays.setdefault("chord_m", np.zeros(k))
    arrays.setdefault("ea_fraction", np.full(k, 0.5))
    table = SectionTable(**arrays, where=where)
    if abs(table.length_m - length) > 1e-9 * max(1.0, length):
        raise AircraftDefinitionError(
            f"{where}.station_m[-1] = {table.length_m}: must equal length_m = {length} (tables span root to tip)"
        )
    return table


def _component(name: str, table: Any, frame: _Frame) -> Component:
    where = f"components.{name}"
    if name not in COMPONENT_NAMES:
        raise AircraftDefinitionError(f"{where}: unknown component; allowed: {', '.join(COMPONENT_NAMES)}")
    _check_keys(where, table, _COMPONENT_KEYS)
    length = _number(f"{where}.length_m", table["length_m"])
    if not length > 0:
        raise AircraftDefinitionError(f"{where}.length_m = {length}: must be > 0")
    lo, hi, unit = PLAUSIBLE["length_m"]
    if not lo <= length <= hi:  # also catches nan and inf, which defeat the station comparison below
        raise AircraftDefinitionError(f"{where}.length_m = {length}: outside the plausible range [{lo:g}, {hi:g}] {unit} (check the units)")
    surface = None
    if "control_surface" in table:
        cs = table["control_surface"]
        _check_keys(f"{where}.control_surface", cs, _SURFACE_KEYS)
        surface = ControlSurface(
            kind=str(cs["kind"]),
            hinge_fraction=_number(f"{where}.control_surface.hinge_fraction", cs["hinge_fraction"]),
            start_m=_number(f"{where}.control_surface.start_m", cs["start_m"]),
            end_m=_number(f"{where}.control_surface.end_m", cs["end_m"]),
            max_deflection_rad=np.deg2rad(_number(f"{where}.control_surface.max_deflection_deg", cs.get("max_deflection_deg", 25.0))),
        )
    aero = None
    if "aero" in table:
        at = table["aero"]
        _check_keys(f"{where}.aero", at, _AERO_KEYS)
        slope = at.get("lift_slope", "vlm")
        if not isinstance(slope, str):
            slope = _number(f"{where}.aero.lift_slope", slope)
        aero = StripAero(
            strips=at.get("strips", 8),
            lift_slope=slope,
            cd0=_number(f"{where}.aero.cd0", at.get("cd0", 0.0)),
            incidence_rad=np.deg2rad(_number(f"{where}.aero.incidence_deg", at.get("incidence_deg", 0.0))),
        )
    sweep = table.get("sweep_deg")
    return Component(
        name=name,
        root_m=frame.point(_vector(f"{where}.root_m", table["root_m"])),
        euler_rad=np.deg2rad(_vector(f"{where}.euler_deg", table["euler_deg"])),
        sections=_sections(f"{where}.sections", table["sections"], length),
        bending_modes=table.get("bending_modes", 2),
        torsion_modes=table.get("torsion_modes", 2),
        rigid=table.get("rigid", False),
        section_inertia=table.get("section_inertia", "chordwise" if name != "fuselage" else "axisymmetric"),
        control_surface=surface,
        aero=aero,
        sweep_rad=None if sweep is None else np.deg2rad(_number(f"{where}.sweep_deg", sweep)),
    )


def _masses(key: str, items: Any, frame: _Frame) -> list[LumpedMass]:
    if not isinstance(items, list):
        raise AircraftDefinitionError(f"{key} = {items!r}: must be an array of tables ([[{key}]])")
    out = []
    spec = _ENGINE_KEYS if key == "engines" else _MASS_KEYS
    for i, item in enumerate(items):
        where = f"{key}[{i}]"
        _check_keys(where, item, spec)
        inertia = item.get("inertia_kg_m2", [0.0, 0.0, 0.0])
        if isinstance(inertia, list) and len(inertia) == 3 and all(isinstance(v, list) for v in inertia):
            tensor = np.array([_vector(f"{where}.inertia_kg_m2[{j}]", row) for j, row in enumerate(inertia)])
        else:
            tensor = np.diag(_vector(f"{where}.inertia_kg_m2", inertia))
        kwargs = dict(
            name=str(item["name"]),
            component=str(item["component"]),
            position_m=frame.point(_vector(f"{where}.position_m", item["position_m"])),
            mass_kg=_number(f"{where}.mass_kg", item["mass_kg"]),
            inertia_kg_m2=frame.tensor(tensor),
            where=key,
        )
        if key == "engines":
            out.append(Engine(**kwargs, max_thrust_n=_number(f"{where}.max_thrust_n", item["max_thrust_n"])))
        else:
            out.append(LumpedMass(**kwargs))
    return out


def _attached_items(table: Any, key: str, keys: Any, frame: "_Frame", cls: type, numbers: tuple[str, ...]) -> tuple:
    """The ``[[aero.<key>]]`` array of tables as ``cls`` items riding on a component (name, component,
    position_m in the file's frame [m], and the named numbers); errors name ``aero.<key>[i].<field>``."""
    items = table.get(key, [])
    if not isinstance(items, list):
        raise AircraftDefinitionError(f"aero.{key} = {items!r}: must be an array of tables ([[aero.{key}]])")
    out = []
    for i, item in enumerate(items):
        where = f"aero.{key}[{i}]"
        _check_keys(where, item, keys)
        out.append(cls(name=str(item["name"]), component=str(item["component"]),
                       position_m=frame.point(_vector(f"{where}.position_m", item["position_m"])),
                       **{k: _number(f"{where}.{k}", item[k]) for k in numbers}))
    return out


def _aero_settings(table: Any, frame: "_Frame") -> AeroSettings:
    table = {} if table is None else table
    _check_keys("aero", table, _AIRCRAFT_AERO_KEYS)
    comp = table.get("compressibility", "prandtl-glauert")
    if not isinstance(comp, str):
        raise AircraftDefinitionError(f"aero.compressibility = {comp!r}: must be \"prandtl-glauert\" or \"none\"")
    drag = _attached_items(table, "drag", _DRAG_KEYS, frame, DragItem, ("drag_area_m2",))
    bodies = _attached_items(table, "body", _BODY_KEYS, frame, BodyItem, ("length_m", "diameter_m", "volume_m3"))
    max_alpha_deg = _number("aero.max_alpha_deg", table.get("max_alpha_deg", DEFAULT_MAX_ALPHA_DEG))
    if not 0.0 < max_alpha_deg <= MAX_ALPHA_LIMIT_DEG:  # named in degrees, as written (also catches nan)
        raise AircraftDefinitionError(f"aero.max_alpha_deg = {max_alpha_deg!r}: must be in (0, {MAX_ALPHA_LIMIT_DEG:g}] deg")
    return AeroSettings(compressibility=comp, drag=tuple(drag), bending_incidence=table.get("bending_incidence", False),
                        bodies=tuple(bodies), downwash_gradient=table.get("downwash_gradient", 0.0),
                        max_alpha_rad=float(np.deg2rad(max_alpha_deg)))


def _envelope(table: Any) -> Envelope | None:
    if table is None:
        return None
    _check_keys("envelope", table, _ENVELOPE_KEYS)
    return Envelope(**{key: _number(f"envelope.{key}", value) for key, value in table.items()})


def load_envelope(name_or_path: str | Path) -> Envelope | None:
    """The ``[envelope]`` table of an aircraft file alone (None without one), without building the aircraft.

    For a command that needs only the flight envelope before the aircraft is loaded where it is used (the flutter
    search range, :func:`flexsim.linear.envelope.search_range`). The rest of the file is checked when it is loaded.

    Raises
    ------
    AircraftDefinitionError
        For a file that is not TOML or a bad ``[envelope]`` table, prefixed with the file name.
    """
    path = resolve_aircraft_path(name_or_path)
    try:
        doc = tomllib.loads(path.read_text(encoding="utf-8-sig"))
        return _envelope(doc.get("envelope"))
    except tomllib.TOMLDecodeError as exc:
        raise AircraftDefinitionError(f"{path}: not valid TOML: {exc}") from None
    except AircraftDefinitionError as exc:
        raise AircraftDefinitionError(f"{path}: {exc}") from None


def parse_aircraft(text: str, source: str = "<string>") -> Aircraft:
    """Parse the TOML text of an aircraft definition.

    Parameters
    ----------
    text : str
        TOML document (format: ``docs/aircraft-format.md``).
    source : str
        Name used as the prefix of error messages (normally the file path).

    Raises
    ------
    AircraftDefinitionError
        ``"<source>: <field> = <value>: <what is allowed>"``.
    """
    try:
        if len(text) > MAX_FILE_BYTES:
            raise AircraftDefinitionError(f"text of {len(text)} characters: at most {MAX_FILE_BYTES} are read")
        if not text.strip():
            raise AircraftDefinitionError("the file is empty, not an aircraft definition")
        text = text.removeprefix("\ufeff")
        try:
            doc = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise AircraftDefinitionError(f"not valid TOML: {exc}") from None
        except RecursionError:
            raise AircraftDefinitionError("not valid TOML for flexsim: arrays or tables nested too deeply") from None
        _check_keys("<top level>", doc, _TOP_KEYS)
        version = doc["schema_version"]
        if version != SCHEMA_VERSION:
            raise AircraftDefinitionError(f"schema_version = {version!r}: this flexsim reads version {SCHEMA_VERSION}")
        frame = _Frame(doc.get("frame"))
        comps = doc["components"]
        if not isinstance(comps, dict) or not comps:
            raise AircraftDefinitionError("components: must contain at least one [components.<name>] table")
        components = [_component(name, table, frame) for name, table in comps.items()]
        return Aircraft(
            name=str(doc["name"]),
            description=str(doc.get("description", "")),
            components=tuple(components),
            lumped_masses=tuple(_masses("lumped_masses", doc.get("lumped_masses", []), frame)),
            engines=tuple(_masses("engines", doc.get("engines", []), frame)),  # type: ignore[arg-type]
            source=source,
            design_origin_m=frame.origin if frame.kind == "design" else None,
            structural_damping_ratio=doc.get("structural_damping_ratio", 0.0),
            formulation=doc.get("formulation", "physical"),
            aero_settings=_aero_settings(doc.get("aero"), frame),
            envelope=_envelope(doc.get("envelope")),
        )
    except AircraftDefinitionError as exc:
        raise AircraftDefinitionError(f"{source}: {exc}") from None
