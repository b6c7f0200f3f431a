"""Turn a flight log into a Rerun recording with a default layout (3D aircraft + time series).

The recording (application id ``"flexsim"``) has one duration timeline, ``sim_time`` (simulation
time from 0), and no wall-clock timeline, so the same log always gives the same data. Entities:

* ``/world``: view coordinates, ENU world frame, z up (see :mod:`flexsim.io.flight_log`);
* ``/world/aircraft``: pose of the FRD body frame per sample (``Transform3D``) and its axes;
* ``/world/aircraft/structure/<component>``: deformed beam per sample, ``LineStrips3D`` +
  ``Points3D`` in body axes, so the beams move with the aircraft;
* ``/world/flight_path``: the whole trajectory (static ``LineStrips3D``);
* ``/plots/attitude`` (roll, pitch, yaw [deg]), ``/plots/altitude`` (-z [m]), ``/plots/speed``
  (ground speed from the positions and the ``airspeed_m_s`` signal [m/s]),
  ``/plots/controls/<name>``, ``/plots/tip_deflections`` (signals ``tip_deflection_<component>_m``),
  ``/plots/tip_twists`` (``tip_twist_<component>_rad``), ``/plots/modal/bending`` and ``/plots/modal/torsion``
  (states ``q_<component>_<k>_m`` and ``xi_<component>_<k>_rad``); series are selected by the output vocabulary
  (:mod:`flexsim.io.vocabulary`), so logs of every format version are plotted alike;
* ``/events``: ``TextLog``.

Viewing: :func:`log_to_recording` with ``spawn=True`` starts a Rerun viewer through the recording
(:func:`spawn_viewer`: ``rerun.spawn(recording=rec)``, rerun-sdk 0.41) and streams to it over gRPC; with
``connect=URL`` it streams to a viewer or server that is already running. Where no viewer window can open
(no ``DISPLAY``/``WAYLAND_DISPLAY`` on Linux), :func:`spawn_viewer` raises :class:`ViewerUnavailableError` at
once, naming the headless alternatives (save an ``.rrd`` file, or connect to a viewer elsewhere).
"""

from __future__ import annotations

import argparse
import os
from collections.abc import Sequence
from pathlib import Path

import numpy as np
import rerun as rr
import rerun.blueprint as rrb

from flexsim.io.output_paths import check_not_link, open_output
from flexsim.io.flight_log import FlightLog, read_flight_log, viewer_pose
from flexsim.io.vocabulary import quantity
from flexsim.io.viewer import HEADLESS_HINT, ViewerUnavailableError, viewer_unavailable_reason

__all__ = ["APPLICATION_ID", "TIMELINE", "VIEWER_PORT", "ViewerUnavailableError", "default_blueprint", "log_to_recording",
           "spawn_viewer", "viewer_unavailable_reason"]

APPLICATION_ID = "flexsim"
#: Port of a spawned viewer (Rerun's default).
VIEWER_PORT = 9876
TIMELINE = "sim_time"
MAX_PATH_POINTS = 20_000
_TEXT_LOG_LEVEL = {"info": rr.TextLogLevel.INFO, "warning": rr.TextLogLevel.WARN,
                   "error": rr.TextLogLevel.ERROR}
_COMPONENT_COLORS = [(230, 159, 0), (86, 180, 233), (0, 158, 115), (240, 228, 66), (0, 114, 178),
                     (213, 94, 0), (204, 121, 167)]


def _plot_groups(log: FlightLog) -> dict[str, tuple[list[str], np.ndarray]]:
    """Time series to plot: entity path -> (series names, values (N, n_series)).

    Groups without any series (e.g. no ``tip_*`` signal in the log) are left out.
    """
    groups: dict[str, tuple[list[str], np.ndarray]] = {
        "/plots/attitude": (["roll [deg]", "pitch [deg]", "yaw [deg]"], np.rad2deg(log.euler_rad)),
        "/plots/altitude": (["altitude [m]"], -log.position_m[:, 2:3]),
    }
    speed_names = [n for n in log.signal_names if n == "airspeed_m_s"]
    speeds = [log.signal(n) for n in speed_names]
    if len(log.t) >= 2:
        speed_names.append("ground speed [m/s]")
        speeds.append(np.linalg.norm(np.gradient(log.position_m, log.t, axis=0), axis=1))
    if speeds:
        groups["/plots/speed"] = (speed_names, np.column_stack(speeds))
    for i, name in enumerate(log.control_names):
        groups[f"/plots/controls/{rr.escape_entity_path_part(name)}"] = (
            [name], log.controls[:, i:i + 1])
    for path, columns, pattern in [
            ("/plots/tip_deflections", log.signal_names, "tip_deflection_{component}_m"),
            ("/plots/tip_twists", log.signal_names, "tip_twist_{component}_rad"),
            ("/plots/modal/bending", log.state_names, "q_{component}_{k}_m"),
            ("/plots/modal/torsion", log.state_names, "xi_{component}_{k}_rad")]:
        index = [i for i, n in enumerate(columns) if _pattern(n) == pattern]
        if index:
            values = log.signals if columns is log.signal_names else log.state
            groups[path] = ([columns[i] for i in index], values[:, index])
    return groups


def _pattern(name: str) -> str | None:
    """The vocabulary pattern a name matches (:mod:`flexsim.io.vocabulary`), None for a name outside it."""
    try:
        return quantity(name).pattern
    except KeyError:
        return None


def default_blueprint(log: FlightLog) -> rrb.Blueprint:
    """Default layout: 3D views (large, left), events below them, time-series panels on the right.

    Parameters
    ----------
    log : FlightLog
        Used only to leave out panels that would be empty.

    Returns
    -------
    rerun.blueprint.Blueprint
    """
    return _blueprint(_plot_groups(log))


def _blueprint(groups: dict[str, tuple[list[str], np.ndarray]]) -> rrb.Blueprint:
    """The layout of :func:`default_blueprint` for the plot groups of :func:`_plot_groups`."""
    plots: list[rrb.View | rrb.Container] = [
        rrb.TimeSeriesView(origin="/plots/attitude", name="Attitude [deg]"),
        rrb.Horizontal(*[rrb.TimeSeriesView(origin=p, name=n) for p, n in
                         [("/plots/speed", "Speed [m/s]"), ("/plots/altitude", "Altitude [m]")]
                         if p in groups])]
    controls = [p for p in groups if p.startswith("/plots/controls/")]
    if controls:
        plots.append(rrb.Grid(*[rrb.TimeSeriesView(origin=p, name=groups[p][0][0])
                                for p in controls], name="Controls"))
    if "/plots/tip_deflections" in groups:
        plots.append(rrb.TimeSeriesView(origin="/plots/tip_deflections", name="Tip deflections [m]"))
    if "/plots/tip_twists" in groups:
        plots.append(rrb.TimeSeriesView(origin="/plots/tip_twists", name="Tip twists [rad]"))
    if any(p.startswith("/plots/modal/") for p in groups):
        plots.append(rrb.TimeSeriesView(origin="/plots/modal", name="Modal coordinates"))
    scene = rrb.Tabs(
        rrb.Spatial3DView(origin="/world", name="World (ENU, z up)",
                          eye_controls=rrb.EyeControls3D(tracking_entity="/world/aircraft")),
        rrb.Spatial3DView(origin="/world/aircraft", name="Aircraft (body axes FRD)"))
    return rrb.Blueprint(rrb.Horizontal(
        rrb.Vertical(scene, rrb.TextLogView(origin="/events", name="Events"), row_shares=[4, 1]),
        rrb.Vertical(*plots), column_shares=[3, 2]))


def _send_scene(rec: rr.RecordingStream, log: FlightLog, time: list[rr.TimeColumn]) -> None:
    """Aircraft pose, deformed structure and flight path."""
    translation, quaternion = viewer_pose(log.position_m, log.euler_rad)
    extent = max((float(np.max(np.abs(s))) for s in log.structure.values() if s.size),
                 default=0.0) or 1.0  # [m], sets axis length and line radii
    rec.log("/world", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
    rec.log("/world/aircraft", rr.ViewCoordinates.FRD, rr.TransformAxes3D(0.3 * extent),
            static=True)
    rec.send_columns("/world/aircraft", indexes=time, columns=rr.Transform3D.columns(
        translation=translation, quaternion=quaternion))
    n_samples = len(log.t)
    for k, (name, nodes) in enumerate(log.structure.items()):
        path = f"/world/aircraft/structure/{name}"
        color = _COMPONENT_COLORS[k % len(_COMPONENT_COLORS)]
        rec.log(path, rr.LineStrips3D.from_fields(radii=0.004 * extent, colors=[color]),
                rr.Points3D.from_fields(radii=0.008 * extent, colors=[color]), static=True)
        n_nodes = nodes.shape[1]
        rec.send_columns(path, indexes=time, columns=[
            *rr.LineStrips3D.columns(strips=list(nodes)),
            *rr.Points3D.columns(positions=nodes.reshape(-1, 3)).partition([n_nodes] * n_samples)])
    step = max(1, -(-n_samples // MAX_PATH_POINTS))
    path_points = np.concatenate([translation[::step], translation[-1:]])
    rec.log("/world/flight_path", rr.LineStrips3D([path_points], colors=[(160, 160, 160)]),
            static=True)


def _send_plots(rec: rr.RecordingStream, groups: dict[str, tuple[list[str], np.ndarray]],
                time: list[rr.TimeColumn]) -> None:
    """All time series of :func:`_plot_groups`, one ``send_columns`` call per entity."""
    for path, (names, values) in groups.items():
        rec.log(path, rr.SeriesLines(names=names), static=True)
        rec.send_columns(path, indexes=time, columns=rr.Scalars.columns(scalars=values))


def _send_events(rec: rr.RecordingStream, log: FlightLog) -> None:
    if not log.events:
        return
    rec.send_columns(
        "/events", indexes=[rr.TimeColumn(TIMELINE, duration=[e.t_s for e in log.events])],
        columns=rr.TextLog.columns(text=[e.text for e in log.events],
                                   level=[_TEXT_LOG_LEVEL[e.level] for e in log.events]))


def spawn_viewer(rec: rr.RecordingStream, *, port: int = VIEWER_PORT, executable: str | None = None) -> str:
    """Start a Rerun viewer for ``rec`` (not yet connected) and return the gRPC URL to stream to.

    Parameters
    ----------
    rec : rerun.RecordingStream
        The recording the viewer is started for; passed to ``rerun.spawn(recording=rec)`` (rerun-sdk 0.41
        ignores ``spawn`` without an enabled recording, which is why the module-level call never opened one).
    port : int, optional
        Port the viewer listens on [9876, Rerun's default]; an already running viewer on that port is reused.
    executable : str, optional
        Path of the ``rerun`` executable to start (default: the one installed with rerun-sdk).

    Raises
    ------
    ViewerUnavailableError
        At once, if no viewer window can open here (:func:`viewer_unavailable_reason`), or if the viewer
        process cannot be started.
    """
    reason = viewer_unavailable_reason()
    if reason is not None:
        raise ViewerUnavailableError(f"cannot open a Rerun viewer: {reason}; {HEADLESS_HINT}")
    try:
        rr.spawn(port=port, connect=False, recording=rec, executable_path=executable)
    except Exception as exc:  # rerun raises RuntimeError/OSError variants when the executable cannot start
        raise ViewerUnavailableError(f"cannot start the Rerun viewer ({exc}); {HEADLESS_HINT}") from exc
    return f"rerun+http://127.0.0.1:{port}/proxy"


def log_to_recording(log: FlightLog | str | os.PathLike, *, rrd_path: str | os.PathLike | None = None,
                     spawn: bool = False, connect: str | None = None, viewer_port: int = VIEWER_PORT,
                     viewer_executable: str | None = None) -> None:
    """Send a flight log to Rerun: save it as an ``.rrd`` file and/or show it in a viewer.

    Parameters
    ----------
    log : FlightLog or path
        A log read by :func:`~flexsim.io.flight_log.read_flight_log`, or the path of a ``.mcap``
        flight log (read here; a truncated log is recovered with a warning).
    rrd_path : path, optional
        Write the recording, with its default blueprint, to this ``.rrd`` file (headless).
    spawn : bool, optional
        Start a Rerun viewer (:func:`spawn_viewer`) and stream the recording to it.
    connect : str, optional
        Stream the recording to a viewer or Rerun server already running at this gRPC URL
        (``rerun+http://HOST:PORT/proxy``) instead of spawning one.
    viewer_port, viewer_executable : optional
        Port and executable of a spawned viewer (see :func:`spawn_viewer`).

    Raises
    ------
    ValueError
        If neither ``rrd_path``, ``spawn`` nor ``connect`` is given, both ``spawn`` and ``connect`` are, or
        ``rrd_path`` does not end in ``.rrd``.
    FileNotFoundError
        If the directory of ``rrd_path`` does not exist.
    ViewerUnavailableError
        If a viewer cannot be spawned (before anything is sent) or does not take the recording.
    """
    if rrd_path is None and not spawn and connect is None:
        raise ValueError("log_to_recording: give rrd_path (save an .rrd file), spawn=True (open a viewer) "
                         "and/or connect=URL (stream to a running viewer); got none")
    if spawn and connect is not None:
        raise ValueError(f"log_to_recording: spawn=True and connect={connect!r} both given; choose one viewer")
    if rrd_path is not None:
        rrd_path = check_not_link("rrd_path", rrd_path)
        if rrd_path.suffix != ".rrd":
            raise ValueError(f"rrd_path: the suffix must be '.rrd', got {str(rrd_path)!r}")
        if not rrd_path.parent.is_dir():
            raise FileNotFoundError(f"rrd_path: directory {str(rrd_path.parent)!r} does not exist")
    if not isinstance(log, FlightLog):
        log = read_flight_log(log)
    groups = _plot_groups(log)
    rec = rr.RecordingStream(APPLICATION_ID, recording_id=log.metadata.get("run_id"))
    rec.set_log_time_enabled(False)
    sinks: list[rr.FileSink | rr.GrpcSink] = []
    url = spawn_viewer(rec, port=viewer_port, executable=viewer_executable) if spawn else connect
    memory = None
    if rrd_path is not None and url is None:
        # kept in memory and written by Python at the end: a write error (a full disk) is an OSError naming the file;
        # rerun's own file sink waited forever on it
        memory = rec.memory_recording()
        rr.send_blueprint(_blueprint(groups), make_active=False, make_default=True, recording=rec)
    elif rrd_path is not None:
        sinks.append(rr.FileSink(str(rrd_path)))
    if url is not None:
        sinks.append(rr.GrpcSink(url))
    if sinks:
        rec.set_sinks(*sinks, default_blueprint=_blueprint(groups))
    try:
        if len(log.t):
            time = [rr.TimeColumn(TIMELINE, duration=log.t)]
            _send_scene(rec, log, time)
            _send_plots(rec, groups, time)
        _send_events(rec, log)
        try:
            rec.flush()
        except RuntimeError as exc:  # the gRPC sink gave up (viewer closed, or nothing listening at the URL)
            if url is None:
                raise
            raise ViewerUnavailableError(f"the Rerun viewer at {url} did not take the recording ({exc}); "
                                         f"{HEADLESS_HINT}") from exc
        if memory is not None:
            _write_recording(rrd_path, memory.drain_as_bytes())
    finally:
        rec.disconnect()


def _write_recording(path: Path, data: bytes) -> None:
    """``data`` written to ``path`` (no symbolic link followed); on a write error (disk full, quota) the partial file
    is removed and the error names the file."""
    try:
        with open_output(path) as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
    except OSError as exc:
        path.unlink(missing_ok=True)
        raise OSError(exc.errno, f"rrd_path = {str(path)!r}: the recording ({len(data)} bytes) could not be written: "
                                 f"{exc.strerror or exc}") from None


def main(argv: Sequence[str] | None = None) -> None:
    """Command line: ``python -m flexsim.io.rerun_view LOG.mcap [--rrd OUT.rrd] [--no-spawn]``."""
    parser = argparse.ArgumentParser(
        prog="python -m flexsim.io.rerun_view",
        description="Show a flexsim flight log (.mcap) in Rerun with the default layout.")
    parser.add_argument("log", help="flight log (.mcap)")
    parser.add_argument("--rrd", help="also save the recording to this .rrd file")
    parser.add_argument("--no-spawn", action="store_true", help="do not open a viewer")
    parser.add_argument("--connect", metavar="URL", help="stream to a running viewer (rerun+http://HOST:9876/proxy)")
    args = parser.parse_args(argv)
    if args.no_spawn and args.rrd is None and args.connect is None:
        parser.error("--no-spawn needs --rrd or --connect")
    try:
        log_to_recording(args.log, rrd_path=args.rrd, spawn=not args.no_spawn and args.connect is None,
                         connect=args.connect)
    except (ViewerUnavailableError, ValueError, FileNotFoundError) as exc:
        parser.exit(2, f"{parser.prog}: error: {exc}\n")


if __name__ == "__main__":
    main()
