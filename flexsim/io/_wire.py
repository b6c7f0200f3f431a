"""The protobuf wire format of a flight log's per-sample messages, and their MCAP records, written directly.

A 60 s flight log holds 3,000 samples of 8 messages each; built as protobuf objects and added one by one through
``mcap``'s writer they cost about three times the flight itself (``docs/performance.md``). Here the messages whose
layout is fixed are encoded from their fields (``flexsim.AircraftState``: :func:`state_messages`; the time stamp and
pose of ``foxglove.FrameTransform`` and ``foxglove.PointCloud``: :func:`timestamp_field`, :func:`tf_pose`) and
appended to the MCAP chunk as ``mcap.writer.Writer.add_message`` would (:class:`Messages`). The bytes are the same:
proto3 wire format (https://protobuf.dev/programming-guides/encoding/: fields in number order, a scalar left out when
all its bits are zero, repeated doubles packed, varint lengths) and MCAP's Message record (opcode 0x05, record
length, channel id, sequence, log time, publish time, data; https://mcap.dev/spec). ``tests/io/test_flight_log.py``
compares them with protobuf's and mcap's own output.
"""

from __future__ import annotations

import struct
from collections.abc import Sequence

import numpy as np
from mcap.opcode import Opcode
from mcap.records import MessageIndex

__all__ = ["varint", "state_messages", "timestamp_field", "tf_pose", "CLOUD_DATA_KEY", "Messages"]


def varint(value: int) -> bytes:
    """The protobuf base-128 varint of a non-negative int."""
    if value < len(_SMALL_VARINTS):
        return _SMALL_VARINTS[value]
    return _varint_of(value)


def _varint_of(value: int) -> bytes:
    out = bytearray()
    while value > 0x7F:
        out.append((value & 0x7F) | 0x80)
        value >>= 7
    out.append(value)
    return bytes(out)


_SMALL_VARINTS = tuple(_varint_of(i) for i in range(1 << 14))
#: Wire-format keys (field number << 3 | wire type) of the packed repeated double fields 2-6 of ``AircraftState``.
_PACKED_KEYS = tuple(varint(number << 3 | 2) for number in range(2, 7))
_T_KEY = varint(1 << 3 | 1)  # field 1, t: a 64-bit double


CLOUD_DATA_KEY = varint(6 << 3 | 2)  # PointCloud field 6, data: bytes
_DOUBLE = struct.Struct("<d")
_ZERO = b"\0" * 8


def state_messages(times: Sequence[float], *fields: np.ndarray) -> list[bytes]:
    """The serialised ``flexsim.AircraftState`` of K samples at times [s] (K,) with the fields position_ned_m,
    euler_rad, state, controls, signals (K, size) each, as ``SerializeToString`` writes it (fields in number order, t
    only if its bits are not all zero, each repeated double packed, empty ones left out): the packed fields of all
    samples laid out in one array of bytes, one row per sample (their sizes do not change from sample to sample), the
    time field added per sample."""
    k = len(times)
    columns = []
    for key, values in zip(_PACKED_KEYS, fields):
        if values.shape[1]:
            head = np.frombuffer(key + varint(8 * values.shape[1]), np.uint8)
            columns += [np.broadcast_to(head, (k, head.size)), np.ascontiguousarray(values, "<f8").view(np.uint8)]
    rows = np.concatenate(columns, axis=1) if columns else np.zeros((k, 0), np.uint8)
    t = np.asarray(times, "<f8").reshape(k, 1)
    heads = np.concatenate([np.broadcast_to(np.frombuffer(_T_KEY, np.uint8), (k, len(_T_KEY))), t.view(np.uint8)], axis=1)
    out = []
    for i in range(k):
        head = heads[i].tobytes()
        out.append(head + rows[i].tobytes() if head[len(_T_KEY):] != _ZERO else rows[i].tobytes())
    return out


def timestamp_field(ns: int) -> bytes:
    """Field 1 (``google.protobuf.Timestamp`` timestamp) of a FrameTransform or PointCloud at ``ns`` [ns], as
    ``timestamp.FromNanoseconds(ns)`` and ``SerializeToString`` write it: present, with seconds (field 1) and nanos
    (field 2) as varints where not 0."""
    seconds, nanos = divmod(ns, 1_000_000_000)
    body = (b"\x08" + varint(seconds) if seconds else b"") + (b"\x10" + varint(nanos) if nanos else b"")
    return b"\x0a" + varint(len(body)) + body


def _doubles(values: Sequence[float]) -> bytes:
    """The fields 1, 2, ... (64-bit doubles) of a message of doubles (Vector3, Quaternion), those whose bits are not all
    zero (proto3)."""
    out = []
    for number, value in enumerate(values, start=1):
        data = _DOUBLE.pack(value)
        if data != _ZERO:
            out += [bytes((number << 3 | 1,)), data]
    return b"".join(out)


def tf_pose(translation: Sequence[float], rotation: Sequence[float]) -> bytes:
    """Fields 4 (translation, Vector3) and 5 (rotation, Quaternion) of the body frame's FrameTransform, both present."""
    t, r = _doubles(translation), _doubles(rotation)
    return b"\x22" + varint(len(t)) + t + b"\x2a" + varint(len(r)) + r


class Messages:
    """Appends Message records to the current chunk of an ``mcap`` writer exactly as its ``add_message`` does (the same
    record bytes, message indexes, statistics and chunk boundaries: the same file), without its per-message Python
    objects: about a third of the cost of a flight log's samples. It uses the chunk builder and statistics of
    ``mcap.writer.Writer`` (mcap 1.6); a writer without them (another mcap version) gets ``add_message``."""

    _RECORD = struct.Struct("<BQHIQQ")  # opcode 0x05, record length, channel id, sequence, log time, publish time

    def __init__(self, writer: McapWriter) -> None:
        self._writer = writer
        builder = getattr(writer, "_Writer__chunk_builder", None)
        self._builder = builder
        self._stats = getattr(writer, "_Writer__statistics", None)
        self._finalize = getattr(writer, "_Writer__maybe_finalize_chunk", None)
        self._chunk_size = getattr(writer, "_Writer__chunk_size", None)
        self.fast = (builder is not None and self._stats is not None and self._finalize is not None
                     and isinstance(self._chunk_size, int)
                     and all(hasattr(builder, a) for a in ("message_indices", "num_messages", "message_start_time",
                                                            "message_end_time", "record_writer"))
                     and all(hasattr(self._stats, a) for a in ("message_count", "message_start_time", "message_end_time",
                                                              "channel_message_counts"))
                     and hasattr(builder.record_writer, "_buffer"))

    def add_sample(self, ns: int, messages: list[tuple[int, bytes]]) -> None:
        """Add the messages (channel, data) of one sample, in order, all at log and publish time ``ns``."""
        if not self.fast:
            for channel, data in messages:
                self._writer.add_message(channel_id=channel, log_time=ns, publish_time=ns, data=data)
            return
        stats, builder, pack, limit = self._stats, self._builder, self._RECORD.pack, self._chunk_size
        # the statistics and chunk times of len(messages) add_message calls at the one time ns
        stats.message_start_time = ns if stats.message_count == 0 else min(ns, stats.message_start_time)
        stats.message_end_time = max(ns, stats.message_end_time)
        stats.message_count += len(messages)
        counts, indices = stats.channel_message_counts, builder.message_indices
        buffer = builder.record_writer._buffer
        at = buffer.tell()
        if at + sum(31 + len(data) for _, data in messages) <= limit:  # the usual case: no new chunk within the sample
            builder.message_start_time = ns if builder.num_messages == 0 else min(builder.message_start_time, ns)
            builder.message_end_time = max(builder.message_end_time, ns)
            builder.num_messages += len(messages)
            parts = []
            for channel, data in messages:
                counts[channel] += 1
                index = indices.get(channel)
                if not index:
                    index = indices[channel] = _MessageIndex(channel_id=channel, records=[])
                index.records.append((ns, at))
                parts += [pack(Opcode.MESSAGE, 22 + len(data), channel, 0, ns, ns), data]
                at += 31 + len(data)  # opcode, record length, 22 bytes of fields, the data
            buffer.write(b"".join(parts))
            return
        chunk_started = True
        for channel, data in messages:
            counts[channel] += 1
            if chunk_started:
                builder.message_start_time = ns if builder.num_messages == 0 else min(builder.message_start_time, ns)
                builder.message_end_time = max(builder.message_end_time, ns)
                chunk_started = False
            index = indices.get(channel)
            if not index:
                index = indices[channel] = _MessageIndex(channel_id=channel, records=[])
            index.records.append((ns, buffer.tell()))
            builder.num_messages += 1
            buffer.write(pack(Opcode.MESSAGE, 22 + len(data), channel, 0, ns, ns))
            buffer.write(data)
            if buffer.tell() > limit:
                self._finalize()
                buffer, chunk_started = builder.record_writer._buffer, True


class _MessageIndex(MessageIndex):
    """mcap's MessageIndex record with its entries packed in one call (the same bytes)."""

    def write(self, stream) -> None:
        records = self.records
        stream.start_record(Opcode.MESSAGE_INDEX)
        stream.write2(self.channel_id)
        stream.write4(len(records) * 16)
        stream.write(np.array(records, dtype="<u8").reshape(-1).tobytes())
        stream.finish_record()
