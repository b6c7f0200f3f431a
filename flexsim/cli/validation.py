"""Checks of command-line options, run before any computation (the CLI never silently
changes the question).

Every check raises :class:`CliError` naming the option as the user typed it, the value and what is
allowed; options a user may mean although they leave the model's validity (Mach beyond the
Prandtl-Glauert range) give an explicit warning on stderr instead. Commands call these helpers first,
so a bad option or output path costs no computation. Text printed by the CLI passes through
:func:`printable`, so terminal escape sequences from files (an aircraft ``name``, a log event) are shown
escaped, never executed by the terminal.
"""

from __future__ import annotations

import math
import os
import re
import sys
from pathlib import Path
from typing import Iterable, TextIO

from flexsim.errors import FlexsimError

__all__ = ["CliError", "in_user_words", "printable", "json_text", "SanitisedStream", "warn", "check_mach", "check_altitudes", "check_workers",
           "check_count", "check_damping", "check_trim_options", "check_plot_path", "check_log_path", "check_out_dir",
           "check_mach_range", "flight_condition", "PRANDTL_GLAUERT_MACH_MAX"]

#: Highest Mach number of the Prandtl-Glauert correction used by the model; above it the lift slopes
#: are those of this Mach number (same value as ``flexsim.model.coupling._MACH_CAP``, tested).
PRANDTL_GLAUERT_MACH_MAX = 0.95


class CliError(FlexsimError, ValueError):
    """A command-line option is invalid or conflicts with another one."""


#: Parameters of the Python API that messages from it may name, and the command-line option a user gave instead.
API_TO_OPTION = {
    "mach_range[0]": "--mach-min",
    "mach_range[1]": "--mach-max",
    "speed_range[0]": "the lower speed of --speed-range-m-s",
    "speed_range[1]": "the upper speed of --speed-range-m-s",
    "speed_range": "--speed-range-m-s",
    "structural_damping": "--structural-damping",
    "turn_radius_m": "--turn-radius-m",
    "altitude_m": "--altitude-m",
    "duration_s": "--duration",
    "mach_step": "--mach-step",
    "speed_step": "--speed-step-m-s",
}
_API_NAME = re.compile(r"(?<![\w.\-])(?:" + "|".join(re.escape(k) for k in sorted(API_TO_OPTION, key=len, reverse=True)) + r")(?![\w\[])")


def in_user_words(text: str) -> str:
    """A message of the Python API in the command line's words: the parameters it names (``mach_range[0]``,
    ``speed_range[0]`` ...) replaced by the options a user typed (:data:`API_TO_OPTION`)."""
    return _API_NAME.sub(lambda m: API_TO_OPTION[m.group()], text)


_CONTROL = re.compile(r"[\x00-\x08\x0b-\x1f\x7f-\x9f]")


def printable(text: str) -> str:
    """``text`` with control characters (ESC, BEL, C1 codes ...) shown as ``\\xNN`` escapes; newlines and tabs kept."""
    return _CONTROL.sub(lambda m: f"\\x{ord(m.group()):02x}", text)


class SanitisedStream:
    """A text stream that writes through :func:`printable` (used for the CLI's stdout)."""

    def __init__(self, stream: TextIO) -> None:
        self._stream = stream

    def write(self, text: str) -> int:
        return self._stream.write(printable(text))

    def __getattr__(self, name: str):
        return getattr(self._stream, name)


def _strict(value):
    if isinstance(value, float) and not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if isinstance(value, dict):
        return {k: _strict(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_strict(v) for v in value]
    return value


def json_text(value) -> str:
    """Strict JSON of the CLI's ``--json`` output: a non-finite number is written as the string "inf",
    "-inf" or "nan" (e.g. the turn radius of straight flight), never as the non-standard tokens
    ``Infinity``/``NaN`` that strict parsers reject."""
    import json

    return json.dumps(_strict(value), indent=2, allow_nan=False, default=str)


def warn(command: str, text: str) -> None:
    """Print ``flexsim <command>: warning: <text>`` on stderr."""
    print(f"flexsim {command}: warning: {printable(text)}", file=sys.stderr)


def check_mach(command: str, mach: float, option: str = "--mach", allow_zero: bool = False) -> None:
    """Mach in (0, 1) ([0, 1) with ``allow_zero``); a warning at or above :data:`PRANDTL_GLAUERT_MACH_MAX`."""
    lo_ok = mach >= 0.0 if allow_zero else mach > 0.0
    if not (math.isfinite(mach) and lo_ok and mach < 1.0):
        raise CliError(f"{option} = {mach!r}: must be in {'[' if allow_zero else '('}0, 1) (the aerodynamics are subsonic; "
                       f"Prandtl-Glauert diverges at M = 1)")
    if mach >= PRANDTL_GLAUERT_MACH_MAX:
        warn(command, f"{option} = {mach:g} is beyond the Prandtl-Glauert range [0, {PRANDTL_GLAUERT_MACH_MAX}): the lift "
                      f"slopes are those of M = {PRANDTL_GLAUERT_MACH_MAX} (capped); transonic effects are not modelled")


def check_mach_range(lo: float, hi: float) -> None:
    """Flutter search range: 0 < --mach-min < --mach-max < 1."""
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi < 1.0):
        raise CliError(f"--mach-min, --mach-max = {lo!r}, {hi!r}: must satisfy 0 < mach-min < mach-max < 1")


def check_altitudes(altitudes: Iterable[float], option: str = "--altitudes") -> None:
    """Every altitude inside the ISA range of :mod:`flexsim.atmosphere`."""
    from flexsim.atmosphere import isa

    for h in altitudes:
        try:
            isa(h)
        except ValueError as exc:
            raise CliError(f"{option} = {h!r}: {exc}") from None


def check_workers(workers: int) -> None:
    if workers < 1:
        raise CliError(f"--workers = {workers}: must be an integer >= 1 (local processes)")


def check_count(count: int) -> None:
    if count < 0:
        raise CliError(f"--count = {count}: must be >= 0 (0 prints every mode)")


def check_damping(zeta: float | None) -> None:
    """Structural damping ratio in [0, 0.1], the range of the aircraft file's ``structural_damping_ratio``."""
    if zeta is not None and not (math.isfinite(zeta) and 0.0 <= zeta <= 0.1):
        raise CliError(f"--structural-damping = {zeta!r}: must be a damping ratio in [0, 0.1] (as in aircraft files)")


def check_trim_options(args) -> None:
    """``trim``: Mach (or airspeed), altitude, turn radius and flight path checked and reconciled before trimming; an
    altitude or speed not given is None here (the aircraft's cruise point, :func:`flight_condition`)."""
    speed = getattr(args, "speed_m_s", None)
    if args.mach is not None and speed is not None:
        raise CliError(f"--mach {args.mach:g} and --speed-m-s {speed:g}: give the speed once (Mach or true airspeed)")
    if args.mach is not None:
        check_mach("trim", args.mach)
    if speed is not None and not (math.isfinite(speed) and speed > 0.0):
        raise CliError(f"--speed-m-s = {speed!r}: must be a true airspeed > 0 [m/s] (subsonic at the altitude)")
    if args.altitude_m is not None:
        check_altitudes([args.altitude_m], "--altitude-m")
    r = args.turn_radius_m
    if r is not None and not (r == math.inf or r == -math.inf or (math.isfinite(r) and abs(r) >= 100.0)):
        raise CliError(f"--turn-radius-m = {r!r}: must be |R| >= 100 m (a steady turn; negative turns left) or inf for "
                       f"straight flight (omit the option)")
    climb = getattr(args, "climb_deg", None)
    if getattr(args, "glide", False) and climb is not None:
        raise CliError(f"--glide and --climb-deg {climb:g}: a glide has zero thrust and finds its own flight-path "
                       f"angle; give one of them")
    if climb is not None and not (math.isfinite(climb) and abs(climb) <= 30.0):
        raise CliError(f"--climb-deg = {climb!r}: must be within +-30 deg")


def flight_condition(command: str, args):
    """The altitude and speed of ``trim``, ``linearize`` or ``simulate``: ``--altitude-m`` and ``--mach`` or
    ``--speed-m-s`` as given, else the aircraft's cruise point (:func:`flexsim.linear.envelope.cruise_point`: its file's
    ``[envelope]``, or derived and said so). A speed beyond the Prandtl-Glauert range is warned about as ``--mach``."""
    from flexsim.linear.envelope import cruise_point

    try:
        point = cruise_point(args.aircraft, altitude_m=args.altitude_m, mach=args.mach,
                             speed_m_s=getattr(args, "speed_m_s", None))
    except ValueError as exc:
        raise CliError(str(exc).replace("speed_m_s = ", "--speed-m-s = ").replace("give one of them, or the speed",
                                                                                 "give one of them, or --mach / --speed-m-s")) from None
    if args.mach is None:
        check_mach(command, point.mach, "the speed")
    return point


def check_plot_path(path: str) -> Path:
    """A figure file to write: a supported image suffix in an existing, writable directory, not a directory."""
    p = Path(path)
    if p.is_dir():
        raise CliError(f"--plot = {path!r}: is a directory; give a file name such as {str(p / 'cla.png')!r}")
    from matplotlib.figure import Figure

    formats = Figure().canvas.get_supported_filetypes()
    suffix = p.suffix.lstrip(".").lower()
    if suffix not in formats:
        raise CliError(f"--plot = {path!r}: the suffix must be one of {', '.join('.' + f for f in sorted(formats))}")
    check_writable_dir("--plot", path, p.parent)
    return p


def check_writable_dir(option: str, path: str, directory: Path) -> None:
    """``option = path``: its directory exists and is writable (CliError naming both otherwise)."""
    directory = directory if str(directory) else Path(".")
    if not directory.is_dir():
        raise CliError(f"{option} = {path!r}: directory {str(directory)!r} does not exist")
    if not os.access(directory, os.W_OK):
        raise CliError(f"{option} = {path!r}: directory {str(directory)!r} is not writable")


def check_log_path(command: str, path: str) -> None:
    """An existing file at a flight-log path is overwritten only if it is an MCAP file (with a warning); never
    through a symbolic link."""
    p = Path(path)
    if p.is_symlink():
        raise CliError(f"--log = {path!r}: is a symbolic link (to {os.readlink(p)!r}); flexsim does not write through "
                       "links (that would create or replace the link's target): give the real path")
    if p.is_file():
        with open(p, "rb") as f:
            head = f.read(8)
        if head and head != b"\x89MCAP0\r\n":
            raise CliError(f"--log = {path!r}: an existing file that is not a flight log (MCAP); it is not overwritten — "
                           f"remove it or choose another name")
        warn(command, f"--log = {path!r}: overwriting the existing flight log")


def check_out_dir(path: str) -> Path:
    """Create the output folder of a long command before computing; a clear error if it cannot be."""
    p = Path(path)
    if p.exists() and not p.is_dir():
        raise CliError(f"--out = {path!r}: exists and is not a directory")
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise CliError(f"--out = {path!r}: cannot create the output folder ({exc.strerror or exc})") from None
    if not os.access(p, os.W_OK):
        raise CliError(f"--out = {path!r}: the output folder is not writable")
    return p
