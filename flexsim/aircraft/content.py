"""Content keys of aircraft definitions: a canonical digest of every field, for caches keyed by content.

:meth:`flexsim.aircraft.definition.Aircraft.content_digest` feeds the definition through :func:`feed_digest`;
:class:`ContentKey` makes it a ``functools.lru_cache`` key (docs/design.md, "Caches are keyed by content").
"""

from __future__ import annotations

from dataclasses import fields, is_dataclass
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from flexsim.aircraft.definition import Aircraft

__all__ = ["ContentKey", "feed_digest"]


class ContentKey:
    """An :class:`Aircraft` as a cache key (``functools.lru_cache``): hashed and compared by its
    :meth:`~Aircraft.content_digest`, carrying the aircraft itself for the cached computation.

    Attributes
    ----------
    aircraft : Aircraft
    digest : str
    """

    __slots__ = ("aircraft", "digest")

    def __init__(self, aircraft: "Aircraft") -> None:
        self.aircraft = aircraft
        self.digest = aircraft.content_digest()

    def __hash__(self) -> int:
        return hash(self.digest)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, ContentKey) and other.digest == self.digest

    def __repr__(self) -> str:
        return f"ContentKey({self.aircraft.name!r}, {self.digest[:12]})"


def feed_digest(digest, value) -> None:
    """Feed a canonical, type-tagged serialisation of ``value`` (dataclasses, arrays, containers, scalars)."""
    if is_dataclass(value) and not isinstance(value, type):
        digest.update(f"<{type(value).__name__}".encode())
        for f in fields(value):
            digest.update(f.name.encode())
            feed_digest(digest, getattr(value, f.name))
        digest.update(b">")
    elif isinstance(value, np.ndarray):
        digest.update(f"<array {value.dtype.str} {value.shape}>".encode())
        digest.update(np.ascontiguousarray(value).tobytes())
    elif isinstance(value, (tuple, list)):
        digest.update(f"<seq {len(value)}>".encode())
        for item in value:
            feed_digest(digest, item)
    elif isinstance(value, dict):
        digest.update(f"<map {len(value)}>".encode())
        for key in sorted(value, key=repr):
            feed_digest(digest, key)
            feed_digest(digest, value[key])
    else:
        digest.update(f"<{type(value).__name__} {value!r}>".encode())

