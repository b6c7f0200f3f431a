"""Objects immutable after construction (house style: parameters frozen, state passed per call, not stored).

:class:`Immutable` is the base of the model objects built once from frozen inputs (``AircraftModel``,
``StructuralModel``, ``AeroCoupling``, ``ParasiteDrag``). When the constructor returns — the outermost one, so a
subclass's ``__init__`` may still set attributes — the object is sealed: setting or deleting an attribute raises
AttributeError naming the class and the attribute, and every ndarray reachable from its attributes (directly, in
tuples, lists, dict values and frozen dataclasses, such as the aircraft definition) is read-only, so writing into
one raises numpy's ValueError ("assignment destination is read-only"). ``functools.cached_property`` values are
still computed once (they bypass ``__setattr__``).
"""

from __future__ import annotations

import dataclasses

import numpy as np

__all__ = ["Immutable", "freeze_arrays"]


def freeze_arrays(value, _seen: set[int] | None = None) -> None:
    """Mark every ndarray reachable from ``value`` read-only: the array itself, the items of tuples, lists and dict
    values, and the fields of dataclasses (recursively; other objects are left alone)."""
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


class _SealedAfterInit(type):
    """Metaclass: seal the instance once its (outermost) constructor has returned."""

    def __call__(cls, *args, **kwargs):
        obj = super().__call__(*args, **kwargs)
        obj._seal()
        return obj


class Immutable(metaclass=_SealedAfterInit):
    """Base of objects immutable after construction (module docstring)."""

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
