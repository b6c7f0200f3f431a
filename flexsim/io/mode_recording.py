"""A Rerun recording of an aircraft oscillating in one of its modes (e.g. the flutter mode), with its participation.

The writer of :func:`write_mode_recording` takes the animation as arrays (:class:`ModeAnimation`, made from a model
and an eigenvector by :func:`flexsim.linear.mode_animation.mode_animation`) and draws it with the scene code of
``flexsim view`` (:mod:`flexsim.io.rerun_view`: the body pose and the deformed beams of every component, in the same
entities and frames). The recording (application id ``"flexsim"``, one duration timeline ``sim_time``) has:

* ``/world``, ``/world/aircraft``, ``/world/aircraft/structure/<component>``: as in a flight recording (ENU world,
  FRD body axes), the aircraft at the origin of the world, oscillating about its trim;
* ``/plots/attitude`` (roll, pitch, yaw [deg]), ``/plots/modal/bending`` and ``/plots/modal/torsion``: time series;
* ``/participation/linear_m`` and ``/participation/angles_deg``: bar charts of the mode's leading coordinates
  (magnitudes in m and deg per unit of the normalising coordinate, as the paper's Figs. 11 and 16), and
  ``/participation/table`` a table of their labels and phases; ``/description`` a text naming the mode;

and a default layout that plays the oscillation in a loop, slowed to about two seconds per cycle.
:func:`open_recording` shows such a file (any ``.rrd``) in a Rerun viewer, as ``flexsim view FILE.rrd`` does.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import rerun as rr
import rerun.blueprint as rrb

from flexsim.io.flight_log import FlightLog
from flexsim.io.rerun_view import APPLICATION_ID, TIMELINE, VIEWER_PORT, _send_plots, _send_scene, spawn_viewer
from flexsim.io.viewer import ViewerUnavailableError, viewer_unavailable_reason

__all__ = ["ParticipationBar", "ModeAnimation", "write_mode_recording", "open_recording"]

#: First bytes of a Rerun recording file (rerun-sdk 0.41).
RRD_MAGIC = b"RRF2"

#: Wall-clock seconds per cycle of the default playback.
SECONDS_PER_CYCLE = 2.0


@dataclass(frozen=True)
class ParticipationBar:
    """One coordinate of a mode in the bar charts.

    Attributes
    ----------
    label : str
        DOF label (e.g. ``"fuselage bending 1"``).
    magnitude : float
        |amplitude| per unit of the normalising coordinate, in ``unit``.
    unit : {"m", "deg"}
    phase_deg : float
        Phase relative to the normalising coordinate [deg].
    """

    label: str
    magnitude: float
    unit: str
    phase_deg: float

    def __post_init__(self) -> None:
        if self.unit not in ("m", "deg"):
            raise ValueError(f"unit = {self.unit!r}: must be 'm' or 'deg'")
        if not (math.isfinite(self.magnitude) and self.magnitude >= 0.0):
            raise ValueError(f"magnitude = {self.magnitude!r}: must be a finite number >= 0")


@dataclass(frozen=True, eq=False)
class ModeAnimation:
    """An oscillating aircraft as samples (N frames).

    Attributes
    ----------
    t_s : ndarray, shape (N,)
        Times [s], increasing.
    position_ned_m : ndarray, shape (N, 3)
        Body origin in NED axes [m] (relative to its trim position).
    euler_rad : ndarray, shape (N, 3)
        3-2-1 Euler angles [rad].
    structure : dict of str to ndarray, shape (N, n_nodes, 3)
        Deformed beam nodes of every component in body axes (FRD) [m].
    coordinate_names : tuple of str
        Names of the elastic coordinates (``q_<component>_<k>_m``, ``xi_<component>_<k>_rad``).
    coordinates : ndarray, shape (N, k)
        Their values.
    participation : tuple of ParticipationBar
        The bars (linear ones in m, angles in deg).
    frequency_rad_s : float
        Frequency of the oscillation [rad/s], > 0.
    title : str
        One line naming the mode (the recording's description starts with it).
    description : str
        Markdown text about the mode (flight condition, eigenvalue, amplitude scaling).
    """

    t_s: np.ndarray
    position_ned_m: np.ndarray
    euler_rad: np.ndarray
    structure: dict[str, np.ndarray]
    coordinate_names: tuple[str, ...]
    coordinates: np.ndarray
    participation: tuple[ParticipationBar, ...]
    frequency_rad_s: float
    title: str = ""
    description: str = field(default="")

    def __post_init__(self) -> None:
        t = np.asarray(self.t_s, float)
        n = t.size
        if t.ndim != 1 or n < 2 or not np.all(np.isfinite(t)) or np.any(np.diff(t) <= 0):
            raise ValueError(f"t_s: must be at least 2 finite, increasing times, got shape {t.shape}")
        if not (math.isfinite(self.frequency_rad_s) and self.frequency_rad_s > 0.0):
            raise ValueError(f"frequency_rad_s = {self.frequency_rad_s!r}: must be a finite number > 0")
        for name, shape in (("position_ned_m", (n, 3)), ("euler_rad", (n, 3)),
                            ("coordinates", (n, len(self.coordinate_names)))):
            value = np.asarray(getattr(self, name), float)
            if value.shape != shape or not np.all(np.isfinite(value)):
                raise ValueError(f"{name}: expected finite values of shape {shape}, got {value.shape}")
        for comp, nodes in self.structure.items():
            nodes = np.asarray(nodes, float)
            if nodes.ndim != 3 or nodes.shape[0] != n or nodes.shape[2] != 3 or not np.all(np.isfinite(nodes)):
                raise ValueError(f"structure[{comp!r}]: expected finite values of shape ({n}, n_nodes, 3), got {nodes.shape}")


def _table(bars: tuple[ParticipationBar, ...]) -> str:
    rows = ["| bar | coordinate | magnitude | phase [deg] |", "|---:|---|---:|---:|"]
    for unit, title in (("m", "linear [m]"), ("deg", "angles [deg]")):
        chosen = [b for b in bars if b.unit == unit]
        for i, b in enumerate(chosen):
            rows.append(f"| {title} {i} | {b.label} | {b.magnitude:.4g} {unit} | {b.phase_deg:+.1f} |")
    return "\n".join(rows)


def _blueprint(animation: ModeAnimation, has_bars: dict[str, bool]) -> rrb.Blueprint:
    period = 2.0 * math.pi / animation.frequency_rad_s
    side: list[rrb.View] = [rrb.TextDocumentView(origin="/description", name="Mode")]
    if has_bars["m"]:
        side.append(rrb.BarChartView(origin="/participation/linear_m", name="Participation, linear [m]"))
    if has_bars["deg"]:
        side.append(rrb.BarChartView(origin="/participation/angles_deg", name="Participation, angles [deg]"))
    side += [rrb.TextDocumentView(origin="/participation/table", name="Participation (bars, phases)"),
             rrb.TimeSeriesView(origin="/plots/modal", name="Elastic coordinates")]
    scene = rrb.Tabs(rrb.Spatial3DView(origin="/world", name="Mode (ENU, z up)"),
                     rrb.Spatial3DView(origin="/world/aircraft", name="Aircraft (body axes FRD)"))
    return rrb.Blueprint(rrb.Horizontal(scene, rrb.Vertical(*side), column_shares=[3, 2]),
                         rrb.TimePanel(timeline=TIMELINE, play_state="playing", loop_mode="all",
                                       playback_speed=period / SECONDS_PER_CYCLE))


def write_mode_recording(animation: ModeAnimation, path: str | os.PathLike) -> Path:
    """Write ``animation`` to the Rerun recording ``path`` (``.rrd``, module docstring); returns the path.

    Raises
    ------
    ValueError
        ``path`` does not end in ``.rrd`` or is a directory.
    FileNotFoundError
        Its directory does not exist.
    """
    path = Path(path)
    if path.is_dir():
        raise ValueError(f"path = {str(path)!r}: is a directory; give a file name ending in .rrd")
    if path.suffix != ".rrd":
        raise ValueError(f"path = {str(path)!r}: the suffix must be '.rrd' (a Rerun recording)")
    if not path.parent.is_dir():
        raise FileNotFoundError(f"path = {str(path)!r}: directory {str(path.parent)!r} does not exist")
    n = animation.t_s.size
    names = tuple(animation.coordinate_names)
    log = FlightLog(t=np.asarray(animation.t_s, float), position_m=np.asarray(animation.position_ned_m, float),
                    euler_rad=np.asarray(animation.euler_rad, float), state=np.asarray(animation.coordinates, float),
                    controls=np.zeros((n, 0)), signals=np.zeros((n, 0)), state_names=names, control_names=(),
                    signal_names=(), structure={k: np.asarray(v, float) for k, v in animation.structure.items()},
                    events=())
    groups = {"/plots/attitude": (["roll [deg]", "pitch [deg]", "yaw [deg]"], np.rad2deg(log.euler_rad))}
    for entity, prefix in (("/plots/modal/bending", "q_"), ("/plots/modal/torsion", "xi_")):
        cols = [i for i, name in enumerate(names) if name.startswith(prefix)]
        if cols:
            groups[entity] = ([names[i] for i in cols], log.state[:, cols])
    bars = {unit: [b for b in animation.participation if b.unit == unit] for unit in ("m", "deg")}
    has_bars = {unit: bool(v) for unit, v in bars.items()}
    rec = rr.RecordingStream(APPLICATION_ID)
    rec.set_log_time_enabled(False)
    rec.set_sinks(rr.FileSink(str(path)), default_blueprint=_blueprint(animation, has_bars))
    try:
        time = [rr.TimeColumn(TIMELINE, duration=log.t)]
        _send_scene(rec, log, time)
        _send_plots(rec, groups, time)
        for unit, entity in (("m", "/participation/linear_m"), ("deg", "/participation/angles_deg")):
            if bars[unit]:
                rec.log(entity, rr.BarChart([b.magnitude for b in bars[unit]]), static=True)
        rec.log("/participation/table", rr.TextDocument(_table(animation.participation), media_type=rr.MediaType.MARKDOWN),
                static=True)
        text = f"## {animation.title}\n\n{animation.description}" if animation.title else animation.description
        rec.log("/description", rr.TextDocument(text, media_type=rr.MediaType.MARKDOWN), static=True)
        rec.flush()
    finally:
        rec.disconnect()
    return path


def open_recording(path: str | os.PathLike, *, connect: str | None = None, viewer_port: int = VIEWER_PORT,
                   viewer_executable: str | None = None) -> str:
    """Show a Rerun recording (``.rrd``) in a viewer: a new one (:func:`flexsim.io.rerun_view.spawn_viewer`), or the
    viewer or server at ``connect`` (``rerun+http://HOST:PORT/proxy``). Returns the URL the file was sent to.

    Raises
    ------
    FileNotFoundError
        No such file.
    ValueError
        The file is not a Rerun recording.
    ViewerUnavailableError
        No viewer can open here (no display) and ``connect`` is not given, or the viewer did not take the file.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{str(path)!r}: no such file")
    with path.open("rb") as f:
        head = f.read(len(RRD_MAGIC))
    if head != RRD_MAGIC:
        raise ValueError(f"{str(path)!r}: not a Rerun recording (first bytes {head!r}, expected {RRD_MAGIC!r})")
    if connect is None:
        reason = viewer_unavailable_reason()
        if reason is not None:
            raise ViewerUnavailableError(
                f"cannot open a Rerun viewer: {reason}; the recording {str(path)!r} is complete: open it with "
                f"`rerun {path}` where there is a display, or stream it to a viewer running elsewhere "
                f"(flexsim view {path} --connect rerun+http://HOST:9876/proxy)")
    from rerun.chunk import RrdReader

    stores = [e for e in RrdReader(path).recordings() if e.kind == "recording"]
    # send as the file's own recording, so that the viewer gets one recording, not the file's and an empty one
    rec = (rr.RecordingStream(stores[0].application_id, recording_id=stores[0].recording_id) if stores
           else rr.RecordingStream(APPLICATION_ID))
    url = connect if connect is not None else spawn_viewer(rec, port=viewer_port, executable=viewer_executable)
    rec.set_sinks(rr.GrpcSink(url))
    try:
        rec.log_file_from_path(path)
        try:
            rec.flush()
        except RuntimeError as exc:
            raise ViewerUnavailableError(f"the Rerun viewer at {url} did not take the recording ({exc})") from exc
    finally:
        rec.disconnect()
    return url
