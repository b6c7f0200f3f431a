"""Structural outputs of a state: tip deflection, tip twist, their rates and the root bending moment.

The one implementation of these outputs, used by the trim (:class:`flexsim.trimming.TrimPoint`), the simulation
outputs and logs (:class:`flexsim.sim.outputs.OutputMaps`) and the environments' observations
(:class:`flexsim.envs.dynamics.FlightDynamics`). With the modal expansion of paper eq. (1),
``w(x, t) = sum_k U_k(x) q_k(t)`` and ``psi(x, t) = sum_k Psi_k(x) xi_k(t)`` (clamped-free shapes,
:mod:`flexsim.structure.shapes`), each output is a fixed row times a block of the state:

* tip deflection ``w(L) = U(L) . q`` [m], along the component's z_i (down on a wing half), and its rate
  ``U(L) . s`` [m/s] (``s = dq/dt``, paper eq. 4);
* tip twist ``psi(L) = Psi(L) . xi`` [rad] (nose up on the right wing; the left wing's y_i points forward, so
  nose down there), and its rate ``Psi(L) . eta`` [rad/s];
* root bending moment ``EI(0) w''(0) = EI(0) U''(0) . q`` [N m] (mode-displacement method; w positive down:
  negative when a wing bends up under lift).

Signs and frames: ``docs/conventions.md``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexsim._arrays import readonly
from flexsim.structure.shapes import bending_shapes, torsion_shapes

__all__ = ["ComponentSensor", "SensorBank", "SENSOR_QUANTITIES", "structural_sensors"]

#: The outputs of one component, in the order of :meth:`SensorBank.evaluate`'s middle axis.
SENSOR_QUANTITIES = ("tip_deflection_m", "tip_deflection_rate_m_s", "tip_twist_rad", "tip_twist_rate_rad_s",
                     "root_bending_moment_n_m")


def _take(x: np.ndarray, idx: np.ndarray) -> np.ndarray:
    """Columns ``idx`` of one state (n,) or of states (N, n) (plain indexing for one state: 2x faster)."""
    x = np.asarray(x)
    return x[idx] if x.ndim == 1 else x[:, idx]


@dataclass(frozen=True, eq=False)
class ComponentSensor:
    """Rows of one component's structural outputs (arrays read-only).

    Attributes
    ----------
    name : str
        Component name.
    q_idx, s_idx, xi_idx, eta_idx : ndarray of int
        Indices of the component's bending coordinates, their rates, torsion coordinates and their rates in
        the state vector.
    w_tip : ndarray, shape (n_bending,)
        Bending shapes at the tip U_k(L) [-].
    psi_tip : ndarray, shape (n_torsion,)
        Torsion shapes at the tip Psi_k(L) [-].
    root_moment : ndarray, shape (n_bending,)
        EI(0) U_k''(0) [N m per m of q_k].
    """

    name: str
    q_idx: np.ndarray
    s_idx: np.ndarray
    xi_idx: np.ndarray
    eta_idx: np.ndarray
    w_tip: np.ndarray
    psi_tip: np.ndarray
    root_moment: np.ndarray

    def tip_deflection_m(self, x: np.ndarray) -> np.ndarray:
        """w(L) [m] of state(s) x, shape (n_states,) -> scalar array or (N, n_states) -> (N,)."""
        return _take(x, self.q_idx) @ self.w_tip

    def tip_deflection_rate_m_s(self, x: np.ndarray) -> np.ndarray:
        """dw(L)/dt [m/s]."""
        return _take(x, self.s_idx) @ self.w_tip

    def tip_twist_rad(self, x: np.ndarray) -> np.ndarray:
        """psi(L) [rad]."""
        return _take(x, self.xi_idx) @ self.psi_tip

    def tip_twist_rate_rad_s(self, x: np.ndarray) -> np.ndarray:
        """dpsi(L)/dt [rad/s]."""
        return _take(x, self.eta_idx) @ self.psi_tip

    def root_bending_moment_n_m(self, x: np.ndarray) -> np.ndarray:
        """EI(0) w''(0) [N m]."""
        return _take(x, self.q_idx) @ self.root_moment


@dataclass(frozen=True, eq=False)
class SensorBank:
    """The batched form of the outputs of several components: one matrix S with ``X S`` every output of every
    state at once (batched environments: one product for N aircraft instead of 5 x C dot products each).

    Column ``5 c + k`` of S holds the row of output k (:data:`SENSOR_QUANTITIES`) of component c: the
    :class:`ComponentSensor` vectors (``w_tip``, ``psi_tip``, ``root_moment``) placed at its state indices, so
    ``X S`` equals the sensor's methods up to the rounding of the summation order.

    Attributes
    ----------
    names : tuple of str
        Components, in column order.
    matrix : ndarray, shape (n_states, 5 C)
        S (read-only).
    """

    names: tuple[str, ...]
    matrix: np.ndarray

    @classmethod
    def of(cls, sensors: dict[str, ComponentSensor], names: tuple[str, ...], n_states: int) -> SensorBank:
        """The bank of the components ``names`` (keys of ``sensors``, e.g. :func:`structural_sensors`)."""
        s = np.zeros((int(n_states), len(SENSOR_QUANTITIES) * len(names)))
        for c, name in enumerate(names):
            sensor = sensors[name]
            cols = len(SENSOR_QUANTITIES) * c
            for k, (idx, vec) in enumerate(((sensor.q_idx, sensor.w_tip), (sensor.s_idx, sensor.w_tip),
                                            (sensor.xi_idx, sensor.psi_tip), (sensor.eta_idx, sensor.psi_tip),
                                            (sensor.q_idx, sensor.root_moment))):
                s[idx, cols + k] = vec
        return cls(tuple(names), readonly(s))

    def evaluate(self, x: np.ndarray) -> np.ndarray:
        """All outputs of states x (N, n_states): shape (N, 5, C), ``[:, k, c]`` output k
        (:data:`SENSOR_QUANTITIES`, SI units as there) of component ``names[c]``."""
        out = np.asarray(x, dtype=float) @ self.matrix
        return out.reshape(out.shape[0], len(self.names), len(SENSOR_QUANTITIES)).transpose(0, 2, 1)


def structural_sensors(model) -> dict[str, ComponentSensor]:
    """The :class:`ComponentSensor` of every component with elastic coordinates in the state, in file order.

    Parameters
    ----------
    model : flexsim.model.aircraft_model.AircraftModel
        Any variant; a quasi-rigid model (no elastic states) has none.
    """
    lay, dofs = model.layout, model.structure.dofs
    out: dict[str, ComponentSensor] = {}
    if lay.nq + lay.nxi == 0:
        return out
    for comp in model.aircraft.components:
        nb, nt = comp.bending_modes, comp.torsion_modes
        if not (nb or nt):
            continue
        length = comp.length_m
        q_pos = np.arange(lay.q.start, lay.q.stop)[dofs.bending[comp.name]]
        s_pos = np.arange(lay.s.start, lay.s.stop)[dofs.bending[comp.name]]
        xi_pos = np.arange(lay.xi.start, lay.xi.stop)[dofs.torsion[comp.name]]
        eta_pos = np.arange(lay.eta.start, lay.eta.stop)[dofs.torsion[comp.name]]
        w_tip = bending_shapes(length, length, nb)[0] if nb else np.zeros(0)
        psi_tip = torsion_shapes(length, length, nt)[0] if nt else np.zeros(0)
        ei_root = float(comp.sections.at("ei_nm2", np.array([0.0]))[0])
        root = ei_root * bending_shapes(0.0, length, nb, derivative=2)[0] if nb else np.zeros(0)
        out[comp.name] = ComponentSensor(comp.name, *(readonly(np.array(a)) for a in
                                                      (q_pos, s_pos, xi_pos, eta_pos, w_tip, psi_tip, root)))
    return out
