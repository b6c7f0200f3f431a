"""Flight logs: MCAP files written while a simulation runs, and read back for analysis and viewing.

A flight log is an `MCAP <https://mcap.dev>`_ file with protobuf-encoded messages, which both Rerun
(``rerun log.mcap``) and Foxglove open natively (format for users: ``docs/logs.md``). Topics:
``/tf`` (``foxglove.FrameTransform``, frame ``body`` in frame ``world``), ``/structure/<component>``
(``foxglove.PointCloud`` of beam nodes in frame ``body``), ``/aircraft/state``
(``flexsim.AircraftState``: exact t, NED position, Euler angles, state, controls, signals) and
``/events`` (``foxglove.Log``). Message log and publish times are the simulation time in ns from 0.
The MCAP metadata record ``"flexsim"`` holds the format name and version, the name lists with their units,
the structure topology and, when the writer is given them, the model's physical terms (``"terms"``:
:meth:`flexsim.model.terms.Terms.record`) and its aerodynamic formulation (``"formulation"``) (JSON strings); the
record ``"run"`` holds the caller's metadata.

Names. Format 2 (written now) takes every state, control and signal name from the one output vocabulary,
:data:`flexsim.io.vocabulary.QUANTITIES` (SI units and radians, the unit in the name; ``docs/logs.md``); the
writer rejects any other name. Format 1 logs came in two dialects (the simulator's and the environments'); the
reader translates both into the format-2 vocabulary (:func:`flexsim.io.vocabulary.upgrade_v1`), so old logs keep
loading with today's names and units.

Frames. The simulator uses inertial axes north-east-down (NED) and body axes x forward, y right,
z down (FRD) with 3-2-1 Euler angles (see ``docs/conventions.md``). Viewers expect a z-up world, so
the log's ``world`` frame is east-north-up (ENU): ``r_enu = T r_ned`` with
``T = [[0, 1, 0], [1, 0, 0], [0, 0, -1]]`` (det T = +1, a 180 deg rotation about (1, 1, 0)/sqrt 2).
The ``body`` frame is the simulator's FRD body frame unchanged, so structure points are logged as the
simulator computes them; the ``/tf`` rotation ``R = T C^T`` (C: NED -> body direction cosine matrix)
is a proper rotation between two right-handed frames.
"""

from __future__ import annotations

import json
import math
import numbers
import os
import re
import struct
import time
import warnings
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, NamedTuple

import numpy as np
import zstandard
from foxglove_schemas_protobuf.FrameTransform_pb2 import FrameTransform
from foxglove_schemas_protobuf.Log_pb2 import Log
from foxglove_schemas_protobuf.PackedElementField_pb2 import PackedElementField
from foxglove_schemas_protobuf.PointCloud_pb2 import PointCloud
from google.protobuf import descriptor_pb2, descriptor_pool, message_factory
from google.protobuf.message import DecodeError
from mcap.exceptions import McapError
from mcap.well_known import MessageEncoding, SchemaEncoding
from mcap.writer import Writer as McapWriter
from mcap_protobuf.decoder import DecoderFactory
from mcap_protobuf.schema import build_file_descriptor_set

from flexsim.io.output_paths import open_output
from flexsim.errors import FlexsimError
from flexsim.io._wire import CLOUD_DATA_KEY, Messages, state_messages, tf_pose, timestamp_field, varint
from flexsim.io.vocabulary import VOCABULARY_VERSION, check_names, unit, upgrade_v1

FORMAT_NAME = "flexsim-flight-log"
#: Format version written (the vocabulary version: names from flexsim.io.vocabulary).
FORMAT_VERSION = VOCABULARY_VERSION
#: Format versions the reader reads (1: two name dialects, translated on reading).
READABLE_VERSIONS = ("1", "2")
METADATA_RECORD = "flexsim"
RUN_METADATA_RECORD = "run"
TOPIC_TF = "/tf"
TOPIC_STATE = "/aircraft/state"
TOPIC_EVENTS = "/events"
STRUCTURE_TOPIC_PREFIX = "/structure/"
WORLD_FRAME = "world"
BODY_FRAME = "body"
WALL_FLUSH_INTERVAL_S = 1.0

ENU_FROM_NED = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
_MCAP_MAGIC = b"\x89MCAP0\r\n"
_COMPONENT_NAME = re.compile(r"^[A-Za-z0-9_]+$")
_FOXGLOVE_LEVEL = {"info": Log.INFO, "warning": Log.WARNING, "error": Log.ERROR}
_LEVEL_FROM_FOXGLOVE = {Log.WARNING: "warning", Log.ERROR: "error", Log.FATAL: "error"}  # else info
_POINT_DTYPES = {PackedElementField.FLOAT32: "<f4", PackedElementField.FLOAT64: "<f8"}


class FlightLogError(FlexsimError, ValueError):
    """A file is not a readable flexsim flight log (not MCAP, empty, or missing flexsim records)."""


class FlightLogRecoveryWarning(UserWarning):
    """A flight log was unfinished or truncated; only part of it could be recovered."""


class LogEvent(NamedTuple):
    """One event of a flight log: simulation time ``t_s`` [s], ``level`` (``"info"``,
    ``"warning"`` or ``"error"``) and free ``text``."""

    t_s: float
    level: str
    text: str


def _build_aircraft_state_class() -> type:
    """Build the ``flexsim.AircraftState`` protobuf message class at run time (no ``protoc``)."""
    fdp = descriptor_pb2.FileDescriptorProto(
        name="flexsim/aircraft_state.proto", package="flexsim", syntax="proto3")
    msg = fdp.message_type.add(name="AircraftState")
    spec = descriptor_pb2.FieldDescriptorProto
    for number, name in enumerate(
            ["t", "position_ned_m", "euler_rad", "state", "controls", "signals"], start=1):
        msg.field.add(name=name, number=number, type=spec.TYPE_DOUBLE,
                      label=spec.LABEL_OPTIONAL if name == "t" else spec.LABEL_REPEATED)
    pool = descriptor_pool.DescriptorPool()
    pool.Add(fdp)
    return message_factory.GetMessageClass(pool.FindMessageTypeByName("flexsim.AircraftState"))


AircraftState = _build_aircraft_state_class()


def viewer_pose(position_ned_m: np.ndarray, euler_rad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pose of the FRD body frame in the z-up ENU viewer world frame.

    Parameters
    ----------
    position_ned_m : array_like, shape (..., 3)
        Position of the body origin in inertial NED axes [m].
    euler_rad : array_like, shape (..., 3)
        3-2-1 Euler angles (roll phi, pitch theta, yaw psi) [rad]; ``C = R_x(phi) R_y(theta)
        R_z(psi)`` maps NED components to body components.

    Returns
    -------
    translation_enu_m : ndarray, shape (..., 3)
        Body origin in ENU world axes [m]: ``T @ position_ned_m`` with ``T = ENU_FROM_NED``.
    quaternion_xyzw : ndarray, shape (..., 4)
        Unit quaternion (x, y, z, w) of ``R = T C^T``, which maps body (FRD) components to ENU
        components: ``r_enu = translation + R r_body``.
    """
    position = np.asarray(position_ned_m, dtype=float)
    half = 0.5 * np.asarray(euler_rad, dtype=float)
    cr, cp, cy = np.cos(half[..., 0]), np.cos(half[..., 1]), np.cos(half[..., 2])
    sr, sp, sy = np.sin(half[..., 0]), np.sin(half[..., 1]), np.sin(half[..., 2])
    # q_ned_from_body = (x, y, z, w) of C^T (3-2-1 sequence), then the Hamilton product with the
    # quaternion of T, (1, 1, 0, 0)/sqrt 2, written out.
    x, y = sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy
    z, w = cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy
    quaternion = math.sqrt(0.5) * np.stack([w + z, w - z, y - x, -(x + y)], axis=-1)
    return position @ ENU_FROM_NED.T, quaternion


def _validate_names(field_name: str, names: Sequence[str]) -> tuple[str, ...]:
    """Return ``names`` as a tuple after checking they are non-empty, unique strings."""
    if isinstance(names, str):
        raise ValueError(f"{field_name}: expected a sequence of names, got the string {names!r}")
    names = tuple(names)
    for name in names:
        if not isinstance(name, str) or not name.strip():
            raise ValueError(f"{field_name}: every name must be a non-empty string, got {name!r} "
                             f"in {list(names)}")
    duplicates = sorted({n for n in names if names.count(n) > 1})
    if duplicates:
        raise ValueError(f"{field_name}: names must be unique, {duplicates} appear more than once")
    return names


def _finite_vector(field_name: str, value: Any, size: int,
                   names: Sequence[str] | None = None) -> np.ndarray:
    """Return ``value`` as a float64 array of shape ``(size,)``; raise ValueError otherwise."""
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"{field_name}: expected numbers of shape ({size},), got {value!r}") from exc
    if array.shape != (size,):
        raise ValueError(f"{field_name}: expected shape ({size},), got shape {array.shape}")
    bad = np.flatnonzero(~np.isfinite(array))
    if bad.size:
        labels = [f"{field_name}[{i}]" + (f" ({names[i]!r})" if names else "") + f" = {array[i]}"
                  for i in bad[:5]]
        raise ValueError(f"{field_name}: values must be finite, got {', '.join(labels)}")
    return array


def _finite_rows(field_name: str, value: Any, k: int, size: int,
                 names: Sequence[str] | None = None) -> np.ndarray:
    """``value`` as a float64 array (k, size) of finite numbers (the rows of K samples, :func:`_finite_vector` of
    each; its message for the first bad row)."""
    try:
        array = np.asarray(value, dtype=np.float64)
    except (TypeError, ValueError):
        array = None
    if array is None or array.shape != (k, size) or not np.all(np.isfinite(array)):
        rows = list(value) if array is None or array.ndim >= 1 and len(array) == k else [value]
        for row in rows:
            _finite_vector(field_name, row, size, names)
        raise ValueError(f"{field_name}: expected shape ({k}, {size}) for {k} samples, got {np.shape(value)}")
    return array


class FlightLogWriter:
    """Write a flexsim flight log (protobuf MCAP) sample by sample, crash-safe.

    Parameters
    ----------
    path : str or os.PathLike
        Output file; suffix ``.mcap``; its directory must exist and be writable. An existing file
        is overwritten.
    state_names, control_names, signal_names : sequence of str
        Names of the entries of ``state`` (n,), ``controls`` (n_u,; 4 for flexsim's
        [T_e, delta_a, delta_e, delta_r]) and ``signals`` (k,) passed to :meth:`write`; unique within each
        list, and each a name of its kind in the output vocabulary (:mod:`flexsim.io.vocabulary`).
    structure_topology : mapping of str to int
        Component name (letters, digits, ``_``) -> number of beam nodes logged for it (>= 1).
    metadata : mapping of str to str, optional
        Free run metadata (e.g. aircraft file, git revision), stored in the MCAP record ``"run"``.
    terms : mapping, optional
        The physical terms of the logged model, JSON-ready (:meth:`flexsim.model.terms.Terms.record`), stored as
        JSON in the header record ``"flexsim"`` (key ``"terms"``) with ``formulation``; None: not recorded.
    formulation : str, optional
        The model's aerodynamic force resolution (``"physical"`` or ``"paper"``; None: no aerodynamics), recorded
        with ``terms``.
    flush_interval_s : float, optional
        Simulation time [s] between flushes to disk; the writer also flushes at least every
        ``WALL_FLUSH_INTERVAL_S`` of wall time. A process killed with SIGKILL loses at most the
        samples written since the last flush.

    Notes
    -----
    Use as a context manager, or call :meth:`close`, which writes the MCAP summary and footer.
    """

    def __init__(self, path: str | os.PathLike, *, state_names: Sequence[str],
                 control_names: Sequence[str], signal_names: Sequence[str],
                 structure_topology: Mapping[str, int], metadata: Mapping[str, str] = {},
                 terms: Mapping[str, Any] | None = None, formulation: str | None = None,
                 flush_interval_s: float = 1.0) -> None:
        path = Path(path)
        if path.suffix != ".mcap":
            raise ValueError(f"path: the suffix must be '.mcap', got {str(path)!r}")
        if not path.parent.is_dir():
            raise FileNotFoundError(f"path: directory {str(path.parent)!r} of {str(path)!r} "
                                    "does not exist")
        if not os.access(path.parent, os.W_OK):
            raise ValueError(f"path: directory {str(path.parent)!r} is not writable")
        self.state_names = check_names("state", _validate_names("state_names", state_names))
        self.control_names = check_names("control", _validate_names("control_names", control_names))
        self.signal_names = check_names("signal", _validate_names("signal_names", signal_names))
        self.structure_topology = self._validate_topology(structure_topology)
        metadata = dict(metadata)
        for key, value in metadata.items():
            if not isinstance(key, str) or not isinstance(value, str):
                raise ValueError(f"metadata: keys and values must be str, got {key!r}: {value!r}")
        model = {}
        if terms is not None:
            if formulation is not None and not isinstance(formulation, str):
                raise ValueError(f"formulation = {formulation!r}: must be a str (or None: no aerodynamics)")
            try:
                model = {"terms": json.dumps(dict(terms), allow_nan=False), "formulation": json.dumps(formulation)}
            except (TypeError, ValueError) as exc:
                raise ValueError(f"terms = {terms!r}: must be a JSON-ready mapping of finite values ({exc})") from None
        if not (isinstance(flush_interval_s, numbers.Real) and 0 < flush_interval_s < math.inf):
            raise ValueError(f"flush_interval_s: must be a finite number > 0 [s], "
                             f"got {flush_interval_s!r}")
        self.path = path
        self.flush_interval_s = float(flush_interval_s)
        self._file = open_output(path)  # never through a symbolic link
        self._closed = False
        self._last_ns = -1
        self._sim_flushed_s = -math.inf
        self._wall_flushed_s = time.monotonic()
        self._mcap = McapWriter(self._file, enable_data_crcs=True)
        self._mcap.start(profile="", library="flexsim")
        self._mcap.add_metadata(METADATA_RECORD, {
            "format": FORMAT_NAME, "format_version": FORMAT_VERSION,
            "state_names": json.dumps(self.state_names),
            "control_names": json.dumps(self.control_names),
            "signal_names": json.dumps(self.signal_names),
            "state_units": json.dumps([unit(n) for n in self.state_names]),
            "control_units": json.dumps([unit(n) for n in self.control_names]),
            "signal_units": json.dumps([unit(n) for n in self.signal_names]),
            "structure_topology": json.dumps(self.structure_topology),
            "world_frame": "ENU (x east, y north, z up)",
            "body_frame": "FRD (x forward, y right, z down)",
            "time": "log_time = simulation time in ns from 0", **model})
        self._mcap.add_metadata(RUN_METADATA_RECORD, metadata)
        self._schema_ids: dict[str, int] = {}
        self._channels = {topic: self._register(topic, cls) for topic, cls in
                          [(TOPIC_TF, FrameTransform), (TOPIC_STATE, AircraftState),
                           (TOPIC_EVENTS, Log)]}
        for name in self.structure_topology:
            self._channels[STRUCTURE_TOPIC_PREFIX + name] = self._register(
                STRUCTURE_TOPIC_PREFIX + name, PointCloud)
        self._mcap.flush()
        self._messages = Messages(self._mcap)
        self._tf = FrameTransform(parent_frame_id=WORLD_FRAME, child_frame_id=BODY_FRAME)
        self._cloud = PointCloud(frame_id=BODY_FRAME, point_stride=24, fields=[
            PackedElementField(name=axis, offset=8 * i, type=PackedElementField.FLOAT64)
            for i, axis in enumerate("xyz")])
        self._cloud.pose.orientation.w = 1.0
        # the fields of the per-sample messages that do not change: FrameTransform fields 2-3 (frame ids) and
        # PointCloud fields 2-5 (frame id, pose, stride, fields), serialised once (:func:`flexsim.io._wire.timestamp_field`)
        self._tf_frames = FrameTransform(parent_frame_id=WORLD_FRAME, child_frame_id=BODY_FRAME).SerializeToString()
        self._cloud_middle = self._cloud.SerializeToString()

    @staticmethod
    def _validate_topology(topology: Mapping[str, int]) -> dict[str, int]:
        """Check component names and node counts; return a plain dict."""
        result = {}
        for name, n_nodes in dict(topology).items():
            if not isinstance(name, str) or not _COMPONENT_NAME.match(name):
                raise ValueError(f"structure_topology: component names must be non-empty and use "
                                 f"only letters, digits and '_', got {name!r}")
            if isinstance(n_nodes, bool) or not isinstance(n_nodes, (int, np.integer)) or n_nodes < 1:
                raise ValueError(f"structure_topology[{name!r}]: the number of nodes must be an "
                                 f"integer >= 1, got {n_nodes!r}")
            result[name] = int(n_nodes)
        return result

    def _register(self, topic: str, message_class: type) -> int:
        """Register a channel for ``topic`` (and, once per class, the protobuf schema)."""
        name = message_class.DESCRIPTOR.full_name
        if name not in self._schema_ids:
            self._schema_ids[name] = self._mcap.register_schema(
                name=name, encoding=SchemaEncoding.Protobuf,
                data=build_file_descriptor_set(message_class).SerializeToString())
        return self._mcap.register_channel(topic=topic, message_encoding=MessageEncoding.Protobuf,
                                           schema_id=self._schema_ids[name])

    def _check_open(self) -> None:
        if self._closed:
            raise ValueError(f"FlightLogWriter for {str(self.path)!r} is closed")

    @staticmethod
    def _time_ns(t_s: float) -> int:
        if not (isinstance(t_s, numbers.Real) and 0 <= t_s < math.inf):
            raise ValueError(f"t_s: simulation time must be a finite number >= 0 [s], got {t_s!r}")
        return round(float(t_s) * 1e9)

    def _add(self, topic: str, ns: int, message: Any) -> None:
        self._mcap.add_message(channel_id=self._channels[topic], log_time=ns, publish_time=ns,
                               data=message.SerializeToString())

    def _maybe_flush(self, t_s: float, force: bool = False) -> None:
        """Flush after ``flush_interval_s`` of sim time or ``WALL_FLUSH_INTERVAL_S`` of wall time."""
        wall = time.monotonic()
        if (force or t_s - self._sim_flushed_s >= self.flush_interval_s
                or wall - self._wall_flushed_s >= WALL_FLUSH_INTERVAL_S):
            self._mcap.flush()
            self._sim_flushed_s = t_s
            self._wall_flushed_s = wall

    def write(self, t_s: float, *, position_m: Any, euler_rad: Any, state: Any, controls: Any,
              signals: Any, structure: Mapping[str, Any]) -> None:
        """Append one sample.

        Parameters
        ----------
        t_s : float
            Simulation time [s], >= 0 and strictly increasing from sample to sample.
        position_m : array_like, shape (3,)
            Inertial NED position of the body origin [m].
        euler_rad : array_like, shape (3,)
            3-2-1 Euler angles roll, pitch, yaw [rad].
        state : array_like, shape (n,)
            State vector, entries named by ``state_names``.
        controls : array_like, shape (n_u,)
            Controls, named by ``control_names``.
        signals : array_like, shape (k,)
            Output signals, named by ``signal_names``.
        structure : mapping of str to array_like, shape (n_nodes, 3)
            For every component of ``structure_topology``, the beam node positions in body axes
            (x forward, y right, z down) [m].

        Raises
        ------
        ValueError
            If the writer is closed, time does not increase, a shape is wrong, a component is
            missing or unknown, or a value is not finite. Nothing is written then.
        """
        self._check_open()
        if set(structure) != set(self.structure_topology):
            raise ValueError(f"structure: expected components {sorted(self.structure_topology)}, "
                             f"got {sorted(structure)}")
        try:
            nodes = {name: np.asarray(structure[name], dtype=np.float64)[None] for name in self.structure_topology}
        except (TypeError, ValueError) as exc:
            raise ValueError(f"structure: node positions must be numbers ({exc})") from None
        self._write_rows([t_s], [position_m], [euler_rad], [state], [controls], [signals], nodes, single=True)

    def write_samples(self, t_s: Any, *, position_m: Any, euler_rad: Any, state: Any, controls: Any, signals: Any,
                      structure: Mapping[str, Any]) -> None:
        """Append K samples at once: the arguments of :meth:`write` with a leading axis of K samples (``t_s`` (K,),
        ``position_m`` (K, 3), ..., ``structure[name]`` (K, n_nodes, 3)).

        The file is the one K calls of :meth:`write` give (the same messages, checks and flushes), written with the
        checks and the pose of all samples done at once and the state message encoded directly (its protobuf
        wire format: :func:`flexsim.io._wire.state_messages`). Nothing is written if any sample fails a check.
        """
        self._check_open()
        if set(structure) != set(self.structure_topology):
            raise ValueError(f"structure: expected components {sorted(self.structure_topology)}, "
                             f"got {sorted(structure)}")
        try:
            nodes = {name: np.asarray(structure[name], dtype=np.float64) for name in self.structure_topology}
        except (TypeError, ValueError) as exc:
            raise ValueError(f"structure: node positions must be numbers ({exc})") from None
        self._write_rows(t_s, position_m, euler_rad, state, controls, signals, nodes, single=False)

    def _write_rows(self, t_s, position_m, euler_rad, state, controls, signals, nodes, single: bool) -> None:
        """Check K samples (all before any is written) and write them (:meth:`write_samples`)."""
        times = list(t_s) if np.ndim(t_s) else [t_s]
        ns_list = [self._time_ns(t) for t in times]
        k = len(ns_list)
        last = self._last_ns
        for t, ns in zip(times, ns_list):
            if ns <= last:
                raise ValueError(f"t_s: simulation time must increase strictly, got {t!r} s after "
                                 f"{last / 1e9!r} s")
            last = ns
        position = _finite_rows("position_m", position_m, k, 3)
        euler = _finite_rows("euler_rad", euler_rad, k, 3)
        state = _finite_rows("state", state, k, len(self.state_names), self.state_names)
        controls = _finite_rows("controls", controls, k, len(self.control_names), self.control_names)
        signals = _finite_rows("signals", signals, k, len(self.signal_names), self.signal_names)
        clouds = []
        for name, n_nodes in self.structure_topology.items():
            array = nodes[name]
            if array.shape != (k, n_nodes, 3):
                shape = array.shape[1:] if single else array.shape
                expected = f"({n_nodes}, 3)" if single else f"({k}, {n_nodes}, 3)"
                raise ValueError(f"structure[{name!r}]: expected shape {expected}, got shape {shape}")
            if not np.all(np.isfinite(array)):
                raise ValueError(f"structure[{name!r}]: node positions must be finite")
            data = np.ascontiguousarray(array, dtype="<f8").tobytes()
            size = n_nodes * 24
            clouds.append((self._channels[STRUCTURE_TOPIC_PREFIX + name], data, size))
        translation, quaternion = viewer_pose(position, euler)
        translation, quaternion = translation.tolist(), quaternion.tolist()
        states = state_messages(times, position, euler, state, controls, signals)
        add = self._messages.add_sample
        tf_channel, state_channel = self._channels[TOPIC_TF], self._channels[TOPIC_STATE]
        for i, ns in enumerate(ns_list):
            stamp = timestamp_field(ns)
            messages = [(tf_channel, stamp + self._tf_frames + tf_pose(translation[i], quaternion[i]))]
            for channel, data, size in clouds:
                part = data[i * size:(i + 1) * size]
                messages.append((channel, b"".join((stamp, self._cloud_middle, CLOUD_DATA_KEY, varint(len(part)), part))))
            # The state message goes last: a recovered state message implies the whole sample survived.
            messages.append((state_channel, states[i]))
            add(ns, messages)
            self._last_ns = ns
            self._maybe_flush(float(times[i]))

    def event(self, t_s: float, text: str, level: str = "info") -> None:
        """Log an event (a ``foxglove.Log`` message on ``/events``).

        Parameters
        ----------
        t_s : float
            Simulation time of the event [s], >= 0 (need not follow the sample order).
        text : str
            Message text.
        level : {"info", "warning", "error"}
            Severity; ``"error"`` events are flushed to disk at once.
        """
        self._check_open()
        ns = self._time_ns(t_s)
        if level not in _FOXGLOVE_LEVEL:
            raise ValueError(f"level: expected one of {list(_FOXGLOVE_LEVEL)}, got {level!r}")
        if not isinstance(text, str):
            raise ValueError(f"text: expected a str, got {text!r}")
        message = Log(level=_FOXGLOVE_LEVEL[level], message=text, name="flexsim")
        message.timestamp.FromNanoseconds(ns)
        self._add(TOPIC_EVENTS, ns, message)
        self._maybe_flush(float(t_s), force=level == "error")

    def close(self) -> None:
        """Write the MCAP summary and footer and close the file; calling it again does nothing."""
        if self._closed:
            return
        self._closed = True
        try:
            self._mcap.finish()
        finally:
            self._file.close()

    def __enter__(self) -> FlightLogWriter:
        return self

    def __exit__(self, *exc_info: object) -> None:
        self.close()


@dataclass(frozen=True)
class FlightLog:
    """A flight log read back into arrays (all arrays read-only; N samples).

    Attributes
    ----------
    t : ndarray, shape (N,)
        Simulation time [s].
    position_m : ndarray, shape (N, 3)
        Inertial NED position of the body origin [m].
    euler_rad : ndarray, shape (N, 3)
        3-2-1 Euler angles roll, pitch, yaw [rad].
    state, controls, signals : ndarray, shapes (N, n), (N, n_u), (N, k)
        Columns named by ``state_names``, ``control_names``, ``signal_names`` (as written in format 2; a
        format-1 log is translated into the format-2 vocabulary and units).
    state_names, control_names, signal_names : tuple of str
        Names from :data:`flexsim.io.vocabulary.QUANTITIES` (units: :meth:`unit`).
    structure : dict of str to ndarray, shape (N, n_nodes, 3)
        Beam node positions per component in body axes (FRD) [m].
    events : tuple of LogEvent
        Events ``(t_s, level, text)`` sorted by time.
    metadata : dict of str to str
        Run metadata given to the writer.
    terms : dict or None
        The physical terms of the logged model (:meth:`flexsim.model.terms.Terms.record`, from the header record
        ``"flexsim"``); None when the log does not record them (written without ``terms``, or before they were).
    formulation : str or None
        The model's aerodynamic force resolution recorded with ``terms`` (None: no aerodynamics, or not recorded).
    complete : bool
        False if the file had no valid footer (the writer did not finish) or is damaged, and was
        recovered.
    damage : tuple of str
        Where the file is damaged (a chunk, the data section or the summary failing its CRC, an
        unreadable record), one sentence each with the byte offset and the time span lost; empty for
        an intact file. Every CRC the file carries is checked.
    recovered_until_s : float
        Time of the last sample read [s] (NaN if there is none).
    format_version : str
        Format version of the file (``"1"`` or ``"2"``).
    dialect : str
        Format 1 only: whose names the file carried, ``"simulate"``, ``"env"`` or ``"other"``
        (:func:`flexsim.io.vocabulary.upgrade_v1`); ``""`` for format 2.
    """

    t: np.ndarray
    position_m: np.ndarray
    euler_rad: np.ndarray
    state: np.ndarray
    controls: np.ndarray
    signals: np.ndarray
    state_names: tuple[str, ...]
    control_names: tuple[str, ...]
    signal_names: tuple[str, ...]
    structure: dict[str, np.ndarray]
    events: tuple[LogEvent, ...]
    metadata: dict[str, str] = field(default_factory=dict)
    terms: dict[str, Any] | None = None
    formulation: str | None = None
    complete: bool = True
    recovered_until_s: float = math.nan
    damage: tuple[str, ...] = ()
    format_version: str = FORMAT_VERSION
    dialect: str = ""

    @staticmethod
    def unit(name: str) -> str:
        """Unit of a state, control or signal name (``"1"``: dimensionless), from the vocabulary."""
        return unit(name)

    def signal(self, name: str) -> np.ndarray:
        """Return the signal ``name`` as an array of shape (N,).

        Raises
        ------
        KeyError
            If ``name`` is not in ``signal_names``; the message lists the available names.
        """
        if name not in self.signal_names:
            raise KeyError(f"no signal named {name!r}; available signals: {list(self.signal_names)}")
        return self.signals[:, self.signal_names.index(name)]


_READ_ERRORS = (McapError, DecodeError, zstandard.ZstdError, struct.error, EOFError, ValueError,
                KeyError, IndexError, OverflowError, MemoryError)


class _Scan(NamedTuple):
    """What one integrity-checked pass over a flight log found."""

    metadata: dict[str, dict[str, str]]
    messages: list[tuple[str, int, Any]]
    finished: bool  # a footer was read (the writer closed the file)
    damage: tuple[str, ...]  # where the file is damaged, one sentence each


def _time_span(start_ns: int, end_ns: int) -> str:
    return f"t = {start_ns / 1e9:.6g} .. {end_ns / 1e9:.6g} s"


def _scan(path: Path) -> _Scan:
    """Read every record of an MCAP flight log in file order, checking all of its checksums.

    The MCAP format stores a CRC-32 per chunk (of the uncompressed records), of the whole data section
    (in the DataEnd record; written by :class:`FlightLogWriter` since data CRCs were enabled, 0 = not
    stored) and of the summary (in the footer). A chunk that fails its CRC, cannot be decompressed or
    holds a message that does not decode is dropped and named; the chunks before and after it are kept.
    A record that cannot be parsed (a damaged length or opcode) ends the sequential pass; reading resumes
    at the next chunk listed in an intact summary section, if the file has one.
    """
    import io
    import zlib

    from mcap.records import Channel, Chunk, ChunkIndex, DataEnd, Footer, Message, Metadata, Schema
    from mcap.stream_reader import StreamReader, breakup_chunk, get_chunk_data_stream

    data = path.read_bytes()
    damage: list[str] = []
    schemas: dict[int, Any] = {}
    channels: dict[int, Any] = {}
    raw: list[tuple[int, int, bytes, int]] = []  # (channel id, log time, data, chunk offset)
    metadata: dict[str, dict[str, str]] = {}
    finished = False

    # The summary (if the file was finished and its summary CRC holds) lists every chunk's offset,
    # so reading can resume past a record whose header is damaged.
    index_offsets: list[int] = []
    summary_ok = False
    if len(data) >= 8 + 8 + 37 and data.endswith(_MCAP_MAGIC):
        foot = len(data) - 8 - 29  # footer record: opcode, length, 3 x uint64 ... uint32 crc = 29 bytes + 8 magic
        try:
            summary_start, _summary_offset_start, summary_crc = struct.unpack_from("<QQI", data, foot + 9)
            if data[foot] == 0x02 and 0 < summary_start < foot:
                summary_ok = summary_crc == 0 or zlib.crc32(data[summary_start : foot + 9 + 16]) == summary_crc
                if not summary_ok:
                    damage.append(f"the summary section (bytes {summary_start}..{foot}) fails its CRC")
                else:
                    for record in StreamReader(io.BytesIO(data[summary_start:foot]), skip_magic=True).records:
                        if isinstance(record, ChunkIndex):
                            index_offsets.append(record.chunk_start_offset)
                        elif isinstance(record, Schema):
                            schemas.setdefault(record.id, record)
                        elif isinstance(record, Channel):
                            channels.setdefault(record.id, record)
        except (*_READ_ERRORS, Exception):  # noqa: BLE001 - any damage in the tail only disables the index
            summary_ok = False
    index_offsets.sort()

    offset = 8
    while offset < len(data):
        stream = io.BytesIO(data)
        stream.seek(offset)
        reader = StreamReader(stream, skip_magic=True, emit_chunks=True, record_size_limit=len(data))
        start = offset
        try:
            for record in reader.records:
                end = stream.tell()
                if isinstance(record, Chunk):
                    span = _time_span(record.message_start_time, record.message_end_time)
                    try:
                        get_chunk_data_stream(record, validate_crc=True)
                        inner = breakup_chunk(record, validate_crc=False)
                    except (*_READ_ERRORS, McapError) as exc:
                        damage.append(f"the chunk at byte {start} ({span}) is damaged ({type(exc).__name__}: "
                                      f"{str(exc)[:80]}); its samples are dropped")
                    else:
                        for r in inner:
                            if isinstance(r, Schema):
                                schemas.setdefault(r.id, r)
                            elif isinstance(r, Channel):
                                channels.setdefault(r.id, r)
                            elif isinstance(r, Message):
                                raw.append((r.channel_id, r.log_time, r.data, start))
                elif isinstance(record, Schema):
                    schemas.setdefault(record.id, record)
                elif isinstance(record, Channel):
                    channels.setdefault(record.id, record)
                elif isinstance(record, Metadata):
                    metadata.setdefault(record.name, dict(record.metadata))
                elif isinstance(record, DataEnd):
                    crc = zlib.crc32(data[:start])
                    if record.data_section_crc not in (0, crc):
                        damage.append(f"the data section (bytes 0..{start}) fails its CRC")
                elif isinstance(record, Footer):
                    finished = True
                    if not data.endswith(_MCAP_MAGIC):
                        damage.append(f"the closing magic bytes after the footer (byte {end}) are damaged or cut")
                    break
                start = end
            break  # the generator only ends through an exception or the footer
        except (*_READ_ERRORS, McapError, OSError) as exc:
            resume = next((o for o in index_offsets if o > start), None)
            if resume is not None:
                damage.append(f"the record at byte {start} is unreadable ({type(exc).__name__}); reading resumes "
                              f"at the chunk at byte {resume} (from the summary index)")
                offset = resume
                continue
            header_cut = start + 9 > len(data)
            length = struct.unpack_from("<Q", data, start + 1)[0] if not header_cut else 0
            if not (header_cut or start + 9 + length > len(data)) or summary_ok:
                # the record lies inside the file: damaged, not cut (a cut is reported as incomplete)
                damage.append(f"the record at byte {start} of {len(data)} is unreadable ({type(exc).__name__}); "
                              f"nothing after it can be read")
            break
    factory = DecoderFactory()
    decoders: dict[int, Any] = {}
    messages: list[tuple[str, int, Any]] = []
    bad_chunks: dict[int, int] = {}
    for channel_id, log_time, payload, chunk_at in raw:
        channel = channels.get(channel_id)
        schema = schemas.get(channel.schema_id) if channel is not None else None
        try:
            if channel is None or schema is None:
                raise KeyError(f"channel {channel_id} has no definition")
            if channel_id not in decoders:
                decoders[channel_id] = factory.decoder_for(channel.message_encoding, schema)
            messages.append((channel.topic, log_time, decoders[channel_id](payload)))
        except (*_READ_ERRORS, TypeError) as exc:
            bad_chunks[chunk_at] = bad_chunks.get(chunk_at, 0) + 1
    for at, n in bad_chunks.items():
        damage.append(f"{n} message(s) of the chunk at byte {at} do not decode; they are dropped")
    return _Scan(metadata, messages, finished, tuple(damage))


def _points(cloud: Any, path: Path) -> np.ndarray:
    """Node positions (n, 3) [m] of a ``foxglove.PointCloud`` with float x, y, z fields."""
    fields = {f.name: f for f in cloud.fields}
    if any(fields.get(a) is None or fields[a].type not in _POINT_DTYPES for a in "xyz"):
        raise FlightLogError(f"{path}: point cloud without float x, y, z fields: {list(fields)}")
    dtype = np.dtype({"names": list("xyz"), "formats": [_POINT_DTYPES[fields[a].type] for a in "xyz"],
                      "offsets": [fields[a].offset for a in "xyz"], "itemsize": cloud.point_stride})
    packed = np.frombuffer(cloud.data, dtype=dtype)
    return np.stack([packed[a].astype(np.float64) for a in "xyz"], axis=-1)


def _frozen(array: np.ndarray) -> np.ndarray:
    array.setflags(write=False)
    return array


def _stack(rows: list[Any], shape: tuple[int, ...], what: str, path: Path) -> np.ndarray:
    """Stack per-sample rows into a read-only array (N, *shape); FlightLogError on a wrong row."""
    if any(np.shape(row) != shape for row in rows):
        raise FlightLogError(f"{path}: corrupt flight log, not every {what} has shape {shape}")
    return _frozen(np.array(rows, dtype=np.float64).reshape((len(rows),) + shape))


def read_flight_log(path: str | os.PathLike) -> FlightLog:
    """Read a flight log written by :class:`FlightLogWriter`.

    A finished file is read through its index. An unfinished or truncated file (no valid footer,
    e.g. the simulation was killed) is read sequentially up to the damage: the result has
    ``complete=False`` and a :class:`FlightLogRecoveryWarning` states up to which time data were
    recovered.

    Parameters
    ----------
    path : str or os.PathLike
        The ``.mcap`` file.

    Returns
    -------
    FlightLog

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    FlightLogError
        If the file is empty, not an MCAP file, or not a flexsim flight log.
    """
    path = Path(path)
    if not path.is_file():
        raise FileNotFoundError(f"{path}: no such flight log file")
    with open(path, "rb") as stream:
        head = stream.read(len(_MCAP_MAGIC))
    if not head:
        raise FlightLogError(f"{path}: the file is empty (0 bytes), not a flight log")
    if head != _MCAP_MAGIC:
        raise FlightLogError(f"{path}: not an MCAP file (first bytes {head!r}, expected "
                             f"{_MCAP_MAGIC!r})")
    metadata, messages, finished, damage = _scan(path)
    complete = finished and not damage

    info = metadata.get(METADATA_RECORD, {})
    if info.get("format") != FORMAT_NAME:
        if damage:
            reason = "it is damaged before its header records: " + "; ".join(damage[:2])
        elif not finished:
            reason = "it was truncated before its header records"
        else:
            reason = f"it has no '{METADATA_RECORD}' metadata record with format={FORMAT_NAME!r}"
        raise FlightLogError(f"{path}: not a flexsim flight log ({reason})")
    version = info.get("format_version")
    if version not in READABLE_VERSIONS:
        raise FlightLogError(f"{path}: unsupported flight-log format version {version!r}; this reader reads "
                             f"{', '.join(READABLE_VERSIONS)}")
    try:
        state_names, control_names, signal_names = (
            tuple(json.loads(info[key])) for key in ("state_names", "control_names", "signal_names"))
        topology = {str(k): int(v) for k, v in json.loads(info["structure_topology"]).items()}
        terms = json.loads(info["terms"]) if "terms" in info else None
        formulation = json.loads(info["formulation"]) if "formulation" in info else None
    except (KeyError, TypeError, ValueError) as exc:
        raise FlightLogError(f"{path}: corrupt '{METADATA_RECORD}' metadata record: {exc}") from exc

    by_topic: dict[str, dict[int, Any]] = {}
    event_messages = []
    for topic, ns, decoded in messages:
        if topic == TOPIC_EVENTS:
            event_messages.append((ns, decoded))
        else:
            by_topic.setdefault(topic, {})[ns] = decoded
    clouds = {name: by_topic.get(STRUCTURE_TOPIC_PREFIX + name, {}) for name in topology}
    # A sample counts if its state and all its structure messages are present (recovery may cut
    # inside a sample); the writer always writes all of them.
    sample_ns = sorted(ns for ns in by_topic.get(TOPIC_STATE, {})
                       if all(ns in cloud for cloud in clouds.values()))
    states = [by_topic[TOPIC_STATE][ns] for ns in sample_ns]
    structure = {name: _stack([_points(clouds[name][ns], path) for ns in sample_ns], (n_nodes, 3),
                              f"structure '{name}' sample", path)
                 for name, n_nodes in topology.items()}
    events = tuple(sorted((LogEvent(ns / 1e9, _LEVEL_FROM_FOXGLOVE.get(m.level, "info"), m.message)
                           for ns, m in event_messages), key=lambda e: e.t_s))
    n_samples = len(states)
    t = _frozen(np.array([m.t for m in states], dtype=np.float64))
    recovered_until_s = float(t[-1]) if n_samples else math.nan
    if damage:
        warnings.warn(f"{path}: the flight log is damaged: {'; '.join(damage)}; recovered the intact part, "
                      f"{n_samples} samples up to t = {recovered_until_s:.6g} s",
                      FlightLogRecoveryWarning, stacklevel=2)
    elif not complete:
        warnings.warn(f"{path}: the flight log is incomplete (no valid MCAP footer: the writer did "
                      f"not finish, e.g. the process was killed, or the file was cut); recovered "
                      f"{n_samples} samples up to t = {recovered_until_s:.6g} s",
                      FlightLogRecoveryWarning, stacklevel=2)
    rows = {key: [list(getattr(m, key)) for m in states]
            for key in ("position_ned_m", "euler_rad", "state", "controls", "signals")}
    signals = _stack(rows["signals"], (len(signal_names),), "signal vector", path)
    dialect = ""
    if version == "1":  # two name dialects: translated into today's vocabulary and units
        up = upgrade_v1(state_names, signal_names)
        dialect, state_names, signal_names = up.dialect, up.state_names, up.signal_names
        signals = _frozen(signals[:, list(up.signal_columns)] * np.array(up.signal_factors))
    return FlightLog(
        t=t, position_m=_stack(rows["position_ned_m"], (3,), "position", path),
        euler_rad=_stack(rows["euler_rad"], (3,), "Euler angle triple", path),
        state=_stack(rows["state"], (len(state_names),), "state", path),
        controls=_stack(rows["controls"], (len(control_names),), "control vector", path),
        signals=signals, state_names=state_names, control_names=control_names, signal_names=signal_names,
        structure=structure, events=events, metadata=metadata.get(RUN_METADATA_RECORD, {}), terms=terms,
        formulation=formulation, complete=complete, recovered_until_s=recovered_until_s, damage=damage, format_version=version,
        dialect=dialect)
