"""Small helpers shared across flexsim (no physics): read-only arrays and objects immutable after construction."""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["readonly", "freeze_arrays", "Immutable"]


def readonly(array: np.ndarray) -> np.ndarray:
    """Mark ``array`` read-only (frozen results and parameter bundles are immutable) and return it."""
    array.flags.writeable = False
    return array


def freeze_arrays(value, _seen: set[int] | None = None) -> None:
    """Mark every ndarray reachable from ``value`` read-only: the array itself, the items of tuples, lists and dict
    values, and the fields of frozen dataclasses (recursively; other objects are left alone)."""
    seen = set() if _seen is None else _seen
    if id(value) in seen:
        return
    seen.add(id(value))
    if isinstance(value, np.ndarray):
        if value.dtype != object:
            value.flags.writeable = False
    elif isinstance(value, (tuple, list)):
        for item in value:
            freeze_arrays(item, seen)
    elif isinstance(value, dict):
        for item in value.values():
            freeze_arrays(item, seen)
    elif dataclasses.is_dataclass(value) and not isinstance(value, type):
        for f in dataclasses.fields(value):
            freeze_arrays(getattr(value, f.name, None), seen)


class Immutable:
    """Mixin of objects that are immutable after construction (house style: state passed per call, not stored).

    The class's ``__init__`` ends with :meth:`_seal`: afterwards, setting or deleting an attribute raises
    AttributeError naming the class and the attribute, and every ndarray held in an attribute (directly, in a
    tuple, list, dict or frozen dataclass) is read-only, so writing into it raises ValueError. ``cached_property``
    values are still computed once (they bypass ``__setattr__``).
    """

    __slots__ = ()

    def _seal(self) -> None:
        for value in vars(self).values():
            freeze_arrays(value)
        object.__setattr__(self, "_sealed_", True)

    def _refuse(self, name: str, what: str) -> None:
        if vars(self).get("_sealed_", False):
            cls = type(self).__name__
            raise AttributeError(f"{cls} is immutable after construction: cannot {what} attribute {name!r}; build a new "
                                 f"{cls} from changed inputs, and pass disturbances and options per call")

    def __setattr__(self, name: str, value) -> None:
        self._refuse(name, "set")
        object.__setattr__(self, name, value)

    def __delattr__(self, name: str) -> None:
        self._refuse(name, "delete")
        object.__delattr__(self, name)
