"""Zero-lift (parasite) drag of the aircraft's parts: fuselage, nacelles, tails, wing profile drag.

Not in the paper, whose drag is the strips' induced drag only. Each drag item of the aircraft file
(``[[aero.drag]]``: component, point, drag area f = C_D0 S [m^2]) carries the force of a body in the flow
(Raymer, *Aircraft Design: A Conceptual Approach*, 6th ed., 2018, sec. 12.5, component build-up):

    f_i = -1/2 rho f |v_p| v_p,        v_p = A_i(q) V + omega_sec x rho_i

along the local air velocity at the item's point p (component axes), v_p the velocity of the point relative
to still air: the velocity of its elastic-axis station plus the section's rotation times the offset rho_i of
the point from the axis. The generalized force follows from virtual work at that point (eqs. 17-24):
Q = A_i(q)^T f_i + B_i^T (rho_i x f_i), so the drag also pitches and yaws the aircraft and loads the
structure (e.g. nacelle drag below a swept wing). Units: SI; shapes in :class:`ParasiteDrag`. The per-call arithmetic is the compiled kernel
:func:`flexsim._kernels.parasite_drag`.

Simplification (documented in docs/options.md): the drag items see the aircraft's motion in still air, not
the wind field (a gust's change of the parasite drag is neglected; the strips do see the wind).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from flexsim._immutable import Immutable
from flexsim import _kernels as _k
from flexsim._arrays import kernel_arg
from flexsim.structure.model import StructuralModel

__all__ = ["ParasiteDrag", "attached_point_maps", "attached_items_maps"]


def attached_point_maps(structure: StructuralModel, component: str, position_m: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Kinematic maps of a point riding on ``component`` at ``position_m`` (body axes [m]), eqs. (5)-(6), (18).

    Returns g0 (6, n_v) and g1 (3, 3, nq) of its elastic-axis station (velocity A(q) V = (g0[:3] + g1 q) V
    with g1 on the omega columns, section rotation rate g0[3:] V; component axes) and the offset rho (3,) of the
    point from that station in component axes [m]. The station is the point's projection on the elastic axis,
    clipped to [0, length].
    """
    comp = structure.aircraft.component(component)
    station = float(np.clip(comp.station_of(position_m), 0.0, comp.length_m))
    maps = structure.point_maps(component, np.array([station]))
    return maps.g0[0], maps.g1[0], comp.dcm @ (np.asarray(position_m, float) - maps.r0[0])



def attached_items_maps(structure: StructuralModel, items) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`attached_point_maps` of k items (each with ``component`` and ``position_m``), stacked:
    g0 (k, 6, n_v), g1 (k, 3, 3, nq), offsets (k, 3) [m] (component axes)."""
    k, n_v, nq = len(items), structure.dofs.n_v, structure.dofs.nq
    g0, g1, offset = np.zeros((k, 6, n_v)), np.zeros((k, 3, 3, nq)), np.zeros((k, 3))
    for j, item in enumerate(items):
        g0[j], g1[j], offset[j] = attached_point_maps(structure, item.component, item.position_m)
    return g0, g1, offset

class _DragOf(NamedTuple):
    """What :class:`flexsim._kernels.ParasiteDragData` reads of a model: its drag items and structure."""

    parasite_drag: "ParasiteDrag"
    structure: StructuralModel


class ParasiteDrag(Immutable):
    """Drag items of an aircraft, with their kinematic maps (built once; :meth:`generalized_force` per call).

    Parameters
    ----------
    structure : StructuralModel
        Its aircraft's ``aero_settings.drag`` items are used.

    Attributes
    ----------
    names : tuple of str
    area_m2 : ndarray, shape (k,)
        Drag areas f = C_D0 S [m^2].
    """

    def __init__(self, structure: StructuralModel) -> None:
        items = structure.aircraft.aero_settings.drag
        self.names = tuple(d.name for d in items)
        self.area_m2 = np.array([d.drag_area_m2 for d in items], dtype=float)
        #: The items' maps (:func:`attached_items_maps`): g0 (k, 6, n_v), g1 (k, 3, 3, nq), offsets (k, 3) [m].
        self.g0, self.g1, self.offset_m = attached_items_maps(structure, items)
        #: The items' packed data (:class:`flexsim._kernels.KernelData`), filled by their term data class as for the
        #: model (:meth:`flexsim._kernels.ParasiteDragData.fields_of`).
        self.kernel_data = _k.pack_fields(_k.fields_of(_DragOf(self, structure), (_k.ParasiteDragData,)))

    @property
    def n_items(self) -> int:
        """Number of drag items k."""
        return self.area_m2.size

    def generalized_force(self, q: np.ndarray, vel: np.ndarray, rho: float) -> np.ndarray:
        """Q_drag, shape (n_v,): generalized force of every item's drag (module docstring) [N, N m].

        Parameters
        ----------
        q : ndarray, shape (nq,)
            Bending coordinates [m].
        vel : ndarray, shape (n_v,)
            Global velocity vector V.
        rho : float
            Air density [kg/m^3].
        """
        return _k.parasite_drag(*self.kernel_data, kernel_arg(q), kernel_arg(vel), float(rho))
