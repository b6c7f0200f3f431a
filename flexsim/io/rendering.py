"""The render modes of the environments (:mod:`flexsim.envs`): ``rgb_array`` (matplotlib, Agg) and ``human`` (a Rerun viewer).

Both draw the deformed beams of every component (``PointMaps.positions``, body axes) placed with the
aircraft's attitude, and the recent flight path. ``human`` starts a Rerun viewer on its first frame only
(nothing is spawned before ``render()`` is called in that mode), through the recording
(:func:`flexsim.io.rerun_view.spawn_viewer`); where no viewer can open (a headless machine) the environment
refuses ``render_mode="human"`` at construction (:func:`flexsim.io.viewer.viewer_unavailable_reason`) and ``rgb_array`` still works.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from scipy.spatial.transform import Rotation

from flexsim.io.flight_log import ENU_FROM_NED, viewer_pose

__all__ = ["RgbRenderer", "RerunStreamer"]


_COLORS = {"fuselage": "#444444", "right_wing": "#0072b2", "left_wing": "#d55e00", "right_htail": "#56b4e9",
           "left_htail": "#e69f00", "vtail": "#009e73"}


class RgbRenderer:
    """Off-screen matplotlib image: the deformed aircraft (3D, ENU, z up) and its recent ground track.

    Parameters
    ----------
    width_px, height_px : int
        Image size (default 640 x 400).
    """

    def __init__(self, width_px: int = 640, height_px: int = 400) -> None:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        dpi = 100
        self.figure = Figure(figsize=(width_px / dpi, height_px / dpi), dpi=dpi)
        self.canvas = FigureCanvasAgg(self.figure)
        self.ax3d = self.figure.add_subplot(1, 2, 1, projection="3d")
        self.ax_path = self.figure.add_subplot(1, 2, 2)

    def draw(self, meas, nodes: Mapping[str, np.ndarray], path_ned_m: np.ndarray, controls: np.ndarray,
             title: str, errors: Mapping[str, float]) -> np.ndarray:
        """One frame as a uint8 array of shape (height, width, 3) of the outputs ``meas``
        (:class:`flexsim.sim.measurements.Measurements`), the beam ``nodes`` in body axes [m], the flight path (k, 3) [m,
        NED], the applied ``controls`` [N, rad], a ``title`` and the task ``errors``."""
        enu_from_body = Rotation.from_quat(viewer_pose(meas.position_ned_m, meas.euler_rad)[1]).as_matrix()
        ax = self.ax3d
        ax.clear()
        extent = 1.0
        for name, pts in nodes.items():
            enu = pts @ enu_from_body.T  # body -> ENU, relative to the body origin
            extent = max(extent, float(np.abs(enu).max()))
            ax.plot(enu[:, 0], enu[:, 1], enu[:, 2], "-o", ms=2, lw=2, color=_COLORS.get(name, "k"))
        centre = np.mean([p.mean(axis=0) for p in nodes.values()], axis=0) @ enu_from_body.T
        half = 0.6 * extent
        ax.set_xlim(centre[0] - half, centre[0] + half)
        ax.set_ylim(centre[1] - half, centre[1] + half)
        ax.set_zlim(centre[2] - half, centre[2] + half)
        ax.set_xlabel("east [m]", fontsize=7)
        ax.set_ylabel("north [m]", fontsize=7)
        ax.set_zlabel("up [m]", fontsize=7)
        ax.tick_params(labelsize=6)
        tips = ", ".join(f"{c.split('_')[0][0] if c != 'vtail' else 'fin'}:{v:+.2f}" for c, v in meas.tip_deflection_m.items())
        ax.set_title(f"t = {meas.time_s:5.2f} s   tip [m] {tips}", fontsize=7)
        axp = self.ax_path
        axp.clear()
        if len(path_ned_m):
            axp.plot(path_ned_m[:, 1], path_ned_m[:, 0], color="0.5")
            axp.plot(path_ned_m[-1, 1], path_ned_m[-1, 0], "o", color="#0072b2")
        axp.set_aspect("equal", adjustable="datalim")
        axp.set_xlabel("east [m]", fontsize=7)
        axp.set_ylabel("north [m]", fontsize=7)
        axp.tick_params(labelsize=6)
        axp.set_title(f"{title}\nh = {meas.altitude_m:.0f} m, V = {meas.airspeed_m_s:.1f} m/s, "
                      f"alpha = {np.degrees(meas.alpha_rad):.1f} deg", fontsize=7)
        self.figure.tight_layout()
        self.canvas.draw()
        return np.asarray(self.canvas.buffer_rgba())[:, :, :3].copy()

    def close(self) -> None:
        """Release the figure."""
        self.figure.clear()


class RerunStreamer:
    """Streams frames to a Rerun viewer (spawned on the first frame), with a ``sim_time`` timeline.

    Entities follow the flight-log layout of :mod:`flexsim.io.rerun_view`: ``/world/aircraft`` (pose),
    ``/world/aircraft/structure/<component>`` (deformed beams in body axes), ``/plots/...`` (scalars).
    """

    def __init__(self, application_id: str = "flexsim_env") -> None:
        self._application_id = application_id
        self._rec = None

    def _recording(self):
        import rerun as rr

        from flexsim.io.rerun_view import spawn_viewer

        if self._rec is None:
            rec = rr.RecordingStream(self._application_id)
            rec.set_sinks(rr.GrpcSink(spawn_viewer(rec)))
            self._rec = rec
            self._rec.log("/world", rr.ViewCoordinates.RIGHT_HAND_Z_UP, static=True)
            self._rec.log("/world/aircraft", rr.ViewCoordinates.FRD, static=True)
        return self._rec

    def draw(self, meas, nodes: Mapping[str, np.ndarray], path_ned_m: np.ndarray, controls: np.ndarray,
             title: str, errors: Mapping[str, float]) -> None:
        """Send one frame (arguments of :meth:`RgbRenderer.draw`; returns None, as gymnasium's human mode)."""
        import rerun as rr

        rec = self._recording()
        rec.set_time("sim_time", duration=meas.time_s)
        translation, quaternion = viewer_pose(meas.position_ned_m, meas.euler_rad)
        rec.log("/world/aircraft", rr.Transform3D(translation=translation, quaternion=rr.Quaternion(xyzw=quaternion)))
        for name, pts in nodes.items():
            rec.log(f"/world/aircraft/structure/{name}", rr.LineStrips3D([pts], radii=0.1))
        if len(path_ned_m) > 1:
            rec.log("/world/flight_path", rr.LineStrips3D([path_ned_m @ ENU_FROM_NED.T], colors=[(160, 160, 160)]))
        rec.log("/plots/altitude", rr.Scalars(meas.altitude_m))
        rec.log("/plots/speed", rr.Scalars(meas.airspeed_m_s))
        for c, value in meas.tip_deflection_m.items():
            rec.log(f"/plots/tip_deflections/{c}", rr.Scalars(value))
        for name, value in errors.items():
            rec.log(f"/plots/task/{name}", rr.Scalars(float(value)))
        for name, value in zip(("thrust_N", "aileron_rad", "elevator_rad", "rudder_rad"), controls):
            rec.log(f"/plots/controls/{name}", rr.Scalars(float(value)))

    def close(self) -> None:
        """Flush and disconnect from the viewer."""
        if self._rec is not None:
            self._rec.flush()
            self._rec.disconnect()
            self._rec = None
